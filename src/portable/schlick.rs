//! Schlick's phase function in the portable tier (Blasi, Le Saëc & Schlick,
//! Computer Graphics Forum 12(3), 1993, eq. 3),
//! `p(μ) = (1 − k²)/(4π (1 − kμ)²)`, with the library's cancellation-free
//! inverse (`crate::phase::schlick`): `μ = −1 + 2u(1 + k)/D` where `μ ≤ 0`
//! and `1 − 2(1 − k)(1 − u)/D` where `μ > 0`, `D = 1 − k + 2ku` summed
//! from two non-negative terms, so neither end cancels.

use super::clamp01;
use super::phase::DirSample;
use crate::math::real::Real;

/// Schlick's constants for one `k ∈ (−1, 1)` (the header's `skp_schlick`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schlick {
    /// `k`.
    pub k: f32,
    /// `1 − k`.
    pub omk: f32,
    /// `1 + k`.
    pub opk: f32,
    /// `(1 − k)(1 + k)/(4π)`, rounded left to right.
    pub norm: f32,
}

impl Schlick {
    /// `None` unless `−1 < k < 1` (NaN fails): the header's
    /// `skp_schlick_new`, which fills the constants with NaN then.
    pub fn new(k: f32) -> Option<Schlick> {
        if !(k > -1.0 && k < 1.0) {
            return None;
        }
        let (omk, opk) = (1.0 - k, 1.0 + k);
        Some(Schlick {
            k,
            omk,
            opk,
            norm: omk * opk * 0.079_577_47,
        })
    }
}

/// `cos θ` at `u ∈ [0, 1]` (clamped; NaN gives NaN), monotone in `u`.
#[inline(always)]
pub fn schlick_sample_cos(p: &Schlick, u: f32) -> f32 {
    let u = clamp01(u);
    let d = if p.k >= 0.0 {
        p.omk + (2.0 * p.k) * u
    } else {
        p.opk - (2.0 * p.k) * (1.0 - u)
    };
    let mu = if 2.0 * u <= p.omk {
        (2.0 * u) * p.opk / d - 1.0
    } else {
        1.0 - (2.0 * p.omk) * (1.0 - u) / d
    };
    mu.clamp(-1.0, 1.0)
}

/// The density per steradian at `cos θ = mu`, `1 − kμ` summed from two
/// non-negative terms (it cancels at the peak written directly).
#[inline(always)]
pub fn schlick_pdf(p: &Schlick, mu: f32) -> f32 {
    let d = if p.k >= 0.0 {
        p.omk + p.k * (1.0 - mu)
    } else {
        p.opk - p.k * (1.0 + mu)
    };
    p.norm / (d * d)
}

/// A direction about the unit `w_in`, its `cos θ` and its density per
/// steradian.
#[inline(always)]
pub fn schlick_sample_dir(p: &Schlick, w_in: [f32; 3], u1: f32, u2: f32) -> DirSample {
    let mu = schlick_sample_cos(p, u1);
    let s = Real::sqrt((1.0 - mu) * (1.0 + mu));
    DirSample::about(w_in, mu, s, u2, schlick_pdf(p, mu))
}
