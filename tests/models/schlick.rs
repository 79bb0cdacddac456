//! Schlick's phase function against double-double: the inverse CDF at and
//! near both ends (where the textbook form cancels), the CDF, the density
//! and the mean cosine (series for small |k|, closed form beyond) against
//! a double-double evaluation and quadrature; and its Legendre moments
//! through the registry's quadrature.

use crate::common;

use common::dd::Dd;
use scatterkit::phase::schlick::Schlick;
use scatterkit::{Phase, PhaseFunction};

/// `μ(u) = (2u − 1 + k)/(1 − k + 2ku)` in double-double.
fn inverse_dd(k: f64, u: f64) -> Dd {
    let (k, u) = (Dd::from(k), Dd::from(u));
    (u * 2.0 - 1.0 + k) / (Dd::from(1.0) - k + k * u * 2.0)
}

/// `F(μ) = (1 − k)(1 + μ)/(2(1 − kμ))` in double-double.
fn cdf_dd(k: f64, mu: f64) -> Dd {
    let (k, mu) = (Dd::from(k), Dd::from(mu));
    (Dd::from(1.0) - k) * (mu + 1.0) / ((Dd::from(1.0) - k * mu) * 2.0)
}

const KS: [f64; 12] = [
    -0.999, -0.9, -0.5, -0.1, -1e-6, 0.0, 1e-9, 0.2, 0.49, 0.51, 0.9, 0.999,
];

#[test]
fn inverse_keeps_its_accuracy_at_both_ends() {
    // |μ − μ_dd| relative to the distance from the nearer end (1 ∓ μ), the
    // quantity a forward or backward peak needs: within 4 ε.
    let us = [
        0.0,
        1e-12,
        1e-6,
        0.1,
        0.3,
        0.5,
        0.5000001,
        0.7,
        0.9,
        1.0 - 1e-6,
        1.0 - 1e-12,
        1.0,
    ];
    for &k in &KS {
        let s = Schlick::<f64>::new(k).unwrap();
        for &u in &us {
            let mu = s.sample_cos(u);
            let exact = inverse_dd(k, u);
            let gap = if mu > 0.0 {
                (Dd::from(1.0) - exact).to_f64()
            } else {
                (exact + 1.0).to_f64()
            };
            let err = (Dd::from(mu) - exact).to_f64().abs();
            // μ itself is rounded to f64: half an ULP of it, plus 4 ε of
            // the gap.
            let ulp = f64::EPSILON * mu.abs().max(f64::MIN_POSITIVE);
            assert!(
                err <= 0.5 * ulp + 4.0 * f64::EPSILON * gap,
                "k = {k}, u = {u}: {mu} against {}, error {err:e}, gap {gap:e}",
                exact.to_f64()
            );
        }
    }
}

#[test]
fn cdf_and_density_agree_with_double_double() {
    for &k in &KS {
        let s = Schlick::<f64>::new(k).unwrap();
        for i in 0..=200 {
            let mu = -1.0 + i as f64 / 100.0;
            let want = cdf_dd(k, mu).to_f64();
            let got = s.cdf(mu);
            assert!(
                (got - want).abs() <= 4.0 * f64::EPSILON * want.max(1e-300),
                "k = {k}, μ = {mu}: {got} vs {want}"
            );
            // The density against the rational in double-double (1 − kμ
            // cancels at the peak in f64).
            let d = Dd::from(1.0) - Dd::from(k) * Dd::from(mu);
            let num = (Dd::from(1.0) - Dd::from(k)) * (Dd::from(1.0) + Dd::from(k));
            let p = (num / (d * d)).to_f64() / (4.0 * core::f64::consts::PI);
            assert!(
                (s.pdf(mu) - p).abs() <= 8.0 * f64::EPSILON * p,
                "k = {k}, μ = {mu}"
            );
        }
    }
}

/// `∫ μ 2π p dμ` by composite Simpson on a grid graded toward the peak.
fn mean_cosine_by_quadrature(k: f64) -> f64 {
    let p = |mu: f64| {
        let d = 1.0 - k * mu;
        (1.0 - k * k) / (2.0 * d * d)
    };
    // μ = ±(1 − s²)-style grading: integrate in t with μ = tanh-free map.
    let n = 200_000;
    let h = 2.0 / n as f64;
    let mut sum = 0.0;
    for i in 0..=n {
        let mu = -1.0 + i as f64 * h;
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        sum += w * mu * p(mu);
    }
    sum * h / 3.0
}

#[test]
fn mean_cosine_matches_quadrature_on_both_sides_of_the_series() {
    for &k in &[
        -0.9, -0.5, -0.4999, -1e-2, 1e-2, 0.3, 0.4999, 0.5, 0.5001, 0.8, 0.95,
    ] {
        let s = Schlick::<f64>::new(k).unwrap();
        let want = mean_cosine_by_quadrature(k);
        let got = s.mean_cosine();
        assert!(
            (got - want).abs() <= 1e-11 * want.abs(),
            "k = {k}: {got} vs {want}"
        );
    }
    // Where quadrature cannot resolve it, the leading terms 2k/3 + 2k³/15
    // (the closed form cancels there: the reason for the series).
    for k in [1e-8, -1e-5, 1e-3] {
        let got = Schlick::<f64>::new(k).unwrap().mean_cosine();
        let want = 2.0 * k / 3.0 + 2.0 * k * k * k / 15.0;
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "k = {k}: {got} vs {want}"
        );
    }
    // The series and the closed form meet at |k| = 1/2 without a step.
    let below = Schlick::<f64>::new(0.5 - 1e-12).unwrap().mean_cosine();
    let at = Schlick::<f64>::new(0.5).unwrap().mean_cosine();
    assert!((below - at).abs() < 1e-12, "{below} {at}");
}

#[test]
fn approximating_hg_follows_blasi_and_stays_inside() {
    let s = Schlick::<f64>::approximating_hg(0.5).unwrap();
    assert!((s.k() - (1.55 * 0.5 - 0.55 * 0.125)).abs() < 1e-15);
    // The cubic peaks above 1 near g = 0.97: held inside (−1, 1).
    for g in [0.96, 0.969, 0.98, 0.999999, -0.969] {
        let s = Schlick::<f64>::approximating_hg(g).unwrap();
        assert!(s.k().abs() < 1.0, "{g}");
    }
    assert!(Schlick::<f64>::approximating_hg(1.0).is_err());
    assert!(Schlick::<f32>::approximating_hg(f32::NAN).is_err());
}

#[test]
fn the_registry_carries_it_in_both_precisions() {
    // Built from its parameters (the C API's sk_phase_new), cast, and
    // reported back.
    let p = Phase::<f64>::from_params(Phase::<f64>::LAST_TAG, &[0.6]).unwrap();
    assert_eq!(p.params().0, 9);
    assert_eq!(p.params().2[0], 0.6);
    let q: Phase<f32> = p.cast();
    assert_eq!(q.params().2[0], 0.6f32);
    assert!((q.sample_cos(0.3) as f64 - p.sample_cos(0.3)).abs() < 3e-7);
    let mut chi = [0.0; 3];
    scatterkit::phase::moments::legendre_moments(&p, &mut chi);
    assert!(
        (chi[0] - 1.0).abs() < 1e-12 && (chi[1] - p.mean_cosine()).abs() < 1e-9,
        "{chi:?}"
    );
}
