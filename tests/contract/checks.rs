//! The contract, one function per property, each returning what failed
//! instead of panicking, so that the mutation test can show each one
//! catches a wrong sampler. Generic over any `PhaseFunction`.

use crate::common::chi2::{chi2_directions_by_cells, integrate, threshold};
use crate::common::{CHI2_SAMPLES, rng, test_directions, uniform_grid};
use scatterkit::{Error, Phase, PhaseFunction, Real, Vec3};
use std::f64::consts::TAU;

pub type Check = Result<(), String>;

/// Tolerance of the normalisation and CDF checks, in f64. (An f32
/// density is checked against the f64 one at f32 arguments instead,
/// [`f32_density_follows_f64`]: integrated over a continuous `μ`, it would
/// be read at `μ` rounded to f32, whose spacing near ±1 misstates a lobe a
/// few thousand spacings wide by 10⁻⁵, the 40 µm fog's.)
pub const QUAD_TOL: f64 = 1e-9;

/// `∫ₐᵇ f` over `[−1, 1]` with the distance to the nearer pole on a log
/// scale: each half by adaptive Simpson in `t = ln(1 − |μ|)`, so a lobe at
/// a pole however narrow (down to the floats' spacing) and a power-law
/// singularity there (Fournier–Forand's `(1 − μ)^{−ν−1}`) are smooth
/// functions of `t`. Each half to absolute tolerance `tol`; at a pole the
/// span below `|1 − μ| = 2⁻⁶⁰` is added as the pole's value times its
/// width (a pole where the density is infinite is kept out of `[a, b]`
/// by [`integrable_span`]).
fn graded(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    // The half [lo, hi] ⊂ [0, 1]: μ = 1 − eᵗ; mirrored for [−1, 0].
    let half = |lo: f64, hi: f64, sign: f64| {
        if lo >= hi {
            return 0.0;
        }
        let floor = -60.0 * std::f64::consts::LN_2;
        let t_far = (1.0 - hi).ln().max(floor);
        let t_near = (1.0 - lo).ln();
        let g = |t: f64| f(-sign * t.exp_m1()) * t.exp();
        let pole = if hi >= 1.0 {
            f(sign) * t_far.exp()
        } else {
            0.0
        };
        integrate(&g, t_far, t_near, tol) + pole
    };
    let pos = half(a.max(0.0), b, 1.0);
    let neg = half((-b).max(0.0), -a, -1.0);
    pos + neg
}

/// `|x| ≤ tol`, and false for NaN (a NaN integral used to pass a check
/// written `|x| > tol`: Fournier–Forand's, whose density is infinite at
/// μ = 1, integrated to NaN and its normalisation was never tested).
fn within(x: f64, tol: f64) -> bool {
    x.abs() <= tol
}

/// The span `[lo, hi]` a quadrature over f64 arguments can integrate: a
/// pole where the density is infinite (an integrable power law, as
/// Fournier–Forand's forward one) is left out down to `|1 − μ| = 2⁻²⁶`,
/// and the mass of that last span is read from the model's CDF (whose
/// forward tail `tests/models/fournier_forand.rs` holds to 50-digit
/// values). Closer in, `μ` rounded to f64 is off by too large a part of
/// `1 − μ` for the density there to stand for its span.
fn integrable_span(p: &impl PhaseFunction<f64>) -> (f64, f64) {
    let cut = 1.0 - 2f64.powi(-26);
    let lo = if p.pdf(-1.0).is_infinite() {
        -cut
    } else {
        -1.0
    };
    let hi = if p.pdf(1.0).is_infinite() { cut } else { 1.0 };
    (lo, hi)
}

/// `2π ∫ p dμ = 1`, and `2π ∫ μ p dμ` is the mean cosine (see
/// [`integrable_span`] for a density infinite at a pole).
pub fn normalised(p: &impl PhaseFunction<f64>) -> Check {
    let tol = QUAD_TOL;
    let pdf = |mu: f64| p.pdf(mu);
    let (lo, hi) = integrable_span(p);
    let (below, above) = (p.cdf(lo), 1.0 - p.cdf(hi));
    let total = TAU * graded(&pdf, lo, hi, tol * 1e-3) + below + above;
    // The mass beyond a cut pole counts at the middle of its span, within
    // half the span's width: at 1 read as 1, a Fournier–Forand pole with
    // a tenth of the mass there put the mean 1.2·10⁻⁹ high (ν = 1 + 1.5·10⁻⁵).
    let (mid_lo, mid_hi) = (0.5 * (-1.0 + lo), 0.5 * (hi + 1.0));
    let cut = 0.5 * (below * (1.0 + lo) + above * (1.0 - hi));
    let mean =
        TAU * graded(&|mu| mu * pdf(mu), lo, hi, tol * 1e-3) + below * mid_lo + above * mid_hi;
    let closed = p.mean_cosine().to_f64();
    if !within(total - 1.0, tol) {
        return Err(format!("2π∫p dμ = {total}"));
    }
    if !within(mean - closed, tol + cut) {
        return Err(format!("mean cosine {mean} by quadrature, {closed} closed"));
    }
    Ok(())
}

/// `cdf(x)` is `2π ∫₋₁ˣ p dμ` (see [`integrable_span`] at the poles).
pub fn cdf_is_integral(p: &impl PhaseFunction<f64>) -> Check {
    let tol = QUAD_TOL;
    let pdf = |mu: f64| p.pdf(mu);
    let (lo, hi) = integrable_span(p);
    for x in [-1.0f64, -0.9, -0.5, -0.1, 0.0, 0.3, 0.7, 0.95, 0.999, 1.0] {
        let end = x.clamp(lo, hi);
        let rest = if x > hi { 1.0 - p.cdf(hi) } else { 0.0 };
        let num = p.cdf(lo) + TAU * graded(&pdf, lo, end, tol * 1e-3) + rest;
        let num = if x < lo { 0.0 } else { num };
        let got = p.cdf(x);
        if !within(got - num, tol) {
            return Err(format!("F({x}) = {got}, ∫ = {num}"));
        }
    }
    Ok(())
}

/// The f32 density and CDF are the f64 ones at every f32 argument tried
/// (a grid over `[−1, 1]` and the 2000 floats nearest each end): the pdf
/// within 32 ε₃₂ relative times its condition number `1 + |μ p′/p|` (an
/// f32 sum such as `1 + g² − 2gμ` rounds by ε, and a steep lobe's power
/// amplifies that), the CDF within 8 ε₃₂ plus what an ε₃₂-relative change
/// of `μ` moves it by, `2π p |μ| ε₃₂` times 4.
pub fn f32_density_follows_f64(
    p32: &impl PhaseFunction<f32>,
    p64: &impl PhaseFunction<f64>,
) -> Check {
    let eps = f32::EPSILON as f64;
    let near_ends = (1..=1000u32).flat_map(|k| {
        let below_one = f32::from_bits(1.0f32.to_bits() - k);
        [below_one, -below_one]
    });
    let grid = uniform_grid(20_001).map(|u| (2.0 * u - 1.0) as f32);
    for x in grid.chain(near_ends) {
        let (a, b) = (p32.pdf(x) as f64, p64.pdf(x as f64));
        let (m, h) = (x as f64, 1e-7);
        let slope = (p64.pdf((m + h).min(1.0)) - p64.pdf((m - h).max(-1.0))) / (2.0 * h);
        let cond = 1.0 + (m * slope / b).abs();
        // (Plus f32's smallest subnormal: where the density underflows
        // f32, its rounding is absolute.)
        if (a - b).abs() > 32.0 * eps * b * cond + f32::from_bits(1) as f64 {
            return Err(format!("pdf({x}): f32 {a}, f64 {b}"));
        }
        let (fa, fb) = (p32.cdf(x) as f64, p64.cdf(x as f64));
        if (fa - fb).abs() > 8.0 * eps + 4.0 * TAU * b * m.abs() * eps {
            return Err(format!("cdf({x}): f32 {fa}, f64 {fb}"));
        }
    }
    Ok(())
}

/// `sample_cos` is monotone with ends at ±1, clamps `u`, passes NaN, and
/// inverts `cdf`: `|F(μ(u)) − u|` within the rounding of F plus the
/// density times the inverse's documented error `mu_tol`.
pub fn inverse_monotone<T: Real>(p: &impl PhaseFunction<T>, mu_tol: f64) -> Check {
    let eps = T::EPSILON.to_f64();
    let ends = [
        (p.sample_cos(T::ZERO) + T::ONE).to_f64(),
        (T::ONE - p.sample_cos(T::ONE)).to_f64(),
    ];
    if ends.iter().any(|&e| e.abs() > mu_tol.max(2.0 * eps)) {
        return Err(format!("ends off ±1 by {ends:?}"));
    }
    if p.sample_cos(-T::ONE) != p.sample_cos(T::ZERO)
        || p.sample_cos(T::TWO) != p.sample_cos(T::ONE)
    {
        return Err("u outside [0, 1] is not clamped".into());
    }
    if !p.sample_cos(T::NAN).is_nan() {
        return Err("NaN in, not NaN out".into());
    }
    let mut prev = -T::ONE;
    for u in uniform_grid(100_001) {
        let u = T::from_f64(u);
        let mu = p.sample_cos(u);
        if mu < prev {
            return Err(format!("not monotone at u = {u:?}"));
        }
        prev = mu;
        let dens = TAU * p.pdf(mu).to_f64();
        let err = (p.cdf(mu).to_f64() - u.to_f64()).abs();
        if err > 8.0 * eps * (1.0 + dens) + dens * mu_tol {
            return Err(format!("|F(μ(u)) − u| = {err:e} at u = {u:?}"));
        }
    }
    Ok(())
}

/// The loops and the in-range form give `sample_cos`'s bits:
/// `sample_cos_each` at every `u` (outside `[0, 1]` and NaN too, clamped or
/// passed alike), and `sample_cos_in_range`, `sample_cos_each_in_range` and
/// `sample_cos_n` at `u` in `[0, 1]`, where the last also refuses a batch
/// with two bad uniforms (a check that cancels them in pairs would not).
pub fn batch_forms_agree<T: Real>(p: &impl PhaseFunction<T>) -> Check {
    let same = |a: T, b: T| a == b || (a.is_nan() && b.is_nan());
    let inside: Vec<T> = uniform_grid(1025)
        .map(T::from_f64)
        .chain([T::EPSILON, T::ONE - T::EPSILON])
        .collect();
    let mut all = inside.clone();
    all.extend([-T::HALF, T::TWO, T::INFINITY, -T::INFINITY, T::NAN]);
    let mut out = vec![T::NAN; all.len()];
    p.sample_cos_each(&all, &mut out);
    for (&u, &c) in all.iter().zip(&out) {
        if !same(c, p.sample_cos(u)) {
            return Err(format!("sample_cos_each differs at u = {u:?}"));
        }
    }
    let mut each = vec![T::NAN; inside.len()];
    p.sample_cos_each_in_range(&inside, &mut each);
    let mut n = vec![T::NAN; inside.len()];
    if p.sample_cos_n(&inside, &mut n).is_err() {
        return Err("sample_cos_n refused uniforms in [0, 1]".into());
    }
    for (i, &u) in inside.iter().enumerate() {
        let want = p.sample_cos(u);
        if ![p.sample_cos_in_range(u), each[i], n[i]]
            .iter()
            .all(|&c| same(c, want))
        {
            return Err(format!("an in-range form differs at u = {u:?}"));
        }
    }
    let two_bad = [-T::TWO, T::HALF, -T::TWO];
    if p.sample_cos_n(&two_bad, &mut [T::ZERO; 3]).is_ok() {
        return Err("sample_cos_n took two bad uniforms".into());
    }
    Ok(())
}

/// The density's support as documented: a `μ` up to 8 ulp beyond ±1 (the
/// rounding of a dot product of unit vectors) is read at ±1, one ulp
/// further it is 0.
pub fn pdf_support<T: Real>(p: &impl PhaseFunction<T>) -> Check {
    let eps = T::EPSILON;
    for pole in [T::ONE, -T::ONE] {
        let at = p.pdf(pole);
        for k in 1..=8 {
            let mu = pole + pole * T::from_f64(k as f64) * eps;
            let got = p.pdf(mu);
            if !(got == at || (got.is_nan() && at.is_nan())) {
                return Err(format!("pdf({mu:?}) = {got:?}, not pdf({pole:?}) = {at:?}"));
            }
        }
        let out = pole + pole * T::from_f64(9.0) * eps;
        if p.pdf(out) != T::ZERO {
            return Err(format!("pdf({out:?}) = {:?}, not 0", p.pdf(out)));
        }
    }
    Ok(())
}

/// The parameters a model reports rebuild it, and `from_params` refuses
/// one more or one fewer with `Error::Size` (isotropic's none included):
/// a model saved and restored, or handed through the C layer's params.
pub fn params_rebuild<T: Real>(p: &Phase<T>) -> Check {
    let (tag, n, stored) = p.params();
    if Phase::from_params(tag, &stored[..n]).as_ref() != Ok(p) {
        return Err(format!("params {:?} do not rebuild it", &stored[..n]));
    }
    let mut more = stored[..n].to_vec();
    more.push(T::HALF);
    if Phase::from_params(tag, &more) != Err(Error::Size) {
        return Err(format!("{} parameters were not refused", n + 1));
    }
    if n > 0 && Phase::from_params(tag, &stored[..n - 1]) != Err(Error::Size) {
        return Err(format!("{} parameters were not refused", n - 1));
    }
    Ok(())
}

fn unit<T: Real>(w: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(w[0]), T::from_f64(w[1]), T::from_f64(w[2]))
        .try_normalize()
        .unwrap()
}

/// Chi² of `CHI2_SAMPLES` directions about two incident directions
/// against `cdf64` (the model's CDF in f64: the cells' probabilities from
/// it, exact even where the density is infinite), at the suite's threshold.
pub fn chi2_sphere<T: Real>(
    p: &impl PhaseFunction<T>,
    cdf64: &dyn Fn(f64) -> f64,
    seed: u64,
) -> Check {
    for (k, w) in test_directions()
        .into_iter()
        .enumerate()
        .filter(|(k, _)| *k == 1 || *k == 4)
    {
        let w_in = unit::<T>(w);
        let mut r = rng(seed + 17 * k as u64);
        let w64 = [w_in.x.to_f64(), w_in.y.to_f64(), w_in.z.to_f64()];
        let cells = |lo, hi| cdf64(hi) - cdf64(lo);
        let res = chi2_directions_by_cells(&cells, w64, CHI2_SAMPLES, || {
            let (d, _) = p.sample_dir(w_in, T::uniform(&mut r), T::uniform(&mut r));
            [d.x.to_f64(), d.y.to_f64(), d.z.to_f64()]
        });
        if !res.passes() {
            return Err(format!(
                "about {w:?}: {res:?} (threshold {:.2e})",
                threshold()
            ));
        }
    }
    Ok(())
}

/// Directions are unit, at `sample_cos(u1)` from the incident one, and
/// come with the density of what was drawn: either `pdf` at the rounded
/// `cos θ` (within `8ε` relative), or, as HG reports it from the sampler's
/// own terms, the f64 model's density at its exact angle for the same `u1`
/// (`pdf_cos_sin` at the angle of `sample_cos_sin`)
/// (within `rel`).
pub fn sample_dir_consistent<T: Real>(
    p: &impl PhaseFunction<T>,
    p64: &impl PhaseFunction<f64>,
    rel: f64,
) -> Check {
    let tol = 8.0 * T::EPSILON.to_f64();
    let mut r = rng(3);
    for w in test_directions() {
        let w_in = unit::<T>(w);
        for _ in 0..5_000 {
            let (u1, u2) = (T::uniform(&mut r), T::uniform(&mut r));
            let (d, pdf) = p.sample_dir(w_in, u1, u2);
            let mu = p.sample_cos(u1);
            if (d.length().to_f64() - 1.0).abs() > tol {
                return Err(format!("|d| = {:?}", d.length()));
            }
            if (d.dot(w_in) - mu).abs().to_f64() > 2.0 * tol {
                return Err(format!("cos θ {:?}, sample_cos {mu:?}", d.dot(w_in)));
            }
            // The density at the sampled angle: `pdf` at its cosine, but
            // where a density infinite at a pole has its own reading of
            // the angle (`pdf_cos_sin`, Fournier–Forand's).
            let at_angle = |(m, s): (f64, f64)| p64.pdf_cos_sin(m, s);
            let own = p.pdf(mu).to_f64();
            let exact = at_angle(p64.sample_cos_sin(u1.to_f64()));
            let got = pdf.to_f64();
            if (got - own).abs() > tol * own && (got - exact).abs() > rel * exact {
                return Err(format!(
                    "pdf {got} with the direction, {own} from pdf, {exact} exact"
                ));
            }
        }
    }
    Ok(())
}

/// The f32 sampler within `tol` of the f64 one built from the same
/// (f32-rounded) parameters, over a grid of `u`.
pub fn f32_follows_f64(
    p32: &impl PhaseFunction<f32>,
    p64: &impl PhaseFunction<f64>,
    tol: f64,
) -> Check {
    for u in uniform_grid(20_001) {
        let u32 = u as f32;
        let (a, b) = (p32.sample_cos(u32) as f64, p64.sample_cos(u32 as f64));
        if (a - b).abs() > tol {
            return Err(format!("u = {u32}: f32 {a}, f64 {b}"));
        }
    }
    Ok(())
}

/// `sample_cos` at the golden uniforms gives the bits of the golden line
/// `name` (its first field per uniform, f32 and f64).
pub fn golden_bits(
    p32: &impl PhaseFunction<f32>,
    p64: &impl PhaseFunction<f64>,
    name: &str,
) -> Check {
    const US: [f64; 8] = [0.0, 1e-7, 0.1, 0.37, 0.5, 0.8125, 0.999999, 1.0];
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/golden/golden.txt"
    ))
    .unwrap();
    for (prec, width) in [("f32", 8), ("f64", 16)] {
        let key = format!("{name} {prec} ");
        let line = text
            .lines()
            .find_map(|l| l.strip_prefix(&key))
            .ok_or(format!("no golden line {key:?}"))?;
        for (u, field) in US.iter().zip(line.split(' ')) {
            let want = field.split(':').next().unwrap();
            let got = if width == 8 {
                format!("{:08x}", p32.sample_cos(*u as f32).to_bits())
            } else {
                format!("{:016x}", p64.sample_cos(*u).to_bits())
            };
            if got != want {
                return Err(format!("{name} {prec} u = {u}: {got}, golden {want}"));
            }
        }
    }
    Ok(())
}
