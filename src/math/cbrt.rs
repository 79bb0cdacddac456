//! Cube roots: Kahan's bit-trick seed refined by Lancaster's iteration
//! (Kahan, "Computing a real cube root", 1991; Lancaster, J. Am. Stat.
//! Assoc. 37, 1942; Frisvad 2011 §4 uses the same pair for Rayleigh's direct
//! method).
//!
//! Special values: `±0`, `±∞` and NaN are returned as they are; every other
//! input, subnormals included, goes through the seed and the steps, and
//! `cbrt(-x) == -cbrt(x)` exactly (the sign is split off first).
//!
//! * Seed: integer division of the magnitude's bits by 3 plus a bias
//!   (FreeBSD msun's `B1`; subnormals are scaled into the normal range first
//!   and use `B2`). Relative error about 3.2 %.
//! * Lancaster's step for `t³ = x` (Halley's method, cubic convergence):
//!   `t ← t (t³ + 2x) / (2t³ + x)`. Each step turns a relative error ε into
//!   about (2/3) ε³.
//!
//! Precision, measured by `tests/models/cbrt.rs` (`docs/guides/c_api.md` has the figures):
//! * `f32`: two steps, carried out in `f64` arithmetic where the product form
//!   above cannot overflow or underflow for any `f32` input (|t³| stays within
//!   [1e-46, 4e38]). `cbrt_fast_f32` takes one step.
//! * `f64`: three steps in the ratio form `r = t²·(t/x)`,
//!   `t ← t + t (1 − r) / (2r + 1)`, which never forms `t³` and so is valid on
//!   every double (the product form overflows above ~4e230 and underflows below
//!   ~6e-232). `cbrt_fast_f64` takes two.

/// f32 seed bias for normal inputs (msun `s_cbrtf.c`, B1).
const B1_F32: u32 = 709_958_130;
/// f32 seed bias after scaling a subnormal by 2²⁴ (B2).
const B2_F32: u32 = 642_849_266;
/// f64 seed bias on the high word for normal inputs (msun `s_cbrt.c`, B1).
const B1_F64: u32 = 715_094_163;
/// f64 seed bias on the high word after scaling a subnormal by 2⁵⁴ (B2).
const B2_F64: u32 = 696_219_795;

/// Kahan's seed for `cbrt(|x|)` with `x`'s sign, for finite nonzero `x`.
#[inline(always)]
fn seed_f32(x: f32) -> f32 {
    let sign = x.to_bits() & 0x8000_0000;
    let mag = x.to_bits() & 0x7fff_ffff;
    let hx = if mag < 0x0080_0000 {
        subnormal_seed_f32(mag)
    } else {
        mag / 3 + B1_F32
    };
    f32::from_bits(sign | hx)
}

/// The seed's bits for a subnormal magnitude: scaled by 2^24 so that the
/// exponent field means something. Out of line and cold, so that the
/// compiler branches to it rather than computing it for every input and
/// selecting (that put a multiply and two register moves on every cube
/// root's critical path: 1.2× libm's `cbrtf` instead of 1.0×).
#[cold]
#[inline(never)]
fn subnormal_seed_f32(mag: u32) -> u32 {
    (f32::from_bits(mag) * 16_777_216.0).to_bits() / 3 + B2_F32
}

/// Kahan's seed for `cbrt(|x|)` with `x`'s sign, for finite nonzero `x`.
#[inline(always)]
fn seed_f64(x: f64) -> f64 {
    let sign = x.to_bits() & 0x8000_0000_0000_0000;
    let mag = x.to_bits() & 0x7fff_ffff_ffff_ffff;
    if ((mag >> 32) as u32) < 0x0010_0000 {
        f64::from_bits(sign | ((subnormal_seed_f64(mag) as u64) << 32))
    } else {
        seed_normal_f64(x)
    }
}

/// The seed's high word for a subnormal magnitude, scaled by 2^54 (out of
/// line for the reason [`subnormal_seed_f32`] is).
#[cold]
#[inline(never)]
fn subnormal_seed_f64(mag: u64) -> u32 {
    let scaled = f64::from_bits(mag) * 18_014_398_509_481_984.0;
    ((scaled.to_bits() >> 32) as u32) / 3 + B2_F64
}

/// Lancaster's step in product form; only for arguments whose cube is a
/// normal double (here: f32 inputs widened to f64).
#[inline(always)]
fn step_product(t: f64, x: f64) -> f64 {
    let t3 = t * t * t;
    t * (t3 + 2.0 * x) / (2.0 * t3 + x)
}

/// Lancaster's step in ratio form: `r = t³/x` is formed as `t²·(t/x)` so
/// neither `t³` nor `t²·t` can overflow or underflow for any finite `x`.
#[inline(always)]
fn step_ratio(t: f64, x: f64) -> f64 {
    let r = (t * t) * (t / x);
    t + t * (1.0 - r) / (2.0 * r + 1.0)
}

/// True for ±0, ±∞ and NaN: the inputs returned unchanged.
#[inline(always)]
fn is_special_f32(x: f32) -> bool {
    (x.to_bits() & 0x7fff_ffff).wrapping_sub(1) >= 0x7f7f_ffff
}

#[inline(always)]
fn is_special_f64(x: f64) -> bool {
    (x.to_bits() & 0x7fff_ffff_ffff_ffff).wrapping_sub(1) >= 0x7fef_ffff_ffff_ffff
}

/// Cube root of an `f32`: within 1 ULP of the correctly rounded result on
/// every input (measured exhaustively: `docs/guides/c_api.md`).
#[inline]
pub fn cbrt_f32(x: f32) -> f32 {
    if is_special_f32(x) {
        return x;
    }
    let xd = x as f64;
    let t = seed_f32(x) as f64;
    step_product(step_product(t, xd), xd) as f32
}

/// Cube root of an `f32` with one Lancaster step: relative error about
/// 2·10⁻⁵ (a few hundred ULP), for samplers that can afford it.
#[inline]
pub fn cbrt_fast_f32(x: f32) -> f32 {
    if is_special_f32(x) {
        return x;
    }
    step_product(seed_f32(x) as f64, x as f64) as f32
}

/// Cube root of an `f64`: about 1 ULP on every input (`docs/guides/c_api.md`).
#[inline]
pub fn cbrt_f64(x: f64) -> f64 {
    if is_special_f64(x) {
        return x;
    }
    let t = seed_f64(x);
    step_ratio(step_ratio(step_ratio(t, x), x), x)
}

/// Cube root of an `f64` with two Lancaster steps: relative error about
/// 10⁻¹⁴ (tens of ULP).
#[inline]
pub fn cbrt_fast_f64(x: f64) -> f64 {
    if is_special_f64(x) {
        return x;
    }
    step_ratio(step_ratio(seed_f64(x), x), x)
}

/// Kahan's seed refined by `steps` Lancaster steps (in f64 arithmetic, as
/// [`cbrt_f32`] does): 0 steps is the seed alone (~3 % error), 1 is
/// [`cbrt_fast_f32`], 2 is [`cbrt_f32`]. For measuring the accuracy/cost
/// curve of the step count; special values are returned as they are.
#[inline]
pub fn cbrt_f32_steps(x: f32, steps: u32) -> f32 {
    if is_special_f32(x) {
        return x;
    }
    let xd = x as f64;
    let mut t = seed_f32(x) as f64;
    for _ in 0..steps {
        t = step_product(t, xd);
    }
    t as f32
}

/// Cube root of an `f64` in product form with two steps (about 10⁻¹⁴
/// relative, like [`cbrt_fast_f64`] at half its divisions), for arguments
/// whose magnitude lies in `[1e-200, 1e200]`, where `t³` cannot overflow or
/// underflow. Outside that range the result is not meaningful (callers check).
/// Such arguments are normal, so the seed needs neither the check for zero,
/// infinity and NaN nor the subnormal case (whose out-of-line call made the
/// caller save its registers on every call).
#[inline]
pub(crate) fn cbrt_moderate_f64(x: f64) -> f64 {
    step_product(step_product(seed_normal_f64(x), x), x)
}

/// [`seed_f64`] for a normal `x`.
#[inline(always)]
fn seed_normal_f64(x: f64) -> f64 {
    let sign = x.to_bits() & 0x8000_0000_0000_0000;
    let high = ((x.to_bits() & 0x7fff_ffff_ffff_ffff) >> 32) as u32;
    f64::from_bits(sign | (((high / 3 + B1_F64) as u64) << 32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_values_pass_through() {
        for f in [cbrt_f32, cbrt_fast_f32] {
            assert_eq!(f(0.0).to_bits(), 0.0f32.to_bits());
            assert_eq!(f(-0.0).to_bits(), (-0.0f32).to_bits());
            assert_eq!(f(f32::INFINITY), f32::INFINITY);
            assert_eq!(f(f32::NEG_INFINITY), f32::NEG_INFINITY);
            assert!(f(f32::NAN).is_nan());
        }
        for f in [cbrt_f64, cbrt_fast_f64] {
            assert_eq!(f(0.0).to_bits(), 0.0f64.to_bits());
            assert_eq!(f(-0.0).to_bits(), (-0.0f64).to_bits());
            assert_eq!(f(f64::INFINITY), f64::INFINITY);
            assert_eq!(f(f64::NEG_INFINITY), f64::NEG_INFINITY);
            assert!(f(f64::NAN).is_nan());
        }
    }

    #[test]
    fn exact_cubes_and_extremes() {
        assert_eq!(cbrt_f32(27.0), 3.0);
        assert_eq!(cbrt_f32(-8.0), -2.0);
        assert!((cbrt_f64(1e-300) / libm::cbrt(1e-300) - 1.0).abs() < 4e-16);
        assert_eq!(cbrt_f64(64.0), 4.0);
        let tiny = f32::from_bits(1);
        assert!((cbrt_f32(tiny) - libm::cbrtf(tiny)).abs() <= f32::EPSILON * libm::cbrtf(tiny));
        let big = f64::MAX;
        assert!((cbrt_f64(big) / libm::cbrt(big) - 1.0).abs() < 4e-16);
        let sub = f64::from_bits(1);
        assert!((cbrt_f64(sub) / libm::cbrt(sub) - 1.0).abs() < 4e-16);
    }
}
