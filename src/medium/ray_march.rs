//! An unbiased ray-marching transmittance estimator (Kettunen, d'Eon,
//! Pantaleoni & Novák, "An Unbiased Ray-Marching Transmittance
//! Estimator", ACM TOG 40(4), 2021, §4–5), in its power-series form.
//!
//! For any pivot `p`, `exp(−τ) = exp(−p) Σ_k (p − τ)^k / k!`. Each march
//! `X_i` is an unbiased estimate of the optical depth `τ`: the segment cut
//! into `n` equal strata, one uniform offset for all, so every point is
//! uniform in its stratum. The estimator takes `N + 1` marches, `N` random.
//! With one march as pivot and the other `N` as `Y_j`, the elementary
//! symmetric mean `e_k(p − Y) / C(N, k)` is unbiased for `(p − τ)^k` given
//! `p` (a sum of products of distinct, independent factors), and term `k`
//! divided by `P(N ≥ k)` makes the random cut unbiased:
//!
//! `T = exp(−p) Σ_{k ≤ N} e_k(p − Y) (N − k)! / (N! P(N ≥ k))`.
//!
//! Every march takes its turn as pivot and the `N + 1` estimates are
//! averaged, which keeps it unbiased and lowers the variance. `N` is at
//! least [`MIN_ORDER`]; after that, the `i`-th further march is taken with
//! probability `2.5 / (MIN_ORDER + i)` (the paper's aggressive roulette).
//! A density that is constant along the ray marches exactly: every
//! `p − Y_j` is 0 and the estimate is `exp(−τ)` with no variance.
//!
//! The cost is `n (N + 1)` density evaluations, `N + 1` about 4.8 on
//! average; the caller picks `n`, e.g. the majorant optical depth along the
//! ray ([`Majorants::optical_depth`](super::majorant::Majorants::optical_depth))
//! rounded up, so that each stratum holds about one mean free path.

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Transmittance, grid_coefficients};
use crate::medium::{Grid, Ray, clip_box};
use rand_core::Rng;

/// The fewest terms of the series beyond the first (`N ≥ MIN_ORDER`, so at
/// least `MIN_ORDER + 1` marches).
pub const MIN_ORDER: u32 = 2;

/// The order at which the series is cut ([`Error::Budget`]): reached with
/// probability below 10⁻²³.
pub const MAX_ORDER: u32 = 32;

/// The roulette's constant: the `i`-th march beyond `MIN_ORDER + 1` is
/// taken with probability `CONTINUE / (MIN_ORDER + i)`.
const CONTINUE: f64 = 2.5;

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
    // x: the marches; q[k] = P(N ≥ k). No indexing below can fail (and
    // none can panic: the C layer's entry points must not).
    let (mut x, mut q) = ([T::ZERO; LEN], [T::ONE; LEN]);
    for xi in x.iter_mut().take(MIN_ORDER as usize + 1) {
        *xi = march(rng)?;
    }
    let (mut order, mut reach) = (MIN_ORDER as usize, T::ONE);
    loop {
        let keep = T::from_f64(CONTINUE) / T::from_index(order + 1);
        if T::uniform(rng) >= keep {
            break;
        }
        order += 1;
        reach *= keep;
        let (Some(xi), Some(qi)) = (x.get_mut(order), q.get_mut(order)) else {
            return Err(Error::Budget);
        };
        *xi = march(rng)?;
        *qi = reach;
    }
    let mut total = T::ZERO;
    for (i, &pivot) in x.iter().take(order + 1).enumerate() {
        total += pivot_estimate(pivot, &x, order + 1, i, &q);
    }
    // Strata far too coarse for the medium can make the series' terms
    // overflow: refused rather than returned as ∞ or NaN.
    let tr = total / T::from_index(order + 1);
    if tr.is_finite() {
        Ok(Transmittance { tr, steps })
    } else {
        Err(Error::Domain)
    }
}

/// The number of marches [`estimate`] can hold.
const LEN: usize = MAX_ORDER as usize + 1;

/// `exp(−p) Σ_k e_k(p − Y) (N − k)! / (N! q[k])` with `p = x[pivot]` and
/// `Y` the other `N = n − 1` of the first `n` marches.
fn pivot_estimate<T: Real>(p: T, x: &[T; LEN], n: usize, pivot: usize, q: &[T; LEN]) -> T {
    // e[k]: the elementary symmetric polynomials of the p − Y_j, built one
    // factor at a time (no power sums, whose Newton identities cancel).
    let mut e = [T::ZERO; LEN];
    e[0] = T::ONE;
    let mut count = 0;
    for (j, &y) in x.iter().take(n).enumerate() {
        if j == pivot {
            continue;
        }
        count = (count + 1).min(LEN - 1);
        for k in (1..=count).rev() {
            e[k] += (p - y) * e[k - 1];
        }
    }
    // c = (N − k)! / N!, from k = 0.
    let (mut sum, mut c) = (T::ZERO, T::ONE);
    for (k, (&ek, &qk)) in e.iter().zip(q).take(count + 1).enumerate() {
        if k > 0 {
            c = c / T::from_index(count + 1 - k);
        }
        sum += ek * c / qk;
    }
    (-p).exp() * sum
}
