//! The fog mixture's inverse CDF for f32 objects from one evaluation of the
//! mixture.
//!
//! `y = 1 + μ` (or `1 − μ`, mirrored) solves `F(y) = t`. A seed `y₀` within
//! a few tenths of a per cent comes from a table built with the object; one
//! evaluation of the mixture at `y₀` gives `F` and its first four
//! derivatives (one square root per lobe, two divisions), and the inverse
//! series of `F` about `y₀` to fourth order,
//!
//! `y = y₀ + a + b₂a² + b₃a³ + b₄a⁴`, `a = (t − F)/F'`,
//! `b₂ = −A₂`, `b₃ = 2A₂² − A₃`, `b₄ = −5A₂³ + 5A₂A₃ − A₄`,
//! `A_k = F⁽ᵏ⁾/(k! F')`
//!
//! (Lagrange inversion of the Taylor series of `F`), leaves an error of
//! order `a⁵`. The iterative solver (`numeric::solve_bracketed`) needs two
//! evaluations from such a seed, and its Halley steps three divisions each.
//!
//! **The seed table.** The mixture's density has a trough near `μ = 0`
//! (Draine's `1 + αμ²`) between a backward rise and the forward HG peak, and
//! one table row across it interpolates poorly. So the rows meet at the
//! trough: `u_s = F(μ = 0)` and `u_f` split `[0, 1]` into three segments:
//!
//! | segment | `u` | frame | anchor `(t_a, y_a)` |
//! |---|---|---|---|
//! | 0, backward pole | `[0, u_s)` | `t = u`, `y = 1 + μ` | `(0, 0)` |
//! | 1, trough side | `[u_s, u_f)` | `t = 1 − u`, `y = 1 − μ` | `(1 − u_s, y(1 − u_s))` |
//! | 2, forward pole | `[u_f, 1]` | `t = 1 − u`, `y = 1 − μ` | `(0, 0)` |
//!
//! Each segment holds `z = (y − y_a)/(t − t_a)` (the inverse of the mean
//! density between the anchor and `y`: smooth, and bounded by the density's
//! extremes) at points evenly spaced in `t` (13, 11 and 15 of them), with
//! its limit `1/F'(y_a)` at the anchor, and the seed is
//! `y₀ = y_a + (t − t_a) z(t)`, `z` quadratic through three nodes. Or the
//! segments hold the mean density `1/z` itself, and `y₀ = y_a + (t − t_a)/z`
//! costs a division: for a sharp HG lobe (`g → 1`) `z` near its pole grows
//! like `1/(1 − |g| + 2|g|(1 − τ))²` in the lobe's own probability `τ`, a
//! near pole just past `τ = 1`, while the mean density is a quadratic over
//! a linear function of `τ` with its pole at `τ ≈ 2`. The pole segments keep
//! the relative precision of `y` near the poles. `u_f` is the best of three
//! candidates (`FORWARD_SPLITS`), and `1/z` is tried only where `z` leaves
//! part of `[0, 1]` to the solver. For the 2 µm fog (`z`) the seed is within
//! 3.1·10⁻³ of `y` and the series within 7.3·10⁻¹³ (relative, 10⁵ values of
//! `u`; `fog::tests`).
//!
//! **When the series is taken.** Every segment is checked when the table is
//! built: the series from the seed at the middle of each of its intervals
//! must agree with the iterative solver to 2⁻³⁶ relative. In a segment that
//! passes, the series answers whenever its last term `b₄a⁴` is at most 2⁻³³
//! of `y` (the next term, of order `a⁵`, is then far below f32 resolution);
//! otherwise, and in segments that fail, the safeguarded Halley solver
//! takes over from the series' result or the seed. Where the segments that
//! pass cover less than half of `[0, 1]` (the fits from 10.35 µm up, whose
//! HG lobe is too narrow for these rows) the object keeps the iterative
//! solver's own table (`phase::seeds`) instead. f64 objects always do: their
//! results need the solver to the last digits.

use crate::math::numeric::Eval;
use crate::math::real::Real;
use crate::phase::seeds::{Y_MAX, half_decode, half_encode};
use core::cell::Cell;

/// Intervals per segment (backward pole, trough side, forward pole): the
/// forward pole's segment covers most of `[0, 1]` and the sharpest change of
/// the density, where the HG lobe gives way to Draine. (The table, 39 nodes
/// of 16 bits and 25 bytes more, keeps an f32 fog within `sk_phase`.)
const K: [usize; 3] = [12, 10, 14];

/// Where each segment's nodes start in [`FogSeeds`]' one array.
const OFFSET: [usize; 3] = [0, K[0] + 1, K[0] + K[1] + 2];

/// Nodes in all.
const NODES: usize = K[0] + K[1] + K[2] + 3;

/// The least share of `[0, 1]` that segments taking the series must cover
/// for the table to be used (module docs).
const MIN_COVERAGE: f64 = 0.5;

/// Covers within this of each other are equal (they are sums of f32
/// widths).
const COVERAGE_TIE: f64 = 1e-6;

/// The candidates for the end `u_f` of the trough-side segment, from `u_s`:
/// 15 % and 30 % of `[u_s, 1]` (best where the HG lobe is broad, as at
/// 1–2 µm), and `u = ½` (where the HG lobe is narrow and the forward pole's
/// segment had better stay inside its mass).
pub(crate) const FORWARD_SPLITS: [Split; 3] = [
    |u_s| u_s + 0.15 * (1.0 - u_s),
    |u_s| u_s + 0.3 * (1.0 - u_s),
    |_| 0.5,
];

/// A candidate end `u_f` of the trough-side segment, from `u_s`.
pub(crate) type Split = fn(f32) -> f32;

/// The candidates a table build chooses among: trough-side splits
/// ([`FORWARD_SPLITS`]) and kinds of table (`false` the inverse CDF,
/// `true` the inverse mean density), each tried in order.
pub(crate) type Candidates<'a> = (&'a [Split], &'a [bool]);

/// The largest last term `b₄a⁴` of the series, relative to `y`, for which an
/// f32 object takes the series' result (2⁻³³ ≈ 1.2·10⁻¹⁰).
const LAST_TERM_TOL: f64 = 1.0 / (1u64 << 33) as f64;

/// How close the series must come to the iterative solution, relative, at
/// every check point of a segment for that segment to take it (2⁻³⁶).
const CHECK_TOL: f64 = 1.0 / (1u64 << 36) as f64;

/// The fog mixture in one orientation, in f64: lobe asymmetries `g_hg`, `g_d`
/// (negated when mirrored), Draine's `α`, and the Draine weight `w`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mixture {
    gh: f64,
    gd: f64,
    alpha: f64,
    w: f64,
}

/// `s² = 1 + g² − 2gμ` at `y = 1 + μ` as a sum of non-negative terms (no
/// cancellation at `μ → sign(g)`, `|g| → 1`): `(1 − g)² + 2g(2 − y)` for
/// `g ≥ 0`, `(1 + g)² − 2gy` otherwise.
#[inline(always)]
fn s2(g: f64, y: f64) -> f64 {
    let pos = (1.0 - g) * (1.0 - g) + 2.0 * g * (2.0 - y);
    let neg = (1.0 + g) * (1.0 + g) - 2.0 * g * y;
    if g >= 0.0 { pos } else { neg }
}

impl Mixture {
    /// The mixture `(1 − w) HG(g_hg) + w Draine(g_d, α)`, mirrored
    /// (`μ → −μ`) if asked.
    #[inline(always)]
    pub(crate) fn new(g_hg: f64, g_d: f64, alpha: f64, w: f64, mirrored: bool) -> Mixture {
        let sign = if mirrored { -1.0 } else { 1.0 };
        Mixture {
            gh: sign * g_hg,
            gd: sign * g_d,
            alpha,
            w,
        }
    }

    /// The fourth-order inverse series from `y0` toward `F(y) = t` (module
    /// docs): `(y, b₄a⁴)`, the result and its last term.
    ///
    /// Each lobe is `n (1 + αμ²)/s³` with `n = (1 − g²)/2` over Draine's
    /// normalisation `c = 1 + α(1 + 2g²)/3` (`α = 0`, `c = 1` for HG), and
    /// with `S = s + 1 + g` its CDF is `(1 − g) y Q/(c s S⁴)`, where
    /// `Q = S³ + (α/3)(3S³ − 6s₀yS² + 4s₀²y²S − 2gs₀y³)`, `s₀ = 1 + g`
    /// (`Params::eval_y`'s `I0 (1 + αP/3)` with `e = y/S` multiplied out;
    /// `Q = S³` for HG). Over the common denominator `E = s_h S_h c s_d S_d⁴`,
    /// `t − F = R/E`; with `M = c s_h³ s_d³ F'` (a sum of positive terms),
    /// the Newton step is `a = R s_h² s_d²/(S_h S_d⁴ M)`, so one division,
    /// which waits only for the square roots and these products, gives `a`
    /// and `1/M`. The k-th derivative of `1/s³` is
    /// `(1·3·5···(2k+1)) zᵏ/s³` with `z = g/s²` (`1/s²` from a second
    /// division that runs beside the square roots), and Leibniz's rule with
    /// `1 + αμ²`, `2αμ`, `2α` gives the density's derivatives, so
    /// `A_{k+1} = (c s_d³ n_h H_k + s_h³ n_d D_k)/((k + 1)! M)` with
    /// `H_k = (1·3···(2k+1)) z_hᵏ` and `D_k` that rule's sum for Draine
    /// (`n_h`, `n_d` carrying the weights `1 − w`, `w`).
    #[inline(always)]
    pub(crate) fn series(&self, t: f64, y: f64) -> (f64, f64) {
        let Mixture { gh, gd, alpha, w } = *self;
        let mu = y - 1.0;
        let (s2h, s2d) = (s2(gh, y), s2(gd, y));
        let inv_s2s = 1.0 / (s2h * s2d);
        let (sh, sd) = (Real::sqrt(s2h), Real::sqrt(s2d));
        let (big_sh, big_sd) = (sh + (1.0 + gh), sd + (1.0 + gd));
        let big_sd2 = big_sd * big_sd;
        let big_sd4 = big_sd2 * big_sd2;
        let (ch, cd) = (sh * s2h, sd * s2d);
        let c = 1.0 + alpha * (1.0 + 2.0 * gd * gd) * (1.0 / 3.0);
        let nh = 0.5 * (1.0 - w) * (1.0 - gh) * (1.0 + gh);
        let nd = 0.5 * w * (1.0 - gd) * (1.0 + gd);
        let pw = 1.0 + alpha * mu * mu;
        let (nh_c_cd, nd_ch) = (nh * c * cd, nd * ch);
        let m = nh_c_cd + nd_ch * pw;
        // R = t E − (1 − w)(1 − g_h) y c s_d S_d⁴ − w (1 − g_d) y Q s_h S_h.
        let s0 = 1.0 + gd;
        let q = big_sd2 * (big_sd * (1.0 + alpha) - 2.0 * alpha * s0 * y)
            + alpha * (1.0 / 3.0) * s0 * y * y * (4.0 * s0 * big_sd - 2.0 * gd * y);
        let hg_part = c * sd * big_sd4;
        let dr_part = sh * big_sh;
        let r = t * (hg_part * dr_part)
            - (1.0 - w) * (1.0 - gh) * y * hg_part
            - w * (1.0 - gd) * y * q * dr_part;
        let p = big_sh * big_sd4;
        let x = 1.0 / (p * m);
        let a = r * (s2h * s2d) * x;
        let inv_m = x * p;
        // z = g/s² of each lobe, and the derivatives over M.
        let (zh, zd) = (gh * s2d * inv_s2s, gd * s2h * inv_s2s);
        let (zh2, zd2) = (zh * zh, zd * zd);
        let (p1, p2) = (2.0 * alpha * mu, 2.0 * alpha);
        let d = |hk: f64, dk: f64| (nh_c_cd * hk + nd_ch * dk) * inv_m;
        let a2 = 0.5 * d(3.0 * zh, 3.0 * zd * pw + p1);
        let a3 = (1.0 / 6.0) * d(15.0 * zh2, 15.0 * zd2 * pw + 6.0 * zd * p1 + p2);
        let a4 = (1.0 / 24.0)
            * d(
                105.0 * zh2 * zh,
                105.0 * zd2 * zd * pw + 45.0 * zd2 * p1 + 9.0 * zd * p2,
            );
        let b2 = -a2;
        let b3 = 2.0 * a2 * a2 - a3;
        let b4 = a2 * (5.0 * a3 - 5.0 * a2 * a2) - a4;
        let aa = a * a;
        let last = aa * aa * b4;
        (y + (a + aa * (b2 + a * b3)) + last, last)
    }
}

/// The seed table (module docs): 13, 11 and 15 nodes for the three segments
/// in the 16-bit format of `seeds::HalfSeeds`, the split points, the trough
/// anchor, each segment's nodes per unit of `t`, and which segments passed
/// their check (bit `j` for segment `j`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FogSeeds {
    nodes: [u16; NODES],
    u_s: f32,
    u_f: f32,
    y_a: f32,
    scale: [f32; 3],
    fast: u8,
    /// The nodes hold the mean density `1/z` instead of `z` (module docs).
    mean_density: bool,
}

/// The solutions a table build has found, by frame and target, so that the
/// second kind of table (`FogSeeds::mean_density`) reuses the first's. In
/// cells, so that it is an `Fn` without a borrow that could fail.
struct Memo<F> {
    solve: F,
    keys: [Cell<(bool, u64)>; MEMO],
    values: [Cell<f64>; MEMO],
    len: Cell<usize>,
}

/// Solutions a [`Memo`] keeps: every node of segment 0 and of segments 1
/// and 2 under each candidate split.
const MEMO: usize = K[0] + (K[1] + K[2]) * FORWARD_SPLITS.len();

impl<F: Fn(bool, f64) -> f64> Memo<F> {
    fn new(solve: F) -> Self {
        Memo {
            solve,
            keys: core::array::from_fn(|_| Cell::new((false, 0))),
            values: core::array::from_fn(|_| Cell::new(0.0)),
            len: Cell::new(0),
        }
    }

    /// `solve(mirrored, t)`, found again or solved and kept while there is
    /// room.
    fn get(&self, mirrored: bool, t: f64) -> f64 {
        let key = (mirrored, t.to_bits());
        let kept = self.keys.iter().zip(&self.values).take(self.len.get());
        if let Some((_, y)) = kept.into_iter().find(|(k, _)| k.get() == key) {
            return y.get();
        }
        let y = (self.solve)(mirrored, t);
        let len = self.len.get();
        if let (Some(k), Some(v)) = (self.keys.get(len), self.values.get(len)) {
            k.set(key);
            v.set(y);
            self.len.set(len + 1);
        }
        y
    }
}

/// Where a sample starts: its frame, target and seed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Start {
    /// Solve in the mirrored frame (`y = 1 − μ`).
    pub(crate) mirrored: bool,
    /// The target `t` in that frame.
    pub(crate) t: f64,
    /// The seed `y₀`.
    pub(crate) y0: f64,
    /// The segment passed its check when built.
    pub(crate) fast: bool,
}

impl FogSeeds {
    /// Builds the table for the mixture `m(mirrored)`, where `eval(mirrored,
    /// y)` gives `F` and `F'` at `y` in that frame, `exact(mirrored, t)` the
    /// solution `y` of `F(y) = t`, `t ∈ [0, 1]`, and `check(mirrored, t, y)`
    /// polishes a near solution (the iterative solver).
    ///
    /// The end of the trough-side segment, `u_f`, is the best of
    /// [`FORWARD_SPLITS`]: the one whose segments that pass their check
    /// cover most of `[0, 1]`, and of those the one with the closest seeds.
    /// `None` if that covers less than [`MIN_COVERAGE`]: the iterative
    /// solver's own table (`phase::seeds`) serves such a mixture better.
    ///
    /// The fog tries every candidate ([`FORWARD_SPLITS`], `[false,
    /// true]`); the tests build each alone to check that the one chosen is
    /// the best.
    pub(crate) fn build(
        m: impl Fn(bool) -> Mixture,
        eval: impl Fn(bool, f64) -> Eval,
        exact: impl Fn(bool, f64) -> f64,
        check: impl Fn(bool, f64, f64) -> f64,
        (splits, kinds): Candidates,
    ) -> Option<FogSeeds> {
        let u_s = (eval(false, 1.0).cdf as f32).clamp(0.0, 1.0);
        let y_a = exact(true, 1.0 - u_s as f64) as f32;
        // Both kinds of table put their nodes at the same points: solve each
        // point once.
        let memo = Memo::new(exact);
        let exact = |mirrored: bool, t: f64| memo.get(mirrored, t);
        let fns = (&m, &eval, &exact, &check);
        let mut best: Option<(f64, f64, FogSeeds)> = None;
        // The mean density needs a division per sample: tried only where the
        // inverse leaves part of [0, 1] to the solver.
        for &mean_density in kinds {
            if best.as_ref().is_some_and(|b| b.0 >= 1.0 - COVERAGE_TIE) {
                break;
            }
            let mut seeds = FogSeeds {
                nodes: [0; NODES],
                u_s,
                u_f: u_s,
                y_a,
                scale: [0.0; 3],
                fast: 0,
                mean_density,
            };
            let (pass0, e0) = seeds.segment(0, fns);
            for split in splits {
                let u_f = split(u_s);
                if !(u_f >= u_s && u_f <= 1.0) {
                    continue;
                }
                let mut trial = FogSeeds { u_f, ..seeds };
                let (pass1, e1) = trial.segment(1, fns);
                let (pass2, e2) = trial.segment(2, fns);
                let share = |pass: bool, width: f32| f64::from(u8::from(pass)) * width as f64;
                let covered = share(pass0, u_s) + share(pass1, u_f - u_s) + share(pass2, 1.0 - u_f);
                let worse = e0.max(e1).max(e2);
                // Equal cover goes to the closer seeds of the same kind, and
                // to the inverse mean density (no division) across kinds.
                let better = match &best {
                    None => true,
                    Some((c, e, b)) => {
                        covered > c + COVERAGE_TIE
                            || (covered >= c - COVERAGE_TIE
                                && b.mean_density == mean_density
                                && worse < *e)
                    }
                };
                if better {
                    best = Some((covered, worse, trial));
                }
            }
        }
        let (covered, _, seeds) = best?;
        (covered >= MIN_COVERAGE).then_some(seeds)
    }

    /// Tabulates segment `j` and checks it (module docs): whether it passed,
    /// and the largest relative error of its seed at the check points (∞ if
    /// the segment is empty).
    fn segment(
        &mut self,
        j: usize,
        (m, eval, exact, check): (
            &impl Fn(bool) -> Mixture,
            &impl Fn(bool, f64) -> Eval,
            &impl Fn(bool, f64) -> f64,
            &impl Fn(bool, f64, f64) -> f64,
        ),
    ) -> (bool, f64) {
        let (mirrored, t0, y0) = self.anchor(j);
        let (j, n) = (j.min(2), K[j.min(2)]);
        let end = if j == 0 {
            self.u_s as f64
        } else {
            1.0 - self.u_f as f64
        };
        let scale = (n as f64 / (end - t0)) as f32;
        self.fast &= !(1 << j);
        self.scale[j] = 0.0;
        let Some(row) = self.nodes.get_mut(OFFSET[j]..=OFFSET[j] + n) else {
            return (false, f64::INFINITY);
        };
        if !(scale.is_finite() && scale != 0.0) {
            return (false, f64::INFINITY);
        }
        let t_at = |k: f64| t0 + k / scale as f64;
        for (k, node) in row.iter_mut().enumerate().skip(1) {
            let t = t_at(k as f64);
            let z = (exact(mirrored, t) - y0) / (t - t0);
            *node = half_encode((if self.mean_density { 1.0 / z } else { z }) as f32);
        }
        let density = eval(mirrored, y0).density;
        let z0 = (if self.mean_density {
            density
        } else {
            1.0 / density
        }) as f32;
        // A density of 0 or ∞ at the anchor leaves no limit: the next node.
        if let [first, next, ..] = row {
            *first = if z0.is_finite() && z0 > 0.0 {
                half_encode(z0)
            } else {
                *next
            };
        }
        self.scale[j] = scale;
        let (mut passes, mut worst) = (true, 0.0f64);
        for k in 0..n {
            let t = t_at(k as f64 + 0.5);
            let u = if mirrored { 1.0 - t } else { t };
            let s = self.start(u);
            let (y, last) = m(s.mirrored).series(s.t, s.y0);
            let reference = check(s.mirrored, s.t, y);
            passes &= s.mirrored == mirrored
                && last.abs() <= LAST_TERM_TOL * y
                && (y - reference).abs() <= CHECK_TOL * reference;
            let seed_error = (s.y0 - reference).abs() / reference;
            // NaN counts as the worst.
            worst = if seed_error.is_nan() {
                f64::INFINITY
            } else {
                worst.max(seed_error)
            };
        }
        self.fast |= u8::from(passes) << j;
        (passes, worst)
    }

    /// The segments' ends `(u_s, u_f)`.
    #[cfg(test)]
    pub(crate) fn splits(&self) -> (f32, f32) {
        (self.u_s, self.u_f)
    }

    /// Whether the table is of the inverse mean density (module docs).
    #[cfg(test)]
    pub(crate) fn mean_density(&self) -> bool {
        self.mean_density
    }

    /// Segment `j`'s frame and anchor `(mirrored, t_a, y_a)`.
    #[inline(always)]
    fn anchor(&self, j: usize) -> (bool, f64, f64) {
        let trough = j == 1;
        (
            j >= 1,
            if trough { 1.0 - self.u_s as f64 } else { 0.0 },
            if trough { self.y_a as f64 } else { 0.0 },
        )
    }

    /// The frame, target and seed for `u ∈ [0, 1]` (not NaN).
    #[inline(always)]
    pub(crate) fn start(&self, u: f64) -> Start {
        let j = (usize::from(u >= self.u_s as f64) + usize::from(u >= self.u_f as f64)).min(2);
        let (mirrored, t_a, y_a) = self.anchor(j);
        let t = if mirrored { 1.0 - u } else { u };
        let dt = t - t_a;
        let s = dt * self.scale[j] as f64;
        // One-sided quadratic through nodes k, k + 1, k + 2 (no branch on
        // which side of the middle s lies).
        let k = Real::to_index(s).min(K[j] - 2);
        let x = s - k as f64;
        // (The min keeps the compiler's bounds checks away.)
        let i = (OFFSET[j] + k).min(NODES - 3);
        let node = |i: usize| half_decode(self.nodes[i]) as f64;
        let (a, b, c) = (node(i), node(i + 1), node(i + 2));
        let z = a + x * (b - a) + 0.5 * x * (x - 1.0) * (c - 2.0 * b + a);
        Start {
            mirrored,
            t,
            y0: (y_a + if self.mean_density { dt / z } else { dt * z }).clamp(0.0, Y_MAX),
            fast: self.fast & (1 << j) != 0,
        }
    }

    /// Whether the series' result `y` may answer in a segment that passed
    /// its check: its last term `last` is small beside `y` (module docs).
    #[inline(always)]
    pub(crate) fn accept(y: f64, last: f64) -> bool {
        last.abs() <= LAST_TERM_TOL * y && y <= 2.0
    }
}
