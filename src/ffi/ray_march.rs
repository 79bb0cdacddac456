//! The unbiased ray-marching transmittance estimators (the power series
//! and the telescoping sum), and the majorant optical depth that sets
//! their step count.

use super::majorant::{MajStore, finish, grid_at, load_maj, rng_for};
use super::medium::GridStore;
use super::{CFn, CVec, bind, sk_rng, sk_status};
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::Ray;
use crate::medium::ray_march::{
    ray_march_transmittance, ray_march_transmittance_fn, telescoping_transmittance,
    telescoping_transmittance_fn,
};
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

/// The `telescoping` flag of the bodies below.
const POWER: bool = false;
const TELESCOPING: bool = true;

/// The estimate through grid `g`, both precisions and both members
/// (`telescoping` picks the telescoping sum).
#[allow(clippy::too_many_arguments)]
unsafe fn march_grid<G: GridStore, S: MajStore<T = G::T, V = G::V>>(
    telescoping: bool,
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
        Ok(if telescoping {
            telescoping_transmittance(&grid, ray, n, budget, &mut r)
        } else {
            ray_march_transmittance(&grid, ray, n, budget, &mut r)
        })
    };
    unsafe { finish(out, found(), S::tr) }
}

/// The estimate through a caller's medium, both precisions and both
/// members.
#[allow(clippy::too_many_arguments)]
unsafe fn march_fn<S: MajStore>(
    telescoping: bool,
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
        Ok(if telescoping {
            telescoping_transmittance_fn(f, ray, n, budget, &mut r)
        } else {
            ray_march_transmittance_fn(f, ray, n, budget, &mut r)
        })
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
    let c = (n, budget);
    unsafe { march_grid::<_, super::sk_majorants>(POWER, g, [o, d], t_max, c, rng, out) }
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
    let c = (n, budget);
    unsafe { march_grid::<_, super::sk_majorants_f64>(POWER, g, [o, d], t_max, c, rng, out) }
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
    let (t, c) = ((t_min, t_max), (n, budget));
    unsafe { march_fn::<super::sk_majorants>(POWER, (f, ctx), [o, d], t, c, rng, out) }
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
    let (t, c) = ((t_min, t_max), (n, budget));
    unsafe { march_fn::<super::sk_majorants_f64>(POWER, (f, ctx), [o, d], t, c, rng, out) }
}

/// The telescoping ray-marching estimator (Rhee & Glynn 2015 as Misso et
/// al. 2022 apply it) through grid g over [0, t_max]: exp(-X_0) of a
/// stratified march of n strata, plus corrections exp(-X_k) - exp(-X'_k-1)
/// between marches of n 2^k and n 2^(k-1) strata that share their points,
/// each further level taken with probability 1/3 and reweighted, so the
/// estimate is unbiased; exact for a constant medium; 3n evaluations on
/// average. Give it finer strata than sk_ray_march_transmittance (about
/// 4x). Arguments, bounds and errors as
/// sk_ray_march_transmittance.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_telescoping_transmittance(
    g: *const super::sk_grid,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_max: f32,
    n: u32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result,
) -> sk_status {
    let c = (n, budget);
    unsafe { march_grid::<_, super::sk_majorants>(TELESCOPING, g, [o, d], t_max, c, rng, out) }
}

/// Double twin of `sk_telescoping_transmittance`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_telescoping_transmittance_f64(
    g: *const super::sk_grid_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_max: f64,
    n: u32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result_f64,
) -> sk_status {
    let c = (n, budget);
    unsafe { march_grid::<_, super::sk_majorants_f64>(TELESCOPING, g, [o, d], t_max, c, rng, out) }
}

/// sk_telescoping_transmittance through the caller's medium f(ctx, p),
/// as sk_ray_march_transmittance_fn.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_telescoping_transmittance_fn(
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
    let (t, c) = ((t_min, t_max), (n, budget));
    unsafe { march_fn::<super::sk_majorants>(TELESCOPING, (f, ctx), [o, d], t, c, rng, out) }
}

/// Double twin of `sk_telescoping_transmittance_fn`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_telescoping_transmittance_fn_f64(
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
    let (t, c) = ((t_min, t_max), (n, budget));
    unsafe { march_fn::<super::sk_majorants_f64>(TELESCOPING, (f, ctx), [o, d], t, c, rng, out) }
}
