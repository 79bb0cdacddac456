//! What a phase holds, for a host to hand to a device.

use super::*;

/// Which phase function an sk_phase holds (its tag, also the value of the
/// enum's discriminant in Rust).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_phase_model {
    /// Uniform over the sphere: no parameters.
    SK_PHASE_ISOTROPIC = 1,
    /// Rayleigh: no parameters.
    SK_PHASE_RAYLEIGH = 2,
    /// Depolarised Rayleigh: `params[0]` = rho.
    SK_PHASE_RAYLEIGH_DEPOLARIZED = 3,
    /// Henyey-Greenstein: `params[0]` = g.
    SK_PHASE_HG = 4,
    /// Draine (Cornette-Shanks for alpha = 1): `params[0]` = g, `params[1]` = alpha.
    SK_PHASE_DRAINE = 5,
    /// The fog mixture: params = g_hg, g_d, alpha, w_d.
    SK_PHASE_FOG = 6,
    /// The Gegenbauer kernel: `params[0]` = alpha, `params[1]` = g.
    SK_PHASE_GEGENBAUER = 7,
    /// Fournier-Forand: `params[0]` = n, `params[1]` = nu = (3 - Junge
    /// slope)/2, `params[2]` = the backscatter fraction.
    SK_PHASE_FOURNIER_FORAND = 8,
}

/// What an sk_phase holds, for a host to hand to a device: the model (an
/// sk_phase_model) and its parameters (`count` of them, the rest 0).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_params {
    /// An sk_phase_model.
    pub model: crate::ffi::enum_arg::sk_phase_model,
    /// How many of `params` the model uses (0 to 4).
    pub count: u32,
    /// The parameters, in the order sk_phase_model lists them.
    pub params: [f32; 4],
}

/// What an sk_phase_f64 holds; see `sk_phase_params`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_params_f64 {
    /// An sk_phase_model.
    pub model: crate::ffi::enum_arg::sk_phase_model,
    /// How many of `params` the model uses (0 to 4).
    pub count: u32,
    /// The parameters.
    pub params: [f64; 4],
}

/// The model and parameters of a phase, in the order the C enum lists them.
fn model_params<T: Real>(p: &Phase<T>) -> (sk_phase_model, u32, [T; 4]) {
    use sk_phase_model::*;
    let z = T::ZERO;
    match *p {
        Phase::Isotropic(_) => (SK_PHASE_ISOTROPIC, 0, [z; 4]),
        Phase::Rayleigh(_) => (SK_PHASE_RAYLEIGH, 0, [z; 4]),
        Phase::RayleighDepolarized(r) => (SK_PHASE_RAYLEIGH_DEPOLARIZED, 1, [r.rho(), z, z, z]),
        Phase::HenyeyGreenstein(h) => (SK_PHASE_HG, 1, [h.g(), z, z, z]),
        Phase::Draine(d) => (SK_PHASE_DRAINE, 2, [d.g(), d.alpha(), z, z]),
        Phase::Fog(f) => {
            let (a, b, c, d) = f.params();
            (SK_PHASE_FOG, 4, [a, b, c, d])
        }
        Phase::Gegenbauer(k) => (SK_PHASE_GEGENBAUER, 2, [k.alpha(), k.g(), z, z]),
        Phase::FournierForand(f) => (
            SK_PHASE_FOURNIER_FORAND,
            3,
            [f.n(), f.nu(), f.backscatter(), z],
        ),
    }
}

/// Writes `make(model, count, params)` for the phase behind `p` to *out.
unsafe fn get_params<S: PhaseStore>(p: *const S, out: *mut S::Params) -> sk_status {
    if p.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let r = unsafe { load(p) }.ok_or(Error::Domain).map(|ph| {
        let (model, count, params) = model_params(ph);
        S::params(model as u32, count, params)
    });
    unsafe { write_result(out, r) }
}

/// Writes what `p` holds to *out. SK_ERR_NULL for NULL pointers;
/// SK_ERR_DOMAIN for an unconstructed phase (its tag is not a model).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_get_params(
    p: *const sk_phase,
    out: *mut sk_phase_params,
) -> sk_status {
    unsafe { get_params(p, out) }
}

/// Double twin of `sk_phase_get_params`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_get_params_f64(
    p: *const sk_phase_f64,
    out: *mut sk_phase_params_f64,
) -> sk_status {
    unsafe { get_params(p, out) }
}
