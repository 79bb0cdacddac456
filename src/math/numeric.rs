//! Numerics the models share, below all of them: the cancellation-free
//! root of a depressed cubic (Rayleigh, depolarised Rayleigh, Draine at
//! `g = 0`), the safeguarded Halley/bisection solver and its tolerances
//! (Draine, fog), and cubic Hermite interpolation of a tabulated inverse CDF
//! (tables). Models and tables import this module; it imports only
//! [`crate::math::real`].

use crate::math::real::Real;

/// The real root of the depressed cubic `x³ + 3a·x = 2b` for `a > 0`
/// (Cardano; the only real root since the cubic is increasing).
///
/// Cardano's `x = w − a/w`, `w = cbrt(b + sqrt(b² + a³))`, loses digits twice:
/// `b + sqrt(b² + a³)` cancels for `b < 0`, and `w − a/w` cancels for
/// `|b| ≪ a^{3/2}` (near the median). We take `w` from `|b|` and use
/// `x = 2b w² / (w⁴ + a w² + a²)`, which follows from `w³ + (−a/w)³ = 2b`,
/// has only positive terms in the denominator, and carries `b`'s sign.
#[inline(always)]
pub(crate) fn depressed_cubic_root<T: Real, const FAST: bool>(a: T, a2: T, b: T) -> T {
    let r = (b * b + a2 * a).sqrt();
    let v = b.abs() + r;
    let w = if FAST { v.cbrt_fast() } else { v.cbrt() };
    let w2 = w * w;
    T::TWO * b * w2 / (w2 * w2 + a * w2 + a2)
}

/// The most Halley/bisection steps one sample may take (bisection alone
/// narrows `[−1, 1]` to below 10⁻¹⁸ in 61 steps).
pub(crate) const MAX_NEWTON: u32 = 64;

/// Halley's iteration stops after a step below this, relative to the
/// variable (`1 + μ` near the pole): the error left is about curvature ×
/// step³, far below f32's resolution. (10⁻⁵ rather than 10⁻⁶ saves a third
/// step for a few per cent of fog samples; 10⁻⁴ was measured to cost
/// accuracy at 10 µm, 3.2·10⁻⁸ instead of 3.0·10⁻⁸.)
pub(crate) const TOL_F32: f64 = 1e-5;
/// For f64, steps continue to the rounding level of `μ` (there is no speed
/// target in f64, and the last steps buy digits where `F` is flat).
pub(crate) const TOL_F64: f64 = 1e-15;

/// The iteration tolerance for results of precision `T`.
#[inline(always)]
pub(crate) fn tol<T: Real>() -> f64 {
    if core::mem::size_of::<T>() == 4 {
        TOL_F32
    } else {
        TOL_F64
    }
}

/// `F(μ)`, `F'(μ)` (the density of μ) and `F''(μ)` at one point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Eval {
    pub(crate) cdf: f64,
    pub(crate) density: f64,
    pub(crate) slope: f64,
}

/// Solves `F(x) = target` for an increasing `F` on `[lo, hi] ⊆ [0, 2]` (the
/// variable is `y = 1 + μ`; `F(lo) ≤ target ≤ F(hi)`), where `f(x)` gives
/// `F`, `F'` and `F''`: Halley's method (cubic convergence) from `seed`, kept
/// inside a shrinking bracket and replaced by bisection whenever a step
/// would leave it. Stops once a Halley step and Newton's estimate `|r/F'|`
/// are both below `tol::<T>()` relative to `x`, and the step below
/// `sqrt(tol)` relative to the distance to the nearer pole (the next error
/// is then about `curvature · step³`), or when a step no longer moves `x`,
/// or after [`MAX_NEWTON`] steps.
#[inline]
pub(crate) fn solve_bracketed<T: Real>(
    f: impl Fn(f64) -> Eval,
    target: f64,
    seed: f64,
    mut lo: f64,
    mut hi: f64,
) -> f64 {
    if target.is_nan() {
        return f64::NAN;
    }
    if target <= 0.0 {
        return lo;
    }
    let tol = tol::<T>();
    let mut x = if seed > lo && seed < hi {
        seed
    } else {
        0.5 * (lo + hi)
    };
    for _ in 0..MAX_NEWTON {
        let e = f(x);
        let r = e.cdf - target;
        if r == 0.0 {
            break;
        }
        if r > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let mut next = x - 2.0 * r * e.density / (2.0 * e.density * e.density - r * e.slope);
        if next == x {
            // The correction is below the resolution of x: converged. (x is
            // also a bracket end now, so the test below would bisect away.)
            break;
        }
        let halley = next > lo && next < hi;
        if !halley {
            next = 0.5 * (lo + hi);
        }
        let step = (next - x).abs();
        // Newton's estimate of the distance to the root, |r/F'|, must be
        // small too (a Halley step far from the root, where r F'' dominates
        // its denominator, can be small without x being near the root).
        let near = r.abs() <= 4.0 * tol * x.abs() * e.density;
        // Near a pole the density's own scale is the distance to it, and
        // Halley's next error is about step³ over that distance squared: a
        // step within tol of x is not enough for a sharp forward lobe whose
        // smaller tail lies near y = 2 (measured: 1.5e-5 at g = 0.999,
        // α = 20). The step must also be within sqrt(tol) of the distance
        // to the nearer pole, which leaves an error below tol^1.5 of it.
        let pole = x.abs().min((2.0 - x).abs());
        let small = step <= tol * x.abs() && step * step <= tol * pole * pole;
        x = next;
        // Stop after a small Halley step (a bisection step says nothing
        // about the error), or when the bracket has shrunk to adjacent
        // floats.
        if (halley && near && small) || hi - lo <= 2.0 * f64::EPSILON * hi.abs().max(lo.abs()) {
            break;
        }
    }
    x
}

/// The inverse of a CDF given in `μ ∈ [−1, 1]`: `μ` with `F(μ) = u`, from
/// `eval(μ) = (F(μ), F'(μ))` and a `seed`, by [`solve_bracketed`] in f64
/// (Newton: no second derivative) in the smaller tail: `F = u` in
/// `y = 1 + μ` for `u ≤ ½`, else `1 − F = 1 − u` in `y = 1 − μ`, so that
/// the residual is taken where it is small and keeps its digits.
pub(crate) fn inverse_cdf(eval: impl Fn(f64) -> (f64, f64), u: f64, seed: f64) -> f64 {
    if u <= 0.5 {
        let f = |y: f64| {
            let (cdf, density) = eval(y - 1.0);
            Eval {
                cdf,
                density,
                slope: 0.0,
            }
        };
        solve_bracketed::<f64>(f, u, 1.0 + seed, 0.0, 2.0) - 1.0
    } else {
        let f = |y: f64| {
            let (cdf, density) = eval(1.0 - y);
            Eval {
                cdf: 1.0 - cdf,
                density,
                slope: 0.0,
            }
        };
        1.0 - solve_bracketed::<f64>(f, 1.0 - u, 1.0 - seed, 0.0, 2.0)
    }
}

/// Cubic Hermite interpolation of a tabulated inverse CDF (`μ_i, d_i`
/// interleaved, `n` intervals, `n_t = n` as a float) at `u ∈ [0, 1]`: the
/// interval `i = ⌊u n⌋` found by arithmetic, no search; the value held in
/// `[μ_i, μ_{i+1}]`, then in `[−1, 1]` (NaN stays NaN).
#[inline(always)]
pub(crate) fn hermite<T: Real>(data: &[T], n: usize, n_t: T, u: T) -> T {
    let x = u * n_t;
    // Saturating conversion (NaN → 0) and the min keep i in bounds.
    let i = x.to_index().min(n - 1);
    let t = x - T::from_index(i);
    let [y0, d0, y1, d1] = match data.get(2 * i..2 * i + 4) {
        Some(&[a, b, c, d]) => [a, b, c, d],
        _ => return T::NAN,
    };
    let dy = y1 - y0;
    let c2 = T::from_f64(3.0) * dy - T::TWO * d0 - d1;
    let c3 = d0 + d1 - T::TWO * dy;
    hold(y0 + t * (d0 + t * (c2 + t * c3)), y0, y1).clamp_unit()
}

/// `mu` held in `[y0, y1]`, the ends of its Hermite interval (NaN stays
/// NaN). The cubic is monotone from `y0` to `y1` on `t ∈ [0, 1]`, but its
/// rounding passes `y1` by an ulp near `t = 1`: past the last node, where
/// the table's density is 0, and above the next interval's first value, a
/// step back across the node. (Within an interval Horner's rounding can
/// still step back by a few ulp where the terms are larger than the sum.)
#[inline(always)]
fn hold<T: Real>(mu: T, y0: T, y1: T) -> T {
    let mu = if mu > y1 { y1 } else { mu };
    if mu < y0 { y0 } else { mu }
}

/// The root in `[lo, hi]` of an increasing `f` with `f(lo) ≤ 0 ≤ f(hi)`,
/// `fd(x) = (f(x), f'(x))`: Newton from `x0`, kept inside the shrinking
/// bracket (bisection where a step leaves it or the slope is not finite and
/// positive), 100 steps at most, stopping when a step or the bracket is
/// within 4 ulp of `x`, or when a step is so small that the next (quadratic
/// convergence) would be: `step² ≤ ulp · max(|x|, 1)`, which assumes
/// `|f''/2f'| ≲ 1` on the scale of `x` (the callers' accuracy tests hold it
/// to 10⁻¹⁵).
pub(crate) fn newton_bracketed(fd: impl Fn(f64) -> (f64, f64), lo: f64, hi: f64, x0: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let mut x = if x0 > lo && x0 < hi {
        x0
    } else {
        0.5 * (lo + hi)
    };
    for _ in 0..100 {
        let (r, d) = fd(x);
        if r == 0.0 {
            return x;
        }
        if r < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let step = r / d;
        let tol = 4.0 * f64::EPSILON * x.abs().max(1e-300);
        let slope_ok = d > 0.0 && d.is_finite();
        // Converged when the step is below the tolerance (even one that
        // rounds onto x itself, and so onto the bracket's end), or when it
        // is so small that the next one, about step² · |f''/2f'|, would be:
        // the callers' functions have |f''/2f'| of order 1 on their scale.
        if slope_ok && (step.abs() <= tol || step * step <= tol * x.abs().max(1.0) * 0.25) {
            return x - step;
        }
        let newton = x - step;
        let next = if slope_ok && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - x).abs() <= tol || hi - lo <= tol {
            return next;
        }
        x = next;
    }
    x
}

/// `∫₀¹ f(u) du` by composite Simpson with `n` intervals (a multiple of
/// 4), extrapolated once (Richardson, which makes it Boole's rule): with the
/// Simpson sums `S_h` over all `n + 1` points and `S_2h` over every other
/// one, `(16 S_h − S_2h)/15` cancels the `h⁴` term of the error, for no
/// more evaluations of `f`. For an integrand that is smooth but steep where
/// a phase function's density is small (the inverse CDF `μ(u)` of a peaked
/// model), plain Simpson at 4096 intervals was off by 1.3·10⁻⁹.
pub(crate) fn simpson_unit(f: impl Fn(f64) -> f64, n: usize) -> f64 {
    let h = 1.0 / n as f64;
    let (mut fine, mut coarse) = (0.0, 0.0);
    for i in 0..=n {
        let y = f(i as f64 * h);
        let end = i == 0 || i == n;
        fine += y * if end {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        if i % 2 == 0 {
            coarse += y * if end {
                1.0
            } else if i % 4 == 2 {
                4.0
            } else {
                2.0
            };
        }
    }
    let (s_h, s_2h) = (fine * h / 3.0, coarse * 2.0 * h / 3.0);
    (16.0 * s_h - s_2h) / 15.0
}
