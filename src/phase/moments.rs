//! Legendre moments of phase functions: `χ_l = ⟨P_l(cos θ)⟩ =
//! 2π ∫ P_l(μ) p(μ) dμ` (`χ_0 = 1`, `χ_1 = g`), the form DISORT and
//! libRadtran take a phase function in (`p = Σ (2l + 1) χ_l P_l / 4π`).
//!
//! **Closed forms.** HG: `χ_l = g^l`. Draine's `p ∝ p_HG (1 + αμ²)` gives,
//! with `μ² P_l = a_l P_{l+2} + b_l P_l + c_l P_{l−2}` (twice the
//! three-term recurrence `(2l + 1) μ P_l = (l + 1) P_{l+1} + l P_{l−1}`),
//!
//! `χ_l = (g^l + α (a_l g^{l+2} + b_l g^l + c_l g^{l−2})) / (1 + α(1 + 2g²)/3)`,
//!
//! `a_l = (l+1)(l+2)/((2l+1)(2l+3))`, `b_l = (l+1)²/((2l+1)(2l+3)) +
//! l²/((2l+1)(2l−1))`, `c_l = l(l−1)/((2l+1)(2l−1))`. Cornette–Shanks is
//! `α = 1`; Rayleigh is `g = 0, α = 1`; depolarised Rayleigh, `∝ 1 + 3γ +
//! (1 − γ)μ²`, is `g = 0, α = (1 − γ)/(1 + 3γ)`; isotropic is
//! `g = α = 0`; the fog and two-lobe HG are weighted sums of these.
//!
//! **Quadrature** for the others (Gegenbauer, Fournier–Forand, tables,
//! mixtures with tables): `χ_l = ∫₀¹ P_l(μ(u)) du` over the model's own
//! inverse CDF, which moves a forward peak's mass evenly over `u`;
//! 16-point Gauss–Legendre on panels that halve toward both ends of
//! `[0, 1]` (down to 2⁻⁴⁰), where `μ(u)` varies fastest, each cut in 16
//! (20 992 evaluations of the sampler). Measured (`tests/models/moments.rs`,
//! `χ_0 … χ_32`): within 10⁻¹² of the closed forms for HG (g = 0.9,
//! −0.99), Draine (0.9, 10), Rayleigh, depolarised Rayleigh, the fog and
//! two-lobe HG; within 10⁻¹⁰ of an independent quadrature over `μ` for
//! Gegenbauer and Fournier–Forand.

use super::{Phase, PhaseFunction};
use crate::math::real::Real;

/// The moments `χ_0 … χ_{n−1}` of `phase` into `out` (`n = out.len()`):
/// closed forms where the model has them (module docs), else
/// [`legendre_moments_by_quadrature`]. Computed in f64.
pub fn legendre_moments<T: Real>(phase: &Phase<T>, out: &mut [T]) {
    match closed_form(phase) {
        Some(chi) => {
            for (l, o) in out.iter_mut().enumerate() {
                *o = T::from_f64(chi(l));
            }
        }
        None => legendre_moments_by_quadrature(phase, out),
    }
}

/// `l ↦ χ_l` for the models with a closed form (module docs), else `None`.
pub fn closed_form<T: Real>(phase: &Phase<T>) -> Option<impl Fn(usize) -> f64> {
    // (g, α) of up to two Draine lobes and the second's weight, as each
    // model declares them (`Model::lobes`).
    let lobes = phase.lobes()?;
    let ((g1, a1), (g2, a2), w) = lobes;
    Some(move |l: usize| {
        let first = draine(g1, a1, l);
        if w == 0.0 {
            first
        } else {
            (1.0 - w) * first + w * draine(g2, a2, l)
        }
    })
}

/// `χ_l` of Draine's function (module docs), `l ≥ 0`.
fn draine(g: f64, alpha: f64, l: usize) -> f64 {
    let x = l as f64;
    let gl = powi(g, l);
    let a = (x + 1.0) * (x + 2.0) / ((2.0 * x + 1.0) * (2.0 * x + 3.0));
    let mut m2 = a * gl * g * g;
    let b = (x + 1.0) * (x + 1.0) / ((2.0 * x + 1.0) * (2.0 * x + 3.0));
    m2 += b * gl;
    if l >= 1 {
        m2 += x * x / ((2.0 * x + 1.0) * (2.0 * x - 1.0)) * gl;
    }
    if l >= 2 {
        let c = x * (x - 1.0) / ((2.0 * x + 1.0) * (2.0 * x - 1.0));
        m2 += c * powi(g, l - 2);
    }
    (gl + alpha * m2) / (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0)
}

/// `g^n` by squaring (no `powi` without `std`).
fn powi(g: f64, mut n: usize) -> f64 {
    let (mut r, mut b) = (1.0, g);
    while n > 0 {
        if n & 1 == 1 {
            r *= b;
        }
        b *= b;
        n >>= 1;
    }
    r
}

/// The moments of any phase function (a model, a table, a mixture) by
/// quadrature over its inverse CDF (module docs), into `out`.
pub fn legendre_moments_by_quadrature<T: Real, P: PhaseFunction<T> + ?Sized>(p: &P, out: &mut [T]) {
    let mu = |u: f64| p.sample_cos(T::from_f64(u)).to_f64();
    legendre_moments_of(mu, 0, out)
}

/// `∫₀¹ P_l(μ(u)) du` for `l = start … start + out.len() − 1`, in blocks
/// of 32 f64 accumulators (no allocation).
pub(crate) fn legendre_moments_of<T: Real>(mu: impl Fn(f64) -> f64, start: usize, out: &mut [T]) {
    let (x, w) = gauss16();
    let mut first = start;
    for block in out.chunks_mut(32) {
        let mut acc = [0.0f64; 32];
        for_each_panel(|a, b| {
            let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
            let nodes = x.iter().zip(w.iter());
            for (&xi, &wi) in nodes {
                let m = mu(mid + half * xi);
                // P_l by the three-term recurrence, from l = 0.
                let (mut p0, mut p1) = (1.0, m);
                for l in 0..first + block.len() {
                    let pl = if l == 0 { 1.0 } else { p1 };
                    if l >= first {
                        if let Some(s) = acc.get_mut(l - first) {
                            *s += wi * half * pl;
                        }
                    }
                    if l >= 1 {
                        let k = l as f64;
                        let next = ((2.0 * k + 1.0) * m * p1 - k * p0) / (k + 1.0);
                        (p0, p1) = (p1, next);
                    }
                }
            }
        });
        for (o, &s) in block.iter_mut().zip(acc.iter()) {
            *o = T::from_f64(s);
        }
        first += block.len();
    }
}

/// Calls `f(a, b)` for the panels of `[0, 1]`: halving toward each end,
/// `[2⁻ᵏ⁻¹, 2⁻ᵏ]` and its mirror for `k = 1 … 40`, plus `[0, 2⁻⁴¹]` and
/// its mirror, each cut in [`CUTS`] equal pieces (a trough of the density
/// makes `μ(u)` steep anywhere in `[0, 1]`).
fn for_each_panel(mut f: impl FnMut(f64, f64)) {
    let mut piece = |a: f64, b: f64| {
        let h = (b - a) / CUTS as f64;
        for i in 0..CUTS {
            f(
                a + h * i as f64,
                if i + 1 == CUTS {
                    b
                } else {
                    a + h * (i + 1) as f64
                },
            );
        }
    };
    let mut hi = 0.5f64;
    for _ in 0..40 {
        let lo = 0.5 * hi;
        piece(lo, hi);
        piece(1.0 - hi, 1.0 - lo);
        hi = lo;
    }
    piece(0.0, hi);
    piece(1.0 - hi, 1.0);
}

/// The pieces each panel is cut in.
const CUTS: usize = 16;

/// The 16-point Gauss–Legendre rule on `[−1, 1]`: nodes by Newton's
/// method on `P_16` from Tricomi's estimates, weights `2/((1 − x²) P'²)`.
fn gauss16() -> ([f64; 16], [f64; 16]) {
    const N: usize = 16;
    let (mut x, mut w) = ([0.0; N], [0.0; N]);
    for (i, (xi, wi)) in x.iter_mut().zip(w.iter_mut()).enumerate() {
        let mut z = (core::f64::consts::PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 1..N {
                let k = k as f64;
                (p0, p1) = (p1, ((2.0 * k + 1.0) * z * p1 - k * p0) / (k + 1.0));
            }
            dp = N as f64 * (z * p1 - p0) / (z * z - 1.0);
            let step = p1 / dp;
            z -= step;
            if step.abs() <= 1e-16 {
                break;
            }
        }
        *xi = z;
        *wi = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}
