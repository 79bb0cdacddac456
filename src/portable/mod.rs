//! The portable f32 tier: samplers written once in single precision, with
//! every operation an IEEE-754 addition, subtraction, multiplication,
//! division or square root in a stated order, and the library's own sine,
//! cosine, logarithm and exponential (no libm, no double precision, no fused
//! multiply-add). `include/scatterkit_portable.h` carries the same
//! functions, operation for operation, for C, C++, CUDA, HIP and OpenCL C;
//! compiled where each operation rounds correctly (C and C++ on any IEEE
//! target; CUDA; OpenCL with correctly rounded division and square root)
//! it returns these functions' bits (`tests/c_abi/portable.rs` compares
//! them over 2²⁴ inputs per case; `docs/guides/portable.md` is the guide).
//!
//! What the tier gives up against the rest of the library, which samples
//! f32 through f64 arithmetic where that is as fast: a few ulp of 1 in
//! `cos θ` (the stated bound of each function, measured against
//! double-double and f64 references in `tests/models/portable.rs`). What it gains: the same bits on every processor,
//! GPU kernels included, and no call out of a kernel or loop.
//!
//! Conventions as everywhere in the crate: `u ∈ [0, 1]` is clamped, NaN
//! propagates; `cos θ = +1` is forward; densities are per steradian.

mod batch;
mod draine;
mod exact;
mod flight;
mod phase;
mod schlick;
mod table;
mod turns;
mod walk;

pub use batch::{
    Model, hg_sample_cos_n, hg_sample_cos_n_in_range, isotropic_sample_cos_n,
    rayleigh_sample_cos_n, sample_dir_n,
};
pub use draine::{
    Draine, DraineSide, Fog, draine_pdf, draine_sample_cos, draine_sample_dir, fog_pdf,
    fog_sample_cos, fog_sample_dir,
};
pub use flight::{exp, free_path, ln, spectral_free_path, transmittance};
pub use phase::{
    DirSample, Hg, TwoLobe, hg_pdf, hg_sample_cos, hg_sample_cos_sin, hg_sample_dir,
    isotropic_sample_cos_sin, isotropic_sample_dir, rayleigh_pdf, rayleigh_sample_cos,
    rayleigh_sample_dir, two_lobe_pdf, two_lobe_sample_cos, two_lobe_sample_dir,
};
pub use schlick::{Schlick, schlick_pdf, schlick_sample_cos, schlick_sample_dir};
pub use table::{
    table_cdf_sample_cos_pdf, table_sample_cos, table_sample_cos_pdf, table2d_sample_cos_pdf,
};
pub use turns::{direction_about, frame, sin_cos_2pi};
pub use walk::{Step, Walk};

/// The Rayleigh sampler's table: 128 intervals of `[μ_i, d_i, c2_i, c3_i]`,
/// the cubic Hermite spline of the inverse CDF over `u ∈ [i/128, (i+1)/128]`
/// (built in f64, rounded to f32). The header carries the same values
/// (`skp_rayleigh_table_`), checked by a test.
pub use crate::math::rayleigh_table::RAYLEIGH_TABLE_F32 as RAYLEIGH_TABLE;

/// `u` clamped to `[0, 1]` with NaN kept: the header's
/// `u > 1 ? 1 : u` then `< 0 ? 0`, in that order.
#[inline(always)]
pub(crate) fn clamp01(u: f32) -> f32 {
    let w = if u > 1.0 { 1.0 } else { u };
    if w < 0.0 { 0.0 } else { w }
}
