//! Surface scattering.

use super::{CRng, CVec, sk_rng, sk_status, sk_vec3, sk_vec3_f64, write_result};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::surface::{self, CrossingPolicy, Fraction, Surface, SurfaceModel};

/// How a surface scatters (passed as uint32_t; other values give SK_ERR_METHOD).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_surface_model {
    /// No scattering: mirror reflection or Snell refraction.
    SK_SURFACE_SPECULAR = 0,
    /// Lambertian: cosine-weighted about the normal on the leaving side.
    SK_SURFACE_LAMBERT = 1,
    /// Phong: cos(dtheta) = u^(1/(alpha+1)) about the specular direction.
    SK_SURFACE_PHONG = 2,
}

same_values!(sk_surface_model = SurfaceModel:
    SK_SURFACE_SPECULAR = Specular,
    SK_SURFACE_LAMBERT = Lambert,
    SK_SURFACE_PHONG = Phong,
);

/// Which share of rays scatters (passed as uint32_t).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_fraction_model {
    /// A constant share in [0, 1].
    SK_FRACTION_CONSTANT = 0,
    /// The scalar-scattering model from the RMS roughness.
    SK_FRACTION_SCALAR = 1,
}

/// What happens to a Phong direction that lands on the wrong side of the
/// surface (passed as uint32_t).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_crossing_policy {
    /// SunSolve: polar angle theta > 90 deg about the leaving-side normal
    /// becomes theta - 90 deg at the same azimuth.
    SK_CROSSING_FOLD = 0,
    /// Draw again until above the surface (16 draws at most, then mirror):
    /// the lobe truncated to the hemisphere and renormalised.
    SK_CROSSING_RESAMPLE = 1,
    /// Reflect the direction across the surface plane.
    SK_CROSSING_MIRROR = 2,
}

same_values!(sk_crossing_policy = CrossingPolicy:
    SK_CROSSING_FOLD = Fold,
    SK_CROSSING_RESAMPLE = Resample,
    SK_CROSSING_MIRROR = Mirror,
);

/// Bit of `event_out`: the ray was transmitted (else reflected).
pub const SK_EVENT_TRANSMITTED: u32 = 1;
/// Bit of `event_out`: the ray was scattered by the model (else specular).
pub const SK_EVENT_SCATTERED: u32 = 2;

/// A surface's scattering behaviour (float). Build it with sk_surface_new;
/// every call checks its fields again, so a value not built that way gives
/// an error rather than undefined behaviour.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_surface {
    /// An sk_surface_model.
    pub model: super::enum_arg::sk_surface_model,
    /// An sk_fraction_model.
    pub fraction_model: super::enum_arg::sk_fraction_model,
    /// An sk_crossing_policy.
    pub policy: super::enum_arg::sk_crossing_policy,
    /// Phong exponent.
    pub phong_alpha: f32,
    /// Constant share, or RMS roughness for the scalar model.
    pub fraction: f32,
}

/// A surface's scattering behaviour (double); see `sk_surface`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_surface_f64 {
    /// An sk_surface_model.
    pub model: super::enum_arg::sk_surface_model,
    /// An sk_fraction_model.
    pub fraction_model: super::enum_arg::sk_fraction_model,
    /// An sk_crossing_policy.
    pub policy: super::enum_arg::sk_crossing_policy,
    /// Phong exponent.
    pub phong_alpha: f64,
    /// Constant share, or RMS roughness for the scalar model.
    pub fraction: f64,
}

/// A C surface type and its float.
pub(crate) trait SurfaceStore: Copy {
    type T: Real;
    fn pack(
        model: u32,
        fraction_model: u32,
        policy: u32,
        alpha: Self::T,
        fraction: Self::T,
    ) -> Self;
    fn unpack(&self) -> (u32, u32, u32, Self::T, Self::T);
}

macro_rules! impl_surface_store {
    ($c:ty, $t:ty) => {
        impl SurfaceStore for $c {
            type T = $t;
            fn pack(
                model: u32,
                fraction_model: u32,
                policy: u32,
                phong_alpha: $t,
                fraction: $t,
            ) -> Self {
                use super::enum_arg as e;
                Self {
                    model: e::sk_surface_model(model),
                    fraction_model: e::sk_fraction_model(fraction_model),
                    policy: e::sk_crossing_policy(policy),
                    phong_alpha,
                    fraction,
                }
            }
            fn unpack(&self) -> (u32, u32, u32, $t, $t) {
                (
                    self.model.0,
                    self.fraction_model.0,
                    self.policy.0,
                    self.phong_alpha,
                    self.fraction,
                )
            }
        }
    };
}
impl_surface_store!(sk_surface, f32);
impl_surface_store!(sk_surface_f64, f64);

/// The `sk_fraction_model` values, for matching.
const FRACTION_CONSTANT: u32 = sk_fraction_model::SK_FRACTION_CONSTANT as u32;
const FRACTION_SCALAR: u32 = sk_fraction_model::SK_FRACTION_SCALAR as u32;

/// The Rust surface from its C fields, validated.
fn build<T: Real>(
    model: u32,
    fraction_model: u32,
    policy: u32,
    alpha: T,
    fraction: T,
) -> Result<Surface<T>, Error> {
    let model = SurfaceModel::try_from(model)?;
    let policy = CrossingPolicy::try_from(policy)?;
    let fraction = match fraction_model {
        FRACTION_CONSTANT => Fraction::Constant(fraction),
        FRACTION_SCALAR => Fraction::Scalar(fraction),
        _ => return Err(Error::Method),
    };
    Surface::new(model, alpha, fraction, policy)
}

/// A unit vector from a C vector, or None for zero or non-finite input.
fn unit<V: CVec>(v: V) -> Option<Vec3<V::T>> {
    v.to_vec().try_normalize()
}

fn nan_vec<V: CVec>() -> V {
    let n = V::T::NAN;
    V::from_vec(Vec3::new(n, n, n))
}

fn reflect<V: CVec>(d: V, n: V) -> V {
    match (unit(d), unit(n)) {
        (Some(d), Some(n)) => V::from_vec(surface::reflect(d, n)),
        _ => nan_vec(),
    }
}

unsafe fn refract<V: CVec>(d: V, n: V, n_i: V::T, n_t: V::T, out: *mut V) -> sk_status {
    let r = match (unit(d), unit(n)) {
        (Some(d), Some(n)) => surface::refract(d, n, n_i, n_t).map(V::from_vec),
        _ => Err(Error::Domain),
    };
    unsafe { write_result(out, r) }
}

fn lambert<V: CVec>(normal: V, u1: V::T, u2: V::T) -> V {
    unit(normal).map_or_else(nan_vec, |n| V::from_vec(surface::lambert_sample(n, u1, u2)))
}

fn phong<V: CVec>(axis: V, normal: V, alpha: V::T, policy: u32, u1: V::T, u2: V::T) -> V {
    match (unit(axis), unit(normal), CrossingPolicy::try_from(policy)) {
        (Some(a), Some(n), Ok(p)) => V::from_vec(surface::phong_sample(a, n, alpha, p, u1, u2)),
        _ => nan_vec(),
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn surface_new<S: SurfaceStore>(
    model: u32,
    phong_alpha: S::T,
    (fraction_model, fraction, sigma_rms): (u32, S::T, S::T),
    policy: u32,
    out: *mut S,
) -> sk_status {
    let value = if fraction_model == FRACTION_SCALAR {
        sigma_rms
    } else {
        fraction
    };
    let r = build(model, fraction_model, policy, phong_alpha, value)
        .map(|_| S::pack(model, fraction_model, policy, phong_alpha, value));
    unsafe { write_result(out, r) }
}

#[allow(clippy::too_many_arguments)]
unsafe fn interact<S: SurfaceStore, V: CVec<T = S::T>>(
    s: *const S,
    d: V,
    normal: V,
    n_i: S::T,
    n_t: S::T,
    wavelength: S::T,
    rng: *mut sk_rng,
    dir_out: *mut V,
    event_out: *mut u32,
) -> sk_status {
    // SAFETY: a non-NULL s points to a surface (module contract).
    let Some(s) = (unsafe { s.as_ref() }) else {
        return sk_status::SK_ERR_NULL;
    };
    let Some(mut r) = (unsafe { CRng::from_ptr(rng) }) else {
        return sk_status::SK_ERR_NULL;
    };
    if dir_out.is_null() || event_out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let (m, f, p, a, x) = s.unpack();
    let result = build(m, f, p, a, x)
        .and_then(|surf| surf.interact(d.to_vec(), normal.to_vec(), n_i, n_t, wavelength, &mut r));
    match result {
        // SAFETY: both out-pointers were checked non-NULL above.
        Ok(x) => unsafe {
            let bits = |on: bool, bit: u32| if on { bit } else { 0 };
            dir_out.write(V::from_vec(x.dir));
            event_out.write(
                bits(x.transmitted, SK_EVENT_TRANSMITTED) | bits(x.scattered, SK_EVENT_SCATTERED),
            );
            sk_status::SK_OK
        },
        Err(e) => e.into(),
    }
}

/// Mirror reflection of direction d at a surface of normal n (either side,
/// any length): d - 2 (d.n) n with both made unit first. NaN for zero or
/// non-finite vectors.
#[unsafe(no_mangle)]
pub extern "C" fn sk_reflect(d: sk_vec3, n: sk_vec3) -> sk_vec3 {
    reflect(d, n)
}

/// Double twin of `sk_reflect`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_reflect_f64(d: sk_vec3_f64, n: sk_vec3_f64) -> sk_vec3_f64 {
    reflect(d, n)
}

/// Snell refraction of direction d through a surface of normal n (either
/// side, any length; both made unit) from index n_i into n_t. SK_ERR_DOMAIN
/// on total internal reflection, for zero or non-finite vectors, indices
/// that are not finite and positive, or n_i/n_t above 2^26 (past it the
/// direction's error, about (n_i/n_t) DBL_EPSILON, is no longer small);
/// SK_ERR_NULL for a NULL out.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_refract(
    d: sk_vec3,
    n: sk_vec3,
    n_i: f32,
    n_t: f32,
    out: *mut sk_vec3,
) -> sk_status {
    unsafe { refract(d, n, n_i, n_t, out) }
}

/// Double twin of `sk_refract`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_refract_f64(
    d: sk_vec3_f64,
    n: sk_vec3_f64,
    n_i: f64,
    n_t: f64,
    out: *mut sk_vec3_f64,
) -> sk_status {
    unsafe { refract(d, n, n_i, n_t, out) }
}

/// Unpolarised Fresnel reflectance (R_s + R_p)/2 of a dielectric interface
/// for light at |cos_i| (either direction of travel) from n_i into n_t; 1 on
/// total internal reflection; NaN for invalid indices or |cos_i| > 1.
#[unsafe(no_mangle)]
pub extern "C" fn sk_fresnel_dielectric(cos_i: f32, n_i: f32, n_t: f32) -> f32 {
    surface::fresnel_dielectric(cos_i, n_i, n_t)
}

/// Double twin of `sk_fresnel_dielectric`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_fresnel_dielectric_f64(cos_i: f64, n_i: f64, n_t: f64) -> f64 {
    surface::fresnel_dielectric(cos_i, n_i, n_t)
}

/// Lambertian direction in the hemisphere of `normal` (the side the ray
/// leaves to; any length): theta = arccos(sqrt(u1)), phi = 2 pi u2. NaN for
/// a zero or non-finite normal.
#[unsafe(no_mangle)]
pub extern "C" fn sk_lambert_sample(normal: sk_vec3, u1: f32, u2: f32) -> sk_vec3 {
    lambert(normal, u1, u2)
}

/// Double twin of `sk_lambert_sample`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_lambert_sample_f64(normal: sk_vec3_f64, u1: f64, u2: f64) -> sk_vec3_f64 {
    lambert(normal, u1, u2)
}

/// Phong direction: cos(dtheta) = u1^(1/(alpha+1)) about the specular
/// direction `axis`, phi = 2 pi u2, kept on the side of `normal` (the side
/// the ray leaves to) by `policy` (sk_crossing_policy; RESAMPLE derives its
/// further uniforms from u1, u2 by a hash). 1 <= alpha <= 1e6. NaN for an
/// invalid alpha or policy, or zero or non-finite vectors.
#[unsafe(no_mangle)]
pub extern "C" fn sk_phong_sample(
    axis: sk_vec3,
    normal: sk_vec3,
    alpha: f32,
    policy: super::enum_arg::sk_crossing_policy,
    u1: f32,
    u2: f32,
) -> sk_vec3 {
    phong(axis, normal, alpha, policy.0, u1, u2)
}

/// Double twin of `sk_phong_sample`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_phong_sample_f64(
    axis: sk_vec3_f64,
    normal: sk_vec3_f64,
    alpha: f64,
    policy: super::enum_arg::sk_crossing_policy,
    u1: f64,
    u2: f64,
) -> sk_vec3_f64 {
    phong(axis, normal, alpha, policy.0, u1, u2)
}

/// Scalar-scattering share on reflection:
/// 1 - exp(-((2 pi/wavelength) sigma_rms 2 n_i cos_i)^2). Wavelength and
/// sigma_rms in one length unit; NaN unless wavelength > 0, sigma_rms >= 0,
/// n_i > 0 (all finite) and |cos_i| <= 1.
#[unsafe(no_mangle)]
pub extern "C" fn sk_scatter_fraction_reflect(
    wavelength: f32,
    sigma_rms: f32,
    n_i: f32,
    cos_i: f32,
) -> f32 {
    surface::scatter_fraction_reflect(wavelength, sigma_rms, n_i, cos_i)
}

/// Double twin of `sk_scatter_fraction_reflect`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_scatter_fraction_reflect_f64(
    wavelength: f64,
    sigma_rms: f64,
    n_i: f64,
    cos_i: f64,
) -> f64 {
    surface::scatter_fraction_reflect(wavelength, sigma_rms, n_i, cos_i)
}

/// Scalar-scattering share on transmission:
/// 1 - exp(-((2 pi/wavelength) sigma_rms |n_i cos_i - n_t cos_t|)^2); NaN on
/// invalid arguments (as sk_scatter_fraction_reflect, and n_t > 0, |cos_t| <= 1).
#[unsafe(no_mangle)]
pub extern "C" fn sk_scatter_fraction_transmit(
    wavelength: f32,
    sigma_rms: f32,
    n_i: f32,
    cos_i: f32,
    n_t: f32,
    cos_t: f32,
) -> f32 {
    surface::scatter_fraction_transmit(wavelength, sigma_rms, n_i, cos_i, n_t, cos_t)
}

/// Double twin of `sk_scatter_fraction_transmit`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_scatter_fraction_transmit_f64(
    wavelength: f64,
    sigma_rms: f64,
    n_i: f64,
    cos_i: f64,
    n_t: f64,
    cos_t: f64,
) -> f64 {
    surface::scatter_fraction_transmit(wavelength, sigma_rms, n_i, cos_i, n_t, cos_t)
}

/// A surface: `model` (sk_surface_model), Phong exponent in [1, 1e6]
/// (checked for SK_SURFACE_PHONG only), `fraction_model`
/// (sk_fraction_model) with a constant `fraction` in [0, 1] or the RMS
/// roughness `sigma_rms` >= 0 (same length unit as the wavelength given to
/// sk_surface_interact), and the crossing `policy` (sk_crossing_policy).
/// SK_ERR_METHOD for unknown enum values, SK_ERR_DOMAIN for values out of
/// range, SK_ERR_NULL for a NULL out.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_surface_new(
    model: super::enum_arg::sk_surface_model,
    phong_alpha: f32,
    fraction_model: super::enum_arg::sk_fraction_model,
    fraction: f32,
    sigma_rms: f32,
    policy: super::enum_arg::sk_crossing_policy,
    out: *mut sk_surface,
) -> sk_status {
    let frac = (fraction_model.0, fraction, sigma_rms);
    unsafe { surface_new(model.0, phong_alpha, frac, policy.0, out) }
}

/// Double twin of `sk_surface_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_surface_new_f64(
    model: super::enum_arg::sk_surface_model,
    phong_alpha: f64,
    fraction_model: super::enum_arg::sk_fraction_model,
    fraction: f64,
    sigma_rms: f64,
    policy: super::enum_arg::sk_crossing_policy,
    out: *mut sk_surface_f64,
) -> sk_status {
    let frac = (fraction_model.0, fraction, sigma_rms);
    unsafe { surface_new(model.0, phong_alpha, frac, policy.0, out) }
}

/// One interaction of a ray along `d` with the surface of geometric normal
/// `normal` (either side; any length), from index n_i into n_t, at
/// `wavelength` (scalar model only). Fresnel picks reflection or
/// transmission, the scattering share picks scattered or specular, the model
/// picks the direction (unit, written to dir_out); event_out gets
/// SK_EVENT_TRANSMITTED and SK_EVENT_SCATTERED bits. SK_ERR_NULL for NULL s,
/// rng, rng->next_u64 or outputs; SK_ERR_DOMAIN for zero or non-finite
/// vectors, invalid indices (as sk_refract) or wavelength; SK_ERR_METHOD for
/// a corrupted s.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_surface_interact(
    s: *const sk_surface,
    d: sk_vec3,
    normal: sk_vec3,
    n_i: f32,
    n_t: f32,
    wavelength: f32,
    rng: *mut sk_rng,
    dir_out: *mut sk_vec3,
    event_out: *mut u32,
) -> sk_status {
    unsafe { interact(s, d, normal, n_i, n_t, wavelength, rng, dir_out, event_out) }
}

/// Double twin of `sk_surface_interact`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_surface_interact_f64(
    s: *const sk_surface_f64,
    d: sk_vec3_f64,
    normal: sk_vec3_f64,
    n_i: f64,
    n_t: f64,
    wavelength: f64,
    rng: *mut sk_rng,
    dir_out: *mut sk_vec3_f64,
    event_out: *mut u32,
) -> sk_status {
    unsafe { interact(s, d, normal, n_i, n_t, wavelength, rng, dir_out, event_out) }
}
