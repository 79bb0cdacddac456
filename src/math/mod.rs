//! The numerics every model stands on: the float trait, vectors and
//! frames, the cube root, the azimuth, double-double arithmetic and the
//! shared root finders and quadratures; and, for the C layer on x86-64, the
//! load-time choice of instruction set (`arch`), the one place the core
//! knows of the C layer. Imports nothing from the rest of the crate but
//! [`Error`](crate::Error).

pub mod azimuth;
pub mod cbrt;
pub(crate) mod double_double;
pub(crate) mod draine_eq6;
pub mod geometry;
pub(crate) mod log;
pub(crate) mod numeric;
pub mod rayleigh_table;
pub mod real;

#[cfg(ifunc)]
pub(crate) mod arch;
