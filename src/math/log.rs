//! `ln(1 − u)` for free paths, hand-written: every tentative collision
//! draws `−ln(1 − u)/σ`, and libm's `log1p` (a division and two polynomial
//! chains) was a fifth of a one-call-per-flight photon's time, about twice
//! glibc's table-driven `log` (measured from C on AMD family 26 model 2).
//!
//! The method is the table-driven one of Tang (1990) as glibc's `log`
//! arranges it (Szabolcs Nagy, 2018), without `fma`: `v = 2^k z` with `z`
//! in `[0.6875, 1.375)`, split into 128 intervals; on interval `i`,
//! `ln z = ln c_i + ln(1 + r)` with `r = (z − c_i)/c_i`. The difference
//! `z − c_i` is exact (Sterbenz: `c_i` and `z` lie within a factor 2), so
//! `r` carries one rounding of its product with `1/c_i`, and `ln(1 + r)`
//! is its degree-7 Taylor polynomial. The two intervals next to 1 take
//! `c = 1`, so there `r = z − 1` exactly and the result keeps its relative
//! accuracy however close `v` is to 1 (a table centre there would cancel
//! against `r`). Every interval but the one above 1 has `|r| ≤ 2⁻⁸`, so
//! the truncation is below `2⁻⁵⁹ |r|`; above 1, `|r| < 2⁻⁷` and the
//! truncation below `2⁻⁵⁹` absolutely, but there `k ≠ 0` (a `u` in
//! `[0, 1)` gives `v ≤ 1`, and `v = 1` has `r = 0`), so the result is at
//! least `ln 2 − 2⁻⁷` in size and the truncation a 64th of its ulp. The
//! table's `ln c_i` are computed at compile time in double-double
//! (`2 atanh((c − 1)/(c + 1))`, 24 terms), so no constant is copied by
//! hand; a test checks the whole function against an independent
//! double-double logarithm.
//!
//! `1 − u` itself is exact for every `u` a generator gives (`k 2⁻⁵³`, and
//! any `u ≥ ½`); where it is not, adding its rounding back cost a second
//! rounding (1.47 ulp measured), so those `u` take libm's `log1p`.

use crate::math::double_double::{Dd, two_prod, two_sum};

/// Whether doubles run in hardware at the speed of single precision, so
/// that f32 callers take the f64 route too (firmware FPUs are single).
pub(crate) const WIDE: bool = cfg!(any(
    target_arch = "x86_64",
    target_arch = "x86",
    target_arch = "aarch64"
));

/// Intervals of `z`.
const N: usize = 128;
/// `z`'s range starts at `0x1.6p-1 = 0.6875`: `bits − OFF` puts the
/// interval index in the top 7 mantissa bits and `k` in the exponent.
const OFF: u64 = 0x3fe6_0000_0000_0000;
/// `ln 2` split so that `k · LN2_HI` is exact for `|k| < 2¹¹`.
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fefa_3800);
const LN2_LO: f64 = f64::from_bits(0x3d2e_f357_93c7_6730);

/// Interval `i`'s `(1/c, c, ln c hi, ln c lo)`.
static TABLE: [[f64; 4]; N] = table();

/// `ln(1 − u)` for `u` in `[0, 1)`, within 1 ulp (0.744 ulp the largest
/// error the test below finds); `−∞` at `u = 1` and NaN for NaN, as
/// `ln_1p(−u)`.
#[inline(always)]
pub(crate) fn ln_1m(u: f64) -> f64 {
    let v = 1.0 - u;
    // 1 − u = v + (1 − v) − u exactly (Fast2Sum, |1| ≥ |u| here): the
    // table route where v is 1 − u, normal and finite; libm's log1p for
    // the rest (off-grid u whose 1 − u rounds, u ≥ 1, NaN). v > 0 is the
    // whole range test: a v of +∞ comes only from u = −∞, whose (1 − v) − u
    // is NaN, and no v is subnormal (the doubles next to 1 are 2⁻⁵³ and
    // 2⁻⁵² from it, so a non-zero 1 − u is at least 2⁻⁵³ in size). The
    // test of v against [MIN_POSITIVE, ∞) it replaces was 4 of the 128 ns
    // of a homogeneous slab photon from Rust (Intel Xeon, family 6 model
    // 167).
    if v > 0.0 && (1.0 - v) - u == 0.0 {
        // ln 1 comes out +0; log1p(−u) gives −0 for u = +0 (and a free
        // path of +0), so the zero takes −u's sign.
        let l = ln_normal(v);
        if l == 0.0 { -u } else { l }
    } else {
        libm::log1p(-u)
    }
}

/// `ln v` for a positive, normal, finite `v`.
#[inline(always)]
fn ln_normal(v: f64) -> f64 {
    let bits = v.to_bits();
    let tmp = bits.wrapping_sub(OFF);
    let i = ((tmp >> 45) % N as u64) as usize;
    let k = (tmp as i64 >> 52) as f64;
    let z = f64::from_bits(bits.wrapping_sub(tmp & (0xfff << 52)));
    let [invc, c, logc_hi, logc_lo] = TABLE[i];
    let r = (z - c) * invc;
    // k ln 2 + ln c as w + we exactly, then + r by Fast2Sum (|w| ≥ |r|
    // wherever w ≠ 0, and w = 0 leaves hi = r).
    let a = k * LN2_HI;
    let w = a + logc_hi;
    let we = (a - w) + logc_hi;
    let hi = w + r;
    let lo = (w - hi) + r + we + logc_lo + k * LN2_LO;
    // ln(1 + r) − r = r² q(r), by Estrin's scheme; q of degree 5 (the
    // module docs bound the r⁸ term it leaves out, which cost 1–3 ns of a
    // slab photon's 125–260 from Rust, Intel Xeon, family 6 model 167; the
    // largest error the test below finds is the same 0.744 ulp with it).
    let (r2, third) = (r * r, 1.0 / 3.0);
    let r4 = r2 * r2;
    let q = (-0.5 + r * third) + r2 * (-0.25 + r * 0.2) + r4 * (-1.0 / 6.0 + r * (1.0 / 7.0));
    hi + (lo + r2 * q)
}

/// Double-double `a + b`.
const fn dd_add(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let Dd { hi: s, lo: e } = two_sum(a.0, b.0);
    let e = e + a.1 + b.1;
    let h = s + e;
    (h, e - (h - s))
}

/// Double-double `a · b`.
const fn dd_mul(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let Dd { hi: p, lo: e } = two_prod(a.0, b.0);
    let e = e + (a.0 * b.1 + a.1 * b.0);
    let h = p + e;
    (h, e - (h - p))
}

/// Double-double `a / b` (two quotient digits and a correction).
const fn dd_div(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let q1 = a.0 / b.0;
    let m = dd_mul(b, (q1, 0.0));
    let r = dd_add(a, (-m.0, -m.1));
    let q2 = r.0 / b.0;
    let m = dd_mul(b, (q2, 0.0));
    let r = dd_add(r, (-m.0, -m.1));
    let q3 = r.0 / b.0;
    dd_add(dd_add((q1, 0.0), (q2, 0.0)), (q3, 0.0))
}

/// `ln c` in double-double for `c` in `[0.6875, 1.375]` with `c ± 1`
/// exact: `2 atanh(s)`, `s = (c − 1)/(c + 1)`, `|s| < 0.16`, so 24 terms
/// of the series leave less than `2⁻¹¹⁰`.
pub(crate) const fn ln_dd(c: f64) -> (f64, f64) {
    let s = dd_div((c - 1.0, 0.0), (c + 1.0, 0.0));
    let s2 = dd_mul(s, s);
    let mut power = s;
    let mut sum = (0.0, 0.0);
    let mut j = 0;
    while j < 24 {
        sum = dd_add(sum, dd_div(power, ((2 * j + 1) as f64, 0.0)));
        power = dd_mul(power, s2);
        j += 1;
    }
    (2.0 * sum.0, 2.0 * sum.1)
}

/// The table: interval `i` of `z` is `[a, a + w)` with the top 7
/// mantissa bits of `bits(z) − OFF` equal to `i`, its centre `c` (1 for
/// the two intervals beside 1).
const fn table() -> [[f64; 4]; N] {
    let mut t = [[0.0; 4]; N];
    let mut i = 0;
    while i < N {
        let (a, w) = interval(i);
        let c = if i == 79 || i == 80 { 1.0 } else { a + 0.5 * w };
        let l = ln_dd(c);
        t[i] = [1.0 / c, c, l.0, l.1];
        i += 1;
    }
    t
}

/// Interval `i` of `z` as `(start, width)`: for `i < 80`, `z` in
/// `[0.5 (1 + m/128), + 2⁻⁸)` with `m = i + 48`; else `[1 + m/128, + 2⁻⁷)`
/// with `m = i − 80`.
const fn interval(i: usize) -> (f64, f64) {
    if i < 80 {
        (0.5 * (1.0 + (i + 48) as f64 / 128.0), 1.0 / 256.0)
    } else {
        (1.0 + (i - 80) as f64 / 128.0, 1.0 / 128.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `ln v` in double-double, independent of the table: `v = 2^k m`
    /// with `m` in `[0.75, 1.5)`, `ln m = 2 atanh((m − 1)/(m + 1))` with
    /// the quotient and 30 terms of the series in double-double.
    fn reference(v: f64) -> (f64, f64) {
        let (mut m, mut k) = (v, 0i32);
        while m >= 1.5 {
            m *= 0.5;
            k += 1;
        }
        while m < 0.75 {
            m *= 2.0;
            k -= 1;
        }
        let ln2 = (
            f64::from_bits(0x3fe6_2e42_fefa_39ef),
            f64::from_bits(0x3c7a_bc9e_3b39_803f),
        );
        // m + 1 rounds for a full-width m: its two-sum keeps it exact.
        let sum = two_sum(m, 1.0);
        let s = dd_div((m - 1.0, 0.0), (sum.hi, sum.lo));
        let s2 = dd_mul(s, s);
        let (mut power, mut sum) = (s, (0.0, 0.0));
        for j in 0..30 {
            sum = dd_add(sum, dd_div(power, ((2 * j + 1) as f64, 0.0)));
            power = dd_mul(power, s2);
        }
        dd_add(dd_mul(ln2, (k as f64, 0.0)), (2.0 * sum.0, 2.0 * sum.1))
    }

    /// Error in ulps of the f64 result `got` against `(hi, lo)`.
    fn ulps(got: f64, want: (f64, f64)) -> f64 {
        let err = (got - want.0) - want.1;
        let ulp = f64::from_bits(want.0.abs().to_bits() + 1) - want.0.abs();
        (err / ulp).abs()
    }

    /// Within 1 ulp of the reference (the bound set before measuring):
    /// 10⁶ generator-grid `u`, every `u = 2⁻ʲ` and `1 − 2⁻ʲ`, each
    /// interval's ends, and off-grid `u` whose `1 − u` rounds.
    #[test]
    fn ln_1m_within_one_ulp() {
        let mut worst = 0.0f64;
        let mut check = |u: f64| {
            let v = (1.0 - u, (1.0 - (1.0 - u)) - u);
            // ln(v.0 + v.1) = ln v.0 + v.1/v.0 to far below an ulp.
            let r = dd_add(reference(v.0), (v.1 / v.0, 0.0));
            if r.0 != 0.0 {
                // Each point on its own: a running `max` passes over NaN.
                let e = ulps(ln_1m(u), r);
                assert!(e <= 1.0, "u = {u:e}: {e} ulp");
                worst = worst.max(e);
            } else {
                assert_eq!(ln_1m(u), 0.0);
            }
        };
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..1_000_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            check((s >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0));
            check(((s >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0)) * 1e-7);
        }
        for j in 1..=1074 {
            check(2f64.powi(-j));
        }
        for j in 1..=53 {
            check(1.0 - 2f64.powi(-j));
        }
        for &[_, c, _, _] in &TABLE {
            for x in [c, c * (1.0 + 1e-3), c * (1.0 - 1e-3)] {
                for scale in [1.0, 0.5, 0.25, 1e-3] {
                    let v = x * scale;
                    if v < 1.0 {
                        check(1.0 - v);
                    }
                }
            }
        }
        // Each interval's ends, where |r| is largest (2⁻⁷ just below 1 +
        // 2⁻⁷, the interval whose c is 1), at v = 2⁻ʲ z.
        for i in 0..N {
            let (a, w) = interval(i);
            let top = f64::from_bits((a + w).to_bits() - 1);
            for z in [a, top] {
                for j in [0, 1, 2, 10, 40] {
                    let v = z * 2f64.powi(-j);
                    if v < 1.0 {
                        check(1.0 - v);
                    }
                }
            }
        }
        extern crate std;
        std::println!("ln(1 − u): worst {worst} ulp");
        assert_eq!(ln_1m(0.0).to_bits(), (-0.0f64).to_bits());
        assert_eq!(ln_1m(-0.0).to_bits(), 0);
        assert_eq!(ln_1m(1.0), f64::NEG_INFINITY);
        assert!(ln_1m(f64::NAN).is_nan());
    }
}
