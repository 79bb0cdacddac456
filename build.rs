//! Sets `cfg(ifunc)` where the C layer's HG cosine batch and uniforms' check
//! are chosen once at load time, SSE2 to AVX-512 (`src/math/arch.rs`): the `ffi` feature on
//! x86-64 Linux with glibc (whose loader runs indirect-function resolvers),
//! and not under cargo-fuzz (`cfg(fuzzing)`), whose sanitizer runtime would
//! see a resolver run before it is set up.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(ifunc)");
    let var = |k: &str| std::env::var(k).unwrap_or_default();
    let ifunc = std::env::var_os("CARGO_FEATURE_FFI").is_some()
        && var("CARGO_CFG_TARGET_ARCH") == "x86_64"
        && var("CARGO_CFG_TARGET_OS") == "linux"
        && var("CARGO_CFG_TARGET_ENV") == "gnu"
        && std::env::var_os("CARGO_CFG_FUZZING").is_none();
    if ifunc {
        println!("cargo::rustc-cfg=ifunc");
    }
    println!("cargo::rerun-if-changed=build.rs");
}
