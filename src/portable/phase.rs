//! Phase-function samplers of the portable tier (module docs of
//! [`crate::portable`]): isotropic, Henyey–Greenstein and Rayleigh, each
//! `cos θ` by its exact inverse CDF, `sin θ` from factors that keep their
//! relative precision at both poles, and the direction about `w_in`.

use super::clamp01;
use super::turns::direction_about;
use crate::math::real::Real;

/// `1/(4π)` rounded to f32.
const INV_4PI: f32 = 0.079_577_47;
/// `3/(16π)` rounded to f32, Rayleigh's density at `μ = 0`.
const RAYLEIGH_K: f32 = 0.059_683_103;

/// `(cos θ, sin θ)` of the isotropic phase function for `u ∈ [0, 1]`:
/// `cos θ = 1 − 2u` (one rounding), `sin θ = 2 sqrt(u (1 − u))`.
#[inline(always)]
pub fn isotropic_sample_cos_sin(u: f32) -> (f32, f32) {
    let u = clamp01(u);
    (1.0 - 2.0 * u, 2.0 * Real::sqrt(u * (1.0 - u)))
}

/// An isotropic direction (independent of any incoming one) and its
/// density `1/(4π)`, from two uniforms: `cos θ` from `u1` about `+z`,
/// azimuth `2π u2`.
#[inline(always)]
pub fn isotropic_sample_dir(u1: f32, u2: f32) -> ([f32; 3], f32) {
    let (mu, s) = isotropic_sample_cos_sin(u1);
    (direction_about([0.0, 0.0, 1.0], mu, s, u2), INV_4PI)
}

/// Henyey–Greenstein's constants for one asymmetry `g`, each rounded
/// from the f32 `g` in a stated order (the header's `skp_hg`, filled by
/// `skp_hg_new`): `C` layout, 8 floats.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hg {
    /// `g' = |g|`, the asymmetry's magnitude (`g ∈ (−1, 1)`).
    pub a: f32,
    /// `+1` for `g > 0`, `−1` for `g ≤ 0`: samples of `g < 0` are the
    /// mirror `μ(g, u) = −μ(−g, 1 − u)`.
    pub sign: f32,
    /// `1 − g'`.
    pub omg: f32,
    /// `2 (1 + g')²`, the factor of `1 + μ'`.
    pub cp: f32,
    /// `2 (1 − g')²`, the factor of `1 − μ'`.
    pub cm: f32,
    /// `2 (1 − g²)`, the factor of `sin θ`.
    pub ks: f32,
    /// `1/(4π (1 − g²)²)`: the density at a sample is this times `d³`.
    pub kd: f32,
    /// `(1 − g')²`, for the density at any `μ`.
    pub k2: f32,
}

impl Hg {
    /// The constants for `g`; `None` unless `|g| < 1` (NaN included).
    pub fn new(g: f32) -> Option<Self> {
        if g.is_nan() || g.abs() >= 1.0 {
            return None;
        }
        let a = g.abs();
        let (omg, opg) = (1.0 - a, 1.0 + a);
        let c = omg * opg;
        Some(Hg {
            a,
            sign: if g > 0.0 { 1.0 } else { -1.0 },
            omg,
            cp: 2.0 * (opg * opg),
            cm: 2.0 * (omg * omg),
            ks: 2.0 * c,
            kd: INV_4PI / (c * c),
            k2: omg * omg,
        })
    }

    /// The asymmetry `g` these constants were built for.
    pub fn g(&self) -> f32 {
        self.sign * self.a
    }
}

/// The sampler's pieces at `u ∈ [0, 1]`, for `g' = |g|` and `u' = u`
/// (`g > 0`) or `1 − u` (the mirror), `v' = 1 − u'` (each of the pair
/// formed from `u` directly, so one of them is exact and the other
/// rounded where the inverse is flat in it): `d = 1 − g' + 2g'u'`,
/// `a = 1 − g' + g'u'`, `b = 1 + g'u'`. With them Henyey & Greenstein's
/// inverse factors exactly as `1 + μ' = P/d²`, `1 − μ' = M/d²`,
/// `P = 2u'(1 + g')² a`, `M = 2v'(1 − g')² b`; every factor is a sum of
/// non-negative terms, so `P`, `M` and `d` keep their relative precision
/// and nothing divides by `g`.
#[inline(always)]
fn hg_parts(p: &Hg, u: f32) -> (f32, f32, f32, f32, f32) {
    let (u1, v1) = if p.sign > 0.0 {
        (u, 1.0 - u)
    } else {
        (1.0 - u, u)
    };
    let gu = p.a * u1;
    let (d, a, b) = (p.omg + (gu + gu), p.omg + gu, 1.0 + gu);
    ((p.cp * u1) * a, (p.cm * v1) * b, d, u1 * v1, a * b)
}

/// `cos θ` from `P`, `M`, `d` (see `hg_parts`): `P/d² − 1` for
/// `μ' < −½` (`P < M/3`), `1 − M/d²` for `μ' > ½`, and `(P − M)/(2d²)`
/// between, where both factors are near 1 and the difference lets the
/// rounding of `d²` scale with `|μ'|` instead of 1. One division either
/// way; the absolute error stays a few ulp of 1.
#[inline(always)]
fn hg_mu(p: &Hg, pp: f32, mm: f32, d: f32) -> f32 {
    let d2 = d * d;
    let (n, c) = if 3.0 * pp < mm {
        (pp, -1.0)
    } else if 3.0 * mm < pp {
        (-mm, 1.0)
    } else {
        (0.5 * (pp - mm), 0.0)
    };
    p.sign * (n / d2 + c)
}

/// Henyey–Greenstein's `cos θ = F⁻¹(u)` for `u ∈ [0, 1]` (clamped; NaN
/// gives NaN), within 2·10⁻⁷ of the exact value for every `|g| < 1`
/// (`tests/portable.rs` gives the measured bound).
#[inline(always)]
pub fn hg_sample_cos(p: &Hg, u: f32) -> f32 {
    let (pp, mm, d, _, _) = hg_parts(p, clamp01(u));
    hg_mu(p, pp, mm, d)
}

/// `(cos θ, sin θ, density)` at `u`. `sin θ = sqrt((1 + μ')(1 − μ'))`
/// from the factors, `2(1 − g²) sqrt(u'v' a b)/d²`, relative precision
/// kept at both poles; the density `d³/(4π (1 − g²)²)` from the sampler's
/// own `d`.
#[inline(always)]
pub fn hg_sample_cos_sin(p: &Hg, u: f32) -> (f32, f32, f32) {
    let (pp, mm, d, uv, ab) = hg_parts(p, clamp01(u));
    let d2 = d * d;
    let s = p.ks * Real::sqrt(uv * ab) / d2;
    (hg_mu(p, pp, mm, d), s, p.kd * (d2 * d))
}

/// The scattered direction about the unit `w_in` (`cos θ` from `u1`,
/// azimuth `2π u2`) and its density per steradian.
#[inline(always)]
pub fn hg_sample_dir(p: &Hg, w_in: [f32; 3], u1: f32, u2: f32) -> ([f32; 3], f32) {
    let (mu, s, pdf) = hg_sample_cos_sin(p, u1);
    (direction_about(w_in, mu, s, u2), pdf)
}

/// Henyey–Greenstein's density per steradian at `cos θ = mu ∈ [−1, 1]`,
/// `(1 − g²)/(4π q^{3/2})` with `q = 1 + g² − 2gμ` written as
/// `(1 − g')² + 2g'(1 − sμ)` (`g' = |g|`, `s` its sign), a sum of
/// non-negative terms that does not cancel in the forward peak.
#[inline(always)]
pub fn hg_pdf(p: &Hg, mu: f32) -> f32 {
    let q = p.k2 + 2.0 * p.a * (1.0 - p.sign * mu);
    INV_4PI * (p.ks * 0.5) / (q * Real::sqrt(q))
}

/// Rayleigh's `cos θ = F⁻¹(u)` for `u ∈ [0, 1]`, the root of
/// `μ³ + 3μ = s`, `s = 4(2u − 1)`: Cardano's root in the stable form
/// `μ = 2s w²/(w⁴ + w² + 1)` with `w = cbrt(a + sqrt(a² + 1))`,
/// `a = |s|/2`, from a cubic seed in `a` and one Halley step on
/// `w⁶ − 2a w³ − 1` (Frisvad 2011 §4 gives the closed form; the seed and
/// step are the library's `RayleighMethod::DirectMinimax`). Branch-free.
#[inline(always)]
pub fn rayleigh_sample_cos(u: f32) -> f32 {
    let s = 2.0 * (2.0 * clamp01(u) - 1.0);
    let a = s.abs();
    let mut w = 0.999_001_3 + a * (0.353_234_77 + a * (-0.001_343_385_3 + a * -0.010_459_901));
    let c = w * w * w;
    let h = c * c - 2.0 * a * c - 1.0;
    let cma = c - a;
    w -= 2.0 * w * h * cma / (12.0 * c * cma * cma - h * (5.0 * c - 2.0 * a));
    let w2 = w * w;
    let mu = 2.0 * s * w2 / (w2 * w2 + w2 + 1.0);
    mu.clamp(-1.0, 1.0)
}

/// Rayleigh's density per steradian, `3(1 + μ²)/(16π)`.
#[inline(always)]
pub fn rayleigh_pdf(mu: f32) -> f32 {
    RAYLEIGH_K * (1.0 + mu * mu)
}

/// A Rayleigh direction about the unit `w_in` and its density.
#[inline(always)]
pub fn rayleigh_sample_dir(w_in: [f32; 3], u1: f32, u2: f32) -> ([f32; 3], f32) {
    let mu = rayleigh_sample_cos(u1);
    let s = Real::sqrt((1.0 - mu) * (1.0 + mu));
    (direction_about(w_in, mu, s, u2), rayleigh_pdf(mu))
}
