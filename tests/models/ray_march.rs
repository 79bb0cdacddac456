//! The unbiased ray-marching transmittance estimators
//! (`medium::ray_march`: the power series and the telescoping sum):
//! unbiased against the optical depth integrated along the ray over the
//! rays and grids of `majorant.rs`, 4·10⁴ rays per case at 4σ, with the
//! step count from the majorant optical depth; the check rejects the
//! biased ray marcher (`exp(−X)` of one march alone) and a telescoping sum
//! whose corrections have the wrong sign; exact for a constant medium;
//! through a callback; variance × density evaluations against ratio
//! tracking.

use super::majorant::{cloud, for_each_grid, mean_se, optical_depth, rays};
use crate::common::rng;
use scatterkit::majorant::Majorants;
use scatterkit::medium::ray_march::{
    MAX_LEVEL, MAX_ORDER, Placement, Series, march_grid_within, march_within,
    ray_march_transmittance, ray_march_transmittance_fn, telescoping_transmittance,
    telescoping_transmittance_fn,
};
use scatterkit::{Error, Grid, Ray, Real, Vec3};

/// Strata for a ray: the majorant optical depth rounded up, at least 1.
fn strata(maj: &Majorants<'_, f64>, ray: Ray<f64>) -> u32 {
    maj.optical_depth(ray).unwrap().ceil().max(1.0) as u32
}

/// Unbiased on every ray of every case; the biased marcher (one jittered
/// march, `exp(−X)`, which Jensen's inequality pulls above `exp(−τ)`) with
/// the same strata fails the check on the ray through the core in every
/// case.
#[test]
fn ray_marching_is_unbiased() {
    unbiased(ray_march_transmittance, 90);
}

/// The telescoping member, as [`ray_marching_is_unbiased`].
#[test]
fn telescoping_is_unbiased() {
    unbiased(telescoping_transmittance, 190);
}

type Estimator = fn(
    &Grid<'_, f64>,
    Ray<f64>,
    u32,
    u32,
    &mut rand_xoshiro::Xoshiro256PlusPlus,
) -> Result<scatterkit::majorant::Transmittance<f64>, Error>;

fn unbiased(estimator: Estimator, seed: u64) {
    for_each_grid(|g, rays, case| {
        let mut store = [0.0; 16 * 16 * 16];
        let maj = Majorants::build(g, [16; 3], &mut store).unwrap();
        let mut r = rng(seed + case);
        for (k, &(o, d, t_max)) in rays.iter().enumerate() {
            let ray = Ray::new(o, d, t_max);
            let n = strata(&maj, ray);
            let p = (-optical_depth(g, o, d, t_max)).exp();
            let tr: Vec<f64> = (0..40_000)
                .map(|_| estimator(g, ray, n, 1 << 24, &mut r).unwrap().tr)
                .collect();
            let (m, se) = mean_se(&tr);
            assert!(
                (m - p).abs() <= 4.0 * se + 1e-12,
                "case {case} ray {k}: {m} ± {se} vs {p} ({n} strata)"
            );
            if k == 0 {
                let biased: Vec<f64> = (0..40_000)
                    .map(|_| (-march(g, o, d, t_max, n, f64::uniform(&mut r))).exp())
                    .collect();
                let (mb, sb) = mean_se(&biased);
                assert!(
                    (mb - p).abs() > 4.0 * sb,
                    "case {case}: the biased marcher passes ({mb} ± {sb} vs {p})"
                );
            }
        }
    });
}

/// One jittered march of `∫ σ_t` over `[0, t_max]` with `n` strata and
/// offset `u` (the test's own, for the biased marcher).
fn march(g: &Grid<'_, f64>, o: Vec3<f64>, d: Vec3<f64>, t_max: f64, n: u32, u: f64) -> f64 {
    let d = d * (1.0 / d.length());
    let (sa, ss) = g.coefficients();
    let h = t_max / n as f64;
    (0..n)
        .map(|j| (sa + ss) * g.density(o + d * ((j as f64 + u) * h)) * h)
        .sum()
}

/// A constant medium marches exactly: every estimate of both members is
/// `exp(−σ ℓ)`.
#[test]
fn a_constant_medium_has_zero_variance() {
    let values = [2.5f64; 27];
    let g = Grid::new(&values, 3, 3, 3, 0.3, 0.9).unwrap();
    let mut r = rng(6);
    // Along x through the middle: 1 unit inside the box.
    let ray = Ray::new(Vec3::new(-0.5, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 3.0);
    let want = (-3.0f64).exp();
    for _ in 0..1000 {
        let t = ray_march_transmittance(&g, ray, 4, 1 << 10, &mut r).unwrap();
        assert!((t.tr - want).abs() <= 1e-12, "{} vs {want}", t.tr);
        let t = telescoping_transmittance(&g, ray, 4, 1 << 20, &mut r).unwrap();
        assert!(
            (t.tr - want).abs() <= 1e-12,
            "telescoping: {} vs {want}",
            t.tr
        );
    }
}

/// Through a callback: a spherical blob `σ_t = σ₀ (1 − r²/R²)` of radius
/// `R` crossed through its centre, `τ = 4σ₀R/3`; both members unbiased
/// at 4σ; a
/// negative coefficient and an infinite segment are `Error::Domain`.
#[test]
fn through_a_callback() {
    let (s0, rad) = (3.0f64, 0.8f64);
    let c = Vec3::new(0.0, 0.0, 0.0);
    let blob = move |p: Vec3<f64>| {
        let q = p - c;
        let r2 = q.dot(q) / (rad * rad);
        (0.0, (s0 * (1.0 - r2)).max(0.0))
    };
    let ray = Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), 2.0);
    let p = (-4.0 * s0 * rad / 3.0).exp();
    let mut r = rng(12);
    let tr: Vec<f64> = (0..40_000)
        .map(|_| {
            ray_march_transmittance_fn(blob, ray, 8, 1 << 20, &mut r)
                .unwrap()
                .tr
        })
        .collect();
    let (m, se) = mean_se(&tr);
    assert!((m - p).abs() <= 4.0 * se, "{m} ± {se} vs {p}");
    let tr: Vec<f64> = (0..40_000)
        .map(|_| {
            telescoping_transmittance_fn(blob, ray, 8, 1 << 24, &mut r)
                .unwrap()
                .tr
        })
        .collect();
    let (m, se) = mean_se(&tr);
    assert!((m - p).abs() <= 4.0 * se, "telescoping: {m} ± {se} vs {p}");
    let bad = |_: Vec3<f64>| (-1.0, 0.0);
    assert_eq!(
        ray_march_transmittance_fn(bad, ray, 8, 100, &mut r).err(),
        Some(Error::Domain)
    );
    let endless = Ray::new(ray.origin, ray.dir, f64::INFINITY);
    assert_eq!(
        ray_march_transmittance_fn(blob, endless, 8, 100, &mut r).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        ray_march_transmittance_fn(blob, ray, 0, 100, &mut r).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        ray_march_transmittance_fn(blob, ray, 8, 7, &mut r).err(),
        Some(Error::Budget)
    );
}

/// Variance × density evaluations per ray on the cloud, against ratio
/// tracking with the same 16³ majorants (printed; the figures are in
/// `docs/guides/media.md`, which says ray marching is better per
/// evaluation on every ray: asserted where either has a variance).
#[test]
fn variance_and_cost_against_ratio_tracking() {
    let values = cloud();
    let g = Grid::new(&values, 12, 10, 9, 0.4, 1.1).unwrap();
    let mut store = [0.0; 16 * 16 * 16];
    let maj = Majorants::build(&g, [16; 3], &mut store).unwrap();
    let mut r = rng(13);
    let n = 20_000;
    for (k, (o, d, t_max)) in rays().into_iter().enumerate() {
        let ray = Ray::new(o, d, t_max);
        let strata = strata(&maj, ray);
        let (mut a, mut b, mut sa, mut sb) = (vec![], vec![], 0u64, 0u64);
        for _ in 0..n {
            let x = maj.ratio_track(&g, ray, 1 << 20, &mut r).unwrap();
            let y = ray_march_transmittance(&g, ray, strata, 1 << 20, &mut r).unwrap();
            (sa, sb) = (sa + x.steps as u64, sb + y.steps as u64);
            a.push(x.tr);
            b.push(y.tr);
        }
        let var = |v: &[f64]| {
            let (_, se) = mean_se(v);
            se * se * v.len() as f64
        };
        let (ca, cb) = (sa as f64 / n as f64, sb as f64 / n as f64);
        let (va, vb) = (var(&a), var(&b));
        let gain = if vb * cb > 0.0 {
            format!("{:.1}× lower", (va * ca) / (vb * cb))
        } else {
            "ray marching exact".to_string()
        };
        assert!(
            va * ca == 0.0 || vb * cb < va * ca,
            "ray {k}: ray marching {:.3e} vs ratio tracking {:.3e}",
            vb * cb,
            va * ca
        );
        eprintln!(
            "ray {k}: ratio var {va:.3e} × {ca:.2} evals, ray marching ({strata} strata) var {vb:.3e} × {cb:.2} evals: {gain}"
        );
    }
}

/// Strata placed by the majorants (`march_within`): unbiased on every
/// ray of every case with 8³ and 64³ extrema, both series, at their
/// default strata; with 64³ cells the grazing and diagonal rays cross more
/// than the 96 cells a walk keeps, so the marches walk again, and must
/// agree all the same.
#[test]
fn strata_placed_by_the_majorants_are_unbiased() {
    use scatterkit::medium::residual::Extrema;
    for res in [8usize, 64] {
        for (si, series) in [Series::Power, Series::Telescoping].into_iter().enumerate() {
            for_each_grid(|g, rays, case| {
                let len = res * res * res;
                let (mut max, mut min) = (vec![0.0; len], vec![0.0; len]);
                let ext = Extrema::build(g, [res; 3], &mut max, &mut min).unwrap();
                let place = Placement {
                    max: ext.majorants(),
                    min: Some(ext.minorants()),
                };
                let mut r = rng(300 + 10 * case + si as u64 + res as u64);
                for (k, &(o, d, t_max)) in rays.iter().enumerate() {
                    let ray = Ray::new(o, d, t_max);
                    let p = (-optical_depth(g, o, d, t_max)).exp();
                    let tr: Vec<f64> = (0..20_000)
                        .map(|_| march_grid_within(series, place, g, ray, 0, 1 << 24, &mut r))
                        .map(|x| x.unwrap().tr)
                        .collect();
                    let (m, se) = mean_se(&tr);
                    let z = (m - p) / se.max(1e-12);
                    assert!(
                        z.abs() < 4.0,
                        "{series:?}, {res}³, case {case}, ray {k}: {m} vs {p} (z = {z:.2})"
                    );
                }
            });
        }
    }
}

/// With minorants equal to the majorants (a medium constant in each cell)
/// the residual is 0 everywhere: the estimate is `exp(−∫σ_min)`, exact,
/// with no evaluation, whatever the strata; a ray that misses the box is
/// 1, with none.
#[test]
fn no_residual_is_exact_with_no_evaluation() {
    let values = [0.7f64; 27];
    let g = Grid::new(&values, 3, 3, 3, 0.5, 1.5).unwrap();
    let cells = [1.4f64; 8];
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let m = Majorants::new(&cells, [2; 3], lo, hi).unwrap();
    let place = Placement {
        max: m,
        min: Some(m),
    };
    let ray = Ray::new(Vec3::new(-1.0, 0.3, 0.4), Vec3::new(1.0, 0.0, 0.0), 5.0);
    for strata in [0, 1, 7] {
        for series in [Series::Power, Series::Telescoping] {
            let t = march_grid_within(series, place, &g, ray, strata, 10, &mut rng(1)).unwrap();
            assert_eq!(t.steps, 0);
            assert!((t.tr - (-1.4f64).exp()).abs() < 1e-15, "{}", t.tr);
        }
    }
    let miss = Ray::new(Vec3::new(-1.0, 3.0, 0.4), Vec3::new(1.0, 0.0, 0.0), 5.0);
    let t = march_grid_within(Series::Power, place, &g, miss, 0, 10, &mut rng(1)).unwrap();
    assert_eq!((t.tr, t.steps), (1.0, 0));
}

/// Bounds that do not hold are refused, never used: a density above its
/// cell's majorant where a point lands, a minorant above its majorant, a
/// majorant changed to NaN; a grid in another box; and a spent budget.
#[test]
fn placed_strata_refuse_bounds_that_do_not_hold() {
    let values = [0.7f64; 27];
    let g = Grid::new(&values, 3, 3, 3, 0.5, 1.5).unwrap();
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let ray = Ray::new(Vec3::new(-1.0, 0.3, 0.4), Vec3::new(1.0, 0.0, 0.0), 5.0);
    let low = [1.0f64; 8];
    let (ok, zero) = ([2.0f64; 8], [0.0f64; 8]);
    let mut nan = ok;
    nan[0] = f64::NAN;
    let run = |max: &[f64; 8], min: Option<&[f64; 8]>, budget: u32| {
        let max = Majorants::from_parts(max, [2; 3], lo, hi).unwrap();
        let min = min.map(|m| Majorants::from_parts(m, [2; 3], lo, hi).unwrap());
        let place = Placement { max, min };
        march_grid_within(Series::Power, place, &g, ray, 0, budget, &mut rng(2))
    };
    assert_eq!(run(&low, None, 1000).unwrap_err(), Error::Domain);
    assert_eq!(run(&ok, Some(&[3.0; 8]), 1000).unwrap_err(), Error::Domain);
    assert_eq!(run(&nan, Some(&zero), 1000).unwrap_err(), Error::Domain);
    assert_eq!(run(&ok, Some(&zero), 3).unwrap_err(), Error::Budget);
    assert!(run(&ok, Some(&zero), 1000).is_ok());
    let other = Majorants::new(&ok, [2; 3], lo, Vec3::new(2.0, 1.0, 1.0)).unwrap();
    let place = Placement {
        max: other,
        min: None,
    };
    let r = march_grid_within(Series::Power, place, &g, ray, 0, 1000, &mut rng(2));
    assert_eq!(r.unwrap_err(), Error::Domain);
}

/// The strata the library picks when the caller passes 0, exactly as
/// documented: ⌈4τ⌉ for the power series, 16⌈τ⌉ for the telescoping sum,
/// at least 1; a depth needing more than `u32::MAX` strata is a spent
/// budget, a negative, NaN or infinite one refused.
#[test]
fn default_strata_are_the_documented_counts() {
    for (depth, power, telescoping) in [
        (0.0, 1, 1),
        (0.1, 1, 16),
        (0.25, 1, 16),
        (1.0, 4, 16),
        (1.01, 5, 32),
        (2.6, 11, 48),
        (100.0, 400, 1600),
    ] {
        assert_eq!(Series::Power.default_strata(depth), Ok(power), "τ {depth}");
        assert_eq!(
            Series::Telescoping.default_strata(depth),
            Ok(telescoping),
            "τ {depth}"
        );
    }
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            Series::Power.default_strata(bad),
            Err(Error::Domain),
            "τ {bad}"
        );
    }
    // More strata than a u32 holds: more evaluations than any budget.
    let (most_power, most_telescoping) = (f64::from(u32::MAX) / 4.0, 268_435_455.0);
    assert_eq!(Series::Power.default_strata(most_power), Ok(u32::MAX));
    assert_eq!(
        Series::Telescoping.default_strata(most_telescoping),
        Ok(u32::MAX - 15)
    );
    for series in [Series::Power, Series::Telescoping] {
        for long in [2e9, 1e300] {
            assert_eq!(series.default_strata(long), Err(Error::Budget), "τ {long}");
        }
    }
}

/// A path whose majorant depth is not finite (an infinite majorant met on
/// the way) is refused even when the caller fixes the strata, not marched.
#[test]
fn an_infinite_majorant_depth_is_refused() {
    let values = [0.7f64; 27];
    let g = Grid::new(&values, 3, 3, 3, 0.5, 1.5).unwrap();
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let ray = Ray::new(Vec3::new(-1.0, 0.3, 0.4), Vec3::new(1.0, 0.0, 0.0), 5.0);
    let inf = [f64::INFINITY; 8];
    let max = Majorants::from_parts(&inf, [2; 3], lo, hi).unwrap();
    for strata in [0, 7] {
        for series in [Series::Power, Series::Telescoping] {
            let place = Placement { max, min: None };
            let r = march_grid_within(series, place, &g, ray, strata, 1000, &mut rng(3));
            assert_eq!(r.unwrap_err(), Error::Domain, "{strata} strata");
        }
    }
}

/// A medium exactly at its majorant is within it, as documented: marched,
/// not refused, and (constant) estimated exactly by both series (a
/// mutation test's `σ > σ_maj` → `≥` refused it, unnoticed: every other
/// test's bound had room).
#[test]
fn a_medium_at_its_majorant_is_marched() {
    let half = [0.5f64];
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let max = Majorants::from_parts(&half, [1; 3], lo, hi).unwrap();
    let ray = Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 1.0);
    for series in [Series::Power, Series::Telescoping] {
        let place = Placement { max, min: None };
        let got = march_within(
            series,
            place,
            |_| (0.25, 0.25),
            ray,
            4,
            1 << 20,
            &mut rng(4),
        );
        let tr = got.unwrap().tr;
        assert!((tr - (-0.5f64).exp()).abs() < 1e-12, "{series:?}: {tr}");
    }
}

/// An optical depth that overflows `T` but not f64 (f32, σ_t = 3·10³⁸
/// over a length of 10) is refused by both series, as documented (a
/// mutation test's `fine && coarse` finite `|| diff` finite took it: the
/// sums are finite in f64, and the difference of coarse and fine too).
#[test]
fn a_depth_that_overflows_f32_is_refused() {
    let ray = Ray::new(Vec3::new(0.0f32, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), 10.0);
    let dense = |_: Vec3<f32>| (0.0f32, 3e38f32);
    let mut r = rng(11);
    for _ in 0..32 {
        let power = ray_march_transmittance_fn(dense, ray, 4, 1 << 20, &mut r);
        assert_eq!(power.err(), Some(Error::Domain));
        let telescoping = telescoping_transmittance_fn(dense, ray, 4, 1 << 20, &mut r);
        assert_eq!(telescoping.err(), Some(Error::Domain));
    }
}

/// The telescoping sum's deepest level is [`MAX_LEVEL`], as documented: a
/// generator whose every uniform is 0 passes every level's coin, so one
/// stratum marches at levels 0 to 24 (`2^k` points each, `2²⁵ − 1` density
/// evaluations) and the next coin ends it with [`Error::Budget`] (a
/// mutation test stopped a level earlier, unnoticed: reached with
/// probability `3^−24`, no random test gets there). That coin is drawn:
/// failed, it returns the estimate (another ended the loop before it).
#[test]
fn every_coin_passing_ends_past_the_deepest_level() {
    let [stuck, last_fails] = zeros_then_last_fails(Series::Telescoping);
    assert_eq!(stuck.0.err(), Some(Error::Budget));
    assert_eq!(stuck.1, (1u64 << (MAX_LEVEL + 1)) - 1);
    assert!(last_fails.0.unwrap().is_finite());
    assert_eq!((last_fails.1, last_fails.2), (stuck.1, stuck.2));
}

/// The power series is cut at [`MAX_ORDER`], as documented: with every
/// roulette passed (uniforms of 0), one stratum marches `MAX_ORDER + 1`
/// times and the next order ends it with [`Error::Budget`]; with the last
/// roulette failed, the estimate of those marches is returned (a mutation
/// test's array of `MAX_ORDER` marches, one short, cut a term earlier,
/// unnoticed: reached with probability below 10⁻²³).
#[test]
fn every_roulette_passing_ends_past_the_highest_order() {
    let [stuck, last_fails] = zeros_then_last_fails(Series::Power);
    assert_eq!(stuck.0.err(), Some(Error::Budget));
    assert_eq!(stuck.1, u64::from(MAX_ORDER) + 1);
    assert!(last_fails.0.unwrap().is_finite());
    assert_eq!((last_fails.1, last_fails.2), (stuck.1, stuck.2));
}

/// One stratum of a constant medium estimated by `series` twice: with
/// every uniform 0 (every coin or roulette passed), then with the same
/// draws but the last, a uniform of `1 − 2⁻⁵³`. Each run's estimate,
/// density evaluations and draws.
fn zeros_then_last_fails(series: Series) -> [(Result<f64, Error>, u64, u64); 2] {
    let count = core::cell::Cell::new(0u64);
    let medium = |_: Vec3<f64>| {
        count.set(count.get() + 1);
        (0.25, 0.25)
    };
    let ray = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), 1.0);
    let run = |zeros: u64| {
        count.set(0);
        let mut g = ZeroThenOne { zeros, drawn: 0 };
        let got = match series {
            Series::Power => ray_march_transmittance_fn(medium, ray, 1, u32::MAX, &mut g),
            Series::Telescoping => telescoping_transmittance_fn(medium, ray, 1, u32::MAX, &mut g),
        };
        (got.map(|t| t.tr), count.get(), g.drawn)
    };
    let stuck = run(u64::MAX);
    [stuck, run(stuck.2 - 1)]
}

/// A generator giving `zeros` words of 0 (uniforms of 0), then words of
/// all ones (uniforms of `1 − 2⁻⁵³`), counting its draws.
struct ZeroThenOne {
    zeros: u64,
    drawn: u64,
}

impl rand_xoshiro::rand_core::TryRng for ZeroThenOne {
    type Error = core::convert::Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
        self.try_next_u64().map(|x| (x >> 32) as u32)
    }
    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        self.drawn += 1;
        Ok(if self.drawn <= self.zeros {
            0
        } else {
            u64::MAX
        })
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
        dst.fill(0);
        Ok(())
    }
}

/// The budget is the most density evaluations a call may make: a call
/// that needs `k` succeeds with a budget of `k`, with the same estimate and
/// count, and ends with [`Error::Budget`] at `k − 1` (a mutation test's
/// `steps > budget` → `≥` went unnoticed), for both series.
#[test]
fn a_budget_of_exactly_the_evaluations_needed_suffices() {
    let medium = |p: Vec3<f64>| (0.0, 1.0 + p.x);
    let ray = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), 2.0);
    let estimate = |telescoping: bool, budget: u32, seed: u64| {
        let mut r = rng(seed);
        if telescoping {
            telescoping_transmittance_fn(medium, ray, 4, budget, &mut r)
        } else {
            ray_march_transmittance_fn(medium, ray, 4, budget, &mut r)
        }
    };
    for (name, telescoping) in [("power", false), ("telescoping", true)] {
        for seed in 0..16 {
            let free = estimate(telescoping, u32::MAX, seed).unwrap();
            let k = free.steps;
            let exact = estimate(telescoping, k, seed).unwrap();
            assert_eq!(
                (exact.tr.to_bits(), exact.steps),
                (free.tr.to_bits(), k),
                "{name}, seed {seed}"
            );
            assert_eq!(
                estimate(telescoping, k - 1, seed).err(),
                Some(Error::Budget),
                "{name}, seed {seed}: {k} evaluations"
            );
        }
    }
}
