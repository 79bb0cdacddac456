//! `include/scatterkit_table.h`, the header-only table lookups, against the
//! library: `tests/c/table_lookup.c` compiled as C99 and as C++ (`-Wall
//! -Wextra -Werror -pedantic`) compares them bit for bit with
//! `sk_table_sample_cos` over 2²² + 1 values of `u` (plus values outside
//! `[0, 1]`, NaN and the ends) for every table kind, f32 and f64, at four
//! resolutions, and with `sk_table2d_sample_cos` over 2049 × 2049 `(x, u)`
//! (`x` beyond both ends too, plus NaN and infinite `x`) for 2-D tables of
//! both Hermite kinds at three resolutions: over 10⁷ lookups per kind and
//! precision.

use crate::common;

use common::cbuild::{build_program_with, root, run};

fn check(cpp: bool) {
    let src = root().join("tests/c/table_lookup.c");
    let exe = build_program_with(&src, cpp, &[], if cpp { "_cpp" } else { "" });
    let (code, out) = run(&exe);
    println!("{out}");
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("lookups compared, 0 mismatched"), "{out}");
}

#[test]
fn header_lookup_is_bit_identical_as_c() {
    if !crate::common::repository("header_lookup_is_bit_identical_as_c") {
        return;
    }
    check(false);
}

#[test]
fn header_lookup_is_bit_identical_as_cpp() {
    if !crate::common::repository("header_lookup_is_bit_identical_as_cpp") {
        return;
    }
    check(true);
}
