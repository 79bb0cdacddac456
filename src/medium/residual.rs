//! Residual ratio tracking (Novák, Selle & Jarosz, "Residual Ratio
//! Tracking for Estimating Attenuation in Participating Media", ACM TOG
//! 33(6), 2014, §4): the transmittance `exp(−∫σ_t)` split as
//! `exp(−∫σ_c) · exp(−∫(σ_t − σ_c))`, with the control extinction `σ_c`
//! each cell's minorant. The first factor is exact, summed cell by cell
//! along the ray; the second is ratio tracking at the residual majorant
//! `σ_maj − σ_c`. Where the density varies little within a cell the
//! residual is small: few tentative collisions, each weight near 1. In a
//! medium that is constant in each cell (minorant = majorant = `σ_t`) no
//! collision is drawn and the estimate is exact.
//!
//! Tentative collisions are drawn at [`RESIDUAL_RATE`] = 2 times the
//! residual majorant `r = σ_maj − σ_c` by default, not at `r` itself as in
//! Novák et al.: ratio tracking is unbiased at any rate at or above what it
//! tracks. At rate `κ r` its relative variance is `e^{B/κ} − 1`, with
//! `B = ∫ σ_r²/r ≤ ∫ r = D` (`σ_r = σ_t − σ_c`, the residual), and its
//! work `c₀ + κ c₁ D` (a fixed part `c₀`, the ray's setup and the cells
//! crossed, and `c₁` per collision). Since `e^B − 1 = (e^{B/2} − 1)
//! (e^{B/2} + 1)` and `e^{B/2} + 1 ≥ 2`, variance × work at `κ = 2` is
//! never above that at `κ = 1`, on any medium; and as plain ratio tracking
//! is the case `σ_c = 0`, `r = σ_maj`, with a larger `B` and `D`, never
//! above ratio tracking's but for the walk's own bookkeeping (a larger
//! `c₀`: the minorants read). Russian roulette, which this ignores, adds a
//! little variance to both. The gain is largest where `B` is small and
//! `c₀` is not; measured on the main example's suite of media, residual
//! tracking at `κ = 1` lost to ratio tracking in its worst class
//! (0.85–0.89×: no minorant, the walk's bookkeeping) and at `κ = 2` gains
//! 1.1× there; a sweep of `κ` over that suite, run once while choosing,
//! found 2 best in the worst class among 1, 1.25, 1.5, 1.75, 2, 2.5 and 3
//! (higher rates lose where a cell's residual depth is large: a dense sheet
//! in a cell of haze spends their collisions in the haze).
//! [`Extrema::residual_ratio_track_rate`] takes any whole multiple, 1 for
//! the published estimator.
//!
//! An [`Extrema`] pairs a grid's majorants with its minorants over the
//! same cells; [`Extrema::build`] fills both from a density [`Grid`] in
//! one pass each ([`Majorants::build`], [`Majorants::build_minorants`]).

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Majorants, Tentative, Transmittance};
use crate::medium::{Grid, Ray, roulette};
use core::cell::Cell;
use rand_core::Rng;

/// The default rate of residual ratio tracking's tentative collisions, as
/// a multiple of each cell's residual majorant `σ_maj − σ_min` (see the
/// module's documentation for why it is not 1).
pub const RESIDUAL_RATE: u32 = 2;

/// Majorants and minorants (per length unit) over the same cells of the
/// same box: `0 ≤ minorant ≤ majorant` in every cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extrema<'a, T> {
    max: Majorants<'a, T>,
    min: Majorants<'a, T>,
}

impl<'a, T: Real> Extrema<'a, T> {
    /// Pairs `max` with `min`: [`Error::Domain`] unless both have the same
    /// cells and box and every minorant is at most its cell's majorant.
    /// Each must bound `σ_t` over its closed cell, from above and from
    /// below; tracking reports [`Error::Domain`] where `σ_t` exceeds a
    /// majorant. A minorant above `σ_t` keeps the estimate unbiased where
    /// its cell's residual `σ_maj − σ_min` is positive (its weights are
    /// then above one) but costs variance; a cell whose minorant equals
    /// its majorant draws nothing and reads no density, so there `σ_t` is
    /// taken to be that value.
    pub fn new(max: Majorants<'a, T>, min: Majorants<'a, T>) -> Result<Self, Error> {
        let pair = Self::paired(max, min)?;
        let m = max.dims();
        for k in 0..m[2] {
            for j in 0..m[1] {
                for i in 0..m[0] {
                    if min.get(i, j, k) > max.get(i, j, k) {
                        return Err(Error::Domain);
                    }
                }
            }
        }
        Ok(pair)
    }

    /// [`new`](Self::new) without the pass over the cells, for values a
    /// caller stores (the C layer's `sk_extrema`): same cells and box, else
    /// [`Error::Domain`]. Tracking still reports a cell whose minorant
    /// exceeds its majorant as [`Error::Domain`] when a ray crosses it.
    pub(crate) fn paired(max: Majorants<'a, T>, min: Majorants<'a, T>) -> Result<Self, Error> {
        if max.dims() != min.dims() || max.bounds() != min.bounds() {
            return Err(Error::Domain);
        }
        Ok(Extrema { max, min })
    }

    /// The majorants of `grid` into `max_out` and its minorants into
    /// `min_out`, on an `m` division of its box, borrowed. Errors as
    /// [`Majorants::new`].
    pub fn build(
        grid: &Grid<'_, T>,
        m: [usize; 3],
        max_out: &'a mut [T],
        min_out: &'a mut [T],
    ) -> Result<Self, Error> {
        let max = Majorants::build(grid, m, max_out)?;
        let min = Majorants::build_minorants(grid, m, min_out)?;
        Self::new(max, min)
    }

    /// The majorants.
    pub fn majorants(&self) -> Majorants<'a, T> {
        self.max
    }

    /// The minorants.
    pub fn minorants(&self) -> Majorants<'a, T> {
        self.min
    }

    /// `∫ σ_c` along `ray` (the control's optical depth), cell by cell.
    /// [`Error::Domain`] for a ray [`Ray`] does not accept.
    pub fn control_depth(&self, ray: Ray<T>) -> Result<T, Error> {
        self.min.optical_depth(ray)
    }

    /// Residual ratio tracking through `grid` (whose extrema these must be:
    /// same box, else [`Error::Domain`]) along `ray`: an unbiased estimate
    /// of the transmittance, with the Russian roulette of ratio tracking on
    /// the residual factor, at the default rate [`RESIDUAL_RATE`]. Budget
    /// and errors as [`Majorants::ratio_track`]. Another rate:
    /// [`residual_ratio_track_rate`](Self::residual_ratio_track_rate) with
    /// `|p| grid.coefficients_at(p)` ([`Grid::coefficients_at`]).
    pub fn residual_ratio_track<R: Rng + ?Sized>(
        &self,
        grid: &Grid<'_, T>,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Transmittance<T>, Error> {
        if grid.bounds() != self.max.bounds() {
            return Err(Error::Domain);
        }
        self.residual_ratio_track_fn(|p| grid.coefficients_at(p), ray, budget, rng)
    }

    /// Residual ratio tracking through a caller's medium,
    /// `coefficients(p) = (σ_a, σ_s)` at a world point (both `≥ 0`, their
    /// sum within the majorant of the cell holding `p`, else
    /// [`Error::Domain`]), along `ray`, at the default rate
    /// [`RESIDUAL_RATE`].
    pub fn residual_ratio_track_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Transmittance<T>, Error> {
        self.residual_ratio_track_rate(coefficients, ray, 0, budget, rng)
    }

    /// [`residual_ratio_track_fn`](Self::residual_ratio_track_fn) with
    /// tentative collisions drawn at `rate` times each cell's residual
    /// majorant `σ_maj − σ_min` (a whole number; 1 is Novák et al.'s
    /// estimator, 0 takes [`RESIDUAL_RATE`]). Each weighs
    /// `1 − (σ_t − σ_min)/(rate (σ_maj − σ_min))`, in `[0, 1]` wherever the
    /// extrema bound `σ_t`. A higher rate spends more density evaluations
    /// (and more of `budget`) for less variance.
    pub fn residual_ratio_track_rate<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        rate: u32,
        budget: u32,
        rng: &mut R,
    ) -> Result<Transmittance<T>, Error> {
        let rate = T::from_f64(f64::from(if rate == 0 { RESIDUAL_RATE } else { rate }));
        let mut tr = T::ONE;
        // The rates (σ_c, σ_maj) of the cell being crossed, set by
        // `residual` as the walk enters it, read at its collisions.
        let rates = Cell::new((T::ZERO, T::ZERO));
        let visit = |c: Tentative<T>, r: &mut R| {
            let (sa, ss) = coefficients(c.p);
            let (sigma_c, sigma_maj) = rates.get();
            if !(sa >= T::ZERO && ss >= T::ZERO && sa + ss <= sigma_maj) {
                return Err(Error::Domain);
            }
            // c.value is the residual majorant σ_maj − σ_c of the cell;
            // the collisions come at `rate` times it.
            tr = roulette(tr * (T::ONE - (sa + ss - sigma_c) / (rate * c.value)), r);
            Ok((tr == T::ZERO).then_some(()))
        };
        // The control's optical depth is summed in the same walk, cell by
        // cell. A cell whose minorant exceeds its majorant or is negative
        // (values a caller stored) would bias it: the walk notes it.
        let (mut control, mut inverted) = (T::ZERO, false);
        let residual = |cell: [usize; 3], length: T| {
            // The two grids share their dimensions (`paired`): one index.
            let i = self.max.index(cell);
            let (lo, hi) = (self.min.at_index(i), self.max.at_index(i));
            rates.set((lo, hi));
            control += lo * length;
            inverted |= !(lo >= T::ZERO && hi >= lo);
            hi - lo
        };
        let walk = self
            .max
            .walk_cells(ray, rate, residual, budget, rng, visit)?;
        if inverted {
            return Err(Error::Domain);
        }
        let tr = if walk.found.is_some() { T::ZERO } else { tr };
        // Where the control is 0 along the ray (a sparse medium) this is
        // ratio tracking at `rate` times the majorant.
        let tr = if control > T::ZERO {
            tr * (-control).exp()
        } else {
            tr
        };
        Ok(Transmittance {
            tr,
            steps: walk.steps,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::SeedableRng;

    /// Extrema stored unchecked (as the C layer keeps them) are refused
    /// where the ray meets a cell whose minorant is negative or above its
    /// majorant, whichever of the two fails (a mutation test's `&&` → `||`
    /// let a negative minorant under a positive majorant through).
    #[test]
    fn stored_extrema_that_do_not_hold_are_refused_on_the_way() {
        let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
        let ray = Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::new(0.0, 0.0, 1.0), 3.0);
        let medium = |_: Vec3<f64>| (0.0, 0.5);
        for (min, max, ok) in [(0.25, 1.0, true), (-1.0, 1.0, false), (2.0, 1.0, false)] {
            let (min, max) = ([min], [max]);
            let pair = Extrema::paired(
                Majorants::from_parts(&max, [1; 3], lo, hi).unwrap(),
                Majorants::from_parts(&min, [1; 3], lo, hi).unwrap(),
            )
            .unwrap();
            let mut r = Xoshiro256PlusPlus::seed_from_u64(3);
            let got = pair.residual_ratio_track_rate(medium, ray, 1, 1 << 20, &mut r);
            assert_eq!(
                got.is_ok(),
                ok,
                "minorant {min:?}, majorant {max:?}: {got:?}"
            );
            if !ok {
                assert_eq!(got.err(), Some(Error::Domain));
            }
        }
    }
}
