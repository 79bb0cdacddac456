//! Mie averaged over a size distribution (double precision).

use super::mie::sk_complex_f64;
use super::{fits, overlaps, sk_status, slice_in, slice_out, write_result};
use crate::mie::Complex;
use crate::mie::polydisperse::{Averages, Polydisperse, SizeDistribution};

/// Which size distribution an sk_size_distribution_f64 holds.
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_size_kind {
    /// Lognormal, n(r) proportional to exp(-ln^2(r/r_g) / (2 ln^2 sigma_g))
    /// / r: `params[0]` = median radius r_g > 0, `params[1]` = geometric
    /// standard deviation sigma_g > 1 (`params[2]` unused).
    SK_SIZE_LOGNORMAL = 0,
    /// Deirmendjian's modified gamma, n(r) proportional to r^alpha exp(-b
    /// r^gamma): params = {alpha in [0, 100], b > 0, gamma in (0, 10]}.
    SK_SIZE_MODIFIED_GAMMA = 1,
    /// Junge's power law, n(r) proportional to r^-slope: `params[0]` =
    /// slope in (0, 10] (ocean particles: 3 to 5), the rest unused. It has
    /// no natural range: sk_size_distribution_range_f64 returns SK_ERR_DOMAIN,
    /// give r_min and r_max.
    SK_SIZE_JUNGE = 2,
}

/// A number distribution of sphere radii (unnormalised; radii in the
/// wavelength's unit).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_size_distribution_f64 {
    /// An sk_size_kind.
    pub kind: super::enum_arg::sk_size_kind,
    /// The parameters, as sk_size_kind describes.
    pub params: [f64; 3],
}

/// Spheres with sizes from a distribution, lit at one wavelength: the
/// input of sk_polydisperse_average_f64.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_polydisperse_f64 {
    /// The number distribution of radii.
    pub distribution: sk_size_distribution_f64,
    /// Smallest radius (> 0, the wavelength's unit).
    pub r_min: f64,
    /// Largest radius (> r_min).
    pub r_max: f64,
    /// Vacuum wavelength (> 0).
    pub wavelength: f64,
    /// Refractive index of the medium around the spheres (> 0).
    pub n_medium: f64,
    /// Relative refractive index of the spheres (as sk_mie_new_f64).
    pub m: sk_complex_f64,
    /// Simpson intervals in ln r: a multiple of 4, from 4 to 2^20.
    pub intervals: usize,
}

/// The averages sk_polydisperse_average_f64 returns.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mie_averages_f64 {
    /// Mean extinction cross section per particle (radius unit squared).
    pub c_ext: f64,
    /// Mean scattering cross section per particle.
    pub c_sca: f64,
    /// Mean backscattering cross section per particle.
    pub c_back: f64,
    /// Asymmetry parameter of the mixture.
    pub g: f64,
    /// Mean geometric cross section pi <r^2>.
    pub area: f64,
    /// Estimated relative errors of c_ext, c_sca, c_back and the absolute
    /// error of g: the difference between Simpson's rule on all nodes and
    /// on every other node, an estimate rather than a bound (within 2.6x of
    /// the actual error in docs/measured/polydisperse.md).
    pub errors: [f64; 4],
    /// Estimated largest relative error of the phase function.
    pub phase_error: f64,
}

const LOGNORMAL: u32 = sk_size_kind::SK_SIZE_LOGNORMAL as u32;
const MODIFIED_GAMMA: u32 = sk_size_kind::SK_SIZE_MODIFIED_GAMMA as u32;
const JUNGE: u32 = sk_size_kind::SK_SIZE_JUNGE as u32;

fn distribution(d: &sk_size_distribution_f64) -> Option<SizeDistribution> {
    let [p0, p1, p2] = d.params;
    match d.kind.0 {
        LOGNORMAL => Some(SizeDistribution::LogNormal {
            median_radius: p0,
            sigma_g: p1,
        }),
        MODIFIED_GAMMA => Some(SizeDistribution::ModifiedGamma {
            alpha: p0,
            b: p1,
            gamma: p2,
        }),
        JUNGE => Some(SizeDistribution::Junge { slope: p0 }),
        _ => None,
    }
}

/// The Rust input behind an sk_polydisperse_f64, or None for NULL or an
/// unknown kind.
unsafe fn load(p: *const sk_polydisperse_f64) -> Option<Polydisperse> {
    // SAFETY: a non-NULL p points to a readable sk_polydisperse_f64 (contract).
    let p = unsafe { p.as_ref() }?;
    Some(Polydisperse {
        distribution: distribution(&p.distribution)?,
        r_min: p.r_min,
        r_max: p.r_max,
        wavelength: p.wavelength,
        n_medium: p.n_medium,
        m: Complex::new(p.m.re, p.m.im),
        intervals: p.intervals,
    })
}

/// A radius range outside which r^3 n(r), the geometric cross section per
/// ln r, is below 1e-12 of its peak. SK_ERR_NULL for NULL pointers;
/// SK_ERR_DOMAIN for an unknown kind, invalid parameters or a power law
/// (SK_SIZE_JUNGE has no peak to measure from). Nothing is written on
/// error.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_size_distribution_range_f64(
    d: *const sk_size_distribution_f64,
    r_min: *mut f64,
    r_max: *mut f64,
) -> sk_status {
    // SAFETY: a non-NULL d points to a readable sk_size_distribution_f64.
    let Some(d) = (unsafe { d.as_ref() }) else {
        return sk_status::SK_ERR_NULL;
    };
    if r_min.is_null() || r_max.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some((lo, hi)) = distribution(d).and_then(|d| d.default_range()) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    // SAFETY: both out-pointers were checked non-NULL.
    unsafe {
        r_min.write(lo);
        r_max.write(hi);
    }
    sk_status::SK_OK
}

/// The number of sk_complex_f64 values sk_polydisperse_average_f64 needs in its
/// buffer (that of the largest sphere); 0 for NULL or input it rejects.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_polydisperse_len_f64(p: *const sk_polydisperse_f64) -> usize {
    unsafe { load(p) }.and_then(|p| p.buffer_len()).unwrap_or(0)
}

/// Averages Mie scattering over the distribution (composite Simpson in ln
/// r, one sphere per node): writes the mean cross sections, g and the error
/// estimates to *out, and the phase function per steradian at `mu[i]` to
/// `phase[i]` for i < count. scratch holds count values (the coarser rule's
/// phase function); buf holds len >= sk_polydisperse_len_f64(p) values.
/// SK_ERR_NULL for NULL p, out or buf, or NULL arrays with count > 0;
/// SK_ERR_DOMAIN for invalid input (see sk_polydisperse_f64, a mu outside [-1,
/// 1]) or overlapping phase and scratch; SK_ERR_SIZE for a short buffer or
/// an impossible count. *out is written only on success.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_polydisperse_average_f64(
    p: *const sk_polydisperse_f64,
    mu: *const f64,
    count: usize,
    phase: *mut f64,
    scratch: *mut f64,
    buf: *mut sk_complex_f64,
    len: usize,
    out: *mut sk_mie_averages_f64,
) -> sk_status {
    if p.is_null() || buf.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(poly) = (unsafe { load(p) }) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    if !fits::<f64>(count) {
        return sk_status::SK_ERR_SIZE;
    }
    // phase and scratch are written through &mut slices: no shared memory.
    if count > 0 && overlaps(phase.cast_const(), scratch.cast_const(), count) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let slices = unsafe {
        (
            slice_in(mu, count),
            slice_out(phase, count),
            slice_out(scratch, count),
            slice_out(buf.cast::<Complex>(), len),
        )
    };
    let (mu, phase, scratch, buf) = match slices {
        (Ok(a), Ok(b), Ok(c), Ok(d)) => (a, b, c, d),
        (Err(e), ..) | (_, Err(e), ..) | (_, _, Err(e), _) | (.., Err(e)) => return e,
    };
    let r = poly.average(mu, phase, scratch, buf).map(to_c);
    unsafe { write_result(out, r) }
}

fn to_c(a: Averages) -> sk_mie_averages_f64 {
    sk_mie_averages_f64 {
        c_ext: a.c_ext,
        c_sca: a.c_sca,
        c_back: a.c_back,
        g: a.g,
        area: a.area,
        errors: a.errors,
        phase_error: a.phase_error,
    }
}
