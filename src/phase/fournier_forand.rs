//! The Fournier–Forand phase function of ocean particles (G. R. Fournier,
//! J. L. Forand, "Analytic phase function for ocean water", Proc. SPIE 2258,
//! 1994; with the CDF of Fournier & Jonasz, Proc. SPIE 3761, 1999): for
//! particles of relative refractive index `n` with a Junge (hyperbolic) size
//! distribution of slope `μ_J`, `ν = (3 − μ_J)/2 ∈ (−1, 0)`,
//! `δ = 4 sin²(θ/2) / (3(n − 1)²)`,
//!
//! `p = [ν(1−δ) − (1−δ^ν) + (δ(1−δ^ν) − ν(1−δ)) / sin²(θ/2)] / (4π (1−δ)² δ^ν) +
//!      (δ₁₈₀^{−ν} − 1)/(δ₁₈₀ − 1) (3μ² − 1)/(16π)`.
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
//! `F_fwd ≈ δ^{−ν}` corrected by a 16-node table built with the object.

use super::function::PhaseFunction;
use super::model::{Lobes, Model, exactly, to};
use crate::error::Error;
use crate::math::numeric::newton_bracketed;
use crate::math::real::Real;

/// Fournier–Forand with relative index `n ∈ (1, 1.8]` and Junge slope
/// `μ_J ∈ (3, 5)` (ocean particles: `n` 1.02–1.2, `μ_J` 3.5–4.5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FournierForand<T> {
    n: T,
    nu: T,
    /// The f64 constants every evaluation needs, computed once, as bit
    /// patterns in u32 halves: the f32 phase must keep 4-byte alignment
    /// (the C layer's `sk_phase` is `uint32_t[32]`).
    ff: [u32; 8],
    /// Seeds of the forward solve ([`SEEDS`]).
    seeds: [f32; SEEDS],
}

/// Nodes of the seed table: the correction `ln s − ln s_p` of the exact
/// forward solution over the power law `s_p = F_fwd^{−1/ν}/k`, over the 8
/// e-folds of `F_fwd` below its largest value (`ln(1 − F(0))`, at `μ = 0`),
/// evenly spaced in `√(ln(1 − F(0)) − ln F_fwd)`: the correction is flat
/// far forward, where the power law holds, and climbs steeply near `μ = 0`
/// (to `ln ½ − ln s_p`), within a small fraction of an e-fold for a peaked
/// lobe, where most `u` of the forward solve can lie (evenly spaced nodes
/// left 41 % of them between the last two nodes at `n` = 1.01, `ν` =
/// −0.25). See `the_seed_table_leaves_newton_few_steps` for the steps.
const SEEDS: usize = 16;
/// The span of `ln F_fwd` the seed table covers (below it the power law is
/// exact to the table's accuracy).
const SEED_SPAN: f64 = 8.0;

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
        Ok(Self::from_parts(n, T::from_f64(0.5 * (3.0 - mf))))
    }

    /// From the backscatter fraction `b = b_b/b ∈ [b_min, ½)` and `n ∈ (1,
    /// 1.8]`, as oceanographers specify it: `ν = −ln(2b(δ₉₀ − 1) + 1) /
    /// ln δ₉₀` (the backscatter fraction is `R(δ₉₀)/2`). `b_min` is the
    /// smallest normal value of `T` (`f32::MIN_POSITIVE`, 1.2·10⁻³⁸, or
    /// `f64::MIN_POSITIVE`, 2.2·10⁻³⁰⁸): below it `ν` (about `2b` or
    /// more) would be subnormal, with too few bits for the model to give
    /// back the `b` asked for. `ν` is rounded to `T` and kept inside `(−1,
    /// 0)` (as `b → ½`, `ν → −1`, and its rounding reached −1, outside the
    /// model's domain). [`Error::Domain`] outside the ranges (NaN
    /// fails).
    pub fn from_backscatter(b: T, n: T) -> Result<Self, Error> {
        let (bf, nf) = (b.to_f64(), n.to_f64());
        let b_min = T::MIN_POSITIVE.to_f64();
        if !(bf >= b_min && bf < 0.5 && nf > 1.0 && nf <= Self::MAX_N) {
            return Err(Error::Domain);
        }
        let d90 = 2.0 / (3.0 * (nf - 1.0) * (nf - 1.0));
        // Finite and in (−1, 0) for every b and n accepted here (δ₉₀ ∈
        // [1.04, 1.4·10³¹], so both logarithms are finite and positive),
        // but within a few ulps of b = ½ the quotient can round onto or
        // below −1 (at 1845 of 4001 n for the last f64 below ½): `nu_in`
        // rounds it back inside, where refusing it left holes below ½.
        let nu = -libm::log1p(2.0 * bf * (d90 - 1.0)) / libm::log(d90);
        Ok(Self::from_parts(n, nu_in(nu)))
    }

    /// Without checks (the caller validated `n` and `ν`).
    pub(crate) fn from_parts(n: T, nu: T) -> Self {
        let ff = Ff::new(n.to_f64(), nu.to_f64());
        let mut seeds = [0.0f32; SEEDS];
        let t_max = libm::log1p(-ff.f0);
        for (j, c) in seeds.iter_mut().enumerate() {
            let t = t_max - SEED_SPAN * node_depth(j);
            // The exact solution from the power-law seed (no table yet), as
            // `s` itself: through `μ = 1 − 2s` it lost every digit below
            // 10⁻¹⁷ (and the table its first nodes).
            let s = ff.forward_s(-libm::expm1(t), &[0.0; SEEDS]);
            let power = -t / ff.nu - libm::log(ff.k);
            *c = if s > 0.0 {
                (libm::log(s) - power) as f32
            } else {
                0.0
            };
        }
        FournierForand {
            n,
            nu,
            ff: ff.to_bits(),
            seeds,
        }
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
        T::from_f64(Ff::from_bits(self.ff).f0)
    }
}

/// `ν` rounded to `T` and kept inside `(−1, −T::MIN_POSITIVE]`: a `ν`
/// within half an ulp of −1 rounds onto −1 (the excluded `μ_J = 5`), and
/// one below `T`'s normal range keeps too few bits; each is moved to the
/// nearest value inside, a change no larger than the rounding itself at
/// the −1 end.
fn nu_in<T: Real>(nu: f64) -> T {
    let above_minus_one = -1.0 + 0.5 * T::EPSILON.to_f64();
    let x = T::from_f64(nu).to_f64();
    T::from_f64(x.max(above_minus_one).min(-T::MIN_POSITIVE.to_f64()))
}

/// Node `j`'s depth below the largest `ln F_fwd`, in units of
/// [`SEED_SPAN`]: `((SEEDS − 1 − j)/(SEEDS − 1))²`.
fn node_depth(j: usize) -> f64 {
    let w = 1.0 - j as f64 / (SEEDS - 1) as f64;
    w * w
}

/// The model's constants in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ff {
    nu: f64,
    /// `δ = k s`, `k = 4/(3(n − 1)²)`.
    k: f64,
    /// `c = (δ₁₈₀^{−ν} − 1)/(δ₁₈₀ − 1) = R(δ₁₈₀)`.
    c: f64,
    /// `F(0) = R(δ₉₀)/2`, the backscatter fraction.
    f0: f64,
}

impl Ff {
    fn to_bits(self) -> [u32; 8] {
        let mut out = [0u32; 8];
        for (pair, v) in out
            .chunks_exact_mut(2)
            .zip([self.nu, self.k, self.c, self.f0])
        {
            let b = v.to_bits();
            if let [lo, hi] = pair {
                (*lo, *hi) = (b as u32, (b >> 32) as u32);
            }
        }
        out
    }
    fn from_bits(b: [u32; 8]) -> Ff {
        let f = |i: usize| f64::from_bits(u64::from(b[2 * i]) | (u64::from(b[2 * i + 1]) << 32));
        Ff {
            nu: f(0),
            k: f(1),
            c: f(2),
            f0: f(3),
        }
    }
    fn new(n: f64, nu: f64) -> Ff {
        let k = 4.0 / (3.0 * (n - 1.0) * (n - 1.0));
        let mut f = Ff {
            nu,
            k,
            c: 0.0,
            f0: 0.0,
        };
        f.c = f.r(k);
        f.f0 = 0.5 * f.r(0.5 * k);
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
    /// `R'(δ)`: `[−ν δ^{−ν−1}(δ − 1) − (δ^{−ν} − 1)] / (δ − 1)²`, whose
    /// numerator cancels to second order near `δ = 1`: there the series.
    /// `δ^{−ν}` by `pow` and `δ^{−ν} − 1` by `expm1`, each where the other
    /// cancels: as `pow − 1` the difference lost every digit as `ν → 0`
    /// (`μ_J → 3`, or a backscatter fraction near 0; the density came out
    /// negative, −1.5·10⁻²⁹ for `b = 10⁻³⁰`), and as `1 + expm1` the power
    /// lost its digits where it is tiny (δ → 0 at the forward pole).
    fn r_prime(&self, delta: f64) -> f64 {
        let nu = self.nu;
        let e = delta - 1.0;
        if e.abs() < 1e-3 {
            return self.near_one(e).1;
        }
        let p = libm::pow(delta, -nu);
        let pm1 = libm::expm1(-nu * libm::log(delta));
        (-nu * p / delta * e - pm1) / (e * e)
    }
    /// `(R, R')` at `δ = 1 + e`, `|e| < 10⁻³`, from `δ^{−ν} = Σ C(−ν, j) e^j`:
    /// `R = Σ_{j≥1} C(−ν, j) e^{j−1}`, `R' = Σ_{j≥2} (j − 1) C(−ν, j) e^{j−2}`;
    /// eight terms leave less than 10⁻¹⁸ (`|C(−ν, j)| ≤ 1`).
    fn near_one(&self, e: f64) -> (f64, f64) {
        let mut b = -self.nu; // C(−ν, 1)
        let (mut r, mut rp, mut pow) = (0.0, 0.0, 1.0); // pow = e^{j−1}
        for j in 1..=8 {
            let jf = j as f64;
            r += b * pow;
            if j >= 2 {
                rp += (jf - 1.0) * b * pow / e;
            }
            b *= (-self.nu - jf) / (jf + 1.0);
            pow *= e;
        }
        (
            r,
            if e == 0.0 {
                self.nu * (self.nu + 1.0) / 2.0
            } else {
                rp
            },
        )
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
        self.density_at(0.5 * (1.0 - mu), mu)
    }
    /// [`density_mu`](Self::density_mu) at `s = (1 − μ)/2` and `μ` given
    /// both (a sampled angle knows `s` more closely than `1 − μ` does).
    fn density_at(&self, s: f64, mu: f64) -> f64 {
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
    /// `(F, F_fwd, dF/dμ)` at `s = (1 − μ)/2`, sharing one `ln δ` and two
    /// `expm1` between the CDF (both forms) and the density: `F` is exact
    /// where it is the smaller tail, `F_fwd` where it is.
    fn eval(&self, s: f64) -> (f64, f64, f64) {
        if s <= 0.0 {
            return (1.0, 0.0, f64::INFINITY);
        }
        self.eval_ln(s, libm::log(self.k * s))
    }
    /// [`eval`](Self::eval) with `ln δ = l` given (the forward solve works
    /// in `ln s`, so `ln δ = ln k + ln s` costs no logarithm).
    fn eval_ln(&self, s: f64, l: f64) -> (f64, f64, f64) {
        let (nu, k, c) = (self.nu, self.k, self.c);
        let delta = k * s;
        let mu = 1.0 - 2.0 * s;
        if delta <= 0.0 {
            return (1.0, 0.0, f64::INFINITY);
        }
        let (e1, e2) = (libm::expm1(-nu * l), libm::expm1(l));
        let (r, rp) = if (delta - 1.0).abs() < 1e-3 {
            self.near_one(delta - 1.0)
        } else {
            (e1 / e2, (-nu * (1.0 + e1) / delta * e2 - e1) / (e2 * e2))
        };
        let poly = 0.5 * c * mu * s * (1.0 - s);
        let lower = (1.0 - s) * r - poly;
        let upper = if (delta - 1.0).abs() < 0.5 {
            1.0 - (1.0 - s) * r + poly
        } else {
            ((1.0 + e1) * (1.0 - s) - (delta - s)) / (1.0 - delta) + poly
        };
        let rho = 0.5 * r - (1.0 - s) * rp * 0.5 * k - c / 8.0 * (1.0 - 3.0 * mu * mu);
        (lower, upper, rho)
    }
    /// The inverse, `μ` with `P(cos θ ≤ μ) = u`, solved in the tail of
    /// the smaller of `u` and `1 − u` (so that the target carries no
    /// rounding: `1 − 0.001` would cost 10⁻¹⁶ in the target and 5·10⁻¹⁴ in
    /// `μ` where the density is 10⁻³), with `sin θ` from the solved
    /// variable (`1 + μ` or `s`), so that f32 directions keep angles `cos θ`
    /// in f32 cannot.
    fn inverse_sin(&self, u: f64, seeds: &[f32; SEEDS]) -> (f64, f64) {
        if !(u > 0.0 && u < 1.0) {
            return (
                if u >= 1.0 {
                    1.0
                } else if u <= 0.0 {
                    -1.0
                } else {
                    f64::NAN
                },
                0.0,
            );
        }
        let f0 = self.f0;
        if u <= f0 {
            // Backward hemisphere, y = 1 + μ ∈ [0, 1]: F rises from 0 to F(0)
            // nearly in proportion to y (the density varies little there).
            let fd = |y: f64| {
                let (f, _, rho) = self.eval(1.0 - 0.5 * y);
                (f - u, rho)
            };
            let y = newton_bracketed(fd, 0.0, 1.0, u / f0);
            return (y - 1.0, libm::sqrt((y * (2.0 - y)).max(0.0)));
        }
        let s = self.forward_s(u, seeds);
        (1.0 - 2.0 * s, 2.0 * libm::sqrt((s * (1.0 - s)).max(0.0)))
    }
    /// The forward hemisphere's inverse, `s = (1 − μ)/2` with `P(cos θ ≤
    /// μ) = u` for `u ∈ (F(0), 1)`: Newton in x = ln s (where ln δ = ln k +
    /// x costs no logarithm), seeded by the forward power law F_fwd ≈ (k
    /// s)^{−ν} corrected by the seed table. Each tail in its own form: u −
    /// F (u ≤ ½) or F_fwd − (1 − u), both exact targets.
    fn forward_s(&self, u: f64, seeds: &[f32; SEEDS]) -> f64 {
        let (fd, lt) = self.forward_problem(u);
        self.solve_log(fd, lt, seeds)
    }
    /// [`forward_s`](Self::forward_s)'s equation in `x = ln s`, `(residual,
    /// slope)`, and the log of its forward mass `1 − u` (for the seed).
    fn forward_problem(&self, u: f64) -> (impl Fn(f64) -> (f64, f64) + '_, f64) {
        let (low, t, ln_k) = (u <= 0.5, 1.0 - u, libm::log(self.k));
        let fd = move |x: f64| {
            let s = libm::exp(x);
            let (f, g, rho) = self.eval_ln(s, ln_k + x);
            (if low { u - f } else { g - t }, 2.0 * s * rho)
        };
        (fd, if low { libm::log1p(-u) } else { libm::log(t) })
    }
    /// The floor of `x = ln s`: below it `s` is 0.
    const LN_S_MIN: f64 = -745.0;
    /// `s ∈ [0, ½]` from Newton in `x = ln s` on an increasing function,
    /// at forward mass `e^{lt}`, seeded by the power law `s ≈
    /// e^{−lt/ν}/k` corrected by the seed table (zeros: none). Below
    /// `e^{−745}` (a forward lobe beyond f64), `s = 0`.
    fn solve_log(&self, fd: impl Fn(f64) -> (f64, f64), lt: f64, seeds: &[f32; SEEDS]) -> f64 {
        const LO: f64 = Ff::LN_S_MIN;
        let hi = -core::f64::consts::LN_2;
        let t_max = libm::log1p(-self.f0);
        // The node position, inverting `node_depth`.
        let depth = ((t_max - lt) / SEED_SPAN).clamp(0.0, 1.0);
        let pos = (SEEDS - 1) as f64 * (1.0 - libm::sqrt(depth));
        let j = (pos as usize).min(SEEDS - 2);
        let f = pos - j as f64;
        let corr = match (seeds.get(j), seeds.get(j + 1)) {
            (Some(&a), Some(&b)) => f64::from(a) + f * (f64::from(b) - f64::from(a)),
            _ => 0.0,
        };
        let seed = -lt / self.nu - libm::log(self.k) + corr;
        // A root within an e-fold of the floor is s = 0: the lobe lies
        // below f64's range. Where the seed says so, one evaluation there
        // decides, without the bisection down to it (50 evaluations where
        // `ν → 0`); a seed on an end of the bracket would start Newton at
        // its midpoint, so it starts just inside.
        let floor = LO + 1.0;
        if seed < floor + 1.0 && fd(floor).0 >= 0.0 {
            return 0.0;
        }
        let x = newton_bracketed(fd, LO, hi, seed.clamp(floor, hi - 1e-9));
        if x <= floor { 0.0 } else { libm::exp(x) }
    }
    /// `1 − ⟨μ⟩`, without cancellation. By parts, `∫₋₁¹ μ dF = 1 −
    /// ∫₋₁¹ F dμ`; of `F = (1 − s) R(δ) − c μ(1 − μ²)/8` the odd term
    /// integrates to 0, so (`dμ = −2 ds`) `1 − ⟨μ⟩ = 2 ∫₀¹ (1 − s) R(k s)
    /// ds`: a positive integrand, with `R` by `expm1` (`−ν` times a finite
    /// function as `ν → 0`, where `⟨μ⟩ → 1`). The tanh–sinh rule
    /// (Takahasi & Mori 1974) in `s = 1/(1 + e^{−π sinh t})`, whose nodes
    /// crowd double exponentially into the branch point `s^{−ν}` at `s =
    /// 0`: step 1/32 over `t ∈ [−4, 3.19]` (`s` down to 10⁻³⁷, below `1/k`
    /// for every f64 `n > 1`; past 3.19 the integrand is below 10⁻³²).
    /// `⟨μ⟩` comes out within 4.4·10⁻¹⁶ of 40-digit quadrature of the
    /// published density (tests/models/fournier_forand.rs). Simpson's rule over `u`
    /// of the inverse, before, was 1.5·10⁻⁴ high in `1 − ⟨μ⟩` as `ν → 0`,
    /// where the inverse is a step at `u = 1`.
    fn one_minus_mean(&self) -> f64 {
        const H: f64 = 1.0 / 32.0;
        let mut sum = 0.0;
        for j in -128..=102 {
            let t = f64::from(j) * H;
            let u = core::f64::consts::PI * libm::sinh(t);
            // s and 1 − s each from e^{−|u|}: neither cancels.
            let e = libm::exp(-u.abs());
            let (small, large) = (e / (1.0 + e), 1.0 / (1.0 + e));
            let (s, rest) = if u < 0.0 {
                (small, large)
            } else {
                (large, small)
            };
            let ds_dt = core::f64::consts::PI * libm::cosh(t) * s * rest;
            sum += ds_dt * rest * self.r(self.k * s);
        }
        2.0 * H * sum
    }
}

/// The density of `μ` (`2π p`, per unit `cos θ`) of Fournier–Forand with
/// index `n` and `ν`, unchecked: for the fits of `particle_mie`.
pub(crate) fn density_of_mu(n: f64, nu: f64) -> impl Fn(f64) -> f64 {
    let ff = Ff::new(n, nu);
    move |mu| ff.density_mu(mu)
}

impl<T: Real> PhaseFunction<T> for FournierForand<T> {
    fn pdf(&self, cos_theta: T) -> T {
        let mu = cos_theta.to_f64();
        if mu.is_nan() {
            return T::NAN;
        }
        let k = Ff::from_bits(self.ff);
        T::from_f64(k.density_mu(mu.clamp(-1.0, 1.0)) / core::f64::consts::TAU)
    }
    fn cdf(&self, cos_theta: T) -> T {
        let mu = cos_theta.to_f64();
        if mu.is_nan() {
            return T::NAN;
        }
        let mu = mu.clamp(-1.0, 1.0);
        let k = Ff::from_bits(self.ff);
        T::from_f64(k.cdf(mu).clamp(0.0, 1.0))
    }
    fn sample_cos(&self, u: T) -> T {
        self.sample_cos_sin(u).0
    }
    /// The density at `s = (1 − μ)/2` taken from `sin θ` in the forward
    /// hemisphere, `s = sin²θ/(2(1 + μ))`: near `ν = 0` the sampler puts
    /// many of its samples within an ulp of `μ = 1` (half of them at `n =
    /// 1.01`, `μ_J = 3.05`), where `cos θ` rounds to 1 and
    /// [`pdf`](Self::pdf) is the pole's ∞, while `sin θ` keeps the angle
    /// and its finite density.
    fn pdf_cos_sin(&self, cos_theta: T, sin_theta: T) -> T {
        let (mu, sin) = (cos_theta.to_f64(), sin_theta.to_f64());
        if !(mu > 0.0 && mu <= 1.0 && sin > 0.0) {
            return self.pdf(cos_theta);
        }
        let s = sin * sin / (2.0 * (1.0 + mu));
        let k = Ff::from_bits(self.ff);
        T::from_f64(k.density_at(s, mu) / core::f64::consts::TAU)
    }
    /// `sin θ` from the solved variable in f64, so f32 directions keep
    /// the forward lobe's angles that `cos θ` in f32 cannot resolve.
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let u = u.clamp01().to_f64();
        if u.is_nan() {
            return (T::NAN, T::NAN);
        }
        let k = Ff::from_bits(self.ff);
        let (mu, sin) = k.inverse_sin(u, &self.seeds);
        (T::from_f64(mu), T::from_f64(sin))
    }
    /// `⟨μ⟩ = 1 − (1 − ⟨μ⟩)`, the difference by a quadrature of a
    /// positive integrand (see `one_minus_mean`).
    fn mean_cosine(&self) -> T {
        T::from_f64(1.0 - Ff::from_bits(self.ff).one_minus_mean())
    }
}

impl<T: Real> Model<T> for FournierForand<T> {
    type In<U: Real> = FournierForand<U>;
    const PARAMS: usize = 3;
    fn params(&self) -> [T; 4] {
        [self.n, self.nu, self.backscatter(), T::ZERO]
    }
    /// From `(n, ν, b)` as reported: `n ∈ (1, 1.8]`, `ν ∈ (−1,
    /// −T::MIN_POSITIVE]` (a subnormal `ν` keeps too few bits: see
    /// [`FournierForand::from_backscatter`]); `b` follows from them and is
    /// not read.
    fn from_params(p: &[T]) -> Result<Self, Error> {
        let [n, nu, _] = exactly(p)?;
        let (nf, nuf) = (n.to_f64(), nu.to_f64());
        let top = -T::MIN_POSITIVE.to_f64();
        if !(nf > 1.0 && nf <= Self::MAX_N && nuf > -1.0 && nuf <= top) {
            return Err(Error::Domain);
        }
        Ok(Self::from_parts(n, nu))
    }
    fn cast<U: Real>(&self) -> FournierForand<U> {
        // ν rounded into U's part of (−1, 0): exact from f32 to f64 (a
        // fixed clamp to [−1 + 10⁻⁷, −10⁻³⁰] moved an f32 ν near either
        // end, and the f64 twin the tests hold f32 to was another model).
        FournierForand::from_parts(to(self.n), nu_in(self.nu.to_f64()))
    }
    fn lobes(&self) -> Option<Lobes> {
        None
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use core::cell::Cell;

    /// Newton's evaluations in `forward_s` at `u` with `seeds`, and its
    /// answer; and whether the root lies below the floor's e-fold.
    fn evaluations(ff: &Ff, u: f64, seeds: &[f32; SEEDS]) -> (usize, f64, bool) {
        let calls = Cell::new(0);
        let (fd, lt) = ff.forward_problem(u);
        let counted = |x: f64| {
            calls.set(calls.get() + 1);
            fd(x)
        };
        let s = ff.solve_log(counted, lt, seeds);
        (calls.get(), s, fd(Ff::LN_S_MIN + 1.0).0 >= 0.0)
    }

    /// The seed table does what its docs say: over the span it covers
    /// (`ln F_fwd` within 8 of its largest value, 200 points), the seeded
    /// Newton takes at most 4 evaluations wherever `s` is normal, no more
    /// in all than the power law alone (within 3 %: where `ν → 0` the
    /// power law is all but exact), and lands on the same root; an answer
    /// of 0 (a lobe below f64) is right. A table built wrong, read at the
    /// wrong node or not at all still solves, only slower: only this sees
    /// it. (With nodes evenly spaced in `ln F_fwd` and `s` through `μ`: up
    /// to 9 at `n` = 1.01, `ν` = −0.25, and 528 in all against 427 with no
    /// table.)
    #[test]
    fn the_seed_table_leaves_newton_few_steps() {
        for n in [1.01, 1.05, 1.1, 1.2, 1.8] {
            for nu in [-0.999, -0.75, -0.5, -0.25, -0.01, -1e-6] {
                let obj = FournierForand::<f64>::from_parts(n, nu);
                let ff = Ff::from_bits(obj.ff);
                let t_max = libm::log1p(-ff.f0);
                let (mut most, mut with, mut without) = (0, 0, 0);
                // From just below ln(1 − F(0)) (F(0) itself is the
                // backward solve's).
                for i in 1..=200 {
                    let lt = t_max - SEED_SPAN * (i as f64 / 200.0);
                    let u = -libm::expm1(lt);
                    let (a, s, below_floor) = evaluations(&ff, u, &obj.seeds);
                    assert!(
                        s != 0.0 || below_floor,
                        "n {n}, ν {nu}, ln F_fwd {lt}: s = 0"
                    );
                    let (b, s_plain, _) = evaluations(&ff, u, &[0.0; SEEDS]);
                    // The same root to the solver's tolerance in x = ln s.
                    let (x, x_plain) = (libm::log(s), libm::log(s_plain));
                    assert!(
                        s == s_plain || (x - x_plain).abs() <= 1e-12 * x_plain.abs().max(1.0),
                        "n {n}, ν {nu}, ln F_fwd {lt}: ln s {x} against {x_plain}"
                    );
                    // Subnormal s (ν → 0) is left to bisection: exp(x)
                    // there has too few bits for Newton's steps in x.
                    if s == 0.0 || s >= f64::MIN_POSITIVE {
                        most = most.max(a);
                    }
                    (with, without) = (with + a, without + b);
                }
                std::println!("n {n}, ν {nu}: at most {most}, {with} against {without} without");
                assert!(most <= 4, "n {n}, ν {nu}: {most} evaluations");
                assert!(
                    with as f64 <= 1.03 * without as f64,
                    "n {n}, ν {nu}: {with} against {without}"
                );
            }
        }
    }
    /// `R(δ)` at `δ = 1` exactly (`ln δ = 0`, where the quotient is `0/0`
    /// and `R` takes its limit `−ν`): the CDF and density there match
    /// their neighbours a float away, at each `n` where some `μ` gives
    /// `k s = 1` exactly, in both of the CDF's forms.
    #[test]
    fn the_cdf_and_density_are_continuous_through_delta_one() {
        let mut found = 0;
        // μ_J = 3.5 puts δ = 1 where the CDF is its lower form, 4.5 (the
        // forward mass there `≈ 1 + ν = ¼`) where it is 1 − the upper one.
        for (n, mu_j) in [1.05, 1.1, 1.15, 1.2, 1.3, 1.4, 1.5, 1.6, 1.8]
            .into_iter()
            .flat_map(|n| [(n, 3.5), (n, 4.5)])
        {
            let obj = FournierForand::<f64>::new(n, mu_j).unwrap();
            let ff = Ff::from_bits(obj.ff);
            let start = (1.0 - 2.0 / ff.k).to_bits();
            let Some(mu) = (start - 64..start + 64)
                .map(f64::from_bits)
                .find(|&m| ff.k * (0.5 * (1.0 - m)) == 1.0)
            else {
                continue;
            };
            found += 1;
            let (below, above) = (
                f64::from_bits(mu.to_bits() - 1),
                f64::from_bits(mu.to_bits() + 1),
            );
            for (what, f) in [
                ("cdf", &(|m: f64| obj.cdf(m)) as &dyn Fn(f64) -> f64),
                ("pdf", &|m: f64| obj.pdf(m)),
            ] {
                let (a, b, c) = (f(below), f(mu), f(above));
                let near = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
                assert!(
                    near(b, a) && near(b, c),
                    "n {n}, μ {mu}: {what} {a}, {b}, {c}"
                );
            }
        }
        assert!(found >= 6, "only {found} objects have k s = 1 exactly");
    }
}
