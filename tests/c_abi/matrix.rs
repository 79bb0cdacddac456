//! The bad-input matrix (`tests/c/matrix.c`) from C, and its coverage: the
//! test fails if a function declared in `include/scatterkit.h` does not
//! appear in the matrix.

use crate::common;

use common::cbuild::{build_program, root, run};

#[test]
fn every_header_function_is_in_the_matrix() {
    let header = std::fs::read_to_string(root().join("include/scatterkit.h")).unwrap();
    let matrix = std::fs::read_to_string(root().join("tests/c/matrix.c")).unwrap();
    let functions: Vec<&str> = header
        .lines()
        .filter(|l| !l.starts_with(' ') && !l.starts_with('#') && l.contains('('))
        .filter_map(|l| {
            l[..l.find('(')?]
                .rsplit(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
        })
        .filter(|n| n.starts_with("sk_"))
        .collect();
    assert!(functions.len() >= 90, "found {} functions", functions.len());
    let missing: Vec<_> = functions
        .iter()
        .filter(|f| !matrix.contains(&format!("{f}(")))
        .collect();
    assert!(
        missing.is_empty(),
        "header functions missing from tests/c/matrix.c: {missing:?}"
    );
}

#[test]
fn the_matrix_passes() {
    if !crate::common::repository("the_matrix_passes") {
        return;
    }
    let exe = build_program(&root().join("tests/c/matrix.c"), false);
    let (code, out) = run(&exe);
    assert!(code == 0 && out.contains(" 0 failed"), "{out}");
}
