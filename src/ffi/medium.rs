//! Participating media.

use super::slot::{self, Slot};
use super::{
    CVec, fits, overlaps, sk_status, sk_vec3, sk_vec3_f64, slice_in, slice_out, write_result,
};
use crate::math::real::Real;
use crate::medium::{self, Event, Grid, Sampling, grid_len};
use core::ffi::c_void;

/// What delta tracking found (sk_track_result.event).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_track_event {
    /// No collision in the segment: t is where the ray leaves the medium
    /// (its box, or t_max), or t_min for a ray that never enters it.
    SK_TRACK_ESCAPED = 0,
    /// A real collision that scatters (probability sigma_s/sigma_t).
    SK_TRACK_SCATTERED = 1,
    /// A real collision that absorbs.
    SK_TRACK_ABSORBED = 2,
    /// A real collision whose kind the caller decides (the Rust API's
    /// tracking through a sigma_t function; no C call returns it).
    SK_TRACK_COLLIDED = 3,
}

same_values!(sk_track_event = Event:
    SK_TRACK_ESCAPED = Escaped,
    SK_TRACK_SCATTERED = Scattered,
    SK_TRACK_ABSORBED = Absorbed,
    SK_TRACK_COLLIDED = Collided,
);

/// A scalar field of the caller's at point p: the emitted radiance L_e of
/// sk_emission_track (finite, >= 0).
pub type sk_emission_fn = Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3) -> f32>;
/// The emitted radiance (double); see `sk_emission_fn`.
pub type sk_emission_fn_f64 = Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3_f64) -> f64>;

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
/// values (x fastest), which must outlive it. Build it with sk_grid_new,
/// which checks every value once; a call loads it in constant time. A
/// plain value: copy it freely; its contents are private (a zeroed or
/// never-built grid gives NaN or SK_ERR_DOMAIN). The values stay yours:
/// one changed afterwards is read as it is, and tracking reports one
/// above its majorant as SK_ERR_DOMAIN.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_grid {
    /// Private storage; do not read or write.
    pub opaque: [u64; 32],
}

/// A density grid (double); see `sk_grid`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_grid_f64 {
    /// Private storage; do not read or write.
    pub opaque: [u64; 32],
}

/// A C grid type and its float.
pub(crate) trait GridStore: Slot {
    type T: Real;
    type V: CVec<T = Self::T>;
    fn grid(v: &Self::Value) -> &Grid<'static, Self::T>;
    fn wrap(g: Grid<'static, Self::T>) -> Self::Value;
}

macro_rules! impl_grid_store {
    ($c:ident, $t:ty, $v:ty, $tag:expr) => {
        impl Slot for $c {
            type Value = Grid<'static, $t>;
            const TAG: u32 = $tag;
            const ZEROED: Self = $c { opaque: [0; 32] };
        }
        impl GridStore for $c {
            type T = $t;
            type V = $v;
            fn grid<'b>(v: &'b Grid<'static, $t>) -> &'b Grid<'static, $t> {
                v
            }
            fn wrap(g: Grid<'static, $t>) -> Grid<'static, $t> {
                g
            }
        }
    };
}
impl_grid_store!(sk_grid, f32, sk_vec3, 0x534b_4700);
impl_grid_store!(sk_grid_f64, f64, sk_vec3_f64, 0x534b_4701);

/// The grid behind `g`, in constant time: `SK_ERR_NULL` for NULL,
/// `SK_ERR_DOMAIN` for one sk_grid_new did not build.
pub(crate) unsafe fn grid_at<'a, S: GridStore>(
    g: *const S,
) -> Result<&'a Grid<'static, S::T>, sk_status> {
    if g.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { slot::load(g) }
        .map(S::grid)
        .ok_or(sk_status::SK_ERR_DOMAIN)
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
    let [nx, ny, nz] = n.map(|k| k as usize);
    let r = Grid::new(values, nx, ny, nz, sigma_a, sigma_s).map(|g| slot::store::<S>(S::wrap(g)));
    unsafe { write_result(out, r) }
}

/// Replaces the grid behind `g` by `f` of it, if `f` accepts it.
unsafe fn grid_update<S: GridStore>(
    g: *mut S,
    f: impl FnOnce(Grid<'static, S::T>) -> Result<Grid<'static, S::T>, sk_status>,
) -> sk_status {
    let grid = match unsafe { grid_at(g) } {
        Ok(grid) => *grid,
        Err(e) => return e,
    };
    match f(grid) {
        // SAFETY: g is non-NULL (grid_at) and writable (module contract).
        Ok(new) => unsafe {
            g.write(slot::store::<S>(S::wrap(new)));
            sk_status::SK_OK
        },
        Err(e) => e,
    }
}

unsafe fn grid_set_box<S: GridStore>(g: *mut S, lo: S::V, hi: S::V) -> sk_status {
    unsafe {
        grid_update(g, |grid| {
            grid.with_box(lo.to_vec(), hi.to_vec()).map_err(Into::into)
        })
    }
}

unsafe fn grid_set_sampling<S: GridStore>(g: *mut S, sampling: u32) -> sk_status {
    let Ok(sampling) = Sampling::try_from(sampling) else {
        return if g.is_null() {
            sk_status::SK_ERR_NULL
        } else {
            sk_status::SK_ERR_METHOD
        };
    };
    unsafe { grid_update(g, |grid| Ok(grid.with_sampling(sampling))) }
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
/// Checks every value once, here. SK_ERR_NULL for NULL density or out; SK_ERR_SIZE
/// for a zero dimension or a product that overflows; SK_ERR_DOMAIN for a
/// negative or non-finite value or coefficient, or a majorant that
/// overflows: (sigma_a + sigma_s) * max(density) * (1 + 4 FLT_EPSILON),
/// the grid's majorant with its slack (DBL_EPSILON for sk_grid_new_f64).
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
/// for a never-built grid, or unless every coordinate is finite and lo < hi
/// on every axis with a finite extent whose reciprocal is finite.
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
/// SK_ERR_METHOD for an unknown value; SK_ERR_DOMAIN for a never-built
/// grid (the grid is then unchanged).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_set_sampling(
    g: *mut sk_grid,
    sampling: super::enum_arg::sk_sampling,
) -> sk_status {
    unsafe { grid_set_sampling(g, sampling.0) }
}

/// Double twin of `sk_grid_set_sampling`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_set_sampling_f64(
    g: *mut sk_grid_f64,
    sampling: super::enum_arg::sk_sampling,
) -> sk_status {
    unsafe { grid_set_sampling(g, sampling.0) }
}

/// The interpolated density at p (0 outside the grid's box); NaN for a
/// NULL or never-built grid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_density(g: *const sk_grid, p: sk_vec3) -> f32 {
    unsafe { grid_at(g) }.map_or(f32::NAN, |grid| grid.density(p.to_vec()))
}

/// Double twin of `sk_grid_density`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_density_f64(g: *const sk_grid_f64, p: sk_vec3_f64) -> f64 {
    unsafe { grid_at(g) }.map_or(f64::NAN, |grid| grid.density(p.to_vec()))
}

/// (sigma_a, sigma_s) of the grid at p: its coefficients times the
/// interpolated density (0 outside its box), what an sk_medium_fn over the
/// grid returns. Both NaN for a NULL or never-built grid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_coefficients(g: *const sk_grid, p: sk_vec3) -> sk_coefficients {
    let (sigma_a, sigma_s) = unsafe { grid_coefficients_at(g, p) };
    sk_coefficients { sigma_a, sigma_s }
}

/// Double twin of `sk_grid_coefficients`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_grid_coefficients_f64(
    g: *const sk_grid_f64,
    p: sk_vec3_f64,
) -> sk_coefficients_f64 {
    let (sigma_a, sigma_s) = unsafe { grid_coefficients_at(g, p) };
    sk_coefficients_f64 { sigma_a, sigma_s }
}

/// `(σ_a, σ_s)` of the grid behind `g` at `p`, NaN for a bad grid.
unsafe fn grid_coefficients_at<S: GridStore>(g: *const S, p: S::V) -> (S::T, S::T) {
    match unsafe { grid_at(g) } {
        Ok(grid) => grid.coefficients_at(p.to_vec()),
        Err(_) => (S::T::NAN, S::T::NAN),
    }
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

/// The caller's medium: sigma_a and sigma_s at point p, both >= 0 with a
/// sum within the majorant of the cell holding p. Tracking decides
/// absorption, scattering or a null collision itself.
pub type sk_medium_fn =
    Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3) -> sk_coefficients>;
/// The caller's medium (double); see `sk_medium_fn`.
pub type sk_medium_fn_f64 =
    Option<unsafe extern "C" fn(ctx: *mut c_void, p: sk_vec3_f64) -> sk_coefficients_f64>;
