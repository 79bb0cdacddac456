//! Every phase model the library ships, one line each: how to build it in
//! either precision from f64 parameters, the parameter sets the contract
//! runs it at, the sets its constructor must refuse, the line of
//! `tests/golden/golden.txt` that pins its bits, and how far its inverse
//! may be from the exact one. A new model is one `model!` line here.

use scatterkit::{Error, Phase};

/// Builds a model in precision `T` from f64 parameters (rounded to `T`).
pub type Build<T> = fn(&[f64]) -> Result<Phase<T>, Error>;

/// One registered model.
#[derive(Clone, Copy)]
pub struct Model {
    pub name: &'static str,
    pub f32: Build<f32>,
    pub f64: Build<f64>,
    /// Parameter sets the contract runs (each must build).
    pub sets: &'static [&'static [f64]],
    /// Parameter sets the constructor must refuse with `Error::Domain`.
    pub bad: &'static [&'static [f64]],
    /// The golden line (name and parameters) pinning its bits.
    pub golden: (&'static str, &'static [f64]),
    /// Largest |μ(u) − μ_exact(u)| its inverse is documented to reach, f32
    /// and f64: the slack the inverse's check gives `F(μ(u)) = u`.
    pub mu_tol: (f64, f64),
}

/// `model!(name, |p| constructor(p[0], …), sets, bad, golden, mu_tol)`: the
/// constructor expression once, built for f32 and for f64.
macro_rules! model {
    ($name:expr, |$p:ident| $build:expr, sets: $sets:expr, bad: $bad:expr, golden: $golden:expr, mu_tol: $tol:expr $(,)?) => {
        Model {
            name: $name,
            f32: |q: &[f64]| {
                let $p: Vec<f32> = q.iter().map(|&x| x as f32).collect();
                let _ = &$p;
                $build
            },
            f64: |q: &[f64]| {
                let $p: Vec<f64> = q.to_vec();
                let _ = &$p;
                $build
            },
            sets: $sets,
            bad: $bad,
            golden: $golden,
            mu_tol: $tol,
        }
    };
}

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;
/// Closed-form inverses: a few ULP.
const CLOSED: (f64, f64) = (3e-7, 1e-14);
/// Iterative inverses (Newton or Halley on the CDF): their documented bounds.
const ITERATIVE: (f64, f64) = (3e-7, 1e-13);

/// Every model.
pub fn models() -> Vec<Model> {
    vec![
        model!("isotropic", |p| Ok(Phase::isotropic()), sets: &[&[]], bad: &[], golden: ("isotropic", &[]), mu_tol: CLOSED),
        model!("rayleigh", |p| Ok(Phase::rayleigh()), sets: &[&[]], bad: &[], golden: ("rayleigh", &[]), mu_tol: CLOSED),
        model!("depolarised rayleigh", |p| Phase::rayleigh_depolarized(p[0]), sets: &[&[0.028], &[0.5], &[0.95]], bad: &[&[-1e-9], &[1.0], &[2.0], &[NAN], &[INF]], golden: ("rayleigh_depolarized_0.028", &[0.028]), mu_tol: CLOSED),
        model!("henyey-greenstein", |p| Phase::henyey_greenstein(p[0]), sets: &[&[-0.9], &[-0.3], &[0.0], &[1e-4], &[0.5], &[0.7], &[0.99]], bad: &[&[1.000_001], &[-1.000_001], &[1.5], &[NAN], &[INF], &[-INF]], golden: ("hg_0.7", &[0.7]), mu_tol: CLOSED),
        model!("draine", |p| Phase::draine(p[0], p[1]), sets: &[&[0.5, 1.0], &[0.9, 10.0], &[0.3, 250.0], &[-0.4, 0.5]], bad: &[&[1.0, 1.0], &[0.5, -1.0], &[NAN, 1.0], &[0.5, INF]], golden: ("draine_0.3_250", &[0.3, 250.0]), mu_tol: ITERATIVE),
        model!("cornette-shanks", |p| Phase::cornette_shanks(p[0]), sets: &[&[0.6], &[-0.8]], bad: &[&[1.0], &[NAN]], golden: ("cornette_shanks_0.6", &[0.6]), mu_tol: ITERATIVE),
        model!("fog", |p| Phase::fog_diameter(p[0]), sets: &[&[2.0], &[10.0], &[40.0]], bad: &[&[0.0], &[-1.0], &[NAN], &[INF]], golden: ("fog_2um", &[2.0]), mu_tol: ITERATIVE),
        model!("two-lobe hg", |p| Phase::two_lobe_hg(p[0], p[1], p[2]), sets: &[&[0.8, -0.3, 0.9], &[-0.9, 0.9, 0.5], &[0.999, -0.999, 0.5]], bad: &[&[1.000_001, 0.0, 0.5], &[0.0, -1.000_001, 0.5], &[0.5, 0.5, -0.1], &[0.5, 0.5, 1.1], &[NAN, 0.0, 0.5], &[0.0, NAN, 0.5], &[0.0, 0.0, NAN]], golden: ("two_lobe_hg_0.8_-0.3_0.9", &[0.8, -0.3, 0.9]), mu_tol: ITERATIVE),
        model!("gegenbauer", |p| Phase::gegenbauer(p[0], p[1]), sets: &[&[-0.25, 0.7], &[0.5, 0.3], &[2.0, -0.6], &[-0.4, 0.6], &[0.0, -0.7], &[0.5, 0.9], &[2.0, 0.5], &[50.0, 0.3], &[-0.499_999_97, 0.999], &[-0.499_999_97, -0.999], &[1000.0, 0.001], &[0.0, 0.999]], bad: &[&[-0.5, 0.3], &[1000.5, 0.3], &[0.5, 1.0], &[0.5, -1.0], &[NAN, 0.3], &[0.5, NAN], &[INF, 0.3]], golden: ("gegenbauer_-0.25_0.7", &[-0.25, 0.7]), mu_tol: ITERATIVE),
        model!("schlick", |p| scatterkit::phase::schlick::Schlick::new(p[0]).map(Phase::from), sets: &[&[-0.9], &[-0.3], &[0.0], &[1e-5], &[0.5], &[0.8], &[0.99]], bad: &[&[1.0], &[-1.0], &[1.5], &[NAN], &[INF], &[-INF]], golden: ("schlick_0.6", &[0.6]), mu_tol: CLOSED),
        model!("fournier-forand", |p| Phase::fournier_forand(p[0], p[1]), sets: &[&[1.1, 4.0], &[1.05, 3.5]], bad: &[&[1.0, 4.0], &[1.81, 4.0], &[1.1, 3.0], &[1.1, 5.0], &[NAN, 4.0], &[1.1, NAN]], golden: ("fournier_forand_1.1_4", &[1.1, 4.0]), mu_tol: ITERATIVE),
    ]
}
