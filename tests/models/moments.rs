//! Legendre moments (`phase::moments`): Draine's closed form (HG,
//! Cornette–Shanks, Rayleigh and depolarised Rayleigh are cases of it)
//! against 40-digit quadrature (mpmath, values below) to 10⁻¹² relative;
//! the quadrature over the inverse CDF against the closed forms for HG,
//! Draine, Rayleigh and the fog; for Gegenbauer and Fournier–Forand
//! (no closed form here) against adaptive quadrature of `p P_l` over `μ`;
//! `χ_1` against every model's mean cosine.

use crate::common::chi2::integrate;
use crate::common::nan_max;
use scatterkit::phase::moments::{closed_form, legendre_moments, legendre_moments_by_quadrature};
use scatterkit::{Phase, PhaseFunction};

/// `χ_0 … χ_8` of Draine's function, by mpmath `quad` at 40 digits of
/// `2π ∫ P_l(μ) p(μ) dμ` with `p = (1 − g²)(1 + αμ²) / (4π (1 + α(1 +
/// 2g²)/3) (1 + g² − 2gμ)^{3/2})`.
const DRAINE: [(f64, f64, [f64; 9]); 3] = [
    (
        0.5,
        1.0,
        [
            1.0,
            0.566_666_666_666_666_7,
            0.357_142_857_142_857_1,
            0.189_682_539_682_539_7,
            0.097_673_160_173_160_17,
            0.049_703_768_453_768_45,
            0.025_145_687_645_687_65,
            0.012_679_110_105_580_69,
            0.006_379_805_211_558_308,
        ],
    ),
    (
        0.9,
        10.0,
        [
            1.0,
            0.946_849_315_068_493_2,
            0.887_227_005_870_841_5,
            0.808_811_154_598_825_8,
            0.732_789_895_036_470_4,
            0.662_228_423_220_615,
            0.597_677_811_504_933_4,
            0.539_005_516_194_756_1,
            0.485_855_267_163_577_8,
        ],
    ),
    (
        -0.3,
        2.0,
        [
            1.0,
            -0.381_492_537_313_432_8,
            0.255_507_462_686_567_2,
            -0.088_992_537_313_432_84,
            0.028_563_093_622_795_12,
            -0.008_909_511_533_242_877,
            0.002_741_811_533_242_877,
            -0.000_837_466_751_536_435_5,
            0.000_254_624_497_481_632_1,
        ],
    ),
];

fn moments(p: &Phase<f64>, n: usize) -> Vec<f64> {
    let mut out = vec![0.0; n];
    legendre_moments(p, &mut out);
    out
}

fn by_quadrature(p: &Phase<f64>, n: usize) -> Vec<f64> {
    let mut out = vec![0.0; n];
    legendre_moments_by_quadrature(p, &mut out);
    out
}

#[test]
fn draine_against_forty_digits() {
    for (g, a, want) in DRAINE {
        let got = moments(&Phase::draine(g, a).unwrap(), 9);
        for (l, (x, y)) in got.iter().zip(want).enumerate() {
            assert!(
                (x - y).abs() <= 1e-12 * y.abs(),
                "Draine {g} {a}: χ_{l} {x} vs {y}"
            );
        }
    }
    // Cases of it: HG (g^l), Rayleigh (χ_2 = 1/10), isotropic.
    let hg = moments(&Phase::henyey_greenstein(0.8).unwrap(), 9);
    for (l, x) in hg.iter().enumerate() {
        assert!((x - 0.8f64.powi(l as i32)).abs() <= 1e-15, "HG χ_{l} {x}");
    }
    let ray = moments(&Phase::rayleigh(), 6);
    assert_eq!(ray, vec![1.0, 0.0, 0.1, 0.0, 0.0, 0.0]);
    assert_eq!(moments(&Phase::isotropic(), 3), vec![1.0, 0.0, 0.0]);
}

#[test]
fn quadrature_agrees_with_the_closed_forms() {
    let cases = [
        Phase::henyey_greenstein(0.9).unwrap(),
        Phase::henyey_greenstein(-0.99).unwrap(),
        Phase::draine(0.9, 10.0).unwrap(),
        Phase::rayleigh(),
        Phase::rayleigh_depolarized(0.03).unwrap(),
        Phase::fog_diameter(2.0).unwrap(),
        Phase::two_lobe_hg(0.8, -0.3, 0.9).unwrap(),
    ];
    for p in cases {
        // Each of these declares its closed form: without it the moments
        // would come from quadrature, which agrees to 10⁻¹², so only the
        // declaration tells the two apart.
        assert!(closed_form(&p).is_some(), "{p:?} has no closed form");
        let (a, b) = (moments(&p, 33), by_quadrature(&p, 33));
        let worst = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, nan_max);
        assert!(worst <= 1e-12, "{p:?}: {worst:.2e}");
        assert!(
            (a[1] - p.mean_cosine()).abs() <= 1e-13,
            "{p:?}: χ_1 {} vs g {}",
            a[1],
            p.mean_cosine()
        );
    }
}

#[test]
fn quadrature_for_models_without_a_closed_form() {
    let cases = [
        Phase::gegenbauer(0.5, 0.7).unwrap(),
        Phase::gegenbauer(1.5, 0.9).unwrap(),
        Phase::fournier_forand(1.1, 3.5).unwrap(),
    ];
    for p in cases {
        let got = by_quadrature(&p, 9);
        // χ_l = P_l(1) − ∫ F P_l' dμ (by parts): F is bounded where the
        // density is not (Fournier–Forand's forward peak), so adaptive
        // quadrature over μ takes it. P_l' by P'_{l+1} = P'_{l−1} + (2l+1) P_l.
        let dlegendre = |l: usize, mu: f64| {
            let (mut p0, mut p1) = (1.0, mu);
            let (mut d0, mut d1) = (0.0, 1.0);
            if l == 0 {
                return 0.0;
            }
            for k in 1..l {
                let kf = k as f64;
                let p2 = ((2.0 * kf + 1.0) * mu * p1 - kf * p0) / (kf + 1.0);
                let d2 = d0 + (2.0 * kf + 1.0) * p1;
                (p0, p1, d0, d1) = (p1, p2, d1, d2);
            }
            d1
        };
        for (l, x) in got.iter().enumerate() {
            let want = 1.0 - integrate(&|mu: f64| p.cdf(mu) * dlegendre(l, mu), -1.0, 1.0, 1e-14);
            assert!((x - want).abs() <= 1e-10, "{p:?}: χ_{l} {x} vs {want}");
        }
        assert!((got[1] - p.mean_cosine()).abs() <= 1e-10, "{p:?}: χ_1 vs g");
        assert_eq!(moments(&p, 9), got, "{p:?}: the dispatch takes quadrature");
    }
}

/// `χ_1 … χ_8` of the Gegenbauer kernel and Fournier–Forand (no closed
/// form here: the library's quadrature) against mpmath at 45 digits
/// (tanh–sinh on `p P_l`, the published FF density of Mobley et al. 2002
/// over θ; `χ_0` came out 1 to every digit printed), within 10⁻¹⁰
/// (measured: 2.1·10⁻¹³ relative at worst).
#[test]
#[allow(clippy::excessive_precision)] // mpmath's digits, as printed
fn gegenbauer_and_fournier_forand_against_forty_digits() {
    #[rustfmt::skip]
    let cases: [(Phase<f64>, [f64; 8]); 4] = [
        (Phase::gegenbauer(1.5, 0.7).unwrap(), [
            0.90458452722063034369, 0.77641833810888246299, 0.64373925501432656707,
            0.52078997134670477812, 0.41367372492836666527, 0.32395612893982798574,
            0.250838455300859511, 0.19243533424068760025]),
        (Phase::gegenbauer(-0.3, 0.5).unwrap(), [
            0.23618356654097110558, 0.080734075882018102489, 0.031235124588776442058,
            0.012866357039615114078, 0.0055050105126787165047, 0.0024161930893875104218,
            0.0010800791479833370177, 0.00048951690672183725713]),
        (Phase::fournier_forand(1.1, 3.5).unwrap(), [
            0.94342913818056430331, 0.89838409254267076798, 0.85539862399954670494,
            0.81878095359566845614, 0.78596755869109718774, 0.75637599961884016624,
            0.72953903861762288528, 0.70507634436400121191]),
        (Phase::fournier_forand(1.05, 4.0).unwrap(), [
            0.90492468403275254167, 0.84730812304426388996, 0.79208982133358044227,
            0.74786052618726632908, 0.70875800039673197818, 0.67375233961219082411,
            0.64213435294115848035, 0.61337923719156990156]),
    ];
    for (p, want) in cases {
        let got = moments(&p, 9);
        for (l, w) in want.iter().enumerate() {
            let x = got[l + 1];
            assert!((x - w).abs() <= 1e-10, "{p:?}: χ_{} {x} vs {w}", l + 1);
        }
    }
}

type ByMoments = fn(f64, f64) -> Result<Phase<f64>, scatterkit::Error>;
/// A family: its name, constructor, `j` of its ratio, and the ratio's
/// range at `g`.
type Family = (
    &'static str,
    ByMoments,
    usize,
    fn(f64) -> f64,
    fn(f64) -> f64,
);

/// `(1 − χ_j)/(1 − χ_1)` of `p` (`j = 2`: γ, `j = 3`: δ) and `χ_1`.
fn g_and_ratio(p: &Phase<f64>, j: usize) -> (f64, f64) {
    let chi = moments(p, 4);
    (chi[1], (1.0 - chi[j]) / (1.0 - chi[1]))
}

/// The round trip of a family set by `(g, γ)` or `(g, δ)` over a 19 × 20
/// grid of `0 < g < 1` and `ratio = lo(g) + (hi(g) − lo(g)) k/20`,
/// `k = 1 … 20`: the worst error of `(g, ratio)` read back from the
/// value's moments.
fn round_trip(make: ByMoments, j: usize, lo: fn(f64) -> f64, hi: fn(f64) -> f64) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 1..20 {
        let g = i as f64 / 20.0;
        for k in 1..=20 {
            let r = lo(g) + (hi(g) - lo(g)) * k as f64 / 20.0;
            let p = make(g, r).unwrap_or_else(|e| panic!("({g}, {r}): {e:?}"));
            let (g_back, r_back) = g_and_ratio(&p, j);
            worst = nan_max(nan_max(worst, (g_back - g).abs()), (r_back - r).abs());
        }
    }
    worst
}

fn assert_domain(make: ByMoments, cases: &[(f64, f64)]) {
    for &(g, r) in cases {
        assert_eq!(make(g, r).err(), Some(scatterkit::Error::Domain), "{g} {r}");
    }
}

/// The two HG-based families set by `(g, γ)` or `(g, δ)` (Bevilacqua &
/// Depeursinge's modified HG with its `cos²θ` lobe, and HG with an
/// isotropic lobe): their moments give `(g, γ)` and `(g, δ)` back within
/// 10⁻¹⁰ over grids of the reachable regions; outside them,
/// `Error::Domain`.
#[test]
fn hg_families_round_trip_g_gamma_and_delta() {
    let families: [Family; 4] = [
        (
            "modified HG (g, γ)",
            Phase::modified_hg,
            2,
            |_| 0.6,
            |g| 1.0 + g,
        ),
        (
            "modified HG (g, δ)",
            Phase::modified_hg_delta,
            3,
            |_| 1.0,
            |g| 1.0 + g + g * g,
        ),
        (
            "HG + isotropic (g, γ)",
            Phase::two_lobe_hg_gamma,
            2,
            |_| 1.0,
            |g| 1.0 + g,
        ),
        (
            "HG + isotropic (g, δ)",
            Phase::two_lobe_hg_delta,
            3,
            |_| 1.0,
            |g| 1.0 + g + g * g,
        ),
    ];
    for (name, make, j, lo, hi) in families {
        let worst = round_trip(make, j, lo, hi);
        assert!(worst <= 1e-10, "{name}: {worst:.2e}");
    }
    let nan = f64::NAN;
    assert_domain(
        Phase::modified_hg,
        &[(0.5, 0.6), (0.5, 1.51), (0.0, 1.2), (1.0, 1.5), (0.5, nan)],
    );
    assert_domain(
        Phase::two_lobe_hg_gamma,
        &[
            (0.5, 1.0),
            (0.5, 1.6),
            (0.0, 1.2),
            (-0.5, 1.2),
            (1.0, 1.5),
            (0.5, nan),
        ],
    );
    for make in [
        Phase::modified_hg_delta as ByMoments,
        Phase::two_lobe_hg_delta,
    ] {
        assert_domain(
            make,
            &[(0.5, 1.0), (0.5, 1.76), (0.0, 1.2), (-0.5, 1.2), (0.5, nan)],
        );
    }
}

/// The modified HG is Bevilacqua & Depeursinge's
/// `β p_HG(g_HG) + (1 − β) (3/4π) cos²θ`: its density matches that sum
/// within 10⁻¹² (relative) at 201 cosines, with `(g_HG, β)` from the
/// quadratic solved here independently, and its sampler inverts its CDF
/// within 10⁻¹² at 1001 uniforms.
#[test]
fn modified_hg_is_hg_plus_cos_squared() {
    for (g, gamma) in [(0.9, 1.6), (0.5, 0.9), (0.2, 1.19)] {
        let p = Phase::<f64>::modified_hg(g, gamma).unwrap();
        // g x² + (γ(1 − g) − 3/5) x − 2g/5 = 0.
        let b: f64 = gamma * (1.0 - g) - 0.6;
        let x = (-b + (b * b + 1.6 * g * g).sqrt()) / (2.0 * g);
        let (beta, hg) = (g / x, Phase::<f64>::henyey_greenstein(x).unwrap());
        for i in 0..=200 {
            let mu = -1.0 + i as f64 / 100.0;
            let want =
                beta * hg.pdf(mu) + (1.0 - beta) * 3.0 / (4.0 * core::f64::consts::PI) * mu * mu;
            assert!(
                (p.pdf(mu) - want).abs() <= 1e-12 * want.max(1e-3),
                "({g}, {gamma}) at {mu}"
            );
        }
        // Its sampler inverts its CDF.
        for i in 0..=1000 {
            let u = i as f64 / 1000.0;
            assert!(
                (p.cdf(p.sample_cos(u)) - u).abs() <= 1e-12,
                "({g}, {gamma}) at u = {u}"
            );
        }
    }
}

/// The Gegenbauer kernel set by `(g, γ)` or `(g, δ)`: kernels on a grid of
/// `(α, g_GK)` (including `α` near −½ and 1000, and `g_GK` in the series
/// range below 0.1) give `(g, γ)` and `(g, δ)` by quadrature of the
/// kernel's own moments (those with `g ≤ 0.99`); the constructors rebuild a kernel whose moments
/// return both within 10⁻¹⁰. Against mpmath (25 digits, bisection on
/// quadrature moments): `(0.6, γ = 1.806338)` is `α = 5`,
/// `g_GK = 0.179792`, `(0.9, δ = 3.325572)` is `α = 1`, `g_GK = 0.780969`
/// (to the 6 digits printed). Outside the reach: `Error::Domain`.
#[test]
fn gegenbauer_round_trips_g_gamma_and_delta() {
    let (mut worst, mut cases): (f64, usize) = (0.0, 0);
    for alpha in [-0.45, -0.2, 0.1, 0.5, 1.5, 4.0, 30.0, 300.0, 990.0] {
        for gk in [0.003, 0.04, 0.2, 0.5, 0.8, 0.95] {
            let k = Phase::<f64>::gegenbauer(alpha, gk).unwrap();
            // Beyond g = 0.99 the moments' 10⁻¹² leave γ ill-conditioned
            // (it divides by 1 − g).
            if k.mean_cosine() > 0.99 {
                continue;
            }
            cases += 1;
            for (j, make) in [
                (2, Phase::gegenbauer_gamma as ByMoments),
                (3, Phase::gegenbauer_delta),
            ] {
                let (g, r) = g_and_ratio(&k, j);
                let p = make(g, r).unwrap_or_else(|e| panic!("α {alpha} g {gk}: {e:?}"));
                let (g_back, r_back) = g_and_ratio(&p, j);
                worst = nan_max(nan_max(worst, (g_back - g).abs()), (r_back - r).abs());
            }
        }
    }
    assert!(worst <= 1e-10 && cases >= 40, "{worst:.2e} over {cases}");
    let params = |p: Phase<f64>| match p {
        Phase::Gegenbauer(k) => (k.alpha(), k.g()),
        p => panic!("{p:?}"),
    };
    let (a, gk) = params(Phase::gegenbauer_gamma(0.6, 1.806338).unwrap());
    assert!(
        (a - 5.0).abs() < 1e-4 && (gk - 0.179792).abs() < 1e-5,
        "{a} {gk}"
    );
    let (a, gk) = params(Phase::gegenbauer_delta(0.9, 3.325572).unwrap());
    assert!(
        (a - 1.0).abs() < 1e-4 && (gk - 0.780969).abs() < 1e-5,
        "{a} {gk}"
    );
    // Above α = 1000's γ, below the reach as α → −½, and bad input.
    let nan = f64::NAN;
    let out = [
        (0.6, 1.88),
        (0.6, 1.3),
        (0.9, 1.45),
        (0.0, 1.2),
        (1.0, 1.5),
        (0.5, nan),
        (0.5, f64::INFINITY),
    ];
    assert_domain(Phase::gegenbauer_gamma, &out);
    assert_domain(
        Phase::gegenbauer_delta,
        &[(0.6, 2.31), (0.6, 1.5), (0.0, 1.2), (0.5, nan)],
    );
}
