//! Mie scattering by a sphere (double precision only: the series needs it;
//! a float caller converts).

use super::{fits, overlaps, sk_status, slice_in, slice_out, write_result};
use crate::mie::{self, Complex, Efficiencies, Mie};

/// A complex number: the relative refractive index m = re + i im (im >= 0
/// absorbs; Wiscombe's MIEV0 writes the same sphere as re - i im) and the
/// amplitude functions.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct sk_complex_f64 {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

/// Efficiencies (cross sections over pi r^2) and asymmetry of a sphere.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mie_efficiencies_f64 {
    /// Extinction efficiency Q_ext.
    pub q_ext: f64,
    /// Scattering efficiency Q_sca.
    pub q_sca: f64,
    /// Backscattering efficiency Q_back = 4 |S1(180 deg)|^2 / x^2.
    pub q_back: f64,
    /// Asymmetry parameter g, the mean of cos theta.
    pub g: f64,
}

/// A solved sphere: its size parameter, efficiencies, and the series
/// coefficients a_1, b_1, ..., a_terms, b_terms in the caller's buffer,
/// which must outlive it. Build it with sk_mie_new_f64.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mie_f64 {
    /// Size parameter x.
    pub x: f64,
    /// 2 terms coefficients in the caller's buffer.
    pub ab: *const sk_complex_f64,
    /// Number of series terms.
    pub terms: usize,
    /// The efficiencies and g.
    pub efficiencies: sk_mie_efficiencies_f64,
}

fn to_c(z: Complex) -> sk_complex_f64 {
    sk_complex_f64 { re: z.re, im: z.im }
}

/// The Rust sphere behind an sk_mie_f64, or None for NULL or malformed fields.
unsafe fn load<'a>(m: *const sk_mie_f64) -> Option<Mie<'a>> {
    // SAFETY: a non-NULL m points to an sk_mie_f64 built by sk_mie_new_f64, whose ab
    // holds 2 terms values (module contract).
    let m = unsafe { m.as_ref() }?;
    let len = m.terms.checked_mul(2)?;
    let ab = unsafe { slice_in(m.ab.cast::<Complex>(), len) }.ok()?;
    let e = m.efficiencies;
    let eff = Efficiencies {
        q_ext: e.q_ext,
        q_sca: e.q_sca,
        q_back: e.q_back,
        g: e.g,
    };
    Some(Mie::from_parts(m.x, ab, eff))
}

/// The refractive index of liquid water at vacuum wavelength_um in
/// [0.182, 1.129] micrometres into *out: Daimon & Masumura's four-term
/// Sellmeier fit at 21.5 C (Appl. Opt. 46, 3811, 2007; 1.3345 at 0.55),
/// the imaginary part 0 (below 1.13 micrometres it stays under 3e-6, Hale
/// & Querry 1973). SK_ERR_NULL for NULL out; SK_ERR_DOMAIN outside the
/// range or NaN (nothing written).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mie_water_index_f64(
    wavelength_um: f64,
    out: *mut sk_complex_f64,
) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    match mie::water(wavelength_um) {
        // SAFETY: out checked non-NULL above.
        Some(m) => unsafe {
            out.write(to_c(m));
            sk_status::SK_OK
        },
        None => sk_status::SK_ERR_DOMAIN,
    }
}

/// The size parameter pi d n_medium / lambda of a sphere of diameter d in a
/// medium of index n_medium at vacuum wavelength lambda (same unit as d).
#[unsafe(no_mangle)]
pub extern "C" fn sk_mie_size_parameter_f64(diameter: f64, wavelength: f64, n_medium: f64) -> f64 {
    mie::size_parameter(diameter, wavelength, n_medium)
}

/// The number of sk_complex_f64 values sk_mie_new_f64 needs for (x, m); 0 for input
/// it rejects: x outside [1e-20, 1e5], re outside (0, 1000], im outside
/// [0, 1000], |m| below 1e-100, |m| x above 2e6, m = 1 (a sphere of the
/// medium's own index does not scatter: it has no phase function), or NaN.
#[unsafe(no_mangle)]
pub extern "C" fn sk_mie_len_f64(x: f64, m: sk_complex_f64) -> usize {
    mie::buffer_len(x, Complex::new(m.re, m.im)).unwrap_or(0)
}

/// Solves the sphere of size parameter x and relative index m into buf (len
/// values, at least sk_mie_len_f64(x, m)) and writes *out, which borrows
/// buf. Wiscombe's term count (two more below x = 8), the logarithmic
/// derivative by downward
/// recurrence. SK_ERR_NULL for NULL buf or out; SK_ERR_DOMAIN for input
/// sk_mie_len_f64 rejects, and for a sphere the series cannot represent:
/// scattering that underflows to 0 (m within about 1e-150 of 1 at the
/// smallest x: no phase function) or terms that overflow (a complex m of
/// modulus below about 1e-60 at x = 1e-20); SK_ERR_SIZE for a short
/// buffer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mie_new_f64(
    x: f64,
    m: sk_complex_f64,
    buf: *mut sk_complex_f64,
    len: usize,
    out: *mut sk_mie_f64,
) -> sk_status {
    if buf.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let slice = match unsafe { slice_out(buf.cast::<Complex>(), len) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let r = Mie::new(x, Complex::new(m.re, m.im), slice).map(|mie| {
        let e = mie.efficiencies;
        sk_mie_f64 {
            x: mie.x(),
            ab: mie.coefficients().as_ptr().cast::<sk_complex_f64>(),
            terms: mie.coefficients().len() / 2,
            efficiencies: sk_mie_efficiencies_f64 {
                q_ext: e.q_ext,
                q_sca: e.q_sca,
                q_back: e.q_back,
                g: e.g,
            },
        }
    });
    unsafe { write_result(out, r) }
}

/// The amplitude functions S1(mu), S2(mu) of a solved sphere at mu = cos
/// theta (clamped to [-1, 1]; NaN gives NaN). SK_ERR_NULL for NULL
/// pointers; SK_ERR_SIZE for a malformed sphere.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mie_amplitudes_f64(
    m: *const sk_mie_f64,
    mu: f64,
    s1_out: *mut sk_complex_f64,
    s2_out: *mut sk_complex_f64,
) -> sk_status {
    if m.is_null() || s1_out.is_null() || s2_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(mie) = (unsafe { load(m) }) else {
        return sk_status::SK_ERR_SIZE;
    };
    let (s1, s2) = mie.amplitudes(mu);
    // SAFETY: both out-pointers were checked non-NULL.
    unsafe {
        s1_out.write(to_c(s1));
        s2_out.write(to_c(s2));
    }
    sk_status::SK_OK
}

/// The unpolarised phase function per steradian of a solved sphere at mu,
/// normalised over the sphere; NaN for a NULL or malformed sphere or NaN mu.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mie_pdf_f64(m: *const sk_mie_f64, mu: f64) -> f64 {
    unsafe { load(m) }.map_or(f64::NAN, |mie| mie.phase(mu))
}

/// Table sizes for a sphere of size parameter x in [1e-20, 1e5]:
/// *angles = max(4000, 16 x) for sk_mie_tabulate_f64 and *intervals = max(16384,
/// 64 x) for sk_table_new_measured_f64 (docs/measured/mie_table.md measures them:
/// total-variation distance 2.8e-6 at x = 10, 2.5e-4 at 100, 1.2e-3 at
/// 1000).
/// SK_ERR_NULL for NULL pointers, SK_ERR_DOMAIN for other x; nothing is
/// written on error. For a 2-D table over wavelengths or sizes (one n for
/// every slice), use the sizes of the largest x.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mie_table_len_f64(
    x: f64,
    angles: *mut usize,
    intervals: *mut usize,
) -> sk_status {
    if angles.is_null() || intervals.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    if !(1e-20..=1e5).contains(&x) {
        return sk_status::SK_ERR_DOMAIN;
    }
    let (a, n) = mie::table_sizes(x);
    // SAFETY: both out-pointers were checked non-NULL.
    unsafe {
        angles.write(a);
        intervals.write(n);
    }
    sk_status::SK_OK
}

/// Tabulates a solved sphere's phase function for sk_table_new_measured_f64:
/// `cos_theta[j]` (decreasing from 1 to -1, the angles crowded into the
/// forward peak, which is about 1/x radians wide) and `pdf[j]`, the phase
/// function per steradian there, for j < count. SK_ERR_NULL for NULL
/// pointers; SK_ERR_OVERLAP for overlapping arrays; SK_ERR_SIZE for count <
/// 2, a malformed sphere, or too many angles to give distinct cosines.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mie_tabulate_f64(
    m: *const sk_mie_f64,
    cos_theta: *mut f64,
    pdf: *mut f64,
    count: usize,
) -> sk_status {
    if m.is_null() || cos_theta.is_null() || pdf.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(mie) = (unsafe { load(m) }) else {
        return sk_status::SK_ERR_SIZE;
    };
    if count < 2 || !fits::<f64>(count) {
        return sk_status::SK_ERR_SIZE;
    }
    // Both arrays are written through &mut slices: they must not share memory.
    if overlaps(cos_theta.cast_const(), pdf.cast_const(), count) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let c = match unsafe { slice_out(cos_theta, count) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let p = match unsafe { slice_out(pdf, count) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    match mie.tabulate(c, p) {
        Ok(()) => sk_status::SK_OK,
        Err(e) => e.into(),
    }
}

// Layout: sk_complex_f64 is Complex (both repr(C) pairs of f64), so the
// caller's buffer is used as it is.
const _: () = {
    use core::mem::{align_of, size_of};
    assert!(size_of::<sk_complex_f64>() == size_of::<Complex>());
    assert!(align_of::<sk_complex_f64>() == align_of::<Complex>());
};
