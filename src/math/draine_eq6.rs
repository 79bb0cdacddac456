//! The constants of Jendersie & d'Eon's closed-form inverse of Draine's
//! phase function (2023, supplemental eq. 6), as the library rearranges it
//! (`phase::draine`'s `Eq6`): everything that does not depend on `u`, for
//! `g` signed as the problem is oriented and `α`, in the precision of the
//! caller (f64 for the accurate tier, f32 for the portable one; the same
//! operations in the same order either way).

use crate::math::real::Real;

/// Eq. 6's `u`-independent constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Eq6Core<T> {
    /// `t4 − r = d + q u`.
    pub d: T,
    /// See `d`.
    pub q: T,
    /// `r = sqrt(4α (1 − g²)² (1 + g²)(3g² + α (1 + g²)²))`.
    pub r: T,
    /// `t0 = α (1 − g²)`.
    pub t0: T,
    /// `t1 = −α (1 − g²)(1 + g²)`.
    pub t1: T,
    /// `t6 = −4 t0 g² (1 − g²)`.
    pub t6: T,
    /// `t6³`.
    pub t6_3: T,
    /// `6 (1 + g²)`.
    pub k: T,
}

/// The constants for `g` and `α` (`α > 0`, `g ≠ 0`).
#[inline(always)]
pub(crate) fn eq6_core<T: Real>(g: T, a: T) -> Eq6Core<T> {
    let c = |x: f64| T::from_f64(x);
    let g2 = g * g;
    let omg = T::ONE - g;
    let omg2 = omg * (T::ONE + g);
    let opg2 = T::ONE + g2;
    let t0 = a * omg2;
    let t6 = c(-4.0) * t0 * g2 * omg2;
    // p = t4 at u = 0 and q = dt4/du, t4 = 3g²(1 + t3) + α(2 + g²(1 +
    // (1 + 2g²) t3)) with t3 = g(2u − 1); p ≥ 0 and p + q ≥ 0.
    let p = omg
        * (c(3.0) * g2 + a * (c(2.0) + g * (c(2.0) + g * (c(3.0) + g * (c(2.0) + c(2.0) * g)))));
    let q = c(2.0) * g * g2 * (c(3.0) + a * (T::ONE + c(2.0) * g2));
    let r = (c(4.0) * a * (omg2 * omg2) * opg2 * (c(3.0) * g2 + a * opg2 * opg2)).sqrt();
    let b = a * (a * (c(4.0) * g2 - g + c(4.0)) + c(6.0) * (c(2.0) * g2 + g + c(2.0))) - c(9.0) * g;
    Eq6Core {
        // t4 − r without the cancellation of p − r: (p² − r²)/(p + r),
        // with p² − r² = −g³(1 − g)² b in closed form.
        d: -(g * g2) * (omg * omg) * b / (p + r),
        q,
        r,
        t0,
        t1: -a * omg2 * opg2,
        t6,
        t6_3: t6 * t6 * t6,
        k: c(6.0) * opg2,
    }
}
