//! The README as the tests read it: its text and its code blocks, so that
//! what a user copies is what the tests build and run.

use super::cbuild::root;

/// README.md.
pub fn text() -> String {
    std::fs::read_to_string(root().join("README.md")).unwrap()
}

/// The contents of the README's code blocks fenced as `lang`, in order.
pub fn blocks(lang: &str) -> Vec<String> {
    let fence = format!("```{lang}\n");
    text()
        .split(&fence)
        .skip(1)
        .filter_map(|b| b.split("```").next())
        .map(str::to_string)
        .collect()
}

/// The lines of the README's `sh` blocks that start with `prefix`.
pub fn sh_lines(prefix: &str) -> Vec<String> {
    blocks("sh")
        .iter()
        .flat_map(|b| b.lines())
        .filter(|l| l.starts_with(prefix))
        .map(str::to_string)
        .collect()
}
