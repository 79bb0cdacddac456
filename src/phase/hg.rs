//! Henyey–Greenstein (SPEC §2):
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
use crate::real::Real;

/// Henyey–Greenstein with asymmetry `g ∈ (-1, 1)`; `g > 0` scatters forward.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein<T> {
    pub(super) g: T,
}

impl<T: Real> HenyeyGreenstein<T> {
    /// Fails with [`Error::Domain`] unless `-1 < g < 1` (NaN and ±∞ fail).
    pub fn new(g: T) -> Result<Self, Error> {
        if g > -T::ONE && g < T::ONE {
            Ok(HenyeyGreenstein { g })
        } else {
            Err(Error::Domain)
        }
    }
    /// The asymmetry parameter `g`.
    pub fn g(&self) -> T {
        self.g
    }
    /// `(1 + μ, 1 − μ)` for `μ = F⁻¹(u)` (module docs).
    #[inline(always)]
    pub(super) fn one_plus_minus_mu(&self, u: T) -> (T, T) {
        let g = self.g;
        let u = u.clamp01();
        let v = T::ONE - u;
        let (omg, opg) = (T::ONE - g, T::ONE + g);
        // d = 1 − g + 2gu, 1 − g + gu and 1 + gu, each written as a sum of
        // non-negative terms for the sign of g: for g < 0, `1 − g + 2gu`
        // cancels as u → 1 and g → −1, but `(1 + g) − 2g(1 − u)` does not.
        let (d, a, b) = if g >= T::ZERO {
            (omg + T::TWO * g * u, omg + g * u, T::ONE + g * u)
        } else {
            (opg - T::TWO * g * v, T::ONE - g * v, opg - g * v)
        };
        let inv_d2 = T::ONE / (d * d);
        (
            T::TWO * u * opg * opg * a * inv_d2,
            T::TWO * v * omg * omg * b * inv_d2,
        )
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
        self.sample_cos_sin(u).0
    }
    /// `sin θ = sqrt((1 + μ)(1 − μ))` from the two factors the sampler forms
    /// anyway, each accurate relative to itself.
    #[inline]
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let (one_plus_mu, one_minus_mu) = self.one_plus_minus_mu(u);
        let mu = if one_plus_mu < T::ONE {
            one_plus_mu - T::ONE
        } else {
            T::ONE - one_minus_mu
        };
        (mu, (one_plus_mu * one_minus_mu).max_of(T::ZERO).sqrt())
    }
    #[inline(always)]
    fn mean_cosine(&self) -> T {
        self.g
    }
}
