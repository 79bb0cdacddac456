//! The multiple-scattering albedo of a layer (`transport::albedo`):
//! against Chandrasekhar's exact albedos of a semi-infinite isotropic
//! medium (the H-function solved here by iteration on graded
//! Gauss–Legendre panels) within 4σ; the inverse against the curve; a deep
//! slab against the semi-infinite layer; the standards' fitted conversions
//! (van de Hulst's spherical-albedo fit as OpenPBR and Kulla & Conty write
//! it, with the similarity remap for `g`, and without it as the first
//! glTF and Enterprise PBR drafts do) against the transport for HG with
//! `g = 0 … 0.9`; bad input.

use crate::common;
use crate::common::nan_max;

use common::rng;
use scatterkit::transport::albedo::{AlbedoCurve, Illumination, Layer, NODES};
use scatterkit::{Error, HenyeyGreenstein, Isotropic};

/// Gauss–Legendre nodes and weights of order `n` on `[a, b]`.
fn gauss_legendre(n: usize, a: f64, b: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            (0.5 * (b - a) * x + 0.5 * (a + b), 0.5 * (b - a) * w)
        })
        .collect()
}

/// Chandrasekhar's H-function of isotropic scattering with albedo `ω`,
/// from `1/H(μ) = √(1 − ω) + (ω/2) ∫₀¹ μ' H(μ')/(μ + μ') dμ'` iterated to
/// 10⁻¹⁴ on 32-point panels graded toward 0; returns `μ ↦ H(μ)`.
fn h_function(omega: f64) -> impl Fn(f64) -> f64 {
    let edges = [0.0, 1e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.2, 0.5, 1.0];
    let q: Vec<(f64, f64)> = edges
        .windows(2)
        .flat_map(|e| gauss_legendre(32, e[0], e[1]))
        .collect();
    let root = (1.0 - omega).sqrt();
    // The right-hand side at μ from the values h at the nodes.
    let rhs = move |q: &[(f64, f64)], h: &[f64], mu: f64| {
        let s: f64 = q
            .iter()
            .zip(h)
            .map(|(&(m, w), &hv)| w * m * hv / (mu + m))
            .sum();
        1.0 / (root + 0.5 * omega * s)
    };
    let mut h = vec![1.0; q.len()];
    for _ in 0..100_000 {
        let next: Vec<f64> = q.iter().map(|&(mu, _)| rhs(&q, &h, mu)).collect();
        let change = next
            .iter()
            .zip(&h)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, nan_max);
        h = next;
        if change < 1e-14 {
            break;
        }
    }
    move |mu: f64| rhs(&q, &h, mu)
}

/// The exact plane albedo `1 − H(μ_0)√(1 − ω)` and spherical albedo
/// `1 − 2√(1 − ω) ∫₀¹ H(μ) μ dμ` of a semi-infinite isotropic medium.
fn exact_albedos(omega: f64, mu0: f64) -> (f64, f64) {
    let h = h_function(omega);
    let root = (1.0 - omega).sqrt();
    let edges = [0.0, 1e-3, 0.05, 0.3, 1.0];
    let moment: f64 = edges
        .windows(2)
        .flat_map(|e| gauss_legendre(32, e[0], e[1]))
        .map(|(mu, w)| w * h(mu) * mu)
        .sum();
    (1.0 - h(mu0) * root, 1.0 - 2.0 * root * moment)
}

const OMEGAS: [f64; 6] = [0.3, 0.6, 0.9, 0.97, 0.99, 0.999];

/// Isotropic scattering, semi-infinite: the estimated albedos (diffuse
/// light, and beams at μ_0 = 1 and 0.5; 10⁵ paths each) within
/// 4σ + 10⁻⁴ (the interpolation between nodes) of Chandrasekhar's exact
/// values at six ω, on and between the nodes.
#[test]
fn isotropic_semi_infinite_matches_chandrasekhar() {
    let iso = Isotropic;
    for (k, light) in [
        Illumination::Diffuse,
        Illumination::Directional(1.0),
        Illumination::Directional(0.5),
    ]
    .into_iter()
    .enumerate()
    {
        let mut r = rng(900 + k as u64);
        let c = AlbedoCurve::simulate(&iso, Layer::SemiInfinite, light, 100_000, &mut r).unwrap();
        for omega in OMEGAS {
            let (plane, spherical) = exact_albedos(
                omega,
                match light {
                    Illumination::Directional(m) => m,
                    Illumination::Diffuse => 1.0,
                },
            );
            let want = if light == Illumination::Diffuse {
                spherical
            } else {
                plane
            };
            let (got, se) = (c.albedo(omega), c.std_error(omega));
            assert!(
                (got - want).abs() <= 4.0 * se + 1e-4,
                "{light:?} ω {omega}: {got} vs {want} (σ {se:.1e})"
            );
        }
    }
}

/// The inverse returns ω within 10⁻¹² from the curve's own albedo; the
/// curve falls strictly with the node index (rises with ω) and is rebuilt
/// bit for bit from its stored nodes; a deep slab
/// (τ = 64) matches the semi-infinite layer within 4σ for ω ≤ 0.99.
#[test]
fn the_inverse_and_the_slab() {
    let hg = HenyeyGreenstein::new(0.6).unwrap();
    let mut r = rng(77);
    let c = AlbedoCurve::simulate(
        &hg,
        Layer::SemiInfinite,
        Illumination::Diffuse,
        40_000,
        &mut r,
    )
    .unwrap();
    let mut r = rng(78);
    let slab = AlbedoCurve::simulate(
        &hg,
        Layer::Slab(64.0),
        Illumination::Diffuse,
        40_000,
        &mut r,
    )
    .unwrap();
    // The semi-infinite curve keeps the coarse nodes alone (smooth in s
    // through the first interval); a slab keeps the fine nodes too.
    assert!(c.fine_nodes().is_none() && slab.fine_nodes().is_some());
    for curve in [&c, &slab] {
        // Every thousandth ω, and inside the first interval every tenth of
        // each fine grid step (ω from 1 − 2.3·10⁻¹⁰ to 1 − 1/4096).
        let fine = (0..100).map(|k| {
            let s = 2f64.powf(-10.0 + k as f64 / 10.0) / 64.0;
            1.0 - s * s
        });
        for omega in (0..=1000).map(|i| i as f64 / 1000.0).chain(fine) {
            let back = curve.single_scattering_albedo(curve.albedo(omega)).unwrap();
            assert!((back - omega).abs() <= 1e-12, "{omega}: {back}");
        }
        // Monotone through the first interval and across its end.
        let mut last = curve.albedo(1.0);
        for k in 0..=4000 {
            let s = k as f64 / 4000.0 / 32.0;
            let a = curve.albedo(1.0 - s * s);
            assert!(a <= last, "s = {s}: {a} after {last}");
            last = a;
        }
        for k in 1..NODES {
            assert!(
                curve.node(k).unwrap().1 < curve.node(k - 1).unwrap().1,
                "node {k}"
            );
        }
        // Stored and restored: the same curve; from the coarse nodes
        // alone, the same beyond the first interval.
        let (rho, se) = curve.nodes();
        let (fine, fine_se) = curve.fine_nodes().unwrap_or_default();
        let back = AlbedoCurve::from_stored(rho, se, fine, fine_se, curve.paths());
        for omega in [0.0, 0.37, 0.9, 0.999, 0.99999, 0.9999999, 1.0] {
            assert_eq!(back.albedo(omega).to_bits(), curve.albedo(omega).to_bits());
            assert_eq!(
                back.std_error(omega).to_bits(),
                curve.std_error(omega).to_bits()
            );
        }
        let coarse = AlbedoCurve::from_nodes(rho, se, curve.paths());
        assert!(coarse.fine_nodes().is_none());
        for omega in [0.0, 0.37, 0.9, 0.999, 1.0 - 1.0 / 4096.0] {
            assert_eq!(
                coarse.albedo(omega).to_bits(),
                curve.albedo(omega).to_bits()
            );
        }
    }
    for omega in [0.3, 0.6, 0.9, 0.97, 0.99] {
        let (a, b) = (c.albedo(omega), slab.albedo(omega));
        let se = c.std_error(omega).hypot(slab.std_error(omega));
        assert!(
            (a - b).abs() <= 4.0 * se,
            "ω {omega}: {a} vs {b} (σ {se:.1e})"
        );
    }
    // A thin slab lets light through: it cannot reach albedo 1.
    let mut r = rng(79);
    let thin = AlbedoCurve::simulate(&hg, Layer::Slab(1.0), Illumination::Diffuse, 20_000, &mut r)
        .unwrap();
    let top = thin.albedo(1.0);
    assert!(top < 0.5, "{top}");
    assert_eq!(
        thin.single_scattering_albedo(top + 0.01),
        Err(Error::Domain)
    );
}

/// A slab so thin that no path comes back (τ = 10⁻⁶, 2000 paths; it
/// reflects about 10⁻⁷): the curve is 0, and its error is not 0 but the
/// most one more path would have added, `ω/paths` (0 at `ω = 0`). It was
/// reported as exactly 0 ± 0.
#[test]
fn a_curve_no_path_came_back_has_an_error() {
    let hg = HenyeyGreenstein::new(0.5).unwrap();
    let mut r = rng(81);
    let c =
        AlbedoCurve::simulate(&hg, Layer::Slab(1e-6), Illumination::Diffuse, 2000, &mut r).unwrap();
    for omega in [1.0, 0.99999, 0.5, 0.0] {
        assert_eq!(c.albedo(omega), 0.0, "ω = {omega}");
        let want = omega / 2000.0;
        let se = c.std_error(omega);
        // Between nodes the error is interpolated (linearly in s): within
        // 10⁻³ of ω/paths.
        assert!(
            (se - want).abs() <= 1e-3 * want,
            "ω = {omega}: {se} against {want}"
        );
    }
}

/// Van de Hulst's fit of the spherical albedo of a semi-infinite medium,
/// `A = (1 − s)(1 − 0.139 s)/(1 + 1.17 s)` with the similarity parameter
/// `s = √((1 − ω)/(1 − ω g))` (OpenPBR), inverted: `s` from the quadratic
/// `0.139 s² − (1.139 + 1.17 A) s + 1 − A = 0` (Kulla & Conty's
/// `4.09712 + 4.20863 A − √(9.59217 + 41.6808 A + 17.7126 A²)` is the
/// same root divided through by 0.278), then `ω = (1 − s²)/(1 − g s²)`.
fn fit_omega(a: f64, g: f64) -> f64 {
    let s = 4.09712 + 4.20863 * a - (9.59217 + 41.6808 * a + 17.7126 * a * a).sqrt();
    (1.0 - s * s) / (1.0 - g * s * s)
}

/// The standards' conversions against the transport, HG with
/// g = 0, 0.5, 0.8, 0.9, diffuse light on a semi-infinite layer (10⁵
/// paths each): for each target albedo, the transport's ω, the fit's ω,
/// and the albedo the fit's ω really gives. Claims (thresholds fixed
/// before the run, from van de Hulst's stated accuracy of about 1 %):
/// with the similarity remap the fit's albedo is within 0.02 of the
/// target for every g; ignoring g (the fit's `ω = 1 − s²`) misses by
/// more than 0.1 at g = 0.9. Prints the table the media guide quotes.
#[test]
fn the_standards_fits_against_the_transport() {
    let targets = [0.1, 0.3, 0.5, 0.7, 0.9];
    println!(
        "| g | target A | ω (transport) | ω (fit, similarity) | its A | ω (fit, g ignored) | its A |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut worst_sim: f64 = 0.0;
    let mut worst_plain_09: f64 = 0.0;
    for (k, g) in [0.0, 0.5, 0.8, 0.9].into_iter().enumerate() {
        let hg = HenyeyGreenstein::new(g).unwrap();
        let mut r = rng(1000 + k as u64);
        let c = AlbedoCurve::simulate(
            &hg,
            Layer::SemiInfinite,
            Illumination::Diffuse,
            100_000,
            &mut r,
        )
        .unwrap();
        for a in targets {
            let omega = c.single_scattering_albedo(a).unwrap();
            let (sim, plain) = (fit_omega(a, g), fit_omega(a, 0.0));
            let (a_sim, a_plain) = (c.albedo(sim), c.albedo(plain));
            println!(
                "| {g} | {a} | {omega:.5} | {sim:.5} | {a_sim:.4} | {plain:.5} | {a_plain:.4} |"
            );
            worst_sim = nan_max(worst_sim, (a_sim - a).abs());
            if g == 0.9 {
                worst_plain_09 = nan_max(worst_plain_09, (a_plain - a).abs());
            }
        }
    }
    println!(
        "worst |A − target| with similarity {worst_sim:.4}, g ignored at 0.9 {worst_plain_09:.4}"
    );
    assert!(worst_sim <= 0.02, "{worst_sim}");
    assert!(worst_plain_09 > 0.1, "{worst_plain_09}");
}

#[test]
fn bad_input_is_an_error() {
    let iso = Isotropic;
    let mut r = rng(5);
    let run =
        |layer, light, paths, r: &mut _| AlbedoCurve::simulate(&iso, layer, light, paths, r).err();
    let d = Illumination::Diffuse;
    assert_eq!(run(Layer::SemiInfinite, d, 0, &mut r), Some(Error::Domain));
    for tau in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(run(Layer::Slab(tau), d, 10, &mut r), Some(Error::Domain));
    }
    for mu0 in [0.0, -0.5, 1.5, f64::NAN] {
        assert_eq!(
            run(
                Layer::SemiInfinite,
                Illumination::Directional(mu0),
                10,
                &mut r
            ),
            Some(Error::Domain)
        );
    }
    let c = AlbedoCurve::simulate(&iso, Layer::SemiInfinite, d, 100, &mut r).unwrap();
    for bad in [-0.1, 1.1, f64::NAN] {
        assert!(c.albedo(bad).is_nan() && c.std_error(bad).is_nan());
        assert_eq!(c.single_scattering_albedo(bad), Err(Error::Domain));
    }
    assert!(c.node(NODES).is_none() && c.paths() == 100);
}

/// Adding-doubling references (Prahl's method as iadpython 0.5.3 computes
/// it: `Sample(a = ω, b = 10⁵, g, n = 1, quad_pts = 16)`, whose `UR1` is
/// the plane albedo at normal incidence and `URU` the spherical albedo;
/// 8 to 20 quadrature points agree to 10⁻⁶): `(g, ω, beam, diffuse)`.
const ADDING_DOUBLING: [(f64, f64, f64, f64); 9] = [
    (0.0, 0.999, 0.912845334, 0.929713284),
    (0.0, 0.9999, 0.971417774, 0.977186969),
    (0.0, 0.99999, 0.990854809, 0.992725346),
    (0.5, 0.999, 0.877970224, 0.902179806),
    (0.5, 0.9999, 0.959570766, 0.967902035),
    (0.5, 0.99999, 0.987022360, 0.989728753),
    (0.9, 0.999, 0.745962529, 0.795431473),
    (0.9, 0.9999, 0.911330046, 0.929755320),
    (0.9, 0.99999, 0.971051981, 0.977189398),
];

/// `1 − ω` at which the same references reflect `A = 0.99` (bisection in
/// `log(1 − ω)`): `(g, beam, diffuse)`.
const AT_099: [(f64, f64, f64); 3] = [
    (0.0, 1.1969053053950605e-05, 1.895149623648574e-05),
    (0.5, 5.918552668127072e-06, 9.476038892286605e-06),
    (0.9, 1.1702630863808018e-06, 1.895284808484096e-06),
];

/// The inverse of curve `c` (HG `g`; light `li`: 0 beam, 1 diffuse) at
/// `A = 0.99` against [`AT_099`]: the relative error in `1 − ω`, and its σ
/// from the curve's reported error and slope.
fn inverse_at_099(c: &AlbedoCurve, g: f64, li: usize) -> (f64, f64) {
    let at = AT_099.iter().find(|x| x.0 == g).unwrap();
    let want = if li == 0 { at.1 } else { at.2 };
    let omega = c.single_scattering_albedo(0.99).unwrap();
    // σ of 1 − ω = s²: 2 σ_s/s, σ_s = σ_A / |dA/ds|.
    let s = (1.0 - omega).sqrt();
    let ds = 1e-3 * s;
    let at_s = |s: f64| c.albedo(1.0 - s * s);
    let slope = (at_s(s + ds) - at_s(s - ds)) / (2.0 * ds);
    let sigma = 2.0 * c.std_error(omega) / slope.abs() / s;
    ((1.0 - omega) / want - 1.0, sigma)
}

/// As `ω → 1` (HG, g = 0, 0.5, 0.9; beam at normal incidence and diffuse;
/// 10⁵ paths each): the curve within 3σ of adding-doubling at ω = 0.999,
/// 0.9999 and 0.99999, σ the reported error (Monte Carlo and
/// interpolation); and the inverse at A = 0.99 within 3σ in `1 − ω`, σ
/// from that error and the curve's slope. Before the first interval took
/// the cubic through four nodes the curve lay above the references by up
/// to 1.5·10⁻³ there (z = 9.4 at g = 0.9, ω = 0.99999, beam) while the
/// reported error fell toward 0.
#[test]
fn near_one_against_adding_doubling() {
    let mut worst = (0.0f64, String::new());
    for (gi, g) in [0.0, 0.5, 0.9].into_iter().enumerate() {
        let lights = [
            (Illumination::Directional(1.0), "beam"),
            (Illumination::Diffuse, "diffuse"),
        ];
        for (li, (light, name)) in lights.into_iter().enumerate() {
            let hg = HenyeyGreenstein::new(g).unwrap();
            let mut r = rng(40 + 2 * gi as u64 + li as u64);
            let c =
                AlbedoCurve::simulate(&hg, Layer::SemiInfinite, light, 100_000, &mut r).unwrap();
            for &(_, omega, beam, diffuse) in ADDING_DOUBLING.iter().filter(|x| x.0 == g) {
                let want = if li == 0 { beam } else { diffuse };
                let z = (c.albedo(omega) - want) / c.std_error(omega);
                assert!(z.abs() < 3.0, "g = {g}, {name}, ω = {omega}: z = {z:.2}");
                if z.abs() > worst.0 {
                    worst = (z.abs(), format!("g = {g}, {name}, ω = {omega}"));
                }
            }
            let (rel, sigma) = inverse_at_099(&c, g, li);
            eprintln!("g = {g}, {name}: 1 − ω at A = 0.99 off by {rel:+.4} (σ {sigma:.4})");
            assert!(
                rel.abs() < 3.0 * sigma,
                "g = {g}, {name}: {rel} (σ {sigma})"
            );
        }
    }
    eprintln!("largest |z| {:.2} ({})", worst.0, worst.1);
}

/// Conservative slabs (ω = 1) by adding-doubling (iadpython 0.5.3,
/// `Sample(a = 1, b = τ, g, n = 1, quad_pts = 16)`: `(g, τ, UR1, URU)`; 12
/// points agree to 4·10⁻⁷ and `R + T = 1` within 2·10⁻⁷. At 24 points and
/// beyond these thick slabs drift: `R + T` = 1.00014 at τ = 10⁴, and 32
/// points give 0.95.)
const CONSERVATIVE_SLABS: [(f64, f64, f64, f64); 6] = [
    (0.0, 100.0, 0.983446948, 0.986853464),
    (0.0, 1000.0, 0.998323545, 0.998668549),
    (0.0, 10000.0, 0.999832024, 0.999866592),
    (0.85, 100.0, 0.896811329, 0.918837706),
    (0.85, 1000.0, 0.988805345, 0.991194926),
    (0.85, 10000.0, 0.998870843, 0.999111870),
];

/// A deep slab at ω = 1 (HG g = 0 and 0.85; τ = 100, 1000, 10⁴; beam at
/// normal incidence and diffuse; 20 000 paths each) within 3.5σ of
/// adding-doubling, σ the reported error. Paths cut after 2¹⁶ scatterings
/// were dropped, as if absorbed: at τ = 10⁴, g = 0.85, diffuse, the
/// albedo came out 0.98673 ± 0.00057 against 0.99911 (z = −22); a cut
/// path now adds the share diffusion returns through the lit face.
#[test]
fn a_deep_conservative_slab_against_adding_doubling() {
    let cases = CONSERVATIVE_SLABS
        .iter()
        .flat_map(|&(g, tau, beam, diffuse)| {
            [(g, tau, true, 1.0, beam), (g, tau, false, 1.0, diffuse)]
        });
    slabs_against_adding_doubling(cases, 500);
}

/// Each slab `(g, τ, beam?, ω, albedo)` (HG; a beam at normal incidence,
/// else diffuse light) traced with 20 000 paths from seed `seed + i`: its
/// curve at `ω` within 3.5σ of the albedo, σ the reported error.
fn slabs_against_adding_doubling(
    cases: impl Iterator<Item = (f64, f64, bool, f64, f64)>,
    seed: u64,
) {
    let mut worst = (0.0f64, String::new());
    for (i, (g, tau, beam, omega, want)) in cases.enumerate() {
        let hg = HenyeyGreenstein::new(g).unwrap();
        let light = if beam {
            Illumination::Directional(1.0)
        } else {
            Illumination::Diffuse
        };
        let mut r = rng(seed + i as u64);
        let c = AlbedoCurve::simulate(&hg, Layer::Slab(tau), light, 20_000, &mut r).unwrap();
        let (a, se) = (c.albedo(omega), c.std_error(omega));
        let z = (a - want) / se;
        let case = format!(
            "g = {g}, τ = {tau}, {}, ω = {omega}",
            if beam { "beam" } else { "diffuse" }
        );
        assert!(
            z.abs() < 3.5,
            "{case}: {a} ± {se:.1e} against {want} (z = {z:.2})"
        );
        if z.abs() > worst.0 {
            worst = (z.abs(), case);
        }
    }
    eprintln!("largest |z| {:.2} ({})", worst.0, worst.1);
}

/// Thick slabs between `ω = 1` and the first node, where a slab bends from
/// its own albedo onto the semi-infinite curve on a scale of
/// `1 − ω ≈ 1/(3τ²(1 − g))` (iadpython 0.5.3, `Sample(a = ω, b = τ, g,
/// n = 1, quad_pts = 16)`): `(g, τ, beam?, ω, albedo)`.
const THICK_NEAR_ONE: [(f64, f64, bool, f64, f64); 9] = [
    (0.0, 1000.0, true, 0.99999, 0.9908544925934376),
    (0.0, 300.0, true, 0.99999, 0.9901518894210856),
    (0.0, 300.0, false, 0.999999, 0.9951845610509579),
    (0.5, 300.0, true, 0.99999, 0.9842541786304606),
    (0.5, 300.0, false, 0.99999, 0.9875410693088505),
    (0.9, 1000.0, true, 0.9999, 0.911327271511241),
    (0.9, 1000.0, true, 0.99999, 0.9692476270291952),
    (0.9, 1000.0, false, 0.9999, 0.9297531402072294),
    (0.9, 1000.0, false, 0.99999, 0.9757712012325956),
];

/// [`THICK_NEAR_ONE`] within 3.5σ (σ the reported error; 20 000 paths per
/// curve). With the first two nodes alone (the cubic through nodes 0–3)
/// these lay 3 to 6.8σ low, up to 0.8 % (g = 0.9, τ = 1000, ω = 0.99999);
/// the fine nodes, where a path cut after 2¹⁶ scatterings adds what
/// diffusion returns of it, follow the bend.
#[test]
fn thick_slabs_near_one_against_adding_doubling() {
    slabs_against_adding_doubling(THICK_NEAR_ONE.iter().copied(), 700);
}

/// The inverse at `A = 0.99` within 1 % in `1 − ω` of adding-doubling, for
/// g = 0, 0.5, 0.9, beam and diffuse, at `SK_ALBEDO_PATHS` paths per curve
/// (10⁷ by default: a standard error of 0.2–0.3 % there, where 10⁵ paths
/// give 1.7–3.3 %, too wide to show 1 %). Ignored: about 25 minutes on two
/// cores; `cargo test --release --test models -- --ignored
/// near_one_inverse_within_one_percent`. The bound, 1 %, is the issue's;
/// the test also asserts 3σ, σ from the curve's reported error.
#[test]
#[ignore]
fn near_one_inverse_within_one_percent() {
    let paths: u64 = std::env::var("SK_ALBEDO_PATHS").map_or(10_000_000, |s| s.parse().unwrap());
    // The forward-scattering cases first: their paths are the longest.
    let cases: Vec<(usize, f64, usize)> = [0.9, 0.5, 0.0]
        .into_iter()
        .map(|g| ([0.0, 0.5, 0.9].iter().position(|&x| x == g).unwrap(), g))
        .flat_map(|(gi, g)| [(gi, g, 0), (gi, g, 1)])
        .collect();
    let run = |&(gi, g, li): &(usize, f64, usize)| {
        let light = if li == 0 {
            Illumination::Directional(1.0)
        } else {
            Illumination::Diffuse
        };
        let hg = HenyeyGreenstein::new(g).unwrap();
        let mut r = rng(140 + 2 * gi as u64 + li as u64);
        let c = AlbedoCurve::simulate(&hg, Layer::SemiInfinite, light, paths, &mut r).unwrap();
        inverse_at_099(&c, g, li)
    };
    // Two workers take the cases in turn (the machine has two cores).
    let next = std::sync::atomic::AtomicUsize::new(0);
    let slots = std::sync::Mutex::new(vec![(f64::NAN, f64::NAN); cases.len()]);
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(case) = cases.get(i) else { break };
                    let x = run(case);
                    slots.lock().unwrap()[i] = x;
                }
            });
        }
    });
    let results = slots.into_inner().unwrap();
    for (&(_, g, li), &(rel, sigma)) in cases.iter().zip(&results) {
        let name = if li == 0 { "beam" } else { "diffuse" };
        eprintln!(
            "g = {g}, {name}: 1 − ω at A = 0.99 off by {rel:+.4} (σ {sigma:.4}), {paths} paths"
        );
    }
    for (&(_, g, li), &(rel, sigma)) in cases.iter().zip(&results) {
        assert!(
            rel.abs() < 0.01 && rel.abs() < 3.0 * sigma,
            "g = {g}, light {li}: {rel} (σ {sigma})"
        );
    }
}
