//! The C ABI from C: builds `libscatterkit.a` (the `capi/` crate, release,
//! `panic = "abort"`), compiles the C examples and C tests with the `cc`
//! crate's compiler (`-std=c99 -Wall -Wextra -Werror`, and the header once as
//! C++), links them statically, runs them and checks their output.

use crate::common;

use common::cbuild::{root, run, run_source};

#[test]
fn example_rayleigh_histogram() {
    if !crate::common::repository("example_rayleigh_histogram") {
        return;
    }
    let out = run_source("c_examples/rayleigh_histogram.c", false);
    assert!(out.contains("SK_RAYLEIGH_DIRECT"), "{out}");
    assert_eq!(
        out.lines().filter(|l| l.starts_with('[')).count(),
        10,
        "{out}"
    );
    // The chi² line is printed and, by the exit code, below its critical value.
    assert!(out.contains("chi2 = "), "{out}");
}

#[test]
fn example_hg_stratified() {
    if !crate::common::repository("example_hg_stratified") {
        return;
    }
    let out = run_source("c_examples/hg_stratified.c", false);
    assert!(out.contains("sorted: yes"), "{out}");
    let err: f64 = out
        .split("error ")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .and_then(|s| s.parse().ok())
        .expect("no error figure");
    assert!(err < 1e-4, "{out}");
}

#[test]
fn example_fog_histogram() {
    if !crate::common::repository("example_fog_histogram") {
        return;
    }
    let out = run_source("c_examples/fog_histogram.c", false);
    assert!(out.starts_with("fog, 2 um droplets"), "{out}");
    assert_eq!(
        out.lines().filter(|l| l.starts_with('[')).count(),
        18,
        "{out}"
    );
}

#[test]
fn example_mie_cloud() {
    if !crate::common::repository("example_mie_cloud") {
        return;
    }
    // The example exits non-zero (and run_source fails) on chi² ≥ 42.31.
    let out = run_source("c_examples/mie_cloud.c", false);
    assert!(out.starts_with("Mie, 10 um water droplet"), "{out}");
    assert!(out.contains(": consistent"), "{out}");
    assert_eq!(
        out.lines().filter(|l| l.starts_with('[')).count(),
        19,
        "{out}"
    );
}

#[test]
fn example_rayleigh_sky() {
    if !crate::common::repository("example_rayleigh_sky") {
        return;
    }
    // The example exits non-zero (and run_source fails) when a value is more
    // than 5 standard errors from Natraj, Li & Yung's table.
    let out = run_source("c_examples/rayleigh_sky.c", false);
    assert!(out.starts_with("tau 0.5, black ground"), "{out}");
    assert_eq!(
        out.lines().filter(|l| l.contains("max |z|")).count(),
        4,
        "{out}"
    );
}

#[test]
fn example_surface_shares() {
    if !crate::common::repository("example_surface_shares") {
        return;
    }
    let out = run_source("c_examples/surface_shares.c", false);
    assert!(
        out.contains("shares within 4 sigma of the closed forms, deviation within 1%: yes"),
        "{out}"
    );
    assert_eq!(out.matches("incidence").count(), 2, "{out}");
}

#[test]
fn example_fog_slab() {
    if !crate::common::repository("example_fog_slab") {
        return;
    }
    let out = run_source("c_examples/fog_slab.c", false);
    assert!(out.contains("absorbing only: transmitted"), "{out}");
    assert!(out.trim_end().ends_with("ok"), "{out}");
}

#[test]
fn example_cloud_majorants() {
    if !crate::common::repository("example_cloud_majorants") {
        return;
    }
    let out = run_source("c_examples/cloud_majorants.c", false);
    assert!(out.contains("fewer density evaluations"), "{out}");
    assert!(out.trim_end().ends_with("ok"), "{out}");
}

#[test]
fn bad_input_from_c() {
    if !crate::common::repository("bad_input_from_c") {
        return;
    }
    let exe = common::cbuild::build_program(&root().join("tests/c/bad_input.c"), false);
    let (code, out) = run(&exe);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains(" 0 failed"), "{out}");
}

/// The edge sweep (`tests/c/edges.c`): valid calls at the edges of every
/// documented domain (tracking in float and double, surfaces, equiangular
/// and homogeneous spectral sampling, polarised Rayleigh, Mie, and the
/// portable header's majorant walk), each answer inside its range or a
/// documented status, never NaN with SK_OK.
#[test]
fn edge_sweep_from_c() {
    if !crate::common::repository("edge_sweep_from_c") {
        return;
    }
    let exe = common::cbuild::build_program(&root().join("tests/c/edges.c"), false);
    let (code, out) = run(&exe);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains(" 0 failed"), "{out}");
}

/// The one-call-per-flight slab benchmark (`benches/c_flight.c`) builds
/// strictly and runs every mode on 20 000 photons: the reflected and
/// transmitted weights of each mode match the slab's adding-doubling
/// values within 5 standard errors (τ = 2, ω = 0.9, g = 0.75, matched
/// boundaries, normal incidence: R 0.097395, T 0.660958 with the
/// unscattered e⁻², iadpython 0.5.3 `Sample(a=0.9, b=2, g=0.75, d=1,
/// n=1, quad_pts=24).rt()`, converged to 10⁻⁶ from 16 to 28 points).
#[test]
fn the_flight_benchmark_runs() {
    if !crate::common::repository("the_flight_benchmark_runs") {
        return;
    }
    let exe = common::cbuild::build_program_with(
        &root().join("benches/c_flight.c"),
        false,
        &["-D_POSIX_C_SOURCE=199309L"],
        "",
    );
    let out = std::process::Command::new(&exe)
        .args(["all", "20000"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    let rows: Vec<(String, f64, f64)> = text
        .lines()
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            (
                f[0].to_string(),
                f[3].parse().unwrap(),
                f[4].parse().unwrap(),
            )
        })
        .collect();
    assert_eq!(rows.len(), 7, "{text}");
    // Binomial-like standard errors of a weight fraction over 20 000
    // photons, generous: sqrt(p (1 - p) / n).
    let se = |p: f64| (p * (1.0 - p) / 20_000.0).sqrt();
    for (mode, r, t) in &rows {
        assert!(
            (r - 0.097395).abs() < 5.0 * se(0.097395),
            "{mode}: R {r}\n{text}"
        );
        assert!(
            (t - 0.660958).abs() < 5.0 * se(0.660958),
            "{mode}: T {t}\n{text}"
        );
    }
}

/// The whole photon loop of the main job (`benches/c_photon.c`) builds
/// strictly and runs: on 20 000 photons every mode (library and inline,
/// three media, the homogeneous medium through delta tracking, and the
/// inline loop calling the callback medium through its pointer)
/// reflects and transmits within 5 of its standard errors of
/// the adding-doubling values above.
#[test]
fn the_photon_loop_agrees_with_adding_doubling() {
    if !crate::common::repository("the_photon_loop_agrees_with_adding_doubling") {
        return;
    }
    let exe = common::cbuild::build_program_with(
        &root().join("benches/c_photon.c"),
        false,
        &["-D_POSIX_C_SOURCE=199309L"],
        "",
    );
    let out = std::process::Command::new(&exe)
        .arg("20000")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    let mut checked = 0;
    for l in text.lines() {
        let f: Vec<&str> = l.split('\t').collect();
        let want = if f[0].ends_with(".R") {
            0.097395
        } else if f[0].ends_with(".T") {
            0.660958
        } else {
            continue;
        };
        let (v, se): (f64, f64) = (f[1].parse().unwrap(), f[2].parse().unwrap());
        assert!((v - want).abs() <= 5.0 * se, "{l}\n{text}");
        checked += 1;
    }
    assert_eq!(checked, 16, "{text}");
}

/// `|g| = 1` through the C ABI and the portable header alike
/// (`tests/c/dirac.c`).
#[test]
fn the_dirac_limit_from_c_and_the_header() {
    if !crate::common::repository("the_dirac_limit_from_c_and_the_header") {
        return;
    }
    let exe = common::cbuild::build_program(&root().join("tests/c/dirac.c"), false);
    let (code, out) = run(&exe);
    println!("{out}");
    assert!(code == 0 && out.contains(" 0 failed"), "{out}");
}

#[test]
fn direction_batches_agree_with_scalar_calls() {
    if !crate::common::repository("direction_batches_agree_with_scalar_calls") {
        return;
    }
    let exe = common::cbuild::build_program(&root().join("tests/c/batch.c"), false);
    let (code, out) = run(&exe);
    assert!(code == 0 && out.contains(" 0 failed"), "{out}");
}

#[test]
fn header_compiles_and_runs_as_cpp() {
    if !crate::common::repository("header_compiles_and_runs_as_cpp") {
        return;
    }
    let out = run_source("tests/c/header.cpp", true);
    assert!(out.starts_with("C++: HG(0.5)"), "{out}");
    // And under the later standards, with the same warnings as errors.
    for std in ["c++17", "c++20"] {
        let src = root().join("tests/c/header.cpp");
        let exe = common::cbuild::build_program_with(&src, true, &[&format!("-std={std}")], std);
        let (code, out) = run(&exe);
        assert!(code == 0 && out.starts_with("C++: HG(0.5)"), "{std}: {out}");
    }
}

/// `include/scatterkit_inline.h` gives `sk_phase_sample_cos`'s bits: every
/// float in `[0, 1]` for one HG phase at `-O2` (C99), every 5th at `-O3
/// -march=native` (where FMA contraction could creep in) and every 7th as
/// C89; both signs of g, a g below the inline path, other models.
#[test]
fn inline_cos_sampler_agrees_bit_for_bit() {
    if !crate::common::repository("inline_cos_sampler_agrees_bit_for_bit") {
        return;
    }
    let src = root().join("tests/c/inline.c");
    for (flags, suffix) in [
        (vec![], ""),
        (vec!["-O3", "-march=native", "-DSK_STRIDE=5"], "_native"),
        (vec!["-std=c89", "-DSK_STRIDE=7"], "_c89"),
    ] {
        let exe = common::cbuild::build_program_with(&src, false, &flags, suffix);
        let (code, out) = run(&exe);
        assert!(
            code == 0 && out.contains(" 0 differ (exact path 1)"),
            "{flags:?}: {out}"
        );
    }
}

#[test]
fn example_portable_slab() {
    if !crate::common::repository("example_portable_slab") {
        return;
    }
    let out = run_source("c_examples/portable_slab.c", false);
    assert!(out.contains("R + T = 1.0000"), "{out}");
    assert!(out.contains("mean cosine of "), "{out}");
}
