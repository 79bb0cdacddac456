//! Surface scattering: Lambert (chi²), Phong (KS on the cone CDF, and α = 1
//! equals Lambert), the crossing policies, Fresnel, Snell, the scattering
//! fractions, and `Surface::interact`'s shares against the formulas.

use crate::common;

use common::chi2::{chi2_directions, threshold};
use common::ks::{ks_critical, ks_statistic};
use common::{CHI2_SAMPLES, rng, test_directions};
use scatterkit::surface::{
    self, CrossingPolicy, Fraction, Surface, SurfaceModel, fresnel_dielectric, lambert_sample,
    phong_sample, phong_sample_rng, reflect, refract, scatter_fraction_reflect,
    scatter_fraction_transmit,
};
use scatterkit::{Real, Vec3};

/// Significance per KS test, with the suite's Šidák correction.
fn ks_alpha() -> f64 {
    threshold()
}

fn to_vec<T: Real>(w: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(w[0]), T::from_f64(w[1]), T::from_f64(w[2]))
        .try_normalize()
        .unwrap()
}

fn f64v<T: Real>(v: Vec3<T>) -> [f64; 3] {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}

#[test]
fn lambert_is_cosine_weighted_about_the_normal() {
    fn check<T: Real>(seed: u64) {
        let normals = [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [0.3, -0.5, 0.81]];
        for (k, w) in normals.into_iter().enumerate() {
            let n = to_vec::<T>(w);
            let mut r = rng(seed + k as u64);
            let pdf = |mu: f64| {
                if mu > 0.0 {
                    mu / std::f64::consts::PI
                } else {
                    0.0
                }
            };
            let res = chi2_directions(&pdf, f64v(n), CHI2_SAMPLES, || {
                f64v(lambert_sample(n, T::uniform(&mut r), T::uniform(&mut r)))
            });
            assert!(res.passes(), "Lambert about {w:?}: {res:?}");
        }
    }
    check::<f32>(10);
    check::<f64>(20);
}

#[test]
fn phong_cone_follows_c_to_the_alpha_plus_one() {
    // At normal incidence no direction crosses: P(cos Δθ ≤ c) = c^{α+1}.
    // f64 for α = 10⁶, where f32's spacing near 1 cannot resolve the cone.
    fn check<T: Real>(alphas: &[f64], seed: u64) {
        let n = Vec3::new(T::ZERO, T::ZERO, T::ONE);
        for &alpha in alphas {
            let mut r = rng(seed);
            let count = 200_000;
            // The statistic in x = (α + 1) ln(1/cos Δθ) ~ Exp(1), which keeps
            // resolution for narrow cones (1 − cos Δθ is tiny).
            let mut xs: Vec<f64> = (0..count)
                .map(|_| {
                    let d = phong_sample(
                        n,
                        n,
                        T::from_f64(alpha),
                        CrossingPolicy::Fold,
                        T::uniform(&mut r),
                        T::uniform(&mut r),
                    );
                    -(alpha + 1.0) * d.z.to_f64().ln()
                })
                .collect();
            let dstat = ks_statistic(&mut xs, |x| -(-x).exp_m1());
            assert!(
                dstat < ks_critical(ks_alpha(), count),
                "α = {alpha}: D = {dstat:e}"
            );
        }
    }
    check::<f32>(&[1.0, 10.0, 1000.0], 30);
    check::<f64>(&[1.0, 10.0, 1000.0, 1e6], 40);
}

#[test]
fn phong_alpha_one_at_normal_incidence_is_lambert() {
    let mut r = rng(5);
    for w in test_directions() {
        let n = to_vec::<f64>(w);
        for _ in 0..10_000 {
            let (u1, u2) = (f64::uniform(&mut r), f64::uniform(&mut r));
            let a = phong_sample(n, n, 1.0, CrossingPolicy::Fold, u1, u2);
            let b = lambert_sample(n, u1, u2);
            assert!((a - b).length() < 1e-15, "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn no_policy_leaves_a_direction_on_the_wrong_side() {
    // Grazing specular directions put half the lobe below the surface.
    let normal = Vec3::new(0.0f64, 0.0, 1.0);
    for policy in [
        CrossingPolicy::Fold,
        CrossingPolicy::Resample,
        CrossingPolicy::Mirror,
    ] {
        for axis in [[1.0, 0.0, 0.01], [0.6, 0.0, 0.8], [0.0, 1.0, 1e-6]] {
            let axis = to_vec::<f64>(axis);
            let mut r = rng(9);
            for alpha in [1.0, 10.0, 1000.0] {
                for _ in 0..20_000 {
                    let d = phong_sample(
                        axis,
                        normal,
                        alpha,
                        policy,
                        f64::uniform(&mut r),
                        f64::uniform(&mut r),
                    );
                    assert!(d.z >= 0.0, "{policy:?} α {alpha}: {d:?}");
                    assert!((d.length() - 1.0).abs() < 1e-12);
                    let e = phong_sample_rng(axis, normal, alpha, policy, &mut r);
                    assert!(
                        e.z >= 0.0 && (e.length() - 1.0).abs() < 1e-12,
                        "{policy:?}: {e:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn policies_produce_their_documented_distributions() {
    // Resample: the lobe truncated to the upper hemisphere and renormalised.
    // Check it against the Phong density (cos Δθ)^α (α + 1)/(2π) restricted
    // to z ≥ 0, by chi² about the axis.
    let axis = to_vec::<f64>([0.8, 0.0, 0.6]);
    let normal = Vec3::new(0.0, 0.0, 1.0);
    let alpha = 3.0;
    // Mass of the lobe above the surface, by sampling the untruncated lobe.
    let mut r = rng(77);
    let m = 4_000_000;
    let above = (0..m)
        .filter(|_| {
            let c = f64::uniform(&mut r).powf(1.0 / (alpha + 1.0));
            let phi = std::f64::consts::TAU * f64::uniform(&mut r);
            scatterkit::geometry::direction_about(axis, c, phi).z >= 0.0
        })
        .count() as f64
        / m as f64;
    let mut r = rng(78);
    let n = CHI2_SAMPLES;
    let mut upper = 0usize;
    let mut samples = Vec::with_capacity(n);
    for _ in 0..n {
        let d = phong_sample_rng(axis, normal, alpha, CrossingPolicy::Resample, &mut r);
        upper += (d.dot(axis) > 0.9) as usize;
        samples.push(d);
    }
    // P(cos Δθ > 0.9 | above) = P(cos Δθ > 0.9)/P(above): every direction
    // within 25.8° of this axis (36.9° above the surface) is above it.
    let expected = (1.0 - 0.9f64.powf(alpha + 1.0)) / above;
    let got = upper as f64 / n as f64;
    let sigma = (expected * (1.0 - expected) / n as f64).sqrt();
    assert!(
        (got - expected).abs() < 4.0 * sigma,
        "resample: {got} vs {expected} ± {sigma}"
    );
    // Mirror: directions are the lobe folded by reflection in the plane;
    // the mirrored mass appears as directions closer to the plane than the
    // lobe alone puts there.
    let mut r = rng(79);
    let below_share: f64 = (0..n)
        .map(|_| {
            let u1 = f64::uniform(&mut r);
            let u2 = f64::uniform(&mut r);
            let raw = scatterkit::geometry::direction_about(
                axis,
                u1.powf(1.0 / (alpha + 1.0)),
                std::f64::consts::TAU * u2,
            );
            let d = phong_sample(axis, normal, alpha, CrossingPolicy::Mirror, u1, u2);
            if raw.z < 0.0 {
                assert!(
                    (d.z + raw.z).abs() < 1e-12 && (d.x - raw.x).abs() < 1e-12,
                    "mirror"
                );
                1.0
            } else {
                assert!((d - raw).length() < 1e-12);
                0.0
            }
        })
        .sum::<f64>()
        / n as f64;
    assert!((below_share - (1.0 - above)).abs() < 4.0 * ((1.0 - above) * above / n as f64).sqrt());
    // Fold: polar angle θ > 90° becomes θ − 90° at the same azimuth.
    let d = Vec3::new(0.6f64, 0.0, -0.8);
    let folded = phong_sample(d, normal, 1e6, CrossingPolicy::Fold, 1.0, 0.0);
    let theta = (-0.8f64).acos(); // θ of d from the normal: 143.13°
    let expect = Vec3::new(
        (theta - std::f64::consts::FRAC_PI_2).sin(),
        0.0,
        (theta - std::f64::consts::FRAC_PI_2).cos(),
    );
    assert!(
        (folded - expect).length() < 1e-6,
        "fold: {folded:?} vs {expect:?}"
    );
}

/// `(nᵢ, nₜ, cos θᵢ, R, R of the f32-rounded inputs)`: the unpolarised
/// reflectance summed in 50 digits (mpmath) from the textbook ratios, for
/// nearly matched indices (`nₜ/nᵢ = 1 ± 10⁻⁶`, `1 + 10⁻⁹`, air against
/// vacuum, an encapsulant against glass) from near-normal to grazing
/// incidence.
#[allow(clippy::excessive_precision)] // mpmath's 17 digits, as printed
const NEARLY_MATCHED: [(f64, f64, f64, f64, f64); 30] = [
    (1.5, 1.5000015, 0.9, 2.637552273485515e-13, 2.81530504e-13),
    (1.5, 1.5000015, 0.5, 2.4999795001023657e-12, 2.66846011e-12),
    (1.5, 1.5000015, 0.01, 2.450367680587248e-5, 2.61379829e-5),
    (1.5, 1.5000015, 0.0001, 0.75381541247463272, 0.757263009),
    (1.5, 1.5000015, 1e-07, 0.99971719707191674, 0.99972177),
    (1.5, 1.4999985, 0.9, 2.637558227881205e-13, 2.81531161e-13),
    (1.5, 1.4999985, 0.5, 2.5000205001023666e-12, 2.66850533e-12),
    (1.5, 1.4999985, 0.01, 2.5503826850234938e-5, 2.7240945e-5),
    (1.5, 1.4999985, 0.0001, 1.0, 1.0),
    (1.5, 1.4999985, 1e-07, 1.0, 1.0),
    (1.5, 1.5000000015, 0.9, 2.6375549033381707e-19, 0.0),
    (1.5, 1.5000000015, 0.5, 2.4999996530531867e-18, 0.0),
    (1.5, 1.5000000015, 0.01, 2.4994497320031169e-11, 0.0),
    (1.5, 1.5000000015, 0.0001, 0.0020746974360425332, 0.0),
    (1.5, 1.5000000015, 1e-07, 0.99109561619037553, 0.0),
    (1.0, 1.000293, 0.9, 2.2635661447833165e-8, 2.26382009e-8),
    (1.0, 1.000293, 0.5, 2.1410790442700829e-7, 2.14131894e-7),
    (1.0, 1.000293, 0.01, 0.20007145042216386, 0.200080024),
    (1.0, 1.000293, 0.0001, 0.983608396337926, 0.983608852),
    (1.0, 1.000293, 1e-07, 0.99998347265727952, 0.999983473),
    (1.000293, 1.0, 0.9, 2.2637369354753739e-8, 2.26399091e-8),
    (1.000293, 1.0, 0.5, 2.1501304486188956e-7, 2.15037187e-7),
    (1.000293, 1.0, 0.01, 1.0, 1.0),
    (1.000293, 1.0, 0.0001, 1.0, 1.0),
    (1.000293, 1.0, 1e-07, 1.0, 1.0),
    (1.48, 1.5, 0.9, 4.7440602194181787e-5, 4.74405125e-5),
    (1.48, 1.5, 0.5, 0.00041033920041781626, 0.000410338448),
    (1.48, 1.5, 0.01, 0.78220035998951416, 0.782200273),
    (1.48, 1.5, 0.0001, 0.99754510171413868, 0.997545101),
    (1.48, 1.5, 1e-07, 0.99999754208584563, 0.999997542),
];

/// [`NEARLY_MATCHED`] within 10⁻¹² (f64) and 10⁻⁶ (f32) relative. The
/// ratios as written lose the indices' difference, and `1 − η² sin²θᵢ`
/// loses `cos²θᵢ` against 1: at `nₜ/nᵢ = 1 + 10⁻⁶` the f32 reflectance
/// was up to 12 % off, at `1 + 10⁻⁹` the f64 one 1.4·10⁻⁷.
#[test]
fn nearly_matched_indices_against_50_digits() {
    let (mut worst64, mut worst32) = (0.0f64, 0.0f64);
    for (ni, nt, c, want, want32) in NEARLY_MATCHED {
        let rel = |got: f64, want: f64| {
            if want == 0.0 {
                got.abs()
            } else {
                (got / want - 1.0).abs()
            }
        };
        let e64 = rel(fresnel_dielectric(c, ni, nt), want);
        let e32 = rel(
            fresnel_dielectric(c as f32, ni as f32, nt as f32) as f64,
            want32,
        );
        assert!(
            e64 <= 1e-12 && e32 <= 1e-6,
            "{ni} {nt} cos {c}: {e64:.1e} (f64), {e32:.1e} (f32)"
        );
        (worst64, worst32) = (worst64.max(e64), worst32.max(e32));
    }
    println!("largest relative error {worst64:.1e} (f64), {worst32:.1e} (f32)");
}

#[test]
fn fresnel_matches_the_closed_forms() {
    for (ni, nt) in [(1.0, 1.5), (1.5, 1.0), (1.5, 3.9), (1.0, 1.333)] {
        let r0 = ((ni - nt) / (ni + nt)) * ((ni - nt) / (ni + nt));
        assert!((fresnel_dielectric(1.0f64, ni, nt) - r0).abs() < 1e-15);
        assert!(
            (fresnel_dielectric(-1.0f64, ni, nt) - r0).abs() < 1e-15,
            "either direction of travel"
        );
        // Brewster: R_p = 0, so R = R_s/2.
        let tb = (nt / ni).atan();
        let (ci, ct) = (tb.cos(), (ni / nt * tb.sin()).asin().cos());
        let rs = ((ni * ci - nt * ct) / (ni * ci + nt * ct)).powi(2);
        assert!(
            (fresnel_dielectric(ci, ni, nt) - rs / 2.0).abs() < 1e-14,
            "Brewster {ni} {nt}"
        );
        if ni > nt {
            let crit = (nt / ni).asin();
            assert_eq!(fresnel_dielectric((crit + 1e-3).cos(), ni, nt), 1.0, "TIR");
            // Continuity at the critical angle: R → 1 from below.
            let below = fresnel_dielectric((crit - 1e-9).cos(), ni, nt);
            assert!(1.0 - below < 2e-3, "{below}");
        }
    }
    // Matched indices: no interface, R = 0 at every angle, grazing too
    // (there both ratios were 0/0 and R was NaN); any other interface
    // reflects everything at grazing incidence.
    for n in [1.0f64, 1.33, 3.5] {
        for c in [1.0, 0.5, 1e-300, 0.0, -0.0, -0.5] {
            assert_eq!(fresnel_dielectric(c, n, n), 0.0, "n {n} cos {c}");
            assert_eq!(fresnel_dielectric(c as f32, n as f32, n as f32), 0.0);
        }
        assert_eq!(fresnel_dielectric(0.0, n, n * 1.5), 1.0);
        assert_eq!(fresnel_dielectric(0.0, n * 1.5, n), 1.0);
    }
    assert!(fresnel_dielectric(0.5f32, -1.0, 1.5).is_nan());
    assert!(fresnel_dielectric(1.5f32, 1.0, 1.5).is_nan());
    assert!(fresnel_dielectric(0.5f32, 1.0, f32::INFINITY).is_nan());
}

#[test]
fn snell_holds_in_the_plane_of_incidence() {
    let mut r = rng(4);
    for _ in 0..100_000 {
        let n = to_vec::<f32>([
            f64::uniform(&mut r) - 0.5,
            f64::uniform(&mut r) - 0.5,
            f64::uniform(&mut r) - 0.5,
        ]);
        let d = to_vec::<f32>([
            f64::uniform(&mut r) - 0.5,
            f64::uniform(&mut r) - 0.5,
            f64::uniform(&mut r) - 0.5,
        ]);
        let (ni, nt) = (
            1.0 + 3.0 * f32::uniform(&mut r),
            1.0 + 3.0 * f32::uniform(&mut r),
        );
        match refract(d, n, ni, nt) {
            Ok(t) => {
                // Snell's law to 1e-6, measured in f64 on the f32 vectors.
                let (d64, n64, t64) = (d.cast::<f64>(), n.cast::<f64>(), t.cast::<f64>());
                let (sin_i, sin_t) = (d64.cross(n64).length(), t64.cross(n64).length());
                let err = (ni as f64 * sin_i - nt as f64 * sin_t).abs();
                assert!(err < 1e-6, "{ni} {sin_i} {nt} {sin_t}: {err:e}");
                assert!(
                    t.dot(d.cross(n)).abs() < 1e-6,
                    "out of the plane of incidence"
                );
                assert!((t.length() - 1.0).abs() < 1e-6);
                // Transmitted to the other side of the surface.
                assert!(t.dot(n) * d.dot(n) >= 0.0);
            }
            Err(_) => assert!(ni / nt * d.cross(n).length() > 1.0 - 1e-6, "false TIR"),
        }
    }
    let g = Vec3::new(0.8f64, 0.0, -0.6);
    let m = reflect(g, Vec3::new(0.0, 0.0, 1.0));
    assert_eq!(m, Vec3::new(0.8, 0.0, 0.6));
}

#[test]
fn scatter_fractions_match_the_formulas() {
    let tau = std::f64::consts::TAU;
    let (lambda, sigma, ni, nt) = (600e-9, 50e-9, 1.5, 3.9);
    for ci in [1.0f64, 0.5, 0.01] {
        let x = tau / lambda * sigma * 2.0 * ni * ci;
        assert!(
            (scatter_fraction_reflect(lambda, sigma, ni, ci) - (1.0 - (-x * x).exp())).abs()
                < 1e-15
        );
        let ct = (1.0 - (ni / nt) * (ni / nt) * (1.0 - ci * ci)).sqrt();
        let y = tau / lambda * sigma * (ni * ci - nt * ct).abs();
        assert!(
            (scatter_fraction_transmit(lambda, sigma, ni, ci, nt, ct) - (1.0 - (-y * y).exp()))
                .abs()
                < 1e-15
        );
    }
    // Λ → 0 as σ → 0, with no cancellation on the way.
    let tiny = scatter_fraction_reflect(600e-9f64, 1e-15, 1.5, 1.0);
    let x = tau / 600e-9 * 1e-15 * 3.0;
    assert!((tiny / (x * x) - 1.0).abs() < 1e-12, "{tiny:e}");
    assert_eq!(scatter_fraction_reflect(600e-9f32, 0.0, 1.5, 1.0), 0.0);
    assert!(scatter_fraction_reflect(0.0f64, 1e-9, 1.5, 1.0).is_nan());
    assert!(scatter_fraction_reflect(600e-9f64, -1e-9, 1.5, 1.0).is_nan());
}

/// Over many events, the reflected share equals Fresnel and the scattered
/// share equals Λ, within 4σ; reflections stay on the incident side and
/// transmissions cross.
fn interact_shares(model: SurfaceModel, theta_deg: f64, n: usize) {
    let (ni, nt, lambda, sigma) = (1.5f64, 3.9, 600e-9, 50e-9);
    let s = Surface::new(model, 1000.0, Fraction::Scalar(sigma), CrossingPolicy::Fold).unwrap();
    let th = theta_deg.to_radians();
    let d = Vec3::new(th.sin(), 0.0, -th.cos());
    let normal = Vec3::new(0.0, 0.0, 3.0); // any length, incident side
    let (ci, ct) = (th.cos(), (1.0 - (ni / nt * th.sin()).powi(2)).sqrt());
    let r_exp = fresnel_dielectric(ci, ni, nt);
    let lr = scatter_fraction_reflect(lambda, sigma, ni, ci);
    let lt = scatter_fraction_transmit(lambda, sigma, ni, ci, nt, ct);
    let mut r = rng(123);
    let (mut refl, mut refl_scat, mut trans_scat) = (0usize, 0usize, 0usize);
    for _ in 0..n {
        let x = s.interact(d, normal, ni, nt, lambda, &mut r).unwrap();
        let dir = x.dir;
        let (transmitted, scattered) = (x.transmitted, x.scattered);
        if transmitted {
            assert!(dir.z < 0.0, "a transmission must cross: {dir:?}");
            trans_scat += scattered as usize;
        } else {
            assert!(dir.z > 0.0, "a reflection must stay: {dir:?}");
            refl += 1;
            refl_scat += scattered as usize;
        }
        assert!((dir.length() - 1.0).abs() < 1e-12);
    }
    let within = |k: usize, total: usize, p: f64| {
        let sd = (p * (1.0 - p) / total as f64).sqrt();
        (k as f64 / total as f64 - p).abs() <= 4.0 * sd + 1e-12
    };
    assert!(
        within(refl, n, r_exp),
        "reflected {} vs Fresnel {r_exp}",
        refl as f64 / n as f64
    );
    if model != SurfaceModel::Specular {
        assert!(
            within(refl_scat, refl, lr),
            "scattered on reflection {} vs {lr}",
            refl_scat as f64 / refl as f64
        );
        assert!(
            within(trans_scat, n - refl, lt),
            "scattered on transmission {} vs {lt}",
            trans_scat as f64 / (n - refl) as f64
        );
    } else {
        assert_eq!(refl_scat + trans_scat, 0);
    }
}

#[test]
fn interact_shares_match_fresnel_and_lambda() {
    for model in [
        SurfaceModel::Specular,
        SurfaceModel::Lambert,
        SurfaceModel::Phong,
    ] {
        for theta in [0.0, 60.0] {
            interact_shares(model, theta, 1_000_000);
        }
    }
}

#[test]
fn total_internal_reflection_always_reflects() {
    let s = Surface::new(
        SurfaceModel::Lambert,
        1.0,
        Fraction::Constant(0.5f64),
        CrossingPolicy::Mirror,
    )
    .unwrap();
    let d = to_vec::<f64>([0.9, 0.0, 0.3]); // grazing, leaving glass upwards
    let n = Vec3::new(0.0, 0.0, 1.0);
    let mut r = rng(2);
    for _ in 0..10_000 {
        let x = s.interact(d, n, 1.5, 1.0, 600e-9, &mut r).unwrap();
        let dir = x.dir;
        assert!(!x.transmitted);
        assert!(dir.z <= 0.0, "stays in the glass: {dir:?}");
    }
}

#[test]
fn constructors_and_interact_reject_bad_input() {
    use scatterkit::Error::*;
    let c = |m, a: f64, f, p| Surface::new(m, a, f, p).err();
    assert_eq!(
        c(
            SurfaceModel::Phong,
            0.5,
            Fraction::Constant(0.5),
            CrossingPolicy::Fold
        ),
        Some(Domain)
    );
    assert_eq!(
        c(
            SurfaceModel::Phong,
            2e6,
            Fraction::Constant(0.5),
            CrossingPolicy::Fold
        ),
        Some(Domain)
    );
    assert_eq!(
        c(
            SurfaceModel::Phong,
            f64::NAN,
            Fraction::Constant(0.5),
            CrossingPolicy::Fold
        ),
        Some(Domain)
    );
    assert_eq!(
        c(
            SurfaceModel::Lambert,
            0.0,
            Fraction::Constant(0.5),
            CrossingPolicy::Fold
        ),
        None,
        "α unused"
    );
    assert_eq!(
        c(
            SurfaceModel::Lambert,
            1.0,
            Fraction::Constant(1.5),
            CrossingPolicy::Fold
        ),
        Some(Domain)
    );
    assert_eq!(
        c(
            SurfaceModel::Lambert,
            1.0,
            Fraction::Constant(f64::NAN),
            CrossingPolicy::Fold
        ),
        Some(Domain)
    );
    assert_eq!(
        c(
            SurfaceModel::Lambert,
            1.0,
            Fraction::Scalar(-1e-9),
            CrossingPolicy::Fold
        ),
        Some(Domain)
    );
    assert_eq!(
        c(
            SurfaceModel::Lambert,
            1.0,
            Fraction::Scalar(f64::INFINITY),
            CrossingPolicy::Fold
        ),
        Some(Domain)
    );
    assert_eq!(SurfaceModel::try_from(3), Err(Method));
    assert_eq!(CrossingPolicy::try_from(3), Err(Method));
    let s = Surface::new(
        SurfaceModel::Lambert,
        1.0,
        Fraction::Scalar(1e-9f64),
        CrossingPolicy::Fold,
    )
    .unwrap();
    let mut r = rng(1);
    let d = Vec3::new(0.0, 0.0, -1.0);
    let n = Vec3::new(0.0, 0.0, 1.0);
    let zero = Vec3::new(0.0, 0.0, 0.0);
    let nan = Vec3::new(f64::NAN, 0.0, 1.0);
    assert_eq!(
        s.interact(zero, n, 1.0, 1.5, 600e-9, &mut r).err(),
        Some(Domain)
    );
    assert_eq!(
        s.interact(d, nan, 1.0, 1.5, 600e-9, &mut r).err(),
        Some(Domain)
    );
    assert_eq!(
        s.interact(d, n, 0.0, 1.5, 600e-9, &mut r).err(),
        Some(Domain)
    );
    assert_eq!(
        s.interact(d, n, 1.0, f64::NAN, 600e-9, &mut r).err(),
        Some(Domain)
    );
    assert_eq!(s.interact(d, n, 1.0, 1.5, 0.0, &mut r).err(), Some(Domain));
    assert!(refract(d, n, 1.0, -1.5).is_err());
    assert!(
        phong_sample(d, n, 0.5, CrossingPolicy::Fold, 0.5, 0.5)
            .x
            .is_nan()
    );
    let _ = surface::RESAMPLE_ATTEMPTS;
}

/// Refraction refuses `n_i/n_t` above 2²⁶, where its direction's error
/// (about `η ε`, two terms of size `η` cancelling to a unit vector) stops
/// being small: at `η = 10⁸` it was noise, at `η = 10¹⁷` NaN at normal
/// incidence with `Ok`. At 2²⁶ normal incidence still goes straight on.
#[test]
fn refraction_refuses_an_index_ratio_beyond_two_to_the_26() {
    let n = Vec3::new(0.0, 0.0, 1.0);
    let d = Vec3::new(0.0, 0.0, -1.0);
    let top = surface::MAX_INDEX_RATIO;
    assert_eq!(top, 67_108_864.0);
    let straight = refract(d, n, top, 1.0).unwrap();
    assert!((straight - d).length() < 1e-15, "{straight:?}");
    for eta in [top * (1.0 + f64::EPSILON), 1e8, 1e17] {
        assert_eq!(
            refract(d, n, eta, 1.0),
            Err(scatterkit::Error::Domain),
            "{eta}"
        );
        let s = Surface::new(
            SurfaceModel::Specular,
            1.0,
            Fraction::Constant(0.0f64),
            CrossingPolicy::Fold,
        )
        .unwrap();
        let x = s.interact(d, n, eta, 1.0, 600e-9, &mut rng(1));
        assert_eq!(x.err(), Some(scatterkit::Error::Domain), "{eta}");
    }
    // The other way round, n_t far above n_i, nothing cancels: accepted.
    let down = refract(Vec3::new(0.6, 0.0, -0.8), n, 1.0, 1e17).unwrap();
    assert!(
        (down.length() - 1.0).abs() < 1e-15 && down.z < 0.0,
        "{down:?}"
    );
}
