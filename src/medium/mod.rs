//! Participating media (pbrt-v3 §15.2): free paths, homogeneous
//! media with spectral coefficients, and unbiased delta and ratio tracking
//! through a density grid or a caller's density function.
//!
//! Units: coefficients σ in inverse length, distances `t` in the same length
//! unit, measured along `d/|d|` (a direction of any non-zero length is
//! accepted and only its direction is used, so `dist·|d|` versus `dist/|d|`
//! cannot go wrong).
//!
//! Every loop is bounded: tracking stops after [`MAX_STEPS`] tentative
//! collisions and then reports [`Error::Budget`]
//! (ratio tracking) rather than a biased answer. A zero majorant, or a ray
//! that misses the medium, returns at once: no interaction, transmittance 1.

pub mod emission;
pub mod equiangular;
pub mod majorant;
pub mod nonbounding;
pub mod ray_march;
pub mod residual;
pub mod spectral;

use crate::error::{Error, try_from_u32};
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use rand_core::Rng;

/// The most tentative collisions one tracking call takes (2²⁰); a medium of
/// majorant optical depth beyond ~10⁶ along one ray reports
/// [`Error::Budget`]. The majorant-grid calls ([`crate::medium::majorant`]) take
/// the caller's budget instead.
pub const MAX_STEPS: u32 = 1 << 20;

/// Distance to the next interaction in a homogeneous medium of extinction
/// `sigma_t` (≥ 0, finite): `t = −ln(1 − u)/σ_t`, the logarithm within 1
/// ulp for every `u` (the crate's table-driven one where `1 − u` is exact,
/// as for every generator's `k·2⁻⁵³`; `ln_1p(−u)` where it would round,
/// so small `u` keep their relative precision). `u` is clamped to
/// `[0, 1]`; `u = 1` or `σ_t = 0` gives +∞ (no interaction). NaN for a
/// negative or non-finite `sigma_t`, or NaN `u`.
#[inline]
pub fn free_path<T: Real>(sigma_t: T, u: T) -> T {
    // The call a photon loop makes (σ_t positive and finite, u in [0, 1))
    // behind one test, with u handed to the logarithm as it is: the checks
    // below, and the clamp's two min/max on the logarithm's input, were 3
    // of the 128 ns of a homogeneous slab photon from Rust (four calls;
    // Intel Xeon, family 6 model 167). The same result for every input.
    if (sigma_t > T::ZERO) & (sigma_t < T::INFINITY) & (u >= T::ZERO) & (u < T::ONE) {
        return -ln_1m(u) / sigma_t;
    }
    free_path_edge(sigma_t, u)
}

/// [`free_path`] for the inputs its first test leaves: a zero, negative or
/// non-finite `sigma_t`, and `u` outside `[0, 1)` or NaN.
#[cold]
fn free_path_edge<T: Real>(sigma_t: T, u: T) -> T {
    if !(sigma_t >= T::ZERO && sigma_t.is_finite()) {
        return T::NAN;
    }
    let u = u.clamp01();
    if sigma_t == T::ZERO {
        return if u.is_nan() { T::NAN } else { T::INFINITY };
    }
    -ln_1m(u) / sigma_t
}

/// `−ln(1 − u)·(1/σ)` without [`free_path`]'s checks, for the tracking
/// loops, whose majorant is checked once (`σ > 0`, finite), whose `u ∈ [0,
/// 1)`, and which take `inv_sigma = 1/σ` once per majorant: a division on
/// every step's dependency chain cost more than the ulp it saves.
#[inline(always)]
pub(crate) fn exponential_step<T: Real>(inv_sigma: T, u: T) -> T {
    -ln_1m(u) * inv_sigma
}

/// `ln(1 − u)`: the crate's table-driven logarithm in f64 (for f32 too
/// where doubles run in hardware), else libm's `log1pf`.
#[inline(always)]
fn ln_1m<T: Real>(u: T) -> T {
    ln_1m_on(u, crate::math::log::WIDE)
}

/// [`ln_1m`] on a host whose doubles run in hardware (`wide`) or not: a
/// parameter, so that one host tests both routes.
#[inline(always)]
fn ln_1m_on<T: Real>(u: T, wide: bool) -> T {
    if core::mem::size_of::<T>() == 8 || wide {
        T::from_f64(crate::math::log::ln_1m(u.to_f64()))
    } else {
        ln_1m_narrow(u)
    }
}

/// `ln(1 − u)` in `T` alone (`log1pf` for f32), where doubles are
/// emulated in software; a function of its own so that hosts with
/// hardware doubles test it too.
#[inline(always)]
fn ln_1m_narrow<T: Real>(u: T) -> T {
    (-u).ln_1p()
}

/// Beer–Lambert transmittance `e^{−σ_t d}` for `sigma_t ≥ 0` and
/// `distance ≥ 0` (either may be +∞; `0·∞` counts as 0, so a vacuum
/// transmits over any distance). NaN for negative or NaN arguments.
#[inline]
pub fn transmittance<T: Real>(sigma_t: T, distance: T) -> T {
    if !(sigma_t >= T::ZERO && distance >= T::ZERO) {
        return T::NAN;
    }
    if sigma_t == T::ZERO || distance == T::ZERO {
        return T::ONE;
    }
    (-(sigma_t * distance)).exp()
}

/// What a homogeneous sample hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HomogeneousSample<T> {
    /// Distance to the event (`t_max` for the surface event).
    pub t: T,
    /// True for a medium (scattering) event, false for the surface at `t_max`.
    pub scattered: bool,
}

/// pbrt's spectral homogeneous sampling: pick a channel uniformly with
/// `u_channel`, sample its free path with `u_dist`, and weight each channel by
/// the average density over channels: at a medium event
/// `β = Tr σ_s / mean(σ_t Tr)`, at the surface `β = Tr / mean(Tr)`, with
/// `Tr = e^{−σ_t t}`. `weight_out` receives β per channel. Where every
/// channel's density has underflowed to 0, β is 0 (the path carries nothing).
///
/// [`Error::Size`] for zero channels or slices of different lengths;
/// [`Error::Domain`] for coefficients that are negative or not finite,
/// `σ_s > σ_t`, or `t_max` negative or NaN (+∞ is allowed). Nothing is
/// written on error.
pub fn homogeneous_sample<T: Real>(
    sigma_t: &[T],
    sigma_s: &[T],
    t_max: T,
    u_channel: T,
    u_dist: T,
    weight_out: &mut [T],
) -> Result<HomogeneousSample<T>, Error> {
    let c = sigma_t.len();
    if c == 0 || sigma_s.len() != c || weight_out.len() != c {
        return Err(Error::Size);
    }
    let valid = |t: T, s: T| t.is_finite() && s.is_finite() && s >= T::ZERO && t >= s;
    if !sigma_t.iter().zip(sigma_s).all(|(&t, &s)| valid(t, s)) || !non_negative(t_max) {
        return Err(Error::Domain);
    }
    let channel = (u_channel.clamp01() * T::from_index(c))
        .to_index()
        .min(c - 1);
    let dist = free_path(sigma_t.get(channel).copied().unwrap_or(T::NAN), u_dist);
    let medium = dist < t_max;
    let t = if medium { dist } else { t_max };
    let mut pdf = T::ZERO;
    for (w, &st) in weight_out.iter_mut().zip(sigma_t) {
        let tr = transmittance(st, t);
        *w = tr;
        pdf += if medium { st * tr } else { tr };
    }
    let pdf = pdf / T::from_index(c);
    for (w, &ss) in weight_out.iter_mut().zip(sigma_s) {
        let num = if medium { *w * ss } else { *w };
        *w = if pdf > T::ZERO { num / pdf } else { T::ZERO };
    }
    Ok(HomogeneousSample {
        t,
        scattered: medium,
    })
}

/// The outcome of delta tracking.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Event {
    /// No collision in `[t_min, t_max]`: the ray leaves the medium.
    Escaped = 0,
    /// A real collision that scatters (grid: chosen with probability σ_s/σ_t).
    Scattered = 1,
    /// A real collision that absorbs.
    Absorbed = 2,
    /// A real collision (caller's density: the caller's albedo decides).
    Collided = 3,
}

/// A ray segment for tracking: from `origin` along `dir` (any non-zero
/// length; distances are measured along `dir/|dir|`, in the coefficients'
/// length unit) over `[t_min, t_max]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<T> {
    /// Where the ray starts (finite).
    pub origin: Vec3<T>,
    /// Its direction (finite, non-zero; only the direction is used).
    pub dir: Vec3<T>,
    /// Where the segment starts (finite, `≥ 0`).
    pub t_min: T,
    /// Where it ends (`≥ t_min`; +∞ allowed).
    pub t_max: T,
}

impl<T: Real> Ray<T> {
    /// The segment `[0, t_max]` from `origin` along `dir`.
    pub fn new(origin: Vec3<T>, dir: Vec3<T>, t_max: T) -> Self {
        Ray {
            origin,
            dir,
            t_min: T::ZERO,
            t_max,
        }
    }

    /// The same ray over `[t_min, t_max]`.
    pub fn segment(self, t_min: T, t_max: T) -> Self {
        Ray {
            t_min,
            t_max,
            ..self
        }
    }

    /// The origin and unit direction, with the interval checked:
    /// [`Error::Domain`] unless the origin is finite, the direction finite
    /// and non-zero, `t_min` finite and `≥ 0`, and `t_max ≥ t_min`.
    /// Inlined, so that a ray its caller has just built is not read back
    /// from memory (wide loads over narrower stores stall).
    #[inline(always)]
    pub(crate) fn checked(&self) -> Result<(Vec3<T>, Vec3<T>), Error> {
        // A direction already unit to within 4 ulp of |d|² (|d| within 2
        // ulp of 1, which is what a caller's own normalisation leaves) is
        // taken as it is: rescaling it would move the distances by no more
        // than that, and its two divisions and square root were a fifth of
        // a one-call-per-flight photon's tracking time, measured from C.
        // NaN and ±∞ components fail the test and take the full check.
        let n2 = self.dir.dot(self.dir);
        let d = if (n2 - T::ONE).abs() <= T::from_f64(4.0) * T::EPSILON {
            self.dir
        } else {
            self.dir.try_normalize().ok_or(Error::Domain)?
        };
        // Every test at once, without a branch per test ([`finite_zero`]):
        // the sum is 0 exactly when the origin and t_min are finite. The
        // tests one by one were 1–4 % of a one-call-per-flight photon's
        // time from Rust and from C (3 % in the homogeneous slab through
        // delta tracking; Intel Xeon, family 6 model 167).
        let o = self.origin;
        let finite =
            finite_zero(o.x) + finite_zero(o.y) + finite_zero(o.z) + finite_zero(self.t_min);
        if (finite == T::ZERO) & (self.t_min >= T::ZERO) & (self.t_max >= self.t_min) {
            Ok((o, d))
        } else {
            Err(Error::Domain)
        }
    }
}

/// `x − x`: 0 for a finite `x`, NaN for ±∞ and NaN, so that a sum of
/// these is 0 exactly when every `x` is finite (one comparison for many
/// tests, where each `is_finite` was a branch of its own).
#[inline(always)]
#[allow(clippy::eq_op)]
pub(crate) fn finite_zero<T: Real>(x: T) -> T {
    x - x
}

/// Where a grid's values sit in its box.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Sampling {
    /// At the nodes: value `i` at `lo + (hi − lo) i/(n − 1)`, so the faces
    /// carry the outermost values and a density linear in x, y, z is
    /// represented exactly. The default.
    Nodes = 0,
    /// At the cell centres: value `i` at `lo + (hi − lo)(i + ½)/n`, as
    /// pbrt-v4 and OpenVDB place voxel values. Between the outermost centres
    /// and the faces the density is held at the outermost value (pbrt-v4
    /// instead blends towards 0 there).
    Cells = 1,
}

try_from_u32!(Sampling: Nodes, Cells);

/// A density grid over an axis-aligned box (the unit cube `[0, 1]³` unless
/// [`Grid::with_box`] says otherwise), borrowed from the caller:
/// `nx·ny·nz` non-negative values, x fastest (`i + nx (j + ny k)`), placed
/// at the nodes of the box or at its cell centres ([`Sampling`]; a
/// dimension of 1 is constant along its axis) and interpolated
/// trilinearly. Zero outside the box. `σ_t(p) = (σ_a + σ_s) density(p)`.
///
/// # Example
///
/// A 2×2×2 grid over a world box, tracked directly with its one majorant
/// and through 4³ local majorants (`crate::medium::majorant`) in caller memory:
///
/// ```
/// use scatterkit::majorant::Majorants;
/// use scatterkit::{Grid, Ray, Sampling, Vec3};
/// use rand_xoshiro::Xoshiro256PlusPlus;
/// use rand_xoshiro::rand_core::SeedableRng;
///
/// let density = [0.0f64, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 8.0];
/// let grid = Grid::new(&density, 2, 2, 2, 0.2, 0.8)
///     .unwrap()
///     .with_box(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0))
///     .unwrap()
///     .with_sampling(Sampling::Cells);
/// let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
/// let (o, d) = (Vec3::new(-3.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
/// let tr = grid.ratio_track(Ray::new(o, d, 10.0), &mut rng).unwrap();
/// assert!((0.0..=1.0).contains(&tr));
///
/// let mut store = [0.0; 4 * 4 * 4];
/// let maj = Majorants::build(&grid, [4; 3], &mut store).unwrap();
/// let hit = maj.delta_track(&grid, Ray::new(o, d, 10.0), 1 << 20, &mut rng).unwrap();
/// assert!(hit.t >= 0.0 && hit.t <= 10.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid<'a, T> {
    density: &'a [T],
    n: [usize; 3],
    sigma_a: T,
    sigma_s: T,
    max_density: T,
    lo: Vec3<T>,
    hi: Vec3<T>,
    /// `1/(hi − lo)` per axis, so that a density lookup multiplies.
    scale: Vec3<T>,
    sampling: Sampling,
    /// What tracking reads at every call, computed once: the majorant, its
    /// reciprocal and the albedo (two divisions a short call paid each
    /// time).
    kept: Kept<T>,
}

/// A grid's majorant, its reciprocal and its albedo, from its
/// coefficients and largest density (see [`Grid::majorant`]).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Kept<T> {
    majorant: T,
    inv_majorant: T,
    albedo: T,
}

impl<T: Real> Kept<T> {
    fn of(sigma_a: T, sigma_s: T, max_density: T) -> Self {
        let st = sigma_a + sigma_s;
        let majorant = st * max_density * (T::ONE + T::from_f64(4.0) * T::EPSILON);
        Kept {
            majorant,
            inv_majorant: T::ONE / majorant,
            albedo: if st > T::ZERO { sigma_s / st } else { T::ZERO },
        }
    }
}

impl<'a, T: Real> Grid<'a, T> {
    /// Validates and borrows `density`. [`Error::Size`] for a zero dimension,
    /// a product that overflows, or a buffer shorter than `nx·ny·nz`;
    /// [`Error::Domain`] for a negative or non-finite density value or
    /// coefficient, or a majorant that overflows (tracking could not step
    /// through it): `(σ_a + σ_s)·max(density)·(1 + 4ε)`, the
    /// [`majorant`](Self::majorant) with its slack, so the last values
    /// accepted are up to 8 ulp below where the product alone would
    /// overflow.
    pub fn new(
        density: &'a [T],
        nx: usize,
        ny: usize,
        nz: usize,
        sigma_a: T,
        sigma_s: T,
    ) -> Result<Self, Error> {
        Self::scan(density, nx, ny, nz, sigma_a, sigma_s).map(|(g, _)| g)
    }

    /// [`Grid::new`], also returning the maximum density it found.
    pub(crate) fn scan(
        density: &'a [T],
        nx: usize,
        ny: usize,
        nz: usize,
        sigma_a: T,
        sigma_s: T,
    ) -> Result<(Self, T), Error> {
        let count = grid_len(nx, ny, nz).ok_or(Error::Size)?;
        let density = density.get(..count).ok_or(Error::Size)?;
        let coeff_ok = |s: T| s >= T::ZERO && s.is_finite();
        if !(coeff_ok(sigma_a) && coeff_ok(sigma_s)) {
            return Err(Error::Domain);
        }
        let mut max_density = T::ZERO;
        for &v in density {
            if !(v >= T::ZERO && v.is_finite()) {
                return Err(Error::Domain);
            }
            max_density = max_density.max_of(v);
        }
        let grid = Grid {
            density,
            n: [nx, ny, nz],
            sigma_a,
            sigma_s,
            max_density,
            lo: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
            hi: Vec3::new(T::ONE, T::ONE, T::ONE),
            scale: Vec3::new(T::ONE, T::ONE, T::ONE),
            sampling: Sampling::Nodes,
            kept: Kept::of(sigma_a, sigma_s, max_density),
        };
        if !grid.majorant().is_finite() {
            return Err(Error::Domain);
        }
        Ok((grid, max_density))
    }

    /// A grid from the parts of one that [`Grid::new`] (and
    /// [`with_box`](Self::with_box)) accepted, as a caller that stores grids
    /// as plain values keeps them (the C layer's `sk_grid` does): the
    /// densities, `[nx, ny, nz]`, `σ_a` and `σ_s` in inverse world units, the
    /// largest density, the box and the sampling. [`Error::Size`] unless
    /// every count is at least 1 and `density` holds `nx·ny·nz` values;
    /// other parts are taken as given (parts `Grid::new` would refuse give
    /// wrong answers, never a panic).
    #[allow(clippy::too_many_arguments)]
    pub fn from_parts(
        density: &'a [T],
        n: [usize; 3],
        sigma_a: T,
        sigma_s: T,
        max_density: T,
        (lo, hi): (Vec3<T>, Vec3<T>),
        sampling: Sampling,
    ) -> Result<Self, Error> {
        let count = n.iter().try_fold(
            1usize,
            |acc, &k| if k == 0 { None } else { acc.checked_mul(k) },
        );
        let density = count.and_then(|c| density.get(..c)).ok_or(Error::Size)?;
        Ok(Grid {
            density,
            n,
            sigma_a,
            sigma_s,
            max_density,
            lo,
            hi,
            scale: inverse_extent(lo, hi),
            sampling,
            kept: Kept::of(sigma_a, sigma_s, max_density),
        })
    }

    /// The grid placed in the world box `[lo, hi]` instead of the unit cube.
    /// [`Error::Domain`] unless every coordinate is finite and `lo < hi` on
    /// every axis with a finite extent whose reciprocal is finite.
    pub fn with_box(self, lo: Vec3<T>, hi: Vec3<T>) -> Result<Self, Error> {
        if valid_box(lo, hi) {
            Ok(Grid {
                lo,
                hi,
                scale: inverse_extent(lo, hi),
                ..self
            })
        } else {
            Err(Error::Domain)
        }
    }

    /// The grid with its values placed as `sampling` says.
    pub fn with_sampling(self, sampling: Sampling) -> Self {
        Grid { sampling, ..self }
    }

    /// The world box `(lo, hi)` the grid spans.
    pub fn bounds(&self) -> (Vec3<T>, Vec3<T>) {
        (self.lo, self.hi)
    }

    /// Where the values sit.
    pub fn sampling(&self) -> Sampling {
        self.sampling
    }

    /// Values per axis `[nx, ny, nz]`.
    pub fn dims(&self) -> [usize; 3] {
        self.n
    }

    /// The coefficients per unit density `(σ_a, σ_s)`.
    pub fn coefficients(&self) -> (T, T) {
        (self.sigma_a, self.sigma_s)
    }

    /// The value at lattice index `(i, j, k)` (in bounds).
    #[inline(always)]
    pub(crate) fn value(&self, i: usize, j: usize, k: usize) -> T {
        let [nx, ny, _] = self.n;
        // In bounds by construction; `get` lets the compiler see it.
        self.density
            .get(i + nx * (j + ny * k))
            .copied()
            .unwrap_or(T::NAN)
    }

    /// The lattice coordinate of local coordinate `x ∈ [0, 1]` on `n`
    /// values: `x (n − 1)` for nodes, `x n − ½` held inside `[0, n − 1]`
    /// for cell centres.
    #[inline(always)]
    pub(crate) fn lattice(&self, x: T, n: usize) -> T {
        let top = T::from_index(n - 1);
        match self.sampling {
            Sampling::Nodes => x * top,
            Sampling::Cells => (x * T::from_index(n) - T::HALF).max_of(T::ZERO).min_of(top),
        }
    }

    /// The interpolated density at `p` (0 outside the box, NaN for a NaN
    /// coordinate).
    #[inline]
    pub fn density(&self, p: Vec3<T>) -> T {
        if p.x.is_nan() || p.y.is_nan() || p.z.is_nan() {
            return T::NAN;
        }
        let (lo, hi) = (self.lo, self.hi);
        let inside = |x: T, l: T, h: T| x >= l && x <= h;
        if !(inside(p.x, lo.x, hi.x) && inside(p.y, lo.y, hi.y) && inside(p.z, lo.z, hi.z)) {
            return T::ZERO;
        }
        // Inside the box (faces included): the local coordinates clamp
        // nothing but a point on the far face rounded just past it.
        self.density_inside(p)
    }

    /// [`density`](Self::density) without its NaN and box tests, as
    /// tracking reads it: its points are finite (a checked origin and
    /// direction, a distance below the clipped exit) and inside the
    /// clipped box up to the rounding of `o + t d`, so each local
    /// coordinate is clamped to `[0, 1]` (the face's value) instead (the
    /// tests were 8 of the 215 ns of a 1 × 1 × 64 grid photon from Rust, 6
    /// of 270 from C). Local coordinates by the stored reciprocal extents
    /// (three divisions per lookup were a third of a grid lookup's time).
    /// A column (`1 × 1 × n_z`, a layered medium) reads two values at its
    /// local z alone: with x and y mapped too, a 1 × 1 × 64 grid's lookup
    /// was 100 instructions of a C photon's 3400 (callgrind).
    #[inline(always)]
    fn density_inside(&self, p: Vec3<T>) -> T {
        let (lo, k) = (self.lo, self.scale);
        let local = |x: T, l: T, k: T| ((x - l) * k).max_of(T::ZERO).min_of(T::ONE);
        let [nx, ny, nz] = self.n;
        if nx == 1 && ny == 1 {
            let (iz, fz) = node(self.lattice(local(p.z, lo.z, k.z), nz), nz);
            let (a, b) = (self.value(0, 0, iz), self.value(0, 0, (iz + 1).min(nz - 1)));
            return a + (b - a) * fz;
        }
        self.interpolate(Vec3::new(
            local(p.x, lo.x, k.x),
            local(p.y, lo.y, k.y),
            local(p.z, lo.z, k.z),
        ))
    }

    /// The interpolated density at local coordinates `l ∈ [0, 1]³` (a
    /// column takes [`density_inside`](Self::density_inside)'s shortcut).
    #[inline(always)]
    fn interpolate(&self, l: Vec3<T>) -> T {
        let [nx, ny, nz] = self.n;
        let (ix, fx) = node(self.lattice(l.x, nx), nx);
        let (iy, fy) = node(self.lattice(l.y, ny), ny);
        let (iz, fz) = node(self.lattice(l.z, nz), nz);
        let at = |i: usize, j: usize, k: usize| {
            self.value(
                (ix + i).min(nx - 1),
                (iy + j).min(ny - 1),
                (iz + k).min(nz - 1),
            )
        };
        let lerp = |a: T, b: T, t: T| a + (b - a) * t;
        let x00 = lerp(at(0, 0, 0), at(1, 0, 0), fx);
        let x10 = lerp(at(0, 1, 0), at(1, 1, 0), fx);
        let x01 = lerp(at(0, 0, 1), at(1, 0, 1), fx);
        let x11 = lerp(at(0, 1, 1), at(1, 1, 1), fx);
        lerp(lerp(x00, x10, fy), lerp(x01, x11, fy), fz)
    }

    /// `(σ_a ρ(p), σ_s ρ(p))` at a world point `p`, `ρ` the interpolated
    /// density: what tracking through the grid reads, and what a call
    /// taking a caller's medium (`*_fn`, `residual_ratio_track_rate`) takes
    /// as `|p| grid.coefficients_at(p)`.
    #[inline(always)]
    pub fn coefficients_at(&self, p: Vec3<T>) -> (T, T) {
        let rho = self.density(p);
        (self.sigma_a * rho, self.sigma_s * rho)
    }

    /// `σ_t(p)`.
    #[inline]
    pub fn sigma_t(&self, p: Vec3<T>) -> T {
        (self.sigma_a + self.sigma_s) * self.density(p)
    }

    /// The majorant `(σ_a + σ_s) max(density)`, raised by a few ULP so the
    /// rounding of the interpolation can never exceed it (any majorant at or
    /// above σ_t keeps tracking unbiased).
    pub fn majorant(&self) -> T {
        self.kept.majorant
    }

    /// The single-scattering albedo `σ_s/(σ_a + σ_s)` (0 for a vacuum).
    pub fn albedo(&self) -> T {
        self.kept.albedo
    }

    /// The majorant and its reciprocal, as tracking steps by them.
    #[inline(always)]
    fn rate(&self) -> Rate<T> {
        Rate(self.kept.majorant, self.kept.inv_majorant)
    }

    /// Delta (Woodcock) tracking along `ray`, first clipped to the grid's
    /// box. Returns the distance and the event (a real collision scatters
    /// with probability σ_s/σ_t; an escape reports `ray.t_max`; for where
    /// the ray leaves the box, see
    /// [`delta_track_within`](Self::delta_track_within)).
    /// [`Error::Domain`] for a ray [`Ray`] does not accept (a zero or
    /// non-finite direction, a non-finite origin, a bad interval);
    /// [`Error::Budget`] when [`MAX_STEPS`] is reached.
    // Inlined: once it took its result from `delta_track_within`'s `Track`,
    // LLVM left it out of line in a photon loop that calls it once per
    // flight, and the loop ran 23 % more instructions (54.6 against 44.4
    // million for 20 000 photons through the 1 × 1 × 64 slab grid,
    // callgrind).
    #[inline(always)]
    pub fn delta_track<R: Rng + ?Sized>(
        &self,
        ray: Ray<T>,
        rng: &mut R,
    ) -> Result<(T, Event), Error> {
        self.delta_track_within(ray, MAX_STEPS, rng)
            .map(|x| match x.event {
                Event::Escaped => (ray.t_max, x.event),
                _ => (x.t, x.event),
            })
    }

    /// [`delta_track`](Self::delta_track) with at most `budget` tentative
    /// collisions ([`Error::Budget`] beyond), the same draws, as a
    /// [`Track`](majorant::Track): the step count, and for an escape where
    /// the ray leaves the box (clipped to `[t_min, t_max]`; `t_min` for a
    /// ray that never enters it), as
    /// [`Majorants::delta_track`](majorant::Majorants::delta_track)
    /// reports it and the C layer's `sk_delta_track` for every medium.
    #[inline(always)]
    pub fn delta_track_within<R: Rng + ?Sized>(
        &self,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<majorant::Track<T>, Error> {
        let (o, d) = ray.checked()?;
        let Some((t0, t1)) = clip(o, d, (self.lo, self.hi), ray.t_min, ray.t_max) else {
            return Ok(majorant::Track {
                t: ray.t_min,
                event: Event::Escaped,
                steps: 0,
            });
        };
        let span = (t0, t1, budget);
        let (t, hit, steps) = delta(GridSigmaT(self), self.rate(), o, d, span, rng)?;
        if !hit {
            // t is t1, where the clipped segment ends.
            let event = Event::Escaped;
            return Ok(majorant::Track { t, event, steps });
        }
        // A second uniform picks scattering with probability σ_s/σ_t (the
        // grid's albedo): the draws 0.1 made, so a seed gives what it gave.
        let event = if T::uniform(rng) < self.albedo() {
            Event::Scattered
        } else {
            Event::Absorbed
        };
        Ok(majorant::Track { t, event, steps })
    }

    /// Ratio tracking: an unbiased estimate of the transmittance along
    /// `ray` (clipped to the box), with Russian roulette once the weight
    /// falls below 0.05 (survival 1/4, weight ×4, as pbrt-v4), so the walk
    /// ends soon after the transmittance is gone. [`Error::Domain`] for a
    /// ray [`Ray`] does not accept; [`Error::Budget`] when [`MAX_STEPS`] is reached (a
    /// medium far below its one majorant over a long ray: walk
    /// [`crate::medium::majorant::Majorants`] instead).
    pub fn ratio_track<R: Rng + ?Sized>(&self, ray: Ray<T>, rng: &mut R) -> Result<T, Error> {
        self.ratio_track_within(ray, MAX_STEPS, rng)
            .map(|(tr, _)| tr)
    }

    /// [`ratio_track`](Self::ratio_track) with at most `budget` tentative
    /// collisions ([`Error::Budget`] beyond), also returning how many it
    /// drew.
    pub(crate) fn ratio_track_within<R: Rng + ?Sized>(
        &self,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
    ) -> Result<(T, u32), Error> {
        let (o, d) = ray.checked()?;
        let Some((t0, t1)) = clip(o, d, (self.lo, self.hi), ray.t_min, ray.t_max) else {
            return Ok((T::ONE, 0));
        };
        let span = (t0, t1, budget);
        ratio(GridSigmaT(self), self.rate(), o, d, span, rng)
    }
}

/// `nx·ny·nz` if no dimension is 0 and the product fits in `usize`.
pub fn grid_len(nx: usize, ny: usize, nz: usize) -> Option<usize> {
    if nx == 0 || ny == 0 || nz == 0 {
        return None;
    }
    nx.checked_mul(ny)?.checked_mul(nz)
}

/// Index and fraction of lattice coordinate `s ∈ [0, n − 1]` on `n` values.
#[inline(always)]
fn node<T: Real>(s: T, n: usize) -> (usize, T) {
    if n == 1 {
        return (0, T::ZERO);
    }
    let i = s.to_index().min(n - 2);
    (i, s - T::from_index(i))
}

/// `1/(hi − lo)` per axis.
fn inverse_extent<T: Real>(lo: Vec3<T>, hi: Vec3<T>) -> Vec3<T> {
    Vec3::new(
        T::ONE / (hi.x - lo.x),
        T::ONE / (hi.y - lo.y),
        T::ONE / (hi.z - lo.z),
    )
}

/// `p` in the coordinates of the box `[lo, hi]` (the box is `[0, 1]³`
/// there; exact at the faces).
#[inline(always)]
pub(crate) fn to_local<T: Real>(p: Vec3<T>, lo: Vec3<T>, hi: Vec3<T>) -> Vec3<T> {
    Vec3::new(
        (p.x - lo.x) / (hi.x - lo.x),
        (p.y - lo.y) / (hi.y - lo.y),
        (p.z - lo.z) / (hi.z - lo.z),
    )
}

/// Finite corners with `lo < hi` on every axis and a finite extent whose
/// reciprocal is finite too.
pub(crate) fn valid_box<T: Real>(lo: Vec3<T>, hi: Vec3<T>) -> bool {
    let axis = |a: T, b: T| {
        let e = b - a;
        a.is_finite() && b.is_finite() && e > T::ZERO && e.is_finite() && (T::ONE / e).is_finite()
    };
    axis(lo.x, hi.x) && axis(lo.y, hi.y) && axis(lo.z, hi.z)
}

/// `x ≥ 0`, false for NaN.
#[inline(always)]
fn non_negative<T: Real>(x: T) -> bool {
    x >= T::ZERO
}

/// The part `[t0, t1]` of `[t_min, t_max]` inside the unit cube (slab
/// method), or `None` if the ray misses it there.
pub fn clip_unit_cube<T: Real>(o: Vec3<T>, d: Vec3<T>, t_min: T, t_max: T) -> Option<(T, T)> {
    let (lo, hi) = (
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        Vec3::new(T::ONE, T::ONE, T::ONE),
    );
    clip_box(o, d, lo, hi, t_min, t_max)
}

/// The part `[t0, t1]` of `[t_min, t_max]` inside the box `[lo, hi]` (slab
/// method), or `None` if the ray misses it there. A direction component of
/// 0 keeps its axis only if the origin lies within that slab.
pub fn clip_box<T: Real>(
    o: Vec3<T>,
    d: Vec3<T>,
    lo: Vec3<T>,
    hi: Vec3<T>,
    t_min: T,
    t_max: T,
) -> Option<(T, T)> {
    clip(o, d, (lo, hi), t_min, t_max)
}

/// [`clip_box`], inlined where tracking clips each call's ray: called,
/// its vectors went through memory (a fifth of a short grid call's time,
/// measured from C).
#[inline(always)]
pub(crate) fn clip<T: Real>(
    o: Vec3<T>,
    d: Vec3<T>,
    (lo, hi): (Vec3<T>, Vec3<T>),
    t_min: T,
    t_max: T,
) -> Option<(T, T)> {
    // One axis at a time, not a loop over an array of the three: LLVM
    // kept that array on the stack and read each axis back with a 16-byte
    // load over two 8-byte stores, which store forwarding cannot serve
    // (16 % of a 1 x 1 x 64 grid call's samples, measured from C).
    let s = slab(o.x, d.x, (lo.x, hi.x), (t_min, t_max))?;
    let s = slab(o.y, d.y, (lo.y, hi.y), s)?;
    let (t0, t1) = slab(o.z, d.z, (lo.z, hi.z), s)?;
    if t0 < t1 { Some((t0, t1)) } else { None }
}

/// [`clip`] on one axis: `[t0, t1]` narrowed to the slab `[l, h]` of a ray
/// with origin coordinate `oc` and direction component `dc`; `None` when a
/// ray parallel to the slab lies outside it.
#[inline(always)]
fn slab<T: Real>(oc: T, dc: T, (l, h): (T, T), (t0, t1): (T, T)) -> Option<(T, T)> {
    // Both ends of the segment within the slab: `oc + dc t` rounds
    // monotonically in t, so every point between them, as the walk
    // computes it, lies within too, and the axis narrows nothing; its
    // division is skipped. A flight inside a box (t_max the caller's own
    // boundary) skips two of the three (2–3 % of a 1 × 1 × 64 grid photon
    // from Rust, 1–2 % from C; Intel Xeon, family 6 model 167). A NaN or
    // infinite end (t_max = ∞) fails the test and takes the division.
    let (a, b) = (oc + dc * t0, oc + dc * t1);
    if (a >= l) & (a <= h) & (b >= l) & (b <= h) {
        return Some((t0, t1));
    }
    let inv = T::ONE / dc;
    if dc == T::ZERO || !inv.is_finite() {
        // Parallel to the faces, or so nearly that 1/dc overflows (a
        // subnormal component): the ray cannot cross the slab over any
        // representable distance. With the overflow taken as a crossing,
        // an origin on a face gave 0·∞ = NaN and a miss of the whole box.
        return (oc >= l && oc <= h).then_some((t0, t1));
    }
    let (a, b) = ((l - oc) * inv, (h - oc) * inv);
    let (near, far) = if a < b { (a, b) } else { (b, a) };
    Some((t0.max_of(near), if far < t1 { far } else { t1 }))
}

/// `σ_t` at `p` from the caller, checked against the majorant.
#[inline(always)]
fn checked<T: Real>(sigma_t: T, sigma_maj: T) -> Result<T, Error> {
    if sigma_t >= T::ZERO && sigma_t <= sigma_maj {
        Ok(sigma_t)
    } else {
        Err(Error::Domain)
    }
}

/// `σ_t` at a point, as the walks read it: a trait with an inlined
/// method, so that a grid's lookup is inlined into the walk and its point
/// stays in registers (as a closure it was left out of line in the C
/// library's tracking call, 22 % of a 1 x 1 x 64 grid call's samples).
/// Closures implement it too.
trait SigmaT<T> {
    fn at(&self, p: Vec3<T>) -> T;
}

impl<T, F: Fn(Vec3<T>) -> T> SigmaT<T> for F {
    #[inline(always)]
    fn at(&self, p: Vec3<T>) -> T {
        self(p)
    }
}

/// A grid's `σ_t = (σ_a + σ_s) × density`.
struct GridSigmaT<'g, 'a, T>(&'g Grid<'a, T>);

impl<T: Real> SigmaT<T> for GridSigmaT<'_, '_, T> {
    #[inline(always)]
    fn at(&self, p: Vec3<T>) -> T {
        (self.0.sigma_a + self.0.sigma_s) * self.0.density_inside(p)
    }
}

/// Walks the tentative collisions of majorant `sigma_maj` over `[t0, t1]`
/// (the loop delta and ratio tracking share): at each, `visit(t, σ_t, rng)`
/// may end the walk with a result. `Ok(None)` when the walk leaves the
/// interval, [`Error::Domain`] for a σ_t outside `[0, σ_maj]`,
/// [`Error::Budget`] after `budget` tentative collisions. Also returns how
/// many it drew.
#[inline(always)]
fn tentative<T: Real, R: Rng + ?Sized, X>(
    sigma_t: impl SigmaT<T>,
    Rate(sigma_maj, inv): Rate<T>,
    (o, d): (Vec3<T>, Vec3<T>),
    (t0, t1, budget): (T, T, u32),
    rng: &mut R,
    mut visit: impl FnMut(T, T, &mut R) -> Option<X>,
) -> Result<(Option<X>, u32), Error> {
    let mut t = t0;
    // Bounded: every pass that does not return counts a step, and the
    // walk ends once `budget` of them are taken (as the majorant walk's).
    // A counter, not `0..=budget`: the inclusive range kept its end flag
    // and count on the stack (75 instructions of a 1 × 1 × 64 grid
    // photon's 3400 from C, callgrind).
    let mut steps = 0;
    loop {
        t += exponential_step(inv, T::uniform(rng));
        if t.is_nan() || t >= t1 {
            return Ok((None, steps));
        }
        if steps == budget {
            return Err(Error::Budget);
        }
        steps += 1;
        let st = checked(sigma_t.at(o + d * t), sigma_maj)?;
        if let Some(x) = visit(t, st, rng) {
            return Ok((Some(x), steps));
        }
    }
}

/// A majorant `σ_maj` and its reciprocal `1/σ_maj` (computed as
/// [`Rate::of`] does, so that a stored one steps as a fresh one).
#[derive(Clone, Copy)]
struct Rate<T>(T, T);

impl<T: Real> Rate<T> {
    fn of(sigma_maj: T) -> Self {
        Rate(sigma_maj, T::ONE / sigma_maj)
    }
}

/// Delta tracking over `[t0, t1]`: `(t, true)` at a real collision (chosen
/// with probability `σ_t/σ_maj` at each tentative one), or `(t1, false)`.
#[inline(always)]
fn delta<T: Real, R: Rng + ?Sized>(
    sigma_t: impl SigmaT<T>,
    rate: Rate<T>,
    o: Vec3<T>,
    d: Vec3<T>,
    (t0, t1, budget): (T, T, u32),
    rng: &mut R,
) -> Result<(T, bool, u32), Error> {
    let sigma_maj = rate.0;
    if sigma_maj.is_nan() || sigma_maj <= T::ZERO {
        return Ok((t1, false, 0));
    }
    let real = |t: T, st: T, r: &mut R| (T::uniform(r) * sigma_maj < st).then_some(t);
    let (hit, steps) = tentative(sigma_t, rate, (o, d), (t0, t1, budget), rng, real)?;
    Ok(hit.map_or((t1, false, steps), |t| (t, true, steps)))
}

/// Below this weight ratio tracking plays Russian roulette (pbrt-v4's rule
/// for transmittance: a weight under 0.05 survives with probability 1/4
/// and is then multiplied by 4, so its expectation is unchanged).
pub(crate) const ROULETTE_BELOW: f64 = 0.05;

/// The roulette's outcome for a weight under [`ROULETTE_BELOW`]: 4 with
/// probability 1/4, else 0 (one uniform).
#[inline(always)]
pub(crate) fn roulette_factor<T: Real, R: Rng + ?Sized>(rng: &mut R) -> T {
    if T::uniform(rng) < T::from_f64(0.25) {
        T::from_f64(4.0)
    } else {
        T::ZERO
    }
}

/// Ratio tracking's weight `tr` after the roulette: unchanged at or above
/// [`ROULETTE_BELOW`], else times [`roulette_factor`].
#[inline(always)]
pub(crate) fn roulette<T: Real, R: Rng + ?Sized>(tr: T, rng: &mut R) -> T {
    if tr < T::from_f64(ROULETTE_BELOW) {
        tr * roulette_factor(rng)
    } else {
        tr
    }
}

/// Ratio tracking over `[t0, t1]`: the product of `1 − σ_t/σ_maj` at the
/// tentative collisions, with Russian roulette once it falls below
/// [`ROULETTE_BELOW`]. Without it, wherever `σ_maj > 2σ_t` the product
/// decays to the smallest subnormal, rounds back onto it at every step and
/// never reaches 0, so the walk ran on to `t1` or the step cap; with it the
/// walk ends a few steps after the transmittance is gone (an expected
/// `1/(1 − 1/4)` roulette draws), and the estimate stays unbiased.
fn ratio<T: Real, R: Rng + ?Sized>(
    sigma_t: impl SigmaT<T>,
    rate: Rate<T>,
    o: Vec3<T>,
    d: Vec3<T>,
    span: (T, T, u32),
    rng: &mut R,
) -> Result<(T, u32), Error> {
    let sigma_maj = rate.0;
    if sigma_maj.is_nan() || sigma_maj <= T::ZERO {
        return Ok((T::ONE, 0));
    }
    let mut tr = T::ONE;
    let (_, steps) = tentative(sigma_t, rate, (o, d), span, rng, |_, st, r| {
        tr = roulette(tr * (T::ONE - st / sigma_maj), r);
        (tr == T::ZERO).then_some(())
    })?;
    Ok((tr, steps))
}

/// Validates the majorant of the callback versions.
fn check_majorant<T: Real>(sigma_maj: T) -> Result<(), Error> {
    if sigma_maj >= T::ZERO && sigma_maj.is_finite() {
        Ok(())
    } else {
        Err(Error::Domain)
    }
}

/// Delta tracking through a caller's medium: `sigma_t(p)` gives σ_t at a
/// point (it must stay in `[0, sigma_maj]`), along `ray`. Returns the
/// distance and [`Event::Collided`] or [`Event::Escaped`] (at
/// `ray.t_max`). [`Error::Domain`] for a bad ray or majorant
/// or a density outside `[0, sigma_maj]` met on the way (reported, not
/// clamped: clamping would bias); [`Error::Budget`] at [`MAX_STEPS`].
pub fn delta_track_fn<T: Real, R: Rng + ?Sized>(
    sigma_t: impl Fn(Vec3<T>) -> T,
    sigma_maj: T,
    ray: Ray<T>,
    rng: &mut R,
) -> Result<(T, Event), Error> {
    let (o, d) = ray.checked()?;
    check_majorant(sigma_maj)?;
    let (t_min, t_max) = (ray.t_min, ray.t_max);
    let span = (t_min, t_max, MAX_STEPS);
    let (t, hit, _) = delta(sigma_t, Rate::of(sigma_maj), o, d, span, rng)?;
    Ok(if hit {
        (t, Event::Collided)
    } else {
        (t_max, Event::Escaped)
    })
}

/// Ratio tracking through a caller's medium (arguments as
/// [`delta_track_fn`]): an unbiased transmittance estimate along `ray`,
/// with the roulette of [`Grid::ratio_track`]. [`Error::Domain`] for a bad
/// ray or majorant or a density
/// outside `[0, sigma_maj]`; [`Error::Budget`] at [`MAX_STEPS`].
pub fn ratio_track_fn<T: Real, R: Rng + ?Sized>(
    sigma_t: impl Fn(Vec3<T>) -> T,
    sigma_maj: T,
    ray: Ray<T>,
    rng: &mut R,
) -> Result<T, Error> {
    let (o, d) = ray.checked()?;
    check_majorant(sigma_maj)?;
    let span = (ray.t_min, ray.t_max, MAX_STEPS);
    ratio(sigma_t, Rate::of(sigma_maj), o, d, span, rng).map(|(tr, _)| tr)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::SeedableRng;

    /// `u_channel = 1` picks the last channel, as `u_channel` just below 1
    /// does (a mutation test found the clamp of the index untested: without
    /// it the channel was one past the end, its σ_t NaN, and the sample a
    /// silent surface event).
    #[test]
    fn a_channel_uniform_of_one_picks_the_last_channel() {
        let (sigma_t, sigma_s) = ([1.0, 2.0, 4.0], [0.5, 1.0, 2.0]);
        let mut w = [0.0; 3];
        let mut w_below = [0.0; 3];
        let last = homogeneous_sample(&sigma_t, &sigma_s, 10.0, 1.0, 0.5, &mut w).unwrap();
        let below = homogeneous_sample(&sigma_t, &sigma_s, 10.0, 0.999, 0.5, &mut w_below);
        assert_eq!(Ok(last), below);
        assert_eq!(w, w_below);
        assert!(last.scattered && last.t == free_path(4.0, 0.5));
    }

    /// A sample that reaches `t_max` is the surface event, also when both
    /// are +∞ (a channel of σ_t = 0 in an unbounded medium), and where
    /// every channel's transmittance has underflowed to 0 the weights are
    /// 0, as documented (a mutation test found both untested: `dist <
    /// t_max` → `≤` reported a scattering at +∞, `pdf > 0` → `≥ 0` gave
    /// NaN weights).
    #[test]
    fn reaching_t_max_is_the_surface_and_no_density_weighs_nothing() {
        let mut w = [f64::NAN; 2];
        let inf = f64::INFINITY;
        let s = homogeneous_sample(&[0.0, 1.0], &[0.0, 0.5], inf, 0.0, 0.5, &mut w).unwrap();
        assert_eq!(
            s,
            HomogeneousSample {
                t: inf,
                scattered: false
            }
        );
        // Tr = (1, 0), mean 1/2.
        assert_eq!(w, [2.0, 0.0]);
        // u_dist = 1: no collision before t_max = 1000, where e^{−1000}
        // and e^{−2000} are 0.
        let mut w = [f64::NAN; 2];
        let s = homogeneous_sample(&[1.0, 2.0], &[0.5, 1.0], 1000.0, 0.0, 1.0, &mut w).unwrap();
        assert!(!s.scattered && s.t == 1000.0);
        assert_eq!(w, [0.0, 0.0]);
    }

    /// A grid of σ_s = 0 never scatters, even where the event's uniform is
    /// 0 (it scatters with probability σ_s/σ_t: `u < albedo`, which `u ≤
    /// albedo`, a mutation test's, broke at 0); a ray leaving through the
    /// face it starts on crosses nothing, escapes, and draws nothing (the
    /// clip's empty span, `t0 < t1` → `≤`, was tracked over with a draw).
    #[test]
    fn an_absorbing_grid_never_scatters_and_an_empty_crossing_draws_nothing() {
        use rand_xoshiro::rand_core::Rng as _;
        let density = [1.0f64; 8];
        let absorbing = Grid::new(&density, 2, 2, 2, 1.0, 0.0).unwrap();
        let up = Vec3::new(0.0, 0.0, 1.0);
        let ray = Ray::new(Vec3::new(0.5, 0.5, 0.5), up, 10.0);
        // Every uniform 0: a collision where the ray starts.
        let hit = absorbing.delta_track(ray, &mut Script(&[])).unwrap();
        assert_eq!(hit, (0.0, Event::Absorbed));
        let on_top = Ray::new(Vec3::new(0.5, 0.5, 1.0), up, 10.0);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        let mut untouched = rng.clone();
        let hit = absorbing.delta_track(on_top, &mut rng).unwrap();
        assert_eq!(hit, (10.0, Event::Escaped));
        assert_eq!(rng.next_u64(), untouched.next_u64());
    }

    /// A generator giving the words of its script in turn (then 0).
    struct Script<'a>(&'a [u64]);

    impl rand_core::TryRng for Script<'_> {
        type Error = core::convert::Infallible;
        fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
            self.try_next_u64().map(|x| (x >> 32) as u32)
        }
        fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
            let (&x, rest) = self.0.split_first().unwrap_or((&0, &[]));
            self.0 = rest;
            Ok(x)
        }
        fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
            dst.fill(0);
            Ok(())
        }
    }

    /// Where σ_t = 0 nothing collides, even at a uniform of 0 (a real
    /// collision is `u σ_maj < σ_t`; a mutation test's `≤` collided in a
    /// vacuum), and a majorant of 0 (a grid of zero density) is crossed by
    /// delta and ratio tracking without a draw (`σ_maj` NaN `||` `≤ 0` →
    /// `&&`, a mutation test's, drew one).
    #[test]
    fn nothing_collides_where_there_is_nothing() {
        // σ_t rises from 0 at z = 0 to 2 at z = 1; the ray runs along the
        // face z = 0. Draws: a step of 0, an acceptance uniform of 0, then
        // a step of 36.7 mean free paths, past the box.
        let rising = [0.0f64, 1.0];
        let grid = Grid::new(&rising, 1, 1, 2, 1.0, 1.0).unwrap();
        let along = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::new(1.0, 0.0, 0.0), 10.0);
        let hit = grid.delta_track(along, &mut Script(&[0, 0, u64::MAX]));
        assert_eq!(hit, Ok((10.0, Event::Escaped)));
        let none = [0.0f64; 8];
        let vacuum = Grid::new(&none, 2, 2, 2, 1.0, 1.0).unwrap();
        let ray = Ray::new(Vec3::new(0.5, 0.5, 0.5), Vec3::new(0.0, 0.0, 1.0), 10.0);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        let mut untouched = rng.clone();
        assert_eq!(
            vacuum.delta_track(ray, &mut rng),
            Ok((10.0, Event::Escaped))
        );
        assert_eq!(vacuum.ratio_track(ray, &mut rng), Ok(1.0));
        use rand_xoshiro::rand_core::Rng as _;
        assert_eq!(rng.next_u64(), untouched.next_u64());
    }

    /// An escape: `delta_track` reports `t_max`, `delta_track_within`
    /// where the ray leaves the box (the segment clipped to it, `t_min` for
    /// a miss), as the majorant walk does, with the same draws; in a vacuum
    /// (no tentative collision) and in a thin medium (the walk steps past
    /// the box). The C layer reports the second for every medium; its grid
    /// route reported `t_max`.
    #[test]
    fn an_escape_within_reports_where_the_ray_leaves_the_box() {
        let below = Vec3::new(0.5, 0.5, -1.0);
        // (origin, t_max, where the clipped segment ends).
        let cases = [
            (Vec3::new(0.5, 0.5, 0.5), 10.0, 0.5),
            (below, 10.0, 2.0),
            (below, 1.5, 1.5),
            (Vec3::new(5.0, 0.5, -1.0), 10.0, 0.125),
        ];
        for value in [0.0f64, 1e-9] {
            let values = [value; 8];
            let grid = Grid::new(&values, 2, 2, 2, 0.0, 1.0).unwrap();
            let ((lo, hi), one) = (grid.bounds(), [grid.majorant()]);
            let maj = majorant::Majorants::new(&one, [1; 3], lo, hi).unwrap();
            for (o, t_max, exit) in cases {
                let ray = Ray::new(o, Vec3::new(0.0, 0.0, 1.0), t_max).segment(0.125, t_max);
                let mut a = Xoshiro256PlusPlus::seed_from_u64(3);
                let (mut b, mut c) = (a.clone(), a.clone());
                let within = grid.delta_track_within(ray, MAX_STEPS, &mut a).unwrap();
                assert_eq!((within.t, within.event), (exit, Event::Escaped), "{o:?}");
                assert_eq!(grid.delta_track(ray, &mut b), Ok((t_max, Event::Escaped)));
                let walked = maj.delta_track(&grid, ray, MAX_STEPS, &mut c).unwrap();
                assert_eq!((walked.t, walked.event), (exit, Event::Escaped), "{o:?}");
            }
        }
    }

    /// The public lookups as documented (a mutation test found three
    /// untested): a NaN in any one coordinate gives NaN; a slab one value
    /// thick in y or in x (not a column) interpolates as the same values
    /// repeated across its thickness do; `sigma_t` is `(σ_a + σ_s)·density`.
    #[test]
    fn the_public_lookups_follow_the_docs() {
        // Values x fastest: (x, z) = (0, 0) 1, (1, 0) 3, (0, 1) 2, (1, 1) 7.
        let slab = [1.0, 3.0, 2.0, 7.0];
        let repeated = [1.0, 3.0, 1.0, 3.0, 2.0, 7.0, 2.0, 7.0];
        let thin = Grid::new(&slab, 2, 1, 2, 0.25, 0.5).unwrap();
        let full = Grid::new(&repeated, 2, 2, 2, 0.25, 0.5).unwrap();
        let repeated_y = [1.0, 1.0, 3.0, 3.0, 2.0, 2.0, 7.0, 7.0];
        let thin_y = Grid::new(&slab, 1, 2, 2, 0.25, 0.5).unwrap();
        let full_y = Grid::new(&repeated_y, 2, 2, 2, 0.25, 0.5).unwrap();
        for p in [
            [0.3, 0.5, 0.6],
            [0.9, 0.1, 0.2],
            [0.0, 1.0, 1.0],
            [0.7, 0.4, 0.0],
        ] {
            let p = Vec3::new(p[0], p[1], p[2]);
            assert_eq!(thin.density(p), full.density(p), "{p:?}");
            assert!(thin.density(p) > 1.0);
            assert_eq!(thin.sigma_t(p), 0.75 * thin.density(p));
            // The same slab turned to vary in y, one cell in x.
            let q = Vec3::new(p.y, p.x, p.z);
            assert_eq!(thin_y.density(q), full_y.density(q), "{q:?}");
            assert_eq!(thin_y.density(q), thin.density(p), "{q:?}");
        }
        let m = 0.5;
        for p in [[f64::NAN, m, m], [m, f64::NAN, m], [m, m, f64::NAN]] {
            assert!(thin.density(Vec3::new(p[0], p[1], p[2])).is_nan());
        }
    }

    /// The f32 logarithm of targets without hardware doubles, checked on
    /// every host (a mutation test found its sign untested where doubles
    /// are fast and the path is not taken): within 2ε relative of the f64
    /// `ln(1 − u)` at every `u = k/4096` and at `1 − 2⁻ʲ`, and 0 at `u = 0`.
    #[test]
    fn the_narrow_logarithm_is_ln_of_one_minus_u() {
        let us = (0..4096)
            .map(|k| k as f32 / 4096.0)
            .chain((1..24).map(|j| 1.0 - (-(j as f32)).exp2()));
        for u in us {
            let got = ln_1m_narrow(u);
            let want = libm::log1p(-(u as f64));
            let ulp = f32::EPSILON as f64 * want.abs().max(f32::MIN_POSITIVE as f64);
            assert!(
                (got as f64 - want).abs() <= 2.0 * ulp,
                "u = {u}: {got} against {want}"
            );
        }
        assert_eq!(ln_1m_narrow(0.0f32), 0.0);
    }

    /// Each route of `ln_1m` is the one its docs give, on hosts with and
    /// without hardware doubles: f64 always takes the f64 table; f32 takes
    /// it rounded once to f32 where doubles are fast, else `log1pf`. The
    /// same bits at every `u = k/2¹⁶` (mutation tests found nothing telling
    /// the routes apart: `||` → `&&`, and `size_of == 8` → `≠ 8`, which on
    /// a host without hardware doubles sends f64 through `log1pf`).
    #[test]
    fn each_logarithm_route_is_the_documented_one() {
        for k in 0..1u32 << 16 {
            let u = k as f32 / 65536.0;
            let table = crate::math::log::ln_1m(u as f64);
            for wide in [false, true] {
                assert_eq!(ln_1m_on(u as f64, wide).to_bits(), table.to_bits());
            }
            assert_eq!(ln_1m_on(u, true).to_bits(), (table as f32).to_bits());
            assert_eq!(ln_1m_on(u, false).to_bits(), ln_1m_narrow(u).to_bits());
            let here = if crate::math::log::WIDE {
                table as f32
            } else {
                ln_1m_narrow(u)
            };
            assert_eq!(ln_1m(u).to_bits(), here.to_bits(), "u = {u}");
        }
    }

    /// A direction within 4 ulp of unit length is taken bit for bit (no
    /// rescaling moves it), and one further off is normalised (a mutation
    /// test found no test reading which).
    #[test]
    fn a_nearly_unit_direction_is_kept_and_others_normalised() {
        let o = Vec3::new(0.0f64, 0.0, 0.0);
        let near = Vec3::new(1.0 + f64::EPSILON, 0.0, 0.0);
        let (_, d) = Ray::new(o, near, 1.0).checked().unwrap();
        assert_eq!(d.x.to_bits(), near.x.to_bits());
        let (_, d) = Ray::new(o, Vec3::new(2.0, 0.0, 0.0), 1.0)
            .checked()
            .unwrap();
        assert_eq!(d.x, 1.0);
    }

    /// The step count the C API reports (`sk_track_result.steps`) is the
    /// number of tentative collisions drawn: in a grid whose density sits
    /// at its majorant every tentative collision is real, so delta
    /// tracking ends at its first and counts 1 (a mutation test found no
    /// test reading the count on a hit).
    #[test]
    fn a_hit_counts_its_tentative_collision() {
        let density = [1.0f64; 8];
        let g = Grid::new(&density, 2, 2, 2, 0.0, 50.0).unwrap();
        let ray = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::new(0.0, 0.0, 1.0), 1.0);
        for seed in 0..16 {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            let x = g.delta_track_within(ray, 100, &mut rng).unwrap();
            assert_eq!(
                (x.event, x.steps),
                (Event::Scattered, 1),
                "seed {seed}, t {}",
                x.t
            );
        }
    }

    /// Tracking's lookup (`density_inside`, no NaN or box tests) reads the
    /// bits of [`Grid::density`] at every point inside a box away from
    /// the origin and of extent other than 1 (where a wrong local
    /// coordinate shows), for nodes and cell centres, columns and full
    /// grids, and the face's value a rounding outside it (a mutation test
    /// of the new lookup found no test reading it in such a box).
    #[test]
    fn tracking_reads_the_density_the_lookup_gives() {
        let values: [f64; 30] = core::array::from_fn(|k| 0.5 + libm::sin(k as f64 * 0.61).abs());
        let (lo, hi) = (Vec3::new(-2.0, 0.5, -1.0), Vec3::new(3.0, 0.75, 4.0));
        let mut r = Xoshiro256PlusPlus::seed_from_u64(9);
        for (n, len) in [([3, 2, 5], 30), ([1, 1, 5], 5)] {
            for sampling in [Sampling::Nodes, Sampling::Cells] {
                let g = Grid::new(&values[..len], n[0], n[1], n[2], 0.3, 1.1)
                    .and_then(|g| g.with_box(lo, hi))
                    .unwrap()
                    .with_sampling(sampling);
                let at = |a: f64, b: f64, u: f64| a + (b - a) * u;
                for _ in 0..20_000 {
                    let (u, v, w) = (
                        f64::uniform(&mut r),
                        f64::uniform(&mut r),
                        f64::uniform(&mut r),
                    );
                    let p = Vec3::new(at(lo.x, hi.x, u), at(lo.y, hi.y, v), at(lo.z, hi.z, w));
                    assert_eq!(
                        g.density_inside(p).to_bits(),
                        g.density(p).to_bits(),
                        "{p:?}"
                    );
                }
                let past = Vec3::new(hi.x.next_up(), lo.y.next_down(), hi.z.next_up());
                assert_eq!(
                    g.density_inside(past),
                    g.density(Vec3::new(hi.x, lo.y, hi.z))
                );
            }
        }
    }

    /// The kept majorant is `σ_t max(density)` raised by a few ULP (at
    /// most 8ε relative), its reciprocal is `1/majorant`, and a vacuum's
    /// albedo is 0, not 0/0 (mutation tests found a majorant raised by 1
    /// and a NaN albedo unread: tracking stays unbiased with either).
    #[test]
    fn the_kept_majorant_and_albedo_are_as_documented() {
        let density = [0.25f64, 3.0, 1.5];
        for (sa, ss) in [(0.5, 2.0), (0.0, 1e-3), (7.0, 0.0), (1e3, 1e3)] {
            let g = Grid::new(&density, 1, 1, 3, sa, ss).unwrap();
            let floor = (sa + ss) * 3.0;
            let m = g.majorant();
            assert!(
                m >= floor && m <= floor * (1.0 + 8.0 * f64::EPSILON),
                "{sa} {ss}: {m}"
            );
            assert_eq!(g.rate().1, 1.0 / m);
            assert_eq!(g.albedo(), ss / (sa + ss));
            let parts = Grid::from_parts(
                &density,
                [1, 1, 3],
                sa,
                ss,
                3.0,
                g.bounds(),
                Sampling::Nodes,
            );
            assert_eq!(parts.unwrap(), g);
        }
        let vacuum = Grid::new(&density, 1, 1, 3, 0.0, 0.0).unwrap();
        assert_eq!((vacuum.majorant(), vacuum.albedo()), (0.0, 0.0));
    }

    /// A zero dimension on any axis is refused ([`Error::Size`]), alone or
    /// beside others (a mutation test turned `||` into `&&` unnoticed: a
    /// grid of no values was then built, and its lookups read past it).
    #[test]
    fn a_zero_dimension_is_refused_on_every_axis() {
        let density = [1.0f64; 4];
        for n in [[0, 2, 2], [2, 0, 2], [2, 2, 0], [0, 0, 1], [0, 0, 0]] {
            assert_eq!(grid_len(n[0], n[1], n[2]), None, "{n:?}");
            let g = Grid::new(&density, n[0], n[1], n[2], 0.0, 1.0);
            assert_eq!(g.err(), Some(Error::Size), "{n:?}");
        }
        assert_eq!(grid_len(1, 2, 2), Some(4));
        assert_eq!(grid_len(usize::MAX, 2, 1), None);
    }

    /// The clip keeps a segment whose ends are inside the box and cuts one
    /// that leaves it at the face it crosses, on each axis, from inside
    /// and from outside.
    #[test]
    fn a_segment_is_kept_inside_the_box_and_cut_where_it_leaves() {
        let (lo, hi) = (Vec3::new(-1.0, -2.0, 0.0), Vec3::new(1.0, 2.0, 4.0));
        let o = Vec3::new(0.0, 0.0, 2.0);
        let axes = [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        for (k, d) in axes.into_iter().enumerate() {
            let half = [1.0, 2.0, 2.0][k];
            for s in [1.0, -1.0] {
                let d = d * s;
                // Inside to inside, inside to the face, inside to beyond.
                assert_eq!(clip_box(o, d, lo, hi, 0.25, 0.5), Some((0.25, 0.5)));
                assert_eq!(clip_box(o, d, lo, hi, 0.0, half), Some((0.0, half)));
                assert_eq!(clip_box(o, d, lo, hi, 0.0, 10.0), Some((0.0, half)));
                // From beyond the far face back in, and wholly outside.
                let far = o + d * 10.0;
                assert_eq!(
                    clip_box(far, d * -1.0, lo, hi, 0.0, 12.0),
                    Some((10.0 - half, 10.0 + half))
                );
                assert_eq!(clip_box(far, d, lo, hi, 0.0, 12.0), None);
            }
        }
        // An oblique segment leaving through x while y stays inside.
        let d = Vec3::new(0.6, 0.8, 0.0);
        let (t0, t1) = clip_box(o, d, lo, hi, 0.0, 10.0).unwrap();
        assert_eq!(t0, 0.0);
        assert!((t1 - 1.0 / 0.6).abs() < 1e-15, "{t1}");
    }

    /// A unit direction may have a subnormal component, whose reciprocal
    /// overflows: from an origin on that axis's face, `0·∞` made the clip
    /// miss the whole box (optical depth 0, every ray escaping). The ray
    /// cannot leave the slab over any representable distance, so it is
    /// taken as parallel to it.
    #[test]
    fn a_subnormal_direction_component_from_a_face_still_crosses_the_box() {
        let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
        for (x, dx) in [(0.0, 1e-310), (1.0, -1e-310), (0.0, -1e-310), (0.5, 1e-320)] {
            let (o, d) = (Vec3::new(x, 0.5, 0.0), Vec3::new(dx, 0.0, 1.0));
            assert_eq!(
                clip_box(o, d, lo, hi, 0.0, 10.0),
                Some((0.0, 1.0)),
                "{x} {dx}"
            );
        }
        let (lo32, hi32) = (Vec3::new(0.0f32, 0.0, 0.0), Vec3::new(1.0f32, 1.0, 1.0));
        let (o, d) = (Vec3::new(0.0f32, 0.5, 0.0), Vec3::new(1e-40f32, 0.0, 1.0));
        assert_eq!(clip_box(o, d, lo32, hi32, 0.0, 10.0), Some((0.0, 1.0)));
        let density = [2.0f64];
        let g = Grid::new(&density, 1, 1, 1, 0.0, 1.0).unwrap();
        let ray = Ray::new(Vec3::new(0.0, 0.5, 0.0), Vec3::new(1e-310, 0.0, 1.0), 10.0);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        let hits = (0..1000)
            .filter(|_| g.delta_track(ray, &mut rng).unwrap().1 != Event::Escaped)
            .count();
        // P(hit) = 1 − e⁻² ≈ 0.865; 1000 draws: σ ≈ 11.
        assert!((800..=930).contains(&hits), "{hits}");
    }
}
