//! Equiangular distance sampling toward a point.

use super::{CVec, sk_status, sk_vec3, sk_vec3_f64};
use crate::math::real::Real;
use crate::medium::Ray;
use crate::medium::equiangular::Equiangular;

/// Equiangular sampling of one ray segment toward one point (a light):
/// distances with density proportional to 1/r^2, r the distance to the
/// point (Kulla & Fajardo 2012, section 3). Filled by sk_equiangular_new;
/// treat the fields as opaque (sample and pdf check them and answer NaN
/// for values sk_equiangular_new would not have written).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct sk_equiangular {
    /// t0, delta, theta_b - theta_a, t_min, t_max.
    pub state: [f32; 5],
}

/// Equiangular sampling (double); see `sk_equiangular`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct sk_equiangular_f64 {
    /// t0, delta, theta_b - theta_a, t_min, t_max.
    pub state: [f64; 5],
}

/// A C equiangular type and its precision.
trait EqStore: Copy {
    type V: CVec;
    fn state(&self) -> [<Self::V as CVec>::T; 5];
    fn from_state(s: [<Self::V as CVec>::T; 5]) -> Self;
}

macro_rules! impl_eq_store {
    ($c:ident, $v:ty, $t:ty) => {
        impl EqStore for $c {
            type V = $v;
            fn state(&self) -> [$t; 5] {
                self.state
            }
            fn from_state(state: [$t; 5]) -> Self {
                $c { state }
            }
        }
    };
}
impl_eq_store!(sk_equiangular, sk_vec3, f32);
impl_eq_store!(sk_equiangular_f64, sk_vec3_f64, f64);

type T<E> = <<E as EqStore>::V as CVec>::T;

/// Builds into `out`, both precisions.
unsafe fn new_into<E: EqStore>(
    [o, d, point]: [E::V; 3],
    (t_min, t_max): (T<E>, T<E>),
    out: *mut E,
) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let ray = Ray::new(o.to_vec(), d.to_vec(), t_max).segment(t_min, t_max);
    match Equiangular::new(ray, point.to_vec()) {
        Ok(e) => {
            // SAFETY: a non-NULL out-pointer is writable (module contract).
            unsafe { out.write(E::from_state(e.parts())) };
            sk_status::SK_OK
        }
        Err(e) => e.into(),
    }
}

/// `f` of the checked state, NaN for NULL or a state `new` would not write.
unsafe fn with<E: EqStore>(e: *const E, f: impl Fn(Equiangular<T<E>>) -> T<E>) -> T<E> {
    if e.is_null() {
        return T::<E>::NAN;
    }
    // SAFETY: a non-NULL pointer points at a readable value (module contract).
    let state = unsafe { e.read() }.state();
    Equiangular::from_parts(state).map_or(T::<E>::NAN, f)
}

/// Equiangular sampling over [t_min, t_max] of the ray from o along d
/// (distances along d/|d|; t_max may be INFINITY) toward point, into *out.
/// SK_ERR_NULL for a NULL out; SK_ERR_DOMAIN for a zero or non-finite d, a
/// non-finite o or point, t_min negative or NaN, an empty segment, or a
/// point on the ray's line or so near it or far from it that the squared
/// distance underflows or overflows, or a segment too short to subtend a
/// representable angle or to have a finite density (its peak overflows:
/// shorter than about 1/FLT_MAX, or 1/DBL_MAX for the _f64 twin, at a
/// distance of 1).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_equiangular_new(
    o: sk_vec3,
    d: sk_vec3,
    t_min: f32,
    t_max: f32,
    point: sk_vec3,
    out: *mut sk_equiangular,
) -> sk_status {
    unsafe { new_into([o, d, point], (t_min, t_max), out) }
}

/// Double twin of `sk_equiangular_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_equiangular_new_f64(
    o: sk_vec3_f64,
    d: sk_vec3_f64,
    t_min: f64,
    t_max: f64,
    point: sk_vec3_f64,
    out: *mut sk_equiangular_f64,
) -> sk_status {
    unsafe { new_into([o, d, point], (t_min, t_max), out) }
}

/// The distance for a uniform u (clamped to [0, 1]), within the segment
/// and monotone in u. NaN for NULL, a NaN u, or a state sk_equiangular_new
/// would not have written.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_equiangular_sample(e: *const sk_equiangular, u: f32) -> f32 {
    unsafe { with(e, |e| e.sample(u)) }
}

/// Double twin of `sk_equiangular_sample`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_equiangular_sample_f64(e: *const sk_equiangular_f64, u: f64) -> f64 {
    unsafe { with(e, |e| e.sample(u)) }
}

/// The density of distance t per unit length: 0 outside the segment (and
/// for a NaN t), NaN for NULL or a state sk_equiangular_new would not have
/// written. For multiple importance sampling with free-flight sampling.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_equiangular_pdf(e: *const sk_equiangular, t: f32) -> f32 {
    unsafe { with(e, |e| e.pdf(t)) }
}

/// Double twin of `sk_equiangular_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_equiangular_pdf_f64(e: *const sk_equiangular_f64, t: f64) -> f64 {
    unsafe { with(e, |e| e.pdf(t)) }
}
