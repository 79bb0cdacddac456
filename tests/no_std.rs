//! `no_std` holds: builds a `#![no_std]` static library that uses scatterkit
//! and brings its own `#[panic_handler]`. If scatterkit (or a dependency)
//! pulled in `std`, the build would fail with a duplicate `panic_impl` lang
//! item.

use std::path::Path;
use std::process::Command;

const MANIFEST: &str = r#"[package]
name = "sk-nostd-check"
version = "0.0.0"
edition = "2024"
publish = false

[lib]
crate-type = ["staticlib"]

[dependencies]
scatterkit = { path = "ROOT" }

[profile.dev]
panic = "abort"

[workspace]
"#;

const LIB: &str = r#"#![no_std]
use scatterkit::{Phase, PhaseFunction, RayleighMethod, Vec3, rayleigh};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

struct Counter(u64);
impl rand_core::TryRng for Counter {
    type Error = core::convert::Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> { Ok(self.try_next_u64()? as u32) }
    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        Ok(self.0)
    }
    fn try_fill_bytes(&mut self, _: &mut [u8]) -> Result<(), Self::Error> { Ok(()) }
}

#[unsafe(no_mangle)]
pub extern "C" fn nostd_sample(g: f32, u: f32) -> f32 {
    let hg = Phase::henyey_greenstein(g).map_or(f32::NAN, |p| p.sample_cos(u));
    let d = rayleigh::sample_dir(RayleighMethod::Simplified, Vec3::new(0.0f32, 0.0, 1.0), &mut Counter(1));
    // Mie in a stack buffer: no allocation.
    let mut buf = [scatterkit::mie::Complex::default(); 128];
    let q = scatterkit::mie::Mie::new(1.0, scatterkit::mie::Complex::new(1.5, 0.01), &mut buf)
        .map_or(f64::NAN, |m| m.efficiencies.q_ext);
    // A size distribution and the honest chooser, in stack memory too.
    let poly = scatterkit::polydisperse::Polydisperse {
        distribution: scatterkit::polydisperse::SizeDistribution::HAZE_M,
        r_min: 0.01,
        r_max: 0.1,
        wavelength: 0.55,
        n_medium: 1.0,
        m: scatterkit::mie::Complex::new(1.5, 0.01),
        intervals: 8,
    };
    let (mu, mut ph, mut sc) = ([1.0f64, -1.0], [0.0f64; 2], [0.0f64; 2]);
    let c = poly.average(&mu, &mut ph, &mut sc, &mut buf).map_or(f64::NAN, |a| a.c_ext);
    let mut work = [0.0f64; scatterkit::choose::mie::WORK_LEN];
    let choice = scatterkit::choose::mie::choose_mie(0.01, 0.55, None, 0.1, true, &mut buf, &mut work)
        .map_or(f64::NAN, |c| c.distance);
    // A 2-D table in stack memory, and a layer's albedo curve.
    let mut t2 = [0.0f32; 2 * 2 * 9];
    let tab = scatterkit::Table2d::inverse(&mut t2, 8, 2, 0.0, 1.0, |x| {
        scatterkit::HenyeyGreenstein::new(0.2 + 0.5 * x)
    })
    .map_or(f32::NAN, |t| t.sample_cos(0.5, u));
    let curve = scatterkit::transport::albedo::AlbedoCurve::simulate(
        &scatterkit::Isotropic,
        scatterkit::transport::albedo::Layer::SemiInfinite,
        scatterkit::transport::albedo::Illumination::Diffuse,
        4,
        &mut Counter(3),
    )
    .map_or(f64::NAN, |c| c.albedo(0.9));
    let gk = Phase::<f64>::gegenbauer_gamma(0.8, 2.0).map_or(f64::NAN, |p| p.mean_cosine());
    hg + d.z + scatterkit::cbrt::cbrt_f32(u) + q as f32 + (c + choice + curve + gk) as f32 + tab
}
"#;

#[test]
fn builds_in_a_no_std_crate_with_its_own_panic_handler() {
    let root = env!("CARGO_MANIFEST_DIR");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("nostd_check");
    std::fs::create_dir_all(dir.join("src")).unwrap();
    std::fs::write(dir.join("Cargo.toml"), MANIFEST.replace("ROOT", root)).unwrap();
    std::fs::write(dir.join("src/lib.rs"), LIB).unwrap();
    // Pin the dependency versions the main build already resolved (and has
    // cached), so the check needs no network.
    std::fs::copy(Path::new(root).join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();
    let manifest = dir.join("Cargo.toml");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    // rand_core is named in the check crate's code, so it needs the dependency too.
    let status = Command::new(&cargo)
        .args([
            "add",
            "--offline",
            "--quiet",
            "rand_core@0.10",
            "--no-default-features",
            "--manifest-path",
        ])
        .arg(&manifest)
        .status()
        .unwrap();
    assert!(status.success(), "cargo add failed");
    let out = Command::new(&cargo)
        .args(["build", "--offline", "--manifest-path"])
        .arg(&manifest)
        .env_remove("RUSTFLAGS")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "the no_std crate failed to build:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
