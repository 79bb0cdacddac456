//! 2-D tables: a phase function that changes along a second variable
//! `x` (wavelength, size parameter, or any parameter the caller chooses),
//! as `k` cubic Hermite inverse-CDF tables ("slices") at `x_j = x_0 + j Δx`.
//!
//! Lookup at `(x, u)`: `s = (x − x_0)/Δx` clamped to `[0, k − 1]`,
//! `j = ⌊s⌋`, `w = s − j`, and
//! `μ = μ_j(u) + w (μ_{j+1}(u) − μ_j(u))` where `w > 0` (else `μ_j(u)`):
//! the inverse CDFs of the two neighbouring slices blended at the same `u`
//! (displacement interpolation: a lobe that narrows or moves between
//! slices narrows or moves, where blending densities would cross-fade two
//! lobes). O(1), monotone in `u`, and exactly a slice at `x = x_j`. The
//! blend is itself a Hermite spline (the spline is linear in its nodes),
//! so [`pdf`](Table2d::pdf) and [`cdf`](Table2d::cdf) are those of the
//! distribution sampled, as for 1-D tables. To space slices evenly in
//! `ln x` (sizes), pass `ln x` as the variable.
//!
//! Layout: the `k` slices one after the other, each `2(n + 1)` values as a
//! 1-D Hermite table (`μ_i, d_i` interleaved); `include/scatterkit_table.h`
//! has the same lookup header-only.

use super::{Table, TableKind, hermite_at};
use crate::error::Error;
use crate::math::geometry::{Vec3, direction_about_turns, sin_from_cos};
use crate::math::numeric::hermite;
use crate::math::real::Real;
use crate::phase::PhaseFunction;

/// A 2-D table (`cos θ × x`) borrowing its data. `Copy`.
///
/// # Example
///
/// HG whose `g` rises with the variable, 17 slices over `x ∈ [0, 1]`:
///
/// ```
/// use scatterkit::{HenyeyGreenstein, PhaseFunction, Table2d};
///
/// let (n, k) = (256, 17);
/// let mut buf = vec![0.0f32; Table2d::<f32>::len(n, k).unwrap()];
/// let g_at = |x: f32| 0.2 + 0.7 * x;
/// let t = Table2d::inverse(&mut buf, n, k, 0.0, 1.0 / 16.0, |x| {
///     HenyeyGreenstein::new(g_at(x))
/// })
/// .unwrap();
/// let hg = HenyeyGreenstein::new(g_at(0.5)).unwrap();
/// // x = 0.5 is a slice: the 1-D table's accuracy.
/// assert!((t.sample_cos(0.5, 0.3) - hg.sample_cos(0.3)).abs() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Table2d<'a, T> {
    data: &'a [T],
    n: usize,
    n_t: T,
    k: usize,
    x0: T,
    dx: T,
}

impl<'a, T: Real> Table2d<'a, T> {
    /// Values a table of `k ≥ 1` slices at resolution `n ≥ 1` occupies:
    /// `2k(n + 1)`; `None` for `n = 0`, `k = 0` or overflow.
    pub fn len(n: usize, k: usize) -> Option<usize> {
        if k == 0 {
            return None;
        }
        TableKind::Inverse.len(n)?.checked_mul(k)
    }

    /// Fills `buf` slice by slice: `fill(j, x_j, slice)` writes slice `j`
    /// (`2(n + 1)` values) as a 1-D Hermite table, typically with
    /// [`Table::inverse`] or [`Table::measured`] (Mie at each wavelength).
    /// [`Error::Size`] for `n = 0`, `k = 0` or a short `buf`;
    /// [`Error::Domain`] unless `x_0` is finite and `Δx` finite and
    /// positive, or if a slice is not a monotone table in `[−1, 1]`
    /// ([`from_data`](Self::from_data)); `fill`'s own errors pass through.
    pub fn build(
        buf: &'a mut [T],
        n: usize,
        k: usize,
        x0: T,
        dx: T,
        mut fill: impl FnMut(usize, T, &mut [T]) -> Result<(), Error>,
    ) -> Result<Self, Error> {
        let len = Self::len(n, k).ok_or(Error::Size)?;
        let buf = buf.get_mut(..len).ok_or(Error::Size)?;
        check_axis(x0, dx)?;
        let per = len / k;
        for j in 0..k {
            // In range by the length check (`get` keeps panics out of the
            // C library).
            let slice = buf.get_mut(j * per..(j + 1) * per).ok_or(Error::Size)?;
            fill(j, x0 + T::from_index(j) * dx, slice)?;
        }
        Self::from_data(buf, n, k, x0, dx)
    }

    /// The inverse CDFs of `phase_at(x_j)` (any phase function: a model, a
    /// [`Phase`](crate::Phase), a mixture) at the `k` slices; see
    /// [`build`](Self::build).
    pub fn inverse<P: PhaseFunction<T>>(
        buf: &'a mut [T],
        n: usize,
        k: usize,
        x0: T,
        dx: T,
        mut phase_at: impl FnMut(T) -> Result<P, Error>,
    ) -> Result<Self, Error> {
        Self::build(buf, n, k, x0, dx, |_, x, slice| {
            Table::inverse(&phase_at(x)?, slice, n).map(|_| ())
        })
    }

    /// A table over data built earlier (by [`build`](Self::build), or by
    /// a C caller slice by slice), checked: [`Error::Size`] for `n = 0`,
    /// `k = 0` or short `data`; [`Error::Domain`] for a non-finite `x_0`,
    /// a `Δx` not finite and positive, or a slice whose nodes are not
    /// non-decreasing within `[−1, 1]` with finite non-negative slopes at
    /// most 3 times each neighbouring secant (what keeps the spline
    /// monotone and within its nodes; the library's own slices are so).
    pub fn from_data(data: &'a [T], n: usize, k: usize, x0: T, dx: T) -> Result<Self, Error> {
        let len = Self::len(n, k).ok_or(Error::Size)?;
        let data = data.get(..len).ok_or(Error::Size)?;
        check_axis(x0, dx)?;
        let per = len / k;
        for j in 0..k {
            check_slice(data.get(j * per..(j + 1) * per).ok_or(Error::Size)?)?;
        }
        Ok(Self::from_parts(data, n, k, x0, dx))
    }

    /// Without the per-slice check (lengths and axis checked by the
    /// caller): the C layer's load of a table built earlier.
    pub(crate) fn from_parts(data: &'a [T], n: usize, k: usize, x0: T, dx: T) -> Self {
        Table2d {
            data,
            n,
            n_t: T::from_index(n),
            k,
            x0,
            dx,
        }
    }

    /// The resolution `n` of each slice.
    pub fn n(&self) -> usize {
        self.n
    }
    /// The number of slices `k`.
    pub fn k(&self) -> usize {
        self.k
    }
    /// The variable at slice 0.
    pub fn x0(&self) -> T {
        self.x0
    }
    /// The spacing of the slices in the variable.
    pub fn dx(&self) -> T {
        self.dx
    }
    /// The tabulated values, slice after slice.
    pub fn data(&self) -> &'a [T] {
        self.data
    }

    /// Slice `j` as a 1-D table (`None` for `j ≥ k`).
    pub fn slice(&self, j: usize) -> Option<Table<'a, T>> {
        let per = 2 * (self.n + 1);
        let data = self.data.get(j * per..(j + 1) * per)?;
        Table::from_data(data, self.n, TableKind::Inverse).ok()
    }

    /// The slice `j` and weight `w ∈ [0, 1)` of `x` (module docs), `None`
    /// for NaN. In the same operations as the header-only lookup.
    #[inline(always)]
    fn at(&self, x: T) -> Option<(usize, T)> {
        if x.is_nan() {
            return None;
        }
        let top = T::from_index(self.k - 1);
        let mut s = (x - self.x0) / self.dx;
        s = if s > top { top } else { s };
        s = if s < T::ZERO { T::ZERO } else { s };
        let j = s.to_index();
        Some((j, s - T::from_index(j)))
    }

    /// `cos θ` at the variable `x` (clamped to the slices' range; NaN
    /// gives NaN) for `u ∈ [0, 1]` (clamped; NaN gives NaN), monotone in
    /// `u` up to rounding (as [`Table::sample_cos`]), O(1): the blend of
    /// the module docs, bit for bit as
    /// `sk_table2d_lookup` of `include/scatterkit_table.h`.
    #[inline]
    pub fn sample_cos(&self, x: T, u: T) -> T {
        let Some((j, w)) = self.at(x) else {
            return T::NAN;
        };
        let u = u.clamp01();
        let per = 2 * (self.n + 1);
        let look = |j: usize| {
            self.data
                .get(j * per..(j + 1) * per)
                .map_or(T::NAN, |s| hermite(s, self.n, self.n_t, u))
        };
        let a = look(j);
        if w > T::ZERO {
            a + w * (look(j + 1) - a)
        } else {
            a
        }
    }

    /// The blended nodes at `x`, as `(μ_i, d_i)` of node `i` in f64: `μ_i`
    /// blended in `T`, as [`sample_cos`](Self::sample_cos) blends its
    /// values (so that the sample at `u = 1`, the blend of the two last
    /// nodes, is the blended last node: blended in f64, an f32 table's
    /// ends fell up to half an ulp inside its samples, where the density
    /// is 0), `d_i` in f64.
    fn nodes(&self, x: T) -> Option<impl Fn(usize) -> (f64, f64) + '_> {
        let (j, w) = self.at(x)?;
        let per = 2 * (self.n + 1);
        let v = |i: usize| self.data.get(i).copied().unwrap_or(T::NAN);
        Some(move |i: usize| {
            let (a, b) = (j * per + 2 * i, (j + 1) * per + 2 * i);
            if w > T::ZERO {
                let blend = |a: T, b: T| a.to_f64() + w.to_f64() * (b.to_f64() - a.to_f64());
                (
                    (v(a) + w * (v(b) - v(a))).to_f64(),
                    blend(v(a + 1), v(b + 1)),
                )
            } else {
                (v(a).to_f64(), v(a + 1).to_f64())
            }
        })
    }

    /// The density per steradian that [`sample_cos`](Self::sample_cos)
    /// draws from at `x`, at `cos_theta`: `1/(2π n μ'(t))` of the blended
    /// spline, `t` solved in f64 (as [`Table::pdf`]); 0 outside the range
    /// it covers, +∞ where it is flat, NaN for NaN.
    pub fn pdf(&self, x: T, cos_theta: T) -> T {
        let Some(node) = self.nodes(x) else {
            return T::NAN;
        };
        if cos_theta.is_nan() {
            return T::NAN;
        }
        let p = match hermite_at(node, self.n, cos_theta.to_f64()) {
            None => 0.0,
            Some((_, _, s)) if s > 0.0 => 1.0 / (core::f64::consts::TAU * self.n as f64 * s),
            Some(_) => f64::INFINITY,
        };
        T::from_f64(p)
    }

    /// `P(cos θ ≤ cos_theta)` of the distribution sampled at `x`, in
    /// `[0, 1]`; NaN for NaN.
    pub fn cdf(&self, x: T, cos_theta: T) -> T {
        let Some(node) = self.nodes(x) else {
            return T::NAN;
        };
        if cos_theta.is_nan() {
            return T::NAN;
        }
        let mu = cos_theta.to_f64().clamp(-1.0, 1.0);
        let first = node(0).0;
        let c = match hermite_at(&node, self.n, mu) {
            Some((i, t, _)) => (i as f64 + t) / self.n as f64,
            None if mu < first => 0.0,
            None => 1.0,
        };
        T::from_f64(c.clamp(0.0, 1.0))
    }

    /// The mean cosine of the distribution sampled at `x`: the blend of
    /// the two slices' exact means (the mean is linear in the nodes).
    pub fn mean_cosine(&self, x: T) -> T {
        let Some((j, w)) = self.at(x) else {
            return T::NAN;
        };
        let m = |j: usize| self.slice(j).map_or(f64::NAN, |s| s.mean_cosine().to_f64());
        let w = w.to_f64();
        let a = m(j);
        T::from_f64(if w > 0.0 { a + w * (m(j + 1) - a) } else { a })
    }

    /// A direction about `w_in` (unit) at `x`: `cos θ` from
    /// [`sample_cos`](Self::sample_cos)`(x, u1)`, the azimuth `2π u2`, and
    /// its density per steradian ([`pdf`](Self::pdf)).
    pub fn sample_dir(&self, x: T, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        let mu = self.sample_cos(x, u1);
        let dir = direction_about_turns(w_in, mu, sin_from_cos(mu), u2.clamp01());
        (dir, self.pdf(x, mu))
    }
}

/// `x_0` finite, `Δx` finite and positive.
fn check_axis<T: Real>(x0: T, dx: T) -> Result<(), Error> {
    if x0.is_finite() && dx.is_finite() && dx > T::ZERO {
        Ok(())
    } else {
        Err(Error::Domain)
    }
}

/// A Hermite slice: nodes non-decreasing within `[−1, 1]`, slopes finite,
/// non-negative and at most 3 times the secant of each neighbouring
/// interval (the Fritsch–Carlson box the library's own tables are limited
/// to): the spline is then monotone and stays within its nodes, so its
/// mean, density and CDF describe what `sample_cos` draws. Steeper slopes
/// overshoot `[−1, 1]`, where `sample_cos` clamps and the mean does not
/// (a fuzzed slice gave a mean cosine of 16).
fn check_slice<T: Real>(slice: &[T]) -> Result<(), Error> {
    let node = |i: usize| slice.get(2 * i).copied();
    let three = T::from_f64(3.0);
    let mut last = -T::ONE;
    for i in 0..slice.len() / 2 {
        let ok = match slice.get(2 * i..2 * i + 2) {
            Some(&[y, d]) => {
                // The same expression as the builder's limiter, so its
                // tables pass bit for bit.
                let left = i == 0 || node(i - 1).is_some_and(|y0| d <= three * (y - y0));
                let right = node(i + 1).is_none_or(|y1| d <= three * (y1 - y));
                let ok = y >= last && y <= T::ONE && d.is_finite() && d >= T::ZERO;
                last = y;
                ok && left && right
            }
            _ => false,
        };
        if !ok {
            return Err(Error::Domain);
        }
    }
    Ok(())
}
