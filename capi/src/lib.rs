//! Builds `libscatterkit.a` and `libscatterkit.so` from the `ffi` layer of the
//! `scatterkit` crate. Nothing lives here but the re-export: the functions,
//! their checks and their docs are in `scatterkit/src/ffi/`.
//!
//! It refuses to compile with unwinding: a Rust panic must never cross
//! `extern "C"` (the workspace's profiles set `panic = "abort"`).
//!
//! On bare-metal targets (`target_os = "none"`: `thumbv7em-none-eabihf`,
//! `riscv32imac-unknown-none-elf`, ...) it is `no_std` with its own panic
//! handler, which traps (a panic is unreachable from the C ABI: a test walks
//! the call graph of the hosted build). Build it with
//! `cargo build --release -p scatterkit-capi --target thumbv7em-none-eabihf`
//! after `rustup target add thumbv7em-none-eabihf`; only the static library
//! is built there.
#![cfg_attr(target_os = "none", no_std)]

#[cfg(panic = "unwind")]
compile_error!(
    "scatterkit-capi must be built with panic = \"abort\" (the workspace profiles set it)"
);

pub use scatterkit_core::ffi::*;

/// Bare metal: a panic traps. The C ABI cannot reach one (see the crate
/// docs); this only satisfies `no_std`.
#[cfg(target_os = "none")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
