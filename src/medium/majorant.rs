//! Majorant grids: tracking that costs what the medium along the ray holds,
//! not its densest voxel.
//!
//! Delta and ratio tracking draw tentative collisions at the rate of a
//! majorant `σ_maj ≥ σ_t` (Woodcock et al. 1965; the null-collision
//! formulation of Galtier et al. 2013 and Novák et al., Computer Graphics
//! Forum 37(2), 2018). With one majorant for the whole medium, a cloud that
//! is thin almost everywhere but dense in its core makes almost every
//! tentative collision a null one. A coarse grid of local majorants, walked
//! cell by cell along the ray (pbrt-v4's `MajorantGrid` and
//! `DDAMajorantIterator`, §11.4 of the 4th edition), bounds the density
//! where the ray actually is; empty cells cost nothing.
//!
//! Within a cell the majorant is constant and free paths are exponential;
//! at a cell face the walk restarts with a fresh exponential draw (the
//! exponential distribution is memoryless, so this is exact). Any majorant
//! that bounds `σ_t` keeps both estimators unbiased; a `σ_t` above its
//! cell's majorant is reported as [`Error::Domain`], never clamped.
//!
//! A [`Majorants`] value borrows the caller's array of `mx·my·mz`
//! majorants (x fastest) over a world box; [`Majorants::build`] fills one
//! from a density [`Grid`] in one pass, conservatively under the grid's
//! trilinear interpolation. No allocation, and every loop is bounded: the
//! walk visits at most `mx + my + mz` cells, and the number of tentative
//! collisions is the caller's budget ([`Error::Budget`] when it runs out).

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::{
    Event, Grid, Ray, clip_box, exponential_step, finite_zero, grid_len, roulette, to_local,
    valid_box,
};
use rand_core::Rng;

/// pbrt-v4's default majorant resolution per axis (16³ cells).
pub const DEFAULT_RES: usize = 16;

/// The number of majorants of an `m[0]·m[1]·m[2]` grid, or `None` for a
/// zero dimension or a product that overflows `usize`.
pub fn majorant_len(m: [usize; 3]) -> Option<usize> {
    grid_len(m[0], m[1], m[2])
}

/// A grid of majorants (per length unit, `≥ 0`) over the world box
/// `[lo, hi]`, one per cell of an `m[0]×m[1]×m[2]` division of the box,
/// borrowed from the caller (x fastest). Outside the box the medium is
/// taken to be empty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Majorants<'a, T> {
    sigma: &'a [T],
    m: [usize; 3],
    lo: Vec3<T>,
    hi: Vec3<T>,
}

/// What delta tracking found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Track<T> {
    /// Distance along the unit direction: of the real collision, or for
    /// [`Event::Escaped`] where the ray leaves the medium's box (clipped to
    /// `[t_min, t_max]`; `t_min` for a ray that never enters it).
    pub t: T,
    /// [`Event::Escaped`], [`Event::Scattered`] or [`Event::Absorbed`].
    pub event: Event,
    /// Tentative collisions drawn (density evaluations), real one included.
    pub steps: u32,
}

/// What ratio tracking found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transmittance<T> {
    /// The unbiased transmittance estimate (≥ 0; Russian roulette can
    /// raise a single estimate above the true value).
    pub tr: T,
    /// Tentative collisions drawn (density evaluations).
    pub steps: u32,
}

impl<'a, T: Real> Majorants<'a, T> {
    /// The caller's majorants: `sigma` holds at least `m[0]·m[1]·m[2]`
    /// values, each finite and `≥ 0`, and each must bound `σ_t` over its
    /// closed cell (tracking reports [`Error::Domain`] where it finds one
    /// that does not). [`Error::Size`] for a zero dimension, an overflowing
    /// product or a short buffer; [`Error::Domain`] for a bad value or box
    /// (see [`Grid::with_box`]).
    pub fn new(sigma: &'a [T], m: [usize; 3], lo: Vec3<T>, hi: Vec3<T>) -> Result<Self, Error> {
        let count = majorant_len(m).ok_or(Error::Size)?;
        let sigma = sigma.get(..count).ok_or(Error::Size)?;
        if !valid_box(lo, hi) || !sigma.iter().all(|&s| s >= T::ZERO && s.is_finite()) {
            return Err(Error::Domain);
        }
        Ok(Majorants { sigma, m, lo, hi })
    }

    /// Majorants from the parts of a value [`Majorants::new`] accepted, as a
    /// caller that stores them keeps them (the C layer's `sk_majorants`), in
    /// constant time: [`Error::Size`] for a zero dimension, an overflowing
    /// product or a short buffer, [`Error::Domain`] for a bad box; the
    /// values are not scanned. A value that is negative, NaN or infinite
    /// (changed after it was checked) is reported as [`Error::Domain`] by
    /// the walk that reaches its cell, never used.
    pub fn from_parts(
        sigma: &'a [T],
        m: [usize; 3],
        lo: Vec3<T>,
        hi: Vec3<T>,
    ) -> Result<Self, Error> {
        let count = majorant_len(m).ok_or(Error::Size)?;
        let sigma = sigma.get(..count).ok_or(Error::Size)?;
        if !valid_box(lo, hi) {
            return Err(Error::Domain);
        }
        Ok(Majorants { sigma, m, lo, hi })
    }

    /// Fills `out` with the majorants of `grid` on an `m` division of its
    /// box, in one pass over the grid, and borrows them: each cell gets
    /// `(σ_a + σ_s)` times the largest grid value whose interpolation
    /// reaches into the cell (the cell widened by a thousandth of itself,
    /// so the walk's rounding at faces stays covered), with the grid
    /// majorant's few ULP of slack. Errors as [`Majorants::new`].
    pub fn build(grid: &Grid<'_, T>, m: [usize; 3], out: &'a mut [T]) -> Result<Self, Error> {
        let (sa, ss) = grid.coefficients();
        Self::build_scaled(grid, m, out, sa + ss)
    }

    /// [`build`](Self::build) for the density itself: each cell holds the
    /// largest density that reaches into it (with the same slack), whatever
    /// the grid's coefficients. The majorants spectral tracking takes
    /// (`spectral`), where each channel scales them by its own `σ_a + σ_s`.
    pub fn build_density(
        grid: &Grid<'_, T>,
        m: [usize; 3],
        out: &'a mut [T],
    ) -> Result<Self, Error> {
        Self::build_scaled(grid, m, out, T::ONE)
    }

    /// Fills `out` with the minorants of `grid` on an `m` division of its
    /// box and borrows them: each cell gets `(σ_a + σ_s)` times the
    /// smallest grid value whose interpolation reaches into the cell (the
    /// same reach as [`build`](Self::build)), less a few ULP. A trilinear
    /// interpolation is a convex combination of the values it reaches, so
    /// it never falls below them: the minorants bound `σ_t` from below
    /// everywhere in the cell, as residual ratio tracking's control
    /// ([`Extrema`](super::residual::Extrema)) needs. Where every value
    /// reaching into a cell is the same `ρ`, the interpolation returns `ρ`
    /// exactly and the cell gets `σ_t` itself, `σ_a ρ + σ_s ρ` as tracking
    /// rounds it, with no slack: a tentative collision there weighs exactly
    /// 1, so a medium constant per cell is exact whatever the residual
    /// majorant's few ULP draw. Errors as [`Majorants::new`].
    pub fn build_minorants(
        grid: &Grid<'_, T>,
        m: [usize; 3],
        out: &'a mut [T],
    ) -> Result<Self, Error> {
        let (sa, ss) = grid.coefficients();
        let scale = (sa + ss) * (T::ONE - T::from_f64(4.0) * T::EPSILON);
        Self::build_with(grid, m, out, |lo, hi| {
            if lo == hi {
                sa * lo + ss * lo
            } else {
                scale * lo
            }
        })
    }

    fn build_scaled(
        grid: &Grid<'_, T>,
        m: [usize; 3],
        out: &'a mut [T],
        coefficient: T,
    ) -> Result<Self, Error> {
        let scale = coefficient * (T::ONE + T::from_f64(4.0) * T::EPSILON);
        Self::build_with(grid, m, out, |_, hi| scale * hi)
    }

    /// Each cell of `out` gets `value(lo, hi)` of the smallest and largest
    /// grid values whose interpolation reaches into the cell.
    fn build_with(
        grid: &Grid<'_, T>,
        m: [usize; 3],
        out: &'a mut [T],
        value: impl Fn(T, T) -> T,
    ) -> Result<Self, Error> {
        let count = majorant_len(m).ok_or(Error::Size)?;
        let cells = out.get_mut(..count).ok_or(Error::Size)?;
        let [nx, ny, nz] = grid.dims();
        let mut cells = cells.iter_mut();
        for c in 0..m[2] {
            let (k0, k1) = reach(grid, c, m[2], nz);
            for b in 0..m[1] {
                let (j0, j1) = reach(grid, b, m[1], ny);
                for a in 0..m[0] {
                    let (i0, i1) = reach(grid, a, m[0], nx);
                    let (mut lo, mut hi) = (T::INFINITY, T::ZERO);
                    for k in k0..=k1 {
                        for j in j0..=j1 {
                            for i in i0..=i1 {
                                let v = grid.value(i, j, k);
                                (lo, hi) = (lo.min_of(v), hi.max_of(v));
                            }
                        }
                    }
                    if let Some(cell) = cells.next() {
                        *cell = value(lo, hi);
                    }
                }
            }
        }
        let (lo, hi) = grid.bounds();
        Majorants::new(out, m, lo, hi)
    }

    /// Cells per axis.
    pub fn dims(&self) -> [usize; 3] {
        self.m
    }

    /// The world box `(lo, hi)`.
    pub fn bounds(&self) -> (Vec3<T>, Vec3<T>) {
        (self.lo, self.hi)
    }

    /// The value of cell `c` (0 outside the grid).
    pub(crate) fn at(&self, c: [usize; 3]) -> T {
        self.get(c[0], c[1], c[2])
    }

    /// The index of cell `c` in the array (`None` outside the grid): the
    /// same for every grid of these dimensions.
    #[inline(always)]
    pub(crate) fn index(&self, c: [usize; 3]) -> Option<usize> {
        let [mx, my, mz] = self.m;
        (c[0] < mx && c[1] < my && c[2] < mz).then(|| c[0] + mx * (c[1] + my * c[2]))
    }

    /// The value at array index `i` (0 past the end).
    #[inline(always)]
    pub(crate) fn at_index(&self, i: Option<usize>) -> T {
        i.and_then(|i| self.sigma.get(i))
            .copied()
            .unwrap_or(T::ZERO)
    }

    /// The majorant of cell `(i, j, k)` (0 outside the grid).
    pub fn get(&self, i: usize, j: usize, k: usize) -> T {
        let [mx, my, mz] = self.m;
        if i >= mx || j >= my || k >= mz {
            return T::ZERO;
        }
        self.sigma
            .get(i + mx * (j + my * k))
            .copied()
            .unwrap_or(T::ZERO)
    }

    /// `∫ σ_maj` along `ray` (the majorant optical depth), cell by cell,
    /// not rounded: [`Error::Domain`] for a ray [`Ray`] does not accept.
    /// Rounded up, the strata [`ray_march`](super::ray_march) takes by
    /// default without minorants: about one majorant mean free path each.
    pub fn optical_depth(&self, ray: Ray<T>) -> Result<T, Error> {
        // At rate 0 the walk draws nothing (its generator is never called)
        // and its tail is the integral of the cell values along the ray.
        let walk = self.walk_at_rate(ray, T::ZERO, 0, &mut NoDraws, |_, _| Ok(None::<()>))?;
        Ok(walk.tail)
    }

    /// Delta tracking through `grid` (whose majorants these must be: same
    /// box, else [`Error::Domain`]) along `ray`: at each tentative
    /// collision one uniform `ξ` decides, absorption if `ξ σ_maj < σ_a`,
    /// scattering if `ξ σ_maj < σ_a + σ_s`, else a null collision. At most
    /// `budget` tentative collisions ([`Error::Budget`]); [`Error::Domain`]
    /// for a ray [`Ray`] does not accept.
    pub fn delta_track<R: Rng + ?Sized>(
        &self,
        grid: &Grid<'_, T>,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Track<T>, Error> {
        self.same_box(grid)?;
        self.delta_track_fn(|p| grid.coefficients_at(p), ray, budget, rng)
    }

    /// Ratio tracking through `grid` (arguments as
    /// [`delta_track`](Self::delta_track)): the transmittance along `ray`,
    /// with the Russian roulette of [`Grid::ratio_track`].
    pub fn ratio_track<R: Rng + ?Sized>(
        &self,
        grid: &Grid<'_, T>,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Transmittance<T>, Error> {
        self.same_box(grid)?;
        self.ratio_track_fn(|p| grid.coefficients_at(p), ray, budget, rng)
    }

    /// Delta tracking through a caller's medium, `coefficients(p) = (σ_a,
    /// σ_s)` at a world point (both `≥ 0`, their sum within the majorant of
    /// the cell holding `p`, else [`Error::Domain`]), along `ray`. Events
    /// and budget as [`delta_track`](Self::delta_track).
    pub fn delta_track_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Track<T>, Error> {
        Walker::Cells(self).delta_track_fn(coefficients, ray, budget, rng)
    }

    /// Ratio tracking through a caller's medium (arguments as
    /// [`delta_track_fn`](Self::delta_track_fn)): the transmittance along
    /// `ray`.
    pub fn ratio_track_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Transmittance<T>, Error> {
        Walker::Cells(self).ratio_track_fn(coefficients, ray, budget, rng)
    }

    /// [`Error::Domain`] unless `grid` spans this grid's box.
    pub(super) fn same_box(&self, grid: &Grid<'_, T>) -> Result<(), Error> {
        if grid.bounds() == (self.lo, self.hi) {
            Ok(())
        } else {
            Err(Error::Domain)
        }
    }

    /// Walks the ray through the cells (a DDA, Amanatides & Woo 1987)
    /// over `[t_min, t_max]` ∩ box, drawing tentative collisions at each
    /// cell's majorant; `visit(p, σ_maj, rng)` decides at each whether the
    /// walk ends there.
    pub(super) fn walk<R: Rng + ?Sized, X>(
        &self,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
        mut visit: impl FnMut(Vec3<T>, T, &mut R) -> Result<Option<X>, Error>,
    ) -> Result<Walk<T, X>, Error> {
        self.walk_at_rate(ray, T::ONE, budget, rng, |c, r| visit(c.p, c.value, r))
    }

    /// [`walk`](Self::walk) with free paths drawn at `rate` times each
    /// cell's value (0 draws none), telling `visit` the cell value and the
    /// integral of the cell values along the ray since the previous
    /// tentative collision (or the start); the walk's `tail` is that
    /// integral from the last one to the exit. Spectral tracking needs
    /// these for every channel's majorant transmittance.
    pub(crate) fn walk_at_rate<R: Rng + ?Sized, X>(
        &self,
        ray: Ray<T>,
        rate: T,
        budget: u32,
        rng: &mut R,
        visit: impl FnMut(Tentative<T>, &mut R) -> Result<Option<X>, Error>,
    ) -> Result<Walk<T, X>, Error> {
        self.walk_cells(ray, rate, |c, _| self.at(c), budget, rng, visit)
    }

    /// [`walk_at_rate`](Self::walk_at_rate) over this grid's cells and box
    /// with the cell values `value_of(cell, length)` in place of this
    /// grid's own (a residual `σ_maj − σ_c`, say), `length` the part of the
    /// ray inside the cell; called once per cell crossed, in order.
    pub(crate) fn walk_cells<R: Rng + ?Sized, X>(
        &self,
        ray: Ray<T>,
        rate: T,
        mut value_of: impl FnMut([usize; 3], T) -> T,
        budget: u32,
        rng: &mut R,
        mut visit: impl FnMut(Tentative<T>, &mut R) -> Result<Option<X>, Error>,
    ) -> Result<Walk<T, X>, Error> {
        let (o, d) = ray.checked()?;
        let mut walk = Walk {
            found: None,
            exit: ray.t_min,
            steps: 0,
            tail: T::ZERO,
        };
        let mut since = T::ZERO;
        let cell = |cell: [usize; 3], t_cell: T, t_end: T| {
            let value = value_of(cell, t_end - t_cell);
            // Values are checked here, per cell crossed, not when the
            // caller's array is loaded (`from_parts`): the cost of a call
            // does not grow with the grid.
            if !(value >= T::ZERO && value.is_finite()) {
                return Err(Error::Domain);
            }
            let sigma_maj = rate * value;
            let (mut t, inv) = (t_cell, T::ONE / sigma_maj);
            // An empty cell (majorant 0) is crossed without a draw.
            while sigma_maj > T::ZERO && t < t_end {
                let next = t + exponential_step(inv, T::uniform(rng));
                if next >= t_end || next.is_nan() {
                    break;
                }
                if walk.steps >= budget {
                    return Err(Error::Budget);
                }
                walk.steps += 1;
                since += value * (next - t);
                t = next;
                let c = Tentative {
                    p: o + d * t,
                    cell,
                    value,
                    since,
                };
                since = T::ZERO;
                if let Some(x) = visit(c, rng)? {
                    walk.found = Some((t, x));
                    return Ok(true);
                }
            }
            since += value * (t_end - t);
            Ok(false)
        };
        if let Some((_, tb)) = self.cells(ray, cell)? {
            walk.exit = tb;
        }
        if walk.found.is_none() {
            walk.tail = since;
        }
        Ok(walk)
    }

    /// Visits the cells `ray` crosses over `[t_min, t_max]` ∩ box, in
    /// order, as `cell(index, t_enter, t_leave)` until it returns `true`;
    /// returns the clipped segment, `None` for a ray that misses the box.
    pub(crate) fn cells(
        &self,
        ray: Ray<T>,
        mut cell: impl FnMut([usize; 3], T, T) -> Result<bool, Error>,
    ) -> Result<Option<(T, T)>, Error> {
        let (o, d) = ray.checked()?;
        // In box coordinates the box is [0, 1]³ and t is unchanged.
        let ol = to_local(o, self.lo, self.hi);
        let (lo, hi) = (self.lo, self.hi);
        let dl = Vec3::new(
            d.x / (hi.x - lo.x),
            d.y / (hi.y - lo.y),
            d.z / (hi.z - lo.z),
        );
        let unit = Vec3::new(T::ZERO, T::ZERO, T::ZERO);
        let one = Vec3::new(T::ONE, T::ONE, T::ONE);
        let Some((ta, tb)) = clip_box(ol, dl, unit, one, ray.t_min, ray.t_max) else {
            return Ok(None);
        };
        let mut dda = Dda::new(ol, dl, ta, self.m);
        let mut t_cell = ta;
        for _ in 0..=(self.m[0] + self.m[1] + self.m[2]) {
            let t_end = dda.next_face().min_of(tb).max_of(t_cell);
            if cell(dda.cell, t_cell, t_end)? || t_end >= tb || !dda.step() {
                break;
            }
            t_cell = t_end;
        }
        Ok(Some((ta, tb)))
    }
}

/// A tentative collision as [`Majorants::walk_at_rate`] reports it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tentative<T> {
    /// Where.
    pub(crate) p: Vec3<T>,
    /// The cell it lies in.
    pub(crate) cell: [usize; 3],
    /// The value of the cell it lies in.
    pub(crate) value: T,
    /// `∫ value dt` along the ray since the previous tentative collision.
    pub(crate) since: T,
}

/// How delta and ratio tracking walk a ray: through the cells of a
/// majorant grid, or at one majorant over the whole segment (a caller's
/// medium with one majorant: the walk a one-cell grid around the segment
/// gives, draw for draw, without building the box or clipping the ray
/// against it, which one call per flight would pay every time).
pub(crate) enum Walker<'m, 'a, T> {
    Cells(&'m Majorants<'a, T>),
    One(T),
}

impl<T: Real> Walker<'_, '_, T> {
    /// The walk along `ray` (`visit(p, σ_maj, rng)` as in
    /// [`Majorants::walk`]). `One` needs a finite segment and a majorant
    /// `≥ 0` and finite ([`Error::Domain`]), as the one-cell grid did.
    /// Inlined, so that what its caller does not read (the tail) is not
    /// computed on the one-majorant route.
    #[inline(always)]
    fn walk<R: Rng + ?Sized, X>(
        &self,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
        mut visit: impl Visit<T, R, X>,
    ) -> Result<Walk<T, X>, Error> {
        let sigma = match self {
            Walker::Cells(m) => return m.walk(ray, budget, rng, |p, s, r| visit.at(p, s, r)),
            Walker::One(sigma) => *sigma,
        };
        let (o, d) = ray.checked()?;
        // Both finite, in one comparison (see Ray::checked).
        let both = finite_zero(ray.t_max) + finite_zero(sigma) == T::ZERO;
        let finite = both & (sigma >= T::ZERO);
        if !finite {
            return Err(Error::Domain);
        }
        // `walk_cells`' loop for its one cell, without what delta and ratio
        // tracking do not read (the cell, the integral since the last
        // tentative collision, the tail; 2–5 % of a one-call-per-flight
        // photon's time, measured from C): its draws and decisions are
        // those of a one-cell grid, checked bit for bit by a test below.
        let mut walk = Walk {
            found: None,
            exit: ray.t_max,
            steps: 0,
            tail: T::ZERO,
        };
        let (mut t, inv) = (ray.t_min, T::ONE / sigma);
        while sigma > T::ZERO && t < ray.t_max {
            let next = t + exponential_step(inv, T::uniform(rng));
            if next >= ray.t_max || next.is_nan() {
                break;
            }
            if walk.steps >= budget {
                return Err(Error::Budget);
            }
            walk.steps += 1;
            t = next;
            if let Some(x) = visit.at(o + d * t, sigma, rng)? {
                walk.found = Some((t, x));
                break;
            }
        }
        Ok(walk)
    }

    /// Delta tracking (see [`Majorants::delta_track_fn`]). Inlined into its
    /// caller, so that the ray stays in registers: passed through memory
    /// just after the caller stored it, its loads waited on those stores
    /// (a short call's largest cost, measured from C).
    #[inline(always)]
    pub(crate) fn delta_track_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Track<T>, Error> {
        let walk = self.walk(ray, budget, rng, Decide(coefficients))?;
        let (t, event) = walk.found.unwrap_or((walk.exit, Event::Escaped));
        Ok(Track {
            t,
            event,
            steps: walk.steps,
        })
    }

    /// Ratio tracking (see [`Majorants::ratio_track_fn`]), inlined as
    /// [`delta_track_fn`](Self::delta_track_fn) is.
    #[inline(always)]
    pub(crate) fn ratio_track_fn<R: Rng + ?Sized>(
        &self,
        coefficients: impl Fn(Vec3<T>) -> (T, T),
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<Transmittance<T>, Error> {
        let mut visit = Ratio {
            coefficients,
            tr: T::ONE,
        };
        let walk = self.walk(ray, budget, rng, &mut visit)?;
        Ok(Transmittance {
            tr: if walk.found.is_some() {
                T::ZERO
            } else {
                visit.tr
            },
            steps: walk.steps,
        })
    }
}

/// What a walk does at a tentative collision `p` under majorant `σ_maj`:
/// end there with a result, or go on. A trait with an inlined method,
/// not a closure: the closure was left out of line on the one-majorant
/// route, so each point went through memory with a wide load over
/// narrower stores, which stalls (a sixth of a short C call's time).
pub(crate) trait Visit<T, R: ?Sized, X> {
    fn at(&mut self, p: Vec3<T>, sigma_maj: T, rng: &mut R) -> Result<Option<X>, Error>;
}

impl<T, R: ?Sized, X, V: Visit<T, R, X>> Visit<T, R, X> for &mut V {
    #[inline(always)]
    fn at(&mut self, p: Vec3<T>, sigma_maj: T, rng: &mut R) -> Result<Option<X>, Error> {
        (**self).at(p, sigma_maj, rng)
    }
}

/// Delta tracking's decision: one uniform `ξ` gives absorption (`ξσ_maj <
/// σ_a`), scattering (`< σ_a + σ_s`) or a null collision.
struct Decide<F>(F);

impl<T: Real, R: Rng + ?Sized, F: Fn(Vec3<T>) -> (T, T)> Visit<T, R, Event> for Decide<F> {
    #[inline(always)]
    fn at(&mut self, p: Vec3<T>, sigma_maj: T, r: &mut R) -> Result<Option<Event>, Error> {
        let st = within((self.0)(p), sigma_maj)?;
        let x = T::uniform(r) * sigma_maj;
        Ok(if x < st.0 {
            Some(Event::Absorbed)
        } else if x < st.0 + st.1 {
            Some(Event::Scattered)
        } else {
            None
        })
    }
}

/// Ratio tracking's weight `tr`, times `1 − σ_t/σ_maj` at each tentative
/// collision, with the roulette; the walk ends once it is 0.
struct Ratio<F, T> {
    coefficients: F,
    tr: T,
}

impl<T: Real, R: Rng + ?Sized, F: Fn(Vec3<T>) -> (T, T)> Visit<T, R, ()> for Ratio<F, T> {
    #[inline(always)]
    fn at(&mut self, p: Vec3<T>, sigma_maj: T, r: &mut R) -> Result<Option<()>, Error> {
        let (sa, ss) = within((self.coefficients)(p), sigma_maj)?;
        self.tr = roulette(self.tr * (T::ONE - (sa + ss) / sigma_maj), r);
        Ok((self.tr == T::ZERO).then_some(()))
    }
}

/// Delta tracking through a caller's medium, `coefficients(p) = (σ_a, σ_s)`
/// at a world point (both `≥ 0`, their sum at most `sigma_maj`, else
/// [`Error::Domain`]), at one majorant `sigma_maj` over the whole segment
/// of `ray`, which must be finite: the walk a one-cell [`Majorants`] around
/// the segment gives, draw for draw, without building its box (for codes
/// that make one call per flight). Events and budget as
/// [`Majorants::delta_track`]; [`Error::Domain`] also for a majorant that
/// is negative, NaN or infinite.
#[inline(always)]
pub fn one_majorant_delta_track<T: Real, R: Rng + ?Sized>(
    coefficients: impl Fn(Vec3<T>) -> (T, T),
    sigma_maj: T,
    ray: Ray<T>,
    budget: u32,
    rng: &mut R,
) -> Result<Track<T>, Error> {
    Walker::One(sigma_maj).delta_track_fn(coefficients, ray, budget, rng)
}

/// Ratio tracking at one majorant (arguments as
/// [`one_majorant_delta_track`]): the transmittance along `ray`, with the
/// Russian roulette of [`Grid::ratio_track`].
#[inline(always)]
pub fn one_majorant_ratio_track<T: Real, R: Rng + ?Sized>(
    coefficients: impl Fn(Vec3<T>) -> (T, T),
    sigma_maj: T,
    ray: Ray<T>,
    budget: u32,
    rng: &mut R,
) -> Result<Transmittance<T>, Error> {
    Walker::One(sigma_maj).ratio_track_fn(coefficients, ray, budget, rng)
}

/// The outcome of a walk: what ended it and where, or where the ray left.
pub(crate) struct Walk<T, X> {
    pub(crate) found: Option<(T, X)>,
    pub(crate) exit: T,
    pub(crate) steps: u32,
    /// `∫ value dt` from the last tentative collision to the exit.
    pub(crate) tail: T,
}

/// Amanatides–Woo cell stepping on the `m` division of `[0, 1]³`. The time
/// of each next face is computed from the cell index, not accumulated, so
/// it does not drift over many cells; the start cell is clamped into the
/// grid, so a start on a face or rounded just outside stays valid.
struct Dda<T> {
    o: Vec3<T>,
    d: Vec3<T>,
    m: [usize; 3],
    cell: [usize; 3],
    next: [T; 3],
}

impl<T: Real> Dda<T> {
    fn new(o: Vec3<T>, d: Vec3<T>, t: T, m: [usize; 3]) -> Self {
        let p = o + d * t;
        let start = |x: T, n: usize| (x * T::from_index(n)).max_of(T::ZERO).to_index().min(n - 1);
        let cell = [start(p.x, m[0]), start(p.y, m[1]), start(p.z, m[2])];
        let mut dda = Dda {
            o,
            d,
            m,
            cell,
            next: [T::INFINITY; 3],
        };
        for a in 0..3 {
            dda.next[a] = dda.face(a);
        }
        dda
    }

    /// Component `a` of a vector.
    fn comp(v: Vec3<T>, a: usize) -> T {
        match a {
            0 => v.x,
            1 => v.y,
            _ => v.z,
        }
    }

    /// When the ray reaches the face of the current cell it moves towards
    /// along axis `a` (+∞ if it does not move along `a`).
    fn face(&self, a: usize) -> T {
        let (o, d) = (Self::comp(self.o, a), Self::comp(self.d, a));
        let i = self.cell[a] + usize::from(d > T::ZERO);
        if d == T::ZERO {
            T::INFINITY
        } else {
            (T::from_index(i) / T::from_index(self.m[a]) - o) / d
        }
    }

    /// The time of the nearest face ahead.
    fn next_face(&self) -> T {
        self.next[0].min_of(self.next[1]).min_of(self.next[2])
    }

    /// Crosses the nearest face; false when that leaves the grid.
    fn step(&mut self) -> bool {
        let mut a = 0;
        for b in 1..3 {
            if self.next[b] < self.next[a] {
                a = b;
            }
        }
        let d = Self::comp(self.d, a);
        if d > T::ZERO {
            if self.cell[a] + 1 >= self.m[a] {
                return false;
            }
            self.cell[a] += 1;
        } else {
            if self.cell[a] == 0 || d == T::ZERO {
                return false;
            }
            self.cell[a] -= 1;
        }
        self.next[a] = self.face(a);
        true
    }
}

/// The lattice indices whose interpolation reaches into cell `c` of `m`
/// along an axis of `n` grid values.
fn reach<T: Real>(grid: &Grid<'_, T>, c: usize, m: usize, n: usize) -> (usize, usize) {
    if n == 1 {
        return (0, 0);
    }
    let (mf, slop) = (T::from_index(m), T::from_f64(1e-3));
    let x0 = ((T::from_index(c) - slop) / mf).max_of(T::ZERO);
    let x1 = ((T::from_index(c + 1) + slop) / mf).min_of(T::ONE);
    let (s0, s1) = (grid.lattice(x0, n), grid.lattice(x1, n));
    let i0 = s0.to_index().min(n - 1);
    let i1 = (s1.to_index() + 1).min(n - 1);
    (i0, i1)
}

/// The coefficients if both are `≥ 0` with a sum within `sigma_maj`.
#[inline(always)]
pub(crate) fn within<T: Real>((sa, ss): (T, T), sigma_maj: T) -> Result<(T, T), Error> {
    if sa >= T::ZERO && ss >= T::ZERO && sa + ss <= sigma_maj {
        Ok((sa, ss))
    } else {
        Err(Error::Domain)
    }
}

/// A generator for walks that draw nothing (rate 0): never called.
pub(crate) struct NoDraws;

impl rand_core::TryRng for NoDraws {
    type Error = core::convert::Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
        Ok(0)
    }
    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        Ok(0)
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
        dst.fill(0);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::SeedableRng;

    /// The one-majorant walk draws what a one-cell grid around the segment
    /// draws: the same distances, events, steps and transmittances, bit for
    /// bit, over rays in every direction, segments starting inside, and a
    /// medium that varies along them (the C layer took the grid before).
    #[test]
    fn one_majorant_walks_as_a_one_cell_grid() {
        let coef = |p: Vec3<f64>| (0.3 + 0.2 * (3.0 * p.x).sin(), 1.0 + 0.5 * (2.0 * p.z).cos());
        let dirs = [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.3, -0.4, -0.866),
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(0.5, 0.5, 0.0),
        ];
        for (k, d) in dirs.into_iter().enumerate() {
            // With an empty segment (0.5, 0.5), which draws nothing.
            for (t0, t1) in [(0.0, 0.3), (0.2, 2.5), (0.0, 40.0), (0.5, 0.5)] {
                let o = Vec3::new(0.1 * k as f64, -0.2, 0.7);
                let ray = Ray::new(o, d, t1).segment(t0, t1);
                let u = d.try_normalize().unwrap();
                let (a, b) = (o + u * t0, o + u * t1);
                let lo =
                    Vec3::new(a.x.min(b.x), a.y.min(b.y), a.z.min(b.z)) - Vec3::new(1.0, 1.0, 1.0);
                let hi =
                    Vec3::new(a.x.max(b.x), a.y.max(b.y), a.z.max(b.z)) + Vec3::new(1.0, 1.0, 1.0);
                let sigma = [2.0f64];
                let cell = Majorants::from_parts(&sigma, [1; 3], lo, hi).unwrap();
                for seed in 0..200u64 {
                    let mut r1 = Xoshiro256PlusPlus::seed_from_u64(seed);
                    let mut r2 = Xoshiro256PlusPlus::seed_from_u64(seed);
                    let x = Walker::One(2.0)
                        .delta_track_fn(coef, ray, 1000, &mut r1)
                        .unwrap();
                    let y = cell.delta_track_fn(coef, ray, 1000, &mut r2).unwrap();
                    assert_eq!(
                        (x.t.to_bits(), x.event, x.steps),
                        (y.t.to_bits(), y.event, y.steps)
                    );
                    let x = Walker::One(2.0)
                        .ratio_track_fn(coef, ray, 1000, &mut r1)
                        .unwrap();
                    let y = cell.ratio_track_fn(coef, ray, 1000, &mut r2).unwrap();
                    assert_eq!((x.tr.to_bits(), x.steps), (y.tr.to_bits(), y.steps));
                    // The generators are left in the same state.
                    assert_eq!(r1, r2, "seed {seed}, segment ({t0}, {t1})");
                }
            }
        }
        // Refused as the one-cell grid was: an infinite segment, a bad
        // majorant; the budget is its own error.
        let mut r = Xoshiro256PlusPlus::seed_from_u64(1);
        let ray = Ray::new(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            f64::INFINITY,
        );
        assert_eq!(
            Walker::One(2.0).delta_track_fn(coef, ray, 10, &mut r).err(),
            Some(Error::Domain)
        );
        let ray = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), 1.0);
        assert_eq!(
            Walker::One(-1.0)
                .delta_track_fn(coef, ray, 10, &mut r)
                .err(),
            Some(Error::Domain)
        );
        assert_eq!(
            Walker::One(f64::NAN)
                .ratio_track_fn(coef, ray, 10, &mut r)
                .err(),
            Some(Error::Domain)
        );
        let long = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), 1e6);
        let thin = |_: Vec3<f64>| (0.0, 1e-9);
        assert_eq!(
            Walker::One(2.0)
                .delta_track_fn(thin, long, 10, &mut r)
                .err(),
            Some(Error::Budget)
        );
    }

    /// A generator whose every uniform is `1 − 2⁻⁵³` (a step of 36.7 mean
    /// free paths), counting its draws.
    struct Far(u32);

    impl rand_core::TryRng for Far {
        type Error = core::convert::Infallible;
        fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
            self.0 += 1;
            Ok(u32::MAX)
        }
        fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
            self.0 += 1;
            Ok(u64::MAX)
        }
        fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
            dst.fill(u8::MAX);
            Ok(())
        }
    }

    /// A ray through a grid's edge crosses a cell of zero length there,
    /// and draws nothing in it: one draw per cell of positive length (a
    /// mutation test's `t < t_end` → `≤` drew in the empty one too). A
    /// single majorant of 0 draws nothing either (`σ > 0` → `≥ 0` drew).
    #[test]
    fn a_cell_crossed_over_no_length_draws_nothing() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), 5.0);
        let vacuum = |_: Vec3<f64>| (0.0, 0.0);
        let mut rng = Far(0);
        let hit = Walker::One(0.0).delta_track_fn(vacuum, ray, 100, &mut rng);
        assert_eq!(
            hit.map(|h| (h.t, h.event, rng.0)),
            Ok((5.0, Event::Escaped, 0))
        );
        let mut rng = Far(0);
        let tr = Walker::One(0.0).ratio_track_fn(vacuum, ray, 100, &mut rng);
        assert_eq!(tr.map(|x| (x.tr, rng.0)), Ok((1.0, 0)));
        let sigma = [2.0f64; 4];
        let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
        let grid = Majorants::from_parts(&sigma, [2, 2, 1], lo, hi).unwrap();
        let coef = |_: Vec3<f64>| (0.5, 0.5);
        // Along the diagonal of the 2 × 2 cells: through the edge x = y =
        // ½, between the cells (0, 0) and (1, 1).
        let diagonal = Ray::new(Vec3::new(0.0, 0.0, 0.5), Vec3::new(1.0, 1.0, 0.0), 10.0);
        let mut rng = Far(0);
        let hit = grid.delta_track_fn(coef, diagonal, 100, &mut rng).unwrap();
        assert_eq!((hit.event, hit.steps, rng.0), (Event::Escaped, 0, 2));
        let mut rng = Far(0);
        let tr = grid.ratio_track_fn(coef, diagonal, 100, &mut rng).unwrap();
        assert_eq!((tr.tr, tr.steps, rng.0), (1.0, 0, 2));
    }
}
