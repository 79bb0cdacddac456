//! Emission along a ray: the radiance a medium emits toward the ray's
//! origin over a segment `[a, b]`,
//!
//! `L = ∫_a^b T(a, t) σ_a(t) L_e(t) dt`,  `T(a, t) = exp(−∫_a^t σ_t)`,
//!
//! with `L_e` the emitted radiance (the source function: the Planck
//! radiance of a thermal emitter, the glow of a flame) and `σ_a L_e` the
//! emission coefficient, as in the radiative transfer equation with
//! Kirchhoff's law (Chandrasekhar 1960, §1.3; pbrt-v4's media carry `L_e`
//! the same way). Emission needs absorption here: a medium that emits must
//! absorb where it does, so the majorant is positive wherever there is
//! something to find. A caller with an emission coefficient `j` of their
//! own passes `L_e = j / σ_a`.
//!
//! [`Majorants::emission_track`] estimates `L` by ratio tracking: at each
//! tentative collision `t_i` (a Poisson process of rate `σ_maj`) it scores
//! `W_i σ_a L_e / σ_maj`, `W_i` the ratio-tracking weight so far, an
//! unbiased estimate of `T(a, t_i)`; by Campbell's theorem the sum is
//! unbiased for `L` (Novák et al., "Monte Carlo Methods for Volumetric
//! Light Transport Simulation", CGF 37(2), 2018, §5). The same walk's
//! final weight estimates `T(a, b)`, for what lies behind.
//!
//! [`emission_cells`] integrates `L` exactly for a medium constant in each
//! cell: per cell crossed over a length `ℓ` with optical depth `τ` before
//! it, `e^{−τ} j ℓ (1 − e^{−σ_t ℓ})/(σ_t ℓ)`.

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Majorants, NoDraws, within};
use crate::medium::{Grid, Ray, roulette};
use rand_core::Rng;

/// The emitted radiance along a ray segment, with the transmittance of the
/// whole segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission<T> {
    /// `∫ T(a, t) σ_a(t) L_e(t) dt` (in the units of `L_e`): an unbiased
    /// estimate, or exact from [`emission_cells`].
    pub radiance: T,
    /// `T(a, b)`, estimated (ratio tracking's weight) or exact.
    pub tr: T,
    /// Tentative collisions drawn (density evaluations); 0 when exact.
    pub steps: u32,
}

impl<T: Real> Majorants<'_, T> {
    /// The emitted radiance along `ray` through `grid` (whose majorants
    /// these must be: same box, else [`Error::Domain`]) with the emitted
    /// radiance `source(p) = L_e(p)` at a world point (finite and `≥ 0`,
    /// else [`Error::Domain`]; an emission grid of your own answers it with
    /// [`Grid::density`]). Budget and errors as
    /// [`ratio_track`](Self::ratio_track); also [`Error::Domain`] when the
    /// radiance overflows.
    pub fn emission_track<R: Rng + ?Sized>(
        &self,
        grid: &Grid<'_, T>,
        source: impl Fn(Vec3<T>) -> T,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Emission<T>, Error> {
        self.same_box(grid)?;
        self.emission_track_fn(|p| grid.coefficients_at(p), source, ray, budget, rng)
    }

    /// The emitted radiance along `ray` through a caller's medium,
    /// `coefficients(p) = (σ_a, σ_s)` (as
    /// [`ratio_track_fn`](Self::ratio_track_fn)), with `source(p) = L_e(p)`
    /// as [`emission_track`](Self::emission_track).
    pub fn emission_track_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        source: impl Fn(Vec3<T>) -> T,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Emission<T>, Error> {
        let (mut w, mut radiance) = (T::ONE, T::ZERO);
        let visit = |p: Vec3<T>, sigma_maj: T, r: &mut R| {
            let (sa, ss) = within(coefficients(p), sigma_maj)?;
            let le = source(p);
            if !(le >= T::ZERO && le.is_finite()) {
                return Err(Error::Domain);
            }
            radiance += w * sa * le / sigma_maj;
            w = roulette(w * (T::ONE - (sa + ss) / sigma_maj), r);
            Ok((w == T::ZERO).then_some(()))
        };
        let walk = self.walk(ray, budget, rng, visit)?;
        // A source near the largest float can overflow the sum: refused
        // rather than returned as ∞.
        if !radiance.is_finite() {
            return Err(Error::Domain);
        }
        Ok(Emission {
            radiance,
            tr: if walk.found.is_some() { T::ZERO } else { w },
            steps: walk.steps,
        })
    }
}

/// The exact emitted radiance along `ray` through a medium constant in each
/// cell: `sigma_t` holds each cell's extinction and `emitted` its emission
/// coefficient `σ_a L_e` (both per length unit, over the same cells and
/// box, else [`Error::Domain`], as for a ray [`Ray`] does not accept or a
/// radiance that overflows). Deterministic; `steps` is 0. The [`Majorants`] type holds any
/// non-negative per-cell values ([`Majorants::new`]).
pub fn emission_cells<T: Real>(
    sigma_t: &Majorants<'_, T>,
    emitted: &Majorants<'_, T>,
    ray: Ray<T>,
) -> Result<Emission<T>, Error> {
    if sigma_t.dims() != emitted.dims() || sigma_t.bounds() != emitted.bounds() {
        return Err(Error::Domain);
    }
    let (mut tau, mut radiance) = (T::ZERO, T::ZERO);
    let per_cell = |cell: [usize; 3], length: T| {
        let (s, j) = (sigma_t.at(cell), emitted.at(cell));
        // A bad emitted value (stored by a caller) stops the walk as a bad
        // extinction does.
        if !(j >= T::ZERO && j.is_finite()) {
            return T::NAN;
        }
        let x = s * length;
        // (1 − e^{−x})/x as −expm1(−x)/x: 1 − e^{−x} cancels for small x.
        let f = if x > T::ZERO {
            -(-x).exp_m1() / x
        } else {
            T::ONE
        };
        radiance += (-tau).exp() * j * length * f;
        tau += x;
        s
    };
    // At rate 0 the walk draws nothing; it visits every cell in order.
    sigma_t.walk_cells(ray, T::ZERO, per_cell, 0, &mut NoDraws, |_, _| {
        Ok(None::<()>)
    })?;
    // Cell values near the largest float can overflow (∞, or ∞ · 0).
    if !radiance.is_finite() {
        return Err(Error::Domain);
    }
    Ok(Emission {
        radiance,
        tr: (-tau).exp(),
        steps: 0,
    })
}
