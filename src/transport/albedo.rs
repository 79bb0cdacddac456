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
//! **Between the first two nodes.** A slab thick against its diffusion
//! length bends between `ω = 1` and the first node, on a scale of
//! `1 − ω ≈ 1/(3 τ² (1 − g))`, from its own albedo at `ω = 1` onto the
//! semi-infinite curve; a slab's curve keeps [`FINE`] more nodes there, at
//! `s = 2^{−(j+1)}/64` (`1 − ω` from 1/16384 to 2.3·10⁻¹⁰), and
//! interpolates them by a monotone cubic in `s`. At those `ω` a path cut
//! after [`MAX_EVENTS`] scatterings still weighs `ω^{2¹⁶}` (`e^{−4}` at
//! the first fine node, nearly 1 at the last), so it adds that times the
//! share of its light diffusion returns through the lit face with
//! absorption (Milne's extrapolated boundaries, `κ = √(3(1 − ω)(1 − ωg))`).
//! Against adding-doubling (iadpython 0.5.3; HG g = 0 to 0.99, τ = 1 to 10⁴ and semi-infinite, beam and
//! diffuse, `ω` from 0.1 to 0.999999, 20 000 paths), with the fine nodes
//! for every layer the 126 points inside the first interval had a mean z
//! of −0.02 and none beyond 3σ (with the
//! first two nodes alone, the cubic through nodes 0–3: mean −0.88, 16
//! beyond 3σ, all slabs, up to 0.8 % low at τ = 1000, g = 0.9,
//! `ω = 0.99999`); the 273 others are unchanged (largest |z| 2.7). A
//! semi-infinite layer, smooth in `s` there, keeps that cubic: with the
//! fine nodes, which lean on the diffusion share of the paths cut, `1 − ω`
//! at A = 0.99 came out 1.06 % off at 10⁷ paths (g = 0.5, beam) where the
//! cubic holds 0.35 %. So does a curve rebuilt from the coarse nodes
//! alone ([`AlbedoCurve::from_nodes`]).

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

/// Fine nodes inside the first interval, `s_j = 2^{−(j+1)}/64`,
/// `j = 0 … 9` (`1 − ω` from 1/16384 down to 2.3·10⁻¹⁰): a slab thick
/// against its diffusion length bends there, on a scale of
/// `1 − ω ≈ 1/(3τ²(1 − g))`, which the first two nodes do not resolve.
pub const FINE: usize = 10;

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
    /// The fine nodes ([`FINE`]), if the curve has them (a curve rebuilt
    /// from the coarse nodes alone does not).
    fine: Option<Fine>,
    paths: u64,
}

/// The first interval on its fine nodes: the albedo and its error at the
/// grid `s_k = 2^{k − FINE}/64`, `k = 0 … FINE` (the fine nodes from the
/// smallest, then node 1), and monotone slopes `dρ/ds` there. The grid is
/// geometric, and the interpolation is in `s` itself: where the curve is
/// near `1 − a s` (a semi-infinite layer, a slab beyond its bend) a cubic
/// in `log s` bent between the nodes (3σ at 10⁵ paths).
#[derive(Clone, Copy, Debug)]
struct Fine {
    y: [f64; FINE + 1],
    se: [f64; FINE + 1],
    slope: [f64; FINE + 1],
}

/// `s = √(1 − ω)` at node `k`.
fn node_s(k: usize) -> f64 {
    k as f64 / (NODES - 1) as f64
}

/// `s = √(1 − ω)` at fine node `j`: `2^{−(j+1)}/64`.
fn fine_s(j: usize) -> f64 {
    libm::ldexp(1.0 / (NODES - 1) as f64, -(j as i32) - 1)
}

impl AlbedoCurve {
    /// Traces `paths ≥ 1` paths through `layer` lit by `light`, scattering
    /// by `phase` (f64), with uniforms from `rng`. [`Error::Domain`] for
    /// `paths = 0`, a slab thickness not finite and positive, or `μ_0`
    /// outside `(0, 1]`. Cost: the paths' scatterings (a deep medium with
    /// a forward phase function takes many: about 10³ per path at
    /// `g = 0.9`), plus 65 exponentials per reflected path (75 in a
    /// slab, and 10 per path a slab cuts after [`MAX_EVENTS`] scatterings).
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
        // 1 − ω_j and ln ω_j at the fine nodes.
        let mut fine_omega = [(0.0, 0.0); FINE];
        for (j, f) in fine_omega.iter_mut().enumerate() {
            let s = fine_s(j);
            *f = (s * s, libm::log1p(-s * s));
        }
        let (mut fsum, mut fsum2) = ([0.0; FINE], [0.0; FINE]);
        let g = phase.mean_cosine();
        for _ in 0..paths {
            match walk(phase, layer, light, rng) {
                End::Reflected(n) => {
                    for k in 0..NODES {
                        let w = libm::exp(n as f64 * ln_omega[k]);
                        sum[k] += w;
                        sum2[k] += w * w;
                    }
                    // The fine nodes serve slabs alone (below).
                    if layer != Layer::SemiInfinite {
                        for (j, &(_, ln)) in fine_omega.iter().enumerate() {
                            let w = libm::exp(n as f64 * ln);
                            fsum[j] += w;
                            fsum2[j] += w * w;
                        }
                    }
                }
                // A cut path is not absorbed at ω = 1, and at the fine
                // nodes it still weighs ω^{2¹⁶} (e^{−4} at the first):
                // it adds that times the share diffusion returns through
                // the lit face from its depth. Dropped, it biased a deep
                // slab's albedo at ω = 1 low by the share of paths cut
                // (1.25 % at τ = 10⁴, HG 0.85, diffuse light: 22σ below
                // adding-doubling). At the coarse nodes below ω = 1 it
                // weighs at most e^{−16}. (A semi-infinite layer's value at
                // ω = 1 is 1, not estimated.)
                End::Cut(z) => {
                    if let Layer::Slab(tau) = layer {
                        let w = lit_face_share(z, tau, g, 0.0);
                        sum[0] += w;
                        sum2[0] += w * w;
                        for (j, &(one_minus, ln)) in fine_omega.iter().enumerate() {
                            let w = libm::exp(MAX_EVENTS as f64 * ln)
                                * lit_face_share(z, tau, g, one_minus);
                            fsum[j] += w;
                            fsum2[j] += w * w;
                        }
                    }
                }
                End::Lost => {}
            }
        }
        let m = paths as f64;
        // The sample's standard error, and one path's largest weight there
        // (ω: a path comes back after one scattering at least) over the
        // paths in quadrature: where no path came back (a thin slab: τ =
        // 10⁻⁴ reflects 10⁻⁵ to 10⁻⁴, and 20 000 paths brought none) the
        // estimate is 0, and its error not 0 but the weight one more path
        // would have added.
        let mean_se = |sum: f64, sum2: f64, omega: f64| {
            let mean = sum / m;
            let var = (sum2 / m - mean * mean).max(0.0) / m;
            (mean, libm::sqrt(var + (omega / m) * (omega / m)))
        };
        let (mut rho, mut se) = ([0.0; NODES], [0.0; NODES]);
        for k in 0..NODES {
            let s = node_s(k);
            (rho[k], se[k]) = mean_se(sum[k], sum2[k], 1.0 - s * s);
        }
        if layer == Layer::SemiInfinite {
            // ω = 1: nothing is absorbed and nothing leaves below.
            rho[0] = 1.0;
            se[0] = 0.0;
            // Smooth in s through the first interval (1 − a s + b s²): the
            // cubic through nodes 0–3 held `1 − ω` at A = 0.99 within
            // 0.35 % at 10⁷ paths, where the fine nodes, leaning on the
            // diffusion share of the paths cut there, were 1.06 % off
            // (g = 0.5, beam). The fine nodes serve slabs.
            return Ok(Self::from_nodes(rho, se, paths));
        }
        let (mut fine, mut fine_se) = ([0.0; FINE], [0.0; FINE]);
        for j in 0..FINE {
            (fine[j], fine_se[j]) = mean_se(fsum[j], fsum2[j], 1.0 - fine_omega[j].0);
        }
        Ok(Self::from_stored(rho, se, fine, fine_se, paths))
    }

    /// A curve from everything [`simulate`](Self::simulate) keeps: the
    /// nodes ([`nodes`](Self::nodes)), the fine nodes
    /// ([`fine_nodes`](Self::fine_nodes)) and the number of paths.
    pub fn from_stored(
        rho: [f64; NODES],
        se: [f64; NODES],
        fine: [f64; FINE],
        fine_se: [f64; FINE],
        paths: u64,
    ) -> Self {
        // Increasing s: the fine nodes from the smallest, then node 1.
        let (mut y, mut e) = ([rho[1]; FINE + 1], [se[1]; FINE + 1]);
        for (dst, src) in y.iter_mut().zip(fine.iter().rev()) {
            *dst = *src;
        }
        for (dst, src) in e.iter_mut().zip(fine_se.iter().rev()) {
            *dst = *src;
        }
        AlbedoCurve {
            rho,
            se,
            slope: fritsch_carlson(&rho),
            // All zero: stored without them (a semi-infinite layer's curve,
            // or one from the coarse nodes alone).
            fine: (fine != [0.0; FINE] || fine_se != [0.0; FINE]).then(|| Fine::new(y, e)),
            paths,
        }
    }

    /// The albedos and their standard errors at the fine nodes
    /// `ω_j = 1 − 4^{−(j+1)}/4096` ([`FINE`]), or `None` for a curve
    /// rebuilt from the coarse nodes alone
    /// ([`from_nodes`](Self::from_nodes)).
    pub fn fine_nodes(&self) -> Option<([f64; FINE], [f64; FINE])> {
        let f = self.fine.as_ref()?;
        let (mut y, mut e) = ([0.0; FINE], [0.0; FINE]);
        for (dst, src) in y.iter_mut().zip(f.y.iter().take(FINE).rev()) {
            *dst = *src;
        }
        for (dst, src) in e.iter_mut().zip(f.se.iter().take(FINE).rev()) {
            *dst = *src;
        }
        Some((y, e))
    }

    /// A curve from node values stored earlier ([`nodes`](Self::nodes)):
    /// the albedos and standard errors at the [`NODES`] values of `ω`, and
    /// the number of paths; the interpolant is rebuilt from them. Without
    /// the fine nodes the first interval takes the cubic through the first
    /// four nodes, which misses a thick slab's bend there (module docs);
    /// [`from_stored`](Self::from_stored) keeps them.
    pub fn from_nodes(rho: [f64; NODES], se: [f64; NODES], paths: u64) -> Self {
        AlbedoCurve {
            rho,
            se,
            slope: fritsch_carlson(&rho),
            fine: None,
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
    /// node's own error: the paths' standard error and `ω/paths` (the
    /// most one more path could add) in quadrature, so that a node no path
    /// reached is 0 with that error, not exactly 0; at `ω = 1` of a
    /// semi-infinite layer, 0, and at `ω = 0`, 0 (no path comes back
    /// unscattered).
    pub fn std_error(&self, omega: f64) -> f64 {
        if !(0.0..=1.0).contains(&omega) {
            return f64::NAN;
        }
        let s = libm::sqrt(1.0 - omega);
        let (i, t) = interval(s);
        if let (0, Some(f)) = (i, &self.fine) {
            return f.std_error(self.se[0], s);
        }
        let e = |k: usize| self.se.get(k).copied().unwrap_or(f64::NAN);
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
        let interpolation = fourth_difference_term(&self.rho, i, t);
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
            if let Some(f) = &self.fine {
                return f.at(self.rho[0], s);
            }
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
        hermite(&self.rho, &self.slope, i, t)
    }
}

/// `s` at point `k` of the fine grid: `2^{k − FINE}/64`.
fn grid_s(k: usize) -> f64 {
    libm::ldexp(1.0 / (NODES - 1) as f64, k as i32 - FINE as i32)
}

/// A reader of a fine-grid array (NaN past its end).
fn fine_at(a: &[f64; FINE + 1]) -> impl Fn(usize) -> f64 + '_ {
    move |k| a.get(k).copied().unwrap_or(f64::NAN)
}

impl Fine {
    /// The fine grid's values, errors and monotone slopes in `s`: at an
    /// inner point the slope of the parabola through it and its
    /// neighbours, held within `[3δ, 0]` of both neighbouring secants `δ`
    /// (Fritsch–Carlson's condition for a monotone cubic), 0 where they
    /// differ in sign; at the ends the adjacent secant.
    fn new(y: [f64; FINE + 1], se: [f64; FINE + 1]) -> Self {
        let v = |k: usize| y.get(k).copied().unwrap_or(f64::NAN);
        let secant = |k: usize| (v(k + 1) - v(k)) / (grid_s(k + 1) - grid_s(k));
        let mut slope = [0.0; FINE + 1];
        slope[0] = secant(0);
        slope[FINE] = secant(FINE - 1);
        for (k, sk) in slope.iter_mut().enumerate().take(FINE).skip(1) {
            let (hl, hr) = (grid_s(k) - grid_s(k - 1), grid_s(k + 1) - grid_s(k));
            let (dl, dr) = (secant(k - 1), secant(k));
            let d = (hr * dl + hl * dr) / (hl + hr);
            *sk = if dl * dr <= 0.0 {
                0.0
            } else {
                d.max(3.0 * dl).max(3.0 * dr).min(0.0)
            };
        }
        Fine { y, se, slope }
    }

    /// The first interval's interpolant at `s ∈ [0, 1/64]` (`rho0` the
    /// albedo at `ω = 1`): the monotone cubic Hermite in `s` on the fine
    /// grid, and linear below its first point (`1 − ω < 2.3·10⁻¹⁰`).
    fn at(&self, rho0: f64, s: f64) -> f64 {
        let first = grid_s(0);
        if s <= first {
            return rho0 + (self.y[0] - rho0) * (s / first);
        }
        let (i, t) = Self::interval(s);
        let h = grid_s(i + 1) - grid_s(i);
        let (y, d) = (fine_at(&self.y), fine_at(&self.slope));
        hermite_step((y(i), y(i + 1)), (d(i) * h, d(i + 1) * h), t)
    }

    /// The fine grid's interval `i` holding `s ∈ (s_0, 1/64]` and the
    /// position `t ∈ [0, 1]` in it.
    fn interval(s: f64) -> (usize, f64) {
        let x = libm::log2(s * (NODES - 1) as f64) + FINE as f64;
        let i = (x.max(0.0) as usize).min(FINE - 1);
        let (a, b) = (grid_s(i), grid_s(i + 1));
        (i, ((s - a) / (b - a)).clamp(0.0, 1.0))
    }

    /// The first interval's error at `s`, as [`AlbedoCurve::std_error`]
    /// computes it on the coarse nodes: the nodes' errors interpolated,
    /// and the next term of the polynomial through the four grid points
    /// around `s`, from the fourth divided difference over five.
    fn std_error(&self, se0: f64, s: f64) -> f64 {
        let first = grid_s(0);
        if s <= first {
            return se0 + (self.se[0] - se0) * (s / first);
        }
        let (i, t) = Self::interval(s);
        let (y, e) = (fine_at(&self.y), fine_at(&self.se));
        let monte_carlo = e(i) + t * (e(i + 1) - e(i));
        // Newton's divided differences over the five grid points j … j+4,
        // one order at a time (order k: points j … j+4−k).
        let j = i.saturating_sub(1).min(FINE + 1 - 5);
        let mut dd: [f64; 5] = core::array::from_fn(|m| y(j + m));
        for order in 1..5 {
            let prev = dd;
            for (m, d) in dd.iter_mut().enumerate().take(5 - order) {
                let at = |k: usize| prev.get(k).copied().unwrap_or(f64::NAN);
                *d = (at(m + 1) - at(m)) / (grid_s(j + m + order) - grid_s(j + m));
            }
        }
        let poly: f64 = (0..4).map(|m| s - grid_s(j + m)).product();
        let interpolation = libm::fabs(dd[0] * poly);
        libm::sqrt(monte_carlo * monte_carlo + interpolation * interpolation)
    }
}

/// The cubic Hermite between `y0` and `y1` with end slopes `d0`, `d1`
/// (per interval), at `t ∈ [0, 1]`, held between its ends.
fn hermite_step((y0, y1): (f64, f64), (d0, d1): (f64, f64), t: f64) -> f64 {
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

/// The monotone cubic Hermite interpolant of `y` with slopes `d` (per
/// grid step) on interval `i` at `t ∈ [0, 1]`.
fn hermite(y: &[f64; NODES], d: &[f64; NODES], i: usize, t: f64) -> f64 {
    let v = |a: &[f64; NODES], k: usize| a.get(k).copied().unwrap_or(f64::NAN);
    hermite_step((v(y, i), v(y, i + 1)), (v(d, i), v(d, i + 1)), t)
}

/// The interpolation's error on interval `i` at `t` of a grid of values
/// `y` (`N ≥ 5`): the next term of the polynomial through the four nodes
/// `j … j+3` around it (`x = t` measured from node `j`),
/// `|Δ⁴y|/4! · |x(x − 1)(x − 2)(x − 3)|`, the fourth difference over
/// `j … j+4` (or the last five nodes).
fn fourth_difference_term(y: &[f64; NODES], i: usize, t: f64) -> f64 {
    let v = |k: usize| y.get(k).copied().unwrap_or(f64::NAN);
    let j = i.saturating_sub(1).min(NODES - 4);
    let x = (i - j) as f64 + t;
    let first = j.min(NODES - 5);
    let d4 = v(first) - 4.0 * v(first + 1) + 6.0 * v(first + 2) - 4.0 * v(first + 3) + v(first + 4);
    let poly = x * (x - 1.0) * (x - 2.0) * (x - 3.0);
    libm::fabs(d4 / 24.0 * poly)
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

/// The share of the light at optical depth `z` of a slab of thickness `τ`
/// that leaves through the lit face, by diffusion, where a share `1 − ω`
/// of each collision is absorbed: a path cut after [`MAX_EVENTS`]
/// scatterings has long forgotten its direction (2¹⁶ (1 − g) transport
/// events). In optical depth units the transport coefficient is
/// `1 − ω g`, the extrapolated boundary `z_e = 0.7104/(1 − ω g)` beyond
/// each face (Milne's extrapolation length in transport mean free paths)
/// and the diffusion constant `κ = √(3 (1 − ω)(1 − ω g))`; the density
/// from a source at `z` that reaches the lit face's extrapolated boundary
/// is `sinh(κ(τ + z_e − z)) / sinh(κ(τ + 2 z_e))` (written
/// `e^{−κ(z + z_e)} · expm1(−2a)/expm1(−2b)`, `a`, `b` the two arguments,
/// so that a thick slab's `sinh` does not overflow), and at `ω = 1` the
/// linear `(τ + z_e − z) / (τ + 2 z_e)`. 0 for `g = 1` (a path that never
/// turns does not come back).
fn lit_face_share(z: f64, tau: f64, g: f64, one_minus_omega: f64) -> f64 {
    // g ≥ 1 or NaN: no diffusion to speak of.
    if g.is_nan() || g >= 1.0 {
        return 0.0;
    }
    let transport = one_minus_omega + (1.0 - one_minus_omega) * (1.0 - g);
    let ze = 0.7104 / transport;
    let kappa = libm::sqrt(3.0 * one_minus_omega * transport);
    let share = if kappa == 0.0 {
        (tau + ze - z) / (tau + 2.0 * ze)
    } else {
        let (a, b) = (kappa * (tau + ze - z), kappa * (tau + 2.0 * ze));
        libm::exp(-kappa * (z + ze)) * libm::expm1(-2.0 * a) / libm::expm1(-2.0 * b)
    };
    share.clamp(0.0, 1.0)
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
