//! Rayleigh: every method of Frisvad (2011) against the pdf (chi²), the known
//! wrong method rejected by the same test, the direct method's accuracy
//! against a double-double reference, and the paper's tabulation figures.

use crate::common;
use crate::common::nan_max;

use common::chi2::{chi2_directions, gamma_q, threshold};
use common::dd;
use common::{CHI2_SAMPLES, Counting, rng, test_directions};
use rand_xoshiro::rand_core::Rng;
use scatterkit::{PhaseFunction, Rayleigh, RayleighMethod, Real, Table, Vec3, rayleigh};

fn rayleigh_pdf(mu: f64) -> f64 {
    3.0 / (16.0 * std::f64::consts::PI) * (1.0 + mu * mu)
}

fn to_vec<T: Real>(w: [f64; 3]) -> Vec3<T> {
    let v = Vec3::new(T::from_f64(w[0]), T::from_f64(w[1]), T::from_f64(w[2]));
    v.try_normalize().unwrap()
}

fn to_f64<T: Real>(v: Vec3<T>) -> [f64; 3] {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}

fn chi2_method<T: Real>(method: RayleighMethod, seed: u64) {
    for (k, w) in test_directions().into_iter().enumerate() {
        let w_in = to_vec::<T>(w);
        let mut r = rng(seed + k as u64);
        let res = chi2_directions(&rayleigh_pdf, to_f64(w_in), CHI2_SAMPLES, || {
            to_f64(rayleigh::sample_dir(method, w_in, &mut r))
        });
        assert!(
            res.passes(),
            "{method:?} ({}) about {w:?}: {res:?}, threshold {:.2e}",
            std::any::type_name::<T>(),
            threshold()
        );
    }
}

macro_rules! chi2_tests {
    ($($name:ident: $m:expr, $seed:expr;)*) => {$(
        #[test]
        fn $name() {
            chi2_method::<f32>($m, $seed);
            chi2_method::<f64>($m, $seed + 100);
        }
    )*};
}

chi2_tests! {
    chi2_reject_cube: RayleighMethod::RejectCube, 1;
    chi2_reject_spherical: RayleighMethod::RejectSpherical, 2;
    chi2_baranoski_corrected: RayleighMethod::Baranoski, 3;
    chi2_simplified: RayleighMethod::Simplified, 4;
    chi2_direct: RayleighMethod::Direct, 5;
    chi2_direct_fast: RayleighMethod::DirectFast, 6;
    chi2_direct_minimax: RayleighMethod::DirectMinimax, 7;
    chi2_table: RayleighMethod::Table, 8;
}

/// Baranoski's rejection as first published: `μ = cos(πξ₁)` accepted with
/// `(1 + μ²)/2`, missing the `sqrt(1 − μ²)` Jacobian and Frisvad's constant.
/// Known wrong; it exists only here.
fn baranoski_uncorrected(rng: &mut impl Rng) -> f64 {
    loop {
        let mu = (std::f64::consts::PI * f64::uniform(rng)).cos();
        if 2.0 * f64::uniform(rng) <= 1.0 + mu * mu {
            return mu;
        }
    }
}

#[test]
fn chi2_rejects_uncorrected_baranoski() {
    for (k, w) in test_directions().into_iter().enumerate() {
        let w_in = to_vec::<f64>(w);
        let mut r = rng(50 + k as u64);
        let res = chi2_directions(&rayleigh_pdf, to_f64(w_in), CHI2_SAMPLES, || {
            let mu = baranoski_uncorrected(&mut r);
            let phi = std::f64::consts::TAU * f64::uniform(&mut r);
            to_f64(scatterkit::geometry::direction_about(w_in, mu, phi))
        });
        assert!(
            !res.passes(),
            "the wrong sampler passed about {w:?}: {res:?}"
        );
    }
}

#[test]
fn chi2_p_values_of_known_quantiles() {
    // chi² quantiles: P(X > 23.209) = 0.01 for 10 dof; P(X > 3.841) = 0.05 for 1.
    assert!((gamma_q(5.0, 23.209 / 2.0) - 0.01).abs() < 1e-4);
    assert!((gamma_q(0.5, 3.841 / 2.0) - 0.05).abs() < 1e-4);
    assert!((gamma_q(500.0, 500.0) - 0.4941).abs() < 1e-3);
}

#[test]
fn every_method_gives_unit_directions_and_zero_mean_cosine() {
    for m in RayleighMethod::ALL {
        let mut r = rng(7);
        let w_in = to_vec::<f32>([0.3, -0.5, 0.81]);
        let (mut sum, n) = (0.0f64, 200_000);
        for _ in 0..n {
            let d = rayleigh::sample_dir(m, w_in, &mut r);
            assert!((d.length() - 1.0).abs() <= 1e-6, "{m:?}: {d:?}");
            sum += d.dot(w_in) as f64;
        }
        // Var(μ) = 2/5 for Rayleigh: 5σ of the mean is 5·sqrt(0.4/n).
        assert!(
            (sum / n as f64).abs() < 5.0 * (0.4f64 / n as f64).sqrt(),
            "{m:?}"
        );
    }
}

/// The four inversion methods (Frisvad's direct forms and the table) say
/// so, and only they fill `inverse_cdf_fill` with cosines; the others fill
/// NaN, as documented.
#[test]
fn the_inversion_methods_are_the_ones_with_an_inverse() {
    use RayleighMethod::*;
    let u = [0.0f64, 0.25, 0.5, 1.0];
    for m in RayleighMethod::ALL {
        let inversion = matches!(m, Direct | DirectFast | DirectMinimax | Table);
        assert_eq!(m.is_inversion(), inversion, "{m:?}");
        let mut c = [0.0f64; 4];
        rayleigh::inverse_cdf_fill(m, &u, &mut c);
        let finite = c.iter().all(|x| (-1.0..=1.0).contains(x));
        assert_eq!(finite, inversion, "{m:?}: {c:?}");
        assert!(inversion || c.iter().all(|x| x.is_nan()), "{m:?}: {c:?}");
    }
}

#[test]
fn method_values_match_the_c_enum() {
    for (i, m) in RayleighMethod::ALL.into_iter().enumerate() {
        assert_eq!(m as u32, i as u32);
        assert_eq!(RayleighMethod::try_from(i as u32), Ok(m));
    }
    assert_eq!(RayleighMethod::try_from(8), Err(scatterkit::Error::Method));
}

/// Max |μ − μ_ref| of an inverse over `n` uniforms including 0 and 1.
fn max_error<T: Real>(f: impl Fn(T) -> T, reference: impl Fn(f64) -> f64, n: usize) -> f64 {
    common::uniform_grid(n)
        .map(|u| {
            let u = T::from_f64(u);
            (f(u).to_f64() - reference(u.to_f64())).abs()
        })
        .fold(0.0, nan_max)
}

#[test]
fn direct_inverse_is_accurate() {
    let n = 1_000_001;
    let e32 = max_error::<f32>(rayleigh::inverse_cdf_direct::<f32>, dd::rayleigh_inverse, n);
    let e64 = max_error::<f64>(rayleigh::inverse_cdf_direct::<f64>, dd::rayleigh_inverse, n);
    let m32 = max_error::<f32>(|u| Rayleigh.sample_cos(u), dd::rayleigh_inverse, n);
    let m64 = max_error::<f64>(|u| Rayleigh.sample_cos(u), dd::rayleigh_inverse, n);
    let fast32 = max_error::<f32>(rayleigh::inverse_cdf_fast::<f32>, dd::rayleigh_inverse, n);
    println!(
        "Rayleigh direct: f32 {e32:.2e}, f64 {e64:.2e}; minimax: f32 {m32:.2e}, f64 {m64:.2e}; f32 fast {fast32:.2e}"
    );
    // Bounds: 4 ULP of 1 (the stable Cardano form has no cancellation left).
    for (name, e, eps) in [
        ("direct", e32, f32::EPSILON as f64),
        ("minimax", m32, f32::EPSILON as f64),
    ] {
        assert!(e <= 4.0 * eps, "{name} f32 {e:e}");
    }
    for (name, e) in [("direct", e64), ("minimax", m64)] {
        assert!(e <= 4.0 * f64::EPSILON, "{name} f64 {e:e}");
    }
    // One Lancaster step: relative cube-root error ~2e-5.
    assert!(fast32 <= 1e-4, "f32 fast {fast32:e}");
    // The built-in Hermite table: interpolation error below f32 resolution.
    let t64 = max_error::<f64>(rayleigh::inverse_cdf_table::<f64>, dd::rayleigh_inverse, n);
    let t32 = max_error::<f32>(rayleigh::inverse_cdf_table::<f32>, dd::rayleigh_inverse, n);
    println!(
        "Rayleigh table (n = {}): f64 {t64:.2e}, f32 {t32:.2e}",
        rayleigh::TABLE_N
    );
    assert!(
        t64 <= 1e-8 && t32 <= 4.0 * f32::EPSILON as f64,
        "table {t64:e} {t32:e}"
    );
}

#[test]
fn direct_inverse_is_monotone_and_inverts_cdf() {
    let mut prev = -1.0f32;
    for i in 0..=(1u32 << 20) {
        let u = i as f32 / (1u32 << 20) as f32;
        let mu = Rayleigh.sample_cos(u);
        assert!(mu >= prev, "not monotone at u = {u}");
        prev = mu;
        // F is Lipschitz with constant 3/4: |F(μ(u)) − u| ≤ 3/4 |Δμ| + rounding.
        assert!((Rayleigh.cdf(mu) - u).abs() <= 6e-7, "u = {u}");
    }
    assert_eq!(Rayleigh.sample_cos(0.0f32), -1.0);
    assert_eq!(Rayleigh.sample_cos(1.0f32), 1.0);
    assert_eq!(Rayleigh.sample_cos(0.5f64), 0.0);
}

/// (rms, max) error in cos θ of Frisvad's table against the exact inverse,
/// over a fine uniform grid of u.
fn table_errors(n: usize) -> (f64, f64) {
    let mut buf = vec![0.0f64; n + 1];
    let table = Table::rayleigh_cdf(&mut buf, n).unwrap();
    let m = 1_000_001;
    let (mut sum2, mut max) = (0.0f64, 0.0f64);
    for u in common::uniform_grid(m) {
        let e = (table.sample_cos(u) - dd::rayleigh_inverse(u)).abs();
        sum2 += e * e;
        max = nan_max(max, e);
    }
    ((sum2 / m as f64).sqrt(), max)
}

#[test]
fn table_reproduces_frisvad_figures() {
    let (rms32, max32) = table_errors(32);
    let (rms8, _) = table_errors(8);
    println!("table n=32: rms {rms32:.3e} max {max32:.3e}; n=8: rms {rms8:.3e}");
    let within = |got: f64, paper: f64| (got / paper - 1.0).abs() <= 0.05;
    assert!(within(rms32, 2.9e-4), "n = 32 rms {rms32:e}, paper 2.9e-4");
    assert!(within(max32, 4.9e-4), "n = 32 max {max32:e}, paper 4.9e-4");
    assert!(within(rms8, 4.5e-3), "n = 8 rms {rms8:e}, paper 4.5e-3");
    // "Each doubling of n quarters the error."
    let (rms64, _) = table_errors(64);
    assert!((rms32 / rms64 - 4.0).abs() < 0.4, "ratio {}", rms32 / rms64);
}

#[test]
fn table_works_for_any_n_and_checks_sizes() {
    let mut buf = [0.0f32; 2];
    let t = Table::rayleigh_cdf(&mut buf, 1).unwrap();
    assert_eq!(t.sample_cos(0.0), -1.0);
    assert_eq!(t.sample_cos(1.0), 1.0);
    assert_eq!(t.sample_cos(0.5), 0.0);
    let mut buf = [0.0f32; 8];
    assert_eq!(
        Table::rayleigh_cdf(&mut buf, 0),
        Err(scatterkit::Error::Size)
    );
    assert_eq!(
        Table::rayleigh_cdf(&mut buf, 8),
        Err(scatterkit::Error::Size)
    );
    let t = Table::rayleigh_cdf(&mut buf, 7).unwrap();
    let mut prev = -1.0;
    for i in 0..=1000 {
        let mu = t.sample_cos(i as f32 / 1000.0);
        assert!(mu >= prev);
        prev = mu;
    }
    assert!(t.sample_cos(f32::NAN).is_nan());
    assert_eq!(t.sample_cos(-3.0), -1.0);
}

#[test]
fn cross_section_and_coefficient() {
    // λ = 500 nm, a = 1 nm, n = 1.5 (in metres): α = 1e-27 · 1.25/4.25,
    // C = 128π⁵/3 · α²/λ⁴ = 1.8072e-26 m² (evaluated by hand).
    let c = rayleigh::cross_section(500e-9, 1e-9, 1.5).unwrap();
    assert!((c / 1.8072e-26 - 1.0).abs() < 1e-4, "{c:e}");
    let s = rayleigh::scattering_coeff(1e20, 500e-9, 1e-9, 1.5).unwrap();
    assert!((s / (1e20 * c) - 1.0).abs() < 1e-15);
    // λ⁻⁴: halving the wavelength scatters 16 times more.
    let c2 = rayleigh::cross_section(250e-9, 1e-9, 1.5).unwrap();
    assert!((c2 / c - 16.0).abs() < 1e-12);
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(rayleigh::cross_section(bad, 1e-9, 1.5).is_err());
        assert!(rayleigh::cross_section(500e-9, bad, 1.5).is_err());
        assert!(rayleigh::cross_section(500e-9, 1e-9, bad).is_err());
    }
    assert!(rayleigh::scattering_coeff(-1.0, 500e-9, 1e-9, 1.5).is_err());
    assert_eq!(rayleigh::scattering_coeff(0.0, 500e-9, 1e-9, 1.5), Ok(0.0));
    // Both forms of the Lorentz factor (n² − 1)/(n² + 2): n = 3 and 1.9
    // against the direct form (no cancellation at either), and the factor
    // reaching 1 where n² overflows (a perfect conductor's limit).
    let direct = |n: f64| {
        let l = (n * n - 1.0) / (n * n + 2.0);
        128.0 * std::f64::consts::PI.powi(5) / 3.0 * (1e-27 * l).powi(2) / 500e-9f64.powi(4)
    };
    for n in [3.0, 1.9, 1e3] {
        let c = rayleigh::cross_section(500e-9, 1e-9, n).unwrap();
        assert!((c / direct(n) - 1.0).abs() < 1e-13, "n {n}: {c:e}");
    }
    let huge = rayleigh::cross_section(500e-9, 1e-9, 1e200).unwrap();
    assert!((huge / direct(1e3) - 1.0).abs() < 1e-5, "{huge:e}");
}

/// Frisvad's table samples exactly the density its linear interpolation
/// implies: piecewise constant in μ, `(F[i+1] − F[i])/Δx` on interval i.
/// chi² against that density checks the search and interpolation.
#[test]
fn chi2_table_samples_its_own_piecewise_density() {
    fn check<T: Real>(n: usize, seed: u64) {
        let mut buf = vec![T::ZERO; n + 1];
        let table = Table::rayleigh_cdf(&mut buf, n).unwrap();
        let f: Vec<f64> = table.data().iter().map(|x| x.to_f64()).collect();
        let dx = 2.0 / n as f64;
        let pdf = move |mu: f64| {
            let i = (((mu + 1.0) / dx) as usize).min(n - 1);
            (f[i + 1] - f[i]) / dx / std::f64::consts::TAU
        };
        for (k, w) in test_directions().into_iter().enumerate() {
            let w_in = to_vec::<T>(w);
            let mut r = rng(seed + k as u64);
            let res = chi2_directions(&pdf, to_f64(w_in), CHI2_SAMPLES, || {
                let mu = table.sample_cos(T::uniform(&mut r));
                let phi = T::TAU * T::uniform(&mut r);
                to_f64(scatterkit::geometry::direction_about(w_in, mu, phi))
            });
            assert!(res.passes(), "table n = {n} about {w:?}: {res:?}");
        }
    }
    // n = 10 and 25 put the table's nodes on the chi² cell edges (50 cells).
    check::<f32>(10, 300);
    check::<f64>(25, 400);
}

/// A generator stuck on one word that every rejection method rejects.
struct Stuck(u64);

impl rand_xoshiro::rand_core::TryRng for Stuck {
    type Error = core::convert::Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Self::Error> {
        Ok((self.0 >> 32) as u32)
    }
    fn try_next_u64(&mut self) -> Result<u64, Self::Error> {
        Ok(self.0)
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Self::Error> {
        dst.fill(0);
        Ok(())
    }
}

/// The module's promise for a broken generator: after `MAX_TRIALS`
/// rejections each rejection method finishes with the direct method on the
/// next uniform, so it neither hangs nor answers something else (a
/// mutation test replaced that fallback by 0 unnoticed). Every uniform is
/// u ≈ 0.99 here, which the simplified, Baranoski's, the spherical and the
/// cube methods all reject (the cube's point lies outside the ball).
#[test]
fn a_stuck_generator_ends_with_the_direct_method() {
    let word = (0.99 * 9_007_199_254_740_992.0f64) as u64 * 2048;
    let u = f64::from_bits_uniform(word);
    let want = rayleigh::inverse_cdf_direct(u);
    for m in [RayleighMethod::Simplified, RayleighMethod::Baranoski] {
        let mu: f64 = rayleigh::sample_cos(m, &mut Stuck(word));
        assert_eq!(mu, want, "{m:?}");
    }
    let z = Vec3::new(0.0f64, 0.0, 1.0);
    for m in [
        RayleighMethod::RejectCube,
        RayleighMethod::RejectSpherical,
        RayleighMethod::Simplified,
        RayleighMethod::Baranoski,
    ] {
        let w = rayleigh::sample_dir(m, z, &mut Stuck(word));
        assert!((w.z - want).abs() < 1e-12, "{m:?}: {} against {want}", w.z);
    }
}

/// Each rejection method accepts at its published rate, read from the
/// uniforms it draws per cosine: the fallback after `MAX_TRIALS` keeps the
/// distribution right whatever the acceptance test does, so the chi² tests
/// cannot see an acceptance that never passes (a mutation test replaced
/// each acceptance by `false`, and the cube's point by `None`, unnoticed).
/// Expected draws per sample, a trial's draws over its acceptance `p`:
/// simplified 2/(2/3) = 3; Baranoski's with Frisvad's correction
/// 2/(√6/π) = 2π/√6; spherical (μ, azimuth, test) 3/(2/3) = 4.5; cube
/// `(3 + π/6)/(π/9)` (three coordinates, a test for the π/6 of points
/// inside the ball; the ball about the centre left out is 10⁻⁹ of it).
/// The same through `sample_dir`, one azimuth more where the method
/// draws a cosine. Within 1 % over 2·10⁵ samples, at least 5.5 standard
/// errors for each.
#[test]
fn rejection_methods_draw_at_their_acceptance_rate() {
    use std::f64::consts::PI;
    let cases = [
        (RayleighMethod::Simplified, 3.0),
        (RayleighMethod::Baranoski, 2.0 * PI / 6f64.sqrt()),
        (RayleighMethod::RejectSpherical, 4.5),
        (RayleighMethod::RejectCube, (3.0 + PI / 6.0) * 9.0 / PI),
    ];
    let n = 200_000;
    let w_in = Vec3::new(0.6f64, 0.0, 0.8);
    for (m, want) in cases {
        // `sample_dir` draws one azimuth more where the method gives a
        // cosine; the spherical and cube methods give the whole direction.
        let whole = matches!(
            m,
            RayleighMethod::RejectSpherical | RayleighMethod::RejectCube
        );
        let want_dir = if whole { want } else { want + 1.0 };
        let (mut g, mut h) = (Counting::new(11), Counting::new(12));
        for _ in 0..n {
            let _: f64 = rayleigh::sample_cos(m, &mut g);
            let _ = rayleigh::sample_dir(m, w_in, &mut h);
        }
        for (what, count, want) in [("cos", g.1, want), ("dir", h.1, want_dir)] {
            let per = count as f64 / n as f64;
            assert!(
                (per / want - 1.0).abs() < 0.01,
                "{m:?} {what}: {per} draws per sample, want {want}"
            );
        }
    }
}

/// `sample_cos_fill` gives, element by element, what `sample_cos` gives on
/// the same generator (a mutation test emptied it unnoticed).
#[test]
fn sample_cos_fill_is_sample_cos_in_a_loop() {
    for m in RayleighMethod::ALL {
        let mut out = [f64::NAN; 37];
        rayleigh::sample_cos_fill(m, &mut rng(5), &mut out);
        let mut r = rng(5);
        for (i, &c) in out.iter().enumerate() {
            let want: f64 = rayleigh::sample_cos(m, &mut r);
            assert_eq!(c.to_bits(), want.to_bits(), "{m:?} at {i}");
        }
    }
}
