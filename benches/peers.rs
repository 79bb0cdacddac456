//! Peer formulas, re-implemented from their published descriptions for
//! side-by-side measurement (not copied code). Shared by `benches/samplers.rs`
//! and the main example (`examples/speed_accuracy/`). Every function maps `u ∈ [0, 1)` to
//! `cos θ` in this crate's orientation (`u = 0 → −1`, `+1` forward).
#![allow(dead_code)]

/// Mitsuba 3's Rayleigh sampler (`rayleigh.cpp`, Mitsuba 3, Jakob et al.):
/// Cardano with two cube roots, `cbrt(s + r) + cbrt(s − r)`, `s = 2(2u − 1)`,
/// `r = sqrt(s² + 1)`; cube roots from libm (Dr.Jit's `cbrt` is correctly
/// rounded too).
#[inline]
pub fn mitsuba_rayleigh(u: f32) -> f32 {
    let s = 2.0 * (2.0 * u - 1.0);
    let r = libm::sqrtf(s * s + 1.0);
    libm::cbrtf(s + r) + libm::cbrtf(s - r)
}

/// The fast inverse cube root Blender Cycles uses for Rayleigh (its volume
/// kernel): seed `0x54a24242 − bits/3` for `x^{−1/3}`, then two Newton steps
/// `y ← y (4 − x y³)/3`.
#[inline]
pub fn fast_inv_cbrt(x: f32) -> f32 {
    let mut y = f32::from_bits(0x54a2_4242u32.wrapping_sub(x.to_bits() / 3));
    for _ in 0..2 {
        y = y * (4.0 - x * y * y * y) * (1.0 / 3.0);
    }
    y
}

/// Cycles' Rayleigh sampler: Cardano's `w − 1/w` with
/// `1/w = fast_inv_cbrt(s + sqrt(s² + 1))`.
#[inline]
pub fn cycles_rayleigh(u: f32) -> f32 {
    let s = 2.0 * (2.0 * u - 1.0);
    let inv_w = fast_inv_cbrt(s + libm::sqrtf(s * s + 1.0));
    1.0 / inv_w - inv_w
}

/// pbrt-v4's `SampleHenyeyGreenstein` (Pharr, Jakob, Humphreys, pbrt-v4):
/// isotropic below `|g| < 10⁻³`, else the textbook inverse. pbrt's `wo`
/// points back along the ray and its `u` runs the other way; with both
/// mapped to this crate's convention the formula reads
/// `μ = (1 + g² − ((1 − g²)/(1 − g + 2gu))²)/(2g)`.
#[inline]
pub fn pbrt_v4_hg(g: f32, u: f32) -> f32 {
    if g.abs() < 1e-3 {
        return 2.0 * u - 1.0;
    }
    let sq = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    (1.0 + g * g - sq * sq) / (2.0 * g)
}

/// Draine by rejection from HG (Jendersie & d'Eon 2023 mention it as the
/// obvious alternative): `μ ~ HG(g)` accepted with `(1 + αμ²)/(1 + α)`.
#[inline]
pub fn draine_rejection(g: f32, alpha: f32, mut uniform: impl FnMut() -> f32) -> f32 {
    use scatterkit::PhaseFunction;
    let hg = scatterkit::HenyeyGreenstein::new(g).unwrap();
    loop {
        let mu = hg.sample_cos(uniform());
        if uniform() * (1.0 + alpha) <= 1.0 + alpha * mu * mu {
            return mu;
        }
    }
}
