//! Phase functions from Legendre moments.

use super::{sk_status, slice_in};
use crate::math::real::Real;
use crate::phase::PhaseFunction;
use crate::phase::legendre::LegendreSeries;

/// A phase function given by its Legendre moments chi_0 .. chi_{n-1}
/// (p = sum (2l + 1) chi_l P_l / 4 pi; DISORT's and libRadtran's form),
/// borrowing the caller's array, which must not change after
/// sk_legendre_new. Build it with sk_legendre_new.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_legendre {
    /// The moments (chi_0 = 1).
    pub chi: *const f32,
    /// How many.
    pub n: usize,
}

/// Legendre moments (double); see `sk_legendre`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_legendre_f64 {
    /// The moments (chi_0 = 1).
    pub chi: *const f64,
    /// How many.
    pub n: usize,
}

/// A C Legendre type and its float.
trait LegStore: Copy {
    type T: Real;
    fn parts(&self) -> (*const Self::T, usize);
    fn pack(chi: *const Self::T, n: usize) -> Self;
}
macro_rules! impl_leg_store {
    ($c:ident, $t:ty) => {
        impl LegStore for $c {
            type T = $t;
            fn parts(&self) -> (*const $t, usize) {
                (self.chi, self.n)
            }
            fn pack(chi: *const $t, n: usize) -> Self {
                $c { chi, n }
            }
        }
    };
}
impl_leg_store!(sk_legendre, f32);
impl_leg_store!(sk_legendre_f64, f64);

/// The series over `chi[0 .. n]` without the sign check.
unsafe fn series<'a, T: Real>(chi: *const T, n: usize) -> Result<LegendreSeries<'a, T>, sk_status> {
    let chi = unsafe { slice_in(chi, n) }?;
    LegendreSeries::unchecked(chi).map_err(sk_status::from)
}

unsafe fn new_series<S: LegStore>(chi: *const S::T, n: usize, out: *mut S) -> sk_status {
    if chi.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    match unsafe { series(chi, n) } {
        Ok(s) if s.check().is_none() => {
            // SAFETY: out checked non-NULL above.
            unsafe { out.write(S::pack(chi, n)) };
            sk_status::SK_OK
        }
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

/// `f` of the series behind `s`, NaN for NULL or a malformed one.
unsafe fn with<S: LegStore>(s: *const S, f: impl Fn(LegendreSeries<'_, S::T>) -> S::T) -> S::T {
    // SAFETY: a non-NULL s points to a series built by sk_legendre_new.
    let Some((chi, n)) = (unsafe { s.as_ref() }).map(|s| s.parts()) else {
        return S::T::NAN;
    };
    unsafe { series(chi, n) }.map_or(S::T::NAN, f)
}

/// Builds *out over chi[0 .. n]. SK_ERR_NULL for NULL pointers; SK_ERR_SIZE
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

/// Where the expansion chi[0 .. n] goes negative: SK_OK if nowhere among
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
