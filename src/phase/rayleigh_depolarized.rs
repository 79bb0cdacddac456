//! Rayleigh scattering with depolarisation (Chandrasekhar, "Radiative Transfer",
//! 1960, ch. I), as atmospheric codes
//! use it for real air (depolarisation factor ρ ≈ 0.028):
//! `p(μ) = 3 (1 + 3γ + (1 − γ) μ²) / (16π (1 + 2γ))`, `γ = ρ/(2 − ρ)`.
//!
//! The CDF is `F(x) = (1 + x) [3(1 + 3γ) + (1 − γ)(x² − x + 1)] / (8(1 + 2γ))`
//! (the `x³ + 1` of the integral factored as `(x + 1)(x² − x + 1)` so `F` does
//! not cancel near `x = −1`), and `F(x) = u` is the depressed cubic
//! `x³ + 3a x = 2b` with `a = (1 + 3γ)/(1 − γ)`, `b = 2(1 + 2γ)(2u − 1)/(1 − γ)`,
//! solved by the same cancellation-free Cardano root as plain Rayleigh.

use super::function::PhaseFunction;
use super::model::{Lobes, Model, exactly, open};
use crate::error::Error;
use crate::math::numeric::depressed_cubic_root;
use crate::math::real::Real;

/// Depolarised Rayleigh scattering; `rho = 0` is plain Rayleigh. Mean cosine 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayleighDepolarized<T> {
    rho: T,
    gamma: T,
    /// `a` of the cubic, and `a²`.
    a: T,
    a2: T,
    /// `b = k (2u − 1)`.
    k: T,
}

impl<T: Real> RayleighDepolarized<T> {
    /// Fails with [`Error::Domain`] unless `0 ≤ rho < 1` (NaN fails).
    pub fn new(rho: T) -> Result<Self, Error> {
        if !(rho >= T::ZERO && rho < T::ONE) {
            return Err(Error::Domain);
        }
        Ok(Self::from_rho(rho))
    }
    /// The constants for a `rho` already known to lie in `[0, 1)`.
    pub(crate) fn from_rho(rho: T) -> Self {
        let gamma = rho / (T::TWO - rho);
        let omg = T::ONE - gamma;
        let a = (T::ONE + T::from_f64(3.0) * gamma) / omg;
        let k = T::TWO * (T::ONE + T::TWO * gamma) / omg;
        RayleighDepolarized {
            rho,
            gamma,
            a,
            a2: a * a,
            k,
        }
    }
    /// The depolarisation factor ρ.
    pub fn rho(&self) -> T {
        self.rho
    }
    /// `γ = ρ/(2 − ρ)`.
    pub fn gamma(&self) -> T {
        self.gamma
    }
}

impl<T: Real> PhaseFunction<T> for RayleighDepolarized<T> {
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        let g = self.gamma;
        let three = T::from_f64(3.0);
        let c = three / (T::from_f64(16.0) * T::PI * (T::ONE + T::TWO * g));
        c * (T::ONE + three * g + (T::ONE - g) * cos_theta * cos_theta)
    }
    #[inline]
    fn cdf(&self, cos_theta: T) -> T {
        // F = (1 + x)(3(1 + 3γ) + (1 − γ)(x² − x + 1)) / (8(1 + 2γ)), with
        // 3(1 + 3γ) + (1 − γ) = 4(1 + 2γ) taken out: F = (1 + x)(½ − c x (1
        // − x)), c = (1 − γ)/(8(1 + 2γ)). Exactly 0 at x = −1 and 1 at x = 1
        // (the sum's rounding left F(1) = 1 − ε as γ → 1), and the bracket
        // stays ≥ ½ − c/4 > 0, so nothing cancels.
        let (g, x) = (self.gamma, cos_theta.clamp_unit());
        let c = (T::ONE - g) / (T::from_f64(8.0) * (T::ONE + T::TWO * g));
        ((T::ONE + x) * (T::HALF - c * x * (T::ONE - x))).clamp01()
    }
    #[inline]
    fn sample_cos(&self, u: T) -> T {
        let b = self.k * (T::TWO * u.clamp01() - T::ONE);
        depressed_cubic_root::<T, false>(self.a, self.a2, b).clamp_unit()
    }
    #[inline(always)]
    fn mean_cosine(&self) -> T {
        T::ZERO
    }
}

impl<T: Real> Model<T> for RayleighDepolarized<T> {
    type In<U: Real> = RayleighDepolarized<U>;
    const PARAMS: usize = 1;
    fn params(&self) -> [T; 4] {
        [self.rho, T::ZERO, T::ZERO, T::ZERO]
    }
    fn from_params(p: &[T]) -> Result<Self, Error> {
        let [rho] = exactly(p)?;
        Self::new(rho)
    }
    fn cast<U: Real>(&self) -> RayleighDepolarized<U> {
        // ρ ∈ [0, 1) stays there: `open` keeps it below 1.
        RayleighDepolarized::from_rho(open(self.rho))
    }
    /// Draine with `g = 0`, `α = (1 − γ)/(1 + 3γ)`.
    fn lobes(&self) -> Option<Lobes> {
        let g = self.gamma.to_f64();
        Some(((0.0, (1.0 - g) / (1.0 + 3.0 * g)), (0.0, 0.0), 0.0))
    }
}
