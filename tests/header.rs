//! `include/scatterkit.h` is generated: this test regenerates it with cbindgen
//! and fails on any difference (`SK_BLESS=1` rewrites it instead), then checks
//! that the version macros and `sk_version()` agree with Cargo.toml.

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
    String::from_utf8(out).unwrap()
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
