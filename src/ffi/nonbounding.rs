//! Tracking through majorants that may not bound: ratio tracking with
//! signed weights and weighted delta tracking.

use super::CRng;
use super::majorant::{MajStore, finish, load_maj, rng_for};
use super::{CFn, CVec, bind, sk_rng, sk_status};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::Ray;
use crate::medium::majorant::Majorants;
use crate::medium::nonbounding::{Exceeded, SignedTransmittance, WeightedTrack};
use core::ffi::c_void;

/// What ratio tracking with signed weights found.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_signed_result {
    /// The unbiased transmittance estimate; negative or above 1 only where
    /// a majorant did not bound.
    pub tr: f32,
    /// Tentative collisions drawn (density evaluations).
    pub steps: u32,
    /// The largest sigma_t / sigma_maj above 1 met on the walk, or 0 when
    /// every majorant met bounded the medium.
    pub exceeded: f32,
    /// The majorant cell (i, j, k) where `exceeded` was met (0s when none):
    /// raise its majorant for later rays.
    pub cell: [u32; 3],
}

/// What ratio tracking with signed weights found (double); see
/// `sk_signed_result`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_signed_result_f64 {
    /// As in `sk_signed_result`.
    pub tr: f64,
    /// Tentative collisions drawn.
    pub steps: u32,
    /// As in `sk_signed_result`.
    pub exceeded: f64,
    /// As in `sk_signed_result`.
    pub cell: [u32; 3],
}

/// What weighted delta tracking found.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_weighted_track {
    /// Distance along d/|d| of the real collision, or where the ray leaves
    /// the box (as in `sk_track_result`).
    pub t: f32,
    /// An sk_track_event: ESCAPED, SCATTERED or ABSORBED.
    pub event: u32,
    /// The path's weight: 1 where every majorant met bounded the medium,
    /// else signed; the outcome counts with this weight.
    pub weight: f32,
    /// Tentative collisions drawn, the real one included.
    pub steps: u32,
    /// As in `sk_signed_result`.
    pub exceeded: f32,
    /// As in `sk_signed_result`.
    pub cell: [u32; 3],
}

/// What weighted delta tracking found (double); see `sk_weighted_track`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_weighted_track_f64 {
    /// As in `sk_weighted_track`.
    pub t: f64,
    /// An sk_track_event.
    pub event: u32,
    /// As in `sk_weighted_track`.
    pub weight: f64,
    /// Tentative collisions drawn.
    pub steps: u32,
    /// As in `sk_signed_result`.
    pub exceeded: f64,
    /// As in `sk_signed_result`.
    pub cell: [u32; 3],
}

/// The excess as (ratio or 0, cell). Cells fit in u32: their counts came
/// from C as u32.
fn excess<T: Real>(e: Option<Exceeded<T>>) -> (T, [u32; 3]) {
    e.map_or((T::ZERO, [0; 3]), |e| (e.ratio, e.cell.map(|c| c as u32)))
}

/// A C majorant type with its two result types.
trait NbStore: MajStore {
    type Signed: Copy;
    type Weighted: Copy;
    fn signed(s: SignedTransmittance<Self::T>) -> Self::Signed;
    fn weighted(w: WeightedTrack<Self::T>) -> Self::Weighted;
}

macro_rules! impl_nb_store {
    ($m:ty, $signed:ident, $weighted:ident) => {
        impl NbStore for $m {
            type Signed = $signed;
            type Weighted = $weighted;
            fn signed(s: SignedTransmittance<Self::T>) -> $signed {
                let (exceeded, cell) = excess(s.exceeded);
                $signed {
                    tr: s.tr,
                    steps: s.steps,
                    exceeded,
                    cell,
                }
            }
            fn weighted(w: WeightedTrack<Self::T>) -> $weighted {
                let (exceeded, cell) = excess(w.exceeded);
                $weighted {
                    t: w.t,
                    event: w.event as u32,
                    weight: w.weight,
                    steps: w.steps,
                    exceeded,
                    cell,
                }
            }
        }
    };
}
impl_nb_store!(super::sk_majorants, sk_signed_result, sk_weighted_track);
impl_nb_store!(
    super::sk_majorants_f64,
    sk_signed_result_f64,
    sk_weighted_track_f64
);

/// One tracker `run` through a caller's medium, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn track<S: MajStore, X, Y>(
    (f, ctx): (CFn<S::V, S::Coef>, *mut c_void),
    m: *const S,
    [o, d]: [S::V; 2],
    (t_min, t_max): (S::T, S::T),
    budget: u32,
    rng: *mut sk_rng,
    out: *mut Y,
    run: impl FnOnce(
        Majorants<'_, S::T>,
        &dyn Fn(Vec3<S::T>) -> (S::T, S::T),
        Ray<S::T>,
        u32,
        &mut CRng,
    ) -> Result<X, Error>,
    to_c: impl Fn(X) -> Y,
) -> sk_status {
    let found = || {
        let coefficients = bind(f, ctx).ok_or(sk_status::SK_ERR_NULL)?;
        let mut r = unsafe { rng_for(out, rng) }?;
        let maj = unsafe { load_maj(m) }?;
        let f = |p: Vec3<S::T>| S::pair(coefficients(S::V::from_vec(p)));
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max);
        Ok(run(maj, &f, ray, budget, &mut r))
    };
    unsafe { finish(out, found(), to_c) }
}

/// Ratio tracking with signed weights through a caller's medium, both
/// precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn signed<S: NbStore>(
    f: (CFn<S::V, S::Coef>, *mut c_void),
    m: *const S,
    od: [S::V; 2],
    t: (S::T, S::T),
    budget: u32,
    rng: *mut sk_rng,
    out: *mut S::Signed,
) -> sk_status {
    let run = |maj: Majorants<'_, S::T>, f: &dyn Fn(_) -> _, ray, budget, r: &mut CRng| {
        maj.ratio_track_signed_fn(f, ray, budget, r)
    };
    unsafe { track(f, m, od, t, budget, rng, out, run, S::signed) }
}

/// Weighted delta tracking through a caller's medium, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn weighted<S: NbStore>(
    f: (CFn<S::V, S::Coef>, *mut c_void),
    m: *const S,
    od: [S::V; 2],
    t: (S::T, S::T),
    budget: u32,
    rng: *mut sk_rng,
    out: *mut S::Weighted,
) -> sk_status {
    let run = |maj: Majorants<'_, S::T>, f: &dyn Fn(_) -> _, ray, budget, r: &mut CRng| {
        maj.delta_track_weighted_fn(f, ray, budget, r)
    };
    unsafe { track(f, m, od, t, budget, rng, out, run, S::weighted) }
}

/// Ratio tracking through the caller's medium f(ctx, p) along the ray
/// from o along d over [t_min, t_max] (clipped to the majorants' box;
/// t_max may be INFINITY) when the majorants m may not bound it: where
/// sigma_t exceeds sigma_maj a factor 1 - sigma_t/sigma_maj turns
/// negative and the estimate stays unbiased (Misso et al. 2023). Reports
/// the largest sigma_t/sigma_maj above 1 and its cell, to raise that
/// majorant for later rays (never during a walk). A cell whose majorant is
/// 0 is crossed unseen: give every cell that may hold density a positive
/// majorant. Writes *out. SK_ERR_NULL for NULL pointers or callback;
/// SK_ERR_DOMAIN for a zero or non-finite vector, t_min, t_max out of
/// order, a coefficient negative or not finite, or a weight that
/// overflows; SK_ERR_BUDGET after `budget` tentative collisions;
/// SK_ERR_SIZE for malformed majorants.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_ratio_track_signed_fn(
    f: super::sk_medium_fn,
    ctx: *mut c_void,
    m: *const super::sk_majorants,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_min: f32,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_signed_result,
) -> sk_status {
    unsafe { signed((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}

/// Double twin of `sk_ratio_track_signed_fn`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_ratio_track_signed_fn_f64(
    f: super::sk_medium_fn_f64,
    ctx: *mut c_void,
    m: *const super::sk_majorants_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_signed_result_f64,
) -> sk_status {
    unsafe { signed((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}

/// Delta tracking through the caller's medium f(ctx, p) when the
/// majorants m may not bound it (arguments, excess report and errors as
/// sk_ratio_track_signed_fn): at a tentative collision with
/// sigma_n = sigma_maj - sigma_t, the collision is real with probability
/// sigma_t/(sigma_t + |sigma_n|) and the weight is multiplied by
/// (sigma_t + |sigma_n|)/sigma_maj, negated for a null collision where
/// sigma_n < 0; where the majorant bounds this is delta tracking with
/// weight 1. The outcome (event, t) counts with out->weight: unbiased.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_delta_track_weighted_fn(
    f: super::sk_medium_fn,
    ctx: *mut c_void,
    m: *const super::sk_majorants,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_min: f32,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_weighted_track,
) -> sk_status {
    unsafe { weighted((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}

/// Double twin of `sk_delta_track_weighted_fn`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_delta_track_weighted_fn_f64(
    f: super::sk_medium_fn_f64,
    ctx: *mut c_void,
    m: *const super::sk_majorants_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut sk_weighted_track_f64,
) -> sk_status {
    unsafe { weighted((f, ctx), m, [o, d], (t_min, t_max), budget, rng, out) }
}
