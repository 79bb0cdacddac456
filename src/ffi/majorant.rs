//! Majorant grids and tracking through them.

use super::medium::{GridStore, load};
use super::{CFn, CRng, CVec, bind, sk_rng, sk_status, sk_vec3, sk_vec3_f64, slice_in, slice_out};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Majorants, Track, Transmittance, majorant_len};
use crate::medium::{Grid, Ray};
use core::ffi::c_void;

/// A grid of majorants (sigma_maj per length unit, >= 0) over a world box,
/// one per cell of an mx*my*mz division of it, borrowing the caller's array
/// (x fastest), which must outlive it. Build it with sk_majorants_build
/// (from a grid) or sk_majorants_new (your own bounds); the fields are what
/// that validated. Every value is checked there, once: a call checks only
/// the fields (constant time, whatever the size of the grid), and a walk
/// reports a value changed since (negative, NaN or infinite) as
/// SK_ERR_DOMAIN when it reaches its cell.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_majorants {
    /// The caller's majorants.
    pub sigma: *const f32,
    /// Cells along x.
    pub mx: u32,
    /// Cells along y.
    pub my: u32,
    /// Cells along z.
    pub mz: u32,
    /// The world box's low corner.
    pub lo: sk_vec3,
    /// The world box's high corner.
    pub hi: sk_vec3,
}

/// A grid of majorants (double); see `sk_majorants`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_majorants_f64 {
    /// The caller's majorants.
    pub sigma: *const f64,
    /// Cells along x.
    pub mx: u32,
    /// Cells along y.
    pub my: u32,
    /// Cells along z.
    pub mz: u32,
    /// The world box's low corner.
    pub lo: sk_vec3_f64,
    /// The world box's high corner.
    pub hi: sk_vec3_f64,
}

/// What delta tracking through majorants found.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_track_result {
    /// Distance along d/|d|: of the real collision, or for
    /// SK_TRACK_ESCAPED where the ray leaves the medium's box (within
    /// [t_min, t_max]; t_min if it never enters the box).
    pub t: f32,
    /// An sk_track_event: ESCAPED, SCATTERED or ABSORBED.
    pub event: u32,
    /// Tentative collisions drawn (density evaluations), the real one
    /// included: the cost of the walk.
    pub steps: u32,
}

/// What delta tracking through majorants found (double); see `sk_track_result`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_track_result_f64 {
    /// As in `sk_track_result`.
    pub t: f64,
    /// An sk_track_event.
    pub event: u32,
    /// Tentative collisions drawn.
    pub steps: u32,
}

/// What ratio tracking through majorants found.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_ratio_result {
    /// The unbiased transmittance estimate (>= 0; Russian roulette can raise
    /// one estimate above the true value).
    pub tr: f32,
    /// Tentative collisions drawn (density evaluations).
    pub steps: u32,
}

/// What ratio tracking through majorants found (double).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_ratio_result_f64 {
    /// As in `sk_ratio_result`.
    pub tr: f64,
    /// Tentative collisions drawn.
    pub steps: u32,
}

/// Absorption and scattering coefficients at a point (per length unit).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_coefficients {
    /// sigma_a >= 0.
    pub sigma_a: f32,
    /// sigma_s >= 0.
    pub sigma_s: f32,
}

/// Absorption and scattering coefficients (double).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_coefficients_f64 {
    /// sigma_a >= 0.
    pub sigma_a: f64,
    /// sigma_s >= 0.
    pub sigma_s: f64,
}

/// The caller's medium for tracking through majorants: sigma_a and sigma_s
/// at point p, both >= 0 with a sum within the majorant of the cell holding
/// p. Tracking decides absorption, scattering or a null collision itself.
pub type sk_medium_fn =
    Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3) -> sk_coefficients>;
/// The caller's medium (double); see `sk_medium_fn`.
pub type sk_medium_fn_f64 =
    Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3_f64) -> sk_coefficients_f64>;

/// A C majorant type, its float and the C result types of its precision.
pub(crate) trait MajStore: Copy {
    type T: Real;
    type V: CVec<T = Self::T>;
    type Track: Copy;
    type Tr: Copy;
    type Coef: Copy;
    fn pack(sigma: *const Self::T, m: [u32; 3], lo: Self::V, hi: Self::V) -> Self;
    fn unpack(&self) -> (*const Self::T, [u32; 3], Self::V, Self::V);
    fn track(t: Track<Self::T>) -> Self::Track;
    fn tr(t: Transmittance<Self::T>) -> Self::Tr;
    fn pair(k: Self::Coef) -> (Self::T, Self::T);
}

macro_rules! impl_maj_store {
    ($c:ty, $t:ty, $v:ty, $track:ident, $tr:ident, $coef:ident) => {
        impl MajStore for $c {
            type T = $t;
            type V = $v;
            type Track = $track;
            type Tr = $tr;
            type Coef = $coef;
            fn pack(sigma: *const $t, m: [u32; 3], lo: $v, hi: $v) -> Self {
                Self {
                    sigma,
                    mx: m[0],
                    my: m[1],
                    mz: m[2],
                    lo,
                    hi,
                }
            }
            fn unpack(&self) -> (*const $t, [u32; 3], $v, $v) {
                (self.sigma, [self.mx, self.my, self.mz], self.lo, self.hi)
            }
            fn track(t: Track<$t>) -> $track {
                $track {
                    t: t.t,
                    event: t.event as u32,
                    steps: t.steps,
                }
            }
            fn tr(t: Transmittance<$t>) -> $tr {
                $tr {
                    tr: t.tr,
                    steps: t.steps,
                }
            }
            fn pair(k: $coef) -> ($t, $t) {
                (k.sigma_a, k.sigma_s)
            }
        }
    };
}
impl_maj_store!(
    sk_majorants,
    f32,
    sk_vec3,
    sk_track_result,
    sk_ratio_result,
    sk_coefficients
);
impl_maj_store!(
    sk_majorants_f64,
    f64,
    sk_vec3_f64,
    sk_track_result_f64,
    sk_ratio_result_f64,
    sk_coefficients_f64
);

/// `[m0, m1, m2]` as `usize`.
fn dims(m: [u32; 3]) -> [usize; 3] {
    m.map(|x| x as usize)
}

/// The Rust majorants behind a C value, in constant time: `Err` for NULL
/// or malformed fields. The values were checked when the majorants were
/// built; a walk reports one the caller changed since as `SK_ERR_DOMAIN`
/// when it reaches its cell (`Majorants::from_parts`), so a call costs the
/// same at 1 cell or 128^3.
pub(crate) unsafe fn load_maj<'a, S: MajStore>(
    m: *const S,
) -> Result<Majorants<'a, S::T>, sk_status> {
    // SAFETY: a non-NULL m points to majorants built by this library, whose
    // array holds mx*my*mz values (module contract).
    let (ptr, n, lo, hi) = unsafe { m.as_ref() }
        .ok_or(sk_status::SK_ERR_NULL)?
        .unpack();
    let count = majorant_len(dims(n)).ok_or(sk_status::SK_ERR_SIZE)?;
    let sigma = unsafe { slice_in(ptr, count) }?;
    Majorants::from_parts(sigma, dims(n), lo.to_vec(), hi.to_vec()).map_err(Into::into)
}

/// [`load_maj`] with every value checked (finite, `>= 0`), for the
/// constructors that take majorants: what they build is then checked once.
pub(crate) unsafe fn load_maj_checked<'a, S: MajStore>(
    m: *const S,
) -> Result<Majorants<'a, S::T>, sk_status> {
    let maj = unsafe { load_maj(m) }?;
    let (lo, hi) = maj.bounds();
    let (ptr, _, _, _) = unsafe { &*m }.unpack();
    let count = majorant_len(maj.dims()).ok_or(sk_status::SK_ERR_SIZE)?;
    let sigma = unsafe { slice_in(ptr, count) }?;
    Majorants::new(sigma, maj.dims(), lo, hi).map_err(Into::into)
}

/// Writes `Ok` values through `out` (checked non-NULL by the caller).
pub(super) unsafe fn write<V, X>(
    out: *mut V,
    r: Result<X, Error>,
    f: impl Fn(X) -> V,
) -> sk_status {
    match r {
        // SAFETY: the callers checked `out` for NULL.
        Ok(x) => unsafe {
            out.write(f(x));
            sk_status::SK_OK
        },
        Err(e) => e.into(),
    }
}

/// The caller's generator for a call that writes through `out`:
/// `SK_ERR_NULL` if either is NULL (or the generator's callback is).
pub(super) unsafe fn rng_for<V>(out: *mut V, rng: *mut sk_rng) -> Result<CRng, sk_status> {
    if out.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { CRng::from_ptr(rng) }.ok_or(sk_status::SK_ERR_NULL)
}

/// The grid behind a non-NULL `g`: `SK_ERR_SIZE` for a malformed one.
pub(super) unsafe fn grid_at<'a, G: GridStore>(g: *const G) -> Result<Grid<'a, G::T>, sk_status> {
    unsafe { load(g) }.ok_or(sk_status::SK_ERR_SIZE)
}

/// Writes what a tracking call found through `out` (as [`write`]), or
/// returns the status of the check that stopped it first.
pub(super) unsafe fn finish<V, X>(
    out: *mut V,
    found: Result<Result<X, Error>, sk_status>,
    f: impl Fn(X) -> V,
) -> sk_status {
    match found {
        Ok(r) => unsafe { write(out, r, f) },
        Err(e) => e,
    }
}

unsafe fn build<G: GridStore, S: MajStore<T = G::T, V = G::V>>(
    g: *const G,
    m: [u32; 3],
    out: *mut G::T,
    out_len: usize,
    maj_out: *mut S,
) -> sk_status {
    if g.is_null() || out.is_null() || maj_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(grid) = (unsafe { load(g) }) else {
        return sk_status::SK_ERR_SIZE;
    };
    let Some(count) = majorant_len(dims(m)) else {
        return sk_status::SK_ERR_SIZE;
    };
    if out_len < count {
        return sk_status::SK_ERR_SIZE;
    }
    let cells = match unsafe { slice_out(out, count) } {
        Ok(c) => c,
        Err(e) => return e,
    };
    let (lo, hi) = grid.bounds();
    let r = Majorants::build(&grid, dims(m), cells).map(|_| ());
    unsafe {
        write(maj_out, r, |()| {
            S::pack(out, m, G::V::from_vec(lo), G::V::from_vec(hi))
        })
    }
}

unsafe fn new_maj<S: MajStore>(
    sigma: *const S::T,
    m: [u32; 3],
    lo: S::V,
    hi: S::V,
    out: *mut S,
) -> sk_status {
    if sigma.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(count) = majorant_len(dims(m)) else {
        return sk_status::SK_ERR_SIZE;
    };
    let values = match unsafe { slice_in(sigma, count) } {
        Ok(v) => v,
        Err(e) => return e,
    };
    let r = Majorants::new(values, dims(m), lo.to_vec(), hi.to_vec()).map(|_| ());
    unsafe { write(out, r, |()| S::pack(sigma, m, lo, hi)) }
}

/// Delta or ratio tracking: the walk of `Majorants` each runs, through a
/// grid or a caller's medium, and the C result it writes.
trait Kind<S: MajStore> {
    /// What the walk returns.
    type Found;
    /// The C result it becomes.
    type Out;
    fn grid(w: Walk<'_, S::T>, g: &Grid<'_, S::T>) -> Result<Self::Found, Error>;
    fn func(
        w: Walk<'_, S::T>,
        f: &dyn Fn(Vec3<S::T>) -> (S::T, S::T),
    ) -> Result<Self::Found, Error>;
    fn out(x: Self::Found) -> Self::Out;
}

/// One walk's majorants, ray, budget and generator.
struct Walk<'a, T: Real> {
    m: &'a Majorants<'a, T>,
    ray: Ray<T>,
    budget: u32,
    rng: &'a mut CRng,
}

/// Delta tracking ([`Kind`]).
struct Delta;
/// Ratio tracking ([`Kind`]).
struct Ratio;

impl<S: MajStore> Kind<S> for Delta {
    type Found = Track<S::T>;
    type Out = S::Track;
    fn grid(w: Walk<'_, S::T>, g: &Grid<'_, S::T>) -> Result<Self::Found, Error> {
        w.m.delta_track(g, w.ray, w.budget, w.rng)
    }
    fn func(
        w: Walk<'_, S::T>,
        f: &dyn Fn(Vec3<S::T>) -> (S::T, S::T),
    ) -> Result<Self::Found, Error> {
        w.m.delta_track_fn(f, w.ray, w.budget, w.rng)
    }
    fn out(x: Self::Found) -> Self::Out {
        S::track(x)
    }
}

impl<S: MajStore> Kind<S> for Ratio {
    type Found = Transmittance<S::T>;
    type Out = S::Tr;
    fn grid(w: Walk<'_, S::T>, g: &Grid<'_, S::T>) -> Result<Self::Found, Error> {
        w.m.ratio_track(g, w.ray, w.budget, w.rng)
    }
    fn func(
        w: Walk<'_, S::T>,
        f: &dyn Fn(Vec3<S::T>) -> (S::T, S::T),
    ) -> Result<Self::Found, Error> {
        w.m.ratio_track_fn(f, w.ray, w.budget, w.rng)
    }
    fn out(x: Self::Found) -> Self::Out {
        S::tr(x)
    }
}

/// Tracking of kind `K` through grid `g` and its majorants `m` from `o`
/// along `d` over `[0, t_max]`, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn grid_track<K: Kind<S>, G: GridStore, S: MajStore<T = G::T, V = G::V>>(
    m: *const S,
    g: *const G,
    [o, d]: [G::V; 2],
    t_max: G::T,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut K::Out,
) -> sk_status {
    let found = || {
        if g.is_null() {
            return Err(sk_status::SK_ERR_NULL);
        }
        let mut r = unsafe { rng_for(out, rng) }?;
        let (maj, grid) = unsafe { (load_maj(m)?, grid_at(g)?) };
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max);
        let (m, rng) = (&maj, &mut r);
        Ok(K::grid(
            Walk {
                m,
                ray,
                budget,
                rng,
            },
            &grid,
        ))
    };
    unsafe { finish(out, found(), K::out) }
}

/// Tracking of kind `K` through the caller's medium `f` and majorants `m`
/// from `o` along `d` over `[t_min, t_max]`, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn fn_track<K: Kind<S>, S: MajStore>(
    (f, ctx): (CFn<S::V, S::Coef>, *mut c_void),
    m: *const S,
    [o, d]: [S::V; 2],
    (t_min, t_max): (S::T, S::T),
    budget: u32,
    rng: *mut sk_rng,
    out: *mut K::Out,
) -> sk_status {
    let found = || {
        let coefficients = bind(f, ctx).ok_or(sk_status::SK_ERR_NULL)?;
        let mut r = unsafe { rng_for(out, rng) }?;
        let maj = unsafe { load_maj(m) }?;
        let f = |p: Vec3<S::T>| S::pair(coefficients(S::V::from_vec(p)));
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max);
        let (m, rng) = (&maj, &mut r);
        Ok(K::func(
            Walk {
                m,
                ray,
                budget,
                rng,
            },
            &f,
        ))
    };
    unsafe { finish(out, found(), K::out) }
}

/// The number of majorants of an mx*my*mz grid (pbrt-v4 uses 16*16*16);
/// 0 for a zero dimension or a count that overflows size_t.
#[unsafe(no_mangle)]
pub extern "C" fn sk_majorant_len(mx: u32, my: u32, mz: u32) -> usize {
    majorant_len(dims([mx, my, mz])).unwrap_or(0)
}

/// Fills out[0 .. mx*my*mz] with the majorants of grid g on an mx*my*mz
/// division of its box, in one pass over the grid: each cell gets
/// (sigma_a + sigma_s) times the largest grid value whose interpolation
/// reaches into it, so the majorants bound the density everywhere. Writes
/// *maj_out borrowing out. SK_ERR_NULL for NULL pointers; SK_ERR_SIZE for a
/// zero dimension, out_len < sk_majorant_len(mx, my, mz) or a malformed
/// grid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_build(
    g: *const super::sk_grid,
    mx: u32,
    my: u32,
    mz: u32,
    out: *mut f32,
    out_len: usize,
    maj_out: *mut sk_majorants,
) -> sk_status {
    unsafe { build(g, [mx, my, mz], out, out_len, maj_out) }
}

/// Double twin of `sk_majorants_build`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_build_f64(
    g: *const super::sk_grid_f64,
    mx: u32,
    my: u32,
    mz: u32,
    out: *mut f64,
    out_len: usize,
    maj_out: *mut sk_majorants_f64,
) -> sk_status {
    unsafe { build(g, [mx, my, mz], out, out_len, maj_out) }
}

/// Your own majorants over the box [lo, hi]: sigma holds mx*my*mz values
/// (x fastest), each finite and >= 0 and bounding sigma_t over its closed
/// cell (tracking reports SK_ERR_DOMAIN where it meets one that does not).
/// SK_ERR_NULL for NULL pointers; SK_ERR_SIZE for a zero dimension;
/// SK_ERR_DOMAIN for a bad value or box (see sk_grid_set_box).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_new(
    sigma: *const f32,
    mx: u32,
    my: u32,
    mz: u32,
    lo: sk_vec3,
    hi: sk_vec3,
    out: *mut sk_majorants,
) -> sk_status {
    unsafe { new_maj(sigma, [mx, my, mz], lo, hi, out) }
}

/// Double twin of `sk_majorants_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_new_f64(
    sigma: *const f64,
    mx: u32,
    my: u32,
    mz: u32,
    lo: sk_vec3_f64,
    hi: sk_vec3_f64,
    out: *mut sk_majorants_f64,
) -> sk_status {
    unsafe { new_maj(sigma, [mx, my, mz], lo, hi, out) }
}

/// Delta tracking through grid g walking its majorants m cell by cell, from
/// o along d (any non-zero length; distances along d/|d|) over [0, t_max]:
/// one uniform per tentative collision decides absorption
/// (xi sigma_maj < sigma_a), scattering (< sigma_a + sigma_s) or a null
/// collision. Writes *out. SK_ERR_NULL for NULL pointers or callback;
/// SK_ERR_DOMAIN for zero or non-finite vectors, t_max negative or NaN,
/// majorants over another box than the grid's, or a density above its
/// cell's majorant; SK_ERR_BUDGET after `budget` tentative collisions;
/// SK_ERR_SIZE for a malformed grid or majorants.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_majorants(
    m: *const sk_majorants,
    g: *const super::sk_grid,
    o: sk_vec3,
    d: sk_vec3,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { grid_track::<Delta, _, _>(m, g, [o, d], t_max, budget, rng, out) }
}

/// Double twin of `sk_delta_track_majorants`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_majorants_f64(
    m: *const sk_majorants_f64,
    g: *const super::sk_grid_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { grid_track::<Delta, _, _>(m, g, [o, d], t_max, budget, rng, out) }
}

/// Ratio tracking through grid g walking its majorants m (arguments and
/// errors as sk_delta_track_majorants): an unbiased transmittance estimate
/// over [0, t_max], with Russian roulette below a weight of 0.05.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_majorants(
    m: *const sk_majorants,
    g: *const super::sk_grid,
    o: sk_vec3,
    d: sk_vec3,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_ratio_result,
) -> sk_status {
    unsafe { grid_track::<Ratio, _, _>(m, g, [o, d], t_max, budget, rng, out) }
}

/// Double twin of `sk_ratio_track_majorants`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_majorants_f64(
    m: *const sk_majorants_f64,
    g: *const super::sk_grid_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_ratio_result_f64,
) -> sk_status {
    unsafe { grid_track::<Ratio, _, _>(m, g, [o, d], t_max, budget, rng, out) }
}

/// Delta tracking through the caller's medium f(ctx, p) = (sigma_a,
/// sigma_s) walking the caller's majorants m, over [t_min, t_max]
/// (0 <= t_min <= t_max) from o along d. Events, budget and errors as
/// sk_delta_track_majorants (SK_ERR_DOMAIN also for negative coefficients
/// or t_min, t_max out of order).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_majorants_fn(
    f: sk_medium_fn,
    ctx: *mut c_void,
    m: *const sk_majorants,
    o: sk_vec3,
    d: sk_vec3,
    t_min: f32,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { fn_track::<Delta, _>((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}

/// Double twin of `sk_delta_track_majorants_fn`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_majorants_fn_f64(
    f: sk_medium_fn_f64,
    ctx: *mut c_void,
    m: *const sk_majorants_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { fn_track::<Delta, _>((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}

/// Ratio tracking through the caller's medium (arguments and errors as
/// sk_delta_track_majorants_fn): an unbiased transmittance estimate over
/// [t_min, t_max].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_majorants_fn(
    f: sk_medium_fn,
    ctx: *mut c_void,
    m: *const sk_majorants,
    o: sk_vec3,
    d: sk_vec3,
    t_min: f32,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_ratio_result,
) -> sk_status {
    unsafe { fn_track::<Ratio, _>((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}

/// Double twin of `sk_ratio_track_majorants_fn`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_majorants_fn_f64(
    f: sk_medium_fn_f64,
    ctx: *mut c_void,
    m: *const sk_majorants_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_ratio_result_f64,
) -> sk_status {
    unsafe { fn_track::<Ratio, _>((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}
