//! Rayleigh by each of Frisvad's methods, and the physical coefficients.

use super::{
    CRng, CVec, SOA_BLOCK, check_soa, sk_rng, sk_status, sk_vec3, sk_vec3_f64, slice_out,
    soa_blocks, write_result,
};
use crate::math::real::Real;
use crate::phase::rayleigh::{self, RayleighMethod};

/// The sampling methods of Frisvad (2011) for `sk_rayleigh_*` (passed as
/// uint32_t; other values give SK_ERR_METHOD).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_rayleigh_method {
    /// von Neumann cube + acceptance (1 + mu^2)/2.
    SK_RAYLEIGH_REJECT_CUBE = 0,
    /// Spherical-coordinate isotropic direction + acceptance (1 + mu^2)/2.
    SK_RAYLEIGH_REJECT_SPHERICAL = 1,
    /// mu = cos(pi xi) with Frisvad's corrected bound.
    SK_RAYLEIGH_BARANOSKI = 2,
    /// mu = 2 xi - 1 with acceptance, then rotated about w_in.
    SK_RAYLEIGH_SIMPLIFIED = 3,
    /// Cardano inversion with sk_cbrt.
    SK_RAYLEIGH_DIRECT = 4,
    /// Cardano inversion with sk_cbrt_fast.
    SK_RAYLEIGH_DIRECT_FAST = 5,
    /// Cardano inversion with cbrt(|s| + sqrt(s^2 + 1)) found as the root of
    /// w^6 - 2|s| w^3 - 1 (cubic minimax seed + one Halley step): as accurate
    /// as DIRECT, branch-free, no sqrt or cbrt; the default of
    /// sk_phase_new_rayleigh. (An addition to Frisvad's six.)
    SK_RAYLEIGH_DIRECT_MINIMAX = 6,
    /// Cubic Hermite table of the inverse CDF (128 intervals, built at compile
    /// time): max error 4e-9, O(1), the fastest accurate direction sampler.
    /// (An addition to Frisvad's six.)
    SK_RAYLEIGH_TABLE = 7,
}

same_values!(sk_rayleigh_method = RayleighMethod:
    SK_RAYLEIGH_REJECT_CUBE = RejectCube,
    SK_RAYLEIGH_REJECT_SPHERICAL = RejectSpherical,
    SK_RAYLEIGH_BARANOSKI = Baranoski,
    SK_RAYLEIGH_SIMPLIFIED = Simplified,
    SK_RAYLEIGH_DIRECT = Direct,
    SK_RAYLEIGH_DIRECT_FAST = DirectFast,
    SK_RAYLEIGH_DIRECT_MINIMAX = DirectMinimax,
    SK_RAYLEIGH_TABLE = Table,
);

unsafe fn sample_dir<V: CVec>(method: u32, w_in: V, rng: *mut sk_rng, out: *mut V) -> sk_status {
    let Ok(m) = RayleighMethod::try_from(method) else {
        return sk_status::SK_ERR_METHOD;
    };
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let dir = rayleigh::sample_dir(m, w_in.to_vec(), &mut r);
    unsafe { write_result(out, Ok(V::from_vec(dir))) }
}

unsafe fn sample_dir_n<T: Real>(
    method: u32,
    w: [*const T; 3],
    rng: *mut sk_rng,
    out: [*mut T; 3],
    n: usize,
) -> sk_status {
    let Ok(m) = RayleighMethod::try_from(method) else {
        return sk_status::SK_ERR_METHOD;
    };
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    if let Err(e) = check_soa(&w, &out.map(|p| (p, false)), n) {
        return e;
    }
    let run = |i: &[[T; SOA_BLOCK]; 3], o: &mut [[T; SOA_BLOCK]; 3], len: usize| {
        let [ix, iy, iz] = i.each_ref().map(|x| x.get(..len).unwrap_or(&[]));
        let [ox, oy, oz] = o.each_mut().map(|x| x.get_mut(..len).unwrap_or(&mut []));
        rayleigh::sample_dir_fill(m, [ix, iy, iz], &mut r, [ox, oy, oz]);
    };
    unsafe { soa_blocks(w, out, n, run) };
    sk_status::SK_OK
}

unsafe fn sample_cos_n<T: Real>(method: u32, rng: *mut sk_rng, out: *mut T, n: usize) -> sk_status {
    let Ok(m) = RayleighMethod::try_from(method) else {
        return sk_status::SK_ERR_METHOD;
    };
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    match unsafe { slice_out(out, n) } {
        Ok(s) => {
            rayleigh::sample_cos_fill(m, &mut r, s);
            sk_status::SK_OK
        }
        Err(e) => e,
    }
}

/// A Rayleigh-distributed propagation direction about the unit vector w_in,
/// by `method` (sk_rayleigh_method), with uniforms from `rng`.
/// SK_ERR_METHOD for an unknown method; SK_ERR_NULL for a NULL rng, NULL
/// rng->next_u64 or NULL dir_out.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_sample_dir(
    method: super::enum_arg::sk_rayleigh_method,
    w_in: sk_vec3,
    rng: *mut sk_rng,
    dir_out: *mut sk_vec3,
) -> sk_status {
    unsafe { sample_dir(method.0, w_in, rng, dir_out) }
}

/// Double twin of `sk_rayleigh_sample_dir`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_sample_dir_f64(
    method: super::enum_arg::sk_rayleigh_method,
    w_in: sk_vec3_f64,
    rng: *mut sk_rng,
    dir_out: *mut sk_vec3_f64,
) -> sk_status {
    unsafe { sample_dir(method.0, w_in, rng, dir_out) }
}

/// n Rayleigh-distributed cosines by `method`, with uniforms from `rng`.
/// SK_ERR_METHOD for an unknown method; SK_ERR_NULL for a NULL rng or
/// callback, or NULL cos_out with n > 0; n = 0 is SK_OK.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_sample_cos_n(
    method: super::enum_arg::sk_rayleigh_method,
    rng: *mut sk_rng,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(method.0, rng, cos_out, n) }
}

/// Double twin of `sk_rayleigh_sample_cos_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_sample_cos_n_f64(
    method: super::enum_arg::sk_rayleigh_method,
    rng: *mut sk_rng,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(method.0, rng, cos_out, n) }
}

/// Rayleigh scattering cross section of a small sphere, 128 pi^5 a^2 /
/// (3 lambda^4) with polarizability a = r^3 (n^2 - 1)/(n^2 + 2). Wavelength
/// and radius in one length unit L (result in L^2); rel_index is the
/// particle's refractive index over the medium's. NaN unless all three are
/// finite and positive.
#[unsafe(no_mangle)]
pub extern "C" fn sk_rayleigh_cross_section_f64(
    wavelength: f64,
    radius: f64,
    rel_index: f64,
) -> f64 {
    rayleigh::cross_section(wavelength, radius, rel_index).unwrap_or(f64::NAN)
}

/// Rayleigh scattering coefficient N * cross section (per L) for
/// number_density N per L^3 (finite, >= 0). NaN on invalid arguments.
#[unsafe(no_mangle)]
pub extern "C" fn sk_rayleigh_scattering_coeff_f64(
    number_density: f64,
    wavelength: f64,
    radius: f64,
    rel_index: f64,
) -> f64 {
    rayleigh::scattering_coeff(number_density, wavelength, radius, rel_index).unwrap_or(f64::NAN)
}

/// Rayleigh directions for n rays, structure of arrays: for each `i < n` in
/// order, `(out_x[i], out_y[i], out_z[i])` is what sk_rayleigh_sample_dir
/// would give for `(w_x[i], w_y[i], w_z[i])` with the same rng, bit for bit
/// (the generator is advanced exactly as by n scalar calls). An output may be
/// the same array as an input (in place); other overlaps are SK_ERR_OVERLAP.
/// SK_ERR_METHOD for an unknown method; SK_ERR_NULL for a NULL rng, NULL
/// rng->next_u64 or a NULL array with n > 0; SK_ERR_SIZE if n floats cannot
/// exist. On error nothing is written; n = 0 is SK_OK.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_rayleigh_sample_dir_n(
    method: super::enum_arg::sk_rayleigh_method,
    w_x: *const f32,
    w_y: *const f32,
    w_z: *const f32,
    rng: *mut sk_rng,
    out_x: *mut f32,
    out_y: *mut f32,
    out_z: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_dir_n(method.0, [w_x, w_y, w_z], rng, [out_x, out_y, out_z], n) }
}

/// Double twin of `sk_rayleigh_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_rayleigh_sample_dir_n_f64(
    method: super::enum_arg::sk_rayleigh_method,
    w_x: *const f64,
    w_y: *const f64,
    w_z: *const f64,
    rng: *mut sk_rng,
    out_x: *mut f64,
    out_y: *mut f64,
    out_z: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_dir_n(method.0, [w_x, w_y, w_z], rng, [out_x, out_y, out_z], n) }
}
