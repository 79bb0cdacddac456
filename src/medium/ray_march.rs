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
//! average, for `n` strata per march.
//!
//! **Strata placed by the majorants** ([`march_within`], and the C layer
//! whenever the call has majorants). Equal lengths put as many points in
//! empty space as in a dense clump; a sharp feature narrower than a
//! stratum then makes the marches scatter by its whole optical depth, and
//! the series' high-order terms explode (on a 64³ sheet of density 1000,
//! equal strata at `⌈τ_maj⌉` put 15 % of the estimates along rays through
//! the sheet outside `[0, 1]`). Instead each
//! stratum holds an equal share `Δ = τ_r / n` of the residual optical depth
//! `τ_r = ∫ (σ_maj − σ_min)` along the ray (σ_min the minorants, or 0):
//! the point at residual depth `s` lies in the cell where the running sum
//! of `(σ_maj − σ_min)·length` passes `s`, and adds
//! `Δ (σ_t − σ_min)/(σ_maj − σ_min)`, a ratio in `[0, 1]` when the bounds
//! hold. That is importance sampling of `∫ (σ_t − σ_min)` by the residual
//! majorant, stratified: unbiased wherever the residual is positive, and
//! where it is 0 (an empty cell, or one whose minorant equals its
//! majorant) `σ_t = σ_min` and there is nothing to estimate. The
//! minorants' part `∫ σ_min` is exact and multiplies the estimate as
//! `exp(−∫ σ_min)`; a ray whose residual is 0 throughout is exact with no
//! evaluation. Each march's terms are bounded by `Δ`, so no stratum can
//! throw the series off. The walk through the cells is made once per
//! estimate (up to 96 cells with a residual are kept; a ray that crosses
//! more is walked again for each march).
//!
//! The library's strata ([`Series::default_strata`]) are `⌈4 τ⌉`, `τ` the
//! optical depth that places them (`τ_r` here, `∫ σ_maj` for equal
//! strata under one majorant): a quarter of a mean free path of the bound
//! per stratum. Measured by the main example over seven kinds of medium
//! and five classes of ray, variance × time against ratio tracking rose
//! from ⌈τ_r⌉ to ⌈4τ_r⌉ on every one (on sparse clumps in empty space,
//! from 10–20× to 38–80×), and keeps rising beyond while the walk, not the
//! evaluations, dominates the cost; four per unit keeps a shadow ray's
//! cost near 20 evaluations per unit of residual depth.
//!
//! **The telescoping member** ([`telescoping_transmittance`]; the
//! debiasing of Rhee & Glynn, "Unbiased Estimation with Square Root
//! Convergence for SDE Models", Operations Research 63(5), 2015, as Misso
//! et al., "Unbiased and Consistent Rendering Using Biased Estimators",
//! SIGGRAPH 2022, apply it to transmittance). `exp(−X_k)`, with `X_k` a
//! stratified march of `n·2^k` strata (an offset of its own in each), is
//! biased (Jensen) but converges to `exp(−τ)`; the sum
//! `exp(−X_0) + Σ_{k≥1} (exp(−X_k) − exp(−X'_{k−1}))/P(K ≥ k)`, cut at a
//! random level `K`, is unbiased when `X'_{k−1}` has the law of `X_{k−1}`.
//! Here `X'_{k−1}` reuses one point of each pair of `X_k`'s strata (a fair
//! coin picks it, so it is uniform over the pair), so the two nearly
//! cancel. Each further level is taken with probability ⅓: the expected
//! cost is `3n` evaluations; the variance is finite where the march's
//! error shrinks at least as fast as `h^{0.8}`. A constant medium is
//! exact. It needs finer strata than the power series, and its estimates
//! are heavier-tailed: the library's strata are `16⌈τ⌉` (at least 16: with
//! `⌈16 τ⌉` a thin blob put 6 % of the estimates outside `[0, 1]`); the
//! power series is the better estimator on every medium of the main
//! example.

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Majorants, Transmittance};
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

/// The telescoping estimator's deepest level ([`Error::Budget`] beyond):
/// reached with probability `3^−MAX_LEVEL`, 4·10⁻¹², at `n·2^24`
/// evaluations (any sensible budget ends the walk first).
pub const MAX_LEVEL: u32 = 24;

/// The probability of each further level of the telescoping sum.
const LEVEL: f64 = 1.0 / 3.0;

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
    through_grid(Series::Power, grid, ray, (n, budget), rng)
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
    through_fn(Series::Power, coefficients, ray, (n, budget), rng)
}

/// The telescoping estimate (module docs) along `ray` through `grid`, `n`
/// strata at the coarsest level; arguments, bounds and errors as
/// [`ray_march_transmittance`], and [`Error::Budget`] past [`MAX_LEVEL`].
pub fn telescoping_transmittance<T: Real, R: Rng + ?Sized>(
    grid: &Grid<'_, T>,
    ray: Ray<T>,
    n: u32,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    through_grid(Series::Telescoping, grid, ray, (n, budget), rng)
}

/// The telescoping estimate through a caller's medium, as
/// [`ray_march_transmittance_fn`].
pub fn telescoping_transmittance_fn<T: Real, R: Rng + ?Sized>(
    coefficients: impl Fn(Vec3<T>) -> (T, T),
    ray: Ray<T>,
    n: u32,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    through_fn(Series::Telescoping, coefficients, ray, (n, budget), rng)
}

/// Which member of the family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Series {
    /// The power series ([`ray_march_transmittance`]).
    Power,
    /// The telescoping sum ([`telescoping_transmittance`]).
    Telescoping,
}

impl Series {
    /// The strata the library takes for an optical depth `depth` that
    /// places them when the caller leaves the choice (module docs,
    /// "Strata placed by the majorants"): `⌈4·depth⌉` for the power series
    /// (a quarter of a mean free path of the bound per stratum),
    /// `16⌈depth⌉` for the telescoping sum; at least 1. [`Error::Domain`]
    /// for a depth that is negative, NaN or infinite; [`Error::Budget`] for
    /// a finite one that needs more than `u32::MAX` strata (more density
    /// evaluations than any budget allows, as a shorter segment that
    /// needs more than its budget reports).
    pub fn default_strata(self, depth: f64) -> Result<u32, Error> {
        let n = match self {
            Series::Power => libm::ceil(4.0 * depth),
            Series::Telescoping => 16.0 * libm::ceil(depth),
        };
        if !(depth >= 0.0 && depth.is_finite()) {
            Err(Error::Domain)
        } else if n <= f64::from(u32::MAX) {
            Ok(n.max(1.0) as u32)
        } else {
            Err(Error::Budget)
        }
    }
}

/// Majorants, and optionally minorants over the same cells, that place a
/// march's points (module docs, "Strata placed by the majorants").
#[derive(Clone, Copy, Debug)]
pub struct Placement<'m, T> {
    /// Bound `σ_t` from above over each closed cell.
    pub max: Majorants<'m, T>,
    /// Bound `σ_t` from below (the control); `None` is 0 everywhere.
    pub min: Option<Majorants<'m, T>>,
}

impl<T: Real> Placement<'_, T> {
    /// `(σ_min, σ_maj − σ_min, σ_maj)` of `cell`: [`Error::Domain`]
    /// unless `0 ≤ σ_min ≤ σ_maj < ∞` (values a caller may have changed).
    fn rates(&self, cell: [usize; 3]) -> Result<(T, T, T), Error> {
        let hi = self.max.at(cell);
        let lo = self.min.map_or(T::ZERO, |m| m.at(cell));
        if lo >= T::ZERO && hi >= lo && hi.is_finite() {
            Ok((lo, hi - lo, hi))
        } else {
            Err(Error::Domain)
        }
    }

    /// `(∫ σ_min, ∫ (σ_maj − σ_min))` along `ray`, cell by cell.
    pub fn depths(&self, ray: Ray<T>) -> Result<(T, T), Error> {
        let p = Path::walk(*self, ray)?;
        Ok((p.control, p.depth))
    }
}

/// The most cells with a residual a [`Path`] keeps; a ray that crosses
/// more is walked again for each march.
const PATH_CELLS: usize = 96;

/// A cell a ray crosses over `[t0, t1]` with rates `(σ_min, σ_maj − σ_min,
/// σ_maj)`, the residual positive.
#[derive(Clone, Copy)]
struct Span<T> {
    t0: T,
    t1: T,
    rates: (T, T, T),
}

/// A ray's walk through the bounds, made once: the control's and the
/// residual's optical depths and the cells with a residual.
struct Path<'m, T> {
    bounds: Placement<'m, T>,
    ray: Ray<T>,
    control: T,
    depth: T,
    spans: [Span<T>; PATH_CELLS],
    len: usize,
    /// Whether every cell with a residual is in `spans`.
    complete: bool,
}

impl<'m, T: Real> Path<'m, T> {
    fn walk(bounds: Placement<'m, T>, ray: Ray<T>) -> Result<Self, Error> {
        let empty = Span {
            t0: T::ZERO,
            t1: T::ZERO,
            rates: (T::ZERO, T::ZERO, T::ZERO),
        };
        let mut p = Path {
            bounds,
            ray,
            control: T::ZERO,
            depth: T::ZERO,
            spans: [empty; PATH_CELLS],
            len: 0,
            complete: true,
        };
        bounds.max.cells(ray, |cell, t0, t1| {
            let rates = bounds.rates(cell)?;
            p.control += rates.0 * (t1 - t0);
            if rates.1 > T::ZERO {
                p.depth += rates.1 * (t1 - t0);
                match p.spans.get_mut(p.len) {
                    Some(s) => *s = Span { t0, t1, rates },
                    None => p.complete = false,
                }
                p.len += 1;
            }
            Ok(false)
        })?;
        Ok(p)
    }

    /// `visit(span)` for every cell with a residual, in order: from the
    /// kept spans, or by walking again when they did not all fit.
    fn each(&self, mut visit: impl FnMut(Span<T>) -> Result<(), Error>) -> Result<(), Error> {
        if self.complete {
            return self.spans.iter().take(self.len).try_for_each(|&s| visit(s));
        }
        let bounds = self.bounds;
        bounds.max.cells(self.ray, |cell, t0, t1| {
            let rates = bounds.rates(cell)?;
            if rates.1 > T::ZERO {
                visit(Span { t0, t1, rates })?;
            }
            Ok(false)
        })?;
        Ok(())
    }
}

/// `series` along `ray` through a caller's medium, `coefficients(p) =
/// (σ_a, σ_s)` (both `≥ 0` and their sum within the cell's majorant, else
/// [`Error::Domain`]), with the strata placed by `bounds` (module docs,
/// "Strata placed by the majorants"): `strata` per march over the
/// residual optical depth, or with `strata = 0` the library's choice,
/// [`Series::default_strata`]. Where the residual is 0 along the whole ray
/// the estimate is `exp(−∫σ_min)`, exact, with no evaluation. Budget and
/// errors as [`ray_march_transmittance`].
pub fn march_within<T: Real, R: Rng + ?Sized>(
    series: Series,
    bounds: Placement<'_, T>,
    coefficients: impl Fn(Vec3<T>) -> (T, T),
    ray: Ray<T>,
    strata: u32,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    let (o, d) = ray.checked()?;
    let path = Path::walk(bounds, ray)?;
    let (control, depth) = (path.control, path.depth);
    if !(control.is_finite() && depth.is_finite()) {
        return Err(Error::Domain);
    }
    if depth <= T::ZERO {
        return Ok(Transmittance {
            tr: (-control).exp(),
            steps: 0,
        });
    }
    let n = match strata {
        0 => series.default_strata(depth.to_f64())?,
        n => n,
    };
    let sigma = extinction(coefficients);
    let line = Line::Warped(&path);
    let t = series.run(Marcher::new(sigma, (o, d), line, (n, budget))?, rng)?;
    Ok(Transmittance {
        tr: t.tr * (-control).exp(),
        steps: t.steps,
    })
}

/// [`march_within`] through `grid`, whose box `bounds` must span
/// ([`Error::Domain`] otherwise).
pub fn march_grid_within<T: Real, R: Rng + ?Sized>(
    series: Series,
    bounds: Placement<'_, T>,
    grid: &Grid<'_, T>,
    ray: Ray<T>,
    strata: u32,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    bounds.max.same_box(grid)?;
    let coefficients = |p| grid.coefficients_at(p);
    march_within(series, bounds, coefficients, ray, strata, budget, rng)
}

/// `series` through `grid`, the ray clipped to its box.
fn through_grid<T: Real, R: Rng + ?Sized>(
    series: Series,
    grid: &Grid<'_, T>,
    ray: Ray<T>,
    cost: (u32, u32),
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
        let (sa, ss) = grid.coefficients_at(p);
        Ok(sa + ss)
    };
    series.run(Marcher::new(sigma, (o, d), Line::Even { a, b }, cost)?, rng)
}

/// `series` through a caller's medium over a finite segment.
fn through_fn<T: Real, R: Rng + ?Sized>(
    series: Series,
    coefficients: impl Fn(Vec3<T>) -> (T, T),
    ray: Ray<T>,
    cost: (u32, u32),
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    let (o, d) = ray.checked()?;
    if !ray.t_max.is_finite() {
        return Err(Error::Domain);
    }
    let sigma = extinction(coefficients);
    let even = Line::Even {
        a: ray.t_min,
        b: ray.t_max,
    };
    let marcher = Marcher::new(sigma, (o, d), even, cost)?;
    series.run(marcher, rng)
}

/// `σ_a + σ_s` from a caller's coefficients, [`Error::Domain`] unless
/// both are `≥ 0`.
fn extinction<T: Real>(
    coefficients: impl Fn(Vec3<T>) -> (T, T),
) -> impl Fn(Vec3<T>) -> Result<T, Error> {
    move |p| {
        let (sa, ss) = coefficients(p);
        if sa >= T::ZERO && ss >= T::ZERO {
            Ok(sa + ss)
        } else {
            Err(Error::Domain)
        }
    }
}

impl Series {
    fn run<T: Real, R: Rng + ?Sized, S: Fn(Vec3<T>) -> Result<T, Error>>(
        self,
        mut m: Marcher<'_, T, S>,
        rng: &mut R,
    ) -> Result<Transmittance<T>, Error> {
        let tr = match self {
            Series::Power => power(&mut m, rng)?,
            Series::Telescoping => telescoping(&mut m, rng)?,
        };
        // Strata far too coarse for the medium can make the terms
        // overflow: refused rather than returned as ∞ or NaN.
        if tr.is_finite() {
            Ok(Transmittance { tr, steps: m.steps })
        } else {
            Err(Error::Domain)
        }
    }
}

/// Where a march puts its strata.
#[derive(Clone, Copy)]
enum Line<'m, T> {
    /// Equal lengths over `[a, b]`.
    Even { a: T, b: T },
    /// Equal shares of the residual optical depth along a path; a march
    /// then estimates `∫ (σ_t − σ_min)`.
    Warped(&'m Path<'m, T>),
}

/// Marches of `∫ σ_t` along the unit-direction ray `(o, d)`, counting
/// density evaluations against the budget.
struct Marcher<'m, T, S> {
    sigma: S,
    o: Vec3<T>,
    d: Vec3<T>,
    line: Line<'m, T>,
    n: u32,
    budget: u32,
    steps: u32,
}

impl<T: Real, S: Fn(Vec3<T>) -> Result<T, Error>> Marcher<'_, T, S> {
    /// [`Error::Domain`] for `n = 0`.
    fn new(
        sigma: S,
        (o, d): (Vec3<T>, Vec3<T>),
        line: Line<'_, T>,
        (n, budget): (u32, u32),
    ) -> Result<Marcher<'_, T, S>, Error> {
        if n == 0 {
            return Err(Error::Domain);
        }
        Ok(Marcher {
            sigma,
            o,
            d,
            line,
            n,
            budget,
            steps: 0,
        })
    }

    /// The march with `n·2^level` strata, stratum `j` sampled at offset
    /// `point(j).0` within it, the march of half as many strata through
    /// the points for which `point(j).1` holds (the coarse march; unused
    /// at level 0), and their difference, coarse − fine, summed pair by
    /// pair. All in f64 whatever `T` (each density is read in `T`): a
    /// level-k march sums `n·2^k` terms, and the telescoping sum takes the
    /// difference of two such sums times `3^k`. Summed in f32 at level 15
    /// (3·10⁶ terms), one estimate came out at 5530 for a transmittance of
    /// 0.3, and the stratum offsets `j + u` themselves lost `u` to
    /// rounding.
    fn march(&mut self, level: u32, point: impl FnMut(usize) -> (T, bool)) -> Result<Sums, Error> {
        if level >= 32 {
            return Err(Error::Budget);
        }
        let strata = (self.n as u64) << level;
        let steps = self.steps as u64 + strata;
        if steps > self.budget as u64 {
            return Err(Error::Budget);
        }
        self.steps = steps as u32;
        let sums = match self.line {
            Line::Even { a, b } => self.even(a.to_f64(), b.to_f64(), strata as usize, point)?,
            Line::Warped(path) => self.warped(path, strata as usize, point)?,
        };
        // Coefficients whose optical depth overflows (or +∞) would turn
        // the series into ∞ − ∞: refused rather than returned as NaN. (In
        // `T`: a depth that is finite only in f64 overflows there.)
        let finite = |x: f64| T::from_f64(x).is_finite();
        if finite(sums.fine) && finite(sums.coarse) && sums.diff.is_finite() {
            Ok(sums)
        } else {
            Err(Error::Domain)
        }
    }

    /// `σ_t` at distance `t` (f64) along the ray, in f64.
    fn sigma_at(&self, t: f64) -> Result<f64, Error> {
        (self.sigma)(self.o + self.d * T::from_f64(t)).map(|s| s.to_f64())
    }

    /// [`march`](Self::march) with strata of equal length over `[a, b]`.
    fn even(
        &self,
        a: f64,
        b: f64,
        strata: usize,
        mut point: impl FnMut(usize) -> (T, bool),
    ) -> Result<Sums, Error> {
        let h = (b - a) / strata as f64;
        let mut sums = Sums::default();
        for j in 0..strata {
            let (u, keep) = point(j);
            sums.add(self.sigma_at(a + (j as f64 + u.to_f64()) * h)?, keep);
        }
        Ok(sums.times(h))
    }

    /// [`march`](Self::march) with strata of equal residual optical depth
    /// `Δ = depth / strata`: the point at residual depth `s` lies in the
    /// cell where the running sum of `(σ_maj − σ_min)·length` passes `s`,
    /// and contributes `Δ (σ_t − σ_min)/(σ_maj − σ_min)`, an unbiased
    /// estimate of its stratum's share of `∫ (σ_t − σ_min)`.
    fn warped(
        &self,
        path: &Path<'_, T>,
        strata: usize,
        point: impl FnMut(usize) -> (T, bool),
    ) -> Result<Sums, Error> {
        let mut pts = Points {
            point,
            delta: path.depth.to_f64() / strata as f64,
            strata,
            j: 0,
            drawn: None,
            sums: Sums::default(),
        };
        // The ratio at t in a cell of rates (σ_min, σ_maj − σ_min, σ_maj).
        let ratio = |t: f64, (lo, rho, hi): (T, T, T)| -> Result<f64, Error> {
            let sigma = self.sigma_at(t)?;
            if sigma > hi.to_f64() {
                return Err(Error::Domain);
            }
            Ok((sigma - lo.to_f64()) / rho.to_f64())
        };
        // The running residual depth (summed as `Path::walk` sums it), and
        // the last span: points that rounding puts past the end go to its
        // far end.
        let (mut start, mut last) = (0.0f64, None);
        path.each(|span| {
            let rho = span.rates.1.to_f64();
            let (t0, t1) = (span.t0.to_f64(), span.t1.to_f64());
            let end = start + rho * (t1 - t0);
            while let Some(s) = pts.next_before(end) {
                let t = (t0 + (s - start) / rho).min(t1);
                pts.take(ratio(t, span.rates)?);
            }
            start = end;
            last = Some(span);
            Ok(())
        })?;
        if let Some(span) = last {
            while pts.next_before(f64::INFINITY).is_some() {
                pts.take(ratio(span.t1.to_f64(), span.rates)?);
            }
        }
        Ok(pts.sums.times(pts.delta))
    }

    /// One jittered march: every point at the same offset in its stratum.
    fn jittered<R: Rng + ?Sized>(&mut self, rng: &mut R) -> Result<T, Error> {
        let u = T::uniform(rng);
        self.march(0, |_| (u, false)).map(|x| T::from_f64(x.fine))
    }

    /// A stratified march at `level` (an offset of its own in every
    /// stratum) and its coarse march: in each pair of strata, a coin keeps
    /// the point of one, which is then uniform over the pair, so the coarse
    /// march has the law of a stratified march at `level − 1`.
    fn stratified<R: Rng + ?Sized>(&mut self, level: u32, rng: &mut R) -> Result<Sums, Error> {
        let mut coin = false;
        self.march(level, |j| {
            if j % 2 == 0 {
                coin = T::uniform(rng) < T::HALF;
            }
            (T::uniform(rng), (j % 2 == 1) == coin)
        })
    }
}

/// The points of a march placed by residual depth: stratum `j` at depth
/// `(j + u_j) Δ`, `point(j) = (u_j, kept by the coarse march)`, drawn in
/// order, once each; the sums of the ratios met so far.
struct Points<T, P> {
    point: P,
    delta: f64,
    strata: usize,
    j: usize,
    drawn: Option<(T, bool)>,
    sums: Sums,
}

/// A fine march, its coarse march and their difference (coarse − fine),
/// summed in f64 ([`Marcher::march`]).
#[derive(Clone, Copy, Default)]
struct Sums {
    fine: f64,
    coarse: f64,
    diff: f64,
}

impl Sums {
    /// Adds a stratum's value `s`, kept by the coarse march or not. The
    /// coarse march counts a kept value twice (its strata are twice as
    /// long), so coarse − fine gains `+s` or `−s`: within each pair the
    /// two nearly cancel, and summed as such the difference keeps its
    /// relative precision.
    #[inline(always)]
    fn add(&mut self, s: f64, keep: bool) {
        self.fine += s;
        if keep {
            self.coarse += s;
            self.diff += s;
        } else {
            self.diff -= s;
        }
    }

    /// The sums as integrals over strata of width `h`.
    fn times(self, h: f64) -> Sums {
        Sums {
            fine: self.fine * h,
            coarse: self.coarse * (h + h),
            diff: self.diff * h,
        }
    }
}

impl<T: Real, P: FnMut(usize) -> (T, bool)> Points<T, P> {
    /// The depth of the next point if there is one below `end`. The draw
    /// for a point is made once, and kept until [`take`](Self::take).
    fn next_before(&mut self, end: f64) -> Option<f64> {
        if self.j >= self.strata {
            return None;
        }
        let s = (self.j as f64 + self.peek().0.to_f64()) * self.delta;
        (s < end).then_some(s)
    }

    /// The next point's draw, made on first sight.
    fn peek(&mut self) -> (T, bool) {
        match self.drawn {
            Some(x) => x,
            None => {
                let x = (self.point)(self.j);
                self.drawn = Some(x);
                x
            }
        }
    }

    /// Adds the next point's ratio `r` and moves on.
    fn take(&mut self, r: f64) {
        let (_, keep) = self.peek();
        self.sums.add(r, keep);
        self.j += 1;
        self.drawn = None;
    }
}

/// The telescoping sum (module docs).
fn telescoping<T: Real, R: Rng + ?Sized, S: Fn(Vec3<T>) -> Result<T, Error>>(
    m: &mut Marcher<'_, T, S>,
    rng: &mut R,
) -> Result<T, Error> {
    // In f64 whatever `T` (see `Marcher::march`): the terms are divided
    // by 3^−k.
    let x0 = m.stratified(0, rng)?.fine;
    let (mut tr, mut reach) = ((-x0).exp(), 1.0f64);
    for level in 1..=MAX_LEVEL + 1 {
        if T::uniform(rng) >= T::from_f64(LEVEL) {
            return Ok(T::from_f64(tr));
        }
        if level > MAX_LEVEL {
            break;
        }
        reach *= LEVEL;
        let x = m.stratified(level, rng)?;
        // exp(−fine) − exp(−coarse) as e^{−coarse} expm1(coarse − fine),
        // the difference summed pair by pair: the two nearly agree, and
        // the plain difference cancels.
        tr += (-x.coarse).exp() * x.diff.exp_m1() / reach;
    }
    Err(Error::Budget)
}

/// The power-series estimate (module docs).
fn power<T: Real, R: Rng + ?Sized, S: Fn(Vec3<T>) -> Result<T, Error>>(
    m: &mut Marcher<'_, T, S>,
    rng: &mut R,
) -> Result<T, Error> {
    power_series(|r: &mut R| m.jittered(r), rng)
}

/// [`power`] over the marches `march` makes (a seam for tests, which
/// choose the marches).
fn power_series<T: Real, R: Rng + ?Sized>(
    mut march: impl FnMut(&mut R) -> Result<T, Error>,
    rng: &mut R,
) -> Result<T, Error> {
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
    Ok(total / T::from_index(order + 1))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `pivot_estimate` is its formula, `exp(−p) Σ_k e_k(p − Y) (N − k)! /
    /// (N! q[k])`, with `e_k` summed over every k-subset of the other
    /// marches by brute force (a mutation test's `/ q[k]` → `· q[k]` was
    /// unnoticed: the terms with `q[k] < 1` are products of `k` march
    /// differences, too small for the unbiasedness tests to see).
    #[test]
    fn the_pivot_estimate_is_its_formula() {
        let mut x = [0.0f64; LEN];
        let marches = [0.3, 1.7, 0.9, 2.4, 0.05, 1.2];
        x[..marches.len()].copy_from_slice(&marches);
        let mut q = [1.0f64; LEN];
        for (k, qk) in q.iter_mut().enumerate().skip(3) {
            *qk = 0.5f64.powi(k as i32 - 2);
        }
        let n = marches.len();
        let fact = |m: usize| (1..=m).map(|i| i as f64).product::<f64>();
        for pivot in 0..n {
            let p = x[pivot];
            let mut others = [0.0f64; 8];
            let mut big_n = 0;
            for j in (0..n).filter(|&j| j != pivot) {
                others[big_n] = p - x[j];
                big_n += 1;
            }
            let mut want = 0.0;
            for (k, &qk) in q.iter().enumerate().take(big_n + 1) {
                let e_k: f64 = (0u32..1 << big_n)
                    .filter(|s| s.count_ones() as usize == k)
                    .map(|s| {
                        (0..big_n)
                            .filter(|&j| s >> j & 1 == 1)
                            .map(|j| others[j])
                            .product::<f64>()
                    })
                    .sum();
                want += e_k * fact(big_n - k) / (fact(big_n) * qk);
            }
            want *= (-p).exp();
            let got = pivot_estimate(p, &x, n, pivot, &q);
            assert!(
                (got - want).abs() <= 1e-13 * want.abs().max(1.0),
                "pivot {pivot}: {got} against {want}"
            );
        }
    }

    /// The power series averages the pivot estimates over all `N + 1`
    /// marches it made, with `q[k]` the roulette's `P(N ≥ k)`: recomputed
    /// here from the marches recorded (a mutation test's `N + 1` → `N`,
    /// which leaves the last march out of every sum, was below the
    /// unbiasedness tests' resolution).
    #[test]
    fn the_power_series_uses_every_march_it_made() {
        use rand_xoshiro::Xoshiro256PlusPlus;
        use rand_xoshiro::rand_core::SeedableRng;
        let mut longest = 0;
        for seed in 0..64u64 {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            let (mut x, mut n) = ([0.0f64; LEN], 0);
            let got = power_series(
                |r: &mut Xoshiro256PlusPlus| {
                    let v = 0.2 + 1.5 * f64::uniform(r);
                    x[n] = v;
                    n += 1;
                    Ok(v)
                },
                &mut rng,
            )
            .unwrap();
            let mut q = [1.0f64; LEN];
            for k in MIN_ORDER as usize + 1..LEN {
                q[k] = q[k - 1] * CONTINUE / k as f64;
            }
            let want = (0..n)
                .map(|i| pivot_estimate(x[i], &x, n, i, &q))
                .sum::<f64>()
                / n as f64;
            assert!(
                (got - want).abs() <= 1e-14 * want.abs(),
                "seed {seed}, {n} marches: {got} against {want}"
            );
            longest = longest.max(n);
        }
        // Some draws went past the fewest marches.
        assert!(longest > MIN_ORDER as usize + 2, "{longest}");
    }
}
