//! [`Phase`]: the closed set of models behind one small `Copy` value, and
//! the dispatch from it to the model inside.

use super::function::{PhaseFunction, PhaseVisitor};
use super::model::{Lobes, Model};
use super::{
    Draine, Fog, FournierForand, Gegenbauer, HenyeyGreenstein, Isotropic, Rayleigh,
    RayleighDepolarized,
};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;

/// The registry of models, one line each: `tag => Variant(Type) "name"`.
/// It generates the `Phase` enum (`#[repr(C, u32)]`, the tags its
/// discriminants), `dispatch!`, `Phase::tag`, `name`, `cast`, `params` and
/// `from_params` (through each model's [`Model`] implementation, so a model
/// missing a method does not compile), and a check, when `Phase<T>` is
/// used, that every model fits in [`Phase::ROOM`] values of its precision,
/// naming the model that does not. A new model is its file and one line.
macro_rules! models {
    ($($(#[$doc:meta])* $tag:literal => $variant:ident($ty:ty) $name:literal),+ $(,)?) => {
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
            $($(#[$doc])* $variant($ty) = $tag,)+
        }

        /// `dispatch!(phase, m => expr)`: `expr` with `m` bound to the model inside.
        macro_rules! dispatch {
            ($self:expr, $m:ident => $e:expr) => {
                match $self {
                    $(Phase::$variant($m) => $e,)+
                }
            };
        }

        $(impl<T: Real> From<$ty> for Phase<T> {
            fn from(m: $ty) -> Self {
                Phase::$variant(m)
            }
        })+

        impl<T: Real> Phase<T> {
            /// Every model fits (checked when `Phase<T>` is used).
            const FITS: () = {
                $(assert!(
                    core::mem::size_of::<$ty>() <= Self::ROOM,
                    concat!("Phase::ROOM has no room for ", stringify!($variant))
                );)+
            };
            /// The tags in use: `1..=LAST_TAG`.
            pub const LAST_TAG: u32 = {
                let tags = [$($tag),+];
                tags[tags.len() - 1]
            };
            /// The model's tag (its discriminant, the C API's
            /// `sk_phase_model`).
            pub fn tag(&self) -> u32 {
                let () = Self::FITS;
                match self {
                    $(Phase::$variant(_) => $tag,)+
                }
            }
            /// The model's name.
            pub fn name(&self) -> &'static str {
                match self {
                    $(Phase::$variant(_) => $name,)+
                }
            }
            /// The same phase function in another precision (parameters
            /// rounded; a parameter that must stay below 1 in magnitude
            /// stays below it).
            pub fn cast<U: Real>(&self) -> Phase<U> {
                match self {
                    $(Phase::$variant(m) => Phase::$variant(Model::<T>::cast::<U>(m)),)+
                }
            }
            /// The model's tag and its parameters (the rest 0), in the
            /// order [`Model::params`] gives them.
            pub fn params(&self) -> (u32, usize, [T; 4]) {
                match self {
                    $(Phase::$variant(m) => ($tag, <$ty as Model<T>>::PARAMS, Model::<T>::params(m)),)+
                }
            }
            /// The model of `tag` from its parameters, the inverse of
            /// [`params`](Self::params): [`Error::Method`] for an unknown
            /// tag, [`Error::Size`] for the wrong number of parameters,
            /// [`Error::Domain`] for values out of range.
            pub fn from_params(tag: u32, p: &[T]) -> Result<Self, Error> {
                let () = Self::FITS;
                match tag {
                    $($tag => <$ty as Model<T>>::from_params(p).map(Phase::$variant),)+
                    _ => Err(Error::Method),
                }
            }
            /// Its Draine lobes if its Legendre moments have a closed form.
            #[inline]
            pub(crate) fn lobes(&self) -> Option<Lobes> {
                match self {
                    $(Phase::$variant(m) => Model::<T>::lobes(m),)+
                }
            }
        }
    };
}

models! {
    /// Uniform over the sphere.
    1 => Isotropic(Isotropic) "isotropic",
    /// Rayleigh, `3/(16π) (1 + μ²)`.
    2 => Rayleigh(Rayleigh) "Rayleigh",
    /// Rayleigh with depolarisation.
    3 => RayleighDepolarized(RayleighDepolarized<T>) "depolarised Rayleigh",
    /// Henyey–Greenstein.
    4 => HenyeyGreenstein(HenyeyGreenstein<T>) "Henyey-Greenstein",
    /// Draine (Cornette–Shanks for α = 1).
    5 => Draine(Draine<T>) "Draine",
    /// The fog mixture of HG and Draine.
    6 => Fog(Fog<T>) "fog",
    /// The Gegenbauer kernel of Reynolds & McCormick.
    7 => Gegenbauer(Gegenbauer<T>) "Gegenbauer",
    /// Fournier–Forand, for ocean particles.
    8 => FournierForand(FournierForand<T>) "Fournier-Forand",
    /// Schlick's rational stand-in for HG.
    9 => Schlick(super::schlick::Schlick<T>) "Schlick",
}

impl<T: Real> Phase<T> {
    /// The room every model must fit in: 63 values of `T` (252 bytes in
    /// f32, 504 in f64; the C layer's fixed storage is 64 with the tag).
    pub const ROOM: usize = 63 * core::mem::size_of::<T>();

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
    /// Henyey–Greenstein with asymmetry `g ∈ [−1, 1]` (`|g| = 1`: the
    /// Dirac limit, [`HenyeyGreenstein`]).
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
    /// Fournier–Forand from the backscatter fraction `b ∈
    /// [T::MIN_POSITIVE, ½)` and `n ∈ (1, 1.8]`, as oceanographers specify
    /// it ([`FournierForand::from_backscatter`]).
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
    /// The model's density, read where [`support`](super::support) puts
    /// `cos_theta` (0 beyond 8 ulp outside `[−1, 1]`).
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        match super::support(cos_theta) {
            Some(mu) => dispatch!(self, m => m.pdf(mu)),
            None => T::ZERO,
        }
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
    #[inline]
    fn pdf_cos_sin(&self, cos_theta: T, sin_theta: T) -> T {
        match super::support(cos_theta) {
            Some(mu) => dispatch!(self, m => m.pdf_cos_sin(mu, sin_theta)),
            None => T::ZERO,
        }
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
