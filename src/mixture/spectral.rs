//! Wavelength-dependent phase functions, sampled at a hero wavelength.
//!
//! A spectral renderer carries `K` wavelength samples (channels) along one
//! path and draws each direction from one of them, the hero `h` (Wilkie et
//! al., "Hero Wavelength Spectral Sampling", EGSR 2014). Where the phase
//! function differs between channels (Mie droplets, whose lobes narrow
//! with wavelength; Rayleigh against a haze), channel `c`'s throughput
//! takes the ratio of its phase function to the density the direction was
//! drawn from:
//!
//! `ratio_c = p_c(μ) / p_h(μ)`
//!
//! (the phase function is its own density, so this is both the value
//! over the pdf and the channel's path density over the hero's, the
//! `r_u` of the spectral media calls). With the hero drawn uniformly among
//! the channels, `ratio_c / mean_k ratio_k = p_c / mean_k p_k` is the
//! one-sample balance heuristic over the hero choice: unbiased for every
//! channel and bounded by `K`, where `ratio_c` alone can be large where
//! the hero's lobe is narrow and channel `c`'s is not.

use super::Part;
use crate::error::Error;
use crate::math::real::Real;

/// The most channels one call takes (as the spectral media calls).
pub const MAX_CHANNELS: usize = 16;

/// A phase function per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpectralPhase<'a, T> {
    channels: [Option<Part<'a, T>>; MAX_CHANNELS],
    n: usize,
}

impl<'a, T: Real> SpectralPhase<'a, T> {
    /// One phase function (or table) per channel. [`Error::Size`] for none
    /// or more than [`MAX_CHANNELS`].
    pub fn new(channels: &[Part<'a, T>]) -> Result<Self, Error> {
        if channels.is_empty() || channels.len() > MAX_CHANNELS {
            return Err(Error::Size);
        }
        let mut s = SpectralPhase {
            channels: [None; MAX_CHANNELS],
            n: channels.len(),
        };
        for (slot, &c) in s.channels.iter_mut().zip(channels) {
            *slot = Some(c);
        }
        Ok(s)
    }

    /// The number of channels.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Never true: there is at least one channel.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The channels in use.
    fn parts(&self) -> impl Iterator<Item = &Part<'a, T>> {
        self.channels.iter().take(self.n).flatten()
    }

    /// Each channel's density per steradian at `cos_theta` into `pdf_out`
    /// (at least [`len`](Self::len) values, else [`Error::Size`]; nothing
    /// written then): for light-sampled directions and their MIS weights.
    pub fn pdf(&self, cos_theta: T, pdf_out: &mut [T]) -> Result<(), Error> {
        if pdf_out.len() < self.n {
            return Err(Error::Size);
        }
        for (out, part) in pdf_out.iter_mut().zip(self.parts()) {
            *out = part.pdf(cos_theta);
        }
        Ok(())
    }

    /// `cos θ` drawn from channel `hero`'s phase function at `u` (its own
    /// sampler: the exact inverse for models, the lookup for tables), and
    /// every channel's `ratio_c = p_c(μ)/p_hero(μ)` into `ratio_out` (module
    /// docs; `ratio_hero = 1`), each density at the sampled angle
    /// ([`Part::pdf_cos_sin`]: near `ν = 0` a Fournier–Forand hero puts up
    /// to half its samples where `cos θ` rounds to 1, its pole).
    /// [`Error::Size`] for `hero` out of range or `ratio_out` shorter than
    /// [`len`](Self::len); [`Error::Domain`] for a
    /// NaN `u` or a `μ` where the hero's density is 0 (a table's gap). On
    /// error nothing is written.
    pub fn sample_cos(&self, hero: usize, u: T, ratio_out: &mut [T]) -> Result<T, Error> {
        if hero >= self.n || ratio_out.len() < self.n {
            return Err(Error::Size);
        }
        let h = self
            .channels
            .get(hero)
            .copied()
            .flatten()
            .ok_or(Error::Size)?;
        if u.is_nan() {
            return Err(Error::Domain);
        }
        let (mu, sin) = h.sample_cos_sin(u);
        let ph = h.pdf_cos_sin(mu, sin);
        if !(ph > T::ZERO && ph.is_finite()) {
            return Err(Error::Domain);
        }
        for (i, (out, part)) in ratio_out.iter_mut().zip(self.parts()).enumerate() {
            *out = if i == hero {
                T::ONE
            } else {
                part.pdf_cos_sin(mu, sin) / ph
            };
        }
        Ok(mu)
    }
}
