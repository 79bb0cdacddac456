//! Spectral media (hero-wavelength tracking): with the hero drawn uniformly
//! among four channels (one of them purely absorbing, one with no
//! scattering), every channel's one-sample-MIS estimates equal its own
//! single-wavelength values integrated along the ray: transmittance from
//! ratio tracking (`weight / mean(r_l)`), and from delta tracking the
//! escape, absorption and scattering shares (`weight / mean(r_u)` on each
//! event). Plus bad input.

use crate::common;

use common::{Zero, rng};
use scatterkit::majorant::Majorants;
use scatterkit::medium::Event;
use scatterkit::spectral::{MAX_CHANNELS, Ratios, Spectrum};
use scatterkit::{Error, Grid, Ray, Real, Vec3};

const SA: [f64; 4] = [0.1, 0.4, 0.0, 0.02];
const SS: [f64; 4] = [0.5, 1.1, 2.0, 0.0];

/// A 6×5×4 density with a dense middle, thin edges and a zero corner.
fn density() -> Vec<f64> {
    let mut v = Vec::new();
    for k in 0..4 {
        for j in 0..5 {
            for i in 0..6 {
                let r2 = ((i as f64 - 2.5).powi(2)
                    + (j as f64 - 2.0).powi(2)
                    + (k as f64 - 1.5).powi(2))
                    / 4.0;
                v.push(if i == 0 && j == 0 {
                    0.0
                } else {
                    3.0 * (-r2).exp() + 0.1
                });
            }
        }
    }
    v
}

/// Along the ray (unit `d`) over `[0, t]`: `(∫ρ, ∫ e^{−k τ(s)} ρ(s) ds)` per
/// channel coefficient `k`, τ the density integral so far (trapezoids,
/// 2·10⁵ panels).
fn along(g: &Grid<'_, f64>, o: Vec3<f64>, d: Vec3<f64>, t: f64, k: f64) -> (f64, f64) {
    let n = 200_000;
    let h = t / n as f64;
    let (mut tau, mut hit) = (0.0, 0.0);
    let mut prev = g.density(o);
    for i in 1..=n {
        let rho = g.density(o + d * (i as f64 * h));
        let step = 0.5 * (prev + rho) * h;
        // e^{−kτ} ρ over the panel, to second order.
        hit += (-k * (tau + 0.5 * step)).exp() * step;
        tau += step;
        prev = rho;
    }
    (tau, hit)
}

fn mean_se(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let v = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, (v / n).sqrt())
}

#[test]
fn hero_tracking_matches_every_channel_alone() {
    let values = density();
    let g = Grid::new(&values, 6, 5, 4, 1.0, 0.0).unwrap();
    let mut store = [0.0; 4 * 4 * 4];
    let maj = Majorants::build_density(&g, [4; 3], &mut store).unwrap();
    let mut r = rng(21);
    let rays = [
        (Vec3::new(-0.5, 0.45, 0.5), Vec3::new(1.0, 0.1, 0.0), 3.0),
        (Vec3::new(0.5, 0.5, 0.5), Vec3::new(-0.3, 0.2, 1.0), 0.4),
        (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0), 5.0),
    ];
    let n = 60_000;
    for (o, d, t_max) in rays {
        let d = d * (1.0 / d.length());
        let mut ratio: Vec<Vec<f64>> = (0..4).map(|_| Vec::with_capacity(n)).collect();
        let mut events = vec![
            [
                Vec::with_capacity(n),
                Vec::with_capacity(n),
                Vec::with_capacity(n)
            ];
            4
        ];
        for _ in 0..n {
            let hero = ((f64::uniform(&mut r) * 4.0) as usize).min(3);
            let s = Spectrum {
                sigma_a: &SA,
                sigma_s: &SS,
                hero,
            };
            let (mut w, mut u, mut l) = ([0.0; 4], [0.0; 4], [0.0; 4]);
            let mut out = Ratios {
                weight: &mut w,
                r_u: &mut u,
                r_l: &mut l,
            };
            maj.ratio_track_spectral(&g, &s, Ray::new(o, d, t_max), 1 << 20, &mut r, &mut out)
                .unwrap();
            let ml = l.iter().sum::<f64>() / 4.0;
            for c in 0..4 {
                ratio[c].push(w[c] / ml);
            }
            let mut out = Ratios {
                weight: &mut w,
                r_u: &mut u,
                r_l: &mut l,
            };
            let tk = maj
                .delta_track_spectral(&g, &s, Ray::new(o, d, t_max), 1 << 20, &mut r, &mut out)
                .unwrap();
            let mu = u.iter().sum::<f64>() / 4.0;
            for c in 0..4 {
                let e = w[c] / mu;
                let which = match tk.event {
                    Event::Escaped => 0,
                    Event::Absorbed => 1,
                    _ => 2,
                };
                for (k, list) in events[c].iter_mut().enumerate() {
                    list.push(if k == which { e } else { 0.0 });
                }
            }
        }
        for c in 0..4 {
            let k = SA[c] + SS[c];
            let (tau, hit) = along(&g, o, d, t_max, k);
            let tr = (-k * tau).exp();
            let expected = [tr, SA[c] * hit, SS[c] * hit];
            let (m, se) = mean_se(&ratio[c]);
            assert!(
                (m - tr).abs() <= 4.0 * se + 1e-12,
                "ray {o:?} channel {c}: ratio {m} ± {se} vs {tr}"
            );
            for (e, (list, name)) in expected
                .iter()
                .zip(events[c].iter().zip(["escape", "absorb", "scatter"]))
            {
                let (m, se) = mean_se(list);
                assert!(
                    (m - e).abs() <= 4.0 * se + 1e-12,
                    "ray {o:?} channel {c}: {name} {m} ± {se} vs {e}"
                );
            }
        }
    }
}

#[test]
fn spectral_bad_input() {
    let values = density();
    let g = Grid::new(&values, 6, 5, 4, 1.0, 0.0).unwrap();
    let mut store = [0.0; 8];
    let maj = Majorants::build_density(&g, [2; 3], &mut store).unwrap();
    let mut r = rng(1);
    let (o, d) = (Vec3::new(-0.5, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0));
    let (mut w, mut u, mut l) = (
        [7.0; MAX_CHANNELS + 1],
        [7.0; MAX_CHANNELS + 1],
        [7.0; MAX_CHANNELS + 1],
    );
    let big = [0.5; MAX_CHANNELS + 1];
    let mut run = |sa: &[f64], ss: &[f64], hero: usize, n_out: usize, d: Vec3<f64>| {
        let s = Spectrum {
            sigma_a: sa,
            sigma_s: ss,
            hero,
        };
        let mut out = Ratios {
            weight: &mut w[..n_out],
            r_u: &mut u[..n_out],
            r_l: &mut l[..n_out],
        };
        maj.ratio_track_spectral(&g, &s, Ray::new(o, d, 2.0), 1 << 20, &mut r, &mut out)
            .err()
    };
    assert_eq!(run(&[], &[], 0, 4, d), Some(Error::Size));
    assert_eq!(run(&big, &big, 0, MAX_CHANNELS + 1, d), Some(Error::Size));
    assert_eq!(run(&SA, &SS[..3], 0, 4, d), Some(Error::Size));
    assert_eq!(run(&SA, &SS, 0, 3, d), Some(Error::Size));
    assert_eq!(run(&SA, &SS, 4, 4, d), Some(Error::Domain));
    assert_eq!(
        run(&[0.1, -0.1, 0.0, 0.0], &SS, 0, 4, d),
        Some(Error::Domain)
    );
    assert_eq!(
        run(&SA, &[0.1, f64::NAN, 0.0, 0.0], 0, 4, d),
        Some(Error::Domain)
    );
    assert_eq!(
        run(&SA, &SS, 0, 4, Vec3::new(0.0, 0.0, 0.0)),
        Some(Error::Domain)
    );
    // The failures wrote nothing.
    assert!(w.iter().chain(&u).chain(&l).all(|&x| x == 7.0));
    let s = Spectrum {
        sigma_a: &SA,
        sigma_s: &SS,
        hero: 1,
    };
    let mut out = Ratios {
        weight: &mut w,
        r_u: &mut u,
        r_l: &mut l,
    };
    assert!(
        maj.ratio_track_spectral(&g, &s, Ray::new(o, d, 2.0), 1 << 20, &mut r, &mut out)
            .is_ok()
    );
    assert!(w[..4].iter().all(|&x| x != 7.0) && w[4..].iter().all(|&x| x == 7.0));
    // One output short beside two that hold every channel (a mutation
    // test's `&&` → `||` in the length check went unnoticed).
    for short in 0..3 {
        let n = |k: usize| if k == short { 3 } else { 4 };
        let (mut w, mut u, mut l) = ([7.0; 4], [7.0; 4], [7.0; 4]);
        let mut out = Ratios {
            weight: &mut w[..n(0)],
            r_u: &mut u[..n(1)],
            r_l: &mut l[..n(2)],
        };
        assert_eq!(
            maj.ratio_track_spectral(&g, &s, Ray::new(o, d, 2.0), 1 << 20, &mut r, &mut out)
                .err(),
            Some(Error::Size),
            "output {short} short"
        );
    }
}

/// Hero delta tracking with a generator stuck on 0 (every step 0, every
/// uniform 0) from inside a 2 × 2 × 2 grid of constant `density` under a
/// density majorant of 1, hero channel 0.
fn stuck_hero_walk(
    density: f64,
    sigma_a: &[f64; 2],
    sigma_s: &[f64; 2],
) -> Result<scatterkit::majorant::Track<f64>, Error> {
    let values = [density; 8];
    let g = Grid::new(&values, 2, 2, 2, 1.0, 1.0).unwrap();
    let (lo, hi) = g.bounds();
    let maj = Majorants::new(&[1.0], [1; 3], lo, hi).unwrap();
    let s = Spectrum {
        sigma_a,
        sigma_s,
        hero: 0,
    };
    let (mut w, mut u, mut l) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    let mut out = Ratios {
        weight: &mut w,
        r_u: &mut u,
        r_l: &mut l,
    };
    let ray = Ray::new(Vec3::new(0.5, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 0.25);
    maj.delta_track_spectral(&g, &s, ray, 100, &mut Zero, &mut out)
}

/// A uniform of exactly 0 in an empty region is a null collision for the
/// hero, as for a single channel (a mutation test let `ξ σ_maj ≤ σ_t`
/// scatter there, with a zero pdf, unnoticed): every step is 0, so the
/// walk stays put until the budget runs out.
#[test]
fn a_vacuum_does_not_collide_at_a_uniform_of_zero() {
    let got = stuck_hero_walk(0.0, &[0.5, 0.25], &[0.5, 1.0]);
    assert_eq!(got.err(), Some(Error::Budget));
}

/// A medium that does not absorb scatters at a uniform of 0 (a mutation
/// test let `ξ σ_maj ≤ σ_a` absorb there), and a density above its
/// majorant is refused by both spectral trackers (a mutation test let it
/// through, unnoticed).
#[test]
fn no_absorption_at_zero_and_low_majorants_are_refused() {
    let (sigma_a, sigma_s) = ([0.0, 0.0], [1.0, 0.5]);
    let hit = stuck_hero_walk(1.0, &sigma_a, &sigma_s);
    assert_eq!(hit.unwrap().event, Event::Scattered);
    // Density majorants of ½ under a density of 1.
    let ones = [1.0; 8];
    let g = Grid::new(&ones, 2, 2, 2, 1.0, 1.0).unwrap();
    let (lo, hi) = g.bounds();
    let low = Majorants::new(&[0.5], [1; 3], lo, hi).unwrap();
    let s = Spectrum {
        sigma_a: &sigma_a,
        sigma_s: &sigma_s,
        hero: 0,
    };
    let (mut w, mut u, mut l) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    let mut out = Ratios {
        weight: &mut w,
        r_u: &mut u,
        r_l: &mut l,
    };
    let long = Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 1.0);
    // With every step 0 the first tentative collision is at the origin.
    let hit = low.delta_track_spectral(&g, &s, long, 1 << 20, &mut Zero, &mut out);
    assert_eq!(hit.err(), Some(Error::Domain));
    let mut r = rng(13);
    let mut refused = 0;
    for _ in 0..16 {
        let tr = low.ratio_track_spectral(&g, &s, long, 1 << 20, &mut r, &mut out);
        // Refused at the first tentative collision; none on the ray
        // (probability e^{−½}) is the only way through.
        assert!(matches!(tr, Err(Error::Domain) | Ok(0)), "{tr:?}");
        refused += usize::from(tr.is_err());
    }
    assert!(refused > 0);
}

/// Delta tracking's `r_l` is the channel's free-flight density over the
/// hero's path density, as pbrt-v4 keeps it: with one channel, every null
/// collision multiplies it by `m/(m − ρ)` (the majorant's density over
/// the null collision's), so a path that escapes a constant density of ½
/// under a majorant of 1 carries `r_l = 2^steps`, `r_u = 1` and weight 1
/// (a mutation test's `k·m` → `k + m` in the factor went unnoticed: no
/// test read delta tracking's `r_l`).
#[test]
fn delta_tracking_keeps_the_free_flight_ratio() {
    let half = [0.5; 8];
    let g = Grid::new(&half, 2, 2, 2, 1.0, 1.0).unwrap();
    let (lo, hi) = g.bounds();
    let maj = Majorants::from_parts(&[1.0], [1; 3], lo, hi).unwrap();
    let s = Spectrum {
        sigma_a: &[0.25],
        sigma_s: &[0.75],
        hero: 0,
    };
    let ray = Ray::new(Vec3::new(-0.5, 0.5, 0.5), Vec3::new(1.0, 0.0, 0.0), 2.0);
    let mut r = rng(17);
    let mut checked = 0;
    for _ in 0..256 {
        let (mut w, mut u, mut l) = ([0.0], [0.0], [0.0]);
        let mut out = Ratios {
            weight: &mut w,
            r_u: &mut u,
            r_l: &mut l,
        };
        let tk = maj.delta_track_spectral(&g, &s, ray, 1 << 20, &mut r, &mut out);
        let tk = tk.unwrap();
        if tk.event == Event::Escaped && tk.steps > 0 {
            let want = 2f64.powi(tk.steps as i32);
            assert!(
                (l[0] - want).abs() <= 1e-12 * want,
                "{} steps: {}",
                tk.steps,
                l[0]
            );
            assert!((u[0] - 1.0).abs() <= 1e-12 && (w[0] - 1.0).abs() <= 1e-12);
            checked += 1;
        }
    }
    assert!(checked >= 32, "{checked}");
}
