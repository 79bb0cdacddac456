//! Builds `libscatterkit.a` and `libscatterkit.so` from the `ffi` layer of the
//! `scatterkit` crate. Nothing lives here but the re-export: the functions,
//! their checks and their docs are in `scatterkit/src/ffi/`.
//!
//! It refuses to compile with unwinding: a Rust panic must never cross
//! `extern "C"` (the workspace's profiles set `panic = "abort"`).

#[cfg(panic = "unwind")]
compile_error!(
    "scatterkit-capi must be built with panic = \"abort\" (the workspace profiles set it)"
);

pub use scatterkit_core::ffi::*;
