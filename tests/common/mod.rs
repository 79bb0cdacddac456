//! Shared test machinery: double-double references, the chi² test, seeded
//! RNGs and the directions every sampler is tested about.
#![allow(dead_code)]

pub mod cbuild;
pub mod chi2;
pub mod dd;
pub mod ks;
pub mod readme;

pub use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// The larger of two errors, NaN if either is NaN. `f64::max` returns the
/// other argument when one is NaN, so a running maximum built on it passes
/// over a sampler gone NaN; built on this, the NaN reaches the assertion
/// (`worst <= tol` is false for NaN).
pub fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// The next cosine up and down, held to [−1, 1] (by the bits: the
/// crate's MSRV predates `f64::next_up`).
pub fn up(x: f64) -> f64 {
    match x {
        _ if x >= 1.0 => 1.0,
        _ if x == 0.0 => f64::from_bits(1),
        _ if x > 0.0 => f64::from_bits(x.to_bits() + 1),
        _ => f64::from_bits(x.to_bits() - 1),
    }
}
/// The next cosine down ([`up`] mirrored).
pub fn down(x: f64) -> f64 {
    -up(-x)
}

/// A fixed-seed generator: every test is deterministic.
pub fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

/// A generator that counts the words drawn from the one it wraps (`.1`),
/// for the tests that pin how many uniforms a call draws.
pub struct Counting(pub Xoshiro256PlusPlus, pub u64);

impl Counting {
    /// The fixed-seed generator [`rng`]`(seed)`, nothing drawn yet.
    pub fn new(seed: u64) -> Self {
        Counting(rng(seed), 0)
    }
}

impl rand_xoshiro::rand_core::TryRng for Counting {
    type Error = core::convert::Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
        self.1 += 1;
        self.0.try_next_u32()
    }
    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        self.1 += 1;
        self.0.try_next_u64()
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
        self.1 += 1;
        self.0.try_fill_bytes(dst)
    }
}

/// A generator stuck on 0: every uniform is exactly 0 (every free path 0,
/// every coin `u < p`), for the edges no seeded generator reaches.
pub struct Zero;

impl rand_xoshiro::rand_core::TryRng for Zero {
    type Error = core::convert::Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
        Ok(0)
    }
    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        Ok(0)
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
        dst.fill(0);
        Ok(())
    }
}

/// The incident directions the chi² tests use: ±z, ±x and one off every axis.
pub fn test_directions() -> [[f64; 3]; 5] {
    let l = (0.3f64 * 0.3 + 0.5 * 0.5 + 0.81 * 0.81).sqrt();
    [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.3 / l, -0.5 / l, 0.81 / l],
    ]
}

/// Samples per chi² test.
pub const CHI2_SAMPLES: usize = 1_000_000;

/// `n` uniforms evenly over `[0, 1]` including both ends.
pub fn uniform_grid(n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| i as f64 / (n - 1) as f64)
}

/// `count ≥ 2` runs `(lo, lo + len)` of consecutive f32 bit patterns,
/// evenly spaced from 0 to `top` (the first starts at 0, the last ends at
/// `top`): the neighbours a test of monotonicity needs, at `count·len` of
/// the floats.
pub fn runs_of_neighbours(top: u32, len: u32, count: u64) -> Vec<(u32, u32)> {
    (0..count)
        .map(|k| {
            let lo = (k * (top - len) as u64 / (count - 1)) as u32;
            (lo, lo + len)
        })
        .collect()
}

/// Calls `f` on every item, on as many threads as the machine has cores
/// (items taken in order as threads free up). A panic in `f` fails the
/// caller when the threads are joined.
pub fn for_each_parallel<I: Sync>(items: &[I], f: impl Fn(&I) + Sync) {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let next = AtomicUsize::new(0);
    std::thread::scope(|s| {
        for _ in 0..threads.min(items.len()) {
            s.spawn(|| {
                while let Some(item) = items.get(next.fetch_add(1, Ordering::Relaxed)) {
                    f(item);
                }
            });
        }
    });
}

/// `items.iter().map(f).collect()`, computed on as many threads as the
/// machine has cores; the results in the items' order.
pub fn map_parallel<I: Sync, R: Send>(items: &[I], f: impl Fn(&I) -> R + Sync) -> Vec<R> {
    let out: Vec<std::sync::Mutex<Option<R>>> =
        items.iter().map(|_| std::sync::Mutex::new(None)).collect();
    let indexed: Vec<(usize, &I)> = items.iter().enumerate().collect();
    for_each_parallel(&indexed, |&(i, item)| {
        *out[i].lock().unwrap() = Some(f(item));
    });
    out.into_iter()
        .map(|m| m.into_inner().unwrap().expect("every item mapped"))
        .collect()
}

/// Whether this is the repository (with the C library crate, `capi/`, and
/// the install script), not the crate as `cargo package` makes it; a test
/// that needs it and runs outside it says `SKIPPED` (see [`skip`]).
#[allow(dead_code)]
pub fn repository(test: &str) -> bool {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let here = root.join("capi/Cargo.toml").exists() && root.join("scripts/install.sh").exists();
    if !here {
        skip(&format!(
            "{test}: needs the repository (capi/, scripts/install.sh), not the packaged crate"
        ));
    }
    here
}

/// A test that cannot run here says so on standard error, past the test
/// harness's capture (which takes only `print!`/`eprint!`), so that cargo
/// shows the line; with `SK_REQUIRE_ALL` set (as `.ci/run` sets it) a skip
/// is a failure instead.
pub fn skip(what: &str) {
    use std::io::Write;
    if std::env::var_os("SK_REQUIRE_ALL").is_some() {
        panic!("SKIPPED, but SK_REQUIRE_ALL is set: {what}");
    }
    let _ = writeln!(std::io::stderr(), "SKIPPED: {what}");
}
