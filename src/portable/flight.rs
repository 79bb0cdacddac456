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

/// `ln 2` in two parts for the exponential's reduction, the high part with
/// 12 trailing zero bits so that `k · EXP_LN2_HI` is exact for `|k| ≤ 150`.
const EXP_LN2_HI: f32 = 0.693_145_75;
const EXP_LN2_LO: f32 = 1.428_606_8e-6;
const INV_LN2: f32 = f32::from_bits(0x3fb8_aa3b);
/// Minimax coefficients of `r (e^r + 1)/(e^r − 1) ≈ 2 + P1 r² + P2 r⁴`
/// on `|r| ≤ ½ ln 2`, as in FreeBSD's `e_expf.c` (fdlibm).
const EXP_P1: f32 = 0.166_666_25;
const EXP_P2: f32 = -2.766_733_3e-3;

/// `e^x` within an ulp (the fdlibm `expf` scheme: `x = k ln 2 + r`,
/// `|r| ≤ ½ ln 2`, `e^r = 1 + 2r/(R(r²) − r)` with
/// `R(r²) ≈ r (e^r + 1)/(e^r − 1)`, then the exact scaling by `2^k`).
/// `+∞` from `x ≥ 88.722839` (the largest finite `e^x` is at 88.72283),
/// `0` below `−103.972084`, subnormal results between; NaN gives NaN.
pub fn exp(x: f32) -> f32 {
    if x.is_nan() {
        return x;
    }
    if x >= f32::from_bits(0x42b1_7218) {
        return f32::INFINITY;
    }
    if x < -103.972_084 {
        return 0.0;
    }
    let half = if x < 0.0 { -0.5 } else { 0.5 };
    // |x| ≤ 104: the conversion truncates towards 0, so adding ±½
    // rounds to the nearest k.
    let k = (INV_LN2 * x + half) as i32;
    let kf = k as f32;
    // x − k·ln2_hi is exact (Sterbenz-like: k·ln2_hi exact and close to x);
    // the low part is subtracted separately to keep r's error below an ulp.
    let hi = x - kf * EXP_LN2_HI;
    let lo = kf * EXP_LN2_LO;
    let r = hi - lo;
    let t = r * r;
    let c = r - t * (EXP_P1 + t * EXP_P2);
    if k == 0 {
        return 1.0 - ((r * c) / (c - 2.0) - r);
    }
    let y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi);
    // 2^k as bits; below 2^-125 in two steps so that the subnormal result
    // rounds once.
    if k >= -125 {
        if k == 128 {
            return y * 2.0 * f32::from_bits(0x7f00_0000);
        }
        y * f32::from_bits(((127 + k) as u32) << 23)
    } else {
        y * f32::from_bits(((127 + k + 100) as u32) << 23) * f32::from_bits(0x0d80_0000)
    }
}

/// The transmittance `e^(−σ_t d)` of a homogeneous medium of extinction
/// `sigma_t ≥ 0` (per length unit) over a distance `d ≥ 0`; `d = +∞`
/// gives 0 for `σ_t > 0`, NaN for `σ_t = 0` (as `0 · ∞`).
pub fn transmittance(sigma_t: f32, d: f32) -> f32 {
    exp(-(sigma_t * d))
}

/// Free flight in a spectral medium, one path for several wavelength
/// channels (hero-wavelength sampling: Wilkie et al., EGSR 2014; pbrt-v4
/// §14.2): the distance is drawn at the hero channel's extinction,
/// `t = −ln(1 − u)/σ_t[hero]`, and `ratio[c]` receives channel `c`'s
/// density of the same event over the hero's:
///
/// * a collision (`t < t_max`): `(σ_c/σ_h) e^(−(σ_c − σ_h) t)`;
/// * an escape (`t ≥ t_max`): `e^(−(σ_c − σ_h) t_max)`, the ratio of
///   transmittances.
///
/// Formed as one exponential of the difference, the ratio neither
/// overflows nor underflows where both densities would (`σ_h t` stays
/// below 17 for every `u < 1`). The mean of the ratios is the balance
/// heuristic's denominator over a uniformly drawn hero: a channel's
/// weight is its own estimate over that mean.
///
/// Returns `t` (`+∞` for `u = 1`); NaN, with `ratio` untouched, for a NaN
/// `u`, and unless `hero < sigma_t.len() ≤ ratio.len()` and
/// `σ_t[hero]` is finite and `> 0`. Every
/// `σ_c` must be finite and `≥ 0` (a NaN gives a NaN ratio); `t_max ≥ 0`
/// (+∞ allowed). The header's `skp_spectral_free_path`.
pub fn spectral_free_path(
    sigma_t: &[f32],
    hero: usize,
    u: f32,
    t_max: f32,
    ratio: &mut [f32],
) -> f32 {
    let Some(&sh) = sigma_t.get(hero) else {
        return f32::NAN;
    };
    if !(sh > 0.0 && sh < f32::INFINITY) || ratio.len() < sigma_t.len() {
        return f32::NAN;
    }
    let t = free_path(sh, u);
    if t.is_nan() {
        return t;
    }
    let hit = t < t_max;
    let at = if hit { t } else { t_max };
    for (r, &sc) in ratio.iter_mut().zip(sigma_t) {
        let d = sc - sh;
        let e = if d == 0.0 { 1.0 } else { exp(-(d * at)) };
        *r = if hit { sc / sh * e } else { e };
    }
    t
}
