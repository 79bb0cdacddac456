//! Tracking through majorants that may not bound the medium: a callback
//! density whose maximum is only estimated, or majorants built from a
//! coarser or older version of the data. The strict trackers
//! ([`Majorants::ratio_track_fn`], [`Majorants::delta_track_fn`]) report
//! [`Error::Domain`] where `σ_t` exceeds `σ_maj`; these keep going,
//! unbiased, at the price of signed weights where the bound fails (Misso,
//! Pediredla, Jarosz & Novák, "Progressive Null-Tracking for Volumetric
//! Rendering", SIGGRAPH 2023; the weighted tracking of Galtier et al.
//! 2013 and Kutz et al. 2017, §4).
//!
//! **Ratio tracking** `Π (1 − σ_t(x_i)/σ_maj)` over the tentative
//! collisions of a Poisson process of rate `σ_maj` has the mean
//! `exp(−∫σ_t)` whatever the sign of each factor: the bound only keeps the
//! factors in `[0, 1]`. Where `σ_t > σ_maj` a factor is negative; the
//! estimate stays unbiased, its variance grows with `σ_t/σ_maj`.
//!
//! **Weighted delta tracking**: at a tentative collision with
//! `σ_n = σ_maj − σ_t`, the collision is real with probability
//! `σ_t / (σ_t + |σ_n|)` and the path's weight is multiplied by
//! `(σ_t + |σ_n|)/σ_maj`, negated for a null collision where `σ_n < 0`.
//! Where the majorant bounds (`σ_n ≥ 0`) this is delta tracking with the
//! weight untouched. The weighted outcome is unbiased: `E[w · f(t, event)]`
//! equals `f` averaged over the true collision density.
//!
//! **The one bias left**: a cell whose majorant is 0 is crossed without a
//! draw, so density there is never seen. Give every cell that may hold
//! density a positive majorant.
//!
//! **Re-bounding.** Each result reports the largest `σ_t/σ_maj` above 1
//! it met and the cell, so that the caller can raise that cell's majorant
//! for later rays (Misso et al.'s progressive scheme). Raising majorants
//! between rays keeps every estimate unbiased; changing them during a
//! walk would not.

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Majorants, Tentative};
use crate::medium::{Event, ROULETTE_BELOW, Ray, roulette_factor};
use rand_core::Rng;

/// Where a majorant failed to bound: the largest `σ_t/σ_maj` (> 1) a walk
/// met, and the majorant cell it met it in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exceeded<T> {
    /// `σ_t/σ_maj` there (> 1).
    pub ratio: T,
    /// The cell `[i, j, k]` of the majorant grid.
    pub cell: [usize; 3],
}

/// What ratio tracking with signed weights found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignedTransmittance<T> {
    /// The unbiased transmittance estimate: may be negative, or above 1,
    /// where a majorant did not bound.
    pub tr: T,
    /// Tentative collisions drawn (density evaluations).
    pub steps: u32,
    /// The worst place the majorants failed to bound, if any.
    pub exceeded: Option<Exceeded<T>>,
}

/// What weighted delta tracking found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeightedTrack<T> {
    /// Distance along the unit direction of the real collision, or where
    /// the ray leaves the box (as [`Track`](super::majorant::Track)).
    pub t: T,
    /// [`Event::Escaped`], [`Event::Scattered`] or [`Event::Absorbed`].
    pub event: Event,
    /// The path's weight: 1 where every majorant met bounded `σ_t`; else
    /// signed, and the outcome counts with this weight.
    pub weight: T,
    /// Tentative collisions drawn (density evaluations), real one included.
    pub steps: u32,
    /// The worst place the majorants failed to bound, if any.
    pub exceeded: Option<Exceeded<T>>,
}

/// The coefficients if both are finite and `≥ 0`, and the worst excess.
fn checked<T: Real>(
    (sa, ss): (T, T),
    c: &Tentative<T>,
    worst: &mut Option<Exceeded<T>>,
) -> Result<(T, T), Error> {
    if !(sa >= T::ZERO && ss >= T::ZERO && (sa + ss).is_finite()) {
        return Err(Error::Domain);
    }
    let ratio = (sa + ss) / c.value;
    if ratio > worst.map_or(T::ONE, |w| w.ratio) {
        *worst = Some(Exceeded {
            ratio,
            cell: c.cell,
        });
    }
    Ok((sa, ss))
}

impl<T: Real> Majorants<'_, T> {
    /// Ratio tracking through a caller's medium, `coefficients(p) =
    /// (σ_a, σ_s)` at a world point (both finite and `≥ 0`, else
    /// [`Error::Domain`]; their sum may exceed the majorant), along `ray`:
    /// unbiased with signed weights (module docs), with the Russian
    /// roulette of [`ratio_track`](Self::ratio_track) on the weight's
    /// magnitude. [`Error::Budget`] after `budget` tentative collisions;
    /// [`Error::Domain`] for a ray [`Ray`] does not accept or a weight that
    /// overflows.
    pub fn ratio_track_signed_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<SignedTransmittance<T>, Error> {
        let (mut tr, mut worst) = (T::ONE, None);
        let visit = |c: Tentative<T>, r: &mut R| {
            let (sa, ss) = checked(coefficients(c.p), &c, &mut worst)?;
            tr *= T::ONE - (sa + ss) / c.value;
            if tr.abs() < T::from_f64(ROULETTE_BELOW) {
                tr *= roulette_factor::<T, R>(r);
            }
            if !tr.is_finite() {
                return Err(Error::Domain);
            }
            Ok((tr == T::ZERO).then_some(()))
        };
        let walk = self.walk_at_rate(ray, T::ONE, budget, rng, visit)?;
        Ok(SignedTransmittance {
            tr: if walk.found.is_some() { T::ZERO } else { tr },
            steps: walk.steps,
            exceeded: worst,
        })
    }

    /// Weighted delta tracking through a caller's medium (arguments as
    /// [`ratio_track_signed_fn`](Self::ratio_track_signed_fn)): the first
    /// real collision or the exit, with the weight it carries (module
    /// docs); one uniform per tentative collision decides between
    /// absorption, scattering and a null collision. Errors as
    /// [`ratio_track_signed_fn`](Self::ratio_track_signed_fn).
    pub fn delta_track_weighted_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<WeightedTrack<T>, Error> {
        let (mut weight, mut worst) = (T::ONE, None);
        let visit = |c: Tentative<T>, r: &mut R| {
            let (sa, ss) = checked(coefficients(c.p), &c, &mut worst)?;
            let (st, sn) = (sa + ss, c.value - (sa + ss));
            // total = σ_maj where the majorant bounds; else σ_t + |σ_n|.
            let total = st + sn.abs();
            let x = T::uniform(r) * total;
            let event = if x < sa {
                Some(Event::Absorbed)
            } else if x < st {
                Some(Event::Scattered)
            } else {
                None
            };
            if sn < T::ZERO {
                let sign = if event.is_some() { T::ONE } else { -T::ONE };
                weight *= sign * total / c.value;
                if !weight.is_finite() {
                    return Err(Error::Domain);
                }
            }
            Ok(event)
        };
        let walk = self.walk_at_rate(ray, T::ONE, budget, rng, visit)?;
        let (t, event) = walk.found.unwrap_or((walk.exit, Event::Escaped));
        Ok(WeightedTrack {
            t,
            event,
            weight,
            steps: walk.steps,
            exceeded: worst,
        })
    }
}
