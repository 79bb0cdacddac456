//! The media report: tracking through majorant grids against one global
//! majorant.

use crate::*;
use std::fmt::Write as _;

/// Delta and ratio tracking through a cloud with 16³ local majorants and
/// with one global majorant (a 1³ majorant grid, the same code): counts per
/// ray, time per ray (interleaved), and how the cost grows with the ratio
/// of peak to mean density. Markdown for `docs/measured/PERFORMANCE.md`.
pub(crate) fn media_report() -> String {
    use scatterkit::majorant::{DEFAULT_RES, Majorants};
    use scatterkit::medium::Event;
    let budget = 1 << 24;
    // Per ray: (tentative collisions of delta tracking, real collisions,
    // tentative collisions of ratio tracking).
    let counts = |grid: &Grid<'_, f32>, maj: &Majorants<'_, f32>, rays: &[Ray<f32>]| {
        let mut r = fast_rng();
        let (mut steps, mut real, mut ratio) = (0u64, 0u64, 0u64);
        for &ray in rays {
            let t = maj.delta_track(grid, ray, budget, &mut r).unwrap();
            steps += t.steps as u64;
            real += (t.event != Event::Escaped) as u64;
            ratio += maj.ratio_track(grid, ray, budget, &mut r).unwrap().steps as u64;
        }
        let n = rays.len() as f64;
        (steps as f64 / n, real as f64 / n, ratio as f64 / n)
    };
    let n = 128;
    let values = cloud::cloud(n, 60.0);
    let grid = cloud::grid(&values, n);
    let (mut local_store, mut global_store) = (vec![0.0f32; DEFAULT_RES.pow(3)], [0.0f32; 1]);
    let (local, global) = cloud::majorants(&grid, &mut local_store, &mut global_store);
    let rays = cloud::rays(2000);
    let (cl, cg) = (counts(&grid, &local, &rays), counts(&grid, &global, &rays));
    let timer = |maj: &Majorants<'_, f32>, ratio: bool| {
        let mut r = fast_rng();
        let start = Instant::now();
        let mut acc = 0.0f32;
        for &ray in &rays {
            acc += if ratio {
                maj.ratio_track(&grid, ray, budget, &mut r).unwrap().tr
            } else {
                maj.delta_track(&grid, ray, budget, &mut r).unwrap().t
            };
        }
        black_box(acc);
        start.elapsed().as_nanos() as f64 / rays.len() as f64
    };
    let [dl, dg, rl, rg] = interleaved([
        &mut || timer(&local, false),
        &mut || timer(&global, false),
        &mut || timer(&local, true),
        &mut || timer(&global, true),
    ]);
    let nulls = (cg.0 - cg.1) / (cl.0 - cl.1);
    let mut md = String::new();
    writeln!(
        md,
        "\n## Media: majorant grids\n\nA {n}³ cloud over [−1, 1]³ (`benches/cloud.rs`: a Gaussian core, a haze of at most 5 % of the peak, \
         an empty corner; peak/mean density {:.0}), 2000 rays from a sphere of radius 3 into the box, f32. \
         Tracking walks {DEFAULT_RES}³ local majorants (`Majorants::build`) or one global majorant (a 1³ majorant grid, the same code). \
         Times are per ray, the fastest of {REPEATS} interleaved runs.\n",
        cloud::peak_over_mean(&values)
    )
    .unwrap();
    writeln!(md, "| majorants | delta: evaluations per ray | null collisions per ray | ns per ray | ratio: evaluations per ray | ns per ray |").unwrap();
    writeln!(md, "|---|---:|---:|---:|---:|---:|").unwrap();
    for (name, c, d, r) in [("local 16³", cl, dl, rl), ("global", cg, dg, rg)] {
        writeln!(
            md,
            "| {name} | {:.1} | {:.1} | {:.0} | {:.1} | {:.0} |",
            c.0,
            c.0 - c.1,
            d,
            c.2,
            r
        )
        .unwrap();
    }
    writeln!(md, "\n| target | measured | |\n|---|---|---|").unwrap();
    let row = |md: &mut String, what: &str, v: f64, bound: f64| {
        let ok = if v >= bound { "met" } else { "**missed**" };
        writeln!(md, "| {what} | {v:.1}× | {ok} |").unwrap();
    };
    row(
        &mut md,
        "null collisions per ray, global / local ≥ 5×",
        nulls,
        5.0,
    );
    row(
        &mut md,
        "delta tracking time per ray, global / local ≥ 3×",
        dg / dl,
        3.0,
    );
    row(
        &mut md,
        "ratio tracking time per ray, global / local ≥ 3×",
        rg / rl,
        3.0,
    );
    writeln!(
        md,
        "\nHow the cost grows with the peak: the same cloud at 64³ with cores of rising peak, 1000 rays. \
         With one majorant the evaluations per ray grow with the peak; with local majorants they follow \
         the optical depth the rays actually cross.\n\n\
         | peak / mean density | delta, local | delta, global | ratio, local | ratio, global |\n|---:|---:|---:|---:|---:|"
    )
    .unwrap();
    let rays = cloud::rays(1000);
    for peak in [2.0f32, 10.0, 50.0, 250.0, 1000.0] {
        let values = cloud::cloud(64, peak);
        let grid = cloud::grid(&values, 64);
        let (mut ls, mut gs) = (vec![0.0f32; DEFAULT_RES.pow(3)], [0.0f32; 1]);
        let (local, global) = cloud::majorants(&grid, &mut ls, &mut gs);
        let (a, b) = (counts(&grid, &local, &rays), counts(&grid, &global, &rays));
        writeln!(
            md,
            "| {:.0} | {:.1} | {:.1} | {:.1} | {:.1} |",
            cloud::peak_over_mean(&values),
            a.0,
            b.0,
            a.2,
            b.2
        )
        .unwrap();
    }
    md
}
