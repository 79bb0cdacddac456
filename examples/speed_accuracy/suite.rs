//! The media suite: every transmittance estimator at its default on media
//! of different kinds and rays of different classes
//! (`benches/media_suite.rs`), variance × time against ratio tracking and
//! the share of estimates outside [0, 1], from Rust and from C
//! (`benches/c_suite.c`, through `sk_track_args` with `strata = 0`).

use crate::media_suite::{CLASSES, Class, ESTIMATORS, KINDS, Kind, Medium};
use crate::*;
use std::collections::BTreeMap;
use std::fmt::Write as _;

const RAYS: usize = 100;
const PER_RAY: usize = 100;
/// A variance that is f32 rounding alone.
const FLOOR: f64 = 1e-13;

/// A C cell outside the repository (the section says why).
const SKIP: &str = "skipped";

const NAMES: [&str; 5] = ["delta", "ratio", "residual", "march", "telescoping"];
const LABELS: [&str; 5] = [
    "delta tracking (escapes)",
    "ratio tracking",
    "residual ratio tracking",
    "ray marching, power series",
    "ray marching, telescoping",
];

/// One estimate of estimator `e` (an index into [`NAMES`]) from Rust; NaN
/// for an error.
fn estimate(m: &Medium<'_>, e: usize, ray: Ray<f32>, r: &mut SplitMix) -> f32 {
    crate::media_suite::estimate(m, ESTIMATORS[e], ray, r).unwrap_or(f32::NAN)
}

/// Per (estimator, class): (ns per estimate, mean per-ray variance, share
/// outside [0, 1]).
type Stats = BTreeMap<(usize, usize), (f64, f64, f64)>;

fn rust_stats(m: &Medium<'_>, rays: &[Vec<Ray<f32>>]) -> Stats {
    let mut out = Stats::new();
    for (c, rays) in rays.iter().enumerate() {
        let mut ns = [f64::INFINITY; NAMES.len()];
        // The estimators take turns, run after run: the machine's drift
        // falls on all of them alike.
        let mut r = SplitMix(5);
        for _ in 0..REPEATS {
            for (e, best) in ns.iter_mut().enumerate() {
                let start = Instant::now();
                let mut acc = 0.0f32;
                for &ray in rays {
                    acc += estimate(m, e, ray, &mut r);
                }
                black_box(acc);
                *best = best.min(start.elapsed().as_nanos() as f64 / rays.len() as f64);
            }
        }
        for (e, &t) in ns.iter().enumerate() {
            let mut r = SplitMix(3);
            let (mut var, mut outside) = (0.0f64, 0usize);
            for &ray in rays {
                let (mut s, mut s2) = (0.0f64, 0.0f64);
                for _ in 0..PER_RAY {
                    let t = estimate(m, e, ray, &mut r);
                    s += t as f64;
                    s2 += t as f64 * t as f64;
                    outside += usize::from(!(0.0..=1.0).contains(&t));
                }
                let mean = s / PER_RAY as f64;
                var += (s2 - PER_RAY as f64 * mean * mean).max(0.0) / (PER_RAY - 1) as f64;
            }
            let n = rays.len() as f64;
            let share = outside as f64 / (n * PER_RAY as f64);
            out.insert((e, c), (t, var / n, share));
        }
    }
    out
}

/// The file `benches/c_suite.c` reads (its header says the layout).
fn write_data(
    kind: Kind,
    values: &[f32],
    m: &Medium<'_>,
    rays: &[Vec<Ray<f32>>],
) -> std::path::PathBuf {
    let mut b: Vec<u8> = Vec::new();
    let mut put = |x: [u8; 4]| b.extend(x);
    let n = m.grid.map_or(0, |g| g.dims()[0] as u32);
    put(n.to_le_bytes());
    put(u32::from(kind == Kind::SheetCells).to_le_bytes());
    let (sa, ss) = m.grid.map_or((0.0, 0.0), |g| g.coefficients());
    put(sa.to_le_bytes());
    put(ss.to_le_bytes());
    put((rays.len() as u32).to_le_bytes());
    put((RAYS as u32).to_le_bytes());
    if n > 0 {
        values.iter().for_each(|v| put(v.to_le_bytes()));
    } else {
        let [mx, my, mz] = m.extrema.majorants().dims();
        for ext in [m.extrema.majorants(), m.extrema.minorants()] {
            for k in 0..mz {
                for j in 0..my {
                    for i in 0..mx {
                        put(ext.get(i, j, k).to_le_bytes());
                    }
                }
            }
        }
    }
    for r in rays.iter().flatten() {
        for x in [
            r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z,
        ] {
            put(x.to_le_bytes());
        }
    }
    let path = target_dir().join("c_abi_bench/suite.bin");
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(&path, b).unwrap();
    path
}

/// The C side, `None` outside the repository.
fn c_stats(path: &std::path::Path) -> Option<Stats> {
    if !c_library_here() {
        return None;
    }
    let from_c = run_c_env("benches/c_suite.c", &[], &[("SK_MEDIA_DATA", path)])
        .expect("compiling benches/c_suite.c failed");
    let mut out = Stats::new();
    for e in 0..NAMES.len() {
        for c in 0..CLASSES.len() {
            let (ns, var) = from_c[&format!("suite.{}.{c}", NAMES[e])];
            let (share, _) = from_c[&format!("suite.{}.{c}.out", NAMES[e])];
            out.insert((e, c), (ns, var, share));
        }
    }
    Some(out)
}

/// Variance × time of ratio tracking over estimator `e`'s on class `c`:
/// `None` where ratio tracking's variance is rounding alone (every
/// estimate 0 or exact), +∞ where `e`'s is.
fn gain(s: &Stats, e: usize, c: usize) -> Option<f64> {
    let (t0, v0, _) = s[&(1, c)];
    let (t, v, _) = s[&(e, c)];
    if v0 <= FLOOR {
        None
    } else if v <= FLOOR {
        Some(f64::INFINITY)
    } else {
        Some(v0 * t0 / (v * t))
    }
}

fn show(g: Option<f64>) -> String {
    match g {
        None => "—".into(),
        Some(g) if g.is_infinite() => "exact".into(),
        Some(g) if g >= 100.0 => format!("{g:.0}×"),
        Some(g) => format!("{g:.2}×"),
    }
}

/// Markdown for `docs/measured/PERFORMANCE.md`, and whether every target
/// was met.
pub(crate) fn suite_report() -> String {
    let mut per_medium = Vec::new();
    for kind in KINDS {
        let values = crate::media_suite::values(kind);
        let (mut max, mut min) = (vec![0.0f32; 4096], vec![0.0f32; 4096]);
        let m = crate::media_suite::build(kind, &values, &mut max, &mut min);
        let rays: Vec<Vec<Ray<f32>>> = CLASSES
            .iter()
            .map(|&c| crate::media_suite::rays(kind, c, RAYS))
            .collect();
        let path = write_data(kind, &values, &m, &rays);
        let rust = rust_stats(&m, &rays);
        let c = c_stats(&path);
        per_medium.push((kind, rust, c));
    }
    let mut md = String::new();
    writeln!(
        md,
        "\n## Media suite: every estimator at its default, on media it was not tuned on\n\n\
         Seven media (`benches/media_suite.rs`, all over [−1, 1]³ with 16³ majorants and minorants): the 128³ cloud \
         and fog bank above; seven small dense clumps in empty space (64³); a smooth field over four decades, \
         10⁻³ to 10 (64³); one plane of nodes at density 1000 over a floor of 0.1 (σ_t 0.1 per unit density), read at \
         the nodes and at cell centres (64³); a Gaussian blob (peak 12, radius 0.35) through a callback with exact \
         per-cell extrema. Five classes of ray, {RAYS} each: from outside through the densest part; grazing (aimed \
         within 0.03 of a face); starting inside; lying in a face of the box or of the majorant cells; from outside \
         aimed anywhere. {PER_RAY} estimates per ray for the variance (the mean over rays of the per-ray sample \
         variance), f32, SplitMix64; ns per estimate the fastest of {REPEATS} runs over the rays, the estimators taking turns. From C: \
         `benches/c_suite.c` at `-O2` through `sk_track_args` with `strata = 0`. The gain is ratio tracking's \
         variance × time over the estimator's, Rust / C; — where ratio tracking's variance is rounding alone \
         (every estimate 0), exact where the estimator's is.\n"
    )
    .unwrap();
    if per_medium.iter().any(|m| m.2.is_none()) {
        writeln!(md, "C: SKIPPED, {C_SKIPPED}.\n").unwrap();
    }
    writeln!(
        md,
        "Ray marching (power series) at its default, gain per class, Rust / C:\n\n| medium | {} |\n|---|{}",
        CLASSES.map(Class::name).join(" | "),
        "---:|".repeat(CLASSES.len())
    )
    .unwrap();
    let per_class = |md: &mut String, e: usize| {
        for (kind, rust, c) in &per_medium {
            let cells: Vec<String> = (0..CLASSES.len())
                .map(|k| {
                    let from_c = c.as_ref().map_or(SKIP.into(), |c| show(gain(c, e, k)));
                    format!("{} / {from_c}", show(gain(rust, e, k)))
                })
                .collect();
            writeln!(md, "| {} | {} |", kind.name(), cells.join(" | ")).unwrap();
        }
    };
    per_class(&mut md, 3);
    writeln!(
        md,
        "\nResidual ratio tracking, gain per class, Rust / C:\n\n| medium | {} |\n|---|{}",
        CLASSES.map(Class::name).join(" | "),
        "---:|".repeat(CLASSES.len())
    )
    .unwrap();
    per_class(&mut md, 2);
    writeln!(
        md,
        "\nEvery estimator: the worst and best class's gain, and the largest share of estimates outside [0, 1] \
         over the classes, Rust / C:\n\n| medium | estimator | worst class | best class | outside [0, 1] |\n|---|---|---:|---:|---:|"
    )
    .unwrap();
    let worst_best = |s: &Stats, e: usize| {
        let gs: Vec<f64> = (0..CLASSES.len()).filter_map(|c| gain(s, e, c)).collect();
        let worst = gs.iter().copied().fold(f64::INFINITY, f64::min);
        let best = gs.iter().copied().fold(0.0f64, f64::max);
        (worst, best)
    };
    let out_share = |s: &Stats, e: usize| {
        (0..CLASSES.len())
            .map(|c| s[&(e, c)].2)
            .fold(0.0f64, f64::max)
    };
    for (kind, rust, c) in &per_medium {
        for e in [0usize, 2, 3, 4] {
            let (rw, rb) = worst_best(rust, e);
            let from_c = |f: &dyn Fn(&Stats) -> String| c.as_ref().map_or(SKIP.into(), f);
            let cw = from_c(&|c| show(Some(worst_best(c, e).0)));
            let cb = from_c(&|c| show(Some(worst_best(c, e).1)));
            let co = from_c(&|c| format!("{:.2} %", 100.0 * out_share(c, e)));
            writeln!(
                md,
                "| {} | {} | {} / {cw} | {} / {cb} | {:.2} % / {co} |",
                kind.name(),
                LABELS[e],
                show(Some(rw)),
                show(Some(rb)),
                100.0 * out_share(rust, e),
            )
            .unwrap();
        }
    }
    // The targets.
    let all = |e: usize, floor: f64, kinds: &[Kind]| {
        let mut worst = f64::INFINITY;
        for (kind, rust, c) in &per_medium {
            if kinds.contains(kind) {
                worst = worst.min(worst_best(rust, e).0);
                if let Some(c) = c {
                    worst = worst.min(worst_best(c, e).0);
                }
            }
        }
        (worst, worst >= floor)
    };
    let ok = |b: bool| if b { "met" } else { "**missed**" };
    let (p1, p1ok) = all(3, 1.0, &KINDS);
    let (p10, p10ok) = all(3, 10.0, &[Kind::Cloud, Kind::Sparse]);
    let (r1, r1ok) = all(2, 1.0, &KINDS);
    let out_max = per_medium
        .iter()
        .map(|(_, r, c)| out_share(r, 3).max(c.as_ref().map_or(0.0, |c| out_share(c, 3))))
        .fold(0.0f64, f64::max);
    writeln!(
        md,
        "\n| target | measured (worst over media, classes, Rust and C) | |\n|---|---|---|"
    )
    .unwrap();
    writeln!(
        md,
        "| power series at its default ≥ 1× ratio tracking on every medium and class | {} | {} |",
        show(Some(p1)),
        ok(p1ok)
    )
    .unwrap();
    writeln!(
        md,
        "| power series ≥ 10× on the 128³ cloud and the sparse clumps, every class | {} | {} |",
        show(Some(p10)),
        ok(p10ok)
    )
    .unwrap();
    writeln!(
        md,
        "| residual ratio tracking ≥ 1× on every medium and class | {} | {} |",
        show(Some(r1)),
        ok(r1ok)
    )
    .unwrap();
    writeln!(
        md,
        "| power series: < 1 % of estimates outside [0, 1] on every medium | {:.2} % | {} |",
        100.0 * out_max,
        ok(out_max < 0.01)
    )
    .unwrap();
    md
}
