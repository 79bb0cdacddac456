//! Mie scattering averaged over a distribution of sphere sizes (fog, cloud,
//! haze, ocean particles), in f64, into the caller's memory.
//!
//! For a number distribution `n(r)` of radii on `[r_min, r_max]` the mean
//! cross sections per particle are `C = ∫ n(r) π r² Q(x(r)) dr / ∫ n(r) dr`
//! (`x = 2π r n_medium / λ`), the asymmetry `g = ∫ n C_sca g dr / ∫ n C_sca
//! dr`, and the phase function per steradian
//! `p(μ) = ∫ n (|S1|² + |S2|²)/(2k²) dr / ∫ n C_sca dr`, `k = 2π n_medium / λ`
//! (Bohren & Huffman 1983, §4.4; Hansen & Travis, Space Sci. Rev. 16, 1974,
//! §2). The distribution is used as truncated to the range and normalised
//! over it.
//!
//! Quadrature: composite Simpson in `ln r` with `intervals` (a multiple of
//! 4) equal steps, one Mie solution per node. The error estimate is the
//! difference between that rule and Simpson's rule on every other node
//! (half the intervals), which costs nothing more. For a smooth integrand
//! it overstates the error about fifteenfold; for nearly non-absorbing
//! spheres, whose efficiencies carry narrow resonances in `x` that the
//! grid samples almost at random, it is an estimate, not a bound: against
//! sums at 65536 intervals the actual error was within 2.6× of it
//! (`docs/measured/polydisperse.md`, `tests/models/polydisperse.rs`). Raise `intervals`
//! until the estimate is small enough.

use crate::error::Error;
use crate::mie::{self, Complex, Mie};
use core::f64::consts::PI;

/// A number distribution of sphere radii (any length unit, the same as the
/// wavelength's), unnormalised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeDistribution {
    /// Lognormal: `n(r) ∝ exp(−ln²(r/r_g) / (2 ln² σ_g)) / r`, median radius
    /// `r_g > 0`, geometric standard deviation `σ_g > 1` (haze, smoke,
    /// fog).
    LogNormal {
        /// Median radius `r_g`.
        median_radius: f64,
        /// Geometric standard deviation `σ_g`.
        sigma_g: f64,
    },
    /// Deirmendjian's modified gamma: `n(r) ∝ r^α exp(−b r^γ)`, `α ≥ 0`,
    /// `b > 0`, `γ > 0` (clouds, haze; mode radius `(α / (b γ))^{1/γ}`).
    ModifiedGamma {
        /// `α`.
        alpha: f64,
        /// `b` (in the radius unit to the power `−γ`).
        b: f64,
        /// `γ`.
        gamma: f64,
    },
    /// Junge's power law: `n(r) ∝ r^{−slope}`, `0 < slope ≤ 10` (ocean
    /// particles, slope 3 to 5; Fournier–Forand's `μ_J`). A power law has
    /// no natural range: give `r_min` and `r_max`
    /// ([`default_range`](Self::default_range) is `None`).
    Junge {
        /// The slope `μ_J` of the number density per unit radius.
        slope: f64,
    },
}

impl SizeDistribution {
    /// Deirmendjian's cumulus cloud C.1 (radii in µm): `α = 6`, `b = 1.5`,
    /// `γ = 1`, mode 4 µm (D. Deirmendjian, *Electromagnetic Scattering on
    /// Spherical Polydispersions*, 1969, §6).
    pub const CLOUD_C1: SizeDistribution = SizeDistribution::ModifiedGamma {
        alpha: 6.0,
        b: 1.5,
        gamma: 1.0,
    };
    /// Deirmendjian's haze M (marine, radii in µm): `α = 1`, `b = 8.9443`,
    /// `γ = ½`, mode 0.05 µm.
    pub const HAZE_M: SizeDistribution = SizeDistribution::ModifiedGamma {
        alpha: 1.0,
        b: 8.9443,
        gamma: 0.5,
    };
    /// Deirmendjian's haze L (continental, radii in µm): `α = 2`,
    /// `b = 15.1186`, `γ = ½`, mode 0.07 µm.
    pub const HAZE_L: SizeDistribution = SizeDistribution::ModifiedGamma {
        alpha: 2.0,
        b: 15.1186,
        gamma: 0.5,
    };

    fn valid(&self) -> bool {
        match *self {
            SizeDistribution::LogNormal {
                median_radius,
                sigma_g,
            } => median_radius > 0.0 && median_radius.is_finite() && sigma_g > 1.0 && sigma_g < 1e3,
            SizeDistribution::ModifiedGamma { alpha, b, gamma } => {
                (0.0..=100.0).contains(&alpha)
                    && b > 0.0
                    && b < 1e100
                    && gamma > 0.0
                    && gamma <= 10.0
            }
            SizeDistribution::Junge { slope } => slope > 0.0 && slope <= 10.0,
        }
    }

    /// `ln n(r)` up to a constant (finite for `r > 0` and valid parameters).
    fn ln_density(&self, r: f64) -> f64 {
        let lr = libm::log(r);
        match *self {
            SizeDistribution::LogNormal {
                median_radius,
                sigma_g,
            } => {
                let s = libm::log(sigma_g);
                let z = (lr - libm::log(median_radius)) / s;
                -0.5 * z * z - lr
            }
            SizeDistribution::ModifiedGamma { alpha, b, gamma } => {
                alpha * lr - b * libm::exp(gamma * lr)
            }
            SizeDistribution::Junge { slope } => -slope * lr,
        }
    }

    /// The radius where the area-weighted density per `ln r`, `r³ n(r)`,
    /// peaks (`None` for a power law, which has no peak).
    fn area_peak(&self) -> Option<f64> {
        Some(match *self {
            SizeDistribution::LogNormal {
                median_radius,
                sigma_g,
            } => {
                let s = libm::log(sigma_g);
                median_radius * libm::exp(2.0 * s * s)
            }
            SizeDistribution::ModifiedGamma { alpha, b, gamma } => {
                libm::pow((alpha + 3.0) / (b * gamma), 1.0 / gamma)
            }
            SizeDistribution::Junge { .. } => return None,
        })
    }

    /// A radius range outside which `r³ n(r)`, the density of geometric
    /// cross section per `ln r`, is below `10⁻¹²` of its peak: what the
    /// cross sections lose by the truncation is of that order (the
    /// efficiencies are bounded). `None` for invalid parameters, and for
    /// valid ones whose range lies beyond f64 (a modified gamma with a
    /// tiny `b` or `γ`), and for a power law (no peak to measure from).
    pub fn default_range(&self) -> Option<(f64, f64)> {
        if !self.valid() {
            return None;
        }
        let peak = self.area_peak()?;
        let weight = |r: f64| 3.0 * libm::log(r) + self.ln_density(r);
        let top = weight(peak);
        let cut = top + libm::log(1e-12);
        let walk = |factor: f64| {
            let mut r = peak;
            // At most 5000 steps of 2 %: a factor 10⁴³ either way.
            for _ in 0..5000 {
                if weight(r) < cut {
                    break;
                }
                r *= factor;
            }
            r
        };
        let (lo, hi) = (walk(1.0 / 1.02), walk(1.02));
        (lo > 0.0 && hi.is_finite() && lo < hi).then_some((lo, hi))
    }
}

/// Spheres of one material with sizes from a distribution, lit at one
/// wavelength: the input of [`Polydisperse::average`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Polydisperse {
    /// The number distribution of radii.
    pub distribution: SizeDistribution,
    /// Smallest radius (> 0, same unit as the wavelength).
    pub r_min: f64,
    /// Largest radius (> `r_min`).
    pub r_max: f64,
    /// Vacuum wavelength.
    pub wavelength: f64,
    /// Refractive index of the medium around the spheres (> 0).
    pub n_medium: f64,
    /// Relative refractive index `n + ik` of the spheres (as [`Mie::new`]).
    pub m: Complex,
    /// Simpson intervals in `ln r`: a multiple of 4, at least 4.
    pub intervals: usize,
}

/// The averages of [`Polydisperse::average`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Averages {
    /// Mean extinction cross section per particle (the radius unit squared).
    pub c_ext: f64,
    /// Mean scattering cross section per particle.
    pub c_sca: f64,
    /// Mean backscattering cross section per particle (`π r² Q_back`).
    pub c_back: f64,
    /// Asymmetry parameter of the mixture.
    pub g: f64,
    /// Mean geometric cross section `π <r²>` (so `c_ext / area` is the
    /// mean extinction efficiency).
    pub area: f64,
    /// Estimated relative errors of `c_ext`, `c_sca`, `c_back` and the
    /// absolute error of `g`, in that order (module docs). `c_back` is the
    /// slowest to converge: `Q_back` swings with a period in `x` far
    /// shorter than the other efficiencies' (`docs/measured/polydisperse.md`).
    pub errors: [f64; 4],
    /// Estimated largest relative error of the phase function over the
    /// cosines asked for.
    pub phase_error: f64,
}

impl Polydisperse {
    /// The largest size parameter in the range.
    pub fn max_size_parameter(&self) -> f64 {
        2.0 * PI * self.r_max * self.n_medium / self.wavelength
    }

    fn valid(&self) -> bool {
        self.distribution.valid()
            && self.r_min > 0.0
            && self.r_max > self.r_min
            && self.r_max.is_finite()
            && self.wavelength > 0.0
            && self.wavelength.is_finite()
            && self.n_medium > 0.0
            && self.n_medium.is_finite()
            && self.intervals >= 4
            && self.intervals % 4 == 0
            && self.intervals <= 1 << 20
    }

    /// The number of [`Complex`] values [`average`](Self::average) needs in
    /// `buf` (that of the largest sphere), or `None` for input it rejects.
    pub fn buffer_len(&self) -> Option<usize> {
        if !self.valid() {
            return None;
        }
        let x_min = 2.0 * PI * self.r_min * self.n_medium / self.wavelength;
        mie::buffer_len(x_min, self.m)?;
        mie::buffer_len(self.max_size_parameter(), self.m)
    }

    /// Averages over the distribution: the cross sections and `g`
    /// returned, the phase function per steradian at each `mu[i]` written
    /// to `phase[i]`. `scratch` (as long as `mu`) holds the coarser rule's
    /// phase function for the error estimate; `buf` holds at least
    /// [`buffer_len`](Self::buffer_len) values. [`Error::Domain`] for
    /// invalid input (parameters, radii, or a `mu` outside `[−1, 1]`),
    /// [`Error::Size`] for slices of the wrong length or a short `buf`.
    pub fn average(
        &self,
        mu: &[f64],
        phase: &mut [f64],
        scratch: &mut [f64],
        buf: &mut [Complex],
    ) -> Result<Averages, Error> {
        let len = self.buffer_len().ok_or(Error::Domain)?;
        if phase.len() != mu.len() || scratch.len() != mu.len() {
            return Err(Error::Size);
        }
        if !mu.iter().all(|m| (-1.0..=1.0).contains(m)) {
            return Err(Error::Domain);
        }
        let buf = buf.get_mut(..len).ok_or(Error::Size)?;
        phase.fill(0.0);
        scratch.fill(0.0);
        let k = 2.0 * PI * self.n_medium / self.wavelength;
        let (l0, l1) = (libm::log(self.r_min), libm::log(self.r_max));
        let h = (l1 - l0) / self.intervals as f64;
        // Density scale: the largest ln(n r) on the nodes keeps exp() in
        // range however far into a tail the range reaches.
        let ln_nr = |j: usize| {
            let lr = l0 + j as f64 * h;
            self.distribution.ln_density(libm::exp(lr)) + lr
        };
        let ln_ref = (0..=self.intervals)
            .map(ln_nr)
            .fold(f64::NEG_INFINITY, f64::max);
        if !ln_ref.is_finite() {
            return Err(Error::Domain);
        }
        // Sums of [number, area, C_ext, C_sca, C_back, C_sca g] for the
        // fine rule and the coarse rule.
        let (mut fine, mut coarse) = ([0.0f64; 6], [0.0f64; 6]);
        for j in 0..=self.intervals {
            let r = libm::exp(l0 + j as f64 * h);
            let (wf, wc) = simpson_weights(j, self.intervals);
            // n(r) dr = n(r) r d(ln r), scaled by the largest.
            let dens = libm::exp(ln_nr(j) - ln_ref);
            let sphere = Mie::new(k * r, self.m, buf)?;
            let e = sphere.efficiencies;
            let area = PI * r * r;
            let terms = [
                1.0,
                area,
                area * e.q_ext,
                area * e.q_sca,
                area * e.q_back,
                area * e.q_sca * e.g,
            ];
            for ((f, c), t) in fine.iter_mut().zip(coarse.iter_mut()).zip(terms) {
                *f += wf * dens * t;
                *c += wc * dens * t;
            }
            if dens > 0.0 {
                let scale = dens / (2.0 * k * k);
                for ((p, s), &m) in phase.iter_mut().zip(scratch.iter_mut()).zip(mu) {
                    let (s1, s2) = sphere.amplitudes(m);
                    let v = scale * (s1.norm_sqr() + s2.norm_sqr());
                    *p += wf * v;
                    *s += wc * v;
                }
            }
        }
        let [n_f, a_f, e_f, s_f, b_f, g_f] = fine;
        let [n_c, _, e_c, s_c, b_c, g_c] = coarse;
        if !(n_f > 0.0 && s_f > 0.0 && n_c > 0.0 && s_c > 0.0) {
            return Err(Error::Domain);
        }
        let rel = |a: f64, b: f64| {
            if a != 0.0 {
                ((a - b) / a).abs()
            } else {
                b.abs()
            }
        };
        let (g_fine, g_coarse) = (g_f / s_f, g_c / s_c);
        let errors = [
            rel(e_f / n_f, e_c / n_c),
            rel(s_f / n_f, s_c / n_c),
            rel(b_f / n_f, b_c / n_c),
            (g_fine - g_coarse).abs(),
        ];
        let mut phase_error = 0.0f64;
        for (p, s) in phase.iter_mut().zip(scratch.iter()) {
            let (pf, pc) = (*p / s_f, *s / s_c);
            // Not `f64::max`, which passes over NaN: a NaN in the phase
            // function must show in its error estimate.
            let e = rel(pf, pc);
            if e > phase_error || e.is_nan() {
                phase_error = e;
            }
            *p = pf;
        }
        Ok(Averages {
            c_ext: e_f / n_f,
            c_sca: s_f / n_f,
            c_back: b_f / n_f,
            g: g_fine,
            area: a_f / n_f,
            errors,
            phase_error,
        })
    }
}

/// Composite Simpson weights (in units of the step `h`, which cancels in
/// every ratio) of node `j` of `k` intervals, for the fine rule and for the
/// rule on every other node (`k/2` intervals of `2h`; zero at odd `j`).
fn simpson_weights(j: usize, k: usize) -> (f64, f64) {
    let end = j == 0 || j == k;
    let fine = if end {
        1.0 / 3.0
    } else if j % 2 == 1 {
        4.0 / 3.0
    } else {
        2.0 / 3.0
    };
    let coarse = if j % 2 == 1 {
        0.0
    } else if end {
        2.0 / 3.0
    } else if (j / 2) % 2 == 1 {
        8.0 / 3.0
    } else {
        4.0 / 3.0
    };
    (fine, coarse)
}
