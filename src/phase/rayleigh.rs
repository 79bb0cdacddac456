//! Rayleigh scattering (Frisvad, "Importance sampling the Rayleigh
//! phase function", JOSA A 28(12), 2011).
//!
//! `p(μ) = 3/(16π) (1 + μ²)`, `F(x) = 1/2 + 3x/8 + x³/8`, mean cosine 0.
//! Six samplers, every one of Frisvad's methods, named by [`RayleighMethod`].
//! The rejection methods stop after [`MAX_TRIALS`] rejections and finish with
//! the direct method on fresh uniforms: the first trials are independent of
//! what follows, so the output distribution stays exact, and a broken RNG
//! (one that returns a constant) cannot hang the caller.

use super::function::{PhaseFunction, dir_each};
use super::model::{Lobes, Model, exactly};
use crate::error::{Error, try_from_u32};
use crate::math::geometry::{Vec3, direction_about_turns, sin_from_cos};
use crate::math::numeric::depressed_cubic_root;
use crate::math::rayleigh_table::{RAYLEIGH_TABLE, RAYLEIGH_TABLE_F32};
use crate::math::real::Real;
use rand_core::Rng;

/// Rejection loops give up after this many trials (the cheapest acceptance,
/// Baranoski's, is about 0.42: 64 straight rejections have probability < 10⁻¹⁵).
pub const MAX_TRIALS: u32 = 64;

/// Rayleigh scattering, `p(μ) = 3/(16π) (1 + μ²)`. `sample_cos` is the
/// built-in Hermite table in f32 and the sqrt-free Cardano inverse in f64
/// (see [`PhaseFunction::sample_cos`] below).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rayleigh;

/// The sampling methods of Frisvad (2011), with the C enum's values.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RayleighMethod {
    /// Isotropic direction from the von Neumann cube (points in `[-1,1]³`
    /// kept inside the unit ball, normalised), accepted with probability
    /// `(1 + μ²)/2`. Overall acceptance π/6 · 2/3.
    RejectCube = 0,
    /// Isotropic direction from spherical coordinates, accepted with
    /// probability `(1 + μ²)/2`.
    RejectSpherical = 1,
    /// Baranoski's `μ = cos(πξ)` with Frisvad's corrected acceptance
    /// `(9/(4√6)) (1 + μ²) sqrt(1 − μ²)`.
    Baranoski = 2,
    /// `μ = 2ξ − 1` accepted with probability `(1 + μ²)/2`, then rotated into
    /// the frame of `w_in`.
    Simplified = 3,
    /// Cardano inversion of the CDF with [`Real::cbrt`].
    Direct = 4,
    /// Cardano inversion with [`Real::cbrt_fast`] (one Lancaster step fewer).
    DirectFast = 5,
    /// Cardano inversion with `cbrt(|s| + sqrt(s² + 1))` taken as the root
    /// of `w⁶ − 2|s| w³ − 1`: a cubic minimax seed and one Halley step (two
    /// in f64). No cube root, no square root, no branch: vectorisable, as
    /// accurate as `Direct`; the default of the Rayleigh phase object.
    DirectMinimax = 6,
    /// The inverse CDF from a cubic Hermite table of [`TABLE_N`] intervals
    /// built at compile time (2 KB, no setup): O(1) lookup with the shortest
    /// dependency chain of the accurate methods, the fastest for directions;
    /// max error 4·10⁻⁹ (below f32's resolution; it is the table's error in
    /// f64 too).
    Table = 7,
}

impl RayleighMethod {
    /// Every method, in the order of their values.
    pub const ALL: [RayleighMethod; 8] = [
        RayleighMethod::RejectCube,
        RayleighMethod::RejectSpherical,
        RayleighMethod::Baranoski,
        RayleighMethod::Simplified,
        RayleighMethod::Direct,
        RayleighMethod::DirectFast,
        RayleighMethod::DirectMinimax,
        RayleighMethod::Table,
    ];
    /// True for the methods that map one uniform to `cos θ` deterministically
    /// (and so can be stratified).
    pub fn is_inversion(self) -> bool {
        matches!(
            self,
            RayleighMethod::Direct
                | RayleighMethod::DirectFast
                | RayleighMethod::DirectMinimax
                | RayleighMethod::Table
        )
    }
}

try_from_u32!(
    RayleighMethod: RejectCube,
    RejectSpherical,
    Baranoski,
    Simplified,
    Direct,
    DirectFast,
    DirectMinimax,
    Table,
);

/// Rayleigh's inverse CDF, `F(μ) = u` ⇔ `μ³ + 3μ = 4(2u − 1)`.
#[inline(always)]
pub(crate) fn inverse_cdf<T: Real, const FAST: bool>(u: T) -> T {
    let s = T::TWO * (T::TWO * u.clamp01() - T::ONE);
    depressed_cubic_root::<T, FAST>(T::ONE, T::ONE, s).clamp_unit()
}

/// Rayleigh's inverse CDF by [`RayleighMethod::Direct`] (Cardano with
/// [`Real::cbrt`]). `u` is clamped to `[0, 1]`.
#[inline]
pub fn inverse_cdf_direct<T: Real>(u: T) -> T {
    inverse_cdf::<T, false>(u)
}

/// Rayleigh's inverse CDF with [`Real::cbrt_fast`]: about 2·10⁻⁵ from the
/// exact `cos θ` in f32, for callers who trade that for speed
/// ([`RayleighMethod::DirectFast`]). `u` is clamped to `[0, 1]`.
#[inline]
pub fn inverse_cdf_fast<T: Real>(u: T) -> T {
    inverse_cdf::<T, true>(u)
}

/// `w = cbrt(a + sqrt(a² + 1))` for `a ∈ [0, 2]`, without the square root:
/// `w` is the root of `h(w) = w⁶ − 2a w³ − 1` (since `w³ − w⁻³ = 2a`). A cubic
/// minimax seed in `a` (relative error 1.0·10⁻³ on `[0, 2]`, fitted by
/// reweighted least squares) and Halley's step on `h` — once in f32
/// (8.8·10⁻⁹ before rounding), twice in f64. With `c = w³` the step is
/// `w ← w − 2w h (c − a) / (12 c (c − a)² − h (5c − 2a))`: one division.
/// Branch-free and free of `sqrt`, so batches vectorise.
#[inline(always)]
fn cardano_w<T: Real>(a: T) -> T {
    let k = |x: f64| T::from_f64(x);
    let mut w = k(0.999_001_297_444_754_6)
        + a * (k(0.353_234_767_755_447_4)
            + a * (k(-0.001_343_385_289_570_21) + a * k(-0.010_459_901_086_701_195)));
    let steps = if core::mem::size_of::<T>() == 4 { 1 } else { 2 };
    for _ in 0..steps {
        let c = w * w * w;
        let h = c * c - T::TWO * a * c - T::ONE;
        let cma = c - a;
        w -= T::TWO * w * h * cma / (k(12.0) * c * cma * cma - h * (k(5.0) * c - T::TWO * a));
    }
    w
}

/// Rayleigh's inverse CDF by [`RayleighMethod::DirectMinimax`]: the same
/// stable Cardano root as [`inverse_cdf_direct`], `μ = 2s w²/(w⁴ + w² + 1)`,
/// with `w` from `cardano_w` (a minimax seed and Halley steps); branch-free
/// so batches vectorise. `u` is clamped to `[0, 1]`.
#[inline(always)]
pub fn inverse_cdf_minimax<T: Real>(u: T) -> T {
    let s = T::TWO * (T::TWO * u.clamp01() - T::ONE);
    let w2 = {
        let w = cardano_w(s.abs());
        w * w
    };
    (T::TWO * s * w2 / (w2 * w2 + w2 + T::ONE)).clamp_unit()
}

/// Intervals of the built-in Rayleigh inverse table ([`RayleighMethod::Table`]).
pub const TABLE_N: usize = crate::math::rayleigh_table::TABLE_N;

/// Rayleigh's inverse CDF by [`RayleighMethod::Table`]. `u` is clamped to
/// `[0, 1]`.
#[inline(always)]
pub fn inverse_cdf_table<T: Real>(u: T) -> T {
    let table = T::pick(&RAYLEIGH_TABLE_F32, &RAYLEIGH_TABLE);
    let x = u.clamp01() * T::from_index(TABLE_N);
    // Saturating conversion (NaN → 0) and the min keep i in bounds.
    let i = x.to_index().min(TABLE_N - 1);
    let t = x - T::from_index(i);
    let [y0, d0, c2, c3] = match table.get(4 * i..4 * i + 4) {
        Some(&[a, b, c, d]) => [a, b, c, d],
        _ => return T::NAN,
    };
    // Horner: one rounding at the scale of μ (Estrin's pairing would add a
    // second and cost 3·10⁻⁸ of accuracy in f32).
    (y0 + t * (d0 + t * (c2 + t * c3))).clamp_unit()
}

impl<T: Real> PhaseFunction<T> for Rayleigh {
    #[inline(always)]
    fn pdf(&self, cos_theta: T) -> T {
        T::from_f64(3.0 / (16.0 * core::f64::consts::PI)) * (T::ONE + cos_theta * cos_theta)
    }
    /// `(1 + x)(x² − x + 4)/8`: the textbook `1/2 + 3x/8 + x³/8` factored so it does
    /// not cancel near `x = −1`.
    #[inline(always)]
    fn cdf(&self, cos_theta: T) -> T {
        let x = cos_theta.clamp_unit();
        (T::ONE + x) * (x * x - x + T::from_f64(4.0)) * T::from_f64(0.125)
    }
    /// f32: [`RayleighMethod::Table`] (max error 6.0·10⁻⁸, below the
    /// direct methods' 2·10⁻⁷, and the shortest dependency chain, which is
    /// what a direction's latency is made of); f64:
    /// [`RayleighMethod::DirectMinimax`] (4.4·10⁻¹⁶, where the table's
    /// 3·10⁻⁹ would be the larger error).
    #[inline(always)]
    fn sample_cos(&self, u: T) -> T {
        if core::mem::size_of::<T>() == 4 {
            inverse_cdf_table(u)
        } else {
            inverse_cdf_minimax(u)
        }
    }
    #[inline(always)]
    fn mean_cosine(&self) -> T {
        T::ZERO
    }
    /// The default loop with the default `sample_dir`'s body inlined into
    /// it, so that it vectorises in f64: calling `sample_dir` at each
    /// element (left out of line in the C library's build),
    /// `sk_phase_sample_dir_n_f64` took the scalar call's 38 ns per
    /// direction (Intel Xeon, family 6 model 167). In f32 the table lookup
    /// does not vectorise either way.
    fn sample_dir_each(
        &self,
        w_in: [&[T]; 3],
        u1: &[T],
        u2: &[T],
        out: [&mut [T]; 3],
        pdf_out: &mut [T],
    ) {
        dir_each(w_in, [u1, u2], out, pdf_out, |w, a, b| {
            let (mu, sin_theta) = self.sample_cos_sin(a);
            let dir = direction_about_turns(w, mu, sin_theta, b.clamp01());
            (dir, self.pdf(mu))
        });
    }
}

/// Acceptance `(1 + μ²)/2` of the Rayleigh density against the isotropic one.
#[inline(always)]
fn accept_isotropic<T: Real>(mu: T, xi: T) -> bool {
    xi * T::TWO <= T::ONE + mu * mu
}

/// Frisvad's corrected acceptance for `μ = cos(πξ)`:
/// `ξ ≤ (9/(4√6)) (1 + μ²) sqrt(1 − μ²)`.
#[inline(always)]
fn accept_baranoski<T: Real>(mu: T, xi: T) -> bool {
    let c = T::from_f64(9.0 / (4.0 * 2.449_489_742_783_178));
    let sin_theta = sin_from_cos(mu);
    xi <= c * (T::ONE + mu * mu) * sin_theta
}

/// A cosine from the direct method on fresh uniforms: the tail of every
/// rejection loop.
#[inline(never)]
fn fallback_cos<T: Real, R: Rng + ?Sized>(rng: &mut R) -> T {
    inverse_cdf::<T, false>(T::uniform(rng))
}

/// An isotropic unit vector from the von Neumann cube, or `None` if the
/// point fell outside the unit ball (or too near its centre to normalise).
#[inline(always)]
fn cube_point<T: Real, R: Rng + ?Sized>(rng: &mut R) -> Option<Vec3<T>> {
    let mut c = || T::TWO * T::uniform(rng) - T::ONE;
    let v = Vec3::new(c(), c(), c());
    let l2 = v.dot(v);
    // Rejecting a small ball about the centre keeps the directions uniform.
    if l2 <= T::ONE && l2 > T::from_f64(1e-6) {
        Some(v * (T::ONE / l2.sqrt()))
    } else {
        None
    }
}

/// An isotropic unit vector from spherical coordinates, in world axes.
#[inline(always)]
fn spherical_point<T: Real, R: Rng + ?Sized>(rng: &mut R) -> Vec3<T> {
    let mu = T::TWO * T::uniform(rng) - T::ONE;
    about_with_uniform_azimuth(Vec3::unit_z(), mu, rng)
}

/// `cos θ` by Frisvad's simplified rejection.
#[inline(always)]
fn simplified_cos<T: Real, R: Rng + ?Sized>(rng: &mut R) -> T {
    for _ in 0..MAX_TRIALS {
        let mu = T::TWO * T::uniform(rng) - T::ONE;
        if accept_isotropic(mu, T::uniform(rng)) {
            return mu;
        }
    }
    fallback_cos(rng)
}

/// `cos θ` by Baranoski's rejection with Frisvad's correction.
#[inline(always)]
fn baranoski_cos<T: Real, R: Rng + ?Sized>(rng: &mut R) -> T {
    for _ in 0..MAX_TRIALS {
        // cos(πξ) = cos(2π·ξ/2), reduced exactly (ξ/2 is exact).
        let mu = (T::HALF * T::uniform(rng)).sin_cos_2pi().1;
        if accept_baranoski(mu, T::uniform(rng)) {
            return mu;
        }
    }
    fallback_cos(rng)
}

/// A whole direction from a rejection method that samples isotropic
/// directions in world axes and accepts against `w_in`.
#[inline(always)]
fn reject_isotropic<T: Real, R: Rng + ?Sized>(
    w_in: Vec3<T>,
    rng: &mut R,
    mut point: impl FnMut(&mut R) -> Option<Vec3<T>>,
) -> Vec3<T> {
    for _ in 0..MAX_TRIALS {
        if let Some(w) = point(rng) {
            if accept_isotropic(w.dot(w_in), T::uniform(rng)) {
                return w;
            }
        }
    }
    let mu = fallback_cos(rng);
    about_with_uniform_azimuth(w_in, mu, rng)
}

/// A Rayleigh-distributed propagation direction about the unit vector `w_in`
/// by `method`, drawing uniforms from `rng` (the crate's uniform conversion). Inlined
/// always: with a constant `method` only that method's code remains.
#[inline(always)]
pub fn sample_dir<T: Real, R: Rng + ?Sized>(
    method: RayleighMethod,
    w_in: Vec3<T>,
    rng: &mut R,
) -> Vec3<T> {
    let mu = match method {
        RayleighMethod::RejectCube => return reject_isotropic(w_in, rng, cube_point),
        RayleighMethod::RejectSpherical => {
            return reject_isotropic(w_in, rng, |r| Some(spherical_point(r)));
        }
        _ => sample_cos(method, rng),
    };
    about_with_uniform_azimuth(w_in, mu, rng)
}

/// The direction at polar cosine `mu` about `axis`, azimuth from one uniform.
#[inline(always)]
fn about_with_uniform_azimuth<T: Real, R: Rng + ?Sized>(
    axis: Vec3<T>,
    mu: T,
    rng: &mut R,
) -> Vec3<T> {
    direction_about_turns(axis, mu, sin_from_cos(mu), T::uniform(rng))
}

/// A Rayleigh-distributed `cos θ` by `method` (for the methods that produce
/// whole directions, the z component of a direction about +z).
#[inline(always)]
pub fn sample_cos<T: Real, R: Rng + ?Sized>(method: RayleighMethod, rng: &mut R) -> T {
    match method {
        RayleighMethod::RejectCube => reject_isotropic(Vec3::unit_z(), rng, cube_point).z,
        RayleighMethod::RejectSpherical => {
            reject_isotropic(Vec3::unit_z(), rng, |r| Some(spherical_point(r))).z
        }
        RayleighMethod::Baranoski => baranoski_cos(rng),
        RayleighMethod::Simplified => simplified_cos(rng),
        _ => inverse_cdf_by(method, T::uniform(rng)),
    }
}

/// Rayleigh directions about many unit directions `w_in` (the `[x, y, z]`
/// component slices; structure of arrays), written to `out`, over the
/// shortest slice's length: `out[i]` is what [`sample_dir`] returns for
/// `w_in[i]` when called in order with the same generator, bit for bit.
/// For the inversion methods the uniforms of a block of directions are drawn
/// first (in the scalar order) and the arithmetic then runs as a loop the
/// compiler can vectorise.
pub fn sample_dir_fill<T: Real, R: Rng + ?Sized>(
    method: RayleighMethod,
    w_in: [&[T]; 3],
    rng: &mut R,
    out: [&mut [T]; 3],
) {
    const BLOCK: usize = 64;
    let [wx, wy, wz] = w_in;
    let [ox, oy, oz] = out;
    let n = [wx.len(), wy.len(), wz.len(), ox.len(), oy.len(), oz.len()]
        .into_iter()
        .fold(usize::MAX, usize::min);
    let mut start = 0;
    while start < n {
        let len = BLOCK.min(n - start);
        let end = start + len;
        let (Some(wx), Some(wy), Some(wz)) =
            (wx.get(start..end), wy.get(start..end), wz.get(start..end))
        else {
            return;
        };
        let (Some(ox), Some(oy), Some(oz)) = (
            ox.get_mut(start..end),
            oy.get_mut(start..end),
            oz.get_mut(start..end),
        ) else {
            return;
        };
        if method.is_inversion() {
            let (mut u1, mut u2) = ([T::ZERO; BLOCK], [T::ZERO; BLOCK]);
            for (a, b) in u1.iter_mut().zip(u2.iter_mut()).take(len) {
                *a = T::uniform(rng);
                *b = T::uniform(rng);
            }
            for i in 0..len {
                let mu = inverse_cdf_by(method, u1[i]);
                let d = direction_about_turns(
                    Vec3::new(wx[i], wy[i], wz[i]),
                    mu,
                    sin_from_cos(mu),
                    u2[i],
                );
                (ox[i], oy[i], oz[i]) = (d.x, d.y, d.z);
            }
        } else {
            for i in 0..len {
                let d = sample_dir(method, Vec3::new(wx[i], wy[i], wz[i]), rng);
                (ox[i], oy[i], oz[i]) = (d.x, d.y, d.z);
            }
        }
        start = end;
    }
}

/// `cos_out[i]` = the inverse CDF of the inversion method `method` at
/// `u[i]` (clamped to `[0, 1]`), over the common length; a method that is
/// not an inversion ([`RayleighMethod::is_inversion`]) fills NaN. For
/// [`RayleighMethod::DirectMinimax`] the loop has no branch, square root or
/// cube root, and vectorises.
pub fn inverse_cdf_fill<T: Real>(method: RayleighMethod, u: &[T], cos_out: &mut [T]) {
    match method {
        RayleighMethod::DirectMinimax => {
            for (c, &x) in cos_out.iter_mut().zip(u) {
                *c = inverse_cdf_minimax(x);
            }
        }
        _ => {
            for (c, &x) in cos_out.iter_mut().zip(u) {
                *c = inverse_cdf_by(method, x);
            }
        }
    }
}

/// The inverse CDF of an inversion method (`is_inversion`); NaN for the
/// others.
#[inline(always)]
fn inverse_cdf_by<T: Real>(method: RayleighMethod, u: T) -> T {
    match method {
        RayleighMethod::Direct => inverse_cdf::<T, false>(u),
        RayleighMethod::DirectFast => inverse_cdf::<T, true>(u),
        RayleighMethod::DirectMinimax => inverse_cdf_minimax(u),
        RayleighMethod::Table => inverse_cdf_table(u),
        _ => T::NAN,
    }
}

/// Fills `cos_out` with Rayleigh cosines by `method`.
pub fn sample_cos_fill<T: Real, R: Rng + ?Sized>(
    method: RayleighMethod,
    rng: &mut R,
    cos_out: &mut [T],
) {
    for c in cos_out.iter_mut() {
        *c = sample_cos(method, rng);
    }
}

/// Rayleigh scattering cross section of one small sphere,
/// `C_s = 128 π⁵ α² / (3 λ⁴)` with polarizability `α = a³ (n² − 1)/(n² + 2)`
/// (Bohren & Huffman, "Absorption and Scattering of Light by Small
/// Particles", 1983, ch. 5). `wavelength` λ and `radius` a in one length unit L (result in
/// L²); `rel_index` n is the particle's refractive index over the medium's.
/// Valid for `a ≪ λ`. Fails with [`Error::Domain`] unless all three are
/// finite and positive.
pub fn cross_section(wavelength: f64, radius: f64, rel_index: f64) -> Result<f64, Error> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !(positive(wavelength) && positive(radius) && positive(rel_index)) {
        return Err(Error::Domain);
    }
    let n2 = rel_index * rel_index;
    // (n² − 1)/(n² + 2), as 1 − 3/(n² + 2) for large n, where n² may
    // overflow (∞/∞); the first form near n = 1, where the second cancels.
    let lorentz = if n2 > 4.0 {
        1.0 - 3.0 / (n2 + 2.0)
    } else {
        (n2 - 1.0) / (n2 + 2.0)
    };
    let alpha = radius * radius * radius * lorentz;
    let pi = core::f64::consts::PI;
    let l2 = wavelength * wavelength;
    // λ⁴ as (λ²)² and the π⁵ factor split so neither overflows early.
    Ok(128.0 * pi * pi * pi * pi * pi / 3.0 * (alpha / l2) * (alpha / l2))
}

/// Rayleigh scattering coefficient `σ_s = N C_s` (per unit length L) for
/// `number_density` N particles per L³ (finite, ≥ 0) and the arguments of
/// [`cross_section`].
pub fn scattering_coeff(
    number_density: f64,
    wavelength: f64,
    radius: f64,
    rel_index: f64,
) -> Result<f64, Error> {
    if !(number_density.is_finite() && number_density >= 0.0) {
        return Err(Error::Domain);
    }
    Ok(number_density * cross_section(wavelength, radius, rel_index)?)
}

impl<T: Real> Model<T> for Rayleigh {
    type In<U: Real> = Rayleigh;
    const PARAMS: usize = 0;
    fn params(&self) -> [T; 4] {
        [T::ZERO; 4]
    }
    fn from_params(p: &[T]) -> Result<Self, Error> {
        exactly::<T, 0>(p).map(|_| Rayleigh)
    }
    fn cast<U: Real>(&self) -> Rayleigh {
        Rayleigh
    }
    /// Draine with `g = 0`, `α = 1`.
    fn lobes(&self) -> Option<Lobes> {
        Some(((0.0, 1.0), (0.0, 0.0), 0.0))
    }
}
