//! Mixtures of phase functions (`mixture`): chi² over the sphere of the
//! exact inverse and of the lobe choice for mixtures of 2, 3 and 8
//! components (with Rayleigh, and with a table among the 3 and the 8); the
//! exact inverse against a double-double bisection of the mixture's CDF
//! for mixtures of the Draine family (Rayleigh, isotropic, HG, Draine),
//! whose CDFs `tests/common/dd.rs` evaluates in double-double; monotone
//! over 2²⁰ + 3·2¹⁸ f32 uniforms at three mixtures in CI, and over every
//! f32 `u` by the ignored `the_exact_inverse_is_monotone_over_every_f32`
//! (33 min on two cores); `F(μ(u)) = u`; the mean cosine and the
//! normalisation against quadrature; bad input.

use crate::common;
use crate::common::nan_max;

use common::chi2::{chi2_directions, integrate, threshold};
use common::dd::{Dd, draine_cdf};
use common::{CHI2_SAMPLES, rng};
use scatterkit::mixture::{MAX_PARTS, Mixture, Part};
use scatterkit::{Error, Phase, PhaseFunction, Real, Table, TableKind, Vec3};

/// The fog of 5 µm droplets as an f32 inverse-CDF table of 256 intervals.
fn fog_table(buf: &mut Vec<f32>) -> Table<'_, f32> {
    let fog = Phase::<f32>::fog_diameter(5.0).unwrap();
    *buf = vec![0.0; TableKind::Inverse.len(256).unwrap()];
    Table::inverse(&fog, buf, 256).unwrap()
}

/// The three test mixtures (f32): 2, 3 and 8 components.
fn mixtures(table: Table<'_, f32>) -> Vec<Vec<(Part<'_, f32>, f32)>> {
    let p = |x: Result<Phase<f32>, Error>| Part::Phase(x.unwrap());
    vec![
        vec![
            (Part::Phase(Phase::rayleigh()), 0.7),
            (p(Phase::henyey_greenstein(0.8)), 0.3),
        ],
        vec![
            (Part::Phase(Phase::rayleigh()), 0.5),
            (p(Phase::henyey_greenstein(-0.4)), 0.2),
            (Part::Table(table), 0.3),
        ],
        vec![
            (Part::Phase(Phase::isotropic()), 0.05),
            (Part::Phase(Phase::rayleigh()), 0.2),
            (p(Phase::rayleigh_depolarized(0.03)), 0.1),
            (p(Phase::henyey_greenstein(0.95)), 0.15),
            (p(Phase::draine(0.6, 2.0)), 0.1),
            (p(Phase::fog_diameter(2.0)), 0.2),
            (p(Phase::gegenbauer(0.5, 0.7)), 0.1),
            (Part::Table(table), 0.1),
        ],
    ]
}

/// `Σ w_i p_i(μ)` (`cdf` false) or `Σ w_i F_i(μ)` from the components
/// themselves in f64 (a table's own distribution, from its data in f64),
/// normalised weights.
fn reference(parts: &[(Part<'_, f32>, f32)], mu: f64, cdf: bool) -> f64 {
    let total: f64 = parts.iter().map(|&(_, w)| w as f64).sum();
    parts
        .iter()
        .map(|&(part, w)| {
            let p = match part {
                Part::Phase(ph) => {
                    let ph = ph.cast::<f64>();
                    if cdf { ph.cdf(mu) } else { ph.pdf(mu) }
                }
                Part::Table(t) => {
                    let data: Vec<f64> = t.data().iter().map(|&v| v as f64).collect();
                    let t = Table::from_data(&data, t.n(), t.kind()).unwrap();
                    if cdf { t.cdf(mu) } else { t.pdf(mu) }
                }
            };
            w as f64 / total * p
        })
        .sum()
}

#[test]
fn both_samplers_pass_chi2_over_the_sphere() {
    let mut buf = Vec::new();
    let table = fog_table(&mut buf);
    let w64 = [0.3, -0.5, 0.8];
    let len = (0.3f64 * 0.3 + 0.25 + 0.64).sqrt();
    let w_in = Vec3::new((0.3 / len) as f32, (-0.5 / len) as f32, (0.8 / len) as f32);
    for (k, parts) in mixtures(table).into_iter().enumerate() {
        let m = Mixture::new(&parts).unwrap();
        let pdf = |mu: f64| reference(&parts, mu, false);
        let mut r = rng(600 + k as u64);
        let res = chi2_directions(&pdf, w64, CHI2_SAMPLES, || {
            let (d, _) = m.sample_dir(w_in, f32::uniform(&mut r), f32::uniform(&mut r));
            [d.x as f64, d.y as f64, d.z as f64]
        });
        assert!(
            res.passes(),
            "mixture {k}, exact inverse: {res:?} ({:.2e})",
            threshold()
        );
        let mut r = rng(700 + k as u64);
        let res = chi2_directions(&pdf, w64, CHI2_SAMPLES, || {
            let mu = m.sample_cos_by_lobe(f32::uniform(&mut r)) as f64;
            let phi = std::f64::consts::TAU * f64::uniform(&mut r);
            let s = (1.0 - mu * mu).max(0.0).sqrt();
            let w = Vec3::new(w64[0], w64[1], w64[2]);
            let w = w * (1.0 / w.length());
            let (b1, b2) = scatterkit::onb(w);
            let d = b1 * (s * phi.cos()) + b2 * (s * phi.sin()) + w * mu;
            [d.x, d.y, d.z]
        });
        assert!(
            res.passes(),
            "mixture {k}, lobe choice: {res:?} ({:.2e})",
            threshold()
        );
    }
}

/// Draine-family components `(g, α, w)`: HG is α = 0, Rayleigh g = 0 and
/// α = 1, isotropic g = α = 0.
type Lobes = Vec<(f64, f64, f64)>;

fn draine_mixtures() -> Vec<Lobes> {
    vec![
        vec![(0.0, 1.0, 0.6), (0.85, 0.0, 0.4)],
        vec![(0.0, 1.0, 0.3), (-0.5, 0.0, 0.3), (0.9, 2.0, 0.4)],
        vec![
            (0.0, 0.0, 0.1),
            (0.0, 1.0, 0.2),
            (0.3, 0.0, 0.1),
            (-0.7, 0.0, 0.1),
            (0.95, 0.0, 0.15),
            (0.6, 2.0, 0.1),
            (0.8, 1.0, 0.1),
            (-0.2, 5.0, 0.15),
        ],
    ]
}

fn build<T: Real>(lobes: &Lobes) -> Mixture<'static, T> {
    let parts: Vec<(Part<'static, T>, T)> = lobes
        .iter()
        .map(|&(g, a, w)| {
            let ph = Phase::draine(T::from_f64(g), T::from_f64(a)).unwrap();
            (Part::Phase(ph), T::from_f64(w))
        })
        .collect();
    Mixture::new(&parts).unwrap()
}

/// The inverse of the mixture's CDF, bisected on its double-double CDF
/// (in the smaller tail, by the mirror `F_{−g}(−μ) = 1 − F_g(μ)`).
fn dd_inverse(lobes: &Lobes, u: f64) -> f64 {
    let total: f64 = lobes.iter().map(|l| l.2).sum();
    let (sign, target) = if u > 0.5 {
        (-1.0, Dd::new(1.0) - u)
    } else {
        (1.0, Dd::new(u))
    };
    if target.hi <= 0.0 {
        return -sign;
    }
    let cdf = |x: Dd| {
        lobes.iter().fold(Dd::new(0.0), |s, &(g, a, w)| {
            s + draine_cdf(sign * g, a, x) * (w / total)
        })
    };
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    for _ in 0..64 {
        let mid = 0.5 * (lo + hi);
        if cdf(Dd::new(mid)) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    sign * 0.5 * (lo + hi)
}

#[test]
fn the_exact_inverse_matches_double_double() {
    let mut us: Vec<f64> = (0..=512).map(|i| i as f64 / 512.0).collect();
    for k in [1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.01] {
        us.push(k);
        us.push(1.0 - k);
    }
    for (k, lobes) in draine_mixtures().iter().enumerate() {
        let (m64, m32) = (build::<f64>(lobes), build::<f32>(lobes));
        let (mut e64, mut e32) = (0.0f64, 0.0f64);
        for &u in &us {
            let want = dd_inverse(lobes, u);
            e64 = nan_max(e64, (m64.sample_cos(u) - want).abs());
            e32 = nan_max(e32, (m32.sample_cos(u as f32) as f64 - want).abs());
        }
        eprintln!("mixture {k}: max error f64 {e64:.2e}, f32 {e32:.2e}");
        assert!(e64 <= 1e-13, "mixture {k}: f64 {e64:.3e}");
        assert!(e32 <= 1e-6, "mixture {k}: f32 {e32:.3e}");
    }
}

/// Every f32 `u` in `[0, 1]` (1 065 353 217 values) at the three test
/// mixtures: the exact inverse never decreases and stays in `[−1, 1]`.
/// About 10⁹ solves per mixture (~20 min per mixture on one core): run
/// with `cargo test --release --test models -- --ignored every_f32`;
/// `SK_THREADS` sets the threads (default 2), `SK_MIXTURES` which of the
/// three (default all: "012").
#[test]
#[ignore]
fn the_exact_inverse_is_monotone_over_every_f32() {
    let mut buf = Vec::new();
    let table = fog_table(&mut buf);
    let threads: u32 = std::env::var("SK_THREADS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2);
    let top = 1.0f32.to_bits();
    // SK_MIXTURES picks some of the three (for instance "2"), to spread
    // the run over machines or processes.
    let only = std::env::var("SK_MIXTURES").ok();
    for (k, parts) in mixtures(table).into_iter().enumerate() {
        if only.as_ref().is_some_and(|o| !o.contains(&k.to_string())) {
            continue;
        }
        let m = Mixture::new(&parts).unwrap();
        let chunk = top / threads + 1;
        // Each thread checks its run of consecutive floats and reports its
        // first and last cosine, so the joins are checked too.
        let ends: Vec<(f32, f32)> = std::thread::scope(|s| {
            let m = &m;
            let handles: Vec<_> = (0..threads)
                .map(|t| {
                    s.spawn(move || {
                        let (from, to) = (t * chunk, ((t + 1) * chunk - 1).min(top));
                        let first = m.sample_cos(f32::from_bits(from));
                        let mut prev = first;
                        for b in from..=to {
                            let mu = m.sample_cos(f32::from_bits(b));
                            assert!(
                                mu >= prev && (-1.0..=1.0).contains(&mu),
                                "mixture {k}: μ at bits {b:#x} = {mu} < {prev}"
                            );
                            prev = mu;
                        }
                        (first, prev)
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        for w in ends.windows(2) {
            assert!(w[1].0 >= w[0].1, "mixture {k}: join {w:?}");
        }
        println!("mixture {k}: {} floats, monotone", top as u64 + 1);
    }
}

#[test]
fn the_exact_inverse_is_monotone_and_inverts_the_cdf() {
    let mut buf = Vec::new();
    let table = fog_table(&mut buf);
    for (k, parts) in mixtures(table).into_iter().enumerate() {
        let m = Mixture::new(&parts).unwrap();
        // 2²⁰ evenly spaced u, and 2¹⁸ consecutive floats from 0, from
        // just below ½ and up to 1.
        let mut us: Vec<f32> = (0..=1u32 << 20)
            .map(|i| i as f32 / (1u32 << 20) as f32)
            .collect();
        let run = |from: f32, n: usize| {
            (0..n).scan(from, |x, _| {
                let v = *x;
                *x = f32::from_bits(x.to_bits() + 1);
                Some(v)
            })
        };
        us.extend(run(0.0, 1 << 18));
        us.extend(run(f32::from_bits(0.5f32.to_bits() - (1 << 17)), 1 << 18));
        us.extend(run(f32::from_bits(1.0f32.to_bits() - (1 << 18)), 1 << 18));
        us.sort_by(f32::total_cmp);
        us.dedup();
        let mut prev = -1.0f32;
        for &u in &us {
            let mu = m.sample_cos(u);
            assert!(
                mu >= prev && (-1.0..=1.0).contains(&mu),
                "mixture {k}: μ({u}) = {mu} < {prev}"
            );
            prev = mu;
        }
        // μ(u) is the float whose neighbours' CDFs (in f64) bracket u
        // (near a forward peak one f32 step of μ moves F by 10⁻⁵).
        for u in [0.01f32, 0.25, 0.5, 0.75, 0.99] {
            let mu = m.sample_cos(u);
            let f = |x: f32| reference(&parts, x as f64, true);
            let (lo, hi) = (f(mu.next_down()), f(mu.next_up()));
            let u = u as f64;
            assert!(
                lo <= u && u <= hi,
                "mixture {k}: F around μ({u}) = {mu}: [{lo}, {hi}]"
            );
        }
    }
}

#[test]
fn mean_cosine_and_normalisation_against_quadrature() {
    let mut buf = Vec::new();
    let table = fog_table(&mut buf);
    for (k, parts) in mixtures(table).into_iter().enumerate() {
        let m = Mixture::new(&parts).unwrap();
        let pdf = |mu: f64| m.pdf(mu as f32) as f64;
        let tau = std::f64::consts::TAU;
        let total = tau * integrate(&pdf, -1.0, 1.0, 1e-9);
        let g = tau * integrate(&|mu: f64| mu * pdf(mu), -1.0, 1.0, 1e-9);
        assert!((total - 1.0).abs() < 2e-5, "mixture {k}: ∫p = {total}");
        assert!(
            (g - m.mean_cosine() as f64).abs() < 2e-5,
            "mixture {k}: g {g} vs {}",
            m.mean_cosine()
        );
        assert!((m.cdf(1.0) - 1.0).abs() < 1e-6 && m.cdf(-1.0).abs() < 1e-6);
    }
}

#[test]
fn bad_input_is_refused() {
    let hg = Part::Phase(Phase::<f64>::henyey_greenstein(0.5).unwrap());
    assert_eq!(Mixture::<f64>::new(&[]).err(), Some(Error::Size));
    let nine = vec![(hg, 1.0); MAX_PARTS + 1];
    assert_eq!(Mixture::new(&nine).err(), Some(Error::Size));
    for w in [-1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            Mixture::new(&[(hg, 1.0), (hg, w)]).err(),
            Some(Error::Domain),
            "{w}"
        );
    }
    assert_eq!(
        Mixture::new(&[(hg, 0.0), (hg, 0.0)]).err(),
        Some(Error::Domain)
    );
    // A zero weight is a component that is never chosen.
    let m = Mixture::new(&[(hg, 0.0), (Part::Phase(Phase::isotropic()), 2.0)]).unwrap();
    assert_eq!(m.weight(1), 1.0);
    assert!(m.sample_cos(f64::NAN).is_nan() && m.sample_cos_by_lobe(f64::NAN).is_nan());
    assert_eq!(m.sample_cos_by_lobe(0.25), -0.5);
    assert_eq!((m.sample_cos(-1.0), m.sample_cos(2.0)), (-1.0, 1.0));
    // A zero weight last: u = 1 still lands on the component with weight
    // (isotropic at 1 gives μ = 1; the HG lobe at its rescaled 0 would
    // give −1).
    let m = Mixture::new(&[(Part::Phase(Phase::isotropic()), 1.0), (hg, 0.0)]).unwrap();
    assert_eq!(m.sample_cos_by_lobe(1.0), 1.0);
}

/// Legendre moments of a mixture (each model's closed form or quadrature,
/// weighted) against quadrature over the mixture's own exact inverse.
#[test]
fn legendre_moments_of_a_mixture() {
    let fog = Phase::<f64>::fog_diameter(5.0).unwrap();
    let mut buf = vec![0.0; TableKind::Inverse.len(256).unwrap()];
    let table = Table::inverse(&fog, &mut buf, 256).unwrap();
    let parts = [
        (Part::Phase(Phase::rayleigh()), 0.5),
        (Part::Phase(Phase::gegenbauer(0.5, 0.7).unwrap()), 0.2),
        (Part::Table(table), 0.3),
    ];
    let m = Mixture::new(&parts).unwrap();
    let (mut a, mut b) = ([0.0f64; 40], [0.0f64; 40]);
    m.legendre_moments(&mut a);
    scatterkit::phase::moments::legendre_moments_by_quadrature(&m, &mut b);
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, nan_max);
    assert!(worst <= 1e-10, "{worst:.2e}");
    assert!((a[0] - 1.0).abs() < 1e-12 && (a[1] - m.mean_cosine()).abs() < 1e-9);
}
