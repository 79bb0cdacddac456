//! An unbiased ray-marching transmittance estimator (Kettunen, d'Eon,
//! Pantaleoni & Novák, "An Unbiased Ray-Marching Transmittance
//! Estimator", ACM TOG 40(4), 2021), in its power-series form.
//!
//! For any control `τ_c`, `exp(−τ) = exp(−τ_c) Σ_k (τ_c − τ)^k / k!`. Let
//! `X_0, X_1, …` be independent unbiased estimates of the optical depth
//! `τ`, each a jittered ray march (the segment cut into `n` equal strata,
//! one uniform offset for all: every point is uniform in its stratum). With
//! `τ_c = X_0`, the product `Π_{i≤k} (τ_c − X_i)/i` is unbiased for the
//! `k`-th term given `τ_c`; the series stops at a random order `K`, each
//! term divided by `P(K ≥ k)`, so the sum is unbiased for the series. Here
//! the first [`MIN_ORDER`] terms are always taken and each further one with
//! probability ½. A density that is constant along the ray marches exactly:
//! every `τ_c − X_i` is 0 and the estimate is `exp(−τ)` with no variance.
//! The cost is `n (1 + K)` density evaluations; the caller picks `n`, e.g.
//! the majorant optical depth along the ray
//! ([`Majorants::optical_depth`](super::majorant::Majorants::optical_depth))
//! rounded up, so that each stratum holds about one mean free path.

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Transmittance, grid_coefficients};
use crate::medium::{Grid, Ray, clip_box};
use rand_core::Rng;

/// Terms of the series always taken (beyond the first, `k = 0`).
pub const MIN_ORDER: u32 = 2;
/// The order at which the series is cut ([`Error::Budget`]): reached with
/// probability `2^−(MAX_ORDER − MIN_ORDER)`, 2·10⁻¹⁸.
pub const MAX_ORDER: u32 = 64;

/// The estimate along `ray` through `grid` (clipped to its box) with `n`
/// strata per march. Unbiased, but not bounded: a high-order term can make
/// one estimate exceed 1 or (rarely, where `n` is too coarse for the
/// medium) fall below 0. Errors: [`Error::Domain`] for a ray [`Ray`] does not accept
/// or `n = 0` or when the series overflows (strata far too coarse for the
/// medium), [`Error::Budget`] when more than `budget` density evaluations
/// would be needed.
pub fn ray_march_transmittance<T: Real, R: Rng + ?Sized>(
    grid: &Grid<'_, T>,
    ray: Ray<T>,
    n: u32,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    let (o, d) = ray.checked()?;
    let (lo, hi) = grid.bounds();
    let Some((a, b)) = clip_box(o, d, lo, hi, ray.t_min, ray.t_max) else {
        return Ok(Transmittance {
            tr: T::ONE,
            steps: 0,
        });
    };
    let sigma = |p: Vec3<T>| {
        let (sa, ss) = grid_coefficients(grid, p);
        Ok(sa + ss)
    };
    estimate(sigma, (o, d), (a, b), n, budget, rng)
}

/// The estimate through a caller's medium, `coefficients(p) = (σ_a, σ_s)`
/// (both `≥ 0`, else [`Error::Domain`], as is an optical depth that
/// overflows), over `[t_min, t_max]` of `ray`, which must be finite
/// ([`Error::Domain`]). Other errors as [`ray_march_transmittance`].
pub fn ray_march_transmittance_fn<T: Real, R: Rng + ?Sized>(
    coefficients: impl Fn(Vec3<T>) -> (T, T),
    ray: Ray<T>,
    n: u32,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    let (o, d) = ray.checked()?;
    if !ray.t_max.is_finite() {
        return Err(Error::Domain);
    }
    let sigma = |p: Vec3<T>| {
        let (sa, ss) = coefficients(p);
        if sa >= T::ZERO && ss >= T::ZERO {
            Ok(sa + ss)
        } else {
            Err(Error::Domain)
        }
    };
    estimate(sigma, (o, d), (ray.t_min, ray.t_max), n, budget, rng)
}

/// The power-series estimate over `[a, b]` of the unit-direction ray
/// `(o, d)` (module docs).
fn estimate<T: Real, R: Rng + ?Sized>(
    sigma: impl Fn(Vec3<T>) -> Result<T, Error>,
    (o, d): (Vec3<T>, Vec3<T>),
    (a, b): (T, T),
    n: u32,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    if n == 0 {
        return Err(Error::Domain);
    }
    let mut steps = 0u32;
    let h = (b - a) / T::from_index(n as usize);
    let mut march = |r: &mut R| -> Result<T, Error> {
        steps = steps
            .checked_add(n)
            .filter(|&s| s <= budget)
            .ok_or(Error::Budget)?;
        let u = T::uniform(r);
        let mut sum = T::ZERO;
        for j in 0..n {
            let t = a + (T::from_index(j as usize) + u) * h;
            sum += sigma(o + d * t)?;
        }
        // Coefficients whose optical depth overflows (or +∞) would turn
        // the series into ∞ − ∞: refused rather than returned as NaN.
        let x = sum * h;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(Error::Domain)
        }
    };
    let control = march(rng)?;
    let (mut term, mut total) = (T::ONE, T::ONE);
    let mut weight = T::ONE;
    for k in 1..=MAX_ORDER {
        if k > MIN_ORDER {
            if T::uniform(rng) >= T::HALF {
                // Strata far too coarse for the medium can make the series'
                // terms overflow: refused rather than returned as ∞ or NaN.
                let tr = (-control).exp() * total;
                return if tr.is_finite() {
                    Ok(Transmittance { tr, steps })
                } else {
                    Err(Error::Domain)
                };
            }
            weight *= T::TWO;
        }
        term *= (control - march(rng)?) / T::from_index(k as usize);
        total += weight * term;
    }
    Err(Error::Budget)
}
