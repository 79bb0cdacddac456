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

#[cfg(test)]
mod tests {
    use super::*;

    /// A tail whose `z = y/t` is linear in `t` (`y = t(a + bt)`), with its
    /// pole density `1/a`: the table's interpolation is then exact up to the
    /// rounding of its f32 nodes. Each row its own `(a, b)`.
    const ROWS: [(f64, f64); 2] = [(0.75, 1.5), (3.0, -2.0)];

    fn linear_z() -> Seeds {
        let ab = |m: bool| ROWS[m as usize];
        Seeds::build(|m| 1.0 / ab(m).0, |m, t| t * (ab(m).0 + ab(m).1 * t))
    }

    /// Every `t` of a fine grid over `[0, ½]` (nodes, between them and the
    /// ends), in both rows, and the half table within its 2⁻¹¹ besides.
    #[test]
    fn a_linear_z_is_interpolated_exactly_in_both_rows() {
        let (full, half) = (linear_z(), linear_z().to_half());
        for (m, (a, b)) in [false, true].into_iter().zip(ROWS) {
            for i in 0..=240 {
                let t = 0.5 * i as f64 / 240.0;
                let want = t * (a + b * t);
                let got = full.y(m, t);
                assert!(
                    (got - want).abs() <= 1e-7 * want,
                    "{m} {t}: {got} for {want}"
                );
                let got = half.y(m, t);
                assert!(
                    (got - want).abs() <= 1e-3 * want,
                    "half {m} {t}: {got} for {want}"
                );
            }
        }
    }

    /// A pole density of 0 or ∞ leaves no limit `1/f`: the first node is
    /// the next one's value; interpolation past `y = 2` is kept at
    /// [`Y_MAX`], just below it.
    #[test]
    fn the_pole_node_and_the_cap() {
        for pole in [0.0, f64::INFINITY] {
            let s = Seeds::build(|_| pole, |_, t| 0.5 * t);
            assert_eq!(s.0[0][0], s.0[0][1]);
            assert_eq!(s.0[1][0], 0.5);
        }
        let steep = Seeds::build(|_| 0.25, |_, t| 4.5 * t);
        let y = steep.y(false, 0.5);
        assert_eq!(y, Y_MAX);
        assert!(y < 2.0 && y > 2.0 - 1e-5, "{y}");
    }

    /// The 16-bit nodes: rounded to nearest (relative error ≤ 2⁻¹¹) over
    /// `[2⁻³¹, 2³³)`, a tie rounding up, and clamped into that range.
    #[test]
    fn half_nodes_round_to_nearest_and_clamp() {
        let mut z = 2f32.powi(-31);
        while z < 2f32.powi(33) * 0.999 {
            let back = half_decode(half_encode(z));
            assert!(((back - z) / z).abs() <= 2f32.powi(-11), "{z:e}: {back:e}");
            z *= 1.013;
        }
        let tie = f32::from_bits(1.5f32.to_bits() + (1 << 12));
        assert_eq!(
            half_decode(half_encode(tie)),
            f32::from_bits(1.5f32.to_bits() + (1 << 13))
        );
        assert_eq!(half_decode(half_encode(1.5)), 1.5);
        assert_eq!(half_decode(half_encode(1e-30)), 2f32.powi(-31));
        assert_eq!(half_encode(f32::MAX), half_encode(2f32.powi(33) * 0.9999));
        assert_eq!(
            half_decode(half_encode(f32::MAX)),
            2f32.powi(33) * (1.0 - 2f32.powi(-11))
        );
    }
}
