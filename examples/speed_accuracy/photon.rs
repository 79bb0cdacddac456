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
         albedo 0.9 as a weight, HG g = 0.75, matched boundaries, 10⁶ photons at normal incidence. \
         `lib`: through the C ABI, one `sk_delta_track_f64` per flight (arguments filled once per medium) \
         and `sk_phase_sample_dir_f64` per scattering; `inline`: the peers' formulas (MCML's free path, HG and \
         direction update; pbrt-v4's delta tracking at the majorant in the heterogeneous media). \
         Media of one optical depth: homogeneous, a callback σ_t = 1 + 2z (majorant 3), the same on a 1×1×64 grid. \
         R and T against adding-doubling (iadpython 0.5.3: R 0.097395, T 0.660958).\n\n",
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
    let mark = |ok: bool| if ok { "met" } else { "**missed**" };
    for (medium, label) in [
        ("hom", "photon loop, homogeneous"),
        ("cb", "photon loop, callback σ_t = 1 + 2z"),
        ("grid", "photon loop, 1×1×64 grid"),
    ] {
        let (lib, inl) = (
            c[&format!("lib.{medium}")].0,
            c[&format!("inline.{medium}")].0,
        );
        let (r, t) = (c[&format!("lib.{medium}.R")], c[&format!("lib.{medium}.T")]);
        let within = |(v, se): (f64, f64), want: f64| (v - want).abs() <= 4.0 * se;
        let all = ["lib", "inline"].iter().all(|k| {
            within(c[&format!("{k}.{medium}.R")], AD.0)
                && within(c[&format!("{k}.{medium}.T")], AD.1)
        });
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
            mark(lib <= 1.2 * inl)
        )
        .unwrap();
    }
    s
}
