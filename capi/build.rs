//! Gives the shared library a SONAME on Linux (`libscatterkit.so.0.2`: major
//! and minor while the major is 0, as cargo-c names it), so programs record
//! the ABI they were linked against rather than a bare `libscatterkit.so`.

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
    }
}
