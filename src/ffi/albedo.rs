//! The multiple-scattering albedo of a layer and its inverse.

use super::phase::load;
use super::{CRng, sk_phase_f64, sk_rng, sk_status, write_result};
use crate::error::Error;
use crate::transport::albedo::{AlbedoCurve, FINE, Illumination, Layer, NODES};

/// Nodes of an sk_albedo_curve_f64: omega_k = 1 - (k/64)^2, k = 0..64.
pub const SK_ALBEDO_NODES: usize = 65;
const _: () = assert!(SK_ALBEDO_NODES == NODES);

/// Fine nodes of an sk_albedo_curve_f64 between the first two:
/// omega_j = 1 - 4^-(j+1)/4096, j = 0..9.
pub const SK_ALBEDO_FINE: usize = 10;
const _: () = assert!(SK_ALBEDO_FINE == FINE);

/// The multiple-scattering albedo of a layer as a function of the
/// single-scattering albedo omega, from sk_albedo_curve_new_f64: at
/// omega_k = 1 - (k/64)^2, k = 0..64, the albedo `rho[k]` and its standard
/// error `se[k]`, and between the first two nodes (where a slab thick
/// against its diffusion length bends) at omega_j = 1 - 4^-(j+1)/4096,
/// j = 0..9, `fine_rho[j]` and `fine_se[j]`; the functions below
/// interpolate between them. A plain value: copy it, store it, read the
/// nodes. A curve whose fine arrays are all zero (a semi-infinite layer's,
/// smooth there, or one stored from the coarse nodes alone) is
/// interpolated between the first two nodes by the cubic through the
/// first four, which misses a slab's bend.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_albedo_curve_f64 {
    /// The albedo at omega_k.
    pub rho: [f64; SK_ALBEDO_NODES],
    /// Its standard error.
    pub se: [f64; SK_ALBEDO_NODES],
    /// Paths traced.
    pub paths: u64,
    /// The albedo at the fine node omega_j.
    pub fine_rho: [f64; SK_ALBEDO_FINE],
    /// Its standard error.
    pub fine_se: [f64; SK_ALBEDO_FINE],
}

/// The curve (all-zero fine arrays: the coarse nodes alone, as
/// `from_stored` reads them).
fn curve(c: &sk_albedo_curve_f64) -> AlbedoCurve {
    AlbedoCurve::from_stored(c.rho, c.se, c.fine_rho, c.fine_se, c.paths)
}

/// Traces `paths` paths through a plane-parallel layer with index-matched
/// faces, scattering by `phase` (double): semi-infinite for tau = +INFINITY,
/// else a slab of optical thickness tau (finite, > 0); lit diffusely
/// (uniform radiance: the spherical albedo the material standards fit) for
/// mu0 = 0, else by a beam at cos theta_0 = mu0 in (0, 1]. One set of
/// paths with omega = 1 gives the albedo at every omega (a path leaving the
/// lit face after N scatterings counts omega^N). SK_ERR_NULL for NULL
/// pointers or callback; SK_ERR_DOMAIN for an unconstructed phase,
/// paths = 0, or a bad tau or mu0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_albedo_curve_new_f64(
    phase: *const sk_phase_f64,
    tau: f64,
    mu0: f64,
    paths: u64,
    rng: *mut sk_rng,
    out: *mut sk_albedo_curve_f64,
) -> sk_status {
    if phase.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    let Some(p) = (unsafe { load(phase) }) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    let layer = if tau == f64::INFINITY {
        Layer::SemiInfinite
    } else {
        Layer::Slab(tau)
    };
    let light = if mu0 == 0.0 {
        Illumination::Diffuse
    } else {
        Illumination::Directional(mu0)
    };
    let result = AlbedoCurve::simulate(p, layer, light, paths, &mut r).map(|c| {
        let (rho, se) = c.nodes();
        let (fine_rho, fine_se) = c.fine_nodes().unwrap_or(([0.0; FINE], [0.0; FINE]));
        sk_albedo_curve_f64 {
            rho,
            se,
            paths: c.paths(),
            fine_rho,
            fine_se,
        }
    });
    unsafe { write_result(out, result) }
}

/// The multiple-scattering albedo at single-scattering albedo omega in
/// [0, 1] (monotone cubic between the nodes); NaN outside, for NaN, or a
/// NULL curve.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_albedo_curve_albedo_f64(
    c: *const sk_albedo_curve_f64,
    omega: f64,
) -> f64 {
    // SAFETY: a non-NULL c points to a curve (module contract).
    unsafe { c.as_ref() }.map_or(f64::NAN, |c| curve(c).albedo(omega))
}

/// The error (one standard deviation) of sk_albedo_curve_albedo_f64 at
/// omega, Monte Carlo and interpolation together; NaN as there.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_albedo_curve_std_error_f64(
    c: *const sk_albedo_curve_f64,
    omega: f64,
) -> f64 {
    // SAFETY: as above.
    unsafe { c.as_ref() }.map_or(f64::NAN, |c| curve(c).std_error(omega))
}

/// The single-scattering albedo whose multiple-scattering albedo is
/// `albedo`, written to omega_out. SK_ERR_NULL for NULL pointers;
/// SK_ERR_DOMAIN for NaN or an albedo outside `[0, rho[0]]` (`rho[0]` = 1 for a
/// semi-infinite layer; less for a slab).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_albedo_curve_single_scattering_albedo_f64(
    c: *const sk_albedo_curve_f64,
    albedo: f64,
    omega_out: *mut f64,
) -> sk_status {
    // SAFETY: as above.
    let Some(c) = (unsafe { c.as_ref() }) else {
        return sk_status::SK_ERR_NULL;
    };
    let r: Result<f64, Error> = curve(c).single_scattering_albedo(albedo);
    unsafe { write_result(omega_out, r) }
}
