//! The `extern "C"` layer: argument checks, conversion, and a call into the
//! core, nothing else. `include/scatterkit.h` is generated from these files by
//! cbindgen (`SK_BLESS=1 cargo test --release -p scatterkit-dev` rewrites it).
//!
//! # Safety (every function here)
//! Pointer arguments are either NULL (checked, reported as `SK_ERR_NULL` or a
//! NaN result) or valid for the reads and writes the function documents,
//! for the element counts it is given. `sk_phase`, `sk_table` and friends
//! must come from this library's constructors. The callback in `sk_rng` is
//! called with its `state` and must not unwind.
#![allow(non_camel_case_types, clippy::missing_safety_doc)]

/// Compile-time proof that a C enum, written as literals so cbindgen can
/// print them, carries the core enum's values: every variant of each is
/// paired (an unpaired one does not compile) and each pair is equal.
macro_rules! same_values {
    ($c:ident = $core:ident: $($cv:ident = $rv:ident),+ $(,)?) => {
        const _: () = {
            let _: fn($c) = |x| match x {
                $($c::$cv => (),)+
            };
            let _: fn($core) = |x| match x {
                $($core::$rv => (),)+
            };
            assert!(true $(&& $c::$cv as u32 == $core::$rv as u32)+);
        };
    };
}

/// The enum-valued arguments and fields as the C layer receives them: a
/// `uint32_t` under the enum's own name, so that the header's signatures
/// are typed (cbindgen prints the enum's name) while a value outside the
/// enum, which C allows, arrives as a plain integer and is refused
/// (`SK_ERR_METHOD`) rather than being undefined behaviour in Rust.
pub mod enum_arg {
    macro_rules! enum_arg {
        ($($name:ident),* $(,)?) => {
            $(
                #[doc = concat!("`", stringify!($name), "` as received from C.")]
                #[repr(transparent)]
                #[derive(Clone, Copy, Debug, PartialEq, Eq)]
                pub struct $name(pub u32);
            )*
        };
    }
    enum_arg!(
        sk_sampling,
        sk_rayleigh_method,
        sk_table_kind,
        sk_surface_model,
        sk_fraction_model,
        sk_crossing_policy,
        sk_size_kind,
        sk_particle_model,
        sk_phase_model,
        sk_status,
    );
}

// The families in the order the header presents them (cbindgen writes
// the functions in the order it meets them); status, vectors and the
// generator, in this file, come first. Each group is its own block, so
// that rustfmt keeps the order.

// Phase functions.
mod phase;

mod moments;

mod rayleigh;

mod polarization;

// Tables.
mod table;

mod table2d;

// Mixtures and expansions.
mod mixture;

mod spectral_phase;

mod legendre;

// Media.
mod medium;

mod majorant;

mod track;

mod equiangular;

mod albedo;

// Surfaces.
mod surface;

// Particles.
mod mie;

mod polydisperse;

// Utilities.
mod cbrt;

mod geometry;

// Internal: no entry points.
mod slot;
mod verbs;

pub use albedo::*;
pub use cbrt::*;
pub use equiangular::*;
pub use geometry::*;
pub use legendre::*;
pub use majorant::*;
pub use medium::*;
pub use mie::*;
pub use mixture::*;
pub use moments::*;
pub use phase::*;
pub use polarization::*;
pub use polydisperse::*;
pub use rayleigh::*;
pub use spectral_phase::*;
pub use surface::*;
pub use table::*;
pub use table2d::*;
pub use track::*;

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use core::convert::Infallible;
use core::ffi::{c_char, c_void};

/// Result of every fallible call. Out-pointers are written only on `SK_OK`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum sk_status {
    /// Success.
    SK_OK = 0,
    /// A required pointer was NULL.
    SK_ERR_NULL = 1,
    /// A parameter was NaN, infinite or outside its domain.
    SK_ERR_DOMAIN = 2,
    /// A buffer was too small or a count out of range.
    SK_ERR_SIZE = 3,
    /// An enum-valued argument was out of range.
    SK_ERR_METHOD = 4,
    /// Volume tracking used up its step budget before it could answer.
    SK_ERR_BUDGET = 5,
    /// Arrays that must not share memory do (an output overlapping an
    /// input or another output; in place is allowed where documented).
    SK_ERR_OVERLAP = 6,
}

/// A short English description of `status` (an sk_status value), as a
/// static NUL-terminated string: "ok", "NULL pointer", ...; "unknown
/// status" for a value that is no sk_status. Never NULL.
#[unsafe(no_mangle)]
pub extern "C" fn sk_status_string(status: enum_arg::sk_status) -> *const c_char {
    let s: &'static str = match status.0 {
        0 => "ok\0",
        1 => "NULL pointer\0",
        2 => "parameter NaN, infinite or outside its domain\0",
        3 => "buffer too small or count out of range\0",
        4 => "enum value out of range\0",
        5 => "step budget used up\0",
        6 => "arrays overlap\0",
        _ => "unknown status\0",
    };
    s.as_ptr().cast()
}

/// Every status has its own string (`sk_status_string`): the compiler
/// stops here when a status is added without one.
const _: fn(sk_status) -> u32 = |s| match s {
    sk_status::SK_OK
    | sk_status::SK_ERR_NULL
    | sk_status::SK_ERR_DOMAIN
    | sk_status::SK_ERR_SIZE
    | sk_status::SK_ERR_METHOD
    | sk_status::SK_ERR_BUDGET
    | sk_status::SK_ERR_OVERLAP => s as u32,
};

impl From<Error> for sk_status {
    fn from(e: Error) -> Self {
        match e {
            Error::Domain => sk_status::SK_ERR_DOMAIN,
            Error::Size => sk_status::SK_ERR_SIZE,
            Error::Method => sk_status::SK_ERR_METHOD,
            Error::Budget => sk_status::SK_ERR_BUDGET,
        }
    }
}

/// A 3-vector of floats (a unit propagation direction where one is expected).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_vec3 {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component.
    pub z: f32,
}

/// A 3-vector of doubles.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct sk_vec3_f64 {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
    /// z component.
    pub z: f64,
}

/// Conversions between the C vector types and [`Vec3`].
pub(crate) trait CVec: Copy {
    type T: Real;
    fn to_vec(self) -> Vec3<Self::T>;
    fn from_vec(v: Vec3<Self::T>) -> Self;
    /// The vector at `self`, each coordinate read by a load of its own: a
    /// caller's struct is stored with stores of its compiler's choosing,
    /// and a load the optimiser widens across two of them is not forwarded
    /// from the store buffer, so it waits for both to retire (2–3 % of a
    /// photon's time on the one-call-per-flight slab, 5–6 % with an exit
    /// estimator per vertex: `benches/c_flight.c` on AMD Zen 5). For
    /// argument structs the caller has just written.
    fn read_each(&self) -> Vec3<Self::T>;
}

macro_rules! impl_cvec {
    ($c:ty, $t:ty) => {
        impl CVec for $c {
            type T = $t;
            #[inline(always)]
            fn to_vec(self) -> Vec3<$t> {
                Vec3::new(self.x, self.y, self.z)
            }
            #[inline(always)]
            fn from_vec(v: Vec3<$t>) -> Self {
                Self {
                    x: v.x,
                    y: v.y,
                    z: v.z,
                }
            }
            #[inline(always)]
            fn read_each(&self) -> Vec3<$t> {
                // SAFETY: references to this struct's own fields.
                unsafe {
                    Vec3::new(
                        core::ptr::read_volatile(&self.x),
                        core::ptr::read_volatile(&self.y),
                        core::ptr::read_volatile(&self.z),
                    )
                }
            }
        }
    };
}
impl_cvec!(sk_vec3, f32);
impl_cvec!(sk_vec3_f64, f64);

/// The caller's random number generator: `next_u64(state)` returns 64
/// uniformly random bits. Uniform floats are taken from the top 24 (float) or
/// 53 (double) bits.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_rng {
    /// Passed to `next_u64` unchanged; may be NULL if the callback allows.
    pub state: *mut c_void,
    /// The generator. Must not be NULL.
    pub next_u64: Option<unsafe extern "C" fn(state: *mut c_void) -> u64>,
}

/// [`sk_rng`] as a `rand_core` generator.
pub(crate) struct CRng {
    state: *mut c_void,
    next: unsafe extern "C" fn(*mut c_void) -> u64,
}

impl CRng {
    /// `None` if `rng` or its callback is NULL.
    pub(crate) unsafe fn from_ptr(rng: *mut sk_rng) -> Option<CRng> {
        // SAFETY: non-NULL `rng` points to an sk_rng (module contract).
        let r = unsafe { rng.as_ref() }?;
        Some(CRng {
            state: r.state,
            next: r.next_u64?,
        })
    }
}

impl rand_core::TryRng for CRng {
    type Error = Infallible;
    #[inline(always)]
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok((self.try_next_u64()? >> 32) as u32)
    }
    #[inline(always)]
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        // SAFETY: the caller's callback, called with the caller's state.
        Ok(unsafe { (self.next)(self.state) })
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        rand_core::utils::fill_bytes_via_next_word(dst, || self.try_next_u64())
    }
}

/// A uniform float in [0, 1) from one draw of `rng`, taken exactly as the
/// library's samplers take theirs: the top 24 bits of the 64-bit word times
/// 2^-24. For a caller's own decisions (Russian roulette, a lobe or light
/// choice) from the generator it also passes to the library. NaN if `rng`
/// or its callback is NULL (nothing is drawn).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_uniform(rng: *mut sk_rng) -> f32 {
    // SAFETY: `rng` is NULL or points to an sk_rng (module contract).
    unsafe { CRng::from_ptr(rng) }.map_or(f32::NAN, |mut r| f32::uniform(&mut r))
}

/// Double twin of `sk_uniform`: the top 53 bits times 2^-53.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_uniform_f64(rng: *mut sk_rng) -> f64 {
    // SAFETY: as `sk_uniform`.
    unsafe { CRng::from_ptr(rng) }.map_or(f64::NAN, |mut r| f64::uniform(&mut r))
}

/// A caller's callback with its context pointer, as the C API takes them:
/// `sk_emission_fn` is `CFn<sk_vec3, f32>`, `sk_medium_fn` is
/// `CFn<sk_vec3, sk_coefficients>`.
pub(crate) type CFn<A, R> = Option<unsafe extern "C" fn(ctx: *mut c_void, a: A) -> R>;

/// The caller's callback bound to its context; `None` for a NULL callback.
pub(crate) fn bind<A, R>(f: CFn<A, R>, ctx: *mut c_void) -> Option<impl Fn(A) -> R> {
    let f = f?;
    // SAFETY: the caller's callback with the caller's context (the entry
    // points' contract).
    Some(move |a| unsafe { f(ctx, a) })
}

/// Writes `r`'s value through `out` on success; the status either way.
#[inline(always)]
pub(crate) unsafe fn write_result<V>(out: *mut V, r: Result<V, Error>) -> sk_status {
    if out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    match r {
        // SAFETY: non-NULL `out` is writable (module contract).
        Ok(v) => unsafe {
            out.write(v);
            sk_status::SK_OK
        },
        Err(e) => e.into(),
    }
}

/// True when `n` elements of `T` can exist in one allocation.
#[inline(always)]
pub(crate) fn fits<T>(n: usize) -> bool {
    n <= isize::MAX as usize / core::mem::size_of::<T>()
}

/// A shared slice from a C array of `n` elements: `Ok(&[])` for `n = 0`
/// (whatever the pointer), `SK_ERR_NULL` for NULL with `n > 0`, `SK_ERR_SIZE`
/// if `n` elements cannot exist in one allocation.
#[inline(always)]
pub(crate) unsafe fn slice_in<'a, T>(p: *const T, n: usize) -> Result<&'a [T], sk_status> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    if !fits::<T>(n) {
        return Err(sk_status::SK_ERR_SIZE);
    }
    // SAFETY: non-NULL, valid for n elements (module contract), size checked.
    Ok(unsafe { core::slice::from_raw_parts(p, n) })
}

/// The mutable twin of [`slice_in`].
#[inline(always)]
pub(crate) unsafe fn slice_out<'a, T>(p: *mut T, n: usize) -> Result<&'a mut [T], sk_status> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    if !fits::<T>(n) {
        return Err(sk_status::SK_ERR_SIZE);
    }
    // SAFETY: as in slice_in, and the caller's array is writable.
    Ok(unsafe { core::slice::from_raw_parts_mut(p, n) })
}

/// True when the arrays of `n` elements at `a` and `b` share memory.
pub(crate) fn overlaps<T>(a: *const T, b: *const T, n: usize) -> bool {
    overlaps_len(a, n, b, n)
}

/// True when the array of `na` elements at `a` and that of `nb` at `b`
/// share memory.
pub(crate) fn overlaps_len<T, U>(a: *const T, na: usize, b: *const U, nb: usize) -> bool {
    let ea = (a as usize).saturating_add(na.saturating_mul(core::mem::size_of::<T>()));
    let eb = (b as usize).saturating_add(nb.saturating_mul(core::mem::size_of::<U>()));
    na > 0 && nb > 0 && (a as usize) < eb && (b as usize) < ea
}

/// Runs `f(u, out)` over two C arrays of `n` elements that are either
/// disjoint or the same array (in place); partial overlap is `SK_ERR_OVERLAP`.
/// In place, the inputs are copied in chunks to the stack first, after `check`
/// has seen all of them, so nothing is written unless every input is valid.
pub(crate) unsafe fn map_arrays<T: Real>(
    u: *const T,
    out: *mut T,
    n: usize,
    check: impl Fn(&[T]) -> Result<(), Error>,
    f: impl Fn(&[T], &mut [T]) -> Result<(), Error>,
) -> sk_status {
    // SAFETY (all blocks): pointers valid for n elements (module contract).
    let u_s = match unsafe { slice_in(u, n) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    if out.is_null() && n > 0 {
        return sk_status::SK_ERR_NULL;
    }
    if let Err(e) = check(u_s) {
        return e.into();
    }
    if n == 0 {
        return sk_status::SK_OK;
    }
    if u == out.cast_const() {
        const CHUNK: usize = 64;
        let mut start = 0;
        while start < n {
            let len = CHUNK.min(n - start);
            let mut tmp = [T::ZERO; CHUNK];
            // SAFETY: in bounds; `u_s` is not used past this point in place.
            unsafe { core::ptr::copy_nonoverlapping(u.add(start), tmp.as_mut_ptr(), len) };
            let dst = unsafe { core::slice::from_raw_parts_mut(out.add(start), len) };
            if let Err(e) = f(&tmp[..len], dst) {
                return e.into();
            }
            start += len;
        }
        sk_status::SK_OK
    } else if overlaps(u, out.cast_const(), n) {
        sk_status::SK_ERR_OVERLAP
    } else {
        let out_s = unsafe { core::slice::from_raw_parts_mut(out, n) };
        match f(u_s, out_s) {
            Ok(()) => sk_status::SK_OK,
            Err(e) => e.into(),
        }
    }
}

/// The library version, `"MAJOR.MINOR.PATCH"`, as a static NUL-terminated
/// string; it agrees with the `SK_VERSION_*` macros of the header.
#[unsafe(no_mangle)]
pub extern "C" fn sk_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// Elements per block of the structure-of-arrays batches (stack buffers).
pub(crate) const SOA_BLOCK: usize = 64;

/// Checks the arrays of a structure-of-arrays batch of `n` elements: every
/// input and every non-optional output non-NULL (`SK_ERR_NULL`), `n`
/// elements possible (`SK_ERR_SIZE`); no output overlapping another output,
/// nor an input unless it is that same array (`SK_ERR_OVERLAP`). `outputs`
/// pairs each pointer with whether it may be NULL.
pub(crate) fn check_soa<T>(
    inputs: &[*const T],
    outputs: &[(*mut T, bool)],
    n: usize,
) -> Result<(), sk_status> {
    if n == 0 {
        return Ok(());
    }
    let missing = inputs.iter().any(|p| p.is_null())
        || outputs.iter().any(|(p, optional)| p.is_null() && !optional);
    if missing {
        return Err(sk_status::SK_ERR_NULL);
    }
    if !fits::<T>(n) {
        return Err(sk_status::SK_ERR_SIZE);
    }
    let outs = outputs
        .iter()
        .map(|(p, _)| p.cast_const())
        .filter(|p| !p.is_null());
    for (k, o) in outs.clone().enumerate() {
        let clash_out = outs.clone().skip(k + 1).any(|o2| overlaps(o, o2, n));
        let clash_in = inputs.iter().any(|&i| i != o && overlaps(i, o, n));
        if clash_out || clash_in {
            return Err(sk_status::SK_ERR_OVERLAP);
        }
    }
    Ok(())
}

/// Runs a checked structure-of-arrays batch block by block: each block's
/// inputs are copied to the stack, `f(inputs, outputs, len)` fills the stack
/// outputs, and those are copied out (NULL outputs are skipped). Since a
/// block is read before any of it is written, an output may be the same
/// array as an input.
///
/// # Safety
/// The arrays passed [`check_soa`] for `n`.
pub(crate) unsafe fn soa_blocks<T: Real, const I: usize, const O: usize>(
    inputs: [*const T; I],
    outputs: [*mut T; O],
    n: usize,
    mut f: impl FnMut(&[[T; SOA_BLOCK]; I], &mut [[T; SOA_BLOCK]; O], usize),
) {
    let mut ins = [[T::ZERO; SOA_BLOCK]; I];
    let mut outs = [[T::ZERO; SOA_BLOCK]; O];
    let mut start = 0;
    while start < n {
        let len = SOA_BLOCK.min(n - start);
        for (buf, p) in ins.iter_mut().zip(inputs) {
            // SAFETY: p is valid for n elements and start + len <= n.
            unsafe { core::ptr::copy_nonoverlapping(p.add(start), buf.as_mut_ptr(), len) };
        }
        f(&ins, &mut outs, len);
        for (buf, p) in outs.iter().zip(outputs) {
            if !p.is_null() {
                // SAFETY: as above; outputs do not overlap other outputs.
                unsafe { core::ptr::copy_nonoverlapping(buf.as_ptr(), p.add(start), len) };
            }
        }
        start += len;
    }
}
