//! The install path for C users: `scripts/install.sh` (what `cargo cinstall`
//! does, without cargo-c) into temporary prefixes, then a C example built
//! with `pkg-config --cflags --libs scatterkit`, against the shared library
//! and (with `--static`) the static one, and run; and the header-only
//! tier, `c_examples/portable_slab.c`, built with `pkg-config --cflags
//! scatterkit-portable` alone (every header is installed).

mod common;

use std::path::Path;
use std::process::Command;

fn sh(cmd: &mut Command) -> String {
    let out = cmd.output().expect("command failed to start");
    assert!(
        out.status.success(),
        "{cmd:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn install_and_build(mode: &str, pc_static: bool) -> (String, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("install{mode}"));
    let _ = std::fs::remove_dir_all(&tmp);
    let target = tmp.parent().unwrap().parent().unwrap();
    sh(Command::new("sh")
        .arg(root.join("scripts/install.sh"))
        .arg(&tmp)
        .arg(mode)
        .env("CARGO_TARGET_DIR", target));
    let pc = tmp.join("lib/pkgconfig");
    let mut args = vec!["--cflags", "--libs", "scatterkit"];
    if pc_static {
        args.insert(0, "--static");
    }
    let flags = sh(Command::new("pkg-config")
        .args(&args)
        .env("PKG_CONFIG_PATH", &pc));
    let exe = tmp.join("hg_stratified");
    let mut cc = Command::new("cc");
    cc.args(["-std=c99", "-Wall", "-Wextra", "-Werror"])
        .arg(root.join("c_examples/hg_stratified.c"))
        .arg("-o")
        .arg(&exe);
    cc.args(flags.split_whitespace());
    sh(&mut cc);
    let run = sh(Command::new(&exe).env("LD_LIBRARY_PATH", tmp.join("lib")));
    let ldd = sh(Command::new("ldd").arg(&exe));
    // Every header is installed, and the portable one builds a program
    // with no library.
    for h in [
        "scatterkit.h",
        "scatterkit_inline.h",
        "scatterkit_table.h",
        "scatterkit_portable.h",
    ] {
        assert!(tmp.join("include").join(h).exists(), "{h} not installed");
    }
    let flags = sh(Command::new("pkg-config")
        .args(["--cflags", "scatterkit-portable"])
        .env("PKG_CONFIG_PATH", &pc));
    let slab = tmp.join("portable_slab");
    let mut cc = Command::new("cc");
    cc.args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
        .arg(root.join("c_examples/portable_slab.c"))
        .args(flags.split_whitespace())
        .arg("-o")
        .arg(&slab)
        .arg("-lm");
    sh(&mut cc);
    let slab_out = sh(&mut Command::new(&slab));
    assert!(slab_out.contains("R + T = 1.0000"), "{slab_out}");
    (run, ldd)
}

#[test]
fn shared_library_through_pkg_config() {
    if !crate::common::repository("shared_library_through_pkg_config") {
        return;
    }
    let (run, ldd) = install_and_build("--shared-only", false);
    assert!(run.contains("sorted: yes"), "{run}");
    // The program records the SONAME (as cargo-c installs it), and the
    // install holds the versioned file it names.
    assert!(
        ldd.contains("libscatterkit.so.0.2"),
        "not linked to the shared library by its SONAME:\n{ldd}"
    );
}

#[test]
fn static_library_through_pkg_config() {
    if !crate::common::repository("static_library_through_pkg_config") {
        return;
    }
    let (run, ldd) = install_and_build("--static-only", true);
    assert!(run.contains("sorted: yes"), "{run}");
    assert!(
        !ldd.contains("libscatterkit"),
        "linked to a shared scatterkit:\n{ldd}"
    );
}
