//! The C ABI from C: builds `libscatterkit.a` (the `capi/` crate, release,
//! `panic = "abort"`), compiles the C examples and C tests with the `cc`
//! crate's compiler (`-std=c99 -Wall -Wextra -Werror`, and the header once as
//! C++), links them statically, runs them and checks their output.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The target directory this test was built into (`CARGO_TARGET_TMPDIR` is
/// `<target>/tmp`).
fn target_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// Builds the static library once per test run; returns its path.
fn static_lib() -> &'static Path {
    static LIB: OnceLock<PathBuf> = OnceLock::new();
    LIB.get_or_init(|| {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let status = Command::new(cargo)
            .args(["build", "--release", "-p", "scatterkit-capi"])
            .arg("--target-dir")
            .arg(target_dir())
            .current_dir(root())
            .status()
            .expect("cargo build of the C library failed to start");
        assert!(status.success(), "cargo build -p scatterkit-capi failed");
        target_dir().join("release/libscatterkit.a")
    })
}

/// The host triple, from `rustc -vV` (tests get no TARGET variable).
fn host_triple() -> String {
    let out = Command::new("rustc")
        .arg("-vV")
        .output()
        .expect("rustc -vV");
    let text = String::from_utf8(out.stdout).unwrap();
    text.lines()
        .find_map(|l| l.strip_prefix("host: "))
        .expect("no host line")
        .to_string()
}

/// Compiles and links one C (or C++) source against the static library.
fn build_program(src: &Path, cpp: bool) -> PathBuf {
    let lib = static_lib();
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_programs");
    std::fs::create_dir_all(&out_dir).unwrap();
    let exe = out_dir.join(src.file_stem().unwrap());
    let triple = host_triple();
    let compiler = cc::Build::new()
        .cpp(cpp)
        .target(&triple)
        .host(&triple)
        .opt_level(2)
        .out_dir(&out_dir)
        .cargo_metadata(false)
        .warnings_into_errors(true)
        .get_compiler();
    let mut cmd = compiler.to_command();
    cmd.arg(if cpp { "-std=c++11" } else { "-std=c99" })
        .args(["-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(root().join("include"))
        .arg(src)
        .arg("-o")
        .arg(&exe)
        .arg(lib)
        .args(["-lpthread", "-ldl", "-lm"]);
    let out = cmd.output().expect("C compiler failed to start");
    assert!(
        out.status.success(),
        "compiling {} failed:\n{}",
        src.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    exe
}

/// Runs a built program; returns (exit code, stdout).
fn run(exe: &Path) -> (i32, String) {
    let out = Command::new(exe).output().expect("program failed to start");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

fn run_source(rel: &str, cpp: bool) -> String {
    let exe = build_program(&root().join(rel), cpp);
    let (code, stdout) = run(&exe);
    assert_eq!(code, 0, "{rel} exited with {code}:\n{stdout}");
    stdout
}

#[test]
fn example_rayleigh_histogram() {
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
    let out = run_source("c_examples/fog_histogram.c", false);
    assert!(out.starts_with("fog, 2 um droplets"), "{out}");
    assert_eq!(
        out.lines().filter(|l| l.starts_with('[')).count(),
        18,
        "{out}"
    );
}

#[test]
fn example_surface_shares() {
    let out = run_source("c_examples/surface_shares.c", false);
    assert!(
        out.contains("shares within 4 sigma of the closed forms, deviation within 1%: yes"),
        "{out}"
    );
    assert_eq!(out.matches("incidence").count(), 2, "{out}");
}

#[test]
fn example_fog_slab() {
    let out = run_source("c_examples/fog_slab.c", false);
    assert!(out.contains("absorbing only: transmitted"), "{out}");
    assert!(out.trim_end().ends_with("ok"), "{out}");
}

#[test]
fn bad_input_from_c() {
    let exe = build_program(&root().join("tests/c/bad_input.c"), false);
    let (code, out) = run(&exe);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains(" 0 failed"), "{out}");
}

#[test]
fn header_compiles_and_runs_as_cpp() {
    let out = run_source("tests/c/header.cpp", true);
    assert!(out.starts_with("C++: HG(0.5)"), "{out}");
}
