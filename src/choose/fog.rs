//! Model no more than the scene needs: the cheapest phase function whose
//! density is within a total-variation distance of the fog fit for a droplet
//! diameter (`sk_phase_new_particle` in C).
//!
//! Candidates, in order of measured sampling cost (f32 `sample_cos`, ns per
//! sample on the project machine, `cargo run --release --example
//! speed_accuracy`): isotropic, Henyey–Greenstein, Rayleigh, Draine, the full
//! fog mixture ([`COST_ORDER`]). HG and Draine take the parameters that
//! minimise the distance (golden-section search in g; for Draine also over a
//! grid of α refined in log α).
//!
//! The distance `TV(p, p_fog) = ½ ∫ |p − p_fog| dω` equals
//! `∫ (p_fog − p)₊ dω = ∫₀¹ (1 − p/p_fog)₊ dx` with `x` the fog's own quantile
//! (`μ = F_fog⁻¹(x)`): a bounded integrand on `[0, 1]` however peaked the
//! fog is, taken by the midpoint rule at [`NODES`] points held on the stack.
//! A model is accepted when its estimate is at most `(1 − MARGIN)` times the
//! tolerance, which covers the quadrature error (measured ≤ 2 % of the
//! distance in `tests/models/choose_fog.rs`).
//!
//! Two-lobe HG and Fournier–Forand are candidates against real Mie
//! (`particle_mie`) only: against the fog fit, two-lobe HG's exact inverse
//! (115 ns through the C ABI) costs more than the fog's own (43 ns at 2 µm
//! since its f32 inverse takes one evaluation of the mixture) while the fog
//! is the reference itself, and Fournier–Forand costs more (350 ns).

use crate::error::Error;
use crate::math::real::Real;
use crate::phase::draine::Params;
use crate::phase::fournier_forand;
use crate::phase::{Draine, Fog, HenyeyGreenstein, Phase, PhaseFunction};

/// Quadrature nodes for the distance (midpoint rule in the fog's quantile).
pub const NODES: usize = 512;
/// Share of the tolerance kept back for the quadrature error.
pub const MARGIN: f64 = 0.05;

/// The candidate models, cheapest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Model {
    /// Uniform over the sphere.
    Isotropic,
    /// Henyey–Greenstein with fitted g.
    HenyeyGreenstein,
    /// Rayleigh.
    Rayleigh,
    /// Draine with fitted g and α.
    Draine,
    /// The full fog fit.
    Fog,
    /// A table of the exact Mie phase function (`particle_mie`).
    MieTable,
    /// Two Henyey–Greenstein lobes with fitted `g1`, `g2` and weight
    /// (`particle_mie`, without a table).
    TwoLobeHg,
    /// Fournier–Forand with fitted `n` and `ν` (`particle_mie`, without a
    /// table).
    FournierForand,
    /// The mixture of Rayleigh and one Henyey–Greenstein lobe with fitted
    /// `g` and weight (molecules and aerosol in one cell; `particle_mie`
    /// and `choose_measured`, without a table). Sampled as a fog mixture
    /// with a Rayleigh lobe (Draine with `g = 0`, `α = 1`).
    RayleighHg,
}

/// Candidates in order of measured `sample_cos` cost, cheapest first.
/// Measured (f32 `sample_cos`, ns per sample, median of 7 × 2²⁰, the main
/// example on the project machine): isotropic 3.2, HG 3.6, Rayleigh 8.0,
/// Draine 38–164 (by g and α), fog (exact mixture inverse) 271. (Draine was
/// measured before eq. 6, rearranged, became the f32 answer for
/// `|g| ≥ 10⁻³`, `10⁻⁴ ≤ α ≤ 10⁴`: 26 ns there through the C ABI, still
/// above Rayleigh; the fog before its f32 inverse took one evaluation of
/// the mixture: 43–103 ns over the fits from Rust, still above Draine.)
pub const COST_ORDER: [Model; 5] = [
    Model::Isotropic,
    Model::HenyeyGreenstein,
    Model::Rayleigh,
    Model::Draine,
    Model::Fog,
];

/// The fog's density at its own quantiles: what every distance needs.
struct Reference {
    mu: [f64; NODES],
    density: [f64; NODES],
}

impl Reference {
    fn new(fog: &Fog<f64>) -> Reference {
        let mut r = Reference {
            mu: [0.0; NODES],
            density: [0.0; NODES],
        };
        for k in 0..NODES {
            let mu = fog.sample_cos((k as f64 + 0.5) / NODES as f64);
            r.mu[k] = mu;
            r.density[k] = core::f64::consts::TAU * fog.pdf(mu);
        }
        r
    }

    fn view(&self) -> Quantiles<'_> {
        Quantiles {
            mu: &self.mu,
            density: &self.density,
        }
    }
}

/// A reference density of `μ` at its own midpoint quantiles `μ_k =
/// F⁻¹((k + ½)/n)`: the nodes of the distance's quadrature.
#[derive(Clone, Copy)]
pub(crate) struct Quantiles<'a> {
    pub(crate) mu: &'a [f64],
    pub(crate) density: &'a [f64],
}

impl Quantiles<'_> {
    /// `TV` of the density of μ `f` against the reference.
    pub(crate) fn distance(&self, f: impl Fn(f64) -> f64) -> f64 {
        let mut sum = 0.0;
        for (&mu, &d) in self.mu.iter().zip(self.density) {
            let ratio = f(mu) / d;
            if ratio < 1.0 {
                sum += 1.0 - ratio;
            }
        }
        sum / self.mu.len().max(1) as f64
    }
}

/// Golden-section search for the minimum of `f` on `[a, b]`; returns
/// `(x, f(x))`.
fn golden(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64, iterations: u32) -> (f64, f64) {
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    let mut c = b - INV_PHI * (b - a);
    let mut d = a + INV_PHI * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..iterations {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - INV_PHI * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + INV_PHI * (b - a);
            fd = f(d);
        }
    }
    if fc < fd { (c, fc) } else { (d, fd) }
}

/// Best-fit HG: `(g, distance)`.
pub(crate) fn fit_hg(r: &Quantiles) -> (f64, f64) {
    golden(
        |g| r.distance(|mu| Params::new(g, 0.0).density(mu)),
        -0.999,
        0.999,
        48,
    )
}

/// Best-fit Draine: `(g, α, distance)`, over a grid of α refined in log α.
pub(crate) fn fit_draine(r: &Quantiles) -> (f64, f64, f64) {
    let dist = |g: f64, a: f64| r.distance(|mu| Params::new(g, a).density(mu));
    let best_g = |a: f64| golden(|g| dist(g, a), -0.999, 0.999, 40);
    let mut best = (0.0, 0.0, f64::INFINITY);
    for a in [
        0.0, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0, 1e4,
    ] {
        let (g, d) = best_g(a);
        if d < best.2 {
            best = (g, a, d);
        }
    }
    if best.1 > 0.0 {
        let la = libm::log(best.1);
        let (la, _) = golden(|la| best_g(libm::exp(la)).1, la - 1.2, la + 1.2, 24);
        let a = libm::exp(la);
        let (g, d) = best_g(a);
        if d < best.2 {
            best = (g, a, d);
        }
    }
    best
}

/// The cheapest model within `tolerance` (total variation, `0 < tolerance < 1`)
/// of the fog fit for droplets of `diameter_um` µm (`0 < d ≤ 50`), with its
/// fitted parameters and estimated distance. [`Error::Domain`] outside those
/// ranges.
///
/// # Example
///
/// ```
/// use scatterkit::choose::fog::{Model, choose};
///
/// // Droplets far below the wavelength: Rayleigh is close enough.
/// let (_, model, _) = choose(0.01, 0.01).unwrap();
/// assert_eq!(model, Model::Rayleigh);
/// // Cloud droplets: the chooser returns a model within the tolerance.
/// let (phase, _, distance) = choose(10.0, 0.05).unwrap();
/// assert!(distance <= 0.05);
/// let _ = phase; // a Phase<f64>, ready to sample
/// ```
pub fn choose(diameter_um: f64, tolerance: f64) -> Result<(Phase<f64>, Model, f64), Error> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(Error::Domain);
    }
    let fog = Fog::<f64>::from_diameter(diameter_um)?;
    let reference = Reference::new(&fog);
    let r = reference.view();
    let accept = (1.0 - MARGIN) * tolerance;
    for model in COST_ORDER {
        let chosen = match model {
            Model::Isotropic => {
                let d = r.distance(|_| 0.5);
                (d <= accept).then_some((Phase::isotropic(), d))
            }
            Model::Rayleigh => {
                let d = r.distance(|mu| 0.375 * (1.0 + mu * mu));
                (d <= accept).then_some((Phase::rayleigh(), d))
            }
            Model::HenyeyGreenstein => {
                let (g, d) = fit_hg(&r);
                (d <= accept).then_some((Phase::HenyeyGreenstein(HenyeyGreenstein::from_g(g)), d))
            }
            Model::Draine => {
                let (g, alpha, d) = fit_draine(&r);
                (d <= accept).then_some((Phase::Draine(Draine::from_parts(g, alpha)), d))
            }
            _ => Some((Phase::Fog(fog), 0.0)),
        };
        if let Some((phase, d)) = chosen {
            return Ok((phase, model, d));
        }
    }
    Ok((Phase::Fog(fog), Model::Fog, 0.0))
}

impl<T: Real> Phase<T> {
    /// The cheapest of isotropic, HG, Rayleigh, Draine and the full fog fit
    /// whose density stays within total-variation distance `tolerance`
    /// (`0 < tolerance < 1`) of the fog fit for droplets of `diameter_um` µm
    /// (`0 < d ≤ 50`). Costs a few milliseconds (a few hundred quadratures of
    /// 512 points): build it once per medium. [`Error::Domain`] outside the
    /// ranges.
    pub fn particle(diameter_um: T, tolerance: T) -> Result<Self, Error> {
        let (p, _, _) = choose(diameter_um.to_f64(), tolerance.to_f64())?;
        Ok(p.cast())
    }
}

/// Best-fit two-lobe HG, `w p_HG(g1) + (1 − w) p_HG(g2)`: `(g1, g2, w,
/// distance)`. The lobe with weight `w ≥ ½` is lobe 1 (the other order is
/// the same model). A grid in `(w, g2)` with a golden-section search in
/// `g1` at each point, then three sweeps of coordinate descent in a
/// shrinking window about the best; a local search, so it keeps the single
/// HG `hg` (w = 1) when it finds nothing closer.
pub(crate) fn fit_two_lobe_hg(r: &Quantiles, hg: (f64, f64)) -> (f64, f64, f64, f64) {
    let dist = |g1: f64, g2: f64, w: f64| {
        let (p1, p2) = (Params::new(g1, 0.0), Params::new(g2, 0.0));
        r.distance(|mu| w * p1.density(mu) + (1.0 - w) * p2.density(mu))
    };
    let mut best = (hg.0, 0.0, 1.0, hg.1);
    for w in [0.5, 0.7, 0.8, 0.9, 0.95, 0.98] {
        for g2 in [-0.9, -0.6, -0.3, 0.0, 0.3, 0.6, 0.9, 0.99, 0.999] {
            let (g1, d) = golden(|g| dist(g, g2, w), -0.999, 0.999, 20);
            if d < best.3 {
                best = (g1, g2, w, d);
            }
        }
    }
    let window = |x: f64, h: f64, lo: f64, hi: f64| ((x - h).max(lo), (x + h).min(hi));
    let mut h = 0.3;
    for _ in 0..3 {
        let (g1, g2, w, _) = best;
        let (a, b) = window(g1, h, -0.999, 0.999);
        let (g1, _) = golden(|g| dist(g, g2, w), a, b, 18);
        let (a, b) = window(g2, h, -0.999, 0.999);
        let (g2, _) = golden(|g| dist(g1, g, w), a, b, 18);
        let (a, b) = window(w, h / 3.0, 0.5, 1.0);
        let (w, d) = golden(|w| dist(g1, g2, w), a, b, 18);
        if d < best.3 {
            best = (g1, g2, w, d);
        }
        h *= 0.5;
    }
    best
}

/// Best-fit mixture `w HG(g) + (1 − w) Rayleigh`: `(g, w, distance)`, a
/// golden-section search in `w ∈ [0, 1]` around one in `g` (both
/// unimodal for the references tried; `w = 1` is HG, `w = 0` Rayleigh).
pub(crate) fn fit_rayleigh_hg(r: &Quantiles) -> (f64, f64, f64) {
    let dist = |g: f64, w: f64| {
        let p = Params::new(g, 0.0);
        r.distance(|mu| w * p.density(mu) + (1.0 - w) * 0.375 * (1.0 + mu * mu))
    };
    let best_g = |w: f64| golden(|g| dist(g, w), -0.999, 0.999, 30);
    let (w, d) = golden(|w| best_g(w).1, 0.0, 1.0, 30);
    (best_g(w).0, w, d)
}

/// Best-fit Fournier–Forand: `(n, ν, distance)`, golden-section search in
/// `ν ∈ (−1, 0)` over a grid of `n ∈ (1, 1.8]`, refined in `ln(n − 1)`.
pub(crate) fn fit_fournier_forand(r: &Quantiles) -> (f64, f64, f64) {
    let best_nu = |n: f64| {
        golden(
            |nu| r.distance(fournier_forand::density_of_mu(n, nu)),
            -0.999,
            -0.001,
            22,
        )
    };
    let mut best = (f64::NAN, f64::NAN, f64::INFINITY);
    for n in [1.01, 1.02, 1.05, 1.1, 1.15, 1.2, 1.33, 1.5, 1.8] {
        let (nu, d) = best_nu(n);
        if d < best.2 {
            best = (n, nu, d);
        }
    }
    let ln = libm::log(best.0 - 1.0);
    let hi = libm::log(0.8f64).min(ln + 0.7);
    let (l, _) = golden(|l| best_nu(1.0 + libm::exp(l)).1, ln - 0.7, hi, 14);
    let n = 1.0 + libm::exp(l);
    let (nu, d) = best_nu(n);
    if d < best.2 { (n, nu, d) } else { best }
}
