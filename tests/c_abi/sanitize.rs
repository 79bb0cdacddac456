//! Every C example and C test program under AddressSanitizer and
//! UndefinedBehaviorSanitizer (gcc, errors fatal, leaks checked), and under
//! valgrind's memcheck (`--error-exitcode=1`, leaks are errors).

use crate::common;

use common::cbuild::{build_program, build_program_with, root};
use std::process::Command;

/// The longest under valgrind first, so that the parallel runs end together.
const PROGRAMS: [&str; 14] = [
    "tests/c/matrix.c",
    "c_examples/cloud_majorants.c",
    "c_examples/surface_shares.c",
    "c_examples/rayleigh_histogram.c",
    "c_examples/hg_stratified.c",
    "c_examples/fog_histogram.c",
    "c_examples/fog_slab.c",
    "c_examples/mie_cloud.c",
    "c_examples/rayleigh_sky.c",
    "tests/c/bad_input.c",
    "tests/c/edges.c",
    "tests/c/dirac.c",
    "tests/c/golden.c",
    "tests/c/batch.c",
];

#[test]
fn programs_are_clean_under_asan_and_ubsan() {
    if !crate::common::repository("programs_are_clean_under_asan_and_ubsan") {
        return;
    }
    let flags = [
        "-fsanitize=address,undefined",
        "-fno-sanitize-recover=undefined",
        "-fno-omit-frame-pointer",
        "-g",
    ];
    // Two or more programs at a time: the machine's cores are otherwise idle.
    common::for_each_parallel(&PROGRAMS, |src| {
        let exe = build_program_with(&root().join(src), false, &flags, "_asan");
        let out = Command::new(&exe)
            .env(
                "ASAN_OPTIONS",
                "detect_leaks=1:abort_on_error=0:halt_on_error=1",
            )
            .env("UBSAN_OPTIONS", "print_stacktrace=1:halt_on_error=1")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success(),
            "{src} under ASan/UBSan: {:?}\n{stderr}",
            out.status
        );
        assert!(
            !stderr.contains("runtime error") && !stderr.contains("Sanitizer"),
            "{src}: {stderr}"
        );
    });
}

#[test]
fn programs_are_clean_under_valgrind() {
    if !crate::common::repository("programs_are_clean_under_valgrind") {
        return;
    }
    let have = Command::new("valgrind")
        .arg("--version")
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    assert!(
        have,
        "valgrind is not installed: every machine of this project has it"
    );
    common::for_each_parallel(&PROGRAMS, |src| {
        let exe = build_program(&root().join(src), false);
        let out = Command::new("valgrind")
            .args([
                "--quiet",
                "--error-exitcode=1",
                "--leak-check=full",
                "--errors-for-leak-kinds=definite,indirect",
            ])
            .arg(&exe)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{src} under valgrind: {:?}\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    });
}
