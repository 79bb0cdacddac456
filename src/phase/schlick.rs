//! Schlick's phase function (Blasi, Le Saëc & Schlick, "A Rendering
//! Algorithm for Discrete Volume Density Objects", Computer Graphics Forum
//! 12(3), 1993, eq. 3): the cheap stand-in for Henyey–Greenstein of
//! pbrt-v2 (`PhaseSchlick`) and many GPU renderers,
//!
//! `p(μ) = (1 − k²) / (4π (1 − kμ)²)`,  `−1 < k < 1`,
//!
//! with `μ = cos θ` between propagation directions, so `k > 0` scatters
//! forward. It is a density with a rational CDF and a rational inverse, no
//! power and no square root:
//!
//! `F(μ) = (1 − k)(1 + μ) / (2(1 − kμ))`,  `μ(u) = (2u − 1 + k)/(1 − k + 2ku)`.
//!
//! The inverse is evaluated as `−1 + 2u(1 + k)/D` where `μ ≤ 0`
//! (`2u ≤ 1 − k`) and `1 − 2(1 − k)(1 − u)/D` where `μ > 0`,
//! `D = 1 − k + 2ku > 0`: each form keeps its relative accuracy at its own
//! end (the textbook form subtracts `1 − k` from `2u` and cancels where
//! `μ` is near ±1). `D` and `1 − kμ` are each summed from two non-negative
//! terms, so neither cancels at the peak either. Its mean cosine is
//! `(k − (1 − k²) atanh k)/k²`, which cancels for small `|k|` (its leading
//! terms agree to `O(k³)`); there the all-positive series
//! `Σ_{n≥1} 2k^{2n−1}/((2n − 1)(2n + 1))` is used instead. Schlick's
//! `k ≈ 1.55g − 0.55g³` approximates HG of asymmetry `g`
//! ([`Schlick::approximating_hg`]); its own mean cosine is not `g`.

use super::function::PhaseFunction;
use super::model::{Lobes, Model, exactly, open};
use crate::error::Error;
use crate::math::real::Real;

/// Schlick's phase function with parameter `k ∈ (−1, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schlick<T> {
    k: T,
    /// `1 − k`, `1 + k`, `(1 − k²)/(4π)`.
    omk: T,
    opk: T,
    norm: T,
}

impl<T: Real> Schlick<T> {
    /// Fails with [`Error::Domain`] unless `−1 < k < 1` (NaN fails).
    pub fn new(k: T) -> Result<Self, Error> {
        if k > -T::ONE && k < T::ONE {
            Ok(Self::from_k(k))
        } else {
            Err(Error::Domain)
        }
    }

    /// The fit of Blasi et al. to Henyey–Greenstein of asymmetry `g`:
    /// `k = 1.55g − 0.55g³` (pbrt-v2's), for `−1 < g < 1`.
    pub fn approximating_hg(g: T) -> Result<Self, Error> {
        if !(g > -T::ONE && g < T::ONE) {
            return Err(Error::Domain);
        }
        // The cubic passes 1 near g = 0.97 (its peak is 1.0015): held inside.
        let k = T::from_f64(1.55) * g - T::from_f64(0.55) * g * g * g;
        let edge = T::ONE - T::EPSILON;
        Self::new(k.max_of(-edge).min_of(edge))
    }

    /// The constants for a `k` already known to lie in `(−1, 1)`.
    pub(crate) fn from_k(k: T) -> Self {
        let (omk, opk) = (T::ONE - k, T::ONE + k);
        let norm =
            T::from_f64((1.0 - k.to_f64()) * (1.0 + k.to_f64()) / (4.0 * core::f64::consts::PI));
        Schlick { k, omk, opk, norm }
    }

    /// `k`.
    pub fn k(&self) -> T {
        self.k
    }
}

impl<T: Real> Schlick<T> {
    /// `1 − kμ` as a sum of two non-negative terms: `1 − k + k(1 − μ)` for
    /// `k ≥ 0`, `1 + k − k(1 + μ)` for `k < 0`. Written as `1 − kμ` it
    /// cancels where `kμ → 1`, at the peak.
    #[inline(always)]
    fn one_minus_k_mu(&self, mu: T) -> T {
        if self.k >= T::ZERO {
            self.omk + self.k * (T::ONE - mu)
        } else {
            self.opk - self.k * (T::ONE + mu)
        }
    }
}

impl<T: Real> PhaseFunction<T> for Schlick<T> {
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        let d = self.one_minus_k_mu(cos_theta);
        self.norm / (d * d)
    }
    #[inline]
    fn cdf(&self, cos_theta: T) -> T {
        let mu = cos_theta.clamp_unit();
        let d = T::TWO * self.one_minus_k_mu(mu);
        let f = self.omk * (T::ONE + mu) / d;
        // Above ½, one minus the upper tail `(1 + k)(1 − μ)/(2(1 − kμ))`
        // (the numerators sum to `2(1 − kμ)`): a product, so `1 − tail`
        // rises with μ, where `f` stepped back by up to three ulps of 1
        // as k → −1.
        if f > T::HALF {
            (T::ONE - self.opk * (T::ONE - mu) / d).clamp01()
        } else {
            f.clamp01()
        }
    }
    #[inline]
    fn sample_cos(&self, u: T) -> T {
        let u = u.clamp01();
        // D = 1 − k + 2ku, as two non-negative terms (it cancels as
        // k → −1, u → 1 written directly).
        let d = if self.k >= T::ZERO {
            self.omk + T::TWO * self.k * u
        } else {
            self.opk - T::TWO * self.k * (T::ONE - u)
        };
        // μ(u) changes sign at u = (1 − k)/2: each side from its own end.
        let mu = if T::TWO * u <= self.omk {
            T::TWO * u * self.opk / d - T::ONE
        } else {
            T::ONE - T::TWO * self.omk * (T::ONE - u) / d
        };
        mu.clamp_unit()
    }
    fn mean_cosine(&self) -> T {
        T::from_f64(mean_cosine(self.k.to_f64()))
    }
}

/// The mean cosine of Schlick's function with parameter `k` (module docs).
fn mean_cosine(k: f64) -> f64 {
    if k.abs() < 0.5 {
        let (k2, mut term, mut sum) = (k * k, k, 0.0);
        for n in 1..=40 {
            let m = n as f64;
            sum += 2.0 * term / ((2.0 * m - 1.0) * (2.0 * m + 1.0));
            term *= k2;
        }
        sum
    } else {
        (k - (1.0 - k * k) * libm::atanh(k)) / (k * k)
    }
}

impl<T: Real> Model<T> for Schlick<T> {
    type In<U: Real> = Schlick<U>;
    const PARAMS: usize = 1;
    fn params(&self) -> [T; 4] {
        [self.k, T::ZERO, T::ZERO, T::ZERO]
    }
    fn from_params(p: &[T]) -> Result<Self, Error> {
        let [k] = exactly(p)?;
        Self::new(k)
    }
    fn cast<U: Real>(&self) -> Schlick<U> {
        Schlick::from_k(open(self.k))
    }
    /// Not a Draine lobe: its moments come by quadrature.
    fn lobes(&self) -> Option<Lobes> {
        None
    }
}
