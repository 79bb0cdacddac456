//! Legendre moments (`phase::moments`): Draine's closed form (HG,
//! Cornette–Shanks, Rayleigh and depolarised Rayleigh are cases of it)
//! against 40-digit quadrature (mpmath, values below) to 10⁻¹² relative;
//! the quadrature over the inverse CDF against the closed forms for HG,
//! Draine, Rayleigh and the fog; for Gegenbauer and Fournier–Forand
//! (no closed form here) against adaptive quadrature of `p P_l` over `μ`;
//! `χ_1` against every model's mean cosine.

use crate::common::chi2::integrate;
use scatterkit::phase::moments::{legendre_moments, legendre_moments_by_quadrature};
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
        let (a, b) = (moments(&p, 33), by_quadrature(&p, 33));
        let worst = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
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

/// The modified HG set by `(g, γ)`: its moments give `(g, γ)` back
/// (`γ = (1 − χ_2)/(1 − χ_1)`) to 10⁻¹⁰ over a grid of the reachable
/// region; outside it, `Error::Domain`.
#[test]
fn modified_hg_round_trips_g_and_gamma() {
    let mut worst: f64 = 0.0;
    for i in 1..20 {
        let g = i as f64 / 20.0;
        for j in 1..=20 {
            let gamma = 1.0 + g * j as f64 / 20.0;
            let p = Phase::modified_hg(g, gamma).unwrap();
            let chi = moments(&p, 3);
            let back = (1.0 - chi[2]) / (1.0 - chi[1]);
            worst = worst.max((chi[1] - g).abs()).max((back - gamma).abs());
        }
    }
    assert!(worst <= 1e-10, "{worst:.2e}");
    for (g, gamma) in [
        (0.5, 1.0),
        (0.5, 1.6),
        (0.0, 1.2),
        (-0.5, 1.2),
        (1.0, 1.5),
        (0.5, f64::NAN),
    ] {
        assert_eq!(
            Phase::modified_hg(g, gamma).err(),
            Some(scatterkit::Error::Domain),
            "{g} {gamma}"
        );
    }
}

/// The modified HG set by `(g, δ)`, `δ = (1 − χ_3)/(1 − χ_1)`: the round
/// trip within 10⁻¹⁰ over the reachable region; outside, `Error::Domain`.
#[test]
fn modified_hg_round_trips_g_and_delta() {
    let mut worst: f64 = 0.0;
    for i in 1..20 {
        let g = i as f64 / 20.0;
        for j in 1..=20 {
            let delta = 1.0 + (g + g * g) * j as f64 / 20.0;
            let p = Phase::modified_hg_delta(g, delta).unwrap();
            let chi = moments(&p, 4);
            let back = (1.0 - chi[3]) / (1.0 - chi[1]);
            worst = worst.max((chi[1] - g).abs()).max((back - delta).abs());
        }
    }
    assert!(worst <= 1e-10, "{worst:.2e}");
    for (g, delta) in [
        (0.5, 1.0),
        (0.5, 1.76),
        (0.0, 1.2),
        (-0.5, 1.2),
        (0.5, f64::NAN),
    ] {
        assert_eq!(
            Phase::modified_hg_delta(g, delta).err(),
            Some(scatterkit::Error::Domain),
            "{g} {delta}"
        );
    }
}
