//! A phase function given by its Legendre moments, the form DISORT and
//! libRadtran take (`p = Σ_{l≤L} (2l + 1) χ_l P_l(μ) / 4π`, `χ_0 = 1`):
//! density, CDF and an exact inverse, so that a user's expansion can be
//! sampled (or tabulated, [`Table::inverse`](crate::table::Table::inverse))
//! without refitting it to a model.
//!
//! The CDF is exact term by term: `∫_{−1}^{μ} P_0 = μ + 1` and
//! `∫_{−1}^{μ} P_l = (P_{l+1}(μ) − P_{l−1}(μ))/(2l + 1)` for `l ≥ 1`, so
//! `F(μ) = ½ (μ + 1 + Σ_{l≥1} χ_l (P_{l+1}(μ) − P_{l−1}(μ)))`. A truncated
//! expansion of a peaked function goes negative (ringing); such an
//! expansion is refused: [`LegendreSeries::new`] evaluates the density at
//! `64 (L + 1) + 1` evenly spaced cosines (a dip narrower than that
//! spacing can pass unseen) and reports the first negative one.

use super::PhaseFunction;
use crate::error::Error;
use crate::math::numeric::inverse_cdf;
use crate::math::real::Real;

/// The most moments a series takes (`L ≤ 1023`).
pub const MAX_MOMENTS: usize = 1024;

/// A phase function from its Legendre moments, borrowed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegendreSeries<'a, T> {
    chi: &'a [T],
}

/// Where an expansion went negative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Negative {
    /// The first cosine checked where the density is below 0.
    pub cos_theta: f64,
    /// The density there (per steradian, < 0).
    pub pdf: f64,
}

impl<'a, T: Real> LegendreSeries<'a, T> {
    /// The series of `chi = [χ_0, …, χ_L]`. [`Error::Size`] for none or
    /// more than [`MAX_MOMENTS`]; [`Error::Domain`] unless `χ_0 = 1` (to
    /// 10⁻⁶), every `χ_l` is finite and in `[−1, 1]`, and the density is
    /// non-negative where [`check`](Self::check) looks.
    pub fn new(chi: &'a [T]) -> Result<Self, Error> {
        let s = Self::unchecked(chi)?;
        if s.check().is_some() {
            return Err(Error::Domain);
        }
        Ok(s)
    }

    /// The series without the sign check (for [`check`](Self::check) to
    /// say where it fails). Errors as [`new`](Self::new) otherwise.
    pub fn unchecked(chi: &'a [T]) -> Result<Self, Error> {
        if chi.is_empty() || chi.len() > MAX_MOMENTS {
            return Err(Error::Size);
        }
        let first = chi.first().map_or(f64::NAN, |c| c.to_f64());
        let bounded = chi.iter().all(|c| c.is_finite() && c.abs() <= T::ONE);
        if !bounded || (first - 1.0).abs() > 1e-6 {
            return Err(Error::Domain);
        }
        Ok(LegendreSeries { chi })
    }

    /// The moments `χ_0 … χ_L` the series holds.
    pub fn moments(&self) -> &'a [T] {
        self.chi
    }

    /// The first of `64 (L + 1) + 1` evenly spaced cosines where the
    /// density is negative, or `None`.
    pub fn check(&self) -> Option<Negative> {
        let m = 64 * self.chi.len();
        (0..=m).find_map(|i| {
            let mu = -1.0 + 2.0 * i as f64 / m as f64;
            let pdf = self.density(mu);
            (pdf < 0.0).then_some(Negative { cos_theta: mu, pdf })
        })
    }

    /// `(F(μ), 2π p(μ))` in f64, by the three-term recurrence.
    fn eval(&self, mu: f64) -> (f64, f64) {
        let (mut p_prev, mut p) = (1.0, mu); // P_{l−1}, P_l from l = 1
        let (mut density, mut cdf) = (0.0, 0.0);
        for (l, c) in self.chi.iter().enumerate() {
            let c = c.to_f64();
            let x = l as f64;
            if l == 0 {
                density += c;
                cdf += c * (mu + 1.0);
                continue;
            }
            let next = ((2.0 * x + 1.0) * mu * p - x * p_prev) / (x + 1.0);
            density += (2.0 * x + 1.0) * c * p;
            cdf += c * (next - p_prev);
            (p_prev, p) = (p, next);
        }
        (0.5 * cdf, 0.5 * density)
    }

    /// The density per steradian in f64.
    fn density(&self, mu: f64) -> f64 {
        self.eval(mu).1 / core::f64::consts::TAU
    }
}

impl<T: Real> PhaseFunction<T> for LegendreSeries<'_, T> {
    fn pdf(&self, cos_theta: T) -> T {
        T::from_f64(self.density(cos_theta.to_f64()))
    }
    fn cdf(&self, cos_theta: T) -> T {
        let mu = cos_theta.to_f64();
        if mu.is_nan() {
            return T::NAN;
        }
        T::from_f64(self.eval(mu.clamp(-1.0, 1.0)).0.clamp(0.0, 1.0))
    }
    /// The exact inverse: `F(μ) = u` by safeguarded Newton in f64 from
    /// `μ = 2u − 1`, in the smaller tail.
    fn sample_cos(&self, u: T) -> T {
        let u = u.clamp01().to_f64();
        if u.is_nan() {
            return T::NAN;
        }
        let mu = inverse_cdf(|mu| self.eval(mu), u, 2.0 * u - 1.0);
        T::from_f64(mu.clamp(-1.0, 1.0))
    }
    /// `χ_1`.
    fn mean_cosine(&self) -> T {
        self.chi.get(1).copied().unwrap_or(T::ZERO)
    }
}
