//! Draine's phase function (Draine, ApJ 598, 2003; Jendersie & d'Eon 2023, supplemental
//! §2.2), with Cornette–Shanks as α = 1 and Henyey–Greenstein as α = 0:
//!
//! `p(μ) = (1/4π) (1 − g²)/(1 + g² − 2gμ)^{3/2} · (1 + αμ²)/(1 + α(1 + 2g²)/3)`.
//!
//! # Sampling, accurate on the whole domain
//! The published closed form (eq. 6, [`sample_cos_eq6`]) divides by `g` and by
//! `α`, cancels for small `|g|` and large `α`, and is NaN at `g = 0`, at
//! `α = 0` and (in f32) from α ≈ 1000. We solve `F(μ) = u` instead, in f64:
//!
//! 1. **A CDF that does not cancel** (our rearrangement of the
//!    supplemental's CDF): with `s = sqrt(1 + g² − 2gμ)`,
//!    `s0 = 1 + g`, `e = (1 + μ)/(s + s0)`,
//!    `F = N (I0 + α I2)`, `I0 = 2e/(s s0)`,
//!    `I2 = 2e (3 − 6 s0 e + 4 s0² e² − 2g s0 e³)/(3 s s0)`,
//!    `N = (1 − g)(1 + g)/(2 (1 + α(1 + 2g²)/3))`: every term is a product of
//!    positive factors or an alternating sum bounded away from cancellation,
//!    and `F` is accurate relative to itself near `μ = −1`.
//! 2. **The small tail.** For `u > 1/2` we solve the mirror problem
//!    `F_{−g}(ν) = 1 − u`, `μ = −ν` (the density is symmetric under
//!    `(g, μ) → (−g, −μ)`); `1 − u` is exact there, and so `F` is always
//!    evaluated where it is small and relatively accurate.
//! 3. **A seed**: eq. 6 evaluated in f64 with its three cancellations
//!    removed (where `t5` changes sign, `t5 < 0` in the resolvent, and
//!    `g → 1`; the `Eq6` type in the source), for `|g| ≥ 10⁻³`; or the
//!    exact `g = 0` solution (a depressed cubic) for smaller `|g|`, or when
//!    eq. 6 is not finite. For f32 results where this seed is already
//!    within 2.2·10⁻¹² (`|g| ≥ 10⁻³`, `10⁻⁴ ≤ α ≤ 10⁴`), it is the
//!    answer. Such an object computes
//!    eq. 6's constants (everything that does not depend on `u`, for both
//!    orientations) when it is built, so that a sample costs only the chain
//!    from `u` on: a square root, a cube root (two Lancaster steps, a
//!    division each), two more square roots and two more divisions
//!    (0.95–1.1× eq. 6 in f32 through the C ABI, at α from 1 to 1000).
//!    f32 objects outside that region with `α > 10` (`|g| < 10⁻³`, or
//!    `α > 10⁴`) seed the iteration from a table of the inverse built with
//!    the object (`phase::seeds`) instead.
//! 4. **Halley's method safeguarded by bisection** on `[−1, 1]`: a step that
//!    leaves the bracket is replaced by bisection, so the iteration converges
//!    from any seed; it stops when a step and Newton's `|r/F'|` fall below
//!    the precision's tolerance, relative to the variable and (for the step,
//!    its square root) to the distance to the nearer pole (at most
//!    64 steps). `F`, `F'` and `F''` cost one
//!    square root and one division together.
//!
//! f32 objects run the same f64 code and round once at the end.
//!
//! Above α = 10⁴ (tested up to 10⁴; the constructor accepts any finite α ≥ 0)
//! the same iteration applies; the density tends to the α → ∞ limit
//! `∝ μ² p_HG`, and `F` stays finite for every α below f64's overflow.

use super::function::PhaseFunction;
use super::hg::HenyeyGreenstein;
use super::model::{Lobes, Model, exactly, open, to};
use super::seeds::Seeds;
use crate::error::Error;
use crate::math::numeric::{Eval, depressed_cubic_root, solve_bracketed};
use crate::math::real::{PackedF64, Real};

/// Draine's phase function with asymmetry-like parameter `g ∈ (−1, 1)` and
/// `α ≥ 0` (finite). `α = 1` is Cornette–Shanks; `α = 0` is HG.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Draine<T> {
    pub(super) g: T,
    pub(super) alpha: T,
    /// What the sampler keeps beside the parameters (f32 objects only).
    pub(super) aux: Aux,
}

/// What a Draine object's sampler keeps, built with the object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Aux {
    /// Nothing: f64 objects, and f32 objects outside the two cases below.
    None,
    /// Seeds of the inverse where eq. 6 is not the answer (`phase::seeds`):
    /// f32 objects with `α > 10` outside the eq. 6 region (`|g| < 10⁻³` or
    /// `α > 10⁴`).
    Seeds(Seeds),
    /// Eq. 6's constants in both orientations ([`Eq6::pack`]): f32 objects
    /// in the region where eq. 6 is the answer.
    Eq6(PackedF64<12>),
}

impl<T: Real> Draine<T> {
    /// Fails with [`Error::Domain`] unless `−1 < g < 1` and `0 ≤ alpha < ∞`.
    pub fn new(g: T, alpha: T) -> Result<Self, Error> {
        let g_ok = g > -T::ONE && g < T::ONE;
        let a_ok = alpha >= T::ZERO && alpha.is_finite();
        if g_ok && a_ok {
            Ok(Self::from_parts(g, alpha))
        } else {
            Err(Error::Domain)
        }
    }
    /// A Draine lobe from parameters already known to be valid, with what
    /// its f32 sampler keeps: eq. 6's constants in the eq. 6 region
    /// (`|g| ≥ 10⁻³`, `10⁻⁴ ≤ α ≤ 10⁴`), else, for `α > 10`, a seed table
    /// (3–5 µs to build), where the `g = 0` root is a poor seed. (Below
    /// α = 10⁻⁴, for a nearly HG lobe, a table of `y/t` at 13 points
    /// is a poorer seed than eq. 6: measured 1.1·10⁻⁵ at g = 0.99.)
    pub(crate) fn from_parts(g: T, alpha: T) -> Self {
        let mut d = Self::lobe(g, alpha);
        let p = d.params();
        if core::mem::size_of::<T>() != 4 {
            return d;
        }
        if eq6_region(p.g, p.alpha) {
            d.aux = Aux::Eq6(Eq6::pack(p.g, p.alpha));
        } else if p.alpha > SEEDS_MIN_ALPHA {
            let oriented = |m: bool| if m { p.mirrored() } else { p };
            d.aux = Aux::Seeds(Seeds::build(
                |m| oriented(m).eval_y(0.0).density,
                |m, t| inverse_tail::<f64>(oriented(m), t),
            ));
        }
        d
    }
    /// A Draine lobe without a seed table (for evaluating it, or for the fog
    /// mixture's lobe sampler, which samples it through eq. 6 seeds).
    pub(crate) fn lobe(g: T, alpha: T) -> Self {
        Draine {
            g,
            alpha,
            aux: Aux::None,
        }
    }
    /// Cornette–Shanks (1992): Draine with `α = 1`.
    pub fn cornette_shanks(g: T) -> Result<Self, Error> {
        Self::new(g, T::ONE)
    }
    /// The parameter `g`.
    pub fn g(&self) -> T {
        self.g
    }
    /// The parameter `α`.
    pub fn alpha(&self) -> T {
        self.alpha
    }
    fn params(&self) -> Params {
        Params::new(self.g.to_f64(), self.alpha.to_f64())
    }
}

impl<T: Real> PhaseFunction<T> for Draine<T> {
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        T::from_f64(self.params().density(cos_theta.to_f64()) / core::f64::consts::TAU)
    }
    #[inline]
    fn cdf(&self, cos_theta: T) -> T {
        T::from_f64(
            self.params()
                .cdf(cos_theta.to_f64().clamp(-1.0, 1.0))
                .clamp(0.0, 1.0),
        )
    }
    #[inline]
    fn sample_cos(&self, u: T) -> T {
        let (g, alpha, u) = (self.g.to_f64(), self.alpha.to_f64(), u.clamp01().to_f64());
        let mu = match &self.aux {
            // Eq. 6 from the stored constants, inline; the rest out of line.
            Aux::Eq6(c) => {
                let (mu, flip) = oriented(g, u, |g, t, m| match eq6_stored(c, m, g, t) {
                    // μ of the tail problem, without forming y = 1 + μ.
                    Ok(mu) => mu,
                    Err(mu) => eq6_rest::<T>(g, alpha, t, 1.0 + mu) - 1.0,
                });
                f64::from_bits(mu.to_bits() ^ flip)
            }
            aux => inverse_cos::<T>(g, alpha, aux, u),
        };
        T::from_f64(mu)
    }
    /// `sin θ` from the f64 solution, so forward and backward lobes keep
    /// angles that `cos θ` in f32 cannot resolve.
    #[inline]
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let (g, alpha, u) = (self.g.to_f64(), self.alpha.to_f64(), u.clamp01().to_f64());
        let (mu, sin) = inverse::<T>(g, alpha, &self.aux, u);
        (T::from_f64(mu), T::from_f64(sin))
    }
    /// `g (1 + α(3 + 2g²)/5) / (1 + α(1 + 2g²)/3)`.
    #[inline]
    fn mean_cosine(&self) -> T {
        let (g, a) = (self.g.to_f64(), self.alpha.to_f64());
        let g2 = g * g;
        T::from_f64(g * (1.0 + a * (3.0 + 2.0 * g2) / 5.0) / (1.0 + a * (1.0 + 2.0 * g2) / 3.0))
    }
}

/// Draine's parameters in f64 with the normalisation `c = 1 + α(1 + 2g²)/3`
/// and the constants every evaluation needs.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Params {
    g: f64,
    alpha: f64,
    /// `N = (1 − g)(1 + g)/(2c)`.
    n: f64,
    /// `1/(1 + g)`.
    inv_s0: f64,
    /// `α/3`.
    alpha_3: f64,
}

impl Params {
    pub(crate) fn new(g: f64, alpha: f64) -> Params {
        let c = 1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0;
        Params {
            g,
            alpha,
            n: (1.0 - g) * (1.0 + g) / (2.0 * c),
            inv_s0: 1.0 / (1.0 + g),
            alpha_3: alpha / 3.0,
        }
    }

    /// The mirror image `(g, μ) → (−g, −μ)`.
    pub(crate) fn mirrored(self) -> Params {
        Params::new(-self.g, self.alpha)
    }

    /// `s = sqrt(1 + g² − 2gμ)` at `y = 1 + μ`, as a sum of non-negative terms
    /// for either sign of g: `(1 − g)² + 2g(2 − y)` or `(1 + g)² − 2g y` (no
    /// cancellation at `μ → sign(g)`, `|g| → 1`).
    #[inline(always)]
    fn s(&self, y: f64) -> f64 {
        let g = self.g;
        let d = if g >= 0.0 {
            (1.0 - g) * (1.0 - g) + 2.0 * g * (2.0 - y)
        } else {
            (1.0 + g) * (1.0 + g) - 2.0 * g * y
        };
        Real::sqrt(d)
    }

    /// Density of `μ = cos θ` (that is, `2π p(μ)`): `N (1 + αμ²)/s³`, with
    /// `s² = (1 − g)² + 2g(1 − μ)` for `g ≥ 0` (`(1 + g)² − 2g(1 + μ)`
    /// for `g < 0`) from `μ` itself: through `y = 1 + μ`, which rounds near
    /// `μ = 1`, the `1 − μ` a forward lobe with `g → 1` lives on was lost
    /// (130× at `1 − g = 3·10⁻⁹`, `μ = 1 − 2⁻⁵³`).
    #[inline(always)]
    pub(crate) fn density(&self, mu: f64) -> f64 {
        let s = self.s_mu(mu);
        self.n * (1.0 + self.alpha * mu * mu) / (s * s * s)
    }

    /// [`s`](Self::s) from `μ` itself: the difference `1 ∓ μ` it needs is
    /// exact near the pole the lobe faces.
    #[inline(always)]
    fn s_mu(&self, mu: f64) -> f64 {
        let g = self.g;
        let d = if g >= 0.0 {
            (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu)
        } else {
            (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu)
        };
        Real::sqrt(d)
    }

    /// `F(μ) = P(cos θ ≤ μ)` alone, the smaller of `F` and `1 − F` to
    /// its own relative precision: `F` from `μ` itself
    /// ([`s_mu`](Self::s_mu)), and where it exceeds ½, one minus the
    /// mirrored tail `P(cos θ ≥ μ)`. (Through `y = 1 + μ`, `F` near
    /// `μ = 1` of a lobe with `g → 1` was 1.0 where it is 0.197.)
    pub(crate) fn cdf(&self, mu: f64) -> f64 {
        let f = self.cdf_direct(mu);
        if f > 0.5 {
            let m = self.mirrored();
            1.0 - m.eval_at(1.0 - mu, m.s_mu(-mu), -mu).cdf
        } else {
            f
        }
    }

    /// `F(μ)` from `μ` itself ([`s_mu`](Self::s_mu)): to its own
    /// relative precision where `F ≤ ½`, to `F`'s rounding above.
    #[inline(always)]
    pub(crate) fn cdf_direct(&self, mu: f64) -> f64 {
        self.eval_at(1.0 + mu, self.s_mu(mu), mu).cdf
    }

    /// `F`, `F'` and `F''` at `y = 1 + μ` (the variable the solver works in,
    /// so that `1 + μ` near the pole keeps its relative precision), from one
    /// square root and one division. With `q = 1/(s (s + s0))`:
    /// `1/s = q (s + s0)`, `e = y/(s + s0) = y q s`,
    /// `F = N I0 (1 + α P/3)` with `I0 = 2e/(s s0)` and
    /// `P = 3 − 6 s0 e + 4 (s0 e)² − 2g s0 e³` (`I2 = I0 P/3`, item 1 of the module docs),
    /// `F' = N (1 + αμ²)/s³`, `F'' = N/s³ (2αμ + 3g (1 + αμ²)/s²)`.
    #[inline(always)]
    pub(crate) fn eval_y(&self, y: f64) -> Eval {
        self.eval_at(y, self.s(y), y - 1.0)
    }

    /// [`eval_y`](Self::eval_y) with `s` and `μ` given (`y = 1 + μ` may
    /// then be rounded: it enters only as a factor).
    #[inline(always)]
    fn eval_at(&self, y: f64, s: f64, mu: f64) -> Eval {
        let g = self.g;
        let sum = s + (1.0 + g);
        let q = 1.0 / (s * sum);
        let inv_s = q * sum;
        let e = y * q * s;
        let se = (1.0 + g) * e;
        let i0 = 2.0 * e * inv_s * self.inv_s0;
        let p = 3.0 - 6.0 * se + 4.0 * se * se - 2.0 * g * se * e * e;
        let inv_s3 = inv_s * inv_s * inv_s;
        let w = 1.0 + self.alpha * mu * mu;
        Eval {
            // α/3 taken once in `new`: a division here would sit on the
            // solver's chain at every step.
            cdf: self.n * i0 * (1.0 + self.alpha_3 * p),
            density: self.n * w * inv_s3,
            slope: self.n * inv_s3 * (2.0 * self.alpha * mu + 3.0 * g * w * inv_s * inv_s),
        }
    }
}

impl Params {
    /// [`eval_y`](Self::eval_y) for `α = 0` (Henyey–Greenstein): the same
    /// terms without the `α` ones, for the fog mixture's HG lobe.
    #[inline(always)]
    pub(crate) fn eval_y_hg(&self, y: f64) -> Eval {
        let g = self.g;
        let s = self.s(y);
        let sum = s + (1.0 + g);
        let q = 1.0 / (s * sum);
        let inv_s = q * sum;
        let e = y * q * s;
        let inv_s3 = inv_s * inv_s * inv_s;
        Eval {
            cdf: self.n * (2.0 * e * inv_s * self.inv_s0),
            density: self.n * inv_s3,
            slope: self.n * inv_s3 * (3.0 * g * inv_s * inv_s),
        }
    }
}

/// The exact inverse CDF at `g = 0`: `αμ³ + 3μ = (3 + α)(2u − 1)`. With
/// `μ = y/√α` this is `y³ + 3y = 2β`, `β = (3 + α)(2u − 1)√α/2`, solved by the
/// cancellation-free Cardano root; the scaling keeps α → 0 finite
/// (`μ → 2u − 1`) and large α from overflowing.
#[inline]
fn inverse_g0(alpha: f64, u: f64) -> f64 {
    if alpha < 1e-12 {
        // αμ³ is below 10⁻¹²: one fixed-point correction of μ = 2u − 1.
        let mu0 = 2.0 * u - 1.0;
        return mu0 + alpha * (mu0 - mu0 * mu0 * mu0) / 3.0;
    }
    let alpha = alpha.min(1e30);
    let ra = Real::sqrt(alpha);
    let beta = (3.0 + alpha) * (2.0 * u - 1.0) * ra * 0.5;
    let y = depressed_cubic_root::<f64, false>(1.0, 1.0, beta);
    y / ra
}

/// Eq. 6 of Jendersie & d'Eon (2023) in f64, rearranged where it cancels,
/// and with everything that does not depend on `u` formed once.
///
/// Three rearrangements (`docs/measured/draine_accuracy.md` has the measured effect):
/// - `t5 = t0 (t1 t2 + t4²) + t1³` is a sum of terms of size `α³` that
///   cancel where `t5` changes sign (there it lost up to 10⁻⁶ in `μ` at
///   α = 10⁴). Since `t1 t2 + t1³/t0 = −r²` with
///   `r² = 4α(1 − g²)²(1 + g²)(3g² + α(1 + g²)²)` (a product: no
///   cancellation), `t5 = t0 (t4 − r)(t4 + r)`, and `t4 − r = D + Q u`
///   with `D = P − r` taken as `(P² − r²)/(P + r)`,
///   `P² − r² = −g³ (1 − g)² (α²(4g² − g + 4) + 6α(2g² + g + 2) − 9g)`
///   (expanded and factored by computer algebra): `t5` keeps its
///   relative precision through its zero.
/// - `t5 + sqrt(t5² − t6³)` cancels for `t5 < 0`: the other cube root of
///   the resolvent ([`resolvent`]).
/// - `t4` at `u = 0`, `P = 3g²(1 − g) + α(2 + g² − g³ − 2g⁵)`, cancels as
///   `g → 1`: `P = (1 − g)(3g² + α(2 + 2g + 3g² + 2g³ + 2g⁴))`.
///
/// It still divides by `g` and by `α`; measured against a 60-digit
/// evaluation of the same formula, it is within 2·10⁻¹² in `μ` (2.2·10⁻¹²
/// against the iterative f64 inverse, a unit test below) for
/// `|g| ≥ 10⁻³`, `10⁻⁴ ≤ α ≤ 10⁴` and `1 + μ ≥ 10⁻⁵` (the error grows like
/// 6·10⁻¹⁶/|g| and with α: 10⁻¹⁰ at α = 10⁶). NaN where its cube root's
/// argument leaves `[1e-200, 1e200]`.
///
/// An f32 object in the eq. 6 region keeps the constants ([`Aux::Eq6`]);
/// elsewhere they are formed per sample ([`seed_eq6`]).
#[derive(Clone, Copy, Debug)]
struct Eq6 {
    /// `t4 − r = D + Q u`.
    d: f64,
    q: f64,
    /// `r` (above).
    r: f64,
    t0: f64,
    t1: f64,
    t6: f64,
    t6_3: f64,
    inv_t0: f64,
    /// `6(1 + g²)`.
    k: f64,
    g: f64,
    /// `1/(2g)`.
    inv_2g: f64,
}

impl Eq6 {
    /// The constants for `g` (signed as the problem is oriented) and `α`.
    #[inline(always)]
    fn new(g: f64, a: f64) -> Eq6 {
        let e = crate::math::draine_eq6::eq6_core(g, a);
        Eq6 {
            d: e.d,
            q: e.q,
            r: e.r,
            t0: e.t0,
            t1: e.t1,
            t6: e.t6,
            t6_3: e.t6_3,
            inv_t0: 1.0 / e.t0,
            k: e.k,
            g,
            inv_2g: 0.5 / g,
        }
    }

    /// Both orientations' constants for `g ≥ 0` or `g < 0` and `α`: `D` and
    /// `Q` for `g` and for `−g`, then the rest (even in `g`, but for `1/(2g)`,
    /// whose sign the mirror flips).
    fn pack(g: f64, a: f64) -> PackedF64<12> {
        let (e, m) = (Eq6::new(g, a), Eq6::new(-g, a));
        PackedF64::new([
            e.d, e.q, m.d, m.q, e.r, e.t0, e.t1, e.t6, e.t6_3, e.inv_t0, e.k, e.inv_2g,
        ])
    }

    /// The constants [`pack`](Self::pack) stored, for the problem oriented
    /// by `g`: the object's `g`, or its negation if `mirrored`.
    #[inline(always)]
    fn unpack(c: &PackedF64<12>, mirrored: bool, g: f64) -> Eq6 {
        let i = 2 * mirrored as usize;
        Eq6 {
            d: c.get(i),
            q: c.get(i + 1),
            r: c.get(4),
            t0: c.get(5),
            t1: c.get(6),
            t6: c.get(7),
            t6_3: c.get(8),
            inv_t0: c.get(9),
            k: c.get(10),
            g,
            inv_2g: f64::from_bits(c.get(11).to_bits() ^ ((mirrored as u64) << 63)),
        }
    }

    /// `μ` for `u` by eq. 6, `t5 = t0 (t4 − r)(t4 + r)`, and the operations
    /// after `t5` grouped for a short chain: `t6/c = c² (t6/m)` with `t6/m`
    /// formed beside the cube root, so that `t8` is two operations after
    /// `c`. The chain `sqrt → cbrt → sqrt → sqrt` is the sampler's latency.
    #[inline(always)]
    fn seed(&self, u: f64) -> f64 {
        let lo = self.d + self.q * u;
        let t4 = lo + self.r;
        let t5 = self.t0 * (lo * (lo + 2.0 * self.r));
        let Some(m) = resolvent(t5, self.t6_3) else {
            return f64::NAN;
        };
        let t6_m = self.t6 / m;
        let c = crate::math::cbrt::cbrt_moderate_f64(m);
        let t8 = ((self.t1 + c) + (c * c) * t6_m) * (2.0 * self.inv_t0);
        self.finish(t4, t8)
    }

    /// Eq. 6 from `t8` on: `t9 = sqrt(6(1 + g²) + t8)`,
    /// `d = sqrt(6(1 + g²) − t8 + 8 t4/(t0 t9)) − t9`, `μ = g/2 + (1 − d²/4)/(2g)`.
    #[inline(always)]
    fn finish(&self, t4: f64, t8: f64) -> f64 {
        let t9 = Real::sqrt(self.k + t8);
        let d = Real::sqrt(self.k - t8 + 8.0 * t4 * self.inv_t0 / t9) - t9;
        // g/2 + 1/(2g) − d²/(8g)
        self.g * 0.5 + (1.0 - 0.25 * d * d) * self.inv_2g
    }
}

/// The argument `m` of eq. 6's cube root, `t5 + sign(t5) sqrt(t5² − t6³)`,
/// or `None` where it leaves `[1e-200, 1e200]`.
///
/// The resolvent's two cube roots `c± = cbrt(t5 ± root)` have the product
/// `t6` (the cube of the product is `t5² − root² = t6³`), and eq. 6 needs
/// their sum `c+ + t6/c+`. Taking `c = cbrt(t5 + sign(t5) root)` instead adds
/// like signs, so the cancellation of `t5 + root` for `t5 < 0` is gone
/// without a branch.
#[inline(always)]
fn resolvent(t5: f64, t6_3: f64) -> Option<f64> {
    let root = Real::sqrt(t5 * t5 - t6_3);
    let m = t5 + root.copysign(t5);
    (m.abs() > 1e-200 && m.abs() < 1e200).then_some(m)
}

/// Eq. 6 in f64 for `(g, α)` at `u` ([`Eq6`]), its constants formed here.
#[inline]
fn seed_eq6(g: f64, a: f64, u: f64) -> f64 {
    Eq6::new(g, a).seed(u)
}

/// `F⁻¹(u)` in f64 for `u ∈ [0, 1]`, for results of precision `T` (module
/// docs): `(cos θ, sin θ)`.
#[inline(always)]
fn inverse<T: Real>(g: f64, alpha: f64, aux: &Aux, u: f64) -> (f64, f64) {
    let (y, flip) = inverse_tail_of::<T>(g, alpha, aux, u);
    let (mu, sin) = from_tail(y, false);
    (f64::from_bits(mu.to_bits() ^ flip), sin)
}

/// `cos θ = F⁻¹(u)` alone (no `sin θ`), as [`inverse`].
#[inline(never)]
fn inverse_cos<T: Real>(g: f64, alpha: f64, aux: &Aux, u: f64) -> f64 {
    let (y, flip) = inverse_tail_of::<T>(g, alpha, aux, u);
    f64::from_bits((y - 1.0).to_bits() ^ flip)
}

/// The tail solution `y` of `F⁻¹(u)` and the sign bit that maps it to `μ`
/// (`μ = ±(y − 1)`). With a seed table, Halley's iteration on `[0, 2]`
/// starts from it; without, from eq. 6 (or the `g = 0` root).
#[inline(always)]
fn inverse_tail_of<T: Real>(g: f64, alpha: f64, aux: &Aux, u: f64) -> (f64, u64) {
    let (y, flip) = oriented_tail_of::<T>(g, alpha, aux, u);
    if y > 2.0 - FAR_POLE {
        return far_pole::<T>(g, alpha, u, flip, y);
    }
    (y, flip)
}

/// Within this of the far pole (`y = 1 + μ > 2 − FAR_POLE`), the tail
/// frame's `y` cannot resolve `1 − μ` (its ulp there is `2⁻⁵²`, four of
/// `μ`'s): [`far_pole`] solves again in the other frame. Only lobes whose
/// median lies within about 10⁻⁶ of a pole (`1 − |g| ≲ 10⁻³`) get there.
const FAR_POLE: f64 = 1.0 / 1_048_576.0;

/// The solution of a tail problem that landed at its far pole, solved
/// again in the mirrored frame, where `y' = 1 ∓ μ` is small and exact:
/// target `1 − t` (`t = min(u, 1 − u)`), seeded from `2 − y`. At
/// `1 − g = 3·10⁻⁹` the tail frame gave `1 − 2⁻⁵¹` for `u = ½`, where the
/// answer rounds to 1.
#[cold]
#[inline(never)]
fn far_pole<T: Real>(g: f64, alpha: f64, u: f64, flip: u64, y: f64) -> (f64, u64) {
    let flip = flip ^ (1 << 63);
    let p = Params::new(f64::from_bits(g.to_bits() ^ flip), alpha);
    let t = if u < 1.0 - u { u } else { 1.0 - u };
    let y = if alpha == 0.0 {
        HenyeyGreenstein::from_g(p.g).one_plus_minus_mu(1.0 - t).0
    } else {
        solve_bracketed::<T>(|y| p.eval_y(y), 1.0 - t, 2.0 - y, 0.0, 2.0)
    };
    (y, flip)
}

/// [`inverse_tail_of`] in the frame of the smaller tail.
#[inline(always)]
fn oriented_tail_of<T: Real>(g: f64, alpha: f64, aux: &Aux, u: f64) -> (f64, u64) {
    oriented(g, u, |g, target, mirrored| {
        // The parameters (four divisions) only if the solver runs: where
        // eq. 6 is the answer they would occupy the divider that eq. 6's own
        // chain of divisions and square roots waits on.
        let params = || Params::new(g, alpha);
        match aux {
            Aux::Seeds(seeds) => {
                let p = params();
                let seed = seeds.y(mirrored, target);
                solve_bracketed::<T>(|y| p.eval_y(y), target, seed, 0.0, 2.0)
            }
            Aux::Eq6(c) => match eq6_stored(c, mirrored, g, target) {
                Ok(mu) => 1.0 + mu,
                Err(mu) => eq6_rest::<T>(g, alpha, target, 1.0 + mu),
            },
            Aux::None => inverse_tail_lazy::<T>(g, alpha, target, params),
        }
    })
}

/// `tail(g', t, mirrored)` for the problem oriented so that
/// `t = min(u, 1 − u)` is the smaller tail (`g' = −g`, mirrored, for
/// `u > 1/2`), and the sign bit that flips `μ` back. The mirrored problem's
/// parameters directly, without a branch: with random `u` a branch on
/// `u > 1/2` mispredicts half the time, and each miss discards the next
/// samples' work that the processor had started.
#[inline(always)]
fn oriented(g: f64, u: f64, tail: impl FnOnce(f64, f64, bool) -> f64) -> (f64, u64) {
    let mirrored = u > 0.5;
    let flip = (mirrored as u64) << 63;
    let g = f64::from_bits(g.to_bits() ^ flip);
    // The smaller of u and 1 − u (NaN for NaN u), as one `minsd`.
    let v = 1.0 - u;
    let t = if u < v { u } else { v };
    (tail(g, t, mirrored), flip)
}

/// `(cos θ, sin θ)` from a tail solution `y = 1 + μ_tail` (of the mirrored
/// problem if `mirrored`): `sin θ = sqrt(y (2 − y))` keeps the precision `y`
/// has near the pole.
#[inline(always)]
pub(crate) fn from_tail(y: f64, mirrored: bool) -> (f64, f64) {
    let mu = if mirrored { 1.0 - y } else { y - 1.0 };
    (mu, Real::sqrt((y * (2.0 - y)).max(0.0)))
}

/// `y = 1 + F⁻¹(target)` without the mirror step: accurate when
/// `target ≤ 1/2`.
pub(crate) fn inverse_tail<T: Real>(p: Params, target: f64) -> f64 {
    inverse_tail_lazy::<T>(p.g, p.alpha, target, || p)
}

/// [`inverse_tail`] for `(g, α)`, with the parameters built by `params` only
/// when the solver runs.
#[inline(always)]
fn inverse_tail_lazy<T: Real>(
    g: f64,
    alpha: f64,
    target: f64,
    params: impl FnOnce() -> Params,
) -> f64 {
    if alpha == 0.0 {
        return HenyeyGreenstein::from_g(g).one_plus_minus_mu(target).0;
    }
    if target.is_nan() {
        return f64::NAN;
    }
    if target <= 0.0 {
        return 0.0;
    }
    let seed = if g.abs() >= EQ6_MIN_G {
        1.0 + seed_eq6(g, alpha, target)
    } else {
        f64::NAN
    };
    if eq6_region(g, alpha) && core::mem::size_of::<T>() == 4 && (EQ6_MIN_Y..=2.0).contains(&seed) {
        // Eq. 6 in f64 on the small tail is within ~10⁻¹¹ here (see
        // docs/measured/draine_accuracy.md), 10³ finer than f32 resolves, and y is
        // large enough for that absolute error to leave sin θ exact: done.
        return seed;
    }
    solve_from::<T>(alpha, target, seed, params())
}

/// Eq. 6 for an f32 object in the eq. 6 region, from its stored constants
/// `c` ([`Aux::Eq6`]), at tail probability `target`: `Ok(μ)` of the tail
/// problem where it is the answer (`y = 1 + μ ≥` [`EQ6_MIN_Y`], the test of
/// [`inverse_tail_lazy`], whose region test holds by construction here),
/// else `Err(μ)` for [`eq6_rest`] to start from.
#[inline(always)]
fn eq6_stored(c: &PackedF64<12>, mirrored: bool, g: f64, target: f64) -> Result<f64, f64> {
    let mu = Eq6::unpack(c, mirrored, g).seed(target);
    if target > 0.0 && (EQ6_MIN_Y - 1.0..=1.0).contains(&mu) {
        Ok(mu)
    } else {
        Err(mu)
    }
}

/// `y` where [`eq6_stored`] is not the answer: the ends, NaN, and the
/// solver from `seed` (cold, so that the code for the usual case runs
/// straight through).
#[cold]
#[inline(never)]
fn eq6_rest<T: Real>(g: f64, alpha: f64, target: f64, seed: f64) -> f64 {
    if target.is_nan() {
        return f64::NAN;
    }
    if target <= 0.0 {
        return 0.0;
    }
    solve_from::<T>(alpha, target, seed, Params::new(g, alpha))
}

/// The solver's part of [`inverse_tail_lazy`], out of line: where eq. 6 is
/// the answer, the sampler does not set up the solver's stack frame.
#[inline(never)]
fn solve_from<T: Real>(alpha: f64, target: f64, seed: f64, p: Params) -> f64 {
    let seed = if seed.is_finite() {
        seed
    } else {
        1.0 + inverse_g0(alpha, target)
    };
    solve_bracketed::<T>(|y| p.eval_y(y), target, seed, 0.0, 2.0)
}

/// True where eq. 6 in f64 is used as it is for f32 results (below).
fn eq6_region(g: f64, alpha: f64) -> bool {
    g.abs() >= EQ6_MIN_G && (EQ6_MIN_ALPHA..=EQ6_MAX_ALPHA).contains(&alpha)
}

/// Below this `y = 1 + μ` the eq. 6 shortcut is not taken: its absolute
/// error in the eq. 6 region (≤ 2.2·10⁻¹², [`Eq6`]; the tests bound it by
/// 2·10⁻¹¹) must stay below f32's resolution of `sin θ = sqrt(y (2 − y))`,
/// whose relative error is `δy/(2y)`: ≤ 10⁻⁶ of an already tiny angle at
/// `y = 10⁻⁵`.
const EQ6_MIN_Y: f64 = 1e-5;

/// Where eq. 6 (in f64, on the small tail, [`Eq6`]) is used as it is for
/// f32 results: `|g| ≥ 10⁻³`, `10⁻⁴ ≤ α ≤ 10⁴`, where it is within
/// 2.2·10⁻¹² of the exact inverse (its error grows like 6·10⁻¹⁶/|g| below,
/// and with α above: 10⁻¹⁰ at α = 10⁶). The stability sweep and the eq. 6
/// region test in `tests/models/draine.rs` hold this region to the same bounds as
/// everything else.
const EQ6_MIN_G: f64 = 1e-3;
const EQ6_MIN_ALPHA: f64 = 1e-4;
const EQ6_MAX_ALPHA: f64 = 1e4;

/// Outside the eq. 6 region, f32 objects above this `α` keep a seed table
/// (`phase::seeds`): the `g = 0` root is a poor seed there.
const SEEDS_MIN_ALPHA: f64 = 10.0;

/// Eq. 6 of Jendersie & d'Eon (2023) exactly as published, in the precision
/// `T`: the reference the accuracy map and benchmarks compare against. It is
/// NaN at `g = 0` and `α = 0` and inaccurate for small `|g|` and large `α`
/// (see `docs/measured/draine_accuracy.md`); use [`Draine::sample_cos`] instead.
pub fn sample_cos_eq6<T: Real>(g: T, alpha: T, u: T) -> T {
    let one = T::ONE;
    let (two, three, four, six, eight) = (
        T::TWO,
        T::from_f64(3.0),
        T::from_f64(4.0),
        T::from_f64(6.0),
        T::from_f64(8.0),
    );
    let a = alpha;
    let g2 = g * g;
    let g4 = g2 * g2;
    let t0 = a - a * g2;
    let t1 = a * g4 - a;
    let t2 = -three * (four * (g4 - g2) + t1 * (one + g2));
    let t3 = g * (two * u - one);
    let t4 = three * g2 * (one + t3) + a * (two + g2 * (one + (one + two * g2) * t3));
    let t5 = t0 * (t1 * t2 + t4 * t4) + t1 * t1 * t1;
    let t6 = t0 * four * (g4 - g2);
    let t7 = (t5 + (t5 * t5 - t6 * t6 * t6).sqrt()).cbrt();
    let t8 = two * (t1 + t6 / t7 + t7) / t0;
    let t9 = (six * (one + g2) + t8).sqrt();
    let d = (six * (one + g2) - t8 + eight * t4 / (t0 * t9)).sqrt() - t9;
    g / two + (one / (two * g) - d * d / (eight * g))
}

impl<T: Real> Model<T> for Draine<T> {
    type In<U: Real> = Draine<U>;
    const PARAMS: usize = 2;
    fn params(&self) -> [T; 4] {
        [self.g(), self.alpha(), T::ZERO, T::ZERO]
    }
    fn from_params(p: &[T]) -> Result<Self, Error> {
        let [g, alpha] = exactly(p)?;
        Self::new(g, alpha)
    }
    fn cast<U: Real>(&self) -> Draine<U> {
        Draine::from_parts(open(self.g()), to(self.alpha()))
    }
    fn lobes(&self) -> Option<Lobes> {
        let f = |x: T| x.to_f64();
        Some(((f(self.g()), f(self.alpha())), (0.0, 0.0), 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Within a few ulps of `F` (3.3·10⁻¹⁶ the largest error measured),
    /// on both sides of the switch to the small-α correction at 10⁻¹²,
    /// where leaving the correction out would err by 6·10⁻¹⁴.
    #[test]
    fn g0_inverse_solves_its_cubic() {
        let alphas = [1e-20, 1e-13, 5e-13, 9.9e-13, 1e-12, 1.01e-12, 1e-11];
        for alpha in alphas.into_iter().chain([1e-6, 0.5, 1.0, 250.0, 1e4, 1e40]) {
            for u in [0.0, 0.01, 0.1, 0.21, 0.5, 0.77, 0.9, 1.0] {
                let mu = inverse_g0(alpha, u);
                let p = Params::new(0.0, alpha);
                assert!(
                    (p.cdf(mu) - u).abs() < 1e-15,
                    "α = {alpha}, u = {u}: F = {}",
                    p.cdf(mu)
                );
            }
        }
    }

    /// Eq. 6 as rearranged ([`Eq6`]) against the iterative f64 inverse
    /// (itself within 10⁻¹³, `tests/models/draine.rs`) over the eq. 6 region, on a
    /// grid of u and around the zero of `t5` (`t4 = r`), where eq. 6 as
    /// published cancels: within 5·10⁻¹² (bound fixed before the run, from
    /// 2·10⁻¹² measured against a 60-digit evaluation of the same formula).
    #[test]
    fn eq6_rearranged_is_accurate_over_its_region() {
        let mut worst = (0.0, 0.0, 0.0, 0.0);
        for g in [1e-3, 0.01, 0.05, 0.3, 0.9, 0.999, 0.9999] {
            for g in [g, -g] {
                for a in [1e-4, 1.0, 10.0, 11.4, 250.0, 1e3, 1e4] {
                    let e = Eq6::new(g, a);
                    let t5_zero = -e.d / e.q;
                    let near = (1..16).flat_map(|k| {
                        let f = 10f64.powi(-k);
                        [t5_zero * (1.0 + f), t5_zero * (1.0 - f)]
                    });
                    let grid = (1..=512).map(|i| i as f64 / 1024.0);
                    let tails = (2..13).map(|k| 10f64.powi(-k));
                    for u in grid.chain(tails).chain(near) {
                        if !(u > 0.0 && u <= 0.5) {
                            continue;
                        }
                        let want = inverse_tail::<f64>(Params::new(g, a), u);
                        if want < EQ6_MIN_Y {
                            continue;
                        }
                        let err = (1.0 + e.seed(u) - want).abs();
                        assert!(err <= 5e-12, "g {g}, α {a}, u {u:e}: {err:e}");
                        if err > worst.0 {
                            worst = (err, g, a, u);
                        }
                    }
                }
            }
        }
        extern crate std;
        std::println!("eq. 6 rearranged: worst {worst:?}");
    }

    /// What an object keeps beside its parameters ([`Aux`]), as
    /// [`Draine::from_parts`] documents it: f32 objects eq. 6's constants
    /// in the eq. 6 region, a seed table above α = 10 outside it, nothing
    /// at or below; f64 objects nothing. (The sampler gives the same
    /// answers from any seed, so only this tells the cases apart.)
    #[test]
    fn f32_objects_keep_what_their_region_needs() {
        fn kind<T: Real>(g: f64, a: f64) -> &'static str {
            match Draine::<T>::from_parts(T::from_f64(g), T::from_f64(a)).aux {
                Aux::None => "none",
                Aux::Seeds(_) => "seeds",
                Aux::Eq6(_) => "eq6",
            }
        }
        let cases = [
            (0.5, 1.0, "eq6"),
            (-0.9, 1e4, "eq6"),
            (2e-3, 1e-3, "eq6"),
            (1e-4, 100.0, "seeds"),
            (0.0, 10.5, "seeds"),
            (0.5, 2e4, "seeds"),
            (1e-4, 10.0, "none"),
            (0.0, 5.0, "none"),
            (0.5, 1e-5, "none"),
        ];
        for (g, a, want) in cases {
            assert_eq!(kind::<f32>(g, a), want, "f32 g = {g}, α = {a}");
            assert_eq!(kind::<f64>(g, a), "none", "f64 g = {g}, α = {a}");
        }
    }

    /// An f32 object's stored eq. 6 constants ([`Eq6::pack`],
    /// [`Eq6::unpack`]) give, in both orientations, the bits of the
    /// constants formed per sample ([`seed_eq6`]), and [`eq6_stored`]
    /// answers (`Ok`, with that value) exactly where its docs say, leaving
    /// the rest to the solver: the smallest tails (`y < 10⁻⁵`, where eq. 6's
    /// absolute error would show in f32's `sin θ`), `t = 0` and NaN. The
    /// solver gives the same answer from any seed, so wrong constants, or a
    /// shortcut never taken or taken too often, changed no other test.
    #[test]
    fn stored_eq6_is_the_per_sample_eq6_and_answers_where_documented() {
        extern crate std;
        let (mut answered, mut left) = (0, 0);
        for g in [1e-3, 0.3, 0.9, 0.9999].into_iter().flat_map(|g| [g, -g]) {
            for a in [1e-4, 1.0, 250.0, 1e4] {
                let c = Eq6::pack(g, a);
                for mirrored in [false, true] {
                    let g = if mirrored { -g } else { g };
                    for t in [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.1, 0.3, 0.5, f64::NAN] {
                        let formed = seed_eq6(g, a, t);
                        let stored = Eq6::unpack(&c, mirrored, g).seed(t);
                        let at = std::format!("g {g}, α {a}, mirrored {mirrored}, t {t:e}");
                        assert_eq!(stored.to_bits(), formed.to_bits(), "{at}");
                        let answers = t > 0.0 && (EQ6_MIN_Y..=2.0).contains(&(1.0 + formed));
                        match eq6_stored(&c, mirrored, g, t) {
                            Ok(mu) if answers => assert_eq!(mu.to_bits(), formed.to_bits()),
                            Err(_) if !answers => {}
                            r => panic!("{at}: {r:?}, eq. 6 gives {formed:e}"),
                        }
                        if answers { answered += 1 } else { left += 1 }
                    }
                }
            }
        }
        assert!(
            answered >= 16 && left >= 16,
            "{answered} answered, {left} left"
        );
    }

    /// [`resolvent`] refuses what the cube root cannot take: below 10⁻²⁰⁰
    /// (the bound itself included), infinities and NaN. Above, `m` cannot
    /// be finite beyond 2.7·10¹⁵⁴ (`t5²` overflows first), so the upper
    /// bound only keeps out infinity.
    #[test]
    fn resolvent_refuses_what_the_cube_root_cannot_take() {
        let above = |x: f64| f64::from_bits(x.to_bits() + 1);
        assert_eq!(resolvent(1.0, 0.0), Some(2.0));
        assert_eq!(resolvent(-1.0, -3.0), Some(-3.0));
        assert_eq!(resolvent(above(1e-200), 0.0), Some(above(1e-200)));
        // The largest finite m.
        assert_eq!(resolvent(0.0, -f64::MAX), Some(f64::MAX.sqrt()));
        for (t5, t6_3) in [(1e-200, 0.0), (-1e-200, 0.0), (1e-250, 0.0), (-1e-250, 0.0)] {
            assert_eq!(resolvent(t5, t6_3), None, "t5 = {t5:e}");
        }
        for (t5, t6_3) in [
            (1e200, 0.0),
            (0.0, -f64::INFINITY),
            (f64::NAN, 0.0),
            (1.0, 2.0),
        ] {
            assert_eq!(resolvent(t5, t6_3), None, "t5 = {t5:e}, t6³ = {t6_3:e}");
        }
    }

    #[test]
    fn mirror_symmetry_of_the_cdf() {
        let p = Params::new(0.6, 3.0);
        for mu in [-0.9, -0.2, 0.4, 0.95] {
            let upper = 1.0 - p.cdf(mu);
            assert!((upper - p.mirrored().cdf(-mu)).abs() < 1e-14);
        }
    }
}
