//! Phase functions: densities of scattering directions per steradian.
//!
//! Conventions (as in the crate docs): `cos θ = dot(w_in, w_out)` with both vectors
//! propagation directions, so `+1` is forward. Every phase function `p`
//! satisfies `2π ∫₋₁¹ p(μ) dμ = 1`. [`PhaseFunction::sample_cos`] is the
//! inverse of [`PhaseFunction::cdf`] with `F(x) = P(cos θ ≤ x)`: `u = 0 → −1`,
//! `u → 1 → +1`, monotone non-decreasing, so stratified and low-discrepancy
//! uniforms stay stratified.
//!
//! [`Phase`] is the closed set of models behind one small `Copy` value; each
//! model is also usable on its own.

pub mod draine;
pub mod fog;
mod fog_inverse;
pub mod fournier_forand;
pub mod gegenbauer;
mod hg;
mod hg_batch;
mod isotropic;
pub mod particle;
pub mod particle_mie;
pub mod rayleigh;
mod rayleigh_depolarized;
pub mod rayleigh_polarized;
mod seeds;

pub use draine::Draine;
pub use fog::{Fog, FogParams, fog_fit};
pub use fournier_forand::FournierForand;
pub use gegenbauer::Gegenbauer;
pub use hg::HenyeyGreenstein;
pub use isotropic::Isotropic;
pub use rayleigh::{Rayleigh, RayleighMethod};
pub use rayleigh_depolarized::RayleighDepolarized;
pub use rayleigh_polarized::{RayleighMueller, RayleighPolarized, StokesSample};

use crate::error::Error;
use crate::geometry::{Vec3, direction_about_turns, sin_from_cos};
use crate::real::Real;

/// A phase function over the cosine of the scattering angle.
pub trait PhaseFunction<T: Real> {
    /// Density per steradian at `cos_theta` (domain `[-1, 1]`; outside it
    /// the formula is evaluated as is).
    fn pdf(&self, cos_theta: T) -> T;
    /// `P(cos θ ≤ cos_theta)`, in `[0, 1]`; arguments outside `[-1, 1]` are
    /// clamped.
    fn cdf(&self, cos_theta: T) -> T;
    /// The inverse of [`cdf`](Self::cdf): maps `u ∈ [0, 1]` to `cos θ`.
    /// `u` outside `[0, 1]` is clamped, NaN gives NaN.
    fn sample_cos(&self, u: T) -> T;
    /// Mean cosine `⟨cos θ⟩ = 2π ∫ μ p(μ) dμ` (the asymmetry parameter).
    fn mean_cosine(&self) -> T;

    /// `(cos θ, sin θ)` for `cos θ = sample_cos(u)`, with `sin θ` as
    /// accurate as the sampler knows it: where `1 − |cos θ|` is known to
    /// better than the spacing of floats near 1, `sin θ` keeps it.
    #[inline]
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let mu = self.sample_cos(u);
        (mu, sin_from_cos(mu))
    }

    /// A direction scattered from the unit propagation direction `w_in`:
    /// `cos θ = sample_cos(u1)`, azimuth `2π u2` in the basis
    /// [`onb`](crate::geometry::onb)`(w_in)`, the polar angle from
    /// [`sample_cos_sin`](Self::sample_cos_sin). Returns the direction and
    /// its density per steradian.
    #[inline]
    fn sample_dir(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        let (mu, sin_theta) = self.sample_cos_sin(u1);
        let dir = direction_about_turns(w_in, mu, sin_theta, u2.clamp01());
        (dir, self.pdf(mu))
    }

    /// [`sample_cos`](Self::sample_cos) for a `u` the caller has already
    /// checked to lie in `[0, 1]` (not NaN): samplers may skip the clamp.
    /// Outside `[0, 1]` the result is unspecified (but no undefined
    /// behaviour).
    #[inline]
    fn sample_cos_in_range(&self, u: T) -> T {
        self.sample_cos(u)
    }

    /// Fills `cos_out[i] = sample_cos(u[i])` over the common length, without
    /// checks (each `u` is clamped as in [`sample_cos`](Self::sample_cos)).
    #[inline]
    fn sample_cos_each(&self, u: &[T], cos_out: &mut [T]) {
        for (c, &ui) in cos_out.iter_mut().zip(u) {
            *c = self.sample_cos(ui);
        }
    }

    /// [`sample_cos_each`](Self::sample_cos_each) for uniforms already
    /// checked to lie in `[0, 1]` ([`check_uniforms`]), through
    /// [`sample_cos_in_range`](Self::sample_cos_in_range).
    #[inline]
    fn sample_cos_each_in_range(&self, u: &[T], cos_out: &mut [T]) {
        for (c, &ui) in cos_out.iter_mut().zip(u) {
            *c = self.sample_cos_in_range(ui);
        }
    }

    /// Fills `cos_out[i] = sample_cos(u[i])`. Fails with [`Error::Size`] if
    /// the slices differ in length and with [`Error::Domain`] if any `u` is NaN
    /// or outside `[0, 1]`; on failure nothing is written.
    fn sample_cos_n(&self, u: &[T], cos_out: &mut [T]) -> Result<(), Error> {
        if u.len() != cos_out.len() {
            return Err(Error::Size);
        }
        check_uniforms(u)?;
        self.sample_cos_each_in_range(u, cos_out);
        Ok(())
    }

    /// Directions for many rays at once, in the structure-of-arrays layout
    /// wavefront renderers keep their rays in: `w_in` and `out` are the
    /// `[x, y, z]` component slices, and for every `i`
    /// `(out[i], pdf_out[i]) = sample_dir(w_in[i], u1[i], u2[i])`, bit for
    /// bit. Fails with [`Error::Size`] unless all nine slices have one
    /// length, and with [`Error::Domain`] if any `u1` or `u2` is NaN or
    /// outside `[0, 1]`; on failure nothing is written.
    fn sample_dir_n(
        &self,
        w_in: [&[T]; 3],
        u1: &[T],
        u2: &[T],
        out: [&mut [T]; 3],
        pdf_out: &mut [T],
    ) -> Result<(), Error> {
        let n = u1.len();
        let same = w_in.iter().all(|s| s.len() == n)
            && out.iter().all(|s| s.len() == n)
            && u2.len() == n
            && pdf_out.len() == n;
        if !same {
            return Err(Error::Size);
        }
        check_uniforms(u1)?;
        check_uniforms(u2)?;
        self.sample_dir_each(w_in, u1, u2, out, pdf_out);
        Ok(())
    }

    /// The loop of [`sample_dir_n`](Self::sample_dir_n) without its checks,
    /// over the shortest slice's length. Written branch-free for the
    /// closed-form samplers, so the compiler vectorises it.
    #[inline]
    fn sample_dir_each(
        &self,
        w_in: [&[T]; 3],
        u1: &[T],
        u2: &[T],
        out: [&mut [T]; 3],
        pdf_out: &mut [T],
    ) {
        let [wx, wy, wz] = w_in;
        let [ox, oy, oz] = out;
        let n = [wx.len(), wy.len(), wz.len(), u1.len(), u2.len()]
            .into_iter()
            .chain([ox.len(), oy.len(), oz.len(), pdf_out.len()])
            .fold(usize::MAX, usize::min);
        // Slices of exactly n elements: the indexing below needs no checks.
        let (Some(wx), Some(wy), Some(wz), Some(u1), Some(u2)) = (
            wx.get(..n),
            wy.get(..n),
            wz.get(..n),
            u1.get(..n),
            u2.get(..n),
        ) else {
            return;
        };
        let (Some(ox), Some(oy), Some(oz), Some(pdf)) = (
            ox.get_mut(..n),
            oy.get_mut(..n),
            oz.get_mut(..n),
            pdf_out.get_mut(..n),
        ) else {
            return;
        };
        for i in 0..n {
            let (d, p) = self.sample_dir(Vec3::new(wx[i], wy[i], wz[i]), u1[i], u2[i]);
            ox[i] = d.x;
            oy[i] = d.y;
            oz[i] = d.z;
            pdf[i] = p;
        }
    }
}

/// [`Error::Domain`] if any `u` is NaN or outside `[0, 1]`.
#[inline]
pub fn check_uniforms<T: Real>(u: &[T]) -> Result<(), Error> {
    #[cfg(ifunc)]
    let ok = match T::as_f32s(u) {
        // SAFETY: `u` is valid for `u.len()` reads.
        #[allow(unsafe_code)]
        Some(u) => unsafe { sk__all_unit_f32(u.as_ptr(), u.len()) },
        None => all_unit(u),
    };
    #[cfg(not(ifunc))]
    let ok = all_unit(u);
    if ok { Ok(()) } else { Err(Error::Domain) }
}

#[cfg(ifunc)]
crate::ifunc::load_time_choice! {
    /// [`all_unit`] from C: `true` if every one of the `n` floats at `u`
    /// lies in `[0, 1]`; `u` valid for `n` reads.
    sk__all_unit_f32: fn(u: *const f32, n: usize) -> bool {
        // SAFETY: the symbol's contract.
        all_unit(unsafe { core::slice::from_raw_parts(u, n) })
    }
}

/// True if every `u` lies in `[0, 1]` (the loop of [`check_uniforms`]).
#[inline(always)]
fn all_unit<T: Real>(u: &[T]) -> bool {
    // f32, on the bit patterns `b`: `u` is +0 or a positive number up to 1
    // exactly when `b` ≤ 0x3F80_0000 (1.0), that is when neither `b` (NaN,
    // −0 and negatives have the sign bit) nor `b + 0x407F_FFFF` (which
    // reaches the sign bit for every `b` above 1.0 up to +NaN) has the sign
    // bit set. Three integer operations per element, which SSE2 has, instead
    // of two float compares; only if it fails (a bad value, or −0, which the
    // rule accepts) does the exact loop below run.
    if let Some(f) = T::as_f32s(u)
        && f.iter().fold(0u32, |acc, &x| {
            let b = x.to_bits();
            acc | b | b.wrapping_add(0x407F_FFFF)
        }) >> 31
            == 0
    {
        return true;
    }
    // `!(x >= 0 && x <= 1)` is true for NaN too; `fold` keeps this branch-free.
    !u.iter()
        .fold(false, |bad, &x| bad | !(x >= T::ZERO && x <= T::ONE))
}

/// One phase function, chosen at run time. A small `Copy` value with no
/// pointers: build it once per medium, share it across threads.
///
/// `#[repr(C, u32)]` with discriminants from 1, so that the C layer can check
/// the tag of a caller's `sk_phase` (an all-zero value is invalid) before it
/// reads the payload.
///
/// # Example
///
/// Henyey–Greenstein with `g = 0.7`: a direction about the incoming one,
/// its density, and the inverse CDF that stratified or quasi-random
/// uniforms keep stratified.
///
/// ```
/// use scatterkit::{Phase, PhaseFunction, Vec3};
///
/// let hg = Phase::<f32>::henyey_greenstein(0.7).unwrap();
/// let w_in = Vec3::new(0.0, 0.0, 1.0);
/// let (w_out, pdf) = hg.sample_dir(w_in, 0.25, 0.5);
/// assert!((w_out.length() - 1.0).abs() < 1e-6);
/// assert!((pdf - hg.pdf(w_out.dot(w_in))).abs() < 1e-3 * pdf);
/// // Monotone in u: the median direction, and F(μ(u)) = u.
/// let mu = hg.sample_cos(0.5);
/// assert!((hg.cdf(mu) - 0.5).abs() < 1e-6);
/// ```
#[repr(C, u32)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Phase<T> {
    /// Uniform over the sphere.
    Isotropic(Isotropic) = 1,
    /// Rayleigh, `3/(16π) (1 + μ²)`.
    Rayleigh(Rayleigh) = 2,
    /// Rayleigh with depolarisation.
    RayleighDepolarized(RayleighDepolarized<T>) = 3,
    /// Henyey–Greenstein.
    HenyeyGreenstein(HenyeyGreenstein<T>) = 4,
    /// Draine (Cornette–Shanks for α = 1).
    Draine(Draine<T>) = 5,
    /// The fog mixture of HG and Draine.
    Fog(Fog<T>) = 6,
    /// The Gegenbauer kernel of Reynolds & McCormick.
    Gegenbauer(Gegenbauer<T>) = 7,
    /// Fournier–Forand, for ocean particles.
    FournierForand(FournierForand<T>) = 8,
}

impl<T: Real> Phase<T> {
    /// The same phase function in another precision (parameters rounded;
    /// a parameter that must stay below 1 in magnitude stays below it).
    pub fn cast<U: Real>(&self) -> Phase<U> {
        let c = |x: T| U::from_f64(x.to_f64());
        let open = |x: T| {
            let y = U::from_f64(x.to_f64());
            if y.abs() < U::ONE {
                y
            } else {
                (U::ONE - U::EPSILON * U::HALF).copysign(y)
            }
        };
        match *self {
            Phase::Isotropic(i) => Phase::Isotropic(i),
            Phase::Rayleigh(r) => Phase::Rayleigh(r),
            Phase::RayleighDepolarized(r) => match RayleighDepolarized::new(open(r.rho())) {
                Ok(d) => Phase::RayleighDepolarized(d),
                Err(_) => Phase::Rayleigh(Rayleigh),
            },
            Phase::HenyeyGreenstein(h) => {
                Phase::HenyeyGreenstein(HenyeyGreenstein::from_g(open(h.g())))
            }
            Phase::Draine(d) => Phase::Draine(Draine::from_parts(open(d.g), c(d.alpha))),
            Phase::Fog(f) => {
                let (a, b, al, w) = f.params();
                Phase::Fog(Fog::from_parts(open(a), open(b), c(al), c(w)))
            }
            Phase::Gegenbauer(k) => match Gegenbauer::new(c(k.alpha()), open(k.g())) {
                Ok(k) => Phase::Gegenbauer(k),
                // α just above −½ can round onto it: the nearest valid α.
                Err(_) => Phase::Gegenbauer(Gegenbauer::from_parts(
                    U::from_f64(-0.5 + 1e-7),
                    open(k.g()),
                )),
            },
            Phase::FournierForand(f) => Phase::FournierForand(FournierForand::from_parts(
                c(f.n()),
                // ν stays inside (−1, 0) after rounding.
                U::from_f64(f.nu().to_f64().clamp(-1.0 + 1e-7, -1e-30)),
            )),
        }
    }

    /// `cos θ` by lobe: for the fog mixture, the paper's sampler
    /// ([`Fog::sample_cos_by_lobe`]: one uniform picks the lobe and is reused
    /// inside it; exact in distribution, cheaper, not monotone in `u`); for
    /// every single-lobe phase function the same as `sample_cos`.
    #[inline]
    pub fn sample_cos_by_lobe(&self, u: T) -> T {
        match self {
            Phase::Fog(f) => f.sample_cos_by_lobe(u),
            p => p.sample_cos(u),
        }
    }

    /// The discriminant of the last variant (the C layer checks tags against
    /// `1..=LAST_TAG`).
    #[cfg_attr(not(feature = "ffi"), allow(dead_code))]
    pub(crate) const LAST_TAG: u32 = 8;

    /// Isotropic scattering.
    pub fn isotropic() -> Self {
        Phase::Isotropic(Isotropic)
    }
    /// Rayleigh scattering.
    pub fn rayleigh() -> Self {
        Phase::Rayleigh(Rayleigh)
    }
    /// Rayleigh scattering with depolarisation factor `rho ∈ [0, 1)`.
    pub fn rayleigh_depolarized(rho: T) -> Result<Self, Error> {
        RayleighDepolarized::new(rho).map(Phase::RayleighDepolarized)
    }
    /// Henyey–Greenstein with asymmetry `g ∈ (-1, 1)`.
    pub fn henyey_greenstein(g: T) -> Result<Self, Error> {
        HenyeyGreenstein::new(g).map(Phase::HenyeyGreenstein)
    }
    /// Draine with `g ∈ (-1, 1)` and finite `alpha ≥ 0`.
    pub fn draine(g: T, alpha: T) -> Result<Self, Error> {
        Draine::new(g, alpha).map(Phase::Draine)
    }
    /// Cornette–Shanks with `g ∈ (-1, 1)` (Draine with `α = 1`).
    pub fn cornette_shanks(g: T) -> Result<Self, Error> {
        Draine::cornette_shanks(g).map(Phase::Draine)
    }
    /// The fog mixture `(1 − w_d) HG(g_hg) + w_d Draine(g_d, alpha)`.
    pub fn fog(g_hg: T, g_d: T, alpha: T, w_d: T) -> Result<Self, Error> {
        Fog::new(g_hg, g_d, alpha, w_d).map(Phase::Fog)
    }
    /// The fitted fog phase function for droplets of `diameter_um` µm,
    /// `0 < d ≤ 50`.
    pub fn fog_diameter(diameter_um: T) -> Result<Self, Error> {
        Fog::from_diameter(diameter_um).map(Phase::Fog)
    }
    /// The Gegenbauer kernel of Reynolds & McCormick (1980),
    /// `p ∝ (1 + g² − 2gμ)^{−(α+1)}`, with `−½ < α ≤ 1000` and `|g| < 1`
    /// (`α = ½` is HG); see [`Gegenbauer`].
    pub fn gegenbauer(alpha: T, g: T) -> Result<Self, Error> {
        Gegenbauer::new(alpha, g).map(Phase::Gegenbauer)
    }
    /// Fournier–Forand for ocean particles of relative index `n ∈ (1, 1.8]`
    /// with a Junge size distribution of slope `mu_j ∈ (3, 5)`; see
    /// [`FournierForand`].
    pub fn fournier_forand(n: T, mu_j: T) -> Result<Self, Error> {
        FournierForand::new(n, mu_j).map(Phase::FournierForand)
    }
    /// Fournier–Forand from the backscatter fraction `b ∈ (0, ½)` and
    /// `n ∈ (1, 1.8]`, as oceanographers specify it.
    pub fn fournier_forand_backscatter(b: T, n: T) -> Result<Self, Error> {
        FournierForand::from_backscatter(b, n).map(Phase::FournierForand)
    }
    /// Two-lobe Henyey–Greenstein, `w HG(g1) + (1 − w) HG(g2)`, for clouds,
    /// skin and materials: `|g1| < 1`, `|g2| < 1`, `0 ≤ w ≤ 1`, else
    /// [`Error::Domain`]. It is the fog mixture with a Draine lobe of
    /// `α = 0` (which is HG), so it shares the fog's samplers: `sample_cos`
    /// inverts the mixture's CDF exactly (monotone in `u`), and
    /// [`sample_cos_by_lobe`](Self::sample_cos_by_lobe) picks a lobe with
    /// the uniform and reuses it (cheaper, not monotone). It reports itself
    /// as a fog mixture (`g_hg = g2`, `g_d = g1`, `α = 0`, `w_d = w`).
    ///
    /// ```
    /// use scatterkit::{Phase, PhaseFunction};
    /// // A forward lobe with a weaker backward one.
    /// let p = Phase::<f64>::two_lobe_hg(0.8, -0.3, 0.9).unwrap();
    /// assert!((p.mean_cosine() - (0.9 * 0.8 - 0.1 * 0.3)).abs() < 1e-12);
    /// assert!((p.cdf(p.sample_cos(0.3)) - 0.3).abs() < 1e-12);
    /// ```
    pub fn two_lobe_hg(g1: T, g2: T, w: T) -> Result<Self, Error> {
        Fog::new(g2, g1, T::ZERO, w).map(Phase::Fog)
    }
}

macro_rules! dispatch {
    ($self:expr, $m:ident => $e:expr) => {
        match $self {
            Phase::Isotropic($m) => $e,
            Phase::Rayleigh($m) => $e,
            Phase::RayleighDepolarized($m) => $e,
            Phase::HenyeyGreenstein($m) => $e,
            Phase::Draine($m) => $e,
            Phase::Fog($m) => $e,
            Phase::Gegenbauer($m) => $e,
            Phase::FournierForand($m) => $e,
        }
    };
}
/// `dispatch!(phase, m => expr)`: `expr` with `m` bound to the model inside.
#[cfg_attr(not(feature = "ffi"), allow(unused_imports))]
pub(crate) use dispatch;

impl<T: Real> PhaseFunction<T> for Phase<T> {
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        dispatch!(self, m => m.pdf(cos_theta))
    }
    #[inline]
    fn cdf(&self, cos_theta: T) -> T {
        dispatch!(self, m => m.cdf(cos_theta))
    }
    #[inline]
    fn sample_cos(&self, u: T) -> T {
        dispatch!(self, m => m.sample_cos(u))
    }
    #[inline]
    fn mean_cosine(&self) -> T {
        dispatch!(self, m => m.mean_cosine())
    }
    #[inline]
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        dispatch!(self, m => m.sample_cos_sin(u))
    }
    // Always inlined: where the caller's model is known (`Phase::rayleigh()`
    // in firmware, say) the match folds to that one model, and a firmware
    // image links only its code, not every model's (tests/bare_metal.rs).
    #[inline(always)]
    fn sample_dir(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        dispatch!(self, m => m.sample_dir(w_in, u1, u2))
    }
    #[inline]
    fn sample_cos_in_range(&self, u: T) -> T {
        dispatch!(self, m => m.sample_cos_in_range(u))
    }
    /// Dispatches once, then runs the model's own loop.
    fn sample_cos_each(&self, u: &[T], cos_out: &mut [T]) {
        dispatch!(self, m => m.sample_cos_each(u, cos_out))
    }
    /// Dispatches once, then runs the model's own loop.
    fn sample_cos_each_in_range(&self, u: &[T], cos_out: &mut [T]) {
        dispatch!(self, m => m.sample_cos_each_in_range(u, cos_out))
    }
    /// Dispatches once, then runs the model's own loop.
    fn sample_dir_each(
        &self,
        w_in: [&[T]; 3],
        u1: &[T],
        u2: &[T],
        out: [&mut [T]; 3],
        pdf_out: &mut [T],
    ) {
        dispatch!(self, m => m.sample_dir_each(w_in, u1, u2, out, pdf_out))
    }
}

#[cfg(test)]
mod check_tests {
    /// The bit-pattern test of `all_unit` agrees with the rule for every
    /// 4099th f32 pattern and every pattern near 0, 1, −0, +∞ and NaN.
    #[test]
    fn bit_test_is_the_rule() {
        extern crate std;
        let near =
            |c: u32| (c.saturating_sub(300)..=c.saturating_add(300)).collect::<std::vec::Vec<_>>();
        let mut bits: std::vec::Vec<u32> = (0..=u32::MAX).step_by(4099).collect();
        for c in [
            0,
            0x3F80_0000,
            0x8000_0000,
            0x7F80_0000,
            0x7FC0_0000,
            0xBF80_0000,
            u32::MAX,
        ] {
            bits.extend(near(c));
        }
        for b in bits {
            let x = f32::from_bits(b);
            assert_eq!(
                super::all_unit(&[0.5, x, 0.25]),
                (0.0..=1.0).contains(&x),
                "{b:#x}"
            );
        }
    }
}

#[cfg(all(test, ifunc))]
mod tests {
    extern crate std;
    use super::sk__all_unit_f32::BUILDS;
    use crate::ifunc::detected;

    /// Every build of the uniforms' check agrees with the rule (NaN, −0,
    /// the neighbours of 0 and 1, ±∞, a negative NaN) at the first, a middle
    /// and the last element, for every build this processor runs.
    #[test]
    fn all_builds_check_alike() {
        let u: std::vec::Vec<f32> = (0..=4099).map(|i| i as f32 / 4099.0).collect();
        let bad = [
            -0.0f32,
            -1e-45,
            1.000_000_1,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            0.5,
        ];
        for (needs, build) in BUILDS {
            if needs > detected() {
                std::println!("{needs:?} not available: its build is not checked");
                continue;
            }
            for x in bad {
                for at in [0, 7, 4099] {
                    let mut v = u.clone();
                    v[at] = x;
                    let want = (0.0..=1.0).contains(&x);
                    // SAFETY: valid for v.len() reads; the build's level is present.
                    #[allow(unsafe_code)]
                    let got = unsafe { build(v.as_ptr(), v.len()) };
                    assert_eq!(got, want, "{needs:?}, {x} at {at}");
                }
            }
        }
    }
}
