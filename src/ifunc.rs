//! Loops chosen once, when the program is loaded: an SSE2 build (x86-64's
//! baseline) and an AVX build of the same Rust code, for the C layer on
//! x86-64 Linux with glibc (`cfg(ifunc)`, set by `build.rs`).
//!
//! Each symbol here is an indirect function (`STT_GNU_IFUNC`, the mechanism
//! glibc uses to pick its own `memcpy` and libm variants): its resolver runs
//! once, before `main` (in the dynamic loader, or in the C library's start-up
//! code of a static program), and picks the AVX build when the processor has
//! AVX and the operating system saves its registers (CPUID leaf 1 `OSXSAVE`
//! and `AVX`, then `XCR0` bits 1 and 2), else the SSE2 build. The library
//! keeps no state for this: the loader writes the choice into the program's
//! relocations, and a call costs no test. (Asking the processor on each call
//! is not an option: `cpuid` took 5 µs in the virtual machines we measured,
//! longer than a batch of 4096 samples.)
//!
//! Why AVX: the loops here are bound by the f64 divider or by loads, and AVX
//! doubles the width at the same cost per instruction (AMD EPYC: 1.25 ns per
//! `divpd` of 2 or 4 lanes). Both builds run the same IEEE operations in the
//! same order: AVX adds width, not fused multiply–adds (which would round
//! differently), so they return the same bits, which the tests beside each
//! use (`phase::hg_batch`, `phase`) check wherever the processor runs both.
//!
//! Not under cargo-fuzz (its sanitizer runtime is not set up when resolvers
//! run) and not for Rust callers without the `ffi` feature (two versions of
//! the crate in one program would define the same symbols, as they already
//! would the `sk_*` ones).
#![allow(unsafe_code)]

/// Defines `$sym`, an indirect function with the C signature given, whose
/// builds both run `$body` (module docs); `$body` sees the arguments and the
/// invoking module's items. The two builds are `$sym::sse2` and
/// `$sym::avx`, for tests.
macro_rules! load_time_choice {
    ($(#[$doc:meta])* $sym:ident: fn($($arg:ident: $ty:ty),* $(,)?) $(-> $ret:ty)? $body:block) => {
        $(#[$doc])*
        #[allow(non_snake_case, unsafe_code)]
        pub(crate) mod $sym {
            #[allow(unused_imports)]
            use super::*;

            // The resolver is a jump to `resolve`, so that the indirect
            // symbol is defined in the object that carries its type
            // directive, whichever codegen unit `resolve` lands in. Hidden:
            // not exported from the shared library.
            core::arch::global_asm!(
                concat!(".pushsection .text.", stringify!($sym), ",\"ax\",@progbits"),
                concat!(".globl ", stringify!($sym)),
                concat!(".hidden ", stringify!($sym)),
                concat!(".type ", stringify!($sym), ", @gnu_indirect_function"),
                ".p2align 4",
                concat!(stringify!($sym), ":"),
                "jmp {resolve}",
                concat!(".size ", stringify!($sym), ", . - ", stringify!($sym)),
                ".popsection",
                resolve = sym resolve,
            );

            unsafe extern "C" {
                /// Resolved once by the loader to [`sse2`] or [`avx`].
                pub(crate) fn $sym($($arg: $ty),*) $(-> $ret)?;
            }

            /// Runs before `main`: registers and the processor only.
            extern "C" fn resolve() -> unsafe extern "C" fn($($ty),*) $(-> $ret)? {
                if $crate::ifunc::avx_usable() { avx } else { sse2 }
            }

            /// The SSE2 build.
            ///
            /// # Safety
            /// The contract of the symbol (its documentation).
            pub(crate) unsafe extern "C" fn sse2($($arg: $ty),*) $(-> $ret)? $body

            /// The AVX build.
            ///
            /// # Safety
            /// As [`sse2`], and AVX usable.
            #[target_feature(enable = "avx")]
            pub(crate) unsafe extern "C" fn avx($($arg: $ty),*) $(-> $ret)? $body
        }
        pub(crate) use $sym::$sym;
    };
}
pub(crate) use load_time_choice;

/// AVX is usable when the processor has it (CPUID.1:ECX bit 28) and the
/// operating system saves the YMM registers on a context switch (`OSXSAVE`,
/// bit 27, then `XCR0` bits 1 and 2).
pub(crate) fn avx_usable() -> bool {
    let ecx = core::arch::x86_64::__cpuid(1).ecx;
    if ecx & (1 << 27) == 0 || ecx & (1 << 28) == 0 {
        return false;
    }
    let xcr0: u32;
    // SAFETY: `xgetbv` with ECX = 0 is defined once OSXSAVE is set (checked
    // above); it reads a register and touches no memory.
    unsafe {
        core::arch::asm!(
            "xgetbv",
            in("ecx") 0u32,
            out("eax") xcr0,
            out("edx") _,
            options(nomem, nostack, preserves_flags),
        );
    }
    xcr0 & 0b110 == 0b110
}
