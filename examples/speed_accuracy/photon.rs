//! The whole photon loop (`benches/c_photon.c`): a slab Monte Carlo through
//! the C ABI, one tracking call per flight, against the same loop with the
//! peers' formulas inline (MCML's step and HG, pbrt-v4's delta tracking),
//! homogeneous and heterogeneous (a callback, a grid); photons per second,
//! and the reflectance and transmittance against adding-doubling.

use crate::*;
use std::fmt::Write as _;

/// Adding-doubling for the slab every mode simulates (τ = 2, ω = 0.9,
/// g = 0.75, matched boundaries, normal incidence; the transmittance
/// includes the unscattered e⁻²): iadpython 0.5.3,
/// `Sample(a=0.9, b=2, g=0.75, d=1, n=1, quad_pts=24).rt()`, the same to
/// 10⁻⁶ from 16 to 28 quadrature points.
const AD: (f64, f64) = (0.097395, 0.660958);

/// The section of PERFORMANCE.md.
pub(crate) fn photon_report() -> String {
    let mut s = String::from(
        "\n## A whole photon loop\n\n`benches/c_photon.c`, gcc -O2 against `libscatterkit.a`: a slab of optical depth 2, \
         albedo 0.9 as a weight, HG g = 0.75, matched boundaries, 10⁶ photons at normal incidence; times are the \
         median of 5 rounds, each running every mode once in turn. \
         `lib`: through the C ABI, one call per flight, `sk_free_path_f64` in the homogeneous slab (the call a \
         homogeneous code makes, one draw per flight as MCML's) and `sk_delta_track_f64` in the others (arguments \
         filled once per medium), and `sk_phase_sample_dir_f64` per scattering; `inline`: the peers' formulas (MCML's free path, HG and \
         direction update; pbrt-v4's delta tracking at the majorant in the heterogeneous media), reading σ_t, the \
         majorant and g from a struct filled at run time as those codes read their input (compiled in, they were \
         folded into constants); each mode compiled as its own function. \
         Media of one optical depth: homogeneous, a callback σ_t = 1 + 2z (majorant 3), the same on a 1×1×64 grid. \
         R and T against adding-doubling (iadpython 0.5.3: R 0.097395, T 0.660958). The row marked (no target) \
         tracks the homogeneous slab with delta tracking at its own majorant, two draws and a callback per flight: \
         what it costs a code that sends every medium through one tracking call. The row marked (like with like) \
         sets the callback row against the inline loop reading the same callback through a function pointer it \
         cannot see into, as a code holds a medium its user supplies: the rest of the callback row's ratio is what \
         calling a medium through a pointer costs any loop (an opaque call in the flight's loop: every \
         floating-point register saved around it).\n\n",
    );
    let Some(c) = run_c("benches/c_photon.c", &[]) else {
        writeln!(s, "SKIPPED: {C_SKIPPED}.").unwrap();
        return s;
    };
    writeln!(
        s,
        "| medium | lib ns/photon | inline ns/photon | lib R (σ) | lib T (σ) | within 4σ of adding-doubling | lib / inline | ≤ 1.2× |\n|---|---:|---:|---|---|---|---:|---|"
    )
    .unwrap();
    for (medium, inline, label, target) in [
        ("hom", "hom", "photon loop, homogeneous", Some(1.2)),
        (
            "homdt",
            "hom",
            "photon loop, homogeneous through `sk_delta_track_f64` (no target)",
            None,
        ),
        ("cb", "cb", "photon loop, callback σ_t = 1 + 2z", Some(1.2)),
        (
            "cb",
            "cbfn",
            "photon loop, callback σ_t = 1 + 2z, against the inline loop calling the same callback (like with like, no target)",
            None,
        ),
        ("grid", "grid", "photon loop, 1×1×64 grid", Some(1.2)),
    ] {
        let (lib, inl) = (
            c[&format!("lib.{medium}")].0,
            c[&format!("inline.{inline}")].0,
        );
        let (r, t) = (c[&format!("lib.{medium}.R")], c[&format!("lib.{medium}.T")]);
        let within = |(v, se): (f64, f64), want: f64| (v - want).abs() <= 4.0 * se;
        let all = [format!("lib.{medium}"), format!("inline.{inline}")]
            .iter()
            .all(|k| within(c[&format!("{k}.R")], AD.0) && within(c[&format!("{k}.T")], AD.1));
        row(&mut s, label, (lib, inl), (r, t), all, target);
    }
    rust_rows(&mut s);
    s
}

/// The slab's media (as `benches/c_photon.c`).
#[derive(Clone, Copy)]
enum Medium {
    Hom,
    /// The homogeneous slab through delta tracking at its own majorant.
    HomDt,
    Cb,
    Grid,
}

const ALBEDO: f64 = 0.9;
const G: f64 = 0.75;
const NZ: usize = 64;

/// σ_t at height `z` of the callback media.
fn sigma_t(m: Medium, z: f64) -> f64 {
    match m {
        Medium::Cb => 1.0 + 2.0 * z,
        _ => 2.0,
    }
}

/// A uniform in `[0, 1)` from the top 53 bits, as the C loop's `xo_u`.
fn u01(rng: &mut Xoshiro256PlusPlus) -> f64 {
    use rand_xoshiro::rand_core::Rng as _;
    (rng.next_u64() >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0)
}

/// The distance to the slab's boundary (z in [0, 1]).
fn to_boundary(z: f64, dz: f64) -> f64 {
    if dz > 0.0 {
        (1.0 - z) / dz
    } else if dz < 0.0 {
        -z / dz
    } else {
        1e30
    }
}

/// The medium as the inline loop reads it, at run time (as MCML reads its
/// layer records): compiled-in constants would be folded.
#[derive(Clone, Copy)]
struct Layer {
    sigma_t: f64,
    sigma_maj: f64,
    g: f64,
}

/// MCML's HG inverse and direction update (Wang, Jacques & Zheng 1995).
fn mcml_scatter(d: &mut [f64; 3], g: f64, rng: &mut Xoshiro256PlusPlus) {
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u01(rng));
    let ct = (1.0 + g * g - s * s) / (2.0 * g);
    let st = (1.0 - ct * ct).max(0.0).sqrt();
    let (sp, cp) = (2.0 * std::f64::consts::PI * u01(rng)).sin_cos();
    let [ux, uy, uz] = *d;
    *d = if uz.abs() > 0.99999 {
        [st * cp, st * sp, if uz > 0.0 { ct } else { -ct }]
    } else {
        let t = (1.0 - uz * uz).sqrt();
        [
            st * (ux * uz * cp - uy * sp) / t + ux * ct,
            st * (uy * uz * cp + ux * sp) / t + uy * ct,
            -st * cp * t + uz * ct,
        ]
    };
}

/// The inline flight: MCML's step in the homogeneous slab, pbrt-v4's
/// delta tracking at the majorant 3 in the others (the grid read as a
/// code reads its own 1-D grid).
fn inline_flight(
    (m, l): (Medium, Layer),
    o: [f64; 3],
    d: [f64; 3],
    tb: f64,
    density: &[f64],
    rng: &mut Xoshiro256PlusPlus,
) -> f64 {
    if let Medium::Hom | Medium::HomDt = m {
        return -(1.0 - u01(rng)).ln() / l.sigma_t;
    }
    let mut t = 0.0;
    loop {
        t += -(1.0 - u01(rng)).ln() / l.sigma_maj;
        if t >= tb {
            return t;
        }
        let z = o[2] + t * d[2];
        let sigma = if let Medium::Grid = m {
            let x = z * (NZ - 1) as f64;
            let i = if x <= 0.0 {
                0
            } else {
                (x as usize).min(NZ - 2)
            };
            density[i] + (x - i as f64) * (density[i + 1] - density[i])
        } else {
            sigma_t(m, z)
        };
        if u01(rng) * l.sigma_maj < sigma {
            return t;
        }
    }
}

/// ns per photon, (R, σ) and (T, σ).
type Slab = (f64, (f64, f64), (f64, f64));

/// The slab from Rust, each medium and loop compiled as a function of its
/// own (as `benches/c_photon.c` compiles each mode), as a code whose medium
/// is known when it is compiled has it. In one body taking the medium and
/// the loop at run time, each loop's time moved with the others' code:
/// the inline homogeneous loop took 147 ns per photon in one build of
/// such a body and 112 in a function of its own (Intel Xeon, family 6
/// model 167), and the inline callback loop, which re-read the medium's
/// kind at every tentative collision, 210 against 170.
fn rust_slab(m: Medium, lib: bool, photons: usize) -> Slab {
    match (m, lib) {
        (Medium::Hom, false) => slab_mode::<0, false>(photons),
        (Medium::Hom, true) => slab_mode::<0, true>(photons),
        (Medium::HomDt, false) => slab_mode::<1, false>(photons),
        (Medium::HomDt, true) => slab_mode::<1, true>(photons),
        (Medium::Cb, false) => slab_mode::<2, false>(photons),
        (Medium::Cb, true) => slab_mode::<2, true>(photons),
        (Medium::Grid, false) => slab_mode::<3, false>(photons),
        (Medium::Grid, true) => slab_mode::<3, true>(photons),
    }
}

/// [`slab`] for medium `M` (the order of [`Medium`]) and loop `LIB`.
#[inline(never)]
fn slab_mode<const M: u8, const LIB: bool>(photons: usize) -> Slab {
    let m = [Medium::Hom, Medium::HomDt, Medium::Cb, Medium::Grid][M as usize];
    slab(m, LIB, photons)
}

/// The slab: `lib` through the library's calls (one `free_path`,
/// `one_majorant_delta_track` or `Grid::delta_track` per flight,
/// `HenyeyGreenstein::sample_dir` per scattering), else inline.
#[inline(always)]
fn slab(m: Medium, lib: bool, photons: usize) -> Slab {
    use scatterkit::medium::majorant::one_majorant_delta_track;
    let density: Vec<f64> = (0..NZ)
        .map(|k| 1.0 + 2.0 * k as f64 / (NZ - 1) as f64)
        .collect();
    let grid = Grid::new(&density, 1, 1, NZ, 0.0, 1.0)
        .and_then(|g| g.with_box(Vec3::new(-1e6, -1e6, 0.0), Vec3::new(1e6, 1e6, 1.0)))
        .expect("the slab's grid");
    let hg = scatterkit::HenyeyGreenstein::new(G).expect("HG");
    let maj = if let Medium::Cb = m { 3.0 } else { 2.0 };
    let layer = black_box(Layer {
        sigma_t: 2.0,
        sigma_maj: 3.0,
        g: G,
    });
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(42);
    let (mut r, mut t) = ([0.0f64; 2], [0.0f64; 2]);
    let start = Instant::now();
    for _ in 0..photons {
        let (mut o, mut d, mut w) = ([0.0f64; 3], [0.0, 0.0, 1.0], 1.0f64);
        loop {
            let tb = to_boundary(o[2], d[2]);
            let s = if lib && matches!(m, Medium::Hom) {
                scatterkit::medium::free_path(layer.sigma_t, u01(&mut rng))
            } else if lib {
                let ray = Ray::new(Vec3::new(o[0], o[1], o[2]), Vec3::new(d[0], d[1], d[2]), tb);
                let hit = match m {
                    Medium::Grid => grid.delta_track(ray, &mut rng),
                    _ => one_majorant_delta_track(
                        |p: Vec3<f64>| (0.0, sigma_t(m, p.z)),
                        maj,
                        ray,
                        scatterkit::medium::MAX_STEPS,
                        &mut rng,
                    )
                    .map(|x| (x.t, x.event)),
                };
                match hit.expect("tracking the slab") {
                    (_, scatterkit::medium::Event::Escaped) => tb,
                    (s, _) => s,
                }
            } else {
                inline_flight((m, layer), o, d, tb, &density, &mut rng)
            };
            if s >= tb {
                let tally = if d[2] > 0.0 { &mut t } else { &mut r };
                tally[0] += w;
                tally[1] += w * w;
                break;
            }
            for k in 0..3 {
                o[k] += s * d[k];
            }
            w *= ALBEDO;
            if w < 1e-4 {
                if u01(&mut rng) < 0.1 {
                    w *= 10.0;
                } else {
                    break;
                }
            }
            if lib {
                let (u1, u2) = (u01(&mut rng), u01(&mut rng));
                let (out, _) = hg.sample_dir(Vec3::new(d[0], d[1], d[2]), u1, u2);
                d = [out.x, out.y, out.z];
            } else {
                mcml_scatter(&mut d, layer.g, &mut rng);
            }
        }
    }
    let ns = start.elapsed().as_secs_f64() * 1e9 / photons as f64;
    let n = photons as f64;
    let stat = |x: [f64; 2]| {
        let mean = x[0] / n;
        (mean, ((x[1] / n - mean * mean) / n).sqrt())
    };
    (ns, stat(r), stat(t))
}

/// The Rust rows: the same slab through the library's Rust calls and
/// inline, with the ≤ 1.1× target.
fn rust_rows(s: &mut String) {
    writeln!(
        s,
        "\nThe same slab from Rust (`examples/speed_accuracy/photon.rs`, rustc -O, xoshiro256++): `lib` makes one \
         `free_path` (homogeneous), `one_majorant_delta_track` (callback; the homogeneous row with no target) or \
         `Grid::delta_track` call per flight and one \
         `HenyeyGreenstein::sample_dir` per scattering; `inline` is the loop above with Rust's `ln`, `sin_cos`. \
         Each medium and loop is compiled as a function of its own, as in the C program; times are the median \
         of 5 rounds of the two loops in turn.\n\n\
         | medium | lib ns/photon | inline ns/photon | lib R (σ) | lib T (σ) | within 4σ of adding-doubling | lib / inline | ≤ 1.1× |\n|---|---:|---:|---|---|---|---:|---|"
    )
    .unwrap();
    for (m, label, target) in [
        (Medium::Hom, "Rust photon loop, homogeneous", Some(1.1)),
        (
            Medium::HomDt,
            "Rust photon loop, homogeneous through `one_majorant_delta_track` (no target)",
            None,
        ),
        (
            Medium::Cb,
            "Rust photon loop, callback σ_t = 1 + 2z",
            Some(1.1),
        ),
        (Medium::Grid, "Rust photon loop, 1×1×64 grid", Some(1.1)),
    ] {
        let photons = 1_000_000;
        let (mut inl, mut lib) = ([0.0; ROUNDS], [0.0; ROUNDS]);
        let (mut ri, mut ti, mut r, mut t) = Default::default();
        for k in 0..ROUNDS {
            (inl[k], ri, ti) = rust_slab(m, false, photons);
            (lib[k], r, t) = rust_slab(m, true, photons);
        }
        let (inl, lib) = (median(inl), median(lib));
        let within = |(v, se): (f64, f64), want: f64| (v - want).abs() <= 4.0 * se;
        let all = within(r, AD.0) && within(t, AD.1) && within(ri, AD.0) && within(ti, AD.1);
        row(s, label, (lib, inl), (r, t), all, target);
    }
}

/// Rounds of each Rust mode, run in turn (as `benches/c_photon.c` runs
/// its modes); the times reported are the medians. One run of a mode moved
/// by up to 8 % from run to run on a shared machine; in rounds, a drift
/// reaches the library's and the inline loop's times alike. Each round
/// starts from the same seed, so R and T are the same in each.
const ROUNDS: usize = 5;

/// The median of an odd number of times.
fn median<const N: usize>(mut x: [f64; N]) -> f64 {
    x.sort_by(f64::total_cmp);
    x[N / 2]
}

/// One row of a photon-loop table: times, the library's R and T with their
/// standard errors, whether both loops agree with adding-doubling, and the
/// ratio against its `target` (none: "—").
fn row(
    s: &mut String,
    label: &str,
    (lib, inl): (f64, f64),
    (r, t): ((f64, f64), (f64, f64)),
    all: bool,
    target: Option<f64>,
) {
    writeln!(
        s,
        "| {label} | {lib:.0} | {inl:.0} | {:.5} ({:.5}) | {:.5} ({:.5}) | {} | {:.2}× | {} |",
        r.0,
        r.1,
        t.0,
        t.1,
        if all {
            "yes (lib and inline)"
        } else {
            "**no**"
        },
        lib / inl,
        match target {
            None => "—",
            Some(x) if lib <= x * inl => "met",
            Some(_) => "**missed**",
        }
    )
    .unwrap();
}
