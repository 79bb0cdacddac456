//! The azimuth `(sin 2πu, cos 2πu)`: f32 exhaustively over every float in
//! `[0, 1]`, f64 by sampling against a double-double reference. Bounds set
//! before measuring: f32 ≤ 2 ULP, f64 ≤ 4 ULP, and `sin² + cos²` within
//! 4 ULP of 1 (f32) and 8 ULP (f64).

use crate::common;
use crate::common::nan_max;

use common::dd::Dd;
use rand_xoshiro::rand_core::Rng;
use scatterkit::azimuth::{sin_cos_2pi_f32, sin_cos_2pi_f64};

/// The exact reduction of `2πu` in turns: `(q mod 4, r)` with `4u = q + r`.
fn reduce(u: f64) -> (u64, f64) {
    let q = (4.0 * u).round();
    (q as u64 & 3, 4.0 * u - q)
}

/// `(sin, cos)` of the quadrant `q` and `x = πr/2` given as their values at `x`.
fn by_quadrant(q: u64, s: Dd, c: Dd) -> (Dd, Dd) {
    match q {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `(sin 2πu, cos 2πu)` in double-double: Taylor series of `x = πr/2`,
/// `|x| ≤ π/4`, to 30 terms (the remainder is below 10⁻³⁴).
fn reference(u: f64) -> (Dd, Dd) {
    let (q, r) = reduce(u);
    let half_pi = Dd::from(core::f64::consts::FRAC_PI_2) + Dd::from(6.123_233_995_736_766e-17);
    let x = half_pi * Dd::from(r);
    let x2 = x * x;
    let (mut s, mut c) = (Dd::from(0.0), Dd::from(0.0));
    let (mut ts, mut tc) = (x, Dd::from(1.0));
    for k in 0..30 {
        s = s + ts;
        c = c + tc;
        let (a, b) = ((2 * k + 2) as f64, (2 * k + 3) as f64);
        ts = -(ts * x2) / Dd::from(a * b);
        tc = -(tc * x2) / Dd::from((2 * k + 1) as f64 * a);
    }
    by_quadrant(q, s, c)
}

fn ulp_f32(x: f64) -> f64 {
    let x = (x as f32).abs();
    if x < f32::MIN_POSITIVE {
        return 2f64.powi(-149);
    }
    // 2^(e − 150) from its bits (exact, without `powi`'s loop: this runs
    // for every f32).
    f64::from_bits(((((x.to_bits() >> 23) as i32) - 150 + 1023) as u64) << 52)
}

fn ulp_f64(x: f64) -> f64 {
    let x = x.abs();
    if x < f64::MIN_POSITIVE {
        return 2f64.powi(-1074);
    }
    2f64.powi((x.to_bits() >> 52) as i32 - 1023 - 52)
}

/// The f32 `sin_cos_2pi` against the f64 one (≤ 1 ULP of f64 by the test
/// below, 10⁻⁹ of an f32 ULP) over the floats of `[0, 1]` whose bit
/// patterns `keep` accepts: within 2 ULP, and `sin² + cos²` within 4 ε of
/// 1. Two threads share them; prints the worst.
fn f32_within_2_ulp(keep: impl Fn(u32) -> bool + Sync) {
    let last = 1.0f32.to_bits();
    let worker = |lo: u32, hi: u32| {
        let (mut worst, mut worst_u, mut norm) = (0.0f64, 0.0f32, 0.0f64);
        for b in (lo..hi).filter(|&b| keep(b)) {
            let u = f32::from_bits(b);
            let (s, c) = sin_cos_2pi_f32(u);
            let (rs, rc) = sin_cos_2pi_f64(u as f64);
            let e = nan_max(
                (s as f64 - rs).abs() / ulp_f32(rs),
                (c as f64 - rc).abs() / ulp_f32(rc),
            );
            if e > worst || e.is_nan() {
                worst = e;
                worst_u = u;
            }
            let (s, c) = (s as f64, c as f64);
            norm = nan_max(norm, (s * s + c * c - 1.0).abs());
        }
        (worst, worst_u, norm)
    };
    let mid = last / 2;
    let (a, b) = std::thread::scope(|sc| {
        let h = sc.spawn(|| worker(0, mid));
        (worker(mid, last + 1), h.join().unwrap())
    });
    let (worst, u, norm) = if b.0.is_nan() || b.0 > a.0 { b } else { a };
    let norm = nan_max(nan_max(norm, a.2), b.2);
    println!("f32: max {worst:.3} ULP at u = {u:e}; max |sin² + cos² − 1| = {norm:.2e}");
    assert!(worst <= 2.0, "f32 sin_cos_2pi: {worst} ULP at u = {u:e}");
    assert!(
        norm <= 4.0 * f32::EPSILON as f64,
        "f32 unit length off by {norm:e}"
    );
}

/// Every float of `[0, 1]` (1.07·10⁹; about 70 s on two cores, so run by
/// hand: `cargo test --release --test models -- --ignored azimuth::`).
/// CI runs the sample below.
#[test]
#[ignore = "exhaustive, about 70 s: the sample below runs in CI"]
fn f32_every_float_in_unit_interval() {
    f32_within_2_ulp(|_| true);
}

/// Every 16th float of `[0, 1]`, and every float within 2¹⁶ of the
/// quarter turns `u = 0, ¼, ½, ¾, 1`, where sin or cos is small or the
/// reduction changes quadrant.
#[test]
fn f32_sampled_floats_in_unit_interval() {
    let near: Vec<(u32, u32)> = [0.0f32, 0.25, 0.5, 0.75, 1.0]
        .iter()
        .map(|q| (q.to_bits().saturating_sub(1 << 16), q.to_bits() + (1 << 16)))
        .collect();
    f32_within_2_ulp(|b| b % 16 == 0 || near.iter().any(|&(a, z)| (a..=z).contains(&b)));
}

#[test]
fn f64_against_double_double() {
    let mut rng = common::rng(41);
    let mut us: Vec<f64> = (0..=4096).map(|i| i as f64 / 4096.0).collect();
    // Near the quadrant boundaries and the ends, where sin or cos is small.
    for k in 0..=4 {
        for e in 1..60 {
            let d = 2f64.powi(-e);
            us.extend([k as f64 / 4.0 - d, k as f64 / 4.0 + d]);
        }
    }
    let samples = if cfg!(debug_assertions) {
        200_000
    } else {
        2_000_000
    };
    us.extend((0..samples).map(|_| (rng.next_u64() >> 11) as f64 * 2f64.powi(-53)));
    us.push(0.5 - f64::EPSILON / 4.0);
    let (mut worst, mut worst_u, mut norm) = (0.0f64, 0.0, 0.0f64);
    for &u in us.iter().filter(|u| (0.0..=1.0).contains(*u)) {
        let (s, c) = sin_cos_2pi_f64(u);
        let (rs, rc) = reference(u);
        let es = (Dd::from(s) - rs).to_f64().abs() / ulp_f64(rs.to_f64());
        let ec = (Dd::from(c) - rc).to_f64().abs() / ulp_f64(rc.to_f64());
        let e = nan_max(es, ec);
        if e > worst || e.is_nan() {
            worst = e;
            worst_u = u;
        }
        let n = Dd::from(s) * Dd::from(s) + Dd::from(c) * Dd::from(c) - Dd::from(1.0);
        norm = nan_max(norm, n.to_f64().abs());
    }
    println!("f64: max {worst:.3} ULP at u = {worst_u:e}; max |sin² + cos² − 1| = {norm:.2e}");
    assert!(
        worst <= 4.0,
        "f64 sin_cos_2pi: {worst} ULP at u = {worst_u:e}"
    );
    assert!(
        norm <= 8.0 * f64::EPSILON,
        "f64 unit length off by {norm:e}"
    );
}

#[test]
fn exact_at_the_quadrant_points() {
    for (u, s, c) in [
        (0.0, 0.0, 1.0),
        (0.25, 1.0, 0.0),
        (0.5, 0.0, -1.0),
        (0.75, -1.0, 0.0),
        (1.0, 0.0, 1.0),
    ] {
        let (a, b) = sin_cos_2pi_f32(u as f32);
        assert_eq!((a, b), (s as f32, c as f32), "f32 at u = {u}");
        let (a, b) = sin_cos_2pi_f64(u);
        assert_eq!((a, b), (s, c), "f64 at u = {u}");
    }
    // Below the double-double reference's range: sin 2πu = 2πu to the last bit.
    assert_eq!(sin_cos_2pi_f64(1e-300).0, core::f64::consts::TAU * 1e-300);
    assert_eq!(sin_cos_2pi_f32(1e-40).0, core::f32::consts::TAU * 1e-40);
    assert!(sin_cos_2pi_f32(f32::NAN).0.is_nan());
    assert!(sin_cos_2pi_f64(f64::NAN).1.is_nan());
}

#[test]
fn f32_beats_libm_near_the_zeros() {
    // sin(fl(2π·u)) near u = 1/2 carries the rounding of 2π as a relative
    // error; the exact reduction does not.
    let u = 0.5f32 - 2f32.powi(-24);
    let exact = reference(u as f64).0.to_f64();
    let ours = sin_cos_2pi_f32(u).0 as f64;
    let libm = libm::sinf(core::f32::consts::TAU * u) as f64;
    assert!((ours - exact).abs() <= ulp_f32(exact));
    assert!(
        (libm - exact).abs() > 100.0 * ulp_f32(exact),
        "libm {libm} exact {exact}"
    );
}
