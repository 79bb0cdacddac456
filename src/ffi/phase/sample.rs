//! Sampling and evaluation: pdf, cdf, mean cosine, `cos θ`, directions and
//! their batches, and the inline sampler's constants.

use super::*;

/// cos theta by lobe: for a fog phase, the paper's sampler (u < w_d picks the
/// Draine lobe and u is rescaled and reused inside the lobe): exact in
/// distribution and cheaper than sk_phase_sample_cos, but not monotone in u.
/// For every other phase the same as sk_phase_sample_cos. NaN for a NULL or
/// unconstructed phase.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_by_lobe(p: *const sk_phase, u: f32) -> f32 {
    unsafe { load(p) }.map_or(f32::NAN, |ph| ph.sample_cos_by_lobe(u))
}

/// Double twin of `sk_phase_sample_cos_by_lobe`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_by_lobe_f64(p: *const sk_phase_f64, u: f64) -> f64 {
    unsafe { load(p) }.map_or(f64::NAN, |ph| ph.sample_cos_by_lobe(u))
}

/// Density per steradian at cos_theta in [-1, 1]; a cos_theta within 8 ulp
/// beyond +-1 (where a dot product of unit vectors rounds) is read at +-1,
/// and one further out has density 0 (the CDF is 0 or 1 there), in every
/// model (as the Rust `Phase` and the Python package). NaN for NaN, or a
/// NULL or unconstructed phase.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_pdf(p: *const sk_phase, cos_theta: f32) -> f32 {
    unsafe { pdf(p, cos_theta) }
}

/// Double twin of `sk_phase_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_pdf_f64(p: *const sk_phase_f64, cos_theta: f64) -> f64 {
    unsafe { pdf(p, cos_theta) }
}

/// Mean cosine (asymmetry parameter). NaN for a NULL or unconstructed phase.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_mean_cosine(p: *const sk_phase) -> f32 {
    unsafe { mean_cosine(p) }
}

/// Double twin of `sk_phase_mean_cosine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_mean_cosine_f64(p: *const sk_phase_f64) -> f64 {
    unsafe { mean_cosine(p) }
}

/// Inverse CDF: maps u in [0, 1] monotonically to cos theta in [-1, 1]
/// (u = 0 gives -1). u outside [0, 1] is clamped; NaN gives NaN, as does a
/// NULL or unconstructed phase (as in Rust; the Python package raises
/// ValueError for u outside [0, 1] or NaN instead).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos(p: *const sk_phase, u: f32) -> f32 {
    unsafe { sample_cos(p, u) }
}

/// Double twin of `sk_phase_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_f64(p: *const sk_phase_f64, u: f64) -> f64 {
    unsafe { sample_cos(p, u) }
}

/// What `sk_phase_cos_inline_sample` (include/scatterkit_inline.h) needs to
/// draw cos theta without a call into the library: fill it with
/// sk_phase_cos_inline_new, then treat it as read-only. For a
/// Henyey-Greenstein phase on x86, x86-64 and AArch64 (|g| >= 2^-10) it
/// holds the constants of the f32 sampler's double-precision formula, so
/// the inline function returns sk_phase_sample_cos's bits; for every other
/// phase the constants are 0 and the inline function calls
/// sk_phase_sample_cos.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_cos_inline {
    /// k, A and B of cos theta = A - B / (u' + k)^2, computed in double and
    /// rounded once to float; all 0 where the library is called instead.
    pub kab: [f64; 3],
    /// 1 where u' = 1 - u (g <= 0), else 0 (u' = u).
    pub mirror: u32,
    /// Zero.
    pub reserved: u32,
    /// The phase itself, for the calls that go to the library.
    pub phase: sk_phase,
}

/// Fills *out for sk_phase_cos_inline_sample from the phase *p (any model;
/// see sk_phase_cos_inline). SK_ERR_NULL for a NULL pointer; SK_ERR_DOMAIN
/// for an unconstructed phase. *out is written only on SK_OK. Float only,
/// with no double twin: the inline sampler exists to reproduce the float
/// sk_phase_sample_cos without a call (double callers call
/// sk_phase_sample_cos_f64).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cos_inline_new(
    p: *const sk_phase,
    out: *mut sk_phase_cos_inline,
) -> sk_status {
    if p.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let r = match unsafe { load(p) } {
        Some(ph) => {
            let (kab, mirror) = match ph {
                Phase::HenyeyGreenstein(h) => h.f64_path_constants().unwrap_or(([0.0; 3], false)),
                _ => ([0.0; 3], false),
            };
            Ok(sk_phase_cos_inline {
                kab,
                mirror: mirror as u32,
                reserved: 0,
                // SAFETY: p is non-NULL and points to an sk_phase.
                phase: unsafe { p.read() },
            })
        }
        None => Err(Error::Domain),
    };
    unsafe { write_result(out, r) }
}

/// CDF: P(cos theta <= cos_theta), the inverse map of `sk_phase_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cdf(p: *const sk_phase, cos_theta: f32) -> f32 {
    unsafe { cdf(p, cos_theta) }
}

/// Double twin of `sk_phase_cdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_cdf_f64(p: *const sk_phase_f64, cos_theta: f64) -> f64 {
    unsafe { cdf(p, cos_theta) }
}

/// Scattered propagation direction about the unit vector w_in: cos theta =
/// sk_phase_sample_cos(p, u1), azimuth 2 pi u2 in the basis sk_onb(w_in).
/// Writes the direction's density per steradian to pdf_out unless it is NULL.
/// A NULL or unconstructed phase gives NaN (direction and pdf).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_dir(
    p: *const sk_phase,
    w_in: sk_vec3,
    u1: f32,
    u2: f32,
    pdf_out: *mut f32,
) -> sk_vec3 {
    unsafe { sample_dir(p, w_in, u1, u2, pdf_out) }
}

/// Double twin of `sk_phase_sample_dir`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_dir_f64(
    p: *const sk_phase_f64,
    w_in: sk_vec3_f64,
    u1: f64,
    u2: f64,
    pdf_out: *mut f64,
) -> sk_vec3_f64 {
    unsafe { sample_dir(p, w_in, u1, u2, pdf_out) }
}

/// `cos_out[i] = sk_phase_sample_cos(p, u[i])` for `i < n`. `u` and `cos_out`
/// may be the same array; other overlaps give SK_ERR_OVERLAP. SK_ERR_DOMAIN if
/// any `u[i]` is NaN or outside `[0, 1]`, or p is unconstructed; SK_ERR_NULL for NULL
/// p, or NULL arrays with n > 0; SK_ERR_SIZE if n floats cannot exist. On
/// error nothing is written; n = 0 is SK_OK.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_n(
    p: *const sk_phase,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(p, u, cos_out, n) }
}

/// The portable tier's model of the phase at `p`, checked as a batch
/// checks it ([`load_batch`], then [`portable_model`]).
unsafe fn portable_at(p: *const sk_phase) -> Result<crate::portable::Model, sk_status> {
    portable_model(unsafe { load_batch(p) }?)
}

/// The portable tier's cosines for uniforms in `[0, 1]`, the header's bits.
fn portable_cos_n(phase: &crate::portable::Model, u: &[f32], out: &mut [f32]) {
    use crate::portable::{self, Model};
    match phase {
        Model::Hg(h) => portable::hg_sample_cos_n_in_range(h, u, out),
        Model::Rayleigh => portable::rayleigh_sample_cos_n(u, out),
        Model::Isotropic => portable::isotropic_sample_cos_n(u, out),
    }
}

/// The portable tier's model for a phase, chosen once per batch:
/// SK_ERR_METHOD for a model the tier has no batch for.
fn portable_model(ph: &Phase<f32>) -> Result<crate::portable::Model, sk_status> {
    use crate::portable::{Hg, Model};
    match ph {
        Phase::HenyeyGreenstein(h) => Hg::new(h.g())
            .map(Model::Hg)
            .ok_or(sk_status::SK_ERR_DOMAIN),
        Phase::Isotropic(_) => Ok(Model::Isotropic),
        Phase::Rayleigh(_) => Ok(Model::Rayleigh),
        _ => Err(sk_status::SK_ERR_METHOD),
    }
}

/// The portable f32 tier in bulk (include/scatterkit_portable.h): for an
/// isotropic, Henyey-Greenstein or Rayleigh phase, `cos_out[i]` is the
/// cosine that header returns for `u[i]` (`2u - 1`, `skp_hg_sample_cos`
/// with the constants of `skp_hg_new(g)`, `skp_rayleigh_sample_cos`), bit
/// for bit, computed in float alone. Within 1.6e-7 of the exact cosine for
/// HG (`sk_phase_sample_cos_n`, evaluated in double and rounded once:
/// 6e-8) and 6e-8 for Rayleigh: the fast end of the chart.
/// Errors as `sk_phase_sample_cos_n`; SK_ERR_METHOD for any other model.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_n_portable(
    p: *const sk_phase,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    let phase = match unsafe { portable_at(p) } {
        Ok(m) => m,
        Err(e) => return e,
    };
    unsafe {
        map_arrays(u, cos_out, n, check_uniforms, |u, out| {
            portable_cos_n(&phase, u, out);
            Ok(())
        })
    }
}

/// Double twin of `sk_phase_sample_cos_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_sample_cos_n_f64(
    p: *const sk_phase_f64,
    u: *const f64,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(p, u, cos_out, n) }
}

/// Directions for n rays at once, structure of arrays (the layout of
/// wavefront renderers): for each `i < n`, the direction
/// `sk_phase_sample_dir(p, (w_x[i], w_y[i], w_z[i]), u1[i], u2[i], &pdf)`
/// goes to `(out_x[i], out_y[i], out_z[i])` and its density to `pdf_out[i]`,
/// bit for bit the scalar call's. pdf_out may be NULL. An output array may
/// be the same array as an input (in place); any other overlap, or outputs
/// overlapping each other, is SK_ERR_OVERLAP; SK_ERR_DOMAIN for any `u1[i]` or `u2[i]` NaN
/// or outside [0, 1], or an unconstructed p. SK_ERR_NULL for a NULL p or a
/// NULL array (other than pdf_out) with n > 0; SK_ERR_SIZE if n floats
/// cannot exist. On error nothing is written; n = 0 is SK_OK. The loop runs
/// in blocks of 64 through stack buffers and vectorises for isotropic and
/// HG, and for Rayleigh in double (its float table lookup runs at about the
/// scalar call's pace).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_n(
    p: *const sk_phase,
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
    unsafe { sample_dir_n(p, w, u1, u2, out, pdf_out, n) }
}

/// The portable f32 tier's directions in bulk, structure of arrays, with
/// the arguments, checks and errors of `sk_phase_sample_dir_n`: for an
/// isotropic, Henyey-Greenstein or Rayleigh phase, direction `i` is
/// `skp_hg_sample_dir` (with the constants of `skp_hg_new(g)`) or
/// `skp_rayleigh_sample_dir` of include/scatterkit_portable.h at
/// `(w[i], u1[i], u2[i])`, bit for bit (isotropic: `skp_direction_about` at
/// `skp_isotropic_sample_cos_sin(u1[i])`, density 1/(4 pi)); float
/// arithmetic throughout, vectorised. SK_ERR_METHOD for any other model.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_n_portable(
    p: *const sk_phase,
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
    use crate::portable::sample_dir_n;
    let phase = match unsafe { portable_at(p) } {
        Ok(m) => m,
        Err(e) => return e,
    };
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe {
        crate::ffi::verbs::dir_block_slices((w, u1, u2), (out, pdf_out), n, |w, u, o, pdf| {
            sample_dir_n(&phase, w, u, o, pdf)
        })
    }
}

/// `sk_phase_sample_dir_n` with each direction's cos theta to `cos_out[i]`
/// (the cosine the direction was built from, `sk_phase_sample_cos(p,
/// u1[i])` bit for bit), for codes that tally the scattering angle
/// (angular scoring, momentum transfer) beside the direction. cos_out must
/// not be NULL (SK_ERR_NULL for n > 0); pdf_out may be. Arrays, overlaps
/// (cos_out counts as an output) and statuses as `sk_phase_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_cos_n(
    p: *const sk_phase,
    w_x: *const f32,
    w_y: *const f32,
    w_z: *const f32,
    u1: *const f32,
    u2: *const f32,
    out_x: *mut f32,
    out_y: *mut f32,
    out_z: *mut f32,
    cos_out: *mut f32,
    pdf_out: *mut f32,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_cos_n(p, w, u1, u2, out, cos_out, pdf_out, n) }
}

/// Double twin of `sk_phase_sample_dir_cos_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_cos_n_f64(
    p: *const sk_phase_f64,
    w_x: *const f64,
    w_y: *const f64,
    w_z: *const f64,
    u1: *const f64,
    u2: *const f64,
    out_x: *mut f64,
    out_y: *mut f64,
    out_z: *mut f64,
    cos_out: *mut f64,
    pdf_out: *mut f64,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_cos_n(p, w, u1, u2, out, cos_out, pdf_out, n) }
}

/// The portable f32 tier's directions with their cos theta:
/// `sk_phase_sample_dir_n_portable` with `cos_out[i]` the `cos_theta` of
/// the header's `skp_dir_sample` at the same inputs, bit for bit. Arrays
/// and statuses as `sk_phase_sample_dir_cos_n`; SK_ERR_METHOD for a model
/// other than isotropic, Henyey-Greenstein and Rayleigh.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_cos_n_portable(
    p: *const sk_phase,
    w_x: *const f32,
    w_y: *const f32,
    w_z: *const f32,
    u1: *const f32,
    u2: *const f32,
    out_x: *mut f32,
    out_y: *mut f32,
    out_z: *mut f32,
    cos_out: *mut f32,
    pdf_out: *mut f32,
    n: usize,
) -> sk_status {
    use crate::portable;
    let phase = match unsafe { portable_at(p) } {
        Ok(m) => m,
        Err(e) => return e,
    };
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe {
        crate::ffi::verbs::dir_cos_block_slices(
            (w, u1, u2),
            (out, cos_out, pdf_out),
            n,
            |w, u, o, cos, pdf| {
                portable::sample_dir_n(&phase, w, u, o, pdf);
                portable_cos_n(&phase, u[0], cos);
            },
        )
    }
}

/// Double twin of `sk_phase_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_sample_dir_n_f64(
    p: *const sk_phase_f64,
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
    unsafe { sample_dir_n(p, w, u1, u2, out, pdf_out, n) }
}
