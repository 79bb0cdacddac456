//! The choosers from C: the cheapest adequate model for a droplet (fog fit,
//! Mie, measured data).

use super::*;
use crate::ffi::mie::sk_complex_f64;
use crate::ffi::{fits, slice_in, slice_out};

/// The models sk_phase_new_particle_mie_f64 chooses from.
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_particle_model {
    /// Uniform over the sphere.
    SK_PARTICLE_ISOTROPIC = 0,
    /// Henyey-Greenstein with the best-fit g.
    SK_PARTICLE_HG = 1,
    /// Rayleigh.
    SK_PARTICLE_RAYLEIGH = 2,
    /// Draine with the best-fit g and alpha.
    SK_PARTICLE_DRAINE = 3,
    /// The fog fit (Jendersie & d'Eon 2023).
    SK_PARTICLE_FOG = 4,
    /// A table of the exact Mie phase function: build it with sk_mie_new_f64,
    /// sk_mie_table_len_f64, sk_mie_tabulate_f64 and sk_table_new_measured_f64.
    SK_PARTICLE_MIE_TABLE = 5,
    /// Two Henyey-Greenstein lobes with the best-fit g1, g2 and weight
    /// (considered only without a table).
    SK_PARTICLE_TWO_LOBE_HG = 6,
    /// Fournier-Forand with the best-fit n and nu (considered only without
    /// a table).
    SK_PARTICLE_FOURNIER_FORAND = 7,
    /// w HG(g) + (1 - w) Rayleigh with the best-fit g and w (considered only
    /// without a table), sampled as a fog mixture with a Rayleigh lobe.
    SK_PARTICLE_RAYLEIGH_HG = 8,
}

/// What sk_phase_new_particle_mie_f64 found.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_particle_choice_f64 {
    /// The chosen model, an sk_particle_model.
    pub model: crate::ffi::enum_arg::sk_particle_model,
    /// 1 when distance is within the tolerance (without a table none may
    /// be, and the closest model is returned), else 0.
    pub within_tolerance: u32,
    /// The chosen model's total-variation distance to the Mie phase
    /// function (0 for the table, the reference itself; the table built at
    /// sk_mie_table_len_f64 adds at most 1.2e-3 for x <= 1000).
    pub distance: f64,
    /// Each candidate's best distance: isotropic, HG, Rayleigh, Draine, fog
    /// fit, two-lobe HG, Fournier-Forand, Rayleigh + HG (NaN for the fog
    /// fit beyond 50 um, and for the last three when a table is allowed:
    /// they are fitted only without one).
    pub distances: [f64; 8],
    /// The droplets' size parameter.
    pub x: f64,
    /// The refractive index used.
    pub m: sk_complex_f64,
    /// The chosen model ready to sample; unconstructed (every query NaN)
    /// for SK_PARTICLE_MIE_TABLE.
    pub phase: sk_phase_f64,
}

/// The sk_complex_f64 values sk_phase_new_particle_mie_f64 needs in buf; 0 for input
/// it rejects. m = {0, 0} means water at that wavelength (0.182 to 1.129
/// um).
#[unsafe(no_mangle)]
pub extern "C" fn sk_particle_mie_len_f64(
    diameter_um: f64,
    wavelength_um: f64,
    m: sk_complex_f64,
) -> usize {
    let m = (m.re != 0.0 || m.im != 0.0).then(|| crate::mie::Complex::new(m.re, m.im));
    crate::choose::mie::buffer_len(diameter_um, wavelength_um, m).unwrap_or(0)
}

/// The honest chooser: the cheapest model whose total-variation distance to
/// the exact Mie phase function of droplets of diameter_um micrometres in
/// air at vacuum wavelength wavelength_um is within tolerance (0 <
/// tolerance < 1). m is the droplets' relative index (re + i im, im >= 0
/// absorbs); {0, 0} means water (Daimon & Masumura 2007, 0.182 to 1.129
/// um). Candidates in order of sampling cost: isotropic, HG, Rayleigh, then
/// with allow_table != 0 the Mie table, else Draine, two-lobe HG, the fog
/// fit and Fournier-Forand (each with best-fit parameters). buf
/// holds len >= sk_particle_mie_len_f64 values, work work_len >= 4096
/// doubles. Takes about 0.15 s at x = 300 with a table, 0.25 to 0.4 s
/// without: build once per medium.
/// SK_ERR_NULL for NULL buf, work or out; SK_ERR_DOMAIN for invalid input;
/// SK_ERR_OVERLAP for overlapping buffers; SK_ERR_SIZE for short buffers. *out is written
/// only on success.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_phase_new_particle_mie_f64(
    diameter_um: f64,
    wavelength_um: f64,
    m: sk_complex_f64,
    tolerance: f64,
    allow_table: u32,
    buf: *mut sk_complex_f64,
    len: usize,
    work: *mut f64,
    work_len: usize,
    out: *mut sk_particle_choice_f64,
) -> sk_status {
    use crate::choose::mie::choose_mie;
    use crate::mie::Complex;
    if buf.is_null() || work.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    if !fits::<Complex>(len) || !fits::<f64>(work_len) {
        return sk_status::SK_ERR_SIZE;
    }
    let bytes = |n: usize, size: usize| n.saturating_mul(size);
    let (b0, w0) = (buf as usize, work as usize);
    let (b1, w1) = (
        b0.saturating_add(bytes(len, 16)),
        w0.saturating_add(bytes(work_len, 8)),
    );
    if b0 < w1 && w0 < b1 {
        return sk_status::SK_ERR_OVERLAP;
    }
    let slices = unsafe {
        (
            slice_out(buf.cast::<Complex>(), len),
            slice_out(work, work_len),
        )
    };
    let (buf, work) = match slices {
        (Ok(b), Ok(w)) => (b, w),
        (Err(e), _) | (_, Err(e)) => return e,
    };
    let m = (m.re != 0.0 || m.im != 0.0).then(|| Complex::new(m.re, m.im));
    let r = choose_mie(
        diameter_um,
        wavelength_um,
        m,
        tolerance,
        allow_table != 0,
        buf,
        work,
    )
    .map(choice_to_c);
    unsafe { write_result(out, r) }
}

fn choice_to_c(c: crate::choose::mie::MieChoice) -> sk_particle_choice_f64 {
    use crate::choose::fog::Model;
    let model = match c.model {
        Model::Isotropic => sk_particle_model::SK_PARTICLE_ISOTROPIC,
        Model::HenyeyGreenstein => sk_particle_model::SK_PARTICLE_HG,
        Model::Rayleigh => sk_particle_model::SK_PARTICLE_RAYLEIGH,
        Model::Draine => sk_particle_model::SK_PARTICLE_DRAINE,
        Model::Fog => sk_particle_model::SK_PARTICLE_FOG,
        Model::TwoLobeHg => sk_particle_model::SK_PARTICLE_TWO_LOBE_HG,
        Model::FournierForand => sk_particle_model::SK_PARTICLE_FOURNIER_FORAND,
        Model::RayleighHg => sk_particle_model::SK_PARTICLE_RAYLEIGH_HG,
        _ => sk_particle_model::SK_PARTICLE_MIE_TABLE,
    };
    sk_particle_choice_f64 {
        model: crate::ffi::enum_arg::sk_particle_model(model as u32),
        within_tolerance: u32::from(c.within_tolerance),
        distance: c.distance,
        distances: c.distances,
        x: c.x,
        m: sk_complex_f64 {
            re: c.m.re,
            im: c.m.im,
        },
        phase: c.phase.map_or(sk_phase_f64::ZEROED, store),
    }
}

/// The cheapest model within total-variation distance `tolerance` (0 <
/// tolerance < 1) of a phase function measured or tabulated at m >= 2
/// cosines, as sk_table_new_measured_f64 takes it (`cos_theta[j]` strictly
/// monotone within [-1, 1], `pdf[j]` finite and non-negative, any scale;
/// linear in cos theta between the points): a size distribution's Mie
/// average from sk_polydisperse_average_f64, a measured volume scattering
/// function. Candidates as sk_phase_new_particle_mie_f64 without the fog fit
/// (`distances[4]` is NaN); SK_PARTICLE_MIE_TABLE means
/// sk_table_new_measured_f64 over the same data. x and m of the result are
/// NaN. work holds work_len >= 4096 doubles and must not overlap the data.
/// Takes about 0.25 s without a table: build once per medium. SK_ERR_NULL
/// for NULL pointers; SK_ERR_DOMAIN for a tolerance outside (0, 1), invalid
/// data; SK_ERR_OVERLAP for overlapping arrays; SK_ERR_SIZE for m < 2 or a short work. *out
/// is written only on success.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_particle_measured_f64(
    cos_theta: *const f64,
    pdf: *const f64,
    m: usize,
    tolerance: f64,
    allow_table: u32,
    work: *mut f64,
    work_len: usize,
    out: *mut sk_particle_choice_f64,
) -> sk_status {
    use crate::choose::mie::choose_measured;
    if cos_theta.is_null() || pdf.is_null() || work.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    if !fits::<f64>(m) || !fits::<f64>(work_len) {
        return sk_status::SK_ERR_SIZE;
    }
    let range = |p: *const f64, n: usize| {
        let a = p as usize;
        (a, a.saturating_add(n.saturating_mul(8)))
    };
    let w = range(work, work_len);
    let apart = |(a0, a1): (usize, usize)| a1 <= w.0 || w.1 <= a0 || a0 == a1;
    if !(apart(range(cos_theta, m)) && apart(range(pdf, m))) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let slices = unsafe {
        (
            slice_in(cos_theta, m),
            slice_in(pdf, m),
            slice_out(work, work_len),
        )
    };
    let (c, p, work) = match slices {
        (Ok(c), Ok(p), Ok(w)) => (c, p, w),
        (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => return e,
    };
    let r = choose_measured(c, p, tolerance, allow_table != 0, work).map(choice_to_c);
    unsafe { write_result(out, r) }
}
