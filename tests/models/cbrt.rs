//! Cube-root accuracy in ULP of the result: exhaustive over every positive
//! f32 (normals and subnormals), and 10⁷ doubles spread over every binade
//! (subnormals included) against a double-double reference.

use crate::common;

use common::dd::Dd;
use scatterkit::cbrt::{cbrt_f32, cbrt_f64, cbrt_fast_f32, cbrt_fast_f64};

/// Spacing of f32 values at `y` (a positive normal f32 magnitude).
fn ulp32(y: f64) -> f64 {
    let e = ((y as f32).to_bits() >> 23) as i32;
    // 2^(e − 150), built from its bits (exact, as `powi` is for powers of
    // two, without `powi`'s loop: this runs for every f32).
    f64::from_bits(((e - 150 + 1023) as u64) << 52)
}

/// Spacing of f64 values at `y` (positive normal).
fn ulp64(y: f64) -> f64 {
    let e = (y.to_bits() >> 52) as i32;
    2f64.powi(e - 1023 - 52)
}

#[derive(Default, Clone, Copy, Debug)]
struct Stats {
    max: f64,
    sum2: f64,
    n: u64,
}

impl Stats {
    fn add(&mut self, e: f64) {
        self.max = self.max.max(e);
        self.sum2 += e * e;
        self.n += 1;
    }
    fn merge(mut self, o: Stats) -> Stats {
        self.max = self.max.max(o.max);
        self.sum2 += o.sum2;
        self.n += o.n;
        self
    }
    fn rms(&self) -> f64 {
        (self.sum2 / self.n as f64).sqrt()
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "exhaustive over 2.1e9 floats: run with --release"
)]
fn cbrtf_exhaustive_within_1_5_ulp() {
    // Every positive finite f32, split over two threads. libm's f64 cbrt is
    // correctly rounded, so its value is the true cube root to ~1e-9 f32 ULP.
    const END: u32 = 0x7f80_0000;
    let (full, fast) = std::thread::scope(|s| {
        let halves: Vec<_> = [(1u32, END / 2), (END / 2, END)]
            .into_iter()
            .map(|(a, b)| {
                s.spawn(move || {
                    let (mut full, mut fast) = (Stats::default(), Stats::default());
                    for bits in a..b {
                        let x = f32::from_bits(bits);
                        let exact = libm::cbrt(x as f64);
                        let ulp = ulp32(exact);
                        full.add((cbrt_f32(x) as f64 - exact).abs() / ulp);
                        fast.add((cbrt_fast_f32(x) as f64 - exact).abs() / ulp);
                    }
                    (full, fast)
                })
            })
            .collect();
        halves
            .into_iter()
            .map(|h| h.join().unwrap())
            .reduce(|a, b| (a.0.merge(b.0), a.1.merge(b.1)))
            .unwrap()
    });
    println!(
        "cbrtf over {} floats: max {:.3} ULP, rms {:.3}; fast: max {:.1}, rms {:.1}",
        full.n,
        full.max,
        full.rms(),
        fast.max,
        fast.rms()
    );
    assert_eq!(full.n, END as u64 - 1);
    assert!(full.max <= 1.5, "cbrtf max {} ULP", full.max);
    assert!(fast.max <= 1000.0, "cbrtf_fast max {} ULP", fast.max);
}

/// The true cube root of a positive double, in double-double. Tiny inputs are
/// scaled by 2³⁰⁰ first so the reference's own error terms stay normal.
fn cbrt_ref(x: f64) -> f64 {
    if x < 2f64.powi(-900) {
        return cbrt_ref(x * 2f64.powi(300)) * 2f64.powi(-100);
    }
    Dd::new(x).cbrt().to_f64()
}

#[test]
fn cbrt_f64_within_1_5_ulp_over_every_binade() {
    let mut r = common::rng(2024);
    let (mut full, mut fast) = (Stats::default(), Stats::default());
    // 2098 binades (1022 + 52 subnormal ones below 2^-1022, up to 2^1023),
    // 4800 random significands each: 10,070,400 inputs.
    for e in -1074..1024 {
        for _ in 0..4800 {
            let bits: u64 = rand_xoshiro::rand_core::Rng::next_u64(&mut r);
            let x = if e < -1022 {
                // Subnormal binade [2^e, 2^(e+1)): integer significand bits below the top.
                let k = (e + 1074) as u32;
                f64::from_bits((1u64 << k) | (bits & ((1u64 << k) - 1)))
            } else {
                f64::from_bits((((e + 1023) as u64) << 52) | (bits >> 12))
            };
            let exact = cbrt_ref(x);
            let ulp = ulp64(exact);
            full.add((cbrt_f64(x) - exact).abs() / ulp);
            fast.add((cbrt_fast_f64(x) - exact).abs() / ulp);
            assert_eq!(cbrt_f64(-x), -cbrt_f64(x), "odd symmetry at {x:e}");
        }
    }
    println!(
        "cbrt (f64) over {} doubles: max {:.3} ULP, rms {:.3}; fast: max {:.1}, rms {:.2}",
        full.n,
        full.max,
        full.rms(),
        fast.max,
        fast.rms()
    );
    assert!(full.n >= 10_000_000);
    assert!(full.max <= 1.5, "cbrt max {} ULP", full.max);
    assert!(fast.max <= 100.0, "cbrt_fast max {} ULP", fast.max);
}

#[test]
fn odd_symmetry_and_special_values_f32() {
    for bits in (1u32..0x7f80_0000).step_by(9973) {
        let x = f32::from_bits(bits);
        assert_eq!(cbrt_f32(-x), -cbrt_f32(x));
        assert_eq!(cbrt_fast_f32(-x), -cbrt_fast_f32(x));
    }
    for x in [0.0f32, -0.0, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(cbrt_f32(x).to_bits(), x.to_bits());
    }
    assert!(cbrt_f32(f32::NAN).is_nan());
    assert!(cbrt_f64(-f64::NAN).is_nan());
}
