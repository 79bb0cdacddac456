//! The float trait every algorithm is written against once, and uniform floats
//! from the caller's RNG (the crate's conventions, see the crate docs).
//!
//! [`Real`] is implemented for `f32` and `f64` only (it is sealed). Its math
//! functions are `libm`'s, except [`Real::cbrt`] and [`Real::cbrt_fast`],
//! which are this crate's own (see [`crate::math::cbrt`]).

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};
use rand_core::Rng;

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A floating-point type the samplers run in: `f32` or `f64`.
pub trait Real:
    sealed::Sealed
    + Copy
    + Debug
    + Default
    + PartialEq
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 1/2.
    const HALF: Self;
    /// π.
    const PI: Self;
    /// 2π.
    const TAU: Self;
    /// 1/(4π): the isotropic phase function, per steradian.
    const INV_4PI: Self;
    /// Machine epsilon (spacing of floats just above 1).
    const EPSILON: Self;
    /// The smallest positive normal value (below it, subnormals keep
    /// fewer significant bits).
    const MIN_POSITIVE: Self;
    /// Not a number.
    const NAN: Self;
    /// +∞.
    const INFINITY: Self;

    /// Converts an `f64` constant, rounding to nearest.
    fn from_f64(x: f64) -> Self;
    /// Widens (or copies) to `f64`.
    fn to_f64(self) -> f64;
    /// A uniform float in `[0, 1)` from one `next_u64` (the crate's convention):
    /// f32 `(x >> 40)·2⁻²⁴`, f64 `(x >> 11)·2⁻⁵³`.
    fn uniform<R: Rng + ?Sized>(rng: &mut R) -> Self;
    /// The same conversion from a raw 64-bit word.
    fn from_bits_uniform(x: u64) -> Self;

    /// Square root (correctly rounded).
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// `self` with the sign bit of `sign`.
    fn copysign(self, sign: Self) -> Self;
    /// Cube root, ≤ ~1 ULP on every input (this crate's Kahan + Lancaster).
    fn cbrt(self) -> Self;
    /// Cube root with one Lancaster step fewer (see [`crate::math::cbrt`]).
    fn cbrt_fast(self) -> Self;
    /// Sine and cosine of an angle in radians.
    fn sin_cos(self) -> (Self, Self);
    /// Cosine of an angle in radians.
    fn cos(self) -> Self;
    /// `(sin 2π·self, cos 2π·self)` for `self ∈ [0, 1]` (a fraction of a
    /// turn), reduced exactly: see [`crate::math::azimuth`].
    fn sin_cos_2pi(self) -> (Self, Self);
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// `ln(1 + self)`, accurate for small `self`.
    fn ln_1p(self) -> Self;
    /// `e^self`.
    fn exp(self) -> Self;
    /// `e^self − 1`, accurate for small `self`.
    fn exp_m1(self) -> Self;
    /// `self^p`.
    fn powf(self, p: Self) -> Self;
    /// `atan2(self, x)`.
    fn atan2(self, x: Self) -> Self;
    /// `⌊self⌋` as an index for `self ≥ 0`; saturating (NaN gives 0).
    fn to_index(self) -> usize;
    /// An index as a float.
    fn from_index(i: usize) -> Self;
    /// The slice of `Self`'s precision from a pair of tables kept in both.
    fn pick<'a>(f32s: &'a [f32], f64s: &'a [f64]) -> &'a [Self];
    /// The pair `(u, out)` as f32 slices if `Self` is f32, else `None` (for
    /// loops written for f32 alone).
    #[doc(hidden)]
    fn as_f32_io<'a>(u: &'a [Self], out: &'a mut [Self]) -> Option<(&'a [f32], &'a mut [f32])>;
    /// `u` as an f32 slice if `Self` is f32, else `None`.
    #[doc(hidden)]
    fn as_f32s(u: &[Self]) -> Option<&[f32]>;
    /// `out` as an f32 slice if `Self` is f32, else `None`.
    #[doc(hidden)]
    fn as_f32s_mut(out: &mut [Self]) -> Option<&mut [f32]>;
    /// True unless NaN or ±∞.
    fn is_finite(self) -> bool;
    /// True for NaN.
    fn is_nan(self) -> bool;

    /// Clamps to `[0, 1]`; NaN stays NaN (the crate's rule for uniforms).
    /// Upper bound first, then the lower bound on that result: each step is
    /// then one `min`/`max` instruction that passes NaN through.
    #[inline(always)]
    fn clamp01(self) -> Self {
        let y = if self > Self::ONE { Self::ONE } else { self };
        if y < Self::ZERO { Self::ZERO } else { y }
    }
    /// Clamps to `[-1, 1]`; NaN stays NaN. Two branch-free instructions, as
    /// [`clamp01`](Self::clamp01).
    #[inline(always)]
    fn clamp_unit(self) -> Self {
        let y = if self > Self::ONE { Self::ONE } else { self };
        if y < -Self::ONE { -Self::ONE } else { y }
    }
    /// The larger of two values; `b` if `self` is NaN.
    #[inline(always)]
    fn max_of(self, b: Self) -> Self {
        if self > b { self } else { b }
    }
    /// The smaller of two values; `b` if `self` is NaN.
    #[inline(always)]
    fn min_of(self, b: Self) -> Self {
        if self < b { self } else { b }
    }
}

macro_rules! impl_real {
    ($t:ty, $sign:expr, $shift:expr, $scale:expr, $cbrt:path, $cbrt_fast:path,
     $pick:expr, $as_f32:expr, $sc2pi:path, $sqrt:path, $sincos:ident, $cos:ident, $log:ident, $log1p:ident,
     $exp:ident, $expm1:ident, $pow:ident, $atan2:ident) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const TWO: Self = 2.0;
            const HALF: Self = 0.5;
            const PI: Self = core::f64::consts::PI as $t;
            const TAU: Self = core::f64::consts::TAU as $t;
            const INV_4PI: Self = (0.25 * core::f64::consts::FRAC_1_PI) as $t;
            const EPSILON: Self = <$t>::EPSILON;
            const MIN_POSITIVE: Self = <$t>::MIN_POSITIVE;
            const NAN: Self = <$t>::NAN;
            const INFINITY: Self = <$t>::INFINITY;

            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline(always)]
            fn uniform<R: Rng + ?Sized>(rng: &mut R) -> Self {
                // The generator's own method, not `Rng::next_u64`: that
                // blanket wrapper stayed out of line in the C library's
                // tracking loop (a call around every callback draw, 2 % of
                // a 1 × 1 × 64 grid photon's samples, measured from C).
                let Ok(x) = rng.try_next_u64();
                Self::from_bits_uniform(x)
            }
            #[inline(always)]
            fn from_bits_uniform(x: u64) -> Self {
                // Through i64 (the shifted word fits in 53 or 24 bits, so
                // the value is the same): one signed conversion, where an
                // unsigned one takes a branch and several instructions.
                ((x >> $shift) as i64) as $t * $scale
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                $sqrt(self)
            }
            // abs and copysign on the bits: libm's are out-of-line calls, and
            // copysign sits on every direction's path (the basis).
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::from_bits(self.to_bits() & !$sign)
            }
            #[inline(always)]
            fn copysign(self, sign: Self) -> Self {
                <$t>::from_bits((self.to_bits() & !$sign) | (sign.to_bits() & $sign))
            }
            #[inline(always)]
            fn cbrt(self) -> Self {
                $cbrt(self)
            }
            #[inline(always)]
            fn cbrt_fast(self) -> Self {
                $cbrt_fast(self)
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                libm::$sincos(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                libm::$cos(self)
            }
            #[inline(always)]
            fn sin_cos_2pi(self) -> (Self, Self) {
                $sc2pi(self)
            }
            #[inline(always)]
            fn ln(self) -> Self {
                libm::$log(self)
            }
            #[inline(always)]
            fn ln_1p(self) -> Self {
                libm::$log1p(self)
            }
            #[inline(always)]
            fn exp(self) -> Self {
                libm::$exp(self)
            }
            #[inline(always)]
            fn exp_m1(self) -> Self {
                libm::$expm1(self)
            }
            #[inline(always)]
            fn powf(self, p: Self) -> Self {
                libm::$pow(self, p)
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                libm::$atan2(self, x)
            }
            #[inline(always)]
            fn to_index(self) -> usize {
                // Through i64: one cvttss2si/cvttsd2si on x86-64, where a
                // direct unsigned conversion takes several instructions.
                // Negative values and NaN give 0.
                (self as i64).max(0) as usize
            }
            #[inline(always)]
            fn from_index(i: usize) -> Self {
                // Through i64 for the same reason (indices stay below 2⁶³).
                i as i64 as $t
            }
            #[inline(always)]
            fn pick<'a>(f32s: &'a [f32], f64s: &'a [f64]) -> &'a [Self] {
                $pick(f32s, f64s)
            }
            #[inline(always)]
            fn as_f32_io<'a>(
                u: &'a [Self],
                out: &'a mut [Self],
            ) -> Option<(&'a [f32], &'a mut [f32])> {
                $as_f32(u, out)
            }
            #[inline(always)]
            fn as_f32s(u: &[Self]) -> Option<&[f32]> {
                Self::as_f32_io(u, &mut []).map(|(u, _)| u)
            }
            #[inline(always)]
            fn as_f32s_mut(out: &mut [Self]) -> Option<&mut [f32]> {
                Self::as_f32_io(&[], out).map(|(_, o)| o)
            }
            #[inline(always)]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline(always)]
            fn is_nan(self) -> bool {
                <$t>::is_nan(self)
            }
        }
    };
}

impl_real!(
    f32,
    1u32 << 31,
    40,
    1.0 / (1u64 << 24) as f32,
    crate::math::cbrt::cbrt_f32,
    crate::math::cbrt::cbrt_fast_f32,
    |a, _| a,
    |u, out| Some((u, out)),
    crate::math::azimuth::sin_cos_2pi_f32,
    sqrt_f32,
    sincosf,
    cosf,
    logf,
    log1pf,
    expf,
    expm1f,
    powf,
    atan2f
);
impl_real!(
    f64,
    1u64 << 63,
    11,
    1.0 / (1u64 << 53) as f64,
    crate::math::cbrt::cbrt_f64,
    crate::math::cbrt::cbrt_fast_f64,
    |_, b| b,
    |_, _| None,
    crate::math::azimuth::sin_cos_2pi_f64,
    sqrt_f64,
    sincos,
    cos,
    log,
    log1p,
    exp,
    expm1,
    pow,
    atan2
);

// Square roots. On x86-64 through the SSE2 intrinsics (part of the
// baseline): libm's `sqrtf`/`sqrt` are inline assembly there, which the
// compiler cannot vectorise, so a batch loop with a square root in it stayed
// scalar. Both give the correctly rounded `sqrtss`/`sqrtsd` result.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
#[allow(unsafe_code)]
fn sqrt_f32(x: f32) -> f32 {
    use core::arch::x86_64::{_mm_cvtss_f32, _mm_set_ss, _mm_sqrt_ss};
    // SAFETY: SSE2 is part of every x86-64 target.
    unsafe { _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))) }
}
#[cfg(target_arch = "x86_64")]
#[inline(always)]
#[allow(unsafe_code)]
fn sqrt_f64(x: f64) -> f64 {
    use core::arch::x86_64::{_mm_cvtsd_f64, _mm_set_sd, _mm_sqrt_sd};
    // SAFETY: as above.
    unsafe { _mm_cvtsd_f64(_mm_sqrt_sd(_mm_set_sd(x), _mm_set_sd(x))) }
}
// Hard-float 32-bit ARM (Cortex-M4F/M7, `*-eabihf`): the FPU's `vsqrt.f32`,
// correctly rounded; libm's `sqrtf` is a software routine there. These FPUs
// may be single-precision only, so f64 keeps libm.
#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
#[inline(always)]
#[allow(unsafe_code)]
fn sqrt_f32(x: f32) -> f32 {
    let bits: u32;
    // SAFETY: FPU instructions on registers only. The value travels through
    // core registers because the compiler's `sreg` class needs
    // double-precision VFP, which these FPUs may lack; for the same reason s0
    // cannot be declared clobbered (`clobber_abi("C")` names d16–d31, which
    // a single-precision FPU reserves), so its contents are saved in r1 and
    // put back: the block changes only r0 and r1, both declared.
    unsafe {
        core::arch::asm!(
            "vmov r1, s0",
            "vmov s0, r0",
            "vsqrt.f32 s0, s0",
            "vmov r0, s0",
            "vmov s0, r1",
            inlateout("r0") x.to_bits() => bits,
            out("r1") _,
            options(pure, nomem, nostack),
        );
    }
    f32::from_bits(bits)
}
#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
use libm::sqrt as sqrt_f64;
#[cfg(not(any(
    target_arch = "x86_64",
    all(target_arch = "arm", target_abi = "eabihf")
)))]
use libm::{sqrt as sqrt_f64, sqrtf as sqrt_f32};

/// `N` doubles kept as pairs of 32-bit halves (low word first), so that a
/// model holding them keeps the 4-byte alignment of its f32 form: `sk_phase`
/// is a 128-byte, 4-byte-aligned value for C.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PackedF64<const N: usize>([[u32; 2]; N]);

impl<const N: usize> PackedF64<N> {
    /// All zeros (as a constant: no conversion code is generated for it).
    pub(crate) const ZERO: Self = PackedF64([[0; 2]; N]);
    pub(crate) fn new(values: [f64; N]) -> Self {
        Self::first_of(values)
    }
    /// The `i`-th value, bit for bit as stored.
    #[inline(always)]
    pub(crate) fn get(&self, i: usize) -> f64 {
        match self.0.get(i) {
            Some(&[lo, hi]) => f64::from_bits(lo as u64 | ((hi as u64) << 32)),
            // Only an empty pack (a model that keeps no f64 constants on
            // this target) is read past its end: it reads as zeros.
            None => 0.0,
        }
    }
    /// The first `N` of `values` (a model that keeps fewer constants, or
    /// none, on targets that do not use them).
    pub(crate) fn first_of<const M: usize>(values: [f64; M]) -> Self {
        let mut out = Self::ZERO;
        for (slot, v) in out.0.iter_mut().zip(values) {
            let b = v.to_bits();
            *slot = [b as u32, (b >> 32) as u32];
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_conversion_matches_spec() {
        assert_eq!(f32::from_bits_uniform(0), 0.0);
        assert_eq!(f32::from_bits_uniform(u64::MAX), 1.0 - 2f32.powi(-24));
        assert_eq!(f64::from_bits_uniform(u64::MAX), 1.0 - 2f64.powi(-53));
        assert_eq!(f32::from_bits_uniform(1u64 << 63), 0.5);
        // Only the top 24 / 53 bits matter.
        assert_eq!(f32::from_bits_uniform((1u64 << 40) - 1), 0.0);
        assert_eq!(f64::from_bits_uniform((1u64 << 11) - 1), 0.0);
    }

    #[test]
    fn clamps_keep_nan() {
        assert!(f32::NAN.clamp01().is_nan());
        assert_eq!((-0.5f64).clamp01(), 0.0);
        assert_eq!(1.5f32.clamp01(), 1.0);
        assert_eq!((-2.0f64).clamp_unit(), -1.0);
        assert!(f64::NAN.clamp_unit().is_nan());
    }
}
