//! The Gegenbauer kernel phase function of Reynolds & McCormick ("Approximate
//! two-parameter phase function for light scattering", JOSA 70(10), 1980),
//! used in tissue optics beside Henyey–Greenstein:
//! `p(μ) = K (1 + g² − 2gμ)^{−(α+1)}`, `α > −½`, `|g| < 1`; `α = ½` is HG.
//!
//! With `y = 1 + g² − 2gμ`, `L_1 = ln((1+g)²/(1−g)²)`,
//! `L_y = ln((1+g)²/y)` (0 at `μ = −1`, `L_1` at `μ = 1`) and
//! `D = L_1 − L_y = ln(y/(1−g)²)`, the CDF from `μ = −1` is
//! `F = expm1(α L_y) / expm1(α L_1)` (eq. 8 of the paper, rearranged). The
//! published form, `[y^{−α} − (1+g)^{−2α}] / [(1−g)^{−2α} − (1+g)^{−2α}]`
//! (times `(1 − g²)^{2α}` above and below), subtracts nearly equal powers
//! wherever `α` or `g` is small and overflows for large `α`; here
//! * every difference of powers is an `expm1` of a logarithm, and each
//!   logarithm a `log1p` of a small quantity (`L_y = −log1p(−2g(1+μ)/(1+g)²)`,
//!   `D = log1p(2g(1−μ)/(1−g)²)`), so nothing cancels as `g → 0`, `α → 0`
//!   or `μ → ±1`;
//! * where `α L_1 > 0` the form with non-positive exponents,
//!   `F = e^{−αD} expm1(−α L_y) / expm1(−α L_1)`, is used instead, so
//!   nothing overflows for a large `α` or `|g| → 1`;
//! * `α = 0` is the limit `F = L_y / L_1` (`p ∝ 1/y`).
//!
//! The inverse solves the same relations for `L_y` (where `α L_1 ≤ 0`) or
//! `D` (where `α L_1 > 0`) in closed form and turns them into `1 + μ` or
//! `1 − μ` with `expm1`, never through `y`.

use super::function::PhaseFunction;
use super::model::{Lobes, Model, exactly, open, to};
use crate::error::Error;
use crate::math::numeric::simpson_unit;
use crate::math::real::{PackedF64, Real};

/// The Gegenbauer kernel phase function with `α ∈ (−½, 1000]` and
/// `g ∈ (−1, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gegenbauer<T> {
    alpha: T,
    g: T,
    /// `L_1`, `e^{∓αL_1}`, `expm1(∓αL_1)` (upper sign for `αL_1 > 0`) and
    /// where the inverse changes route, computed once in f64 and kept as 32-bit halves (the f32
    /// model stays 4-byte aligned): each sample then costs two
    /// transcendentals, not five.
    k: PackedF64<4>,
}

impl<T: Real> Gegenbauer<T> {
    /// The largest `α` accepted.
    pub const MAX_ALPHA: f64 = 1000.0;

    /// Fails with [`Error::Domain`] unless `−½ < α ≤ 1000` and `|g| < 1`
    /// (NaN fails).
    pub fn new(alpha: T, g: T) -> Result<Self, Error> {
        let ok =
            alpha.to_f64() > -0.5 && alpha.to_f64() <= Self::MAX_ALPHA && g > -T::ONE && g < T::ONE;
        if ok {
            Ok(Self::from_parts(alpha, g))
        } else {
            Err(Error::Domain)
        }
    }
    /// Without checks (the caller validated).
    pub(crate) fn from_parts(alpha: T, g: T) -> Self {
        let k = K::new(alpha.to_f64(), g.to_f64());
        Gegenbauer {
            alpha,
            g,
            k: PackedF64::new([k.l1, k.e, k.m, k.u0]),
        }
    }
    /// The constants, as [`K::new`] computed them.
    fn constants(&self) -> K {
        let at = |i: usize| self.k.get(i);
        let (a, l1) = (self.alpha.to_f64(), at(0));
        K {
            a,
            g: self.g.to_f64(),
            l1,
            s: a * l1,
            e: at(1),
            m: at(2),
            u0: at(3),
        }
    }
    /// `α`.
    pub fn alpha(&self) -> T {
        self.alpha
    }
    /// `g` (not the mean cosine unless `α = ½`).
    pub fn g(&self) -> T {
        self.g
    }
}

/// Beyond this `|D|` or `|L_y|` the inverse takes a Newton step
/// ([`K::route`]).
const POLISH_LOG: f64 = 16.0;

/// A cosine with its distances to the poles, `w = 1 − μ` and `v = 1 + μ`:
/// for a float `μ` as float arithmetic gives them ([`At::of`]); from the
/// inverse's route, the one it solved for kept finer than `μ` resolves
/// near its pole ([`At::by`]), so that the Newton step reads the CDF at
/// the point it stepped from, not at `μ` rounded.
#[derive(Clone, Copy, Debug)]
struct At {
    mu: f64,
    w: f64,
    v: f64,
}

impl At {
    /// A float `μ`.
    fn of(mu: f64) -> At {
        At {
            mu,
            w: 1.0 - mu,
            v: 1.0 + mu,
        }
    }
    /// `z = 1 − μ` (`by_d`) or `1 + μ`.
    fn by(z: f64, by_d: bool) -> At {
        if by_d {
            At {
                mu: 1.0 - z,
                w: z,
                v: 2.0 - z,
            }
        } else {
            At {
                mu: z - 1.0,
                w: 2.0 - z,
                v: z,
            }
        }
    }
}

/// The model's constants in f64.
#[derive(Clone, Copy, Debug)]
struct K {
    a: f64,
    g: f64,
    /// `L_1 = 2 (log1p(g) − log1p(−g))`.
    l1: f64,
    /// `α L_1`.
    s: f64,
    /// `e^{−s}` for `s > 0`, else `e^{s}`.
    e: f64,
    /// `expm1(−s)` for `s > 0`, else `expm1(s)`.
    m: f64,
    /// Where the inverse changes route: `F` at [`switch`](Self::switch)
    /// where both routes are finite ([`both_routes`](Self::both_routes));
    /// beyond, 0 for `s > 0` (`D` for every `u`) and `∞` for `s < 0`
    /// (`L_y` for every `u`), so the route is one comparison either way.
    u0: f64,
}

/// Up to this `|s| = |α L_1|` both routes of the inverse keep their
/// exponentials finite (`e^{|s|}` ≤ 10³⁰⁴).
const BOTH_ROUTES_S: f64 = 700.0;

impl K {
    fn new(a: f64, g: f64) -> K {
        let l1 = 2.0 * (libm::log1p(g) - libm::log1p(-g));
        let s = a * l1;
        let t = if s > 0.0 { -s } else { s };
        let mut k = K {
            a,
            g,
            l1,
            s,
            e: libm::exp(t),
            m: libm::expm1(t),
            u0: 0.0,
        };
        if !k.both_routes() {
            k.u0 = if s > 0.0 { 0.0 } else { f64::INFINITY };
        } else if g != 0.0 {
            k.u0 = k.cdf(k.switch());
        }
        k
    }
    /// Whether the inverse may take either route (`|s| ≤ 700`: every
    /// `α ≤ 0`, where `|s| ≤ 38`, and `α > 0` short of the narrowest
    /// lobes).
    fn both_routes(&self) -> bool {
        self.s.abs() <= BOTH_ROUTES_S
    }
    /// Where the two routes of the inverse are equally accurate: `1 − μ`
    /// from `D` carries an error of about `|D| ε (1 − μ)`, `1 + μ` from
    /// `L_y` one of `|L_y| ε (1 + μ)`; the first falls from `2|L_1| ε` at
    /// `μ = −1` to 0 at 1, the second rises from 0. Bisection to a few
    /// parts in 10⁴ (the two errors are comparable over a wide stretch).
    fn switch(&self) -> f64 {
        let excess = |mu: f64| {
            let at = At::of(mu);
            self.d(at).abs() * at.w - self.l_y(at).abs() * at.v
        };
        let (mut lo, mut hi) = (-1.0, 1.0);
        for _ in 0..14 {
            let mid = 0.5 * (lo + hi);
            if excess(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
    /// `expm1(α L_1)/α`, `L_1` at `α = 0` (for `s ≤ 0`).
    fn em_l1(&self) -> f64 {
        if self.a == 0.0 {
            self.l1
        } else {
            self.m / self.a
        }
    }
    /// `y = 1 + g² − 2gμ` from the end nearer to its zero: a sum of
    /// non-negative terms for either sign of `g`.
    fn y(&self, at: At) -> f64 {
        let (g, mu) = (self.g, at.mu);
        if g * mu >= 0.0 {
            // 1 − |μ|: the distance to the pole μ's sign points at.
            let ag = g.abs();
            let near = if mu >= 0.0 { at.w } else { at.v };
            (1.0 - ag) * (1.0 - ag) + 2.0 * ag * near
        } else {
            1.0 + g * g - 2.0 * g * mu
        }
    }
    /// `L_y = ln((1+g)²/y) = −log1p(−x)`, `x = 2g(1+μ)/(1+g)²`. Where
    /// `x > ½` (`μ` near 1 for `g → 1`) `1 − x` cancels, to nothing at
    /// `μ = 1` once `1 − g < 10⁻⁸`; there it is `2 log1p(g) − ln y`, with
    /// `y` from the near end, a difference of at least `ln 2`.
    fn l_y(&self, at: At) -> f64 {
        let g = self.g;
        let x = 2.0 * g * at.v / ((1.0 + g) * (1.0 + g));
        if x <= 0.5 {
            -libm::log1p(-x)
        } else {
            2.0 * libm::log1p(g) - libm::log(self.y(at))
        }
    }
    /// `D = ln(y/(1−g)²) = log1p(x)`, `x = 2g(1−μ)/(1−g)²`; where
    /// `x < −½` (`μ` near −1 for `g → −1`), `ln y − 2 log1p(−g)`, as
    /// [`l_y`](Self::l_y).
    fn d(&self, at: At) -> f64 {
        let g = self.g;
        let x = 2.0 * g * at.w / ((1.0 - g) * (1.0 - g));
        if x >= -0.5 {
            libm::log1p(x)
        } else {
            libm::log(self.y(at)) - 2.0 * libm::log1p(-g)
        }
    }
    /// `expm1(α t) / α`, `t` at `α = 0`.
    fn em(&self, t: f64) -> f64 {
        if self.a == 0.0 {
            t
        } else {
            libm::expm1(self.a * t) / self.a
        }
    }
    /// `P(cos θ ≤ μ)`.
    fn cdf(&self, mu: f64) -> f64 {
        self.cdf_at(At::of(mu))
    }
    /// [`cdf`](Self::cdf) at a cosine given with its distances to the poles.
    fn cdf_at(&self, at: At) -> f64 {
        if self.g == 0.0 {
            return 0.5 * at.v;
        }
        if self.s > 0.0 {
            // e^{−αD} expm1(−α L_y)/expm1(−α L_1): exponents ≤ 0.
            let (ly, d) = (self.l_y(at), self.d(at));
            libm::exp(-self.a * d) * libm::expm1(-self.a * ly) / self.m
        } else {
            self.em(self.l_y(at)) / self.em_l1()
        }
    }
    /// Density of `μ` (`2π p`): `dF/dμ = (2g/y) α e^{αL_y}/expm1(αL_1)`.
    fn density_mu(&self, mu: f64) -> f64 {
        self.density_at(At::of(mu))
    }
    /// [`density_mu`](Self::density_mu) at a cosine given with its
    /// distances to the poles.
    fn density_at(&self, at: At) -> f64 {
        let g = self.g;
        if g == 0.0 {
            return 0.5;
        }
        let y = self.y(at);
        let factor = if self.s > 0.0 {
            libm::exp(-self.a * self.d(at)) * self.a / -self.m
        } else {
            libm::exp(self.a * self.l_y(at)) / self.em_l1()
        };
        2.0 * g / y * factor
    }
    /// The inverse of [`cdf`](Self::cdf) for `u ∈ [0, 1]`: solved for `D`
    /// (giving `1 − μ`) or for `L_y` (giving `1 + μ`). For `α > 0` the
    /// sign of `s` picks the route whose exponents cannot overflow (the
    /// pole the kernel peaks at) where `|s| > 700`. Elsewhere (every `α ≤
    /// 0`, where `|s| ≤ 38`) either route is safe: the more accurate one
    /// at the answer (`D` for `u` at or above `F` at
    /// [`switch`](Self::switch)), so that a kernel with `g → 1` and `α < 0`
    /// keeps `1 − μ` where `1 + μ` would round it away, `μ` near 0 is not
    /// taken from a `D` of 40, and a kernel peaked at one pole keeps the
    /// distance to the other in its far tail (from `1 ± μ` near 2 it was
    /// 3·10⁻⁸ in `sin θ` at the far pole itself, `α = ½`, `g = −0.999999`).
    fn inverse(&self, u: f64) -> f64 {
        Self::mu_of(self.route(u), u)
    }
    /// [`inverse`](Self::inverse) with `sin θ` from the `1 ∓ μ` the route
    /// solved for, so that a forward lobe keeps the angle `μ` rounds away.
    fn inverse_cs(&self, u: f64) -> (f64, f64) {
        let route = self.route(u);
        let mu = Self::mu_of(route, u);
        let z = route.map_or(1.0 - mu, |(z, _)| z);
        (mu, libm::sqrt(z * (2.0 - z)))
    }
    /// `μ` from a [`route`](Self::route)'s answer (`g = 0`: `2u − 1`).
    fn mu_of(route: Option<(f64, bool)>, u: f64) -> f64 {
        route.map_or(2.0 * u - 1.0, |(z, by_d)| At::by(z, by_d).mu)
    }
    /// `(z, by_d)`: `z = 1 − μ` (`by_d`) or `1 + μ`, in `[0, 2]`, from the
    /// route [`inverse`](Self::inverse) takes; `None` for `g = 0`.
    fn route(&self, u: f64) -> Option<(f64, bool)> {
        if self.g == 0.0 {
            return None;
        }
        let by_d = u >= self.u0;
        let (z, log) = if by_d {
            self.one_minus_mu(u)
        } else {
            self.one_plus_mu(u)
        };
        let z = z.clamp(0.0, 2.0);
        // `z` comes from `expm1` of the route's logarithm, whose rounding
        // (|log| ε absolute) it multiplies: beyond |log| = 16 (`1 − |g|`
        // below about 7·10⁻⁴) that passed 8ε of backward error (18 ulp of
        // μ at `1 − g = 2.4·10⁻¹⁰`, `α = −¼`). There one Newton step on
        // the CDF, which is accurate to a few ε, takes it back.
        if log.abs() > POLISH_LOG {
            return Some((self.polish(z, by_d, u, log), by_d));
        }
        Some((z, by_d))
    }
    /// One Newton step of `F(μ) = u` from the route's `z` (`1 − μ` if
    /// `by_d`, else `1 + μ`), kept in `[0, 2]`, where it is the more
    /// accurate: the route's `z` is off by about `|log| ε z`, the step's by
    /// the CDF's rounding over the density, about `ε u / f`.
    #[cold]
    fn polish(&self, z: f64, by_d: bool, u: f64, log: f64) -> f64 {
        // At z itself, not at μ = 1 ∓ z rounded: where the lobe is
        // narrower than the floats' spacing near its pole, a step from the
        // rounded point moved with u by less than its own linearisation
        // error, and μ stepped back by an ulp as u rose (α = ½,
        // 1 − g = 7.3·10⁻¹², u = 2.7·10⁻⁴).
        let at = At::by(z, by_d);
        let f = self.density_at(at);
        // In a peaked kernel's far tail the density is small, and a step
        // there added the CDF's rounding over it: 3.3·10⁻¹¹ in μ at α = ½,
        // g = −0.999999, u = 1 − 10⁻⁶ (the route alone: 10⁻¹⁶).
        if !(f > 0.0 && f.is_finite()) || u > log.abs() * z * f {
            return z;
        }
        let step = (u - self.cdf_at(at)) / f;
        let z = if by_d { z - step } else { z + step };
        z.clamp(0.0, 2.0)
    }
    /// `(e^{±s}, expm1(±s))` (upper sign for `positive`) from the stored
    /// `(e^{∓s}, expm1(∓s))`: the mirrored pair is formed only where
    /// [`both_routes`](Self::both_routes) (`|s| ≤ 700`, so the stored
    /// `e^{−|s|}` is a normal float and its reciprocal finite).
    fn exp_pair(&self, positive: bool) -> (f64, f64) {
        if (self.s > 0.0) != positive {
            (self.e, self.m)
        } else {
            (1.0 / self.e, -self.m / self.e)
        }
    }
    /// `1 − μ` from `e^{−αD} = u + (1 − u) e^{−s}`:
    /// `1 − μ = (1 − g)² expm1(D)/(2g)`; and `D`.
    fn one_minus_mu(&self, u: f64) -> (f64, f64) {
        let (a, g) = (self.a, self.g);
        let d = if a == 0.0 {
            (1.0 - u) * self.l1
        } else {
            let (e, m) = self.exp_pair(false);
            // The direct sum only where it is far from 1 (else its log
            // would cancel): there log1p of the small product is exact.
            let direct = u + (1.0 - u) * e;
            if direct < 0.5 {
                -libm::log(direct) / a
            } else {
                -libm::log1p((1.0 - u) * m) / a
            }
        };
        ((1.0 - g) * (1.0 - g) * libm::expm1(d) / (2.0 * g), d)
    }
    /// `1 + μ` from `e^{αL_y} = (1 − u) + u e^{s}`:
    /// `1 + μ = −(1 + g)² expm1(−L_y)/(2g)`; and `L_y`.
    fn one_plus_mu(&self, u: f64) -> (f64, f64) {
        let (a, g) = (self.a, self.g);
        let ly = if a == 0.0 {
            u * self.l1
        } else {
            let (e, m) = self.exp_pair(true);
            let direct = (1.0 - u) + u * e;
            if direct < 0.5 {
                libm::log(direct) / a
            } else {
                libm::log1p(u * m) / a
            }
        };
        (-(1.0 + g) * (1.0 + g) * libm::expm1(-ly) / (2.0 * g), ly)
    }
}

impl<T: Real> PhaseFunction<T> for Gegenbauer<T> {
    /// `p = dF/dμ / 2π`, evaluated in f64 without overflow.
    fn pdf(&self, cos_theta: T) -> T {
        let k = self.constants();
        T::from_f64(k.density_mu(cos_theta.to_f64()) / core::f64::consts::TAU)
    }
    fn cdf(&self, cos_theta: T) -> T {
        let mu = cos_theta.to_f64();
        if mu.is_nan() {
            return T::NAN;
        }
        let k = self.constants();
        T::from_f64(k.cdf(mu.clamp(-1.0, 1.0)).clamp(0.0, 1.0))
    }
    fn sample_cos(&self, u: T) -> T {
        let u = u.clamp01().to_f64();
        if u.is_nan() {
            return T::NAN;
        }
        let k = self.constants();
        T::from_f64(k.inverse(u))
    }
    /// `sin θ` from the `1 ∓ μ` the inverse solved for, in f64: in f32 a
    /// forward lobe with `1 − g ≲ 10⁻⁴` lies within a few spacings of
    /// floats below 1, whose `sin θ` would be quantised.
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let u = u.clamp01().to_f64();
        if u.is_nan() {
            return (T::NAN, T::NAN);
        }
        let (mu, sin) = self.constants().inverse_cs(u);
        (T::from_f64(mu), T::from_f64(sin))
    }
    /// `⟨μ⟩` in closed form (the module function `mean_cosine`).
    fn mean_cosine(&self) -> T {
        T::from_f64(mean_cosine(self.alpha.to_f64(), self.g.to_f64()))
    }
}

/// `⟨μ⟩` in f64. With `t = 1 + g² − 2gμ` the density is `∝ t^−(α+1)`, so
/// `⟨μ⟩ = (1 + g² − ⟨t⟩)/(2g)` with `⟨t⟩ = ∫ t^−α dt / ∫ t^−(α+1) dt` over
/// `[a, b] = [(1 − |g|)², (1 + |g|)²]`. Taking `a^−α` out of both integrals,
/// with `L = ln(a/b) = −4 atanh|g|` and `φ(x) = (e^{xL} − 1)/x` (`L` at
/// `x = 0`), `⟨t⟩ = a φ(α − 1)/φ(α)`: `expm1` keeps it exact through
/// `α = 1` and `α = 0`, where the textbook form (Reynolds & McCormick's
/// eq. 11) divides zero by zero, and nothing overflows at `α = 1000`.
/// The subtraction from `1 + g²` and the division by `2g` cost a factor
/// `1/|g|`: within `2ε/|g|` of 40-digit quadrature (tests) for
/// `|g| ≥ 10⁻³`. Below that the mean of the inverse CDF by Simpson's rule
/// (extrapolated) takes over, where the density is within `e^{4α|g|} ≤ e⁴`
/// of flat (10⁻¹³, tests).
fn mean_cosine(a: f64, g: f64) -> f64 {
    if g == 0.0 {
        return 0.0;
    }
    let ag = g.abs();
    if ag < 1e-3 {
        let k = K::new(a, g);
        return simpson_unit(|u| k.inverse(u), 4096);
    }
    let l = -4.0 * libm::atanh(ag);
    let phi = |x: f64| if x == 0.0 { l } else { libm::expm1(x * l) / x };
    let t_mean = (1.0 - ag) * (1.0 - ag) * phi(a - 1.0) / phi(a);
    (1.0 + g * g - t_mean) / (2.0 * g)
}

/// Below this `g` the low moments come from the series
/// ([`low_moments_series`]): the closed form divides by `(2g)³`.
const SERIES_BELOW_G: f64 = 0.1;

/// The Legendre moments `[χ_1, χ_2, χ_3]` of the kernel with `α > −½` and
/// `0 < g < 1`, in f64: the closed form of [`low_moments_closed`] for
/// `g ≥ 0.1` (within about 10⁻¹³, the cube of `(1 + g²)/2g` times a few
/// ε), the all-positive series of [`low_moments_series`] below.
pub(crate) fn low_moments(a: f64, g: f64) -> [f64; 3] {
    if g >= SERIES_BELOW_G {
        low_moments_closed(a, g)
    } else {
        low_moments_series(a, g)
    }
}

/// With `t = 1 + g² − 2gμ` (density `∝ t^{−(α+1)}` on
/// `[b_−, b_+] = [(1 − g)², (1 + g)²]`), `⟨t^k⟩ = b_−^k φ(α − k)/φ(α)` with
/// `φ(x) = expm1(xL)/x`, `L = −4 atanh g` (as in `mean_cosine`), and
/// `μ = (c − t)/2g`, `c = 1 + g²`, so the raw moments `⟨μ^k⟩` are
/// binomial sums in `⟨t^j⟩`; then `χ_1 = ⟨μ⟩`, `χ_2 = (3⟨μ²⟩ − 1)/2`,
/// `χ_3 = (5⟨μ³⟩ − 3⟨μ⟩)/2`.
fn low_moments_closed(a: f64, g: f64) -> [f64; 3] {
    let l = -4.0 * libm::atanh(g);
    let phi = |x: f64| if x == 0.0 { l } else { libm::expm1(x * l) / x };
    let (b, p0) = ((1.0 - g) * (1.0 - g), phi(a));
    let t1 = b * phi(a - 1.0) / p0;
    let t2 = b * b * phi(a - 2.0) / p0;
    let t3 = b * b * b * phi(a - 3.0) / p0;
    let (c, h) = (1.0 + g * g, 2.0 * g);
    let m1 = (c - t1) / h;
    let m2 = (c * c - 2.0 * c * t1 + t2) / (h * h);
    let m3 = (c * c * c - 3.0 * c * c * t1 + 3.0 * c * t2 - t3) / (h * h * h);
    [m1, 0.5 * (3.0 * m2 - 1.0), 0.5 * (5.0 * m3 - 3.0 * m1)]
}

/// The moments from the kernel's expansion in Gegenbauer polynomials,
/// `t^{−λ} = Σ_n C_n^λ(μ) g^n` (`λ = α + 1`), and the connection formula
/// `C_n^λ = Σ_k (λ)_{n−k} (λ − ½)_k (n − 2k + ½) / ((½)_{n−k+1} k!) P_{n−2k}`:
/// orthogonality of the `P_l` leaves
/// `χ_l = Σ_k N_k / Σ_k D_k` with `N_0 = g^l (λ)_l / (2 (½)_{l+1})`,
/// `N_{k+1}/N_k = g² (λ + l + k)(λ − ½ + k) / ((l + k + 3/2)(k + 1))`, and
/// `D_k` the same with `l = 0` (`D_0 = 1`). For `α > −½` and `g > 0` every
/// term is positive, so the sums lose nothing; they stop once a term no
/// longer moves the sum (the ratio falls below `g²` times a bounded factor
/// once `k` passes `λ`; a few hundred terms at `α = 1000`, `g = 0.1`).
fn low_moments_series(a: f64, g: f64) -> [f64; 3] {
    let lam = a + 1.0;
    let g2 = g * g;
    let sum = |l: f64, first: f64| {
        let (mut term, mut total, mut k) = (first, first, 0.0);
        while k < 10_000.0 {
            term *= g2 * (lam + l + k) * (lam - 0.5 + k) / ((l + k + 1.5) * (k + 1.0));
            let next = total + term;
            if next == total && k > lam {
                break;
            }
            total = next;
            k += 1.0;
        }
        total
    };
    let d = sum(0.0, 1.0);
    // N_0 = g^l (λ)_l / (2 (½)_{l+1}).
    let n1 = g * lam / (2.0 * 0.5 * 1.5);
    let n2 = g2 * lam * (lam + 1.0) / (2.0 * 0.5 * 1.5 * 2.5);
    let n3 = g2 * g * lam * (lam + 1.0) * (lam + 2.0) / (2.0 * 0.5 * 1.5 * 2.5 * 3.5);
    [sum(1.0, n1) / d, sum(2.0, n2) / d, sum(3.0, n3) / d]
}

impl<T: Real> Model<T> for Gegenbauer<T> {
    type In<U: Real> = Gegenbauer<U>;
    const PARAMS: usize = 2;
    fn params(&self) -> [T; 4] {
        [self.alpha, self.g, T::ZERO, T::ZERO]
    }
    fn from_params(p: &[T]) -> Result<Self, Error> {
        let [alpha, g] = exactly(p)?;
        Self::new(alpha, g)
    }
    fn cast<U: Real>(&self) -> Gegenbauer<U> {
        // α just above −½ can round onto it: then a valid α just above
        // (−½ + 10⁻⁷, which f32 holds as −0.49999991).
        let alpha = to::<T, U>(self.alpha);
        let alpha = if alpha.to_f64() > -0.5 {
            alpha
        } else {
            U::from_f64(-0.5 + 1e-7)
        };
        Gegenbauer::from_parts(alpha, open(self.g))
    }
    fn lobes(&self) -> Option<Lobes> {
        None
    }
}
