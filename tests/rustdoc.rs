//! The docs render as written: in every doc comment of `src/`, a line that
//! continues a paragraph must not begin with what Markdown reads as a list
//! item (`+ `, `- `, `* `, `1. `) while a code span is open, since the item
//! would cut the span in two (docs.rs showed the Mie module's recurrence
//! as a stray nested list). Rustdoc's own lints (broken links, bad HTML,
//! bare URLs) run in CI as `RUSTDOCFLAGS="-D warnings" cargo doc`.

use std::path::{Path, PathBuf};

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The text of a doc-comment line, or `None` for any other line.
fn doc_text(line: &str) -> Option<&str> {
    let t = line.trim_start();
    t.strip_prefix("//!")
        .or_else(|| t.strip_prefix("///"))
        .map(|s| s.strip_prefix(' ').unwrap_or(s))
}

fn starts_a_list_item(text: &str) -> bool {
    let t = text.trim_start();
    let bullet = ["+ ", "- ", "* "].iter().any(|m| t.starts_with(m));
    let digits = t.chars().take_while(|c| c.is_ascii_digit()).count();
    let ordered = digits > 0 && t[digits..].starts_with(". ");
    bullet || ordered
}

#[test]
fn no_code_span_is_cut_by_a_list_item() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    sources(&root.join("src"), &mut files);
    let mut bad = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        // Backticks so far in the current paragraph (odd: a span is open),
        // and whether a fenced code block is open.
        let (mut ticks, mut fenced) = (0usize, false);
        for (n, line) in text.lines().enumerate() {
            let Some(doc) = doc_text(line) else {
                ticks = 0;
                continue;
            };
            if doc.trim_start().starts_with("```") {
                fenced = !fenced;
                ticks = 0;
                continue;
            }
            if fenced {
                continue;
            }
            if doc.trim().is_empty() {
                ticks = 0;
                continue;
            }
            if ticks % 2 == 1 && starts_a_list_item(doc) {
                bad.push(format!("{}:{}: {doc}", file.display(), n + 1));
            }
            ticks += doc.matches('`').count();
        }
    }
    assert!(
        bad.is_empty(),
        "code spans cut by list items:\n{}",
        bad.join("\n")
    );
}
