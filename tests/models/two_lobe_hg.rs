//! Two-lobe Henyey–Greenstein (`Phase::two_lobe_hg`, `sk_phase_new_two_lobe_hg`):
//! the exact inverse against a double-double bisection of the mixture's CDF
//! over the whole accepted domain (|g| up to 0.999, every weight), chi² of
//! both samplers over the sphere, and the mean cosine.
//!
//! Bounds (the issue's): f32 `max |cos θ error| ≤ 2·10⁻⁷`; f64 `≤ 10⁻¹⁴`
//! everywhere, including where the two lobes point apart and the density
//! between them is small. There `μ(u)` amplifies the rounding of
//! `u ↦ F(μ)` (a few ε) by `1/p_μ`: with the residual in f64 alone the
//! error reached 1.6·10⁻¹³ at `(g1, g2, w) = (−0.999, 0.999, ½)`, so the
//! f64 sampler takes one Newton step on a double-double residual.

use crate::common;
use crate::common::nan_max;

use common::chi2::{chi2_directions, threshold};
use common::{CHI2_SAMPLES, dd, rng};
use scatterkit::{Phase, PhaseFunction, Real, Vec3};

fn u_values() -> Vec<f64> {
    let mut u: Vec<f64> = (0..=128).map(|i| i as f64 / 128.0).collect();
    for k in [1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.01] {
        u.push(k);
        u.push(1.0 - k);
    }
    u.sort_by(f64::total_cmp);
    u
}

const GS: [f64; 15] = [
    -0.999999, -0.999, -0.99, -0.9, -0.5, -0.1, -1e-3, 0.0, 1e-3, 0.1, 0.5, 0.9, 0.99, 0.999,
    0.999999,
];
const WS: [f64; 7] = [0.0, 1e-3, 0.1, 0.5, 0.9, 0.999, 1.0];

#[test]
fn inverse_is_accurate_over_the_whole_domain() {
    let t = |x: f64| x as f32 as f64;
    let params: Vec<_> = GS
        .into_iter()
        .flat_map(|g1| GS.into_iter().flat_map(move |g2| WS.map(|w| (g1, g2, w))))
        .collect();
    // (f32 error, (f64 error, where)) per parameter set, on every core.
    let errors = common::map_parallel(&params, |&(g1, g2, w)| {
        let (mut e32, mut e64) = (0.0f64, (0.0f64, [0.0; 3]));
        let p = Phase::<f64>::two_lobe_hg(g1, g2, w).unwrap();
        let p32 = Phase::<f32>::two_lobe_hg(g1 as f32, g2 as f32, w as f32).unwrap();
        let mut prev = -2.0;
        for u in u_values() {
            // dd::fog_inverse(g_hg, g_d, α, w_d): lobe 1 is the "Draine" lobe.
            let exact = dd::fog_inverse(g2, g1, 0.0, w, u);
            let got = p.sample_cos(u);
            assert!((-1.0..=1.0).contains(&got), "{g1} {g2} {w} {u}: {got}");
            assert!(got >= prev, "not monotone at {g1} {g2} {w} {u}");
            prev = got;
            let err = (got - exact).abs();
            assert!(err <= 1e-14, "{g1} {g2} {w} u {u}: error {err:e}");
            if err > e64.0 {
                e64 = (err, [g1, g2, w]);
            }
            let u32 = u as f32;
            let ex32 = dd::fog_inverse(t(g2), t(g1), 0.0, t(w), u32 as f64);
            let got32 = p32.sample_cos(u32);
            assert!(!got32.is_nan() && got32.abs() <= 1.0);
            e32 = nan_max(e32, (got32 as f64 - ex32).abs());
        }
        (e32, e64)
    });
    let e32 = errors.iter().map(|e| e.0).fold(0.0, nan_max);
    let e64 = errors
        .iter()
        .map(|e| e.1)
        .fold((0.0, [0.0; 3]), |a, b| if b.0 > a.0 { b } else { a });
    println!(
        "two-lobe HG: f32 {e32:.1e}; f64 {:.1e} (at g1, g2, w = {:?})",
        e64.0, e64.1
    );
    assert!(e32 <= 2e-7, "f32 {e32:e}");
}

#[test]
fn mean_cosine_is_the_weighted_mean() {
    for g1 in GS {
        for g2 in GS {
            for w in WS {
                let p = Phase::<f64>::two_lobe_hg(g1, g2, w).unwrap();
                let want = w * g1 + (1.0 - w) * g2;
                assert!((p.mean_cosine() - want).abs() < 1e-12, "{g1} {g2} {w}");
            }
        }
    }
}

#[test]
fn chi2_of_both_samplers() {
    fn check<T: Real>(seed: u64) {
        let l = (0.3f64 * 0.3 + 0.25 + 0.81 * 0.81).sqrt();
        let w_in = Vec3::new(
            T::from_f64(0.3 / l),
            T::from_f64(-0.5 / l),
            T::from_f64(0.81 / l),
        );
        let w64 = [w_in.x.to_f64(), w_in.y.to_f64(), w_in.z.to_f64()];
        for (k, (g1, g2, w)) in [
            (0.8, -0.3, 0.9),
            (0.99, -0.9, 0.5),
            (0.2, 0.6, 0.3),
            (-0.7, 0.95, 0.02),
        ]
        .into_iter()
        .enumerate()
        {
            let p =
                Phase::<T>::two_lobe_hg(T::from_f64(g1), T::from_f64(g2), T::from_f64(w)).unwrap();
            let p64: Phase<f64> = p.cast();
            let pdf = |mu: f64| p64.pdf(mu);
            let mut r = rng(seed + k as u64);
            let res = chi2_directions(&pdf, w64, CHI2_SAMPLES, || {
                let (d, _) = p.sample_dir(w_in, T::uniform(&mut r), T::uniform(&mut r));
                [d.x.to_f64(), d.y.to_f64(), d.z.to_f64()]
            });
            assert!(
                res.passes(),
                "{g1} {g2} {w} exact inverse: {res:?} ({:.2e})",
                threshold()
            );
            let mut r = rng(seed + 100 + k as u64);
            let res = chi2_directions(&pdf, w64, CHI2_SAMPLES, || {
                let mu = p.sample_cos_by_lobe(T::uniform(&mut r));
                let s = scatterkit::geometry::sin_from_cos(mu);
                let d =
                    scatterkit::geometry::direction_about_turns(w_in, mu, s, T::uniform(&mut r));
                [d.x.to_f64(), d.y.to_f64(), d.z.to_f64()]
            });
            assert!(res.passes(), "{g1} {g2} {w} by lobe: {res:?}");
        }
    }
    check::<f32>(9100);
    check::<f64>(9200);
}

#[test]
fn lobe_sampler_is_finite_at_the_ends_of_the_weight() {
    // w = 0 and w = 1 are accepted (one lobe only): the lobe choice must
    // then never divide by a zero weight, at u = 0 and u = 1 included.
    for w in [0.0, 1.0, 0.5] {
        for (g1, g2) in [(0.8, -0.3), (-0.999, 0.999)] {
            let p32 = Phase::<f32>::two_lobe_hg(g1 as f32, g2 as f32, w as f32).unwrap();
            let p64 = Phase::<f64>::two_lobe_hg(g1, g2, w).unwrap();
            for u in [0.0, 1e-7, 0.5, 1.0 - 1e-7, 1.0] {
                let a = p32.sample_cos_by_lobe(u as f32);
                let b = p64.sample_cos_by_lobe(u);
                assert!((-1.0..=1.0).contains(&a), "f32 w = {w}, u = {u}: {a}");
                assert!((-1.0..=1.0).contains(&b), "f64 w = {w}, u = {u}: {b}");
            }
            // At the ends the lobe sampler gives the mixture's poles.
            assert_eq!(p64.sample_cos_by_lobe(0.0), -1.0, "w = {w}");
            assert_eq!(p64.sample_cos_by_lobe(1.0), 1.0, "w = {w}");
        }
    }
}

/// The exact sample of the lobe `u` falls in, in f64 from `u` itself:
/// HG's factored forms multiplied through by the lobe's share `L`
/// (`x = u − o`, `y = o + L − u` and `L` exact in f64, so each factor
/// carries a few roundings), `1 + μ` or `1 − μ` whichever is smaller.
fn lobe_sample_at(g1: f64, g2: f64, w: f64, u: f64) -> f64 {
    let (g, o, l) = if u < w {
        (g1, 0.0, w)
    } else {
        (g2, w, 1.0 - w)
    };
    let (x, y) = (u - o, o + l - u);
    // μ(g, x, y) = −μ(−g, y, x).
    let (ga, x, y, s) = if g >= 0.0 {
        (g, x, y, 1.0)
    } else {
        (-g, y, x, -1.0)
    };
    let d = (1.0 - ga) * l + 2.0 * ga * x;
    let opm = 2.0 * x * (1.0 + ga) * (1.0 + ga) * ((1.0 - ga) * l + ga * x) / (d * d);
    let omm = 2.0 * y * (1.0 - ga) * (1.0 - ga) * (l + ga * x) / (d * d);
    s * if opm < 1.0 { opm - 1.0 } else { 1.0 - omm }
}

/// The f32 lobe choice of `p` (made from `g1, g2, w`) at `u` against the
/// exact lobe sample there: `excess(got, want)`, asserted to be at most
/// `bound`.
fn lobe_check(
    p: &Phase<f32>,
    (g1, g2, w): (f64, f64, f64),
    u: f32,
    bound: f64,
    excess: impl Fn(f64, f64) -> f64,
) -> f64 {
    let got = p.sample_cos_by_lobe(u) as f64;
    let want = lobe_sample_at(g1, g2, w, u as f64);
    let e = excess(got, want);
    assert!(
        e <= bound,
        "({g1}, {g2}, {w}) u = {u}: {got} against {want}"
    );
    e
}

/// `|got − want|`.
fn abs_error(got: f64, want: f64) -> f64 {
    (got - want).abs()
}

#[test]
fn f32_lobe_choice_is_within_half_an_ulp_of_the_lobe_sample() {
    // The f32 lobe choice computes in f64 where its error bound (module
    // docs of `phase::fog`) is below 2^20 ε: every (g1, g2, w) here. The
    // bound, fixed before the run: half an ULP of the result plus 1e-9
    // (a few ε · 2^20 is 5e-10).
    const G: [f64; 8] = [-0.99, -0.8, -0.3, -0.01, 0.01, 0.3, 0.8, 0.99];
    const W: [f64; 4] = [0.01, 0.3, 0.9, 0.99];
    let params: Vec<_> = G
        .into_iter()
        .flat_map(|g1| G.into_iter().flat_map(move |g2| W.map(|w| (g1, g2, w))))
        .collect();
    let worst = common::map_parallel(&params, |&(g1, g2, w)| {
        let p = Phase::<f32>::two_lobe_hg(g1 as f32, g2 as f32, w as f32).unwrap();
        let (g1, g2, w) = (g1 as f32 as f64, g2 as f32 as f64, w as f32 as f64);
        let mut worst = 0.0f64;
        let mut r = rng(9300);
        let us = (0..4000).map(|_| f32::uniform(&mut r)).chain([
            0.0,
            1.0,
            w as f32,
            (w as f32).next_up(),
            (w as f32).next_down(),
        ]);
        let beyond_half_ulp = |got: f64, want: f64| {
            let half_ulp = 0.5 * ((got as f32).abs().next_up() as f64 - (got as f32).abs() as f64);
            (got - want).abs() - half_ulp
        };
        for u in us {
            worst = nan_max(worst, lobe_check(&p, (g1, g2, w), u, 1e-9, beyond_half_ulp));
        }
        worst
    });
    let worst = worst.into_iter().fold(0.0, nan_max);
    eprintln!("f32 lobe choice: at most {worst:.1e} beyond half an ULP");
}

#[test]
fn f32_nearly_isotropic_lobes_stay_within_the_rescaled_bound() {
    // A lobe with |g| near 0 has a = (1 + g²)/2g beyond any bound: the f32
    // lobe choice's multiplied-through formula cancels there (a − b/t² of
    // two terms near 1/2g), so the object must take the rescaled path. Its
    // documented accuracy, fixed before the run: 3e-7 of the lobe's exact
    // sample (the lobe is smooth, so the rescaling of u moves the exact
    // sample by a few 1e-8 at most).
    let mut params = vec![];
    for tiny in [1e-30, 1e-20, 1e-12, 1e-9] {
        for g in [-tiny, tiny] {
            for (other, w) in [(0.5, 0.3), (-0.3, 0.7), (0.8, 0.5)] {
                params.push((g, other, w, true));
                params.push((other, g, 1.0 - w, false));
            }
        }
    }
    let worst = common::map_parallel(&params, |&(g1, g2, w, first)| {
        let p = Phase::<f32>::two_lobe_hg(g1 as f32, g2 as f32, w as f32).unwrap();
        let (g1, g2, w) = (g1 as f32 as f64, g2 as f32 as f64, w as f32 as f64);
        let mut r = rng(9400);
        let mut worst = 0.0f64;
        for _ in 0..4000 {
            // u inside the nearly isotropic lobe.
            let t = f64::uniform(&mut r);
            let u = if first { t * w } else { w + t * (1.0 - w) } as f32;
            if (u as f64 >= w) == first {
                continue;
            }
            worst = nan_max(worst, lobe_check(&p, (g1, g2, w), u, 3e-7, abs_error));
        }
        worst
    });
    let worst = worst.into_iter().fold(0.0, nan_max);
    eprintln!("f32 nearly isotropic lobes: at most {worst:.1e} from the exact lobe sample");
}

#[test]
fn f32_sharp_lobes_with_a_small_share_stay_within_the_rescaled_bound() {
    // A sharp lobe (g → 1) whose share of [0, 1] is a few f32 steps has an
    // error bound far past 2^20 (k = (1 − g)L cancels against 2g·w): the
    // multiplied-through formula is 4.5e-6 to 1e-5 off there, so these
    // objects take the rescaled path. Fixed before the run: 3e-7 of the
    // lobe's exact sample at every f32 u from 20 steps below the weight to
    // 1 (the rescaled path is within 3e-8 on them).
    let below_one = |k: u32| f32::from_bits(1.0f32.to_bits() - k);
    for (g1, g2, w) in [
        (0.5f32, 0.999f32, below_one(1)),
        (0.5, 0.9999, below_one(4)),
        (-0.5, 0.99, below_one(1)),
    ] {
        let p = Phase::<f32>::two_lobe_hg(g1, g2, w).unwrap();
        let mut u = f32::from_bits(w.to_bits() - 20);
        let params = (g1 as f64, g2 as f64, w as f64);
        while u <= 1.0 {
            lobe_check(&p, params, u, 3e-7, abs_error);
            u = u.next_up();
        }
    }
}
