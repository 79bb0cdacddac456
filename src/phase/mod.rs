//! Phase functions: densities of scattering directions per steradian.
//!
//! Conventions (as in the crate docs): `cos θ = dot(w_in, w_out)` with both vectors
//! propagation directions, so `+1` is forward. Every phase function `p`
//! satisfies `2π ∫₋₁¹ p(μ) dμ = 1`. [`PhaseFunction::sample_cos`] is the
//! inverse of [`PhaseFunction::cdf`] with `F(x) = P(cos θ ≤ x)`: `u = 0 → −1`,
//! `u → 1 → +1`, monotone non-decreasing, so stratified and low-discrepancy
//! uniforms stay stratified.
//!
//! [`Phase`] is the closed set of models behind one small `Copy` value; each
//! model is also usable on its own.

mod any;
mod by_moments;
pub mod draine;
pub mod fog;
pub mod fournier_forand;
mod function;
pub mod gegenbauer;
mod hg;
mod isotropic;
pub mod legendre;
mod model;
pub mod moments;
pub mod rayleigh;
mod rayleigh_depolarized;
pub mod rayleigh_polarized;
pub mod schlick;
mod seeds;

pub use any::Phase;
pub use draine::Draine;
pub use fog::{Fog, FogParams, fog_fit};
pub use fournier_forand::FournierForand;
pub use function::{PhaseFunction, PhaseVisitor, check_uniforms, support};
pub use gegenbauer::Gegenbauer;
pub use hg::HenyeyGreenstein;
pub use isotropic::Isotropic;
pub use model::{Lobes, Model};
pub use rayleigh::{Rayleigh, RayleighMethod};
pub use rayleigh_depolarized::RayleighDepolarized;
pub use rayleigh_polarized::{RayleighMueller, RayleighPolarized, StokesSample};
