//! Surface scattering as solar-cell ray tracers do it (PV Lighthouse, SunSolve's
//! "Optical scattering" models).
//!
//! At an interface a ray is first reflected or transmitted (Fresnel, chosen
//! stochastically); then a share Λ of rays scatters by the surface's model
//! (Lambertian or Phong) and the rest go on specularly (mirror reflection or
//! Snell refraction).
//!
//! Conventions: every direction is a unit **propagation** direction. A
//! surface normal may be given on either side of the surface; functions that
//! need a side say which (`sk_surface_interact` accepts either and orients
//! the normal against the incident ray). Polarisation is not tracked.
//!
//! # Phong directions that cross the surface
//! A Phong lobe about a grazing specular direction reaches below the surface.
//! [`CrossingPolicy`] names what happens to a sampled direction on the wrong
//! side (polar angle θ > 90° from the leaving-side normal `n`):
//! * [`CrossingPolicy::Fold`] (SunSolve): θ becomes θ − 90° at the same
//!   azimuth about `n`; as a vector, `d' = |d·n| t + sqrt(1 − (d·n)²) n` with
//!   `t` the unit tangential part of `d`. The density above the surface is the
//!   lobe's plus the crossed part moved by that rotation (its solid angle
//!   changes by `cos θ'/sin θ'`: crossed rays pile up towards the surface
//!   plane's opposite edge and the normal).
//! * [`CrossingPolicy::Resample`]: draw again until the direction is above
//!   the surface (at most [`RESAMPLE_ATTEMPTS`] draws), which gives exactly
//!   the lobe truncated to the hemisphere and renormalised; if every draw
//!   crosses, the last one is mirrored. Draws come from the caller's RNG in
//!   [`Surface::interact`]; [`phong_sample`] (which has only two uniforms)
//!   derives further uniforms from them by a splitmix64 hash.
//! * [`CrossingPolicy::Mirror`]: reflect the direction across the surface
//!   plane, `d' = d − 2 (d·n) n`; the density above is the lobe's plus its
//!   mirror image's.

use crate::error::{Error, try_from_u32};
use crate::math::geometry::{Vec3, direction_about_turns, onb, sin_from_cos};
use crate::math::real::Real;
use rand_core::Rng;

/// Mirror reflection of the propagation direction `d` at a surface with
/// normal `n` (either side): `d − 2 (d·n) n`.
#[inline]
pub fn reflect<T: Real>(d: Vec3<T>, n: Vec3<T>) -> Vec3<T> {
    d - n * (T::TWO * d.dot(n))
}

/// `n` turned to face against `d` (towards the side `d` comes from).
#[inline(always)]
fn facing<T: Real>(d: Vec3<T>, n: Vec3<T>) -> Vec3<T> {
    if d.dot(n) > T::ZERO { -n } else { n }
}

/// Snell refraction of the unit propagation direction `d` through a surface
/// with unit normal `n` (either side) from index `n_i` into index `n_t`:
/// `η d + (η cos θᵢ − cos θₜ) n_f` with `η = n_i/n_t` and `n_f` facing
/// against `d`, computed in f64 and rounded once (so f32 results keep
/// `nᵢ sin θᵢ = nₜ sin θₜ` to the rounding of the output). [`Error::Domain`]
/// on total internal reflection, for indices that are not finite and
/// positive, or for `n_i/n_t` above [`MAX_INDEX_RATIO`].
pub fn refract<T: Real>(d: Vec3<T>, n: Vec3<T>, n_i: T, n_t: T) -> Result<Vec3<T>, Error> {
    let eta = index_ratio(n_i, n_t).ok_or(Error::Domain)?;
    snell(d.cast(), facing(d, n).cast(), eta)
        .map(Vec3::cast)
        .ok_or(Error::Domain)
}

/// The unit refracted direction for `d`, the normal `nf` facing against it,
/// and `η = nᵢ/nₜ`; `None` on total internal reflection (or zero vectors).
/// Both vectors are renormalised here in f64: an f32 "unit" vector is unit
/// only to ~10⁻⁷, and refraction amplifies that by up to η².
#[inline]
fn snell(d: Vec3<f64>, nf: Vec3<f64>, eta: f64) -> Option<Vec3<f64>> {
    let (d, nf) = (d.try_normalize()?, nf.try_normalize()?);
    // Matched indices: no interface, the ray goes on. (`cos θₜ` from
    // `1 − η² sin²θᵢ` loses `cos²θᵢ` against 1 at grazing incidence, and
    // bent the ray by up to 10⁻⁸ there.)
    if eta == 1.0 {
        return Some(d);
    }
    let cos_i = -d.dot(nf);
    let cos_t = transmitted(cos_i, eta, 1.0)?.cos_t;
    // η d and the normal term nearly cancel for large η: renormalise so the
    // result is unit to rounding.
    let t = d * eta + nf * (eta * cos_i - cos_t);
    Some(t * (1.0 / t.length()))
}

/// The refracted side of an interface: `cos θₜ`, `η = nᵢ/nₜ` and `1 − η²`
/// ([`transmitted`]), what both the direction and the reflectance use.
#[derive(Clone, Copy)]
struct Transmitted {
    cos_t: f64,
    eta: f64,
    one_minus_eta2: f64,
}

/// [`Transmitted`] for `|cos θᵢ|` = `c` and `η = nᵢ/nₜ`, or `None` on
/// total internal reflection (or NaN input): `cos²θₜ = 1 − η² sin²θᵢ`
/// written as `(1 − η²) + η² cos²θᵢ`, with `1 − η² = ((nₜ − nᵢ)/nₜ)(1 +
/// η)`. No cancellation at grazing incidence or for nearly matched
/// indices: `1 − η² sin²θᵢ` lost `cos²θᵢ` against 1, and `1 − η` formed
/// from a rounded `η` lost the indices' difference (at `nₜ/nᵢ = 1 + 10⁻⁶`
/// the f32 reflectance was 12 % off).
#[inline]
fn transmitted(c: f64, n_i: f64, n_t: f64) -> Option<Transmitted> {
    let eta = n_i / n_t;
    let k = (n_t - n_i) / n_t * (1.0 + eta);
    let ct2 = k + eta * c * (eta * c);
    (ct2 >= 0.0).then(|| Transmitted {
        cos_t: libm::sqrt(ct2),
        eta,
        one_minus_eta2: k,
    })
}

#[inline(always)]
fn positive<T: Real>(x: T) -> bool {
    x > T::ZERO && x.is_finite()
}

/// The largest `n_i/n_t` refraction takes: 2²⁶. Near normal incidence the
/// refracted direction is `η d + (η cos θᵢ − cos θₜ) n_f`, two terms of
/// size `η` that cancel to a unit vector, so its error is about `η ε`
/// (below 1.5·10⁻⁸ here); from `η ≈ 10⁸` the direction was noise, and
/// from 2⁵³ NaN at normal incidence.
pub const MAX_INDEX_RATIO: f64 = 67_108_864.0;

/// `η = n_i/n_t` in f64 for indices refraction accepts (finite and
/// positive, `η` at most [`MAX_INDEX_RATIO`]), else `None`.
#[inline(always)]
fn index_ratio<T: Real>(n_i: T, n_t: T) -> Option<f64> {
    let eta = n_i.to_f64() / n_t.to_f64();
    (positive(n_i) && positive(n_t) && eta <= MAX_INDEX_RATIO).then_some(eta)
}

/// Unpolarised Fresnel reflectance of a dielectric interface, `(R_s + R_p)/2`,
/// for light arriving at `|cos_i|` (either direction of travel) from index
/// `n_i` into `n_t`; 1 on total internal reflection, 0 for matched indices
/// (no interface, grazing incidence included). NaN for indices that are not
/// finite and positive or `|cos_i| > 1`.
pub fn fresnel_dielectric<T: Real>(cos_i: T, n_i: T, n_t: T) -> T {
    let c = cos_i.abs();
    if !(positive(n_i) && positive(n_t) && c <= T::ONE) {
        return T::NAN;
    }
    // Matched indices: no interface. The formula below gives 0 there only
    // where `cₜ` comes out as `c`, but `cₜ = √(1 − sin²θₜ)` loses `c²`
    // against 1: at n = 1.33 it gave R = 1.4·10⁻⁴ at |c| = 10⁻³ and 1 at
    // 10⁻⁴ in f32 (9·10⁻⁶ at 10⁻⁷ and 1 at 10⁻⁹ in f64), and at `c = 0`
    // both ratios were 0/0 (NaN).
    if n_i == n_t {
        return T::ZERO;
    }
    let c = c.to_f64();
    T::from_f64(reflectance(c, transmitted(c, n_i.to_f64(), n_t.to_f64())))
}

/// [`fresnel_dielectric`] for `c = |cos θᵢ|` in f64. The amplitude ratios
/// `(nᵢc − nₜcₜ)/(nᵢc + nₜcₜ)` and `(nₜc − nᵢcₜ)/(nₜc + nᵢcₜ)` with their
/// numerators multiplied out by the denominators: `(nᵢc)² − (nₜcₜ)² = nᵢ² −
/// nₜ²` and `(nₜc)² − (nᵢcₜ)² = (nₜ² − nᵢ²)(c² − sin²θₜ)`, so that, over
/// `nₜ²`, `r_s = −(1 − η²)/(ηc + cₜ)²` and `r_p = (1 − η²)(c² − η²(1 −
/// c²))/(c + ηcₜ)²`: the nearly equal terms of nearly matched indices
/// never meet. 1 on total internal reflection (`t` is `None`).
fn reflectance(c: f64, t: Option<Transmitted>) -> f64 {
    let Some(Transmitted {
        cos_t: ct,
        eta,
        one_minus_eta2: k,
    }) = t
    else {
        return 1.0;
    };
    let (a, b) = (eta * c + ct, c + eta * ct);
    // r_s up to its sign, which R squares away.
    let rs = k / (a * a);
    let rp = k * (c * c - eta * eta * (1.0 - c) * (1.0 + c)) / (b * b);
    // At most 1: at grazing incidence both ratios are −1 up to the
    // rounding of `cₜ = √k`, which made R = 1 + 4·10⁻¹⁶.
    ((rs * rs + rp * rp) * 0.5).min(1.0)
}

/// A cosine-weighted (Lambertian) direction in the hemisphere of the unit
/// `normal` (the side the ray leaves to): `θ = arccos √u1`, `φ = 2π u2`
/// (SunSolve). Density `cos θ / π` per steradian.
#[inline]
pub fn lambert_sample<T: Real>(normal: Vec3<T>, u1: T, u2: T) -> Vec3<T> {
    cone_sample(normal, u1.clamp01().sqrt(), u2)
}

/// The direction at polar cosine `c` and azimuth `2π u` about `axis`
/// (`u` clamped to `[0, 1]`).
#[inline(always)]
fn cone_sample<T: Real>(axis: Vec3<T>, c: T, u: T) -> Vec3<T> {
    direction_about_turns(axis, c, sin_from_cos(c), u.clamp01())
}

/// What happens to a Phong direction that lands on the wrong side of the
/// surface (module docs). The C enum `sk_crossing_policy`.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CrossingPolicy {
    /// SunSolve's rule: polar angle θ > 90° becomes θ − 90°, same azimuth.
    Fold = 0,
    /// Draw again (bounded), then mirror.
    Resample = 1,
    /// Reflect across the surface plane.
    Mirror = 2,
}

try_from_u32!(CrossingPolicy: Fold, Resample, Mirror);

/// Draws [`CrossingPolicy::Resample`] makes before it mirrors.
pub const RESAMPLE_ATTEMPTS: u32 = 16;

/// The Phong exponent's accepted range (SunSolve's): `[1, 10⁶]`.
pub const PHONG_ALPHA_MIN: f64 = 1.0;
/// Upper end of the Phong exponent's range.
pub const PHONG_ALPHA_MAX: f64 = 1e6;

/// One Phong direction about `axis`: `cos Δθ = u1^{1/(α+1)}`, `φ = 2π u2`.
#[inline(always)]
fn phong_lobe<T: Real>(axis: Vec3<T>, alpha: T, u1: T, u2: T) -> Vec3<T> {
    // u^{1/(α+1)} = exp(ln u/(α+1)); 1 − cos Δθ = −expm1(ln u/(α+1)) would be
    // finer near the axis, but the direction is built from cos and sin below.
    let u1 = u1.clamp01();
    let c = u1.powf(T::ONE / (alpha + T::ONE));
    cone_sample(axis, c, u2)
}

/// `d` moved to the leaving side of `normal` by `policy`'s deterministic
/// rule (Fold or Mirror; Resample's fallback is Mirror).
#[inline]
fn uncross<T: Real>(d: Vec3<T>, normal: Vec3<T>, policy: CrossingPolicy) -> Vec3<T> {
    let c = d.dot(normal);
    match policy {
        CrossingPolicy::Fold => {
            // θ → θ − 90° at the same azimuth: rotate by −90° in the plane
            // of d and the normal.
            let tangential = d - normal * c;
            let t = tangential.try_normalize().unwrap_or_else(|| onb(normal).0);
            let s = sin_from_cos(c);
            t * (-c) + normal * s
        }
        CrossingPolicy::Resample | CrossingPolicy::Mirror => d - normal * (T::TWO * c),
    }
}

/// A Phong-scattered direction (SunSolve, after Schümacher):
/// `cos Δθ = u1^{1/(α+1)}` about the unit specular direction `axis`, azimuth
/// `2π u2`, kept on the side of the unit `normal` (the side the ray leaves
/// to) by `policy`. `alpha` must be in `[1, 10⁶]`; at `α = 1` about the
/// normal this is [`lambert_sample`]. [`CrossingPolicy::Resample`] draws
/// further uniforms from a splitmix64 hash of `(u1, u2)` here (use
/// [`phong_sample_rng`] to draw them from an RNG). NaN for `alpha` outside
/// its range.
pub fn phong_sample<T: Real>(
    axis: Vec3<T>,
    normal: Vec3<T>,
    alpha: T,
    policy: CrossingPolicy,
    u1: T,
    u2: T,
) -> Vec3<T> {
    let mut stream = HashStream::new(u1.to_f64(), u2.to_f64());
    phong_with(axis, normal, alpha, policy, u1, u2, || {
        (
            T::from_bits_uniform(stream.next()),
            T::from_bits_uniform(stream.next()),
        )
    })
}

/// [`phong_sample`] with every uniform from `rng` (Resample's extra draws too).
pub fn phong_sample_rng<T: Real, R: Rng + ?Sized>(
    axis: Vec3<T>,
    normal: Vec3<T>,
    alpha: T,
    policy: CrossingPolicy,
    rng: &mut R,
) -> Vec3<T> {
    let (u1, u2) = (T::uniform(rng), T::uniform(rng));
    phong_with(axis, normal, alpha, policy, u1, u2, || {
        (T::uniform(rng), T::uniform(rng))
    })
}

fn phong_with<T: Real>(
    axis: Vec3<T>,
    normal: Vec3<T>,
    alpha: T,
    policy: CrossingPolicy,
    u1: T,
    u2: T,
    mut more: impl FnMut() -> (T, T),
) -> Vec3<T> {
    if !(alpha >= T::from_f64(PHONG_ALPHA_MIN) && alpha <= T::from_f64(PHONG_ALPHA_MAX)) {
        return Vec3::new(T::NAN, T::NAN, T::NAN);
    }
    let mut d = phong_lobe(axis, alpha, u1, u2);
    if policy == CrossingPolicy::Resample {
        let mut attempts = 1;
        while d.dot(normal) < T::ZERO && attempts < RESAMPLE_ATTEMPTS {
            let (a, b) = more();
            d = phong_lobe(axis, alpha, a, b);
            attempts += 1;
        }
    }
    if d.dot(normal) < T::ZERO {
        uncross(d, normal, policy)
    } else {
        d
    }
}

/// A deterministic stream of 64-bit words from two uniforms (splitmix64 of
/// their bits): Resample's further draws when no RNG is at hand.
struct HashStream(u64);

impl HashStream {
    fn new(a: f64, b: f64) -> Self {
        HashStream(a.to_bits() ^ b.to_bits().rotate_left(32) ^ 0x5ca7_7e2e_d5ca_77e2)
    }
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
}

/// The scalar-scattering model's share of scattered rays on reflection,
/// `Λ = 1 − exp(−((2π/λ) σ_rms · 2 nᵢ cos θᵢ)²)` (SunSolve, "Optical scattering",
/// scalar scattering model). `wavelength` λ
/// and `sigma_rms` in one length unit; λ > 0, σ ≥ 0, `n_i > 0` finite,
/// `|cos_i| ≤ 1`; NaN otherwise.
pub fn scatter_fraction_reflect<T: Real>(wavelength: T, sigma_rms: T, n_i: T, cos_i: T) -> T {
    if !(positive(wavelength)
        && sigma_rms >= T::ZERO
        && sigma_rms.is_finite()
        && positive(n_i)
        && cos_i.abs() <= T::ONE)
    {
        return T::NAN;
    }
    one_minus_exp_neg_sq(T::TAU / wavelength * sigma_rms * T::TWO * n_i * cos_i.abs())
}

/// The scalar-scattering model's share on transmission,
/// `Λ = 1 − exp(−((2π/λ) σ_rms |nᵢ cos θᵢ − nₜ cos θₜ|)²)`; arguments as in
/// [`scatter_fraction_reflect`] plus `n_t > 0` and `|cos_t| ≤ 1`.
pub fn scatter_fraction_transmit<T: Real>(
    wavelength: T,
    sigma_rms: T,
    n_i: T,
    cos_i: T,
    n_t: T,
    cos_t: T,
) -> T {
    let ok = positive(wavelength)
        && sigma_rms >= T::ZERO
        && sigma_rms.is_finite()
        && positive(n_i)
        && positive(n_t)
        && cos_i.abs() <= T::ONE
        && cos_t.abs() <= T::ONE;
    if !ok {
        return T::NAN;
    }
    one_minus_exp_neg_sq(
        T::TAU / wavelength * sigma_rms * (n_i * cos_i.abs() - n_t * cos_t.abs()).abs(),
    )
}

/// `1 − e^{−x²}` as `−expm1(−x²)`: no cancellation for small roughness.
#[inline]
fn one_minus_exp_neg_sq<T: Real>(x: T) -> T {
    -(-(x * x)).exp_m1()
}

/// How a surface scatters (the C enum `sk_surface_model`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SurfaceModel {
    /// No scattering: every ray goes on specularly.
    Specular = 0,
    /// Lambertian: cosine-weighted about the normal, independent of incidence.
    Lambert = 1,
    /// Phong about the specular direction.
    Phong = 2,
}

try_from_u32!(SurfaceModel: Specular, Lambert, Phong);

/// The share of rays that scatter (the C enum `sk_fraction_model` picks it).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Fraction<T> {
    /// A constant share Λ ∈ [0, 1].
    Constant(T),
    /// The scalar-scattering model with RMS roughness σ_rms ≥ 0 (in the
    /// length unit of the wavelength passed to [`Surface::interact`]).
    Scalar(T),
}

/// What one interaction did ([`Surface::interact`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interaction<T> {
    /// The new unit propagation direction.
    pub dir: Vec3<T>,
    /// True if the ray crossed into the second medium (else reflected).
    pub transmitted: bool,
    /// True if the surface model scattered it (else specular).
    pub scattered: bool,
}

/// An interface's scattering behaviour, validated once. A plain `Copy` value.
///
/// # Example
///
/// A textured glass–silicon interface as a solar-cell ray tracer sees it:
/// Fresnel decides reflection, a constant share of rays scatters with a
/// Phong lobe of exponent 20.
///
/// ```
/// use scatterkit::{CrossingPolicy, Fraction, Surface, SurfaceModel, Vec3};
/// use rand_xoshiro::Xoshiro256PlusPlus;
/// use rand_xoshiro::rand_core::SeedableRng;
///
/// let s = Surface::new(SurfaceModel::Phong, 20.0f64, Fraction::Constant(0.3), CrossingPolicy::Resample)
///     .unwrap();
/// let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
/// let (d, normal) = (Vec3::new(0.6, 0.0, -0.8), Vec3::new(0.0, 0.0, 1.0));
/// let x = s.interact(d, normal, 1.5, 3.9, 600e-9, &mut rng).unwrap();
/// assert!((x.dir.length() - 1.0).abs() < 1e-12);
/// // Transmitted rays leave on the far side of the interface.
/// assert_eq!(x.transmitted, x.dir.z < 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface<T> {
    model: SurfaceModel,
    phong_alpha: T,
    fraction: Fraction<T>,
    policy: CrossingPolicy,
}

impl<T: Real> Surface<T> {
    /// Fails with [`Error::Domain`] for a Phong exponent outside `[1, 10⁶]`
    /// (checked only for [`SurfaceModel::Phong`]), a constant fraction
    /// outside `[0, 1]`, or a negative or non-finite roughness.
    pub fn new(
        model: SurfaceModel,
        phong_alpha: T,
        fraction: Fraction<T>,
        policy: CrossingPolicy,
    ) -> Result<Self, Error> {
        let alpha_ok = model != SurfaceModel::Phong
            || (phong_alpha >= T::from_f64(PHONG_ALPHA_MIN)
                && phong_alpha <= T::from_f64(PHONG_ALPHA_MAX));
        let fraction_ok = match fraction {
            Fraction::Constant(f) => f >= T::ZERO && f <= T::ONE,
            Fraction::Scalar(s) => s >= T::ZERO && s.is_finite(),
        };
        if alpha_ok && fraction_ok {
            Ok(Surface {
                model,
                phong_alpha,
                fraction,
                policy,
            })
        } else {
            Err(Error::Domain)
        }
    }

    /// One interaction of a ray travelling along `d` (need not be unit
    /// length) with the surface of geometric normal `normal` (either side,
    /// any length), from index `n_i` into `n_t`, at `wavelength` (used by the
    /// scalar model only; same length unit as σ_rms). Fresnel picks reflection
    /// or transmission, Λ picks scattered or specular, the model picks the
    /// direction. Returns the new unit direction and what happened.
    ///
    /// [`Error::Domain`] for zero or non-finite vectors, indices that are not
    /// finite and positive or whose ratio `n_i/n_t` is above
    /// [`MAX_INDEX_RATIO`] (as [`refract`]), or (scalar model) a wavelength
    /// that is not.
    pub fn interact<R: Rng + ?Sized>(
        &self,
        d: Vec3<T>,
        normal: Vec3<T>,
        n_i: T,
        n_t: T,
        wavelength: T,
        rng: &mut R,
    ) -> Result<Interaction<T>, Error> {
        let (Some(d), Some(n)) = (d.try_normalize(), normal.try_normalize()) else {
            return Err(Error::Domain);
        };
        let scalar = matches!(self.fraction, Fraction::Scalar(_));
        let Some(eta) = index_ratio(n_i, n_t) else {
            return Err(Error::Domain);
        };
        if scalar && !positive(wavelength) {
            return Err(Error::Domain);
        }
        let nf = facing(d, n);
        let cos_i = (-d.dot(nf)).clamp_unit();
        // The refracted side once, for the reflectance and `cos θₜ` alike
        // (the indices are checked above; matched ones reflect nothing, as
        // `fresnel_dielectric` says).
        let c = cos_i.abs().to_f64();
        let t = transmitted(c, n_i.to_f64(), n_t.to_f64());
        let cos_t = t.map(|t| T::from_f64(t.cos_t));
        let reflectance = if n_i == n_t {
            T::ZERO
        } else {
            T::from_f64(reflectance(c, t))
        };
        let reflected = T::uniform(rng) < reflectance;
        // The specular direction and the normal on the side the ray leaves to.
        let refracted = if reflected {
            None
        } else {
            cos_t.zip(snell(d.cast(), nf.cast(), eta))
        };
        let (specular, leaving, lambda) = match refracted {
            Some((ct, t)) => {
                let l = match self.fraction {
                    Fraction::Constant(f) => f,
                    Fraction::Scalar(s) => {
                        scatter_fraction_transmit(wavelength, s, n_i, cos_i, n_t, ct)
                    }
                };
                (t.cast(), -nf, l)
            }
            None => {
                let l = match self.fraction {
                    Fraction::Constant(f) => f,
                    Fraction::Scalar(s) => scatter_fraction_reflect(wavelength, s, n_i, cos_i),
                };
                (reflect(d, nf), nf, l)
            }
        };
        let transmitted = refracted.is_some();
        let scattered = self.model != SurfaceModel::Specular && T::uniform(rng) < lambda;
        let dir = if !scattered {
            specular
        } else if self.model == SurfaceModel::Lambert {
            lambert_sample(leaving, T::uniform(rng), T::uniform(rng))
        } else {
            phong_sample_rng(specular, leaving, self.phong_alpha, self.policy, rng)
        };
        Ok(Interaction {
            dir,
            transmitted,
            scattered,
        })
    }
}
