//! Stokes vectors and polarised Rayleigh scattering.

use super::{CVec, sk_status, sk_vec3, sk_vec3_f64, write_result};
use crate::error::Error;
use crate::math::real::Real;
use crate::phase::{RayleighMueller, RayleighPolarized, StokesSample};
use crate::stokes::Stokes;

/// A Stokes vector (I, Q, U, V) with its reference vector: Q is the light
/// polarised along `reference` minus that along k x reference, for light
/// travelling along the unit direction k, with `reference` a unit vector
/// perpendicular to k. U is the same for the diagonals, V the circular
/// part. Turning the reference by alpha about k (new reference = cos alpha
/// reference + sin alpha k x reference) turns Q' = cos 2 alpha Q + sin 2
/// alpha U, U' = -sin 2 alpha Q + cos 2 alpha U.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_stokes {
    /// Intensity (>= 0).
    pub i: f32,
    /// Linear polarisation along the reference minus across it.
    pub q: f32,
    /// Linear polarisation along the diagonals.
    pub u: f32,
    /// Circular polarisation.
    pub v: f32,
    /// The reference vector (unit, perpendicular to the direction).
    pub reference: sk_vec3,
}

/// Double twin of `sk_stokes`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_stokes_f64 {
    /// Intensity (>= 0).
    pub i: f64,
    /// Linear polarisation along the reference minus across it.
    pub q: f64,
    /// Linear polarisation along the diagonals.
    pub u: f64,
    /// Circular polarisation.
    pub v: f64,
    /// The reference vector (unit, perpendicular to the direction).
    pub reference: sk_vec3_f64,
}

/// The non-zero elements of the normalised Rayleigh Mueller matrix
/// (Hansen & Travis 1974, eq. 2.15; the mean of p11 over the sphere is 1;
/// p21 = p12).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_rayleigh_mueller {
    /// P11.
    pub p11: f32,
    /// P12 = P21.
    pub p12: f32,
    /// P22.
    pub p22: f32,
    /// P33.
    pub p33: f32,
    /// P44.
    pub p44: f32,
}

/// Double twin of `sk_rayleigh_mueller`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_rayleigh_mueller_f64 {
    /// P11.
    pub p11: f64,
    /// P12 = P21.
    pub p12: f64,
    /// P22.
    pub p22: f64,
    /// P33.
    pub p33: f64,
    /// P44.
    pub p44: f64,
}

/// A sampled scattering: the unit direction, the Stokes vector carried on
/// (referred to the new scattering plane) and the direction's density per
/// steradian.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_stokes_sample {
    /// Scattered direction.
    pub dir: sk_vec3,
    /// The Stokes vector after scattering.
    pub stokes: sk_stokes,
    /// Density of dir per steradian.
    pub pdf: f32,
}

/// Double twin of `sk_stokes_sample`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_stokes_sample_f64 {
    /// Scattered direction.
    pub dir: sk_vec3_f64,
    /// The Stokes vector after scattering.
    pub stokes: sk_stokes_f64,
    /// Density of dir per steradian.
    pub pdf: f64,
}

/// Polarised Rayleigh scattering with depolarisation rho, built by
/// sk_rayleigh_polarized_new: opaque, copyable, no resources.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_rayleigh_polarized {
    /// Opaque contents.
    pub opaque: [u32; 16],
}

/// Double twin of `sk_rayleigh_polarized`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_rayleigh_polarized_f64 {
    /// Opaque contents.
    pub opaque: [u64; 16],
}

/// What the opaque storage holds: a tag, then the model.
#[repr(C)]
struct Stored<T> {
    tag: u32,
    model: RayleighPolarized<T>,
}

const TAG: u32 = 0x534b_5052;

const _: () = {
    use core::mem::{align_of, size_of};
    assert!(size_of::<Stored<f32>>() <= size_of::<sk_rayleigh_polarized>());
    assert!(align_of::<Stored<f32>>() <= align_of::<sk_rayleigh_polarized>());
    assert!(size_of::<Stored<f64>>() <= size_of::<sk_rayleigh_polarized_f64>());
    assert!(align_of::<Stored<f64>>() <= align_of::<sk_rayleigh_polarized_f64>());
};

/// The C types of one precision.
trait Types {
    type T: Real;
    type V: CVec<T = Self::T>;
    type S: Copy;
    type M;
    type Sample;
    type P;
    fn stokes(s: &Self::S) -> Stokes<Self::T>;
    fn c_stokes(s: Stokes<Self::T>) -> Self::S;
    fn c_mueller(m: RayleighMueller<Self::T>) -> Self::M;
    fn c_sample(s: StokesSample<Self::T>) -> Self::Sample;
}

macro_rules! impl_types {
    ($marker:ident, $t:ty, $v:ty, $s:ident, $m:ident, $smp:ident, $p:ty) => {
        struct $marker;
        impl Types for $marker {
            type T = $t;
            type V = $v;
            type S = $s;
            type M = $m;
            type Sample = $smp;
            type P = $p;
            fn stokes(s: &$s) -> Stokes<$t> {
                Stokes {
                    i: s.i,
                    q: s.q,
                    u: s.u,
                    v: s.v,
                    reference: s.reference.to_vec(),
                }
            }
            fn c_stokes(s: Stokes<$t>) -> $s {
                $s {
                    i: s.i,
                    q: s.q,
                    u: s.u,
                    v: s.v,
                    reference: <$v>::from_vec(s.reference),
                }
            }
            fn c_mueller(m: RayleighMueller<$t>) -> $m {
                $m {
                    p11: m.p11,
                    p12: m.p12,
                    p22: m.p22,
                    p33: m.p33,
                    p44: m.p44,
                }
            }
            fn c_sample(s: StokesSample<$t>) -> $smp {
                $smp {
                    dir: <$v>::from_vec(s.dir),
                    stokes: Self::c_stokes(s.stokes),
                    pdf: s.pdf,
                }
            }
        }
    };
}

impl_types!(
    F32,
    f32,
    sk_vec3,
    sk_stokes,
    sk_rayleigh_mueller,
    sk_stokes_sample,
    sk_rayleigh_polarized
);
impl_types!(
    F64,
    f64,
    sk_vec3_f64,
    sk_stokes_f64,
    sk_rayleigh_mueller_f64,
    sk_stokes_sample_f64,
    sk_rayleigh_polarized_f64
);

/// The model behind `p`, or `None` for NULL or storage not written by the
/// constructor.
unsafe fn load<'a, X: Types>(p: *const X::P) -> Option<&'a RayleighPolarized<X::T>> {
    // SAFETY: a non-NULL p points to an X::P (module contract), whose
    // storage is large and aligned enough for Stored (checked above); its
    // first u32 is the tag, and the model is floats, valid for any bits.
    let stored = unsafe { p.cast::<Stored<X::T>>().as_ref() }?;
    (stored.tag == TAG).then_some(&stored.model)
}

unsafe fn new<X: Types>(rho: X::T, out: *mut X::P) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    match RayleighPolarized::new(rho) {
        // SAFETY: non-NULL out is writable and fits Stored (checked above).
        Ok(model) => unsafe {
            out.cast::<u8>()
                .write_bytes(0, core::mem::size_of::<X::P>());
            out.cast::<Stored<X::T>>().write(Stored { tag: TAG, model });
            sk_status::SK_OK
        },
        Err(e) => e.into(),
    }
}

/// A direction the samplers accept: finite and of unit length within 10⁻³.
fn unit<T: Real>(v: crate::Vec3<T>) -> Result<crate::Vec3<T>, Error> {
    let ok = v.is_finite() && (v.length().to_f64() - 1.0).abs() <= 1e-3;
    ok.then_some(v).ok_or(Error::Domain)
}

/// The checked Stokes vector behind `s` (see `Stokes::new`).
unsafe fn stokes<X: Types>(s: *const X::S) -> Result<Stokes<X::T>, sk_status> {
    // SAFETY: a non-NULL s points to a readable X::S (module contract).
    let s = unsafe { s.as_ref() }.ok_or(sk_status::SK_ERR_NULL)?;
    let s = X::stokes(s);
    Stokes::new(s.i, s.q, s.u, s.v, s.reference).map_err(Into::into)
}

/// The model, the direction and the Stokes vector of a call, checked.
type Inputs<'a, T> = (&'a RayleighPolarized<T>, crate::Vec3<T>, Stokes<T>);

/// Everything a call on (model, k, Stokes) needs, checked.
unsafe fn inputs<'a, X: Types>(
    p: *const X::P,
    k: X::V,
    s: *const X::S,
) -> Result<Inputs<'a, X::T>, sk_status> {
    if p.is_null() || s.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    let m = unsafe { load::<X>(p) }.ok_or(sk_status::SK_ERR_DOMAIN)?;
    let k = unit(k.to_vec())?;
    let s = unsafe { stokes::<X>(s) }?;
    Ok((m, k, s))
}

unsafe fn eval<X: Types>(
    p: *const X::P,
    k: X::V,
    s: *const X::S,
    w: X::V,
    r: X::V,
    out: *mut X::S,
) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let r = unsafe { inputs::<X>(p, k, s) }.and_then(|(m, k, s)| {
        let (w, r) = (unit(w.to_vec())?, unit(r.to_vec())?);
        Ok(X::c_stokes(m.eval(k, &s, w, r)))
    });
    unsafe { write_status(out, r) }
}

unsafe fn pdf<X: Types>(p: *const X::P, k: X::V, s: *const X::S, w: X::V) -> X::T {
    unsafe { inputs::<X>(p, k, s) }
        .ok()
        .and_then(|(m, k, s)| Some(m.pdf(k, &s, unit(w.to_vec()).ok()?)))
        .unwrap_or(X::T::NAN)
}

unsafe fn sample<X: Types>(
    p: *const X::P,
    k: X::V,
    s: *const X::S,
    u1: X::T,
    u2: X::T,
    scalar: bool,
    out: *mut X::Sample,
) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let uniform = |u: X::T| u >= X::T::ZERO && u <= X::T::ONE;
    let r = unsafe { inputs::<X>(p, k, s) }.and_then(|(m, k, s)| {
        if !(uniform(u1) && uniform(u2)) {
            return Err(sk_status::SK_ERR_DOMAIN);
        }
        let x = if scalar {
            m.sample_scalar(k, &s, u1, u2)
        } else {
            m.sample(k, &s, u1, u2)
        };
        Ok(X::c_sample(x))
    });
    unsafe { write_status(out, r) }
}

/// Writes `Ok` through `out` (checked non-NULL by the caller), or returns
/// the error status.
unsafe fn write_status<V>(out: *mut V, r: Result<V, sk_status>) -> sk_status {
    match r {
        // SAFETY: the caller checked `out`; non-NULL out-pointers are writable.
        Ok(v) => unsafe { write_result(out, Ok(v)) },
        Err(e) => e,
    }
}

/// Builds polarised Rayleigh scattering with depolarisation factor 0 <=
/// rho < 1 (air: about 0.028). SK_ERR_NULL for a NULL out, SK_ERR_DOMAIN
/// otherwise (NaN fails); *out is written only on success.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_new(
    rho: f32,
    out: *mut sk_rayleigh_polarized,
) -> sk_status {
    unsafe { new::<F32>(rho, out) }
}

/// Double twin of `sk_rayleigh_polarized_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_new_f64(
    rho: f64,
    out: *mut sk_rayleigh_polarized_f64,
) -> sk_status {
    unsafe { new::<F64>(rho, out) }
}

/// The matrix at cos theta = cos_theta in [-1, 1], each element within 1
/// ULP of Hansen & Travis eq. 2.15 with depolarisation. Every element NaN
/// for a NULL or unconstructed model.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_mueller(
    p: *const sk_rayleigh_polarized,
    cos_theta: f32,
) -> sk_rayleigh_mueller {
    let m = unsafe { load::<F32>(p) }.map(|m| m.mueller(cos_theta));
    m.map_or(F32::c_mueller(nan_mueller()), F32::c_mueller)
}

/// Double twin of `sk_rayleigh_polarized_mueller`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_mueller_f64(
    p: *const sk_rayleigh_polarized_f64,
    cos_theta: f64,
) -> sk_rayleigh_mueller_f64 {
    let m = unsafe { load::<F64>(p) }.map(|m| m.mueller(cos_theta));
    m.map_or(F64::c_mueller(nan_mueller()), F64::c_mueller)
}

fn nan_mueller<T: Real>() -> RayleighMueller<T> {
    RayleighMueller {
        p11: T::NAN,
        p12: T::NAN,
        p22: T::NAN,
        p33: T::NAN,
        p44: T::NAN,
    }
}

/// The Stokes vector scattered from light *s travelling along the unit
/// direction k into the unit direction w, per steradian, referred to
/// out_reference (unit, perpendicular to w): the next-event estimate
/// towards a detector. s->reference must be perpendicular to k. SK_ERR_NULL
/// for NULL pointers; SK_ERR_DOMAIN for an unconstructed model, a
/// direction not of unit length (within 1e-3) or not finite, or an
/// unphysical Stokes vector (I < 0, Q^2 + U^2 + V^2 > I^2, reference not of
/// unit length; a relative 1e-6 of rounding is accepted). *out is written
/// only on success. Every Stokes vector returned here and by the samplers
/// has Q^2 + U^2 + V^2 <= I^2 (rounding above I is clamped), so an output is
/// always accepted as the next input.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_eval(
    p: *const sk_rayleigh_polarized,
    k: sk_vec3,
    s: *const sk_stokes,
    w: sk_vec3,
    out_reference: sk_vec3,
    out: *mut sk_stokes,
) -> sk_status {
    unsafe { eval::<F32>(p, k, s, w, out_reference, out) }
}

/// Double twin of `sk_rayleigh_polarized_eval`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_eval_f64(
    p: *const sk_rayleigh_polarized_f64,
    k: sk_vec3_f64,
    s: *const sk_stokes_f64,
    w: sk_vec3_f64,
    out_reference: sk_vec3_f64,
    out: *mut sk_stokes_f64,
) -> sk_status {
    unsafe { eval::<F64>(p, k, s, w, out_reference, out) }
}

/// The density per steradian with which sk_rayleigh_polarized_sample draws
/// w for light *s along k: (P11 + P12 q_phi) / 4 pi. NaN for the input
/// sk_rayleigh_polarized_eval rejects.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_pdf(
    p: *const sk_rayleigh_polarized,
    k: sk_vec3,
    s: *const sk_stokes,
    w: sk_vec3,
) -> f32 {
    unsafe { pdf::<F32>(p, k, s, w) }
}

/// Double twin of `sk_rayleigh_polarized_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_pdf_f64(
    p: *const sk_rayleigh_polarized_f64,
    k: sk_vec3_f64,
    s: *const sk_stokes_f64,
    w: sk_vec3_f64,
) -> f64 {
    unsafe { pdf::<F64>(p, k, s, w) }
}

/// Draws the scattered direction of light *s along k from u1, u2 in [0, 1]
/// by the exact polarisation-dependent sampler (azimuth by Kepler's
/// equation, then cos theta; docs of RayleighPolarized): the Stokes vector
/// keeps I and refers to the new scattering plane. With unpolarised light
/// the direction is sk_phase_sample_dir's for depolarised Rayleigh, bit for
/// bit. Errors as sk_rayleigh_polarized_eval, and SK_ERR_DOMAIN for u1 or
/// u2 outside [0, 1] or NaN; *out is written only on success.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_sample(
    p: *const sk_rayleigh_polarized,
    k: sk_vec3,
    s: *const sk_stokes,
    u1: f32,
    u2: f32,
    out: *mut sk_stokes_sample,
) -> sk_status {
    unsafe { sample::<F32>(p, k, s, u1, u2, false, out) }
}

/// Double twin of `sk_rayleigh_polarized_sample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_sample_f64(
    p: *const sk_rayleigh_polarized_f64,
    k: sk_vec3_f64,
    s: *const sk_stokes_f64,
    u1: f64,
    u2: f64,
    out: *mut sk_stokes_sample_f64,
) -> sk_status {
    unsafe { sample::<F64>(p, k, s, u1, u2, false, out) }
}

/// Scalar sampling with matrix weighting: the direction from P11 alone
/// (depolarised Rayleigh's sampler) and the Stokes vector I P S / P11, so
/// its I changes by the weight (P11 + P12 q_phi) / P11; the density is
/// P11 / 4 pi. Errors as sk_rayleigh_polarized_sample.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_sample_scalar(
    p: *const sk_rayleigh_polarized,
    k: sk_vec3,
    s: *const sk_stokes,
    u1: f32,
    u2: f32,
    out: *mut sk_stokes_sample,
) -> sk_status {
    unsafe { sample::<F32>(p, k, s, u1, u2, true, out) }
}

/// Double twin of `sk_rayleigh_polarized_sample_scalar`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_rayleigh_polarized_sample_scalar_f64(
    p: *const sk_rayleigh_polarized_f64,
    k: sk_vec3_f64,
    s: *const sk_stokes_f64,
    u1: f64,
    u2: f64,
    out: *mut sk_stokes_sample_f64,
) -> sk_status {
    unsafe { sample::<F64>(p, k, s, u1, u2, true, out) }
}

/// *s referred to new_reference (unit, perpendicular to the direction of
/// travel k): Q and U turned by the angle between the references about k.
/// Every field NaN for a NULL s.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_stokes_rotate(
    s: *const sk_stokes,
    k: sk_vec3,
    new_reference: sk_vec3,
) -> sk_stokes {
    unsafe { rotate::<F32>(s, k, new_reference) }
}

/// Double twin of `sk_stokes_rotate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_stokes_rotate_f64(
    s: *const sk_stokes_f64,
    k: sk_vec3_f64,
    new_reference: sk_vec3_f64,
) -> sk_stokes_f64 {
    unsafe { rotate::<F64>(s, k, new_reference) }
}

unsafe fn rotate<X: Types>(s: *const X::S, k: X::V, r: X::V) -> X::S {
    // SAFETY: a non-NULL s points to a readable X::S (module contract).
    match unsafe { s.as_ref() } {
        Some(s) => X::c_stokes(X::stokes(s).rotate_to(k.to_vec(), r.to_vec())),
        None => {
            let n = X::T::NAN;
            X::c_stokes(Stokes {
                i: n,
                q: n,
                u: n,
                v: n,
                reference: crate::Vec3::new(n, n, n),
            })
        }
    }
}

/// The meridian reference of the unit direction k: the unit vector along
/// increasing polar angle (from +z), in the plane of k and the z axis, as
/// plane-parallel radiative transfer refers Stokes vectors; along k = +-z
/// the azimuth hint_azimuth (radians) fixes it.
#[unsafe(no_mangle)]
pub extern "C" fn sk_meridian_reference(k: sk_vec3, hint_azimuth: f32) -> sk_vec3 {
    sk_vec3::from_vec(crate::stokes::meridian_reference(k.to_vec(), hint_azimuth))
}

/// Double twin of `sk_meridian_reference`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_meridian_reference_f64(k: sk_vec3_f64, hint_azimuth: f64) -> sk_vec3_f64 {
    sk_vec3_f64::from_vec(crate::stokes::meridian_reference(k.to_vec(), hint_azimuth))
}

/// A reference vector for the unit direction k when the caller has no
/// preferred one: b1 of sk_onb(k) (continuous except across k.z = 0 from
/// below).
#[unsafe(no_mangle)]
pub extern "C" fn sk_implicit_reference(k: sk_vec3) -> sk_vec3 {
    sk_vec3::from_vec(crate::stokes::implicit_reference(k.to_vec()))
}

/// Double twin of `sk_implicit_reference`.
#[unsafe(no_mangle)]
pub extern "C" fn sk_implicit_reference_f64(k: sk_vec3_f64) -> sk_vec3_f64 {
    sk_vec3_f64::from_vec(crate::stokes::implicit_reference(k.to_vec()))
}
