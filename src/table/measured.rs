//! Phase functions measured or tabulated at points, read as a density
//! linear in `cos θ` between them: validation, and the inverse CDF swept
//! segment by segment (the CDF is quadratic on each). Shared by
//! `Table::measured` and the chooser against data
//! (`choose::mie::choose_measured`), below both.

use crate::error::Error;
use crate::math::real::Real;

/// Validated measured data: `m` points in increasing `cos θ` order (the
/// caller's order reversed if it was decreasing).
pub(crate) struct Measured<'d, T> {
    x: &'d [T],
    p: &'d [T],
    reversed: bool,
    /// `∫ p dμ` by the trapezoid rule (exact for the linear density).
    area: f64,
}

impl<'d, T: Real> Measured<'d, T> {
    /// Validates the data (errors as `Table::measured`).
    pub(crate) fn new(x: &'d [T], p: &'d [T]) -> Result<Self, Error> {
        if x.len() != p.len() || x.len() < 2 {
            return Err(Error::Size);
        }
        let reversed = x.get(1) < x.first();
        let mut area = 0.0;
        let mut prev: Option<(f64, f64)> = None;
        for (&xj, &pj) in x.iter().zip(p) {
            let (xj, pj) = (xj.to_f64(), pj.to_f64());
            if !((-1.0..=1.0).contains(&xj) && pj >= 0.0 && pj.is_finite()) {
                return Err(Error::Domain);
            }
            if let Some((xp, pp)) = prev {
                let step = xj - xp;
                if !(if reversed { step < 0.0 } else { step > 0.0 }) {
                    return Err(Error::Domain);
                }
                area += 0.5 * step.abs() * (pj + pp);
            }
            prev = Some((xj, pj));
        }
        if !(area > 0.0 && area.is_finite()) {
            return Err(Error::Domain);
        }
        Ok(Measured {
            x,
            p,
            reversed,
            area,
        })
    }

    /// The k-th point in increasing order, density normalised to ∫ = 1.
    fn point(&self, k: usize) -> (f64, f64) {
        let j = if self.reversed {
            self.x.len() - 1 - k
        } else {
            k
        };
        let at = |s: &[T]| s.get(j).map_or(f64::NAN, |v| v.to_f64());
        (at(self.x), at(self.p) / self.area)
    }

    /// `emit(i, F⁻¹(u_i), density there)` for `count` increasing targets
    /// `u_i = target(i)`, sweeping the segments once (the CDF is quadratic
    /// on each).
    pub(crate) fn sweep(
        &self,
        count: usize,
        target: impl Fn(usize) -> f64,
        mut emit: impl FnMut(usize, f64, f64),
    ) {
        let m = self.x.len();
        // The last segment with mass: F⁻¹(1) is where the support ends,
        // its right end. Summed in the caller's order, the masses can
        // total a rounding below 1, and u = 1 then walked on through the
        // zero-density segments beyond the support (to the last one's
        // start: a table that sampled where the data says 0); or a
        // rounding above 1, and u = 1 stopped short of the end.
        let end = (0..m - 1)
            .rev()
            .find(|&k| {
                let ((x0, q0), (x1, q1)) = (self.point(k), self.point(k + 1));
                (x1 - x0) * (q0 + q1) > 0.0
            })
            .unwrap_or(m - 2);
        let (mut k, mut cdf0) = (0usize, 0.0f64);
        for i in 0..count {
            let u = target(i);
            if u >= 1.0 {
                let (x1, q1) = self.point(end + 1);
                emit(i, x1, q1);
                continue;
            }
            // Advance to the segment [k, k+1] holding u.
            loop {
                let ((x0, q0), (x1, q1)) = (self.point(k), self.point(k + 1));
                let mass = 0.5 * (x1 - x0) * (q0 + q1);
                // Zero-mass segments are skipped: F⁻¹(0) is where the support starts.
                if (mass > 0.0 && cdf0 + mass >= u) || k >= end {
                    let r = (u - cdf0).max(0.0);
                    let tau = segment_root(x1 - x0, q0, q1, r);
                    // max/min rather than clamp, which asserts its bounds are ordered.
                    let mu = (x0 + tau).max(x0).min(x1);
                    let q = q0 + (q1 - q0) * ((mu - x0) / (x1 - x0));
                    emit(i, mu, q);
                    break;
                }
                cdf0 += mass;
                k += 1;
            }
        }
    }
}

/// The density of `μ` of measured data (as [`Table::measured`](crate::Table::measured) takes it:
/// linear in `cos θ` between the points, normalised) at its midpoint
/// quantiles `F⁻¹((i + ½)/n)`, `n = mu.len() = density.len()`: the nodes of
/// the choosers' distance. Errors as [`Table::measured`](crate::Table::measured).
pub(crate) fn measured_quantiles(
    cos_theta: &[f64],
    pdf: &[f64],
    mu: &mut [f64],
    density: &mut [f64],
) -> Result<(), Error> {
    let data = Measured::new(cos_theta, pdf)?;
    let n = mu.len().min(density.len());
    data.sweep(
        n,
        |i| (i as f64 + 0.5) / n as f64,
        |i, m, q| {
            if let (Some(a), Some(b)) = (mu.get_mut(i), density.get_mut(i)) {
                (*a, *b) = (m, q);
            }
        },
    );
    Ok(())
}

/// The offset `τ ∈ [0, L]` at which a segment of length `L` with density
/// linear from `q0` to `q1` accumulates mass `r`:
/// `q0 τ + (q1 − q0) τ²/(2L) = r`, as `2r / (q0 + sqrt(q0² + 2(q1 − q0) r/L))`
/// (the form without the cancellation of `−q0 + sqrt(...)`).
fn segment_root(len: f64, q0: f64, q1: f64, r: f64) -> f64 {
    let disc = (q0 * q0 + 2.0 * (q1 - q0) * r / len).max(0.0);
    let den = q0 + libm::sqrt(disc);
    if den > 0.0 {
        (2.0 * r / den).min(len)
    } else {
        0.0
    }
}
