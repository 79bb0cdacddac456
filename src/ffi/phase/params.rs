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
    /// slope)/2 (in (-1, -FLT_MIN], or -DBL_MIN for the double twin),
    /// `params[2]` = the backscatter fraction.
    SK_PHASE_FOURNIER_FORAND = 8,
    /// Schlick's phase function (1 - k^2)/(4 pi (1 - k mu)^2): `params[0]` = k.
    SK_PHASE_SCHLICK = 9,
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

/// Writes `make(model, count, params)` for the phase behind `p` to *out.
unsafe fn get_params<S: PhaseStore>(p: *const S, out: *mut S::Params) -> sk_status {
    if p.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let r = unsafe { load(p) }.ok_or(Error::Domain).map(|ph| {
        let (model, count, params) = ph.params();
        S::params(model, count as u32, params)
    });
    unsafe { write_result(out, r) }
}

/// The phase of `model` from `n` parameters at `params`.
unsafe fn new_from_params<S: PhaseStore>(
    model: crate::ffi::enum_arg::sk_phase_model,
    params: *const S::T,
    n: usize,
    out: *mut S,
) -> sk_status {
    let p = match unsafe { crate::ffi::slice_in(params, n) } {
        Ok(p) => p,
        Err(e) => return e,
    };
    unsafe { construct(out, Phase::from_params(model.0, p)) }
}

/// Builds the phase function of `model` (an sk_phase_model) from its `n`
/// parameters at `params`, in the order sk_phase_model lists them: the
/// inverse of sk_phase_get_params (`sk_phase_new(q.model, q.params,
/// q.count, &p)` rebuilds what q describes). It checks them as the model's
/// own constructor does. SK_ERR_NULL for a NULL out, or NULL params with
/// n > 0; SK_ERR_METHOD for an unknown model; SK_ERR_SIZE for another
/// number of parameters than the model has; SK_ERR_DOMAIN for values out
/// of range.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new(
    model: crate::ffi::enum_arg::sk_phase_model,
    params: *const f32,
    n: usize,
    out: *mut sk_phase,
) -> sk_status {
    unsafe { new_from_params(model, params, n, out) }
}

/// Double twin of `sk_phase_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_phase_new_f64(
    model: crate::ffi::enum_arg::sk_phase_model,
    params: *const f64,
    n: usize,
    out: *mut sk_phase_f64,
) -> sk_status {
    unsafe { new_from_params(model, params, n, out) }
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
