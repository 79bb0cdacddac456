//! Henyey–Greenstein (Henyey & Greenstein, ApJ 93, 1941):
//! `p(μ) = (1/4π) (1 − g²) / (1 + g² − 2gμ)^{3/2}`, mean cosine `g`.
//!
//! The textbook inverse `μ = (1 + g² − s²)/(2g)`, `s = (1 − g²)/(1 − g + 2gu)`
//! divides by `g` and cancels as `g → 0` (f32: 10⁻³ error at `g = 10⁻⁴`) and is
//! 0/0 at `|g| → 1`. Factoring `1 ± μ` exactly gives two forms with only
//! positive factors and no division by `g`, with `d = 1 − g + 2gu`
//! (`= (1 + g) − 2g(1 − u)`, the form used for `g < 0`):
//!
//! * `1 + μ = 2u (1 + g)² (1 − g + gu) / d²`
//! * `1 − μ = 2(1 − u) (1 − g)² (1 + gu) / d²`
//!
//! Each is accurate to a few ULP in relative terms; we take `μ = −1 + (1 + μ)`
//! while that correction is below 1 (μ ≤ 0) and `μ = 1 − (1 − μ)` otherwise, so
//! the absolute error is a few ULP of 1 on the whole open interval `|g| < 1`,
//! with no threshold on `g` and no jump between the forms beyond that.

use super::PhaseFunction;
use crate::error::Error;
use crate::geometry::{Vec3, direction_about_turns};
use crate::real::Real;

/// Henyey–Greenstein with asymmetry `g ∈ (-1, 1)`; `g > 0` scatters forward.
/// Holds `g` and the constants every sample needs, computed once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein<T> {
    g: T,
    /// `1 − g` and `1 + g`.
    omg: T,
    opg: T,
    /// `1/(4π (1 − g²)²)`: the density of a sample is this times `d³`.
    pdf_k: T,
}

impl<T: Real> HenyeyGreenstein<T> {
    /// Fails with [`Error::Domain`] unless `-1 < g < 1` (NaN and ±∞ fail).
    pub fn new(g: T) -> Result<Self, Error> {
        if g > -T::ONE && g < T::ONE {
            Ok(Self::from_g(g))
        } else {
            Err(Error::Domain)
        }
    }
    /// The constants for a `g` already known to lie in `(-1, 1)`.
    pub(crate) fn from_g(g: T) -> Self {
        let (omg, opg) = (T::ONE - g, T::ONE + g);
        let omg2 = omg * opg;
        HenyeyGreenstein {
            g,
            omg,
            opg,
            pdf_k: T::INV_4PI / (omg2 * omg2),
        }
    }
    /// The asymmetry parameter `g`.
    pub fn g(&self) -> T {
        self.g
    }
    /// `(1 + μ, 1 − μ)` for `μ = F⁻¹(u)` (module docs).
    #[inline(always)]
    pub(super) fn one_plus_minus_mu(&self, u: T) -> (T, T) {
        let (opm, omm, _) = self.factors(u.clamp01());
        (opm, omm)
    }

    /// `(1 + μ, 1 − μ, d)` for `u ∈ [0, 1]` (not clamped here), with
    /// `d = 1 − g + 2gu` (module docs).
    #[inline(always)]
    fn factors(&self, u: T) -> (T, T, T) {
        let g = self.g;
        let v = T::ONE - u;
        // d = 1 − g + 2gu, 1 − g + gu and 1 + gu, each written as a sum of
        // non-negative terms for the sign of g: for g < 0, `1 − g + 2gu`
        // cancels as u → 1 and g → −1, but `(1 + g) − 2g(1 − u)` does not.
        let (d, a, b) = if g >= T::ZERO {
            let gu = g * u;
            (self.omg + (gu + gu), self.omg + gu, T::ONE + gu)
        } else {
            let gv = g * v;
            (self.opg - (gv + gv), T::ONE - gv, self.opg - gv)
        };
        let inv_d2 = T::ONE / (d * d);
        // The factors in this order (not 2(1 ± g)² taken once): it is the
        // order whose rounding the accuracy figures were measured with.
        let (omg, opg) = (self.omg, self.opg);
        (
            T::TWO * u * opg * opg * a * inv_d2,
            T::TWO * v * omg * omg * b * inv_d2,
            d,
        )
    }

    /// `cos θ` from `(1 + μ, 1 − μ)`: `−1 + (1 + μ)` while that correction
    /// is below 1, else `1 − (1 − μ)`, so the absolute error stays a few ULP
    /// of 1 at both poles.
    #[inline(always)]
    fn cos_from(opm: T, omm: T) -> T {
        if opm < T::ONE {
            opm - T::ONE
        } else {
            T::ONE - omm
        }
    }

    /// `1 + g² − 2gμ`, written as a sum of non-negative terms so it does not
    /// cancel at `μ → sign(g)`, `|g| → 1`.
    #[inline(always)]
    fn denom(&self, mu: T) -> T {
        let g = self.g;
        if g >= T::ZERO {
            (T::ONE - g) * (T::ONE - g) + T::TWO * g * (T::ONE - mu)
        } else {
            (T::ONE + g) * (T::ONE + g) - T::TWO * g * (T::ONE + mu)
        }
    }
}

impl<T: Real> PhaseFunction<T> for HenyeyGreenstein<T> {
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        let g = self.g;
        let d = self.denom(cos_theta);
        T::INV_4PI * (T::ONE - g) * (T::ONE + g) / (d * d.sqrt())
    }
    /// `F(μ) = (1 − g)(1 + μ) / (s (1 + g + s))`, `s = sqrt(1 + g² − 2gμ)`:
    /// the textbook `(1 − g²)/(2g) (1/s − 1/(1 + g))` with the `1/g` cancelled
    /// analytically.
    #[inline]
    fn cdf(&self, cos_theta: T) -> T {
        let g = self.g;
        let mu = cos_theta.clamp_unit();
        let s = self.denom(mu).sqrt();
        ((T::ONE - g) * (T::ONE + mu) / (s * (T::ONE + g + s))).clamp01()
    }
    #[inline]
    fn sample_cos(&self, u: T) -> T {
        let (opm, omm, _) = self.factors(u.clamp01());
        Self::cos_from(opm, omm)
    }
    #[inline]
    fn sample_cos_in_range(&self, u: T) -> T {
        let (opm, omm, _) = self.factors(u);
        Self::cos_from(opm, omm)
    }
    /// `sin θ = sqrt((1 + μ)(1 − μ))` from the two factors the sampler forms
    /// anyway, each accurate relative to itself.
    #[inline]
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let (opm, omm, _) = self.factors(u.clamp01());
        (Self::cos_from(opm, omm), (opm * omm).max_of(T::ZERO).sqrt())
    }
    /// The density comes from the sampler's own `d`: with
    /// `1 + g² − 2gμ = ((1 − g²)/d)²`, `p = d³ / (4π (1 − g²)²)`, with no
    /// square root or division.
    #[inline]
    fn sample_dir(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        let (opm, omm, d) = self.factors(u1.clamp01());
        let sin_theta = (opm * omm).max_of(T::ZERO).sqrt();
        let dir = direction_about_turns(w_in, Self::cos_from(opm, omm), sin_theta, u2.clamp01());
        (dir, self.pdf_k * d * d * d)
    }
    #[inline(always)]
    fn mean_cosine(&self) -> T {
        self.g
    }
}
