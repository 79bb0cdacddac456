//! Every constructor with arbitrary parameters: an error or an object whose
//! samplers return finite values in range and unit directions.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rand_xoshiro::SplitMix64;
use rand_xoshiro::rand_core::SeedableRng;
use scatterkit::surface::{CrossingPolicy, Fraction, Surface, SurfaceModel};
use scatterkit::{Grid, Phase, PhaseFunction, Table, Vec3};

fn floats(data: &[u8]) -> Vec<f64> {
    data.chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

fn check(p: &Phase<f64>, u: f64) {
    let mu = p.sample_cos(u);
    assert!(
        u.is_nan() || (mu.is_finite() && mu.abs() <= 1.0),
        "{p:?} u {u}: {mu}"
    );
    let (d, pdf) = p.sample_dir(Vec3::new(0.0, 0.6, 0.8), u, 0.3);
    assert!(
        u.is_nan() || ((d.length() - 1.0).abs() < 1e-9 && pdf >= 0.0),
        "{p:?}: {d:?}"
    );
    let c = p.cdf(u);
    assert!(c.is_nan() == u.is_nan() && (u.is_nan() || (0.0..=1.0).contains(&c)));
    let p32: Phase<f32> = p.cast();
    let m32 = p32.sample_cos(u as f32);
    assert!(
        u.is_nan() || (m32.is_finite() && m32.abs() <= 1.0),
        "{p32:?}: {m32}"
    );
}

fuzz_target!(|data: &[u8]| {
    let v = floats(data);
    let x = |i: usize| v.get(i).copied().unwrap_or(0.5);
    let u = x(4);
    let phases = [
        Phase::henyey_greenstein(x(0)),
        Phase::draine(x(0), x(1)),
        Phase::cornette_shanks(x(0)),
        Phase::fog(x(0), x(1), x(2), x(3)),
        Phase::fog_diameter(x(2)),
        Phase::rayleigh_depolarized(x(3)),
    ];
    for p in phases.iter().flatten() {
        check(p, u);
    }
    if v.len() < 16 {
        // The model chooser is slower: fuzz it on short inputs only.
        if let Ok(p) = Phase::particle(x(2), x(3)) {
            check(&p, u);
        }
    }
    if let Ok(s) = Surface::new(
        SurfaceModel::Phong,
        x(1),
        Fraction::Scalar(x(3).abs() * 1e-7),
        CrossingPolicy::Resample,
    ) {
        let mut rng = scatterkit_fuzz_rng(data);
        if let Ok(scatterkit::surface::Interaction { dir: d, .. }) = s.interact(
            Vec3::new(x(5), x(6), x(7)),
            Vec3::new(x(8), x(9), x(10)),
            1.5,
            3.9,
            6e-7,
            &mut rng,
        ) {
            assert!((d.length() - 1.0).abs() < 1e-9, "{d:?}");
        }
    }
    if let Ok(g) = Grid::new(&v, v.len().max(1), 1, 1, x(1).abs(), x(2).abs()) {
        let mut rng = scatterkit_fuzz_rng(data);
        let r = g.ratio_track(
            scatterkit::Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 3.0),
            &mut rng,
        );
        // Roulette raises a weight below 0.05 at most 4 times: it stays in [0, 1].
        assert!(r.map_or(true, |r| (0.0..=1.0).contains(&r)), "{r:?}");
    }
    let n = v.len() / 2;
    if n >= 2 {
        let mut buf = vec![0.0; 2 * 17];
        if let Ok(t) = Table::measured(&v[..n], &v[n..2 * n], &mut buf, 16) {
            let mu = t.sample_cos(u);
            assert!(u.is_nan() || mu.abs() <= 1.0, "{mu}");
        }
    }
});

/// A deterministic generator from the input bytes.
fn scatterkit_fuzz_rng(data: &[u8]) -> SplitMix64 {
    SplitMix64::seed_from_u64(
        data.iter()
            .fold(1u64, |h, &b| h.wrapping_mul(31).wrapping_add(b as u64)),
    )
}
