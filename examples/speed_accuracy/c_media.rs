//! Media and mixtures through the C ABI against the same calls from Rust:
//! the 128³ cloud with majorants at 16³, 64³ and 128³, the same rays, the
//! same generator (SplitMix64; from C through the `sk_rng` callback), per
//! ray; a ray that misses the box; the exact mixture sample.

use crate::*;
use scatterkit::majorant::Majorants;
use scatterkit::medium::ray_march::{Placement, Series, march_grid_within};
use scatterkit::medium::residual::Extrema;
use scatterkit::mixture::{Mixture, Part};
use std::fmt::Write as _;

const BUDGET: u32 = 1 << 24;
const RESOLUTIONS: [usize; 3] = [16, 64, 128];
const ESTIMATORS: [&str; 4] = ["delta", "ratio", "residual", "march"];

/// SplitMix64, as `benches/c_media.c` has it.
pub(crate) struct SplitMix(pub(crate) u64);

impl TryRng for SplitMix {
    type Error = Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok((self.try_next_u64()? >> 32) as u32)
    }
    #[inline(always)]
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        self.0 = self.0.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        Ok(z ^ (z >> 31))
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        rand_xoshiro::rand_core::utils::fill_bytes_via_next_word(dst, || self.try_next_u64())
    }
}

/// One estimate from Rust: its t or transmittance.
fn estimate(
    e: usize,
    (grid, ext): (&Grid<'_, f32>, &Extrema<'_, f32>),
    ray: Ray<f32>,
    r: &mut SplitMix,
) -> f32 {
    let maj: Majorants<'_, f32> = ext.majorants();
    let tr = |x: Result<scatterkit::majorant::Transmittance<f32>, _>| x.map_or(f32::NAN, |t| t.tr);
    match e {
        0 => maj
            .delta_track(grid, ray, BUDGET, r)
            .map_or(f32::NAN, |t| t.t),
        1 => tr(maj.ratio_track(grid, ray, BUDGET, r)),
        2 => tr(ext.residual_ratio_track(grid, ray, BUDGET, r)),
        _ => {
            let place = Placement {
                max: maj,
                min: Some(ext.minorants()),
            };
            tr(march_grid_within(
                Series::Power,
                place,
                grid,
                ray,
                0,
                BUDGET,
                r,
            ))
        }
    }
}

/// ns per call of `f` over `count` calls, one run.
fn once(count: usize, mut f: impl FnMut(&mut SplitMix, usize) -> f32) -> f64 {
    let mut r = SplitMix(7);
    let start = Instant::now();
    let mut acc = 0.0f32;
    for i in 0..count {
        acc += f(&mut r, i);
    }
    black_box(acc);
    start.elapsed().as_nanos() as f64 / count as f64
}

/// The data file `benches/c_media.c` reads (its header says the layout).
fn write_data(values: &[f32], n: usize, rays: &[Ray<f32>]) -> std::path::PathBuf {
    let mut bytes = Vec::with_capacity(8 + 4 * (values.len() + 6 * rays.len()));
    bytes.extend((n as u32).to_le_bytes());
    bytes.extend((rays.len() as u32).to_le_bytes());
    for v in values {
        bytes.extend(v.to_le_bytes());
    }
    for r in rays {
        for x in [
            r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z,
        ] {
            bytes.extend(x.to_le_bytes());
        }
    }
    let path = target_dir().join("c_abi_bench/media.bin");
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Rounds of Rust runs and C runs, taking turns; each keeps its fastest.
const ROUNDS: usize = 3;

/// The Rust side of one round: `key → ns`, the keys of `benches/c_media.c`.
fn rust_round(
    grid: &Grid<'_, f32>,
    media: &[(usize, Extrema<'_, f32>)],
    rays: &[Ray<f32>],
    mix: &Mixture<'_, f32>,
) -> std::collections::BTreeMap<String, f64> {
    let mut out = std::collections::BTreeMap::new();
    for (m, ext) in media {
        let mut timers: Vec<Box<dyn FnMut() -> f64 + '_>> = (0..ESTIMATORS.len())
            .map(|e| {
                Box::new(move || once(rays.len(), |r, i| estimate(e, (grid, ext), rays[i], r)))
                    as Box<dyn FnMut() -> f64>
            })
            .collect();
        let [a, b, c, d] = &mut timers[..] else {
            unreachable!()
        };
        let ns = interleaved([&mut **a, &mut **b, &mut **c, &mut **d]);
        for (name, t) in ESTIMATORS.iter().zip(ns) {
            out.insert(format!("media.{name}.{m}"), t);
        }
    }
    let calls = 1 << 14;
    let t = (0..REPEATS)
        .map(|_| {
            once(calls, |_, i| {
                mix.sample_cos((i as f32 + 0.5) / calls as f32)
            })
        })
        .fold(f64::INFINITY, f64::min);
    out.insert("mix_exact".into(), t);
    out
}

/// Markdown for `docs/measured/PERFORMANCE.md`: per ray from Rust and
/// from C, their ratio against the 1.2× target, the missing ray against
/// 0.2 µs, and the exact mixture sample.
pub(crate) fn c_media_report() -> String {
    if !c_library_here() {
        return format!("\n## Media and mixtures: from C against Rust\n\nSKIPPED: {C_SKIPPED}.\n");
    }
    let n = 128;
    let values = cloud::cloud(n, 60.0);
    let grid = cloud::grid(&values, n);
    let rays = cloud::rays(2000);
    let data = write_data(&values, n, &rays);
    let mut stores: Vec<(usize, Vec<f32>, Vec<f32>)> = RESOLUTIONS
        .iter()
        .map(|&m| (m, vec![0.0f32; m * m * m], vec![0.0f32; m * m * m]))
        .collect();
    let media: Vec<(usize, Extrema<'_, f32>)> = stores
        .iter_mut()
        .map(|(m, max, min)| {
            let ext = Extrema::build(&grid, [*m; 3], max, min).expect("extrema");
            (*m, ext)
        })
        .collect();
    let parts = [
        (Part::Phase(Phase::<f32>::rayleigh()), 0.5f32),
        (Part::Phase(Phase::henyey_greenstein(0.7).unwrap()), 0.3),
        (Part::Phase(Phase::fog_diameter(2.0).unwrap()), 0.2),
    ];
    let mix = Mixture::new(&parts).unwrap();
    let (mut rust, mut c) = (
        std::collections::BTreeMap::<String, f64>::new(),
        std::collections::BTreeMap::<String, f64>::new(),
    );
    let keep = |into: &mut std::collections::BTreeMap<String, f64>, k: String, v: f64| {
        let e = into.entry(k).or_insert(f64::INFINITY);
        *e = e.min(v);
    };
    for _ in 0..ROUNDS {
        for (k, v) in rust_round(&grid, &media, &rays, &mix) {
            keep(&mut rust, k, v);
        }
        let from_c = run_c_env("benches/c_media.c", &[], &[("SK_MEDIA_DATA", &data)])
            .expect("compiling benches/c_media.c failed");
        for (k, (v, _)) in from_c {
            keep(&mut c, k, v);
        }
    }
    let mut md = String::new();
    writeln!(
        md,
        "\n## Media and mixtures: from C against Rust\n\nThe {n}³ cloud of the media report with its majorants and minorants at each resolution, \
         the same 2000 rays and the same generator (SplitMix64; from C through the `sk_rng` callback), \
         `benches/c_media.c` built at `-O2` against `libscatterkit.a`. ns per ray, the fastest of {ROUNDS} rounds in which \
         Rust and C take turns, each round the fastest of {REPEATS} runs; \
         ray marching (power series) with the library's strata (`strata = 0`). A ray that misses the box: ns per call from C.\n\n\
         | estimator | majorants | Rust ns/ray | C ns/ray | C / Rust | ≤ 1.2× | missing ray from C, ns | ≤ 200 ns |\n|---|---|---:|---:|---:|---|---:|---|"
    )
    .unwrap();
    let mark = |ok: bool| if ok { "met" } else { "**missed**" };
    for m in RESOLUTIONS {
        for name in ESTIMATORS {
            let key = format!("media.{name}.{m}");
            let (r, from_c, missed) = (rust[&key], c[&key], c[&format!("miss.{name}.{m}")]);
            writeln!(
                md,
                "| {name} | {m}³ | {r:.0} | {from_c:.0} | {:.2}× | {} | {missed:.1} | {} |",
                from_c / r,
                mark(from_c <= 1.2 * r),
                mark(missed <= 200.0)
            )
            .unwrap();
        }
    }
    // The miss against one majorant cell: the cost of a call does not
    // grow with the majorant grid (checked once, when built).
    let ratios: Vec<String> = ESTIMATORS
        .iter()
        .map(|name| {
            let (one, big) = (c[&format!("miss.{name}.1")], c[&format!("miss.{name}.64")]);
            format!(
                "{name} {big:.1} vs {one:.1} ns, {:.2}× ({})",
                big / one,
                mark(big <= 1.1 * one && big <= 200.0)
            )
        })
        .collect();
    writeln!(
        md,
        "\nA missing ray with 64³ majorants against one majorant cell (target ≤ 1.1× and ≤ 200 ns): {}.",
        ratios.join("; ")
    )
    .unwrap();
    let (r, from_c) = (rust["mix_exact"], c["mix_exact"]);
    writeln!(
        md,
        "\nThe exact inverse of Rayleigh + HG 0.7 + fog 2 µm (0.5 : 0.3 : 0.2), f32, 2¹⁴ evenly spaced u: \
         Rust {r:.0} ns, C (`sk_mixture_sample_cos`) {from_c:.0} ns per sample, {:.2}× (target ≤ 1.2×: {}).",
        from_c / r,
        mark(from_c <= 1.2 * r)
    )
    .unwrap();
    md
}
