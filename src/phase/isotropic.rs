//! Isotropic scattering: `p(μ) = 1/(4π)`.

use super::function::PhaseFunction;
use super::model::{Lobes, Model, exactly};
use crate::error::Error;
use crate::math::real::Real;

/// Uniform scattering over the sphere. Mean cosine 0.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Isotropic;

impl<T: Real> PhaseFunction<T> for Isotropic {
    /// `1/(4π)`; NaN for a NaN argument, as every pdf.
    #[inline(always)]
    fn pdf(&self, cos_theta: T) -> T {
        if cos_theta.is_nan() {
            T::NAN
        } else {
            T::INV_4PI
        }
    }
    #[inline(always)]
    fn cdf(&self, cos_theta: T) -> T {
        (T::ONE + cos_theta.clamp_unit()) * T::HALF
    }
    /// `μ = 2u − 1`.
    #[inline(always)]
    fn sample_cos(&self, u: T) -> T {
        T::TWO * u.clamp01() - T::ONE
    }
    #[inline(always)]
    fn mean_cosine(&self) -> T {
        T::ZERO
    }
}

impl<T: Real> Model<T> for Isotropic {
    type In<U: Real> = Isotropic;
    const PARAMS: usize = 0;
    fn params(&self) -> [T; 4] {
        [T::ZERO; 4]
    }
    fn from_params(p: &[T]) -> Result<Self, Error> {
        exactly::<T, 0>(p).map(|_| Isotropic)
    }
    fn cast<U: Real>(&self) -> Isotropic {
        Isotropic
    }
    fn lobes(&self) -> Option<Lobes> {
        Some(((0.0, 0.0), (0.0, 0.0), 0.0))
    }
}
