//! Each constructor's reach, found to the bit, and the contract held at
//! its ends. For every parameter of each constructor form in `reaches`
//! (the registry's models, the fog by its four parameters, the HG forms
//! set by moments, Fournier–Forand by backscatter, Schlick's fit to HG and
//! `Phase::particle`, and Fournier–Forand by its stored `(n, ν)` through
//! `Phase::from_params`; a mixture's weight in its own test below; the
//! Gegenbauer kernel by `γ` and `δ`, whose bands are measured, is swept in
//! `tests/models/gegenbauer.rs`), the others at a base set, bisection
//! over the ordered bit patterns between an accepted value and a refused
//! one finds the last accepted float and the first refused one, in f32
//! and in f64; each must be the edge the constructor's docs state
//! (closed: the edge is the last accepted; open: the first refused), and
//! values between the base and the edge must all be accepted (the
//! accepted set is an interval). Then, at the last accepted value and at
//! 2⁴ and 2²⁰ floats inside it, the parameters the model reports rebuild
//! it bit for bit, and the density, CDF and inverse keep the contract:
//! normalised (by a quadrature graded toward both poles), `cdf`
//! the integral of `pdf`, the inverse monotone and inverting `cdf`, the
//! f32 model following the f64 one of its own stored parameters (the
//! higher-precision oracle) at every f32 argument, and every sampler
//! finite and inside `[−1, 1]` (an HG lobe at `|g| = 1`, a Dirac limit,
//! takes the range checks alone: see `contract_at`).

use crate::checks::{self, Check};
use crate::common::{map_parallel, uniform_grid};
use crate::registry::{Model, models};
use scatterkit::mixture::{Mixture, Part};
use scatterkit::phase::schlick::Schlick;
use scatterkit::{Phase, PhaseFunction, Real};
use std::f64::consts::TAU;

/// One end of a documented parameter range.
#[derive(Clone, Copy, Debug)]
enum End {
    /// The value is accepted; the next float beyond it is not.
    Closed(f64),
    /// The value is refused; the float before it is accepted.
    Open(f64),
    /// The docs give a measured band, not a formula: the edge is found
    /// and the contract checked there, but not compared.
    Measured,
    /// Closed at the precision's smallest normal value
    /// (`MIN_POSITIVE`).
    SmallestNormal,
    /// Closed at minus it.
    MinusSmallestNormal,
}

/// A parameter's documented range at a base set of the others.
#[derive(Clone)]
struct Reach {
    model: Model,
    param: usize,
    base: &'static [f64],
    lo: End,
    hi: End,
}

const INF: f64 = f64::INFINITY;
/// The slack of the iterative inverses (as the registry's).
const ITERATIVE: (f64, f64) = (3e-7, 1e-13);

/// The forms the registry does not hold (it has one constructor per
/// model): the fog by its four parameters, the forms set by moments,
/// Fournier–Forand by backscatter, Schlick's fit to HG and the cheapest
/// model for a droplet diameter (`Phase::particle`).
fn more_forms() -> Vec<Model> {
    vec![
        model!("fog by parameters", |p| Phase::fog(p[0], p[1], p[2], p[3]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        model!("modified hg", |p| Phase::modified_hg(p[0], p[1]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        model!("modified hg by δ", |p| Phase::modified_hg_delta(p[0], p[1]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        model!("two-lobe hg by γ", |p| Phase::two_lobe_hg_gamma(p[0], p[1]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        model!("two-lobe hg by δ", |p| Phase::two_lobe_hg_delta(p[0], p[1]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        model!("fournier-forand by backscatter", |p| Phase::fournier_forand_backscatter(p[0], p[1]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        model!("schlick approximating hg", |p| Schlick::approximating_hg(p[0]).map(Phase::from), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        model!("particle", |p| Phase::particle(p[0], p[1]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
        // Tag 8 (`SK_PHASE_FOURNIER_FORAND`): (n, ν, b), b not read.
        model!("fournier-forand by params", |p| Phase::from_params(8, &[p[0], p[1], p[0]]), sets: &[], bad: &[], golden: ("", &[]), mu_tol: ITERATIVE),
    ]
}

/// HG's value `hg` of `γ` or `δ` with the documented 4ε of slack.
fn top(hg: f64) -> f64 {
    hg * (1.0 + 4.0 * f64::EPSILON)
}

/// Every documented range, as each constructor's docs state it.
fn reaches() -> Vec<Reach> {
    use End::{Closed, Measured, MinusSmallestNormal, Open, SmallestNormal};
    let all: Vec<Model> = models().into_iter().chain(more_forms()).collect();
    let m = |name: &str| *all.iter().find(|m| m.name == name).unwrap();
    let r = |name: &str, param: usize, base: &'static [f64], lo: End, hi: End| Reach {
        model: m(name),
        param,
        base,
        lo,
        hi,
    };
    vec![
        r("depolarised rayleigh", 0, &[0.5], Closed(0.0), Open(1.0)),
        r("henyey-greenstein", 0, &[0.5], Closed(-1.0), Closed(1.0)),
        r("draine", 0, &[0.5, 1.0], Open(-1.0), Open(1.0)),
        r("draine", 1, &[0.5, 1.0], Closed(0.0), Open(INF)),
        r("cornette-shanks", 0, &[0.6], Open(-1.0), Open(1.0)),
        r("fog", 0, &[10.0], Open(0.0), Closed(50.0)),
        r(
            "two-lobe hg",
            0,
            &[0.8, -0.3, 0.9],
            Closed(-1.0),
            Closed(1.0),
        ),
        r(
            "two-lobe hg",
            1,
            &[0.8, -0.3, 0.9],
            Closed(-1.0),
            Closed(1.0),
        ),
        r(
            "two-lobe hg",
            2,
            &[0.8, -0.3, 0.9],
            Closed(0.0),
            Closed(1.0),
        ),
        r("gegenbauer", 0, &[0.5, 0.3], Open(-0.5), Closed(1000.0)),
        r("gegenbauer", 1, &[0.5, 0.3], Open(-1.0), Open(1.0)),
        r("schlick", 0, &[0.5], Open(-1.0), Open(1.0)),
        r("fournier-forand", 0, &[1.1, 4.0], Open(1.0), Closed(1.8)),
        r("fournier-forand", 1, &[1.1, 4.0], Open(3.0), Open(5.0)),
        r(
            "fog by parameters",
            0,
            &[0.5, 0.3, 1.0, 0.5],
            Closed(-1.0),
            Closed(1.0),
        ),
        r(
            "fog by parameters",
            1,
            &[0.5, 0.3, 1.0, 0.5],
            Open(-1.0),
            Open(1.0),
        ),
        r(
            "fog by parameters",
            2,
            &[0.5, 0.3, 1.0, 0.5],
            Closed(0.0),
            Open(INF),
        ),
        r(
            "fog by parameters",
            3,
            &[0.5, 0.3, 1.0, 0.5],
            Closed(0.0),
            Closed(1.0),
        ),
        // The HG families' tops carry 4ε of slack (their module docs).
        r("modified hg", 1, &[0.5, 1.2], Measured, Closed(top(1.5))),
        // g over its whole range (γ = 0.8 ≤ 1 + g for every g > 0): refused
        // at 0; near 1, where g_HG rounds to 1, a measured edge.
        r("modified hg", 0, &[0.5, 0.8], Open(0.0), Measured),
        r(
            "modified hg by δ",
            1,
            &[0.5, 1.5],
            Open(1.0),
            Closed(top(1.75)),
        ),
        r(
            "two-lobe hg by γ",
            1,
            &[0.5, 1.2],
            Open(1.0),
            Closed(top(1.5)),
        ),
        r(
            "two-lobe hg by δ",
            1,
            &[0.5, 1.5],
            Open(1.0),
            Closed(top(1.75)),
        ),
        // The lower ends again at g = 0.1, where 1 − (1 − g) is not g:
        // at g = ½ the end's g_HG is exactly 1 and refused on that ground
        // alone, which hid a check on γ or δ taking the end itself (its
        // g_HG rounds below 1 at g = 0.1). The tops there: 1 + g rounded
        // in each precision, measured.
        r("two-lobe hg by γ", 1, &[0.1, 1.05], Open(1.0), Measured),
        r("two-lobe hg by δ", 1, &[0.1, 1.05], Open(1.0), Measured),
        r("modified hg by δ", 1, &[0.1, 1.05], Open(1.0), Measured),
        r(
            "fournier-forand by backscatter",
            0,
            &[0.1, 1.1],
            SmallestNormal,
            Open(0.5),
        ),
        r(
            "fournier-forand by backscatter",
            1,
            &[0.1, 1.1],
            Open(1.0),
            Closed(1.8),
        ),
        r("schlick approximating hg", 0, &[0.5], Open(-1.0), Open(1.0)),
        r("particle", 0, &[10.0, 0.05], Open(0.0), Closed(50.0)),
        r("particle", 1, &[10.0, 0.05], Open(0.0), Open(1.0)),
        r(
            "fournier-forand by params",
            0,
            &[1.1, -0.5],
            Open(1.0),
            Closed(1.8),
        ),
        r(
            "fournier-forand by params",
            1,
            &[1.1, -0.5],
            Open(-1.0),
            MinusSmallestNormal,
        ),
    ]
}

/// A float whose bit patterns can be walked in order, and the registry's
/// builder for its precision.
pub(crate) trait Walk: Real {
    /// A key increasing with the value (−0 and +0 share 0).
    fn key(self) -> i64;
    fn from_key(k: i64) -> Self;
    /// `m` built in this precision from f64 parameters (rounded to it).
    fn build(m: &Model, p: &[f64]) -> Option<Phase<Self>>;
}

impl Walk for f64 {
    fn key(self) -> i64 {
        let b = self.to_bits() as i64;
        if b < 0 { i64::MIN - b } else { b }
    }
    fn from_key(k: i64) -> Self {
        f64::from_bits((if k < 0 { i64::MIN - k } else { k }) as u64)
    }
    fn build(m: &Model, p: &[f64]) -> Option<Phase<Self>> {
        (m.f64)(p).ok()
    }
}

impl Walk for f32 {
    fn key(self) -> i64 {
        let b = self.to_bits() as i32;
        (if b < 0 { i32::MIN - b } else { b }) as i64
    }
    fn from_key(k: i64) -> Self {
        let k = k as i32;
        f32::from_bits((if k < 0 { i32::MIN - k } else { k }) as u32)
    }
    fn build(m: &Model, p: &[f64]) -> Option<Phase<Self>> {
        (m.f32)(p).ok()
    }
}

/// The model of `reach` in precision `T` with parameter `param` at `x`.
fn build<T: Walk>(reach: &Reach, x: T) -> Option<Phase<T>> {
    let mut p = reach.base.to_vec();
    p[reach.param] = x.to_f64();
    T::build(&reach.model, &p)
}

/// `(last accepted, first refused)`: adjacent floats between the accepted
/// `good` and the refused `bad`.
pub(crate) fn edge<T: Walk>(ok: &dyn Fn(T) -> bool, mut good: T, mut bad: T) -> (T, T) {
    while (good.key() as i128 - bad.key() as i128).abs() > 1 {
        let mid = T::from_key(((good.key() as i128 + bad.key() as i128) / 2) as i64);
        if ok(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    (good, bad)
}

/// A value beyond the documented end `end` on the side `dir` (±1).
fn beyond<T: Walk>(end: End, base: T, dir: f64) -> T {
    match end {
        End::Closed(x) | End::Open(x) if x.is_infinite() => T::from_f64(x),
        End::Closed(x) | End::Open(x) => T::from_f64(x + dir * x.abs().max(1.0)),
        End::SmallestNormal | End::MinusSmallestNormal => T::from_f64(dir),
        End::Measured => base + T::from_f64(dir * base.to_f64().abs().max(1.0)),
    }
}

/// The edge of `reach` on side `dir` in precision `T`, checked against
/// its docs and for the interval between it and the base.
fn found_edge<T: Walk>(reach: &Reach, dir: f64) -> Result<T, String> {
    let ok = |x: T| build::<T>(reach, x).is_some();
    let base = T::from_f64(reach.base[reach.param]);
    let end = if dir < 0.0 { reach.lo } else { reach.hi };
    let far = beyond::<T>(end, base, dir);
    if ok(far) {
        return Err(format!("{far:?}, beyond the documented end, is accepted"));
    }
    let (last, first) = edge(&ok, base, far);
    let want = |x: f64| T::from_f64(x);
    match end {
        End::Closed(x) if last != want(x) => {
            return Err(format!(
                "closed at {x}: last accepted {last:?}, first refused {first:?}"
            ));
        }
        End::Open(x) if first != want(x) => {
            return Err(format!(
                "open at {x}: last accepted {last:?}, first refused {first:?}"
            ));
        }
        End::SmallestNormal if last != T::MIN_POSITIVE => {
            return Err(format!(
                "closed at the smallest normal: last accepted {last:?}, first refused {first:?}"
            ));
        }
        End::MinusSmallestNormal if last != -T::MIN_POSITIVE => {
            return Err(format!(
                "closed at minus the smallest normal: last accepted {last:?}, first refused {first:?}"
            ));
        }
        _ => {}
    }
    // The accepted set between the base and the edge is an interval:
    // values spread evenly in bit patterns (every scale) and in value.
    let (kb, ke) = (base.key(), last.key());
    for i in 0..=256i128 {
        let by_bits = T::from_key((kb as i128 + (ke as i128 - kb as i128) * i / 256) as i64);
        // Rounded, `base + (last − base)` can land one float past `last`.
        let by_value = base + (last - base) * T::from_f64(i as f64 / 256.0);
        let by_value = T::from_key(by_value.key().clamp(kb.min(ke), kb.max(ke)));
        for x in [by_bits, by_value] {
            if !ok(x) {
                return Err(format!(
                    "{x:?} refused between the base and the edge {last:?}"
                ));
            }
        }
    }
    Ok(last)
}

/// `(reach, side)` of every range end.
fn ends() -> Vec<(Reach, f64)> {
    reaches()
        .into_iter()
        .flat_map(|r| [(r.clone(), -1.0), (r, 1.0)])
        .collect()
}

fn describe(r: &Reach, dir: f64) -> String {
    let side = if dir < 0.0 { "low" } else { "high" };
    format!("{} parameter {} ({side} end)", r.model.name, r.param)
}

/// Runs `in_f32` and `in_f64` on every end and fails listing every
/// failure, each marked with its precision.
fn on_every_end(what: &str, in_f32: fn(&Reach, f64) -> Check, in_f64: fn(&Reach, f64) -> Check) {
    let ends = ends();
    let failures: Vec<String> = map_parallel(&ends, |(r, dir)| {
        let found: Vec<String> = [("f32", in_f32), ("f64", in_f64)]
            .into_iter()
            .filter_map(|(name, check)| check(r, *dir).err().map(|e| format!("{name}: {e}")))
            .collect();
        (!found.is_empty()).then(|| format!("{}: {}", describe(r, *dir), found.join("; ")))
    })
    .into_iter()
    .flatten()
    .collect();
    assert!(failures.is_empty(), "{what}:\n{}", failures.join("\n"));
}

#[test]
fn every_parameter_reaches_exactly_its_documented_edge() {
    on_every_end(
        "reach",
        |r, dir| found_edge::<f32>(r, dir).map(|_| ()),
        |r, dir| found_edge::<f64>(r, dir).map(|_| ()),
    );
}

/// The float steps from an end `last` toward `base` at which a sweep
/// checks the contract: 0, 2⁴ and 2²⁰, or (`dense`) 0 and `2^j` for `j =
/// 0, 2, 4, …, 40`; only those short of the base.
pub(crate) fn steps_inside<T: Walk>(last: T, base: T, dense: bool) -> Vec<i64> {
    let span = (last.key() as i128 - base.key() as i128).unsigned_abs();
    let powers: Vec<u32> = if dense {
        (0..=40).step_by(2).collect()
    } else {
        vec![4, 20]
    };
    let short = powers
        .into_iter()
        .map(|j| 1i64 << j)
        .filter(|&k| (k as u128) < span);
    [0].into_iter().chain(short).collect()
}

/// The floats `k` steps inside `last` (toward `base`), for the ladder.
pub(crate) fn inside<T: Walk>(last: T, base: T, k: i64) -> T {
    let step = if base.key() < last.key() { -k } else { k };
    T::from_key(last.key() + step)
}

/// The float of precision `T` just below `x` (a value of `T`).
fn one_ulp_below<T: Walk>(x: f64) -> f64 {
    T::from_key(T::from_f64(x).key() - 1).to_f64()
}

/// A phase function with a lobe-by-lobe sampler besides its inverse.
trait ByLobe<T: Real>: PhaseFunction<T> {
    fn by_lobe(&self, u: T) -> T;
}

impl<T: Real> ByLobe<T> for Phase<T> {
    fn by_lobe(&self, u: T) -> T {
        self.sample_cos_by_lobe(u)
    }
}

impl<T: Real> ByLobe<T> for Mixture<'_, T> {
    fn by_lobe(&self, u: T) -> T {
        self.sample_cos_by_lobe(u)
    }
}

/// Every sampler finite and in `[−1, 1]`, the density finite and ≥ 0, the
/// CDF in `[0, 1]` and non-decreasing with ends 0 and 1.
fn finite_in_range<T: Walk>(p: &impl ByLobe<T>) -> Check {
    let eps = T::EPSILON.to_f64();
    let near_ends = (0..64).flat_map(|k| {
        let x = 1.0 - eps * k as f64 / 2.0;
        [-x, x]
    });
    let mut mus: Vec<f64> = uniform_grid(2001)
        .map(|u| 2.0 * u - 1.0)
        .chain(near_ends)
        .collect();
    mus.sort_by(f64::total_cmp);
    let mut prev = 0.0;
    for &m in &mus {
        let mu = T::from_f64(m);
        let (d, c) = (p.pdf(mu).to_f64(), p.cdf(mu).to_f64());
        if d.is_nan() || d < 0.0 {
            return Err(format!("pdf({m}) = {d}"));
        }
        // One ulp of the previous value of slack for monotone, subnormal
        // values included. (HG's and Schlick's stepped back by up to five
        // ulps of 1 near F = 1 as |g| → 1 when this sweep first allowed
        // none; both now take the upper tail there. Fournier–Forand's CDF
        // wandered by tens of subnormals near F = 0 at b = 5·10⁻³²⁴, its ν
        // subnormal; such b are now refused.)
        if !(0.0..=1.0).contains(&c) || c < one_ulp_below::<T>(prev) {
            return Err(format!("cdf({m}) = {c} after {prev}"));
        }
        prev = c;
    }
    // (A Dirac limit at μ = −1 has all its mass there: F(−1) = 1.)
    let (lo, hi) = (p.cdf(-T::ONE), p.cdf(T::ONE));
    if (lo != T::ZERO && p.pdf(-T::ONE).to_f64().is_finite()) || hi != T::ONE {
        return Err(format!("cdf(−1) = {lo:?}, cdf(1) = {hi:?}"));
    }
    let us = uniform_grid(4001).chain([eps / 4.0, 1.0 - eps / 4.0]);
    for u in us {
        let u = T::from_f64(u);
        for (what, mu) in [("sample_cos", p.sample_cos(u)), ("by_lobe", p.by_lobe(u))] {
            if mu.is_nan() || mu.to_f64().abs() > 1.0 {
                return Err(format!("{what}({u:?}) = {mu:?}"));
            }
        }
    }
    Ok(())
}

/// Whether parameter `x` of `r` at ±1 is an HG lobe's `g` (HG alone, either
/// lobe of the two-lobe HG, the fog's HG lobe).
fn dirac_limit(r: &Reach, x: f64) -> bool {
    let lobe = matches!(
        (r.model.name, r.param),
        ("henyey-greenstein", 0) | ("two-lobe hg", 0 | 1) | ("fog by parameters", 0)
    );
    lobe && x.abs() == 1.0
}

/// The contract at one parameter set near an edge, in precision `T`
/// (the f64 checks against quadrature for f64; the f32 model against the
/// f64 one of the same, f32-rounded, parameters for f32).
fn contract_at<T: Walk>(r: &Reach, x: T) -> Check {
    let Some(p) = build::<T>(r, x) else {
        return Err(format!("{x:?} refused"));
    };
    checks::params_rebuild(&p)?;
    finite_in_range(&p)?;
    let mut params = r.base.to_vec();
    params[r.param] = x.to_f64();
    let p64 = f64::build(&r.model, &params).ok_or("the f64 twin refused")?;
    // An HG lobe at |g| = 1 is a Dirac limit, with no density to check:
    // the range checks alone. (Fournier–Forand's integrable power law is
    // infinite at μ = 1 too, and takes every check.)
    if dirac_limit(r, x.to_f64()) {
        return Ok(());
    }
    let (top, bottom) = (p64.pdf(1.0), p64.pdf(-1.0));
    if T::EPSILON.to_f64() == f64::EPSILON {
        checks::inverse_monotone(&p64, r.model.mu_tol.1)?;
        // A lobe narrower than the floats at its pole puts more than the
        // quadrature's tolerance into one float's span there: no
        // quadrature over f64 arguments can see it (Draine at 1 − g =
        // 2⁻⁵³: width 10⁻³², spacing 10⁻¹⁶).
        // (An infinite pole is integrated from the CDF: see
        // `checks::normalised`.)
        let finite = |d: f64| if d.is_finite() { d } else { 0.0 };
        let cell = TAU * (finite(top) * f64::EPSILON / 2.0).max(finite(bottom) * f64::EPSILON);
        if cell <= checks::QUAD_TOL {
            checks::normalised(&p64)?;
            checks::cdf_is_integral(&p64)?;
        }
    } else {
        // The f64 twin holds the f32 model's own stored parameters: a
        // form set by moments stores derived ones (`g_HG`, `β`), and near
        // its edge their rounding to f32 is the model's, not an error.
        let p32 = f32::build(&r.model, &params).ok_or("f32 refused")?;
        checks::inverse_monotone(&p32, r.model.mu_tol.0)?;
        checks::f32_density_follows_f64(&p32, &p32.cast::<f64>())?;
    }
    Ok(())
}

/// The contract at each end's last accepted value and 2⁴ and 2²⁰ floats
/// inside it.
fn contract_near<T: Walk>(r: &Reach, dir: f64) -> Check {
    contract_inside::<T>(r, dir, false)
}

/// [`contract_near`], or (`dense`) at `2^j` floats inside for every even
/// `j` up to 40.
fn contract_inside<T: Walk>(r: &Reach, dir: f64, dense: bool) -> Check {
    let end = if dir < 0.0 { r.lo } else { r.hi };
    if matches!(end, End::Open(x) | End::Closed(x) if x.is_infinite()) {
        return Ok(());
    }
    let last = found_edge::<T>(r, dir)?;
    let base = T::from_f64(r.base[r.param]);
    for k in steps_inside(last, base, dense) {
        let x = inside(last, base, k);
        contract_at(r, x).map_err(|e| format!("at {x:?}: {e}"))?;
    }
    Ok(())
}

#[test]
fn the_contract_holds_at_every_edge() {
    on_every_end("at the edges", contract_near::<f32>, contract_near::<f64>);
}

/// The same at 2⁰, 2², …, 2⁴⁰ floats inside every end (run with
/// `--ignored`).
#[test]
#[ignore]
fn the_contract_holds_inside_every_edge_densely() {
    on_every_end(
        "inside the edges",
        |r, dir| contract_inside::<f32>(r, dir, true),
        |r, dir| contract_inside::<f64>(r, dir, true),
    );
}

/// A mixture's weight: finite and `≥ 0` beside a part of weight 1
/// (`Mixture::new`), so the reach is `[0, MAX]` (`MAX + 1` rounds to
/// `MAX`, a finite total); bisected to the bit like the constructors
/// above, the accepted set an interval, and the contract at 0, at `MAX`
/// and at 2⁰, 2², …, 2⁴⁰ floats inside each end
/// (a part of weight 0; one of weight 10⁻³²⁴ beside 1; a part of 1 beside
/// `MAX`, its normalised weight subnormal).
#[test]
fn a_mixture_weight_reaches_zero_and_the_largest_float() {
    fn mixture<T: Walk>(w: T) -> Result<Mixture<'static, T>, scatterkit::Error> {
        let hg = Phase::henyey_greenstein(T::from_f64(0.7)).unwrap();
        Mixture::new(&[
            (Part::Phase(hg), w),
            (Part::Phase(Phase::rayleigh()), T::ONE),
        ])
    }
    fn sweep<T: Walk>() -> Check {
        let ok = |w: T| mixture(w).is_ok();
        let one = T::ONE;
        let (low, below) = edge(&ok, one, T::from_f64(-1.0));
        let (high, above) = edge(&ok, one, T::INFINITY);
        if low.key() != 0 || below.key() != -1 || above != T::INFINITY {
            return Err(format!("ends {below:?} | {low:?} … {high:?} | {above:?}"));
        }
        for end in [low, high] {
            let (kb, ke) = (one.key(), end.key());
            for i in 0..=256i128 {
                let w = T::from_key((kb as i128 + (ke as i128 - kb as i128) * i / 256) as i64);
                if !ok(w) {
                    return Err(format!("{w:?} refused between 1 and {end:?}"));
                }
            }
            for k in steps_inside(end, one, true) {
                let w = inside(end, one, k);
                let m = mixture(w).map_err(|e| format!("{w:?}: {e:?}"))?;
                finite_in_range(&m).map_err(|e| format!("at {w:?}: {e}"))?;
                let m64 = mixture(w.to_f64()).map_err(|e| format!("{w:?} in f64: {e:?}"))?;
                checks::normalised(&m64).map_err(|e| format!("at {w:?}: {e}"))?;
                checks::cdf_is_integral(&m64).map_err(|e| format!("at {w:?}: {e}"))?;
                checks::inverse_monotone(&m64, ITERATIVE.1)
                    .map_err(|e| format!("at {w:?}: {e}"))?;
            }
        }
        Ok(())
    }
    let found: Vec<String> = [
        ("f32", sweep::<f32> as fn() -> Check),
        ("f64", sweep::<f64>),
    ]
    .into_iter()
    .filter_map(|(name, f)| f().err().map(|e| format!("{name}: {e}")))
    .collect();
    assert!(found.is_empty(), "{}", found.join("\n"));
}
