//! The C boundary with arbitrary arguments: statuses, NaN results, and no
//! crash, for the functions that take arrays, sizes and enums.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scatterkit::ffi::*;

/// The fuzzed grid as a caller's medium (its density times its
/// coefficients), for the trackers that take a callback.
unsafe extern "C" fn grid_medium(ctx: *mut core::ffi::c_void, p: sk_vec3) -> sk_coefficients {
    // SAFETY: ctx is the fuzz target's own grid, alive for the call.
    unsafe { sk_grid_coefficients(ctx as *const sk_grid, p) }
}

/// A batch over the fuzzed floats as uniforms: OK with every cosine in
/// [-1, 1], or DOMAIN for a uniform outside [0, 1].
fn batch(s: sk_status, outs: &[f32]) {
    match s {
        sk_status::SK_OK => assert!(outs.iter().all(|c| c.abs() <= 1.0), "{outs:?}"),
        s => assert_eq!(s, sk_status::SK_ERR_DOMAIN),
    }
}

/// A direction batch with the fuzzed floats as directions and uniforms:
/// OK or DOMAIN (a uniform outside [0, 1]); never a crash.
fn batch_dirs(
    f: &[f32],
    run: impl Fn([*const f32; 3], *const f32, [*mut f32; 3], *mut f32) -> sk_status,
) {
    let n = f.len();
    let mut o = [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
    let mut pdf = vec![0.0f32; n];
    let w = [f.as_ptr(); 3];
    let [a, b, c] = &mut o;
    let s = run(
        w,
        f.as_ptr(),
        [a.as_mut_ptr(), b.as_mut_ptr(), c.as_mut_ptr()],
        pdf.as_mut_ptr(),
    );
    assert!(
        matches!(s, sk_status::SK_OK | sk_status::SK_ERR_DOMAIN),
        "{s:?}"
    );
}

/// Tracking arguments through grid `g` over `[0, t_max]`.
fn args(g: &sk_grid, o: sk_vec3, d: sk_vec3, t_max: f32, rng: &mut sk_rng) -> sk_track_args {
    sk_track_args {
        medium: sk_medium {
            grid: g,
            coefficients: None,
            ctx: core::ptr::null_mut(),
            majorants: core::ptr::null(),
            sigma_maj: 0.0,
            emission: core::ptr::null(),
            emission_fn: None,
            emission_cells: core::ptr::null(),
        },
        o,
        d,
        t_min: 0.0,
        t_max,
        budget: 0,
        strata: 0,
        flags: 0,
        rng,
        spectrum: core::ptr::null(),
    }
}

unsafe extern "C" fn next(state: *mut core::ffi::c_void) -> u64 {
    // SAFETY: the state is the u64 below.
    let s = unsafe { &mut *(state as *mut u64) };
    *s = s
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    *s
}

fuzz_target!(|data: &[u8]| {
    let f: Vec<f32> = data
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    let x = |i: usize| f.get(i).copied().unwrap_or(0.5);
    let word = |i: usize| data.get(i).copied().unwrap_or(0) as u32;
    let mut state = data.len() as u64;
    let mut rng = sk_rng {
        state: &mut state as *mut u64 as *mut _,
        next_u64: Some(next),
    };
    let mut p = sk_phase { opaque: [0; 64] };
    let n = f.len();
    let mut out = vec![0.0f32; n];
    // Any value has a status string, never NULL.
    let text = sk_status_string(enum_arg::sk_status(
        word(0) | (word(1) << 8) | (word(2) << 24),
    ));
    assert!(!text.is_null());
    unsafe {
        let statuses = [
            sk_phase_new_hg(x(0), &mut p),
            sk_phase_new_draine(x(0), x(1), &mut p),
            sk_phase_new_fog(x(0), x(1), x(2), x(3), &mut p),
            sk_phase_new_fog_diameter(x(2), &mut p),
            sk_phase_new_rayleigh_depolarized(x(3), &mut p),
            sk_phase_new_modified_hg(x(1), x(2), &mut p),
            sk_phase_new_modified_hg_delta(x(2), x(3), &mut p),
            sk_phase_new_two_lobe_hg_gamma(x(1), x(2), &mut p),
            sk_phase_new_two_lobe_hg_delta(x(2), x(3), &mut p),
            sk_phase_new_gegenbauer_gamma(x(1), x(2), &mut p),
            sk_phase_new_gegenbauer_delta(x(2), x(3), &mut p),
        ];
        for s in statuses {
            assert!(matches!(s, sk_status::SK_OK | sk_status::SK_ERR_DOMAIN));
        }
        // Any model from fuzzed parameters: built, or refused with the
        // status that says why; a built one reports what it was given.
        let model = enum_arg::sk_phase_model(word(3) % 12);
        let count = (word(4) as usize % 6).min(n);
        let mut q = sk_phase { opaque: [0; 64] };
        match sk_phase_new(model, f.as_ptr(), count, &mut q) {
            sk_status::SK_OK => {
                let mut back = core::mem::MaybeUninit::<sk_phase_params>::uninit();
                assert_eq!(sk_phase_get_params(&q, back.as_mut_ptr()), sk_status::SK_OK);
                let back = back.assume_init();
                assert_eq!((back.model.0, back.count as usize), (model.0, count));
            }
            s => assert!(matches!(
                s,
                sk_status::SK_ERR_DOMAIN | sk_status::SK_ERR_SIZE | sk_status::SK_ERR_METHOD
            )),
        }
        // Batch with arbitrary uniforms: OK with every cosine in range, or DOMAIN.
        match sk_phase_sample_cos_n(&p, f.as_ptr(), out.as_mut_ptr(), n) {
            sk_status::SK_OK => assert!(out.iter().all(|c| c.abs() <= 1.0)),
            s => assert!(s == sk_status::SK_ERR_DOMAIN || p.opaque[0] == 0, "{s:?}"),
        }
        let mu = sk_phase_sample_cos(&p, x(4));
        assert!(mu.is_nan() || mu.abs() <= 1.0);
        // A mixture of the fuzzed phase (which may be unconstructed) and
        // Rayleigh with fuzzed weights: OK or an error; once built, every
        // sample in [-1, 1] (NaN only for a NaN u) and the density >= 0.
        let mut ray = sk_phase { opaque: [0; 64] };
        let _ = sk_phase_new_rayleigh(&mut ray);
        let parts = [
            sk_mixture_part {
                phase: &p,
                table: core::ptr::null(),
                weight: x(5),
            },
            sk_mixture_part {
                phase: &ray,
                table: core::ptr::null(),
                weight: x(6),
            },
        ];
        let mut mix = core::mem::MaybeUninit::<sk_mixture>::uninit();
        if sk_mixture_new(parts.as_ptr(), 2, mix.as_mut_ptr()) == sk_status::SK_OK {
            let mix = mix.assume_init();
            for mu in [
                sk_mixture_sample_cos(&mix, x(7)),
                sk_mixture_sample_cos_by_lobe(&mix, x(7)),
            ] {
                assert!((x(7).is_nan() && mu.is_nan()) || mu.abs() <= 1.0, "{mu}");
            }
            // The batches take the fuzzed floats as uniforms: OK with
            // every cosine in range, or DOMAIN for one outside [0, 1].
            let mut outs = vec![0.0f32; n];
            for s in [
                sk_mixture_sample_cos_n(&mix, f.as_ptr(), outs.as_mut_ptr(), n),
                sk_mixture_sample_cos_by_lobe_n(&mix, f.as_ptr(), outs.as_mut_ptr(), n),
            ] {
                match s {
                    sk_status::SK_OK => assert!(outs.iter().all(|c| c.abs() <= 1.0)),
                    s => assert_eq!(s, sk_status::SK_ERR_DOMAIN),
                }
            }
            batch_dirs(&f, |w, u, o, pdf| {
                sk_mixture_sample_dir_n(&mix, w[0], w[1], w[2], u, u, o[0], o[1], o[2], pdf, n)
            });
            let d = sk_mixture_pdf(&mix, x(8).clamp(-1.0, 1.0));
            assert!(x(8).is_nan() || d >= 0.0, "{d}");
            let mut chi = [0.0f32; 4];
            if sk_mixture_legendre_moments(&mix, chi.as_mut_ptr(), 4) == sk_status::SK_OK {
                assert!(chi.iter().all(|c| c.abs() <= 1.0 + 1e-3), "{chi:?}");
            }
        }
        // A Legendre series with fuzzed moments: refused, or every sample
        // in [-1, 1] (NaN only for a NaN u) with a density >= 0 there.
        let chi = [1.0f32, x(10), x(11), x(12)];
        let mut lg = core::mem::MaybeUninit::<sk_legendre>::uninit();
        if sk_legendre_new(chi.as_ptr(), 4, lg.as_mut_ptr()) == sk_status::SK_OK {
            let lg = lg.assume_init();
            let mu = sk_legendre_sample_cos(&lg, x(13));
            assert!((x(13).is_nan() && mu.is_nan()) || mu.abs() <= 1.0, "{mu}");
            let mut outs = vec![0.0f32; n];
            batch(
                sk_legendre_sample_cos_n(&lg, f.as_ptr(), outs.as_mut_ptr(), n),
                &outs,
            );
            batch_dirs(&f, |w, u, o, pdf| {
                sk_legendre_sample_dir_n(&lg, w[0], w[1], w[2], u, u, o[0], o[1], o[2], pdf, n)
            });
            let mut chi4 = [0.0f32; 6];
            assert_eq!(
                sk_legendre_legendre_moments(&lg, chi4.as_mut_ptr(), 6),
                sk_status::SK_OK
            );
            assert_eq!(sk_legendre_mean_cosine(&lg), chi[1]);
            let mut pdf = 0.0f32;
            let up = sk_vec3 {
                x: 0.0,
                y: 0.0,
                z: 1.0,
            };
            let d = sk_legendre_sample_dir(&lg, up, x(13), x(14), &mut pdf);
            assert!(d.x.is_nan() || (d.x * d.x + d.y * d.y + d.z * d.z - 1.0).abs() < 1e-4);
        }
        // The fuzzed floats as a 2-D table's data: refused, or a cosine in
        // [-1, 1] (NaN only for NaN x or u) and a density >= 0 (or NaN).
        let mut t2 = core::mem::MaybeUninit::<sk_table2d>::uninit();
        let (n2, k2) = (word(1) as usize % 8 + 1, word(2) as usize % 4 + 1);
        if sk_table2d_new(f.as_ptr(), f.len(), n2, k2, x(0), x(1), t2.as_mut_ptr())
            == sk_status::SK_OK
        {
            let t2 = t2.assume_init();
            let mu = sk_table2d_sample_cos(&t2, x(2), x(3));
            assert!(
                ((x(2).is_nan() || x(3).is_nan()) && mu.is_nan()) || mu.abs() <= 1.0,
                "{mu}"
            );
            let d = sk_table2d_pdf(&t2, x(2), x(4));
            assert!(d.is_nan() || d >= 0.0, "{d}");
            let c = sk_table2d_cdf(&t2, x(2), x(4));
            assert!(c.is_nan() || (0.0..=1.0).contains(&c), "{c}");
            let g = sk_table2d_mean_cosine(&t2, x(2));
            assert!(g.is_nan() || g.abs() <= 1.0 + 1e-5, "{g}");
            let mut chi = [0.0f32; 4];
            if sk_table2d_legendre_moments(&t2, x(2), chi.as_mut_ptr(), 4) == sk_status::SK_OK {
                assert!(
                    chi.iter().all(|c| c.is_nan() || c.abs() <= 1.0 + 1e-3),
                    "{chi:?}"
                );
            }
            let mut outs = vec![0.0f32; n];
            let s = sk_table2d_sample_cos_n(&t2, x(2), f.as_ptr(), outs.as_mut_ptr(), n);
            if !x(2).is_nan() {
                batch(s, &outs);
            }
            batch_dirs(&f, |w, u, o, pdf| {
                sk_table2d_sample_dir_n(&t2, x(2), w[0], w[1], w[2], u, u, o[0], o[1], o[2], pdf, n)
            });
        }
        // An albedo curve of a fuzzed HG layer, a few paths: OK or DOMAIN;
        // then albedos in [0, 1] (NaN only outside) and the inverse.
        let mut hgd = core::mem::MaybeUninit::<sk_phase_f64>::uninit();
        if sk_phase_new_hg_f64(x(0) as f64, hgd.as_mut_ptr()) == sk_status::SK_OK {
            let hgd = hgd.assume_init();
            let mut rng2 = sk_rng {
                state: &mut state as *mut u64 as *mut _,
                next_u64: Some(next),
            };
            let mut curve = core::mem::MaybeUninit::<sk_albedo_curve_f64>::uninit();
            let s = sk_albedo_curve_new_f64(
                &hgd,
                x(1) as f64,
                x(2) as f64,
                (word(5) % 8) as u64,
                &mut rng2,
                curve.as_mut_ptr(),
            );
            assert!(
                matches!(s, sk_status::SK_OK | sk_status::SK_ERR_DOMAIN),
                "{s:?}"
            );
            if s == sk_status::SK_OK {
                let curve = curve.assume_init();
                let a = sk_albedo_curve_albedo_f64(&curve, x(3) as f64);
                assert!(a.is_nan() || (0.0..=1.0).contains(&a), "{a}");
                let mut w = 0.0f64;
                if sk_albedo_curve_single_scattering_albedo_f64(&curve, x(4) as f64, &mut w)
                    == sk_status::SK_OK
                {
                    assert!((0.0..=1.0).contains(&w), "{w}");
                }
            }
        }
        // The same two as channels of a spectral phase function, the hero
        // fuzzed: a cosine in [-1, 1] and finite ratios, or an error.
        let ch = [
            sk_channel_phase {
                phase: &p,
                table: core::ptr::null(),
            },
            sk_channel_phase {
                phase: &ray,
                table: core::ptr::null(),
            },
        ];
        let (mut c, mut ratio) = (0.0f32, [0.0f32; 2]);
        if sk_spectral_phase_sample(
            ch.as_ptr(),
            2,
            word(3) as usize % 3,
            x(9),
            &mut c,
            ratio.as_mut_ptr(),
        ) == sk_status::SK_OK
        {
            assert!(
                c.abs() <= 1.0 && ratio.iter().all(|r| *r >= 0.0),
                "{c} {ratio:?}"
            );
        }
        // Polarised Rayleigh with fuzzed depolarisation, directions, Stokes
        // vector and uniforms (the first floats again: inputs are short):
        // OK with a physical result, or DOMAIN.
        let mut air = sk_rayleigh_polarized { opaque: [0; 16] };
        let st = sk_rayleigh_polarized_new(x(1), &mut air);
        assert!(matches!(st, sk_status::SK_OK | sk_status::SK_ERR_DOMAIN));
        let v3 = |a: f32, b: f32, c: f32| sk_vec3 { x: a, y: b, z: c };
        let stokes = sk_stokes {
            i: x(2),
            q: x(3),
            u: x(4),
            v: x(5),
            reference: v3(x(6), 0.0, 0.0),
        };
        let k = v3(0.0, x(7), 1.0);
        let mut smp = core::mem::MaybeUninit::<sk_stokes_sample>::uninit();
        if sk_rayleigh_polarized_sample(&air, k, &stokes, x(8), x(0), smp.as_mut_ptr())
            == sk_status::SK_OK
        {
            let r = smp.assume_init();
            let s = r.stokes;
            let len = r.dir.x * r.dir.x + r.dir.y * r.dir.y + r.dir.z * r.dir.z;
            assert!(
                (len - 1.0).abs() < 1e-4 && r.pdf >= 0.0 && s.i == stokes.i,
                "{r:?}"
            );
            assert!(
                (s.q * s.q + s.u * s.u + s.v * s.v).sqrt() <= s.i * 1.001 + 1e-30,
                "{r:?}"
            );
        }
        let mut ev = core::mem::MaybeUninit::<sk_stokes>::uninit();
        let w = v3(x(1), 0.0, 1.0);
        if sk_rayleigh_polarized_eval(&air, k, &stokes, w, v3(1.0, 0.0, 0.0), ev.as_mut_ptr())
            == sk_status::SK_OK
        {
            let e = ev.assume_init();
            assert!(
                e.i >= 0.0 && (e.q * e.q + e.u * e.u + e.v * e.v).sqrt() <= e.i * 1.001 + 1e-30,
                "{e:?}"
            );
        }
        // Enums arrive as arbitrary integers.
        let mut d = sk_vec3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        };
        let s = sk_rayleigh_sample_dir(
            enum_arg::sk_rayleigh_method(word(0)),
            sk_vec3 {
                x: 0.0,
                y: 0.0,
                z: 1.0,
            },
            &mut rng,
            &mut d,
        );
        assert!((s == sk_status::SK_OK) == (word(0) <= 7));
        let mut surf = sk_surface {
            model: enum_arg::sk_surface_model(0),
            fraction_model: enum_arg::sk_fraction_model(0),
            policy: enum_arg::sk_crossing_policy(0),
            phong_alpha: 1.0,
            fraction: 0.0,
        };
        let s = sk_surface_new(
            enum_arg::sk_surface_model(word(1)),
            x(5),
            enum_arg::sk_fraction_model(word(2)),
            x(6),
            x(7),
            enum_arg::sk_crossing_policy(word(3)),
            &mut surf,
        );
        if s == sk_status::SK_OK {
            let mut ev = 0u32;
            let _ = sk_surface_interact(
                &surf,
                sk_vec3 {
                    x: x(8),
                    y: x(9),
                    z: x(10),
                },
                sk_vec3 {
                    x: x(11),
                    y: x(12),
                    z: x(13),
                },
                x(14),
                x(15),
                x(16),
                &mut rng,
                &mut d,
                &mut ev,
            );
        }
        // Tables from arbitrary measured data and sizes.
        let m = n / 2;
        let len = word(4) as usize;
        let mut buf = vec![0.0f32; len.min(4096)];
        let mut t = sk_table {
            data: core::ptr::null(),
            n: 0,
            kind: enum_arg::sk_table_kind(0),
        };
        let s = sk_table_new_measured(
            f.as_ptr(),
            f.as_ptr().add(m),
            m,
            buf.as_mut_ptr(),
            buf.len(),
            word(5) as usize,
            &mut t,
        );
        if s == sk_status::SK_OK {
            let c = sk_table_sample_cos(&t, x(4));
            assert!(c.is_nan() || c.abs() <= 1.0);
            let c = sk_table_cdf(&t, x(4));
            assert!(c.is_nan() || (0.0..=1.0).contains(&c), "{c}");
            let g = sk_table_mean_cosine(&t);
            assert!(g.abs() <= 1.0 + 1e-5, "{g}");
            let mut outs = vec![0.0f32; n];
            batch(
                sk_table_sample_cos_n(&t, f.as_ptr(), outs.as_mut_ptr(), n),
                &outs,
            );
            batch_dirs(&f, |w, u, o, pdf| {
                sk_table_sample_dir_n(&t, w[0], w[1], w[2], u, u, o[0], o[1], o[2], pdf, n)
            });
            let mut chi = [0.0f32; 4];
            if sk_table_legendre_moments(&t, chi.as_mut_ptr(), 4) == sk_status::SK_OK {
                assert!(chi.iter().all(|c| c.abs() <= 1.0 + 1e-3), "{chi:?}");
            }
        }
        // Homogeneous media with arbitrary channels.
        let mut w = vec![0.0f32; m];
        let (mut tt, mut sc) = (0.0f32, 0u32);
        let _ = sk_homogeneous_sample(
            f.as_ptr(),
            f.as_ptr().add(m),
            m,
            x(17),
            x(18),
            x(19),
            &mut tt,
            &mut sc,
            w.as_mut_ptr(),
        );
        // Grids of arbitrary dimensions over the data.
        let mut g = sk_grid { opaque: [0; 32] };
        let (nx, ny) = (word(6) % 8, word(7) % 8);
        if (nx as usize) * (ny as usize) <= n
            && sk_grid_new(f.as_ptr(), nx, ny, 1, x(20), x(21), &mut g) == sk_status::SK_OK
        {
            // The trackers' budget from byte 12: 1 to 254 steps, and 255
            // for 0 (the library's, 2^20 steps). Taken as the byte itself,
            // 0 for a zero or absent byte (as most fuzzed inputs have),
            // seven walks through a fuzzed majorant ran to 2^20 steps: up
            // to a minute per input under the sanitizer, most of the
            // corpus replay's time in CI.
            let budget = match data.get(12) {
                Some(255) => 0,
                Some(&b) => u32::from(b).max(1),
                None => 1,
            };
            let mut a = args(
                &g,
                v3(x(22), 0.5, 0.5),
                v3(1.0, x(23), 0.0),
                x(24),
                &mut rng,
            );
            a.budget = budget;
            let mut r = core::mem::MaybeUninit::<sk_track_result>::uninit();
            if sk_ratio_track(&a, r.as_mut_ptr()) == sk_status::SK_OK {
                let tr = r.assume_init().tr;
                assert!((0.0..=1.0).contains(&tr), "{tr}");
            }
            // The same grid in a fuzzed box and sampling, through majorants
            // of a fuzzed resolution with a fuzzed budget.
            let (lo, hi) = (v3(x(25), x(26), -1.0), v3(x(27), 2.0, 1.0));
            let (blo, bhi) = if sk_grid_set_box(&mut g, lo, hi) == sk_status::SK_OK {
                (lo, hi)
            } else {
                (v3(0.0, 0.0, 0.0), v3(1.0, 1.0, 1.0))
            };
            let _ = sk_grid_set_sampling(&mut g, enum_arg::sk_sampling(word(8) % 3));
            let mut store = [0.0f32; 64];
            let (mx, my, mz) = (1 + word(9) % 4, 1 + word(10) % 4, 1 + word(11) % 4);
            let mut maj = core::mem::MaybeUninit::<sk_majorants>::uninit();
            let null = core::ptr::null_mut();
            if sk_majorants_new_from_grid(
                &g,
                mx,
                my,
                mz,
                store.as_mut_ptr(),
                null,
                64,
                maj.as_mut_ptr(),
            ) == sk_status::SK_OK
            {
                let maj = maj.assume_init();
                a = args(
                    &g,
                    v3(x(28), x(29), 0.25),
                    v3(x(30), 1.0, x(31)),
                    x(32),
                    &mut rng,
                );
                a.medium.majorants = &maj;
                a.budget = budget;
                let cap = if budget == 0 { 1 << 20 } else { budget };
                let tau = sk_majorants_optical_depth(&maj, a.o, a.d, 0.0, x(32));
                assert!(tau.is_nan() || tau >= 0.0, "{tau}");
                if sk_ratio_track(&a, r.as_mut_ptr()) == sk_status::SK_OK {
                    let r = r.assume_init();
                    assert!((0.0..=1.0).contains(&r.tr) && r.steps <= cap, "{r:?}");
                }
                if sk_delta_track(&a, r.as_mut_ptr()) == sk_status::SK_OK {
                    let t = r.assume_init();
                    assert!(
                        t.t >= 0.0 && (t.event as u32) <= 2 && t.steps <= cap,
                        "{t:?}"
                    );
                }
                // The unbiased ray marchers (power series, telescoping)
                // with a fuzzed step count (0: the library's): a finite
                // estimate within the budget.
                a.strata = word(13) % 16;
                for march in [sk_ray_march, sk_telescoping_march] {
                    if march(&a, r.as_mut_ptr()) == sk_status::SK_OK {
                        let r = r.assume_init();
                        assert!(r.tr.is_finite() && r.steps <= cap, "{r:?}");
                    }
                }
                // Emission with the grid as its own emitted radiance, and
                // the exact integral over the majorants' cells: a finite,
                // non-negative radiance within the budget.
                a.medium.emission = &g;
                if sk_emission_track(&a, r.as_mut_ptr()) == sk_status::SK_OK {
                    let e = r.assume_init();
                    assert!(e.radiance >= 0.0 && e.radiance.is_finite(), "{e:?}");
                    assert!(e.tr >= 0.0 && e.steps <= cap, "{e:?}");
                }
                let mut cells = a;
                cells.medium.grid = core::ptr::null();
                cells.medium.emission = core::ptr::null();
                cells.medium.emission_cells = &maj;
                if sk_emission_track(&cells, r.as_mut_ptr()) == sk_status::SK_OK {
                    let e = r.assume_init();
                    assert!(e.radiance >= 0.0 && (0.0..=1.0).contains(&e.tr), "{e:?}");
                }
                // Majorants that may not bound, cut to a fuzzed fraction:
                // signed weights, finite; the strict estimators refuse or
                // answer, never crash.
                let cut = store.map(|s| s * x(33).abs().min(1.0));
                let mut low = core::mem::MaybeUninit::<sk_majorants>::uninit();
                let no_min = core::ptr::null();
                if sk_majorants_new(cut.as_ptr(), no_min, mx, my, mz, blo, bhi, low.as_mut_ptr())
                    == sk_status::SK_OK
                {
                    let low = low.assume_init();
                    let mut nb = a;
                    nb.medium.emission = core::ptr::null();
                    nb.medium.majorants = &low;
                    nb.flags = SK_TRACK_NONBOUNDING;
                    if sk_ratio_track(&nb, r.as_mut_ptr()) == sk_status::SK_OK {
                        let r = r.assume_init();
                        assert!(r.tr.is_finite() && r.steps <= cap, "{r:?}");
                        assert!(r.exceeded == 0.0 || r.exceeded > 1.0, "{r:?}");
                    }
                    // The same through the grid as the caller's medium.
                    nb.medium.grid = core::ptr::null();
                    nb.medium.coefficients = Some(grid_medium);
                    nb.medium.ctx = &g as *const sk_grid as *mut core::ffi::c_void;
                    if sk_delta_track(&nb, r.as_mut_ptr()) == sk_status::SK_OK {
                        let w = r.assume_init();
                        assert!(w.weight.is_finite() && (w.event as u32) <= 2, "{w:?}");
                    }
                    nb.flags = 0;
                    let _ = sk_ratio_track(&nb, r.as_mut_ptr());
                }
                // Residual ratio tracking with the grid's minorants at the
                // same resolution: a transmittance (a weight may pass 1 by
                // the minorants' rounding, never by more).
                let (mut hi8, mut lo8) = ([0.0f32; 64], [0.0f32; 64]);
                let mut ext = core::mem::MaybeUninit::<sk_majorants>::uninit();
                let (h, l) = (hi8.as_mut_ptr(), lo8.as_mut_ptr());
                if sk_majorants_new_from_grid(&g, mx, my, mz, h, l, 64, ext.as_mut_ptr())
                    == sk_status::SK_OK
                {
                    let ext = ext.assume_init();
                    a.medium.emission = core::ptr::null();
                    a.medium.majorants = &ext;
                    if sk_residual_ratio_track(&a, r.as_mut_ptr()) == sk_status::SK_OK {
                        let r = r.assume_init();
                        assert!(
                            (0.0..=1.0 + 1e-5).contains(&r.tr) && r.steps <= cap,
                            "{r:?}"
                        );
                    }
                }
            }
        }
        // Equiangular sampling with a fuzzed ray, segment and point: OK or
        // DOMAIN; once built, every distance lies in the segment (or is NaN
        // for a NaN uniform) and every density is finite and >= 0.
        let mut eq = core::mem::MaybeUninit::<sk_equiangular>::uninit();
        let st = sk_equiangular_new(
            v3(x(0), x(1), x(2)),
            v3(x(3), x(4), 1.0),
            x(5),
            x(6),
            v3(x(7), x(8), x(9)),
            eq.as_mut_ptr(),
        );
        assert!(matches!(st, sk_status::SK_OK | sk_status::SK_ERR_DOMAIN));
        if st == sk_status::SK_OK {
            let eq = eq.assume_init();
            let (a, b) = (x(5), x(6));
            let t = sk_equiangular_sample(&eq, x(10));
            assert!(x(10).is_nan() || (a..=b).contains(&t), "{t} in [{a}, {b}]");
            let p = sk_equiangular_pdf(&eq, x(11));
            assert!(p >= 0.0 && !p.is_nan(), "{p}");
        }
    }
});
