//! Tabulated samplers over caller-owned memory (no allocation).
//!
//! * [`TableKind::RayleighCdf`] is Frisvad's (2011, §3C) table: the exact
//!   Rayleigh CDF at `n + 1` equally spaced cosines, inverted by binary search
//!   and linear interpolation. Its error in `cos θ` falls as `1/n²`; it is here
//!   to reproduce the paper, not because it is the best table.
//! * [`TableKind::Inverse`] tabulates the inverse CDF itself at `n + 1`
//!   equally spaced `u`, with its slope `dμ/du = 1/(2π p(μ))`, and evaluates a
//!   cubic Hermite spline: O(1) lookup (no search), error falling as `1/n⁴`.
//!   Slopes are limited (Fritsch–Carlson) so the map stays monotone in `u`.
//! * [`TableKind::Measured`] is the same spline built from a measured or
//!   otherwise tabulated phase function given at `m` cosines: the density is
//!   taken as linear in `cos θ` between the given points (zero outside their
//!   range) and normalised, and its inverse CDF is tabulated exactly.
//!
//! Layout of the Hermite kinds: `2(n + 1)` values `μ_i, d_i` interleaved,
//! `d_i = (dμ/du)(u_i) / n` (the slope per interval).

pub(crate) mod measured;
mod two_d;

pub use two_d::Table2d;

use crate::error::{Error, try_from_u32};
use crate::math::geometry::{Vec3, direction_about_turns, sin_from_cos};
use crate::math::numeric::hermite;
use crate::math::real::Real;
use crate::phase::{PhaseFunction, Rayleigh};
use crate::table::measured::Measured;

/// What a table holds (the C enum `sk_table_kind`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TableKind {
    /// Frisvad's tabulated Rayleigh CDF: `n + 1` values `F(x_i)`,
    /// `x_i = −1 + 2i/n`.
    RayleighCdf = 0,
    /// The inverse CDF of a phase function, cubic Hermite in `u`.
    Inverse = 1,
    /// The inverse CDF of a measured phase function, cubic Hermite in `u`.
    Measured = 2,
}

try_from_u32!(TableKind: RayleighCdf, Inverse, Measured);

impl TableKind {
    /// Number of floats a table of resolution `n` occupies, or `None` if
    /// `n = 0` or the count overflows `usize`.
    pub fn len(self, n: usize) -> Option<usize> {
        if n == 0 {
            return None;
        }
        match self {
            TableKind::RayleighCdf => n.checked_add(1),
            TableKind::Inverse | TableKind::Measured => n.checked_add(1)?.checked_mul(2),
        }
    }
}

/// A table sampler borrowing its data. `Copy`: share it freely.
///
/// # Example
///
/// The inverse CDF of the fog phase function of 2 µm droplets, tabulated
/// once into caller memory, then looked up in O(1) (no search):
///
/// ```
/// use scatterkit::{Fog, PhaseFunction, Table, TableKind};
///
/// let fog = Fog::<f32>::from_diameter(2.0).unwrap();
/// let n = 256;
/// let mut buf = vec![0.0f32; TableKind::Inverse.len(n).unwrap()];
/// let table = Table::inverse(&fog, &mut buf, n).unwrap();
/// for u in [0.1f32, 0.5, 0.9] {
///     assert!((table.sample_cos(u) - fog.sample_cos(u)).abs() < 1e-3);
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Table<'a, T> {
    data: &'a [T],
    n: usize,
    /// `n` as a float (the lookup's scale).
    n_t: T,
    kind: TableKind,
}

impl<'a, T: Real> Table<'a, T> {
    /// Fills `buf` with Frisvad's Rayleigh CDF table of `n ≥ 1` intervals
    /// (`n + 1` values, each `F(x_i)` written from the closed form rather than
    /// accumulated) and returns a sampler over it. Fails with [`Error::Size`]
    /// if `n = 0` or `buf` is shorter than [`TableKind::len`].
    pub fn rayleigh_cdf(buf: &'a mut [T], n: usize) -> Result<Self, Error> {
        let len = TableKind::RayleighCdf.len(n).ok_or(Error::Size)?;
        let buf = buf.get_mut(..len).ok_or(Error::Size)?;
        let dx = T::TWO / T::from_f64(n as f64);
        for (i, f) in buf.iter_mut().enumerate() {
            let x = T::from_f64(i as f64) * dx - T::ONE;
            *f = PhaseFunction::<T>::cdf(&Rayleigh, x);
        }
        // The ends exactly, whatever the rounding of x_n.
        if let Some(first) = buf.first_mut() {
            *first = T::ZERO;
        }
        if let Some(last) = buf.last_mut() {
            *last = T::ONE;
        }
        Ok(Table {
            data: buf,
            n_t: T::from_index(n),
            n,
            kind: TableKind::RayleighCdf,
        })
    }

    /// Tabulates the inverse CDF of `phase` at `n ≥ 1` intervals in `buf`
    /// (at least `2(n + 1)` values) for O(1) cubic Hermite lookup. Fails with
    /// [`Error::Size`] if `n = 0` or `buf` is too short.
    pub fn inverse<P: PhaseFunction<T>>(
        phase: &P,
        buf: &'a mut [T],
        n: usize,
    ) -> Result<Self, Error> {
        let len = TableKind::Inverse.len(n).ok_or(Error::Size)?;
        let buf = buf.get_mut(..len).ok_or(Error::Size)?;
        let h = T::ONE / T::from_f64(n as f64);
        for (i, pair) in buf.chunks_exact_mut(2).enumerate() {
            let u = if i == n {
                T::ONE
            } else {
                T::from_f64(i as f64) * h
            };
            let mu = phase.sample_cos(u);
            if let [y, d] = pair {
                *y = mu;
                *d = h / (T::TAU * phase.pdf(mu));
            }
        }
        limit_slopes(buf, n);
        Ok(Table {
            data: buf,
            n_t: T::from_index(n),
            n,
            kind: TableKind::Inverse,
        })
    }

    /// Builds a sampler from a phase function measured at `m ≥ 2` cosines:
    /// `cos_theta` strictly increasing or strictly decreasing within
    /// `[−1, 1]`, `pdf` finite and non-negative with a positive integral (any
    /// scale: it is normalised). The density is linear in `cos θ` between the
    /// points and zero outside their range. `buf` holds at least `2(n + 1)`
    /// values. [`Error::Size`] for `n = 0`, `m < 2`, slices of different
    /// lengths or a short `buf`; [`Error::Domain`] for invalid data.
    pub fn measured(cos_theta: &[T], pdf: &[T], buf: &'a mut [T], n: usize) -> Result<Self, Error> {
        let len = TableKind::Measured.len(n).ok_or(Error::Size)?;
        let buf = buf.get_mut(..len).ok_or(Error::Size)?;
        let data = Measured::new(cos_theta, pdf)?;
        fill_inverse(&data, buf, n);
        limit_slopes(buf, n);
        Ok(Table {
            data: buf,
            n_t: T::from_index(n),
            n,
            kind: TableKind::Measured,
        })
    }

    /// A sampler over data built earlier (for instance by the C caller).
    /// Fails with [`Error::Size`] if `n = 0` or `data` is too short.
    pub fn from_data(data: &'a [T], n: usize, kind: TableKind) -> Result<Self, Error> {
        let len = kind.len(n).ok_or(Error::Size)?;
        let data = data.get(..len).ok_or(Error::Size)?;
        Ok(Table {
            data,
            n,
            n_t: T::from_index(n),
            kind,
        })
    }

    /// The table's resolution `n`.
    pub fn n(&self) -> usize {
        self.n
    }
    /// What the table holds.
    pub fn kind(&self) -> TableKind {
        self.kind
    }
    /// The tabulated values.
    pub fn data(&self) -> &'a [T] {
        self.data
    }

    /// `cos θ` for `u ∈ [0, 1]` (clamped; NaN gives NaN), monotone in `u`
    /// up to the rounding of the interpolation (a Hermite table's cubic can
    /// step back by a few ulp within an interval; never across a node).
    #[inline(always)]
    pub fn sample_cos(&self, u: T) -> T {
        match self.kind {
            TableKind::RayleighCdf => self.sample_cdf_table(u.clamp01()),
            TableKind::Inverse | TableKind::Measured => self.sample_hermite(u.clamp01()),
        }
    }

    /// The density per steradian that [`sample_cos`](Self::sample_cos)
    /// draws from, at `cos_theta` (NaN for NaN; 0 outside the range the
    /// table covers). Not the density the table was built from: the
    /// table's own, so that a sample and its pdf agree exactly (MIS).
    ///
    /// * Frisvad's CDF table: piecewise constant,
    ///   `(F_{i+1} − F_i) / (2π · 2/n)` on interval `i` of `μ`.
    /// * Hermite tables: `1 / (2π n μ'(t))` with `μ(t)` the interval's cubic
    ///   (module docs) and `t` solved from `μ(t) = cos θ` in f64 (bisection
    ///   safeguarding Newton); +∞ where the spline is flat (a slope limited
    ///   to 0 at a node: the sampler puts no spread there).
    pub fn pdf(&self, cos_theta: T) -> T {
        if cos_theta.is_nan() {
            return T::NAN;
        }
        let mu = cos_theta.to_f64();
        let p = match self.kind {
            TableKind::RayleighCdf => self.pdf_cdf_table(mu),
            TableKind::Inverse | TableKind::Measured => self.pdf_hermite(mu),
        };
        T::from_f64(p)
    }

    /// A direction about `w_in` (unit): `cos θ` from
    /// [`sample_cos`](Self::sample_cos)`(u1)`, the azimuth `2π u2`, and its
    /// density per steradian ([`pdf`](Self::pdf)).
    pub fn sample_dir(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        let mu = self.sample_cos(u1);
        let dir = direction_about_turns(w_in, mu, sin_from_cos(mu), u2.clamp01());
        (dir, self.pdf(mu))
    }

    /// Frisvad's table: the CDF is linear on each of the `n` intervals of
    /// `μ`, so the density is the interval's CDF step over its width.
    fn pdf_cdf_table(&self, mu: f64) -> f64 {
        if !(-1.0..=1.0).contains(&mu) {
            return 0.0;
        }
        let f = |i: usize| self.data.get(i).map_or(f64::NAN, |v| v.to_f64());
        let dx = 2.0 / self.n as f64;
        let i = Real::to_index((mu + 1.0) / dx).min(self.n - 1);
        (f(i + 1) - f(i)) / dx / core::f64::consts::TAU
    }

    /// The Hermite tables: the slope at `μ` inverted.
    fn pdf_hermite(&self, mu: f64) -> f64 {
        match self.hermite_at(mu) {
            None => 0.0,
            Some((_, _, s)) if s > 0.0 => 1.0 / (core::f64::consts::TAU * self.n as f64 * s),
            Some(_) => f64::INFINITY,
        }
    }

    /// For a Hermite table: [`hermite_at`] over its nodes.
    fn hermite_at(&self, mu: f64) -> Option<(usize, f64, f64)> {
        let v = |i: usize| self.data.get(i).map_or(f64::NAN, |v| v.to_f64());
        hermite_at(|i| (v(2 * i), v(2 * i + 1)), self.n, mu)
    }

    /// `P(cos θ ≤ cos_theta)` of the distribution
    /// [`sample_cos`](Self::sample_cos) draws from (the table's own, as
    /// [`pdf`](Self::pdf)): in `[0, 1]`, NaN for NaN.
    pub fn cdf(&self, cos_theta: T) -> T {
        T::from_f64(self.cdf_f64(cos_theta.to_f64()))
    }

    /// [`cdf`](Self::cdf) in f64, before rounding to `T` (NaN for NaN).
    pub(crate) fn cdf_f64(&self, mu: f64) -> f64 {
        if mu.is_nan() {
            return f64::NAN;
        }
        let mu = mu.clamp(-1.0, 1.0);
        let c = match self.kind {
            TableKind::RayleighCdf => {
                let f = |i: usize| self.data.get(i).map_or(f64::NAN, |v| v.to_f64());
                let x = (mu + 1.0) * 0.5 * self.n as f64;
                let i = Real::to_index(x).min(self.n - 1);
                f(i) + (f(i + 1) - f(i)) * (x - i as f64)
            }
            TableKind::Inverse | TableKind::Measured => {
                let first = self.data.first().map_or(f64::NAN, |v| v.to_f64());
                match self.hermite_at(mu) {
                    Some((i, t, _)) => (i as f64 + t) / self.n as f64,
                    None if mu < first => 0.0,
                    None => 1.0,
                }
            }
        };
        c.clamp(0.0, 1.0)
    }

    /// [`pdf`](Self::pdf) in f64, before rounding to `T`.
    pub(crate) fn pdf_f64(&self, mu: f64) -> f64 {
        match self.kind {
            TableKind::RayleighCdf => self.pdf_cdf_table(mu),
            TableKind::Inverse | TableKind::Measured => self.pdf_hermite(mu),
        }
    }

    /// The mean cosine of the distribution the table samples, exactly:
    /// for Frisvad's CDF table `Σ ΔF_i (x_i + x_{i+1})/2`; for the Hermite
    /// tables `∫₀¹ μ(u) du`, per interval `(μ_i + μ_{i+1})/2 + (d_i −
    /// d_{i+1})/12` (the integral of the cubic Hermite piece, `d` the
    /// node slopes per interval).
    pub fn mean_cosine(&self) -> T {
        let v = |i: usize| self.data.get(i).map_or(f64::NAN, |v| v.to_f64());
        let n = self.n;
        let mut sum = 0.0;
        match self.kind {
            TableKind::RayleighCdf => {
                let dx = 2.0 / n as f64;
                for i in 0..n {
                    let x0 = -1.0 + dx * i as f64;
                    sum += (v(i + 1) - v(i)) * (x0 + 0.5 * dx);
                }
            }
            TableKind::Inverse | TableKind::Measured => {
                for i in 0..n {
                    let (y0, d0, y1, d1) = (v(2 * i), v(2 * i + 1), v(2 * i + 2), v(2 * i + 3));
                    sum += 0.5 * (y0 + y1) + (d0 - d1) / 12.0;
                }
                sum /= n as f64;
            }
        }
        T::from_f64(sum)
    }

    /// Cubic Hermite interpolation of the tabulated inverse: interval
    /// `i = ⌊u n⌋` found by arithmetic, no search.
    #[inline(always)]
    fn sample_hermite(&self, u: T) -> T {
        hermite(self.data, self.n, self.n_t, u)
    }

    /// Binary search for `F[i] ≤ u < F[i+1]`, then linear interpolation
    /// (Frisvad 2011, §3C, in the crate's orientation). Kept out of line
    /// so the O(1) Hermite lookup beside it inlines into the caller's loop.
    #[inline(never)]
    fn sample_cdf_table(&self, u: T) -> T {
        // Indices stay below n + 1 = data.len(); `get` makes that a fact the
        // compiler can see (no bounds-check panic in the C library).
        let f = |i: usize| self.data.get(i).copied().unwrap_or(T::NAN);
        let lo = last_at_or_below(f, self.n, u);
        let hi = lo + 1;
        let t = (u - f(lo)) / (f(hi) - f(lo));
        let dx = T::TWO / T::from_f64(self.n as f64);
        ((T::from_f64(lo as f64) + t) * dx - T::ONE).clamp_unit()
    }
}

/// The largest `i < n` with `f(i) ≤ x`, by bisection over non-decreasing
/// values `f(0) … f(n)` (0 when none is).
#[inline(always)]
fn last_at_or_below<V: PartialOrd>(f: impl Fn(usize) -> V, n: usize, x: V) -> usize {
    let (mut lo, mut hi) = (0usize, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if f(mid) <= x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// For a cubic Hermite inverse CDF with `n` intervals and nodes
/// `node(i) = (μ_i, d_i)` (non-decreasing `μ_i`): the interval `i` whose
/// node values bracket `μ`, the `t ∈ [0, 1]` where its cubic reaches `μ`
/// and the cubic's slope there; `None` outside the range the nodes cover.
pub(crate) fn hermite_at(
    node: impl Fn(usize) -> (f64, f64),
    n: usize,
    mu: f64,
) -> Option<(usize, f64, f64)> {
    let y = |i: usize| node(i).0;
    if !(mu >= y(0) && mu <= y(n)) {
        return None;
    }
    // The last node at or below μ (nodes are non-decreasing).
    let lo = last_at_or_below(y, n, mu);
    let ((y0, d0), (y1, d1)) = (node(lo), node(lo + 1));
    let dy = y1 - y0;
    let c2 = 3.0 * dy - 2.0 * d0 - d1;
    let c3 = d0 + d1 - 2.0 * dy;
    let cubic = |t: f64| y0 + t * (d0 + t * (c2 + t * c3));
    let slope = |t: f64| d0 + t * (2.0 * c2 + 3.0 * c3 * t);
    let t = solve_unit(|t| cubic(t) - mu, slope);
    Some((lo, t, slope(t)))
}

/// Fritsch–Carlson: each node's slope is clamped to `[0, 3Δ]` for the secants
/// `Δ` of both neighbouring intervals, which keeps the cubic Hermite spline
/// monotone (and turns the infinite slopes of zero densities into finite ones).
fn limit_slopes<T: Real>(buf: &mut [T], n: usize) {
    let three = T::from_f64(3.0);
    for i in 0..=n {
        let y = |k: usize| buf.get(k).copied().unwrap_or(T::NAN);
        let mut d = y(2 * i + 1);
        if d.is_nan() || d < T::ZERO {
            d = T::ZERO;
        }
        if i > 0 {
            d = upto(d, three * (y(2 * i) - y(2 * i - 2)));
        }
        if i < n {
            d = upto(d, three * (y(2 * i + 2) - y(2 * i)));
        }
        if let Some(slot) = buf.get_mut(2 * i + 1) {
            *slot = d;
        }
    }
}

/// The root in `[0, 1]` of a non-decreasing `f` with `f(0) ≤ 0 ≤ f(1)`:
/// Newton steps kept inside a shrinking bracket, bisection where a step
/// would leave it; 60 steps at most (bisection alone reaches 10⁻¹⁸).
fn solve_unit(f: impl Fn(f64) -> f64, slope: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi, mut t) = (0.0f64, 1.0f64, 0.5f64);
    for _ in 0..60 {
        let r = f(t);
        if r == 0.0 {
            break;
        }
        if r < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let s = slope(t);
        let newton = t - r / s;
        t = if s > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo <= 1e-16 {
            break;
        }
    }
    t
}

/// `d` capped at `limit` (an infinite `d` becomes `limit`).
#[inline]
fn upto<T: Real>(d: T, limit: T) -> T {
    if d > limit { limit } else { d }
}

/// Writes `μ_i = F⁻¹(i/n)` and the limited-later slopes.
fn fill_inverse<T: Real>(data: &Measured<'_, T>, buf: &mut [T], n: usize) {
    data.sweep(
        n + 1,
        |i| i as f64 / n as f64,
        |i, mu, q| {
            if let Some([y, d]) = buf.get_mut(2 * i..2 * i + 2) {
                *y = T::from_f64(mu);
                *d = T::from_f64(1.0 / (q * n as f64));
            }
        },
    );
}
