//! Free flight in the portable tier: `t = −ln(1 − u)/σ_t`, with the
//! natural logarithm in f32 operations alone.

use super::clamp01;

/// `ln 2` in two parts, the high part with 8 trailing zero bits so that
/// `k · LN2_HI` is exact for every exponent `k`.
const LN2_HI: f32 = 0.693_138_1;
const LN2_LO: f32 = 9.058_001e-6;
/// Minimax coefficients of `(ln((1 + s)/(1 − s)) − 2s)/s` in `s²` on
/// `|s| ≤ 0.1716` (the reduction below), as in FreeBSD's `e_logf.c`
/// (fdlibm): `R(z) = Lg1 z + Lg2 z² + Lg3 z³ + Lg4 z⁴`.
const LG1: f32 = 0.666_666_6;
const LG2: f32 = 0.400_009_72;
const LG3: f32 = 0.284_987_87;
const LG4: f32 = 0.242_790_79;

/// The natural logarithm of a positive, normal or subnormal `x`, within
/// an ulp (the fdlibm `logf` scheme: `x = 2^k m`, `m ∈ [√½, √2)`,
/// `f = m − 1` exact, `ln m = f − (f²/2 − s(f²/2 + R))`, `s = f/(2 + f)`).
/// `ln 0 = −∞`, `ln ∞ = ∞`; negative or NaN `x` gives NaN.
pub fn ln(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 {
        return if x == 0.0 {
            f32::NEG_INFINITY
        } else {
            f32::NAN
        };
    }
    if x == f32::INFINITY {
        return x;
    }
    // Subnormals scaled into the normal range by 2²⁵ (exact).
    let (x, k0) = if x < f32::MIN_POSITIVE {
        (x * 33_554_432.0, -25)
    } else {
        (x, 0)
    };
    let bits = x.to_bits();
    // The exponent of x, with m ≥ √2 (mantissa above 0x3504f3) moved to the
    // next power so that m lands in [√½, √2).
    let ix = bits.wrapping_add(0x3f80_0000 - 0x3f35_04f3);
    let k = k0 + (ix >> 23) as i32 - 127;
    let m = f32::from_bits((ix & 0x007f_ffff) + 0x3f35_04f3);
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let z = s * s;
    let w = z * z;
    let r = z * (LG1 + w * LG3) + w * (LG2 + w * LG4);
    let hfsq = 0.5 * f * f;
    let dk = k as f32;
    dk * LN2_HI - ((hfsq - (s * (hfsq + r) + dk * LN2_LO)) - f)
}

/// A free-flight distance `t = −ln(1 − u)/σ_t` in a homogeneous medium of
/// extinction `sigma_t > 0` (per length unit), `u ∈ [0, 1]` (clamped;
/// NaN gives NaN); `u = 1` gives `+∞`. `ln(1 − u)` is formed as
/// `ln w + ((1 − w) − u)/w`, `w = 1 − u` rounded: the second term restores
/// what the rounding of `w` lost, so small `u` keep their relative
/// precision (`−ln(1 − u) ≈ u`), where `ln(1 − u)` alone would be off by
/// up to 100 %.
pub fn free_path(sigma_t: f32, u: f32) -> f32 {
    let u = clamp01(u);
    let w = 1.0 - u;
    // (1 − w) is exact (Sterbenz, w ≥ ½ whenever u ≤ ½) and so is its
    // difference from u; for u > ½, w is exact and the term is 0.
    let l = if w == 0.0 {
        f32::NEG_INFINITY
    } else {
        ln(w) + ((1.0 - w) - u) / w
    };
    -l / sigma_t
}
