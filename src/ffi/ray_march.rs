//! The unbiased ray-marching transmittance estimator, and the majorant
//! optical depth that sets its step count.

use super::majorant::{MajStore, finish, grid_at, load_maj, rng_for};
use super::medium::GridStore;
use super::{CFn, CVec, bind, sk_rng, sk_status};
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::Ray;
use crate::medium::ray_march::{ray_march_transmittance, ray_march_transmittance_fn};
use core::ffi::c_void;

/// `∫ σ_maj` along the ray, NaN for NULL or malformed majorants or a ray
/// `Ray` refuses.
unsafe fn depth<S: MajStore>(m: *const S, [o, d]: [S::V; 2], t: (S::T, S::T)) -> S::T {
    let ray = Ray::new(o.to_vec(), d.to_vec(), t.1).segment(t.0, t.1);
    match unsafe { load_maj(m) } {
        Ok(maj) => maj.optical_depth(ray).unwrap_or(S::T::NAN),
        Err(_) => S::T::NAN,
    }
}

/// The estimate through grid `g`, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn march_grid<G: GridStore, S: MajStore<T = G::T, V = G::V>>(
    g: *const G,
    [o, d]: [G::V; 2],
    t_max: G::T,
    (n, budget): (u32, u32),
    rng: *mut sk_rng,
    out: *mut S::Tr,
) -> sk_status {
    let found = || {
        if g.is_null() {
            return Err(sk_status::SK_ERR_NULL);
        }
        let mut r = unsafe { rng_for(out, rng) }?;
        let grid = unsafe { grid_at(g) }?;
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max);
        Ok(ray_march_transmittance(&grid, ray, n, budget, &mut r))
    };
    unsafe { finish(out, found(), S::tr) }
}

/// The estimate through a caller's medium, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn march_fn<S: MajStore>(
    (f, ctx): (CFn<S::V, S::Coef>, *mut c_void),
    [o, d]: [S::V; 2],
    (t_min, t_max): (S::T, S::T),
    (n, budget): (u32, u32),
    rng: *mut sk_rng,
    out: *mut S::Tr,
) -> sk_status {
    let found = || {
        let coefficients = bind(f, ctx).ok_or(sk_status::SK_ERR_NULL)?;
        let mut r = unsafe { rng_for(out, rng) }?;
        let f = |p: Vec3<S::T>| S::pair(coefficients(S::V::from_vec(p)));
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max);
        Ok(ray_march_transmittance_fn(f, ray, n, budget, &mut r))
    };
    unsafe { finish(out, found(), S::tr) }
}

/// The majorant optical depth along the ray from o along d over
/// [t_min, t_max] (distances along d/|d|), cell by cell: rounded up, a
/// step count for sk_ray_march_transmittance that gives each stratum about
/// one majorant mean free path. NaN for NULL or malformed majorants, a
/// zero or non-finite vector, or t_min, t_max out of order.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_optical_depth(
    m: *const super::sk_majorants,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_min: f32,
    t_max: f32,
) -> f32 {
    unsafe { depth(m, [o, d], (t_min, t_max)) }
}

/// Double twin of `sk_majorants_optical_depth`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_optical_depth_f64(
    m: *const super::sk_majorants_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_min: f64,
    t_max: f64,
) -> f64 {
    unsafe { depth(m, [o, d], (t_min, t_max)) }
}

/// The unbiased ray-marching transmittance estimator (Kettunen et al.
/// 2021, power-series form) through grid g (the ray clipped to its box)
/// over [0, t_max], with n strata per march: a power series in
/// independent jittered marches (at least 3, on average 4.8), cut at a
/// random order and reweighted, each march in turn the pivot, so the
/// estimate is unbiased; exact for a constant medium.
/// Not bounded: one estimate may exceed 1 or, rarely, fall below 0. Writes
/// *out (tr and the density evaluations). SK_ERR_NULL for NULL pointers or
/// callback; SK_ERR_DOMAIN for n = 0, a zero or non-finite vector, t_max
/// negative or NaN, or strata far too coarse for the medium (the series
/// overflows); SK_ERR_BUDGET when more than `budget` density
/// evaluations would be needed; SK_ERR_SIZE for a malformed grid.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_ray_march_transmittance(
    g: *const super::sk_grid,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_max: f32,
    n: u32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result,
) -> sk_status {
    unsafe { march_grid::<_, super::sk_majorants>(g, [o, d], t_max, (n, budget), rng, out) }
}

/// Double twin of `sk_ray_march_transmittance`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_ray_march_transmittance_f64(
    g: *const super::sk_grid_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_max: f64,
    n: u32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result_f64,
) -> sk_status {
    unsafe { march_grid::<_, super::sk_majorants_f64>(g, [o, d], t_max, (n, budget), rng, out) }
}

/// The estimator through the caller's medium f(ctx, p) = (sigma_a, sigma_s)
/// over [t_min, t_max], which must be finite (SK_ERR_DOMAIN otherwise, and
/// for a negative coefficient); other arguments and errors as
/// sk_ray_march_transmittance.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_ray_march_transmittance_fn(
    f: super::sk_medium_fn,
    ctx: *mut c_void,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_min: f32,
    t_max: f32,
    n: u32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result,
) -> sk_status {
    let t = (t_min, t_max);
    unsafe { march_fn::<super::sk_majorants>((f, ctx), [o, d], t, (n, budget), rng, out) }
}

/// Double twin of `sk_ray_march_transmittance_fn`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_ray_march_transmittance_fn_f64(
    f: super::sk_medium_fn_f64,
    ctx: *mut c_void,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    n: u32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result_f64,
) -> sk_status {
    let t = (t_min, t_max);
    unsafe { march_fn::<super::sk_majorants_f64>((f, ctx), [o, d], t, (n, budget), rng, out) }
}
