//! Emission along a ray: ratio tracking that scores the emitted radiance,
//! and the exact integral for a medium constant per cell.

use super::majorant::{MajStore, finish, grid_at, load_maj, rng_for, write};
use super::medium::GridStore;
use super::{CFn, CVec, bind, sk_rng, sk_status};
use crate::math::geometry::Vec3;
use crate::medium::Ray;
use crate::medium::emission::{Emission, emission_cells};
use core::ffi::c_void;

/// The emitted radiance along a ray segment and the segment's
/// transmittance.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_emission_result {
    /// The integral of T(a, t) sigma_a(t) L_e(t) dt along the segment (in
    /// the units of L_e): an unbiased estimate, or exact from
    /// sk_emission_cells.
    pub radiance: f32,
    /// The transmittance of the whole segment (estimated, or exact).
    pub tr: f32,
    /// Tentative collisions drawn (density evaluations); 0 when exact.
    pub steps: u32,
}

/// The emitted radiance along a ray segment (double); see
/// `sk_emission_result`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_emission_result_f64 {
    /// As in `sk_emission_result`.
    pub radiance: f64,
    /// As in `sk_emission_result`.
    pub tr: f64,
    /// Tentative collisions drawn.
    pub steps: u32,
}

/// A C majorant type with its emission result.
trait EmStore: MajStore {
    type Out: Copy;
    fn out(e: Emission<Self::T>) -> Self::Out;
}

macro_rules! impl_em_store {
    ($m:ty, $out:ident) => {
        impl EmStore for $m {
            type Out = $out;
            fn out(e: Emission<Self::T>) -> $out {
                $out {
                    radiance: e.radiance,
                    tr: e.tr,
                    steps: e.steps,
                }
            }
        }
    };
}
impl_em_store!(super::sk_majorants, sk_emission_result);
impl_em_store!(super::sk_majorants_f64, sk_emission_result_f64);

/// Through grid `g` with the emitted radiance of grid `le`, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn track_grid<G: GridStore, S: EmStore<T = G::T, V = G::V>>(
    m: *const S,
    (g, le): (*const G, *const G),
    [o, d]: [G::V; 2],
    t_max: G::T,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut S::Out,
) -> sk_status {
    let found = || {
        if g.is_null() || le.is_null() {
            return Err(sk_status::SK_ERR_NULL);
        }
        let mut r = unsafe { rng_for(out, rng) }?;
        let (maj, grid, source) = unsafe { (load_maj(m)?, grid_at(g)?, grid_at(le)?) };
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max);
        Ok(maj.emission_track(&grid, |p| source.density(p), ray, budget, &mut r))
    };
    unsafe { finish(out, found(), S::out) }
}

/// Through a caller's medium with a caller's emitted radiance, both
/// precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn track_fn<S: EmStore>(
    (f, ctx): (CFn<S::V, S::Coef>, *mut c_void),
    (le, le_ctx): (CFn<S::V, S::T>, *mut c_void),
    m: *const S,
    [o, d]: [S::V; 2],
    (t_min, t_max): (S::T, S::T),
    budget: u32,
    rng: *mut sk_rng,
    out: *mut S::Out,
) -> sk_status {
    let found = || {
        let coefficients = bind(f, ctx).ok_or(sk_status::SK_ERR_NULL)?;
        let source = bind(le, le_ctx).ok_or(sk_status::SK_ERR_NULL)?;
        let mut r = unsafe { rng_for(out, rng) }?;
        let maj = unsafe { load_maj(m) }?;
        let f = |p: Vec3<S::T>| S::pair(coefficients(S::V::from_vec(p)));
        let s = |p: Vec3<S::T>| source(S::V::from_vec(p));
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max);
        Ok(maj.emission_track_fn(f, s, ray, budget, &mut r))
    };
    unsafe { finish(out, found(), S::out) }
}

/// The exact integral over cells, both precisions.
unsafe fn cells<S: EmStore>(
    (sigma_t, emitted): (*const S, *const S),
    [o, d]: [S::V; 2],
    (t_min, t_max): (S::T, S::T),
    out: *mut S::Out,
) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let (s, j) = match unsafe { (load_maj(sigma_t), load_maj(emitted)) } {
        (Ok(s), Ok(j)) => (s, j),
        (Err(e), _) | (_, Err(e)) => return e,
    };
    let ray = Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max);
    unsafe { write(out, emission_cells(&s, &j, ray), S::out) }
}

/// The radiance grid g (with majorants m, as sk_ratio_track_majorants)
/// emits toward the ray's origin over [0, t_max] (the ray clipped to the
/// box): the integral of T(0, t) sigma_a(t) L_e(t) dt, L_e(p) the emitted
/// radiance read from grid le (its interpolated density; its own box and
/// sampling, its coefficients unused). Ratio tracking that scores
/// W sigma_a L_e / sigma_maj at each tentative collision, W the weight so
/// far: unbiased; its final weight estimates the transmittance. Writes
/// *out. SK_ERR_NULL for NULL pointers or callback; SK_ERR_DOMAIN for a
/// zero or non-finite vector, t_max negative or NaN, g over another box
/// than m, coefficients above the majorant or an L_e negative or not
/// finite where a collision reads it; SK_ERR_BUDGET when more than
/// `budget` tentative collisions would be needed; SK_ERR_SIZE for
/// malformed grids or majorants.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_emission_track(
    m: *const super::sk_majorants,
    g: *const super::sk_grid,
    le: *const super::sk_grid,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_emission_result,
) -> sk_status {
    unsafe { track_grid(m, (g, le), [o, d], t_max, budget, rng, out) }
}

/// Double twin of `sk_emission_track`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_emission_track_f64(
    m: *const super::sk_majorants_f64,
    g: *const super::sk_grid_f64,
    le: *const super::sk_grid_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_emission_result_f64,
) -> sk_status {
    unsafe { track_grid(m, (g, le), [o, d], t_max, budget, rng, out) }
}

/// sk_emission_track through a caller's medium f(ctx, p) (coefficients
/// within the majorants m) with the emitted radiance le(le_ctx, p) (finite
/// and >= 0, else SK_ERR_DOMAIN), over [t_min, t_max] (clipped to the
/// majorants' box; t_max may be INFINITY). Other errors as
/// sk_emission_track.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_emission_track_fn(
    f: super::sk_medium_fn,
    ctx: *mut c_void,
    le: super::sk_density_fn,
    le_ctx: *mut c_void,
    m: *const super::sk_majorants,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_min: f32,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_emission_result,
) -> sk_status {
    unsafe {
        track_fn(
            (f, ctx),
            (le, le_ctx),
            m,
            [o, d],
            (t_min, t_max),
            budget,
            rng,
            out,
        )
    }
}

/// Double twin of `sk_emission_track_fn`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_emission_track_fn_f64(
    f: super::sk_medium_fn_f64,
    ctx: *mut c_void,
    le: super::sk_density_fn_f64,
    le_ctx: *mut c_void,
    m: *const super::sk_majorants_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_emission_result_f64,
) -> sk_status {
    unsafe {
        track_fn(
            (f, ctx),
            (le, le_ctx),
            m,
            [o, d],
            (t_min, t_max),
            budget,
            rng,
            out,
        )
    }
}

/// The exact emitted radiance along the ray over [t_min, t_max] through a
/// medium constant in each cell: sigma_t holds each cell's extinction and
/// emitted its emission coefficient sigma_a L_e (per length unit; both
/// built or checked by sk_majorants_new, over the same cells and box). Per
/// cell crossed over a length l after optical depth tau:
/// exp(-tau) j l (1 - exp(-sigma_t l))/(sigma_t l). Writes *out (steps 0).
/// SK_ERR_NULL for NULL pointers; SK_ERR_SIZE for malformed grids;
/// SK_ERR_DOMAIN for grids over different cells or boxes, a zero or
/// non-finite vector, t_min, t_max out of order, or a radiance that
/// overflows.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_emission_cells(
    sigma_t: *const super::sk_majorants,
    emitted: *const super::sk_majorants,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_min: f32,
    t_max: f32,
    out: *mut sk_emission_result,
) -> sk_status {
    unsafe { cells((sigma_t, emitted), [o, d], (t_min, t_max), out) }
}

/// Double twin of `sk_emission_cells`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_emission_cells_f64(
    sigma_t: *const super::sk_majorants_f64,
    emitted: *const super::sk_majorants_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    out: *mut sk_emission_result_f64,
) -> sk_status {
    unsafe { cells((sigma_t, emitted), [o, d], (t_min, t_max), out) }
}
