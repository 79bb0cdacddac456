//! Majorant grids, with or without minorants, and their optical depth.

use super::medium::{GridStore, grid_at};
use super::slot::{self, Slot};
use super::{CVec, overlaps, sk_status, sk_vec3, sk_vec3_f64, slice_in, slice_out, write_result};
use crate::math::real::Real;
use crate::medium::Ray;
use crate::medium::majorant::{Majorants, majorant_len};
use crate::medium::residual::Extrema;

/// Per-cell bounds of a medium over a world box, one value per cell of an
/// mx*my*mz division of it (x fastest, per length unit, >= 0): majorants
/// (sigma_maj >= sigma_t), and optionally minorants (<= sigma_t, the
/// control of residual ratio tracking). The arrays stay the caller's and
/// must outlive it. Built by sk_majorants_new_from_grid (from a grid) or
/// sk_majorants_new (your own values), which check every value once; a
/// call loads it in constant time, whatever the number of cells, and a
/// walk reports a value changed since (negative, NaN, infinite, or a
/// minorant above its majorant) as SK_ERR_DOMAIN when it reaches its cell.
/// A plain value: copy it freely; its contents are private.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_majorants {
    /// Private storage; do not read or write.
    pub opaque: [u64; 32],
}

/// Per-cell bounds (double); see `sk_majorants`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_majorants_f64 {
    /// Private storage; do not read or write.
    pub opaque: [u64; 32],
}

/// What an `sk_majorants` holds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bounds<T: 'static> {
    pub(crate) max: Majorants<'static, T>,
    pub(crate) min: Option<Majorants<'static, T>>,
}

/// A C majorant type, its float and vector.
pub(crate) trait MajStore: Slot {
    type T: Real;
    type V: CVec<T = Self::T>;
    fn bounds(v: &Self::Value) -> &Bounds<Self::T>;
    fn wrap(b: Bounds<Self::T>) -> Self::Value;
}

macro_rules! impl_maj_store {
    ($c:ident, $t:ty, $v:ty, $tag:expr) => {
        impl Slot for $c {
            type Value = Bounds<$t>;
            const TAG: u32 = $tag;
            const ZEROED: Self = $c { opaque: [0; 32] };
        }
        impl MajStore for $c {
            type T = $t;
            type V = $v;
            fn bounds(v: &Bounds<$t>) -> &Bounds<$t> {
                v
            }
            fn wrap(b: Bounds<$t>) -> Bounds<$t> {
                b
            }
        }
    };
}
impl_maj_store!(sk_majorants, f32, sk_vec3, 0x534b_4d00);
impl_maj_store!(sk_majorants_f64, f64, sk_vec3_f64, 0x534b_4d01);

/// The bounds behind `m`, in constant time: `SK_ERR_NULL` for NULL,
/// `SK_ERR_DOMAIN` for majorants no constructor built.
pub(crate) unsafe fn bounds_at<'a, S: MajStore>(
    m: *const S,
) -> Result<&'a Bounds<S::T>, sk_status> {
    if m.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { slot::load(m) }
        .map(S::bounds)
        .ok_or(sk_status::SK_ERR_DOMAIN)
}

/// `[m0, m1, m2]` as `usize`.
fn dims(m: [u32; 3]) -> [usize; 3] {
    m.map(|x| x as usize)
}

unsafe fn build<G: GridStore, S: MajStore<T = G::T>>(
    g: *const G,
    m: [u32; 3],
    (max_out, min_out): (*mut G::T, *mut G::T),
    len: usize,
    out: *mut S,
) -> sk_status {
    if max_out.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let grid = match unsafe { grid_at(g) } {
        Ok(grid) => grid,
        Err(e) => return e,
    };
    let Some(count) = majorant_len(dims(m)) else {
        return sk_status::SK_ERR_SIZE;
    };
    if len < count {
        return sk_status::SK_ERR_SIZE;
    }
    if !min_out.is_null() && overlaps(max_out, min_out, count) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let max = match unsafe { slice_out(max_out, count) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let built = if min_out.is_null() {
        Majorants::build(grid, dims(m), max).map(|max| Bounds { max, min: None })
    } else {
        let min = match unsafe { slice_out(min_out, count) } {
            Ok(s) => s,
            Err(e) => return e,
        };
        Extrema::build(grid, dims(m), max, min).map(|e| Bounds {
            max: e.majorants(),
            min: Some(e.minorants()),
        })
    };
    unsafe { write_result(out, built.map(|b| slot::store::<S>(S::wrap(b)))) }
}

unsafe fn new_maj<S: MajStore>(
    (max, min): (*const S::T, *const S::T),
    m: [u32; 3],
    lo: S::V,
    hi: S::V,
    out: *mut S,
) -> sk_status {
    if max.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(count) = majorant_len(dims(m)) else {
        return sk_status::SK_ERR_SIZE;
    };
    let (lo, hi) = (lo.to_vec(), hi.to_vec());
    let checked = |p: *const S::T| -> Result<Majorants<'static, S::T>, sk_status> {
        // 'static: the handle's contract is that the caller's array
        // outlives the handle.
        let values = unsafe { slice_in(p, count) }?;
        Majorants::new(values, dims(m), lo, hi).map_err(Into::into)
    };
    let bounds = checked(max).and_then(|max| {
        if min.is_null() {
            return Ok(Bounds { max, min: None });
        }
        let e = Extrema::new(max, checked(min)?).map_err(sk_status::from)?;
        Ok(Bounds {
            max: e.majorants(),
            min: Some(e.minorants()),
        })
    });
    match bounds {
        Ok(b) => unsafe { write_result(out, Ok(slot::store::<S>(S::wrap(b)))) },
        Err(e) => e,
    }
}

/// `∫ σ_maj` along the ray, NaN for bad majorants or a ray `Ray` refuses.
unsafe fn depth<S: MajStore>(m: *const S, [o, d]: [S::V; 2], (t0, t1): (S::T, S::T)) -> S::T {
    let ray = Ray::new(o.to_vec(), d.to_vec(), t1).segment(t0, t1);
    match unsafe { bounds_at(m) } {
        Ok(b) => b.max.optical_depth(ray).unwrap_or(S::T::NAN),
        Err(_) => S::T::NAN,
    }
}

/// The number of cells of an mx*my*mz grid (pbrt-v4 uses 16*16*16); 0 for
/// a zero dimension or a count that overflows size_t.
#[unsafe(no_mangle)]
pub extern "C" fn sk_majorant_len(mx: u32, my: u32, mz: u32) -> usize {
    majorant_len(dims([mx, my, mz])).unwrap_or(0)
}

/// Fills `max_out[0]` to `max_out[mx*my*mz - 1]` with the majorants of grid g on an
/// mx*my*mz division of its box, in one pass over the grid: each cell gets
/// (sigma_a + sigma_s) times the largest grid value whose interpolation
/// reaches into it, so the majorants bound the density everywhere. With a
/// non-NULL min_out, also the minorants (the smallest such value, so they
/// bound it from below), for residual ratio tracking. Writes *out
/// borrowing the arrays. SK_ERR_NULL for NULL g, max_out or out;
/// SK_ERR_DOMAIN for a never-built grid; SK_ERR_SIZE for a zero dimension
/// or len < sk_majorant_len(mx, my, mz); SK_ERR_OVERLAP if the two arrays
/// overlap.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_majorants_new_from_grid(
    g: *const super::sk_grid,
    mx: u32,
    my: u32,
    mz: u32,
    max_out: *mut f32,
    min_out: *mut f32,
    len: usize,
    out: *mut sk_majorants,
) -> sk_status {
    unsafe { build(g, [mx, my, mz], (max_out, min_out), len, out) }
}

/// Double twin of `sk_majorants_new_from_grid`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_majorants_new_from_grid_f64(
    g: *const super::sk_grid_f64,
    mx: u32,
    my: u32,
    mz: u32,
    max_out: *mut f64,
    min_out: *mut f64,
    len: usize,
    out: *mut sk_majorants_f64,
) -> sk_status {
    unsafe { build(g, [mx, my, mz], (max_out, min_out), len, out) }
}

/// Your own bounds over the box [lo, hi]: max holds mx*my*mz majorants (x
/// fastest), each finite and >= 0 and bounding sigma_t over its closed
/// cell (tracking reports SK_ERR_DOMAIN where it meets one that does not);
/// min, if not NULL, as many minorants, each at most its cell's majorant.
/// SK_ERR_NULL for NULL max or out; SK_ERR_SIZE for a zero dimension;
/// SK_ERR_DOMAIN for a bad value or box (see sk_grid_set_box).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_majorants_new(
    max: *const f32,
    min: *const f32,
    mx: u32,
    my: u32,
    mz: u32,
    lo: sk_vec3,
    hi: sk_vec3,
    out: *mut sk_majorants,
) -> sk_status {
    unsafe { new_maj((max, min), [mx, my, mz], lo, hi, out) }
}

/// Double twin of `sk_majorants_new`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_majorants_new_f64(
    max: *const f64,
    min: *const f64,
    mx: u32,
    my: u32,
    mz: u32,
    lo: sk_vec3_f64,
    hi: sk_vec3_f64,
    out: *mut sk_majorants_f64,
) -> sk_status {
    unsafe { new_maj((max, min), [mx, my, mz], lo, hi, out) }
}

/// The majorant optical depth (the integral of sigma_maj) along the ray
/// from o along d over [t_min, t_max] (distances along d/|d|), cell by
/// cell; not rounded. Without minorants its ceiling is the step count
/// sk_ray_march takes by default. NaN for NULL or never-built majorants, a bad value on the
/// ray, a zero or non-finite vector, or t_min, t_max out of order.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_optical_depth(
    m: *const sk_majorants,
    o: sk_vec3,
    d: sk_vec3,
    t_min: f32,
    t_max: f32,
) -> f32 {
    unsafe { depth(m, [o, d], (t_min, t_max)) }
}

/// Double twin of `sk_majorants_optical_depth`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_majorants_optical_depth_f64(
    m: *const sk_majorants_f64,
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_min: f64,
    t_max: f64,
) -> f64 {
    unsafe { depth(m, [o, d], (t_min, t_max)) }
}
