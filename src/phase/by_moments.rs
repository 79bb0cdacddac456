//! Models set by their first Legendre moments, as tissue optics specifies
//! phase functions: the mean cosine `g = χ_1` with the similarity parameter
//! `γ = (1 − χ_2)/(1 − χ_1)` (Bevilacqua & Depeursinge, JOSA A 16(12),
//! 1999) or `δ = (1 − χ_3)/(1 − χ_1)`. Each family reaches a region of the
//! `(g, γ)` or `(g, δ)` plane; outside it the constructors answer
//! [`Error::Domain`].
//!
//! | family | `0 < g < 1` and |
//! |---|---|
//! | modified HG, `β HG + (1 − β) (3/4π) cos²θ` | `0.6 < γ ≤ 1 + g`; `1 < δ ≤ 1 + g + g²` |
//! | two-lobe HG with an isotropic lobe | `1 < γ ≤ 1 + g`; `1 < δ ≤ 1 + g + g²` |
//! | Gegenbauer kernel, `−½ < α ≤ 1000` | a band around HG's `γ = 1 + g`, `δ = 1 + g + g²`, reaching above them |
//!
//! The HG families take their top (`1 + g`, `1 + g + g²`, HG itself) with
//! a relative slack of `4ε` (ε of f64): a `γ` or `δ` computed as `1 + g`
//! and rounded up is HG, not an error.
//!
//! Every mixture of HG lobes (and the modified HG) has `χ_2 ≥ χ_1²`, so
//! `γ ≤ 1 + g`: phase functions flatter than HG at the same `g`
//! (`γ > 1 + g`) are the Gegenbauer kernel's with `α > ½`.

use super::gegenbauer::low_moments;
use super::{Gegenbauer, Phase};
use crate::error::Error;
use crate::math::real::Real;

/// The largest `γ` or `δ` taken for the top `hg` (HG's own value): `hg`
/// with 4ε of slack, for a caller's value rounded up from it (the module
/// docs).
fn top_of(hg: f64) -> f64 {
    hg * (1.0 + 4.0 * f64::EPSILON)
}

/// The Draine `α` that stands for the modified HG's `cos²θ` lobe: Draine
/// with `g = 0` is `∝ 1 + αμ²`, which differs from `3μ²/2` by at most
/// `3/(2α)` ≈ 10⁻²¹, below the resolution of an f64 density; its
/// sampler draws `cbrt(2u − 1)` to 6·10⁻¹⁵ (f64) and 3·10⁻⁸ (f32). A
/// power of two, so that f32 holds it exactly.
const COS_SQUARED_ALPHA: f64 = 1_180_591_620_717_411_303_424.0; // 2⁷⁰

impl<T: Real> Phase<T> {
    /// The modified Henyey–Greenstein function of Bevilacqua & Depeursinge
    /// (1999), `p = β p_HG(g_HG) + (1 − β) (3/4π) cos²θ` (as PyXopto's
    /// `MHg`), set by its mean cosine `g` and `γ = (1 − χ_2)/(1 − χ_1)`.
    /// Its moments are `χ_1 = β g_HG = g` and
    /// `χ_2 = β g_HG² + (1 − β) 2/5`, so `g_HG = x` solves
    /// `g x² + (γ(1 − g) − 3/5) x − 2g/5 = 0` (the positive root) and
    /// `β = g/x`. It reaches `0.6 < γ ≤ 1 + g` for `0 < g < 1`
    /// (`γ = 1 + g` is HG itself), less the values where `g_HG` rounds to
    /// 1 in `T`: γ so close to 0.6 (γ − 0.6 below about 10⁻¹⁵ in f64,
    /// 10⁻⁶ in f32 at g = 0.95), or, below `γ = 1 + g`, g so close to 1
    /// (1 − g below 10⁻¹⁵ in f64, 2.4·10⁻⁷ in f32 at γ = 0.8); other
    /// `(g, γ)` are [`Error::Domain`]. As
    /// `γ → 0.6` the HG lobe narrows below the spacing of floats near
    /// `μ = 1`; densities, CDF and the exact inverse stay accurate there
    /// (`tests/models/edges.rs`: within 10⁻⁹ of 50-digit values down to
    /// `γ = 0.6 + 10⁻⁹`).
    ///
    /// The `cos²θ` lobe is the Draine function with `g = 0` and `α = 2⁷⁰`
    /// (within 10⁻²¹ of it), so the value is a fog mixture
    /// (`g_hg = g_HG`, `g_d = 0`, `α = 2⁷⁰`, `w_d = 1 − β`) with its exact
    /// monotone inverse and its lobe sampler.
    ///
    /// ```
    /// use scatterkit::Phase;
    /// use scatterkit::phase::moments::legendre_moments;
    /// let p = Phase::<f64>::modified_hg(0.9, 1.6).unwrap();
    /// let mut chi = [0.0; 3];
    /// legendre_moments(&p, &mut chi);
    /// assert!((chi[1] - 0.9).abs() < 1e-12);
    /// assert!(((1.0 - chi[2]) / (1.0 - chi[1]) - 1.6).abs() < 1e-10);
    /// ```
    pub fn modified_hg(g: T, gamma: T) -> Result<Self, Error> {
        let (g, gamma) = (g.to_f64(), gamma.to_f64());
        if !(g > 0.0 && g < 1.0 && gamma > 0.6 && gamma <= top_of(1.0 + g)) {
            return Err(Error::Domain);
        }
        // The positive root of g x² + b x − 2g/5 = 0 without cancellation:
        // from the product of the roots (−2/5) where b ≥ 0.
        let b = gamma * (1.0 - g) - 0.6;
        let s = (b * b + 1.6 * g * g).sqrt();
        let x = if b >= 0.0 {
            0.8 * g / (b + s)
        } else {
            (s - b) / (2.0 * g)
        };
        Self::hg_and_lobe(g, x, COS_SQUARED_ALPHA)
    }

    /// The modified HG of [`modified_hg`](Self::modified_hg) set by `g`
    /// and `δ = (1 − χ_3)/(1 − χ_1)`: the `cos²θ` lobe has no odd moments,
    /// so `χ_3 = β g_HG³ = g g_HG²` and `g_HG = √((1 − δ(1 − g))/g)`. It
    /// reaches `1 < δ ≤ 1 + g + g²` for `0 < g < 1` (the top is HG); other
    /// `(g, δ)` are [`Error::Domain`].
    pub fn modified_hg_delta(g: T, delta: T) -> Result<Self, Error> {
        Self::by_delta(g, delta, COS_SQUARED_ALPHA)
    }

    /// The two-lobe HG whose second lobe is isotropic,
    /// `(1 − β) p_HG(g_HG) + β/4π` (the "modified HG" of Prahl's thesis,
    /// *Light transport in tissue*, 1988, used by MCML-era codes), set by
    /// `g` and `γ`: its moments are `χ_l = (1 − β) g_HG^l` for `l ≥ 1`, so
    /// `g_HG = (1 − γ(1 − g))/g` and `β = 1 − g/g_HG`. It reaches
    /// `1 < γ ≤ 1 + g` for `0 < g < 1` (`γ = 1 + g` is HG itself); other
    /// `(g, γ)` are [`Error::Domain`]. The value is
    /// `two_lobe_hg(g_HG, 0, 1 − β)`.
    pub fn two_lobe_hg_gamma(g: T, gamma: T) -> Result<Self, Error> {
        let (g, gamma) = (g.to_f64(), gamma.to_f64());
        if !(g > 0.0 && g < 1.0 && gamma > 1.0 && gamma <= top_of(1.0 + g)) {
            return Err(Error::Domain);
        }
        Self::hg_and_lobe(g, (1.0 - gamma * (1.0 - g)) / g, 0.0)
    }

    /// The two-lobe HG of [`two_lobe_hg_gamma`](Self::two_lobe_hg_gamma)
    /// set by `g` and `δ`: `χ_3 = g g_HG²`, so
    /// `g_HG = √((1 − δ(1 − g))/g)`. It reaches `1 < δ ≤ 1 + g + g²` for
    /// `0 < g < 1`; other `(g, δ)` are [`Error::Domain`].
    pub fn two_lobe_hg_delta(g: T, delta: T) -> Result<Self, Error> {
        Self::by_delta(g, delta, 0.0)
    }

    /// The Gegenbauer kernel ([`Gegenbauer`]) with mean cosine `g` and
    /// `γ = (1 − χ_2)/(1 − χ_1)`, `0 < g < 1`. Along the curve of kernels
    /// with mean cosine `g`, `γ` rises with `α`, so `(α, g_GK)` is found
    /// by a root search in `α` around one in `g_GK` (regula falsi,
    /// Illinois), on the moments in closed form (a positive series for
    /// `g_GK < 0.1`); construction takes about 0.3 ms (0.27–0.30 ms on an
    /// AMD EPYC), so build the value once. The
    /// reach: `γ` between its value as `α → −½` (or where `g` is no longer
    /// reachable, `g_GK → 1`) and at `α = 1000`, less a sliver at the
    /// lower end where `g_GK` is so close to 1 that the kernel as stored
    /// (`α` and `g_GK` rounded to `T`) cannot reproduce `g` and `γ` to
    /// 10⁻¹¹ in f64 (16 ULP in f32): one ULP of `g_GK` there moves the mean
    /// cosine by up to 10⁻⁴. The sliver ends where one step of `α` or
    /// `g_GK` in `T` moves the moments by half that tolerance, so the
    /// accepted `γ` at each `g` are an interval (swept by 10⁻⁶ in
    /// `tests/models/gegenbauer.rs`). Accepted, measured: `1.09112 ≤ γ ≤
    /// 1.10441` at `g = 0.1`; `1.33334 ≤ γ ≤ 1.87420` at `g = 0.6` (f32
    /// from 1.33553); `1.47231 ≤ γ ≤ 2.69969` at `g = 0.9` (f32 from
    /// 1.53538); `1.50736 ≤ γ ≤ 2.84984` at `g = 0.95` (f32 from
    /// 1.59935). Outside it: [`Error::Domain`].
    ///
    /// ```
    /// use scatterkit::Phase;
    /// use scatterkit::phase::moments::legendre_moments;
    /// // Flatter than HG at the same g (γ > 1 + g): HG mixtures cannot.
    /// let p = Phase::<f64>::gegenbauer_gamma(0.9, 2.2).unwrap();
    /// let mut chi = [0.0; 3];
    /// legendre_moments(&p, &mut chi);
    /// assert!((chi[1] - 0.9).abs() < 1e-10);
    /// assert!(((1.0 - chi[2]) / (1.0 - chi[1]) - 2.2).abs() < 1e-10);
    /// ```
    pub fn gegenbauer_gamma(g: T, gamma: T) -> Result<Self, Error> {
        Self::gegenbauer_by(g, gamma, 1)
    }

    /// The Gegenbauer kernel with mean cosine `g` and
    /// `δ = (1 − χ_3)/(1 − χ_1)`, `0 < g < 1`, found as in
    /// [`gegenbauer_gamma`](Self::gegenbauer_gamma) (`δ` also rises with
    /// `α` at fixed `g`), with the same check of the stored kernel.
    /// Accepted, measured (an interval at each `g`, as for `γ`):
    /// `1.10683 ≤ δ ≤ 1.11082` at `g = 0.1`; `1.51283 ≤ δ ≤ 2.30220` at
    /// `g = 0.6` (f32 from 1.51679); `1.77744 ≤ δ ≤ 4.64894` at `g = 0.9`
    /// (f32 from 1.90620). Outside the reach: [`Error::Domain`].
    pub fn gegenbauer_delta(g: T, delta: T) -> Result<Self, Error> {
        Self::gegenbauer_by(g, delta, 2)
    }

    /// `β HG(x) + (1 − β) Draine(0, α)` with `β = g/x` (`α = 0` is the
    /// isotropic lobe), checked: `g ≤ x < 1` up to rounding.
    fn hg_and_lobe(g: f64, x: f64, alpha: f64) -> Result<Self, Error> {
        // At the top of the range (HG itself) rounding can leave x a few
        // ULP below g, and β a few ULP above 1. Near γ = 0.6 (and δ = 1)
        // x → 1: refused where it rounds to 1 in T (the lobe would be a
        // delta, its sampler NaN).
        let beta = (g / x).min(1.0);
        if !(x < 1.0 && T::from_f64(x) < T::ONE && beta > 0.0) {
            return Err(Error::Domain);
        }
        Self::fog(
            T::from_f64(x),
            T::ZERO,
            T::from_f64(alpha),
            T::from_f64(1.0 - beta),
        )
    }

    /// [`modified_hg_delta`](Self::modified_hg_delta) and
    /// [`two_lobe_hg_delta`](Self::two_lobe_hg_delta): their second lobes
    /// have no odd moments, so both share `g_HG = √((1 − δ(1 − g))/g)`.
    fn by_delta(g: T, delta: T, alpha: f64) -> Result<Self, Error> {
        let (g, delta) = (g.to_f64(), delta.to_f64());
        if !(g > 0.0 && g < 1.0 && delta > 1.0 && delta <= top_of(1.0 + g + g * g)) {
            return Err(Error::Domain);
        }
        Self::hg_and_lobe(g, ((1.0 - delta * (1.0 - g)) / g).sqrt(), alpha)
    }

    /// The kernel with `χ_1 = g` and `(1 − χ_{j+1})/(1 − χ_1) = target`.
    fn gegenbauer_by(g: T, target: T, j: usize) -> Result<Self, Error> {
        let (g, target) = (g.to_f64(), target.to_f64());
        if !(g > 0.0 && g < 1.0 && target.is_finite()) {
            return Err(Error::Domain);
        }
        // χ_2 for j = 1, χ_3 for j = 2 (constant indices: no bound check).
        let ratio = |chi: [f64; 3]| (1.0 - if j == 1 { chi[1] } else { chi[2] }) / (1.0 - chi[0]);
        // The ratio rises with α; where g is out of reach (small α) it is
        // below every reachable one.
        let excess = |a: f64| gegenbauer_g_for(a, g).map(|gk| ratio(low_moments(a, gk)) - target);
        let a = root_increasing(excess, -0.5, Gegenbauer::<f64>::MAX_ALPHA).ok_or(Error::Domain)?;
        let gk = gegenbauer_g_for(a, g).ok_or(Error::Domain)?;
        // The kernel as stored (α and g_GK rounded to T) must have the
        // moments asked for. Near the edge where g_GK → 1 with α < 0 the
        // mean cosine moves by up to 10⁻⁴ per ULP of g_GK, so there no
        // stored kernel reproduces them (in f64 as in f32): refused, not
        // returned off. Whether one does depended on where the exact
        // g_GK fell between two floats, so refusals alternated with
        // acceptances over a stretch of γ (1014 of 3001 values at g =
        // 0.85). Now the edge is where one step of α or g_GK in T moves
        // the moments by half the tolerance, a smooth function of the
        // target, and inside it the best of three stored g_GK is within
        // the tolerance: the accepted set is an interval (swept by the
        // tests).
        let tol = MOMENT_TOLERANCE.max(16.0 * T::EPSILON.to_f64());
        let a_t64 = T::from_f64(a).to_f64();
        let gk_t64 = T::from_f64(gk).to_f64();
        // The moments' change per step, measured over `k` steps each way
        // so that the rounding of the moments themselves (a few 10⁻¹⁶ of
        // them near g_GK → 1, against steps of 10⁻¹² at the edge) does not
        // make the edge ragged.
        let k = if core::mem::size_of::<T>() == 4 {
            4
        } else {
            64
        };
        let (gk_lo, gk_hi) = neighbours::<T>(gk_t64, k);
        let (a_lo, a_hi) = neighbours::<T>(a_t64, k);
        if !(gk_lo > 0.0 && gk_hi < 1.0) {
            return Err(Error::Domain);
        }
        let per_step = 2.0 * k as f64;
        let spread = |x: [f64; 3], y: [f64; 3]| {
            (
                (x[0] - y[0]).abs() / per_step / g,
                (ratio(x) - ratio(y)).abs() / per_step / target,
            )
        };
        let (chi_hi, chi_lo) = (low_moments(a_t64, gk_hi), low_moments(a_t64, gk_lo));
        let by_gk = spread(chi_hi, chi_lo);
        let by_a = spread(low_moments(a_hi, gk_t64), low_moments(a_lo, gk_t64));
        let half = tol / 2.0;
        if !(by_gk.0 <= half && by_gk.1 <= half && by_a.0 <= half && by_a.1 <= half) {
            return Err(Error::Domain);
        }
        let miss = |gk: f64| {
            let chi = low_moments(a_t64, gk);
            ((chi[0] - g).abs() / g).max((ratio(chi) - target).abs() / target)
        };
        // The root search leaves g_GK a few steps from the float that
        // best gives g where one step moves the mean cosine by 10⁻¹²: one
        // secant step in whole steps of T, then the best of that float
        // and its two neighbours.
        let slope = (chi_hi[0] - chi_lo[0]) / per_step;
        let off = libm::round((g - low_moments(a_t64, gk_t64)[0]) / slope);
        let gk_c = if off.is_finite() && off.abs() <= 1024.0 && off != 0.0 {
            let (lo, hi) = neighbours::<T>(gk_t64, off.abs() as i64);
            let c = if off > 0.0 { hi } else { lo };
            if c > 0.0 && c < 1.0 { c } else { gk_t64 }
        } else {
            gk_t64
        };
        let (gk_down, gk_up) = neighbours::<T>(gk_c, 1);
        let gk_best = [gk_down, gk_up]
            .into_iter()
            .filter(|&c| c > 0.0 && c < 1.0)
            .fold(gk_c, |b, c| if miss(c) < miss(b) { c } else { b });
        let missed = miss(gk_best);
        if missed.is_nan() || missed > tol {
            return Err(Error::Domain);
        }
        let (a_t, gk_t) = (T::from_f64(a_t64), T::from_f64(gk_best));
        Self::gegenbauer(a_t, gk_t)
    }
}

/// The floats of `T` `k` steps below and above `x` (a float of `T` at
/// least `k` steps from the largest), in f64: by the bits away from 0,
/// and by multiples of the smallest subnormal at 0 (`α` may be 0).
fn neighbours<T: Real>(x: f64, k: i64) -> (f64, f64) {
    let f32_ = core::mem::size_of::<T>() == 4;
    if x == 0.0 {
        let tiny = if f32_ {
            f32::from_bits(1) as f64
        } else {
            f64::from_bits(1)
        };
        return (-(k as f64) * tiny, k as f64 * tiny);
    }
    let k = k * x.signum() as i64;
    if f32_ {
        let b = (x as f32).to_bits() as i64;
        let at = |k: i64| f32::from_bits((b + k) as u32) as f64;
        (at(-k), at(k))
    } else {
        let b = x.to_bits() as i64;
        let at = |k: i64| f64::from_bits((b + k) as u64);
        (at(-k), at(k))
    }
}

/// How closely a kernel set by moments reproduces them (relative), in f64;
/// in f32, 16 ULP.
pub(crate) const MOMENT_TOLERANCE: f64 = 1e-11;

/// `g_GK` of the kernel with exponent `α` and mean cosine `g` (the mean
/// cosine rises with `g_GK` on `(0, 1)`), or `None` where even `g_GK → 1`
/// stays below `g` (`α ≤ 0`).
fn gegenbauer_g_for(a: f64, g: f64) -> Option<f64> {
    let top = 1.0 - f64::EPSILON;
    root_increasing(|gk| Some(low_moments(a, gk)[0] - g), 0.0, top)
}

/// The root of an increasing `f` on `(lo, hi]`, where `f(x)` is `None`
/// (below every value) on an initial stretch of the interval: the
/// Illinois variant of regula falsi where both ends have values,
/// bisection elsewhere; `None` if `f(hi) < 0` or `f(hi)` is `None`.
/// Returns the upper end of the final bracket, within a few ULP of the
/// root (about ten evaluations where bisection takes fifty).
fn root_increasing(f: impl Fn(f64) -> Option<f64>, lo: f64, hi: f64) -> Option<f64> {
    let f_hi = f(hi)?;
    if f_hi < 0.0 {
        return None;
    }
    let (mut lo, mut hi, mut f_lo, mut f_hi) = (lo, hi, None::<f64>, f_hi);
    // Which end moved last (Illinois halves the other end's value when
    // the same end moves twice).
    let mut last_hi = None;
    for _ in 0..200 {
        let x = match f_lo {
            Some(fl) if f_hi > fl => lo + (hi - lo) * (-fl / (f_hi - fl)),
            _ => 0.5 * (lo + hi),
        };
        // Keep the new point strictly inside, else stop: the bracket is
        // as narrow as f64 makes it.
        let x = if x > lo && x < hi { x } else { 0.5 * (lo + hi) };
        if !(x > lo && x < hi) {
            break;
        }
        match f(x) {
            Some(v) if v >= 0.0 => {
                if v == 0.0 {
                    return Some(x);
                }
                hi = x;
                f_hi = v;
                if last_hi == Some(true) {
                    f_lo = f_lo.map(|fl| 0.5 * fl);
                }
                last_hi = Some(true);
            }
            v => {
                lo = x;
                f_lo = v;
                if last_hi == Some(false) {
                    f_hi *= 0.5;
                }
                last_hi = Some(false);
            }
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(f64::MIN_POSITIVE) {
            break;
        }
    }
    Some(hi)
}

#[cfg(test)]
mod tests {
    use super::neighbours;

    /// Steps away from 0 and across it: below, above, and at `α = 0`.
    #[test]
    fn neighbours_step_through_the_floats() {
        assert_eq!(
            neighbours::<f64>(1.0, 1),
            (1.0 - f64::EPSILON / 2.0, 1.0 + f64::EPSILON)
        );
        assert_eq!(
            neighbours::<f64>(-1.0, 1),
            (-1.0 - f64::EPSILON, -1.0 + f64::EPSILON / 2.0)
        );
        assert_eq!(
            neighbours::<f32>(0.5, 2),
            (
                0.5 - 2.0 * f32::EPSILON as f64 / 4.0,
                0.5 + 2.0 * f32::EPSILON as f64 / 2.0
            )
        );
        let (lo, hi) = neighbours::<f64>(0.0, 64);
        assert!(lo < 0.0 && hi > 0.0 && hi == -lo && hi < 1e-300);
        let (lo, hi) = neighbours::<f32>(0.0, 4);
        assert!(lo < 0.0 && hi > 0.0 && (hi as f32) > 0.0);
    }
}
