//! The multiple-scattering albedo of a layer (the share of light a
//! medium reflects after any number of scatterings) as a function of its
//! single-scattering albedo `ω = σ_s/σ_t`, for any phase function, and its
//! inverse: the `ω` that makes a layer look a given colour. Material
//! standards specify subsurface and volume colour this way and convert it
//! with fitted formulas (van de Hulst's similarity fit, Kulla & Conty
//! 2017); `docs/guides/media.md` measures those against this transport.
//!
//! **Transport.** A plane-parallel layer, semi-infinite or a slab of
//! optical thickness `τ`, with index-matched boundaries (no Fresnel
//! reflection: the standards' fits assume the same), lit diffusely
//! (uniform incident radiance: the "spherical" or bihemispherical albedo)
//! or by a parallel beam at `μ_0 = cos θ_0` (the plane albedo). Paths are
//! traced once with `ω = 1`: free paths `−ln(1 − u)` in optical depth,
//! directions from the phase function's own sampler. A path that leaves
//! through the lit face after `N` scatterings contributes `ω^N` to the
//! albedo at every `ω` at once, so one set of paths gives the whole curve
//! and the curve is strictly monotone in `ω` for any sample (each
//! contribution is). The curve is kept at [`NODES`] values
//! `ω_k = 1 − (k/64)²` (even in `s = √(1 − ω)`, the variable in which the
//! albedo is smooth near `ω = 1`: `1 − a s + b s² + …`) and interpolated
//! between them by a monotone cubic (Fritsch–Carlson), except between the
//! first two nodes (`1 − 1/4096 < ω ≤ 1`), where the curvature is large
//! and the cubic through the first four nodes is taken (where monotone);
//! the inverse solves the interpolant by bisection. The reported error
//! includes the interpolation's (see [`AlbedoCurve::std_error`]). Paths are cut after [`MAX_EVENTS`] scatterings, where the
//! largest `ω` below 1 weighs them by `e^{−16}`; for the semi-infinite
//! layer the value at `ω = 1` is 1 (every path returns), not estimated,
//! and for a slab a cut path adds to the value at `ω = 1` the share of
//! its light diffusion sends back through the lit face from its depth
//! (a path cut there is not absorbed; dropped, it put a deep slab's albedo
//! at `ω = 1` 1.2 % low).
//!
//! **Where the nodes do not reach.** A slab thick against its diffusion
//! length bends between `ω = 1` and the first node, on a scale of
//! `1 − ω ≈ 1/(3 τ² (1 − g))`, from its own albedo at `ω = 1` onto the
//! semi-infinite curve, and two nodes do not resolve that bend. Against
//! adding-doubling (iadpython 0.5.3; HG g = 0, 0.5, 0.85, 0.9, 0.95,
//! 0.99; τ from 1 to 10⁴ and semi-infinite; beam and diffuse; 20 000
//! paths): at 273 points at the nodes' reach (`ω ≤ 1 − 1/4096`, or `ω = 1`)
//! the largest |z| is 2.7; at 126 points inside the first interval 16
//! slabs lie beyond 3σ, all low, up to 0.8 % (τ = 1000, g = 0.9,
//! `ω = 0.99999`: 6.8σ); semi-infinite layers there stay within 2.7σ.
//! Finer nodes there would need paths far longer than [`MAX_EVENTS`] (at
//! `1 − ω = 10⁻⁵` a path cut at 2¹⁶ still weighs `e^{−0.66}`).

use crate::error::Error;
use crate::math::real::Real;
use crate::phase::PhaseFunction;
use rand_core::Rng;

/// Nodes of the albedo curve: `ω_k = 1 − (k/64)²`, `k = 0 … 64`.
pub const NODES: usize = 65;

/// The most scatterings a path takes before it is dropped (2¹⁶): the
/// largest `ω` below 1 among the nodes, `1 − 64⁻²`, weighs such a path by
/// `(1 − 64⁻²)^{2¹⁶} = e^{−16}` ≈ 1.1·10⁻⁷, so dropping it biases that
/// node by less than 1.1·10⁻⁷ times the share of paths dropped.
pub const MAX_EVENTS: u32 = 1 << 16;

/// The layer: semi-infinite, or a slab of optical thickness `τ` (finite,
/// positive) with nothing beneath (light leaving the bottom is lost).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Layer {
    /// Infinitely deep.
    SemiInfinite,
    /// Of optical thickness `τ = σ_t · thickness`.
    Slab(f64),
}

/// How the layer is lit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Illumination {
    /// Uniform incident radiance from the whole hemisphere (incident
    /// cosines with density `2μ`): the spherical (bihemispherical)
    /// albedo, which the material standards' fits describe.
    Diffuse,
    /// A parallel beam at `μ_0 = cos θ_0 ∈ (0, 1]` from the normal.
    Directional(f64),
}

/// The multiple-scattering albedo of one layer, phase function and
/// illumination as a function of `ω` (module docs): a Monte Carlo
/// estimate at [`NODES`] values of `ω` with its standard errors,
/// interpolated monotonically, and inverted.
///
/// # Example
///
/// The single-scattering albedo that makes a deep HG (g = 0.8) medium
/// reflect half the light falling on it diffusely:
///
/// ```
/// use rand_xoshiro::rand_core::SeedableRng;
/// use scatterkit::transport::albedo::{AlbedoCurve, Illumination, Layer};
/// use scatterkit::HenyeyGreenstein;
///
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7);
/// let hg = HenyeyGreenstein::new(0.8).unwrap();
/// let curve = AlbedoCurve::simulate(&hg, Layer::SemiInfinite, Illumination::Diffuse, 4000, &mut rng)
///     .unwrap();
/// let omega = curve.single_scattering_albedo(0.5).unwrap();
/// assert!(omega > 0.97 && omega < 0.995);
/// assert!((curve.albedo(omega) - 0.5).abs() < 1e-9);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct AlbedoCurve {
    /// The albedo at each node.
    rho: [f64; NODES],
    /// Its standard error.
    se: [f64; NODES],
    /// Fritsch–Carlson slopes of `ρ` in `s` at each node (per node step).
    slope: [f64; NODES],
    paths: u64,
}

/// `s = √(1 − ω)` at node `k`.
fn node_s(k: usize) -> f64 {
    k as f64 / (NODES - 1) as f64
}

impl AlbedoCurve {
    /// Traces `paths ≥ 1` paths through `layer` lit by `light`, scattering
    /// by `phase` (f64), with uniforms from `rng`. [`Error::Domain`] for
    /// `paths = 0`, a slab thickness not finite and positive, or `μ_0`
    /// outside `(0, 1]`. Cost: the paths' scatterings (a deep medium with
    /// a forward phase function takes many: about 10³ per path at
    /// `g = 0.9`), plus 65 exponentials per reflected path.
    pub fn simulate<P: PhaseFunction<f64> + ?Sized, R: Rng + ?Sized>(
        phase: &P,
        layer: Layer,
        light: Illumination,
        paths: u64,
        rng: &mut R,
    ) -> Result<Self, Error> {
        let slab_ok = match layer {
            Layer::SemiInfinite => true,
            Layer::Slab(tau) => tau.is_finite() && tau > 0.0,
        };
        let light_ok = match light {
            Illumination::Diffuse => true,
            Illumination::Directional(mu0) => mu0 > 0.0 && mu0 <= 1.0,
        };
        if paths == 0 || !slab_ok || !light_ok {
            return Err(Error::Domain);
        }
        let mut ln_omega = [0.0; NODES];
        for (k, l) in ln_omega.iter_mut().enumerate() {
            let s = node_s(k);
            // ln(1 − s²) without cancellation for small s.
            *l = libm::log1p(-s * s);
        }
        let (mut sum, mut sum2) = ([0.0; NODES], [0.0; NODES]);
        let g = phase.mean_cosine();
        for _ in 0..paths {
            match walk(phase, layer, light, rng) {
                End::Reflected(n) => {
                    for k in 0..NODES {
                        let w = libm::exp(n as f64 * ln_omega[k]);
                        sum[k] += w;
                        sum2[k] += w * w;
                    }
                }
                // At ω = 1 a cut path is not absorbed: it leaves through
                // one face or the other. Dropped, it biased a deep slab's
                // albedo at ω = 1 low by the share of paths cut (1.25 %
                // at τ = 10⁴, HG 0.85, diffuse light: 22σ below
                // adding-doubling). Below ω = 1 it weighs at most e^{−16}.
                End::Cut(z) => {
                    if let Layer::Slab(tau) = layer {
                        let w = lit_face_share(z, tau, g);
                        sum[0] += w;
                        sum2[0] += w * w;
                    }
                }
                End::Lost => {}
            }
        }
        let m = paths as f64;
        let (mut rho, mut se) = ([0.0; NODES], [0.0; NODES]);
        for k in 0..NODES {
            rho[k] = sum[k] / m;
            let var = (sum2[k] / m - rho[k] * rho[k]).max(0.0);
            se[k] = (var / m).sqrt();
        }
        if layer == Layer::SemiInfinite {
            // ω = 1: nothing is absorbed and nothing leaves below.
            rho[0] = 1.0;
            se[0] = 0.0;
        }
        Ok(AlbedoCurve {
            rho,
            se,
            slope: fritsch_carlson(&rho),
            paths,
        })
    }

    /// A curve from node values stored earlier ([`nodes`](Self::nodes)):
    /// the albedos and standard errors at the [`NODES`] values of `ω`, and
    /// the number of paths; the interpolant is rebuilt from them.
    pub fn from_nodes(rho: [f64; NODES], se: [f64; NODES], paths: u64) -> Self {
        AlbedoCurve {
            rho,
            se,
            slope: fritsch_carlson(&rho),
            paths,
        }
    }

    /// The albedos and their standard errors at the nodes
    /// `ω_k = 1 − (k/64)²` (for storing the curve).
    pub fn nodes(&self) -> ([f64; NODES], [f64; NODES]) {
        (self.rho, self.se)
    }

    /// The number of paths traced.
    pub fn paths(&self) -> u64 {
        self.paths
    }

    /// Node `k < NODES`: `(ω_k, albedo, standard error)`.
    pub fn node(&self, k: usize) -> Option<(f64, f64, f64)> {
        let s = node_s(k);
        Some((1.0 - s * s, *self.rho.get(k)?, *self.se.get(k)?))
    }

    /// The multiple-scattering albedo at single-scattering albedo
    /// `ω ∈ [0, 1]` (NaN outside or for NaN): the monotone cubic through
    /// the nodes, in `s = √(1 − ω)`.
    pub fn albedo(&self, omega: f64) -> f64 {
        if !(0.0..=1.0).contains(&omega) {
            return f64::NAN;
        }
        self.at_s(libm::sqrt(1.0 - omega))
    }

    /// The error of [`albedo`](Self::albedo) at `ω` as one standard
    /// deviation (NaN outside `[0, 1]`): the Monte Carlo part and the
    /// interpolation's, in quadrature. The Monte Carlo part combines the
    /// nodes' standard errors with the interpolant's weights as errors
    /// fully correlated (one set of paths gives every node, and `ω^N`
    /// at neighbouring nodes moves together): `|Σ weight × error|`, linear
    /// between two nodes. The interpolation part is the next term of the
    /// interpolating polynomial, `|Δ⁴ρ|/4! · |Π(t − t_j)|` over the four
    /// nodes around `ω` (the fourth difference over five nodes); it also
    /// carries the nodes' noise, so it errs high. At a node both are the
    /// node's own error; at `ω = 1` of a semi-infinite layer, 0.
    pub fn std_error(&self, omega: f64) -> f64 {
        if !(0.0..=1.0).contains(&omega) {
            return f64::NAN;
        }
        let (i, t) = interval(libm::sqrt(1.0 - omega));
        let e = |k: usize| self.se.get(k).copied().unwrap_or(f64::NAN);
        let y = |k: usize| self.rho.get(k).copied().unwrap_or(f64::NAN);
        let monte_carlo = if i == 0 && self.near_one(t).is_some() {
            // The cubic's Lagrange weights on nodes 0..3 at t.
            let w = [
                -(t - 1.0) * (t - 2.0) * (t - 3.0) / 6.0,
                t * (t - 2.0) * (t - 3.0) / 2.0,
                -t * (t - 1.0) * (t - 3.0) / 2.0,
                t * (t - 1.0) * (t - 2.0) / 6.0,
            ];
            libm::fabs((0..4).map(|k| w[k] * e(k)).sum::<f64>())
        } else {
            e(i) + t * (e(i + 1) - e(i))
        };
        // The four nodes j..j+3 around the interval (t − j measured from
        // node j), and the fourth difference over j..j+4 (or j−1..j+3
        // at the last nodes).
        let j = i.saturating_sub(1).min(NODES - 4);
        let x = (i - j) as f64 + t;
        let first = j.min(NODES - 5);
        let d4 =
            y(first) - 4.0 * y(first + 1) + 6.0 * y(first + 2) - 4.0 * y(first + 3) + y(first + 4);
        let poly = x * (x - 1.0) * (x - 2.0) * (x - 3.0);
        let interpolation = libm::fabs(d4 / 24.0 * poly);
        libm::sqrt(monte_carlo * monte_carlo + interpolation * interpolation)
    }

    /// The single-scattering albedo `ω` whose multiple-scattering albedo
    /// is `albedo`, by bisection on the monotone interpolant (within
    /// 10⁻¹⁵ in `s`). [`Error::Domain`] for NaN or an `albedo` outside
    /// what the layer reaches, `[0, albedo(1)]` (1 for a semi-infinite
    /// layer; less for a slab, which lets light through).
    pub fn single_scattering_albedo(&self, albedo: f64) -> Result<f64, Error> {
        let top = self.rho[0];
        if !(albedo >= 0.0 && albedo <= top) {
            return Err(Error::Domain);
        }
        // ρ falls as s rises: find s with ρ(s) = albedo.
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.at_s(mid) > albedo {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let s = 0.5 * (lo + hi);
        Ok(1.0 - s * s)
    }

    /// The interpolant at `s ∈ [0, 1]`: in the first interval the cubic
    /// through the first four nodes ([`near_one`](Self::near_one)), where
    /// it is monotone; elsewhere the monotone cubic Hermite.
    fn at_s(&self, s: f64) -> f64 {
        let (i, t) = interval(s);
        if i == 0 {
            if let Some(v) = self.near_one(t) {
                return v;
            }
        }
        self.hermite(i, t)
    }

    /// Near `ω = 1` the albedo is `1 − a s + b s² + …` with a large
    /// curvature (for g = 0.9, `b s²` at the first node is a tenth of
    /// `a s`), and the Hermite cubic, whose slope at `s = 0` is the first
    /// interval's secant, lay above the curve there by up to 1.5·10⁻³ (18σ
    /// at `ω = 0.99999`, HG g = 0.9, 10⁵ paths). The cubic through nodes
    /// 0–3 follows the curvature (its error is fourth order in the node
    /// spacing); it is used at `t ∈ [0, 1]` of the first interval if it is
    /// monotone there, `None` otherwise.
    fn near_one(&self, t: f64) -> Option<f64> {
        let y = |k: usize| self.rho.get(k).copied();
        let (y0, y1, y2, y3) = (y(0)?, y(1)?, y(2)?, y(3)?);
        // Newton's divided differences on the nodes 0, 1, 2, 3 (step 1 in t).
        let d1 = y1 - y0;
        let d2 = (y2 - 2.0 * y1 + y0) / 2.0;
        let d3 = (y3 - 3.0 * y2 + 3.0 * y1 - y0) / 6.0;
        let p = |t: f64| y0 + t * (d1 + (t - 1.0) * (d2 + (t - 2.0) * d3));
        // p'(t) = d1 + d2 (2t − 1) + d3 (3t² − 6t + 2): a quadratic, whose
        // largest value on [0, 1] is at an end or at its vertex
        // t = 1 − d2/(3 d3) when that lies inside.
        let slope = |t: f64| d1 + d2 * (2.0 * t - 1.0) + d3 * (3.0 * t * t - 6.0 * t + 2.0);
        let vertex = 1.0 - d2 / (3.0 * d3);
        let inside = vertex > 0.0 && vertex < 1.0;
        if slope(0.0) > 0.0 || slope(1.0) > 0.0 || (inside && slope(vertex) > 0.0) {
            return None;
        }
        // Held between its ends as the Hermite cubic is (by comparisons:
        // `clamp` would panic on ends out of order, and the C layer's
        // entry points must not).
        let v = p(t);
        Some(if v > y0 {
            y0
        } else if v < y1 {
            y1
        } else {
            v
        })
    }

    /// The monotone cubic Hermite interpolant on interval `i` at `t`.
    fn hermite(&self, i: usize, t: f64) -> f64 {
        let v = |a: &[f64; NODES], k: usize| a.get(k).copied().unwrap_or(f64::NAN);
        let (y0, y1) = (v(&self.rho, i), v(&self.rho, i + 1));
        let (d0, d1) = (v(&self.slope, i), v(&self.slope, i + 1));
        let dy = y1 - y0;
        let c2 = 3.0 * dy - 2.0 * d0 - d1;
        let c3 = d0 + d1 - 2.0 * dy;
        // The monotone cubic stays between its ends; the clamp only keeps
        // rounding from leaving them (an albedo of −10⁻¹⁸ at ω = 0).
        let v = y0 + t * (d0 + t * (c2 + t * c3));
        if v > y0 {
            y0
        } else if v < y1 {
            y1
        } else {
            v
        }
    }
}

/// The node interval `i` holding `s ∈ [0, 1]` and the position `t ∈ [0, 1]`
/// in it.
fn interval(s: f64) -> (usize, f64) {
    let x = s * (NODES - 1) as f64;
    let i = (x as usize).min(NODES - 2);
    (i, x - i as f64)
}

/// One path with `ω = 1`: how it ended ([`End`]: through the lit face
/// after `N` scatterings, through a slab's bottom, or cut after
/// [`MAX_EVENTS`] at a depth). Only the depth `z` (optical) and the
/// direction cosine `μ` to the inward normal matter in a plane-parallel
/// layer.
fn walk<P: PhaseFunction<f64> + ?Sized, R: Rng + ?Sized>(
    phase: &P,
    layer: Layer,
    light: Illumination,
    rng: &mut R,
) -> End {
    let mut mu = match light {
        // Incident cosines with density 2μ: μ = √u.
        Illumination::Diffuse => libm::sqrt(f64::uniform(rng)),
        Illumination::Directional(mu0) => mu0,
    };
    let mut z = 0.0;
    for n in 0..=MAX_EVENTS {
        z += mu * -libm::log1p(-f64::uniform(rng));
        if z < 0.0 {
            return End::Reflected(n);
        }
        if let Layer::Slab(tau) = layer {
            if z > tau {
                return End::Lost;
            }
        }
        // Scatter: the new direction cosine from cos θ and the azimuth.
        let c = phase.sample_cos(f64::uniform(rng));
        let phi = core::f64::consts::TAU * f64::uniform(rng);
        let (s, sm) = (
            (1.0 - c * c).max(0.0).sqrt(),
            (1.0 - mu * mu).max(0.0).sqrt(),
        );
        mu = (mu * c + sm * s * libm::cos(phi)).clamp(-1.0, 1.0);
    }
    End::Cut(z)
}

/// How a path ended.
enum End {
    /// Back out through the lit face after this many scatterings.
    Reflected(u32),
    /// Out through the bottom of a slab.
    Lost,
    /// Cut after [`MAX_EVENTS`] scatterings, at this optical depth.
    Cut(f64),
}

/// The share of the light at optical depth `z` of a conservative slab of
/// thickness `τ` that leaves through the lit face, by diffusion: a path
/// cut after [`MAX_EVENTS`] scatterings has long forgotten its direction
/// (2¹⁶ (1 − g) transport events). With the extrapolated boundary
/// `z_e = 0.7104 / (1 − g)` beyond each face (Milne's extrapolation length
/// in transport mean free paths), the diffusion solution between them is
/// linear: `(τ + z_e − z) / (τ + 2 z_e)`. 0 for `g = 1` (a path that never
/// turns does not come back).
fn lit_face_share(z: f64, tau: f64, g: f64) -> f64 {
    // g ≥ 1 or NaN: no diffusion to speak of.
    if g.is_nan() || g >= 1.0 {
        return 0.0;
    }
    let ze = 0.7104 / (1.0 - g);
    ((tau + ze - z) / (tau + 2.0 * ze)).clamp(0.0, 1.0)
}

/// Fritsch–Carlson slopes (per node step) for values `y` that fall with
/// the node index: the three-point estimate clamped to `[3Δ, 0]` of both
/// neighbouring secants `Δ` (≤ 0), so the cubic Hermite interpolant is
/// monotone.
fn fritsch_carlson(y: &[f64; NODES]) -> [f64; NODES] {
    let mut d = [0.0; NODES];
    let v = |k: usize| y.get(k).copied().unwrap_or(f64::NAN);
    for (k, dk) in d.iter_mut().enumerate() {
        let left = if k > 0 { v(k) - v(k - 1) } else { v(1) - v(0) };
        let right = if k + 1 < NODES { v(k + 1) - v(k) } else { left };
        let mut s = 0.5 * (left + right);
        for secant in [left, right] {
            s = s.max(3.0 * secant).min(0.0);
        }
        if left * right <= 0.0 {
            s = 0.0;
        }
        *dk = s;
    }
    d
}
