//! The media constructors' reach, found to the bit as `reach.rs` finds the
//! phase functions': for each scalar parameter of `Grid::new` (σ_a, σ_s,
//! the largest density), `Grid::with_box` (a face on each side),
//! `Majorants::new` (a cell's value, beside cells of 1, or of 0 and the
//! largest float), `Extrema::new` (a cell's minorant and majorant), the
//! one majorant of
//! `one_majorant_*_track`, spectral tracking (the hero's coefficients,
//! the density), `Equiangular::new` (the point's distance, the segment's
//! end), and `free_path` and `transmittance` (whose refusal is NaN),
//! bisection over the ordered bit patterns finds the last accepted float
//! and the first refused one, in f32 and f64; each must be the edge the
//! docs state, NaN must be refused, and values between the base and the
//! edge must all be accepted (the accepted set is an interval). At the
//! last accepted value and 2⁰, 2², …, 2⁴⁰ floats inside it, what was built
//! must work: densities within the grid's majorant; delta and ratio
//! tracking (by the grid's one majorant, by majorants built on it, and
//! spectral, every output finite and `≥ 0`) ending in the segment with a
//! transmittance in `[0, 1]`, or in `Error::Budget` (a majorant optical
//! depth past the budget), never `Error::Domain` for an accepted medium
//! and a valid ray; residual ratio tracking, both ray marchers, signed
//! ratio and weighted delta tracking and emission finite, or refused as
//! their docs say; equiangular distances monotone within the segment with
//! finite densities; free paths `≥ 0` and non-decreasing in `u`,
//! transmittance in `[0, 1]`.

use crate::checks::Check;
use crate::common::map_parallel;
use crate::reach::{Walk, edge, inside, steps_inside};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;
use scatterkit::medium::equiangular::Equiangular;
use scatterkit::medium::majorant::{one_majorant_delta_track, one_majorant_ratio_track};
use scatterkit::medium::ray_march::{ray_march_transmittance, telescoping_transmittance};
use scatterkit::medium::residual::Extrema;
use scatterkit::medium::spectral::{Ratios, Spectrum};
use scatterkit::medium::{Event, free_path, transmittance};
use scatterkit::{Error, Grid, Majorants, Ray, Vec3};

/// A constructor form and its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Form {
    /// `Grid::new` of 2 × 2 × 2 values: `[σ_a, σ_s, v]`, the values `v`,
    /// `v/2`, 0 and 1 (so `v` is the largest above 1).
    Grid,
    /// `Grid::with_box` of that grid (σ_a = σ_s = ½, `v` = 2): `[lo_z,
    /// hi_z]`, x and y on `[0, 1]`.
    GridBox,
    /// `Majorants::new` on a 2 × 1 × 1 division of the unit cube: `[s]`,
    /// the first cell's value (the second's 1).
    Majorants,
    /// `Majorants::new` on a 3 × 1 × 1 division of the unit cube with
    /// cells of every kind beside each other: `[s]`, the first cell's
    /// value, then 0 (nothing to collide with) and the largest float.
    MajorantsMixed,
    /// `Extrema::new` on the 2 × 1 × 1 division: `[min, max]`, the first
    /// cell's minorant and majorant (the second cell's ½ and 1).
    Extrema,
    /// `one_majorant_delta_track`'s and `one_majorant_ratio_track`'s
    /// majorant: `[σ_maj]`.
    OneMajorant,
    /// `free_path`: `[σ_t]`.
    FreePath,
    /// `transmittance`: `[σ_t, distance]`.
    Transmittance,
    /// Spectral (hero-wavelength) tracking: the hero channel's `[σ_a, σ_s]`
    /// per unit density, beside a channel of (½, ½), and `s`, through
    /// [`Form::Grid`]'s values at `v` = 2 times `s`, by their density
    /// majorants.
    Spectral,
    /// `Equiangular::new` on the ray from the origin along x over
    /// `[0, t_max]` toward the point `(½, Δ, 0)`: `[Δ, t_max]`.
    Equiangular,
}

/// One end of a documented range, in the precision at hand.
#[derive(Clone, Copy, Debug)]
enum End {
    /// The value is accepted; the next float beyond it is not.
    Closed(f64),
    /// The value is refused; the float before it is accepted.
    Open(f64),
    /// Closed at the largest finite float.
    Largest,
    /// Closed at minus it.
    MinusLargest,
    /// Where the grid's majorant `(σ_a + σ_s)·max·(1 + 4ε)` overflows
    /// (`Grid::new`'s docs): the last value keeping it finite.
    MajorantFinite,
    /// The smallest extent `hi − lo > 0` whose reciprocal is finite
    /// (`Grid::with_box`'s docs), as a face's value at the other's base.
    ExtentReciprocal,
    /// Where `σ_a + σ_s` of the parameters overflows (the spectral
    /// calls' docs): the last value keeping it finite.
    SumFinite,
    /// The smallest positive value whose square is not 0 (`Δ²`
    /// underflows below it: `Equiangular::new`'s docs).
    SquarePositive,
    /// The largest value whose square is finite.
    SquareFinite,
    /// Found and checked, but not compared (the docs give the rule, not
    /// the value: a box whose extent overflows).
    Measured,
}

/// A parameter's documented range at a base set of the others.
#[derive(Clone, Copy, Debug)]
struct Reach {
    form: Form,
    param: usize,
    base: &'static [f64],
    lo: End,
    hi: End,
}

const INF: f64 = f64::INFINITY;

fn reaches() -> Vec<Reach> {
    use End::*;
    let r = |form, param, base, lo, hi| Reach {
        form,
        param,
        base,
        lo,
        hi,
    };
    vec![
        r(Form::Grid, 0, &[0.5, 0.5, 2.0], Closed(0.0), MajorantFinite),
        r(Form::Grid, 1, &[0.5, 0.5, 2.0], Closed(0.0), MajorantFinite),
        r(Form::Grid, 2, &[0.5, 0.5, 2.0], Closed(0.0), MajorantFinite),
        // A face on each side; a box of extent near the largest float.
        r(Form::GridBox, 0, &[0.0, 1.0], MinusLargest, Open(1.0)),
        r(Form::GridBox, 1, &[0.0, 1.0], ExtentReciprocal, Largest),
        r(Form::GridBox, 0, &[0.0, f64::MAX], Measured, Open(f64::MAX)),
        r(Form::Majorants, 0, &[1.0], Closed(0.0), Largest),
        r(Form::MajorantsMixed, 0, &[1.0], Closed(0.0), Largest),
        // A minorant up to its cell's majorant; a majorant from the
        // minorant up.
        r(Form::Extrema, 0, &[0.5, 1.0], Closed(0.0), Closed(1.0)),
        r(Form::Extrema, 1, &[0.5, 1.0], Closed(0.5), Largest),
        r(Form::Extrema, 0, &[0.5, f64::MAX], Closed(0.0), Largest),
        r(Form::OneMajorant, 0, &[1.0], Closed(0.0), Largest),
        r(Form::FreePath, 0, &[1.0], Closed(0.0), Largest),
        r(
            Form::Transmittance,
            0,
            &[1.0, 1.0],
            Closed(0.0),
            Closed(INF),
        ),
        r(
            Form::Transmittance,
            1,
            &[1.0, 1.0],
            Closed(0.0),
            Closed(INF),
        ),
        // Density majorants below ¼: the coefficients' sum overflows first.
        r(Form::Spectral, 0, &[1.0, 1.0, 0.125], Closed(0.0), Largest),
        r(Form::Spectral, 1, &[1.0, 1.0, 0.125], Closed(0.0), Largest),
        r(
            Form::Spectral,
            0,
            &[1.0, f64::MAX, 0.125],
            Closed(0.0),
            SumFinite,
        ),
        // Up to 2: a channel's majorant `(σ_a + σ_s)·σ_maj` overflows first.
        r(Form::Spectral, 0, &[1.0, 1.0, 2.0], Closed(0.0), Measured),
        r(Form::Spectral, 2, &[1.0, 1.0, 2.0], Closed(0.0), Measured),
        r(
            Form::Equiangular,
            0,
            &[1.0, 1.0],
            SquarePositive,
            SquareFinite,
        ),
        // Short segments: the peak density overflows first (measured).
        r(Form::Equiangular, 1, &[1.0, 1.0], Measured, Closed(INF)),
    ]
}

/// The largest finite float of `T`.
fn largest<T: Walk>() -> T {
    T::from_key(T::INFINITY.key() - 1)
}

/// A base value or documented end in precision `T`: `f64::MAX` stands for
/// the precision's largest finite float.
fn t_of<T: Walk>(x: f64) -> T {
    if x == f64::MAX {
        largest()
    } else {
        T::from_f64(x)
    }
}

/// The parameters of `reach` in precision `T`.
fn base_of<T: Walk>(reach: &Reach) -> Vec<T> {
    reach.base.iter().map(|&x| t_of(x)).collect()
}

/// The 2 × 2 × 2 values of [`Form::Grid`] with largest value `v`.
fn values<T: Walk>(v: T) -> [T; 8] {
    let (z, o) = (T::ZERO, T::ONE);
    [v, v * T::HALF, z, o, o, z, v * T::HALF, o]
}

/// `(σ_a, σ_s, values, lo, hi)` of the grid forms at parameters `p`.
type GridParts<T> = (T, T, [T; 8], Vec3<T>, Vec3<T>);

fn grid_parts<T: Walk>(form: Form, p: &[T]) -> GridParts<T> {
    let (z, o) = (T::ZERO, T::ONE);
    match form {
        Form::Grid => (
            p[0],
            p[1],
            values(p[2]),
            Vec3::new(z, z, z),
            Vec3::new(o, o, o),
        ),
        _ => (
            T::HALF,
            T::HALF,
            values(T::TWO),
            Vec3::new(z, z, p[0]),
            Vec3::new(o, o, p[1]),
        ),
    }
}

/// Whether the form accepts `p` (a function's refusal is NaN).
fn accepts<T: Walk>(form: Form, p: &[T]) -> bool {
    let (z, o) = (T::ZERO, T::ONE);
    match form {
        Form::Grid | Form::GridBox => {
            let (sa, ss, v, lo, hi) = grid_parts(form, p);
            Grid::new(&v, 2, 2, 2, sa, ss)
                .and_then(|g| g.with_box(lo, hi))
                .is_ok()
        }
        Form::Majorants => Majorants::new(
            &[p[0], o],
            [2, 1, 1],
            Vec3::new(z, z, z),
            Vec3::new(o, o, o),
        )
        .is_ok(),
        Form::MajorantsMixed => mixed(&[p[0], z, largest()]).is_ok(),
        Form::Extrema => {
            let (max, min) = ([p[1], o], [p[0], T::HALF]);
            extrema(&max, &min).is_ok()
        }
        Form::OneMajorant => {
            let ray = Ray::new(Vec3::new(z, z, z), Vec3::new(z, z, o), o);
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
            let vacuum = |_: Vec3<T>| (z, z);
            one_majorant_delta_track(vacuum, p[0], ray, 1, &mut rng).err() != Some(Error::Domain)
        }
        Form::FreePath => !free_path(p[0], T::HALF).is_nan(),
        Form::Equiangular => equiangular(p).is_ok(),
        Form::Spectral => {
            let ray = Ray::new(
                Vec3::new(T::HALF, T::HALF, T::HALF),
                Vec3::new(o, z, z),
                T::INFINITY,
            );
            spectral(p, ray, 1, true).err() != Some(Error::Domain)
        }
        Form::Transmittance => !transmittance(p[0], p[1]).is_nan(),
    }
}

/// The documented edge `end` of `reach` in precision `T`, if it names one.
fn documented<T: Walk>(reach: &Reach, end: End, far: T) -> Option<T> {
    let base = base_of::<T>(reach);
    match end {
        End::Closed(x) | End::Open(x) => Some(t_of(x)),
        End::Largest => Some(largest()),
        End::MinusLargest => Some(-largest::<T>()),
        End::MajorantFinite => {
            // The docs' rule, evaluated on its own: σ_t·max·(1 + 4ε) finite.
            let rule = |x: T| {
                let mut q = base.clone();
                q[reach.param] = x;
                let max = q[2].max_of(T::ONE);
                ((q[0] + q[1]) * max * (T::ONE + T::from_f64(4.0) * T::EPSILON)).is_finite()
            };
            Some(edge(&rule, base[reach.param], far).0)
        }
        End::ExtentReciprocal => {
            let other = base[1 - reach.param];
            let rule = |x: T| {
                let e = if reach.param == 1 {
                    x - other
                } else {
                    other - x
                };
                e > T::ZERO && (T::ONE / e).is_finite()
            };
            Some(edge(&rule, base[reach.param], other).0)
        }
        End::SumFinite => {
            let other = base[1 - reach.param];
            Some(edge(&|x: T| (x + other).is_finite(), base[reach.param], far).0)
        }
        End::SquarePositive => Some(edge(&|x: T| x * x > T::ZERO, T::ONE, T::ZERO).0),
        End::SquareFinite => Some(edge(&|x: T| (x * x).is_finite(), T::ONE, far).0),
        End::Measured => None,
    }
}

/// A value beyond the end `end` on side `dir` (±1).
fn beyond<T: Walk>(end: End, dir: f64) -> T {
    match end {
        End::Closed(x) | End::Open(x) if x.is_infinite() => T::from_f64(x),
        End::Closed(x) | End::Open(x) => T::from_f64(x + dir * x.abs().max(1.0)),
        // Δ and −Δ are the same point's distance: the low end is where
        // the square underflows on the positive side.
        End::SquarePositive => T::ZERO,
        _ => T::from_f64(dir * INF),
    }
}

/// The last accepted value of `reach` on side `dir`, checked against the
/// docs, for NaN and for the interval between it and the base.
fn found_edge<T: Walk>(reach: &Reach, dir: f64) -> Result<T, String> {
    let at = |x: T| {
        let mut p = base_of::<T>(reach);
        p[reach.param] = x;
        p
    };
    let ok = |x: T| accepts(reach.form, &at(x));
    if ok(T::NAN) {
        return Err("NaN is accepted".into());
    }
    let base = base_of::<T>(reach)[reach.param];
    let end = if dir < 0.0 { reach.lo } else { reach.hi };
    let far = beyond::<T>(end, dir);
    let last = match end {
        End::Closed(x) if x.is_infinite() => {
            return if ok(far) {
                Ok(far)
            } else {
                Err(format!("{far:?} refused"))
            };
        }
        _ if ok(far) => return Err(format!("{far:?}, beyond the documented end, is accepted")),
        _ => {
            let (last, first) = edge(&ok, base, far);
            let want = documented::<T>(reach, end, far);
            let wanted = match end {
                End::Open(_) => first,
                _ => last,
            };
            if want.is_some_and(|w| w != wanted) {
                return Err(format!(
                    "{end:?}: want {want:?}; last accepted {last:?}, first refused {first:?}"
                ));
            }
            last
        }
    };
    let (kb, ke) = (base.key(), last.key());
    for i in 0..=256i128 {
        let x = T::from_key((kb as i128 + (ke as i128 - kb as i128) * i / 256) as i64);
        if !ok(x) {
            return Err(format!(
                "{x:?} refused between the base and the edge {last:?}"
            ));
        }
    }
    Ok(last)
}

/// Rays through the grid's box from its centre and from its low corner,
/// in eight directions, to +∞ (the box bounds them).
fn rays<T: Walk>(lo: Vec3<T>, hi: Vec3<T>) -> Vec<Ray<T>> {
    let mid = |a: T, b: T| a * T::HALF + b * T::HALF;
    let centre = Vec3::new(mid(lo.x, hi.x), mid(lo.y, hi.y), mid(lo.z, hi.z));
    let mut out = Vec::new();
    for k in 0..8 {
        let s = |bit: usize| if k >> bit & 1 == 0 { T::ONE } else { -T::ONE };
        let d = Vec3::new(s(0), s(1), s(2) * T::HALF);
        out.push(Ray::new(centre, d, T::INFINITY));
    }
    out.push(Ray::new(
        lo,
        Vec3::new(T::ONE, T::HALF, T::from_f64(0.25)),
        T::INFINITY,
    ));
    out
}

/// A tracking call's outcome: in the segment, or out of budget.
fn tracked<T: Walk>(what: &str, r: Result<(T, bool), Error>, ray: &Ray<T>) -> Check {
    match r {
        Ok((t, _)) if t >= ray.t_min && t <= ray.t_max => Ok(()),
        Err(Error::Budget) => Ok(()),
        other => Err(format!("{what} along {ray:?}: {other:?}")),
    }
}

/// A transmittance estimate's outcome: in `[0, 1]`, or out of budget.
fn estimated<T: Walk>(what: &str, r: Result<T, Error>, ray: &Ray<T>) -> Check {
    match r {
        Ok(tr) if tr >= T::ZERO && tr <= T::ONE => Ok(()),
        Err(Error::Budget) => Ok(()),
        other => Err(format!("{what} along {ray:?}: {other:?}")),
    }
}

/// The grid forms at `p`: densities, the majorant, and tracking by the
/// grid and by majorants built on it.
fn grid_works<T: Walk>(form: Form, p: &[T]) -> Check {
    let (sa, ss, v, lo, hi) = grid_parts(form, p);
    let g = Grid::new(&v, 2, 2, 2, sa, ss)
        .and_then(|g| g.with_box(lo, hi))
        .map_err(|e| format!("refused: {e:?}"))?;
    let max = v[0].max_of(T::ONE);
    if !(g.majorant().is_finite() && g.majorant() >= (sa + ss) * max) {
        return Err(format!("majorant {:?}", g.majorant()));
    }
    for i in 0..=16 {
        let f = T::from_f64(i as f64 / 16.0);
        let at = |a: T, b: T| a + (b - a) * f;
        let q = Vec3::new(at(lo.x, hi.x), at(lo.y, hi.y), at(lo.z, hi.z));
        let rho = g.density(q);
        if !(rho >= T::ZERO && (sa + ss) * rho <= g.majorant()) {
            return Err(format!("density({q:?}) = {rho:?}"));
        }
    }
    let mut cells = [T::ZERO; 8];
    let maj =
        Majorants::build(&g, [2, 2, 2], &mut cells).map_err(|e| format!("majorants: {e:?}"))?;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
    for ray in rays(lo, hi) {
        let hit = |e: Event| e != Event::Escaped;
        tracked(
            "delta",
            g.delta_track(ray, &mut rng).map(|(t, e)| (t, hit(e))),
            &ray,
        )?;
        estimated("ratio", g.ratio_track(ray, &mut rng), &ray)?;
        let d = maj
            .delta_track(&g, ray, 4096, &mut rng)
            .map(|x| (x.t, hit(x.event)));
        tracked("majorant delta", d, &ray)?;
        let r = maj.ratio_track(&g, ray, 4096, &mut rng).map(|x| x.tr);
        estimated("majorant ratio", r, &ray)?;
        other_estimators(&g, &maj, ray, &mut rng)?;
    }
    Ok(())
}

/// The estimators beyond delta and ratio tracking, through grid `g` and
/// majorants `maj` built on it: finite results, or the errors their docs
/// give (the budget; a series, weight or radiance that overflows).
fn other_estimators<T: Walk>(
    g: &Grid<'_, T>,
    maj: &Majorants<'_, T>,
    ray: Ray<T>,
    rng: &mut Xoshiro256PlusPlus,
) -> Check {
    let coef = |p: Vec3<T>| g.coefficients_at(p);
    let (mut hi, mut lo) = ([T::ZERO; 8], [T::ZERO; 8]);
    let ext =
        Extrema::build(g, [2, 2, 2], &mut hi, &mut lo).map_err(|e| format!("extrema: {e:?}"))?;
    let residual = ext.residual_ratio_track(g, ray, 4096, rng).map(|x| x.tr);
    estimated("residual ratio", residual, &ray)?;
    let overflow = [Error::Budget, Error::Domain];
    let march = ray_march_transmittance(g, ray, 4, 4096, rng).map(|x| x.tr);
    finite("ray march", march, &overflow, &ray)?;
    let tele = telescoping_transmittance(g, ray, 16, 4096, rng).map(|x| x.tr);
    finite("telescoping", tele, &overflow, &ray)?;
    let signed = maj
        .ratio_track_signed_fn(coef, ray, 4096, rng)
        .map(|x| x.tr);
    finite("signed ratio", signed, &overflow, &ray)?;
    let weighted = maj
        .delta_track_weighted_fn(coef, ray, 4096, rng)
        .map(|x| x.weight);
    finite("weighted delta", weighted, &overflow, &ray)?;
    let emitted = maj.emission_track(g, |_| T::ONE, ray, 4096, rng);
    finite("emission", emitted.map(|x| x.radiance), &overflow, &ray)?;
    estimated("emission's transmittance", emitted.map(|x| x.tr), &ray)
}

/// An estimate's outcome: finite, or one of the errors `allowed`.
fn finite<T: Walk>(what: &str, r: Result<T, Error>, allowed: &[Error], ray: &Ray<T>) -> Check {
    match r {
        Ok(x) if x.is_finite() => Ok(()),
        Err(e) if allowed.contains(&e) => Ok(()),
        other => Err(format!("{what} along {ray:?}: {other:?}")),
    }
}

/// Spectral delta (`delta`) or ratio tracking along `ray` with the hero
/// `p` and a channel of (½, ½): the distance and whether the walk ended in
/// a real collision (ratio tracking: the transmittance, and false), after
/// checking every channel's outputs finite and `≥ 0`: outputs that are not
/// come back as [`Error::Size`], which these well-formed slices cannot
/// otherwise give.
fn spectral<T: Walk>(p: &[T], ray: Ray<T>, budget: u32, delta: bool) -> Result<(T, bool), Error> {
    let v = values(T::TWO).map(|x| x * p[2]);
    let g = Grid::new(&v, 2, 2, 2, T::ZERO, T::ONE)?;
    let mut cells = [T::ZERO; 8];
    let m = Majorants::build_density(&g, [2, 2, 2], &mut cells)?;
    let (sa, ss) = ([p[0], T::HALF], [p[1], T::HALF]);
    let spectrum = Spectrum {
        sigma_a: &sa,
        sigma_s: &ss,
        hero: 0,
    };
    let (mut w, mut r_u, mut r_l) = ([T::NAN; 2], [T::NAN; 2], [T::NAN; 2]);
    let mut out = Ratios {
        weight: &mut w,
        r_u: &mut r_u,
        r_l: &mut r_l,
    };
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let found = if delta {
        m.delta_track_spectral(&g, &spectrum, ray, budget, &mut rng, &mut out)
            .map(|x| (x.t, x.event != Event::Escaped))
    } else {
        m.ratio_track_spectral(&g, &spectrum, ray, budget, &mut rng, &mut out)
            .map(|_| (out.weight[0], false))
    }?;
    let fine = |x: &T| *x >= T::ZERO && x.is_finite();
    if [w, r_u, r_l].iter().flatten().all(fine) {
        Ok(found)
    } else {
        Err(Error::Size)
    }
}

/// The unit cube.
fn unit_box<T: Walk>() -> (Vec3<T>, Vec3<T>) {
    let (z, o) = (T::ZERO, T::ONE);
    (Vec3::new(z, z, z), Vec3::new(o, o, o))
}

/// [`Form::MajorantsMixed`]'s majorants: the values `sigma` on a 3 × 1 × 1
/// division of the unit cube.
fn mixed<T: Walk>(sigma: &[T]) -> Result<Majorants<'_, T>, Error> {
    let (lo, hi) = unit_box();
    Majorants::new(sigma, [3, 1, 1], lo, hi)
}

/// [`Form::Extrema`]'s extrema: majorants `max` and minorants `min` on a
/// 2 × 1 × 1 division of the unit cube.
fn extrema<'a, T: Walk>(max: &'a [T], min: &'a [T]) -> Result<Extrema<'a, T>, Error> {
    let (lo, hi) = unit_box();
    Extrema::new(
        Majorants::new(max, [2, 1, 1], lo, hi)?,
        Majorants::new(min, [2, 1, 1], lo, hi)?,
    )
}

/// A majorant or control optical depth: `≥ 0` (+∞ where the integral
/// overflows the precision).
fn depth<T: Walk>(what: &str, r: Result<T, Error>, ray: &Ray<T>) -> Check {
    match r {
        Ok(x) if x >= T::ZERO => Ok(()),
        other => Err(format!("{what} along {ray:?}: {other:?}")),
    }
}

/// [`Form::MajorantsMixed`] at `s`: a vacuum tracked through cells of
/// majorant `s`, 0 and the largest float escapes (or runs out of budget
/// in the last), with a transmittance of exactly 1.
fn mixed_works<T: Walk>(s: T, rng: &mut Xoshiro256PlusPlus) -> Check {
    let z = T::ZERO;
    let sigma = [s, z, largest()];
    let m = mixed(&sigma).map_err(|e| format!("{e:?}"))?;
    let vacuum = |_: Vec3<T>| (z, z);
    let (lo, hi) = unit_box();
    for ray in rays(lo, hi) {
        match m.delta_track_fn(vacuum, ray, 4096, rng) {
            Ok(x) if x.event == Event::Escaped => {}
            Err(Error::Budget) => {}
            other => return Err(format!("delta along {ray:?}: {other:?}")),
        }
        match m.ratio_track_fn(vacuum, ray, 4096, rng) {
            Ok(x) if x.tr == T::ONE => {}
            Err(Error::Budget) => {}
            other => return Err(format!("ratio along {ray:?}: {other:?}")),
        }
        depth("optical depth", m.optical_depth(ray), &ray)?;
    }
    Ok(())
}

/// [`Form::Extrema`] at `p`: residual ratio tracking of a medium of
/// `σ_t = ½ min(max, 1)` (within every cell's majorant, below a minorant
/// above it: weights above 1, so the estimate is `≥ 0` and finite, not
/// held to `[0, 1]`), at the default rate, 1 and 16.
fn extrema_works<T: Walk>(p: &[T], rng: &mut Xoshiro256PlusPlus) -> Check {
    let (z, o) = (T::ZERO, T::ONE);
    let (max, min) = ([p[1], o], [p[0], T::HALF]);
    let e = extrema(&max, &min).map_err(|e| format!("{e:?}"))?;
    let sigma = p[1].min_of(o) * T::HALF;
    let medium = |_: Vec3<T>| (z, sigma);
    let (lo, hi) = unit_box();
    for ray in rays(lo, hi) {
        for rate in [0, 1, 16] {
            let r = e.residual_ratio_track_rate(medium, ray, rate, 4096, rng);
            match r {
                Ok(x) if x.tr >= z && x.tr.is_finite() => {}
                Err(Error::Budget) => {}
                other => return Err(format!("residual (rate {rate}) along {ray:?}: {other:?}")),
            }
        }
        depth("control depth", e.control_depth(ray), &ray)?;
    }
    Ok(())
}

/// [`Form::Equiangular`] at `p`.
fn equiangular<T: Walk>(p: &[T]) -> Result<Equiangular<T>, Error> {
    let (z, o) = (T::ZERO, T::ONE);
    let ray = Ray::new(Vec3::new(z, z, z), Vec3::new(o, z, z), p[1]);
    Equiangular::new(ray, Vec3::new(T::HALF, p[0], z))
}

/// What the form built at `p` gives, checked.
fn works<T: Walk>(form: Form, p: &[T]) -> Check {
    let (z, o) = (T::ZERO, T::ONE);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    let unit = |t_max: T| Ray::new(Vec3::new(z, z, z), Vec3::new(o, T::HALF, o), t_max);
    match form {
        Form::Grid | Form::GridBox => grid_works(form, p),
        Form::Majorants => {
            let (lo, hi) = (Vec3::new(z, z, z), Vec3::new(o, o, o));
            let sigma = [p[0], o];
            let m = Majorants::new(&sigma, [2, 1, 1], lo, hi).map_err(|e| format!("{e:?}"))?;
            // Half the smaller majorant, scattering, everywhere (bounded in
            // either cell, whichever a face's rounding puts a point in).
            let half = |_: Vec3<T>| (z, p[0].min_of(o) * T::HALF);
            for ray in rays(lo, hi) {
                let d = m.delta_track_fn(half, ray, 4096, &mut rng);
                tracked("delta", d.map(|x| (x.t, x.event != Event::Escaped)), &ray)?;
                let r = m.ratio_track_fn(half, ray, 4096, &mut rng).map(|x| x.tr);
                estimated("ratio", r, &ray)?;
            }
            Ok(())
        }
        Form::MajorantsMixed => mixed_works(p[0], &mut rng),
        Form::Extrema => extrema_works(p, &mut rng),
        Form::OneMajorant => {
            let half = |_: Vec3<T>| (z, p[0] * T::HALF);
            for t_max in [o, T::from_f64(1e6)] {
                let ray = unit(t_max);
                let d = one_majorant_delta_track(half, p[0], ray, 4096, &mut rng);
                tracked("delta", d.map(|x| (x.t, x.event != Event::Escaped)), &ray)?;
                let r = one_majorant_ratio_track(half, p[0], ray, 4096, &mut rng);
                estimated("ratio", r.map(|x| x.tr), &ray)?;
            }
            Ok(())
        }
        Form::FreePath => {
            let mut prev = z;
            for i in 0..=1024 {
                let u = T::from_f64(i as f64 / 1024.0);
                let t = free_path(p[0], u);
                if t.is_nan() || t < prev {
                    return Err(format!(
                        "free_path({:?}, {u:?}) = {t:?} after {prev:?}",
                        p[0]
                    ));
                }
                prev = t;
            }
            Ok(())
        }
        Form::Spectral => {
            let (lo, hi) = (Vec3::new(z, z, z), Vec3::new(o, o, o));
            for ray in rays(lo, hi) {
                let d = spectral(p, ray, 4096, true);
                tracked("spectral delta (outputs finite, ≥ 0)", d, &ray)?;
                let r = spectral(p, ray, 4096, false).map(|x| x.0);
                estimated("spectral ratio (outputs finite, ≥ 0)", r, &ray)?;
            }
            Ok(())
        }
        Form::Equiangular => {
            let e = equiangular(p).map_err(|e| format!("{e:?}"))?;
            let mut prev = z;
            for i in 0..=1024 {
                let u = T::from_f64(i as f64 / 1024.0);
                let t = e.sample(u);
                let pdf = e.pdf(t);
                let inside = t >= prev && t <= p[1] && (t < p[1] || i > 0);
                if !(inside && pdf >= z && (pdf.is_finite() || !t.is_finite())) {
                    return Err(format!("sample({u:?}) = {t:?} after {prev:?}, pdf {pdf:?}"));
                }
                prev = t;
            }
            Ok(())
        }
        Form::Transmittance => {
            let tr = transmittance(p[0], p[1]);
            if tr >= z && tr <= o {
                Ok(())
            } else {
                Err(format!("transmittance = {tr:?}"))
            }
        }
    }
}

/// The form works at each end's last accepted value and `2^j` floats
/// inside it for `j = 0, 2, 4, …, 40` (those between the end and the
/// base).
fn works_near<T: Walk>(reach: &Reach, dir: f64) -> Check {
    let last = found_edge::<T>(reach, dir)?;
    let base = base_of::<T>(reach)[reach.param];
    for k in steps_inside(last, base, true) {
        let x = if !last.is_finite() {
            last
        } else {
            inside(last, base, k)
        };
        let mut p = base_of::<T>(reach);
        p[reach.param] = x;
        works(reach.form, &p).map_err(|e| format!("at {x:?}: {e}"))?;
    }
    Ok(())
}

#[test]
fn every_media_parameter_reaches_its_documented_edge_and_works_there() {
    let ends: Vec<(Reach, f64)> = reaches()
        .into_iter()
        .flat_map(|r| [(r, -1.0), (r, 1.0)])
        .collect();
    let failures: Vec<String> = map_parallel(&ends, |(r, dir)| {
        let found: Vec<String> = [
            ("f32", works_near::<f32>(r, *dir)),
            ("f64", works_near::<f64>(r, *dir)),
        ]
        .into_iter()
        .filter_map(|(name, c)| c.err().map(|e| format!("{name}: {e}")))
        .collect();
        let side = if *dir < 0.0 { "low" } else { "high" };
        (!found.is_empty()).then(|| {
            format!(
                "{:?} parameter {} at {:?} ({side} end): {}",
                r.form,
                r.param,
                r.base,
                found.join("; ")
            )
        })
    })
    .into_iter()
    .flatten()
    .collect();
    assert!(failures.is_empty(), "media reach:\n{}", failures.join("\n"));
}
