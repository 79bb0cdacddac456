//! Mixtures of phase functions: a cell of atmosphere or cloud holds
//! molecules, aerosol and droplets at once, and its phase function is the
//! scattering-weighted sum of theirs,
//!
//! `p(μ) = Σ_i w_i p_i(μ)`,  `F(μ) = Σ_i w_i F_i(μ)`,  `g = Σ_i w_i g_i`,
//!
//! with `w_i` the component's share of the scattering coefficient. A
//! [`Mixture`] holds up to [`MAX_PARTS`] components, each a [`Phase`] or a
//! [`Table`] (measured data, or any phase function tabulated), and samples
//! it two ways:
//!
//! * [`Mixture::sample_cos_by_lobe`]: one uniform picks the component by
//!   its weight and, rescaled into that component's share of `[0, 1]`,
//!   samples it. Exact in distribution, as fast as the chosen component
//!   plus a short search; not monotone in `u`.
//! * [`sample_cos`](PhaseFunction::sample_cos): the exact inverse of `F`,
//!   monotone in `u` (for stratified and quasi-random uniforms): a
//!   safeguarded Newton solve in f64 on the f64 CDFs of the components, in
//!   the smaller tail (`F = u` for `u ≤ ½`, `1 − F = 1 − u` above), from
//!   the weighted mean of the components' own samples at `u`.

pub mod spectral;

use crate::error::Error;
use crate::math::geometry::{Vec3, direction_about_turns, sin_from_cos};
use crate::math::numeric::inverse_cdf;
use crate::math::real::Real;
use crate::phase::{Phase, PhaseFunction, moments};
use crate::table::Table;

/// The most components one mixture holds.
pub const MAX_PARTS: usize = 8;

/// One component of a [`Mixture`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Part<'a, T> {
    /// A phase function model.
    Phase(Phase<T>),
    /// A table (its own distribution: [`Table::pdf`], [`Table::cdf`]).
    Table(Table<'a, T>),
}

impl<T: Real> Part<'_, T> {
    /// The component's density per steradian at `cos_theta`.
    pub fn pdf(&self, cos_theta: T) -> T {
        match self {
            Part::Phase(p) => p.pdf(cos_theta),
            Part::Table(t) => t.pdf(cos_theta),
        }
    }
    /// The component's CDF at `cos_theta`.
    pub fn cdf(&self, cos_theta: T) -> T {
        match self {
            Part::Phase(p) => p.cdf(cos_theta),
            Part::Table(t) => t.cdf(cos_theta),
        }
    }
    /// The component's own sampler at `u`.
    pub fn sample_cos(&self, u: T) -> T {
        match self {
            Part::Phase(p) => p.sample_cos(u),
            Part::Table(t) => t.sample_cos(u),
        }
    }
    /// The component's own sampler at `u`, with `sin θ` as closely as it
    /// knows it ([`PhaseFunction::sample_cos_sin`]; a table's from `cos θ`).
    pub fn sample_cos_sin(&self, u: T) -> (T, T) {
        match self {
            Part::Phase(p) => p.sample_cos_sin(u),
            Part::Table(t) => {
                let mu = t.sample_cos(u);
                (mu, sin_from_cos(mu))
            }
        }
    }
    /// The component's density per steradian at the angle `(cos θ, sin θ)`
    /// ([`PhaseFunction::pdf_cos_sin`]; a table's at `cos θ`).
    pub fn pdf_cos_sin(&self, cos_theta: T, sin_theta: T) -> T {
        match self {
            Part::Phase(p) => p.pdf_cos_sin(cos_theta, sin_theta),
            Part::Table(t) => t.pdf(cos_theta),
        }
    }
    /// The component's mean cosine.
    pub fn mean_cosine(&self) -> T {
        match self {
            Part::Phase(p) => p.mean_cosine(),
            Part::Table(t) => t.mean_cosine(),
        }
    }
}

/// A component with what the exact inverse evaluates: a model again in
/// f64 (a table evaluates in f64 itself).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Held<'a, T> {
    part: Part<'a, T>,
    wide: Option<Phase<f64>>,
}

impl<T: Real> Held<'_, T> {
    /// `(F(μ), p(μ))` in f64.
    fn wide(&self, mu: f64) -> (f64, f64) {
        // By reference: matching on copies moved a model of up to 256
        // bytes per evaluation where the compiler did not see through it.
        match (&self.wide, &self.part) {
            (Some(p), _) => (p.cdf(mu), p.pdf(mu)),
            (None, Part::Table(t)) => (t.cdf_f64(mu), t.pdf_f64(mu)),
            (None, Part::Phase(p)) => (
                p.cdf(T::from_f64(mu)).to_f64(),
                p.pdf(T::from_f64(mu)).to_f64(),
            ),
        }
    }
}

/// A mixture of up to [`MAX_PARTS`] phase functions and tables with
/// weights (normalised to sum 1). `Copy`; borrows its tables' data.
///
/// # Example
///
/// Air with a little haze: Rayleigh and a forward HG lobe, 70 : 30.
///
/// ```
/// use scatterkit::mixture::{Mixture, Part};
/// use scatterkit::{Phase, PhaseFunction};
///
/// let air = Part::Phase(Phase::<f64>::rayleigh());
/// let haze = Part::Phase(Phase::henyey_greenstein(0.8).unwrap());
/// let mix = Mixture::new(&[(air, 0.7), (haze, 0.3)]).unwrap();
/// assert!((mix.mean_cosine() - 0.3 * 0.8).abs() < 1e-12);
/// let mu = mix.sample_cos(0.25); // monotone in u
/// assert!((mix.cdf(mu) - 0.25).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mixture<'a, T> {
    parts: [Option<Held<'a, T>>; MAX_PARTS],
    /// The normalised weights, and their running sums (the last is 1).
    weights: [T; MAX_PARTS],
    ends: [T; MAX_PARTS],
    /// The weights normalised in f64, for the exact inverse (normalising
    /// in `T` would perturb an f32 mixture's CDF by its rounding).
    wide_weights: [f64; MAX_PARTS],
    /// `F(−1 + ε/4)` in f64 (`ε` the machine epsilon of `T`, so `ε/4`
    /// is half the spacing of `T` just above −1): below it the exact
    /// inverse rounds to −1 in `T`.
    floor: f64,
    n: usize,
}

impl<'a, T: Real> Mixture<'a, T> {
    /// The mixture of `parts`, each with a weight (finite, `≥ 0`, not all
    /// 0; normalised here). [`Error::Size`] for no part or more than
    /// [`MAX_PARTS`]; [`Error::Domain`] for a bad weight.
    pub fn new(parts: &[(Part<'a, T>, T)]) -> Result<Self, Error> {
        Self::new_with(parts, true)
    }

    /// [`new`](Self::new), with the f64 copies of the models if `wide`.
    fn new_with(parts: &[(Part<'a, T>, T)], wide: bool) -> Result<Self, Error> {
        if parts.is_empty() || parts.len() > MAX_PARTS {
            return Err(Error::Size);
        }
        let total = parts.iter().fold(T::ZERO, |s, &(_, w)| s + w);
        let bad = |w: T| !(w >= T::ZERO && w.is_finite());
        if parts.iter().any(|&(_, w)| bad(w)) || !(total > T::ZERO && total.is_finite()) {
            return Err(Error::Domain);
        }
        let mut m = Mixture {
            parts: [None; MAX_PARTS],
            weights: [T::ZERO; MAX_PARTS],
            ends: [T::ONE; MAX_PARTS],
            wide_weights: [0.0; MAX_PARTS],
            floor: 0.0,
            n: parts.len(),
        };
        let wide_total = parts.iter().fold(0.0, |s, &(_, w)| s + w.to_f64());
        let mut sum = T::ZERO;
        for (i, &(part, w)) in parts.iter().enumerate() {
            let wide = match part {
                Part::Phase(p) if wide => Some(p.cast()),
                _ => None,
            };
            m.parts[i] = Some(Held { part, wide });
            m.weights[i] = w / total;
            m.wide_weights[i] = w.to_f64() / wide_total;
            sum += w;
            // The last running sum is exactly 1, so every u finds a part.
            m.ends[i] = if i + 1 == parts.len() {
                T::ONE
            } else {
                sum / total
            };
        }
        m.floor = m.wide(-1.0 + 0.25 * T::EPSILON.to_f64()).0;
        Ok(m)
    }

    /// [`new`](Self::new) without the f64 copies of the models, cheaper to
    /// build: for callers that use only the lobe choice, the density and
    /// the CDF (the C layer's fast calls). Its exact inverse evaluates the
    /// models in `T`: an f32 mixture's then loses digits.
    pub fn new_narrow(parts: &[(Part<'a, T>, T)]) -> Result<Self, Error> {
        Self::new_with(parts, false)
    }

    /// The running sums of the normalised weights that the lobe choice
    /// compares `u` with (the last is exactly 1; entries past the last
    /// component are 1).
    pub fn ends(&self) -> [T; MAX_PARTS] {
        self.ends
    }

    /// The number of components.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Never true: a mixture has at least one component.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Component `i`'s normalised weight (0 past the last).
    pub fn weight(&self, i: usize) -> T {
        self.weights.get(i).copied().unwrap_or(T::ZERO)
    }

    /// The components with their normalised weights.
    fn held(&self) -> impl Iterator<Item = (&Held<'a, T>, T)> {
        self.parts
            .iter()
            .zip(self.weights.iter())
            .take(self.n)
            .filter_map(|(p, &w)| p.as_ref().map(|p| (p, w)))
    }

    /// The lobe choice: the component whose share of `[0, 1]` holds `u`
    /// (clamped; NaN gives NaN), sampled at `u` rescaled into that share.
    /// Exact in distribution; not monotone in `u`.
    pub fn sample_cos_by_lobe(&self, u: T) -> T {
        match lobe(self.ends.get(..self.n).unwrap_or(&[]), u) {
            // Borrowed, not copied: a held component carries its f64 twin.
            Some((i, v)) => self
                .parts
                .get(i)
                .and_then(Option::as_ref)
                .map_or(T::NAN, |h| h.part.sample_cos(v)),
            None => T::NAN,
        }
    }

    /// Component `i` (`None` past the last).
    pub fn part(&self, i: usize) -> Option<Part<'a, T>> {
        self.parts.get(i).copied().flatten().map(|h| h.part)
    }

    /// A direction about the unit `w_in` with `cos θ` from
    /// [`sample_cos_by_lobe`](Self::sample_cos_by_lobe)`(u1)` and azimuth
    /// `2π u2`, and the mixture's density per steradian there: what a
    /// renderer wants (the exact inverse costs a solve).
    pub fn sample_dir_by_lobe(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        let mu = self.sample_cos_by_lobe(u1);
        let dir = direction_about_turns(w_in, mu, sin_from_cos(mu), u2.clamp01());
        (dir, self.pdf(mu))
    }

    /// The Legendre moments `χ_0 … χ_{n−1}` into `out` (`n = out.len()`):
    /// `Σ w_i χ_{l,i}`, each model's by its closed form where it has one,
    /// the others and tables by quadrature over their inverse CDF
    /// ([`crate::phase::moments`]).
    pub fn legendre_moments(&self, out: &mut [T]) {
        for o in out.iter_mut() {
            *o = T::ZERO;
        }
        for (h, w) in self.held() {
            if let Part::Phase(p) = h.part {
                if let Some(chi) = moments::closed_form(&p) {
                    for (l, o) in out.iter_mut().enumerate() {
                        *o += w * T::from_f64(chi(l));
                    }
                    continue;
                }
            }
            let mu = |u: f64| h.part.sample_cos(T::from_f64(u)).to_f64();
            let mut block = [T::ZERO; 32];
            for (k, chunk) in out.chunks_mut(32).enumerate() {
                let part = block.get_mut(..chunk.len()).unwrap_or(&mut []);
                moments::legendre_moments_of(mu, 32 * k, part);
                for (o, &b) in chunk.iter_mut().zip(part.iter()) {
                    *o += w * b;
                }
            }
        }
    }

    /// `(F, 2π p)` of the mixture at `μ`, in f64.
    fn wide(&self, mu: f64) -> (f64, f64) {
        let parts = self.parts.iter().zip(self.wide_weights.iter()).take(self.n);
        parts.fold((0.0, 0.0), |(f, d), (p, &w)| {
            let (pf, pd) = p.as_ref().map_or((f64::NAN, f64::NAN), |p| p.wide(mu));
            (f + w * pf, d + w * pd * core::f64::consts::TAU)
        })
    }

    /// The exact inverse in f64 (module docs).
    fn inverse(&self, u: T) -> f64 {
        let u = u.clamp01();
        if u.is_nan() {
            return f64::NAN;
        }
        let seed = self.held().fold(0.0, |s, (p, w)| {
            s + w.to_f64() * p.part.sample_cos(u).to_f64()
        });
        inverse_cdf(|mu| self.wide(mu), u.to_f64(), seed)
    }
}

/// The lobe choice on the running sums `ends` of normalised weights (the
/// last 1): the first component whose share of `[0, 1]` holds `u`
/// (clamped) and `u` rescaled into that share; at `u = 1` the last
/// component with a positive share, at 1. `None` for a NaN `u` or no
/// share.
pub(crate) fn lobe<T: Real>(ends: &[T], u: T) -> Option<(usize, T)> {
    let u = u.clamp01();
    if u.is_nan() {
        return None;
    }
    let (mut start, mut last) = (T::ZERO, None);
    for (i, &end) in ends.iter().enumerate() {
        let w = end - start;
        if w > T::ZERO {
            if u < end {
                return Some((i, ((u - start) / w).clamp01()));
            }
            last = Some((i, T::ONE));
        }
        start = end;
    }
    last
}

impl<T: Real> PhaseFunction<T> for Mixture<'_, T> {
    fn pdf(&self, cos_theta: T) -> T {
        self.held()
            .fold(T::ZERO, |s, (p, w)| s + w * p.part.pdf(cos_theta))
    }
    fn cdf(&self, cos_theta: T) -> T {
        let c = self
            .held()
            .fold(T::ZERO, |s, (p, w)| s + w * p.part.cdf(cos_theta));
        if c.is_nan() { c } else { c.clamp01() }
    }
    fn sample_cos(&self, u: T) -> T {
        // Where the exact answer lies within half a spacing of T above −1
        // it rounds to −1: no solve. (In that far tail, u down to the
        // subnormals, the solve costs several times a usual one, and it is
        // where most f32 values of u lie.)
        if u.to_f64() < self.floor {
            return -T::ONE;
        }
        T::from_f64(self.inverse(u).clamp(-1.0, 1.0))
    }
    fn mean_cosine(&self) -> T {
        self.held()
            .fold(T::ZERO, |s, (p, w)| s + w * p.part.mean_cosine())
    }
}
