//! Spectral media: delta and ratio tracking for several wavelength samples
//! at once, one path per hero wavelength (pbrt-v4, §14.2 of the 4th
//! edition; Wilkie et al., "Hero Wavelength Spectral Sampling", EGSR 2014).
//!
//! A grid holds the density `ρ(p)`; channel `c` (a wavelength sample) has
//! its own coefficients per unit density, `σ_a,c ρ` and `σ_s,c ρ`. The
//! majorants are those of the density ([`Majorants::build_density`]):
//! channel `c`'s majorant is `k_c M` with `k_c = σ_a,c + σ_s,c` and `M` the
//! cell's density majorant. Free paths are drawn at the hero channel's
//! majorant `k_h M`; every channel's weight carries the ratio of its own
//! path density to the hero's, as pbrt-v4's `VolPathIntegrator` keeps them:
//!
//! * `weight` (pbrt's `β` or `T_ray`): the path's contribution for the
//!   channel over the hero's sampling density;
//! * `r_u`: the channel's probability of the same path under delta
//!   tracking (unidirectional), over the hero's sampling density;
//! * `r_l`: the same under free-flight sampling alone (ratio tracking, as
//!   light sampling uses it), over the hero's sampling density.
//!
//! With the hero chosen uniformly among the channels, `weight[c] /
//! mean(r_u)` is an unbiased estimate for channel `c` of what delta
//! tracking estimates (the one-sample balance heuristic over the hero
//! choice), and `weight[c] / mean(r_l)` of the transmittance from ratio
//! tracking; a renderer that also samples lights keeps multiplying the
//! ratios along the path as pbrt-v4 does. With a fixed hero those
//! quotients are biased where channels differ: rotate or draw the hero.
//!
//! At most [`MAX_CHANNELS`] channels (the accumulators live on the stack:
//! no allocation); outputs are written only on success.

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::majorant::{Majorants, Tentative, Track};
use crate::medium::{Event, Grid, ROULETTE_BELOW, Ray, roulette_factor};
use rand_core::Rng;

/// The most channels one spectral call takes.
pub const MAX_CHANNELS: usize = 16;

/// The channels' coefficients per unit density and the hero.
#[derive(Clone, Copy, Debug)]
pub struct Spectrum<'a, T> {
    /// `σ_a,c` per unit density, one per channel, each finite and `≥ 0`.
    pub sigma_a: &'a [T],
    /// `σ_s,c` per unit density, as many as `sigma_a`.
    pub sigma_s: &'a [T],
    /// The channel whose majorant draws the free paths (`< channels`).
    pub hero: usize,
}

/// The per-channel outputs (module docs), each at least as long as the
/// spectrum; written only on success.
#[derive(Debug)]
pub struct Ratios<'a, T> {
    /// The path weight per channel (pbrt-v4's `β`, or `T_ray` for ratio
    /// tracking).
    pub weight: &'a mut [T],
    /// Delta-tracking path density of each channel over the hero's.
    pub r_u: &'a mut [T],
    /// Free-flight path density of each channel over the hero's.
    pub r_l: &'a mut [T],
}

/// Per-channel accumulators.
#[derive(Clone, Copy)]
struct Acc<T> {
    n: usize,
    k: [T; MAX_CHANNELS],
    /// The largest `k_c`.
    k_max: T,
    weight: [T; MAX_CHANNELS],
    r_u: [T; MAX_CHANNELS],
    r_l: [T; MAX_CHANNELS],
}

impl<T: Real> Acc<T> {
    fn new(s: &Spectrum<'_, T>) -> Result<Self, Error> {
        let n = s.sigma_a.len();
        if n == 0 || n > MAX_CHANNELS || s.sigma_s.len() != n {
            return Err(Error::Size);
        }
        if s.hero >= n {
            return Err(Error::Domain);
        }
        let mut k = [T::ZERO; MAX_CHANNELS];
        for ((kc, &a), &b) in k.iter_mut().zip(s.sigma_a).zip(s.sigma_s) {
            let ok = |x: T| x >= T::ZERO && x.is_finite();
            if !(ok(a) && ok(b) && (a + b).is_finite()) {
                return Err(Error::Domain);
            }
            *kc = a + b;
        }
        let one = [T::ONE; MAX_CHANNELS];
        Ok(Acc {
            n,
            k,
            k_max: k.iter().fold(T::ZERO, |a, &b| a.max_of(b)),
            weight: one,
            r_u: one,
            r_l: one,
        })
    }

    /// Multiplies channel `c`'s weight, `r_u` and `r_l` by `T_maj,c` times
    /// `w`, `u` and `l` of `f(c, k_c)`, over `pdf`; `since` is `∫ M dt`
    /// since the previous event (`T_maj,c = exp(−k_c since)`).
    fn scale(&mut self, since: T, pdf: T, f: impl Fn(usize, T) -> (T, T, T)) {
        let channels = self
            .k
            .iter()
            .zip(
                self.weight
                    .iter_mut()
                    .zip(self.r_u.iter_mut().zip(self.r_l.iter_mut())),
            )
            .take(self.n)
            .enumerate();
        for (c, (&k, (w, (u, l)))) in channels {
            let tm = (-(k * since)).exp();
            let (fw, fu, fl) = f(c, k);
            *w *= tm * fw / pdf;
            *u *= tm * fu / pdf;
            *l *= tm * fl / pdf;
        }
    }

    /// The mean of the first `n` values.
    fn mean(x: &[T; MAX_CHANNELS], n: usize) -> T {
        x.iter().take(n).fold(T::ZERO, |a, &b| a + b) / T::from_index(n)
    }

    /// The weights of the channels in use.
    fn weights(&mut self) -> impl Iterator<Item = &mut T> {
        self.weight.iter_mut().take(self.n)
    }

    /// `k_c` of channel `c` (0 out of range).
    fn k(&self, c: usize) -> T {
        self.k.get(c).copied().unwrap_or(T::ZERO)
    }

    fn write(&self, out: &mut Ratios<'_, T>) {
        let pairs = [
            (&mut *out.weight, &self.weight),
            (&mut *out.r_u, &self.r_u),
            (&mut *out.r_l, &self.r_l),
        ];
        for (dst, src) in pairs {
            for (d, &s) in dst.iter_mut().zip(src.iter()).take(self.n) {
                *d = s;
            }
        }
    }
}

/// Coefficient `c` of a channel slice (0 out of range).
#[inline(always)]
fn at<T: Real>(x: &[T], c: usize) -> T {
    x.get(c).copied().unwrap_or(T::ZERO)
}

/// [`Error::Size`] unless every output holds `n` values.
fn check_out<T>(out: &Ratios<'_, T>, n: usize) -> Result<(), Error> {
    if out.weight.len() >= n && out.r_u.len() >= n && out.r_l.len() >= n {
        Ok(())
    } else {
        Err(Error::Size)
    }
}

impl<T: Real> Majorants<'_, T> {
    /// Spectral delta tracking through `grid`'s density with the channels
    /// of `spectrum`, walking these density majorants
    /// ([`Majorants::build_density`]; same box as the grid) along `ray`. At each tentative collision one uniform picks
    /// absorption, scattering or a null collision with the hero's
    /// probabilities; null collisions and the real event update every
    /// channel's ratios as pbrt-v4 does. Returns the event (the distance,
    /// or the exit for an escape) and writes the ratios; a path whose
    /// weights all fall to 0 on the way ends as [`Event::Absorbed`] with
    /// zero weights. Errors: as
    /// [`Majorants::delta_track`], and [`Error::Size`] for 0 or more than
    /// [`MAX_CHANNELS`] channels, coefficient slices of different lengths
    /// or short outputs, [`Error::Domain`] for a negative or non-finite
    /// coefficient, a channel's `σ_a + σ_s` that overflows, a hero out of
    /// range, or a cell met on the way where a channel's majorant
    /// `(σ_a + σ_s)·σ_maj` overflows (tracking could not step through it:
    /// its weights would be ∞/∞).
    #[allow(clippy::too_many_arguments)]
    pub fn delta_track_spectral<R: Rng + ?Sized>(
        &self,
        grid: &Grid<'_, T>,
        spectrum: &Spectrum<'_, T>,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
        out: &mut Ratios<'_, T>,
    ) -> Result<Track<T>, Error> {
        let mut acc = self.prepare(grid, spectrum, ray, out)?;
        let (h, sa, ss) = (spectrum.hero, spectrum.sigma_a, spectrum.sigma_s);
        let rate = acc.k(h);
        let k_max = acc.k_max;
        let visit = |c: Tentative<T>, r: &mut R| {
            let rho = density_within(grid, c.p, c.value)?;
            let m = scalable(k_max, c.value)?;
            // The hero's free-flight density and event probabilities.
            let tm_h = (-(rate * c.since)).exp();
            let (a_h, s_h) = (at(sa, h) * rho, at(ss, h) * rho);
            let maj_h = rate * m;
            let x = T::uniform(r) * maj_h;
            let null = |k: T| (k * (m - rho)).max_of(T::ZERO);
            if x < a_h + s_h {
                let (coef, event) = if x < a_h {
                    (sa, Event::Absorbed)
                } else {
                    (ss, Event::Scattered)
                };
                let pdf = tm_h * at(coef, h) * rho;
                acc.scale(c.since, pdf, |ch, _| {
                    let s = at(coef, ch) * rho;
                    (s, s, T::ZERO)
                });
                return Ok(Some(event));
            }
            let pdf = tm_h * null(rate);
            if pdf == T::ZERO {
                // Only rounding lands here (the hero has no null
                // collisions where the density meets its majorant):
                // pbrt-v4 ends such a path with weight 0.
                acc.weights().for_each(|w| *w = T::ZERO);
                return Ok(Some(Event::Absorbed));
            }
            acc.scale(c.since, pdf, |_, k| (null(k), null(k), k * m));
            let alive = acc.weights().any(|w| *w > T::ZERO);
            Ok((!alive).then_some(Event::Absorbed))
        };
        let walk = self.walk_at_rate(ray, rate, budget, rng, visit)?;
        let (t, event) = match walk.found {
            Some((t, e)) => (t, e),
            None => {
                let tm_h = (-(rate * walk.tail)).exp();
                acc.scale(walk.tail, tm_h, |_, _| (T::ONE, T::ONE, T::ONE));
                (walk.exit, Event::Escaped)
            }
        };
        acc.write(out);
        Ok(Track {
            t,
            event,
            steps: walk.steps,
        })
    }

    /// Spectral ratio tracking (arguments as
    /// [`delta_track_spectral`](Self::delta_track_spectral)): every
    /// tentative collision is a null one for the estimate; `weight` is
    /// pbrt-v4's `T_ray`, with its Russian roulette once
    /// `max_c weight/mean(r_l + r_u)` falls below 0.05. Returns the number
    /// of tentative collisions.
    #[allow(clippy::too_many_arguments)]
    pub fn ratio_track_spectral<R: Rng + ?Sized>(
        &self,
        grid: &Grid<'_, T>,
        spectrum: &Spectrum<'_, T>,
        ray: Ray<T>,
        budget: u32,
        rng: &mut R,
        out: &mut Ratios<'_, T>,
    ) -> Result<u32, Error> {
        let mut acc = self.prepare(grid, spectrum, ray, out)?;
        let h = spectrum.hero;
        let floor = T::from_f64(ROULETTE_BELOW);
        let rate = acc.k(h);
        let k_max = acc.k_max;
        let visit = |c: Tentative<T>, r: &mut R| {
            let rho = density_within(grid, c.p, c.value)?;
            let m = scalable(k_max, c.value)?;
            let null = |k: T| (k * (m - rho)).max_of(T::ZERO);
            let pdf = (-(rate * c.since)).exp() * rate * m;
            acc.scale(c.since, pdf, |_, k| (null(k), null(k), k * m));
            let n = acc.n;
            let mixed = Acc::mean(&acc.r_l, n) + Acc::mean(&acc.r_u, n);
            let top = acc.weights().fold(T::ZERO, |a, w| a.max_of(*w));
            if top / mixed < floor {
                let keep = roulette_factor(r);
                acc.weights().for_each(|w| *w *= keep);
            }
            Ok(acc.weights().all(|w| *w == T::ZERO).then_some(()))
        };
        let walk = self.walk_at_rate(ray, rate, budget, rng, visit)?;
        if walk.found.is_none() {
            let tm_h = (-(rate * walk.tail)).exp();
            acc.scale(walk.tail, tm_h, |_, _| (T::ONE, T::ONE, T::ONE));
        }
        acc.write(out);
        Ok(walk.steps)
    }

    /// Validates what both spectral calls take (the ray is checked by the
    /// walk).
    fn prepare(
        &self,
        grid: &Grid<'_, T>,
        spectrum: &Spectrum<'_, T>,
        ray: Ray<T>,
        out: &Ratios<'_, T>,
    ) -> Result<Acc<T>, Error> {
        if grid.bounds() != self.bounds() {
            return Err(Error::Domain);
        }
        let acc = Acc::new(spectrum)?;
        check_out(out, acc.n)?;
        ray.checked()?;
        Ok(acc)
    }
}

/// The cell's density majorant `m` if every channel's majorant `k_c·m`
/// is finite (`k_max` the largest `k_c`). Where one overflows, its
/// free-flight density and the weights it divides are ∞/∞ (NaN weights
/// were returned as a result): [`Error::Domain`], as [`Grid::new`]
/// refuses a majorant that overflows.
#[inline(always)]
fn scalable<T: Real>(k_max: T, m: T) -> Result<T, Error> {
    if (k_max * m).is_finite() {
        Ok(m)
    } else {
        Err(Error::Domain)
    }
}

/// The grid's density at `p` if it lies within the cell's majorant `m`.
#[inline(always)]
fn density_within<T: Real>(grid: &Grid<'_, T>, p: Vec3<T>, m: T) -> Result<T, Error> {
    let rho = grid.density(p);
    if rho >= T::ZERO && rho <= m {
        Ok(rho)
    } else {
        Err(Error::Domain)
    }
}
