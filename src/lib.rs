//! # scatterkit
//!
//! Light-scattering samplers for Monte Carlo light transport: renderers (fog,
//! clouds, skies, skin), atmospheric and ocean radiative transfer, tissue
//! optics, and ray tracers for solar cells. `#![no_std]`, no allocation, no
//! global state, generic over `f32` and `f64`, with a C ABI (`sk_*`, header
//! `include/scatterkit.h`) built by the `capi/` crate.
//!
//! ## Conventions
//! * Directions are unit **propagation** directions; `cos θ = dot(w_in, w_out)`,
//!   `+1` is forward, and a positive asymmetry `g` scatters forward.
//! * Phase functions are densities **per steradian**, `2π ∫ p(μ) dμ = 1`.
//! * Inverse-CDF samplers map `u ∈ [0, 1]` monotonically to `cos θ ∈ [−1, 1]`
//!   with `u = 0 → −1`; `u` outside `[0, 1]` is clamped, NaN propagates.
//! * Randomness is the caller's: any
//!   [`rand_core::Rng`](https://docs.rs/rand_core/0.10/rand_core/trait.Rng.html);
//!   one `next_u64` per
//!   uniform (f32 `(x >> 40)·2⁻²⁴`, f64 `(x >> 11)·2⁻⁵³`).
//! * Constructors validate; built objects are valid, and their hot paths do
//!   not re-check.
//!
//! ## Results
//! One rule: a pure formula of floats returns a float, and NaN in gives NaN
//! out, as libm does ([`medium::free_path`], `pdf`, `cdf`, `sample_cos`);
//! anything that validates structure (buffers, dimensions, enums, boxes) or
//! can hit an iteration cap returns `Result<_, `[`Error`]`>`, and the cap
//! is its own error ([`Error::Budget`]: the tracking calls). Nothing panics
//! on any input.
//!
//! ## Features
//! | feature | default | what |
//! |---|---|---|
//! | `ffi` | off | the `extern "C"` layer (`sk_*` symbols); `capi/` turns it on |
//!
//! ## Example
//! ```
//! use scatterkit::{Phase, PhaseFunction, Vec3};
//! let hg = Phase::henyey_greenstein(0.7f32).unwrap();
//! let w_in = Vec3::new(0.0, 0.0, 1.0);
//! let (w_out, pdf) = hg.sample_dir(w_in, 0.25, 0.5);
//! assert!((w_out.length() - 1.0).abs() < 1e-6);
//! assert!((pdf - hg.pdf(w_out.dot(w_in))).abs() < 1e-3 * pdf);
//! // Rayleigh by any of Frisvad's methods, with the caller's RNG:
//! # struct Lcg(u64);
//! # impl rand_core::TryRng for Lcg {
//! #     type Error = core::convert::Infallible;
//! #     fn try_next_u32(&mut self) -> Result<u32, Self::Error> { Ok((self.try_next_u64()? >> 32) as u32) }
//! #     fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
//! #         self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); Ok(self.0) }
//! #     fn try_fill_bytes(&mut self, d: &mut [u8]) -> Result<(), Self::Error> { rand_core::utils::fill_bytes_via_next_word(d, || self.try_next_u64()) }
//! # }
//! let mut rng = Lcg(1);
//! let dir = scatterkit::rayleigh::sample_dir(
//!     scatterkit::RayleighMethod::Direct, Vec3::new(1.0f64, 0.0, 0.0), &mut rng);
//! assert!((dir.length() - 1.0).abs() < 1e-12);
//! ```
#![no_std]
#![warn(missing_docs)]
// The boundaries the compiler holds: `unsafe` only in the C layer and the
// x86-64 square root (`real.rs`), each allowed where it is; every public
// type can be printed.
#![deny(unsafe_code)]
#![deny(missing_debug_implementations)]

// The layers, lowest first: each folder imports only from those above it
// in this list (`tests/layering.rs`; `ARCHITECTURE.md` has the map).
pub mod choose;
mod error;
mod math;
pub mod medium;
pub mod mie;
pub mod mixture;
pub mod phase;
pub mod portable;
pub mod stokes;
pub mod surface;
pub mod table;
pub mod transport;

// The numerics, the particle size distributions and the media's grids keep
// their paths at the crate root.
pub use math::{azimuth, cbrt, geometry, real};
pub use medium::{majorant, spectral};
pub use mie::polydisperse;

#[cfg(feature = "ffi")]
#[allow(unsafe_code)]
pub mod ffi;

pub use error::Error;
pub use geometry::{Vec3, onb};
pub use majorant::Majorants;
pub use medium::{Grid, Ray, Sampling};
pub use phase::rayleigh;
pub use phase::{
    Draine, Fog, FournierForand, Gegenbauer, HenyeyGreenstein, Isotropic, Phase, PhaseFunction,
    Rayleigh, RayleighDepolarized, RayleighMethod, RayleighPolarized,
};
pub use real::Real;
pub use stokes::Stokes;
pub use surface::{CrossingPolicy, Fraction, Surface, SurfaceModel};
pub use table::{Table, Table2d, TableKind};
