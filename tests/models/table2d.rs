//! 2-D tables (`Table2d`, `cos θ × x`): at a slice the 1-D table bit for
//! bit; between slices monotone in `u`, its pdf and CDF those of the
//! distribution sampled (chi² over the sphere, `F(μ(u)) = u`, the mean);
//! the total-variation distance to the exact phase function at the sizes
//! the guide recommends, for HG whose `g` changes with `x` and for Mie
//! scattering by a water droplet over the visible wavelengths; bad input.
//! The header-only lookup against the library is `tests/c_abi/table_header.rs`.

use crate::common;
use crate::common::nan_max;

use common::chi2::{chi2_directions_by_cells, threshold};
use common::{CHI2_SAMPLES, rng};
use scatterkit::mie::{self, Complex, Mie};
use scatterkit::{Error, HenyeyGreenstein, PhaseFunction, Real, Table, Table2d, TableKind, Vec3};
use std::cmp::Ordering;
use std::f64::consts::PI;

/// HG with `g = 0.2 + 0.7 x` on `x ∈ [0, 1]`, `k` slices of `n` intervals.
fn hg_table<T: Real>(buf: &mut Vec<T>, n: usize, k: usize) -> Table2d<'_, T> {
    *buf = vec![T::ZERO; Table2d::<T>::len(n, k).unwrap()];
    let dx = T::ONE / T::from_f64((k - 1) as f64);
    Table2d::inverse(buf, n, k, T::ZERO, dx, |x| {
        HenyeyGreenstein::new(T::from_f64(0.2) + T::from_f64(0.7) * x)
    })
    .unwrap()
}

fn hg_at(x: f64) -> HenyeyGreenstein<f64> {
    HenyeyGreenstein::new(0.2 + 0.7 * x).unwrap()
}

/// `½ ∫ |a − b| dΩ` on 40 000 angles crowded quadratically toward θ = 0
/// (midpoint rule in θ).
fn tv(a: impl Fn(f64) -> f64, b: impl Fn(f64) -> f64) -> f64 {
    let m = 40_000;
    let edge = |i: usize| PI * (i as f64 / m as f64).powi(2);
    let sum: f64 = (0..m)
        .map(|i| {
            let (t0, t1) = (edge(i), edge(i + 1));
            let th = 0.5 * (t0 + t1);
            (a(th.cos()) - b(th.cos())).abs() * th.sin() * (t1 - t0)
        })
        .sum();
    PI * sum
}

#[test]
fn slices_are_the_1d_tables_and_the_blend_is_monotone() {
    let mut buf = Vec::new();
    let t = hg_table::<f32>(&mut buf, 256, 9);
    let mut one = vec![0.0f32; TableKind::Inverse.len(256).unwrap()];
    for j in 0..9 {
        let x = j as f32 / 8.0;
        let g = 0.2 + 0.7 * x;
        let s = Table::inverse(&HenyeyGreenstein::new(g).unwrap(), &mut one, 256).unwrap();
        for i in 0..=4096 {
            let u = i as f32 / 4096.0;
            assert_eq!(
                t.sample_cos(x, u).to_bits(),
                s.sample_cos(u).to_bits(),
                "slice {j} u {u}"
            );
        }
    }
    // Monotone in u between slices (2²⁰ + 1 uniforms at three x).
    for x in [0.03f32, 0.5 + 1.0 / 16.0, 0.97] {
        let mut last = -1.0f32;
        for i in 0..=1 << 20 {
            let mu = t.sample_cos(x, i as f32 / (1 << 20) as f32);
            assert!(mu >= last && mu.abs() <= 1.0, "x {x} i {i}");
            last = mu;
        }
    }
    // Outside the slices' range: the end slices; NaN in, NaN out.
    assert_eq!(t.sample_cos(-3.0, 0.4), t.sample_cos(0.0, 0.4));
    assert_eq!(t.sample_cos(7.0, 0.4), t.sample_cos(1.0, 0.4));
    assert!(t.sample_cos(f32::NAN, 0.4).is_nan() && t.sample_cos(0.4, f32::NAN).is_nan());
    assert!(t.pdf(f32::NAN, 0.4).is_nan() && t.cdf(0.3, f32::NAN).is_nan());
}

/// Between slices the pdf, CDF and mean are those of the blend sampled:
/// chi² over the sphere (10⁶ samples, cells from the table's CDF) at a
/// point between two slices; `F(μ(u)) = u` within 10⁻¹² (f64); the pdf is
/// the CDF's derivative within 10⁻⁶; the mean against the mean of `μ(u)`.
#[test]
fn pdf_and_cdf_are_those_of_the_blend() {
    let mut buf = Vec::new();
    let t = hg_table::<f64>(&mut buf, 64, 5);
    let x = 0.3;
    let mut r = rng(4242);
    let w_in = Vec3::new(0.0, 0.6, 0.8);
    let cells = |lo: f64, hi: f64| t.cdf(x, hi) - t.cdf(x, lo);
    let res = chi2_directions_by_cells(&cells, [0.0, 0.6, 0.8], CHI2_SAMPLES, || {
        let (d, _) = t.sample_dir(x, w_in, f64::uniform(&mut r), f64::uniform(&mut r));
        [d.x, d.y, d.z]
    });
    assert!(res.passes(), "{res:?} ({:.2e})", threshold());
    let mut mean = 0.0;
    let m = 200_000;
    for i in 0..=m {
        let u = i as f64 / m as f64;
        let mu = t.sample_cos(x, u);
        assert!((t.cdf(x, mu) - u).abs() <= 1e-12, "u {u}");
        mean += if i == 0 || i == m { 0.5 * mu } else { mu };
    }
    assert!((t.mean_cosine(x) - mean / m as f64).abs() <= 1e-9);
    for mu in [-0.9, -0.2, 0.4, 0.95] {
        let h = 1e-6;
        let slope = (t.cdf(x, mu + h) - t.cdf(x, mu - h)) / (2.0 * h) / (2.0 * PI);
        assert!((t.pdf(x, mu) - slope).abs() <= 1e-6 * slope, "μ {mu}");
    }
}

/// Mie for a water droplet of diameter `d` µm at wavelength `lam` µm.
fn mie_at(d: f64, lam: f64, buf: &mut Vec<Complex>) -> Mie<'_> {
    let m = mie::water(lam).unwrap();
    let x = mie::size_parameter(d, lam, 1.0);
    buf.resize(mie::buffer_len(x, m).unwrap(), Complex::default());
    Mie::new(x, m, buf).unwrap()
}

/// The total-variation distance to the exact phase function at the
/// midpoints between slices (the worst place), at the sizes the guide
/// recommends, with thresholds set from the guide's claims:
/// * HG with `g` from 0.2 to 0.9 in 33 slices (`Δg` ≈ 0.022), n = 256:
///   ≤ 2.5·10⁻³ at every midpoint, ≤ 10⁻⁶ at a slice;
/// * Mie, water droplets of 0.2 µm and 1 µm over 380–780 nm in slices
///   0.1 in size parameter or closer (17 and 65 slices), the tables of
///   `mie::table_sizes`: ≤ 2.5·10⁻³ and ≤ 10⁻² at every midpoint.
#[test]
fn total_variation_at_the_recommended_sizes() {
    let mut buf = Vec::new();
    let t = hg_table::<f64>(&mut buf, 256, 33);
    let worst = (0..32)
        .map(|j| {
            let x = (j as f64 + 0.5) / 32.0;
            tv(|mu| t.pdf(x, mu), |mu| hg_at(x).pdf(mu))
        })
        .fold(0.0, nan_max);
    assert!(worst <= 2.5e-3, "HG between slices: {worst:.2e}");
    let at_slice = tv(|mu| t.pdf(0.5, mu), |mu| hg_at(0.5).pdf(mu));
    assert!(at_slice <= 1e-6, "HG at a slice: {at_slice:.2e}");
    for (d, k, limit) in [(0.2, 17, 2.5e-3), (1.0, 65, 1e-2)] {
        let (count, n) = mie::table_sizes(mie::size_parameter(d, 0.38, 1.0));
        let mut buf = vec![0.0f64; Table2d::<f64>::len(n, k).unwrap()];
        let dx = 0.4 / (k - 1) as f64;
        let (mut c, mut p, mut mb) = (vec![0.0; count], vec![0.0; count], Vec::new());
        let t = Table2d::build(&mut buf, n, k, 0.38, dx, |_, lam, slice| {
            mie_at(d, lam, &mut mb).tabulate(&mut c, &mut p)?;
            Table::measured(&c, &p, slice, n).map(|_| ())
        })
        .unwrap();
        let worst = (0..k - 1)
            .map(|j| {
                let lam = 0.38 + (j as f64 + 0.5) * dx;
                let exact = mie_at(d, lam, &mut mb);
                tv(|mu| t.pdf(lam, mu), |mu| exact.phase(mu))
            })
            .fold(0.0, nan_max);
        eprintln!("Mie d = {d} µm, {k} slices: worst TV over every midpoint {worst:.2e}");
        assert!(worst <= limit, "Mie d = {d} µm, {k} slices: {worst:.2e}");
    }
}

#[test]
fn bad_input_is_an_error() {
    let mut buf = vec![0.0f32; Table2d::<f32>::len(16, 3).unwrap()];
    let hg = |_: f32| HenyeyGreenstein::new(0.5f32);
    assert_eq!(Table2d::<f32>::len(0, 3), None);
    assert_eq!(Table2d::<f32>::len(16, 0), None);
    assert_eq!(Table2d::<f32>::len(usize::MAX / 2, 3), None);
    let err = |r: Result<Table2d<'_, f32>, Error>| r.err();
    assert_eq!(
        err(Table2d::inverse(&mut buf, 16, 4, 0.0, 1.0, hg)),
        Some(Error::Size)
    );
    assert_eq!(
        err(Table2d::inverse(&mut buf, 0, 3, 0.0, 1.0, hg)),
        Some(Error::Size)
    );
    for (x0, dx) in [
        (0.0, 0.0),
        (0.0, -1.0),
        (f32::NAN, 1.0),
        (0.0, f32::INFINITY),
    ] {
        assert_eq!(
            err(Table2d::inverse(&mut buf, 16, 3, x0, dx, hg)),
            Some(Error::Domain)
        );
    }
    let bad_g = |x: f32| HenyeyGreenstein::new(x);
    assert_eq!(
        err(Table2d::inverse(&mut buf, 16, 3, 0.0, 1.0, bad_g)),
        Some(Error::Domain)
    );
    let good = Table2d::inverse(&mut buf, 16, 3, 0.0, 1.0, hg).unwrap();
    assert!(good.slice(2).is_some() && good.slice(3).is_none());
    // Data that is not a monotone table in [−1, 1].
    for (i, v) in [(6, -0.999), (1, f32::NAN), (3, -1.0), (0, -1.5), (34, 1.5)] {
        let mut data = buf.clone();
        data[i] = v;
        assert_eq!(
            err(Table2d::from_data(&data, 16, 3, 0.0, 1.0)),
            Some(Error::Domain),
            "{i}"
        );
    }
}

#[test]
fn slices_must_stay_monotone_within_their_nodes() {
    // The library's own slices pass the check of caller data; a slope
    // above 3 times a neighbouring secant (a spline that overshoots its
    // nodes, whose mean cosine and density would not be those sampled) is
    // refused, and so is a negative or non-finite one.
    let mut buf = Vec::new();
    let t = hg_table::<f64>(&mut buf, 16, 3);
    let (n, k, x0, dx) = (t.n(), t.k(), t.x0(), t.dx());
    let data = t.data().to_vec();
    assert!(Table2d::from_data(&data, n, k, x0, dx).is_ok());
    for (i, bad) in [(3usize, 1e30), (5, -1.0), (7, f64::NAN)] {
        let mut d = data.clone();
        // Node 1's slope, then later ones (odd entries are slopes).
        d[i] = if bad == 1e30 {
            3.0 * (d[i + 1] - d[i - 1]) * 1.0001 + 1e-12
        } else {
            bad
        };
        assert_eq!(
            Table2d::from_data(&d, n, k, x0, dx).err(),
            Some(Error::Domain),
            "{i}"
        );
    }
    // Every mean cosine a valid table reports is that of what it samples:
    // within [-1, 1].
    for j in 0..=40 {
        let x = x0 + dx * (k - 1) as f64 * j as f64 / 40.0;
        assert!(t.mean_cosine(x).abs() <= 1.0);
    }
}

/// Slices of measured data whose supports end at different cosines
/// inside (−1, 1): every sample at every `x` (at the slices and between)
/// has a positive density of the blend, f32 and f64.
#[test]
fn a_blend_of_measured_slices_samples_where_its_density_is_positive() {
    fn check<T: Real>() -> (usize, usize) {
        let (n, k) = (16usize, 5usize);
        let xs = [-1.0, -0.6, -0.2, 0.1, 0.3, 0.55, 0.8, 1.0];
        let mut buf = vec![T::ZERO; Table2d::<T>::len(n, k).unwrap()];
        let t = Table2d::build(&mut buf, n, k, T::ZERO, T::ONE, |j, _, slice| {
            // Slice j: mass between points 1 + j % 3 and 6 - j % 2.
            let (a, b) = (1 + j % 3, 6 - j % 2);
            let x: Vec<T> = xs.iter().map(|&c| T::from_f64(c)).collect();
            let p: Vec<T> = (0..xs.len())
                .map(|i| {
                    T::from_f64(if i > a && i < b {
                        1.0 + 0.3 * i as f64
                    } else {
                        0.0
                    })
                })
                .collect();
            Table::measured(&x, &p, slice, n).map(|_| ())
        })
        .unwrap();
        let (mut bad, mut all) = (0, 0);
        for ix in 0..=400 {
            let x = T::from_f64(4.0 * ix as f64 / 400.0);
            for iu in 0..=2000 {
                let u = T::from_f64(iu as f64 / 2000.0);
                let mu = t.sample_cos(x, u);
                all += 1;
                // Positive, not NaN.
                bad += usize::from(t.pdf(x, mu).partial_cmp(&T::ZERO) != Some(Ordering::Greater));
            }
        }
        (bad, all)
    }
    let (b32, a32) = check::<f32>();
    let (b64, a64) = check::<f64>();
    assert!(
        b32 == 0 && b64 == 0,
        "f32 {b32} of {a32}, f64 {b64} of {a64} with pdf 0"
    );
}
