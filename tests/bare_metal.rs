//! The bare-metal C library and what a firmware image pays for sampling:
//! for each embedded target that is installed (`rustup target add
//! thumbv7em-none-eabihf riscv32imac-unknown-none-elf`), builds
//! `scatterkit-capi` as a `no_std` static library, and links a small probe
//! (HG and Rayleigh directions in f32 through the Rust API) with
//! `rust-lld --gc-sections` from each entry point alone, reporting the
//! `.text` size. On the Cortex-M4F target (single-precision FPU) the f32
//! direction paths must call no software double-precision routine and no
//! software square root. A target that is not installed is reported on
//! standard error and skipped (a failure where `SK_REQUIRE_ALL` is set, as
//! in CI). `SK_BLESS=1` writes the sizes
//! to `docs/measured/bare_metal.md`.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

const TARGETS: [&str; 2] = ["thumbv7em-none-eabihf", "riscv32imac-unknown-none-elf"];

const MANIFEST: &str = r#"[package]
name = "sk-bare-probe"
version = "0.0.0"
edition = "2024"
publish = false

[lib]
crate-type = ["staticlib"]

[dependencies]
scatterkit = { path = "ROOT" }

[profile.release]
panic = "abort"
opt-level = "s"

[workspace]
"#;

const LIB: &str = r#"#![no_std]
use scatterkit::{HenyeyGreenstein, Phase, PhaseFunction, Rayleigh, Vec3};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// One HG direction (f32): out = (x, y, z, pdf).
#[unsafe(no_mangle)]
pub extern "C" fn probe_hg_dir(g: f32, w: &[f32; 3], u1: f32, u2: f32, out: &mut [f32; 4]) {
    if let Ok(hg) = HenyeyGreenstein::new(g) {
        let (d, p) = hg.sample_dir(Vec3::new(w[0], w[1], w[2]), u1, u2);
        *out = [d.x, d.y, d.z, p];
    }
}

/// One Rayleigh direction (f32, the built-in table).
#[unsafe(no_mangle)]
pub extern "C" fn probe_rayleigh_dir(w: &[f32; 3], u1: f32, u2: f32, out: &mut [f32; 4]) {
    let (d, p) = Phase::<f32>::rayleigh().sample_dir(Vec3::new(w[0], w[1], w[2]), u1, u2);
    *out = [d.x, d.y, d.z, p];
}

/// The same through the model type instead of the `Phase` enum.
#[unsafe(no_mangle)]
pub extern "C" fn probe_rayleigh_model_dir(w: &[f32; 3], u1: f32, u2: f32, out: &mut [f32; 4]) {
    let (d, p) = Rayleigh.sample_dir(Vec3::new(w[0], w[1], w[2]), u1, u2);
    *out = [d.x, d.y, d.z, p];
}
"#;

fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())
}

fn installed(target: &str) -> bool {
    let sysroot = Command::new("rustc")
        .args(["--print", "sysroot"])
        .output()
        .unwrap();
    let sysroot = String::from_utf8(sysroot.stdout).unwrap();
    Path::new(sysroot.trim())
        .join("lib/rustlib")
        .join(target)
        .join("lib")
        .is_dir()
}

/// rust-lld from the toolchain's host directory.
fn rust_lld() -> Option<PathBuf> {
    let out = Command::new("rustc")
        .args(["--print", "sysroot"])
        .output()
        .ok()?;
    let sysroot = String::from_utf8(out.stdout).ok()?;
    let host = String::from_utf8(Command::new("rustc").arg("-vV").output().ok()?.stdout).ok()?;
    let host = host
        .lines()
        .find_map(|l| l.strip_prefix("host: "))?
        .to_string();
    let p = Path::new(sysroot.trim())
        .join("lib/rustlib")
        .join(host)
        .join("bin/rust-lld");
    p.exists().then_some(p)
}

/// The size of `.text` and the symbol names of an ELF file.
fn text_and_symbols(elf: &Path) -> (u64, Vec<String>) {
    let data = std::fs::read(elf).unwrap();
    // ELF32 little-endian: section headers at e_shoff (0x20), e_shentsize
    // (0x2e), e_shnum (0x30), e_shstrndx (0x32).
    let u16le = |o: usize| u16::from_le_bytes([data[o], data[o + 1]]) as usize;
    let u32le =
        |o: usize| u32::from_le_bytes([data[o], data[o + 1], data[o + 2], data[o + 3]]) as usize;
    assert_eq!(&data[..5], b"\x7fELF\x01", "expected a 32-bit ELF");
    let (shoff, shentsize, shnum, shstrndx) = (u32le(0x20), u16le(0x2e), u16le(0x30), u16le(0x32));
    let sh = |i: usize| shoff + i * shentsize;
    let strtab_off = u32le(sh(shstrndx) + 0x10);
    let name = |off: usize| {
        let s = &data[off..];
        String::from_utf8_lossy(&s[..s.iter().position(|&b| b == 0).unwrap()]).into_owned()
    };
    let (mut text, mut symbols) = (0u64, Vec::new());
    for i in 0..shnum {
        let n = name(strtab_off + u32le(sh(i)));
        let (kind, off, size, link) = (
            u32le(sh(i) + 4),
            u32le(sh(i) + 0x10),
            u32le(sh(i) + 0x14),
            u32le(sh(i) + 0x18),
        );
        if n.starts_with(".text") {
            text += size as u64;
        }
        if kind == 2 {
            // SYMTAB: 16-byte entries, names in the linked string table.
            let str_off = u32le(sh(link) + 0x10);
            for e in (off..off + size).step_by(16) {
                symbols.push(name(str_off + u32le(e)));
            }
        }
    }
    (text, symbols)
}

#[test]
fn bare_metal_library_and_its_code_size() {
    if !crate::common::repository("bare_metal_library_and_its_code_size") {
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bare_metal");
    let mut report = String::from(
        "# Bare metal\n\nGenerated by `SK_BLESS=1 cargo test --release --test bare_metal`; do not edit.\n\n\
         `.text` bytes of a firmware image that calls one f32 direction sampler through the Rust API, \
         linked with `rust-lld --gc-sections` from that entry point alone (`opt-level = \"s\"`), \
         and of the C library's `sk_phase_sample_dir`, whose dispatch reaches every model \
         (Draine and the fog compute in f64, in software on these targets).\n\n\
         | target | HG direction | Rayleigh direction (`Phase`) | Rayleigh direction (`Rayleigh`) | `sk_phase_sample_dir` (all models) |\n|---|---:|---:|---:|---:|\n",
    );
    let mut built = 0;
    for target in TARGETS {
        if !installed(target) {
            common::skip(&format!(
                "bare_metal: {target} is not installed (rustup target add {target})"
            ));
            continue;
        }
        let Some(lld) = rust_lld() else {
            common::skip("bare_metal: rust-lld is not in the toolchain");
            return;
        };
        // The C library itself.
        // `cargo rustc --crate-type staticlib`, as the README builds it:
        // these targets have no shared libraries, and a plain `cargo build`
        // warns that it drops the cdylib.
        let status = Command::new(cargo())
            .args([
                "rustc",
                "--release",
                "--quiet",
                "-p",
                "scatterkit-capi",
                "--crate-type",
                "staticlib",
                "--target",
                target,
                "--target-dir",
            ])
            .arg(tmp.join("capi"))
            .current_dir(root)
            .output()
            .unwrap();
        let log = String::from_utf8_lossy(&status.stderr);
        assert!(
            status.status.success(),
            "{target}: building scatterkit-capi failed:\n{log}"
        );
        // The README's build line must print no warning (cargo replays the
        // compiler's warnings when nothing is rebuilt, so this holds on
        // every run).
        assert!(
            !log.contains("warning"),
            "{target}: building scatterkit-capi printed a warning:\n{log}"
        );
        let capi = tmp
            .join("capi")
            .join(target)
            .join("release/libscatterkit.a");
        // The probe.
        let dir = tmp.join("probe");
        std::fs::create_dir_all(dir.join("src")).unwrap();
        std::fs::write(
            dir.join("Cargo.toml"),
            MANIFEST.replace("ROOT", root.to_str().unwrap()),
        )
        .unwrap();
        std::fs::write(dir.join("src/lib.rs"), LIB).unwrap();
        std::fs::copy(root.join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();
        let status = Command::new(cargo())
            .args([
                "build",
                "--release",
                "--quiet",
                "--offline",
                "--target",
                target,
                "--manifest-path",
            ])
            .arg(dir.join("Cargo.toml"))
            .output()
            .unwrap();
        let log = String::from_utf8_lossy(&status.stderr);
        assert!(
            status.status.success() && !log.contains("warning"),
            "{target}: building the probe failed or printed a warning:\n{log}"
        );
        let probe = dir
            .join("target")
            .join(target)
            .join("release/libsk_bare_probe.a");
        let link = |lib: &Path, entry: &str, extra: &[&str]| {
            let out = tmp.join(format!("{target}-{entry}.elf"));
            let st = Command::new(&lld)
                .args(["-flavor", "gnu", "--gc-sections", "--entry", entry])
                .args(extra)
                .arg("-o")
                .arg(&out)
                .arg(lib)
                .status()
                .unwrap();
            assert!(st.success(), "{target}: linking {entry} failed");
            text_and_symbols(&out)
        };
        let (hg, hg_syms) = link(&probe, "probe_hg_dir", &[]);
        let (ray, ray_syms) = link(&probe, "probe_rayleigh_dir", &[]);
        let (ray_model, ray_model_syms) = link(&probe, "probe_rayleigh_model_dir", &[]);
        let (all, all_syms) = link(
            &capi,
            "sk_phase_sample_dir",
            &["-u", "sk_phase_new_hg", "-u", "sk_phase_new_rayleigh"],
        );
        println!(
            "{target}: .text HG direction {hg} B, Rayleigh direction {ray} B (model type {ray_model} B), sk_phase_sample_dir {all} B"
        );
        report += &format!("| `{target}` | {hg} | {ray} | {ray_model} | {all} |\n");
        if target.starts_with("thumbv7em") {
            // Software double precision (the EABI helpers and the
            // compiler-builtins routines such as `__adddf3`, `__gedf2`,
            // `__extendsfdf2`) and libm's software square root. The builtins
            // are unmangled `__` names: a mangled Rust symbol's hash is hex
            // and can itself contain "df2" (it did, for a table's symbol, in
            // a checkout at another path).
            let soft = |s: &&String| {
                let builtin = s.starts_with("__") && !s.starts_with("__Z");
                s.starts_with("__aeabi_d")
                    || s.starts_with("__aeabi_f2d")
                    || (builtin && (s.contains("df3") || s.contains("df2")))
                    || s.contains("sqrt")
            };
            let probes = [
                ("HG", &hg_syms),
                ("Rayleigh", &ray_syms),
                ("Rayleigh (model type)", &ray_model_syms),
            ];
            // The check can fail: the whole sampler (Draine and the fog
            // solve in f64) does link software double precision there.
            assert!(
                all_syms.iter().any(|s| soft(&s)),
                "{target}: no software double-precision symbol found in sk_phase_sample_dir's image"
            );
            for (name, syms) in probes {
                let bad: Vec<_> = syms.iter().filter(soft).collect();
                assert!(
                    bad.is_empty(),
                    "{target}: the f32 {name} direction calls {bad:?}"
                );
            }
        }
        built += 1;
    }
    report += "\nThe f32 HG and Rayleigh direction paths on `thumbv7em-none-eabihf` call no software \
               double-precision routine and use the FPU's `vsqrt.f32` (checked on the linked image's \
               symbol table by the test).\n";
    if built == TARGETS.len() && std::env::var_os("SK_BLESS").is_some() {
        std::fs::write(root.join("docs/measured/bare_metal.md"), report).unwrap();
    }
}
