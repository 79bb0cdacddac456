//! Residual ratio tracking (`Extrema`): unbiased against the optical depth
//! integrated along the ray, over the rays and grids of `majorant.rs`
//! (inside starts, faces, grazing, empty cells, both samplings, a world
//! box), 4·10⁴ rays per case at 4σ; exact for a medium constant in each
//! cell; the built minorants bound the density from below; and its
//! variance × density evaluations against ratio tracking with the same
//! majorants on the cloud.

use super::majorant::{check_bounds, cloud, for_each_grid, mean_se, optical_depth, rays};
use crate::common::rng;
use scatterkit::majorant::{DEFAULT_RES, Majorants};
use scatterkit::medium::residual::{Extrema, RESIDUAL_RATE};
use scatterkit::{Error, Grid, Ray, Vec3};

/// Unbiased on every ray of every case; and the check has the power to
/// see a wrong estimator: counting the control's optical depth twice
/// (`exp(−2τ_c)`, as an estimator that applied the control to the
/// residual walk's weights as well would) fails it on the ray through the
/// core in every case.
#[test]
fn residual_ratio_tracking_is_unbiased() {
    for_each_grid(|g, rays, case| {
        let (mut max, mut min) = ([0.0; 16 * 16 * 16], [0.0; 16 * 16 * 16]);
        let ext = Extrema::build(g, [DEFAULT_RES; 3], &mut max, &mut min).unwrap();
        let mut r = rng(70 + case);
        for (k, &(o, d, t_max)) in rays.iter().enumerate() {
            let ray = Ray::new(o, d, t_max);
            let p = (-optical_depth(g, o, d, t_max)).exp();
            let tr: Vec<f64> = (0..40_000)
                .map(|_| {
                    ext.residual_ratio_track(g, ray, 1 << 20, &mut r)
                        .unwrap()
                        .tr
                })
                .collect();
            let (m, se) = mean_se(&tr);
            assert!(
                (m - p).abs() <= 4.0 * se + 1e-12,
                "case {case} ray {k}: {m} ± {se} vs {p}"
            );
            if k == 0 {
                let tau_c = ext.control_depth(ray).unwrap();
                let wrong = (-tau_c).exp();
                let (mw, sw) = (m * wrong, se * wrong);
                assert!(
                    (mw - p).abs() > 4.0 * sw,
                    "case {case}: the control counted twice passes (τ_c {tau_c})"
                );
            }
        }
    });
}

/// Every rate is unbiased, not only the default: rates 1 (Novák et al.'s)
/// and 3 on every ray, grids read at nodes and at cells, 4σ; and rate 0 is the
/// default, [`RESIDUAL_RATE`], draw for draw.
#[test]
fn residual_ratio_tracking_is_unbiased_at_every_rate() {
    for_each_grid(|g, rays, case| {
        if case % 2 == 1 {
            return;
        }
        let (mut max, mut min) = ([0.0; 16 * 16 * 16], [0.0; 16 * 16 * 16]);
        let ext = Extrema::build(g, [DEFAULT_RES; 3], &mut max, &mut min).unwrap();
        let coefficients = |p| g.coefficients_at(p);
        for (k, &(o, d, t_max)) in rays.iter().enumerate() {
            let ray = Ray::new(o, d, t_max);
            let p = (-optical_depth(g, o, d, t_max)).exp();
            for rate in [1, 3] {
                let mut r = rng(90 + case + rate as u64);
                let tr: Vec<f64> = (0..40_000)
                    .map(|_| {
                        let x =
                            ext.residual_ratio_track_rate(coefficients, ray, rate, 1 << 20, &mut r);
                        x.unwrap().tr
                    })
                    .collect();
                let (m, se) = mean_se(&tr);
                assert!(
                    (m - p).abs() <= 4.0 * se + 1e-12,
                    "case {case} ray {k} rate {rate}: {m} ± {se} vs {p}"
                );
            }
            let (mut r0, mut r2) = (rng(5), rng(5));
            for _ in 0..100 {
                let a = ext.residual_ratio_track_rate(coefficients, ray, 0, 1 << 20, &mut r0);
                let b = ext.residual_ratio_track_rate(
                    coefficients,
                    ray,
                    RESIDUAL_RATE,
                    1 << 20,
                    &mut r2,
                );
                assert_eq!(a, b);
            }
        }
    });
}

/// The length of the ray `o + t d/|d|`, `t ∈ [0, t_max]`, inside the unit
/// cube (slabs).
fn inside_unit_cube(o: Vec3<f64>, d: Vec3<f64>, t_max: f64) -> f64 {
    let d = d * (1.0 / d.length());
    let (mut a, mut b) = (0.0f64, t_max);
    for (oc, dc) in [(o.x, d.x), (o.y, d.y), (o.z, d.z)] {
        if dc == 0.0 {
            if !(0.0..=1.0).contains(&oc) {
                return 0.0;
            }
        } else {
            let (t0, t1) = ((0.0 - oc) / dc, (1.0 - oc) / dc);
            a = a.max(t0.min(t1));
            b = b.min(t0.max(t1));
        }
    }
    (b - a).max(0.0)
}

/// A medium constant in each majorant cell: the minorant is `σ_t` itself
/// and the majorant a few ULP above it, almost no collision is drawn, and
/// every estimate is the exact transmittance `exp(−σ_t ℓ)`, `ℓ` the length
/// inside the box (computed in closed form: Simpson's rule across the
/// box's faces, where the density jumps, is off by 10⁻⁵). Where the
/// residual majorant's few ULP do draw, the collision weighs exactly 1: in
/// f32 at a rate that makes draws likely, every estimate along a ray is
/// the same number. (With a minorant a few ULP below `σ_t`, as before, a
/// draw weighed a half at rate 1: the main example's constant medium
/// showed a variance of 2.5·10⁻⁹ where it claimed 0.)
#[test]
fn a_constant_medium_has_zero_variance() {
    let values = [2.5f64; 27];
    let g = Grid::new(&values, 3, 3, 3, 0.3, 0.9).unwrap();
    let (mut max, mut min) = ([0.0; 64], [0.0; 64]);
    let ext = Extrema::build(&g, [4; 3], &mut max, &mut min).unwrap();
    let mut r = rng(5);
    for (o, d, t_max) in rays() {
        let want = (-1.2 * 2.5 * inside_unit_cube(o, d, t_max)).exp();
        for _ in 0..1000 {
            let t = ext
                .residual_ratio_track(&g, Ray::new(o, d, t_max), 10, &mut r)
                .unwrap();
            assert!(t.steps <= 1, "{} steps", t.steps);
            assert!(
                (t.tr - want).abs() <= 1e-12 * want.max(1e-300) + 1e-15,
                "{} vs {want}",
                t.tr
            );
        }
    }
    let values = [2.5f32; 27];
    let g = Grid::new(&values, 3, 3, 3, 0.3, 0.9).unwrap();
    let (mut max, mut min) = ([0.0f32; 64], [0.0f32; 64]);
    let ext = Extrema::build(&g, [4; 3], &mut max, &mut min).unwrap();
    let coefficients = |p| g.coefficients_at(p);
    let mut drawn = 0;
    for (o, d, t_max) in rays() {
        let f = |v: Vec3<f64>| Vec3::new(v.x as f32, v.y as f32, v.z as f32);
        let ray = Ray::new(f(o), f(d), t_max as f32);
        let first = ext
            .residual_ratio_track_rate(coefficients, ray, 1, 10, &mut r)
            .unwrap();
        for _ in 0..1000 {
            let t = ext
                .residual_ratio_track_rate(coefficients, ray, 4_000_000, 1 << 20, &mut r)
                .unwrap();
            drawn += t.steps;
            assert_eq!(t.tr, first.tr, "{} steps", t.steps);
        }
    }
    assert!(drawn > 1000, "{drawn} collisions drawn");
}

#[test]
fn built_minorants_bound_the_density_from_below() {
    check_bounds(4, true, |sigma_t, bound| sigma_t >= bound);
}

#[test]
fn extrema_that_do_not_pair_are_refused() {
    let values = cloud();
    let g = Grid::new(&values, 12, 10, 9, 0.4, 1.1).unwrap();
    let (mut a, mut b, mut c, zeros) = ([0.0; 64], [0.0; 64], [0.0; 27], [0.0; 64]);
    let max = Majorants::build(&g, [4; 3], &mut a).unwrap();
    let min = Majorants::build_minorants(&g, [4; 3], &mut b).unwrap();
    let coarse = Majorants::build_minorants(&g, [3; 3], &mut c).unwrap();
    assert!(Extrema::new(max, min).is_ok());
    assert_eq!(
        Extrema::new(max, coarse).err(),
        Some(Error::Domain),
        "other cells"
    );
    assert_eq!(
        Extrema::new(min, max).err(),
        Some(Error::Domain),
        "minorant above majorant"
    );
    let (lo, hi) = max.bounds();
    let shifted = Majorants::new(&zeros, [4; 3], lo, hi + Vec3::new(1.0, 0.0, 0.0)).unwrap();
    assert_eq!(
        Extrema::new(max, shifted).err(),
        Some(Error::Domain),
        "other box"
    );
    // Extrema of another box are refused for the grid.
    let wide = g.with_box(lo, hi + Vec3::new(1.0, 0.0, 0.0)).unwrap();
    let ext = Extrema::new(max, min).unwrap();
    let ray = Ray::new(Vec3::new(-0.1, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 2.0);
    assert_eq!(
        ext.residual_ratio_track(&wide, ray, 100, &mut rng(1)).err(),
        Some(Error::Domain)
    );
}

/// Variance × density evaluations per ray on the cloud, residual ratio
/// tracking against ratio tracking with the same 16³ majorants (printed;
/// the figures are in `docs/guides/media.md`). Fixed beforehand: residual
/// ratio tracking at least 2× better on the ray through the core.
#[test]
fn residual_ratio_tracking_costs_less_variance_than_ratio_tracking() {
    let values = cloud();
    let g = Grid::new(&values, 12, 10, 9, 0.4, 1.1).unwrap();
    let (mut max, mut min) = ([0.0; 16 * 16 * 16], [0.0; 16 * 16 * 16]);
    let ext = Extrema::build(&g, [16; 3], &mut max, &mut min).unwrap();
    let maj = ext.majorants();
    let mut r = rng(11);
    let n = 20_000;
    for (k, (o, d, t_max)) in rays().into_iter().enumerate() {
        let ray = Ray::new(o, d, t_max);
        let (mut a, mut b, mut sa, mut sb) = (vec![], vec![], 0u64, 0u64);
        for _ in 0..n {
            let x = maj.ratio_track(&g, ray, 1 << 20, &mut r).unwrap();
            let y = ext.residual_ratio_track(&g, ray, 1 << 20, &mut r).unwrap();
            (sa, sb) = (sa + x.steps as u64, sb + y.steps as u64);
            a.push(x.tr);
            b.push(y.tr);
        }
        let var = |v: &[f64]| {
            let (m, se) = mean_se(v);
            let _ = m;
            se * se * v.len() as f64
        };
        let (cost_a, cost_b) = (sa as f64 / n as f64, sb as f64 / n as f64);
        let (va, vb) = (var(&a), var(&b));
        let gain = if vb * cost_b > 0.0 {
            format!("{:.1}× lower", (va * cost_a) / (vb * cost_b))
        } else {
            "both exact".to_string()
        };
        eprintln!(
            "ray {k}: ratio var {va:.3e} × {cost_a:.2} evals, residual var {vb:.3e} × {cost_b:.2} evals: {gain}"
        );
        if k == 0 {
            assert!(
                va * cost_a >= 2.0 * vb * cost_b,
                "ray 0: {va} × {cost_a} vs {vb} × {cost_b}"
            );
        }
    }
}

/// A minorant above `σ_t`, as the docs allow: unbiased where the cell's
/// residual majorant is positive (its weights exceed 1), and where the
/// minorant equals the majorant no density is read and the cell counts
/// at that value, as documented. One cell of the unit cube, `σ_t = ½`,
/// the ray through it along x (length 1, so `T = e^{−½}`): minorant 0.9
/// under majorant 1 within 4σ of `e^{−½}` over 4·10⁴ rays at rates 1 and
/// 2; minorant = majorant = 1 gives `e^{−1}` on every ray without a
/// call to the medium.
#[test]
fn a_minorant_above_the_density_is_unbiased_where_the_residual_is_positive() {
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let ray = Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 2.0);
    let medium = |_: Vec3<f64>| (0.0, 0.5);
    let want = (-0.5f64).exp();
    let (max, min) = ([1.0], [0.9]);
    let ext = Extrema::new(
        Majorants::new(&max, [1, 1, 1], lo, hi).unwrap(),
        Majorants::new(&min, [1, 1, 1], lo, hi).unwrap(),
    )
    .unwrap();
    for rate in [1, 2] {
        let mut r = rng(300 + rate as u64);
        let tr: Vec<f64> = (0..40_000)
            .map(|_| {
                let x = ext.residual_ratio_track_rate(medium, ray, rate, 1 << 20, &mut r);
                x.unwrap().tr
            })
            .collect();
        let (m, se) = mean_se(&tr);
        assert!(
            (m - want).abs() <= 4.0 * se,
            "rate {rate}: {m} ± {se} vs {want}"
        );
        assert!(
            tr.iter().any(|&x| x > 1.0),
            "rate {rate}: no weight above 1"
        );
    }
    let equal = [1.0];
    let ext = Extrema::new(
        Majorants::new(&equal, [1, 1, 1], lo, hi).unwrap(),
        Majorants::new(&equal, [1, 1, 1], lo, hi).unwrap(),
    )
    .unwrap();
    let unread = |_: Vec3<f64>| -> (f64, f64) { panic!("the medium was read") };
    let mut r = rng(310);
    for _ in 0..100 {
        let x = ext
            .residual_ratio_track_fn(unread, ray, 1 << 20, &mut r)
            .unwrap();
        assert_eq!((x.tr, x.steps), ((-1.0f64).exp(), 0));
    }
}

/// The caller's coefficients are checked at each collision: a negative
/// one on either side, or a sum above the cell's majorant however it is
/// split, is refused (a mutation test accepted a negative σ_s beside a
/// positive σ_a, and a σ_s far above the majorant read as `σ_a − σ_s`,
/// unnoticed).
#[test]
fn bad_coefficients_are_refused_at_a_collision() {
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(8.0, 1.0, 1.0));
    let (max, min) = ([2.0], [0.5]);
    let ext = Extrema::new(
        Majorants::new(&max, [1; 3], lo, hi).unwrap(),
        Majorants::new(&min, [1; 3], lo, hi).unwrap(),
    )
    .unwrap();
    // Twelve mean free paths of the residual: a collision is all but sure.
    let ray = Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 8.0);
    let mut r = rng(12);
    for c in [(1.0, -0.25), (-0.25, 1.0), (0.1, 5.0), (5.0, 0.1)] {
        for rate in [1, 16] {
            let got = ext.residual_ratio_track_rate(move |_| c, ray, rate, 1 << 20, &mut r);
            assert_eq!(got.err(), Some(Error::Domain), "{c:?} at rate {rate}");
        }
    }
    // Within the bounds it runs.
    let got = ext.residual_ratio_track_rate(|_| (0.5, 1.0), ray, 16, 1 << 20, &mut r);
    assert!(got.is_ok());
}
