//! Mie scattering against results nobody on this project computed:
//!
//! * Wiscombe's MIEV0 test cases 5–19 (W. J. Wiscombe, "Mie scattering
//!   calculations: advances in technique and fast, vector-speed computer
//!   codes", NCAR Technical Note TN-140+STR, 1979, revised 1996, appendix;
//!   the values MIEV0's own test driver checks): `Q_ext`, `Q_sca` and
//!   `g Q_sca` to the seven significant digits published. MIEV0 writes the
//!   index as `n − ik`; here it is `n + ik`. (Cases 1–4, perfectly
//!   conducting spheres, are outside this implementation's domain.)
//! * Bohren & Huffman's BHMIE example (*Absorption and Scattering of Light
//!   by Small Particles*, 1983, appendix A: `m = 1.55`, `r = 0.525 µm`,
//!   `λ = 0.6328 µm`): `Q_ext = Q_sca = 3.10543`, `Q_back = 2.92534`,
//!   `g = 0.63314`.
//!
//! Plus the optical theorem (`Q_ext = 4 Re S(0) / x²`), `Q_back = 4 |S1(π)|²
//! / x²`, energy bounds and the phase function's normalisation across the
//! domain, and small-x stability; and 182 spheres from `x = 10⁻²⁰` to 30
//! against the series summed in 80 digits.

use crate::common::nan_max;
use scatterkit::mie::{Complex, Mie, buffer_len};

fn solve(x: f64, n: f64, k: f64) -> (Vec<Complex>, f64, Complex) {
    let m = Complex::new(n, k);
    let len = buffer_len(x, m).unwrap();
    (vec![Complex::default(); len], x, m)
}

/// `|got − want|` within half a unit of the last of `digits` significant
/// digits of `want`.
fn agrees(got: f64, want: f64, digits: i32) -> bool {
    let ulp = 10f64.powi(want.abs().log10().floor() as i32 - (digits - 1));
    (got - want).abs() <= 0.5 * ulp * (1.0 + 1e-9)
}

/// (x, n, k, Q_ext, Q_sca, g Q_sca): MIEV0 test cases 5–19.
const MIEV0: [(f64, f64, f64, f64, f64, f64); 15] = [
    (0.099, 0.75, 0.0, 7.417859e-06, 7.417859e-06, 1.074279e-08),
    (0.101, 0.75, 0.0, 8.033542e-06, 8.033542e-06, 1.211000e-08),
    (10.0, 0.75, 0.0, 2.232265, 2.232265, 2.001164),
    (1000.0, 0.75, 0.0, 1.997908, 1.997908, 1.688121),
    (1.0, 1.33, 1e-5, 9.395198e-02, 9.392330e-02, 1.733048e-02),
    (100.0, 1.33, 1e-5, 2.101321, 2.096594, 1.821854),
    (10000.0, 1.33, 1e-5, 2.004089, 1.723857, 1.564987),
    (0.055, 1.5, 1.0, 1.014910e-01, 1.131687e-05, 5.558541e-09),
    (0.056, 1.5, 1.0, 1.033467e-01, 1.216311e-05, 6.193255e-09),
    (1.0, 1.5, 1.0, 2.336321, 6.634538e-01, 1.274736e-01),
    (100.0, 1.5, 1.0, 2.097502, 1.283697, 1.091466),
    (10000.0, 1.5, 1.0, 2.004368, 1.236574, 1.046525),
    (1.0, 10.0, 10.0, 2.532993, 2.049405, -2.267961e-01),
    (100.0, 10.0, 10.0, 2.071124, 1.836785, 1.021648),
    (10000.0, 10.0, 10.0, 2.005914, 1.795393, 9.842238e-01),
];

#[test]
fn wiscombe_miev0_test_cases_to_every_published_digit() {
    for (case, &(x, n, k, qe, qs, gqs)) in MIEV0.iter().enumerate() {
        let (mut buf, x, m) = solve(x, n, k);
        let e = Mie::new(x, m, &mut buf).unwrap().efficiencies;
        println!(
            "case {}: x {x} m {n}+{k}i: Q_ext {:.7e} ({qe:.7e}), Q_sca {:.7e} ({qs:.7e}), g Q_sca {:.7e} ({gqs:.7e})",
            case + 5,
            e.q_ext,
            e.q_sca,
            e.g * e.q_sca
        );
        // Seven digits, except where MIEV0's own seventh digit is not the
        // sphere's: see `where_miev0s_seventh_digit_is_off`.
        let digits = if OFF_IN_SEVENTH.contains(&(case + 5)) {
            6
        } else {
            7
        };
        assert!(
            agrees(e.q_ext, qe, digits),
            "case {}: Q_ext {} vs {qe}",
            case + 5,
            e.q_ext
        );
        assert!(
            agrees(e.q_sca, qs, digits),
            "case {}: Q_sca {} vs {qs}",
            case + 5,
            e.q_sca
        );
        assert!(
            agrees(e.g * e.q_sca, gqs, digits),
            "case {}: g Q_sca {} vs {gqs}",
            case + 5,
            e.g * e.q_sca
        );
    }
}

/// MIEV0 cases whose published seventh digit differs from the exact sphere
/// (MIEV0 evaluates x < 0.1-ish with its small-particle expansion).
const OFF_IN_SEVENTH: [usize; 3] = [5, 6, 12];

/// (case, x, n, k, Q_ext, g Q_sca) from the series summed in 40-digit
/// arithmetic (mpmath 1.3, Riccati–Bessel functions from `besselj` and
/// `bessely`, no recurrences; `scripts/mie_reference.py`), for MIEV0's
/// small spheres, five more of its cases, and (case 0, not MIEV0's) water
/// at x = 1000, where the start of the `D_n` recurrence matters most.
const FORTY_DIGIT: [(usize, f64, f64, f64, f64, f64); 10] = [
    (5, 0.099, 0.75, 0.0, 7.41785911491e-6, 1.07427734367e-8),
    (6, 0.101, 0.75, 0.0, 8.03353814856e-6, 1.21099958183e-8),
    (12, 0.055, 1.5, 1.0, 0.101491041705, 5.55853694541e-9),
    (13, 0.056, 1.5, 1.0, 0.10334669465, 6.19325493151e-9),
    (7, 10.0, 0.75, 0.0, 2.23226484250202, 2.00116416533667),
    (14, 1.0, 1.5, 1.0, 2.33632098467261, 0.127473614578647),
    (10, 100.0, 1.33, 1e-5, 2.10132070588026, 1.82185436700066),
    (17, 1.0, 10.0, 10.0, 2.53299307789637, -0.226796095614914),
    (18, 100.0, 10.0, 10.0, 2.07112432672695, 1.02164848287015),
    (0, 1000.0, 1.333, 1e-8, 2.02280787312486, 1.78024105567029),
];

#[test]
fn where_miev0s_seventh_digit_is_off() {
    // MIEV0 publishes g Q_sca = 1.074279e-8 (case 5), Q_ext = 8.033542e-6
    // (case 6) and g Q_sca = 5.558541e-9 (case 12); the 40-digit sums give
    // 1.0742773e-8, 8.0335381e-6 and 5.5585369e-9. This solver must agree
    // with the 40-digit values to 10 digits (measured: 3·10⁻¹¹ or better), and so lands off MIEV0's
    // seventh digit exactly where MIEV0 is off.
    for &(case, x, n, k, qe, gqs) in &FORTY_DIGIT {
        let (mut buf, x, m) = solve(x, n, k);
        let e = Mie::new(x, m, &mut buf).unwrap().efficiencies;
        let gq = e.g * e.q_sca;
        let (rq, rg) = ((e.q_ext / qe - 1.0).abs(), (gq / gqs - 1.0).abs());
        println!("case {case}: relative error Q_ext {rq:.1e}, g Q_sca {rg:.1e}");
        assert!(rq < 1e-10, "case {case}: Q_ext {}", e.q_ext);
        assert!(rg < 1e-10, "case {case}: g Q_sca {gq}");
    }
}

/// `|S|²` agrees with a published `re + i im` given to `digits` significant
/// digits in each part: within what rounding the parts allows.
fn agrees_sq(got: Complex, re: f64, im: f64, digits: i32) -> bool {
    let half = |v: f64| {
        if v == 0.0 {
            0.0
        } else {
            0.5 * 10f64.powi(v.abs().log10().floor() as i32 - (digits - 1))
        }
    };
    let (dr, di) = (half(re), half(im));
    let want = re * re + im * im;
    let slack = 2.0 * (re.abs() * dr + im.abs() * di) + dr * dr + di * di;
    (got.norm_sqr() - want).abs() <= slack * (1.0 + 1e-9)
}

/// MIEV0's amplitudes, as its test driver prints them (Wiscombe, NCAR
/// TN-140, test cases; reproduced in the tests of S. Prahl's miepython):
/// `S1(180°)` for cases 5–8, and `S1`, `S2` at 0°, 30°, …, 180° for case 14
/// (`x = 1`, `m = 1.5 + i`). MIEV0's sign convention conjugates the
/// amplitudes, so the comparison is of `|S1|²` and `|S2|²`.
#[test]
fn miev0_amplitudes_at_the_published_angles() {
    for (x, re, im) in [
        (0.099, 1.81756e-8, -1.64810e-4),
        (0.101, 2.04875e-8, -1.74965e-4),
        (10.0, -1.07857, -3.60881e-2),
        (1000.0, 1.70578e1, 4.84251e2),
    ] {
        let (mut buf, x, m) = solve(x, 0.75, 0.0);
        let mie = Mie::new(x, m, &mut buf).unwrap();
        let (s1, _) = mie.amplitudes(-1.0);
        println!("x {x}: S1(180°) = {s1:?}");
        assert!(
            agrees_sq(s1, re, im, 6),
            "x {x}: S1(180°) {s1:?} vs {re} {im}"
        );
    }
    #[rustfmt::skip]
    let case14: [(f64, [f64; 4]); 7] = [
        (0.0, [0.584080, 0.190515, 0.584080, 0.190515]),
        (30.0, [0.565702, 0.187200, 0.500161, 0.145611]),
        (60.0, [0.517525, 0.178443, 0.287964, 0.041054]),
        (90.0, [0.456340, 0.167167, 0.0362285, -0.0618265]),
        (120.0, [0.400212, 0.156643, -0.174875, -0.122959]),
        (150.0, [0.362157, 0.149391, -0.305682, -0.143846]),
        (180.0, [0.348844, 0.146829, -0.348844, -0.146829]),
    ];
    let (mut buf, x, m) = solve(1.0, 1.5, 1.0);
    let mie = Mie::new(x, m, &mut buf).unwrap();
    for (deg, [r1, i1, r2, i2]) in case14 {
        let mu = if deg == 90.0 {
            0.0
        } else {
            deg.to_radians().cos()
        };
        let (s1, s2) = mie.amplitudes(mu);
        println!("{deg}°: S1 {s1:?} S2 {s2:?}");
        assert!(agrees_sq(s1, r1, i1, 6), "{deg}°: S1 {s1:?}");
        assert!(agrees_sq(s2, r2, i2, 6), "{deg}°: S2 {s2:?}");
    }
}

#[test]
fn bohren_huffman_bhmie_example() {
    let x = std::f64::consts::TAU * 0.525 / 0.6328;
    let (mut buf, x, m) = solve(x, 1.55, 0.0);
    let e = Mie::new(x, m, &mut buf).unwrap().efficiencies;
    println!("BHMIE: {e:?}");
    assert!(
        agrees(e.q_ext, 3.10543, 6) && agrees(e.q_sca, 3.10543, 6),
        "{e:?}"
    );
    assert!(agrees(e.q_back, 2.92534, 6), "{e:?}");
    assert!(agrees(e.g, 0.63314, 5), "{e:?}");
}

#[test]
fn optical_theorem_energy_and_normalisation_across_the_domain() {
    let mut worst_theorem = 0.0f64;
    for x in [1e-6, 1e-3, 0.1, 1.0, 7.9, 30.0, 300.0, 3000.0, 2e4] {
        for (n, k) in [
            (1.0001, 0.0),
            (1.33, 0.0),
            (1.5, 0.01),
            (2.0, 1.0),
            (4.0, 10.0),
            (10.0, 0.0),
            (10.0, 10.0),
        ] {
            let (mut buf, x, m) = solve(x, n, k);
            let mie = Mie::new(x, m, &mut buf).unwrap();
            let e = mie.efficiencies;
            assert!(
                e.q_ext.is_finite() && e.q_sca.is_finite() && e.g.is_finite(),
                "x {x} m {n}+{k}i: {e:?}"
            );
            // Q_abs ≥ 0 to rounding; |g| ≤ 1.
            assert!(
                e.q_ext - e.q_sca >= -1e-12 * e.q_ext.max(1e-300),
                "x {x} m {n}+{k}i: {e:?}"
            );
            assert!(e.g.abs() <= 1.0 + 1e-12, "x {x} m {n}+{k}i: {e:?}");
            let (s1f, s2f) = mie.amplitudes(1.0);
            let theorem = 4.0 / (x * x) * s1f.re;
            assert!((s1f.re - s2f.re).abs() <= 1e-12 * s1f.re.abs().max(1e-300));
            let rel = (theorem - e.q_ext).abs() / e.q_ext;
            worst_theorem = nan_max(worst_theorem, rel);
            assert!(
                rel < 1e-9,
                "x {x} m {n}+{k}i: optical theorem {theorem} vs {}",
                e.q_ext
            );
            let (s1b, _) = mie.amplitudes(-1.0);
            let qb = 4.0 * s1b.norm_sqr() / (x * x);
            assert!(
                (qb - e.q_back).abs() <= 1e-9 * e.q_back.max(1e-300),
                "x {x}: Q_back {qb} vs {}",
                e.q_back
            );
            if x <= 300.0 {
                // 2π ∫ p sin θ dθ = 1, trapezoids in θ (the forward lobe is
                // about 1/x wide in θ, far narrower in μ).
                let steps = 20_000;
                let h = std::f64::consts::PI / steps as f64;
                let mut sum = 0.0;
                for i in 1..steps {
                    let th = i as f64 * h;
                    sum += mie.phase(th.cos()) * th.sin();
                }
                let total = std::f64::consts::TAU * sum * h;
                assert!(
                    (total - 1.0).abs() < 1e-3,
                    "x {x} m {n}+{k}i: 2π ∫ p = {total}"
                );
            }
        }
    }
    println!("worst optical-theorem mismatch {worst_theorem:.1e}");
}

/// The phase function's normalisation where the uniform grid above would
/// be too coarse: x = 3000 and 2·10⁴, on `table_angle`'s grid (half the
/// angles crowded into the forward peak), 2x angles, trapezoids in θ.
#[test]
fn phase_function_is_normalised_at_large_x() {
    for (x, n, k) in [
        (3000.0, 1.33, 0.0),
        (3000.0, 10.0, 10.0),
        (2e4, 1.33, 0.0),
        (2e4, 10.0, 10.0),
    ] {
        let (mut buf, x, m) = solve(x, n, k);
        let mie = Mie::new(x, m, &mut buf).unwrap();
        let count = (2.0 * x) as usize;
        let theta: Vec<f64> = (0..count)
            .map(|j| scatterkit::mie::table_angle(x, j, count))
            .collect();
        let f: Vec<f64> = theta.iter().map(|t| mie.phase(t.cos()) * t.sin()).collect();
        let total: f64 = (1..count)
            .map(|i| 0.5 * (theta[i] - theta[i - 1]) * (f[i - 1] + f[i]))
            .sum::<f64>()
            * std::f64::consts::TAU;
        println!("x {x} m {n}+{k}i: 2π ∫ p = {total}");
        assert!((total - 1.0).abs() < 1e-5, "x {x} m {n}+{k}i: {total}");
    }
}

#[test]
fn small_spheres_follow_rayleigh() {
    // Q_sca → (8/3) x⁴ |(m² − 1)/(m² + 2)|² as x → 0, to relative O(x²).
    for x in [1e-20, 1e-12, 1e-6, 1e-4, 1e-2] {
        let (mut buf, x, m) = solve(x, 1.5, 0.0);
        let e = Mie::new(x, m, &mut buf).unwrap().efficiencies;
        let l = (1.5f64 * 1.5 - 1.0) / (1.5 * 1.5 + 2.0);
        let rayleigh = 8.0 / 3.0 * x.powi(4) * l * l;
        assert!(
            (e.q_sca / rayleigh - 1.0).abs() < 10.0 * x * x + 1e-9,
            "x {x}: {} vs {rayleigh}",
            e.q_sca
        );
        assert!(e.g.abs() < 10.0 * x * x + 1e-9, "x {x}: g {}", e.g);
    }
}

/// `Q_ext`, `Q_sca` and `g` from `x = 10⁻²⁰` to 30 over 13 indices (near 1,
/// below 1, absorbing up to `k = 10`) against the series summed in 80
/// digits with mpmath's Bessel functions (`scripts/mie_small_reference.py`,
/// `tests/data/mie_small_spheres.txt`): each within 10⁻¹¹ relative. Formed
/// from the logarithmic derivatives, `b_n` (of order `x²(m² − 1)` of its
/// terms) kept only their rounding at small `x`: `g`, which needs `b_1`,
/// was off by a factor 10³ at `x = 10⁻⁹` and 10²⁵ at `x = 10⁻²⁰`, 63 of
/// the 182 points beyond 10⁻⁶.
#[test]
fn small_spheres_against_80_digits() {
    let (mut rows, mut worst) = (0, [0.0f64; 3]);
    for line in include_str!("../data/mie_small_spheres.txt").lines() {
        if line.starts_with('#') {
            continue;
        }
        let v: Vec<f64> = line
            .split_whitespace()
            .map(|s| s.parse().unwrap())
            .collect();
        let (mut buf, x, m) = solve(v[0], v[1], v[2]);
        let e = Mie::new(x, m, &mut buf).unwrap().efficiencies;
        let got = [e.q_ext, e.q_sca, e.g];
        for (i, (g, w)) in got.iter().zip(&v[3..6]).enumerate() {
            let rel = ((g - w) / w).abs();
            worst[i] = nan_max(worst[i], rel);
            assert!(rel <= 1e-11, "x {x} m {m:?}: {g} against {w} ({rel:.1e})");
        }
        rows += 1;
    }
    println!(
        "{rows} spheres; largest relative error Q_ext {:.1e}, Q_sca {:.1e}, g {:.1e}",
        worst[0], worst[1], worst[2]
    );
    assert_eq!(rows, 182);
}

#[test]
fn bad_input_is_rejected() {
    use scatterkit::Error;
    let m = Complex::new(1.5, 0.0);
    let mut buf = vec![Complex::default(); 10];
    for (x, m) in [
        (0.0, m),
        (1e-21, m),
        (-1.0, m),
        (f64::NAN, m),
        (1e6, m),
        (1.0, Complex::new(0.0, 0.0)),
        (1.0, Complex::new(1.5, -0.1)),
        (1.0, Complex::new(f64::INFINITY, 0.0)),
        (1.0, Complex::new(1.5, 1e10)),
        (1.0, Complex::new(1.5, f64::MAX)),
        (1.0, Complex::new(1001.0, 0.0)),
        (1e4, Complex::new(300.0, 0.0)),
        // The medium's own index: no scattering, no phase function (its
        // pdf was 0/0, NaN, beside Q_sca = 0).
        (1.0, Complex::new(1.0, 0.0)),
        (1e-6, Complex::new(1.0, 0.0)),
        // |m| below 10⁻¹⁰⁰ (from 10⁻¹⁵⁴ every output was NaN).
        (1.0, Complex::new(0.99e-100, 0.0)),
        (1.0, Complex::new(1e-154, 0.0)),
        (1e5, Complex::new(f64::MIN_POSITIVE, 0.0)),
    ] {
        assert!(buffer_len(x, m).is_none());
        assert_eq!(Mie::new(x, m, &mut buf).err(), Some(Error::Domain));
    }
    assert_eq!(Mie::new(100.0, m, &mut buf).err(), Some(Error::Size));
}

/// At the edges of the index domain a sphere is refused (`Error::Domain`)
/// or every output is finite and the phase function normalised; never NaN
/// with `Ok` (m = 1 gave a NaN phase function; from `|m| = 10⁻¹⁵⁴`, and a
/// complex `|m|` of 10⁻⁶¹ at `x = 10⁻²⁰`, everything was NaN). The real
/// `|m| = 10⁻¹⁰⁰` and the neighbours of 1 are accepted at every `x`.
#[test]
fn the_index_domain_edges_give_finite_answers_or_domain() {
    let mut buf = vec![Complex::new(0.0, 0.0); 1 << 20];
    let accepted = [
        Complex::new(1e-100, 0.0),
        Complex::new(1.0 + f64::EPSILON, 0.0),
        Complex::new(1.0 - f64::EPSILON / 2.0, 0.0),
        Complex::new(1.0, 1e-12),
    ];
    let either = [
        Complex::new(1.2e-100, 1.6e-100),
        Complex::new(1e-60, 1e-60),
        Complex::new(1.0, 1e-300),
    ];
    for (m, must) in accepted
        .iter()
        .map(|m| (m, true))
        .chain(either.iter().map(|m| (m, false)))
    {
        for x in [1e-20, 1e-6, 1.0, 30.0, 1e3, 1e5] {
            let s = match Mie::new(x, *m, &mut buf) {
                Err(scatterkit::Error::Domain) if !must => continue,
                r => r.unwrap_or_else(|e| panic!("x {x} m {m:?}: {e:?}")),
            };
            let e = s.efficiencies;
            let finite = [e.q_ext, e.q_sca, e.q_back, e.g]
                .iter()
                .all(|v| v.is_finite());
            assert!(
                finite && e.q_sca > 0.0 && (-1.0..=1.0).contains(&e.g),
                "x {x} m {m:?}: {e:?}"
            );
            for mu in [-1.0, -0.3, 0.0, 0.9, 1.0] {
                let p = s.phase(mu);
                assert!(p.is_finite() && p >= 0.0, "x {x} m {m:?} mu {mu}: {p}");
            }
            if x <= 30.0 {
                // Midpoint rule over μ; the peak is wider than 1/x.
                let k = 20_000;
                let total: f64 = (0..k)
                    .map(|i| s.phase(-1.0 + 2.0 * (i as f64 + 0.5) / k as f64))
                    .sum::<f64>()
                    * core::f64::consts::TAU
                    * 2.0
                    / k as f64;
                assert!((total - 1.0).abs() < 1e-4, "x {x} m {m:?}: {total}");
            }
        }
    }
}

/// Backscatter of large spheres against the series summed in 60 digits
/// with terms to spare (`scripts/mie_backscatter_reference.py`, which also
/// prints scattnlay 2.4 and miepython 3.3 beside them): within 10⁻¹⁰.
/// Wiscombe's term count leaves the alternating backward sum truncated
/// (`Q_back` off by 1.7·10⁻⁶ at `x = 1000`, as miepython still is);
/// scattnlay agrees with the reference to 3.4·10⁻¹⁰.
#[test]
#[allow(clippy::excessive_precision)] // the script's 17 digits, as printed
fn backscatter_of_large_spheres_against_60_digits() {
    let want = [
        (1000.0, 1.33, 0.0, 0.67613648032557662),
        (1000.0, 1.33, 1e-08, 0.67599848295242736),
        (1000.0, 1.33, 0.001, 0.020635033032293417),
        (1000.0, 1.5, 0.01, 0.040015372722717059),
        (5000.0, 1.33, 0.0, 4.7339286866317579),
        (5000.0, 1.33, 1e-08, 4.72459582132897),
        (5000.0, 1.33, 0.001, 0.020059505686449316),
        (5000.0, 1.5, 0.01, 0.040015360272978686),
    ];
    for (x, n, k, q_back) in want {
        let (mut buf, x, m) = solve(x, n, k);
        let e = Mie::new(x, m, &mut buf).unwrap().efficiencies;
        let rel = (e.q_back / q_back - 1.0).abs();
        assert!(
            rel <= 1e-10,
            "x = {x}, m = {n} + {k}i: Q_back {} against {q_back}: {rel:.1e}",
            e.q_back
        );
    }
}
