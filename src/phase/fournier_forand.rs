//! The Fournier–Forand phase function of ocean particles (G. R. Fournier,
//! J. L. Forand, "Analytic phase function for ocean water", Proc. SPIE 2258,
//! 1994; with the CDF of Fournier & Jonasz, Proc. SPIE 3761, 1999): for
//! particles of relative refractive index `n` with a Junge (hyperbolic) size
//! distribution of slope `μ_J`, `ν = (3 − μ_J)/2 ∈ (−1, 0)`,
//! `δ = 4 sin²(θ/2) / (3(n − 1)²)`,
//!
//! `p = [ν(1−δ) − (1−δ^ν) + (δ(1−δ^ν) − ν(1−δ)) / sin²(θ/2)] / (4π (1−δ)² δ^ν)
//!      + (δ₁₈₀^{−ν} − 1)/(δ₁₈₀ − 1) (3μ² − 1)/(16π)`.
//!
//! Its CDF from the forward direction is
//! `F_fwd = [1 − δ^{ν+1} − (1 − δ^ν) s] / ((1 − δ) δ^ν) + c μ(1 − μ²)/8`,
//! `s = sin²(θ/2)`, `c = (δ₁₈₀^{−ν} − 1)/(δ₁₈₀ − 1)`. As published it divides
//! `0/0` at `δ = 1` (Cycles switches to a Taylor expansion within 10⁻³ of
//! it) and its numerator cancels there. Rearranged (`1 − s = (1 + μ)/2`):
//!
//! * `P(cos θ ≤ μ) = (1 + μ)/2 · R(δ) − c μ(1 − μ²)/8` with
//!   `R(δ) = (δ^{−ν} − 1)/(δ − 1) = expm1(−ν ln δ)/expm1(ln δ)`, smooth
//!   through `δ = 1` (`R → −ν`), used where `F ≤ ½` (its second term is
//!   at most a sixteenth of the first, so it cancels less than a bit);
//! * `F_fwd = [δ^{−ν}(1 − s) − (δ − s)]/(1 − δ) + c μ(1 − μ²)/8`, whose
//!   terms are all positive as `θ → 0` (`δ^{−ν}` dominates `δ`), used where
//!   `F > ½` (and as `1 − (1 − s) R(δ)` within ½ of `δ = 1`).
//!
//! The density is `p = (dF/dμ)/(2π)` from the same forms.
//!
//! Sampling solves `F(μ) = u` in f64 in the tail of `min(u, 1 − u)`, in
//! `1 + μ` or `s = (1 − μ)/2`, by Newton steps kept inside a shrinking bracket
//! (bisection where a step leaves it), seeded from the forward power law
//! `F_fwd ≈ δ^{−ν}`.

use super::PhaseFunction;
use crate::error::Error;
use crate::real::Real;

/// Fournier–Forand with relative index `n ∈ (1, 1.8]` and Junge slope
/// `μ_J ∈ (3, 5)` (ocean particles: `n` 1.02–1.2, `μ_J` 3.5–4.5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FournierForand<T> {
    n: T,
    nu: T,
}

impl<T: Real> FournierForand<T> {
    /// The largest relative index accepted: below it `δ₉₀ > 1`, and the
    /// backscatter parameterisation is one to one.
    pub const MAX_N: f64 = 1.8;

    /// From the relative refractive index `n ∈ (1, 1.8]` and the Junge
    /// slope `mu_j ∈ (3, 5)`. [`Error::Domain`] otherwise (NaN fails).
    pub fn new(n: T, mu_j: T) -> Result<Self, Error> {
        let (nf, mf) = (n.to_f64(), mu_j.to_f64());
        if !(nf > 1.0 && nf <= Self::MAX_N && mf > 3.0 && mf < 5.0) {
            return Err(Error::Domain);
        }
        Ok(FournierForand {
            n,
            nu: T::from_f64(0.5 * (3.0 - mf)),
        })
    }

    /// From the backscatter fraction `b = b_b/b ∈ (0, ½)` and `n ∈ (1,
    /// 1.8]`, as oceanographers specify it: `ν = −ln(2b(δ₉₀ − 1) + 1) /
    /// ln δ₉₀` (the backscatter fraction is `R(δ₉₀)/2`). [`Error::Domain`]
    /// outside the ranges, or where `ν` would leave `(−1, 0)`.
    pub fn from_backscatter(b: T, n: T) -> Result<Self, Error> {
        let (bf, nf) = (b.to_f64(), n.to_f64());
        if !(bf > 0.0 && bf < 0.5 && nf > 1.0 && nf <= Self::MAX_N) {
            return Err(Error::Domain);
        }
        let d90 = 2.0 / (3.0 * (nf - 1.0) * (nf - 1.0));
        let nu = -libm::log1p(2.0 * bf * (d90 - 1.0)) / libm::log(d90);
        if !(nu > -1.0 && nu < 0.0) {
            return Err(Error::Domain);
        }
        Ok(FournierForand {
            n,
            nu: T::from_f64(nu),
        })
    }

    /// The relative refractive index `n`.
    pub fn n(&self) -> T {
        self.n
    }
    /// `ν = (3 − μ_J)/2`.
    pub fn nu(&self) -> T {
        self.nu
    }
    /// The backscatter fraction `R(δ₉₀)/2`.
    pub fn backscatter(&self) -> T {
        let k = Ff::new(self.n.to_f64(), self.nu.to_f64());
        T::from_f64(0.5 * k.r(0.5 * k.k))
    }
}

/// The model's constants in f64.
#[derive(Clone, Copy, Debug)]
struct Ff {
    nu: f64,
    /// `δ = k s`, `k = 4/(3(n − 1)²)`.
    k: f64,
    /// `c = (δ₁₈₀^{−ν} − 1)/(δ₁₈₀ − 1) = R(δ₁₈₀)`.
    c: f64,
}

impl Ff {
    fn new(n: f64, nu: f64) -> Ff {
        let k = 4.0 / (3.0 * (n - 1.0) * (n - 1.0));
        let mut f = Ff { nu, k, c: 0.0 };
        f.c = f.r(k);
        f
    }
    /// `R(δ) = (δ^{−ν} − 1)/(δ − 1)`, by `expm1` of `ln δ`: no cancellation
    /// near `δ = 1`, where it tends to `−ν`. `R(0) = 1`.
    fn r(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            return 1.0;
        }
        let l = libm::log(delta);
        if l == 0.0 {
            return -self.nu;
        }
        libm::expm1(-self.nu * l) / libm::expm1(l)
    }
    /// `R'(δ)`: `[−ν δ^{−ν−1}(δ − 1) − (δ^{−ν} − 1)] / (δ − 1)²`, and
    /// `ν(ν + 1)/2` at `δ = 1` (within 10⁻⁴ of it, the series
    /// `ν(ν+1)/2 − ν(ν+1)(ν+2)(δ−1)/6`).
    fn r_prime(&self, delta: f64) -> f64 {
        let nu = self.nu;
        let e = delta - 1.0;
        if e.abs() < 1e-4 {
            return nu * (nu + 1.0) / 2.0 * (1.0 - (nu + 2.0) * e / 3.0);
        }
        let p = libm::pow(delta, -nu);
        (-nu * p / delta * e - (p - 1.0)) / (e * e)
    }
    /// `P(cos θ ≤ μ)` for `μ < 0`: `(1 + μ)/2 · R(δ) − c μ(1 − μ²)/8`.
    fn lower(&self, mu: f64) -> f64 {
        let s = 0.5 * (1.0 - mu);
        (1.0 + mu) * (0.5 * self.r(self.k * s) - self.c / 8.0 * mu * (1.0 - mu))
    }
    /// `F_fwd = P(cos θ ≥ μ)` as a function of `s = (1 − μ)/2 ≤ ½`:
    /// `[δ^{−ν}(1 − s) − (δ − s)]/(1 − δ) + c μ(1 − μ²)/8`; at `s = 0`, 0.
    fn upper(&self, s: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        let delta = self.k * s;
        let mu = 1.0 - 2.0 * s;
        // (δ^{−ν}(1 − s) − (δ − s))/(1 − δ) = 1 − (1 − s) R(δ) rearranged:
        // the form with positive terms is exact as s → 0.
        let main = if (delta - 1.0).abs() < 0.5 {
            1.0 - (1.0 - s) * self.r(delta)
        } else {
            (libm::pow(delta, -self.nu) * (1.0 - s) - (delta - s)) / (1.0 - delta)
        };
        main + self.c / 2.0 * mu * s * (1.0 - s)
    }
    /// `dF/dμ = 2π p` at `μ`: from `F = (1 − s) R(δ) − c μ(1 − μ²)/8` with
    /// `dδ/dμ = −k/2`, `dF/dμ = R/2 − (1 − s) R'(δ) k/2 − c (1 − 3μ²)/8`
    /// (`R' < 0`).
    fn density_mu(&self, mu: f64) -> f64 {
        let s = 0.5 * (1.0 - mu);
        let delta = self.k * s;
        if delta <= 0.0 {
            // The forward pole (ν < 0): infinite density.
            return f64::INFINITY;
        }
        0.5 * self.r(delta)
            - (1.0 - s) * self.r_prime(delta) * 0.5 * self.k
            - self.c / 8.0 * (1.0 - 3.0 * mu * mu)
    }
    /// `P(cos θ ≤ μ)` from the form whose value is the smaller tail.
    fn cdf(&self, mu: f64) -> f64 {
        let lo = self.lower(mu);
        if lo <= 0.5 {
            lo
        } else {
            1.0 - self.upper(0.5 * (1.0 - mu))
        }
    }
    /// The inverse with `sin θ` from the solved variable (`1 + μ` or
    /// `s`), so that f32 directions keep angles `cos θ` in f32 cannot.
    fn inverse_sin(&self, u: f64) -> (f64, f64) {
        if u <= 0.0 || u >= 1.0 || u.is_nan() {
            let mu = self.inverse(u);
            return (mu, 0.0);
        }
        if u <= 0.5 {
            let y = self.solve_lower(u);
            (y - 1.0, libm::sqrt((y * (2.0 - y)).max(0.0)))
        } else {
            let s = self.solve_upper(1.0 - u);
            (1.0 - 2.0 * s, 2.0 * libm::sqrt((s * (1.0 - s)).max(0.0)))
        }
    }
    /// `y = 1 + μ` with `F = u ≤ ½`.
    fn solve_lower(&self, u: f64) -> f64 {
        let f = |y: f64| self.lower(y - 1.0) - u;
        let df = |y: f64| self.density_mu(y - 1.0);
        solve(f, df, 0.0, 2.0, 2.0 * u)
    }
    /// `s = (1 − μ)/2` with `F_fwd = t < ½`; the seed inverts the forward
    /// power law `F_fwd ≈ (k s)^{−ν}`.
    fn solve_upper(&self, t: f64) -> f64 {
        let f = |s: f64| self.upper(s) - t;
        let df = |s: f64| 2.0 * self.density_mu(1.0 - 2.0 * s);
        let seed = (libm::pow(t, -1.0 / self.nu) / self.k).min(0.5);
        solve(f, df, 0.0, 1.0, seed)
    }
    /// The inverse: `μ` with `P(cos θ ≤ μ) = u`, solved in the tail of the
    /// smaller of `u` and `1 − u` (so that the target carries no rounding:
    /// `1 − 0.001` would cost 10⁻¹⁶ in the target and 5·10⁻¹⁴ in `μ` where
    /// the density is 10⁻³).
    fn inverse(&self, u: f64) -> f64 {
        if u <= 0.0 {
            return -1.0;
        }
        if u >= 1.0 {
            return 1.0;
        }
        if u <= 0.5 {
            self.solve_lower(u) - 1.0
        } else {
            1.0 - 2.0 * self.solve_upper(1.0 - u)
        }
    }
}

/// The root in `[lo, hi]` of an increasing `f` with `f(lo) ≤ 0 ≤ f(hi)`:
/// Newton from `x`, kept inside the shrinking bracket (bisection where a
/// step leaves it or the slope is not finite and positive), 100 steps at
/// most, stopping when a step moves by less than 10⁻¹⁷ relative.
fn solve(f: impl Fn(f64) -> f64, df: impl Fn(f64) -> f64, lo: f64, hi: f64, x: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let mut x = if x > lo && x < hi { x } else { 0.5 * (lo + hi) };
    for _ in 0..100 {
        let r = f(x);
        if r == 0.0 {
            return x;
        }
        if r < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let d = df(x);
        let newton = x - r / d;
        let next = if d > 0.0 && d.is_finite() && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - x).abs() <= 1e-17 * x.abs().max(1e-300) || hi - lo <= 1e-300 {
            return next;
        }
        x = next;
    }
    x
}

impl<T: Real> PhaseFunction<T> for FournierForand<T> {
    fn pdf(&self, cos_theta: T) -> T {
        let mu = cos_theta.to_f64();
        if mu.is_nan() {
            return T::NAN;
        }
        let k = Ff::new(self.n.to_f64(), self.nu.to_f64());
        T::from_f64(k.density_mu(mu.clamp(-1.0, 1.0)) / core::f64::consts::TAU)
    }
    fn cdf(&self, cos_theta: T) -> T {
        let mu = cos_theta.to_f64();
        if mu.is_nan() {
            return T::NAN;
        }
        let mu = mu.clamp(-1.0, 1.0);
        let k = Ff::new(self.n.to_f64(), self.nu.to_f64());
        T::from_f64(k.cdf(mu).clamp(0.0, 1.0))
    }
    fn sample_cos(&self, u: T) -> T {
        self.sample_cos_sin(u).0
    }
    /// `sin θ` from the solved variable in f64, so f32 directions keep
    /// the forward lobe's angles that `cos θ` in f32 cannot resolve.
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let u = u.clamp01().to_f64();
        if u.is_nan() {
            return (T::NAN, T::NAN);
        }
        let k = Ff::new(self.n.to_f64(), self.nu.to_f64());
        let (mu, sin) = k.inverse_sin(u);
        (T::from_f64(mu), T::from_f64(sin))
    }
    /// `⟨μ⟩ = ∫₀¹ μ(u) du` by Simpson's rule over 4096 intervals of `u`
    /// (the inverse is smooth in `u` but for its forward end, where `μ → 1`).
    fn mean_cosine(&self) -> T {
        let k = Ff::new(self.n.to_f64(), self.nu.to_f64());
        let n = 4096usize;
        let h = 1.0 / n as f64;
        let mut sum = 0.0;
        for i in 0..=n {
            let c = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            sum += c * k.inverse(i as f64 * h);
        }
        T::from_f64(sum * h / 3.0)
    }
}
