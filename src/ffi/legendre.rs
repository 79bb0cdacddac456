//! Phase functions from Legendre moments.

use super::slot::{self, Slot};
use super::verbs;
use super::{CVec, sk_status, sk_vec3, sk_vec3_f64, slice_in, slice_out, write_result};
use crate::math::real::Real;
use crate::phase::PhaseFunction;
use crate::phase::legendre::LegendreSeries;

/// A phase function given by its Legendre moments chi_0 .. chi_{n-1}
/// (p = sum (2l + 1) chi_l P_l / 4 pi; DISORT's and libRadtran's form),
/// borrowing the caller's array, which must outlive it. Build it with
/// sk_legendre_new, which checks every moment and the sign of the density
/// once; a call loads it in constant time. A plain value: copy it freely;
/// its contents are private (a zeroed or never-built series gives NaN or
/// SK_ERR_DOMAIN). Moments changed after building are read as they are
/// (NaN in, NaN out), never out of bounds.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_legendre {
    /// Private storage; do not read or write.
    pub opaque: [u64; 8],
}

/// Legendre moments (double); see `sk_legendre`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_legendre_f64 {
    /// Private storage; do not read or write.
    pub opaque: [u64; 8],
}

/// A C Legendre type and its float.
trait LegStore: Slot {
    type T: Real;
    type V: CVec<T = Self::T>;
    fn series(v: &Self::Value) -> &LegendreSeries<'static, Self::T>;
    fn wrap(s: LegendreSeries<'static, Self::T>) -> Self::Value;
}
macro_rules! impl_leg_store {
    ($c:ident, $t:ty, $v:ty, $tag:expr) => {
        impl Slot for $c {
            type Value = LegendreSeries<'static, $t>;
            const TAG: u32 = $tag;
            const ZEROED: Self = $c { opaque: [0; 8] };
        }
        impl LegStore for $c {
            type T = $t;
            type V = $v;
            fn series<'b>(v: &'b LegendreSeries<'static, $t>) -> &'b LegendreSeries<'static, $t> {
                v
            }
            fn wrap(s: LegendreSeries<'static, $t>) -> LegendreSeries<'static, $t> {
                s
            }
        }
    };
}
impl_leg_store!(sk_legendre, f32, sk_vec3, 0x534b_4c00);
impl_leg_store!(sk_legendre_f64, f64, sk_vec3_f64, 0x534b_4c01);

/// The series over `chi[0]` to `chi[n - 1]` without the sign check.
unsafe fn series<'a, T: Real>(chi: *const T, n: usize) -> Result<LegendreSeries<'a, T>, sk_status> {
    let chi = unsafe { slice_in(chi, n) }?;
    LegendreSeries::unchecked(chi).map_err(sk_status::from)
}

/// The series behind `s`, in constant time: `SK_ERR_NULL` for NULL,
/// `SK_ERR_DOMAIN` for one sk_legendre_new did not build.
unsafe fn series_at<'a, S: LegStore>(
    s: *const S,
) -> Result<&'a LegendreSeries<'static, S::T>, sk_status> {
    if s.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { slot::load(s) }
        .map(S::series)
        .ok_or(sk_status::SK_ERR_DOMAIN)
}

unsafe fn new_series<S: LegStore>(chi: *const S::T, n: usize, out: *mut S) -> sk_status {
    if chi.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    match unsafe { series(chi, n) } {
        Ok(s) if s.check().is_none() => unsafe {
            write_result(out, Ok(slot::store::<S>(S::wrap(s))))
        },
        Ok(_) => sk_status::SK_ERR_DOMAIN,
        Err(e) => e,
    }
}

unsafe fn check<T: Real>(chi: *const T, n: usize, cos_out: *mut T) -> sk_status {
    if chi.is_null() || cos_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    match unsafe { series(chi, n) }.map(|s| s.check()) {
        Ok(None) => sk_status::SK_OK,
        Ok(Some(neg)) => {
            // SAFETY: cos_out checked non-NULL above.
            unsafe { cos_out.write(T::from_f64(neg.cos_theta)) };
            sk_status::SK_ERR_DOMAIN
        }
        Err(e) => e,
    }
}

/// `f` of the series behind `s`, NaN for NULL or a never-built one.
unsafe fn with<S: LegStore>(s: *const S, f: impl Fn(&LegendreSeries<'_, S::T>) -> S::T) -> S::T {
    unsafe { series_at(s) }.map_or(S::T::NAN, f)
}

/// Builds *out over `chi[0]` to `chi[n - 1]`. SK_ERR_NULL for NULL pointers; SK_ERR_SIZE
/// for n = 0 or n > 1024; SK_ERR_DOMAIN unless chi_0 = 1 (to 1e-6), every
/// chi_l is finite in [-1, 1], and the density is non-negative at
/// 64 n + 1 evenly spaced cosines (sk_legendre_check says where not).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_new(
    chi: *const f32,
    n: usize,
    out: *mut sk_legendre,
) -> sk_status {
    unsafe { new_series(chi, n, out) }
}

/// Double twin of `sk_legendre_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_new_f64(
    chi: *const f64,
    n: usize,
    out: *mut sk_legendre_f64,
) -> sk_status {
    unsafe { new_series(chi, n, out) }
}

/// Where the expansion `chi[0]` to `chi[n - 1]` goes negative: SK_OK if nowhere among
/// the 64 n + 1 cosines checked, SK_ERR_DOMAIN with the first such cosine
/// in *cos_out; other errors as sk_legendre_new.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_check(
    chi: *const f32,
    n: usize,
    cos_out: *mut f32,
) -> sk_status {
    unsafe { check(chi, n, cos_out) }
}

/// Double twin of `sk_legendre_check`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_check_f64(
    chi: *const f64,
    n: usize,
    cos_out: *mut f64,
) -> sk_status {
    unsafe { check(chi, n, cos_out) }
}

/// The density per steradian at cos_theta. NaN for NULL or a malformed
/// series.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_pdf(s: *const sk_legendre, cos_theta: f32) -> f32 {
    unsafe { with(s, |s| s.pdf(cos_theta)) }
}

/// Double twin of `sk_legendre_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_pdf_f64(s: *const sk_legendre_f64, cos_theta: f64) -> f64 {
    unsafe { with(s, |s| s.pdf(cos_theta)) }
}

/// The CDF at cos_theta, exact term by term (NaN as sk_legendre_pdf).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_cdf(s: *const sk_legendre, cos_theta: f32) -> f32 {
    unsafe { with(s, |s| s.cdf(cos_theta)) }
}

/// Double twin of `sk_legendre_cdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_cdf_f64(s: *const sk_legendre_f64, cos_theta: f64) -> f64 {
    unsafe { with(s, |s| s.cdf(cos_theta)) }
}

/// cos theta by the exact inverse of the CDF (safeguarded Newton in
/// double; monotone in u). NaN for a NaN u and as sk_legendre_pdf.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_sample_cos(s: *const sk_legendre, u: f32) -> f32 {
    unsafe { with(s, |s| s.sample_cos(u)) }
}

/// Double twin of `sk_legendre_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_sample_cos_f64(s: *const sk_legendre_f64, u: f64) -> f64 {
    unsafe { with(s, |s| s.sample_cos(u)) }
}

/// A direction about w_in (unit): cos theta from sk_legendre_sample_cos(s,
/// u1), the azimuth 2 pi u2 (clamped); writes its density (sk_legendre_pdf)
/// to pdf_out unless NULL. NaN (direction and pdf) for a NULL or never-built
/// series.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_sample_dir(
    s: *const sk_legendre,
    w_in: sk_vec3,
    u1: f32,
    u2: f32,
    pdf_out: *mut f32,
) -> sk_vec3 {
    unsafe { sample_dir(s, w_in, (u1, u2), pdf_out) }
}

/// Double twin of `sk_legendre_sample_dir`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_sample_dir_f64(
    s: *const sk_legendre_f64,
    w_in: sk_vec3_f64,
    u1: f64,
    u2: f64,
    pdf_out: *mut f64,
) -> sk_vec3_f64 {
    unsafe { sample_dir(s, w_in, (u1, u2), pdf_out) }
}

/// The mean cosine, chi_1 (0 for a series of one moment). NaN as
/// sk_legendre_pdf.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_mean_cosine(s: *const sk_legendre) -> f32 {
    unsafe { with(s, |s| s.mean_cosine()) }
}

/// Double twin of `sk_legendre_mean_cosine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_mean_cosine_f64(s: *const sk_legendre_f64) -> f64 {
    unsafe { with(s, |s| s.mean_cosine()) }
}

/// `cos_out[i] = sk_legendre_sample_cos(s, u[i])` for `i < n`, bit for bit;
/// arrays, overlaps and statuses as sk_phase_sample_cos_n (SK_ERR_DOMAIN
/// also for a never-built series).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_sample_cos_n(
    s: *const sk_legendre,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(s, u, cos_out, n) }
}

/// Double twin of `sk_legendre_sample_cos_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_sample_cos_n_f64(
    s: *const sk_legendre_f64,
    u: *const f64,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(s, u, cos_out, n) }
}

/// Directions for n rays, structure of arrays, each bit for bit
/// sk_legendre_sample_dir's; arrays, overlaps and statuses as
/// sk_phase_sample_dir_n.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_legendre_sample_dir_n(
    s: *const sk_legendre,
    w_x: *const f32,
    w_y: *const f32,
    w_z: *const f32,
    u1: *const f32,
    u2: *const f32,
    out_x: *mut f32,
    out_y: *mut f32,
    out_z: *mut f32,
    pdf_out: *mut f32,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_n(s, w, (u1, u2), out, pdf_out, n) }
}

/// Double twin of `sk_legendre_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_legendre_sample_dir_n_f64(
    s: *const sk_legendre_f64,
    w_x: *const f64,
    w_y: *const f64,
    w_z: *const f64,
    u1: *const f64,
    u2: *const f64,
    out_x: *mut f64,
    out_y: *mut f64,
    out_z: *mut f64,
    pdf_out: *mut f64,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_n(s, w, (u1, u2), out, pdf_out, n) }
}

/// The Legendre moments chi_0 .. chi_{n-1} of the series: its own, and 0
/// past the last it holds. SK_ERR_NULL for NULL s or a NULL out with
/// n > 0; SK_ERR_DOMAIN for a never-built series; SK_ERR_SIZE if n values
/// cannot exist.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_legendre_moments(
    s: *const sk_legendre,
    out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { moments(s, out, n) }
}

/// Double twin of `sk_legendre_legendre_moments`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_legendre_legendre_moments_f64(
    s: *const sk_legendre_f64,
    out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { moments(s, out, n) }
}

unsafe fn sample_dir<S: LegStore>(
    s: *const S,
    w_in: S::V,
    (u1, u2): (S::T, S::T),
    pdf_out: *mut S::T,
) -> S::V {
    let found = unsafe { series_at(s) }
        .ok()
        .map(|s| s.sample_dir(w_in.to_vec(), u1, u2));
    unsafe { verbs::dir_one(found, pdf_out) }
}

unsafe fn sample_cos_n<S: LegStore>(
    s: *const S,
    u: *const S::T,
    out: *mut S::T,
    n: usize,
) -> sk_status {
    match unsafe { series_at(s) } {
        Ok(series) => unsafe { verbs::cos_n(u, out, n, |v| series.sample_cos(v)) },
        Err(e) => e,
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn sample_dir_n<S: LegStore>(
    s: *const S,
    w: [*const S::T; 3],
    (u1, u2): (*const S::T, *const S::T),
    out: [*mut S::T; 3],
    pdf_out: *mut S::T,
    n: usize,
) -> sk_status {
    match unsafe { series_at(s) } {
        Ok(series) => unsafe {
            verbs::dir_n((w, u1, u2), (out, pdf_out), n, |w_in, a, b| {
                series.sample_dir(w_in, a, b)
            })
        },
        Err(e) => e,
    }
}

unsafe fn moments<S: LegStore>(s: *const S, out: *mut S::T, n: usize) -> sk_status {
    let series = match unsafe { series_at(s) } {
        Ok(series) => series,
        Err(e) => return e,
    };
    match unsafe { slice_out(out, n) } {
        Ok(out) => {
            let chi = series.moments();
            for (l, o) in out.iter_mut().enumerate() {
                *o = chi.get(l).copied().unwrap_or(S::T::ZERO);
            }
            sk_status::SK_OK
        }
        Err(e) => e,
    }
}
