//! The timing harness (fastest of interleaved runs), the slow generator in
//! the spirit of the paper's `rand()`, the accuracy measure, and the
//! interleaved pairs the speed targets are taken from.

use crate::*;

/// Accuracy: errors over `SAMPLES + 1` evenly spaced u.
pub(crate) const SAMPLES: usize = 1 << 20;

/// Speed: the fastest of `REPEATS` runs of `TIMED` calls. This shared
/// machine's noise only ever adds time (single runs vary by up to 2×), so
/// the minimum of many short runs is the stable figure, as in the C
/// benchmark.
pub(crate) const TIMED: usize = 1 << 18;

pub(crate) const REPEATS: usize = 15;

/// Where rejection samplers are plotted: half an ULP of 1 in f32.
pub(crate) const FLOOR: f64 = 5.960_464_477_539_063e-8;

/// A slow generator in the spirit of the C `rand()` the paper timed: a 15-bit
/// LCG (the MSVC constants) behind an opaque function pointer, five calls per
/// 64-bit word.
pub(crate) struct SlowRand {
    pub(crate) state: u32,
    pub(crate) step: fn(&mut u32) -> u32,
}

pub(crate) fn lcg15(s: &mut u32) -> u32 {
    *s = s.wrapping_mul(214_013).wrapping_add(2_531_011);
    (*s >> 16) & 0x7fff
}

impl SlowRand {
    pub(crate) fn new(seed: u32) -> Self {
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
pub(crate) fn run_once(mut f: impl FnMut() -> f32) -> f64 {
    let start = Instant::now();
    let mut acc = 0.0f32;
    for _ in 0..TIMED {
        acc += f();
    }
    black_box(acc);
    start.elapsed().as_nanos() as f64 / TIMED as f64
}

/// Nanoseconds per call of `f`: the fastest of `REPEATS` runs of `TIMED` calls.
pub(crate) fn time_ns(mut f: impl FnMut() -> f32) -> f64 {
    interleaved([&mut || run_once(&mut f)])[0]
}

/// The fastest of `REPEATS` runs of each timer (each returns ns per call of
/// one run), the timers taking turns within every round: the machine's
/// drift over a run then falls on all of them alike, which is what makes
/// their ratios comparable. The targets are measured this way.
pub(crate) fn interleaved<const N: usize>(mut timers: [&mut dyn FnMut() -> f64; N]) -> [f64; N] {
    let mut best = [f64::INFINITY; N];
    for _ in 0..REPEATS {
        for (b, t) in best.iter_mut().zip(timers.iter_mut()) {
            *b = b.min(t());
        }
    }
    best
}

/// The Rust-side targets' samplers, re-timed in interleaved pairs.
pub(crate) struct Pairs {
    /// Directions: simplified rejection, built-in table, isotropic.
    pub(crate) simplified: f64,
    pub(crate) table_dir: f64,
    pub(crate) iso_dir: f64,
    /// Cos θ: Hermite table n = 64, Frisvad's table n = 32.
    pub(crate) hermite64: f64,
    pub(crate) frisvad32: f64,
    /// Cube roots: ours, libm, powf.
    pub(crate) cbrt: [f64; 3],
    /// Draine against eq. 6 at (0.5, 1) and (0.9, 10).
    pub(crate) draine: [(f64, f64); 2],
    /// HG g = 0.7 (the model itself) against pbrt-v4's formula.
    pub(crate) hg: (f64, f64),
}

pub(crate) fn pairs() -> Pairs {
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
        &mut || run_once(|| scatterkit::cbrt::cbrt_f32(next(&mut i1))),
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
pub(crate) fn errors(
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
pub(crate) fn rayleigh_exact(u: f64) -> f64 {
    let s = 2.0 * (2.0 * u - 1.0);
    let w = libm::cbrt(s.abs() + (s * s + 1.0).sqrt());
    (w - 1.0 / w).copysign(s)
}

pub(crate) fn rayleigh_cdf(x: f64) -> f64 {
    (1.0 + x) * (x * x - x + 4.0) / 8.0
}

pub(crate) fn fast_rng() -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(3)
}

/// Batch against scalar: ns per element of `batch` over 4096 u and of 4096
/// calls of `scalar`.
pub(crate) fn batch_ratio(
    batch: impl Fn(&[f32], &mut [f32]),
    scalar: impl Fn(f32) -> f32,
) -> (f64, f64) {
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
