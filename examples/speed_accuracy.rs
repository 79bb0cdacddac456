//! Frisvad's Table 1 (JOSA A 2011), re-run today: every Rayleigh sampling
//! method side by side with Henyey–Greenstein, the isotropic floor and the
//! cube roots, in one run, with a fast RNG and a deliberately slow one, beside
//! each deterministic method's accuracy.
//!
//!     cargo run --release --example speed_accuracy
//!
//! Speed: nanoseconds per f32 direction (median of 7 runs of 2²⁰ samples),
//! and the ratio to simplified rejection, which the paper found fastest.
//! Accuracy: max |cos θ − exact| over 2²⁰ + 1 evenly spaced u including 0 and
//! 1, against an f64 evaluation of the exact inverse. Rejection methods are
//! exact in distribution, so their column says so instead of a number.

use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{SeedableRng, TryRng};
use scatterkit::{Phase, PhaseFunction, RayleighMethod, Real, Table, Vec3, rayleigh};
use std::convert::Infallible;
use std::hint::black_box;
use std::time::Instant;

const SAMPLES: usize = 1 << 20;
const REPEATS: usize = 7;

/// A slow generator in the spirit of the C `rand()` the paper timed: a 15-bit
/// LCG (the MSVC constants) behind an opaque function pointer, five calls per
/// 64-bit word.
struct SlowRand {
    state: u32,
    step: fn(&mut u32) -> u32,
}

fn lcg15(s: &mut u32) -> u32 {
    *s = s.wrapping_mul(214_013).wrapping_add(2_531_011);
    (*s >> 16) & 0x7fff
}

impl SlowRand {
    fn new(seed: u32) -> Self {
        SlowRand {
            state: seed,
            step: black_box(lcg15 as fn(&mut u32) -> u32),
        }
    }
}

impl TryRng for SlowRand {
    type Error = Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok((self.try_next_u64()? >> 32) as u32)
    }
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        let mut x = 0u64;
        for _ in 0..5 {
            x = (x << 15) | (self.step)(&mut self.state) as u64;
        }
        Ok(x)
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        rand_xoshiro::rand_core::utils::fill_bytes_via_next_word(dst, || self.try_next_u64())
    }
}

/// Median nanoseconds per call of `f` over `SAMPLES` calls.
fn time_ns(mut f: impl FnMut() -> f32) -> f64 {
    let mut runs: Vec<f64> = (0..REPEATS)
        .map(|_| {
            let start = Instant::now();
            let mut acc = 0.0f32;
            for _ in 0..SAMPLES {
                acc += f();
            }
            black_box(acc);
            start.elapsed().as_nanos() as f64 / SAMPLES as f64
        })
        .collect();
    runs.sort_by(f64::total_cmp);
    runs[REPEATS / 2]
}

/// Max |f(u) − exact(u)| over an even grid of u including both ends.
fn max_error(f: impl Fn(f32) -> f32, exact: impl Fn(f64) -> f64) -> f64 {
    (0..=SAMPLES)
        .map(|i| {
            let u = i as f32 / SAMPLES as f32;
            (f(u) as f64 - exact(u as f64)).abs()
        })
        .fold(0.0, f64::max)
}

/// Rayleigh's exact inverse in f64 (Cardano with odd symmetry).
fn rayleigh_exact(u: f64) -> f64 {
    let s = 2.0 * (2.0 * u - 1.0);
    let w = libm::cbrt(s.abs() + (s * s + 1.0).sqrt());
    (w - 1.0 / w).copysign(s)
}

/// HG's textbook inverse in f64 (accurate away from g = 0 and |g| = 1).
fn hg_exact(g: f64, u: f64) -> f64 {
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
}

struct Row {
    name: String,
    fast_ns: f64,
    slow_ns: f64,
    accuracy: String,
}

/// Times `$sample` (an expression in the RNG `$r` giving a `Vec3<f32>`) with
/// both generators; a macro so each loop is monomorphised for its RNG.
macro_rules! row {
    ($rows:ident, $name:expr, $acc:expr, |$r:ident| $sample:expr) => {{
        let mut fast = Xoshiro256PlusPlus::seed_from_u64(1);
        let mut slow = SlowRand::new(1);
        let fast_ns = {
            let $r = &mut fast;
            time_ns(|| $sample.z)
        };
        let slow_ns = {
            let $r = &mut slow;
            time_ns(|| $sample.z)
        };
        $rows.push(Row {
            name: $name.to_string(),
            fast_ns,
            slow_ns,
            accuracy: $acc,
        });
    }};
}

fn direction_rows() -> Vec<Row> {
    let w_in = Vec3::new(0.48f32, 0.6, 0.64);
    let mut rows = Vec::new();
    let iso = Phase::<f32>::isotropic();
    row!(rows, "isotropic (floor)", "exact".into(), |r| iso
        .sample_dir(w_in, f32::uniform(r), f32::uniform(r))
        .0);
    for (m, name) in [
        (RayleighMethod::RejectCube, "Rayleigh, von Neumann cube"),
        (
            RayleighMethod::RejectSpherical,
            "Rayleigh, spherical coordinates",
        ),
        (RayleighMethod::Baranoski, "Rayleigh, Baranoski (corrected)"),
        (RayleighMethod::Simplified, "Rayleigh, simplified rejection"),
    ] {
        row!(rows, name, "exact (rejection)".into(), |r| {
            rayleigh::sample_dir(m, w_in, r)
        });
    }
    let direct = max_error(rayleigh::inverse_cdf_direct::<f32>, rayleigh_exact);
    row!(
        rows,
        "Rayleigh, direct (Cardano, cbrt)",
        format!("{direct:.1e}"),
        |r| { rayleigh::sample_dir(RayleighMethod::Direct, w_in, r) }
    );
    let mm = max_error(rayleigh::inverse_cdf_minimax::<f32>, rayleigh_exact);
    row!(
        rows,
        "Rayleigh, direct (minimax cube root)",
        format!("{mm:.1e}"),
        |r| { rayleigh::sample_dir(RayleighMethod::DirectMinimax, w_in, r) }
    );
    let fast = max_error(rayleigh::inverse_cdf_fast::<f32>, rayleigh_exact);
    row!(
        rows,
        "Rayleigh, direct (cbrt_fast)",
        format!("{fast:.1e}"),
        |r| { rayleigh::sample_dir(RayleighMethod::DirectFast, w_in, r) }
    );
    let te = max_error(rayleigh::inverse_cdf_table::<f32>, rayleigh_exact);
    row!(
        rows,
        "Rayleigh, built-in Hermite table (n = 128)",
        format!("{te:.1e}"),
        |r| { rayleigh::sample_dir(RayleighMethod::Table, w_in, r) }
    );
    for n in [8usize, 32] {
        let mut buf = vec![0.0f32; n + 1];
        let table = Table::rayleigh_cdf(&mut buf, n).unwrap();
        let err = max_error(|u| table.sample_cos(u), rayleigh_exact);
        row!(
            rows,
            format!("Rayleigh, Frisvad's table n = {n}"),
            format!("{err:.1e}"),
            |r| {
                let mu = table.sample_cos(f32::uniform(r));
                scatterkit::geometry::direction_about(w_in, mu, f32::TAU * f32::uniform(r))
            }
        );
    }
    let up = Vec3::new(0.0f32, 0.0, 1.0);
    row!(rows, "surface: Lambert", "exact".into(), |r| {
        scatterkit::surface::lambert_sample(up, f32::uniform(r), f32::uniform(r))
    });
    let spec = Vec3::new(0.6f32, 0.0, 0.8);
    row!(
        rows,
        "surface: Phong alpha = 1000, fold",
        "exact".into(),
        |r| scatterkit::surface::phong_sample(
            spec,
            up,
            1000.0,
            scatterkit::CrossingPolicy::Fold,
            f32::uniform(r),
            f32::uniform(r)
        )
    );
    let surf = scatterkit::Surface::new(
        scatterkit::SurfaceModel::Phong,
        1000.0f32,
        scatterkit::Fraction::Scalar(50e-9),
        scatterkit::CrossingPolicy::Fold,
    )
    .unwrap();
    let incident = Vec3::new(0.6f32, 0.0, -0.8);
    row!(
        rows,
        "surface: interact (Fresnel, scalar model, Phong)",
        "exact".into(),
        |r| surf
            .interact(incident, up, 1.5, 3.9, 600e-9, r)
            .map_or(up, |x| x.0)
    );
    let g = 0.7f32;
    let hg = Phase::henyey_greenstein(g).unwrap();
    let err = max_error(|u| hg.sample_cos(u), |u| hg_exact(g as f64, u));
    row!(
        rows,
        "Henyey-Greenstein g = 0.7",
        format!("{err:.1e}"),
        |r| hg.sample_dir(w_in, f32::uniform(r), f32::uniform(r)).0
    );
    rows
}

/// Inverse CDFs: ns per `sample_cos(u)` with u from the fast RNG, and max
/// error against the f64 sampler (itself within 10⁻¹³ of double-double).
fn inverse_rows() -> Vec<(String, f64, f64)> {
    let mut rows = Vec::new();
    let mut push = |name: String, f: &dyn Fn(f32) -> f32, exact: &dyn Fn(f64) -> f64| {
        let mut r = Xoshiro256PlusPlus::seed_from_u64(3);
        let ns = time_ns(|| f(f32::uniform(&mut r)));
        rows.push((name, ns, max_error(f, exact)));
    };
    let cases: Vec<(&str, Phase<f64>)> = vec![
        ("isotropic", Phase::isotropic()),
        (
            "Henyey-Greenstein g = 0.7",
            Phase::henyey_greenstein(0.7).unwrap(),
        ),
        ("Rayleigh (direct)", Phase::rayleigh()),
        (
            "Rayleigh depolarized rho = 0.028",
            Phase::rayleigh_depolarized(0.028).unwrap(),
        ),
        (
            "Cornette-Shanks g = 0.5",
            Phase::cornette_shanks(0.5).unwrap(),
        ),
        (
            "Draine g = 0.3, alpha = 250",
            Phase::draine(0.3, 250.0).unwrap(),
        ),
        (
            "Draine g = 0, alpha = 1000",
            Phase::draine(0.0, 1000.0).unwrap(),
        ),
        (
            "fog 2 um (exact mixture inverse)",
            Phase::fog_diameter(2.0).unwrap(),
        ),
    ];
    for (name, p64) in cases {
        // The f64 reference sees the parameters the f32 object holds.
        let p32: Phase<f32> = p64.cast();
        let reference: Phase<f64> = p32.cast();
        push(name.to_string(), &|u| p32.sample_cos(u), &|u| {
            reference.sample_cos(u)
        });
    }
    let fog32 = Phase::<f32>::fog_diameter(2.0).unwrap();
    let fog64: Phase<f64> = fog32.cast();
    push(
        "fog 2 um, paper's lobe sampler (not monotone)".into(),
        &|u| fog32.sample_cos_by_lobe(u),
        &|u| fog64.sample_cos_by_lobe(u),
    );
    for (g, a) in [(0.5f32, 1.0f32), (0.3, 250.0)] {
        let d64 = Phase::<f64>::draine(g as f64, a as f64).unwrap();
        push(
            format!("Draine g = {g}, alpha = {a}: eq. 6 as published"),
            &|u| scatterkit::phase::draine::sample_cos_eq6(g, a, u),
            &|u| d64.sample_cos(u),
        );
    }
    for n in [32usize, 64, 256] {
        let mut buf = vec![0.0f32; 2 * (n + 1)];
        let t = Table::inverse(&Phase::<f32>::rayleigh(), &mut buf, n).unwrap();
        push(
            format!("Rayleigh, Hermite inverse table n = {n}"),
            &|u| t.sample_cos(u),
            &rayleigh_exact,
        );
    }
    let mut buf = vec![0.0f32; 33];
    let t = Table::rayleigh_cdf(&mut buf, 32).unwrap();
    push(
        "Rayleigh, Frisvad's CDF table n = 32".into(),
        &|u| t.sample_cos(u),
        &rayleigh_exact,
    );
    for n in [64usize, 256, 1024] {
        let mut buf = vec![0.0f32; 2 * (n + 1)];
        let t = Table::inverse(&fog32, &mut buf, n).unwrap();
        push(
            format!("fog 2 um, Hermite inverse table n = {n}"),
            &|u| t.sample_cos(u),
            &|u| fog64.sample_cos(u),
        );
    }
    rows
}

/// Draine by rejection from HG: accept μ ~ HG(g) with probability
/// `(1 + αμ²)/(1 + α)`.
fn draine_by_rejection<R: TryRng<Error = Infallible>>(g: f32, alpha: f32, r: &mut R) -> f32 {
    let hg = Phase::henyey_greenstein(g).unwrap();
    loop {
        let mu = hg.sample_cos(f32::uniform(r));
        if f32::uniform(r) * (1.0 + alpha) <= 1.0 + alpha * mu * mu {
            return mu;
        }
    }
}

/// The three Draine samplers, ns per cosine with the fast RNG.
fn draine_rows() -> Vec<(String, f64)> {
    let mut rows = Vec::new();
    for (g, a) in [(0.5f32, 1.0f32), (0.9, 10.0), (0.3, 250.0), (0.01, 1000.0)] {
        let d = Phase::draine(g, a).unwrap();
        let mut r = Xoshiro256PlusPlus::seed_from_u64(4);
        let ours = time_ns(|| d.sample_cos(f32::uniform(&mut r)));
        let eq6 = time_ns(|| scatterkit::phase::draine::sample_cos_eq6(g, a, f32::uniform(&mut r)));
        let rej = time_ns(|| draine_by_rejection(g, a, &mut r));
        rows.push((format!("g = {g}, alpha = {a}: ours {ours:.1} | eq. 6 {eq6:.1} | HG rejection {rej:.1} | ours/eq. 6 {:.2}", ours / eq6), ours));
    }
    rows
}

/// Media: ns per call and per tracking step.
fn media_rows() -> Vec<(String, f64)> {
    use scatterkit::medium::{free_path, homogeneous_sample};
    let mut r = Xoshiro256PlusPlus::seed_from_u64(5);
    let mut rows = Vec::new();
    rows.push((
        "free path".to_string(),
        time_ns(|| free_path(2.0f32, f32::uniform(&mut r))),
    ));
    let (st, ss, mut w) = ([0.5f32, 1.0, 2.0], [0.4f32, 0.9, 1.5], [0.0f32; 3]);
    rows.push((
        "homogeneous sample, 3 channels".to_string(),
        time_ns(|| {
            homogeneous_sample(
                &st,
                &ss,
                1.0,
                f32::uniform(&mut r),
                f32::uniform(&mut r),
                &mut w,
            )
            .map_or(0.0, |s| s.t)
        }),
    ));
    let values: Vec<f32> = (0..16 * 16 * 16)
        .map(|i| ((i * 7919) % 101) as f32 / 100.0)
        .collect();
    let grid = scatterkit::Grid::new(&values, 16, 16, 16, 2.0, 14.0).unwrap();
    let (o, d) = (Vec3::new(-0.5f32, 0.31, 0.47), Vec3::new(1.0f32, 0.0, 0.0));
    let steps = grid.majorant() as f64; // expected tentative collisions across the cube
    let ns = time_ns(|| grid.ratio_track(o, d, 2.0, &mut r));
    rows.push(("ratio tracking, 16³ grid: per step".to_string(), ns / steps));
    rows
}

/// Cube roots: ns per call over inputs spread across [1e-6, 1e6], and max
/// error in ULP (relative to f32 spacing) against libm's correctly rounded f64.
fn cbrt_rows() -> Vec<(String, f64, f64)> {
    let xs: Vec<f32> = (0..4096).map(|i| 1e-6f32 * 1.0034f32.powi(i * 2)).collect();
    let ulp_error = |f: &dyn Fn(f32) -> f32| {
        (1u32..0x7f80_0000)
            .step_by(101)
            .map(|b| {
                let x = f32::from_bits(b);
                let exact = libm::cbrt(x as f64);
                let ulp = 2f64.powi(((exact as f32).to_bits() >> 23) as i32 - 150);
                (f(x) as f64 - exact).abs() / ulp
            })
            .fold(0.0, f64::max)
    };
    let mut rows = Vec::new();
    let cases: [(&str, &dyn Fn(f32) -> f32); 4] = [
        ("scatterkit cbrt (2 steps)", &|x| {
            scatterkit::cbrt::cbrt_f32(x)
        }),
        ("scatterkit cbrt_fast (1 step)", &|x| {
            scatterkit::cbrt::cbrt_fast_f32(x)
        }),
        ("libm cbrtf", &|x| libm::cbrtf(x)),
        ("powf(x, 1/3)", &|x| libm::powf(x, 1.0 / 3.0)),
    ];
    for (name, f) in cases {
        let mut i = 0usize;
        let ns = time_ns(|| {
            i = (i + 1) & 4095;
            f(black_box(xs[i]))
        });
        rows.push((name.to_string(), ns, ulp_error(f)));
    }
    rows
}

fn main() {
    println!(
        "scatterkit {} — speed against accuracy (f32)\n",
        env!("CARGO_PKG_VERSION")
    );
    let rows = direction_rows();
    let base = rows
        .iter()
        .find(|r| r.name.contains("simplified"))
        .map(|r| (r.fast_ns, r.slow_ns))
        .unwrap();
    println!(
        "Directions: ns per sample (median of {REPEATS} × 2^20), and speed relative to simplified rejection"
    );
    println!();
    println!(
        "| method | ns, xoshiro256++ | × simplified | ns, slow rand() | × simplified | max abs error in cos θ |"
    );
    println!("|---|---:|---:|---:|---:|---|");
    for r in &rows {
        println!(
            "| {} | {:.2} | {:.2} | {:.2} | {:.2} | {} |",
            r.name,
            r.fast_ns,
            base.0 / r.fast_ns,
            r.slow_ns,
            base.1 / r.slow_ns,
            r.accuracy
        );
    }
    println!();
    println!("Inverse CDFs (f32): ns per sample_cos(u), max |cos θ error| against the f64 sampler");
    println!();
    println!("| sampler | ns | max abs error |");
    println!("|---|---:|---:|");
    for (name, ns, err) in inverse_rows() {
        println!("| {name} | {ns:.2} | {err:.1e} |");
    }
    println!();
    println!("Draine samplers (f32), ns per cosine:");
    for (line, _) in draine_rows() {
        println!("  {line}");
    }
    println!();
    println!("Media (f32): ns per call");
    println!();
    println!("| operation | ns |");
    println!("|---|---:|");
    for (name, ns) in media_rows() {
        println!("| {name} | {ns:.2} |");
    }
    println!();
    println!("Cube roots: ns per call and max error (ULP of f32, every 101st positive float)");
    println!();
    println!("| cube root | ns | max ULP |");
    println!("|---|---:|---:|");
    for (name, ns, ulp) in cbrt_rows() {
        println!("| {name} | {ns:.2} | {ulp:.2} |");
    }
}
