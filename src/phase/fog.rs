//! The fog phase function of Jendersie & d'Eon (2023, SIGGRAPH Talks and its
//! supplemental): a mixture of
//! Henyey–Greenstein and Draine,
//! `p_fog = (1 − w_D) p_HG(g_HG) + w_D p_D(g_D, α)`,
//! with their fits of the four parameters to Mie scattering by water droplets
//! of diameter `d` (0 < d ≤ 50 µm).
//!
//! Two samplers:
//! * [`PhaseFunction::sample_cos`] is the exact inverse of the mixture's CDF,
//!   monotone in `u` as the crate promises: a safeguarded Halley iteration
//!   on the mixture's CDF (f64, solved in the smaller tail), seeded from a
//!   table of the inverse built with the object.
//! * [`Fog::sample_cos_by_lobe`] is the paper's sampler: one uniform picks
//!   the lobe (Draine when `u < w_D`) and is rescaled and reused inside it.
//!   Cheaper, exact in distribution, but not monotone in `u` and not the
//!   inverse of [`PhaseFunction::cdf`].

use super::PhaseFunction;
use super::draine::{Params, from_tail, inverse_tail};
use super::seeds::Seeds;
use crate::double_double::Dd;
use crate::error::Error;
use crate::numeric::{Eval, solve_bracketed};
use crate::real::Real;

/// The fog mixture. Built from its four parameters or from a droplet
/// diameter ([`Fog::from_diameter`]); construction also tabulates the seeds
/// of its inverse (8–14 µs measured): build it once per medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog<T> {
    g_hg: T,
    g_d: T,
    alpha: T,
    w_d: T,
    /// Seeds of the exact inverse (`phase::seeds`): with them the Halley
    /// iteration on the mixture converges in two steps for 97 % of `u` at
    /// 2 µm (three otherwise), and the lobes' own quantiles, one of them an
    /// iterative solve, are no longer needed as a bracket: 1.8× the paper's
    /// lobe choice instead of 5×.
    seeds: Seeds,
}

/// The four fitted parameters of the fog phase function at one diameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FogParams {
    /// Henyey–Greenstein lobe's `g`.
    pub g_hg: f64,
    /// Draine lobe's `g`.
    pub g_d: f64,
    /// Draine lobe's `α`.
    pub alpha: f64,
    /// Weight of the Draine lobe, `w_D`.
    pub w_d: f64,
}

/// Jendersie & d'Eon's fits (supplemental §3) for droplet diameter `d` in µm,
/// `0 < d ≤ 50`; [`Error::Domain`] outside (or for NaN). Natural logarithms.
pub fn fog_fit(d: f64) -> Result<FogParams, Error> {
    if !(d > 0.0 && d <= 50.0) {
        return Err(Error::Domain);
    }
    let ln = libm::log;
    let p = if d <= 0.1 {
        FogParams {
            g_hg: 13.8 * d * d,
            g_d: 1.1456 * d * libm::sin(9.29044 * d),
            alpha: 250.0,
            w_d: 0.252977 - 312.983 * libm::pow(d, 4.3),
        }
    } else if d < 1.5 {
        let l = ln(d);
        let inner = (l - 0.238604) * (l + 1.00667) / (0.507522 - 0.15677 * l);
        FogParams {
            g_hg: 0.862 - 0.143 * l * l,
            g_d: 0.379685 * libm::cos(1.19692 * libm::cos(inner) + 1.37932 * l + 0.0625835)
                + 0.344213,
            alpha: 250.0,
            w_d: 0.146209 * libm::cos(3.38707 * l + 2.11193) + 0.316072 + 0.0778917 * l,
        }
    } else if d < 5.0 {
        let l = ln(d);
        let ll = ln(l);
        FogParams {
            g_hg: 0.0604931 * ll + 0.940256,
            g_d: 0.500411 - 0.081287 / (-2.0 * l + libm::tan(l) + 1.27551),
            alpha: 7.30354 * l + 6.31675,
            w_d: 0.026914 * (l - libm::cos(5.68947 * (ll - 0.0292149))) + 0.376475,
        }
    } else {
        FogParams {
            g_hg: libm::exp(-0.0990567 / (d - 1.67154)),
            g_d: libm::exp(-2.20679 / (d + 3.91029) - 0.428934),
            alpha: libm::exp(3.62489 - 8.29288 / (d + 5.52825)),
            w_d: libm::exp(-0.599085 / (d - 0.641583) - 0.665888),
        }
    };
    Ok(p)
}

impl<T: Real> Fog<T> {
    /// Fails with [`Error::Domain`] unless `|g_hg| < 1`, `|g_d| < 1`,
    /// `0 ≤ alpha < ∞` and `0 ≤ w_d ≤ 1` (NaN fails).
    pub fn new(g_hg: T, g_d: T, alpha: T, w_d: T) -> Result<Self, Error> {
        let g_ok = |g: T| g > -T::ONE && g < T::ONE;
        let ok = g_ok(g_hg)
            && g_ok(g_d)
            && alpha >= T::ZERO
            && alpha.is_finite()
            && w_d >= T::ZERO
            && w_d <= T::ONE;
        if ok {
            Ok(Self::from_parts(g_hg, g_d, alpha, w_d))
        } else {
            Err(Error::Domain)
        }
    }

    /// The fitted fog phase function for water droplets of diameter
    /// `diameter_um` µm, `0 < d ≤ 50` ([`fog_fit`]).
    ///
    /// # Example
    ///
    /// ```
    /// use scatterkit::{Fog, PhaseFunction};
    ///
    /// let fog = Fog::<f64>::from_diameter(2.0).unwrap();
    /// // Strongly forward, like the Mie phase function it fits.
    /// assert!(fog.mean_cosine() > 0.5);
    /// // The monotone inverse CDF: F(μ(u)) = u.
    /// let mu = fog.sample_cos(0.3);
    /// assert!((fog.cdf(mu) - 0.3).abs() < 1e-12);
    /// assert!(Fog::<f64>::from_diameter(60.0).is_err());
    /// ```
    pub fn from_diameter(diameter_um: T) -> Result<Self, Error> {
        let p = fog_fit(diameter_um.to_f64())?;
        let t = T::from_f64;
        Self::new(t(p.g_hg), t(p.g_d), t(p.alpha), t(p.w_d))
    }

    /// A mixture from parameters already known to be valid.
    pub(crate) fn from_parts(g_hg: T, g_d: T, alpha: T, w_d: T) -> Self {
        let mut fog = Fog {
            g_hg,
            g_d,
            alpha,
            w_d,
            seeds: Seeds::NONE,
        };
        let (h, d, w) = fog.lobes();
        let oriented = |m: bool| {
            if m {
                (h.mirrored(), d.mirrored())
            } else {
                (h, d)
            }
        };
        fog.seeds = Seeds::build(
            |m| {
                let (h, d) = oriented(m);
                mixture(h, d, w, 0.0).density
            },
            |m, t| {
                let (h, d) = oriented(m);
                tail_by_lobes::<f64>(h, d, w, t)
            },
        );
        fog
    }

    /// The four parameters `(g_hg, g_d, alpha, w_d)`.
    pub fn params(&self) -> (T, T, T, T) {
        (self.g_hg, self.g_d, self.alpha, self.w_d)
    }

    /// The lobes as f64 Draine parameters (HG is Draine with α = 0).
    fn lobes(&self) -> (Params, Params, f64) {
        (
            Params::new(self.g_hg.to_f64(), 0.0),
            Params::new(self.g_d.to_f64(), self.alpha.to_f64()),
            self.w_d.to_f64(),
        )
    }

    /// The exact inverse of the mixture's CDF, in f64 (module docs):
    /// `(cos θ, sin θ)`, solved for `1 + μ` in the smaller tail from the
    /// tabulated seed.
    fn inverse(&self, u: T) -> (f64, f64) {
        let u = u.clamp01().to_f64();
        // Solve in the smaller tail (mirror both lobes for u > 1/2).
        let (sign, target, mirrored) = if u > 0.5 {
            (-1.0, 1.0 - u, true)
        } else {
            (1.0, u, false)
        };
        let h = Params::new(sign * self.g_hg.to_f64(), 0.0);
        let d = Params::new(sign * self.g_d.to_f64(), self.alpha.to_f64());
        let w = self.w_d.to_f64();
        if target.is_nan() {
            return (f64::NAN, f64::NAN);
        }
        let seed = self.seeds.y(mirrored, target);
        let mut y = solve_bracketed::<T>(|y| mixture(h, d, w, y), target, seed, 0.0, 2.0);
        if self.alpha == T::ZERO && T::EPSILON.to_f64() < 1e-10 {
            let g = (sign * self.g_hg.to_f64(), sign * self.g_d.to_f64());
            y = polish_two_hg(g, w, target, y, mixture(h, d, w, y).density);
        }
        from_tail(y, mirrored)
    }

    /// The paper's sampler (Jendersie & d'Eon 2023): the Draine lobe when
    /// `u < w_D` (or `w_D = 1`), with `u/w_D` reused inside it, else HG with
    /// `(u − w_D)/(1 − w_D)`. Exact in distribution; not monotone in `u`. `u`
    /// is clamped to `[0, 1]`. The HG lobes take HG's factored forms in `T`
    /// (within 3·10⁻⁷ in f32), whose constants cost no division per sample.
    pub fn sample_cos_by_lobe(&self, u: T) -> T {
        let (u, w) = (u.clamp01(), self.w_d);
        // `w = 1` takes the first lobe at u = 1 too, so neither branch
        // divides by a zero weight (at u = 1, `(u − w)/(1 − w)` was 0/0).
        if u < w || w == T::ONE {
            let v = u / w;
            if self.alpha == T::ZERO {
                // Draine with α = 0 is HG: the closed form, not Draine's solve
                // (a two-lobe HG samples both lobes this way).
                return super::HenyeyGreenstein::sample_cos_factored(self.g_d, v);
            }
            super::Draine::lobe(self.g_d, self.alpha).sample_cos(v)
        } else {
            super::HenyeyGreenstein::sample_cos_factored(self.g_hg, (u - w) / (T::ONE - w))
        }
    }
}

/// The tail solution `y = 1 + F⁻¹(t)`, `t ≤ ½`, bracketed by the lobes' own
/// quantiles (the mixture's quantile lies between them): the reference the
/// seeds are built from.
fn tail_by_lobes<T: Real>(h: Params, d: Params, w: f64, target: f64) -> f64 {
    let a = inverse_tail::<T>(h, target);
    let b = inverse_tail::<T>(d, target);
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    let seed = (1.0 - w) * a + w * b;
    solve_bracketed::<T>(|y| mixture(h, d, w, y), target, seed, lo, hi)
}

/// One Newton step for two HG lobes (`g = (g_hg, g_d)`, `α = 0`) with the
/// residual `target − F(y)` formed in double-double. Where the lobes point
/// apart the density between them is small and `y(u)` amplifies the f64
/// rounding of `F` (a few ε) by `1/F'(y)` (2.8·10⁻¹³ at `g = ∓0.999`,
/// `w = ½`); with the residual exact to ~10⁻³⁰ the step leaves an error of
/// order `(F''/2F') Δy²`, far below f64 rounding of `μ`.
fn polish_two_hg(g: (f64, f64), w: f64, target: f64, y: f64, density: f64) -> f64 {
    if density.is_nan() || density <= 0.0 {
        return y;
    }
    let f = Dd::sum(1.0, -w) * hg_tail_cdf_dd(g.0, y) + Dd::from(w) * hg_tail_cdf_dd(g.1, y);
    let r = (Dd::from(target) - f).hi;
    (y + r / density).clamp(0.0, 2.0)
}

/// Henyey–Greenstein's CDF at `y = 1 + μ` in double-double:
/// `F = (1 − g) y / (s (1 + g + s))`, `s² = 1 + g² − 2gμ = (1 + g)² − 2gy`.
/// The subtraction in `s²`, which cancels as `g → 1`, `y → 2`, is exact in
/// double-double because its operands are.
fn hg_tail_cdf_dd(g: f64, y: f64) -> Dd {
    let opg = Dd::sum(1.0, g);
    let s = (opg * opg - Dd::product(2.0 * g, y)).sqrt();
    Dd::sum(1.0, -g) * Dd::from(y) / (s * (opg + s))
}

/// `F`, `F'`, `F''` of the mixture at `y = 1 + μ` (`h` has `α = 0`).
#[inline(always)]
fn mixture(h: Params, d: Params, w: f64, y: f64) -> Eval {
    let (a, b) = (h.eval_y_hg(y), d.eval_y(y));
    let mix = |p: f64, q: f64| (1.0 - w) * p + w * q;
    Eval {
        cdf: mix(a.cdf, b.cdf),
        density: mix(a.density, b.density),
        slope: mix(a.slope, b.slope),
    }
}

impl<T: Real> PhaseFunction<T> for Fog<T> {
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        let (h, d, w) = self.lobes();
        T::from_f64(mixture(h, d, w, 1.0 + cos_theta.to_f64()).density / core::f64::consts::TAU)
    }
    #[inline]
    fn cdf(&self, cos_theta: T) -> T {
        let (h, d, w) = self.lobes();
        T::from_f64(
            mixture(h, d, w, 1.0 + cos_theta.to_f64().clamp(-1.0, 1.0))
                .cdf
                .clamp(0.0, 1.0),
        )
    }
    fn sample_cos(&self, u: T) -> T {
        T::from_f64(self.inverse(u).0)
    }
    /// `sin θ` from the f64 solution, so forward lobes keep angles that
    /// `cos θ` in f32 cannot resolve (see [`Draine`](super::Draine)).
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let (mu, sin) = self.inverse(u);
        (T::from_f64(mu), T::from_f64(sin))
    }
    /// `(1 − w_D) g_HG + w_D ⟨cos θ⟩_Draine`.
    fn mean_cosine(&self) -> T {
        let draine = super::Draine::lobe(self.g_d, self.alpha);
        let w = self.w_d;
        (T::ONE - w) * self.g_hg + w * draine.mean_cosine()
    }
}
