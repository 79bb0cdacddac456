//! Phase functions from Legendre moments (`phase::legendre`): HG given by
//! its moments `g^l` (41 of them) samples within 10⁻⁹ of HG's own exact
//! inverse and passes chi² over the sphere; Rayleigh's three moments
//! reproduce Rayleigh's sampler to 10⁻¹³; the moments of the series by
//! quadrature return the input; a truncated peaked expansion (HG 0.9 at
//! L = 4) is refused where it goes negative; bad input.

use crate::common::chi2::{chi2_directions, threshold};
use crate::common::nan_max;
use crate::common::{CHI2_SAMPLES, rng};
use scatterkit::phase::legendre::LegendreSeries;
use scatterkit::phase::moments::legendre_moments_by_quadrature;
use scatterkit::{Error, Phase, PhaseFunction, Real, Vec3};

fn hg_moments(g: f64, n: usize) -> Vec<f64> {
    (0..n).map(|l| g.powi(l as i32)).collect()
}

#[test]
fn hg_from_its_moments() {
    let chi = hg_moments(0.5, 41);
    let s = LegendreSeries::new(&chi).unwrap();
    let hg = Phase::henyey_greenstein(0.5).unwrap();
    let mut worst: f64 = 0.0;
    for i in 0..=4096 {
        let u = i as f64 / 4096.0;
        worst = nan_max(worst, (s.sample_cos(u) - hg.sample_cos(u)).abs());
    }
    assert!(worst <= 1e-9, "{worst:.2e}");
    assert!((s.mean_cosine() - 0.5).abs() < 1e-15 && (s.cdf(0.3) - hg.cdf(0.3)).abs() < 1e-11);
    let w = [0.0, 0.6, 0.8];
    let w_in = Vec3::new(0.0, 0.6, 0.8);
    let mut r = rng(51);
    let res = chi2_directions(&|mu| s.pdf(mu), w, CHI2_SAMPLES, || {
        let (d, _) = s.sample_dir(w_in, f64::uniform(&mut r), f64::uniform(&mut r));
        [d.x, d.y, d.z]
    });
    assert!(res.passes(), "{res:?} ({:.2e})", threshold());
    let mut back = [0.0; 41];
    legendre_moments_by_quadrature(&s, &mut back);
    let err = back
        .iter()
        .zip(&chi)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, nan_max);
    assert!(err <= 1e-12, "moments round trip {err:.2e}");
}

#[test]
fn rayleigh_from_three_moments() {
    let chi = [1.0, 0.0, 0.1];
    let s = LegendreSeries::new(&chi).unwrap();
    let ray = Phase::<f64>::rayleigh();
    for i in 0..=1000 {
        let u = i as f64 / 1000.0;
        assert!(
            (s.sample_cos(u) - ray.sample_cos(u)).abs() <= 1e-13,
            "u {u}"
        );
        let mu = -1.0 + 2.0 * u;
        assert!((s.pdf(mu) - ray.pdf(mu)).abs() <= 1e-15);
    }
}

#[test]
fn a_negative_expansion_is_refused() {
    let chi = hg_moments(0.9, 5);
    assert_eq!(LegendreSeries::new(&chi).err(), Some(Error::Domain));
    let s = LegendreSeries::unchecked(&chi).unwrap();
    let neg = s.check().unwrap();
    assert!(neg.pdf < 0.0, "{neg:?}");
    // Found on the documented grid of 64 (L + 1) + 1 cosines, the first
    // negative one: the grid point before it is not negative.
    let m = 64.0 * chi.len() as f64;
    let i = (neg.cos_theta + 1.0) * m / 2.0;
    assert!((i - i.round()).abs() < 1e-9, "{neg:?} is not on the grid");
    assert!(i > 0.0 && s.pdf(neg.cos_theta - 2.0 / m) >= 0.0, "{neg:?}");
    // A density that touches 0 without going below (`(1 + μ)/4π`, zero at
    // μ = −1) is taken.
    assert!(LegendreSeries::new(&[1.0, 1.0 / 3.0]).is_ok());
    // The same HG with enough terms is fine.
    assert!(LegendreSeries::new(&hg_moments(0.9, 300)).is_ok());
}

#[test]
fn bad_input_is_refused() {
    assert_eq!(LegendreSeries::<f64>::new(&[]).err(), Some(Error::Size));
    // Up to L = 1023: 1024 moments (isotropic, χ_0 = 1) taken, 1025 not.
    let mut long = vec![0.0f64; 1025];
    long[0] = 1.0;
    assert!(LegendreSeries::new(&long[..1024]).is_ok());
    assert_eq!(LegendreSeries::new(&long).err(), Some(Error::Size));
    // A moment beyond [−1, 1] is refused before the sign check runs.
    assert_eq!(
        LegendreSeries::unchecked(&[1.0, 0.0, 1.5]).err(),
        Some(Error::Domain)
    );
    for chi in [
        [0.5, 0.1],
        [1.0, f64::NAN],
        [1.0, 1.5],
        [f64::INFINITY, 0.0],
    ] {
        assert_eq!(
            LegendreSeries::new(&chi).err(),
            Some(Error::Domain),
            "{chi:?}"
        );
    }
    let s = LegendreSeries::new(&[1.0f32, 0.3]).unwrap();
    assert!(s.sample_cos(f32::NAN).is_nan() && s.cdf(f32::NAN).is_nan());
    assert_eq!((s.sample_cos(-1.0), s.sample_cos(2.0)), (-1.0, 1.0));
}
