//! Builds `libscatterkit.a` and `libscatterkit.so` from the `ffi` layer of the
//! `scatterkit` crate. Nothing lives here but the re-export: the functions,
//! their checks and their docs are in `scatterkit/src/ffi/`.
pub use scatterkit_core::ffi::*;
