//! Speed against accuracy: every sampler of scatterkit beside the peers'
//! formulas (Mitsuba 3, Cycles, pbrt-v4, Draine eq. 6, Draine by rejection)
//! and Frisvad's Table 1 (JOSA A 2011) re-run today, in one run.
//!
//!     cargo run --release --example speed_accuracy
//!
//! Prints a short summary (the targets met and missed, where the files
//! went) and writes `speed_accuracy.csv`,
//! `speed_accuracy.svg` (one log-log panel per family: ns per sample
//! against max error, Rust calls and calls through the C ABI, the Pareto
//! frontier drawn) and `PERFORMANCE.md` (Frisvad's ratios, the project's
//! speed targets and the C view, computed from this run) to
//! `target/speed_accuracy/`; with `SK_REFRESH_DOCS=1`, to `docs/measured/`
//! instead, the copies the README and the guides show. The C
//! view is `benches/c_abi.c`, built here with the `cc` crate at `-O2` against
//! `libscatterkit.a` and run once.
//!
//! Speed: ns per sample, the fastest of 15 runs of 2¹⁸ samples, f32, xoshiro256++
//! (and a deliberately slow generator in the spirit of the paper's C
//! `rand()`). Accuracy: max |cos θ − exact| and max |F(μ(u)) − u| over 2²⁰ + 1
//! evenly spaced u including 0 and 1, against an f64 evaluation of the exact
//! inverse (itself within 10⁻¹³ of double-double; see the tests). Rejection
//! methods are exact in distribution: the chart draws them hollow in a strip
//! under each panel's error axis, and the frontier counts them as more
//! accurate than any inverse (their tables give f32's rounding floor, half
//! an ULP of 1).
//!
//! Layout: `measure` (timing and accuracy), `entries` (the measured
//! points), `c_view` (the C benchmarks), `chart` (CSV and SVG), `report`
//! (PERFORMANCE.md), `media` (majorant grids), `transmittance` and `suite`
//! (the transmittance estimators, and the suite of media kinds, from Rust
//! and from C), `mie` (Mie tables against the cheap models, and the solver
//! against BHMIE). With `SK_MEDIA_ONLY=1` the run prints the two
//! transmittance sections alone (about a minute) and writes nothing.

#[path = "../../benches/cloud.rs"]
mod cloud;
#[path = "../../benches/media_suite.rs"]
mod media_suite;
#[path = "../../benches/peers.rs"]
mod peers;

mod c_media;
mod c_view;
mod chart;
mod entries;
mod measure;
mod media;
mod mie;
mod photon;
mod polarization;
mod report;
mod suite;
mod transmittance;

pub(crate) use c_media::*;
pub(crate) use c_view::*;
pub(crate) use chart::*;
pub(crate) use entries::*;
pub(crate) use measure::*;
pub(crate) use media::*;
pub(crate) use mie::*;
pub(crate) use photon::*;
pub(crate) use polarization::*;
pub(crate) use report::*;
pub(crate) use suite::*;
pub(crate) use transmittance::*;

pub(crate) use rand_xoshiro::Xoshiro256PlusPlus;
pub(crate) use rand_xoshiro::rand_core::{SeedableRng, TryRng};
pub(crate) use scatterkit::{
    Grid, Phase, PhaseFunction, Ray, RayleighMethod, Real, Table, Vec3, rayleigh,
};
pub(crate) use std::convert::Infallible;
use std::fmt::Write as _;
pub(crate) use std::hint::black_box;
pub(crate) use std::time::Instant;

/// What `--help` prints.
const HELP: &str = "speed_accuracy: every sampler of scatterkit beside the peers' formulas, speed against accuracy.

Usage: cargo run --release --example speed_accuracy [-- --help]

Runs about a minute and a half on two cores once built; prints a summary
(the targets met and missed) and writes the full report, PERFORMANCE.md,
with speed_accuracy.csv and speed_accuracy.svg, to target/speed_accuracy/.

Environment:
  SK_REFRESH_DOCS=1  write the three files to docs/measured/ instead (the
                     copies the README and the guides show)
  SK_MEDIA_ONLY=1    run the two transmittance sections alone (about a
                     minute), print them, write nothing
  SK_PHOTON_ONLY=1   run the whole-photon-loop section alone (C and Rust,
                     about 20 seconds), print it, write nothing
  SK_MEDIA_DATA=path used by the run itself: the 128^3 cloud and rays it
                     hands to benches/c_media.c (not set by hand)
  SK_REPORT=full     print the whole report on the terminal too
";

fn main() -> std::io::Result<()> {
    if std::env::args().skip(1).any(|a| a == "--help" || a == "-h") {
        print!("{HELP}");
        return Ok(());
    }
    if let Some(a) = std::env::args().nth(1) {
        eprintln!("speed_accuracy: unknown argument {a:?} (see --help)");
        std::process::exit(2);
    }
    let start = Instant::now();
    if std::env::var_os("SK_MEDIA_ONLY").is_some() {
        print!("{}{}", transmittance_report(), suite_report());
        return Ok(());
    }
    if std::env::var_os("SK_PHOTON_ONLY").is_some() {
        print!("{}", photon_report());
        return Ok(());
    }
    println!("Measured on {}.\n", machine());
    let mut es = Vec::new();
    rayleigh_entries(&mut es);
    hg_entries(&mut es);
    schlick_entries(&mut es);
    draine_entries(&mut es);
    cbrt_entries(&mut es);
    mie_entries(&mut es);
    let minimax = RayleighMethod::DirectMinimax;
    let rayleigh_batch = batch_ratio(
        |u, out| rayleigh::inverse_cdf_fill(minimax, u, out),
        rayleigh::inverse_cdf_minimax,
    );
    let hg = Phase::<f32>::henyey_greenstein(0.7).unwrap();
    let hg_batch = batch_ratio(
        |u, out| hg.sample_cos_n(u, out).unwrap(),
        |u| hg.sample_cos(u),
    );
    let c = c_abi();
    for (key, family, label, is_cos) in C_KEYS {
        let Some(c) = &c else {
            break;
        };
        let &(ns, err) = c
            .get(key)
            .unwrap_or_else(|| panic!("the C benchmark gave no {key}"));
        if !is_cos {
            continue;
        }
        es.push(c_entry(family, format!("C ABI: {label}"), ns, err));
    }
    // The peers' inline C again, built with -O3 -march=native (the library's
    // calls are the same archive: only the peers' points move).
    let native = c_abi_native();
    for (key, family, label, is_cos) in C_KEYS {
        let Some(&(ns, err)) = native.as_ref().and_then(|n| n.get(key)) else {
            continue;
        };
        if !is_cos || !label.starts_with("peer:") {
            continue;
        }
        es.push(c_entry(family, format!("C ABI native: {label}"), ns, err));
    }

    let mut md = String::new();
    writeln!(
        md,
        "### Directions (f32): ns per direction, and speed relative to simplified rejection\n"
    )
    .unwrap();
    writeln!(md, "| method | ns, xoshiro256++ | × simplified | ns, slow rand() | × simplified | max abs error in cos θ |").unwrap();
    writeln!(md, "|---|---:|---:|---:|---:|---|").unwrap();
    let simp = find(&es, Key::Simplified).dir_ns.unwrap();
    for e in es.iter().filter(|e| e.dir_ns.is_some()) {
        let (f, s) = e.dir_ns.unwrap();
        writeln!(
            md,
            "| {} | {f:.2} | {:.2} | {s:.2} | {:.2} | {} |",
            e.name,
            simp.0 / f,
            simp.1 / s,
            fmt_err(e)
        )
        .unwrap();
    }
    writeln!(
        md,
        "\n### Cosines (f32): ns per cos θ, max |cos θ error|, max |F(μ(u)) − u|\n"
    )
    .unwrap();
    writeln!(
        md,
        "| family | method | ns | max abs error | max CDF error |"
    )
    .unwrap();
    writeln!(md, "|---|---|---:|---:|---:|").unwrap();
    for e in es.iter().filter(|e| e.family != "cbrt") {
        let cdf = if e.rejection {
            "exact in distribution".into()
        } else if e.cdf_err.is_nan() {
            // Not measured (the C view times the call, its error is the
            // Rust sampler's).
            "—".into()
        } else {
            format!("{:.1e}", e.cdf_err)
        };
        writeln!(
            md,
            "| {} | {} | {:.2} | {} | {} |",
            e.family,
            e.name,
            e.ns,
            // Mie's points are measured by the CDF alone (no exact inverse).
            if e.family == "Mie" {
                "—".into()
            } else {
                fmt_err(e)
            },
            cdf
        )
        .unwrap();
    }
    writeln!(
        md,
        "\n### Cube roots (f32): ns per call, max error in ULP\n"
    )
    .unwrap();
    writeln!(md, "| cube root | ns | max ULP |").unwrap();
    writeln!(md, "|---|---:|---:|").unwrap();
    for e in es.iter().filter(|e| e.family == "cbrt") {
        writeln!(md, "| {} | {:.2} | {:.2} |", e.name, e.ns, e.err).unwrap();
    }
    writeln!(
        md,
        "\n### Batches (f32, 4096 uniforms): ns per element\n\n| sampler | batch | scalar calls | batch speed-up |\n|---|---:|---:|---:|\n\
         | Rayleigh direct (sqrt-free minimax, `rayleigh::inverse_cdf_fill`) | {:.2} | {:.2} | {:.2}× |\n| HG g = 0.7 | {:.2} | {:.2} | {:.2}× |",
        rayleigh_batch.0,
        rayleigh_batch.1,
        rayleigh_batch.1 / rayleigh_batch.0,
        hg_batch.0,
        hg_batch.1,
        hg_batch.1 / hg_batch.0
    )
    .unwrap();
    let full = std::env::var("SK_REPORT").is_ok_and(|v| v == "full");
    let show = |text: &str| {
        if full {
            print!("{text}");
        }
    };
    show(&md);

    let docs = out_dir()?;
    std::fs::write(docs.join("speed_accuracy.csv"), csv(&es))?;
    std::fs::write(docs.join("speed_accuracy.svg"), svg(&es))?;
    let pairs = pairs();
    let c_md = c.as_ref().map_or_else(
        || format!("\n## Through the C ABI\n\nSKIPPED: {C_SKIPPED}.\n"),
        |c| c_tables(c, &pairs),
    );
    show(&c_md);
    let native_md = native.map_or_else(
        || if c.is_none() {
            format!("\n## Through the C ABI, built with `-O3 -march=native`\n\nSKIPPED: {C_SKIPPED}.\n")
        } else {
            "\n## Through the C ABI, built with `-O3 -march=native`\n\nThis compiler rejected `-march=native`.\n".to_string()
        },
        |n| native_tables(&n),
    );
    show(&native_md);
    let media_md = media_report() + &c_media_report();
    show(&media_md);
    let transmittance_md = transmittance_report() + &suite_report();
    show(&transmittance_md);
    let (mie_md, _) = mie_report(&es);
    show(&mie_md);
    let pol_md = polarization_report();
    show(&pol_md);
    let photon_md = photon_report();
    show(&photon_md);
    let perf = performance(&es, rayleigh_batch, hg_batch, &pairs)
        + &c_md
        + &native_md
        + &frontier_peers(&es)
        + &media_md
        + &transmittance_md
        + &mie_md
        + &pol_md
        + &photon_md;
    std::fs::write(docs.join("PERFORMANCE.md"), &perf)?;
    // The summary: every target row of the report, met or missed, counted.
    // A target row's last cell says "met" (perhaps "met, under 10 %
    // margin") or "**missed**".
    let verdict = |l: &str| {
        let cell = l
            .trim_end()
            .trim_end_matches('|')
            .rsplit('|')
            .next()
            .unwrap_or("")
            .trim();
        (cell.starts_with("met"), cell.starts_with("**missed**"))
    };
    let rows: Vec<&str> = perf
        .lines()
        .filter(|l| l.starts_with('|') && (verdict(l).0 || verdict(l).1))
        .collect();
    let missed: Vec<&str> = rows.iter().copied().filter(|l| verdict(l).1).collect();
    println!(
        "{} of {} speed and accuracy targets met on {}.",
        rows.len() - missed.len(),
        rows.len(),
        machine()
    );
    for l in &missed {
        println!(
            "missed: {}",
            l.trim_matches('|').split(" | ").next().unwrap_or(l)
        );
    }
    println!(
        "The full report, PERFORMANCE.md, with speed_accuracy.csv and speed_accuracy.svg: {} ({:.1} s; SK_REPORT=full prints it here).",
        docs.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Where the reports go: `target/speed_accuracy/` (beside the build, so a
/// run leaves the checkout clean), or `docs/measured/`, the copies the
/// README shows, with `SK_REFRESH_DOCS=1`.
fn out_dir() -> std::io::Result<std::path::PathBuf> {
    let dir = if std::env::var_os("SK_REFRESH_DOCS").is_some() {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/measured")
    } else {
        target_dir().join("speed_accuracy")
    };
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}

/// A point of the C view: `err < 0` marks a sampler exact in distribution.
fn c_entry(family: &'static str, name: String, ns: f64, err: f64) -> Entry {
    let mut e = if err < 0.0 {
        Entry::rejection(family, name, ns)
    } else {
        Entry::new(family, name, ns, (err, f64::NAN))
    };
    e.c_abi = true;
    e
}
