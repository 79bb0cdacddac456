//! Gives the shared library a SONAME on Linux (`libscatterkit.so.0.2`: major
//! and minor while the major is 0, as cargo-c names it), so programs record
//! the ABI they were linked against rather than a bare `libscatterkit.so`;
//! and puts the link of that name beside it in the build tree
//! (`target/release/libscatterkit.so.0.2 → libscatterkit.so`), so that a
//! program linked against `target/release/libscatterkit.so` runs from the
//! build tree too, not only after `scripts/install.sh`.

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if os == "linux" {
        let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap();
        let minor = std::env::var("CARGO_PKG_VERSION_MINOR").unwrap();
        let soname = if major == "0" {
            format!("libscatterkit.so.{major}.{minor}")
        } else {
            format!("libscatterkit.so.{major}")
        };
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,{soname}");
        link_in_build_tree(&soname);
    }
}

/// `<profile dir>/<soname>` → `libscatterkit.so`, where the profile dir
/// (`target/release`, or `target/<triple>/release`) is three levels above
/// `OUT_DIR` (`…/build/scatterkit-capi-<hash>/out`). A link already there
/// is left alone; a failure only loses the convenience.
fn link_in_build_tree(soname: &str) {
    #[cfg(unix)]
    {
        let Ok(out) = std::env::var("OUT_DIR") else {
            return;
        };
        let Some(profile) = std::path::Path::new(&out).ancestors().nth(3) else {
            return;
        };
        let link = profile.join(soname);
        if std::fs::symlink_metadata(&link).is_err() {
            let _ = std::os::unix::fs::symlink("libscatterkit.so", &link);
        }
    }
    #[cfg(not(unix))]
    let _ = soname;
}
