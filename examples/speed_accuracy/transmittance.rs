//! The transmittance report: ratio tracking, residual ratio tracking and
//! the two unbiased ray-marching estimators, variance against cost, on the
//! cloud, a smooth fog bank and a constant medium.

use crate::*;
use scatterkit::majorant::{DEFAULT_RES, Majorants};
use scatterkit::medium::ray_march::{Placement, Series, march_grid_within};
use scatterkit::medium::residual::Extrema;
use std::fmt::Write as _;

/// Rays per medium, and estimates per ray for the variance.
const RAYS: usize = 400;
const PER_RAY: usize = 100;
const BUDGET: u32 = 1 << 24;
/// A variance that is rounding alone: f32 rounds a transmittance in
/// [0.01, 1] to within 6·10⁻⁸, whose square is 4·10⁻¹⁵.
const FLOOR: f64 = 1e-13;

/// The three estimators, all given the same 16³ majorants.
#[derive(Clone, Copy)]
enum Estimator {
    Ratio,
    Residual,
    RayMarch,
    Telescoping,
}

const ESTIMATORS: [(Estimator, &str); 4] = [
    (Estimator::Ratio, "ratio tracking"),
    (
        Estimator::Residual,
        "residual ratio tracking (minorant control)",
    ),
    (
        Estimator::RayMarch,
        "ray marching, power series (default strata)",
    ),
    (
        Estimator::Telescoping,
        "ray marching, telescoping (default strata)",
    ),
];

struct Medium<'a> {
    grid: Grid<'a, f32>,
    extrema: Extrema<'a, f32>,
}

impl Medium<'_> {
    /// One estimate along `ray`: (transmittance, density evaluations).
    fn estimate(&self, e: Estimator, ray: Ray<f32>, r: &mut Xoshiro256PlusPlus) -> (f32, u32) {
        let maj: Majorants<'_, f32> = self.extrema.majorants();
        // The ray marchers' strata: the library's, placed by the extrema.
        let place = Placement {
            max: maj,
            min: Some(self.extrema.minorants()),
        };
        let march = |s: Series, r: &mut Xoshiro256PlusPlus| {
            march_grid_within(s, place, &self.grid, ray, 0, BUDGET, r)
        };
        let t = match e {
            Estimator::Ratio => maj.ratio_track(&self.grid, ray, BUDGET, r),
            Estimator::Residual => self
                .extrema
                .residual_ratio_track(&self.grid, ray, BUDGET, r),
            Estimator::RayMarch => march(Series::Power, r),
            Estimator::Telescoping => march(Series::Telescoping, r),
        }
        .expect("the estimators accept these rays");
        (t.tr, t.steps)
    }
}

/// Per estimator: (mean per-ray variance, evaluations per estimate, ns per
/// estimate).
fn measure(m: &Medium<'_>, rays: &[Ray<f32>]) -> [(f64, f64, f64); 4] {
    let stats = |e: Estimator| {
        let mut r = fast_rng();
        let (mut var, mut evals) = (0.0f64, 0u64);
        for &ray in rays {
            let (mut s, mut s2) = (0.0f64, 0.0f64);
            for _ in 0..PER_RAY {
                let (tr, steps) = m.estimate(e, ray, &mut r);
                s += tr as f64;
                s2 += tr as f64 * tr as f64;
                evals += steps as u64;
            }
            let mean = s / PER_RAY as f64;
            var += (s2 - PER_RAY as f64 * mean * mean).max(0.0) / (PER_RAY - 1) as f64;
        }
        let n = rays.len() as f64;
        (var / n, evals as f64 / (n * PER_RAY as f64))
    };
    let timer = |e: Estimator| {
        let mut r = fast_rng();
        let start = Instant::now();
        let mut acc = 0.0f32;
        for &ray in rays {
            acc += m.estimate(e, ray, &mut r).0;
        }
        black_box(acc);
        start.elapsed().as_nanos() as f64 / rays.len() as f64
    };
    let ns = interleaved([
        &mut || timer(Estimator::Ratio),
        &mut || timer(Estimator::Residual),
        &mut || timer(Estimator::RayMarch),
        &mut || timer(Estimator::Telescoping),
    ]);
    let mut out = [(0.0, 0.0, 0.0); 4];
    for (i, (e, _)) in ESTIMATORS.iter().enumerate() {
        let (v, c) = stats(*e);
        out[i] = (v, c, ns[i]);
    }
    out
}

/// The grid of `values` (`n³`, over `[−1, 1]³`) with its 16³ extrema,
/// handed to `f`.
fn with_medium<R>(values: &[f32], n: usize, f: impl FnOnce(&Medium<'_>) -> R) -> R {
    let grid = cloud::grid(values, n);
    let (mut max, mut min) = (
        vec![0.0f32; DEFAULT_RES.pow(3)],
        vec![0.0f32; DEFAULT_RES.pow(3)],
    );
    let extrema = Extrema::build(&grid, [DEFAULT_RES; 3], &mut max, &mut min).expect("extrema");
    f(&Medium { grid, extrema })
}

/// Markdown for `docs/measured/PERFORMANCE.md`: variance, cost and
/// variance × time against ratio tracking for each medium, and the targets.
pub(crate) fn transmittance_report() -> String {
    let rays = cloud::rays(RAYS);
    let media: [(&str, Vec<f32>, usize); 3] = [
        ("128³ cloud (peak 60)", cloud::cloud(128, 60.0), 128),
        ("128³ smooth fog bank", cloud::fog_bank(128, 8.0), 128),
        ("32³ constant medium (σ_t = 2)", vec![2.0; 32 * 32 * 32], 32),
    ];
    let mut md = String::new();
    writeln!(
        md,
        "\n## Media: transmittance estimators\n\n\
         Variance against cost of four unbiased transmittance estimators given the same 16³ majorants \
         (and, for residual ratio tracking, the 16³ minorants as control): {RAYS} rays of the set above, \
         {PER_RAY} estimates per ray for its variance (the mean over rays of the per-ray sample variance), f32. \
         Evaluations are density lookups per estimate; ns per estimate is the fastest of {REPEATS} interleaved \
         runs over the rays and includes, for the two ray marchers, the walk that places their strata. \
         The gain is ratio tracking's variance × time over the estimator's.\n\n\
         | medium | estimator | variance | evaluations | ns | variance × time gain |\n|---|---|---:|---:|---:|---:|"
    )
    .unwrap();
    // Per medium: each estimator's (variance, evaluations, ns).
    let mut all = Vec::new();
    for (name, values, n) in &media {
        let m = with_medium(values, *n, |m| measure(m, &rays));
        let base = m[0].0 * m[0].2;
        for (i, (_, label)) in ESTIMATORS.iter().enumerate() {
            let (v, c, ns) = m[i];
            let gain = if i == 0 {
                "1".to_string()
            } else if v > FLOOR {
                format!("{:.1}×", base / (v * ns))
            } else {
                "∞ (variance 0 to rounding)".to_string()
            };
            writeln!(
                md,
                "| {name} | {label} | {v:.2e} | {c:.1} | {ns:.0} | {gain} |"
            )
            .unwrap();
        }
        all.push(m);
    }
    let gain = |m: &[(f64, f64, f64); 4], i: usize| m[0].0 * m[0].2 / (m[i].0 * m[i].2);
    let cloud = &all[0];
    let (residual, power, telescoping) = (gain(cloud, 1), gain(cloud, 2), gain(cloud, 3));
    let best = residual.max(power).max(telescoping);
    let ok = |b: bool| if b { "met" } else { "**missed**" };
    writeln!(md, "\n| target | measured | |\n|---|---|---|").unwrap();
    writeln!(
        md,
        "| variance × time on the cloud ≥ 10× lower than ratio tracking | {best:.1}× (power series {power:.1}×, telescoping {telescoping:.1}×, residual {residual:.1}×) | {} |",
        ok(best >= 10.0)
    )
    .unwrap();
    let v = all[2].map(|x| x.0);
    let exact = v[1] <= FLOOR && v[2] <= FLOOR && v[3] <= FLOOR;
    writeln!(
        md,
        "| variance 0 (to rounding, ≤ {FLOOR:.0e}) for a constant medium | residual {:.1e}, power series {:.1e}, telescoping {:.1e} (ratio tracking {:.1e}) | {} |",
        v[1],
        v[2],
        v[3],
        v[0],
        ok(exact)
    )
    .unwrap();
    md
}
