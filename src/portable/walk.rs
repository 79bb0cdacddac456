//! Tracking through a majorant grid in the portable tier: the ray is
//! clipped to the grid's box and its cells are crossed in order
//! (Amanatides and Woo, Eurographics 1987), and one call draws one
//! tentative collision: the optical depth `τ = −ln(1 − u)` is spent cell by
//! cell, `σ_maj,cell` times the length crossed in each, so that one uniform
//! serves the whole step however many cells it crosses (pbrt-v4's
//! `SampleT_maj` instead draws a fresh uniform per cell; the two have the
//! same distribution). Delta, ratio and residual tracking are loops around
//! this step; the caller decides at each collision.
//!
//! The grid is `nx·ny·nz` majorants (x fastest, `i + nx (j + ny k)`), each
//! the bound of the extinction `σ_t` per length unit over its cell, the
//! cells an even division of the box `[lo, hi]`: the layout of
//! `sk_majorants` and of [`crate::majorant::Majorants`].

use super::flight::free_path;

/// A walk along one ray through a majorant grid: where it is (`t`, the
/// cell) and where it ends. Made by [`Walk::new`], advanced by
/// [`Walk::step`]; plain data (the header's `skp_walk`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Walk {
    /// The origin in cell units (`(o − lo) n/(hi − lo)` per axis).
    pub o: [f32; 3],
    /// The direction in cell units per ray parameter.
    pub d: [f32; 3],
    /// The ray parameter at the next face along each axis (`+∞` where the
    /// ray does not move along it).
    pub next: [f32; 3],
    /// The ray parameter reached.
    pub t: f32,
    /// The ray parameter where the walk ends (the box's far face or
    /// `t_max`).
    pub t_end: f32,
    /// The cell the walk is in.
    pub cell: [u32; 3],
    /// The grid's cells per axis.
    pub dims: [u32; 3],
}

/// What [`Walk::step`] found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Step {
    /// A tentative collision at ray parameter `t` in a cell of majorant
    /// `sigma_maj`, at flat index `cell`.
    Collision {
        /// The ray parameter.
        t: f32,
        /// The majorant of the cell it lies in.
        sigma_maj: f32,
        /// That cell's index, `i + nx (j + ny k)`.
        cell: u32,
    },
    /// The walk reached its end at `t_end` without a collision.
    Exit,
    /// A majorant on the way is negative, NaN or infinite, or the grid is
    /// shorter than `nx·ny·nz`.
    BadMajorant,
}

impl Walk {
    /// Starts a walk along `origin + t·dir`, `t ∈ [t_min, t_max]`, through
    /// the grid of `dims` cells over the box `[lo, hi]` (world units; the
    /// ray parameter is a length where `dir` is a unit vector, as the
    /// majorants per length unit need). `Ok(None)` for a segment that
    /// misses the box or touches it in one point; `Err(())` unless
    /// `origin` and `dir` are finite, `dir ≠ 0`, `lo < hi` (finite),
    /// every dimension is `≥ 1` and `< 2²⁴` with `nx·ny·nz < 2³²`,
    /// `0 ≤ t_min` (finite) and
    /// `t_min ≤ t_max` (+∞ allowed), and unless the ray and box are within
    /// float range in cell units: `Err(())` too where `hi − lo`,
    /// `(origin − lo)·n/(hi − lo)` or `dir·n/(hi − lo)` overflows on some
    /// axis (a box from `−f32::MAX` to `f32::MAX`, an origin near
    /// `f32::MAX` from a small box, a direction of length near
    /// `f32::MAX`). The header's `skp_walk_begin` (return values 1, 0 and
    /// −1).
    #[allow(clippy::result_unit_err)]
    pub fn new(
        origin: [f32; 3],
        dir: [f32; 3],
        lo: [f32; 3],
        hi: [f32; 3],
        dims: [u32; 3],
        t_min: f32,
        t_max: f32,
    ) -> Result<Option<Walk>, ()> {
        if !((0.0..f32::INFINITY).contains(&t_min) && t_max >= t_min) {
            return Err(());
        }
        let [nx, ny, nz] = dims;
        let cells = (nx as u64) * (ny as u64) * (nz as u64);
        if dir == [0.0; 3] || cells > u32::MAX as u64 {
            return Err(());
        }
        let mut w = Walk {
            o: [0.0; 3],
            d: [0.0; 3],
            next: [f32::INFINITY; 3],
            t: t_min,
            t_end: t_max,
            cell: [0; 3],
            dims,
        };
        let mut miss = false;
        for a in 0..3 {
            let n = dims[a];
            let span = hi[a] - lo[a];
            if !((1..1 << 24).contains(&n) && span > 0.0 && span < f32::INFINITY) {
                return Err(());
            }
            let scale = n as f32 / span;
            let (o, d) = ((origin[a] - lo[a]) * scale, dir[a] * scale);
            let finite = |x: f32| x > f32::NEG_INFINITY && x < f32::INFINITY;
            if !(finite(o) && finite(d)) {
                return Err(());
            }
            (w.o[a], w.d[a]) = (o, d);
            // The slab [0, n] along this axis. A miss here is reported
            // after every axis is checked, so that a ray beyond float
            // range on a later axis is refused whichever axis it misses on.
            if d == 0.0 {
                miss |= o < 0.0 || o > n as f32;
                continue;
            }
            let (t0, t1) = ((0.0 - o) / d, (n as f32 - o) / d);
            let (near, far) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
            if near > w.t {
                w.t = near;
            }
            if far < w.t_end {
                w.t_end = far;
            }
        }
        // Neither is NaN: t_min and t_max are numbers, the slab times
        // quotients of finite numbers by non-zero ones.
        if miss || w.t >= w.t_end {
            return Ok(None);
        }
        #[allow(clippy::needless_range_loop)] // w.face(a) borrows w whole
        for a in 0..3 {
            // The start cell, clamped into the grid so that a start on a
            // face, or rounded just outside, stays valid.
            let p = w.o[a] + w.d[a] * w.t;
            let c = if p > 0.0 { p as u32 } else { 0 };
            w.cell[a] = if c < dims[a] - 1 { c } else { dims[a] - 1 };
            w.next[a] = w.face(a);
        }
        Ok(Some(w))
    }

    /// The ray parameter at the face of the current cell the ray moves
    /// towards along axis `a` (`+∞` if it does not move along `a`),
    /// computed from the cell index so that it does not drift.
    fn face(&self, a: usize) -> f32 {
        let d = self.d[a];
        if d == 0.0 {
            return f32::INFINITY;
        }
        let i = self.cell[a] + u32::from(d > 0.0);
        (i as f32 - self.o[a]) / d
    }

    /// The flat index of the current cell.
    pub fn cell_index(&self) -> u32 {
        self.cell[0] + self.dims[0] * (self.cell[1] + self.dims[1] * self.cell[2])
    }

    /// Draws the next tentative collision with one uniform `u ∈ [0, 1]`
    /// (clamped; NaN and `u = 1` walk to the end): spends `τ = −ln(1 − u)`
    /// of majorant optical depth from `t` on, crossing cells, and stops at
    /// the collision (the walk stays there, ready for the next step) or at
    /// the end (every later step returns [`Step::Exit`]). Reads at most
    /// `nx + ny + nz` majorants. The header's `skp_walk_step` (return
    /// values 1, 0 and −1).
    pub fn step(&mut self, majorants: &[f32], u: f32) -> Step {
        let mut tau = free_path(1.0, u);
        if tau.is_nan() {
            tau = f32::INFINITY;
        }
        let crossings = self.dims[0] + self.dims[1] + self.dims[2];
        let mut k = 0;
        while self.t < self.t_end && k < crossings {
            k += 1;
            let mut a = 0;
            if self.next[1] < self.next[a] {
                a = 1;
            }
            if self.next[2] < self.next[a] {
                a = 2;
            }
            let mut t_face = if self.next[a] < self.t_end {
                self.next[a]
            } else {
                self.t_end
            };
            if t_face < self.t {
                t_face = self.t;
            }
            let cell = self.cell_index();
            let sigma = match majorants.get(cell as usize) {
                Some(&s) if (0.0..f32::INFINITY).contains(&s) => s,
                _ => return Step::BadMajorant,
            };
            let depth = sigma * (t_face - self.t);
            if tau < depth {
                // τ/σ < t_face − t but for rounding: keep t in the cell.
                let t = self.t + tau / sigma;
                self.t = if t < t_face { t } else { t_face };
                return Step::Collision {
                    t: self.t,
                    sigma_maj: sigma,
                    cell,
                };
            }
            tau -= depth;
            if t_face >= self.t_end || !self.cross(a) {
                break;
            }
            self.t = t_face;
        }
        self.t = self.t_end;
        Step::Exit
    }

    /// Moves into the next cell along axis `a`; false when that leaves the
    /// grid.
    fn cross(&mut self, a: usize) -> bool {
        let c = self.cell[a];
        if self.d[a] > 0.0 {
            if c + 1 >= self.dims[a] {
                return false;
            }
            self.cell[a] = c + 1;
        } else {
            if c == 0 {
                return false;
            }
            self.cell[a] = c - 1;
        }
        self.next[a] = self.face(a);
        true
    }
}
