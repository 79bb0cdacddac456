//! Shared test machinery: double-double references, the chi² test, seeded
//! RNGs and the directions every sampler is tested about.
#![allow(dead_code)]

pub mod cbuild;
pub mod chi2;
pub mod dd;
pub mod ks;

pub use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// A fixed-seed generator: every test is deterministic.
pub fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

/// The incident directions the chi² tests use: ±z, ±x and one off every axis.
pub fn test_directions() -> [[f64; 3]; 5] {
    let l = (0.3f64 * 0.3 + 0.5 * 0.5 + 0.81 * 0.81).sqrt();
    [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.3 / l, -0.5 / l, 0.81 / l],
    ]
}

/// Samples per chi² test.
pub const CHI2_SAMPLES: usize = 1_000_000;

/// `n` uniforms evenly over `[0, 1]` including both ends.
pub fn uniform_grid(n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| i as f64 / (n - 1) as f64)
}
