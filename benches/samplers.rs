//! criterion benchmarks: every sampler of the foundation, f32 and f64, as
//! elements per second (`cargo bench -p scatterkit-dev`; `--no-run` to only build; the package
//! `dev/` builds it, with criterion).

#[path = "cloud.rs"]
mod cloud;
#[path = "peers.rs"]
mod peers;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::Rng;
use rand_xoshiro::rand_core::SeedableRng;
use scatterkit::phase::draine::sample_cos_eq6;
use scatterkit::{
    Draine, Grid, Phase, PhaseFunction, Ray, RayleighMethod, Real, Table, Vec3, rayleigh,
};
use std::hint::black_box;

const BATCH: usize = 4096;

fn rng() -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(7)
}

fn rayleigh_methods<T: Real>(c: &mut Criterion, label: &str) {
    let mut g = c.benchmark_group(format!("rayleigh_dir_{label}"));
    g.throughput(Throughput::Elements(1));
    let w_in = Vec3::new(T::from_f64(0.48), T::from_f64(0.6), T::from_f64(0.64));
    for m in RayleighMethod::ALL {
        let mut r = rng();
        g.bench_function(BenchmarkId::from_parameter(format!("{m:?}")), |b| {
            b.iter(|| rayleigh::sample_dir(m, black_box(w_in), &mut r))
        });
    }
    g.finish();
}

fn phases<T: Real>(c: &mut Criterion, label: &str) {
    let w_in = Vec3::new(T::from_f64(0.48), T::from_f64(0.6), T::from_f64(0.64));
    let cases = [
        ("isotropic", Phase::isotropic()),
        ("rayleigh", Phase::rayleigh()),
        (
            "rayleigh_depolarized",
            Phase::rayleigh_depolarized(T::from_f64(0.028)).unwrap(),
        ),
        (
            "hg_0.7",
            Phase::henyey_greenstein(T::from_f64(0.7)).unwrap(),
        ),
    ];
    let mut g = c.benchmark_group(format!("phase_sample_dir_{label}"));
    g.throughput(Throughput::Elements(1));
    for (name, p) in cases {
        let mut r = rng();
        g.bench_function(name, |b| {
            b.iter(|| p.sample_dir(black_box(w_in), T::uniform(&mut r), T::uniform(&mut r)))
        });
    }
    g.finish();

    let u: Vec<T> = (0..BATCH)
        .map(|i| T::from_f64((i as f64 + 0.5) / BATCH as f64))
        .collect();
    let mut out = vec![T::ZERO; BATCH];
    let mut g = c.benchmark_group(format!("phase_sample_cos_{label}"));
    g.throughput(Throughput::Elements(BATCH as u64));
    for (name, p) in cases {
        g.bench_function(BenchmarkId::new("batch", name), |b| {
            b.iter(|| p.sample_cos_n(black_box(&u), &mut out).unwrap())
        });
        g.bench_function(BenchmarkId::new("scalar", name), |b| {
            b.iter(|| {
                for (o, &ui) in out.iter_mut().zip(&u) {
                    *o = p.sample_cos(black_box(ui));
                }
            })
        });
    }
    g.finish();
}

/// The peers' formulas (benches/peers.rs) beside ours, per cos θ.
fn peer_formulas(c: &mut Criterion) {
    let mut g = c.benchmark_group("peers_sample_cos_f32");
    g.throughput(Throughput::Elements(1));
    let mut r = rng();
    g.bench_function("rayleigh/mitsuba3_two_cbrt", |b| {
        b.iter(|| peers::mitsuba_rayleigh(f32::uniform(&mut r)))
    });
    g.bench_function("rayleigh/cycles_fast_inv_cbrt", |b| {
        b.iter(|| peers::cycles_rayleigh(f32::uniform(&mut r)))
    });
    g.bench_function("rayleigh/ours_direct", |b| {
        b.iter(|| rayleigh::inverse_cdf_direct(f32::uniform(&mut r)))
    });
    g.bench_function("rayleigh/ours_minimax", |b| {
        b.iter(|| rayleigh::inverse_cdf_minimax(f32::uniform(&mut r)))
    });
    g.bench_function("rayleigh/ours_table", |b| {
        b.iter(|| rayleigh::inverse_cdf_table(f32::uniform(&mut r)))
    });
    let hg = Phase::henyey_greenstein(0.7f32).unwrap();
    g.bench_function("hg/pbrt_v4", |b| {
        b.iter(|| peers::pbrt_v4_hg(black_box(0.7), f32::uniform(&mut r)))
    });
    g.bench_function("hg/ours", |b| {
        b.iter(|| hg.sample_cos(f32::uniform(&mut r)))
    });
    g.finish();
}

/// Draine by rejection from HG (benches/peers.rs).
fn draine_rejection<R: Rng>(g: f32, alpha: f32, r: &mut R) -> f32 {
    peers::draine_rejection(g, alpha, || f32::uniform(r))
}

/// Our Draine sampler, eq. 6 as published, and rejection from HG, in the
/// regions of the accuracy map (`docs/measured/draine_accuracy.md`).
fn draine(c: &mut Criterion) {
    let mut g = c.benchmark_group("draine_sample_cos_f32");
    g.throughput(Throughput::Elements(1));
    for (gg, a) in [
        (0.5f32, 1.0f32),
        (0.9, 10.0),
        (0.3, 250.0),
        (0.01, 1000.0),
        (-0.7, 1e4),
    ] {
        let id = format!("g{gg}_a{a}");
        let ours = Draine::new(gg, a).unwrap();
        let mut r = rng();
        g.bench_function(BenchmarkId::new("ours", &id), |b| {
            b.iter(|| ours.sample_cos(f32::uniform(&mut r)))
        });
        g.bench_function(BenchmarkId::new("eq6_published", &id), |b| {
            b.iter(|| sample_cos_eq6(black_box(gg), black_box(a), f32::uniform(&mut r)))
        });
        g.bench_function(BenchmarkId::new("hg_rejection", &id), |b| {
            b.iter(|| draine_rejection(gg, a, &mut r))
        });
    }
    g.finish();
    let mut g = c.benchmark_group("fog_sample_cos_f32");
    g.throughput(Throughput::Elements(1));
    let fog = scatterkit::Fog::<f32>::from_diameter(2.0).unwrap();
    let mut r = rng();
    g.bench_function("exact_inverse_2um", |b| {
        b.iter(|| fog.sample_cos(f32::uniform(&mut r)))
    });
    g.bench_function("by_lobe_2um", |b| {
        b.iter(|| fog.sample_cos_by_lobe(f32::uniform(&mut r)))
    });
    g.finish();
}

fn tables(c: &mut Criterion) {
    let mut g = c.benchmark_group("table_sample_cos_f32");
    g.throughput(Throughput::Elements(BATCH as u64));
    let u: Vec<f32> = (0..BATCH)
        .map(|i| ((i * 2654435761) % BATCH) as f32 / BATCH as f32)
        .collect();
    for n in [8usize, 32, 256] {
        let mut buf = vec![0.0f32; n + 1];
        let t = Table::rayleigh_cdf(&mut buf, n).unwrap();
        g.bench_function(BenchmarkId::new("frisvad_rayleigh_cdf", n), |b| {
            b.iter(|| u.iter().map(|&x| t.sample_cos(black_box(x))).sum::<f32>())
        });
        let mut hbuf = vec![0.0f32; 2 * (n + 1)];
        let h = Table::inverse(&Phase::rayleigh(), &mut hbuf, n).unwrap();
        g.bench_function(BenchmarkId::new("hermite_inverse_rayleigh", n), |b| {
            b.iter(|| u.iter().map(|&x| h.sample_cos(black_box(x))).sum::<f32>())
        });
    }
    g.finish();
}

/// Surface samplers (SunSolve's models), f32 and f64.
fn surfaces<T: Real>(c: &mut Criterion, label: &str) {
    use scatterkit::surface::{
        CrossingPolicy, Fraction, Surface, SurfaceModel, fresnel_dielectric, lambert_sample,
        phong_sample, refract,
    };
    let t = T::from_f64;
    let mut g = c.benchmark_group(format!("surface_{label}"));
    g.throughput(Throughput::Elements(1));
    let n = Vec3::new(T::ZERO, T::ZERO, T::ONE);
    let d = Vec3::new(t(0.6), T::ZERO, t(-0.8));
    let axis = Vec3::new(t(0.6), T::ZERO, t(0.8));
    let mut r = rng();
    g.bench_function("lambert_sample", |b| {
        b.iter(|| lambert_sample(black_box(n), T::uniform(&mut r), T::uniform(&mut r)))
    });
    for policy in [
        CrossingPolicy::Fold,
        CrossingPolicy::Resample,
        CrossingPolicy::Mirror,
    ] {
        g.bench_function(format!("phong_sample_a1000_{policy:?}"), |b| {
            b.iter(|| {
                phong_sample(
                    black_box(axis),
                    n,
                    t(1000.0),
                    policy,
                    T::uniform(&mut r),
                    T::uniform(&mut r),
                )
            })
        });
    }
    g.bench_function("fresnel_dielectric", |b| {
        b.iter(|| fresnel_dielectric(T::uniform(&mut r), t(1.5), t(3.9)))
    });
    g.bench_function("refract", |b| {
        b.iter(|| refract(black_box(d), n, t(1.5), t(3.9)))
    });
    let s = Surface::new(
        SurfaceModel::Phong,
        t(1000.0),
        Fraction::Scalar(t(50e-9)),
        CrossingPolicy::Fold,
    )
    .unwrap();
    g.bench_function("interact_phong_scalar", |b| {
        b.iter(|| s.interact(black_box(d), n, t(1.5), t(3.9), t(600e-9), &mut r))
    });
    g.finish();
}

/// Media: free paths, spectral homogeneous sampling, and tracking through a
/// grid and a callback. Tracking throughput counts tentative collisions
/// (steps): a ray across the unit cube with majorant 16 takes 16 on average.
fn media<T: Real>(c: &mut Criterion, label: &str) {
    use scatterkit::medium::{delta_track_fn, free_path, homogeneous_sample, ratio_track_fn};
    let t = T::from_f64;
    let mut g = c.benchmark_group(format!("medium_{label}"));
    g.throughput(Throughput::Elements(1));
    let mut r = rng();
    g.bench_function("free_path", |b| {
        b.iter(|| free_path(black_box(t(2.0)), T::uniform(&mut r)))
    });
    let st = [t(0.5), t(1.0), t(2.0)];
    let ss = [t(0.4), t(0.9), t(1.5)];
    let mut w = [T::ZERO; 3];
    g.bench_function("homogeneous_sample_3ch", |b| {
        b.iter(|| {
            homogeneous_sample(
                &st,
                &ss,
                t(1.0),
                T::uniform(&mut r),
                T::uniform(&mut r),
                &mut w,
            )
        })
    });
    let values: Vec<T> = (0..16 * 16 * 16)
        .map(|i| t(((i * 7919) % 101) as f64 / 100.0))
        .collect();
    let grid = Grid::new(&values, 16, 16, 16, t(2.0), t(14.0)).unwrap();
    let (o, d) = (
        Vec3::new(t(-0.5), t(0.31), t(0.47)),
        Vec3::new(T::ONE, T::ZERO, T::ZERO),
    );
    let maj = grid.majorant().to_f64();
    g.throughput(Throughput::Elements(maj as u64));
    g.bench_function("ratio_track_grid_steps", |b| {
        b.iter(|| grid.ratio_track(Ray::new(black_box(o), d, t(2.0)), &mut r))
    });
    let blob = |p: Vec3<T>| {
        let q = p - Vec3::new(t(0.5), t(0.5), t(0.5));
        (t(16.0) * (T::ONE - t(4.0) * q.dot(q))).max_of(T::ZERO)
    };
    g.throughput(Throughput::Elements(16));
    g.bench_function("ratio_track_fn_steps", |b| {
        b.iter(|| {
            ratio_track_fn(
                blob,
                t(16.0),
                Ray::new(black_box(o), d, t(1.5)).segment(t(0.5), t(1.5)),
                &mut r,
            )
        })
    });
    g.throughput(Throughput::Elements(1));
    g.bench_function("delta_track_fn_event", |b| {
        b.iter(|| {
            delta_track_fn(
                blob,
                t(16.0),
                Ray::new(black_box(o), d, t(1.5)).segment(t(0.5), t(1.5)),
                &mut r,
            )
        })
    });
    g.finish();
}

/// Rays through a 64³ cloud (`cloud.rs`), per ray: delta and ratio tracking
/// walking 16³ local majorants against one global majorant (a 1³ grid).
fn majorants(c: &mut Criterion) {
    use scatterkit::majorant::DEFAULT_RES;
    let values = cloud::cloud(64, 60.0);
    let grid = cloud::grid(&values, 64);
    let (mut ls, mut gs) = (vec![0.0f32; DEFAULT_RES.pow(3)], [0.0f32; 1]);
    let (local, global) = cloud::majorants(&grid, &mut ls, &mut gs);
    let rays = cloud::rays(256);
    let mut g = c.benchmark_group("majorants_cloud64");
    g.throughput(Throughput::Elements(rays.len() as u64));
    let mut r = rng();
    for (name, maj) in [("local16", &local), ("global", &global)] {
        g.bench_function(BenchmarkId::new("delta_track_ray", name), |b| {
            b.iter(|| {
                for &ray in &rays {
                    black_box(maj.delta_track(&grid, ray, 1 << 24, &mut r).unwrap());
                }
            })
        });
        g.bench_function(BenchmarkId::new("ratio_track_ray", name), |b| {
            b.iter(|| {
                for &ray in &rays {
                    black_box(maj.ratio_track(&grid, ray, 1 << 24, &mut r).unwrap());
                }
            })
        });
    }
    g.finish();
}

fn cube_roots(c: &mut Criterion) {
    let xs: Vec<f32> = (0..BATCH)
        .map(|i| 1e-6 * 1.0068f32.powi(i as i32))
        .collect();
    let xd: Vec<f64> = xs.iter().map(|&x| x as f64 * 1.000001).collect();
    let mut g = c.benchmark_group("cbrt");
    g.throughput(Throughput::Elements(BATCH as u64));
    g.bench_function("f32/scatterkit", |b| {
        b.iter(|| {
            xs.iter()
                .map(|&x| scatterkit::cbrt::cbrt_f32(black_box(x)))
                .sum::<f32>()
        })
    });
    g.bench_function("f32/scatterkit_fast", |b| {
        b.iter(|| {
            xs.iter()
                .map(|&x| scatterkit::cbrt::cbrt_fast_f32(black_box(x)))
                .sum::<f32>()
        })
    });
    g.bench_function("f32/libm_cbrtf", |b| {
        b.iter(|| xs.iter().map(|&x| libm::cbrtf(black_box(x))).sum::<f32>())
    });
    g.bench_function("f32/powf", |b| {
        b.iter(|| {
            xs.iter()
                .map(|&x| libm::powf(black_box(x), 1.0 / 3.0))
                .sum::<f32>()
        })
    });
    g.bench_function("f64/scatterkit", |b| {
        b.iter(|| {
            xd.iter()
                .map(|&x| scatterkit::cbrt::cbrt_f64(black_box(x)))
                .sum::<f64>()
        })
    });
    g.bench_function("f64/scatterkit_fast", |b| {
        b.iter(|| {
            xd.iter()
                .map(|&x| scatterkit::cbrt::cbrt_fast_f64(black_box(x)))
                .sum::<f64>()
        })
    });
    g.bench_function("f64/libm_cbrt", |b| {
        b.iter(|| xd.iter().map(|&x| libm::cbrt(black_box(x))).sum::<f64>())
    });
    g.finish();
}

fn all(c: &mut Criterion) {
    rayleigh_methods::<f32>(c, "f32");
    rayleigh_methods::<f64>(c, "f64");
    phases::<f32>(c, "f32");
    phases::<f64>(c, "f64");
    peer_formulas(c);
    draine(c);
    surfaces::<f32>(c, "f32");
    surfaces::<f64>(c, "f64");
    media::<f32>(c, "f32");
    media::<f64>(c, "f64");
    majorants(c);
    tables(c);
    cube_roots(c);
}

criterion_group!(benches, all);
criterion_main!(benches);
