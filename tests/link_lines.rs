//! Every `cc` line of the README, exactly as written there (read from the
//! file, so the README cannot drift from what works): the in-tree static
//! and shared lines in a directory laid out like the repository (the
//! shared one finds `libscatterkit.so.0.2`, its SONAME, in the build tree:
//! `capi/build.rs` puts the link there), and the pkg-config
//! lines after the README's `scripts/install.sh` line (its own options, into
//! a temporary prefix instead of its own). Each builds the README's C quick
//! start as `app.c`, and the program runs (the shared one without
//! `LD_LIBRARY_PATH`: the line records the library's directory). Each line
//! also builds a program calling C math functions, which must get the C
//! library's and not the copies Rust puts in the static archive. The CMake
//! route is built too (where `cmake` is installed; `.ci/run` installs it).

mod common;

use common::cbuild::{root, static_lib};
use common::readme;
use std::path::{Path, PathBuf};
use std::process::Command;

fn sh(dir: &Path, line: &str, env: &[(&str, &Path)]) -> String {
    let mut cmd = Command::new("sh");
    cmd.arg("-c").arg(line).current_dir(dir);
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "`{line}` failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The README's C quick start, the program every line builds.
fn quick_start() -> String {
    readme::blocks("c")
        .into_iter()
        .next()
        .expect("the README's C quick start")
}

/// What the quick start prints when it works.
const QUICK_START_SAYS: &str = "mean cos theta 0.700";

/// A fresh directory holding `app.c`.
fn workdir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("link_lines")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("app.c"), quick_start()).unwrap();
    dir
}

/// The options of the README's install line, `scripts/install.sh PREFIX
/// [options]` (its comment left off).
fn readme_install_options() -> Vec<String> {
    let lines = readme::sh_lines("scripts/install.sh ");
    let line = lines.first().expect("the README's install line");
    let code = line.split('#').next().unwrap();
    code.split_whitespace()
        .skip(2)
        .map(str::to_string)
        .collect()
}

/// Runs `scripts/install.sh` into `prefix` with the README's options
/// (`mode` replaces them where given).
fn install(prefix: &Path, mode: Option<&str>) {
    let _ = std::fs::remove_dir_all(prefix);
    let target = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .unwrap()
        .to_path_buf();
    let options: Vec<String> = match mode {
        Some(m) => vec![m.to_string()],
        None => readme_install_options(),
    };
    let out = Command::new("sh")
        .arg(root().join("scripts/install.sh"))
        .arg(prefix)
        .args(&options)
        .env("CARGO_TARGET_DIR", target)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "install: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A program calling C math functions that Rust's compiler-builtins also
/// defines, weak and hidden, in every static library it builds.
const MATH_PROBE: &str = r#"#include <math.h>
#include <stdio.h>
#include "scatterkit.h"

int main(int argc, char **argv) {
    volatile double x = argc + 0.5;
    sk_phase hg;
    (void)argv;
    if (sk_phase_new_hg(0.5f, &hg) != SK_OK) return 1;
    printf("%g %g %g %g\n", cbrt(x), fma(x, x, x), fmax(x, 2.0), floor(x));
    return 0;
}
"#;

/// Builds [`MATH_PROBE`] with the README's `line` (in place of `app.c`,
/// `-lm` added at the end) and checks that the program gets the C
/// library's math functions, not copies from the archive
/// (rust-lang/rust#142119: a linker that meets the archive before `-lm`
/// takes them from it): none of them is defined in the program, and
/// `cbrt`, which no compiler inlines, is left to the C library (so the
/// check cannot pass by the calls having gone).
fn assert_math_is_the_c_librarys(dir: &Path, line: &str, env: &[(&str, &Path)]) {
    std::fs::write(dir.join("probe.c"), MATH_PROBE).unwrap();
    // As a program using math links: `-lm` at the end of its line.
    let probe_line = format!("{} -lm", line.replace("app.c", "probe.c"));
    sh(dir, &probe_line, env);
    let exe = dir.join("a.out");
    let nm = Command::new("nm").arg(&exe).output().unwrap();
    let symbols = String::from_utf8_lossy(&nm.stdout);
    let kind = |name: &str| {
        symbols.lines().find_map(|l| {
            // `[address] kind name`: the last two fields.
            let f: Vec<&str> = l.split_whitespace().collect();
            let [.., k, n] = f.as_slice() else {
                return None;
            };
            (*n == name || n.starts_with(&format!("{name}@"))).then(|| k.to_string())
        })
    };
    for name in ["cbrt", "fma", "fmax", "floor"] {
        let k = kind(name);
        assert!(
            k.as_deref().is_none_or(|k| k == "U"),
            "`{probe_line}`: the program's {name} is a copy from the archive ({k:?}), \
             not the C library's"
        );
    }
    assert_eq!(
        kind("cbrt").as_deref(),
        Some("U"),
        "`{probe_line}`: cbrt is not left to the C library:\n{symbols}"
    );
    let run = Command::new(&exe).current_dir(dir).output().unwrap();
    assert!(run.status.success(), "`{probe_line}`: the probe failed");
}

#[test]
fn every_readme_link_line_builds_and_runs() {
    if !crate::common::repository("every_readme_link_line_builds_and_runs") {
        return;
    }
    let lines = readme::sh_lines("cc ");
    assert!(
        lines.len() >= 4,
        "the README lost its link lines: {lines:?}"
    );
    let lib = static_lib();
    for (k, line) in lines.iter().enumerate() {
        let dir = workdir(&format!("line{k}"));
        let mut env: Vec<(&str, PathBuf)> = Vec::new();
        if line.contains("target/release") {
            // The repository's layout: include/ and target/release/.
            std::os::unix::fs::symlink(root().join("include"), dir.join("include")).unwrap();
            std::fs::create_dir_all(dir.join("target")).unwrap();
            std::os::unix::fs::symlink(lib.parent().unwrap(), dir.join("target/release")).unwrap();
        } else if line.contains("pkg-config") {
            // As the README says: one install (its own options), then
            // either line.
            let prefix = dir.join("prefix");
            install(&prefix, None);
            env.push(("PKG_CONFIG_PATH", prefix.join("lib/pkgconfig")));
        } else {
            panic!("a README cc line this test does not know how to run: {line}");
        }
        let env_ref: Vec<(&str, &Path)> = env.iter().map(|(k, v)| (*k, v.as_path())).collect();
        sh(&dir, line, &env_ref);
        let exe = dir.join("a.out");
        let size = std::fs::metadata(&exe).unwrap().len();
        let run = Command::new(&exe).current_dir(&dir).output().unwrap();
        let out = String::from_utf8_lossy(&run.stdout);
        println!("`{line}`: {size} bytes, runs: {}", run.status.success());
        assert!(
            run.status.success() && out.contains(QUICK_START_SAYS),
            "`{line}`: {out}"
        );
        if line.contains("--gc-sections") {
            // The code the program keeps (`size`'s text column), not the
            // file, which also holds debug information.
            let out = Command::new("size").arg(&exe).output().unwrap();
            let table = String::from_utf8_lossy(&out.stdout);
            let text: u64 = table
                .lines()
                .nth(1)
                .and_then(|l| l.split_whitespace().next())
                .and_then(|t| t.parse().ok())
                .unwrap_or(u64::MAX);
            println!("  .text {text} bytes");
            assert!(text < 200_000, "`{line}` kept {text} bytes of code");
        }
        // Last: it builds its own a.out in the same directory.
        assert_math_is_the_c_librarys(&dir, line, &env_ref);
    }
}

#[test]
fn cmake_package_builds_an_app_where_cmake_is_installed() {
    if !crate::common::repository("cmake_package_builds_an_app_where_cmake_is_installed") {
        return;
    }
    if Command::new("cmake").arg("--version").output().is_err() {
        common::skip("link_lines: cmake is not installed, the CMake route is not built");
        return;
    }
    let block = readme::blocks("cmake")
        .into_iter()
        .next()
        .expect("the README's cmake block");
    let dir = workdir("cmake");
    let prefix = dir.join("prefix");
    install(&prefix, None);
    // The README's block, and the header-only target beside it.
    std::fs::copy(
        root().join("c_examples/portable_slab.c"),
        dir.join("slab.c"),
    )
    .unwrap();
    let cmakelists = format!(
        "cmake_minimum_required(VERSION 3.10)\nproject(app C)\nadd_executable(app app.c)\n{block}\n\
         add_executable(slab slab.c)\n\
         target_link_libraries(slab PRIVATE scatterkit::portable m)\n"
    );
    std::fs::write(dir.join("CMakeLists.txt"), cmakelists).unwrap();
    let build = dir.join("build");
    let ok = Command::new("cmake")
        .arg("-S")
        .arg(&dir)
        .arg("-B")
        .arg(&build)
        .arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()))
        .status()
        .unwrap()
        .success()
        && Command::new("cmake")
            .arg("--build")
            .arg(&build)
            .status()
            .unwrap()
            .success();
    assert!(ok, "the CMake route failed");
    let run = Command::new(build.join("app"))
        .env("LD_LIBRARY_PATH", prefix.join("lib"))
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&run.stdout).contains(QUICK_START_SAYS));
    let slab = Command::new(build.join("slab")).output().unwrap();
    let text = String::from_utf8_lossy(&slab.stdout);
    assert!(
        slab.status.success() && text.contains("R + T = 1.0000"),
        "{text}"
    );
}
