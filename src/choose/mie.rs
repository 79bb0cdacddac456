//! The honest chooser: the cheapest model whose density is within a
//! total-variation distance of the real Lorenz–Mie phase function of
//! droplets of one diameter at one wavelength (water by default), and the
//! distance every candidate achieved.
//!
//! The reference is the exact Mie phase function (`crate::mie`), not the
//! fog fit. Its quantiles come from its CDF accumulated on a uniform grid
//! in `θ` of `max(20 000, 100 x)` steps (the forward peak is about `1/x`
//! wide); the distance is `∫₀¹ (1 − p/p_Mie)₊ dv` over the Mie quantile `v`
//! by the midpoint rule at [`MIE_NODES`] nodes, held in the caller's
//! `work`. Candidates, in order of measured sampling cost (ns per `cos θ`,
//! `docs/measured/PERFORMANCE.md`): isotropic, HG (best g), Rayleigh, then either
//! the Mie table itself (`mie::table_sizes`; about 9 ns per f64 sample, so
//! faster than Draine, 38–164 ns, or the fog fit, 270 ns, but it holds
//! `2(intervals + 1)` doubles), or, without a table, Draine (best g and α),
//! two-lobe HG (best `g1`, `g2`, weight; its exact inverse costs about
//! what the fog's does, 115 ns), the mixture of Rayleigh and one HG lobe
//! (best `g`, weight: molecules and aerosol in one cell, sampled by the
//! same exact mixture inverse), the fog fit (for `d ≤ 50 µm`) and
//! Fournier–Forand (best `n`, `ν`; 350 ns). A model is accepted at `(1 −
//! MARGIN)` of the tolerance, like the fog chooser.
//!
//! Fournier–Forand approximates Mie for a Junge (power-law) distribution
//! of particles, the ocean's; against droplets of one size it is a
//! candidate so that its distance is reported, and it is rarely the
//! closest. Two-lobe HG is no closer than one HG for droplets below about
//! 1 µm at 550 nm (checked against a brute-force grid in `(g1, g2, w)`):
//! there Draine's `(1 + αμ²)` shape is what helps.
//!
//! [`choose_measured`] runs the same candidates (without the fog fit)
//! against tabulated data, whose quantiles are exact for its linear
//! density. For Mie over a Junge distribution of ocean particles,
//! Fournier–Forand's own scene, it measures Fournier–Forand 0.15–0.29 away
//! and one or two HG lobes 0.02–0.11 (`docs/measured/ocean_particles.md`).

use super::fog::{
    MARGIN, Model, Quantiles, fit_draine, fit_fournier_forand, fit_hg, fit_rayleigh_hg,
    fit_two_lobe_hg,
};
use crate::error::Error;
use crate::mie::{self, Complex, Mie};
use crate::phase::{Draine, Fog, FournierForand, HenyeyGreenstein, Phase, PhaseFunction};

/// Quadrature nodes of the distance to Mie (the midpoint rule in the Mie
/// quantile): more than the fog chooser's 512, for the oscillations of a
/// large droplet's phase function.
pub const MIE_NODES: usize = 2048;
/// The length of the `work` slice [`choose_mie`] needs.
pub const WORK_LEN: usize = 2 * MIE_NODES;

/// What [`choose_mie`] found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MieChoice {
    /// The chosen model.
    pub model: Model,
    /// The chosen model ready to sample, or `None` for [`Model::MieTable`]
    /// (build it with `Mie::tabulate` and `Table::measured` at
    /// `mie::table_sizes`; after [`choose_measured`], `Table::measured`
    /// over the same data).
    pub phase: Option<Phase<f64>>,
    /// The chosen model's distance to Mie (0 for the table: it is the
    /// reference; the table built at `mie::table_sizes` adds its own, at
    /// most 1.2·10⁻³ for `x ≤ 1000`, `docs/measured/mie_table.md`).
    pub distance: f64,
    /// Whether `distance` is within the tolerance (without a table, none
    /// may be: the closest is returned).
    pub within_tolerance: bool,
    /// The distance of each candidate's best fit: isotropic, HG, Rayleigh,
    /// Draine, fog fit, two-lobe HG, Fournier–Forand, Rayleigh + HG (NaN
    /// for the fog fit beyond 50 µm and always from [`choose_measured`],
    /// and for the last three when a table is allowed: they are fitted only
    /// without one).
    pub distances: [f64; 8],
    /// The droplets' size parameter (NaN from [`choose_measured`]).
    pub x: f64,
    /// The refractive index used (NaN from [`choose_measured`]).
    pub m: Complex,
}

/// The buffer [`choose_mie`] needs for the Mie series (in [`Complex`]
/// values), or `None` for input it rejects. `m = None` means water
/// ([`mie::water`]).
pub fn buffer_len(diameter_um: f64, wavelength_um: f64, m: Option<Complex>) -> Option<usize> {
    let m = match m {
        Some(m) => m,
        None => mie::water(wavelength_um)?,
    };
    mie::buffer_len(mie::size_parameter(diameter_um, wavelength_um, 1.0), m)
}

/// The cheapest model within `tolerance` (total variation, `0 < tolerance
/// < 1`) of the Mie phase function of droplets of `diameter_um` µm in air at
/// vacuum wavelength `wavelength_um` µm, with relative index `m` (`None`:
/// water at that wavelength, which needs `0.182 ≤ λ ≤ 1.129` µm). With
/// `allow_table` the Mie table is the last candidate (always within);
/// without it, Draine and the fog fit are, and the closest model is
/// returned if none is within. `buf` holds at least [`buffer_len`] values,
/// `work` at least [`WORK_LEN`]. Costs a Mie solution, two passes over
/// `max(20 000, 100 x)` angles and a few thousand quadratures of
/// [`MIE_NODES`] points (about 0.15 s at `x = 300` with a table, 0.25 to
/// 0.4 s without, where two-lobe HG and Fournier–Forand are fitted too):
/// build it once per medium. [`Error::Domain`] for invalid input, [`Error::Size`] for short
/// slices.
pub fn choose_mie(
    diameter_um: f64,
    wavelength_um: f64,
    m: Option<Complex>,
    tolerance: f64,
    allow_table: bool,
    buf: &mut [Complex],
    work: &mut [f64],
) -> Result<MieChoice, Error> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(Error::Domain);
    }
    let m = match m {
        Some(m) => m,
        None => mie::water(wavelength_um).ok_or(Error::Domain)?,
    };
    let x = mie::size_parameter(diameter_um, wavelength_um, 1.0);
    let sphere = Mie::new(x, m, buf)?;
    let work = work.get_mut(..WORK_LEN).ok_or(Error::Size)?;
    let (mu, density) = work.split_at_mut_checked(MIE_NODES).ok_or(Error::Size)?;
    quantiles(&|m| sphere.phase(m), x, mu, density);
    let r = Quantiles { mu, density };
    let fog = Fog::<f64>::from_diameter(diameter_um).ok();
    Ok(choose_among(&r, fog, tolerance, allow_table, x, m))
}

/// The cheapest model within `tolerance` (total variation, `0 < tolerance
/// < 1`) of a phase function measured or tabulated at `m ≥ 2` cosines, as
/// [`Table::measured`](crate::Table::measured) takes it (`cos_theta`
/// strictly monotone within `[−1, 1]`, `pdf` finite, non-negative, any
/// scale; linear in `cos θ` between the points, zero outside their range):
/// a size distribution's Mie average (`Polydisperse::average` at
/// `mie::table_angle`), a measured volume scattering function, any
/// reference. Candidates as [`choose_mie`] without the fog fit (there is
/// no droplet diameter; its distance is NaN); [`Model::MieTable`] here
/// means [`Table::measured`](crate::Table::measured) over the same data,
/// the reference itself. In the result `x` and `m` are NaN. The quantiles
/// are exact for the linear density (no angle grid). `work` holds at least
/// [`WORK_LEN`] values. Costs a few thousand quadratures of [`MIE_NODES`]
/// points (about 0.25 s without a table). [`Error::Domain`] for a
/// tolerance outside `(0, 1)` or invalid data, [`Error::Size`] for slices
/// of different lengths, `m < 2` or a short `work`.
pub fn choose_measured(
    cos_theta: &[f64],
    pdf: &[f64],
    tolerance: f64,
    allow_table: bool,
    work: &mut [f64],
) -> Result<MieChoice, Error> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(Error::Domain);
    }
    let work = work.get_mut(..WORK_LEN).ok_or(Error::Size)?;
    let (mu, density) = work.split_at_mut_checked(MIE_NODES).ok_or(Error::Size)?;
    crate::table::measured::measured_quantiles(cos_theta, pdf, mu, density)?;
    let r = Quantiles { mu, density };
    let nan = f64::NAN;
    Ok(choose_among(
        &r,
        None,
        tolerance,
        allow_table,
        nan,
        Complex::new(nan, nan),
    ))
}

/// Fits every candidate to the reference's quantiles `r` and picks the
/// cheapest within the tolerance (module docs).
fn choose_among(
    r: &Quantiles,
    fog: Option<Fog<f64>>,
    tolerance: f64,
    allow_table: bool,
    x: f64,
    m: Complex,
) -> MieChoice {
    let hg = fit_hg(r);
    let draine = fit_draine(r);
    let fog_d = fog.map_or(f64::NAN, |f| {
        r.distance(|mu| core::f64::consts::TAU * f.pdf(mu))
    });
    let two = (!allow_table).then(|| fit_two_lobe_hg(r, hg));
    let ff = (!allow_table).then(|| fit_fournier_forand(r));
    let ray_hg = (!allow_table).then(|| fit_rayleigh_hg(r));
    // In the order of `MieChoice::distances`.
    let distances = [
        r.distance(|_| 0.5),
        hg.1,
        r.distance(|mu| 0.375 * (1.0 + mu * mu)),
        draine.2,
        fog_d,
        two.map_or(f64::NAN, |t| t.3),
        ff.map_or(f64::NAN, |f| f.2),
        ray_hg.map_or(f64::NAN, |m| m.2),
    ];
    let phases = [
        Some(Phase::isotropic()),
        Some(Phase::HenyeyGreenstein(HenyeyGreenstein::from_g(hg.0))),
        Some(Phase::rayleigh()),
        Some(Phase::Draine(Draine::from_parts(draine.0, draine.1))),
        fog.map(Phase::Fog),
        two.and_then(|t| Phase::two_lobe_hg(t.0, t.1, t.2).ok()),
        ff.map(|f| Phase::FournierForand(FournierForand::from_parts(f.0, f.1))),
        // w HG(g) + (1 − w) Rayleigh: a fog with a Rayleigh lobe.
        ray_hg.and_then(|m| Phase::fog(m.0, 0.0, 1.0, 1.0 - m.1).ok()),
    ];
    let models = [
        Model::Isotropic,
        Model::HenyeyGreenstein,
        Model::Rayleigh,
        Model::Draine,
        Model::Fog,
        Model::TwoLobeHg,
        Model::FournierForand,
        Model::RayleighHg,
    ];
    let accept = (1.0 - MARGIN) * tolerance;
    // Cost order (indices into the arrays above): isotropic, HG, Rayleigh,
    // then the table, or Draine, two-lobe HG, Rayleigh + HG (the same exact
    // mixture inverse, a Draine lobe for the second HG), the fog fit,
    // Fournier–Forand.
    let order: &[usize] = if allow_table {
        &[0, 1, 2]
    } else {
        &[0, 1, 2, 3, 5, 7, 4, 6]
    };
    let base = MieChoice {
        model: Model::MieTable,
        phase: None,
        distance: 0.0,
        within_tolerance: true,
        distances,
        x,
        m,
    };
    let mut best: Option<(Model, Option<Phase<f64>>, f64)> = None;
    let candidates = order
        .iter()
        .filter_map(|&i| Some((*models.get(i)?, *phases.get(i)?, *distances.get(i)?)));
    for (model, phase, d) in candidates {
        if d <= accept {
            return MieChoice {
                model,
                phase,
                distance: d,
                ..base
            };
        }
        if d.is_finite() && best.is_none_or(|b| d < b.2) {
            best = Some((model, phase, d));
        }
    }
    match best {
        Some((model, phase, distance)) if !allow_table => MieChoice {
            model,
            phase,
            distance,
            within_tolerance: false,
            ..base
        },
        _ => base,
    }
}

/// The total-variation distance `½ ∫ |p − p_ref| dω` of a phase function
/// `model` from `reference` (both per steradian, functions of `cos θ`),
/// the way [`choose_mie`] measures it: the midpoint rule in the reference's
/// quantile at [`MIE_NODES`] nodes, the quantiles from the reference's CDF
/// on a uniform grid in `θ` of `max(20 000, 100 x)` steps, `x` setting the
/// resolution (a forward peak about `1/x` wide). `work` holds [`WORK_LEN`]
/// values. [`Error::Domain`] for `x` outside `(0, 10⁵]`, [`Error::Size`]
/// for a short `work`.
pub fn tv_distance(
    reference: &dyn Fn(f64) -> f64,
    model: &dyn Fn(f64) -> f64,
    x: f64,
    work: &mut [f64],
) -> Result<f64, Error> {
    if !(x > 0.0 && x <= 1e5) {
        return Err(Error::Domain);
    }
    let work = work.get_mut(..WORK_LEN).ok_or(Error::Size)?;
    let (mu, density) = work.split_at_mut_checked(MIE_NODES).ok_or(Error::Size)?;
    quantiles(reference, x, mu, density);
    let r = Quantiles { mu, density };
    Ok(r.distance(|m| core::f64::consts::TAU * model(m)))
}

/// The density of `μ` of `phase` (per steradian) at its midpoint
/// quantiles: the CDF from `μ = −1` accumulated by trapezoids on a uniform
/// grid in `θ` (one pass for the total, one to place the nodes, each linear
/// in `θ` within its step).
fn quantiles(phase: &dyn Fn(f64) -> f64, x: f64, mu: &mut [f64], density: &mut [f64]) {
    use core::f64::consts::{PI, TAU};
    let steps = ((100.0 * x) as usize).clamp(20_000, 2_000_000);
    let h = PI / steps as f64;
    // Density per unit θ (over 2π), at θ_i.
    let f = |i: usize| {
        let t = i as f64 * h;
        phase(libm::cos(t)) * libm::sin(t)
    };
    let mut total = 0.0;
    let mut prev = f(steps);
    for i in (0..steps).rev() {
        let cur = f(i);
        total += 0.5 * h * (prev + cur);
        prev = cur;
    }
    let n = mu.len();
    let (mut k, mut acc) = (0usize, 0.0);
    let mut prev = f(steps);
    for i in (0..steps).rev() {
        let cur = f(i);
        let mass = 0.5 * h * (prev + cur);
        while k < n && acc + mass >= (k as f64 + 0.5) / n as f64 * total {
            let target = (k as f64 + 0.5) / n as f64 * total;
            let w = if mass > 0.0 {
                (target - acc) / mass
            } else {
                0.5
            };
            let m = libm::cos((i as f64 + 1.0 - w) * h);
            if let (Some(mu_k), Some(d_k)) = (mu.get_mut(k), density.get_mut(k)) {
                *mu_k = m;
                *d_k = TAU * phase(m) * total_scale(total);
            }
            k += 1;
        }
        acc += mass;
        prev = cur;
    }
    // Rounding can leave the last node unplaced: put it at the forward end.
    while k < n {
        if let (Some(mu_k), Some(d_k)) = (mu.get_mut(k), density.get_mut(k)) {
            *mu_k = 1.0;
            *d_k = TAU * phase(1.0) * total_scale(total);
        }
        k += 1;
    }
}

/// The factor normalising a reference whose `2π ∫ p sin θ dθ` came out as
/// `2π total` (1 for a normalised phase function, to the grid's accuracy).
fn total_scale(total: f64) -> f64 {
    let norm = core::f64::consts::TAU * total;
    if norm > 0.0 { 1.0 / norm } else { 1.0 }
}
