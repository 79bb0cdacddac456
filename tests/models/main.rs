//! Each model against references nobody here wrote: double-double and
//! 40–60-digit evaluations, published tables, independent Monte Carlo.
//! One file per model (or family); one test binary. The contract every
//! phase model shares is `tests/contract/`.

#[path = "../common/mod.rs"]
mod common;

mod albedo;
mod azimuth;
mod cbrt;
mod choose_fog;
mod choose_measured;
mod choose_mie;
mod dirac;
mod draine;
mod edges;
mod emission;
mod equiangular;
mod fournier_forand;
mod gegenbauer;
mod hg_and_depolarised;
mod legendre;
mod majorant;
mod media_suite;
mod medium;
mod mie;
mod mie_table;
mod mixture;
mod moments;
mod nonbounding;
mod polydisperse;
mod portable;
mod ray_march;
mod rayleigh;
mod rayleigh_polarized;
mod residual;
mod schlick;
mod spectral;
mod spectral_phase;
mod surface;
mod table2d;
mod two_lobe_hg;
mod vector_mc;
