//! Seed tables for the iterative inverse CDFs (fog mixture, Draine off the
//! eq. 6 region): a few points of the inverse, tabulated when the phase
//! object is built, from which a safeguarded Halley iteration needs two
//! steps instead of a costly closed-form seed or an inner solve.
//!
//! One row per tail (as is, and mirrored for `u > 1/2`): `z_k = y_k / t_k`,
//! the tail solution `y = 1 + μ` over the tail probability `t`, at
//! `t_k = k/(2K)`, with `z_0 = 1/f(pole)` its limit (`y/t` is bounded and
//! smooth at `t → 0`, where `y` itself falls to zero like `t`). Linear
//! interpolation gives a seed within a few per cent (3 % for the 2 µm fog).
//! 26 floats: a phase object that holds one still fits in `sk_phase`
//! ([`HalfSeeds`] keeps them in half the space).

/// The largest seed: just below the pole `y = 2`.
pub(crate) const Y_MAX: f64 = 2.0 - 1.0 / (1u64 << 20) as f64;

/// Intervals of the table of each tail.
const K: usize = 12;

/// The seed table (module docs). All zeros: no table (see [`Seeds::NONE`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Seeds([[f32; K + 1]; 2]);

impl Seeds {
    /// No table: the caller falls back to its closed-form seed.
    pub(crate) const NONE: Seeds = Seeds([[0.0; K + 1]; 2]);

    /// Tabulates `tail(mirrored, t)`, the exact tail solution `y` at tail
    /// probability `t ∈ (0, ½]`, with `pole(mirrored)` the density of `μ`
    /// at the pole (`y = 0`) of that tail.
    pub(crate) fn build(pole: impl Fn(bool) -> f64, tail: impl Fn(bool, f64) -> f64) -> Seeds {
        let mut seeds = Seeds::NONE;
        for (row, mirrored) in seeds.0.iter_mut().zip([false, true]) {
            for (k, z) in row.iter_mut().enumerate().skip(1) {
                let t = 0.5 * k as f64 / K as f64;
                *z = (tail(mirrored, t) / t) as f32;
            }
            let z0 = (1.0 / pole(mirrored)) as f32;
            // A pole density of 0 or ∞ leaves no limit: take the next node.
            row[0] = if z0.is_finite() && z0 > 0.0 {
                z0
            } else {
                row[1]
            };
        }
        seeds
    }

    /// The seed `y ≈ t·z(t)` at tail probability `t ∈ [0, ½]` for the tail
    /// `mirrored`, `z` linear between the nodes.
    #[inline(always)]
    pub(crate) fn y(&self, mirrored: bool, t: f64) -> f64 {
        let row = &self.0[mirrored as usize];
        interpolate(|k| row.get(k).copied(), t)
    }

    /// The table in half the space ([`HalfSeeds`]).
    pub(crate) fn to_half(self) -> HalfSeeds {
        HalfSeeds(self.0.map(|row| row.map(half_encode)))
    }
}

/// A seed table in half the space, for objects that need the other 52
/// bytes: each node (positive) as a 16-bit float of our own, a 6-bit
/// exponent for `[2⁻³¹, 2³³)` and 10 bits of significand (relative
/// rounding ≤ 2⁻¹¹), far below the interpolation's own error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct HalfSeeds([[u16; K + 1]; 2]);

/// The f32 exponent field of the smallest [`HalfSeeds`] node, `2⁻³¹`.
const HALF_EXP_BIAS: u32 = 127 - 31;

impl HalfSeeds {
    /// As [`Seeds::y`].
    #[inline(always)]
    pub(crate) fn y(&self, mirrored: bool, t: f64) -> f64 {
        let row = &self.0[mirrored as usize];
        interpolate(|k| row.get(k).map(|&h| half_decode(h)), t)
    }
}

/// A positive f32 node to the 16-bit format of [`HalfSeeds`], rounded to
/// nearest, clamped into the format's range.
pub(crate) fn half_encode(z: f32) -> u16 {
    let (lo, hi) = (HALF_EXP_BIAS << 23, (HALF_EXP_BIAS + 64) << 23);
    let bits = z.to_bits().clamp(lo, hi - (1 << 13) - 1) - lo;
    ((bits + (1 << 12)) >> 13) as u16
}

/// The f32 value of a node stored by [`half_encode`]: a shift and an add.
#[inline(always)]
pub(crate) fn half_decode(h: u16) -> f32 {
    f32::from_bits(((h as u32) << 13) + (HALF_EXP_BIAS << 23))
}

/// `t·z(t)` with `z` linear between the nodes `node(k)` at `t_k = k/(2K)`.
#[inline(always)]
fn interpolate(node: impl Fn(usize) -> Option<f32>, t: f64) -> f64 {
    let s = (2 * K) as f64 * t;
    // Saturating conversion and the min keep k in bounds (NaN gives 0).
    let k = crate::math::real::Real::to_index(s).min(K - 1);
    let f = s - k as f64;
    match (node(k), node(k + 1)) {
        // Kept inside (0, 2), where the solver takes a seed: a lobe so
        // sharp that y ≈ 2 over the tail interpolates past 2.
        (Some(a), Some(b)) => (t * (a as f64 + f * (b as f64 - a as f64))).min(Y_MAX),
        _ => f64::NAN,
    }
}
