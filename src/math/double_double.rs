//! Double-double arithmetic (Dekker 1971; Shewchuk 1997; Hida, Li &
//! Bailey's QD library): a value is an unevaluated sum `hi + lo` with
//! `|lo| ≤ ulp(hi)/2`, about 106 bits. Only what the exact inverses need to
//! evaluate a residual `u − F(μ)` below f64 rounding; no `fma` is assumed
//! (the products are split, so the result does not depend on the target).

use core::ops::{Add, Div, Mul, Sub};

/// `hi + lo`, normalised so `hi` is the f64 nearest the sum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Dd {
    pub(crate) hi: f64,
    pub(crate) lo: f64,
}

/// `a + b` exactly as `s + e` (Knuth's two-sum, any order of magnitude).
#[inline(always)]
pub(crate) const fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    Dd { hi: s, lo: e }
}

/// `a + b` exactly, for `|a| ≥ |b|` (or `a = 0`).
#[inline(always)]
fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

/// Dekker's split: `a = hi + lo` with each half holding 26 bits.
#[inline(always)]
const fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a·b` exactly as `p + e` (Dekker's product; `|a·b|` well inside the
/// f64 range).
#[inline(always)]
pub(crate) const fn two_prod(a: f64, b: f64) -> Dd {
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    Dd { hi: p, lo: e }
}

impl Dd {
    /// The exact value of an f64.
    #[inline(always)]
    pub(crate) fn from(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }
    /// `a + b` for two f64, exactly.
    #[inline(always)]
    pub(crate) fn sum(a: f64, b: f64) -> Dd {
        two_sum(a, b)
    }
    /// `a·b` for two f64, exactly.
    #[inline(always)]
    pub(crate) fn product(a: f64, b: f64) -> Dd {
        two_prod(a, b)
    }
    /// The square root, one Newton correction of the f64 root:
    /// `x + (a − x²)/(2x)` with `a − x²` formed exactly.
    #[inline]
    pub(crate) fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::from(0.0);
        }
        let x = libm::sqrt(self.hi);
        let r = self - two_prod(x, x);
        quick_two_sum(x, r.hi / (2.0 * x))
    }
}

impl Add for Dd {
    type Output = Dd;
    #[inline(always)]
    fn add(self, b: Dd) -> Dd {
        let s = two_sum(self.hi, b.hi);
        let t = two_sum(self.lo, b.lo);
        let s = quick_two_sum(s.hi, s.lo + t.hi);
        quick_two_sum(s.hi, s.lo + t.lo)
    }
}

impl Sub for Dd {
    type Output = Dd;
    #[inline(always)]
    fn sub(self, b: Dd) -> Dd {
        self + Dd {
            hi: -b.hi,
            lo: -b.lo,
        }
    }
}

impl Mul for Dd {
    type Output = Dd;
    #[inline(always)]
    fn mul(self, b: Dd) -> Dd {
        let p = two_prod(self.hi, b.hi);
        quick_two_sum(p.hi, p.lo + (self.hi * b.lo + self.lo * b.hi))
    }
}

impl Div for Dd {
    type Output = Dd;
    /// Long division: two f64 quotient digits, each remainder formed in
    /// double-double.
    #[inline]
    fn div(self, b: Dd) -> Dd {
        let q1 = self.hi / b.hi;
        let r = self - b * Dd::from(q1);
        let q2 = r.hi / b.hi;
        let r = r - b * Dd::from(q2);
        let q3 = r.hi / b.hi;
        let q = quick_two_sum(q1, q2);
        q + Dd::from(q3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_transformations() {
        let a = 1.0 + f64::EPSILON;
        let p = Dd::product(a, a);
        // (1 + ε)² = 1 + 2ε + ε²: the ε² is the low part.
        assert_eq!(p.hi, 1.0 + 2.0 * f64::EPSILON);
        assert_eq!(p.lo, f64::EPSILON * f64::EPSILON);
        let s = Dd::sum(1.0, 1e-30);
        assert_eq!((s.hi, s.lo), (1.0, 1e-30));
    }

    #[test]
    fn sqrt_and_division_to_double_double_accuracy() {
        // sqrt(2)² − 2 and (1/3)·3 − 1 vanish to ~2⁻¹⁰⁴.
        let r = Dd::from(2.0).sqrt();
        let e = r * r - Dd::from(2.0);
        assert!(e.hi.abs() < 1e-30, "{e:?}");
        let q = Dd::from(1.0) / Dd::from(3.0);
        let e = q * Dd::from(3.0) - Dd::from(1.0);
        assert!(e.hi.abs() < 1e-31, "{e:?}");
    }
}
