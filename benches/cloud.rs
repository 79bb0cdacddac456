//! A cloud-like medium for the majorant-grid measurements (the main
//! example's media report and the criterion bench): an `n³` grid over
//! `[−1, 1]³` with a Gaussian core of density `peak` and a haze of density at
//! most 1 (so for `peak ≥ 20` every voxel outside the core holds at most 5 %
//! of the maximum), empty where `x + y + z > 1.5`; and a fixed set of rays
//! from a sphere of radius 3 aimed at points inside the box.
#![allow(dead_code)]

use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;
use scatterkit::majorant::{DEFAULT_RES, Majorants};
use scatterkit::{Grid, Ray, Real, Vec3};

/// Coefficients per unit density: σ_a, σ_s.
pub const SIGMA: (f32, f32) = (0.2, 0.8);

/// The `n³` values of `f(x, y, z)` at the nodes of `[−1, 1]³` (x fastest).
pub fn sample(n: usize, f: impl Fn(f32, f32, f32) -> f32) -> Vec<f32> {
    let c = |i: usize| 2.0 * i as f32 / (n - 1) as f32 - 1.0;
    let mut v = Vec::with_capacity(n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                v.push(f(c(i), c(j), c(k)));
            }
        }
    }
    v
}

/// The `n³` densities (x fastest).
pub fn cloud(n: usize, peak: f32) -> Vec<f32> {
    sample(n, |x, y, z| {
        let r2 = (x - 0.1) * (x - 0.1) + (y + 0.2) * (y + 0.2) + 2.0 * z * z;
        let haze = 0.5 * (1.0 + (5.0 * x).sin() * (4.0 * y).cos() * (3.0 * z).sin());
        if x + y + z > 1.5 {
            0.0
        } else {
            peak * (-r2 / 0.04).exp() + haze
        }
    })
}

/// The grid of `n³` cloud `values` over `[−1, 1]³` with [`SIGMA`].
pub fn grid(values: &[f32], n: usize) -> Grid<'_, f32> {
    let (lo, hi) = (Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0));
    Grid::new(values, n, n, n, SIGMA.0, SIGMA.1)
        .and_then(|g| g.with_box(lo, hi))
        .expect("the cloud grid is valid")
}

/// Its 16³ local majorants in `local` (`DEFAULT_RES³` values) and its one
/// global majorant (a 1³ grid) in `global`.
pub fn majorants<'a>(
    grid: &Grid<'_, f32>,
    local: &'a mut [f32],
    global: &'a mut [f32; 1],
) -> (Majorants<'a, f32>, Majorants<'a, f32>) {
    let l = Majorants::build(grid, [DEFAULT_RES; 3], local).expect("local majorants");
    let g = Majorants::build(grid, [1; 3], global).expect("global majorant");
    (l, g)
}

/// The largest density over the mean.
pub fn peak_over_mean(v: &[f32]) -> f64 {
    let max = v.iter().fold(0.0f32, |a, &b| a.max(b)) as f64;
    let mean = v.iter().map(|&x| x as f64).sum::<f64>() / v.len() as f64;
    max / mean
}

/// `count` rays over `[0, ∞)`, the same for every caller.
pub fn rays(count: usize) -> Vec<Ray<f32>> {
    let mut r = Xoshiro256PlusPlus::seed_from_u64(11);
    let mut u = move || f32::uniform(&mut r);
    (0..count)
        .map(|_| {
            let zc = 2.0 * u() - 1.0;
            let ph = core::f32::consts::TAU * u();
            let s = (1.0 - zc * zc).sqrt();
            let o = Vec3::new(3.0 * s * ph.cos(), 3.0 * s * ph.sin(), 3.0 * zc);
            let aim = Vec3::new(1.6 * u() - 0.8, 1.6 * u() - 0.8, 1.6 * u() - 0.8);
            Ray::new(o, aim - o, f32::INFINITY)
        })
        .collect()
}

/// A smooth fog bank: the `n³` densities of a layer whose density falls off
/// with height, `peak · exp(−(z + 1)/0.35)`, gently modulated across the
/// box (±20 %), with no edges and no empty region.
pub fn fog_bank(n: usize, peak: f32) -> Vec<f32> {
    sample(n, |x, y, z| {
        let swell = 1.0 + 0.2 * (1.5 * x).sin() * (1.2 * y + 0.3).cos();
        peak * (-(z + 1.0) / 0.35).exp() * swell
    })
}
