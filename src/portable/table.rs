//! Table lookups of the portable tier, for tables the library built (an
//! `sk_table`'s or `Table`'s `data`, copied to a device buffer as it is):
//! the cubic Hermite inverse CDF (`Inverse`, `Measured`), Frisvad's
//! Rayleigh CDF table, and the 2-D blend of Hermite slices. `cos θ` is the
//! library's own lookup bit for bit (`Table::sample_cos`,
//! `Table2d::sample_cos`); the density comes with the sample, from the
//! interval the sample fell in (`1/(2π n μ'(t))` for a Hermite cubic, the
//! CDF step over its width for Frisvad's table), so a kernel needs no
//! root-finding. Layouts: `include/scatterkit_table.h`.
//!
//! Every function returns NaN for `n = 0` or data shorter than the layout
//! needs (`2(n + 1)` values per Hermite slice, `n + 1` for the CDF table).

use super::clamp01;

/// `1/(2π)` rounded to f32.
const INV_2PI: f32 = 0.159_154_94;

/// `(μ, μ'(t))` of the Hermite cubic at `u ∈ [0, 1]` (not clamped here):
/// `x = u n`, `i = min(⌊x⌋, n − 1)`, `t = x − i`, `μ = y0 + t (d0 + t (c2 +
/// t c3))` held in `[y0, y1]` (its rounding can pass `y1` by an ulp), then
/// clamped to `[−1, 1]` (the library's operations), and the cubic's slope
/// in `t`, `d0 + t (2c2 + 3t c3)`.
#[inline(always)]
fn hermite(data: &[f32], n: usize, u: f32) -> (f32, f32) {
    if n == 0 {
        return (f32::NAN, f32::NAN);
    }
    let x = u * n as f32;
    // x ≥ 1 excludes NaN; the conversion truncates, as C's does.
    let i = if x >= 1.0 { (x as usize).min(n - 1) } else { 0 };
    let t = x - i as f32;
    let [y0, d0, y1, d1] = match data.get(2 * i..2 * i + 4) {
        Some(&[a, b, c, d]) => [a, b, c, d],
        _ => return (f32::NAN, f32::NAN),
    };
    let dy = y1 - y0;
    let c2 = 3.0 * dy - 2.0 * d0 - d1;
    let c3 = d0 + d1 - 2.0 * dy;
    let mu = y0 + t * (d0 + t * (c2 + t * c3));
    let mu = if mu > y1 { y1 } else { mu };
    let mu = (if mu < y0 { y0 } else { mu }).clamp(-1.0, 1.0);
    (mu, d0 + t * (2.0 * c2 + 3.0 * t * c3))
}

/// `cos θ` of a Hermite table (`Inverse` or `Measured`, `n` intervals) at
/// `u ∈ [0, 1]` (clamped; NaN gives NaN): `Table::sample_cos`'s bits.
#[inline]
pub fn table_sample_cos(data: &[f32], n: usize, u: f32) -> f32 {
    hermite(data, n, clamp01(u)).0
}

/// `(cos θ, density per steradian)` of a Hermite table at `u`: the
/// density `1/(2π n μ'(t))` of the interval's cubic at the sample (+∞
/// where the spline is flat).
#[inline]
pub fn table_sample_cos_pdf(data: &[f32], n: usize, u: f32) -> (f32, f32) {
    let (mu, dmu) = hermite(data, n, clamp01(u));
    (mu, INV_2PI / (n as f32 * dmu))
}

/// `(cos θ, density)` of Frisvad's Rayleigh CDF table (`n + 1` values
/// `F_i` at `μ_i = −1 + 2i/n`) at `u ∈ [0, 1]` (clamped; NaN gives NaN):
/// the largest `i < n` with `F_i ≤ u` by bisection, `t = (u − F_i)/(F_{i+1}
/// − F_i)`, `μ = (i + t)(2/n) − 1` clamped (`Table::sample_cos`'s bits),
/// and the density `(F_{i+1} − F_i)/(2π · 2/n)` of that interval.
#[inline]
pub fn table_cdf_sample_cos_pdf(data: &[f32], n: usize, u: f32) -> (f32, f32) {
    if n == 0 || data.len() <= n {
        return (f32::NAN, f32::NAN);
    }
    let u = clamp01(u);
    let f = |i: usize| data.get(i).copied().unwrap_or(f32::NAN);
    let (mut lo, mut hi) = (0usize, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if f(mid) <= u {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let step = f(hi) - f(lo);
    let t = (u - f(lo)) / step;
    let dx = 2.0 / n as f32;
    let mu = ((lo as f32 + t) * dx - 1.0).clamp(-1.0, 1.0);
    (mu, INV_2PI * step / dx)
}

/// A 2-D table (`k` Hermite slices of `n` intervals at `x_j = x0 + j dx`,
/// one after the other): `(cos θ, density)` at `(x, u)`. `s = (x − x0)/dx`
/// clamped to `[0, k − 1]`, `j = ⌊s⌋`, `w = s − j`; `μ = a + w (b − a)`
/// from slices `j` and `j + 1` (`a` alone where `w = 0`):
/// `Table2d::sample_cos`'s bits. The density is that of the blend,
/// `1/(2π n (a' + w (b' − a')))`. NaN `x` or `u` gives NaN.
#[inline]
pub fn table2d_sample_cos_pdf(
    data: &[f32],
    n: usize,
    k: usize,
    x0: f32,
    dx: f32,
    x: f32,
    u: f32,
) -> (f32, f32) {
    if x.is_nan() || k == 0 {
        return (f32::NAN, f32::NAN);
    }
    let top = (k - 1) as f32;
    let mut s = (x - x0) / dx;
    s = if s > top { top } else { s };
    s = if s < 0.0 { 0.0 } else { s };
    let j = if s >= 1.0 { s as usize } else { 0 };
    let w = s - j as f32;
    let per = 2 * (n + 1);
    let u = clamp01(u);
    let slice = |j: usize| {
        data.get(j * per..(j + 1) * per)
            .map_or((f32::NAN, f32::NAN), |d| hermite(d, n, u))
    };
    let (a, da) = slice(j);
    let (mu, dmu) = if w > 0.0 {
        let (b, db) = slice(j + 1);
        (a + w * (b - a), da + w * (db - da))
    } else {
        (a, da)
    };
    (mu, INV_2PI / (n as f32 * dmu))
}
