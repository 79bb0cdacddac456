//! Participating media: unbiasedness within 4σ of the homogeneous weights,
//! free-path and collision-distance distributions (KS), delta and ratio
//! tracking through a constant grid, a linear gradient and a spherical blob
//! with analytic optical depth, ratio tracking's variance below the binary
//! estimator's, rays that miss, start or end inside the medium, a callback
//! density above its majorant, the step cap, and bad input.

use crate::common;

use common::chi2::threshold;
use common::ks::{ks_critical, ks_statistic};
use common::rng;
use scatterkit::medium::{
    self, Event, MAX_STEPS, clip_unit_cube, delta_track_fn, free_path, homogeneous_sample,
    ratio_track_fn, transmittance,
};
use scatterkit::{Error, Grid, Ray, Real, Vec3};

const N: usize = 200_000;

/// Mean and standard error of `xs`.
fn mean_se(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let v = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, (v / n).sqrt())
}

fn within_4_sigma(xs: &[f64], expected: f64) -> bool {
    let (m, se) = mean_se(xs);
    (m - expected).abs() <= 4.0 * se + 1e-12
}

#[test]
fn homogeneous_weights_are_unbiased_per_channel() {
    fn check<T: Real>() {
        let st = [0.5, 1.0, 2.0, 0.0].map(T::from_f64);
        let ss = [0.4, 0.5, 1.9, 0.0].map(T::from_f64);
        let t_max = 1.3;
        let mut r = rng(1);
        let mut surf: Vec<Vec<f64>> = vec![Vec::new(); 4];
        let mut med: Vec<Vec<f64>> = vec![Vec::new(); 4];
        let mut w = [T::ZERO; 4];
        for _ in 0..N {
            let s = homogeneous_sample(
                &st,
                &ss,
                T::from_f64(t_max),
                T::uniform(&mut r),
                T::uniform(&mut r),
                &mut w,
            )
            .unwrap();
            for c in 0..4 {
                let b = w[c].to_f64();
                surf[c].push(if s.scattered { 0.0 } else { b });
                med[c].push(if s.scattered { b } else { 0.0 });
            }
        }
        for c in 0..4 {
            let (sigma_t, sigma_s) = (st[c].to_f64(), ss[c].to_f64());
            let tr = (-sigma_t * t_max).exp();
            let med_expected = if sigma_t > 0.0 {
                sigma_s * (1.0 - tr) / sigma_t
            } else {
                0.0
            };
            assert!(
                within_4_sigma(&surf[c], tr),
                "channel {c}: surface {:?} vs {tr}",
                mean_se(&surf[c])
            );
            assert!(
                within_4_sigma(&med[c], med_expected),
                "channel {c}: medium {:?} vs {med_expected}",
                mean_se(&med[c])
            );
        }
    }
    check::<f32>();
    check::<f64>();
}

#[test]
fn free_paths_are_exponential() {
    let sigma = 2.5f64;
    let mut r = rng(2);
    let mut xs: Vec<f64> = (0..N)
        .map(|_| free_path(sigma, f64::uniform(&mut r)))
        .collect();
    let d = ks_statistic(&mut xs, |t| -(-sigma * t).exp_m1());
    assert!(d < ks_critical(threshold(), N), "D = {d}");
    assert_eq!(free_path(0.0f32, 0.5), f32::INFINITY);
    assert_eq!(free_path(1.0f64, 1.0), f64::INFINITY);
    assert_eq!(free_path(1.0f64, 0.0), 0.0);
    assert!(free_path(-1.0f64, 0.5).is_nan() && free_path(f64::NAN, 0.5).is_nan());
    assert!(free_path(1.0f64, f64::NAN).is_nan());
    // Small u: −ln1p(−u) keeps every digit of u.
    assert_eq!(free_path(1.0f64, 1e-300), 1e-300);
    assert_eq!(transmittance(0.0f64, f64::INFINITY), 1.0);
    assert_eq!(transmittance(1.0f64, f64::INFINITY), 0.0);
    assert!(transmittance(-1.0f64, 1.0).is_nan());
}

/// `k` density units along x: a 2×1×1 grid with nodes 0 and 1, σ_s = k.
fn gradient(k: f64) -> ([f64; 2], f64) {
    ([0.0, 1.0], k)
}

#[test]
fn gradient_grid_matches_analytic_depth() {
    let (values, k) = gradient(3.0);
    let grid = Grid::new(&values, 2, 1, 1, 0.0, k).unwrap();
    // Density is x exactly: τ(t) = k t²/2 along +x from (0, ½, ½).
    assert!((grid.density(Vec3::new(0.3, 0.5, 0.5)) - 0.3).abs() < 1e-15);
    let (o, d) = (Vec3::new(-1.0, 0.5, 0.5), Vec3::new(2.0, 0.0, 0.0)); // any length
    let tau_total = k / 2.0;
    let mut r = rng(3);
    let (mut escaped, mut dists) = (0usize, Vec::new());
    for _ in 0..N {
        let (t, e) = grid.delta_track(Ray::new(o, d, 3.0), &mut r).unwrap();
        match e {
            Event::Escaped => {
                assert_eq!(t, 3.0);
                escaped += 1
            }
            Event::Scattered => dists.push(t - 1.0), // distance into the cube
            other => panic!("albedo 1 never absorbs: {other:?}"),
        }
    }
    let p = (-tau_total).exp();
    let se = (p * (1.0 - p) / N as f64).sqrt();
    assert!(
        (escaped as f64 / N as f64 - p).abs() < 4.0 * se,
        "P(escape) {} vs {p}",
        escaped as f64 / N as f64
    );
    // Collision distance given a collision: (1 − e^{−k t²/2})/(1 − e^{−k/2}).
    let n = dists.len();
    let dstat = ks_statistic(&mut dists, |t| {
        -(-k * t * t / 2.0).exp_m1() / -(-tau_total).exp_m1()
    });
    assert!(dstat < ks_critical(threshold(), n), "D = {dstat}");
    // Ratio tracking: mean e^{−τ}, variance below the binary estimator's.
    let est: Vec<f64> = (0..N)
        .map(|_| grid.ratio_track(Ray::new(o, d, 3.0), &mut r).unwrap())
        .collect();
    assert!(within_4_sigma(&est, p), "ratio {:?} vs {p}", mean_se(&est));
    let (_, se_ratio) = mean_se(&est);
    assert!(
        se_ratio < se,
        "ratio tracking's variance must be below the binary estimator's"
    );
}

#[test]
fn constant_grid_and_rays_that_start_end_or_miss() {
    let values = [2.0f64; 8];
    let grid = Grid::new(&values, 2, 2, 2, 0.5, 1.5).unwrap(); // σ_t = 4 everywhere
    let mut r = rng(4);
    let cases = [
        // (origin, direction, t_max, optical depth)
        (
            Vec3::new(-0.5, 0.3, 0.7),
            Vec3::new(1.0, 0.0, 0.0),
            10.0,
            4.0,
        ), // through
        (
            Vec3::new(0.5, 0.5, 0.5),
            Vec3::new(0.0, 1.0, 0.0),
            10.0,
            2.0,
        ), // starts inside
        (
            Vec3::new(-0.2, 0.5, 0.5),
            Vec3::new(1.0, 0.0, 0.0),
            0.5,
            1.2,
        ), // ends inside
        (Vec3::new(0.2, 0.5, 0.5), Vec3::new(0.0, 0.0, 1.0), 0.3, 1.2), // both inside
        (
            Vec3::new(2.0, 2.0, 2.0),
            Vec3::new(1.0, 0.0, 0.0),
            10.0,
            0.0,
        ), // misses
    ];
    for (o, d, t_max, tau) in cases {
        let p = (-tau).exp();
        let mut escaped = 0;
        let mut absorbed = 0;
        for _ in 0..N {
            let (t, e) = grid.delta_track(Ray::new(o, d, t_max), &mut r).unwrap();
            assert!(t <= t_max);
            escaped += (e == Event::Escaped) as usize;
            absorbed += (e == Event::Absorbed) as usize;
        }
        let se = (p * (1.0 - p) / N as f64).sqrt();
        assert!(
            (escaped as f64 / N as f64 - p).abs() <= 4.0 * se + 1e-12,
            "{o:?}: {} vs {p}",
            escaped as f64 / N as f64
        );
        // Albedo 0.75: a quarter of the collisions absorb.
        let coll = N - escaped;
        if coll > 1000 {
            let q = absorbed as f64 / coll as f64;
            assert!(
                (q - 0.25).abs() < 4.0 * (0.25 * 0.75 / coll as f64).sqrt(),
                "absorbed share {q}"
            );
        }
        let est: Vec<f64> = (0..N / 4)
            .map(|_| grid.ratio_track(Ray::new(o, d, t_max), &mut r).unwrap())
            .collect();
        assert!(
            within_4_sigma(&est, p),
            "ratio {o:?}: {:?} vs {p}",
            mean_se(&est)
        );
    }
    // A miss returns at once, without drawing.
    let mut probe = rng(5);
    let before = probe.clone();
    assert_eq!(
        grid.delta_track(
            Ray::new(Vec3::new(2.0, 2.0, 2.0), Vec3::new(1.0, 0.0, 0.0), 10.0),
            &mut probe
        ),
        Ok((10.0, Event::Escaped))
    );
    assert_eq!(
        grid.ratio_track(
            Ray::new(Vec3::new(2.0, 2.0, 2.0), Vec3::new(1.0, 0.0, 0.0), 10.0),
            &mut probe
        ),
        Ok(1.0)
    );
    assert_eq!(format!("{probe:?}"), format!("{before:?}"));
    assert_eq!(
        clip_unit_cube(
            Vec3::new(0.5, 0.5, 0.5),
            Vec3::new(0.0, 0.0, 1.0),
            0.0,
            10.0
        ),
        Some((0.0, 0.5))
    );
}

#[test]
fn spherical_blob_through_a_callback() {
    // σ_t = σ0 (1 − r²/R²) inside a ball of radius R about c; a ray through
    // the centre from distance R before it: τ(t) = σ0 (t − ((t − R)³ + R³)/(3R²)).
    let (sigma0, radius, c) = (2.0f64, 0.8f64, Vec3::new(0.1, -0.2, 0.3));
    let sigma = move |p: Vec3<f64>| {
        let q = p - c;
        (sigma0 * (1.0 - q.dot(q) / (radius * radius))).max(0.0)
    };
    let dir = Vec3::new(1.0, 2.0, -2.0).try_normalize().unwrap();
    let o = c - dir * radius;
    let tau =
        |t: f64| sigma0 * (t - ((t - radius).powi(3) + radius.powi(3)) / (3.0 * radius * radius));
    let total = tau(2.0 * radius);
    assert!((total - sigma0 * 4.0 * radius / 3.0).abs() < 1e-12);
    let mut r = rng(6);
    let mut dists = Vec::new();
    let mut escaped = 0usize;
    for _ in 0..N {
        match delta_track_fn(
            sigma,
            sigma0,
            Ray::new(o, dir * 3.0, 2.0 * radius).segment(0.0, 2.0 * radius),
            &mut r,
        )
        .unwrap()
        {
            (t, Event::Collided) => dists.push(t),
            (_, Event::Escaped) => escaped += 1,
            other => panic!("{other:?}"),
        }
    }
    let p = (-total).exp();
    assert!((escaped as f64 / N as f64 - p).abs() < 4.0 * (p * (1.0 - p) / N as f64).sqrt());
    let n = dists.len();
    let dstat = ks_statistic(&mut dists, |t| -(-tau(t)).exp_m1() / -(-total).exp_m1());
    assert!(dstat < ks_critical(threshold(), n), "D = {dstat}");
    let est: Vec<f64> = (0..N)
        .map(|_| {
            ratio_track_fn(
                sigma,
                sigma0,
                Ray::new(o, dir, 2.0 * radius).segment(0.0, 2.0 * radius),
                &mut r,
            )
            .unwrap()
        })
        .collect();
    assert!(within_4_sigma(&est, p), "ratio {:?} vs {p}", mean_se(&est));
}

#[test]
fn a_density_above_the_majorant_is_reported() {
    let too_dense = |_: Vec3<f64>| 2.0;
    let (o, d) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
    let mut r = rng(7);
    assert_eq!(
        delta_track_fn(
            too_dense,
            1.0,
            Ray::new(o, d, 10.0).segment(0.0, 10.0),
            &mut r
        ),
        Err(Error::Domain)
    );
    assert_eq!(
        ratio_track_fn(
            too_dense,
            1.0,
            Ray::new(o, d, 10.0).segment(0.0, 10.0),
            &mut r
        ),
        Err(Error::Domain)
    );
    let negative = |_: Vec3<f64>| -0.1;
    assert_eq!(
        delta_track_fn(
            negative,
            1.0,
            Ray::new(o, d, 10.0).segment(0.0, 10.0),
            &mut r
        ),
        Err(Error::Domain)
    );
    let nan = |_: Vec3<f64>| f64::NAN;
    assert_eq!(
        ratio_track_fn(nan, 1.0, Ray::new(o, d, 10.0).segment(0.0, 10.0), &mut r),
        Err(Error::Domain)
    );
}

#[test]
fn zero_majorant_and_step_cap() {
    let (o, d) = (Vec3::new(0.0f64, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
    let mut r = rng(8);
    assert_eq!(
        delta_track_fn(
            |_| 0.0,
            0.0,
            Ray::new(o, d, f64::INFINITY).segment(0.0, f64::INFINITY),
            &mut r
        ),
        Ok((f64::INFINITY, Event::Escaped))
    );
    assert_eq!(
        ratio_track_fn(|_| 0.0, 0.0, Ray::new(o, d, 5.0).segment(0.0, 5.0), &mut r),
        Ok(1.0)
    );
    let empty = Grid::new(&[0.0f64; 8], 2, 2, 2, 1.0, 1.0).unwrap();
    assert_eq!(
        empty.delta_track(Ray::new(Vec3::new(-1.0, 0.5, 0.5), d, 9.0), &mut r),
        Ok((9.0, Event::Escaped))
    );
    // A majorant far above the density over a long path: more than 2^20
    // tentative collisions, reported rather than cut short.
    let steps = MAX_STEPS as f64 * 4.0;
    assert_eq!(
        delta_track_fn(
            |_| 0.0,
            steps,
            Ray::new(o, d, 1.0).segment(0.0, 1.0),
            &mut r
        ),
        Err(Error::Budget)
    );
    assert_eq!(
        ratio_track_fn(
            |_| 1.0,
            steps,
            Ray::new(o, d, 1.0).segment(0.0, 1.0),
            &mut r
        ),
        Err(Error::Budget)
    );
}

#[test]
fn bad_input_is_rejected() {
    let v = [1.0f64; 8];
    assert_eq!(Grid::new(&v, 0, 2, 2, 1.0, 1.0).err(), Some(Error::Size));
    assert_eq!(
        Grid::new(&v, usize::MAX, 2, 2, 1.0, 1.0).err(),
        Some(Error::Size)
    );
    assert_eq!(
        Grid::new(&v, 3, 2, 2, 1.0, 1.0).err(),
        Some(Error::Size),
        "buffer too short"
    );
    assert_eq!(
        Grid::new(&[1.0, -1.0], 2, 1, 1, 1.0, 1.0).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        Grid::new(&[1.0, f64::NAN], 2, 1, 1, 1.0, 1.0).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        Grid::new(&[1.0, f64::INFINITY], 2, 1, 1, 1.0, 1.0).err(),
        Some(Error::Domain)
    );
    assert_eq!(Grid::new(&v, 2, 2, 2, -1.0, 1.0).err(), Some(Error::Domain));
    assert_eq!(
        Grid::new(&v, 2, 2, 2, 1.0, f64::NAN).err(),
        Some(Error::Domain)
    );
    // Each factor finite, the majorant (σ_a + σ_s)·max(density) not: tracking
    // could not step through it (it used to report the ray as escaping).
    assert_eq!(
        Grid::new(&[1e200, 1.0], 2, 1, 1, 1e200, 0.0).err(),
        Some(Error::Domain),
        "overflowing majorant"
    );
    assert!(Grid::new(&[1e150, 1.0], 2, 1, 1, 1e150, 0.0).is_ok());
    let g = Grid::new(&v, 2, 2, 2, 1.0, 1.0).unwrap();
    let mut r = rng(9);
    let (o, d, z) = (
        Vec3::new(0.5, 0.5, 0.5),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 0.0),
    );
    assert_eq!(
        g.delta_track(Ray::new(o, z, 1.0), &mut r).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        g.delta_track(Ray::new(Vec3::new(f64::NAN, 0.0, 0.0), d, 1.0), &mut r)
            .err(),
        Some(Error::Domain)
    );
    assert_eq!(
        g.delta_track(Ray::new(o, d, -1.0), &mut r).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        g.ratio_track(Ray::new(o, z, 1.0), &mut r),
        Err(Error::Domain)
    );
    assert_eq!(
        delta_track_fn(|_| 0.5, 1.0, Ray::new(o, d, 1.0).segment(2.0, 1.0), &mut r).err(),
        Some(Error::Domain),
        "t_max < t_min"
    );
    assert_eq!(
        delta_track_fn(|_| 0.5, -1.0, Ray::new(o, d, 1.0).segment(0.0, 1.0), &mut r).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        delta_track_fn(
            |_| 0.5,
            f64::INFINITY,
            Ray::new(o, d, 1.0).segment(0.0, 1.0),
            &mut r
        )
        .err(),
        Some(Error::Domain)
    );
    let st = [1.0f64, 2.0];
    let mut w = [7.0f64; 2];
    assert_eq!(
        homogeneous_sample(&st, &[1.5, 1.0], 1.0, 0.5, 0.5, &mut w).err(),
        Some(Error::Domain),
        "σ_s > σ_t"
    );
    assert_eq!(
        homogeneous_sample(&[1.0, -2.0], &[0.5, 0.0], 1.0, 0.5, 0.5, &mut w).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        homogeneous_sample(&st, &[0.5, 1.0], f64::NAN, 0.5, 0.5, &mut w).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        homogeneous_sample::<f64>(&[], &[], 1.0, 0.5, 0.5, &mut []).err(),
        Some(Error::Size)
    );
    assert_eq!(
        homogeneous_sample(&st, &[0.5], 1.0, 0.5, 0.5, &mut w).err(),
        Some(Error::Size)
    );
    assert_eq!(w, [7.0; 2], "nothing written on error");
    let _ = medium::grid_len(1, 1, 1);
}

#[test]
fn ratio_tracking_stops_once_the_transmittance_is_gone() {
    // σ_maj = 10 σ_t over 10⁵ mean free paths: each tentative collision
    // keeps 0.9 of the weight, so without roulette the product sank to the
    // smallest subnormal and the walk ran to the step cap (10⁶ calls).
    fn check<T: Real>() {
        let mut r = rng(41);
        let (o, d) = (
            Vec3::new(T::ZERO, T::ZERO, T::ZERO),
            Vec3::new(T::ONE, T::ZERO, T::ZERO),
        );
        let (sigma_t, sigma_maj) = (T::ONE, T::from_f64(10.0));
        for _ in 0..200 {
            let calls = core::cell::Cell::new(0u32);
            let density = |_| {
                calls.set(calls.get() + 1);
                sigma_t
            };
            let t_max = T::from_f64(1e5);
            let tr = ratio_track_fn(
                density,
                sigma_maj,
                Ray::new(o, d, t_max).segment(T::ZERO, t_max),
                &mut r,
            )
            .unwrap();
            assert_eq!(tr, T::ZERO, "e^-1e5 is 0 in any precision");
            assert!(calls.get() < 10_000, "{} density calls", calls.get());
        }
    }
    check::<f32>();
    check::<f64>();
}

#[test]
fn no_valid_ray_yields_nan() {
    // Random media (thin to dense, 2–5 nodes per axis), random rays inside,
    // outside and axis-parallel, random lengths (some infinite): every
    // ratio tracking estimate is finite and non-negative, every delta
    // tracking result a distance in range.
    let mut r = rng(42);
    let mut u = move || f64::uniform(&mut r);
    let mut r2 = rng(43);
    for case in 0..2000 {
        let n = [
            2 + (u() * 4.0) as usize,
            2 + (u() * 4.0) as usize,
            2 + (u() * 4.0) as usize,
        ];
        let scale = 10f64.powf(4.0 * u() - 1.0);
        let mut values = [0.0f64; 125];
        for v in values.iter_mut() {
            *v = if u() < 0.3 { 0.0 } else { scale * u() * u() };
        }
        let grid = Grid::new(&values, n[0], n[1], n[2], u(), u()).unwrap();
        let axis = |x: f64| if x < 0.2 { 0.0 } else { 2.0 * x - 1.0 };
        let o = Vec3::new(3.0 * u() - 1.0, 3.0 * u() - 1.0, 3.0 * u() - 1.0);
        let d = Vec3::new(axis(u()), axis(u()), axis(u()));
        if d.x == 0.0 && d.y == 0.0 && d.z == 0.0 {
            continue;
        }
        let t_max = if u() < 0.1 { f64::INFINITY } else { 5.0 * u() };
        match grid.ratio_track(Ray::new(o, d, t_max), &mut r2) {
            Ok(tr) => assert!(tr.is_finite() && tr >= 0.0, "case {case}: {tr}"),
            Err(e) => assert_eq!(e, Error::Budget, "case {case}"),
        }
        match grid.delta_track(Ray::new(o, d, t_max), &mut r2) {
            Ok((t, _)) => assert!(t >= 0.0 && t <= t_max, "case {case}: t = {t}"),
            Err(e) => assert_eq!(e, Error::Budget, "case {case}"),
        }
    }
}

/// A column (1×1×n, a layered medium) reads two values, not eight: the
/// same densities as the same column repeated on a 2×2×n grid, bit for
/// bit, at random points, on the faces and outside the box, for node and
/// cell-centre sampling; and the grid in a world box gives 0 just outside
/// each face and the face's value on it.
#[test]
fn a_column_reads_as_the_full_interpolation() {
    use scatterkit::medium::Sampling;
    let col: Vec<f64> = (0..17)
        .map(|k| 0.5 + (k as f64 * 0.37).sin().abs())
        .collect();
    let wide: Vec<f64> = col.iter().flat_map(|&v| [v; 4]).collect();
    let (lo, hi) = (Vec3::new(-2.0, 0.5, -1.0), Vec3::new(3.0, 0.75, 4.0));
    for sampling in [Sampling::Nodes, Sampling::Cells] {
        let a = Grid::new(&col, 1, 1, 17, 0.3, 1.1)
            .and_then(|g| g.with_box(lo, hi))
            .unwrap()
            .with_sampling(sampling);
        let b = Grid::new(&wide, 2, 2, 17, 0.3, 1.1)
            .and_then(|g| g.with_box(lo, hi))
            .unwrap()
            .with_sampling(sampling);
        let mut r = rng(5);
        for _ in 0..100_000 {
            let p = Vec3::new(
                -2.5 + 6.0 * f64::uniform(&mut r),
                0.45 + 0.35 * f64::uniform(&mut r),
                -1.5 + 6.0 * f64::uniform(&mut r),
            );
            assert_eq!(a.density(p).to_bits(), b.density(p).to_bits(), "{p:?}");
        }
        for (p, inside) in [
            (lo, true),
            (hi, true),
            (Vec3::new(3.0, 0.6, 4.0), true),
            (
                Vec3::new(f64::from_bits(3f64.to_bits() + 1), 0.6, 1.0),
                false,
            ),
            (
                Vec3::new(0.0, f64::from_bits(0.5f64.to_bits() - 1), 1.0),
                false,
            ),
            (
                Vec3::new(0.0, 0.6, f64::from_bits(4f64.to_bits() + 1)),
                false,
            ),
        ] {
            assert_eq!(a.density(p).to_bits(), b.density(p).to_bits(), "{p:?}");
            assert_eq!(a.density(p) > 0.0, inside, "{p:?}");
        }
        assert_eq!(a.density(hi), col[16]);
        assert_eq!(a.density(lo), col[0]);
    }
}

/// Where the values sit: at the nodes (value k at `lo + (hi − lo) k/(n − 1)`)
/// or at the cell centres (`lo + (hi − lo)(k + ½)/n`, clamped beyond the
/// outer centres), checked at points where the two differ (a mutation test
/// found no test telling them apart: every other test compares grids of
/// the same sampling).
#[test]
fn nodes_and_cell_centres_place_the_values_where_documented() {
    use scatterkit::medium::Sampling;
    let values = [0.0, 1.0];
    let grid = |s| {
        Grid::new(&values, 1, 1, 2, 0.0, 1.0)
            .unwrap()
            .with_sampling(s)
    };
    let at = |z: f64| Vec3::new(0.5, 0.5, z);
    let nodes = grid(Sampling::Nodes);
    let cells = grid(Sampling::Cells);
    for (z, want_nodes, want_cells) in [
        (0.0, 0.0, 0.0),
        (0.1, 0.1, 0.0),
        (0.25, 0.25, 0.0),
        (0.5, 0.5, 0.5),
        (0.625, 0.625, 0.75),
        (0.75, 0.75, 1.0),
        (0.9, 0.9, 1.0),
    ] {
        assert!(
            (nodes.density(at(z)) - want_nodes).abs() < 1e-15,
            "nodes at {z}"
        );
        assert!(
            (cells.density(at(z)) - want_cells).abs() < 1e-15,
            "cells at {z}"
        );
    }
}
