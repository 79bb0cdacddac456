//! Participating media.

use super::{
    CFn, CRng, CVec, bind, fits, overlaps, sk_rng, sk_status, sk_vec3, sk_vec3_f64, slice_in,
    slice_out, write_result,
};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::{self, Event, Grid, Ray, Sampling, grid_len, valid_box};
use core::ffi::c_void;

/// What tracking found (written to `scattered_out`).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_track_event {
    /// No collision in the interval: t_out is t_max (the majorant-grid calls
    /// report where the ray leaves the medium's box instead).
    SK_TRACK_ESCAPED = 0,
    /// A real collision that scatters (grid: probability sigma_s/sigma_t).
    SK_TRACK_SCATTERED = 1,
    /// A real collision that absorbs (grid).
    SK_TRACK_ABSORBED = 2,
    /// A real collision in a caller's medium (its albedo decides).
    SK_TRACK_COLLIDED = 3,
}

same_values!(sk_track_event = Event:
    SK_TRACK_ESCAPED = Escaped,
    SK_TRACK_SCATTERED = Scattered,
    SK_TRACK_ABSORBED = Absorbed,
    SK_TRACK_COLLIDED = Collided,
);

/// The caller's medium: sigma_t at point p (per length unit), which must stay
/// in [0, sigma_maj] along the ray.
pub type sk_density_fn = Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3) -> f32>;
/// The caller's medium (double); see `sk_density_fn`.
pub type sk_density_fn_f64 = Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3_f64) -> f64>;

/// Where a grid's values sit in its box.
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_sampling {
    /// At the nodes lo + (hi - lo) i/(n - 1): the faces carry the outermost
    /// values, a linear density is exact. The default.
    SK_SAMPLING_NODES = 0,
    /// At the cell centres lo + (hi - lo)(i + 1/2)/n, as pbrt-v4 and
    /// OpenVDB place voxels; held at the outermost value out to the faces.
    SK_SAMPLING_CELLS = 1,
}

same_values!(sk_sampling = Sampling:
    SK_SAMPLING_NODES = Nodes,
    SK_SAMPLING_CELLS = Cells,
);

/// A density grid over a world box (float; the unit cube unless
/// sk_grid_set_box moves it), borrowing the caller's buffer of nx*ny*nz
/// values (x fastest), which must outlive it. Build it with sk_grid_new;
/// the fields are what that validated.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_grid {
    /// The caller's density values.
    pub density: *const f32,
    /// Grid nodes along x.
    pub nx: u32,
    /// Grid nodes along y.
    pub ny: u32,
    /// Grid nodes along z.
    pub nz: u32,
    /// Absorption coefficient per unit density.
    pub sigma_a: f32,
    /// Scattering coefficient per unit density.
    pub sigma_s: f32,
    /// The largest density value (found by sk_grid_new).
    pub max_density: f32,
    /// The world box's low corner ((0, 0, 0) unless sk_grid_set_box moved it).
    pub lo: sk_vec3,
    /// The world box's high corner ((1, 1, 1) by default).
    pub hi: sk_vec3,
    /// Where the values sit: an sk_sampling (SK_SAMPLING_NODES by default).
    pub sampling: u32,
}

/// A density grid (double); see `sk_grid`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_grid_f64 {
    /// The caller's density values.
    pub density: *const f64,
    /// Grid nodes along x.
    pub nx: u32,
    /// Grid nodes along y.
    pub ny: u32,
    /// Grid nodes along z.
    pub nz: u32,
    /// Absorption coefficient per unit density.
    pub sigma_a: f64,
    /// Scattering coefficient per unit density.
    pub sigma_s: f64,
    /// The largest density value (found by sk_grid_new_f64).
    pub max_density: f64,
    /// The world box's low corner ((0, 0, 0) unless sk_grid_set_box moved it).
    pub lo: sk_vec3_f64,
    /// The world box's high corner ((1, 1, 1) by default).
    pub hi: sk_vec3_f64,
    /// Where the values sit: an sk_sampling (SK_SAMPLING_NODES by default).
    pub sampling: u32,
}

/// A C grid type and its float.
pub(crate) trait GridStore: Copy {
    type T: Real;
    type V: CVec<T = Self::T>;
    fn pack(density: *const Self::T, n: [u32; 3], sigma: (Self::T, Self::T), max: Self::T) -> Self;
    #[allow(clippy::type_complexity)]
    fn unpack(&self) -> (*const Self::T, [u32; 3], Self::T, Self::T, Self::T);
    /// The box and the sampling field.
    fn placement(&self) -> (Self::V, Self::V, u32);
    fn set_box(&mut self, lo: Self::V, hi: Self::V);
    fn set_sampling(&mut self, s: u32);
}

macro_rules! impl_grid_store {
    ($c:ty, $t:ty, $v:ty) => {
        impl GridStore for $c {
            type T = $t;
            type V = $v;
            fn pack(density: *const $t, n: [u32; 3], sigma: ($t, $t), max_density: $t) -> Self {
                Self {
                    density,
                    nx: n[0],
                    ny: n[1],
                    nz: n[2],
                    sigma_a: sigma.0,
                    sigma_s: sigma.1,
                    max_density,
                    lo: <$v>::from_vec(Vec3::new(0.0, 0.0, 0.0)),
                    hi: <$v>::from_vec(Vec3::new(1.0, 1.0, 1.0)),
                    sampling: sk_sampling::SK_SAMPLING_NODES as u32,
                }
            }
            fn unpack(&self) -> (*const $t, [u32; 3], $t, $t, $t) {
                (
                    self.density,
                    [self.nx, self.ny, self.nz],
                    self.sigma_a,
                    self.sigma_s,
                    self.max_density,
                )
            }
            fn placement(&self) -> ($v, $v, u32) {
                (self.lo, self.hi, self.sampling)
            }
            fn set_box(&mut self, lo: $v, hi: $v) {
                self.lo = lo;
                self.hi = hi;
            }
            fn set_sampling(&mut self, s: u32) {
                self.sampling = s;
            }
        }
    };
}
impl_grid_store!(sk_grid, f32, sk_vec3);
impl_grid_store!(sk_grid_f64, f64, sk_vec3_f64);

/// The Rust grid behind a C grid, or None for NULL or malformed fields.
pub(crate) unsafe fn load<'a, S: GridStore>(g: *const S) -> Option<Grid<'a, S::T>> {
    // SAFETY: a non-NULL g points to a grid built by sk_grid_new, whose
    // buffer holds nx*ny*nz values (module contract).
    let g = unsafe { g.as_ref() }?;
    let (ptr, n, sa, ss, max) = g.unpack();
    let (lo, hi, sampling) = g.placement();
    let (lo, hi) = (lo.to_vec(), hi.to_vec());
    let sampling = Sampling::try_from(sampling).ok()?;
    if !valid_box(lo, hi) {
        return None;
    }
    let count = grid_len(n[0] as usize, n[1] as usize, n[2] as usize)?;
    let density = unsafe { slice_in(ptr, count) }.ok()?;
    let n = [n[0] as usize, n[1] as usize, n[2] as usize];
    Grid::from_parts(density, n, sa, ss, max, (lo, hi), sampling).ok()
}

unsafe fn grid_new<S: GridStore>(
    density: *const S::T,
    n: [u32; 3],
    sigma_a: S::T,
    sigma_s: S::T,
    out: *mut S,
) -> sk_status {
    if density.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(count) = grid_len(n[0] as usize, n[1] as usize, n[2] as usize) else {
        return sk_status::SK_ERR_SIZE;
    };
    let values = match unsafe { slice_in(density, count) } {
        Ok(v) => v,
        Err(e) => return e,
    };
    let r = Grid::scan(
        values,
        n[0] as usize,
        n[1] as usize,
        n[2] as usize,
        sigma_a,
        sigma_s,
    )
    .map(|(_, max)| S::pack(density, n, (sigma_a, sigma_s), max));
    unsafe { write_result(out, r) }
}

unsafe fn grid_set_box<S: GridStore>(g: *mut S, lo: S::V, hi: S::V) -> sk_status {
    // SAFETY: a non-NULL g points to a writable grid (module contract).
    let Some(g) = (unsafe { g.as_mut() }) else {
        return sk_status::SK_ERR_NULL;
    };
    if !valid_box(lo.to_vec(), hi.to_vec()) {
        return sk_status::SK_ERR_DOMAIN;
    }
    g.set_box(lo, hi);
    sk_status::SK_OK
}

unsafe fn grid_set_sampling<S: GridStore>(g: *mut S, sampling: u32) -> sk_status {
    // SAFETY: as in grid_set_box.
    let Some(g) = (unsafe { g.as_mut() }) else {
        return sk_status::SK_ERR_NULL;
    };
    if Sampling::try_from(sampling).is_err() {
        return sk_status::SK_ERR_METHOD;
    }
    g.set_sampling(sampling);
    sk_status::SK_OK
}

/// Writes a tracking result.
unsafe fn write_track<T>(
    r: Result<(T, Event), Error>,
    t_out: *mut T,
    event_out: *mut u32,
) -> sk_status {
    match r {
        // SAFETY: the callers checked both pointers for NULL.
        Ok((t, e)) => unsafe {
            t_out.write(t);
            event_out.write(e as u32);
            sk_status::SK_OK
        },
        Err(e) => e.into(),
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn homogeneous<T: Real>(
    sigma_t: *const T,
    sigma_s: *const T,
    channels: usize,
    t_max: T,
    [u_channel, u_dist]: [T; 2],
    (t_out, scattered_out, weight_out): (*mut T, *mut u32, *mut T),
) -> sk_status {
    if channels == 0 || !fits::<T>(channels) {
        return sk_status::SK_ERR_SIZE;
    }
    if t_out.is_null() || scattered_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    // weight_out is written through a &mut slice: it must not alias the inputs.
    if overlaps(weight_out, sigma_t, channels) || overlaps(weight_out, sigma_s, channels) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let slices = unsafe {
        (
            slice_in(sigma_t, channels),
            slice_in(sigma_s, channels),
            slice_out(weight_out, channels),
        )
    };
    let (st, ss, w) = match slices {
        (Ok(a), Ok(b), Ok(c)) => (a, b, c),
        (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => return e,
    };
    // homogeneous_sample validates everything before it writes weight_out.
    match medium::homogeneous_sample(st, ss, t_max, u_channel, u_dist, w) {
        // SAFETY: both out-pointers were checked non-NULL above.
        Ok(s) => unsafe {
            t_out.write(s.t);
            scattered_out.write(s.scattered as u32);
            sk_status::SK_OK
        },
        Err(e) => e.into(),
    }
}

unsafe fn delta_grid<S: GridStore>(
    g: *const S,
    o: S::V,
    d: S::V,
    t_max: S::T,
    rng: *mut sk_rng,
    t_out: *mut S::T,
    event_out: *mut u32,
) -> sk_status {
    if g.is_null() || t_out.is_null() || event_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    let Some(grid) = (unsafe { load(g) }) else {
        return sk_status::SK_ERR_SIZE;
    };
    unsafe {
        write_track(
            grid.delta_track(Ray::new(o.to_vec(), d.to_vec(), t_max), &mut r),
            t_out,
            event_out,
        )
    }
}

unsafe fn ratio_grid<S: GridStore>(
    g: *const S,
    o: S::V,
    d: S::V,
    t_max: S::T,
    rng: *mut sk_rng,
) -> S::T {
    match unsafe { (load(g), CRng::from_ptr(rng)) } {
        (Some(grid), Some(mut r)) => grid
            .ratio_track(Ray::new(o.to_vec(), d.to_vec(), t_max), &mut r)
            .unwrap_or(S::T::NAN),
        _ => S::T::NAN,
    }
}

/// Delta tracking through the caller's density `sigma` (in C vector terms).
#[allow(clippy::too_many_arguments)]
unsafe fn delta_fn<V: CVec>(
    (f, ctx): (CFn<V, V::T>, *mut c_void),
    sigma_maj: V::T,
    [o, d]: [V; 2],
    (t_min, t_max): (V::T, V::T),
    rng: *mut sk_rng,
    (t_out, event_out): (*mut V::T, *mut u32),
) -> sk_status {
    let Some(sigma) = bind(f, ctx) else {
        return sk_status::SK_ERR_NULL;
    };
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    if t_out.is_null() || event_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let res = medium::delta_track_fn(
        |p| sigma(V::from_vec(p)),
        sigma_maj,
        Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max),
        &mut r,
    );
    unsafe { write_track(res, t_out, event_out) }
}

/// Ratio tracking through the caller's density `sigma`; NaN on any error.
#[allow(clippy::too_many_arguments)]
unsafe fn ratio_fn<V: CVec>(
    (f, ctx): (CFn<V, V::T>, *mut c_void),
    sigma_maj: V::T,
    [o, d]: [V; 2],
    (t_min, t_max): (V::T, V::T),
    rng: *mut sk_rng,
) -> V::T {
    let Some(sigma) = bind(f, ctx) else {
        return V::T::NAN;
    };
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return V::T::NAN;
    };
    let res = medium::ratio_track_fn(
        |p| sigma(V::from_vec(p)),
        sigma_maj,
        Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max),
        &mut r,
    );
    res.unwrap_or(V::T::NAN)
}

/// Distance to the next interaction in a homogeneous medium:
/// -ln(1 - u)/sigma_t (u clamped to [0, 1]; u = 1 or sigma_t = 0 gives +inf).
/// NaN for a negative or non-finite sigma_t or NaN u.
#[unsafe(no_mangle)]
pub extern "C" fn sk_free_path(sigma_t: f32, u: f32) -> f32 {
    medium::free_path(sigma_t, u)
}

/// Double twin of `sk_free_path`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_free_path_f64(sigma_t: f64, u: f64) -> f64 {
    medium::free_path(sigma_t, u)
}

/// Beer-Lambert transmittance exp(-sigma_t distance) for sigma_t >= 0 and
/// distance >= 0 (+inf allowed; a vacuum transmits 1 over any distance).
/// NaN for negative or NaN arguments.
#[unsafe(no_mangle)]
pub extern "C" fn sk_transmittance(sigma_t: f32, distance: f32) -> f32 {
    medium::transmittance(sigma_t, distance)
}

/// Double twin of `sk_transmittance`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_transmittance_f64(sigma_t: f64, distance: f64) -> f64 {
    medium::transmittance(sigma_t, distance)
}

/// pbrt's spectral homogeneous sampling: a channel chosen by u_channel, its
/// free path by u_dist; *t_out is the distance (t_max for the surface
/// event), *scattered_out 1 for a medium event and 0 for the surface, and
/// `weight_out[c]` the weight per channel (sigma_s Tr / mean(sigma_t Tr) or
/// Tr / mean(Tr)). sigma_t, sigma_s and weight_out hold `channels` values;
/// weight_out must not overlap the inputs (SK_ERR_OVERLAP).
/// SK_ERR_SIZE for channels = 0; SK_ERR_NULL for NULL pointers;
/// SK_ERR_DOMAIN for negative or non-finite coefficients, sigma_s > sigma_t
/// or t_max negative or NaN. Nothing is written on error.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_homogeneous_sample(
    sigma_t: *const f32,
    sigma_s: *const f32,
    channels: usize,
    t_max: f32,
    u_channel: f32,
    u_dist: f32,
    t_out: *mut f32,
    scattered_out: *mut u32,
    weight_out: *mut f32,
) -> sk_status {
    let out = (t_out, scattered_out, weight_out);
    unsafe { homogeneous(sigma_t, sigma_s, channels, t_max, [u_channel, u_dist], out) }
}

/// Double twin of `sk_homogeneous_sample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_homogeneous_sample_f64(
    sigma_t: *const f64,
    sigma_s: *const f64,
    channels: usize,
    t_max: f64,
    u_channel: f64,
    u_dist: f64,
    t_out: *mut f64,
    scattered_out: *mut u32,
    weight_out: *mut f64,
) -> sk_status {
    let out = (t_out, scattered_out, weight_out);
    unsafe { homogeneous(sigma_t, sigma_s, channels, t_max, [u_channel, u_dist], out) }
}

/// A density grid over the unit cube (sk_grid_set_box and
/// sk_grid_set_sampling change that) from the caller's nx*ny*nz values (x
/// fastest; borrowed, not copied), sampled at the grid nodes and
/// interpolated trilinearly; sigma_t(p) = (sigma_a + sigma_s) density(p).
/// Scans the values once. SK_ERR_NULL for NULL density or out; SK_ERR_SIZE
/// for a zero dimension or a product that overflows; SK_ERR_DOMAIN for a
/// negative or non-finite value or coefficient, or a majorant
/// (sigma_a + sigma_s) * max(density) that overflows.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_new(
    density: *const f32,
    nx: u32,
    ny: u32,
    nz: u32,
    sigma_a: f32,
    sigma_s: f32,
    out: *mut sk_grid,
) -> sk_status {
    unsafe { grid_new(density, [nx, ny, nz], sigma_a, sigma_s, out) }
}

/// Double twin of `sk_grid_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_new_f64(
    density: *const f64,
    nx: u32,
    ny: u32,
    nz: u32,
    sigma_a: f64,
    sigma_s: f64,
    out: *mut sk_grid_f64,
) -> sk_status {
    unsafe { grid_new(density, [nx, ny, nz], sigma_a, sigma_s, out) }
}

/// Places the grid in the world box [lo, hi] (from the unit cube). On
/// failure the grid is unchanged: SK_ERR_NULL for NULL g; SK_ERR_DOMAIN
/// unless every coordinate is finite and lo < hi on every axis with a
/// finite extent whose reciprocal is finite.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_set_box(g: *mut sk_grid, lo: sk_vec3, hi: sk_vec3) -> sk_status {
    unsafe { grid_set_box(g, lo, hi) }
}

/// Double twin of `sk_grid_set_box`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_set_box_f64(
    g: *mut sk_grid_f64,
    lo: sk_vec3_f64,
    hi: sk_vec3_f64,
) -> sk_status {
    unsafe { grid_set_box(g, lo, hi) }
}

/// Sets where the values sit (an sk_sampling). SK_ERR_NULL for NULL g;
/// SK_ERR_METHOD for an unknown value (the grid is then unchanged).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_set_sampling(g: *mut sk_grid, sampling: u32) -> sk_status {
    unsafe { grid_set_sampling(g, sampling) }
}

/// Double twin of `sk_grid_set_sampling`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_set_sampling_f64(g: *mut sk_grid_f64, sampling: u32) -> sk_status {
    unsafe { grid_set_sampling(g, sampling) }
}

/// The interpolated density at p (0 outside the grid's box); NaN for a
/// NULL or malformed grid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_density(g: *const sk_grid, p: sk_vec3) -> f32 {
    unsafe { load(g) }.map_or(f32::NAN, |grid| grid.density(p.to_vec()))
}

/// Double twin of `sk_grid_density`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_density_f64(g: *const sk_grid_f64, p: sk_vec3_f64) -> f64 {
    unsafe { load(g) }.map_or(f64::NAN, |grid| grid.density(p.to_vec()))
}

/// Delta (Woodcock) tracking through the grid from o along d (any non-zero
/// length; distances along d/|d|) over [0, t_max], clipped to the grid's box.
/// Writes the distance and an sk_track_event (ESCAPED with t_max, SCATTERED
/// or ABSORBED). A zero majorant or a ray that misses the box escapes at
/// once. SK_ERR_NULL for NULL pointers or callback; SK_ERR_DOMAIN for zero
/// or non-finite vectors or t_max negative or NaN; SK_ERR_BUDGET after 2^20
/// steps; SK_ERR_SIZE for a malformed grid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track(
    g: *const sk_grid,
    o: sk_vec3,
    d: sk_vec3,
    t_max: f32,
    rng: *mut sk_rng,
    t_out: *mut f32,
    scattered_out: *mut u32,
) -> sk_status {
    unsafe { delta_grid(g, o, d, t_max, rng, t_out, scattered_out) }
}

/// Double twin of `sk_delta_track`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_f64(
    g: *const sk_grid_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_max: f64,
    rng: *mut sk_rng,
    t_out: *mut f64,
    scattered_out: *mut u32,
) -> sk_status {
    unsafe { delta_grid(g, o, d, t_max, rng, t_out, scattered_out) }
}

/// Ratio tracking through the grid: an unbiased estimate of the
/// transmittance from o along d over [0, t_max], with Russian roulette once
/// the weight falls below 0.05 (it survives with probability 1/4, times 4).
/// 1 for a ray that misses the box; NaN for NULL or invalid arguments or
/// after 2^20 steps (a medium far below its majorant over a long ray:
/// sk_ratio_track_majorants walks local majorants and reports a used-up
/// budget as SK_ERR_BUDGET instead).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track(
    g: *const sk_grid,
    o: sk_vec3,
    d: sk_vec3,
    t_max: f32,
    rng: *mut sk_rng,
) -> f32 {
    unsafe { ratio_grid(g, o, d, t_max, rng) }
}

/// Double twin of `sk_ratio_track`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_f64(
    g: *const sk_grid_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_max: f64,
    rng: *mut sk_rng,
) -> f64 {
    unsafe { ratio_grid(g, o, d, t_max, rng) }
}

/// Delta tracking through the caller's medium f(ctx, p) = sigma_t(p) over
/// [t_min, t_max] from o along d, with majorant sigma_maj. Writes the
/// distance and SK_TRACK_COLLIDED or SK_TRACK_ESCAPED (with t_max).
/// SK_ERR_DOMAIN when f returns a value outside [0, sigma_maj] (reported,
/// not clamped: clamping would bias), for zero or non-finite vectors,
/// sigma_maj negative or non-finite, or t_min < 0 or t_max < t_min;
/// SK_ERR_NULL for NULL f, rng or outputs; SK_ERR_BUDGET after 2^20 steps.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_fn(
    f: sk_density_fn,
    ctx: *mut c_void,
    sigma_maj: f32,
    o: sk_vec3,
    d: sk_vec3,
    t_min: f32,
    t_max: f32,
    rng: *mut sk_rng,
    t_out: *mut f32,
    scattered_out: *mut u32,
) -> sk_status {
    let out = (t_out, scattered_out);
    unsafe { delta_fn((f, ctx), sigma_maj, [o, d], (t_min, t_max), rng, out) }
}

/// Double twin of `sk_delta_track_fn`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_fn_f64(
    f: sk_density_fn_f64,
    ctx: *mut c_void,
    sigma_maj: f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    rng: *mut sk_rng,
    t_out: *mut f64,
    scattered_out: *mut u32,
) -> sk_status {
    let out = (t_out, scattered_out);
    unsafe { delta_fn((f, ctx), sigma_maj, [o, d], (t_min, t_max), rng, out) }
}

/// Ratio tracking through the caller's medium (arguments as
/// sk_delta_track_fn): an unbiased transmittance estimate over
/// [t_min, t_max], with the roulette of sk_ratio_track. NaN for NULL or
/// invalid arguments, a density outside [0, sigma_maj], or after 2^20
/// steps (sk_ratio_track_majorants_fn reports each as a status).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_fn(
    f: sk_density_fn,
    ctx: *mut c_void,
    sigma_maj: f32,
    o: sk_vec3,
    d: sk_vec3,
    t_min: f32,
    t_max: f32,
    rng: *mut sk_rng,
) -> f32 {
    unsafe { ratio_fn((f, ctx), sigma_maj, [o, d], (t_min, t_max), rng) }
}

/// Double twin of `sk_ratio_track_fn`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_fn_f64(
    f: sk_density_fn_f64,
    ctx: *mut c_void,
    sigma_maj: f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    rng: *mut sk_rng,
) -> f64 {
    unsafe { ratio_fn((f, ctx), sigma_maj, [o, d], (t_min, t_max), rng) }
}
