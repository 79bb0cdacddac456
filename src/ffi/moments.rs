//! Legendre moments of phase functions and mixtures.

use super::mixture::mixture_at;
use super::phase::{PhaseStore, load};
use super::{sk_mixture, sk_mixture_f64, sk_phase, sk_phase_f64, sk_status, slice_out};
use crate::phase::moments::legendre_moments;

unsafe fn phase_moments<S: PhaseStore>(p: *const S, out: *mut S::T, n: usize) -> sk_status {
    if p.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(phase) = (unsafe { load(p) }) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    match unsafe { slice_out(out, n) } {
        Ok(out) => {
            legendre_moments(phase, out);
            sk_status::SK_OK
        }
        Err(e) => e,
    }
}

unsafe fn mixture_moments<M: super::mixture::MixStore>(
    m: *const M,
    out: *mut M::T,
    n: usize,
) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let mix = match unsafe { mixture_at(m) } {
        Ok(mix) => mix,
        Err(e) => return e,
    };
    match unsafe { slice_out(out, n) } {
        Ok(out) => {
            mix.legendre_moments(out);
            sk_status::SK_OK
        }
        Err(e) => e,
    }
}

/// The Legendre moments chi_0 .. chi_{n-1} of p into out: chi_l = <P_l(cos
/// theta)>, chi_0 = 1, chi_1 = g (the form DISORT and libRadtran take,
/// p = sum (2l + 1) chi_l P_l / 4 pi). Closed forms for isotropic,
/// Rayleigh, depolarised Rayleigh, HG, Draine, the fog and two-lobe HG;
/// quadrature over the inverse CDF for Gegenbauer and Fournier-Forand
/// (within 1e-10; its cost grows as n^2/32 passes of 20 992 samples).
/// SK_ERR_NULL for NULL pointers; SK_ERR_DOMAIN for an unconstructed
/// phase; SK_ERR_SIZE if out cannot hold n values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_legendre_moments(
    p: *const sk_phase,
    out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { phase_moments(p, out, n) }
}

/// Double twin of `sk_phase_legendre_moments`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_legendre_moments_f64(
    p: *const sk_phase_f64,
    out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { phase_moments(p, out, n) }
}

/// The Legendre moments of a mixture, sum of w_i chi_{l,i} (each
/// component's as sk_phase_legendre_moments; tables by quadrature), into
/// `out[0]` to `out[n - 1]`. SK_ERR_NULL for NULL pointers; SK_ERR_SIZE or
/// SK_ERR_DOMAIN for a mixture sk_mixture_new did not build.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_legendre_moments(
    m: *const sk_mixture,
    out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { mixture_moments(m, out, n) }
}

/// Double twin of `sk_mixture_legendre_moments`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_legendre_moments_f64(
    m: *const sk_mixture_f64,
    out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { mixture_moments(m, out, n) }
}
