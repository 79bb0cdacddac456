//! Residual ratio tracking: majorants paired with minorants.

use super::majorant::{MajStore, finish, grid_at, load_maj, load_maj_checked, rng_for, write};
use super::medium::{GridStore, load};
use super::{
    CFn, CVec, bind, overlaps, sk_majorants, sk_majorants_f64, sk_rng, sk_status, slice_out,
};
use crate::math::geometry::Vec3;
use crate::medium::Ray;
use crate::medium::majorant::{Majorants, majorant_len};
use crate::medium::residual::Extrema;
use core::ffi::c_void;

/// Majorants and minorants over the same cells of one box: the control
/// extinction of residual ratio tracking is each cell's minorant. Build it
/// with sk_extrema_build (from a grid) or sk_extrema_new (your own).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_extrema {
    /// The majorants (sigma_maj per length unit).
    pub max: sk_majorants,
    /// The minorants (per length unit, at most the majorants).
    pub min: sk_majorants,
}

/// Majorants and minorants (double); see `sk_extrema`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_extrema_f64 {
    /// The majorants.
    pub max: sk_majorants_f64,
    /// The minorants.
    pub min: sk_majorants_f64,
}

/// A C extrema type and the majorant type of its precision.
pub(crate) trait ExtStore: Copy {
    type M: MajStore;
    fn pack(max: Self::M, min: Self::M) -> Self;
    fn parts(&self) -> (Self::M, Self::M);
}

macro_rules! impl_ext_store {
    ($c:ident, $m:ident) => {
        impl ExtStore for $c {
            type M = $m;
            fn pack(max: $m, min: $m) -> Self {
                $c { max, min }
            }
            fn parts(&self) -> ($m, $m) {
                (self.max, self.min)
            }
        }
    };
}
impl_ext_store!(sk_extrema, sk_majorants);
impl_ext_store!(sk_extrema_f64, sk_majorants_f64);

type T<E> = <<E as ExtStore>::M as MajStore>::T;
type V<E> = <<E as ExtStore>::M as MajStore>::V;

/// The Rust extrema behind a C value: `Err` for NULL or malformed fields,
/// or majorants and minorants over different cells or boxes.
unsafe fn load_ext<'a, E: ExtStore>(e: *const E) -> Result<Extrema<'a, T<E>>, sk_status> {
    // SAFETY: a non-NULL e points to extrema built by this library (module
    // contract); its majorant values are checked as sk_majorants are.
    let (max, min) = unsafe { e.as_ref() }.ok_or(sk_status::SK_ERR_NULL)?.parts();
    let (max, min) = unsafe { (load_maj(&max), load_maj(&min)) };
    Extrema::paired(max?, min?).map_err(Into::into)
}

#[allow(clippy::too_many_arguments)]
unsafe fn build<G: GridStore, E: ExtStore>(
    g: *const G,
    m: [u32; 3],
    (max_out, min_out): (*mut G::T, *mut G::T),
    out_len: usize,
    ext_out: *mut E,
) -> sk_status
where
    E::M: MajStore<T = G::T, V = G::V>,
{
    if g.is_null() || max_out.is_null() || min_out.is_null() || ext_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(grid) = (unsafe { load(g) }) else {
        return sk_status::SK_ERR_SIZE;
    };
    let dims = m.map(|x| x as usize);
    let Some(count) = majorant_len(dims) else {
        return sk_status::SK_ERR_SIZE;
    };
    if out_len < count {
        return sk_status::SK_ERR_SIZE;
    }
    if overlaps(max_out, min_out, count) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let (max, min) = match unsafe { (slice_out(max_out, count), slice_out(min_out, count)) } {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => return e,
    };
    let (lo, hi) = grid.bounds();
    let (lo, hi) = (G::V::from_vec(lo), G::V::from_vec(hi));
    let r = Extrema::build(&grid, dims, max, min).map(|_| ());
    let pack = |()| {
        E::pack(
            E::M::pack(max_out, m, lo, hi),
            E::M::pack(min_out, m, lo, hi),
        )
    };
    unsafe { write(ext_out, r, pack) }
}

unsafe fn new_ext<E: ExtStore>(max: *const E::M, min: *const E::M, ext_out: *mut E) -> sk_status {
    if max.is_null() || min.is_null() || ext_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let (a, b) = unsafe { (load_maj_checked(max), load_maj_checked(min)) };
    let (a, b): (Majorants<'_, T<E>>, Majorants<'_, T<E>>) = match (a, b) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => return e,
    };
    // SAFETY: both checked non-NULL above.
    let r = Extrema::new(a, b).map(|_| unsafe { E::pack(*max, *min) });
    unsafe { write(ext_out, r, |x| x) }
}

/// Residual ratio tracking of extrema `e` through grid `g`, both precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn track_grid<G: GridStore, E: ExtStore>(
    e: *const E,
    g: *const G,
    [o, d]: [G::V; 2],
    t_max: G::T,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut <E::M as MajStore>::Tr,
) -> sk_status
where
    E::M: MajStore<T = G::T, V = G::V>,
{
    let found = || {
        if g.is_null() {
            return Err(sk_status::SK_ERR_NULL);
        }
        let mut r = unsafe { rng_for(out, rng) }?;
        let (ext, grid) = unsafe { (load_ext(e)?, grid_at(g)?) };
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max);
        Ok(ext.residual_ratio_track(&grid, ray, budget, &mut r))
    };
    unsafe { finish(out, found(), E::M::tr) }
}

/// Residual ratio tracking of extrema `e` through a caller's medium, both
/// precisions.
#[allow(clippy::too_many_arguments)]
unsafe fn track_fn<E: ExtStore>(
    (f, ctx): (CFn<V<E>, <E::M as MajStore>::Coef>, *mut c_void),
    e: *const E,
    [o, d]: [V<E>; 2],
    (t_min, t_max): (T<E>, T<E>),
    budget: u32,
    rng: *mut sk_rng,
    out: *mut <E::M as MajStore>::Tr,
) -> sk_status {
    let found = || {
        let coefficients = bind(f, ctx).ok_or(sk_status::SK_ERR_NULL)?;
        let mut r = unsafe { rng_for(out, rng) }?;
        let ext = unsafe { load_ext(e) }?;
        let f = |p: Vec3<T<E>>| E::M::pair(coefficients(V::<E>::from_vec(p)));
        let ray = Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max);
        Ok(ext.residual_ratio_track_fn(f, ray, budget, &mut r))
    };
    unsafe { finish(out, found(), E::M::tr) }
}

/// Fills max_out[0 .. mx*my*mz] with the majorants of grid g (as
/// sk_majorants_build) and min_out with its minorants: each cell gets
/// (sigma_a + sigma_s) times the smallest grid value whose interpolation
/// reaches into it, so the minorants bound the density from below
/// everywhere. Writes *ext_out borrowing both arrays. SK_ERR_NULL for NULL
/// pointers; SK_ERR_SIZE for a zero dimension, out_len <
/// sk_majorant_len(mx, my, mz) or a malformed grid; SK_ERR_OVERLAP if the
/// two arrays overlap.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_extrema_build(
    g: *const super::sk_grid,
    mx: u32,
    my: u32,
    mz: u32,
    max_out: *mut f32,
    min_out: *mut f32,
    out_len: usize,
    ext_out: *mut sk_extrema,
) -> sk_status {
    unsafe { build(g, [mx, my, mz], (max_out, min_out), out_len, ext_out) }
}

/// Double twin of `sk_extrema_build`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_extrema_build_f64(
    g: *const super::sk_grid_f64,
    mx: u32,
    my: u32,
    mz: u32,
    max_out: *mut f64,
    min_out: *mut f64,
    out_len: usize,
    ext_out: *mut sk_extrema_f64,
) -> sk_status {
    unsafe { build(g, [mx, my, mz], (max_out, min_out), out_len, ext_out) }
}

/// Pairs your own majorants and minorants (each built or checked by
/// sk_majorants_new) into *ext_out. SK_ERR_NULL for NULL pointers;
/// SK_ERR_SIZE for malformed ones; SK_ERR_DOMAIN unless both have the same
/// cells and box and every minorant is at most its cell's majorant.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_extrema_new(
    max: *const sk_majorants,
    min: *const sk_majorants,
    ext_out: *mut sk_extrema,
) -> sk_status {
    unsafe { new_ext(max, min, ext_out) }
}

/// Double twin of `sk_extrema_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_extrema_new_f64(
    max: *const sk_majorants_f64,
    min: *const sk_majorants_f64,
    ext_out: *mut sk_extrema_f64,
) -> sk_status {
    unsafe { new_ext(max, min, ext_out) }
}

/// Residual ratio tracking (Novak et al. 2014) through grid g with the
/// extrema e (arguments and errors as sk_ratio_track_majorants): the
/// transmittance exp(-integral of the minorants) along the ray, exact, times
/// ratio tracking of the residual at the rate majorant - minorant. An
/// unbiased estimate over [0, t_max]; exact where the density is constant
/// in each cell. SK_ERR_DOMAIN also for a cell whose minorant exceeds its
/// majorant.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_residual_ratio_track(
    e: *const sk_extrema,
    g: *const super::sk_grid,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result,
) -> sk_status {
    unsafe { track_grid(e, g, [o, d], t_max, budget, rng, out) }
}

/// Double twin of `sk_residual_ratio_track`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_residual_ratio_track_f64(
    e: *const sk_extrema_f64,
    g: *const super::sk_grid_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result_f64,
) -> sk_status {
    unsafe { track_grid(e, g, [o, d], t_max, budget, rng, out) }
}

/// Residual ratio tracking through the caller's medium f(ctx, p) = (sigma_a,
/// sigma_s) with the extrema e, over [t_min, t_max] (arguments and errors
/// as sk_ratio_track_majorants_fn).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_residual_ratio_track_fn(
    f: super::sk_medium_fn,
    ctx: *mut c_void,
    e: *const sk_extrema,
    o: super::sk_vec3,
    d: super::sk_vec3,
    t_min: f32,
    t_max: f32,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result,
) -> sk_status {
    unsafe { track_fn((f, ctx), e, [o, d], (t_min, t_max), budget, rng, out) }
}

/// Double twin of `sk_residual_ratio_track_fn`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_residual_ratio_track_fn_f64(
    f: super::sk_medium_fn_f64,
    ctx: *mut c_void,
    e: *const sk_extrema_f64,
    o: super::sk_vec3_f64,
    d: super::sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    budget: u32,
    rng: *mut sk_rng,
    out: *mut super::sk_ratio_result_f64,
) -> sk_status {
    unsafe { track_fn((f, ctx), e, [o, d], (t_min, t_max), budget, rng, out) }
}
