//! The measured points: every sampler and peer, as `Entry` values.

use crate::*;

/// Times `$sample` (an expression in the RNG `$r` giving a `Vec3<f32>`) with
/// both generators; a macro so each loop is monomorphised for its RNG.
macro_rules! dir_ns {
    (|$r:ident| $sample:expr) => {{
        let mut fast = Xoshiro256PlusPlus::seed_from_u64(1);
        let mut slow = SlowRand::new(1);
        let f = {
            let $r = &mut fast;
            time_ns(|| $sample.z)
        };
        let s = {
            let $r = &mut slow;
            time_ns(|| $sample.z)
        };
        (f, s)
    }};
}

/// One measured method.
pub(crate) struct Entry {
    pub(crate) family: &'static str,
    pub(crate) name: String,
    /// ns per cos θ (inverse CDF or rejection), fast RNG.
    pub(crate) ns: f64,
    /// ns per direction with the fast and the slow RNG, where measured.
    pub(crate) dir_ns: Option<(f64, f64)>,
    pub(crate) err: f64,
    pub(crate) cdf_err: f64,
    /// Exact in distribution (rejection): plotted at the floor.
    pub(crate) rejection: bool,
    /// Part of a curve (tables by n, cube-root steps) rather than a point.
    pub(crate) curve: Option<&'static str>,
    /// Measured from C through the header (drawn as a triangle).
    pub(crate) c_abi: bool,
    /// Set on the entries the report reads.
    pub(crate) key: Option<Key>,
}

/// The entries the report reads by name: a typed key, so renaming a label
/// cannot break a lookup at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Key {
    /// Rayleigh by Cardano with `cbrt`.
    Direct,
    /// Rayleigh by Cardano with `powf` for the cube root (Frisvad's "direct").
    DirectPow,
    /// Frisvad's simplified rejection.
    Simplified,
    /// Frisvad's CDF table with 32 intervals.
    FrisvadTable32,
    /// The Hermite inverse table with 64 intervals.
    Hermite64,
    /// This crate's cube root with two Lancaster steps.
    Cbrt2,
}

impl Entry {
    pub(crate) fn new(
        family: &'static str,
        name: impl Into<String>,
        ns: f64,
        (err, cdf_err): (f64, f64),
    ) -> Entry {
        Entry {
            family,
            name: name.into(),
            ns,
            dir_ns: None,
            err,
            cdf_err,
            rejection: false,
            curve: None,
            c_abi: false,
            key: None,
        }
    }
    pub(crate) fn rejection(family: &'static str, name: impl Into<String>, ns: f64) -> Entry {
        Entry {
            family,
            name: name.into(),
            ns,
            dir_ns: None,
            err: FLOOR,
            cdf_err: FLOOR,
            rejection: true,
            curve: None,
            c_abi: false,
            key: None,
        }
    }
}

/// Every Rayleigh method, peers and tables: cos θ and direction timings.
pub(crate) fn rayleigh_entries(out: &mut Vec<Entry>) {
    let w_in = Vec3::new(0.48f32, 0.6, 0.64);
    let names = [
        (RayleighMethod::RejectCube, "von Neumann cube"),
        (RayleighMethod::RejectSpherical, "spherical coordinates"),
        (RayleighMethod::Baranoski, "Baranoski (corrected)"),
        (RayleighMethod::Simplified, "simplified rejection"),
        (RayleighMethod::Direct, "direct (Cardano, cbrt)"),
        (RayleighMethod::DirectFast, "direct (cbrt_fast)"),
        (RayleighMethod::DirectMinimax, "direct (sqrt-free minimax)"),
        (RayleighMethod::Table, "built-in Hermite table n = 128"),
    ];
    for (m, name) in names {
        let key = match m {
            RayleighMethod::Direct => Some(Key::Direct),
            RayleighMethod::Simplified => Some(Key::Simplified),
            _ => None,
        };
        let mut r = fast_rng();
        let ns = time_ns(|| rayleigh::sample_cos::<f32, _>(m, &mut r));
        // The inverse-CDF methods are measured for accuracy; the rejection
        // methods are exact in distribution.
        let inverse: Option<fn(f32) -> f32> = match m {
            RayleighMethod::Direct => Some(rayleigh::inverse_cdf_direct::<f32>),
            RayleighMethod::DirectFast => Some(rayleigh::inverse_cdf_fast::<f32>),
            RayleighMethod::DirectMinimax => Some(rayleigh::inverse_cdf_minimax::<f32>),
            RayleighMethod::Table => Some(rayleigh::inverse_cdf_table::<f32>),
            _ => None,
        };
        let mut e = match inverse {
            Some(f) => Entry::new(
                "Rayleigh",
                name,
                ns,
                errors(f, rayleigh_exact, rayleigh_cdf),
            ),
            None => Entry::rejection("Rayleigh", name, ns),
        };
        e.key = key;
        e.dir_ns = Some(dir_ns!(|r| rayleigh::sample_dir(m, w_in, r)));
        out.push(e);
    }
    // Direct with the paper's `pow` cube root, for Frisvad's Kahan comparison.
    let pow_direct = |u: f32| {
        let s = 2.0 * (2.0 * u - 1.0);
        let w = libm::powf(s.abs() + libm::sqrtf(s * s + 1.0), 1.0 / 3.0);
        ((w - 1.0 / w).abs()).copysign(s).clamp(-1.0, 1.0)
    };
    type Sampler<'a> = &'a dyn Fn(f32) -> f32;
    let peers: [(&str, Sampler, Option<Key>); 3] = [
        (
            "direct (Cardano, powf cube root)",
            &pow_direct,
            Some(Key::DirectPow),
        ),
        (
            "peer: Mitsuba 3 (two cube roots)",
            &peers::mitsuba_rayleigh,
            None,
        ),
        (
            "peer: Cycles (fast inverse cube root)",
            &peers::cycles_rayleigh,
            None,
        ),
    ];
    for (name, f, key) in peers {
        let mut r = fast_rng();
        let ns = time_ns(|| f(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "Rayleigh",
            name,
            ns,
            errors(f, rayleigh_exact, rayleigh_cdf),
        );
        e.key = key;
        e.dir_ns = Some(dir_ns!(|r| scatterkit::geometry::direction_about(
            w_in,
            f(f32::uniform(r)),
            f32::TAU * f32::uniform(r)
        )));
        out.push(e);
    }
    let iso = Phase::<f32>::isotropic();
    let mut r = fast_rng();
    let mut e = Entry::new(
        "isotropic",
        "isotropic (floor)",
        time_ns(|| iso.sample_cos(f32::uniform(&mut r))),
        (0.0, 0.0),
    );
    e.dir_ns = Some(dir_ns!(|r| iso
        .sample_dir(w_in, f32::uniform(r), f32::uniform(r))
        .0));
    out.push(e);
    for n in [8usize, 16, 32, 64, 128, 256, 512, 1024] {
        let mut buf = vec![0.0f32; n + 1];
        let t = Table::rayleigh_cdf(&mut buf, n).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| t.sample_cos(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "Rayleigh",
            format!("Frisvad's CDF table n = {n}"),
            ns,
            errors(|u| t.sample_cos(u), rayleigh_exact, rayleigh_cdf),
        );
        e.curve = Some("Frisvad's CDF table, n = 8…1024");
        e.key = (n == 32).then_some(Key::FrisvadTable32);
        if n == 8 || n == 32 {
            e.dir_ns = Some(dir_ns!(|r| scatterkit::geometry::direction_about(
                w_in,
                t.sample_cos(f32::uniform(r)),
                f32::TAU * f32::uniform(r)
            )));
        }
        out.push(e);
        let mut hbuf = vec![0.0f32; 2 * (n + 1)];
        let h = Table::inverse(&Phase::<f32>::rayleigh(), &mut hbuf, n).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| h.sample_cos(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "Rayleigh",
            format!("Hermite inverse table n = {n}"),
            ns,
            errors(|u| h.sample_cos(u), rayleigh_exact, rayleigh_cdf),
        );
        e.curve = Some("Hermite inverse table, n = 8…1024");
        e.key = (n == 64).then_some(Key::Hermite64);
        out.push(e);
    }
}

/// HG: ours against pbrt-v4's formula, at several g.
pub(crate) fn hg_entries(out: &mut Vec<Entry>) {
    for g in [0.7f32, 1e-3, -0.99] {
        let p32 = Phase::henyey_greenstein(g).unwrap();
        let p64 = Phase::<f64>::henyey_greenstein(g as f64).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| p32.sample_cos(f32::uniform(&mut r)));
        out.push(Entry::new(
            "HG",
            format!("HG g = {g}"),
            ns,
            errors(|u| p32.sample_cos(u), |u| p64.sample_cos(u), |x| p64.cdf(x)),
        ));
        let mut r = fast_rng();
        let ns = time_ns(|| peers::pbrt_v4_hg(g, f32::uniform(&mut r)));
        out.push(Entry::new(
            "HG",
            format!("peer: pbrt-v4 HG g = {g}"),
            ns,
            errors(
                |u| peers::pbrt_v4_hg(g, u),
                |u| p64.sample_cos(u),
                |x| p64.cdf(x),
            ),
        ));
    }
}

/// Schlick's stand-in for HG (k = 0.8, about HG g = 0.6): the library's
/// f32 sampler, the portable f32 tier, and the textbook inverse
/// `μ = (2u − 1 + k)/(1 − k + 2ku)` as GPU renderers write it.
pub(crate) fn schlick_entries(out: &mut Vec<Entry>) {
    use scatterkit::phase::schlick::Schlick;
    let k = 0.8f32;
    let s32 = Schlick::new(k).unwrap();
    let s64 = Schlick::new(k as f64).unwrap();
    let tier = scatterkit::portable::Schlick::new(k).unwrap();
    let textbook = |u: f32| (2.0 * u - 1.0 + k) / (1.0 - k + 2.0 * k * u);
    let mut r = fast_rng();
    let ns = time_ns(|| s32.sample_cos(f32::uniform(&mut r)));
    let exact = |u: f64| s64.sample_cos(u);
    let cdf = |x: f64| s64.cdf(x);
    out.push(Entry::new(
        "HG",
        format!("Schlick k = {k}"),
        ns,
        errors(|u| s32.sample_cos(u), exact, cdf),
    ));
    let mut r = fast_rng();
    let ns = time_ns(|| scatterkit::portable::schlick_sample_cos(&tier, f32::uniform(&mut r)));
    out.push(Entry::new(
        "HG",
        format!("Schlick k = {k}, portable f32 tier"),
        ns,
        errors(
            |u| scatterkit::portable::schlick_sample_cos(&tier, u),
            exact,
            cdf,
        ),
    ));
    let mut r = fast_rng();
    let ns = time_ns(|| textbook(f32::uniform(&mut r)));
    out.push(Entry::new(
        "HG",
        format!("peer: textbook Schlick inverse k = {k}"),
        ns,
        errors(textbook, exact, cdf),
    ));
}

/// Draine: ours, eq. 6 as published, rejection from HG; and the fog.
pub(crate) fn draine_entries(out: &mut Vec<Entry>) {
    for (g, a) in [(0.5f32, 1.0f32), (0.9, 10.0), (0.3, 250.0), (0.01, 1000.0)] {
        let d32 = Phase::draine(g, a).unwrap();
        let d64: Phase<f64> = d32.cast();
        let mut r = fast_rng();
        let ns = time_ns(|| d32.sample_cos(f32::uniform(&mut r)));
        out.push(Entry::new(
            "Draine",
            format!("Draine g = {g}, α = {a}"),
            ns,
            errors(|u| d32.sample_cos(u), |u| d64.sample_cos(u), |x| d64.cdf(x)),
        ));
        let eq6 = |u: f32| scatterkit::phase::draine::sample_cos_eq6(g, a, u);
        let mut r = fast_rng();
        let ns = time_ns(|| eq6(f32::uniform(&mut r)));
        let (e, c) = errors(eq6, |u| d64.sample_cos(u), |x| d64.cdf(x));
        // NaN outputs count as an error of 2 (the whole range).
        let fix = |x: f64| if x.is_finite() { x } else { 2.0 };
        out.push(Entry::new(
            "Draine",
            format!("peer: eq. 6 as published g = {g}, α = {a}"),
            ns,
            (fix(e), fix(c)),
        ));
        let mut r = fast_rng();
        let ns = time_ns(|| peers::draine_rejection(g, a, || f32::uniform(&mut r)));
        out.push(Entry::rejection(
            "Draine",
            format!("peer: rejection from HG g = {g}, α = {a}"),
            ns,
        ));
    }
    let fog32 = Phase::<f32>::fog_diameter(2.0).unwrap();
    let fog64: Phase<f64> = fog32.cast();
    let mut r = fast_rng();
    let ns = time_ns(|| fog32.sample_cos(f32::uniform(&mut r)));
    out.push(Entry::new(
        "fog",
        "fog 2 µm (exact inverse)",
        ns,
        errors(
            |u| fog32.sample_cos(u),
            |u| fog64.sample_cos(u),
            |x| fog64.cdf(x),
        ),
    ));
    let mut r = fast_rng();
    let ns = time_ns(|| fog32.sample_cos_by_lobe(f32::uniform(&mut r)));
    out.push(Entry::rejection(
        "fog",
        "fog 2 µm (paper's lobe choice)",
        ns,
    ));
    for n in [64usize, 256, 1024] {
        let mut buf = vec![0.0f32; 2 * (n + 1)];
        let t = Table::inverse(&fog32, &mut buf, n).unwrap();
        let mut r = fast_rng();
        let ns = time_ns(|| t.sample_cos(f32::uniform(&mut r)));
        let mut e = Entry::new(
            "fog",
            format!("fog 2 µm Hermite table n = {n}"),
            ns,
            errors(
                |u| t.sample_cos(u),
                |u| fog64.sample_cos(u),
                |x| fog64.cdf(x),
            ),
        );
        e.curve = Some("fog 2 µm Hermite table, n = 64…1024");
        out.push(e);
    }
}

/// Cube roots: ns per call (inputs over [1e-6, 1e6]) and max error in f32
/// ULP (every 101st positive float); our step counts as a curve. Cycles'
/// `fast_inv_cbrt` was made for `[1, 4.3]` (its callers scale into it): it
/// is measured there, timed on inputs in that range, and over every float
/// as well, labelled so.
pub(crate) fn cbrt_entries(out: &mut Vec<Entry>) {
    let xs: Vec<f32> = (0..4096).map(|i| 1e-6f32 * 1.0034f32.powi(i * 2)).collect();
    let home: Vec<f32> = (0..4096).map(|i| 1.0 + 3.3 * i as f32 / 4095.0).collect();
    let ulp_over = |f: &dyn Fn(f32) -> f32, lo: f32, hi: f32| {
        (lo.to_bits()..=hi.to_bits())
            .step_by(101)
            .map(|b| {
                let x = f32::from_bits(b);
                let exact = libm::cbrt(x as f64);
                let ulp = 2f64.powi(((exact as f32).to_bits() >> 23) as i32 - 150);
                (f(x) as f64 - exact).abs() / ulp
            })
            .fold(0.0, f64::max)
    };
    // Every positive finite float.
    let ulp_error = |f: &dyn Fn(f32) -> f32| ulp_over(f, f32::from_bits(1), f32::MAX);
    let time_on = |f: &dyn Fn(f32) -> f32, inputs: &[f32]| {
        let mut i = 0usize;
        time_ns(|| {
            i = (i + 1) & 4095;
            f(black_box(inputs[i]))
        })
    };
    let time = |f: &dyn Fn(f32) -> f32| time_on(f, &xs);
    let cases: [(&str, &dyn Fn(f32) -> f32); 3] = [
        ("libm cbrtf", &libm::cbrtf),
        ("powf(x, 1/3)", &|x| libm::powf(x, 1.0 / 3.0)),
        (
            "peer: Cycles 1/fast_inv_cbrt over every float (outside its domain)",
            &|x| 1.0 / peers::fast_inv_cbrt(x),
        ),
    ];
    for (name, f) in cases {
        let ns = time(f);
        out.push(Entry::new("cbrt", name, ns, (ulp_error(f), f64::NAN)));
    }
    let cycles = |x: f32| 1.0 / peers::fast_inv_cbrt(x);
    let ns = time_on(&cycles, &home);
    out.push(Entry::new(
        "cbrt",
        "peer: Cycles 1/fast_inv_cbrt on [1, 4.3], its domain",
        ns,
        (ulp_over(&cycles, 1.0, 4.3), f64::NAN),
    ));
    for steps in 0..=3u32 {
        let f = move |x: f32| scatterkit::cbrt::cbrt_f32_steps(x, steps);
        let ns = time(&f);
        let mut e = Entry::new(
            "cbrt",
            format!("scatterkit Kahan + {steps} steps"),
            ns,
            (ulp_error(&f), f64::NAN),
        );
        e.curve = Some("scatterkit cube root, 0…3 Lancaster steps");
        e.key = (steps == 2).then_some(Key::Cbrt2);
        out.push(e);
    }
}

/// The entry with key `k` (each key is set on exactly one entry).
pub(crate) fn find(es: &[Entry], k: Key) -> &Entry {
    es.iter()
        .find(|e| e.key == Some(k))
        .unwrap_or_else(|| panic!("no entry keyed {k:?}"))
}

pub(crate) fn fmt_err(e: &Entry) -> String {
    if e.rejection {
        "exact in distribution".into()
    } else if e.err.is_nan() {
        "—".into()
    } else {
        format!("{:.1e}", e.err)
    }
}
