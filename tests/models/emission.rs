//! Emission along a ray (`medium::emission`): ratio tracking that scores
//! `σ_a L_e / σ_maj` at every tentative collision, unbiased at 4σ (4·10⁴
//! estimates per ray) against the closed form for a homogeneous emitting
//! slab and against quadrature for a graded one (density and `L_e` linear
//! in height), from a grid and from callbacks, and against quadrature on
//! the six rays of `majorant.rs` through its cloud (node- and
//! cell-centred, unit cube and world box); the check rejects an
//! estimator that scores the weight after its update. The exact integral
//! for a medium constant per cell against quadrature, and the tracker
//! against it.

use super::majorant::{for_each_grid, mean_se};
use crate::common::chi2::integrate;
use crate::common::rng;
use scatterkit::Vec3;
use scatterkit::majorant::Majorants;
use scatterkit::medium::emission::emission_cells;
use scatterkit::{Error, Grid, Ray};

const N: usize = 40_000;

/// Mean and standard error of `n` estimates of (radiance, transmittance).
fn stats(mut f: impl FnMut() -> (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let (l, t): (Vec<f64>, Vec<f64>) = (0..N).map(|_| f()).unzip();
    (mean_se(&l), mean_se(&t))
}

fn close(what: &str, (m, se): (f64, f64), want: f64) {
    assert!(
        (m - want).abs() <= 4.0 * se + 1e-12,
        "{what}: {m} ± {se} vs {want}"
    );
}

/// A homogeneous slab, `σ_t = 1.5`, `σ_a = 0.6`, `L_e = 2`, the unit cube:
/// `L = L_e (σ_a/σ_t)(1 − e^{−σ_t ℓ})` along each ray's length `ℓ` inside,
/// with tight (16³) and loose (one, 3× the extinction) majorants.
#[test]
fn a_homogeneous_slab_matches_the_closed_form() {
    let values = [1.5; 8];
    let g = Grid::new(&values, 2, 2, 2, 0.4, 0.6).unwrap();
    let mut store = [0.0; 16 * 16 * 16];
    let tight = Majorants::build(&g, [16; 3], &mut store).unwrap();
    let loose_value = [4.5];
    let (lo, hi) = g.bounds();
    let loose = Majorants::new(&loose_value, [1; 3], lo, hi).unwrap();
    let (st, sa, le) = (1.5, 0.6, 2.0);
    let rays = [
        // (origin, direction, t_max, length inside)
        (
            Vec3::new(-1.0, 0.5, 0.5),
            Vec3::new(1.0, 0.0, 0.0),
            f64::INFINITY,
            1.0,
        ),
        (
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
            f64::INFINITY,
            3f64.sqrt(),
        ),
        (
            Vec3::new(0.3, 0.4, 0.5),
            Vec3::new(0.0, 0.0, -1.0),
            0.25,
            0.25,
        ),
    ];
    let mut r = rng(41);
    for (k, (o, d, t_max, len)) in rays.into_iter().enumerate() {
        let ray = Ray::new(o, d, t_max);
        let want = le * sa / st * -(-st * len).exp_m1();
        let tr = (-st * len).exp();
        for (name, maj) in [("tight", &tight), ("loose", &loose)] {
            let (l, t) = stats(|| {
                let e = maj
                    .emission_track(&g, |_| le, ray, 1 << 20, &mut r)
                    .unwrap();
                (e.radiance, e.tr)
            });
            close(&format!("ray {k} {name}: radiance"), l, want);
            close(&format!("ray {k} {name}: transmittance"), t, tr);
        }
        // Through callbacks, the loose majorant.
        let (l, _) = stats(|| {
            let e = loose
                .emission_track_fn(|_| (sa, st - sa), |_| le, ray, 1 << 20, &mut r)
                .unwrap();
            (e.radiance, e.tr)
        });
        close(&format!("ray {k} callback: radiance"), l, want);
        // The mutation: the weight taken after its update at each
        // collision (a source of L_e (1 − σ_t/σ_maj) with the loose
        // majorant) must fail the same check.
        let (l, _) = stats(|| {
            let e = loose
                .emission_track(&g, |_| le * (1.0 - st / 4.5), ray, 1 << 20, &mut r)
                .unwrap();
            (e.radiance, e.tr)
        });
        assert!(
            (l.0 - want).abs() > 4.0 * l.1,
            "ray {k}: the mutated estimator passes ({} ± {} vs {want})",
            l.0,
            l.1
        );
    }
}

/// A graded slab over the unit cube: density `0.5 + 2z` (a 2³ grid at the
/// nodes holds it exactly), `σ_a = σ_s = 0.5` per unit density, and
/// `L_e = 1 + 3z`; rays inside, entering from below and slanting down,
/// against quadrature of `∫ e^{−τ(t)} σ_a(t) L_e(t) dt`.
#[test]
fn a_graded_slab_matches_quadrature() {
    let rho = |z: f64| 0.5 + 2.0 * z;
    let values: Vec<f64> = (0..8).map(|i| rho((i / 4) as f64)).collect();
    let g = Grid::new(&values, 2, 2, 2, 0.5, 0.5).unwrap();
    let mut store = [0.0; 8 * 8 * 8];
    let maj = Majorants::build(&g, [8; 3], &mut store).unwrap();
    let source = |p: Vec3<f64>| 1.0 + 3.0 * p.z;
    let rays = [
        // (origin, unit direction, [a, b] inside the box)
        (
            Vec3::new(0.5, 0.5, -1.0),
            Vec3::new(0.0, 0.0, 1.0),
            (1.0, 2.0),
        ),
        (
            Vec3::new(0.2, 0.3, 0.05),
            Vec3::new(0.3, 0.2, 0.9),
            (0.0, 0.8),
        ),
        (
            Vec3::new(0.1, 0.9, 0.95),
            Vec3::new(0.6, -0.6, -0.5),
            (0.0, 1.1),
        ),
    ];
    let mut r = rng(42);
    for (k, (o, d, (a, b))) in rays.into_iter().enumerate() {
        let d = d * (1.0 / d.length());
        let z = |t: f64| o.z + d.z * t;
        // τ(t) = ∫_a^t σ_t(z(s)) ds, σ_t = ρ, exactly (ρ is linear in t).
        let tau = |t: f64| (t - a) * rho(0.5 * (z(a) + z(t)));
        let want = integrate(
            &|t: f64| (-tau(t)).exp() * 0.5 * rho(z(t)) * source(o + d * t),
            a,
            b,
            1e-13,
        );
        let ray = Ray::new(o, d, if k == 0 { f64::INFINITY } else { b });
        let (l, t) = stats(|| {
            let e = maj
                .emission_track(&g, source, ray, 1 << 20, &mut r)
                .unwrap();
            (e.radiance, e.tr)
        });
        close(&format!("graded ray {k}: radiance"), l, want);
        close(
            &format!("graded ray {k}: transmittance"),
            t,
            (-tau(b)).exp(),
        );
        let ray = Ray::new(o, d, b).segment(a, b);
        let (l, _) = stats(|| {
            let coefficients = |p: Vec3<f64>| (0.5 * rho(p.z), 0.5 * rho(p.z));
            let e = maj
                .emission_track_fn(coefficients, source, ray, 1 << 20, &mut r)
                .unwrap();
            (e.radiance, e.tr)
        });
        close(&format!("graded ray {k} callback: radiance"), l, want);
    }
}

/// Four cells along x, constant in each: the exact integral against
/// quadrature (emission also where there is no extinction), and the
/// tracker, run on the same medium as callbacks with the cells' extinction
/// as majorants, against it.
#[test]
fn a_medium_constant_per_cell_is_integrated_exactly() {
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let sigma = [1.0, 0.0, 2.0, 0.5];
    let emitted = [0.3, 0.7, 0.0, 1.0];
    let s = Majorants::new(&sigma, [4, 1, 1], lo, hi).unwrap();
    let j = Majorants::new(&emitted, [4, 1, 1], lo, hi).unwrap();
    let cell = |t: f64| ((t * 4.0) as usize).min(3);
    // τ at t within cell c (named, not found from t, so that quadrature
    // nodes on a cell's faces take that cell's values).
    let tau =
        |c: usize, t: f64| sigma[..c].iter().sum::<f64>() * 0.25 + sigma[c] * (t - 0.25 * c as f64);
    let ray = Ray::new(Vec3::new(-0.5, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 3.0);
    let e = emission_cells(&s, &j, ray).unwrap();
    let mut want = 0.0;
    for (c, &j) in emitted.iter().enumerate() {
        let (a, b) = (0.25 * c as f64, 0.25 * (c + 1) as f64);
        want += integrate(&|t: f64| (-tau(c, t)).exp() * j, a, b, 1e-14);
    }
    assert!(
        (e.radiance - want).abs() < 1e-13,
        "{} vs {want}",
        e.radiance
    );
    assert!((e.tr - (-tau(3, 1.0)).exp()).abs() < 1e-15);
    assert_eq!(e.steps, 0);
    // The tracker on a medium that can carry it (a pure absorber: L_e =
    // j/σ_a, with j = 0 where σ_a = 0).
    let emitted2 = [0.3, 0.0, 0.8, 1.0];
    let j2 = Majorants::new(&emitted2, [4, 1, 1], lo, hi).unwrap();
    let exact = emission_cells(&s, &j2, ray).unwrap().radiance;
    let at = |p: Vec3<f64>| cell(p.x.clamp(0.0, 1.0));
    let mut r = rng(43);
    let (l, _) = stats(|| {
        let le = |p: Vec3<f64>| {
            let c = at(p);
            if sigma[c] > 0.0 {
                emitted2[c] / sigma[c]
            } else {
                0.0
            }
        };
        let e = s
            .emission_track_fn(|p| (sigma[at(p)], 0.0), le, ray, 1 << 20, &mut r)
            .unwrap();
        (e.radiance, e.tr)
    });
    close("tracker on the cells", l, exact);
}

#[test]
fn bad_input_is_refused() {
    // Dense enough (optical depth 20 on the ray) that a tentative
    // collision, where the source is checked, is all but certain.
    let values = [20.0; 8];
    let g = Grid::new(&values, 2, 2, 2, 0.5, 0.5).unwrap();
    let mut store = [0.0; 8];
    let maj = Majorants::build(&g, [2; 3], &mut store).unwrap();
    let ray = Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::new(0.0, 0.0, 1.0), 3.0);
    let mut r = rng(44);
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            maj.emission_track(&g, |_| bad, ray, 1 << 20, &mut r).err(),
            Some(Error::Domain),
            "L_e = {bad}"
        );
    }
    assert_eq!(
        maj.emission_track(&g, |_| 1.0, ray, 0, &mut r).err(),
        Some(Error::Budget)
    );
    let zero = Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::new(0.0, 0.0, 0.0), 3.0);
    assert_eq!(
        maj.emission_track(&g, |_| 1.0, zero, 1 << 20, &mut r).err(),
        Some(Error::Domain)
    );
    let other = [1.0; 4];
    let m2 = Majorants::new(
        &other,
        [2, 2, 1],
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 1.0),
    )
    .unwrap();
    assert_eq!(emission_cells(&maj, &m2, ray).err(), Some(Error::Domain));
    // A bad emitted value in a cell the ray crosses, stored after the
    // check (as through C), stops the walk (a mutation test found no test
    // giving one).
    let (lo, hi) = maj.bounds();
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        let stored = [bad; 8];
        let j = Majorants::from_parts(&stored, [2; 3], lo, hi).unwrap();
        assert_eq!(
            emission_cells(&maj, &j, ray).err(),
            Some(Error::Domain),
            "J = {bad}"
        );
    }
    // Coefficients above the majorant.
    assert_eq!(
        maj.emission_track_fn(|_| (50.0, 0.0), |_| 1.0, ray, 1 << 20, &mut r)
            .err(),
        Some(Error::Domain)
    );
}

/// `∫ e^{−τ(t)} σ_a(t) L_e(t) dt` and `e^{−τ}` along the ray through `g`
/// over `[0, t_max]`, by the trapezoid rule on 2·10⁵ panels with `τ`
/// accumulated on the same panels (error ~10⁻⁹ here, far below the
/// Monte Carlo's).
fn emitted(
    g: &Grid<'_, f64>,
    source: impl Fn(Vec3<f64>) -> f64,
    o: Vec3<f64>,
    d: Vec3<f64>,
    t_max: f64,
) -> (f64, f64) {
    let d = d * (1.0 / d.length());
    let (sa, ss) = g.coefficients();
    let n = 200_000;
    let h = t_max / n as f64;
    let at = |i: usize| {
        let p = o + d * (i as f64 * h);
        let rho = g.density(p);
        ((sa + ss) * rho, sa * rho * source(p))
    };
    let (mut tau, mut l) = (0.0, 0.0);
    let mut prev = at(0);
    for i in 1..=n {
        let next = at(i);
        let tau_next = tau + 0.5 * h * (prev.0 + next.0);
        l += 0.5 * h * ((-tau).exp() * prev.1 + (-tau_next).exp() * next.1);
        (tau, prev) = (tau_next, next);
    }
    (l, (-tau).exp())
}

#[test]
fn emission_through_the_cloud_matches_quadrature() {
    let source = |p: Vec3<f64>| 1.0 + 0.5 * p.x + 0.25 * p.y * p.y;
    for_each_grid(|g, rays, case| {
        let mut store = [0.0; 16 * 16 * 16];
        let maj = Majorants::build(g, [16; 3], &mut store).unwrap();
        let mut r = rng(50 + case);
        for (k, &(o, d, t_max)) in rays.iter().enumerate() {
            let (want, tr) = emitted(g, source, o, d, t_max);
            let ray = Ray::new(o, d, t_max);
            let (l, t) = stats(|| {
                let e = maj.emission_track(g, source, ray, 1 << 20, &mut r).unwrap();
                (e.radiance, e.tr)
            });
            close(&format!("case {case} ray {k}: radiance"), l, want);
            close(&format!("case {case} ray {k}: transmittance"), t, tr);
        }
    });
}
