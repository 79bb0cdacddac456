//! `include/scatterkit.h` is generated: this test regenerates it with cbindgen
//! and fails on any difference (`SK_BLESS=1` rewrites it instead), then checks
//! that the version macros and `sk_version()` agree with Cargo.toml.

mod common;

use std::path::Path;

fn generate() -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let config = cbindgen::Config::from_file(Path::new(root).join("cbindgen.toml")).unwrap();
    let version = format!(
        "\n#define SK_VERSION_MAJOR {}\n#define SK_VERSION_MINOR {}\n#define SK_VERSION_PATCH {}\n",
        env!("CARGO_PKG_VERSION_MAJOR"),
        env!("CARGO_PKG_VERSION_MINOR"),
        env!("CARGO_PKG_VERSION_PATCH"),
    );
    let mut out = Vec::new();
    cbindgen::Builder::new()
        .with_src(Path::new(root).join("src/ffi/mod.rs"))
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
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("include/scatterkit.h");
    let fresh = generate();
    if std::env::var_os("SK_BLESS").is_some() {
        std::fs::write(&path, &fresh).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == fresh,
        "include/scatterkit.h is out of date: run `SK_BLESS=1 cargo test --release --test header` \
         and commit the result"
    );
}

#[test]
fn version_macros_agree_with_cargo_toml() {
    let header =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("include/scatterkit.h"))
            .unwrap();
    for (name, value) in [
        ("MAJOR", env!("CARGO_PKG_VERSION_MAJOR")),
        ("MINOR", env!("CARGO_PKG_VERSION_MINOR")),
        ("PATCH", env!("CARGO_PKG_VERSION_PATCH")),
    ] {
        let line = format!("#define SK_VERSION_{name} {value}\n");
        assert!(header.contains(&line), "header lacks `{}`", line.trim());
    }
}

/// The headers (the generated one, and the inline sampler's beside it)
/// compile as C89 (older C codes build with
/// `-std=c89 -pedantic`), C99, C11 and C++11/17/20, every warning an error.
#[test]
fn header_compiles_in_every_standard() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("header_standards");
    std::fs::create_dir_all(&dir).unwrap();
    // scatterkit_inline.h includes scatterkit.h: both headers, unused
    // inline function and all.
    let source = "#include \"scatterkit_inline.h\"\nint main(void) { return sk_version() == 0; }\n";
    let triple = common::cbuild::host_triple();
    for (std, cpp) in [
        ("c89", false),
        ("gnu89", false),
        ("c99", false),
        ("c11", false),
        ("c++11", true),
        ("c++17", true),
        ("c++20", true),
    ] {
        let src = dir.join(if cpp { "h.cpp" } else { "h.c" });
        std::fs::write(&src, source).unwrap();
        let compiler = cc::Build::new()
            .cpp(cpp)
            .target(&triple)
            .host(&triple)
            .opt_level(0)
            .cargo_metadata(false)
            .get_compiler();
        let out = compiler
            .to_command()
            .arg(format!("-std={std}"))
            .args([
                "-pedantic",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-fsyntax-only",
                "-I",
            ])
            .arg(root.join("include"))
            .arg(&src)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "the header as {std}:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
