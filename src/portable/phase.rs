//! Phase-function samplers of the portable tier (module docs of
//! [`crate::portable`]): isotropic, Henyey–Greenstein and Rayleigh, each
//! `cos θ` by its exact inverse CDF, `sin θ` from factors that keep their
//! relative precision at both poles, and the direction about `w_in`.

use super::clamp01;
use super::exact::{mul, two_sum};
use super::turns::direction_about;
use crate::math::rayleigh_table::{RAYLEIGH_TABLE_F32, TABLE_N};
use crate::math::real::Real;

/// `1/(4π)` rounded to f32.
const INV_4PI: f32 = 0.079_577_47;
/// `3/(16π)` rounded to f32, Rayleigh's density at `μ = 0`.
const RAYLEIGH_K: f32 = 0.059_683_103;

/// `(cos θ, sin θ)` of the isotropic phase function for `u ∈ [0, 1]`:
/// `cos θ = 2u − 1` (one rounding; `u = 0` gives −1, as every sampler
/// here), `sin θ = 2 sqrt(u (1 − u))`.
#[inline(always)]
pub fn isotropic_sample_cos_sin(u: f32) -> (f32, f32) {
    let u = clamp01(u);
    (2.0 * u - 1.0, 2.0 * Real::sqrt(u * (1.0 - u)))
}

/// A sampled direction (the header's `skp_dir_sample`): the unit
/// direction, the cosine of its angle to `w_in` (the sampled `cos θ`,
/// exactly) and its density per steradian.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirSample {
    /// The unit direction.
    pub dir: [f32; 3],
    /// `cos θ` between `w_in` and `dir`, as sampled.
    pub cos_theta: f32,
    /// The density per steradian at `dir`.
    pub pdf: f32,
}

impl DirSample {
    /// The direction at `cos θ = mu`, `sin θ = sin_theta`, azimuth
    /// `2π turns` about the unit `w_in`, with density `pdf`.
    #[inline(always)]
    pub(super) fn about(w_in: [f32; 3], mu: f32, sin_theta: f32, turns: f32, pdf: f32) -> Self {
        DirSample {
            dir: direction_about(w_in, mu, sin_theta, turns),
            cos_theta: mu,
            pdf,
        }
    }
}

/// An isotropic direction (independent of any incoming one), its `cos θ`
/// about `+z` and its density `1/(4π)`, from two uniforms: `cos θ` from
/// `u1`, azimuth `2π u2`.
#[inline(always)]
pub fn isotropic_sample_dir(u1: f32, u2: f32) -> DirSample {
    let (mu, s) = isotropic_sample_cos_sin(u1);
    DirSample::about([0.0, 0.0, 1.0], mu, s, u2, INV_4PI)
}

/// Henyey–Greenstein's constants for one asymmetry `g` (the header's
/// `skp_hg`, filled by `skp_hg_new`): `C` layout, 10 floats. `c1 … c4`
/// are rounded once from their exact values at the f32 `g`
/// (error-free transformations in f32, so any target computes the same).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hg {
    /// `g' = |g|`, the asymmetry's magnitude (`g ∈ [−1, 1]`).
    pub a: f32,
    /// `+1` for `g > 0`, `−1` for `g ≤ 0`: samples of `g < 0` are the
    /// mirror `μ(g, u) = −μ(−g, 1 − u)`.
    pub sign: f32,
    /// `1 − g'`.
    pub omg: f32,
    /// `2 (1 + g')² (1 − g')`.
    pub c1: f32,
    /// `2 g' (1 + g')²`.
    pub c2: f32,
    /// `2 (1 − g')²`.
    pub c3: f32,
    /// `2 g' (1 − g')²`.
    pub c4: f32,
    /// `1/(4π (1 − g²)²)`: the density at a sample is this times `d³`
    /// (`+∞` for `|g| = 1`).
    pub kd: f32,
    /// `(1 − g')²`, for the density at any `μ`.
    pub k2: f32,
    /// `(1 − g²)/(4π)`, the density's numerator.
    pub kp: f32,
}

impl Hg {
    /// The constants for `g`; `None` unless `|g| ≤ 1` (NaN included).
    /// `|g| = 1` is the Dirac limit (all scattering at `cos θ = g`), which
    /// transport codes give a background medium: the samplers return
    /// `cos θ = g` (`sin θ = 0`) for every `u` but NaN, the density is `+∞`
    /// at `μ = g` and 0 elsewhere (HG's density as `|g| → 1`, point by
    /// point), and a sample's density is `+∞`.
    pub fn new(g: f32) -> Option<Self> {
        if g.is_nan() || g.abs() > 1.0 {
            return None;
        }
        let a = g.abs();
        // 1 ± g' and their squares as exact pairs; each constant then
        // rounds once.
        let opg = two_sum(1.0, a);
        let omg = two_sum(1.0, -a);
        let (opg2, omg2) = (mul(opg, opg), mul(omg, omg));
        let round = |x: (f32, f32)| 2.0 * (x.0 + x.1);
        let c = omg.0 * opg.0;
        // kd is +∞ at |g| = 1, the Dirac limit's density.
        Some(Hg {
            a,
            sign: if g > 0.0 { 1.0 } else { -1.0 },
            omg: omg.0,
            c1: round(mul(opg2, omg)),
            c2: round(mul(opg2, (a, 0.0))),
            c3: round(omg2),
            c4: round(mul(omg2, (a, 0.0))),
            kd: INV_4PI / (c * c),
            k2: omg.0 * omg.0,
            kp: INV_4PI * c,
        })
    }

    /// The asymmetry `g` these constants were built for.
    pub fn g(&self) -> f32 {
        self.sign * self.a
    }
}

/// `(P, M, g'u')` at `u ∈ [0, 1]`, for `g' = |g|` and `u' = u` (`g > 0`)
/// or `1 − u` (the mirror), `v' = 1 − u'` (each of the pair formed from
/// `u` directly: one is exact, the other rounded where the inverse is flat
/// in it). Henyey & Greenstein's inverse factors exactly as
/// `1 + μ' = P/d²`, `1 − μ' = M/d²` with `d = 1 − g' + 2g'u'`,
/// `P = 2u'(1 + g')²(1 − g' + g'u') = u'(c1 + c2 u')` and
/// `M = 2v'(1 − g')²(1 + g'u') = v'(c3 + c4 u')`: sums of non-negative
/// terms, each within a few ulp in relative terms, and no division by `g`.
#[inline(always)]
fn hg_pm(p: &Hg, u: f32) -> (f32, f32, f32) {
    let (u1, v1) = if p.sign > 0.0 {
        (u, 1.0 - u)
    } else {
        (1.0 - u, u)
    };
    let (pp, mm) = hg_pm_of(p, u1, v1);
    (pp, mm, p.a * u1)
}

/// `(P, M)` at `(u', v')` (see `hg_pm`): the one place they are formed,
/// for the scalar sampler and the batch alike.
#[inline(always)]
pub(super) fn hg_pm_of(p: &Hg, u1: f32, v1: f32) -> (f32, f32) {
    (u1 * (p.c1 + p.c2 * u1), v1 * (p.c3 + p.c4 * u1))
}

/// `cos θ = ±(P − M)/(P + M)`: since `P + M = 2d²`, the ratio is `μ'`
/// exactly, and `d` (whose two roundings would count twice in `d²`)
/// drops out. Its error is `2PM (δ_P − δ_M)/(P + M)²` (at most half the
/// difference of the factors' relative errors) plus three roundings: a
/// few ulp of 1, at both poles too (`P → 0` gives `−1` exactly).
#[inline(always)]
fn hg_mu(p: &Hg, pp: f32, mm: f32) -> f32 {
    p.sign * ((pp - mm) / (pp + mm))
}

/// Whether these are the Dirac limit's constants (`|g| = 1`).
#[inline(always)]
pub(super) fn is_dirac(p: &Hg) -> bool {
    p.a == 1.0
}

/// The Dirac limit's `x` at `u`: NaN for a NaN `u`, else `x`.
#[inline(always)]
pub(super) fn dirac(u: f32, x: f32) -> f32 {
    if u.is_nan() { u } else { x }
}

/// Henyey–Greenstein's `cos θ = F⁻¹(u)` for `u ∈ [0, 1]` (clamped; NaN
/// gives NaN), within 1.6·10⁻⁷ of the exact value for every `|g| < 1`
/// (`tests/models/portable.rs` gives the measured bound); `g` itself for
/// `|g| = 1`.
#[inline(always)]
pub fn hg_sample_cos(p: &Hg, u: f32) -> f32 {
    if is_dirac(p) {
        return dirac(u, p.sign);
    }
    let (pp, mm, _) = hg_pm(p, clamp01(u));
    hg_mu(p, pp, mm)
}

/// `(cos θ, sin θ, density)` at `u`: `sin θ = sqrt((1 + μ)(1 − μ))
/// = 2 sqrt(P M)/(P + M)`, relative precision kept at both poles; the
/// density `d³/(4π (1 − g²)²)` from `d = 1 − g' + 2g'u'` (for `|g| = 1`:
/// `(g, 0, +∞)`).
#[inline(always)]
pub fn hg_sample_cos_sin(p: &Hg, u: f32) -> (f32, f32, f32) {
    if is_dirac(p) {
        return (dirac(u, p.sign), dirac(u, 0.0), dirac(u, p.kd));
    }
    let (pp, mm, gu) = hg_pm(p, clamp01(u));
    let sum = pp + mm;
    let d = p.omg + (gu + gu);
    (
        hg_mu(p, pp, mm),
        2.0 * Real::sqrt(pp * mm) / sum,
        p.kd * (d * d * d),
    )
}

/// The scattered direction about the unit `w_in` (`cos θ` from `u1`,
/// azimuth `2π u2`), its `cos θ` and its density per steradian.
#[inline(always)]
pub fn hg_sample_dir(p: &Hg, w_in: [f32; 3], u1: f32, u2: f32) -> DirSample {
    let (mu, s, pdf) = hg_sample_cos_sin(p, u1);
    DirSample::about(w_in, mu, s, u2, pdf)
}

/// Henyey–Greenstein's density per steradian at `cos θ = mu ∈ [−1, 1]`,
/// `(1 − g²)/(4π q^{3/2})` with `q = 1 + g² − 2gμ` written as
/// `(1 − g')² + 2g'(1 − sμ)` (`g' = |g|`, `s` its sign), a sum of
/// non-negative terms that does not cancel in the forward peak. For
/// `|g| = 1`: `+∞` at `μ = g` (`q = 0`), 0 elsewhere in `[−1, 1]`.
#[inline(always)]
pub fn hg_pdf(p: &Hg, mu: f32) -> f32 {
    let q = p.k2 + 2.0 * p.a * (1.0 - p.sign * mu);
    if is_dirac(p) {
        return if q > 0.0 {
            0.0
        } else if q == 0.0 {
            p.kd
        } else {
            f32::NAN
        };
    }
    p.kp / (q * Real::sqrt(q))
}

/// Rayleigh's `cos θ = F⁻¹(u)` for `u ∈ [0, 1]` (clamped; NaN gives
/// NaN) from the built-in table ([`RAYLEIGH_TABLE`](super::RAYLEIGH_TABLE)):
/// `x = 128u`, `i = min(⌊x⌋, 127)`, `t = x − i`, the interval's cubic
/// `μ_i + t (d_i + t (c2_i + t c3_i))` by Horner, clamped to `[−1, 1]`.
/// The same bits as the library's f32 `RayleighMethod::Table`, within
/// 6·10⁻⁸ of the exact inverse (5.8·10⁻⁸ measured); no division, no root.
#[inline(always)]
pub fn rayleigh_sample_cos(u: f32) -> f32 {
    let x = clamp01(u) * TABLE_N as f32;
    // x ≥ 1 excludes NaN; the conversion truncates, as C's does.
    let i = if x >= 1.0 {
        (x as usize).min(TABLE_N - 1)
    } else {
        0
    };
    let t = x - i as f32;
    let [y0, d0, c2, c3] = match RAYLEIGH_TABLE_F32.get(4 * i..4 * i + 4) {
        Some(&[a, b, c, d]) => [a, b, c, d],
        _ => return f32::NAN,
    };
    (y0 + t * (d0 + t * (c2 + t * c3))).clamp(-1.0, 1.0)
}

/// Rayleigh's density per steradian, `3(1 + μ²)/(16π)`.
#[inline(always)]
pub fn rayleigh_pdf(mu: f32) -> f32 {
    RAYLEIGH_K * (1.0 + mu * mu)
}

/// A Rayleigh direction about the unit `w_in`, its `cos θ` and density.
#[inline(always)]
pub fn rayleigh_sample_dir(w_in: [f32; 3], u1: f32, u2: f32) -> DirSample {
    let mu = rayleigh_sample_cos(u1);
    let s = Real::sqrt((1.0 - mu) * (1.0 + mu));
    DirSample::about(w_in, mu, s, u2, rayleigh_pdf(mu))
}

/// Two Henyey–Greenstein lobes mixed with weight `w` on the first (the
/// header's `skp_two_lobe`): `p = w p_1 + (1 − w) p_2`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoLobe {
    /// The first lobe.
    pub first: Hg,
    /// The second lobe.
    pub second: Hg,
    /// The first lobe's weight, in `[0, 1]`.
    pub w: f32,
}

impl TwoLobe {
    /// The lobes `g1`, `g2` (each in `[−1, 1]`; `|g| = 1` is a Dirac lobe,
    /// [`Hg::new`]) with weight `w ∈ [0, 1]` on the first; `None` otherwise
    /// (NaN included).
    pub fn new(g1: f32, g2: f32, w: f32) -> Option<Self> {
        if !(0.0..=1.0).contains(&w) {
            return None;
        }
        Some(TwoLobe {
            first: Hg::new(g1)?,
            second: Hg::new(g2)?,
            w,
        })
    }
}

/// `(lobe, u')`: the lobe one uniform picks (`u < w`: the first, with
/// `u' = u/w`; else the second, with `u' = (u − w)/(1 − w)`), the uniform
/// rescaled and reused inside it; `u = 1` with `w = 1` stays in the first
/// lobe at `u' = 1`.
#[inline(always)]
fn two_lobe_pick(p: &TwoLobe, u: f32) -> (&Hg, f32) {
    let u = clamp01(u);
    if u < p.w {
        (&p.first, u / p.w)
    } else if p.w < 1.0 {
        (&p.second, (u - p.w) / (1.0 - p.w))
    } else {
        (&p.first, 1.0)
    }
}

/// Two-lobe HG's `cos θ` for `u ∈ [0, 1]` (clamped; NaN gives NaN), the
/// lobe chosen by `u` itself (exact in distribution, not monotone in `u`
/// across the lobes).
#[inline(always)]
pub fn two_lobe_sample_cos(p: &TwoLobe, u: f32) -> f32 {
    let (lobe, v) = two_lobe_pick(p, u);
    hg_sample_cos(lobe, v)
}

/// Two-lobe HG's density per steradian at `cos θ = mu`,
/// `w p_1(μ) + (1 − w) p_2(μ)`; a lobe of weight 0 adds nothing, even a
/// Dirac lobe where its density is `+∞`.
#[inline(always)]
pub fn two_lobe_pdf(p: &TwoLobe, mu: f32) -> f32 {
    let a = if p.w > 0.0 {
        p.w * hg_pdf(&p.first, mu)
    } else {
        0.0
    };
    let b = if p.w < 1.0 {
        (1.0 - p.w) * hg_pdf(&p.second, mu)
    } else {
        0.0
    };
    a + b
}

/// A two-lobe HG direction about the unit `w_in` (`cos θ` and the lobe
/// from `u1`, azimuth `2π u2`), its `cos θ` and the mixture's density
/// there.
#[inline(always)]
pub fn two_lobe_sample_dir(p: &TwoLobe, w_in: [f32; 3], u1: f32, u2: f32) -> DirSample {
    let (lobe, v) = two_lobe_pick(p, u1);
    let (mu, s, _) = hg_sample_cos_sin(lobe, v);
    DirSample::about(w_in, mu, s, u2, two_lobe_pdf(p, mu))
}
