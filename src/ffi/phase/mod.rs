//! Phase functions.
//!
//! `sk_phase` holds a [`Phase<f32>`] (`sk_phase_f64` a `Phase<f64>`) in
//! private storage. Every call checks the stored tag before it reads the
//! value, so a NULL, zeroed or never-constructed phase gives NaN or an error
//! rather than undefined behaviour.

use super::{CVec, map_arrays, sk_status, sk_vec3, sk_vec3_f64, write_result};
use crate::error::Error;
use crate::math::real::Real;
use crate::phase::{Phase, PhaseFunction, PhaseVisitor, check_uniforms};

/// A phase function (float). A plain value with no pointers inside: build it
/// with sk_phase_new or a named constructor (sk_phase_new_hg, ...), then copy it and
/// share it freely across threads. 256 bytes: a tag and room for 63 floats
/// (the largest model takes 31). Its contents are private, and some of its
/// bytes are padding a constructor need not define: compare phases with
/// sk_phase_get_params, not memcmp.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase {
    /// Private storage; do not read or write.
    pub opaque: [u32; 64],
}

/// A phase function (double); see `sk_phase`. 512 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_phase_f64 {
    /// Private storage; do not read or write.
    pub opaque: [u64; 64],
}

/// Storage of a [`Phase<T>`] behind a C type.
pub(crate) trait PhaseStore: Copy {
    /// The float type of the phase stored.
    type T: Real;
    /// The C type `sk_phase_get_params` writes for it.
    type Params;
    const ZEROED: Self;
    fn params(model: u32, count: u32, params: [Self::T; 4]) -> Self::Params;
}
macro_rules! impl_phase_store {
    ($c:ident, $t:ty, $params:ident) => {
        impl PhaseStore for $c {
            type T = $t;
            type Params = $params;
            const ZEROED: Self = $c { opaque: [0; 64] };
            fn params(model: u32, count: u32, params: [$t; 4]) -> $params {
                $params {
                    model: crate::ffi::enum_arg::sk_phase_model(model),
                    count,
                    params,
                }
            }
        }
    };
}
impl_phase_store!(sk_phase, f32, sk_phase_params);
impl_phase_store!(sk_phase_f64, f64, sk_phase_params_f64);

const _: () = {
    use core::mem::{align_of, size_of};
    // The tag and the room every model is checked to fit in (Phase::ROOM).
    assert!(size_of::<u32>() + Phase::<f32>::ROOM <= size_of::<sk_phase>());
    assert!(size_of::<u64>() + Phase::<f64>::ROOM <= size_of::<sk_phase_f64>());
    assert!(size_of::<Phase<f32>>() <= size_of::<sk_phase>());
    assert!(align_of::<Phase<f32>>() <= align_of::<sk_phase>());
    assert!(size_of::<Phase<f64>>() <= size_of::<sk_phase_f64>());
    assert!(align_of::<Phase<f64>>() <= align_of::<sk_phase_f64>());
};

/// Packs a phase into zeroed storage. The enum's padding (after the tag,
/// and past a shorter variant) need not be written: compare two phases by
/// their parameters (sk_phase_get_params), not by their bytes.
fn store<S: PhaseStore>(phase: Phase<S::T>) -> S {
    let mut s = S::ZEROED;
    // SAFETY: size and alignment checked above; S is plain bytes.
    unsafe { (&mut s as *mut S).cast::<Phase<S::T>>().write(phase) };
    s
}

/// The phase behind `p`, or `None` if `p` is NULL or its tag is not one
/// `store` writes.
#[inline(always)]
pub(crate) unsafe fn load<'a, S: PhaseStore>(p: *const S) -> Option<&'a Phase<S::T>> {
    if p.is_null() {
        return None;
    }
    // SAFETY: p points to an S (module contract), which begins with the u32
    // tag of the repr(C, u32) enum; the payload is floats, valid for any bits.
    let tag = unsafe { p.cast::<u32>().read() };
    if tag == 0 || tag > Phase::<S::T>::LAST_TAG {
        return None;
    }
    Some(unsafe { &*p.cast::<Phase<S::T>>() })
}

unsafe fn construct<S: PhaseStore>(out: *mut S, r: Result<Phase<S::T>, Error>) -> sk_status {
    unsafe { write_result(out, r.map(store)) }
}

unsafe fn pdf<S: PhaseStore>(p: *const S, cos_theta: S::T) -> S::T {
    unsafe { load(p) }.map_or(S::T::NAN, |ph| ph.pdf(cos_theta))
}

unsafe fn cdf<S: PhaseStore>(p: *const S, cos_theta: S::T) -> S::T {
    unsafe { load(p) }.map_or(S::T::NAN, |ph| ph.cdf(cos_theta))
}

unsafe fn mean_cosine<S: PhaseStore>(p: *const S) -> S::T {
    unsafe { load(p) }.map_or(S::T::NAN, |ph| ph.mean_cosine())
}

// The scalar entry points check the pointer and the tag, then jump to one
// function per model (`#[inline(never)]`): the entry stays a check and a
// jump, and each model's code saves only the registers it needs, instead of
// every call paying the prologue of the largest model.

#[inline(never)]
fn cos_of<T: Real, M: PhaseFunction<T>>(m: &M, u: T) -> T {
    m.sample_cos(u)
}

/// [`cos_of`] on the model inside a `Phase`.
struct CosOf<T>(T);

impl<T: Real> PhaseVisitor<T> for CosOf<T> {
    type Output = T;
    #[inline(always)]
    fn visit<M: PhaseFunction<T>>(self, m: &M) -> T {
        cos_of(m, self.0)
    }
}

unsafe fn sample_cos<S: PhaseStore>(p: *const S, u: S::T) -> S::T {
    match unsafe { load(p) } {
        Some(ph) => ph.visit(CosOf(u)),
        None => S::T::NAN,
    }
}

/// One model's direction; writes the density through a non-NULL `pdf_out`.
/// With the C calling convention of the entry points (the vector in
/// registers both ways), so that the entry ends in a jump here: with Rust's,
/// it called this, the vector went through the stack both ways, and the
/// result's three 4-byte stores were read back as one 8-byte load, which
/// store forwarding cannot serve.
#[inline(never)]
unsafe extern "C" fn dir_of<T: Real, M: PhaseFunction<T>, V: CVec<T = T>>(
    m: &M,
    w_in: V,
    u1: T,
    u2: T,
    pdf_out: *mut T,
) -> V {
    let (dir, pdf) = m.sample_dir(w_in.to_vec(), u1, u2);
    // SAFETY: a non-NULL pdf_out is writable (module contract).
    if let Some(out) = unsafe { pdf_out.as_mut() } {
        *out = pdf;
    }
    V::from_vec(dir)
}

/// [`dir_of`] on the model inside a `Phase`, with a `pdf_out` the caller
/// vouches for (NULL or writable).
struct DirOf<T, V> {
    w_in: V,
    u1: T,
    u2: T,
    pdf_out: *mut T,
}

impl<T: Real, V: CVec<T = T>> PhaseVisitor<T> for DirOf<T, V> {
    type Output = V;
    #[inline(always)]
    fn visit<M: PhaseFunction<T>>(self, m: &M) -> V {
        // SAFETY: pdf_out is NULL or writable (the entry points' contract).
        unsafe { dir_of(m, self.w_in, self.u1, self.u2, self.pdf_out) }
    }
}

unsafe fn sample_dir<S: PhaseStore, V: CVec<T = S::T>>(
    p: *const S,
    w_in: V,
    u1: S::T,
    u2: S::T,
    pdf_out: *mut S::T,
) -> V {
    match unsafe { load(p) } {
        Some(ph) => ph.visit(DirOf {
            w_in,
            u1,
            u2,
            pdf_out,
        }),
        None => {
            let nan = S::T::NAN;
            // SAFETY: as in dir_of.
            if let Some(out) = unsafe { pdf_out.as_mut() } {
                *out = nan;
            }
            V::from_vec(crate::Vec3::new(nan, nan, nan))
        }
    }
}

/// The phase behind `p` for a batch call: `SK_ERR_NULL` for NULL,
/// `SK_ERR_DOMAIN` for one never constructed.
unsafe fn load_batch<'a, S: PhaseStore>(p: *const S) -> Result<&'a Phase<S::T>, sk_status> {
    if p.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { load(p) }.ok_or(sk_status::SK_ERR_DOMAIN)
}

unsafe fn sample_cos_n<S: PhaseStore>(
    p: *const S,
    u: *const S::T,
    cos_out: *mut S::T,
    n: usize,
) -> sk_status {
    let ph = match unsafe { load_batch(p) } {
        Ok(ph) => ph,
        Err(e) => return e,
    };
    unsafe {
        map_arrays(u, cos_out, n, check_uniforms, |u, out| {
            ph.sample_cos_each_in_range(u, out);
            Ok(())
        })
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn sample_dir_n<S: PhaseStore>(
    p: *const S,
    w: [*const S::T; 3],
    u1: *const S::T,
    u2: *const S::T,
    out: [*mut S::T; 3],
    pdf_out: *mut S::T,
    n: usize,
) -> sk_status {
    let ph = match unsafe { load_batch(p) } {
        Ok(ph) => ph,
        Err(e) => return e,
    };
    // The model's own loop per block (it vectorises for the closed forms).
    unsafe {
        super::verbs::dir_block_slices((w, u1, u2), (out, pdf_out), n, |w, [a, b], o, pdf| {
            ph.sample_dir_each(w, a, b, o, pdf)
        })
    }
}

/// [`sample_dir_n`] with each direction's `cos θ` to `cos_out`: the
/// model's `sample_cos` at the same `u1` (the cosine its `sample_dir`
/// turns into the direction, bit for bit).
#[allow(clippy::too_many_arguments)]
unsafe fn sample_dir_cos_n<S: PhaseStore>(
    p: *const S,
    w: [*const S::T; 3],
    u1: *const S::T,
    u2: *const S::T,
    out: [*mut S::T; 3],
    cos_out: *mut S::T,
    pdf_out: *mut S::T,
    n: usize,
) -> sk_status {
    let ph = match unsafe { load_batch(p) } {
        Ok(ph) => ph,
        Err(e) => return e,
    };
    unsafe {
        super::verbs::dir_cos_block_slices(
            (w, u1, u2),
            (out, cos_out, pdf_out),
            n,
            |w, [a, b], o, cos, pdf| {
                ph.sample_dir_each(w, a, b, o, pdf);
                ph.sample_cos_each_in_range(a, cos);
            },
        )
    }
}

#[cfg(test)]
mod tag_tests {
    use super::*;

    /// Every model's stored tag is its registry tag, in `1..=LAST_TAG`, and
    /// the registry's tags are exactly `1..=LAST_TAG`.
    #[test]
    fn tags_match_the_repr() {
        let models: [Phase<f32>; 8] = [
            Phase::isotropic(),
            Phase::rayleigh(),
            Phase::rayleigh_depolarized(0.03).unwrap(),
            Phase::henyey_greenstein(0.7).unwrap(),
            Phase::draine(0.5, 1.0).unwrap(),
            Phase::fog_diameter(2.0).unwrap(),
            Phase::gegenbauer(0.5, 0.7).unwrap(),
            Phase::fournier_forand_backscatter(0.0183, 1.1).unwrap(),
        ];
        for m in &models {
            // SAFETY: Phase is repr(C, u32): it begins with its u32 tag.
            let stored = unsafe { (m as *const Phase<f32>).cast::<u32>().read() };
            assert_eq!(stored, m.tag());
            assert!((1..=Phase::<f32>::LAST_TAG).contains(&stored));
        }
        for tag in 1..=Phase::<f32>::LAST_TAG {
            assert_ne!(
                Phase::<f32>::from_params(tag, &[]),
                Err(Error::Method),
                "{tag}"
            );
        }
        assert_eq!(
            Phase::<f32>::from_params(Phase::<f32>::LAST_TAG + 1, &[]),
            Err(Error::Method)
        );
    }
}

// The entry points, in the order of the header (cbindgen reads them in
// this order).
mod new;
pub use new::*;
mod choose;
pub use choose::*;
mod sample;
pub use sample::*;
mod params;
pub use params::*;
