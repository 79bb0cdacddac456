//! Majorant grids: delta and ratio tracking through them are unbiased
//! against the optical depth integrated along the ray (rays that start
//! inside, graze cell faces, run along them, pass through empty cells; node
//! and cell-centred grids; a world box), a majorant that does not bound the
//! density is caught, the budget is its own error, escapes report where the
//! ray leaves the box, and the built majorants bound the interpolated
//! density everywhere.

use crate::common;

use common::{Zero, rng};
use scatterkit::majorant::{DEFAULT_RES, Majorants, majorant_len};
use scatterkit::medium::Event;
use scatterkit::{Error, Grid, Ray, Real, Sampling, Vec3};

/// A cloud-like 12×10×9 density: a dense core, a thin shell, and empty
/// regions (a slab of zeros and a zero corner).
pub(crate) fn cloud() -> Vec<f64> {
    let n = [12usize, 10, 9];
    let mut v = Vec::with_capacity(n[0] * n[1] * n[2]);
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let p = [i, j, k].map(|x| x as f64);
                let c = [5.5, 4.5, 4.0];
                let r2: f64 = (0..3).map(|a| (p[a] - c[a]) * (p[a] - c[a])).sum();
                let core = 8.0 * (-r2 / 4.0).exp();
                let shell = 0.05 * (1.0 + (p[0] * 0.7).sin());
                let empty = i < 2 || (j > 7 && k > 6);
                v.push(if empty { 0.0 } else { core + shell });
            }
        }
    }
    v
}

/// `∫ σ_t` along the ray over `[0, t]` by composite Simpson (the
/// interpolated density is piecewise cubic along a ray; 40 000 panels).
pub(crate) fn optical_depth(g: &Grid<'_, f64>, o: Vec3<f64>, d: Vec3<f64>, t: f64) -> f64 {
    let d = d * (1.0 / d.length());
    let (sa, ss) = g.coefficients();
    let n = 40_000;
    let h = t / n as f64;
    let f = |s: f64| (sa + ss) * g.density(o + d * s);
    let mut sum = f(0.0) + f(t);
    for i in 1..n {
        sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

pub(crate) fn mean_se(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let v = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, (v / n).sqrt())
}

/// The rays: (origin, direction, t_max).
pub(crate) fn rays() -> Vec<(Vec3<f64>, Vec3<f64>, f64)> {
    vec![
        // From outside, through the core.
        (Vec3::new(-0.3, 0.45, 0.5), Vec3::new(1.0, 0.05, -0.02), 2.0),
        // Starting inside, ending inside.
        (Vec3::new(0.4, 0.5, 0.45), Vec3::new(0.3, -1.0, 0.4), 0.35),
        // Along a majorant face (y = 8/16 exactly) and a grid node plane.
        (Vec3::new(-0.1, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 3.0),
        // Grazing: nearly parallel to the z faces, crossing many x cells.
        (Vec3::new(0.0, 0.2, 0.25), Vec3::new(1.0, 0.3, 1e-7), 5.0),
        // Through the empty slab x < 2/11 and the empty corner.
        (Vec3::new(0.05, 0.95, 0.95), Vec3::new(0.0, -0.2, -1.0), 4.0),
        // Backwards along every axis, from a corner on a face.
        (Vec3::new(1.0, 1.0, 1.0), Vec3::new(-0.6, -0.5, -0.7), 9.0),
    ]
}

/// The four grids the unbiasedness tests run over (node- and
/// cell-centred, in the unit cube and in a world box), each with its rays
/// (`placed`): `f(grid, rays, case)`, `case` counting from 0.
pub(crate) fn for_each_grid(
    mut f: impl FnMut(&Grid<'_, f64>, &[(Vec3<f64>, Vec3<f64>, f64)], u64),
) {
    let values = cloud();
    let (lo, hi) = (Vec3::new(-0.5, -1.0, 0.25), Vec3::new(1.5, 0.5, 1.0));
    let mut case = 0;
    for sampling in [Sampling::Nodes, Sampling::Cells] {
        for boxed in [false, true] {
            let mut g = Grid::new(&values, 12, 10, 9, 0.4, 1.1)
                .unwrap()
                .with_sampling(sampling);
            if boxed {
                g = g.with_box(lo, hi).unwrap();
            }
            f(&g, &placed(boxed, lo, hi), case);
            case += 1;
        }
    }
}

/// The rays, written for the unit cube, mapped into `[lo, hi]` when
/// `boxed`.
pub(crate) fn placed(
    boxed: bool,
    lo: Vec3<f64>,
    hi: Vec3<f64>,
) -> Vec<(Vec3<f64>, Vec3<f64>, f64)> {
    let e = hi - lo;
    rays()
        .into_iter()
        .map(|(o, d, t)| {
            if boxed {
                (
                    Vec3::new(lo.x + o.x * e.x, lo.y + o.y * e.y, lo.z + o.z * e.z),
                    Vec3::new(d.x * e.x, d.y * e.y, d.z * e.z),
                    t,
                )
            } else {
                (o, d, t)
            }
        })
        .collect()
}

/// For both samplings and four resolutions, the built majorants (or, with
/// `minorants`, the minorants) of the cloud, and `holds(σ_t, bound)` checked
/// at 2·10⁵ random points against the bound of the cell holding each.
pub(crate) fn check_bounds(seed: u64, minorants: bool, holds: fn(f64, f64) -> bool) {
    let values = cloud();
    for sampling in [Sampling::Nodes, Sampling::Cells] {
        for m in [[1, 1, 1], [3, 5, 7], [16, 16, 16], [40, 3, 20]] {
            let g = Grid::new(&values, 12, 10, 9, 0.4, 1.1)
                .unwrap()
                .with_sampling(sampling);
            let mut store = vec![0.0; majorant_len(m).unwrap()];
            let bounds = if minorants {
                Majorants::build_minorants(&g, m, &mut store)
            } else {
                Majorants::build(&g, m, &mut store)
            }
            .unwrap();
            let mut r = rng(seed);
            for _ in 0..200_000 {
                let p = Vec3::new(
                    f64::uniform(&mut r),
                    f64::uniform(&mut r),
                    f64::uniform(&mut r),
                );
                let c = [p.x, p.y, p.z];
                let idx = [0, 1, 2].map(|a| ((c[a] * m[a] as f64) as usize).min(m[a] - 1));
                assert!(
                    holds(1.5 * g.density(p), bounds.get(idx[0], idx[1], idx[2])),
                    "{sampling:?} {m:?} at {p:?}"
                );
            }
        }
    }
}

#[test]
fn tracking_through_majorants_is_unbiased() {
    for_each_grid(|g, rays, case| {
        let mut store = [0.0; 16 * 16 * 16];
        let maj = Majorants::build(g, [DEFAULT_RES; 3], &mut store).unwrap();
        let mut r = rng(7 + case);
        for &(o, d, t_max) in rays {
            let p = (-optical_depth(g, o, d, t_max)).exp();
            let n = 40_000;
            let mut hits = 0usize;
            let mut absorbed = 0usize;
            let mut tr = Vec::with_capacity(n);
            for _ in 0..n {
                let tk = maj
                    .delta_track(g, Ray::new(o, d, t_max), 1 << 20, &mut r)
                    .unwrap();
                match tk.event {
                    Event::Escaped => {}
                    Event::Absorbed => {
                        hits += 1;
                        absorbed += 1;
                    }
                    _ => hits += 1,
                }
                tr.push(
                    maj.ratio_track(g, Ray::new(o, d, t_max), 1 << 20, &mut r)
                        .unwrap()
                        .tr,
                );
            }
            let q = 1.0 - hits as f64 / n as f64;
            let se = (p * (1.0 - p) / n as f64).sqrt().max(1e-12);
            assert!(
                (q - p).abs() <= 4.0 * se,
                "case {case}: P(escape) {q} vs {p} ± {se}, ray {o:?}"
            );
            let (m, se_r) = mean_se(&tr);
            assert!(
                (m - p).abs() <= 4.0 * se_r + 1e-12,
                "case {case}: ratio {m} ± {se_r} vs {p}, ray {o:?}"
            );
            if hits > 1000 {
                let share = absorbed as f64 / hits as f64;
                let a = 0.4 / 1.5;
                assert!(
                    (share - a).abs() <= 4.0 * (a * (1.0 - a) / hits as f64).sqrt(),
                    "absorbed share {share}"
                );
            }
        }
    });
}

#[test]
fn built_majorants_bound_the_density() {
    check_bounds(3, false, |sigma_t, bound| sigma_t <= bound);
}

#[test]
fn a_majorant_that_does_not_bound_is_caught() {
    // Mutation check: the built majorants scaled by 0.9 no longer bound the
    // core; tracking must report it rather than return a biased answer.
    let values = cloud();
    let g = Grid::new(&values, 12, 10, 9, 0.4, 1.1).unwrap();
    let mut store = [0.0; 16 * 16 * 16];
    Majorants::build(&g, [16; 3], &mut store).unwrap();
    for s in store.iter_mut() {
        *s *= 0.9;
    }
    let low = Majorants::new(
        &store,
        [16; 3],
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 1.0),
    )
    .unwrap();
    let (o, d) = (Vec3::new(-0.3, 0.45, 0.45), Vec3::new(1.0, 0.0, 0.0));
    let mut r = rng(9);
    let caught = (0..2000)
        .filter(|_| low.ratio_track(&g, Ray::new(o, d, 2.0), 1 << 20, &mut r) == Err(Error::Domain))
        .count();
    assert!(caught > 100, "caught {caught} of 2000");
    // A majorant grid over another box is refused for the grid.
    let other = Majorants::new(
        &store,
        [16; 3],
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 1.0, 1.0),
    )
    .unwrap();
    assert_eq!(
        other
            .delta_track(&g, Ray::new(o, d, 2.0), 100, &mut r)
            .err(),
        Some(Error::Domain)
    );
}

#[test]
fn values_changed_after_the_check_are_caught_where_a_walk_meets_them() {
    // Majorants loaded in constant time (`from_parts`, as the C layer loads
    // a caller's array) are checked per cell crossed: a negative, NaN or
    // infinite value on the ray is Domain for every estimator that walks
    // it, a bad value off the ray changes nothing.
    let values = cloud();
    let g = Grid::new(&values, 12, 10, 9, 0.4, 1.1).unwrap();
    let mut store = [0.0; 4 * 4 * 4];
    Majorants::build(&g, [4; 3], &mut store).unwrap();
    let (lo, hi) = g.bounds();
    // Along x at y = z = 0.1: cells (i, 0, 0).
    let ray = Ray::new(Vec3::new(-0.5, 0.1, 0.1), Vec3::new(1.0, 0.0, 0.0), 3.0);
    let good = store;
    let mut r = rng(12);
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        for (cell, on_ray) in [(2usize, true), (4 * 4 * 3 + 5, false)] {
            let mut s = good;
            s[cell] = bad;
            let m = Majorants::from_parts(&s, [4; 3], lo, hi).unwrap();
            let d = m.delta_track(&g, ray, 1 << 20, &mut r).map(|_| ());
            let t = m.ratio_track(&g, ray, 1 << 20, &mut r).map(|_| ());
            let tau = m.optical_depth(ray).map(|_| ());
            for found in [d, t, tau] {
                assert_eq!(found.is_err(), on_ray, "{bad} at {cell}: {found:?}");
                if on_ray {
                    assert_eq!(found, Err(Error::Domain));
                }
            }
        }
    }
    // from_parts checks what is cheap: sizes and the box.
    assert_eq!(
        Majorants::from_parts(&good[..63], [4; 3], lo, hi).err(),
        Some(Error::Size)
    );
    assert_eq!(
        Majorants::from_parts(&good, [4; 3], hi, lo).err(),
        Some(Error::Domain)
    );
}

#[test]
fn escapes_report_the_exit_and_budgets_run_out() {
    let values = [0.0f64; 8];
    let g = Grid::new(&values, 2, 2, 2, 1.0, 1.0)
        .unwrap()
        .with_box(Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 1.0))
        .unwrap();
    let mut store = [0.0; 8];
    let maj = Majorants::build(&g, [2; 3], &mut store).unwrap();
    let mut r = rng(1);
    let (o, d) = (Vec3::new(-1.0, 0.5, 0.5), Vec3::new(2.0, 0.0, 0.0));
    let tk = maj
        .delta_track(&g, Ray::new(o, d, 10.0), 0, &mut r)
        .unwrap();
    assert_eq!((tk.t, tk.event, tk.steps), (3.0, Event::Escaped, 0));
    // Ends inside: the exit is t_max; misses: t_min (0 for grids).
    assert_eq!(
        maj.delta_track(&g, Ray::new(o, d, 2.5), 0, &mut r)
            .unwrap()
            .t,
        2.5
    );
    let miss = maj.delta_track(&g, Ray::new(Vec3::new(-1.0, 5.0, 0.5), d, 10.0), 0, &mut r);
    assert_eq!(miss.unwrap().t, 0.0);
    // A dense medium and a small budget: its own error, not NaN.
    let dense = [1e3f64; 8];
    let g = Grid::new(&dense, 2, 2, 2, 1.0, 1.0).unwrap();
    let maj = Majorants::build(&g, [2; 3], &mut store).unwrap();
    let o = Vec3::new(-1.0, 0.5, 0.5);
    let d = Vec3::new(1.0, 0.0, 0.0);
    // Ratio tracking through σ_t = σ_maj stops at the first collision.
    assert_eq!(
        maj.ratio_track(&g, Ray::new(o, d, 10.0), 5, &mut r)
            .unwrap()
            .tr,
        0.0
    );
    let thin = [1e3f64, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3];
    let g = Grid::new(&thin, 2, 2, 2, 1.0, 1.0).unwrap();
    let maj1 = Majorants::build(&g, [1; 3], &mut store).unwrap();
    let far = Vec3::new(-1.0, 0.9, 0.9);
    assert_eq!(
        maj1.delta_track(&g, Ray::new(far, d, 10.0), 3, &mut r)
            .err(),
        Some(Error::Budget)
    );
    // Bad input.
    let z = Vec3::new(0.0, 0.0, 0.0);
    assert_eq!(
        maj1.delta_track(&g, Ray::new(far, z, 1.0), 3, &mut r).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        maj1.delta_track(&g, Ray::new(far, d, f64::NAN), 3, &mut r)
            .err(),
        Some(Error::Domain)
    );
    assert_eq!(
        Majorants::new(&store, [0, 1, 1], z, d).err(),
        Some(Error::Size)
    );
    assert_eq!(
        Majorants::new(&store, [1, 1, 1], z, z).err(),
        Some(Error::Domain)
    );
    assert_eq!(
        Majorants::<f64>::build(&g, [9, 9, 9], &mut store).err(),
        Some(Error::Size)
    );
}

#[test]
fn no_valid_ray_or_budget_yields_nan() {
    // Random media (2–5 values per axis, thin to dense, empty parts, node or
    // cell sampling, a random world box), random majorant resolutions, rays
    // (inside, outside, axis-parallel, some infinite) and budgets: every
    // result is finite and in range, or the budget error.
    let mut r = rng(77);
    let mut u = move || f64::uniform(&mut r);
    let mut r2 = rng(78);
    let mut store = [0.0f64; 6 * 6 * 6];
    for case in 0..3000 {
        let n = [0, 1, 2].map(|_| 2 + (u() * 4.0) as usize);
        let scale = 10f64.powf(5.0 * u() - 2.0);
        let mut values = [0.0f64; 125];
        for v in values.iter_mut() {
            *v = if u() < 0.3 { 0.0 } else { scale * u() * u() };
        }
        let lo = Vec3::new(4.0 * u() - 2.0, 4.0 * u() - 2.0, 4.0 * u() - 2.0);
        let hi = lo + Vec3::new(0.1 + 3.0 * u(), 0.1 + 3.0 * u(), 0.1 + 3.0 * u());
        let sampling = if u() < 0.5 {
            Sampling::Nodes
        } else {
            Sampling::Cells
        };
        let g = Grid::new(&values, n[0], n[1], n[2], u(), u())
            .unwrap()
            .with_box(lo, hi)
            .unwrap()
            .with_sampling(sampling);
        let m = [0, 1, 2].map(|_| 1 + (u() * 6.0) as usize);
        let maj = Majorants::build(&g, m, &mut store).unwrap();
        let axis = |x: f64| if x < 0.2 { 0.0 } else { 2.0 * x - 1.0 };
        let o = Vec3::new(8.0 * u() - 4.0, 8.0 * u() - 4.0, 8.0 * u() - 4.0);
        let d = Vec3::new(axis(u()), axis(u()), axis(u()));
        if d.x == 0.0 && d.y == 0.0 && d.z == 0.0 {
            continue;
        }
        let t_max = if u() < 0.1 { f64::INFINITY } else { 10.0 * u() };
        let budget = if u() < 0.2 {
            (u() * 5.0) as u32
        } else {
            1 << 20
        };
        match maj.ratio_track(&g, Ray::new(o, d, t_max), budget, &mut r2) {
            Ok(tr) => assert!(tr.tr.is_finite() && tr.tr >= 0.0, "case {case}: {tr:?}"),
            Err(e) => assert_eq!(e, Error::Budget, "case {case}"),
        }
        match maj.delta_track(&g, Ray::new(o, d, t_max), budget, &mut r2) {
            Ok(tk) => assert!(tk.t >= 0.0 && tk.t <= t_max, "case {case}: {tk:?}"),
            Err(e) => assert_eq!(e, Error::Budget, "case {case}"),
        }
    }
}

#[test]
fn ratio_tracking_through_majorants_ends_once_the_transmittance_is_gone() {
    // σ_maj = 10 σ_t over 10⁵ mean free paths, through a caller's medium.
    let sigma = [10.0f64];
    let big = Vec3::new(2e5, 1.0, 1.0);
    let maj = Majorants::new(&sigma, [1; 3], Vec3::new(-1.0, 0.0, 0.0), big).unwrap();
    let mut r = rng(5);
    for _ in 0..200 {
        let tr = maj
            .ratio_track_fn(
                |_| (0.5, 0.5),
                Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 1e5).segment(0.0, 1e5),
                10_000,
                &mut r,
            )
            .unwrap();
        assert_eq!(tr.tr, 0.0);
        assert!(tr.steps < 10_000);
    }
}

/// The built majorants bound the density on each cell's faces and one
/// float inside them, where random points never land (a mutation test
/// narrowed the slop that widens each cell's reach over the lattice, and
/// no test saw it): 1-D grids with one spike of 1000 on a floor of 1, at
/// every node in turn, and cell counts that put faces just above or below
/// a node.
#[test]
fn majorants_bound_the_density_on_every_cell_face() {
    // The float after `x ≥ 0`, and the one before `x > 0`.
    let (up, down) = (
        |x: f64| f64::from_bits(x.to_bits() + 1),
        |x: f64| f64::from_bits(x.to_bits() - 1),
    );
    for sampling in [Sampling::Nodes, Sampling::Cells] {
        for (n, m) in [(1002, 3), (1001, 3), (1000, 3), (64, 5), (10, 7), (2, 3)] {
            for spike in 0..n {
                let mut values = vec![1.0; n];
                values[spike] = 1000.0;
                let g = Grid::new(&values, n, 1, 1, 0.5, 0.5)
                    .unwrap()
                    .with_sampling(sampling);
                let mut store = vec![0.0; m];
                let maj = Majorants::build(&g, [m, 1, 1], &mut store).unwrap();
                for c in 0..m {
                    let (lo, hi) = (c as f64 / m as f64, (c + 1) as f64 / m as f64);
                    let inside = (1..16).map(|k| lo + (hi - lo) * k as f64 / 16.0);
                    let faces = [lo, up(lo), hi, down(hi)];
                    for x in faces.into_iter().chain(inside) {
                        let rho = g.density(Vec3::new(x, 0.5, 0.5));
                        assert!(
                            rho <= maj.get(c, 0, 0),
                            "{sampling:?} n = {n}, m = {m}, spike at {spike}, cell {c}, x = {x}: \
                             {rho} above {}",
                            maj.get(c, 0, 0)
                        );
                    }
                }
            }
        }
    }
}

/// `get` is 0 outside the grid on each axis alone, and the stored value
/// inside (a mutation test found `get` past one axis's end untested: it
/// read another cell).
#[test]
fn get_is_zero_outside_on_every_axis() {
    let sigma: Vec<f64> = (1..=12).map(|v| v as f64).collect();
    let maj = Majorants::new(
        &sigma,
        [3, 2, 2],
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 1.0),
    )
    .unwrap();
    for (i, j, k) in [
        (3, 0, 0),
        (0, 2, 0),
        (0, 0, 2),
        (3, 1, 0),
        (2, 2, 1),
        (1, 1, 2),
    ] {
        assert_eq!(maj.get(i, j, k), 0.0, "({i}, {j}, {k})");
    }
    for (i, j, k) in [(0, 0, 0), (2, 1, 0), (1, 0, 1), (2, 1, 1)] {
        assert_eq!(maj.get(i, j, k), sigma[i + 3 * (j + 2 * k)]);
    }
}

/// An empty cell (majorant 0) is crossed without a draw, as documented,
/// so a seed's draws do not depend on how many empty cells a ray crosses
/// (a mutation test let the walk draw once in each, unnoticed).
#[test]
fn an_empty_cell_is_crossed_without_a_draw() {
    let sigma = [2.0, 0.0, 0.0, 2.0];
    let maj = Majorants::new(
        &sigma,
        [4, 1, 1],
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 1.0),
    )
    .unwrap();
    let mut r = crate::common::Counting::new(3);
    // From inside cell 1 to inside cell 2: only empty cells.
    let ray = Ray::new(Vec3::new(0.3, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 0.4);
    let hit = maj
        .delta_track_fn(|_| (0.0, 0.0), ray, 100, &mut r)
        .unwrap();
    assert_eq!((hit.event, r.1), (Event::Escaped, 0));
    let tr = maj
        .ratio_track_fn(|_| (0.0, 0.0), ray, 100, &mut r)
        .unwrap();
    assert_eq!((tr.tr, tr.steps, r.1), (1.0, 0, 0));
}

/// A uniform of exactly 0 at a real collision of a medium that does not
/// absorb scatters (a mutation test let `ξ σ_maj ≤ σ_t` collide where
/// `ξ σ_maj = σ_t`, unnoticed).
#[test]
fn a_medium_that_does_not_absorb_scatters_at_a_uniform_of_zero() {
    let ray = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), 1.0);
    let track = |coefficients: fn(Vec3<f64>) -> (f64, f64)| {
        scatterkit::majorant::one_majorant_delta_track(coefficients, 1.0, ray, 100, &mut Zero)
    };
    assert_eq!(track(|_| (0.0, 1.0)).unwrap().event, Event::Scattered);
    // Nor does a vacuum collide (`ξ σ_maj ≤ σ_t` would scatter there):
    // every step is 0, so the walk stays put until the budget runs out.
    assert_eq!(track(|_| (0.0, 0.0)).err(), Some(Error::Budget));
}
