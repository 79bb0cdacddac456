//! The chooser against tabulated data (`choose::mie::choose_measured`,
//! `sk_phase_new_particle_measured_f64`), and the scene Fournier–Forand is built
//! for: Mie averaged over a Junge (power-law) distribution of ocean
//! particles.
//!
//! Thresholds, fixed before the first run:
//! * a tabulated HG (g = 0.8, 4001 cosines) is recognised as HG within
//!   0.01, with g within 2·10⁻³;
//! * a droplet tabulated at `mie::table_sizes` gives every distance
//!   `choose_mie` gives for it within 3 % plus 2·10⁻³ (the two place the
//!   quantiles differently: an angle grid against the exact linear
//!   density);
//! * in the ocean scenes the chosen model's distance agrees with an
//!   independent integral within 5 % plus 10⁻³ (as `tests/models/choose_mie.rs`),
//!   two-lobe HG is never farther than one HG, and the fitted
//!   Fournier–Forand is never farther than Fournier–Forand with the scene's
//!   own `n` and slope (plus the 10⁻³ of the quadrature).
//!
//! `SK_BLESS=1` writes `docs/measured/ocean_particles.md`.

use scatterkit::choose::fog::Model;
use scatterkit::choose::mie::{WORK_LEN, buffer_len, choose_measured, choose_mie};
use scatterkit::mie::{
    Complex, Mie, buffer_len as mie_buffer_len, size_parameter, table_angle, table_sizes, water,
};
use scatterkit::phase::FournierForand;
use scatterkit::polydisperse::{Polydisperse, SizeDistribution};
use scatterkit::{Error, Phase, PhaseFunction};
use std::f64::consts::PI;

/// The data's density per steradian at `mu`: linear in `μ` between the
/// points (as the chooser and `Table::measured` read it), normalised.
fn linear(cos: &[f64], pdf: &[f64]) -> impl Fn(f64) -> f64 {
    // Increasing order.
    let mut pts: Vec<(f64, f64)> = cos.iter().copied().zip(pdf.iter().copied()).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let area: f64 = pts
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
        .sum();
    move |mu: f64| {
        let k = pts.partition_point(|p| p.0 < mu);
        if k == 0 || k == pts.len() {
            return if k == 0 && mu == pts[0].0 {
                pts[0].1 / area / (2.0 * PI)
            } else {
                0.0
            };
        }
        let ((x0, p0), (x1, p1)) = (pts[k - 1], pts[k]);
        let t = (mu - x0) / (x1 - x0);
        ((1.0 - t) * p0 + t * p1) / area / (2.0 * PI)
    }
}

/// `½ ∫ |p − p_ref| dω` by trapezoids on `steps` equal steps in θ.
fn direct_tv(reference: &dyn Fn(f64) -> f64, p: &dyn Fn(f64) -> f64, steps: usize) -> f64 {
    let h = PI / steps as f64;
    // sin θ = 0 at the ends: a finite density contributes nothing there,
    // and Fournier–Forand's integrable forward pole would give ∞ · 0.
    let f = |i: usize| {
        let t = i as f64 * h;
        if i == 0 || i == steps {
            return 0.0;
        }
        (p(t.cos()) - reference(t.cos())).abs() * t.sin()
    };
    let inner: f64 = (1..steps).map(f).sum();
    PI * h * (inner + 0.5 * (f(0) + f(steps)))
}

fn choose(cos: &[f64], pdf: &[f64], tol: f64, table: bool) -> scatterkit::choose::mie::MieChoice {
    let mut work = vec![0.0; WORK_LEN];
    choose_measured(cos, pdf, tol, table, &mut work).unwrap()
}

#[test]
fn a_tabulated_hg_is_recognised() {
    let hg = Phase::<f64>::henyey_greenstein(0.8).unwrap();
    let n = 4001;
    let cos: Vec<f64> = (0..n)
        .map(|j| (PI * j as f64 / (n - 1) as f64).cos())
        .collect();
    let pdf: Vec<f64> = cos.iter().map(|&c| hg.pdf(c)).collect();
    let c = choose(&cos, &pdf, 0.01, false);
    println!("{:?} {} {:?}", c.model, c.distance, c.distances);
    assert_eq!(c.model, Model::HenyeyGreenstein);
    assert!(c.within_tolerance && c.distance <= 0.01);
    let g = c.phase.unwrap().mean_cosine();
    assert!((g - 0.8).abs() <= 2e-3, "g {g}");
    assert!(c.x.is_nan() && c.m.re.is_nan() && c.distances[4].is_nan());
    // With a table allowed the reference itself is never needed here.
    let t = choose(&cos, &pdf, 0.01, true);
    assert_eq!(t.model, Model::HenyeyGreenstein);
    // A tolerance no model meets: the table, distance 0.
    let t = choose(&cos, &pdf, 1e-9, true);
    assert!(t.model == Model::MieTable && t.distance == 0.0 && t.phase.is_none());
}

/// Molecules and aerosol in one cell: a tabulated `0.3 Rayleigh +
/// 0.7 HG(0.75)` is recognised as the Rayleigh + HG mixture within 0.01
/// (thresholds fixed before the run), with g within 0.01 and the weight
/// within 0.02; no single model (HG, Rayleigh, Draine) is that close.
#[test]
fn molecules_and_aerosol_are_recognised_as_the_mixture() {
    let hg = Phase::<f64>::henyey_greenstein(0.75).unwrap();
    let ray = Phase::<f64>::rayleigh();
    let n = 4001;
    let cos: Vec<f64> = (0..n)
        .map(|j| (PI * j as f64 / (n - 1) as f64).cos())
        .collect();
    let pdf: Vec<f64> = cos
        .iter()
        .map(|&c| 0.3 * ray.pdf(c) + 0.7 * hg.pdf(c))
        .collect();
    let c = choose(&cos, &pdf, 0.01, false);
    println!("{:?} {} {:?}", c.model, c.distance, c.distances);
    assert_eq!(c.model, Model::RayleighHg);
    assert!(c.within_tolerance && c.distance <= 0.01, "{}", c.distance);
    assert!(c.distances[1] > 0.01 && c.distances[2] > 0.01 && c.distances[3] > 0.01);
    match c.phase.unwrap() {
        Phase::Fog(f) => {
            let (g_hg, g_d, alpha, w_d) = f.params();
            assert!(
                (g_hg - 0.75).abs() <= 0.01 && (w_d - 0.3).abs() <= 0.02,
                "{g_hg} {w_d}"
            );
            assert!(g_d == 0.0 && alpha == 1.0, "{g_d} {alpha}");
        }
        p => panic!("{p:?}"),
    }
}

#[test]
fn a_tabulated_droplet_gives_the_distances_choose_mie_gives() {
    let (d, lambda) = (2.0, 0.55);
    let m = water(lambda).unwrap();
    let x = size_parameter(d, lambda, 1.0);
    let mut buf = vec![Complex::default(); mie_buffer_len(x, m).unwrap()];
    let mie = Mie::new(x, m, &mut buf).unwrap();
    let count = table_sizes(x).0;
    let (mut cos, mut pdf) = (vec![0.0; count], vec![0.0; count]);
    mie.tabulate(&mut cos, &mut pdf).unwrap();
    let a = choose(&cos, &pdf, 0.01, false);
    let mut buf = vec![Complex::default(); buffer_len(d, lambda, None).unwrap()];
    let mut work = vec![0.0; WORK_LEN];
    let b = choose_mie(d, lambda, None, 0.01, false, &mut buf, &mut work).unwrap();
    for (i, (&da, &db)) in a.distances.iter().zip(&b.distances).enumerate() {
        if i == 4 {
            assert!(da.is_nan(), "no fog fit from data");
            continue;
        }
        println!("candidate {i}: measured {da:.4e}, Mie {db:.4e}");
        assert!(
            (da - db).abs() <= 0.03 * db + 2e-3,
            "candidate {i}: {da} vs {db}"
        );
    }
}

#[test]
fn bad_input_is_rejected() {
    let mut work = vec![0.0; WORK_LEN];
    let cos = [-1.0, 0.0, 1.0];
    let pdf = [1.0, 1.0, 1.0];
    let mut go = |c: &[f64], p: &[f64], tol: f64, w: usize| {
        choose_measured(c, p, tol, false, &mut work[..w]).map(|c| c.model)
    };
    assert!(go(&cos, &pdf, 0.1, WORK_LEN).is_ok());
    for tol in [0.0, 1.0, -0.1, f64::NAN, f64::INFINITY] {
        assert_eq!(
            go(&cos, &pdf, tol, WORK_LEN),
            Err(Error::Domain),
            "tol {tol}"
        );
    }
    assert_eq!(go(&cos, &pdf, 0.1, WORK_LEN - 1), Err(Error::Size));
    assert_eq!(go(&cos[..1], &pdf[..1], 0.1, WORK_LEN), Err(Error::Size));
    assert_eq!(go(&cos, &pdf[..2], 0.1, WORK_LEN), Err(Error::Size));
    for (c, p) in [
        ([-1.0, 0.5, 0.0], pdf),              // not monotone
        ([-1.0, 0.0, 1.5], pdf),              // outside [-1, 1]
        ([-1.0, 0.0, 1.0], [1.0, -1.0, 1.0]), // negative density
        ([-1.0, 0.0, 1.0], [1.0, f64::NAN, 1.0]),
        ([-1.0, 0.0, 1.0], [0.0, 0.0, 0.0]), // no mass
    ] {
        assert_eq!(go(&c, &p, 0.1, WORK_LEN), Err(Error::Domain), "{c:?} {p:?}");
    }
}

/// Junge slopes and indices relative to water: the ranges of ocean
/// particles (Fournier & Forand 1994; Mobley et al. 2002).
const SCENES: [(f64, f64); 6] = [
    (3.5, 1.05),
    (3.5, 1.15),
    (4.0, 1.05),
    (4.0, 1.15),
    (4.5, 1.05),
    (4.5, 1.15),
];

#[test]
fn ocean_particles() {
    let (lambda, n_water, r_min, r_max) = (0.55, 1.339, 0.02, 50.0);
    let mut doc = String::from(
        "| slope μ_J | n | g (Mie) | chosen, TV ≤ 0.1 | isotropic | HG | Rayleigh | Draine | two-lobe HG | Rayleigh + HG | Fournier–Forand (fit) | Fournier–Forand (n, μ_J of the scene) | within 1°: Mie, FF |\n\
         |---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for (slope, n) in SCENES {
        let poly = Polydisperse {
            distribution: SizeDistribution::Junge { slope },
            r_min,
            r_max,
            wavelength: lambda,
            n_medium: n_water,
            m: Complex::new(n, 0.0),
            intervals: 128,
        };
        let x = poly.max_size_parameter();
        let count = table_sizes(x).0;
        let theta: Vec<f64> = (0..count).map(|j| table_angle(x, j, count)).collect();
        let cos: Vec<f64> = theta.iter().map(|t| t.cos()).collect();
        let mut buf = vec![Complex::default(); poly.buffer_len().unwrap()];
        let (mut pdf, mut scratch) = (vec![0.0; count], vec![0.0; count]);
        let av = poly
            .average(&cos, &mut pdf, &mut scratch, &mut buf)
            .unwrap();
        let c = choose(&cos, &pdf, 0.1, false);
        let reference = linear(&cos, &pdf);
        let steps = ((PI * x / 0.01) as usize).max(200_000);
        let own = FournierForand::<f64>::new(n, slope).unwrap();
        let own_d = direct_tv(&reference, &|m| own.pdf(m), steps);
        let chosen = c.phase.unwrap();
        let direct = direct_tv(&reference, &|m| chosen.pdf(m), steps);
        println!(
            "slope {slope} n {n}: x {x:.0}, g {:.3} (phase error {:.1e}), chose {:?} at {:.3} (direct {direct:.3}); {:?}; FF own {own_d:.3}",
            av.g, av.phase_error, c.model, c.distance, c.distances
        );
        assert!(
            (c.distance - direct).abs() <= 0.05 * direct + 1e-3,
            "{slope} {n}: {} vs {direct}",
            c.distance
        );
        assert!(
            c.distances[5] <= c.distances[1],
            "{slope} {n}: two-lobe {:?}",
            c.distances
        );
        assert!(
            c.distances[6] <= own_d + 1e-3,
            "{slope} {n}: FF fit {} vs own {own_d}",
            c.distances[6]
        );
        let one_degree = 1f64.to_radians();
        let mie_forward: f64 = {
            let k = 20_000;
            let h = one_degree / k as f64;
            (0..k)
                .map(|i| (i as f64 + 0.5) * h)
                .map(|t| reference(t.cos()) * t.sin() * h)
                .sum::<f64>()
                * 2.0
                * PI
        };
        let ff_forward = 1.0 - own.cdf(one_degree.cos());
        let name = |m: Model| match m {
            Model::Isotropic => "isotropic",
            Model::HenyeyGreenstein => "HG",
            Model::Rayleigh => "Rayleigh",
            Model::Draine => "Draine",
            Model::TwoLobeHg => "two-lobe HG",
            Model::FournierForand => "Fournier–Forand",
            Model::RayleighHg => "Rayleigh + HG",
            _ => "other",
        };
        let flag = if c.within_tolerance {
            ""
        } else {
            ", none within"
        };
        let ds: Vec<String> = [0, 1, 2, 3, 5, 7, 6]
            .iter()
            .map(|&i| format!("{:.3}", c.distances[i]))
            .collect();
        doc += &format!(
            "| {slope} | {n} | {:.3} | {} ({:.3}{flag}) | {} | {own_d:.3} | {mie_forward:.3}, {ff_forward:.3} |\n",
            av.g,
            name(c.model),
            c.distance,
            ds.join(" | ")
        );
    }
    println!("{doc}");
    if std::env::var_os("SK_BLESS").is_some() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let text = format!(
            "# Ocean particles: which model fits Mie over a Junge distribution\n\n\
             Generated by `SK_BLESS=1 cargo test --release --test models choose_measured::`; do not edit. \
             Spheres in water (n_water = 1.339) at 550 nm, radii from 0.02 to 50 µm with number \
             density `∝ r^(−μ_J)` (`SizeDistribution::Junge`), relative index `n`: the Mie phase \
             function averaged over the distribution (`Polydisperse::average`, 128 Simpson \
             intervals in ln r, at the `mie::table_sizes` angles of the largest sphere), then \
             `choose::mie::choose_measured` without a table. Columns: the total-variation \
             distance of each candidate's best fit; Fournier–Forand with the scene's own `n` and \
             `μ_J` (its derivation's parameters); and the share of scattering within 1° of \
             forward, Mie against that Fournier–Forand.\n\n\
             Fournier–Forand is derived for this scene (anomalous diffraction over an unbounded \
             Junge distribution), yet against exact Mie over it Fournier–Forand with the scene's \
             own parameters is 0.18–0.29 away and the best-fitting one 0.15–0.19, farther than \
             one HG (0.03–0.11) or two HG lobes (0.02–0.07). With its own parameters it puts \
             1.2–3.4 times Mie's share of scattering within 1° of forward. Part of that excess at \
             μ_J = 3.5 is the truncation: radii beyond 50 µm, which its unbounded distribution \
             includes, would carry roughly a tenth of the scattering there (anomalous-diffraction \
             estimate), all within a fraction of a degree; about 1 % at μ_J = 4 and 0.2 % at \
             4.5, where it is still 0.15–0.28 away. Ocean optics often specifies a scene by its \
             backscatter fraction, which Fournier–Forand matches by construction; in total \
             variation one or two HG lobes are closer, and the chooser picks them. The reference \
             is converged: 512 intervals change no distance by more than 3·10⁻⁴.\n\n{doc}"
        );
        std::fs::write(root.join("docs/measured/ocean_particles.md"), text).unwrap();
    }
}
