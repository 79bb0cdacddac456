//! Speed against accuracy: every sampler of scatterkit beside the peers'
//! formulas (Mitsuba 3, Cycles, pbrt-v4, Draine eq. 6, Draine by rejection)
//! and Frisvad's Table 1 (JOSA A 2011) re-run today, in one run.
//!
//!     cargo run --release --example speed_accuracy
//!
//! Prints markdown tables and writes `docs/speed_accuracy.csv`,
//! `docs/speed_accuracy.svg` (one log-log panel per family: ns per sample
//! against max error, Rust calls and calls through the C ABI, the Pareto
//! frontier drawn) and `docs/PERFORMANCE.md` (Frisvad's ratios, the
//! project's speed targets and the C view, computed from this run). The C
//! view is `benches/c_abi.c`, built here with the `cc` crate at `-O2` against
//! `libscatterkit.a` and run once.
//!
//! Speed: ns per sample, the fastest of 15 runs of 2¹⁸ samples, f32, xoshiro256++
//! (and a deliberately slow generator in the spirit of the paper's C
//! `rand()`). Accuracy: max |cos θ − exact| and max |F(μ(u)) − u| over 2²⁰ + 1
//! evenly spaced u including 0 and 1, against an f64 evaluation of the exact
//! inverse (itself within 10⁻¹³ of double-double; see the tests). Rejection
//! methods are exact in distribution; they are plotted at f32's rounding
//! floor (half an ULP of 1) and marked so.

#[path = "../benches/cloud.rs"]
mod cloud;
#[path = "../benches/peers.rs"]
mod peers;

use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{SeedableRng, TryRng};
use scatterkit::{Grid, Phase, PhaseFunction, RayleighMethod, Real, Table, Vec3, rayleigh};
use std::convert::Infallible;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

/// Accuracy: errors over `SAMPLES + 1` evenly spaced u.
const SAMPLES: usize = 1 << 20;
/// Speed: the fastest of `REPEATS` runs of `TIMED` calls. This shared
/// machine's noise only ever adds time (single runs vary by up to 2×), so
/// the minimum of many short runs is the stable figure, as in the C
/// benchmark.
const TIMED: usize = 1 << 18;
const REPEATS: usize = 15;
/// Where rejection samplers are plotted: half an ULP of 1 in f32.
const FLOOR: f64 = 5.960_464_477_539_063e-8;

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

/// Nanoseconds per call of `f` over one run of `TIMED` calls.
fn run_once(mut f: impl FnMut() -> f32) -> f64 {
    let start = Instant::now();
    let mut acc = 0.0f32;
    for _ in 0..TIMED {
        acc += f();
    }
    black_box(acc);
    start.elapsed().as_nanos() as f64 / TIMED as f64
}

/// Nanoseconds per call of `f`: the fastest of `REPEATS` runs of `TIMED` calls.
fn time_ns(mut f: impl FnMut() -> f32) -> f64 {
    interleaved([&mut || run_once(&mut f)])[0]
}

/// The fastest of `REPEATS` runs of each timer (each returns ns per call of
/// one run), the timers taking turns within every round: the machine's
/// drift over a run then falls on all of them alike, which is what makes
/// their ratios comparable. The targets are measured this way.
fn interleaved<const N: usize>(mut timers: [&mut dyn FnMut() -> f64; N]) -> [f64; N] {
    let mut best = [f64::INFINITY; N];
    for _ in 0..REPEATS {
        for (b, t) in best.iter_mut().zip(timers.iter_mut()) {
            *b = b.min(t());
        }
    }
    best
}

/// The Rust-side targets' samplers, re-timed in interleaved pairs.
struct Pairs {
    /// Directions: simplified rejection, built-in table, isotropic.
    simplified: f64,
    table_dir: f64,
    iso_dir: f64,
    /// Cos θ: Hermite table n = 64, Frisvad's table n = 32.
    hermite64: f64,
    frisvad32: f64,
    /// Cube roots: ours, libm, powf.
    cbrt: [f64; 3],
    /// Draine against eq. 6 at (0.5, 1) and (0.9, 10).
    draine: [(f64, f64); 2],
    /// HG g = 0.7 (the model itself) against pbrt-v4's formula.
    hg: (f64, f64),
}

fn pairs() -> Pairs {
    let w = Vec3::new(0.48f32, 0.6, 0.64);
    let (mut r1, mut r2, mut r3) = (fast_rng(), fast_rng(), fast_rng());
    let iso = Phase::<f32>::isotropic();
    let [simplified, table_dir, iso_dir] = interleaved([
        &mut || run_once(|| rayleigh::sample_dir(RayleighMethod::Simplified, w, &mut r1).z),
        &mut || run_once(|| rayleigh::sample_dir(RayleighMethod::Table, w, &mut r2).z),
        &mut || {
            run_once(|| {
                iso.sample_dir(w, f32::uniform(&mut r3), f32::uniform(&mut r3))
                    .0
                    .z
            })
        },
    ]);
    let (mut b64, mut b32) = (vec![0.0f32; 2 * 65], vec![0.0f32; 33]);
    let h64 = Table::inverse(&Phase::<f32>::rayleigh(), &mut b64, 64).unwrap();
    let f32t = Table::rayleigh_cdf(&mut b32, 32).unwrap();
    let (mut r1, mut r2) = (fast_rng(), fast_rng());
    let [hermite64, frisvad32] = interleaved([
        &mut || run_once(|| h64.sample_cos(f32::uniform(&mut r1))),
        &mut || run_once(|| f32t.sample_cos(f32::uniform(&mut r2))),
    ]);
    let xs: Vec<f32> = (0..4096).map(|i| 1e-6f32 * 1.0034f32.powi(i * 2)).collect();
    let (mut i1, mut i2, mut i3) = (0usize, 0usize, 0usize);
    let next = |i: &mut usize| {
        *i = (*i + 1) & 4095;
        black_box(xs[*i])
    };
    let cbrt = interleaved([
        &mut || run_once(|| scatterkit::cbrt::cbrt_f32_steps(next(&mut i1), 2)),
        &mut || run_once(|| libm::cbrtf(next(&mut i2))),
        &mut || run_once(|| libm::powf(next(&mut i3), 1.0 / 3.0)),
    ]);
    let draine = [(0.5f32, 1.0f32), (0.9, 10.0)].map(|(g, a)| {
        let d = Phase::draine(g, a).unwrap();
        let (mut r1, mut r2) = (fast_rng(), fast_rng());
        let [x, y] = interleaved([
            &mut || run_once(|| d.sample_cos(f32::uniform(&mut r1))),
            &mut || {
                run_once(|| scatterkit::phase::draine::sample_cos_eq6(g, a, f32::uniform(&mut r2)))
            },
        ]);
        (x, y)
    });
    let hg32 = scatterkit::HenyeyGreenstein::new(0.7f32).unwrap();
    let (mut r1, mut r2) = (fast_rng(), fast_rng());
    let [a, b] = interleaved([
        &mut || run_once(|| hg32.sample_cos(f32::uniform(&mut r1))),
        &mut || run_once(|| peers::pbrt_v4_hg(0.7, f32::uniform(&mut r2))),
    ]);
    Pairs {
        simplified,
        table_dir,
        iso_dir,
        hermite64,
        frisvad32,
        cbrt,
        draine,
        hg: (a, b),
    }
}

/// `(max |f(u) − μ(u)|, max |F(f(u)) − u|)` over an even grid of u.
fn errors(
    f: impl Fn(f32) -> f32,
    exact: impl Fn(f64) -> f64,
    cdf: impl Fn(f64) -> f64,
) -> (f64, f64) {
    (0..=SAMPLES).fold((0.0, 0.0), |(e, c), i| {
        let u = i as f32 / SAMPLES as f32;
        let mu = f(u) as f64;
        let uu = u as f64;
        (
            f64::max(e, (mu - exact(uu)).abs()),
            f64::max(c, (cdf(mu.clamp(-1.0, 1.0)) - uu).abs()),
        )
    })
}

/// Rayleigh's exact inverse and CDF in f64.
fn rayleigh_exact(u: f64) -> f64 {
    let s = 2.0 * (2.0 * u - 1.0);
    let w = libm::cbrt(s.abs() + (s * s + 1.0).sqrt());
    (w - 1.0 / w).copysign(s)
}
fn rayleigh_cdf(x: f64) -> f64 {
    (1.0 + x) * (x * x - x + 4.0) / 8.0
}

/// One measured method.
struct Entry {
    family: &'static str,
    name: String,
    /// ns per cos θ (inverse CDF or rejection), fast RNG.
    ns: f64,
    /// ns per direction with the fast and the slow RNG, where measured.
    dir_ns: Option<(f64, f64)>,
    err: f64,
    cdf_err: f64,
    /// Exact in distribution (rejection): plotted at the floor.
    rejection: bool,
    /// Part of a curve (tables by n, cube-root steps) rather than a point.
    curve: Option<&'static str>,
    /// Measured from C through the header (drawn as a triangle).
    c_abi: bool,
}

impl Entry {
    fn new(
        family: &'static str,
        name: impl Into<String>,
        ns: f64,
        (err, cdf_err): (f64, f64),
    ) -> Entry {
        Entry {
            family,
            name: name.into(),
            ns,
            dir_ns: None,
            err,
            cdf_err,
            rejection: false,
            curve: None,
            c_abi: false,
        }
    }
    fn rejection(family: &'static str, name: impl Into<String>, ns: f64) -> Entry {
        Entry {
            family,
            name: name.into(),
            ns,
            dir_ns: None,
            err: FLOOR,
            cdf_err: FLOOR,
            rejection: true,
            curve: None,
            c_abi: false,
        }
    }
}

/// Times `$sample` (an expression in the RNG `$r` giving a `Vec3<f32>`) with
/// both generators; a macro so each loop is monomorphised for its RNG.
macro_rules! dir_ns {
    (|$r:ident| $sample:expr) => {{
        let mut fast = Xoshiro256PlusPlus::seed_from_u64(1);
        let mut slow = SlowRand::new(1);
        let f = {
            let $r = &mut fast;
            time_ns(|| $sample.z)
        };
        let s = {
            let $r = &mut slow;
            time_ns(|| $sample.z)
        };
        (f, s)
    }};
}

fn fast_rng() -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(3)
}

/// Every Rayleigh method, peers and tables: cos θ and direction timings.
fn rayleigh_entries(out: &mut Vec<Entry>) {
    let w_in = Vec3::new(0.48f32, 0.6, 0.64);
    let names = [
        (RayleighMethod::RejectCube, "von Neumann cube"),
        (RayleighMethod::RejectSpherical, "spherical coordinates"),
        (RayleighMethod::Baranoski, "Baranoski (corrected)"),
        (RayleighMethod::Simplified, "simplified rejection"),
        (RayleighMethod::Direct, "direct (Cardano, cbrt)"),
        (RayleighMethod::DirectFast, "direct (cbrt_fast)"),
        (RayleighMethod::DirectMinimax, "direct (sqrt-free minimax)"),
        (RayleighMethod::Table, "built-in Hermite table n = 128"),
    ];
    for (m, name) in names {
        let mut r = fast_rng();
        let ns = time_ns(|| rayleigh::sample_cos::<f32, _>(m, &mut r));
        let mut e = match m {
            RayleighMethod::Direct => Entry::new(
                "Rayleigh",
                name,
                ns,
                errors(
                    rayleigh::inverse_cdf_direct::<f32>,
                    rayleigh_exact,
                    rayleigh_cdf,
                ),
            ),
            RayleighMethod::DirectFast => Entry::new(
                "Rayleigh",
                name,
                ns,
                errors(
                    rayleigh::inverse_cdf_fast::<f32>,
                    rayleigh_exact,
                    rayleigh_cdf,
                ),
            ),
            RayleighMethod::DirectMinimax => Entry::new(
                "Rayleigh",
                name,
                ns,
                errors(
                    rayleigh::inverse_cdf_minimax::<f32>,
                    rayleigh_exact,
                    rayleigh_cdf,
                ),
            ),
            RayleighMethod::Table => Entry::new(
                "Rayleigh",
                name,
                ns,
                errors(
                    rayleigh::inverse_cdf_table::<f32>,
                    rayleigh_exact,
                    rayleigh_cdf,
                ),
            ),
            _ => Entry::rejection("Rayleigh", name, ns),
        };
        e.dir_ns = Some(dir_ns!(|r| rayleigh::sample_dir(m, w_in, r)));
        out.push(e);
    }
    // Direct with the paper's `pow` cube root, for Frisvad's Kahan comparison.
    let pow_direct = |u: f32| {
        let s = 2.0 * (2.0 * u - 1.0);
        let w = libm::powf(s.abs() + libm::sqrtf(s * s + 1.0), 1.0 / 3.0);
        ((w - 1.0 / w).abs()).copysign(s).clamp(-1.0, 1.0)
    };
    let peers: [(&str, &dyn Fn(f32) -> f32); 3] = [
        ("direct (Cardano, powf cube root)", &pow_direct),
        ("peer: Mitsuba 3 (two cube roots)", &peers::mitsuba_rayleigh),
        (
            "peer: Cycles (fast inverse cube root)",
            &peers::cycles_rayleigh,
        ),
    ];
    for (name, f) in peers {
        let mut r = fast_rng();
        let ns = time_ns(|| f(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "Rayleigh",
            name,
            ns,
            errors(f, rayleigh_exact, rayleigh_cdf),
        );
        e.dir_ns = Some(dir_ns!(|r| scatterkit::geometry::direction_about(
            w_in,
            f(f32::uniform(r)),
            f32::TAU * f32::uniform(r)
        )));
        out.push(e);
    }
    let iso = Phase::<f32>::isotropic();
    let mut r = fast_rng();
    let mut e = Entry::new(
        "isotropic",
        "isotropic (floor)",
        time_ns(|| iso.sample_cos(f32::uniform(&mut r))),
        (0.0, 0.0),
    );
    e.dir_ns = Some(dir_ns!(|r| iso
        .sample_dir(w_in, f32::uniform(r), f32::uniform(r))
        .0));
    out.push(e);
    for n in [8usize, 16, 32, 64, 128, 256, 512, 1024] {
        let mut buf = vec![0.0f32; n + 1];
        let t = Table::rayleigh_cdf(&mut buf, n).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| t.sample_cos(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "Rayleigh",
            format!("Frisvad's CDF table n = {n}"),
            ns,
            errors(|u| t.sample_cos(u), rayleigh_exact, rayleigh_cdf),
        );
        e.curve = Some("Frisvad's CDF table, n = 8…1024");
        if n == 8 || n == 32 {
            e.dir_ns = Some(dir_ns!(|r| scatterkit::geometry::direction_about(
                w_in,
                t.sample_cos(f32::uniform(r)),
                f32::TAU * f32::uniform(r)
            )));
        }
        out.push(e);
        let mut hbuf = vec![0.0f32; 2 * (n + 1)];
        let h = Table::inverse(&Phase::<f32>::rayleigh(), &mut hbuf, n).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| h.sample_cos(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "Rayleigh",
            format!("Hermite inverse table n = {n}"),
            ns,
            errors(|u| h.sample_cos(u), rayleigh_exact, rayleigh_cdf),
        );
        e.curve = Some("Hermite inverse table, n = 8…1024");
        out.push(e);
    }
}

/// HG: ours against pbrt-v4's formula, at several g.
fn hg_entries(out: &mut Vec<Entry>) {
    for g in [0.7f32, 1e-3, -0.99] {
        let p32 = Phase::henyey_greenstein(g).unwrap();
        let p64 = Phase::<f64>::henyey_greenstein(g as f64).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| p32.sample_cos(f32::uniform(&mut r)));
        out.push(Entry::new(
            "HG",
            format!("HG g = {g}"),
            ns,
            errors(|u| p32.sample_cos(u), |u| p64.sample_cos(u), |x| p64.cdf(x)),
        ));
        let mut r = fast_rng();
        let ns = time_ns(|| peers::pbrt_v4_hg(g, f32::uniform(&mut r)));
        out.push(Entry::new(
            "HG",
            format!("peer: pbrt-v4 HG g = {g}"),
            ns,
            errors(
                |u| peers::pbrt_v4_hg(g, u),
                |u| p64.sample_cos(u),
                |x| p64.cdf(x),
            ),
        ));
    }
}

/// Draine: ours, eq. 6 as published, rejection from HG; and the fog.
fn draine_entries(out: &mut Vec<Entry>) {
    for (g, a) in [(0.5f32, 1.0f32), (0.9, 10.0), (0.3, 250.0), (0.01, 1000.0)] {
        let d32 = Phase::draine(g, a).unwrap();
        let d64: Phase<f64> = d32.cast();
        let mut r = fast_rng();
        let ns = time_ns(|| d32.sample_cos(f32::uniform(&mut r)));
        out.push(Entry::new(
            "Draine",
            format!("Draine g = {g}, α = {a}"),
            ns,
            errors(|u| d32.sample_cos(u), |u| d64.sample_cos(u), |x| d64.cdf(x)),
        ));
        let eq6 = |u: f32| scatterkit::phase::draine::sample_cos_eq6(g, a, u);
        let mut r = fast_rng();
        let ns = time_ns(|| eq6(f32::uniform(&mut r)));
        let (e, c) = errors(eq6, |u| d64.sample_cos(u), |x| d64.cdf(x));
        // NaN outputs count as an error of 2 (the whole range).
        let fix = |x: f64| if x.is_finite() { x } else { 2.0 };
        out.push(Entry::new(
            "Draine",
            format!("peer: eq. 6 as published g = {g}, α = {a}"),
            ns,
            (fix(e), fix(c)),
        ));
        let mut r = fast_rng();
        let ns = time_ns(|| peers::draine_rejection(g, a, || f32::uniform(&mut r)));
        out.push(Entry::rejection(
            "Draine",
            format!("peer: rejection from HG g = {g}, α = {a}"),
            ns,
        ));
    }
    let fog32 = Phase::<f32>::fog_diameter(2.0).unwrap();
    let fog64: Phase<f64> = fog32.cast();
    let mut r = fast_rng();
    let ns = time_ns(|| fog32.sample_cos(f32::uniform(&mut r)));
    out.push(Entry::new(
        "fog",
        "fog 2 µm (exact inverse)",
        ns,
        errors(
            |u| fog32.sample_cos(u),
            |u| fog64.sample_cos(u),
            |x| fog64.cdf(x),
        ),
    ));
    let mut r = fast_rng();
    let ns = time_ns(|| fog32.sample_cos_by_lobe(f32::uniform(&mut r)));
    out.push(Entry::rejection(
        "fog",
        "fog 2 µm (paper's lobe choice)",
        ns,
    ));
    for n in [64usize, 256, 1024] {
        let mut buf = vec![0.0f32; 2 * (n + 1)];
        let t = Table::inverse(&fog32, &mut buf, n).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| t.sample_cos(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "fog",
            format!("fog 2 µm Hermite table n = {n}"),
            ns,
            errors(
                |u| t.sample_cos(u),
                |u| fog64.sample_cos(u),
                |x| fog64.cdf(x),
            ),
        );
        e.curve = Some("fog 2 µm Hermite table, n = 64…1024");
        out.push(e);
    }
}

/// Cube roots: ns per call (inputs over [1e-6, 1e6]) and max error in f32
/// ULP (every 101st positive float); our step counts as a curve.
fn cbrt_entries(out: &mut Vec<Entry>) {
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
    let time = |f: &dyn Fn(f32) -> f32| {
        let mut i = 0usize;
        time_ns(|| {
            i = (i + 1) & 4095;
            f(black_box(xs[i]))
        })
    };
    let cases: [(&str, &dyn Fn(f32) -> f32); 3] = [
        ("libm cbrtf", &libm::cbrtf),
        ("powf(x, 1/3)", &|x| libm::powf(x, 1.0 / 3.0)),
        (
            "peer: Cycles 1/fast_inv_cbrt (all floats; made for [1, 4.3])",
            &|x| 1.0 / peers::fast_inv_cbrt(x),
        ),
    ];
    for (name, f) in cases {
        let ns = time(f);
        out.push(Entry::new("cbrt", name, ns, (ulp_error(f), f64::NAN)));
    }
    for steps in 0..=3u32 {
        let f = move |x: f32| scatterkit::cbrt::cbrt_f32_steps(x, steps);
        let ns = time(&f);
        let mut e = Entry::new(
            "cbrt",
            format!("scatterkit Kahan + {steps} steps"),
            ns,
            (ulp_error(&f), f64::NAN),
        );
        e.curve = Some("scatterkit cube root, 0…3 Lancaster steps");
        out.push(e);
    }
}

/// Batch against scalar: ns per element of `batch` over 4096 u and of 4096
/// calls of `scalar`.
fn batch_ratio(batch: impl Fn(&[f32], &mut [f32]), scalar: impl Fn(f32) -> f32) -> (f64, f64) {
    let u: Vec<f32> = (0..4096).map(|i| (i as f32 + 0.5) / 4096.0).collect();
    let mut out = vec![0.0f32; 4096];
    let reps = 64;
    let mut batch_ns = Vec::new();
    let mut scalar_ns = Vec::new();
    for _ in 0..REPEATS {
        let t = Instant::now();
        for _ in 0..reps {
            batch(black_box(&u), &mut out);
            black_box(&out);
        }
        batch_ns.push(t.elapsed().as_nanos() as f64 / (reps * 4096) as f64);
        let t = Instant::now();
        for _ in 0..reps {
            for (o, &x) in out.iter_mut().zip(&u) {
                *o = scalar(black_box(x));
            }
            black_box(&out);
        }
        scalar_ns.push(t.elapsed().as_nanos() as f64 / (reps * 4096) as f64);
    }
    batch_ns.sort_by(f64::total_cmp);
    scalar_ns.sort_by(f64::total_cmp);
    (batch_ns[0], scalar_ns[0])
}

/// The C view: `benches/c_abi.c` built at `-O2` like a renderer would
/// build it, linked against `libscatterkit.a` (built here with the release
/// profile), run once. Returns `key → (ns, max error)`; an error below 0
/// means not measured (rejection).
fn c_abi() -> std::collections::BTreeMap<String, (f64, f64)> {
    use std::path::{Path, PathBuf};
    use std::process::Command;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    // The example runs from <target>/release/examples/.
    let exe = std::env::current_exe().expect("current exe");
    let target: PathBuf = exe.ancestors().nth(3).expect("target dir").to_path_buf();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let ok = Command::new(cargo)
        .args([
            "build",
            "--release",
            "-p",
            "scatterkit-capi",
            "--target-dir",
        ])
        .arg(&target)
        .current_dir(root)
        .status()
        .expect("cargo build of the C library failed to start")
        .success();
    assert!(ok, "cargo build -p scatterkit-capi failed");
    let host = String::from_utf8(Command::new("rustc").arg("-vV").output().unwrap().stdout)
        .unwrap()
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))
        .expect("host triple");
    let out_dir = target.join("c_abi_bench");
    std::fs::create_dir_all(&out_dir).unwrap();
    let bin = out_dir.join("c_abi");
    let compiler = cc::Build::new()
        .target(&host)
        .host(&host)
        .opt_level(2)
        .out_dir(&out_dir)
        .cargo_metadata(false)
        .get_compiler();
    let status = compiler
        .to_command()
        .args(["-std=c99", "-D_POSIX_C_SOURCE=199309L"])
        .arg("-I")
        .arg(root.join("include"))
        .arg(root.join("benches/c_abi.c"))
        .arg("-o")
        .arg(&bin)
        .arg(target.join("release/libscatterkit.a"))
        .args(["-lpthread", "-ldl", "-lm"])
        .status()
        .expect("C compiler failed to start");
    assert!(status.success(), "compiling benches/c_abi.c failed");
    let run = Command::new(&bin)
        .output()
        .expect("C benchmark failed to start");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            (
                f[0].to_string(),
                (f[1].parse().unwrap(), f[2].parse().unwrap()),
            )
        })
        .collect()
}

/// What each C measurement is, for the tables and the chart:
/// `(key, family, label, is a cos θ sampler)`.
const C_KEYS: [(&str, &str, &str, bool); 29] = [
    (
        "iso_dir.sk",
        "isotropic",
        "isotropic direction, sk_phase_sample_dir",
        false,
    ),
    (
        "iso_dir.c",
        "isotropic",
        "peer: isotropic direction, inline C (glibc sinf/cosf)",
        false,
    ),
    (
        "hg_dir.sk",
        "HG",
        "HG g = 0.7 direction, sk_phase_sample_dir",
        false,
    ),
    (
        "hg_dir.pbrt",
        "HG",
        "peer: pbrt-v4 HG g = 0.7 direction, inline C",
        false,
    ),
    ("hg_cos.sk", "HG", "HG g = 0.7, sk_phase_sample_cos", true),
    (
        "hg_cos.pbrt",
        "HG",
        "peer: pbrt-v4 HG g = 0.7 cos θ, inline C",
        true,
    ),
    (
        "hg_cos_n.sk",
        "HG",
        "HG g = 0.7, sk_phase_sample_cos_n (4096)",
        true,
    ),
    (
        "hg_cos_n.pbrt",
        "HG",
        "peer: pbrt-v4 HG g = 0.7 cos θ loop, inline C",
        true,
    ),
    (
        "hg_dir_n.sk",
        "HG",
        "HG g = 0.7 directions, sk_phase_sample_dir_n (4096)",
        false,
    ),
    (
        "hg_dir_n.pbrt",
        "HG",
        "peer: pbrt-v4 HG g = 0.7 direction loop, inline C",
        false,
    ),
    (
        "rayleigh_dir.sk",
        "Rayleigh",
        "Rayleigh direction, sk_phase_sample_dir",
        false,
    ),
    (
        "rayleigh_dir.mitsuba",
        "Rayleigh",
        "peer: Mitsuba 3 Rayleigh direction, inline C",
        false,
    ),
    (
        "rayleigh_dir.cycles",
        "Rayleigh",
        "peer: Cycles Rayleigh direction, inline C",
        false,
    ),
    (
        "rayleigh_dir.simplified",
        "Rayleigh",
        "peer: Frisvad simplified rejection direction, inline C",
        false,
    ),
    (
        "rayleigh_rng_dir.direct",
        "Rayleigh",
        "sk_rayleigh_sample_dir DIRECT (sk_rng)",
        false,
    ),
    (
        "rayleigh_rng_dir.minimax",
        "Rayleigh",
        "sk_rayleigh_sample_dir DIRECT_MINIMAX (sk_rng)",
        false,
    ),
    (
        "rayleigh_rng_dir.table",
        "Rayleigh",
        "sk_rayleigh_sample_dir TABLE (sk_rng)",
        false,
    ),
    (
        "rayleigh_rng_dir.simplified_callback",
        "Rayleigh",
        "peer: simplified rejection drawing through sk_rng, inline C",
        false,
    ),
    (
        "rayleigh_rng_dir_n.table",
        "Rayleigh",
        "sk_rayleigh_sample_dir_n TABLE (sk_rng, 4096)",
        false,
    ),
    (
        "fog_cos.sk",
        "fog",
        "fog 2 µm, sk_phase_sample_cos (monotone inverse)",
        true,
    ),
    (
        "fog_cos.lobe",
        "fog",
        "fog 2 µm, sk_phase_sample_cos_lobe (paper's lobe choice)",
        true,
    ),
    (
        "draine_0.5_1.sk",
        "Draine",
        "Draine g = 0.5, α = 1, sk_phase_sample_cos",
        true,
    ),
    (
        "draine_0.5_1.eq6",
        "Draine",
        "peer: eq. 6 g = 0.5, α = 1, inline C",
        true,
    ),
    (
        "draine_0.9_10.sk",
        "Draine",
        "Draine g = 0.9, α = 10, sk_phase_sample_cos",
        true,
    ),
    (
        "draine_0.9_10.eq6",
        "Draine",
        "peer: eq. 6 g = 0.9, α = 10, inline C",
        true,
    ),
    (
        "draine_0.3_250.sk",
        "Draine",
        "Draine g = 0.3, α = 250, sk_phase_sample_cos",
        true,
    ),
    (
        "draine_0.3_250.eq6",
        "Draine",
        "peer: eq. 6 g = 0.3, α = 250, inline C",
        true,
    ),
    (
        "draine_0.01_1000.sk",
        "Draine",
        "Draine g = 0.01, α = 1000, sk_phase_sample_cos",
        true,
    ),
    (
        "draine_0.01_1000.eq6",
        "Draine",
        "peer: eq. 6 g = 0.01, α = 1000, inline C",
        true,
    ),
];

fn find<'a>(es: &'a [Entry], name: &str) -> &'a Entry {
    es.iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("no entry {name}"))
}

fn fmt_err(e: &Entry) -> String {
    if e.rejection {
        "exact (rejection)".into()
    } else if e.err.is_nan() {
        "—".into()
    } else {
        format!("{:.1e}", e.err)
    }
}

fn main() -> std::io::Result<()> {
    let start = Instant::now();
    let mut es = Vec::new();
    rayleigh_entries(&mut es);
    hg_entries(&mut es);
    draine_entries(&mut es);
    cbrt_entries(&mut es);
    let minimax = RayleighMethod::DirectMinimax;
    let rayleigh_batch = batch_ratio(
        |u, out| rayleigh::inverse_cdf_fill(minimax, u, out),
        rayleigh::inverse_cdf_minimax,
    );
    let hg = Phase::<f32>::henyey_greenstein(0.7).unwrap();
    let hg_batch = batch_ratio(
        |u, out| hg.sample_cos_n(u, out).unwrap(),
        |u| hg.sample_cos(u),
    );
    let c = c_abi();
    for (key, family, label, is_cos) in C_KEYS {
        let &(ns, err) = c
            .get(key)
            .unwrap_or_else(|| panic!("the C benchmark gave no {key}"));
        if !is_cos {
            continue;
        }
        let mut e = if err < 0.0 {
            Entry::rejection(family, format!("C ABI: {label}"), ns)
        } else {
            Entry::new(family, format!("C ABI: {label}"), ns, (err, f64::NAN))
        };
        e.c_abi = true;
        es.push(e);
    }

    let mut md = String::new();
    writeln!(
        md,
        "### Directions (f32): ns per direction, and speed relative to simplified rejection\n"
    )
    .unwrap();
    writeln!(md, "| method | ns, xoshiro256++ | × simplified | ns, slow rand() | × simplified | max abs error in cos θ |").unwrap();
    writeln!(md, "|---|---:|---:|---:|---:|---|").unwrap();
    let simp = find(&es, "simplified rejection").dir_ns.unwrap();
    for e in es.iter().filter(|e| e.dir_ns.is_some()) {
        let (f, s) = e.dir_ns.unwrap();
        writeln!(
            md,
            "| {} | {f:.2} | {:.2} | {s:.2} | {:.2} | {} |",
            e.name,
            simp.0 / f,
            simp.1 / s,
            fmt_err(e)
        )
        .unwrap();
    }
    writeln!(
        md,
        "\n### Cosines (f32): ns per cos θ, max |cos θ error|, max |F(μ(u)) − u|\n"
    )
    .unwrap();
    writeln!(
        md,
        "| family | method | ns | max abs error | max CDF error |"
    )
    .unwrap();
    writeln!(md, "|---|---|---:|---:|---:|").unwrap();
    for e in es.iter().filter(|e| e.family != "cbrt") {
        let cdf = if e.rejection {
            "exact (rejection)".into()
        } else {
            format!("{:.1e}", e.cdf_err)
        };
        writeln!(
            md,
            "| {} | {} | {:.2} | {} | {} |",
            e.family,
            e.name,
            e.ns,
            fmt_err(e),
            cdf
        )
        .unwrap();
    }
    writeln!(
        md,
        "\n### Cube roots (f32): ns per call, max error in ULP\n"
    )
    .unwrap();
    writeln!(md, "| cube root | ns | max ULP |").unwrap();
    writeln!(md, "|---|---:|---:|").unwrap();
    for e in es.iter().filter(|e| e.family == "cbrt") {
        writeln!(md, "| {} | {:.2} | {:.2} |", e.name, e.ns, e.err).unwrap();
    }
    writeln!(
        md,
        "\n### Batches (f32, 4096 uniforms): ns per element\n\n| sampler | batch | scalar calls | batch speed-up |\n|---|---:|---:|---:|\n\
         | Rayleigh direct (sqrt-free minimax, `rayleigh::inverse_cdf_fill`) | {:.2} | {:.2} | {:.2}× |\n| HG g = 0.7 | {:.2} | {:.2} | {:.2}× |",
        rayleigh_batch.0,
        rayleigh_batch.1,
        rayleigh_batch.1 / rayleigh_batch.0,
        hg_batch.0,
        hg_batch.1,
        hg_batch.1 / hg_batch.0
    )
    .unwrap();
    print!("{md}");

    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    std::fs::create_dir_all(&docs)?;
    std::fs::write(docs.join("speed_accuracy.csv"), csv(&es))?;
    std::fs::write(docs.join("speed_accuracy.svg"), svg(&es))?;
    let pairs = pairs();
    let c_md = c_tables(&c, &pairs);
    print!("{c_md}");
    let media_md = media_report();
    print!("{media_md}");
    let perf = performance(&es, rayleigh_batch, hg_batch, &pairs)
        + &c_md
        + &frontier_peers(&es)
        + &media_md;
    std::fs::write(docs.join("PERFORMANCE.md"), &perf)?;
    println!(
        "\n{}",
        perf.split_once("## Targets")
            .map_or("", |(_, t)| t)
            .trim_start_matches(|c| c != '|')
    );
    println!(
        "wrote docs/speed_accuracy.csv, docs/speed_accuracy.svg, docs/PERFORMANCE.md in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The C view as markdown: every measurement, then the targets of the
/// C-ABI speed work as ratios from this run.
fn c_tables(c: &std::collections::BTreeMap<String, (f64, f64)>, p: &Pairs) -> String {
    let ns = |k: &str| c[k].0;
    let mut s = String::from(
        "\n## Through the C ABI\n\n`benches/c_abi.c`, compiled with `cc -O2` and linked against \
         `libscatterkit.a`, calls the library through `include/scatterkit.h` beside the peers' \
         formulas written inline in C (xoshiro256++ inline in both, or behind `sk_rng` where the \
         call takes one; minimum of 15 interleaved rounds of 2¹⁸ samples). Errors are measured \
         in C against the library's double-precision sampler (directions: `|dot(w_in, w_out) − \
         cos θ_exact|`).\n\n| what | ns per sample | max error in cos θ |\n|---|---:|---:|\n",
    );
    for (key, _, label, _) in C_KEYS {
        let (t, e) = c[key];
        let err = if e >= 0.0 {
            format!("{e:.1e}")
        } else if key.contains("simplified") || key.contains("lobe") {
            "exact in distribution".into()
        } else {
            "—".into()
        };
        writeln!(s, "| {label} | {t:.2} | {err} |").unwrap();
    }
    let mark = |ok: bool| if ok { "met" } else { "**missed**" };
    let r = |a: &str, b: &str| ns(a) / ns(b);
    let best_rng = ["direct", "minimax", "table"]
        .map(|m| (m, ns(&format!("rayleigh_rng_dir.{m}"))))
        .into_iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    let hg_rust = p.hg.0 / p.hg.1;
    let d = |k: &str| r(&format!("draine_{k}.sk"), &format!("draine_{k}.eq6"));
    let rows: [(String, String, bool); 9] = [
        ("`sk_phase_sample_dir` HG g = 0.7 ≤ 1.15× pbrt-v4 inline C".into(),
         format!("{:.2}× ({:.1} vs {:.1} ns)", r("hg_dir.sk", "hg_dir.pbrt"), ns("hg_dir.sk"), ns("hg_dir.pbrt")),
         r("hg_dir.sk", "hg_dir.pbrt") <= 1.15),
        ("`sk_phase_sample_dir` Rayleigh ≤ 1.0× Mitsuba 3 inline C and ≤ 1.3× the inline-C isotropic direction".into(),
         format!("{:.2}× and {:.2}×", r("rayleigh_dir.sk", "rayleigh_dir.mitsuba"), r("rayleigh_dir.sk", "iso_dir.c")),
         r("rayleigh_dir.sk", "rayleigh_dir.mitsuba") <= 1.0 && r("rayleigh_dir.sk", "iso_dir.c") <= 1.3),
        ("`sk_phase_sample_dir_n` HG ≤ 0.8× the pbrt-v4 inline-C direction loop".into(),
         format!("{:.2}× ({:.2} vs {:.2} ns)", r("hg_dir_n.sk", "hg_dir_n.pbrt"), ns("hg_dir_n.sk"), ns("hg_dir_n.pbrt")),
         r("hg_dir_n.sk", "hg_dir_n.pbrt") <= 0.8),
        ("`sk_phase_sample_cos_n` HG ≤ 1.0× the pbrt-v4 inline-C cosine loop".into(),
         format!("{:.2}× ({:.2} vs {:.2} ns)", r("hg_cos_n.sk", "hg_cos_n.pbrt"), ns("hg_cos_n.sk"), ns("hg_cos_n.pbrt")),
         r("hg_cos_n.sk", "hg_cos_n.pbrt") <= 1.0),
        ("fastest `sk_rayleigh_sample_dir` method with max error ≤ 1e-6 ≤ 1.0× simplified rejection inline C".into(),
         format!("{:.2}× ({}, {:.1} vs {:.1} ns)", best_rng.1 / ns("rayleigh_dir.simplified"), best_rng.0, best_rng.1, ns("rayleigh_dir.simplified")),
         best_rng.1 / ns("rayleigh_dir.simplified") <= 1.0),
        ("fog `sk_phase_sample_cos` ≤ 2× `sk_phase_sample_cos_lobe`".into(),
         format!("{:.2}×", r("fog_cos.sk", "fog_cos.lobe")),
         r("fog_cos.sk", "fog_cos.lobe") <= 2.0),
        ("Draine `sk_phase_sample_cos` ≤ 1.3× eq. 6 inline C (g 0.5, α 1; g 0.9, α 10), ≤ 1.5× (α 250, 1000)".into(),
         format!("{:.2}×, {:.2}×; {:.2}×, {:.2}×", d("0.5_1"), d("0.9_10"), d("0.3_250"), d("0.01_1000")),
         d("0.5_1") <= 1.3 && d("0.9_10") <= 1.3 && d("0.3_250") <= 1.5 && d("0.01_1000") <= 1.5),
        ("`sk_phase_sample_dir` isotropic ≤ 1.0× the inline-C isotropic direction".into(),
         format!("{:.2}× ({:.1} vs {:.1} ns)", r("iso_dir.sk", "iso_dir.c"), ns("iso_dir.sk"), ns("iso_dir.c")),
         r("iso_dir.sk", "iso_dir.c") <= 1.0),
        ("HG `sample_cos` in Rust ≤ 1.1× pbrt-v4's formula inlined (same RNG)".into(),
         format!("{hg_rust:.2}× ({:.2} vs {:.2} ns, interleaved)", p.hg.0, p.hg.1),
         hg_rust <= 1.1),
    ];
    writeln!(
        s,
        "\n## Targets through the C ABI\n\n| target | measured | |\n|---|---|---|"
    )
    .unwrap();
    for (t, m, ok) in rows {
        writeln!(s, "| {t} | {m} | {} |", mark(ok)).unwrap();
    }
    s
}

fn csv(es: &[Entry]) -> String {
    let mut s = String::from(
        "family,method,ns_per_cos,ns_per_dir_fast_rng,ns_per_dir_slow_rng,max_abs_error,max_cdf_error,exact_by_rejection,curve\n",
    );
    for e in es {
        let (df, ds) = e.dir_ns.map_or((String::new(), String::new()), |(f, s)| {
            (format!("{f:.3}"), format!("{s:.3}"))
        });
        let err = if e.rejection {
            String::new()
        } else {
            format!("{:.3e}", e.err)
        };
        let cdf = if e.rejection || e.cdf_err.is_nan() {
            String::new()
        } else {
            format!("{:.3e}", e.cdf_err)
        };
        writeln!(
            s,
            "{},\"{}\",{:.3},{df},{ds},{err},{cdf},{},\"{}\"",
            e.family,
            e.name,
            e.ns,
            e.rejection,
            e.curve.unwrap_or("")
        )
        .unwrap();
    }
    s
}

/// The families, one chart panel each: `(family, title, y-axis label, y range)`.
const PANELS: [(&str, &str, &str, (f64, f64)); 5] = [
    ("Rayleigh", "Rayleigh", "max |cos θ − exact|", (1e-9, 1.0)),
    (
        "HG",
        "Henyey–Greenstein",
        "max |cos θ − exact|",
        (1e-8, 1e-2),
    ),
    (
        "Draine",
        "Draine and Cornette–Shanks",
        "max |cos θ − exact|",
        (1e-8, 10.0),
    ),
    (
        "fog",
        "fog (Jendersie & d'Eon), 2 µm",
        "max |cos θ − exact|",
        (1e-8, 1e-1),
    ),
    ("cbrt", "cube root (f32)", "max error in ULP", (0.1, 1e10)),
];

/// The points of one panel: the family's entries with a finite positive error.
fn panel_points<'a>(es: &'a [Entry], family: &str) -> Vec<&'a Entry> {
    es.iter()
        .filter(|e| e.family == family && e.err > 0.0 && e.err.is_finite())
        .collect()
}

/// The Pareto frontier of a panel: sorted by time, each point more accurate
/// than every faster one.
fn frontier<'a>(pts: &[&'a Entry]) -> Vec<&'a Entry> {
    let mut sorted = pts.to_vec();
    sorted.sort_by(|a, b| a.ns.total_cmp(&b.ns));
    let mut best = f64::INFINITY;
    sorted
        .into_iter()
        .filter(|e| {
            let keep = e.err < best;
            best = best.min(e.err);
            keep
        })
        .collect()
}

/// A label short enough for the chart (the tables keep the full names).
fn short(name: &str) -> String {
    name.replace("C ABI: ", "")
        .replace(", sk_phase_sample_cos_n (4096)", ", batch")
        .replace(
            ", sk_phase_sample_cos_lobe (paper's lobe choice)",
            ", lobe choice",
        )
        .replace(", sk_phase_sample_cos (monotone inverse)", ", inverse")
        .replace(", sk_phase_sample_cos", "")
        .replace(" cos θ loop, inline C", ", loop")
        .replace(" cos θ, inline C", "")
        .replace(", inline C", "")
        .replace("peer: ", "")
}

/// The chart: one log-log panel per family, ns per sample (x) against max
/// error (y); circles are Rust calls, triangles calls through the C ABI from
/// C, squares (hollow triangles) exact-in-distribution samplers plotted at
/// f32's rounding floor; dashed lines are curves (tables by n, cube-root
/// steps); the black line is the Pareto frontier. Labels are placed so that
/// none covers another label or a point; one that finds no free place is
/// numbered and named under its panel.
fn svg(es: &[Entry]) -> String {
    let (pw, ph, gap_x, gap_y) = (470.0, 330.0, 110.0, 150.0);
    let (w, h) = (2.0 * pw + gap_x + 90.0, 3.0 * (ph + gap_y) + 20.0);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"9\">\n\
         <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n"
    );
    for (k, (family, title, ylabel, (y_lo, y_hi))) in PANELS.iter().enumerate() {
        let pts = panel_points(es, family);
        if pts.is_empty() {
            continue;
        }
        let x0 = 70.0 + (k % 2) as f64 * (pw + gap_x);
        let y0 = 40.0 + (k / 2) as f64 * (ph + gap_y);
        let xl = if *family == "cbrt" {
            "ns per cube root"
        } else {
            "ns per sample (f32)"
        };
        panel(
            &mut s,
            &pts,
            (x0, y0, pw, ph),
            title,
            xl,
            ylabel,
            *y_lo,
            *y_hi,
        );
    }
    s += "</svg>\n";
    s
}

const COLORS: [(&str, &str); 6] = [
    ("Rayleigh", "#1f77b4"),
    ("HG", "#2ca02c"),
    ("Draine", "#d62728"),
    ("fog", "#9467bd"),
    ("isotropic", "#7f7f7f"),
    ("cbrt", "#ff7f0e"),
];

fn color(family: &str) -> &'static str {
    COLORS
        .iter()
        .find(|c| c.0 == family)
        .map_or("black", |c| c.1)
}

/// Text for SVG.
fn esc(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// An axis-aligned box `(x0, y0, x1, y1)` for the label placer.
type Rect = (f64, f64, f64, f64);

fn overlaps_any(r: Rect, taken: &[Rect]) -> bool {
    taken
        .iter()
        .any(|t| r.0 < t.2 && t.0 < r.2 && r.1 < t.3 && t.1 < r.3)
}

/// One log-log panel at `(x0, y0, pw, ph)`; x from the data, y over `[y_lo, y_hi]`.
#[allow(clippy::too_many_arguments)]
fn panel(
    s: &mut String,
    pts: &[&Entry],
    (x0, y0, pw, ph): (f64, f64, f64, f64),
    title: &str,
    xl: &str,
    yl: &str,
    y_lo: f64,
    y_hi: f64,
) {
    let (xmin, xmax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), e| {
        (a.min(e.ns), b.max(e.ns))
    });
    let (lx0, lx1) = ((xmin * 0.8).log10().floor(), (xmax * 1.25).log10().ceil());
    let (ly0, ly1) = (y_lo.log10(), y_hi.log10());
    let px = |ns: f64| x0 + (ns.log10() - lx0) / (lx1 - lx0) * pw;
    let py = |e: f64| y0 + ph - (e.clamp(y_lo, y_hi).log10() - ly0) / (ly1 - ly0) * ph;
    writeln!(
        s,
        "<rect x=\"{x0}\" y=\"{y0}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#444\"/>\
         <text x=\"{x0}\" y=\"{}\" font-size=\"13\" font-weight=\"bold\">{}</text>",
        y0 - 22.0,
        esc(title)
    )
    .unwrap();
    for d in (lx0 as i32)..=(lx1 as i32) {
        let x = px(10f64.powi(d));
        writeln!(s, "<line x1=\"{x}\" y1=\"{y0}\" x2=\"{x}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">1e{d}</text>", y0 + ph, y0 + ph + 13.0).unwrap();
    }
    for d in (ly0 as i32)..=(ly1 as i32) {
        let y = py(10f64.powi(d));
        writeln!(s, "<line x1=\"{x0}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{d}</text>", x0 + pw, x0 - 4.0, y + 3.0).unwrap();
    }
    writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"11\">{xl}</text>\
         <text x=\"{}\" y=\"{}\" font-size=\"11\">{yl}</text>",
        x0 + pw / 2.0,
        y0 + ph + 28.0,
        x0 + pw - 120.0,
        y0 - 6.0
    )
    .unwrap();
    let col_of = |e: &Entry| color(e.family);
    // Curves (tables by n, step counts).
    let mut curves: Vec<&str> = Vec::new();
    for c in pts.iter().filter_map(|e| e.curve) {
        if !curves.contains(&c) {
            curves.push(c);
        }
    }
    for c in &curves {
        let line: Vec<String> = pts
            .iter()
            .filter(|e| e.curve == Some(c))
            .map(|e| format!("{:.1},{:.1}", px(e.ns), py(e.err)))
            .collect();
        writeln!(
            s,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-dasharray=\"4,3\"/>",
            line.join(" "),
            pts.iter()
                .find(|e| e.curve == Some(c))
                .map_or("black", |e| col_of(e))
        )
        .unwrap();
    }
    let front: Vec<String> = frontier(pts)
        .iter()
        .map(|e| format!("{:.1},{:.1}", px(e.ns), py(e.err)))
        .collect();
    writeln!(s, "<polyline points=\"{}\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" opacity=\"0.6\"/>", front.join(" ")).unwrap();
    // Markers; every marker's box is taken before any label is placed.
    let mut taken: Vec<Rect> = Vec::new();
    for e in pts {
        let (x, y, col) = (px(e.ns), py(e.err), col_of(e));
        taken.push((x - 5.0, y - 5.0, x + 5.0, y + 5.0));
        if e.c_abi {
            let fill = if e.rejection { "none" } else { col };
            writeln!(s, "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"{fill}\" stroke=\"{col}\"/>", x, y - 5.0, x - 4.5, y + 3.5, x + 4.5, y + 3.5).unwrap();
        } else if e.rejection {
            writeln!(s, "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"7\" height=\"7\" fill=\"none\" stroke=\"{col}\"/>", x - 3.5, y - 3.5).unwrap();
        } else {
            writeln!(
                s,
                "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3.5\" fill=\"{col}\" opacity=\"0.8\"/>"
            )
            .unwrap();
        }
    }
    // The legend box is taken too.
    let (lx, ly) = (x0 + pw - 190.0, y0 + 6.0);
    taken.push((lx - 4.0, ly - 2.0, x0 + pw, ly + 52.0));
    let legend = [
        "● Rust call   ▲ through the C ABI, from C",
        "□ / △ exact in distribution (at f32 floor)",
        "– – curve (tables by n, steps)",
        "—— Pareto frontier",
    ];
    for (i, t) in legend.iter().enumerate() {
        writeln!(
            s,
            "<text x=\"{lx}\" y=\"{}\" fill=\"#333\">{t}</text>",
            ly + 10.0 + 12.0 * i as f64
        )
        .unwrap();
    }
    // Labels: curves at their last point, other entries at their own; the
    // first free place among right, left, above and below, at growing
    // distances; a numbered tag otherwise.
    let mut labelled: Vec<(String, f64, f64, &str)> = Vec::new();
    for c in &curves {
        if let Some(last) = pts.iter().rev().find(|e| e.curve == Some(c)) {
            labelled.push((c.to_string(), px(last.ns), py(last.err), col_of(last)));
        }
    }
    for e in pts.iter().filter(|e| e.curve.is_none()) {
        labelled.push((short(&e.name), px(e.ns), py(e.err), col_of(e)));
    }
    let mut footnotes = Vec::new();
    for (text, x, y, col) in labelled {
        let tw = 4.9 * text.chars().count() as f64;
        let inside = |r: Rect| {
            r.0 >= x0 + 2.0 && r.2 <= x0 + pw - 2.0 && r.1 >= y0 + 2.0 && r.3 <= y0 + ph - 2.0
        };
        let mut spot = None;
        'search: for k in 0..8 {
            let dy = 11.0 * k as f64;
            for (bx, by) in [
                (x + 6.0, y - 4.0 - dy),
                (x + 6.0, y - 4.0 + dy),
                (x - 6.0 - tw, y - 4.0 - dy),
                (x - 6.0 - tw, y - 4.0 + dy),
            ] {
                let r = (bx, by - 6.0, bx + tw, by + 4.0);
                if inside(r) && !overlaps_any(r, &taken) {
                    spot = Some(r);
                    break 'search;
                }
            }
        }
        let (r, shown) = match spot {
            Some(r) => (Some(r), text.clone()),
            None => {
                footnotes.push(text.clone());
                let tag = format!("[{}]", footnotes.len());
                let tw = 5.5 * tag.len() as f64;
                let cands = [
                    (x + 5.0, y - 6.0),
                    (x - 5.0 - tw, y - 6.0),
                    (x - tw / 2.0, y - 10.0),
                    (x - tw / 2.0, y + 14.0),
                ];
                let r = cands
                    .iter()
                    .map(|&(bx, by)| (bx, by - 6.0, bx + tw, by + 4.0))
                    .find(|&r| !overlaps_any(r, &taken));
                (r, tag)
            }
        };
        if let Some(r) = r {
            taken.push(r);
            writeln!(
                s,
                "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"{col}\">{}</text>",
                r.0,
                r.3 - 1.0,
                esc(&shown)
            )
            .unwrap();
        }
    }
    for (i, f) in footnotes.iter().enumerate() {
        writeln!(
            s,
            "<text x=\"{x0}\" y=\"{}\" fill=\"#333\">[{}] {}</text>",
            y0 + ph + 44.0 + 11.0 * i as f64,
            i + 1,
            esc(f)
        )
        .unwrap();
    }
}

/// The peers' points that sit on a panel's Pareto frontier.
fn frontier_peers(es: &[Entry]) -> String {
    let mut s = String::from(
        "\n## Peers on the Pareto frontier\n\nPoints of the chart that no other method of their panel beats in both speed and accuracy, and that are a peer's formula:\n\n",
    );
    let mut any = false;
    for (family, title, _, _) in PANELS {
        for e in frontier(&panel_points(es, family)) {
            if e.name.contains("peer:") {
                any = true;
                writeln!(
                    s,
                    "- {title}: {} ({:.2} ns, max error {:.1e})",
                    e.name, e.ns, e.err
                )
                .unwrap();
            }
        }
    }
    if !any {
        s += "- none\n";
    }
    s
}

/// `docs/PERFORMANCE.md`: Frisvad's Table 1 ratios beside ours, and the
/// targets, all from this run.
fn performance(
    es: &[Entry],
    rayleigh_batch: (f64, f64),
    hg_batch: (f64, f64),
    p: &Pairs,
) -> String {
    let dir = |n: &str| find(es, n).dir_ns.unwrap().0;
    let direct = dir("direct (Cardano, cbrt)");
    let pow = dir("direct (Cardano, powf cube root)");
    let simplified = dir("simplified rejection");
    let table32 = dir("Frisvad's CDF table n = 32");
    // The fastest Rayleigh direction sampler with max error ≤ 1e-6.
    let (best_name, best_ns) = es
        .iter()
        .filter(|e| e.family == "Rayleigh" && e.dir_ns.is_some() && (e.rejection || e.err <= 1e-6))
        .map(|e| (e.name.clone(), e.dir_ns.unwrap().0))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    let h64 = find(es, "Hermite inverse table n = 64");
    let f32t = find(es, "Frisvad's CDF table n = 32");
    let cb_ulp = find(es, "scatterkit Kahan + 2 steps").err;
    let [d1, d2] = p.draine.map(|(ours, eq6)| ours / eq6);
    let mark = |ok: bool| if ok { "met" } else { "**missed**" };
    let mut s = String::new();
    writeln!(s, "# Performance\n\nGenerated by `cargo run --release --example speed_accuracy`; do not edit. \
        f32, xoshiro256++, this project's machine (AMD EPYC, 2 virtual cores, shared: \
        its speed drifts by up to 2× over minutes, so single figures vary between runs; \
        ratios are taken within one run, the targets' with the compared samplers interleaved).\n").unwrap();
    writeln!(s, "## Frisvad (2011), Table 1, re-run\n").unwrap();
    writeln!(s, "Throughput ratios of direction sampling (higher is faster), the paper's from its Table 1 (C `rand()`) and text (Mersenne Twister):\n").unwrap();
    writeln!(
        s,
        "| ratio | Frisvad 2011 | today (xoshiro256++) |\n|---|---:|---:|"
    )
    .unwrap();
    writeln!(
        s,
        "| simplified rejection / direct (`pow` cube root) | 2.473 / 2.251 = 1.10 | {:.2} |",
        pow / simplified
    )
    .unwrap();
    writeln!(
        s,
        "| tabulation n = 32 / direct (`pow`) | 2.710 / 2.251 = 1.20 | {:.2} |",
        pow / table32
    )
    .unwrap();
    writeln!(
        s,
        "| direct with Kahan + Lancaster cube root / with `pow` | 2.606 / 2.251 = 1.16 | {:.2} |",
        pow / direct
    )
    .unwrap();
    writeln!(
        s,
        "| simplified rejection / direct (Kahan cube root) | 2.990 / 2.606 = 1.15 | {:.2} |",
        direct / simplified
    )
    .unwrap();
    writeln!(s, "| fastest exact-to-1e-6 sampler / simplified rejection | (rejection was fastest) | {:.2} ({best_name}) |\n", simplified / best_ns).unwrap();
    writeln!(s, "## Targets\n\nEach ratio re-timed with the compared samplers interleaved, the fastest of 15 runs each.\n").unwrap();
    writeln!(s, "| target | measured | |\n|---|---|---|").unwrap();
    let (tab, simp, isod) = (p.table_dir, p.simplified, p.iso_dir);
    writeln!(s, "| (a) fastest Rayleigh sampler with max error ≤ 1e-6 ≥ 1.3× simplified rejection | {:.2}× (built-in Hermite table n = 128, {tab:.1} ns vs {simp:.1} ns) | {} |", simp / tab, mark(simp / tab >= 1.3)).unwrap();
    writeln!(s, "| (b) Rayleigh directions ≤ 1.25× isotropic directions | {:.2}× ({tab:.1} ns vs {isod:.1} ns) | {} |", tab / isod, mark(tab / isod <= 1.25)).unwrap();
    writeln!(s, "| (c) Hermite table n = 64 faster than Frisvad's n = 32, ≥ 1000× more accurate | {:.1} ns vs {:.1} ns; {:.0}× ({:.1e} vs {:.1e}) | {} |", p.hermite64, p.frisvad32, f32t.err / h64.err, h64.err, f32t.err, mark(p.hermite64 < p.frisvad32 && f32t.err / h64.err >= 1000.0)).unwrap();
    let [cb, libm_cb, powf] = p.cbrt;
    writeln!(s, "| (d) cbrt ≤ 1.1× libm cbrtf at ≤ 1.5 ULP, ≥ 3× faster than powf | {:.2}× libm at {cb_ulp:.2} ULP; {:.1}× faster than powf | {} |", cb / libm_cb, powf / cb, mark(cb / libm_cb <= 1.1 && cb_ulp <= 1.5 && powf / cb >= 3.0)).unwrap();
    writeln!(
        s,
        "| (e) batch ≥ 3× scalar calls (Rayleigh direct, HG) | Rayleigh {:.2}×, HG {:.2}× | {} |",
        rayleigh_batch.1 / rayleigh_batch.0,
        hg_batch.1 / hg_batch.0,
        mark(rayleigh_batch.1 / rayleigh_batch.0 >= 3.0 && hg_batch.1 / hg_batch.0 >= 3.0)
    )
    .unwrap();
    writeln!(s, "| (f) Draine ≤ 2× eq. 6 where eq. 6 works | {d1:.2}× (g 0.5, α 1), {d2:.2}× (g 0.9, α 10) | {} |", mark(d1 <= 2.0 && d2 <= 2.0)).unwrap();
    s
}

/// Delta and ratio tracking through a cloud with 16³ local majorants and
/// with one global majorant (a 1³ majorant grid, the same code): counts per
/// ray, time per ray (interleaved), and how the cost grows with the ratio
/// of peak to mean density. Markdown for `docs/PERFORMANCE.md`.
fn media_report() -> String {
    use scatterkit::majorant::{DEFAULT_RES, Majorants};
    use scatterkit::medium::Event;
    let budget = 1 << 24;
    // Per ray: (tentative collisions of delta tracking, real collisions,
    // tentative collisions of ratio tracking).
    let counts =
        |grid: &Grid<'_, f32>, maj: &Majorants<'_, f32>, rays: &[(Vec3<f32>, Vec3<f32>)]| {
            let mut r = fast_rng();
            let (mut steps, mut real, mut ratio) = (0u64, 0u64, 0u64);
            for &(o, d) in rays {
                let t = maj
                    .delta_track(grid, o, d, f32::INFINITY, budget, &mut r)
                    .unwrap();
                steps += t.steps as u64;
                real += (t.event != Event::Escaped) as u64;
                ratio += maj
                    .ratio_track(grid, o, d, f32::INFINITY, budget, &mut r)
                    .unwrap()
                    .steps as u64;
            }
            let n = rays.len() as f64;
            (steps as f64 / n, real as f64 / n, ratio as f64 / n)
        };
    let n = 128;
    let values = cloud::cloud(n, 60.0);
    let grid = cloud::grid(&values, n);
    let (mut local_store, mut global_store) = (vec![0.0f32; DEFAULT_RES.pow(3)], [0.0f32; 1]);
    let (local, global) = cloud::majorants(&grid, &mut local_store, &mut global_store);
    let rays = cloud::rays(2000);
    let (cl, cg) = (counts(&grid, &local, &rays), counts(&grid, &global, &rays));
    let timer = |maj: &Majorants<'_, f32>, ratio: bool| {
        let mut r = fast_rng();
        let start = Instant::now();
        let mut acc = 0.0f32;
        for &(o, d) in &rays {
            acc += if ratio {
                maj.ratio_track(&grid, o, d, f32::INFINITY, budget, &mut r)
                    .unwrap()
                    .tr
            } else {
                maj.delta_track(&grid, o, d, f32::INFINITY, budget, &mut r)
                    .unwrap()
                    .t
            };
        }
        black_box(acc);
        start.elapsed().as_nanos() as f64 / rays.len() as f64
    };
    let [dl, dg, rl, rg] = interleaved([
        &mut || timer(&local, false),
        &mut || timer(&global, false),
        &mut || timer(&local, true),
        &mut || timer(&global, true),
    ]);
    let nulls = (cg.0 - cg.1) / (cl.0 - cl.1);
    let mut md = String::new();
    writeln!(
        md,
        "\n## Media: majorant grids\n\nA {n}³ cloud over [−1, 1]³ (`benches/cloud.rs`: a Gaussian core, a haze of at most 5 % of the peak, \
         an empty corner; peak/mean density {:.0}), 2000 rays from a sphere of radius 3 into the box, f32. \
         Tracking walks {DEFAULT_RES}³ local majorants (`Majorants::build`) or one global majorant (a 1³ majorant grid, the same code). \
         Times are per ray, the fastest of {REPEATS} interleaved runs.\n",
        cloud::peak_over_mean(&values)
    )
    .unwrap();
    writeln!(md, "| majorants | delta: evaluations per ray | null collisions per ray | ns per ray | ratio: evaluations per ray | ns per ray |").unwrap();
    writeln!(md, "|---|---:|---:|---:|---:|---:|").unwrap();
    for (name, c, d, r) in [("local 16³", cl, dl, rl), ("global", cg, dg, rg)] {
        writeln!(
            md,
            "| {name} | {:.1} | {:.1} | {:.0} | {:.1} | {:.0} |",
            c.0,
            c.0 - c.1,
            d,
            c.2,
            r
        )
        .unwrap();
    }
    writeln!(md, "\n| target | measured | |\n|---|---|---|").unwrap();
    let row = |md: &mut String, what: &str, v: f64, bound: f64| {
        let ok = if v >= bound { "met" } else { "**missed**" };
        writeln!(md, "| {what} | {v:.1}× | {ok} |").unwrap();
    };
    row(
        &mut md,
        "null collisions per ray, global / local ≥ 5×",
        nulls,
        5.0,
    );
    row(
        &mut md,
        "delta tracking time per ray, global / local ≥ 3×",
        dg / dl,
        3.0,
    );
    row(
        &mut md,
        "ratio tracking time per ray, global / local ≥ 3×",
        rg / rl,
        3.0,
    );
    writeln!(
        md,
        "\nHow the cost grows with the peak: the same cloud at 64³ with cores of rising peak, 1000 rays. \
         With one majorant the evaluations per ray grow with the peak; with local majorants they follow \
         the optical depth the rays actually cross.\n\n\
         | peak / mean density | delta, local | delta, global | ratio, local | ratio, global |\n|---:|---:|---:|---:|---:|"
    )
    .unwrap();
    let rays = cloud::rays(1000);
    for peak in [2.0f32, 10.0, 50.0, 250.0, 1000.0] {
        let values = cloud::cloud(64, peak);
        let grid = cloud::grid(&values, 64);
        let (mut ls, mut gs) = (vec![0.0f32; DEFAULT_RES.pow(3)], [0.0f32; 1]);
        let (local, global) = cloud::majorants(&grid, &mut ls, &mut gs);
        let (a, b) = (counts(&grid, &local, &rays), counts(&grid, &global, &rays));
        writeln!(
            md,
            "| {:.0} | {:.1} | {:.1} | {:.1} | {:.1} |",
            cloud::peak_over_mean(&values),
            a.0,
            b.0,
            a.2,
            b.2
        )
        .unwrap();
    }
    md
}
