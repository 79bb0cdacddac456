//! Property tests with fixed seeds (hand-rolled: no extra dependency). For
//! random valid parameters every sampler returns finite values in range and
//! unit directions, `sample_cos` and `cdf` invert each other, and every
//! constructor rejects exactly its documented invalid set.

use crate::common;

use common::{Xoshiro256PlusPlus, rng};
use scatterkit::surface::{CrossingPolicy, Fraction, Surface, SurfaceModel};
use scatterkit::{Error, Grid, Phase, PhaseFunction, Real, Vec3};

const CASES: usize = 400;

fn uni(r: &mut Xoshiro256PlusPlus) -> f64 {
    f64::uniform(r)
}

/// A random valid phase of each kind.
fn random_phase(r: &mut Xoshiro256PlusPlus, k: usize) -> Phase<f64> {
    // g spans the open interval, with mass near 0 and near ±1.
    let g = |r: &mut Xoshiro256PlusPlus| {
        let s = if uni(r) < 0.5 { -1.0 } else { 1.0 };
        match (uni(r) * 3.0) as u32 {
            0 => s * 10f64.powf(-8.0 * uni(r)),
            1 => s * (1.0 - 10f64.powf(-6.0 * uni(r))),
            _ => 2.0 * uni(r) - 1.0,
        }
    };
    let alpha = |r: &mut Xoshiro256PlusPlus| {
        if uni(r) < 0.1 {
            0.0
        } else {
            10f64.powf(-4.0 + 8.0 * uni(r))
        }
    };
    match k % 7 {
        0 => Phase::henyey_greenstein(g(r)).unwrap(),
        1 => Phase::draine(g(r), alpha(r)).unwrap(),
        2 => Phase::cornette_shanks(g(r)).unwrap(),
        3 => Phase::fog(g(r), g(r), alpha(r), uni(r)).unwrap(),
        4 => Phase::fog_diameter(50.0 * (1.0 - uni(r))).unwrap(),
        5 => Phase::rayleigh_depolarized(uni(r) * 0.999).unwrap(),
        _ => Phase::rayleigh(),
    }
}

#[test]
fn samplers_stay_finite_in_range_and_unit() {
    let mut r = rng(100);
    for k in 0..CASES {
        let p64 = random_phase(&mut r, k);
        let p32: Phase<f32> = p64.cast();
        let w = Vec3::new(uni(&mut r) - 0.5, uni(&mut r) - 0.5, uni(&mut r) - 0.5)
            .try_normalize()
            .unwrap();
        let w32: Vec3<f32> = w.cast();
        for u in [0.0, 1e-12, 0.25, 0.5, 0.75, 1.0 - 1e-12, 1.0, uni(&mut r)] {
            let mu = p64.sample_cos(u);
            assert!(mu.is_finite() && mu.abs() <= 1.0, "{p64:?} u {u}: {mu}");
            let mu32 = p32.sample_cos(u as f32);
            assert!(
                mu32.is_finite() && mu32.abs() <= 1.0,
                "{p32:?} u {u}: {mu32}"
            );
            let (d, pdf) = p64.sample_dir(w, u, uni(&mut r));
            assert!(
                (d.length() - 1.0).abs() < 1e-12 && pdf.is_finite() && pdf >= 0.0,
                "{p64:?}: {d:?} {pdf}"
            );
            let (d32, pdf32) = p32.sample_dir(w32, u as f32, 0.3);
            assert!(
                (d32.length() - 1.0).abs() < 1e-6 && pdf32 >= 0.0,
                "{p32:?}: {d32:?} {pdf32}"
            );
        }
    }
}

#[test]
fn sample_cos_and_cdf_invert_each_other() {
    let mut r = rng(101);
    for k in 0..CASES {
        let p = random_phase(&mut r, k);
        for _ in 0..16 {
            // u → μ → F(μ): the round trip is as good as the density allows.
            let u = uni(&mut r);
            let mu = p.sample_cos(u);
            let dens = std::f64::consts::TAU * p.pdf(mu);
            assert!(
                (p.cdf(mu) - u).abs() <= 1e-12 * (1.0 + dens),
                "{p:?}: F(μ({u})) = {}",
                p.cdf(mu)
            );
            // x → F(x) → μ, where the density lets F resolve x.
            let x = 2.0 * uni(&mut r) - 1.0;
            let dens = std::f64::consts::TAU * p.pdf(x);
            if dens > 1e-3 {
                let back = p.sample_cos(p.cdf(x));
                assert!(
                    (back - x).abs() <= 1e-12 / dens + 1e-13,
                    "{p:?}: μ(F({x})) = {back}"
                );
            }
        }
    }
}

/// Values every float parameter is tried with, plus random ones.
fn probes(r: &mut Xoshiro256PlusPlus, lo: f64, hi: f64) -> Vec<f64> {
    let mut v = vec![
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        1.0,
        -1.0,
        50.0,
        1e-310,
        -1e-310,
        1e300,
        -1e300,
    ];
    v.extend((0..200).map(|_| lo + (hi - lo) * uni(r)));
    v
}

#[test]
fn constructors_reject_exactly_the_documented_set() {
    let mut r = rng(102);
    for g in probes(&mut r, -2.0, 2.0) {
        // Open for Draine's g; closed for HG's (|g| = 1, the Dirac limit),
        // the fog's HG lobe and a two-lobe HG's lobes (Draine with α = 0).
        let ok = g > -1.0 && g < 1.0;
        let hg_ok = (-1.0..=1.0).contains(&g);
        assert_eq!(Phase::henyey_greenstein(g).is_ok(), hg_ok, "hg {g}");
        assert_eq!(Phase::cornette_shanks(g).is_ok(), ok, "cs {g}");
        assert_eq!(Phase::draine(g, 1.0).is_ok(), ok, "draine g {g}");
        assert_eq!(Phase::fog(g, 0.5, 1.0, 0.5).is_ok(), hg_ok, "fog g_hg {g}");
        assert_eq!(Phase::fog(0.5, g, 1.0, 0.5).is_ok(), ok, "fog g_d {g}");
        assert_eq!(
            Phase::fog(0.5, g, 0.0, 0.5).is_ok(),
            hg_ok,
            "fog g_d {g}, α = 0"
        );
        // f32 too: the same set after rounding.
        let g32 = g as f32;
        assert_eq!(
            Phase::henyey_greenstein(g32).is_ok(),
            (-1.0..=1.0).contains(&g32),
            "hg f32 {g32}"
        );
    }
    for a in probes(&mut r, -10.0, 1e5) {
        let ok = a >= 0.0 && a.is_finite();
        assert_eq!(Phase::draine(0.3, a).is_ok(), ok, "draine α {a}");
        assert_eq!(Phase::fog(0.5, 0.3, a, 0.5).is_ok(), ok, "fog α {a}");
    }
    for w in probes(&mut r, -0.5, 1.5) {
        assert_eq!(
            Phase::fog(0.5, 0.3, 1.0, w).is_ok(),
            (0.0..=1.0).contains(&w),
            "fog w {w}"
        );
    }
    for rho in probes(&mut r, -0.5, 1.5) {
        assert_eq!(
            Phase::rayleigh_depolarized(rho).is_ok(),
            (0.0..1.0).contains(&rho),
            "rho {rho}"
        );
    }
    for d in probes(&mut r, -10.0, 60.0) {
        let ok = d > 0.0 && d <= 50.0;
        assert_eq!(Phase::fog_diameter(d).is_ok(), ok, "diameter {d}");
        assert_eq!(Phase::particle(d, 0.1).is_ok(), ok, "particle d {d}");
    }
    for t in probes(&mut r, -0.5, 1.5) {
        assert_eq!(
            Phase::particle(2.0, t).is_ok(),
            t > 0.0 && t < 1.0,
            "particle tolerance {t}"
        );
    }
    for a in probes(&mut r, -10.0, 2e6) {
        let ok = (1.0..=1e6).contains(&a);
        let s = Surface::new(
            SurfaceModel::Phong,
            a,
            Fraction::Constant(0.5),
            CrossingPolicy::Fold,
        );
        assert_eq!(s.is_ok(), ok, "phong α {a}");
    }
    for f in probes(&mut r, -0.5, 1.5) {
        let s = Surface::new(
            SurfaceModel::Lambert,
            1.0,
            Fraction::Constant(f),
            CrossingPolicy::Fold,
        );
        assert_eq!(s.is_ok(), (0.0..=1.0).contains(&f), "fraction {f}");
        let s = Surface::new(
            SurfaceModel::Lambert,
            1.0,
            Fraction::Scalar(f),
            CrossingPolicy::Fold,
        );
        assert_eq!(s.is_ok(), f >= 0.0 && f.is_finite(), "sigma_rms {f}");
    }
    for v in probes(&mut r, -1.0, 10.0) {
        let ok = v >= 0.0 && v.is_finite();
        assert_eq!(
            Grid::new(&[v, 1.0], 2, 1, 1, 1.0, 1.0).is_ok(),
            ok,
            "density {v}"
        );
        assert_eq!(
            Grid::new(&[1.0, 1.0], 2, 1, 1, v, 1.0).is_ok(),
            ok,
            "sigma_a {v}"
        );
    }
    assert_eq!(
        Grid::new(&[1.0f64], 1, 0, 1, 1.0, 1.0).err(),
        Some(Error::Size)
    );
}

#[test]
fn surfaces_and_media_stay_finite() {
    let mut r = rng(103);
    for _ in 0..CASES {
        let n = Vec3::new(uni(&mut r) - 0.5, uni(&mut r) - 0.5, uni(&mut r) - 0.5);
        let d = Vec3::new(uni(&mut r) - 0.5, uni(&mut r) - 0.5, uni(&mut r) - 0.5);
        let (ni, nt) = (1.0 + 3.0 * uni(&mut r), 1.0 + 3.0 * uni(&mut r));
        let alpha = 10f64.powf(6.0 * uni(&mut r));
        let policy = CrossingPolicy::try_from((uni(&mut r) * 3.0) as u32).unwrap();
        let s = Surface::new(
            SurfaceModel::Phong,
            alpha,
            Fraction::Scalar(1e-7 * uni(&mut r)),
            policy,
        )
        .unwrap();
        let x = s.interact(d, n, ni, nt, 5e-7, &mut r).unwrap();
        let dir = x.dir;
        assert!((dir.length() - 1.0).abs() < 1e-12, "{x:?}");
        let side = dir.dot(n) * d.dot(n);
        if x.transmitted {
            assert!(side >= -1e-12, "transmitted to the wrong side");
        } else {
            assert!(side <= 1e-12, "reflected to the wrong side");
        }
        let t = scatterkit::medium::free_path(10f64.powf(-3.0 + 6.0 * uni(&mut r)), uni(&mut r));
        assert!(t >= 0.0 && !t.is_nan());
    }
}
