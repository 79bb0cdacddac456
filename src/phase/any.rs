//! [`Phase`]: the closed set of models behind one small `Copy` value, and
//! the dispatch from it to the model inside.

use super::function::{PhaseFunction, PhaseVisitor};
use super::{
    Draine, Fog, FournierForand, Gegenbauer, HenyeyGreenstein, Isotropic, Rayleigh,
    RayleighDepolarized,
};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;

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

/// `dispatch!(phase, m => expr)`: `expr` with `m` bound to the model inside.
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

impl<T: Real> Phase<T> {
    /// Runs `v` on the model inside, compiled once per model: the model's
    /// own code behind one dispatch at this call, where the `Phase` methods
    /// dispatch on every call (an entry point that calls one model function
    /// per model, or a loop that should see one model's code only).
    #[inline(always)]
    pub fn visit<V: PhaseVisitor<T>>(&self, v: V) -> V::Output {
        dispatch!(self, m => v.visit(m))
    }
}

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
