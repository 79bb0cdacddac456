//! `|g| = 1`, the Dirac limit transport codes pass (a background medium at
//! `g = 1`, `g = ±1` allowed elsewhere), in the accurate library: HG, the
//! HG lobes of a two-lobe HG and of the fog, in f32 and f64. Every sample
//! is finite and at the limit (`cos θ = g`, the direction `±w_in`), the
//! density `+∞` at `cos θ = g` and 0 elsewhere, the CDF a step, the
//! mixtures' exact inverse puts each Dirac lobe's weight at its pole, and
//! the portable tier (the header's Rust twin) gives the same values.
//! `tests/c/dirac.c` checks the C ABI and the header against the same.

use scatterkit::portable as p;
use scatterkit::{Fog, HenyeyGreenstein, Phase, PhaseFunction, Real, Vec3};

fn uniforms<T: Real>() -> impl Iterator<Item = T> {
    [0.0, 1e-30, 0.25, 0.5, 0.75, 1.0, -3.0, 4.0, f64::INFINITY]
        .into_iter()
        .map(T::from_f64)
}

fn hg_limit<T: Real + core::fmt::Debug>() {
    let w_in = Vec3::new(T::from_f64(0.48), T::from_f64(0.6), T::from_f64(0.64));
    for g in [T::ONE, -T::ONE] {
        let h = HenyeyGreenstein::new(g).unwrap();
        for u in uniforms::<T>() {
            assert_eq!(h.sample_cos(u), g, "g {g:?} u {u:?}");
            assert_eq!(h.sample_cos_sin(u), (g, T::ZERO));
            let (d, pdf) = h.sample_dir(w_in, u, T::from_f64(0.3));
            assert_eq!(pdf, T::INFINITY);
            for (a, b) in [(d.x, w_in.x), (d.y, w_in.y), (d.z, w_in.z)] {
                assert!((a - g * b).abs().to_f64() < 1e-6, "{d:?}");
            }
        }
        assert!(h.sample_cos(T::NAN).is_nan());
        assert_eq!(h.pdf(g), T::INFINITY);
        assert_eq!(h.pdf(-g), T::ZERO);
        assert_eq!(h.pdf(T::from_f64(0.3)), T::ZERO);
        assert!(h.pdf(T::NAN).is_nan());
        assert_eq!(h.cdf(T::ONE), T::ONE);
        let below = if g > T::ZERO { T::ZERO } else { T::ONE };
        assert_eq!(h.cdf(T::from_f64(0.999_999)), below);
        // All the mass at −1 for g = −1: F(−1) = 1; none for g = +1.
        assert_eq!(h.cdf(-T::ONE), if g < T::ZERO { T::ONE } else { T::ZERO });
        assert_eq!(h.mean_cosine(), g);
        // The batch gives the scalar's values.
        let u: Vec<T> = (0..=64).map(|i| T::from_f64(i as f64 / 64.0)).collect();
        let mut out = vec![T::NAN; u.len()];
        h.sample_cos_each_in_range(&u, &mut out);
        assert!(out.iter().all(|&c| c == g));
    }
}

#[test]
fn hg_at_the_dirac_limit() {
    hg_limit::<f32>();
    hg_limit::<f64>();
    assert!(HenyeyGreenstein::new(1.000_000_1f32).is_err());
    assert!(HenyeyGreenstein::new(f64::NAN).is_err());
}

fn mixtures<T: Real + core::fmt::Debug>() {
    for g in [T::ONE, -T::ONE] {
        let w = T::from_f64(0.25);
        // A two-lobe HG with its first lobe (weight w) a Dirac lobe.
        let two = Phase::two_lobe_hg(g, T::from_f64(-0.3), w).unwrap();
        let hg = HenyeyGreenstein::new(T::from_f64(-0.3)).unwrap();
        assert_eq!(two.pdf(g), T::INFINITY);
        let mu = T::from_f64(0.1);
        let want = (T::ONE - w) * hg.pdf(mu);
        assert!(((two.pdf(mu) - want) / want).abs().to_f64() < 1e-6);
        // The exact inverse: the Dirac lobe's weight at its pole.
        let (at_pole, rest) = if g > T::ZERO {
            (T::from_f64(0.9), T::from_f64(0.5))
        } else {
            (T::from_f64(0.1), T::from_f64(0.5))
        };
        assert_eq!(two.sample_cos(at_pole), g);
        let c = two.sample_cos(rest);
        assert!(c > -T::ONE && c < T::ONE, "{c:?}");
        // Inverse and CDF agree off the pole: F(F⁻¹(u)) = u.
        assert!((two.cdf(c) - rest).abs().to_f64() < 1e-6, "{c:?}");
        // The lobe choice picks the Dirac lobe for u < w.
        if let Phase::Fog(f) = &two {
            assert_eq!(f.sample_cos_by_lobe(T::from_f64(0.1)), g);
        }
        // The fog with a Dirac HG lobe; w_d = 1 leaves it out.
        let fog = Fog::new(g, T::from_f64(0.6), T::from_f64(20.0), T::from_f64(0.4)).unwrap();
        assert_eq!(fog.pdf(g), T::INFINITY);
        assert!(fog.pdf(T::ZERO).is_finite());
        assert_eq!(fog.sample_cos_by_lobe(T::from_f64(0.7)), g);
        let all_d = Fog::new(g, T::from_f64(0.6), T::from_f64(20.0), T::ONE).unwrap();
        assert!(all_d.pdf(g).is_finite());
        for u in uniforms::<T>() {
            let (c, s) = fog.sample_cos_sin(u);
            assert!(c.abs() <= T::ONE && s >= T::ZERO && s <= T::ONE, "{u:?}");
        }
        let m = fog.mean_cosine();
        assert!(m.is_finite() && m.abs() <= T::ONE);
        // A Dirac lobe of weight 1 beside a continuous lobe of weight 0
        // (either lobe): every u, 0 included, samples the pole, never the
        // empty lobe (whose rescaled uniform would be 0/0).
        let only_hg = Fog::new(g, T::from_f64(0.6), T::from_f64(20.0), T::ZERO).unwrap();
        let only_d = Phase::two_lobe_hg(g, T::from_f64(0.5), T::ONE).unwrap();
        for u in uniforms::<T>() {
            assert_eq!(only_hg.sample_cos_sin(u), (g, T::ZERO), "{u:?}");
            assert_eq!(only_d.sample_cos(u), g, "{u:?}");
        }
        // Two Dirac lobes: all mass at the poles.
        let both = Phase::two_lobe_hg(T::ONE, -T::ONE, w).unwrap();
        assert_eq!(both.sample_cos(T::from_f64(0.8)), T::ONE);
        assert_eq!(both.sample_cos(T::from_f64(0.2)), -T::ONE);
    }
    assert!(Fog::new(T::ONE, T::ONE, T::from_f64(20.0), T::from_f64(0.4)).is_err());
}

#[test]
fn mixtures_with_a_dirac_lobe() {
    mixtures::<f32>();
    mixtures::<f64>();
}

/// The library and the portable tier (the header's bits) give the same
/// values at the limit.
#[test]
fn the_library_and_the_portable_tier_agree_at_the_limit() {
    for g in [1.0f32, -1.0] {
        let lib = HenyeyGreenstein::new(g).unwrap();
        let port = p::Hg::new(g).unwrap();
        for u in uniforms::<f32>() {
            assert_eq!(lib.sample_cos(u), p::hg_sample_cos(&port, u));
            let (c, s, pdf) = p::hg_sample_cos_sin(&port, u);
            assert_eq!((c, s), lib.sample_cos_sin(u));
            assert_eq!(pdf, lib.sample_dir(Vec3::new(0.0, 0.0, 1.0), u, 0.5).1);
        }
        for mu in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
            assert_eq!(lib.pdf(mu), p::hg_pdf(&port, mu), "g {g} mu {mu}");
        }
    }
}
