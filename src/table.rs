//! Tabulated samplers over caller-owned memory (no allocation).
//!
//! [`TableKind::RayleighCdf`] is Frisvad's (2011, §3C) table: the exact
//! Rayleigh CDF at `n + 1` equally spaced cosines, inverted by binary search
//! and linear interpolation. Its error in `cos θ` falls as `1/n²`; it is here
//! to reproduce the paper, not because it is the best table.

use crate::error::Error;
use crate::phase::{PhaseFunction, Rayleigh};
use crate::real::Real;

/// What a table holds (the C enum `sk_table_kind`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TableKind {
    /// Frisvad's tabulated Rayleigh CDF: `n + 1` values `F(x_i)`,
    /// `x_i = −1 + 2i/n`.
    RayleighCdf = 0,
}

impl TryFrom<u32> for TableKind {
    type Error = Error;
    fn try_from(v: u32) -> Result<Self, Error> {
        match v {
            0 => Ok(TableKind::RayleighCdf),
            _ => Err(Error::Method),
        }
    }
}

impl TableKind {
    /// Number of floats a table of resolution `n` occupies, or `None` if
    /// `n = 0` or the count overflows `usize`.
    pub fn len(self, n: usize) -> Option<usize> {
        match self {
            TableKind::RayleighCdf if n >= 1 => n.checked_add(1),
            TableKind::RayleighCdf => None,
        }
    }
}

/// A table sampler borrowing its data. `Copy`: share it freely.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Table<'a, T> {
    data: &'a [T],
    n: usize,
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
        buf[0] = T::ZERO;
        buf[n] = T::ONE;
        Ok(Table {
            data: buf,
            n,
            kind: TableKind::RayleighCdf,
        })
    }

    /// A sampler over data built earlier (for instance by the C caller).
    /// Fails with [`Error::Size`] if `n = 0` or `data` is too short.
    pub fn from_data(data: &'a [T], n: usize, kind: TableKind) -> Result<Self, Error> {
        let len = kind.len(n).ok_or(Error::Size)?;
        let data = data.get(..len).ok_or(Error::Size)?;
        Ok(Table { data, n, kind })
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

    /// `cos θ` for `u ∈ [0, 1]` (clamped; NaN gives NaN), monotone in `u`.
    #[inline]
    pub fn sample_cos(&self, u: T) -> T {
        match self.kind {
            TableKind::RayleighCdf => self.sample_cdf_table(u.clamp01()),
        }
    }

    /// Binary search for `F[i] ≤ u < F[i+1]`, then linear interpolation
    /// (Frisvad 2011, §3C, in the orientation of SPEC §0).
    #[inline]
    fn sample_cdf_table(&self, u: T) -> T {
        let f = self.data;
        let (mut lo, mut hi) = (0usize, self.n);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if f[mid] <= u {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let t = (u - f[lo]) / (f[hi] - f[lo]);
        let dx = T::TWO / T::from_f64(self.n as f64);
        ((T::from_f64(lo as f64) + t) * dx - T::ONE).clamp_unit()
    }
}
