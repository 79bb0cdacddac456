//! Wavelength-dependent phase functions (`mixture::spectral`): four
//! channels (HG with g = 0.1, 0.5, 0.85 and a 5 µm fog table), the hero
//! drawn uniformly; each channel's mean of a test integrand from the hero
//! estimator (balance heuristic over the hero, and the plain ratio)
//! against quadrature of that channel alone, 4σ over 2·10⁵ paths, with the
//! variances printed beside sampling each channel alone; giving every
//! channel the hero's pdf (weights 1) fails; bad input.

use super::majorant::mean_se;
use crate::common::chi2::integrate;
use crate::common::rng;
use scatterkit::mixture::Part;
use scatterkit::mixture::spectral::{MAX_CHANNELS, SpectralPhase};
use scatterkit::{Error, Phase, PhaseFunction, Real, Table, TableKind};

/// The test integrand: smooth, and weighting both hemispheres.
fn f(mu: f64) -> f64 {
    1.0 + mu + 2.0 * mu * mu * mu
}

#[test]
fn the_hero_estimator_matches_each_channel_alone() {
    let fog = Phase::<f64>::fog_diameter(5.0).unwrap();
    let mut buf = vec![0.0; TableKind::Inverse.len(512).unwrap()];
    let table = Table::inverse(&fog, &mut buf, 512).unwrap();
    let hg = |g: f64| Part::Phase(Phase::henyey_greenstein(g).unwrap());
    let channels = [hg(0.1), hg(0.5), hg(0.85), Part::Table(table)];
    let k = channels.len();
    let s = SpectralPhase::new(&channels).unwrap();
    let tau = std::f64::consts::TAU;
    let exact: Vec<f64> = channels
        .iter()
        .map(|c| tau * integrate(&|mu: f64| f(mu) * c.pdf(mu), -1.0, 1.0, 1e-11))
        .collect();
    let n = 200_000;
    let mut r = rng(910);
    let (mut balance, mut plain, mut ones) = (vec![vec![]; k], vec![vec![]; k], vec![vec![]; k]);
    let mut ratio = [0.0; 4];
    for _ in 0..n {
        let hero = ((f64::uniform(&mut r) * k as f64) as usize).min(k - 1);
        let mu = s
            .sample_cos(hero, f64::uniform(&mut r), &mut ratio)
            .unwrap();
        let mean = ratio.iter().sum::<f64>() / k as f64;
        for c in 0..k {
            balance[c].push(f(mu) * ratio[c] / mean);
            plain[c].push(f(mu) * ratio[c]);
            ones[c].push(f(mu));
        }
    }
    let mut failed_mutation = 0;
    for c in 0..k {
        let alone: Vec<f64> = (0..n)
            .map(|_| f(channels[c].sample_cos(f64::uniform(&mut r))))
            .collect();
        let var = |x: &[f64]| {
            let (_, se) = mean_se(x);
            se * se * x.len() as f64
        };
        for (name, xs) in [
            ("balance", &balance[c]),
            ("ratio", &plain[c]),
            ("alone", &alone),
        ] {
            let (m, se) = mean_se(xs);
            assert!(
                (m - exact[c]).abs() <= 4.0 * se,
                "channel {c} {name}: {m} ± {se} vs {}",
                exact[c]
            );
        }
        let (m, se) = mean_se(&ones[c]);
        failed_mutation += ((m - exact[c]).abs() > 4.0 * se) as usize;
        eprintln!(
            "channel {c}: variance, hero with balance {:.3}, hero ratio alone {:.3}, channel alone {:.3}",
            var(&balance[c]),
            var(&plain[c]),
            var(&alone)
        );
    }
    // The hero's pdf for every channel (weights 1) averages the channels,
    // whose means all differ from the average: it must fail for each.
    assert_eq!(
        failed_mutation, 4,
        "the mutation failed {failed_mutation} of 4"
    );
}

#[test]
fn bad_input_is_refused() {
    let hg = Part::Phase(Phase::<f32>::henyey_greenstein(0.5).unwrap());
    assert_eq!(SpectralPhase::<f32>::new(&[]).err(), Some(Error::Size));
    let many = vec![hg; MAX_CHANNELS + 1];
    assert_eq!(SpectralPhase::new(&many).err(), Some(Error::Size));
    let s = SpectralPhase::new(&[hg, Part::Phase(Phase::rayleigh())]).unwrap();
    let (mut two, mut one) = ([7.0f32; 2], [7.0f32; 1]);
    assert_eq!(s.sample_cos(2, 0.5, &mut two).err(), Some(Error::Size));
    assert_eq!(s.sample_cos(0, 0.5, &mut one).err(), Some(Error::Size));
    assert_eq!(
        s.sample_cos(0, f32::NAN, &mut two).err(),
        Some(Error::Domain)
    );
    assert_eq!(two, [7.0; 2], "nothing written on error");
    assert_eq!(s.pdf(0.3, &mut one).err(), Some(Error::Size));
    let mu = s.sample_cos(1, 0.25, &mut two).unwrap();
    assert_eq!(two[1], 1.0);
    let hg_only = Phase::<f32>::henyey_greenstein(0.5).unwrap();
    assert!((two[0] - hg_only.pdf(mu) / Phase::<f32>::rayleigh().pdf(mu)).abs() < 1e-6);
}
