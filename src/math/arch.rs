//! Loops chosen once, when the program is loaded: builds of the same Rust
//! code for x86-64's baseline (SSE2), AVX, AVX2 with FMA, and AVX-512 (F, VL,
//! BW, DQ), for the C layer on x86-64 Linux with glibc (`cfg(ifunc)`, set by
//! `build.rs`).
//!
//! Each symbol here is an indirect function (`STT_GNU_IFUNC`, the mechanism
//! glibc uses to pick its own `memcpy` and libm variants): its resolver runs
//! once, before `main` (in the dynamic loader, or in the C library's start-up
//! code of a static program), and picks the widest build the processor has
//! and the operating system saves the registers of ([`level`]). The library
//! keeps no state for this: the loader writes the choice into the program's
//! relocations, and a call costs no test. (Asking the processor on each call
//! is not an option: `cpuid` took 5 µs in the virtual machines we measured,
//! longer than a batch of 4096 samples.)
//!
//! Why wider builds: the loops here are bound by the f64 divider or by loads,
//! and wider vectors do more per instruction (AMD EPYC, Zen 4: 1.25 ns per
//! `divpd` of 2 or 4 lanes; the uniforms' check's integer operations are
//! 256 bits wide from AVX2 on). All builds run the same IEEE operations in the same
//! order: Rust never contracts a multiply and an add into a fused
//! multiply–add (which would round differently) unless the code asks for
//! one, and the code here does not, so the builds return the same bits,
//! which the tests beside each use (`phase::hg::batch`, `phase::function`)
//! check for every build this processor runs.
//!
//! Not under cargo-fuzz (its sanitizer runtime is not set up when resolvers
//! run) and not for Rust callers without the `ffi` feature (two versions of
//! the crate in one program would define the same symbols, as they already
//! would the `sk_*` ones).
#![allow(unsafe_code)]

/// Defines `$sym`, an indirect function with the C signature given, whose
/// builds all run `$body` (module docs), exported to the linker as
/// `sk__$sym` (hidden: not part of the shared library's interface, but a
/// name of the library's own in a static archive); `$body` sees the
/// arguments and the invoking module's items. The builds are `$sym::BUILDS` (with their
/// [`Level`]), for tests.
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
                concat!(".pushsection .text.", "sk__", stringify!($sym), ",\"ax\",@progbits"),
                concat!(".globl ", "sk__", stringify!($sym)),
                concat!(".hidden ", "sk__", stringify!($sym)),
                concat!(".type ", "sk__", stringify!($sym), ", @gnu_indirect_function"),
                ".p2align 4",
                concat!("sk__", stringify!($sym), ":"),
                "jmp {resolve}",
                concat!(".size ", "sk__", stringify!($sym), ", . - ", "sk__", stringify!($sym)),
                ".popsection",
                resolve = sym resolve,
            );

            unsafe extern "C" {
                /// Resolved once by the loader to one of [`BUILDS`].
                #[link_name = concat!("sk__", stringify!($sym))]
                pub(crate) fn $sym($($arg: $ty),*) $(-> $ret)?;
            }

            /// Runs before `main`: registers and the processor only.
            extern "C" fn resolve() -> unsafe extern "C" fn($($ty),*) $(-> $ret)? {
                let level = $crate::math::arch::level();
                let mut best = sse2 as unsafe extern "C" fn($($ty),*) $(-> $ret)?;
                for (needs, build) in BUILDS {
                    if needs <= level {
                        best = build;
                    }
                }
                best
            }

            /// Every build with the level it needs, narrowest first.
            #[allow(dead_code)]
            pub(crate) const BUILDS: [($crate::math::arch::Level, unsafe extern "C" fn($($ty),*) $(-> $ret)?); 4] = [
                ($crate::math::arch::Level::Sse2, sse2),
                ($crate::math::arch::Level::Avx, avx),
                ($crate::math::arch::Level::Avx2, avx2),
                ($crate::math::arch::Level::Avx512, avx512),
            ];

            /// The SSE2 build.
            ///
            /// # Safety
            /// The contract of the symbol (its documentation).
            unsafe extern "C" fn sse2($($arg: $ty),*) $(-> $ret)? $body

            /// The AVX build.
            ///
            /// # Safety
            /// As [`sse2`], and [`Level::Avx`]($crate::math::arch::Level) usable.
            #[target_feature(enable = "avx")]
            unsafe extern "C" fn avx($($arg: $ty),*) $(-> $ret)? $body

            /// The AVX2 + FMA build.
            ///
            /// # Safety
            /// As [`sse2`], and [`Level::Avx2`]($crate::math::arch::Level) usable.
            #[target_feature(enable = "avx2,fma")]
            unsafe extern "C" fn avx2($($arg: $ty),*) $(-> $ret)? $body

            /// The AVX-512 build.
            ///
            /// # Safety
            /// As [`sse2`], and [`Level::Avx512`]($crate::math::arch::Level) usable.
            #[target_feature(enable = "avx512f,avx512vl,avx512bw,avx512dq,avx2,fma")]
            unsafe extern "C" fn avx512($($arg: $ty),*) $(-> $ret)? $body
        }
        pub(crate) use $sym::$sym;
    };
}
pub(crate) use load_time_choice;

/// The widest instruction set a build may use, narrowest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Level {
    /// x86-64's baseline.
    Sse2,
    /// AVX (256-bit floating point).
    Avx,
    /// AVX2 and FMA (256-bit integers too).
    Avx2,
    /// AVX-512 F, VL, BW and DQ, with AVX2 and FMA.
    Avx512,
}

/// The widest [`Level`] this processor has and the operating system saves
/// the registers of: CPUID leaf 1 (`OSXSAVE` ECX 27, `AVX` 28, `FMA` 12),
/// leaf 7 (`AVX2` EBX 5, `AVX512F` 16, `DQ` 17, `BW` 30, `VL` 31), and `XCR0`
/// (bits 1–2 for the YMM state, 5–7 for the opmask and ZMM state).
pub(crate) fn level() -> Level {
    use core::arch::x86_64::{__cpuid, __cpuid_count};
    let ecx = __cpuid(1).ecx;
    if ecx & (1 << 27) == 0 || ecx & (1 << 28) == 0 {
        return Level::Sse2;
    }
    let xcr0 = xgetbv0();
    if xcr0 & 0b110 != 0b110 {
        return Level::Sse2;
    }
    let leaf7 = if __cpuid(0).eax >= 7 {
        __cpuid_count(7, 0).ebx
    } else {
        0
    };
    let has = |bits: &[u32]| bits.iter().all(|&b| leaf7 & (1 << b) != 0);
    if !has(&[5]) || ecx & (1 << 12) == 0 {
        return Level::Avx;
    }
    if !has(&[16, 17, 30, 31]) || xcr0 & 0b1110_0000 != 0b1110_0000 {
        return Level::Avx2;
    }
    Level::Avx512
}

/// `XCR0`, the state the operating system saves; call only once `OSXSAVE`
/// is set.
fn xgetbv0() -> u32 {
    let xcr0: u32;
    // SAFETY: `xgetbv` with ECX = 0 is defined once OSXSAVE is set (checked
    // by the caller); it reads a register and touches no memory.
    unsafe {
        core::arch::asm!(
            "xgetbv",
            in("ecx") 0u32,
            out("eax") xcr0,
            out("edx") _,
            options(nomem, nostack, preserves_flags),
        );
    }
    xcr0
}

/// The [`Level`] of this test process as the standard library detects it,
/// to check that [`level`] agrees.
#[cfg(test)]
pub(crate) fn detected() -> Level {
    extern crate std;
    use std::is_x86_feature_detected as has;
    if has!("avx512f")
        && has!("avx512vl")
        && has!("avx512bw")
        && has!("avx512dq")
        && has!("avx2")
        && has!("fma")
    {
        Level::Avx512
    } else if has!("avx2") && has!("fma") {
        Level::Avx2
    } else if has!("avx") {
        Level::Avx
    } else {
        Level::Sse2
    }
}

#[cfg(test)]
mod tests {
    /// The resolvers' reading of the processor agrees with the standard
    /// library's.
    #[test]
    fn level_matches_detection() {
        assert_eq!(super::level(), super::detected());
    }
}
