//! Error-free transformations in f32 alone (Dekker 1971; Knuth TAOCP 2,
//! §4.2.2): a sum or product as an unevaluated pair `hi + lo` of floats,
//! with no fused multiply-add, so the portable tier's constructors round
//! their constants once from exact values on any IEEE target, GPUs
//! without double precision included. Valid while no step overflows or
//! underflows (the constructors use them on values in `[2⁻⁵⁰, 8]`).

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly (TwoSum).
#[inline(always)]
pub(crate) fn two_sum(a: f32, b: f32) -> (f32, f32) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a` as `hi + lo`, each with at most 12 significant bits (Veltkamp's
/// split with `2¹² + 1`).
#[inline(always)]
fn split(a: f32) -> (f32, f32) {
    let c = 4097.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `(p, e)` with `p = fl(a b)` and `p + e = a b` exactly (Dekker's
/// TwoProduct).
#[inline(always)]
pub(crate) fn two_prod(a: f32, b: f32) -> (f32, f32) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// The product of two pairs, to about 2⁻⁴⁴ relative, renormalised.
#[inline(always)]
pub(crate) fn mul(x: (f32, f32), y: (f32, f32)) -> (f32, f32) {
    let (p, e) = two_prod(x.0, y.0);
    let e = e + (x.0 * y.1 + x.1 * y.0);
    let s = p + e;
    (s, e - (s - p))
}
