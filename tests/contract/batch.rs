//! The batch calls agree with the scalar calls bit for bit (Rust API; the C
//! twins are checked by `tests/c/batch.c`), and reject bad input writing
//! nothing.

use crate::common;

use rand_xoshiro::rand_core::Rng;
use scatterkit::{Error, Phase, PhaseFunction, RayleighMethod, Real, Vec3, rayleigh};

/// `n` unit directions and two uniforms each, with the ends 0 and 1 included.
fn inputs<T: Real>(n: usize) -> ([Vec<T>; 3], Vec<T>, Vec<T>) {
    let mut rng = common::rng(17);
    let mut w: [Vec<T>; 3] = Default::default();
    let (mut u1, mut u2) = (Vec::new(), Vec::new());
    for i in 0..n {
        let v = Vec3::new(
            f64::uniform(&mut rng) - 0.5,
            f64::uniform(&mut rng) - 0.5,
            f64::uniform(&mut rng) - 0.5 + if i % 3 == 0 { 1.0 } else { 0.0 },
        )
        .try_normalize()
        .unwrap();
        for (k, c) in [v.x, v.y, v.z].into_iter().enumerate() {
            w[k].push(T::from_f64(c));
        }
        u1.push(T::uniform(&mut rng));
        u2.push(T::uniform(&mut rng));
    }
    (u1[0], u2[1]) = (T::ZERO, T::ONE);
    (w, u1, u2)
}

fn phases<T: Real>() -> Vec<Phase<T>> {
    let t = T::from_f64;
    vec![
        Phase::isotropic(),
        Phase::rayleigh(),
        Phase::henyey_greenstein(t(0.7)).unwrap(),
        Phase::henyey_greenstein(t(-0.95)).unwrap(),
        Phase::rayleigh_depolarized(t(0.03)).unwrap(),
        Phase::draine(t(0.5), t(1.0)).unwrap(),
        Phase::fog_diameter(t(2.0)).unwrap(),
        Phase::two_lobe_hg(t(0.8), t(-0.3), t(0.9)).unwrap(),
        Phase::gegenbauer(t(-0.25), t(0.7)).unwrap(),
        Phase::gegenbauer(t(10.0), t(-0.5)).unwrap(),
        Phase::fournier_forand(t(1.1), t(4.0)).unwrap(),
    ]
}

fn dirs_agree<T: Real>() {
    let n = 203;
    let (w, u1, u2) = inputs::<T>(n);
    for p in phases::<T>() {
        let mut out: [Vec<T>; 3] = [vec![T::ZERO; n], vec![T::ZERO; n], vec![T::ZERO; n]];
        let mut pdf = vec![T::ZERO; n];
        let [ox, oy, oz] = &mut out;
        p.sample_dir_n([&w[0], &w[1], &w[2]], &u1, &u2, [ox, oy, oz], &mut pdf)
            .unwrap();
        for i in 0..n {
            let (d, q) = p.sample_dir(Vec3::new(w[0][i], w[1][i], w[2][i]), u1[i], u2[i]);
            let got = (out[0][i], out[1][i], out[2][i], pdf[i]);
            // Bit for bit (NaN-free: compare as values and signs).
            assert!(
                got == (d.x, d.y, d.z, q),
                "{p:?} at {i}: {got:?} vs {d:?} {q:?}"
            );
        }
    }
}

#[test]
fn phase_direction_batches_agree_with_scalar_calls() {
    dirs_agree::<f32>();
    dirs_agree::<f64>();
}

#[test]
fn phase_direction_batches_reject_bad_input_writing_nothing() {
    let p = Phase::henyey_greenstein(0.5f32).unwrap();
    let (w, mut u1, u2) = inputs::<f32>(8);
    let mut out = [vec![9.0f32; 8], vec![9.0; 8], vec![9.0; 8]];
    let mut pdf = vec![9.0f32; 8];
    for bad in [f32::NAN, -0.1, 1.5, f32::INFINITY] {
        u1[3] = bad;
        let [ox, oy, oz] = &mut out;
        let r = p.sample_dir_n([&w[0], &w[1], &w[2]], &u1, &u2, [ox, oy, oz], &mut pdf);
        assert_eq!(r, Err(Error::Domain));
    }
    u1[3] = 0.5;
    let [ox, oy, oz] = &mut out;
    let short = &mut [0.0f32; 7];
    let r = p.sample_dir_n([&w[0], &w[1], &w[2]], &u1, &u2, [ox, oy, oz], short);
    assert_eq!(r, Err(Error::Size));
    assert!(out.iter().flatten().chain(&pdf).all(|&x| x == 9.0));
}

fn rayleigh_agrees<T: Real>() {
    let n = 203;
    let (w, _, _) = inputs::<T>(n);
    for m in RayleighMethod::ALL {
        let (mut a, mut b) = (common::rng(5), common::rng(5));
        let mut out: [Vec<T>; 3] = [vec![T::ZERO; n], vec![T::ZERO; n], vec![T::ZERO; n]];
        let [ox, oy, oz] = &mut out;
        rayleigh::sample_dir_fill(m, [&w[0], &w[1], &w[2]], &mut a, [ox, oy, oz]);
        for i in 0..n {
            let d = rayleigh::sample_dir(m, Vec3::new(w[0][i], w[1][i], w[2][i]), &mut b);
            assert!(
                (out[0][i], out[1][i], out[2][i]) == (d.x, d.y, d.z),
                "{m:?} at {i}"
            );
        }
        assert_eq!(
            a.next_u64(),
            b.next_u64(),
            "{m:?}: the generator advanced differently"
        );
    }
}

#[test]
fn rayleigh_direction_batches_agree_with_scalar_calls() {
    rayleigh_agrees::<f32>();
    rayleigh_agrees::<f64>();
}

#[test]
fn rayleigh_inverse_batches_agree_with_scalar_calls() {
    let u: Vec<f32> = (0..=1000).map(|i| i as f32 / 1000.0).collect();
    let mut out = vec![0.0f32; u.len()];
    type Inverse = fn(f32) -> f32;
    let cases: [(RayleighMethod, Inverse); 4] = [
        (RayleighMethod::Direct, rayleigh::inverse_cdf_direct),
        (RayleighMethod::DirectFast, rayleigh::inverse_cdf_fast),
        (RayleighMethod::DirectMinimax, rayleigh::inverse_cdf_minimax),
        (RayleighMethod::Table, rayleigh::inverse_cdf_table),
    ];
    for (m, f) in cases {
        rayleigh::inverse_cdf_fill(m, &u, &mut out);
        assert!(u.iter().zip(&out).all(|(&x, &c)| c == f(x)), "{m:?}");
    }
    rayleigh::inverse_cdf_fill(RayleighMethod::Simplified, &u, &mut out);
    assert!(out.iter().all(|c| c.is_nan()));
}
