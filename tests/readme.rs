//! The README is for users, and everything in it that a user copies works:
//! it stays short, names no issue or plan, its Rust quick start is
//! `examples/quick_start.rs` word for word (built by `cargo test`), and its C
//! quick start is a complete program that builds and runs as C89, C99, C11,
//! C++11, C++17 and C++20 with `-pedantic -Wall -Wextra -Werror`. (Its `cc`,
//! install and CMake lines are run by `tests/link_lines.rs`.)

mod common;

use common::cbuild::{build_program_with, root, run};
use common::readme::{blocks, text};

#[test]
fn readme_is_short_and_for_users() {
    let text = text();
    let lines = text.lines().count();
    assert!(lines <= 230, "README.md has {lines} lines (at most 230)");
    let lower = text.to_lowercase();
    // Whole words only ("tissue" is not "issue").
    let says = |word: &str| {
        lower.match_indices(word).any(|(i, _)| {
            let before = lower[..i].chars().next_back();
            !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
        })
    };
    for word in ["issue", "soon", "todo", "../shared", "spec.md", "api.md"] {
        assert!(!says(word), "README.md says \"{word}\"");
    }
}

#[test]
fn rust_quick_start_is_the_example() {
    let block = blocks("rust");
    let example = std::fs::read_to_string(root().join("examples/quick_start.rs")).unwrap();
    assert_eq!(
        block.len(),
        1,
        "the README should hold one Rust block, the quick start"
    );
    assert!(
        block[0] == example,
        "the README's Rust quick start differs from examples/quick_start.rs"
    );
}

#[test]
fn c_quick_start_builds_and_runs_in_every_standard() {
    if !crate::common::repository("c_quick_start_builds_and_runs_in_every_standard") {
        return;
    }
    let block = blocks("c");
    assert_eq!(block.len(), 1, "the README should hold one C block");
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("readme");
    std::fs::create_dir_all(&dir).unwrap();
    for (std, cpp) in [
        ("c89", false),
        ("c99", false),
        ("c11", false),
        ("c++11", true),
        ("c++17", true),
        ("c++20", true),
    ] {
        let src = dir.join(if cpp {
            "quick_start.cpp"
        } else {
            "quick_start.c"
        });
        std::fs::write(&src, &block[0]).unwrap();
        let exe = build_program_with(&src, cpp, &[&format!("-std={std}")], &format!("_{std}"));
        let (code, out) = run(&exe);
        assert!(
            code == 0 && out.contains("mean cos theta 0.700"),
            "{std}: exit {code}: {out}"
        );
    }
}
