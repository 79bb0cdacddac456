//! A suite of media of different kinds, and rays of different classes
//! through them, for the transmittance estimators: the main example's
//! media report and the unbiasedness tests share it. Every medium lies in
//! `[−1, 1]³` with 16³ majorants and minorants built by the library (the
//! callback blob's are computed here, exactly).
#![allow(dead_code)]

use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{Rng, SeedableRng};
use scatterkit::majorant::{DEFAULT_RES, Majorants, Transmittance};
use scatterkit::medium::Event;
use scatterkit::medium::ray_march::{Placement, Series, march_grid_within, march_within};
use scatterkit::medium::residual::Extrema;
use scatterkit::{Error, Grid, Ray, Real, Sampling, Vec3};

/// The kinds of medium.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// 128³, a dense Gaussian core (peak 60) in a haze, a corner empty.
    Cloud,
    /// 128³, density falling off exponentially with height.
    FogBank,
    /// 64³, seven small dense clumps in empty space.
    Sparse,
    /// 64³, a smooth field spanning four decades (10⁻³ … 10).
    Decades,
    /// 64³, one plane of nodes at density 1000 over a floor of 0.1.
    SheetNodes,
    /// 64³, the same values read at cell centres.
    SheetCells,
    /// A Gaussian blob through a callback, with exact extrema per cell.
    Blob,
}

pub const KINDS: [Kind; 7] = [
    Kind::Cloud,
    Kind::FogBank,
    Kind::Sparse,
    Kind::Decades,
    Kind::SheetNodes,
    Kind::SheetCells,
    Kind::Blob,
];

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::Cloud => "128³ cloud",
            Kind::FogBank => "128³ fog bank",
            Kind::Sparse => "64³ sparse clumps",
            Kind::Decades => "64³ four decades",
            Kind::SheetNodes => "64³ sheet, nodes",
            Kind::SheetCells => "64³ sheet, cells",
            Kind::Blob => "callback blob",
        }
    }

    /// Grid size per axis (the blob's extrema are on the 16³ cells).
    fn n(self) -> usize {
        match self {
            Kind::Cloud | Kind::FogBank => 128,
            _ => 64,
        }
    }

    /// `σ_t` per unit density (`σ_a`, `σ_s` in the ratio 1 : 4).
    fn scale(self) -> f32 {
        match self {
            Kind::SheetNodes | Kind::SheetCells => 0.1,
            _ => 1.0,
        }
    }

    /// Where the densest part lies (rays of [`Class::Dense`] aim there).
    fn dense_points(self) -> &'static [[f32; 3]] {
        match self {
            Kind::Cloud => &[[0.1, -0.2, 0.0]],
            Kind::FogBank => &[[0.0, 0.0, -0.9]],
            Kind::Sparse => &CLUMPS_AT,
            Kind::Decades => &[[0.78, -1.0, 0.5]],
            Kind::SheetNodes | Kind::SheetCells => &[[SHEET_X, 0.0, 0.0]],
            Kind::Blob => &[[0.0, 0.0, 0.0]],
        }
    }
}

/// The sheet's plane: node 32 of 64 over [−1, 1].
pub const SHEET_X: f32 = 2.0 * 32.0 / 63.0 - 1.0;

const CLUMPS_AT: [[f32; 3]; 7] = [
    [-0.6, -0.5, -0.4],
    [0.5, -0.6, 0.2],
    [-0.2, 0.6, 0.5],
    [0.6, 0.5, -0.6],
    [0.0, 0.0, 0.0],
    [-0.7, 0.3, -0.7],
    [0.3, -0.1, 0.7],
];

/// Clump radii and peaks.
const CLUMPS: [(f32, f32); 7] = [
    (0.10, 40.0),
    (0.06, 80.0),
    (0.14, 20.0),
    (0.08, 60.0),
    (0.12, 30.0),
    (0.05, 100.0),
    (0.09, 50.0),
];

/// The blob: `BLOB_PEAK · exp(−|p|²/BLOB_S²)`.
pub const BLOB_PEAK: f64 = 12.0;
pub const BLOB_S: f64 = 0.35;

/// The values of a grid kind (empty for the blob).
pub fn values(kind: Kind) -> Vec<f32> {
    let n = kind.n();
    match kind {
        Kind::Cloud => super::cloud::cloud(128, 60.0),
        Kind::FogBank => super::cloud::fog_bank(128, 8.0),
        Kind::Sparse => super::cloud::sample(n, |x, y, z| {
            let mut rho = 0.0f32;
            for (c, (r, peak)) in CLUMPS_AT.iter().zip(CLUMPS) {
                let d2 = (x - c[0]).powi(2) + (y - c[1]).powi(2) + (z - c[2]).powi(2);
                rho += peak * (-d2 / (r * r)).exp();
            }
            // Empty space is exactly empty.
            if rho < 0.05 { 0.0 } else { rho }
        }),
        Kind::Decades => super::cloud::sample(n, |x, y, z| {
            let f = 0.5 + 0.5 * (2.0 * x).sin() * (1.5 * y + 0.2).cos() * (z + 0.5).sin();
            10f32.powf(-3.0 + 4.0 * f)
        }),
        Kind::SheetNodes | Kind::SheetCells => super::cloud::sample(n, |x, _, _| {
            if (x - SHEET_X).abs() < 1e-4 {
                1000.0
            } else {
                0.1
            }
        }),
        Kind::Blob => Vec::new(),
    }
}

/// A built medium: its grid (none for the blob) and 16³ extrema.
pub struct Medium<'a> {
    pub kind: Kind,
    pub grid: Option<Grid<'a, f32>>,
    pub extrema: Extrema<'a, f32>,
}

/// The box every medium fills.
pub fn bounds() -> (Vec3<f32>, Vec3<f32>) {
    (Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0))
}

/// `(σ_a, σ_s)` per unit density.
fn coefficients(kind: Kind) -> (f32, f32) {
    (0.2 * kind.scale(), 0.8 * kind.scale())
}

/// Builds `kind` over `values` into `max`, `min` (16³ each).
pub fn build<'a>(
    kind: Kind,
    values: &'a [f32],
    max: &'a mut [f32],
    min: &'a mut [f32],
) -> Medium<'a> {
    let (lo, hi) = bounds();
    let m = [DEFAULT_RES; 3];
    if kind == Kind::Blob {
        blob_extrema(max, min);
        let max = Majorants::new(max, m, lo, hi).expect("blob majorants");
        let min = Majorants::new(min, m, lo, hi).expect("blob minorants");
        let extrema = Extrema::new(max, min).expect("blob extrema");
        return Medium {
            kind,
            grid: None,
            extrema,
        };
    }
    let n = kind.n();
    let (sa, ss) = coefficients(kind);
    let sampling = if kind == Kind::SheetCells {
        Sampling::Cells
    } else {
        Sampling::Nodes
    };
    let grid = Grid::new(values, n, n, n, sa, ss)
        .and_then(|g| g.with_box(lo, hi))
        .map(|g| g.with_sampling(sampling))
        .expect("suite grid");
    let extrema = Extrema::build(&grid, m, max, min).expect("suite extrema");
    Medium {
        kind,
        grid: Some(grid),
        extrema,
    }
}

/// The transmittance estimators, each at its default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Estimator {
    /// Delta tracking; its estimate is 1 for an escape, else 0.
    Delta,
    Ratio,
    Residual,
    /// Ray marching, the power series.
    Power,
    /// Ray marching, the telescoping sum.
    Telescoping,
}

pub const ESTIMATORS: [Estimator; 5] = [
    Estimator::Delta,
    Estimator::Ratio,
    Estimator::Residual,
    Estimator::Power,
    Estimator::Telescoping,
];

/// One estimate of `e` along `ray` through `m`, with its 16³ majorants
/// (and minorants for residual tracking and the marchers' strata).
pub fn estimate<R: Rng + ?Sized>(
    m: &Medium<'_>,
    e: Estimator,
    ray: Ray<f32>,
    r: &mut R,
) -> Result<f32, Error> {
    const BUDGET: u32 = 1 << 24;
    let maj = m.extrema.majorants();
    let place = Placement {
        max: maj,
        min: Some(m.extrema.minorants()),
    };
    let tr = |t: Transmittance<f32>| t.tr;
    let blob = blob_coefficients;
    Ok(match (e, &m.grid) {
        (Estimator::Delta, g) => {
            let t = match g {
                Some(g) => maj.delta_track(g, ray, BUDGET, r)?,
                None => maj.delta_track_fn(blob, ray, BUDGET, r)?,
            };
            f32::from(u8::from(t.event == Event::Escaped))
        }
        (Estimator::Ratio, Some(g)) => tr(maj.ratio_track(g, ray, BUDGET, r)?),
        (Estimator::Ratio, None) => tr(maj.ratio_track_fn(blob, ray, BUDGET, r)?),
        (Estimator::Residual, Some(g)) => tr(m.extrema.residual_ratio_track(g, ray, BUDGET, r)?),
        (Estimator::Residual, None) => {
            tr(m.extrema.residual_ratio_track_fn(blob, ray, BUDGET, r)?)
        }
        (Estimator::Power | Estimator::Telescoping, g) => {
            let s = if e == Estimator::Power {
                Series::Power
            } else {
                Series::Telescoping
            };
            tr(match g {
                Some(g) => march_grid_within(s, place, g, ray, 0, BUDGET, r)?,
                None => march_within(s, place, blob, ray, 0, BUDGET, r)?,
            })
        }
    })
}

/// The blob's `σ_t` at `p`.
pub fn blob_sigma(p: Vec3<f32>) -> f32 {
    blob_at(p.x as f64, p.y as f64, p.z as f64) as f32
}

fn blob_at(x: f64, y: f64, z: f64) -> f64 {
    BLOB_PEAK * (-(x * x + y * y + z * z) / (BLOB_S * BLOB_S)).exp()
}

/// The blob's `(σ_a, σ_s)` at `p`.
pub fn blob_coefficients(p: Vec3<f32>) -> (f32, f32) {
    let s = blob_sigma(p);
    (0.2 * s, 0.8 * s)
}

/// The blob's exact optical depth along `o + t d` (`d` a unit vector)
/// over `[a, b]`: the Gaussian integral, by `erf`.
pub fn blob_depth(o: [f64; 3], d: [f64; 3], a: f64, b: f64) -> f64 {
    let s2 = BLOB_S * BLOB_S;
    let tc = -(o[0] * d[0] + o[1] * d[1] + o[2] * d[2]);
    let c = [o[0] + tc * d[0], o[1] + tc * d[1], o[2] + tc * d[2]];
    let r2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    let k = BLOB_PEAK * (-r2 / s2).exp() * BLOB_S * core::f64::consts::PI.sqrt() / 2.0;
    k * (libm::erf((b - tc) / BLOB_S) - libm::erf((a - tc) / BLOB_S))
}

/// Per 16³ cell, the blob's `σ_t` at the nearest and farthest points of
/// the cell to its centre (times 1 ± 10⁻⁵ for rounding), x fastest.
fn blob_extrema(max: &mut [f32], min: &mut [f32]) {
    let m = DEFAULT_RES;
    let w = 2.0 / m as f64;
    let mut idx = 0;
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                let lo = [i, j, k].map(|c| -1.0 + w * c as f64);
                let near = lo.map(|l| (0.0f64).clamp(l, l + w));
                let far = lo.map(|l| if (l + l + w) < 0.0 { l } else { l + w });
                max[idx] = (blob_at(near[0], near[1], near[2]) * (1.0 + 1e-5)) as f32;
                min[idx] = (blob_at(far[0], far[1], far[2]) * (1.0 - 1e-5)) as f32;
                idx += 1;
            }
        }
    }
}

/// The classes of ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// From outside, aimed at the densest part.
    Dense,
    /// From outside, skimming the box: aimed at points within 0.05 of a face.
    Grazing,
    /// From inside the box, any direction, out to its face.
    Inside,
    /// Lying in a face of the box or of the 16³ majorant cells.
    Faces,
    /// From outside, aimed anywhere in the box (for sparse media mostly
    /// through empty space).
    Anywhere,
}

pub const CLASSES: [Class; 5] = [
    Class::Dense,
    Class::Grazing,
    Class::Inside,
    Class::Faces,
    Class::Anywhere,
];

impl Class {
    pub fn name(self) -> &'static str {
        match self {
            Class::Dense => "through the dense part",
            Class::Grazing => "grazing",
            Class::Inside => "starting inside",
            Class::Faces => "along faces",
            Class::Anywhere => "anywhere",
        }
    }
}

/// `count` rays of `class` for `kind`, the same on every call.
pub fn rays(kind: Kind, class: Class, count: usize) -> Vec<Ray<f32>> {
    let mut r = Xoshiro256PlusPlus::seed_from_u64(29 + class as u64);
    let mut u = move || f32::uniform(&mut r);
    let outside = |u: &mut dyn FnMut() -> f32| {
        let zc = 2.0 * u() - 1.0;
        let ph = core::f32::consts::TAU * u();
        let s = (1.0 - zc * zc).sqrt();
        Vec3::new(3.0 * s * ph.cos(), 3.0 * s * ph.sin(), 3.0 * zc)
    };
    let dense = kind.dense_points();
    (0..count)
        .map(|i| match class {
            Class::Dense => {
                let c = dense[i % dense.len()];
                let o = outside(&mut u);
                let aim = Vec3::new(
                    c[0] + 0.04 * (u() - 0.5),
                    c[1] + 0.04 * (u() - 0.5),
                    c[2] + 0.04 * (u() - 0.5),
                );
                Ray::new(o, aim - o, f32::INFINITY)
            }
            Class::Grazing => {
                let o = outside(&mut u);
                let mut a = [1.6 * u() - 0.8, 1.6 * u() - 0.8, 1.6 * u() - 0.8];
                let axis = (u() * 3.0) as usize % 3;
                a[axis] = if u() < 0.5 { -0.97 } else { 0.97 };
                let aim = Vec3::new(a[0], a[1], a[2]);
                Ray::new(o, aim - o, f32::INFINITY)
            }
            Class::Inside => {
                let o = Vec3::new(1.8 * u() - 0.9, 1.8 * u() - 0.9, 1.8 * u() - 0.9);
                let zc = 2.0 * u() - 1.0;
                let ph = core::f32::consts::TAU * u();
                let s = (1.0 - zc * zc).sqrt();
                Ray::new(o, Vec3::new(s * ph.cos(), s * ph.sin(), zc), f32::INFINITY)
            }
            Class::Faces => {
                // A plane x = const: the box face or a majorant cell face
                // (multiples of 1/8), a direction within it.
                let x = -1.0 + 0.125 * ((u() * 17.0) as usize).min(16) as f32;
                let ph = core::f32::consts::TAU * u();
                let o = Vec3::new(x, 2.0 * u() - 1.0, 2.0 * u() - 1.0);
                Ray::new(o, Vec3::new(0.0, ph.cos(), ph.sin()), f32::INFINITY)
            }
            Class::Anywhere => {
                let o = outside(&mut u);
                let aim = Vec3::new(1.8 * u() - 0.9, 1.8 * u() - 0.9, 1.8 * u() - 0.9);
                Ray::new(o, aim - o, f32::INFINITY)
            }
        })
        .collect()
}
