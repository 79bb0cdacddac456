//! Tracking through a medium: one argument struct, one result, one entry
//! point per estimator and precision. The medium (a grid, the caller's
//! coefficients, or per-cell values) and its bounds are chosen inside the
//! arguments.

use super::majorant::{Bounds, MajStore, bounds_at};
use super::medium::{GridStore, grid_at};
use super::{
    CFn, CRng, CVec, bind, overlaps, sk_coefficients, sk_coefficients_f64, sk_emission_fn,
    sk_emission_fn_f64, sk_grid, sk_grid_f64, sk_majorants, sk_majorants_f64, sk_medium_fn,
    sk_medium_fn_f64, sk_rng, sk_status, sk_track_event, sk_vec3, sk_vec3_f64, slice_in, slice_out,
};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::emission::{Emission, emission_cells};
use crate::medium::majorant::{Majorants, one_majorant_delta_track, one_majorant_ratio_track};
use crate::medium::nonbounding::Exceeded;
use crate::medium::ray_march::{
    Placement, Series, march_within, ray_march_transmittance, ray_march_transmittance_fn,
    telescoping_transmittance, telescoping_transmittance_fn,
};
use crate::medium::residual::Extrema;
use crate::medium::spectral::{MAX_CHANNELS, Ratios, Spectrum};
use crate::medium::{Event, Grid, MAX_STEPS, Ray};
use core::ffi::c_void;

/// The step budget a tracking call takes when sk_track_args.budget is 0:
/// tentative collisions, or density evaluations for ray marching.
pub const SK_TRACK_BUDGET: u32 = 1 << 20;
const _: () = assert!(SK_TRACK_BUDGET == MAX_STEPS);

/// sk_track_args.flags: the majorants may not bound sigma_t. Ratio
/// tracking then keeps signed weights and delta tracking weights its path
/// (unbiased, where the strict estimators refuse with SK_ERR_DOMAIN), and
/// the result reports the worst sigma_t/sigma_maj met and its cell. Needs
/// majorants. Delta and ratio tracking only: sk_residual_ratio_track,
/// sk_ray_march, sk_telescoping_march and sk_emission_track refuse it with
/// SK_ERR_DOMAIN (their estimators assume bounding majorants).
pub const SK_TRACK_NONBOUNDING: u32 = 1;

/// The medium a tracking call walks. Its coefficients come from exactly
/// one of `grid` and `coefficients` (or, for sk_emission_track, from
/// per-cell values: both NULL, `majorants` then holding sigma_t per cell).
/// Its bounds: `majorants` (local majorants, with minorants for residual
/// ratio tracking), or, when NULL, one constant majorant: the grid's own
/// ((sigma_a + sigma_s) times its largest value), or `sigma_maj` for
/// `coefficients`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_medium {
    /// A density grid, or NULL.
    pub grid: *const sk_grid,
    /// Or the caller's (sigma_a, sigma_s) at a point, or NULL.
    pub coefficients: sk_medium_fn,
    /// Handed to `coefficients` and `emission_fn`.
    pub ctx: *mut c_void,
    /// Local majorants over the grid's box (or any box for
    /// `coefficients`), or NULL.
    pub majorants: *const sk_majorants,
    /// With `coefficients` and no majorants: the one majorant (finite,
    /// >= 0; the segment must then be finite). Otherwise unused.
    pub sigma_maj: f32,
    /// sk_emission_track: the emitted radiance L_e as a grid over the
    /// medium's box, or NULL.
    pub emission: *const sk_grid,
    /// Or as the caller's field, or NULL.
    pub emission_fn: sk_emission_fn,
    /// Or per cell (sigma_a L_e over the majorants' cells), for the exact
    /// integral through a medium constant per cell, or NULL.
    pub emission_cells: *const sk_majorants,
}

/// The medium (double); see `sk_medium`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_medium_f64 {
    /// A density grid, or NULL.
    pub grid: *const sk_grid_f64,
    /// Or the caller's (sigma_a, sigma_s) at a point, or NULL.
    pub coefficients: sk_medium_fn_f64,
    /// Handed to `coefficients` and `emission_fn`.
    pub ctx: *mut c_void,
    /// Local majorants, or NULL.
    pub majorants: *const sk_majorants_f64,
    /// The one majorant for `coefficients` without majorants.
    pub sigma_maj: f64,
    /// The emitted radiance as a grid, or NULL.
    pub emission: *const sk_grid_f64,
    /// Or as the caller's field, or NULL.
    pub emission_fn: sk_emission_fn_f64,
    /// Or per cell, or NULL.
    pub emission_cells: *const sk_majorants_f64,
}

/// Hero-wavelength tracking (sk_delta_track, sk_ratio_track with a
/// spectrum): each channel's coefficients per unit density, the hero whose
/// majorant draws the free paths, and where each channel's results go.
/// The medium's majorants must bound the density itself (build them on a
/// grid with sigma_a + sigma_s = 1), and each channel's sigma_a + sigma_s
/// times every majorant the ray meets must be finite (SK_ERR_DOMAIN where
/// one overflows: tracking could not step through it).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_spectrum {
    /// sigma_a per unit density, `channels` values (finite, >= 0).
    pub sigma_a: *const f32,
    /// sigma_s per unit density, `channels` values.
    pub sigma_s: *const f32,
    /// 1 to 16.
    pub channels: usize,
    /// The hero channel (< channels).
    pub hero: u32,
    /// Out: the path weight per channel (pbrt-v4's beta; T_ray for ratio
    /// tracking), `channels` values.
    pub weight: *mut f32,
    /// Out: each channel's delta-tracking path density over the hero's.
    pub r_u: *mut f32,
    /// Out: each channel's free-flight path density over the hero's.
    pub r_l: *mut f32,
}

/// Hero-wavelength tracking (double); see `sk_spectrum`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_spectrum_f64 {
    /// sigma_a per unit density.
    pub sigma_a: *const f64,
    /// sigma_s per unit density.
    pub sigma_s: *const f64,
    /// 1 to 16.
    pub channels: usize,
    /// The hero channel.
    pub hero: u32,
    /// Out: the path weight per channel.
    pub weight: *mut f64,
    /// Out: delta-tracking path density ratios.
    pub r_u: *mut f64,
    /// Out: free-flight path density ratios.
    pub r_l: *mut f64,
}

/// What every tracking call takes.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_track_args {
    /// The medium and its bounds.
    pub medium: sk_medium,
    /// The ray's origin (finite).
    pub o: sk_vec3,
    /// Its direction (finite, non-zero, any length: distances are along
    /// d/|d|).
    pub d: sk_vec3,
    /// The segment [t_min, t_max]: 0 <= t_min <= t_max; t_max may be
    /// +inf where the medium has a box (a grid, or majorants).
    pub t_min: f32,
    /// The segment's end.
    pub t_max: f32,
    /// At most this many tentative collisions (density evaluations for ray
    /// marching) before SK_ERR_BUDGET; 0 means SK_TRACK_BUDGET.
    pub budget: u32,
    /// Ray marching: strata per march; 0 lets the library choose
    /// ceil(4 tau), at least 1 (16 ceil(tau), at least 16, for the
    /// telescoping estimator), where tau is the optical depth that places
    /// the strata: with `majorants`, the integral of sigma_maj - sigma_min
    /// along the segment (sigma_min 0 without minorants); without, that of
    /// the one majorant. Residual ratio tracking: the rate of its
    /// tentative collisions as a multiple of sigma_maj - sigma_min; 0 lets
    /// the library choose 2 (1 is Novak et al.'s estimator). Otherwise
    /// unused.
    pub strata: u32,
    /// SK_TRACK_NONBOUNDING (delta and ratio tracking only; the other
    /// estimators refuse it with SK_ERR_DOMAIN) or 0; other bits are
    /// SK_ERR_METHOD.
    pub flags: u32,
    /// The caller's generator.
    pub rng: *mut sk_rng,
    /// Hero-wavelength tracking, or NULL.
    pub spectrum: *const sk_spectrum,
}

/// What every tracking call takes (double); see `sk_track_args`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_track_args_f64 {
    /// The medium and its bounds.
    pub medium: sk_medium_f64,
    /// The ray's origin.
    pub o: sk_vec3_f64,
    /// Its direction.
    pub d: sk_vec3_f64,
    /// The segment's start.
    pub t_min: f64,
    /// The segment's end.
    pub t_max: f64,
    /// The step budget; 0 means SK_TRACK_BUDGET.
    pub budget: u32,
    /// Ray marching: strata per march; residual ratio tracking: its rate;
    /// 0 lets the library choose.
    pub strata: u32,
    /// SK_TRACK_NONBOUNDING or 0.
    pub flags: u32,
    /// The caller's generator.
    pub rng: *mut sk_rng,
    /// Hero-wavelength tracking, or NULL.
    pub spectrum: *const sk_spectrum_f64,
}

/// What every tracking call writes on SK_OK. A field an estimator does not
/// produce is NaN (t, tr), 0 (radiance, exceeded, steps, cell) or 1
/// (weight).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_track_result {
    /// Delta tracking: the distance of the real collision, or where the ray
    /// leaves the medium (its box, or t_max) for SK_TRACK_ESCAPED, t_min
    /// for a ray that never enters it.
    pub t: f32,
    /// The transmittance estimate (ratio, residual ratio tracking, ray
    /// marching, emission): unbiased; ray marching's and signed ratio
    /// tracking's may leave [0, 1].
    pub tr: f32,
    /// Weighted delta tracking (SK_TRACK_NONBOUNDING): the path's weight,
    /// 1 where every majorant bounded.
    pub weight: f32,
    /// sk_emission_track: the radiance emitted along the segment.
    pub radiance: f32,
    /// SK_TRACK_NONBOUNDING: the largest sigma_t/sigma_maj > 1 met, 0 if
    /// every majorant bounded.
    pub exceeded: f32,
    /// Delta tracking: what ended the walk.
    pub event: sk_track_event,
    /// Tentative collisions drawn (density evaluations): the cost.
    pub steps: u32,
    /// SK_TRACK_NONBOUNDING: the majorant cell of `exceeded`.
    pub cell: [u32; 3],
}

/// What every tracking call writes (double); see `sk_track_result`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_track_result_f64 {
    /// As in sk_track_result.
    pub t: f64,
    /// The transmittance estimate.
    pub tr: f64,
    /// The path's weight.
    pub weight: f64,
    /// The radiance emitted along the segment.
    pub radiance: f64,
    /// The largest sigma_t/sigma_maj > 1 met.
    pub exceeded: f64,
    /// What ended the walk.
    pub event: sk_track_event,
    /// Tentative collisions drawn.
    pub steps: u32,
    /// The majorant cell of `exceeded`.
    pub cell: [u32; 3],
}

/// What an estimator found, in Rust terms.
struct Found<T> {
    t: T,
    tr: T,
    weight: T,
    radiance: T,
    exceeded: Option<Exceeded<T>>,
    event: Event,
    steps: u32,
}

impl<T: Real> Found<T> {
    fn nothing() -> Self {
        Found {
            t: T::NAN,
            tr: T::NAN,
            weight: T::ONE,
            radiance: T::ZERO,
            exceeded: None,
            event: Event::Escaped,
            steps: 0,
        }
    }
    fn transmittance(tr: T, steps: u32) -> Self {
        Found {
            tr,
            steps,
            ..Self::nothing()
        }
    }
    fn emission(x: Emission<T>) -> Self {
        Found {
            radiance: x.radiance,
            ..Self::transmittance(x.tr, x.steps)
        }
    }
    fn track(t: T, event: Event, steps: u32) -> Self {
        Found {
            t,
            event,
            steps,
            ..Self::nothing()
        }
    }
}

/// The estimators.
#[derive(Clone, Copy, PartialEq)]
enum Estimator {
    Delta,
    Ratio,
    Residual,
    RayMarch,
    Telescoping,
    Emission,
}

/// The fields of a C argument struct in one precision's types.
struct Parts<P: Prec> {
    grid: *const P::G,
    coefficients: CFn<P::V, P::Coef>,
    ctx: *mut c_void,
    majorants: *const P::M,
    sigma_maj: P::T,
    emission: *const P::G,
    emission_fn: CFn<P::V, P::T>,
    emission_cells: *const P::M,
    ray: Ray<P::T>,
    budget: u32,
    strata: u32,
    flags: u32,
    rng: *mut sk_rng,
    spectrum: Option<SpecParts<P::T>>,
}

/// A C spectrum's fields.
struct SpecParts<T> {
    sigma_a: *const T,
    sigma_s: *const T,
    channels: usize,
    hero: u32,
    out: [*mut T; 3],
}

/// A C argument struct with its types.
trait Prec: Copy {
    type T: Real;
    type V: CVec<T = Self::T>;
    type G: GridStore<T = Self::T>;
    type M: MajStore<T = Self::T>;
    type Coef: Copy;
    type Result: Copy;
    fn pair(c: Self::Coef) -> (Self::T, Self::T);
    /// The fields (the spectrum read through its non-NULL pointer).
    unsafe fn parts(&self) -> Parts<Self>;
    /// The ray and segment, each coordinate and end read by a load of its
    /// own (see [`CVec::read_each`]: the two ends, read as one 16-byte
    /// load, waited for the caller's two stores on every call, 8 % of
    /// `sk_delta_track_f64`'s samples in the C photon loop).
    fn ray_each(&self) -> Ray<Self::T>;
    /// Delta or ratio tracking by the short route, reading only the fields
    /// it needs and writing `*out` (non-NULL) itself, where the call is the
    /// common one (no flags, spectrum or majorants; a callback medium with
    /// one majorant, or a grid): its status, or `None` for every other
    /// call, which takes [`found`]. One call per flight pays this route
    /// on every flight.
    unsafe fn quick(&self, e: Estimator, out: *mut Self::Result) -> Option<sk_status>;
    fn result(f: Found<Self::T>) -> Self::Result;
}

macro_rules! impl_prec {
    ($args:ty, $t:ty, $v:ty, $g:ty, $m:ty, $coef:ident, $res:ident) => {
        impl Prec for $args {
            type T = $t;
            type V = $v;
            type G = $g;
            type M = $m;
            type Coef = $coef;
            type Result = $res;
            fn pair(c: $coef) -> ($t, $t) {
                (c.sigma_a, c.sigma_s)
            }
            unsafe fn parts(&self) -> Parts<Self> {
                let m = &self.medium;
                // SAFETY: a non-NULL spectrum points to one (module contract).
                let spectrum = unsafe { self.spectrum.as_ref() }.map(|s| SpecParts {
                    sigma_a: s.sigma_a,
                    sigma_s: s.sigma_s,
                    channels: s.channels,
                    hero: s.hero,
                    out: [s.weight, s.r_u, s.r_l],
                });
                let ray = self.ray_each();
                Parts {
                    grid: m.grid,
                    coefficients: m.coefficients,
                    ctx: m.ctx,
                    majorants: m.majorants,
                    sigma_maj: m.sigma_maj,
                    emission: m.emission,
                    emission_fn: m.emission_fn,
                    emission_cells: m.emission_cells,
                    ray,
                    budget: self.budget,
                    strata: self.strata,
                    flags: self.flags,
                    rng: self.rng,
                    spectrum,
                }
            }
            #[inline(always)]
            fn ray_each(&self) -> Ray<$t> {
                // SAFETY: references to this struct's own fields.
                let (t_min, t_max) = unsafe {
                    (
                        core::ptr::read_volatile(&self.t_min),
                        core::ptr::read_volatile(&self.t_max),
                    )
                };
                Ray::new(self.o.read_each(), self.d.read_each(), t_max).segment(t_min, t_max)
            }
            #[inline(always)]
            unsafe fn quick(&self, e: Estimator, out: *mut $res) -> Option<sk_status> {
                let m = &self.medium;
                let plain = self.flags == 0 && self.spectrum.is_null() && m.majorants.is_null();
                if !(plain && matches!(e, Estimator::Delta | Estimator::Ratio)) {
                    return None;
                }
                let ray = self.ray_each();
                let budget = if self.budget == 0 {
                    SK_TRACK_BUDGET
                } else {
                    self.budget
                };
                let coefficients = bind(m.coefficients, m.ctx);
                // SAFETY: a non-NULL rng points to an sk_rng (module contract).
                let rng = unsafe { CRng::from_ptr(self.rng) };
                let delta = e == Estimator::Delta;
                let r = match (m.grid.is_null(), coefficients, rng) {
                    (_, _, None) => Err(sk_status::SK_ERR_NULL),
                    (true, Some(f), Some(mut rng)) => {
                        let coef = |p: Vec3<$t>| Self::pair(f(<$v>::from_vec(p)));
                        quick_one(m.sigma_maj, delta, coef, (ray, budget), &mut rng)
                    }
                    (false, None, Some(mut rng)) => match unsafe { grid_at(m.grid) } {
                        Ok(g) => quick_grid(g, delta, (ray, budget), &mut rng),
                        Err(s) => Err(s),
                    },
                    _ => return None,
                };
                Some(match r {
                    // SAFETY: the caller checked out non-NULL.
                    Ok(f) => unsafe {
                        out.write(Self::result(f));
                        sk_status::SK_OK
                    },
                    Err(s) => s,
                })
            }
            fn result(f: Found<$t>) -> $res {
                let (exceeded, cell) = f
                    .exceeded
                    .map_or((0.0, [0; 3]), |e| (e.ratio, e.cell.map(|c| c as u32)));
                $res {
                    t: f.t,
                    tr: f.tr,
                    weight: f.weight,
                    radiance: f.radiance,
                    exceeded,
                    event: event_of(f.event),
                    steps: f.steps,
                    cell,
                }
            }
        }
    };
}
impl_prec!(
    sk_track_args,
    f32,
    sk_vec3,
    sk_grid,
    sk_majorants,
    sk_coefficients,
    sk_track_result
);
impl_prec!(
    sk_track_args_f64,
    f64,
    sk_vec3_f64,
    sk_grid_f64,
    sk_majorants_f64,
    sk_coefficients_f64,
    sk_track_result_f64
);

fn event_of(e: Event) -> sk_track_event {
    match e {
        Event::Escaped => sk_track_event::SK_TRACK_ESCAPED,
        Event::Scattered => sk_track_event::SK_TRACK_SCATTERED,
        Event::Absorbed => sk_track_event::SK_TRACK_ABSORBED,
        Event::Collided => sk_track_event::SK_TRACK_COLLIDED,
    }
}

/// Where the coefficients come from.
enum Source<'a, T: 'static, F> {
    Grid(&'a Grid<'static, T>),
    Fn(F),
    /// Per-cell values (the majorants themselves): emission only.
    Cells,
}

/// One majorant for the whole segment of a callback medium: a one-cell
/// grid over a box around the segment (which must be finite), so that the
/// walk is the majorant walk's.
fn one_cell<T: Real>(sigma: &[T; 1], ray: Ray<T>) -> Result<Majorants<'_, T>, Error> {
    let d = ray.dir.try_normalize().ok_or(Error::Domain)?;
    if !(ray.t_min.is_finite() && ray.t_max.is_finite()) {
        return Err(Error::Domain);
    }
    let (a, b) = (ray.origin + d * ray.t_min, ray.origin + d * ray.t_max);
    // Padded so that the segment lies well inside, whatever rounding does
    // to the box's faces.
    let pad = |x: T, y: T| T::ONE + (x.abs() + y.abs()) * T::from_f64(0.01);
    let lo = Vec3::new(
        a.x.min_of(b.x) - pad(a.x, b.x),
        a.y.min_of(b.y) - pad(a.y, b.y),
        a.z.min_of(b.z) - pad(a.z, b.z),
    );
    let hi = Vec3::new(
        a.x.max_of(b.x) + pad(a.x, b.x),
        a.y.max_of(b.y) + pad(a.y, b.y),
        a.z.max_of(b.z) + pad(a.z, b.z),
    );
    if !(sigma[0] >= T::ZERO && sigma[0].is_finite()) {
        return Err(Error::Domain);
    }
    Majorants::from_parts(sigma, [1; 3], lo, hi)
}

/// The majorant optical depth of the segment through the grid's one
/// majorant (the segment clipped to its box).
fn grid_depth<T: Real>(grid: &Grid<'_, T>, ray: Ray<T>) -> Result<T, Error> {
    let sigma = [grid.majorant()];
    let (lo, hi) = grid.bounds();
    Majorants::from_parts(&sigma, [1; 3], lo, hi)?.optical_depth(ray)
}

/// Delta (`delta`) or ratio tracking through a caller's medium with one
/// majorant: the walk at that majorant over the segment.
#[inline(always)]
fn quick_one<T: Real>(
    sigma_maj: T,
    delta: bool,
    coef: impl Fn(Vec3<T>) -> (T, T),
    (ray, budget): (Ray<T>, u32),
    rng: &mut CRng,
) -> Result<Found<T>, sk_status> {
    let found = if delta {
        one_majorant_delta_track(coef, sigma_maj, ray, budget, rng)
            .map(|x| Found::track(x.t, x.event, x.steps))
    } else {
        one_majorant_ratio_track(coef, sigma_maj, ray, budget, rng)
            .map(|x| Found::transmittance(x.tr, x.steps))
    };
    found.map_err(Into::into)
}

/// Delta or ratio tracking through a grid at its one majorant.
#[inline(always)]
fn quick_grid<T: Real>(
    g: &Grid<'static, T>,
    delta: bool,
    (ray, budget): (Ray<T>, u32),
    rng: &mut CRng,
) -> Result<Found<T>, sk_status> {
    let found = if delta {
        g.delta_track_within(ray, budget, rng)
            .map(|x| Found::track(x.t, x.event, x.steps))
    } else {
        g.ratio_track_within(ray, budget, rng)
            .map(|(tr, steps)| Found::transmittance(tr, steps))
    };
    found.map_err(Into::into)
}

/// Runs estimator `e` with the arguments behind `a` and writes `*out`.
/// Inlined into each entry point, so that each holds only its own
/// estimator's short route (one loop, not four sharing one frame), and the
/// general route stays out of line ([`general`]).
#[inline(always)]
unsafe fn run<P: Prec>(e: Estimator, a: *const P, out: *mut P::Result) -> sk_status {
    if a.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    // SAFETY: a non-NULL a points to arguments (module contract).
    let args = unsafe { &*a };
    if let Some(status) = unsafe { args.quick(e, out) } {
        return status;
    }
    unsafe { general(e, args, out) }
}

/// [`run`]'s general route (every estimator, flag and medium), out of
/// line: inlined with the short route, its registers and frame were the
/// short route's too.
#[inline(never)]
unsafe fn general<P: Prec>(e: Estimator, args: &P, out: *mut P::Result) -> sk_status {
    match unsafe { found(e, args.parts()) } {
        // SAFETY: out checked non-NULL above.
        Ok(f) => unsafe {
            out.write(P::result(f));
            sk_status::SK_OK
        },
        Err(s) => s,
    }
}

/// What estimator `e` finds through the medium the parts describe.
unsafe fn found<P: Prec>(e: Estimator, a: Parts<P>) -> Result<Found<P::T>, sk_status> {
    if a.flags & !SK_TRACK_NONBOUNDING != 0 {
        return Err(sk_status::SK_ERR_METHOD);
    }
    let nonbounding = a.flags & SK_TRACK_NONBOUNDING != 0;
    let mut rng = unsafe { CRng::from_ptr(a.rng) }.ok_or(sk_status::SK_ERR_NULL)?;
    let budget = if a.budget == 0 {
        SK_TRACK_BUDGET
    } else {
        a.budget
    };
    let bounds = if a.majorants.is_null() {
        None
    } else {
        Some(unsafe { bounds_at(a.majorants) }?)
    };
    let coefficients = bind(a.coefficients, a.ctx);
    let source = match (a.grid.is_null(), coefficients) {
        (false, None) => Source::Grid(unsafe { grid_at(a.grid) }?),
        (true, Some(f)) => Source::Fn(move |p: Vec3<P::T>| P::pair(f(P::V::from_vec(p)))),
        (true, None) if e == Estimator::Emission => Source::Cells,
        (true, None) => return Err(sk_status::SK_ERR_NULL),
        (false, Some(_)) => return Err(sk_status::SK_ERR_DOMAIN),
    };
    let w = Walk {
        ray: a.ray,
        budget,
        rng: &mut rng,
    };
    let em = Emitted::<P> {
        grid: a.emission,
        f: a.emission_fn,
        ctx: a.ctx,
        cells: a.emission_cells,
    };
    let r = match source {
        Source::Grid(g) => {
            let coef = |p: Vec3<P::T>| g.coefficients_at(p);
            let spectral = a.spectrum.as_ref();
            match (e, bounds, spectral) {
                (Estimator::Delta | Estimator::Ratio, Some(b), Some(s)) => {
                    return unsafe { spectral_track(e == Estimator::Delta, b, g, s, w) };
                }
                (_, _, Some(_)) => return Err(sk_status::SK_ERR_DOMAIN),
                _ => {}
            }
            estimate(
                e,
                coef,
                Some(g),
                bounds,
                None,
                nonbounding,
                em,
                (a.strata, w),
            )
        }
        Source::Fn(f) => {
            if a.spectrum.is_some() {
                return Err(sk_status::SK_ERR_DOMAIN);
            }
            let one = Some(a.sigma_maj);
            estimate(e, f, None, bounds, one, nonbounding, em, (a.strata, w))
        }
        Source::Cells => {
            let cells = unsafe { bounds_at(a.emission_cells) }?;
            let b = bounds.ok_or(sk_status::SK_ERR_NULL)?;
            emission_cells(&b.max, &cells.max, a.ray).map(Found::emission)
        }
    };
    r.map_err(Into::into)
}

/// The segment, budget and generator of one call.
struct Walk<'a, T> {
    ray: Ray<T>,
    budget: u32,
    rng: &'a mut CRng,
}

/// The emission source of sk_emission_track, as given.
struct Emitted<P: Prec> {
    grid: *const P::G,
    f: CFn<P::V, P::T>,
    ctx: *mut c_void,
    cells: *const P::M,
}

/// Estimator `e` through coefficients `coef` (from `grid` if it is one),
/// bounded by `bounds` or, with none, by the grid's majorant or
/// `sigma_maj` over a one-cell box around the segment.
#[allow(clippy::too_many_arguments)]
fn estimate<P: Prec>(
    e: Estimator,
    coef: impl Fn(Vec3<P::T>) -> (P::T, P::T),
    grid: Option<&Grid<'static, P::T>>,
    bounds: Option<&Bounds<P::T>>,
    sigma_maj: Option<P::T>,
    nonbounding: bool,
    emitted: Emitted<P>,
    (given, w): (u32, Walk<'_, P::T>),
) -> Result<Found<P::T>, Error> {
    let Walk { ray, budget, rng } = w;
    // The one majorant of a callback medium with no majorants.
    let one = [sigma_maj.unwrap_or(P::T::ZERO)];
    let own = match (bounds, grid) {
        (Some(b), _) => Some(b.max),
        (None, Some(_)) => None,
        (None, None) => Some(one_cell(&one, ray)?),
    };
    if let (Some(b), Some(g)) = (bounds, grid) {
        if b.max.bounds() != g.bounds() {
            return Err(Error::Domain);
        }
    }
    if nonbounding {
        let m = bounds.map(|b| b.max).ok_or(Error::Domain)?;
        return match e {
            Estimator::Delta => m
                .delta_track_weighted_fn(coef, ray, budget, rng)
                .map(|x| Found {
                    weight: x.weight,
                    exceeded: x.exceeded,
                    ..Found::track(x.t, x.event, x.steps)
                }),
            Estimator::Ratio => m
                .ratio_track_signed_fn(coef, ray, budget, rng)
                .map(|x| Found {
                    exceeded: x.exceeded,
                    ..Found::transmittance(x.tr, x.steps)
                }),
            _ => Err(Error::Domain),
        };
    }
    match (e, own, grid) {
        (Estimator::Delta, None, Some(g)) => {
            let x = g.delta_track_within(ray, budget, rng)?;
            Ok(Found::track(x.t, x.event, x.steps))
        }
        (Estimator::Ratio, None, Some(g)) => {
            let (tr, steps) = g.ratio_track_within(ray, budget, rng)?;
            Ok(Found::transmittance(tr, steps))
        }
        (Estimator::Delta, Some(m), _) => m
            .delta_track_fn(coef, ray, budget, rng)
            .map(|x| Found::track(x.t, x.event, x.steps)),
        (Estimator::Ratio, Some(m), _) => m
            .ratio_track_fn(coef, ray, budget, rng)
            .map(|x| Found::transmittance(x.tr, x.steps)),
        (Estimator::Residual, ..) => {
            let b = bounds.ok_or(Error::Domain)?;
            let min = b.min.ok_or(Error::Domain)?;
            let ext = Extrema::paired(b.max, min)?;
            let x = ext.residual_ratio_track_rate(coef, ray, given, budget, rng)?;
            Ok(Found::transmittance(x.tr, x.steps))
        }
        (Estimator::RayMarch | Estimator::Telescoping, own, _) => {
            let series = if e == Estimator::RayMarch {
                Series::Power
            } else {
                Series::Telescoping
            };
            // With a majorant grid the strata follow it (and its
            // minorants); with one majorant they are even.
            if let Some(b) = bounds {
                let place = Placement {
                    max: b.max,
                    min: b.min,
                };
                let x = march_within(series, place, coef, ray, given, budget, rng)?;
                return Ok(Found::transmittance(x.tr, x.steps));
            }
            // The majorant optical depth is walked only when the caller
            // leaves the strata to the library.
            let n = match given {
                0 => {
                    let tau = match (own, grid) {
                        (Some(m), _) => m.optical_depth(ray),
                        (None, Some(g)) => grid_depth(g, ray),
                        (None, None) => Err(Error::Domain),
                    }?;
                    series.default_strata(tau.to_f64())?
                }
                n => n,
            };
            let x = match (grid, series) {
                (Some(g), Series::Power) => ray_march_transmittance(g, ray, n, budget, rng),
                (Some(g), _) => telescoping_transmittance(g, ray, n, budget, rng),
                (None, Series::Power) => ray_march_transmittance_fn(coef, ray, n, budget, rng),
                (None, _) => telescoping_transmittance_fn(coef, ray, n, budget, rng),
            }?;
            Ok(Found::transmittance(x.tr, x.steps))
        }
        (Estimator::Emission, own, _) => {
            let m = bounds.map(|b| b.max).or(own).ok_or(Error::Domain)?;
            let x = unsafe { emit(&m, coef, emitted, (ray, budget), rng) }?;
            Ok(Found::emission(x))
        }
        (Estimator::Delta | Estimator::Ratio, None, None) => Err(Error::Domain),
    }
}

/// Emission tracking through majorants `m` with the source given as a grid
/// or a callback (exactly one).
unsafe fn emit<P: Prec>(
    m: &Majorants<'_, P::T>,
    coef: impl Fn(Vec3<P::T>) -> (P::T, P::T),
    src: Emitted<P>,
    (ray, budget): (Ray<P::T>, u32),
    rng: &mut CRng,
) -> Result<Emission<P::T>, Error> {
    let f = bind(src.f, src.ctx);
    if !src.cells.is_null() {
        return Err(Error::Domain);
    }
    match (src.grid.is_null(), f) {
        (false, None) => {
            let le = unsafe { grid_at(src.grid) }.map_err(|_| Error::Domain)?;
            m.emission_track_fn(coef, |p| le.density(p), ray, budget, rng)
        }
        (true, Some(f)) => m.emission_track_fn(coef, |p| f(P::V::from_vec(p)), ray, budget, rng),
        _ => Err(Error::Domain),
    }
}

/// Hero-wavelength delta or ratio tracking.
unsafe fn spectral_track<T: Real>(
    delta: bool,
    b: &Bounds<T>,
    grid: &Grid<'static, T>,
    s: &SpecParts<T>,
    w: Walk<'_, T>,
) -> Result<Found<T>, sk_status> {
    let n = s.channels;
    if n == 0 || n > MAX_CHANNELS {
        return Err(sk_status::SK_ERR_SIZE);
    }
    let [weight, r_u, r_l] = s.out;
    // The outputs are written through &mut slices: none may alias an input
    // or another output.
    for out in s.out {
        if overlaps(out.cast_const(), s.sigma_a, n) || overlaps(out.cast_const(), s.sigma_s, n) {
            return Err(sk_status::SK_ERR_OVERLAP);
        }
    }
    if overlaps(weight, r_u, n) || overlaps(weight, r_l, n) || overlaps(r_u, r_l, n) {
        return Err(sk_status::SK_ERR_OVERLAP);
    }
    let spectrum = Spectrum {
        sigma_a: unsafe { slice_in(s.sigma_a, n) }?,
        sigma_s: unsafe { slice_in(s.sigma_s, n) }?,
        hero: s.hero as usize,
    };
    let mut ratios = Ratios {
        weight: unsafe { slice_out(weight, n) }?,
        r_u: unsafe { slice_out(r_u, n) }?,
        r_l: unsafe { slice_out(r_l, n) }?,
    };
    let (ray, budget, rng) = (w.ray, w.budget, w.rng);
    let r = if delta {
        b.max
            .delta_track_spectral(grid, &spectrum, ray, budget, rng, &mut ratios)
            .map(|x| Found::track(x.t, x.event, x.steps))
    } else {
        b.max
            .ratio_track_spectral(grid, &spectrum, ray, budget, rng, &mut ratios)
            .map(|steps| Found {
                steps,
                ..Found::nothing()
            })
    };
    r.map_err(Into::into)
}

/// Delta (Woodcock) tracking: a free-flight distance through the medium.
/// At each tentative collision one uniform xi decides absorption
/// (xi sigma_maj < sigma_a), scattering (< sigma_a + sigma_s) or a null
/// collision; a grid without majorants instead keeps a collision when
/// xi sigma_maj < sigma_t and then draws a second uniform, scattering
/// below the grid's albedo (the draws of 0.1, so a seed gives what it
/// gave); writes t, event and steps (with SK_TRACK_NONBOUNDING: weighted
/// delta tracking, also weight, exceeded and cell; with a spectrum:
/// hero-wavelength tracking, also the spectrum's outputs).
/// SK_ERR_NULL for NULL args, out, rng or callback, or a medium with
/// neither grid nor coefficients; SK_ERR_DOMAIN for a medium with both, a
/// never-built grid or majorants, majorants over another box than the
/// grid's, a zero or non-finite vector, a bad segment (t_max = +inf with a
/// callback and no majorants), a sigma_t above its majorant (unless
/// SK_TRACK_NONBOUNDING), or a bad majorant value met on the way;
/// SK_ERR_METHOD for unknown flags; SK_ERR_BUDGET when the budget runs out.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track(
    args: *const sk_track_args,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { run(Estimator::Delta, args, out) }
}

/// Double twin of `sk_delta_track`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_delta_track_f64(
    args: *const sk_track_args_f64,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { run(Estimator::Delta, args, out) }
}

/// Ratio tracking: an unbiased estimate of the transmittance of the
/// segment (tr), the product of 1 - sigma_t/sigma_maj at the tentative
/// collisions, with Russian roulette below a weight of 0.05 (it survives
/// with probability 1/4, times 4). With SK_TRACK_NONBOUNDING: signed
/// weights where a majorant does not bound (exceeded, cell); with a
/// spectrum: hero-wavelength ratio tracking into the spectrum's outputs
/// (tr NaN). Statuses as sk_delta_track.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track(
    args: *const sk_track_args,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { run(Estimator::Ratio, args, out) }
}

/// Double twin of `sk_ratio_track`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ratio_track_f64(
    args: *const sk_track_args_f64,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { run(Estimator::Ratio, args, out) }
}

/// Residual ratio tracking (Novak et al. 2014): the transmittance
/// exp(-integral of the minorants) along the segment, exact, times ratio
/// tracking of the residual, its tentative collisions at `strata` times
/// the rate majorant - minorant (0: twice, which halves the variance
/// where the residual is thin for less than twice the time; 1 is the
/// published rate); unbiased, exact where the density is constant per
/// cell. Needs majorants with
/// minorants (SK_ERR_DOMAIN otherwise, and for a cell whose minorant
/// exceeds its majorant); other statuses as sk_ratio_track.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_residual_ratio_track(
    args: *const sk_track_args,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { run(Estimator::Residual, args, out) }
}

/// Double twin of `sk_residual_ratio_track`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_residual_ratio_track_f64(
    args: *const sk_track_args_f64,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { run(Estimator::Residual, args, out) }
}

/// The unbiased ray-marching transmittance estimator (Kettunen et al.
/// 2021, power series): marches of `strata` strata (0: the library's
/// choice, see sk_track_args), a power series in independent marches (at
/// least 3, on average 4.8) cut at a random order and reweighted. With
/// `majorants` the strata are placed by them: each holds an equal share of
/// the integral of sigma_maj - sigma_min along the segment, so cells with
/// no residual (empty, or constant with minorants) take no evaluation and
/// the minorants' part is exact; with one majorant they are equal lengths.
/// Exact for a medium constant along the ray. One estimate may leave
/// [0, 1]. Statuses as sk_ratio_track; also SK_ERR_DOMAIN when
/// the series overflows (strata far too coarse for the medium), and
/// SK_ERR_BUDGET when more than `budget` density evaluations would be
/// needed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ray_march(
    args: *const sk_track_args,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { run(Estimator::RayMarch, args, out) }
}

/// Double twin of `sk_ray_march`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_ray_march_f64(
    args: *const sk_track_args_f64,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { run(Estimator::RayMarch, args, out) }
}

/// The telescoping ray-marching estimator (Rhee & Glynn 2015 as Misso et
/// al. 2022 apply it): exp(-X_0) of a stratified march of n strata (0: the
/// library's choice, see sk_track_args), plus corrections between marches
/// of n 2^k and n 2^(k-1) strata that share their points, each further
/// level taken with probability 1/3 and reweighted; strata placed as
/// sk_ray_march places them; unbiased, exact for a constant medium, 3n
/// evaluations on average. Statuses as sk_ray_march.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_telescoping_march(
    args: *const sk_track_args,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { run(Estimator::Telescoping, args, out) }
}

/// Double twin of `sk_telescoping_march`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_telescoping_march_f64(
    args: *const sk_track_args_f64,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { run(Estimator::Telescoping, args, out) }
}

/// The radiance a medium emits along the segment, the integral of
/// T sigma_a L_e, with the segment's transmittance (tr): by ratio tracking
/// that scores sigma_a L_e / sigma_maj at every tentative collision
/// (unbiased; needs majorants, or sigma_maj for a callback), L_e from
/// medium.emission (a grid over the same box) or medium.emission_fn; or,
/// for a medium constant per cell (no grid, no coefficients: majorants
/// holding sigma_t and emission_cells sigma_a L_e per cell, same cells and
/// box), exactly (steps 0). Statuses as sk_ratio_track; SK_ERR_DOMAIN also
/// for no source or more than one, and for a negative or non-finite L_e.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_emission_track(
    args: *const sk_track_args,
    out: *mut sk_track_result,
) -> sk_status {
    unsafe { run(Estimator::Emission, args, out) }
}

/// Double twin of `sk_emission_track`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_emission_track_f64(
    args: *const sk_track_args_f64,
    out: *mut sk_track_result_f64,
) -> sk_status {
    unsafe { run(Estimator::Emission, args, out) }
}
