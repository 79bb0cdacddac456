//! Draine's phase function (Cornette–Shanks at `α = 1`) in the portable
//! tier: Jendersie & d'Eon's closed-form inverse (2023, supplemental eq. 6)
//! with the library's rearrangement of it (`phase::draine`'s `Eq6`: the
//! cancellations where `t5` changes sign, in the resolvent and as `g → 1`
//! removed, every constant that does not depend on `u` formed once), in
//! f32 operations alone, with a cube root of its own. For `u > ½` it solves
//! the mirror problem `(−g, 1 − u)`, where `1 − u` is exact.
//!
//! Reach: `10⁻³ ≤ |g| < 1`, `1 ≤ α ≤ 10⁴` (elsewhere [`Draine::new`]
//! refuses; below `α = 1` this form can lose to eq. 6's own rounding, and the
//! library's accurate tier covers every `α ≥ 0`). Within it the result is never further from the exact inverse
//! than eq. 6 as published, in f32, and 1.5·10⁻⁶ at `(g, α) = (0.5, 1)`;
//! the worst is at small `|g|` with large `α` (the `1/(2g)` of the last
//! step remains): `tests/models/portable.rs` has the figures.

use super::clamp01;
use super::phase::DirSample;
use crate::math::draine_eq6::eq6_core;
use crate::math::real::Real;

/// `1/(4π)` rounded to f32.
const INV_4PI: f32 = 0.079_577_47;

/// Eq. 6's constants for one orientation (`g` signed as the problem is
/// oriented).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DraineSide {
    /// `t4 − r = d + q u`.
    pub d: f32,
    /// See `d`.
    pub q: f32,
    /// `r = sqrt(4α (1 − g²)² (1 + g²)(3g² + α (1 + g²)²))`.
    pub r: f32,
    /// `t0 = α (1 − g²)`.
    pub t0: f32,
    /// `t1 = −α (1 − g²)(1 + g²)`.
    pub t1: f32,
    /// `t6 = −4 t0 g² (1 − g²)`.
    pub t6: f32,
    /// `t6³`.
    pub t6_3: f32,
    /// `2/t0`.
    pub two_inv_t0: f32,
    /// `8/t0`.
    pub eight_inv_t0: f32,
    /// `6 (1 + g²)`.
    pub k: f32,
    /// `g/2`.
    pub half_g: f32,
    /// `1/(2g)`.
    pub inv_2g: f32,
}

/// Draine's sampler constants (the header's `skp_draine`): both
/// orientations, and the density's.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Draine {
    /// For `u ≤ ½`: the problem as given.
    pub lower: DraineSide,
    /// For `u > ½`: the mirror `(−g, 1 − u)`.
    pub upper: DraineSide,
    /// `g`.
    pub g: f32,
    /// `α`.
    pub alpha: f32,
    /// `(1 − g²)/(4π (1 + α (1 + 2g²)/3))`, the density's constant.
    pub kp: f32,
}

impl DraineSide {
    /// The constants of the accurate tier's eq. 6 (`math::draine_eq6`),
    /// evaluated in f32, and the reciprocals this tier multiplies by.
    fn new(g: f32, a: f32) -> Self {
        let e = eq6_core(g, a);
        DraineSide {
            d: e.d,
            q: e.q,
            r: e.r,
            t0: e.t0,
            t1: e.t1,
            t6: e.t6,
            t6_3: e.t6_3,
            two_inv_t0: 2.0 / e.t0,
            eight_inv_t0: 8.0 / e.t0,
            k: e.k,
            half_g: 0.5 * g,
            inv_2g: 0.5 / g,
        }
    }

    /// `μ` at `u ∈ [0, ½]` by eq. 6: `t5 = t0 (t4 − r)(t4 + r)`, the
    /// resolvent's cube root with like signs added (`m = t5 + sign(t5)
    /// sqrt(t5² − t6³)`, no cancellation for `t5 < 0`), then
    /// `t8 = 2(t1 + c + t6/c)/t0`, `t9 = sqrt(6(1 + g²) + t8)`,
    /// `d = sqrt(6(1 + g²) − t8 + 8 t4/(t0 t9)) − t9`, `μ = g/2 + (1 −
    /// d²/4)/(2g)`.
    #[inline(always)]
    fn sample(&self, u: f32) -> f32 {
        let lo = self.d + self.q * u;
        let t4 = lo + self.r;
        let t5 = self.t0 * (lo * (lo + 2.0 * self.r));
        let root = Real::sqrt(t5 * t5 - self.t6_3);
        let m = t5 + f32::from_bits(root.to_bits() | (t5.to_bits() & 0x8000_0000));
        let c = cbrt(m);
        let t8 = (self.t1 + c + self.t6 / c) * self.two_inv_t0;
        let t9 = Real::sqrt(self.k + t8);
        let d = Real::sqrt(self.k - t8 + t4 * self.eight_inv_t0 / t9) - t9;
        // Rounded, the last step lands up to a few ulp past ±1 (−1 − 8 ulp
        // for u below about 10⁻³ at the fog fit's g = 0.556, α = 22), where
        // sin θ = √((1 − μ)(1 + μ)) is NaN: clamped, NaN kept.
        (self.half_g + (1.0 - 0.25 * d * d) * self.inv_2g).clamp(-1.0, 1.0)
    }
}

impl Draine {
    /// The constants for `g` and `α`; `None` outside the reach
    /// `10⁻³ ≤ |g| < 1`, `1 ≤ α ≤ 10⁴` (NaN included).
    pub fn new(g: f32, alpha: f32) -> Option<Self> {
        let ga = g.abs();
        if !((1e-3..1.0).contains(&ga) && (1.0..=1e4).contains(&alpha)) {
            return None;
        }
        let norm = 1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0;
        Some(Draine {
            lower: DraineSide::new(g, alpha),
            upper: DraineSide::new(-g, alpha),
            g,
            alpha,
            kp: INV_4PI * ((1.0 - g) * (1.0 + g)) / norm,
        })
    }
}

/// `cbrt(x)` for finite `x` with `|x|` in `[2⁻¹²⁶, 2¹²⁷]` or 0, in f32
/// alone: Kahan's seed (the bits of `|x|` divided by 3 plus a bias,
/// about 3 % off) and two of Halley's steps `t ← t (t³ + 2x)/(2t³ + x)`,
/// the sign split off first.
#[inline(always)]
fn cbrt(x: f32) -> f32 {
    let sign = x.to_bits() & 0x8000_0000;
    let a = f32::from_bits(x.to_bits() & 0x7fff_ffff);
    let mut t = f32::from_bits((a.to_bits() / 3).wrapping_add(709_958_130));
    for _ in 0..2 {
        let t3 = t * t * t;
        t = t * (t3 + 2.0 * a) / (2.0 * t3 + a);
    }
    f32::from_bits(t.to_bits() | sign)
}

/// Draine's `cos θ = F⁻¹(u)` for `u ∈ [0, 1]` (clamped; NaN gives NaN).
#[inline(always)]
pub fn draine_sample_cos(p: &Draine, u: f32) -> f32 {
    let u = clamp01(u);
    if u > 0.5 {
        -p.upper.sample(1.0 - u)
    } else {
        p.lower.sample(u)
    }
}

/// Draine's density per steradian at `cos θ = mu`,
/// `(1 − g²)/(4π (1 + g² − 2gμ)^{3/2}) · (1 + αμ²)/(1 + α(1 + 2g²)/3)`.
#[inline(always)]
pub fn draine_pdf(p: &Draine, mu: f32) -> f32 {
    let g = p.g;
    let q = 1.0 + g * g - 2.0 * g * mu;
    p.kp * (1.0 + p.alpha * mu * mu) / (q * Real::sqrt(q))
}

/// A Draine direction about the unit `w_in` (`cos θ` from `u1`, azimuth
/// `2π u2`), its `cos θ` and its density.
#[inline(always)]
pub fn draine_sample_dir(p: &Draine, w_in: [f32; 3], u1: f32, u2: f32) -> DirSample {
    let mu = draine_sample_cos(p, u1);
    let s = Real::sqrt((1.0 - mu) * (1.0 + mu));
    DirSample::about(w_in, mu, s, u2, draine_pdf(p, mu))
}

/// Jendersie & d'Eon's fog phase function (2023): a Henyey–Greenstein lobe
/// and a Draine lobe, `p = (1 − w_D) p_HG + w_D p_D`, sampled by lobe (the
/// paper's sampler: `u < w_D` picks the Draine lobe and `u/w_D` is reused
/// inside it, else HG with `(u − w_D)/(1 − w_D)`): exact in distribution,
/// not monotone in `u` across the lobes. The header's `skp_fog`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    /// The Henyey–Greenstein lobe.
    pub hg: super::phase::Hg,
    /// The Draine lobe.
    pub draine: Draine,
    /// The Draine lobe's weight `w_D ∈ [0, 1]`.
    pub w_d: f32,
}

impl Fog {
    /// The lobes from the fit's parameters (the library's `fog_fit` gives
    /// them for a droplet diameter): `g_hg ∈ [−1, 1]` (`|g_hg| = 1` is a
    /// Dirac lobe, [`Hg::new`](super::Hg::new)), the Draine lobe
    /// within [`Draine::new`]'s reach, `w_d ∈ [0, 1]`; `None` otherwise.
    pub fn new(g_hg: f32, g_d: f32, alpha: f32, w_d: f32) -> Option<Self> {
        if !(0.0..=1.0).contains(&w_d) {
            return None;
        }
        Some(Fog {
            hg: super::phase::Hg::new(g_hg)?,
            draine: Draine::new(g_d, alpha)?,
            w_d,
        })
    }
}

/// The fog's `cos θ` for `u ∈ [0, 1]` (clamped; NaN gives NaN), by lobe.
#[inline(always)]
pub fn fog_sample_cos(p: &Fog, u: f32) -> f32 {
    let u = clamp01(u);
    if u < p.w_d {
        draine_sample_cos(&p.draine, u / p.w_d)
    } else if p.w_d < 1.0 {
        super::phase::hg_sample_cos(&p.hg, (u - p.w_d) / (1.0 - p.w_d))
    } else {
        draine_sample_cos(&p.draine, 1.0)
    }
}

/// The fog's density per steradian at `cos θ = mu`,
/// `(1 − w_D) p_HG(μ) + w_D p_D(μ)`; an HG lobe of weight 0 adds nothing,
/// even a Dirac lobe where its density is `+∞`.
#[inline(always)]
pub fn fog_pdf(p: &Fog, mu: f32) -> f32 {
    let h = if p.w_d < 1.0 {
        (1.0 - p.w_d) * super::phase::hg_pdf(&p.hg, mu)
    } else {
        0.0
    };
    h + p.w_d * draine_pdf(&p.draine, mu)
}

/// A fog direction about the unit `w_in` (`cos θ` and the lobe from `u1`
/// as [`fog_sample_cos`], azimuth `2π u2`), its `cos θ` and the fog's
/// density there.
#[inline(always)]
pub fn fog_sample_dir(p: &Fog, w_in: [f32; 3], u1: f32, u2: f32) -> DirSample {
    let mu = fog_sample_cos(p, u1);
    let s = Real::sqrt((1.0 - mu) * (1.0 + mu));
    DirSample::about(w_in, mu, s, u2, fog_pdf(p, mu))
}
