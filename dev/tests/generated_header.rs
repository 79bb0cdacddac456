//! `include/scatterkit.h` is generated: this test regenerates it with cbindgen
//! from `src/ffi/` and fails on any difference (`SK_BLESS=1` rewrites it
//! instead). It lives in this package so that cbindgen is a dependency of
//! the development tools alone; `tests/header.rs` of the library checks the
//! header's version macros and that it compiles in every C and C++ standard.

use std::path::{Path, PathBuf};

/// The library's root, beside this package.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The library's `version = "…"` in its Cargo.toml, as (major, minor,
/// patch).
fn library_version() -> [String; 3] {
    let manifest = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
    let line = manifest
        .lines()
        .find_map(|l| l.strip_prefix("version = \""))
        .expect("no version line");
    let v: Vec<String> = line
        .trim_end_matches('"')
        .split('.')
        .map(String::from)
        .collect();
    [v[0].clone(), v[1].clone(), v[2].clone()]
}

fn generate() -> String {
    let root = root();
    let config = cbindgen::Config::from_file(root.join("cbindgen.toml")).unwrap();
    let [major, minor, patch] = library_version();
    let version = format!(
        "\n#define SK_VERSION_MAJOR {major}\n#define SK_VERSION_MINOR {minor}\n#define SK_VERSION_PATCH {patch}\n"
    );
    let mut out = Vec::new();
    cbindgen::Builder::new()
        .with_src(root.join("src/ffi/mod.rs"))
        .with_config(config)
        .with_after_include(version)
        .generate()
        .expect("cbindgen failed")
        .write(&mut out);
    c89(&String::from_utf8(out).unwrap())
}

/// cbindgen's output made valid C89 as well (older C codes build with
/// `-std=c89 -pedantic -Werror`): its `// …` comments after `#endif` and
/// `}` become `/* … */`, and the comma after an enum's last value goes.
fn c89(header: &str) -> String {
    let lines: Vec<&str> = header.lines().collect();
    let mut out = String::with_capacity(header.len());
    for (i, line) in lines.iter().enumerate() {
        let mut line = match line.split_once("  // ").or_else(|| line.split_once(" // ")) {
            Some((code, comment)) if code.starts_with("#endif") || code.starts_with('}') => {
                format!("{code} /* {comment} */")
            }
            _ => line.to_string(),
        };
        let closes = lines
            .get(i + 1)
            .is_some_and(|next| next.trim_start().starts_with('}'));
        if closes && line.ends_with(',') {
            line.pop();
        }
        out += &line;
        out.push('\n');
    }
    out
}

#[test]
fn header_matches_code() {
    let path = root().join("include/scatterkit.h");
    let fresh = generate();
    if std::env::var_os("SK_BLESS").is_some() {
        std::fs::write(&path, &fresh).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == fresh,
        "include/scatterkit.h is out of date: run `SK_BLESS=1 cargo test --release -p scatterkit-dev` \
         and commit the result"
    );
}
