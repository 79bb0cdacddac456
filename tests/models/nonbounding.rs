//! Majorants that do not bound (`medium::nonbounding`): ratio tracking
//! with signed weights and weighted delta tracking stay unbiased at 4σ
//! (4·10⁴ estimates per ray) on the four grids and six rays of
//! `majorant.rs` with every majorant cut to 60 %, where the strict
//! trackers refuse; weighted delta tracking reproduces the escape,
//! absorption and early-collision probabilities of a homogeneous medium
//! under a majorant at 40 % of `σ_t`, where clamping the density to the
//! majorant (the usual fallback) fails the same check, for delta and for
//! ratio tracking; the excess is reported in the right cell.

use super::majorant::{cloud, for_each_grid, mean_se, optical_depth};
use crate::common::nan_max;
use crate::common::rng;
use scatterkit::majorant::Majorants;
use scatterkit::medium::Event;
use scatterkit::medium::nonbounding::Exceeded;
use scatterkit::{Error, Grid, Ray, Vec3};

const N: usize = 40_000;

fn close(what: &str, xs: &[f64], want: f64) {
    let (m, se) = mean_se(xs);
    assert!(
        (m - want).abs() <= 4.0 * se + 1e-12,
        "{what}: {m} ± {se} vs {want}"
    );
}

/// The cloud's coefficients at `p`, from its grid.
fn coefficients<'a>(g: &'a Grid<'_, f64>) -> impl Fn(Vec3<f64>) -> (f64, f64) + 'a {
    let (sa, ss) = g.coefficients();
    move |p| {
        let r = g.density(p);
        (sa * r, ss * r)
    }
}

/// Every majorant of the cloud's 16³ grid cut to 60 %, over the four
/// grids and six rays of `majorant.rs`: signed ratio tracking and the
/// weighted escape of delta tracking against `exp(−τ)`; through the core
/// the bound fails (and the strict tracker refuses), and no excess above
/// 1/0.6 is reported.
#[test]
fn both_are_unbiased_under_low_majorants() {
    for_each_grid(|g, rays, case| {
        let mut store = [0.0; 16 * 16 * 16];
        let (lo, hi) = g.bounds();
        let tight = Majorants::build(g, [16; 3], &mut store).unwrap();
        let mut r = rng(71 + case);
        let (o, d, t_max) = rays[0];
        let t = tight
            .ratio_track_signed_fn(coefficients(g), Ray::new(o, d, t_max), 1 << 20, &mut r)
            .unwrap();
        assert_eq!(t.exceeded, None, "true majorants exceed nothing");
        let low: Vec<f64> = store.iter().map(|s| 0.6 * s).collect();
        let low = Majorants::new(&low, [16; 3], lo, hi).unwrap();
        for (k, &(o, d, t_max)) in rays.iter().enumerate() {
            let ray = Ray::new(o, d, t_max);
            let want = (-optical_depth(g, o, d, t_max)).exp();
            let mut worst: f64 = 1.0;
            let (mut tr, mut escaped) = (Vec::with_capacity(N), Vec::with_capacity(N));
            for _ in 0..N {
                let t = low
                    .ratio_track_signed_fn(coefficients(g), ray, 1 << 20, &mut r)
                    .unwrap();
                worst = nan_max(worst, t.exceeded.map_or(1.0, |e| e.ratio));
                tr.push(t.tr);
                let w = low
                    .delta_track_weighted_fn(coefficients(g), ray, 1 << 20, &mut r)
                    .unwrap();
                escaped.push(if w.event == Event::Escaped {
                    w.weight
                } else {
                    0.0
                });
            }
            close(
                &format!("case {case} ray {k}: signed ratio tracking"),
                &tr,
                want,
            );
            close(
                &format!("case {case} ray {k}: weighted delta tracking"),
                &escaped,
                want,
            );
            assert!(
                worst <= 1.0 / 0.6 + 1e-12,
                "case {case} ray {k}: ratio {worst}"
            );
            if k == 0 {
                assert!(worst > 1.2, "case {case} ray 0: ratio {worst}");
                let refused = (0..100)
                    .filter(|_| {
                        let t = low.ratio_track_fn(coefficients(g), ray, 1 << 20, &mut r);
                        t.err() == Some(Error::Domain)
                    })
                    .count();
                assert!(refused > 10, "the strict tracker refused {refused} of 100");
            }
        }
    });
}

/// A homogeneous medium, `σ_a = 0.3`, `σ_s = 0.9`, under one majorant of
/// 0.5 over the unit cube, crossed along x (length 1): the weighted
/// outcome gives `P(escape) = e^{−1.2}`, `P(absorbed) = ¼(1 − e^{−1.2})`
/// and `P(real collision before ½) = 1 − e^{−0.6}`; clamping the density
/// to the majorant escapes with `e^{−0.5}` and fails.
#[test]
fn a_homogeneous_medium_under_a_low_majorant() {
    let (maj, ray) = unit_cell(&[0.5]);
    let mut r = rng(73);
    let (mut esc, mut abs, mut early) = (vec![], vec![], vec![]);
    for _ in 0..N {
        let t = maj
            .delta_track_weighted_fn(|_| (0.3, 0.9), ray, 1 << 20, &mut r)
            .unwrap();
        let w = t.weight;
        esc.push(if t.event == Event::Escaped { w } else { 0.0 });
        abs.push(if t.event == Event::Absorbed { w } else { 0.0 });
        // The box starts at t = 1 along this ray.
        early.push(if t.event != Event::Escaped && t.t <= 1.5 {
            w
        } else {
            0.0
        });
        assert!(
            t.exceeded
                .is_some_and(|e: Exceeded<f64>| (e.ratio - 2.4).abs() < 1e-12)
                || t.steps == 0
        );
    }
    close("escape", &esc, (-1.2f64).exp());
    close("absorbed", &abs, 0.25 * -(-1.2f64).exp_m1());
    close("collision before ½", &early, -(-0.6f64).exp_m1());
    let signed: Vec<f64> = (0..N)
        .map(|_| {
            maj.ratio_track_signed_fn(|_| (0.3, 0.9), ray, 1 << 20, &mut r)
                .unwrap()
                .tr
        })
        .collect();
    close("signed ratio tracking", &signed, (-1.2f64).exp());
    // Ratio tracking with its factors clamped at 0 (the density clamped
    // to the majorant) fails.
    let clamped: Vec<f64> = (0..N)
        .map(|_| {
            maj.ratio_track_fn(|_| (0.125, 0.375), ray, 1 << 20, &mut r)
                .unwrap()
                .tr
        })
        .collect();
    let (m, se) = mean_se(&clamped);
    assert!(
        (m - (-1.2f64).exp()).abs() > 4.0 * se,
        "clamped ratio tracking passes: {m} ± {se}"
    );
    // The usual fallback: the density clamped to the majorant.
    let clamped: Vec<f64> = (0..N)
        .map(|_| {
            let t = maj
                .delta_track_fn(|_| (0.125, 0.375), ray, 1 << 20, &mut r)
                .unwrap();
            if t.event == Event::Escaped { 1.0 } else { 0.0 }
        })
        .collect();
    let (m, se) = mean_se(&clamped);
    assert!(
        (m - (-1.2f64).exp()).abs() > 4.0 * se,
        "clamping passes: {m} ± {se}"
    );
}

/// One majorant cell of an otherwise bounding grid cut to a quarter: every
/// excess reported is in that cell.
#[test]
fn the_excess_is_reported_where_it_is() {
    let values = cloud();
    let g = Grid::new(&values, 12, 10, 9, 0.4, 1.1).unwrap();
    let mut store = [0.0; 8 * 8 * 8];
    let (lo, hi) = g.bounds();
    Majorants::build(&g, [8; 3], &mut store).unwrap();
    // The cell holding the core's centre (5.5/11, 4.5/9, 4/8).
    let cell = [3usize, 4, 4];
    store[cell[0] + 8 * (cell[1] + 8 * cell[2])] *= 0.25;
    let maj = Majorants::new(&store, [8; 3], lo, hi).unwrap();
    let ray = Ray::new(Vec3::new(-0.1, 0.5, 0.53), Vec3::new(1.0, 0.0, 0.0), 3.0);
    let mut r = rng(74);
    let mut seen = 0;
    for _ in 0..2000 {
        let t = maj
            .ratio_track_signed_fn(coefficients(&g), ray, 1 << 20, &mut r)
            .unwrap();
        if let Some(e) = t.exceeded {
            assert_eq!(e.cell, cell);
            assert!(e.ratio > 1.0 && e.ratio <= 4.0 + 1e-9, "{}", e.ratio);
            seen += 1;
        }
    }
    assert!(seen > 100, "seen {seen} times");
}

/// Coefficients of any finite size are taken, however far above the
/// majorant: their sum must be finite, and a call is refused only when the
/// weight it carries overflows. σ_a = σ_s = 10¹⁶⁰ under a majorant of 1
/// multiply the weight by 4·10¹⁶⁰ at each tentative collision, so a walk
/// with at most one of them (most, over a path of length 1) returns a
/// finite weight; a walk with two overflows and is refused.
#[test]
fn huge_finite_coefficients_are_taken() {
    let (maj, ray) = unit_cell(&[1.0]);
    let mut r = rng(5);
    let mut taken = 0;
    for _ in 0..64 {
        match maj.delta_track_weighted_fn(|_| (1e160f64, 1e160f64), ray, 1 << 20, &mut r) {
            Ok(t) => {
                assert!(t.weight.is_finite() && t.steps <= 1, "{t:?}");
                taken += 1;
            }
            Err(e) => assert_eq!(e, Error::Domain),
        }
    }
    assert!(taken >= 32, "{taken} of 64 taken");
}

/// A negative coefficient is refused on either side, alone (a mutation
/// test accepted a negative one beside a positive one, unnoticed), by both
/// trackers.
#[test]
fn a_negative_coefficient_is_refused_on_either_side() {
    let (maj, ray) = unit_cell(&[1.0]);
    let mut r = rng(6);
    for c in [(-0.25, 0.5), (0.5, -0.25), (-0.25, -0.25)] {
        // The first tentative collision inside the box reads them: refused
        // unless the ray escapes first (then nothing was read).
        let coefficients = move |_: Vec3<f64>| c;
        let (mut refused, mut escaped) = (0, 0);
        for _ in 0..64 {
            match maj.ratio_track_signed_fn(coefficients, ray, 1 << 20, &mut r) {
                Err(Error::Domain) => refused += 1,
                Ok(t) if t.steps == 0 => escaped += 1,
                other => panic!("{c:?}: {other:?}"),
            }
            match maj.delta_track_weighted_fn(coefficients, ray, 1 << 20, &mut r) {
                Err(Error::Domain) => refused += 1,
                Ok(t) if t.steps == 0 => escaped += 1,
                other => panic!("{c:?}: {other:?}"),
            }
        }
        assert!(
            refused > 64 && refused + escaped == 128,
            "{c:?}: {refused} refused"
        );
    }
}

/// At a uniform of exactly 0, weighted delta tracking absorbs only where
/// σ_a > 0 and collides only where σ_t > 0 (mutation tests let `x < σ_a`
/// → `≤` absorb in a medium that does not absorb, and `x < σ_t` → `≤`
/// scatter in a vacuum): a medium of (σ_a, σ_s) = (0, 1) scatters where
/// the ray enters the box; in a vacuum every tentative collision is null
/// and every step 0, so the walk stays put until its budget runs out. A
/// medium exactly at its majorant is bounded: no excess is reported
/// (`ratio > 1` → `≥`, another, reported one of ratio 1).
#[test]
fn a_uniform_of_zero_neither_absorbs_nor_collides_where_nothing_does() {
    use crate::common::Zero;
    let (maj, ray) = unit_cell(&[1.0]);
    let hit = maj.delta_track_weighted_fn(|_| (0.0, 1.0), ray, 16, &mut Zero);
    let hit = hit.unwrap();
    assert_eq!((hit.t, hit.event, hit.weight), (1.0, Event::Scattered, 1.0));
    let vacuum = maj.delta_track_weighted_fn(|_| (0.0, 0.0), ray, 16, &mut Zero);
    assert_eq!(vacuum.err(), Some(Error::Budget));
    let mut r = rng(9);
    let at_majorant = |_: Vec3<f64>| (0.25, 0.75);
    let mut crossed = 0;
    for _ in 0..64 {
        let tr = maj.ratio_track_signed_fn(at_majorant, ray, 1 << 20, &mut r);
        let w = maj.delta_track_weighted_fn(at_majorant, ray, 1 << 20, &mut r);
        let (tr, w) = (tr.unwrap(), w.unwrap());
        assert!(tr.exceeded.is_none() && w.exceeded.is_none());
        crossed += (tr.steps > 0) as u32 + (w.steps > 0) as u32;
    }
    assert!(crossed > 64, "{crossed}");
}

/// The roulette runs on the signed weight's magnitude, as documented:
/// with each tentative collision multiplying the weight by exactly ½, an
/// estimate is 0 or a power of two no smaller than 2⁻⁴ (the first below
/// 0.05 is 2⁻⁵, which the roulette sets to 0 or 2⁻³), and none above 1;
/// without the roulette (a mutation test's `|tr| < 0.05` → `== 0.05`,
/// unnoticed) smaller powers appear on long rays, and with it played above
/// the threshold (`> 0.05`, another) weights of 2 and more.
#[test]
fn the_signed_roulette_keeps_weights_above_its_threshold() {
    let one = [1.0];
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(8.0, 1.0, 1.0));
    let maj = Majorants::new(&one, [1; 3], lo, hi).unwrap();
    // Eight mean free paths of the majorant.
    let ray = Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 8.0);
    let mut r = rng(7);
    let mut survived = 0;
    for _ in 0..4000 {
        let t = maj
            .ratio_track_signed_fn(|_| (0.25, 0.25), ray, 1 << 20, &mut r)
            .unwrap();
        assert!(t.tr == 0.0 || (0.0625..=1.0).contains(&t.tr), "{t:?}");
        if t.tr > 0.0 && t.steps >= 5 {
            survived += 1;
        }
    }
    assert!(survived > 0);
}

/// One cell of majorant `value` over the unit box, and a ray along x from
/// one unit before it to two past it.
fn unit_cell(value: &[f64; 1]) -> (Majorants<'_, f64>, Ray<f64>) {
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let maj = Majorants::new(value, [1; 3], lo, hi).unwrap();
    let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 3.0);
    (maj, ray)
}
