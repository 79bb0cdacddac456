//! Building and running C programs against the C library: the static
//! library from the `capi/` crate (release, `panic = "abort"`), compiled
//! with the `cc` crate's compiler, `-std=c99 -Wall -Wextra -Werror -pedantic`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The target directory this test was built into (`CARGO_TARGET_TMPDIR` is
/// `<target>/tmp`).
pub fn target_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// Builds the static library once per test run; returns its path.
pub fn static_lib() -> &'static Path {
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
pub fn host_triple() -> String {
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
pub fn build_program(src: &Path, cpp: bool) -> PathBuf {
    build_program_with(src, cpp, &[], "")
}

/// [`build_program`] with extra compiler flags (sanitizers, say), writing
/// the executable with `suffix` appended to its name.
pub fn build_program_with(src: &Path, cpp: bool, extra: &[&str], suffix: &str) -> PathBuf {
    let lib = static_lib();
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("c_programs");
    std::fs::create_dir_all(&out_dir).unwrap();
    // A name of its own per build: tests of one binary run on parallel
    // threads, and two may build the same source.
    static BUILDS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let exe = out_dir.join(format!(
        "{}{suffix}-{}-{n}",
        src.file_stem().unwrap().to_string_lossy(),
        std::process::id()
    ));
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
        .args(extra)
        .arg("-I")
        .arg(root().join("include"))
        .arg(src)
        .arg("-o")
        .arg(&exe)
        // -lm first, as the README's line: the C library's math, not the
        // copies Rust's compiler-builtins puts in the archive.
        .arg("-lm")
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
pub fn run(exe: &Path) -> (i32, String) {
    let out = Command::new(exe).output().expect("program failed to start");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

pub fn run_source(rel: &str, cpp: bool) -> String {
    let exe = build_program(&root().join(rel), cpp);
    let (code, stdout) = run(&exe);
    assert_eq!(code, 0, "{rel} exited with {code}:\n{stdout}");
    stdout
}
