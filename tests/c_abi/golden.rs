//! Golden values: fixed inputs through every sampler in f32 and f64, as exact
//! bit patterns, compared with the committed `tests/golden/golden.txt`, once
//! through the Rust API (here) and once through the C API
//! (`tests/c/golden.c`). A change to any sampler's output fails this test
//! until the file is regenerated on purpose:
//! `SK_BLESS=1 cargo test --release --test c_abi golden::`.

use crate::common;

use common::cbuild::{build_program, root, run};
use rand_xoshiro::rand_core::TryRng;
use scatterkit::phase::schlick::Schlick;
use scatterkit::surface::{
    CrossingPolicy, Fraction, Surface, SurfaceModel, lambert_sample, phong_sample,
};
use scatterkit::{Grid, Phase, PhaseFunction, Ray, RayleighMethod, Vec3, medium, rayleigh};
use std::fmt::Write;

/// The generator the C program uses: splitmix64.
struct SplitMix(u64);
impl TryRng for SplitMix {
    type Error = core::convert::Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
        Ok((self.try_next_u64()? >> 32) as u32)
    }
    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        Ok(z ^ (z >> 31))
    }
    fn try_fill_bytes(&mut self, d: &mut [u8]) -> Result<(), Self::Error> {
        rand_xoshiro::rand_core::utils::fill_bytes_via_next_word(d, || self.try_next_u64())
    }
}

const K: usize = 8;
const US: [f64; K] = [0.0, 1e-7, 0.1, 0.37, 0.5, 0.8125, 0.999999, 1.0];

fn h32(x: f32) -> String {
    format!("{:08x}", x.to_bits())
}
fn h64(x: f64) -> String {
    format!("{:016x}", x.to_bits())
}

fn phase_lines(s: &mut String, name: &str, p: &Phase<f32>, q: &Phase<f64>) {
    let w32 = Vec3::new(0.48f32, 0.6, 0.64);
    let w64 = Vec3::new(0.48f64, 0.6, 0.64);
    write!(s, "{name} f32").unwrap();
    for i in 0..K {
        let (d, pdf) = p.sample_dir(w32, US[i] as f32, US[(i + 3) % K] as f32);
        let mu = p.sample_cos(US[i] as f32);
        write!(
            s,
            " {}:{}:{}:{}:{}",
            h32(mu),
            h32(d.x),
            h32(d.y),
            h32(d.z),
            h32(pdf)
        )
        .unwrap();
    }
    write!(s, "\n{name} f64").unwrap();
    for i in 0..K {
        let (d, pdf) = q.sample_dir(w64, US[i], US[(i + 3) % K]);
        let mu = q.sample_cos(US[i]);
        write!(
            s,
            " {}:{}:{}:{}:{}",
            h64(mu),
            h64(d.x),
            h64(d.y),
            h64(d.z),
            h64(pdf)
        )
        .unwrap();
    }
    s.push('\n');
}

/// The golden lines through the Rust API.
fn rust_lines() -> String {
    let mut s = String::new();
    let phases: [(&str, Phase<f32>, Phase<f64>); 13] = [
        ("isotropic", Phase::isotropic(), Phase::isotropic()),
        ("rayleigh", Phase::rayleigh(), Phase::rayleigh()),
        (
            "rayleigh_depolarized_0.028",
            Phase::rayleigh_depolarized(0.028).unwrap(),
            Phase::rayleigh_depolarized(0.028).unwrap(),
        ),
        (
            "hg_0.7",
            Phase::henyey_greenstein(0.7).unwrap(),
            Phase::henyey_greenstein(0.7).unwrap(),
        ),
        (
            "hg_-0.999",
            Phase::henyey_greenstein(-0.999).unwrap(),
            Phase::henyey_greenstein(-0.999).unwrap(),
        ),
        (
            "draine_0.3_250",
            Phase::draine(0.3, 250.0).unwrap(),
            Phase::draine(0.3, 250.0).unwrap(),
        ),
        (
            "cornette_shanks_0.6",
            Phase::cornette_shanks(0.6).unwrap(),
            Phase::cornette_shanks(0.6).unwrap(),
        ),
        (
            "fog_2um",
            Phase::fog_diameter(2.0).unwrap(),
            Phase::fog_diameter(2.0).unwrap(),
        ),
        (
            "two_lobe_hg_0.8_-0.3_0.9",
            Phase::two_lobe_hg(0.8, -0.3, 0.9).unwrap(),
            Phase::two_lobe_hg(0.8, -0.3, 0.9).unwrap(),
        ),
        (
            "gegenbauer_-0.25_0.7",
            Phase::gegenbauer(-0.25, 0.7).unwrap(),
            Phase::gegenbauer(-0.25, 0.7).unwrap(),
        ),
        (
            "fournier_forand_1.1_4",
            Phase::fournier_forand(1.1, 4.0).unwrap(),
            Phase::fournier_forand(1.1, 4.0).unwrap(),
        ),
        (
            "schlick_0.6",
            Phase::from(Schlick::new(0.6).unwrap()),
            Phase::from(Schlick::new(0.6).unwrap()),
        ),
        (
            "particle_0.01_0.01",
            Phase::particle(0.01, 0.01).unwrap(),
            Phase::particle(0.01, 0.01).unwrap(),
        ),
    ];
    for (name, p, q) in &phases {
        phase_lines(&mut s, name, p, q);
    }
    for m in RayleighMethod::ALL {
        let (mut r32, mut r64) = (SplitMix(7), SplitMix(7));
        write!(s, "rayleigh_method_{} f32", m as u32).unwrap();
        for _ in 0..K {
            let d = rayleigh::sample_dir(m, Vec3::new(0.48f32, 0.6, 0.64), &mut r32);
            write!(s, " {}:{}:{}", h32(d.x), h32(d.y), h32(d.z)).unwrap();
        }
        write!(s, "\nrayleigh_method_{} f64", m as u32).unwrap();
        for _ in 0..K {
            let d = rayleigh::sample_dir(m, Vec3::new(0.48f64, 0.6, 0.64), &mut r64);
            write!(s, " {}:{}:{}", h64(d.x), h64(d.y), h64(d.z)).unwrap();
        }
        s.push('\n');
    }
    // The C layer makes vectors unit first; do the same.
    let unit = |v: Vec3<f32>| v.try_normalize().unwrap();
    let (n, axis, up) = (
        unit(Vec3::new(0.0, 0.6, 0.8)),
        unit(Vec3::new(0.6, 0.0, 0.8)),
        unit(Vec3::new(0.0, 0.0, 1.0)),
    );
    s += "lambert f32";
    for i in 0..K {
        let d = lambert_sample(n, US[i] as f32, US[(i + 3) % K] as f32);
        write!(s, " {}:{}:{}", h32(d.x), h32(d.y), h32(d.z)).unwrap();
    }
    s.push('\n');
    for pol in [
        CrossingPolicy::Fold,
        CrossingPolicy::Resample,
        CrossingPolicy::Mirror,
    ] {
        write!(s, "phong_{} f32", pol as u32).unwrap();
        for i in 0..K {
            let d = phong_sample(axis, up, 3.0, pol, US[i] as f32, US[(i + 3) % K] as f32);
            write!(s, " {}:{}:{}", h32(d.x), h32(d.y), h32(d.z)).unwrap();
        }
        s.push('\n');
    }
    let surf = Surface::new(
        SurfaceModel::Phong,
        100.0f32,
        Fraction::Scalar(50e-9),
        CrossingPolicy::Resample,
    )
    .unwrap();
    let mut r = SplitMix(11);
    s += "interact f32";
    for _ in 0..K {
        let x = surf
            .interact(
                Vec3::new(0.6, 0.0, -0.8),
                Vec3::new(0.0, 0.0, 1.0),
                1.5,
                3.9,
                600e-9,
                &mut r,
            )
            .unwrap();
        // The C layer's event bits: 1 transmitted, 2 scattered.
        let (d, ev) = (x.dir, x.transmitted as u32 | (x.scattered as u32) << 1);
        write!(s, " {}:{}:{}:{ev}", h32(d.x), h32(d.y), h32(d.z)).unwrap();
    }
    s += "\nfree_path f32";
    for u in US {
        write!(s, " {}", h32(medium::free_path(2.0f32, u as f32))).unwrap();
    }
    s += "\nhomogeneous f32";
    let (st, ss) = ([0.5f32, 1.0, 2.0], [0.4f32, 0.9, 1.5]);
    for i in 0..K {
        let mut w = [0.0f32; 3];
        let h =
            medium::homogeneous_sample(&st, &ss, 1.0, US[i] as f32, US[(i + 3) % K] as f32, &mut w)
                .unwrap();
        write!(
            s,
            " {}:{}:{}:{}:{}",
            h32(h.t),
            h.scattered as u32,
            h32(w[0]),
            h32(w[1]),
            h32(w[2])
        )
        .unwrap();
    }
    let dens = [0.1f32, 0.9, 0.4, 0.7, 1.0, 0.2, 0.3, 0.6];
    let g = Grid::new(&dens, 2, 2, 2, 1.0, 3.0).unwrap();
    let (o, d) = (Vec3::new(-0.5f32, 0.31, 0.47), Vec3::new(1.0f32, 0.1, 0.0));
    let mut r = SplitMix(13);
    s += "\ndelta_track f32";
    for _ in 0..K {
        // `sk_delta_track`'s route: an escape at the box's face.
        let x = g
            .delta_track_within(Ray::new(o, d, 3.0), medium::MAX_STEPS, &mut r)
            .unwrap();
        write!(s, " {}:{}", h32(x.t), x.event as u32).unwrap();
    }
    s += "\nratio_track f32";
    for _ in 0..K {
        write!(
            s,
            " {}",
            h32(g.ratio_track(Ray::new(o, d, 3.0), &mut r).unwrap())
        )
        .unwrap();
    }
    s.push('\n');
    s
}

#[test]
fn golden_values_through_rust_and_c() {
    if !crate::common::repository("golden_values_through_rust_and_c") {
        return;
    }
    let path = root().join("tests/golden/golden.txt");
    let rust = rust_lines();
    if std::env::var_os("SK_BLESS").is_some() {
        std::fs::write(&path, &rust).unwrap();
    }
    let golden = std::fs::read_to_string(&path).unwrap();
    let first_diff = |a: &str, b: &str| a.lines().zip(b.lines()).position(|(x, y)| x != y);
    assert!(
        rust == golden,
        "Rust output differs from tests/golden/golden.txt at line {:?}; if the change is intended, \
         SK_BLESS=1 cargo test --release --test c_abi golden::",
        first_diff(&rust, &golden)
    );
    let exe = build_program(&root().join("tests/c/golden.c"), false);
    let (code, c_out) = run(&exe);
    assert_eq!(code, 0);
    assert!(
        c_out == golden,
        "C output differs from the golden file at line {:?}",
        first_diff(&c_out, &golden)
    );
    assert!(golden.lines().count() >= 36);
}
