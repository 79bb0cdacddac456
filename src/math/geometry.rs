//! Vectors and the orthonormal basis around a direction.
//!
//! Directions are unit propagation directions (the crate's convention): the way light
//! travels, not the way pbrt's `wo` points.

use crate::math::real::Real;
use core::ops::{Add, Mul, Neg, Sub};

/// A 3-vector. `#[repr(C)]`: the same layout as the C `sk_vec3` (f32) and
/// `sk_vec3_f64` (f64).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<T> {
    /// x component.
    pub x: T,
    /// y component.
    pub y: T,
    /// z component.
    pub z: T,
}

impl<T: Real> Vec3<T> {
    /// A vector from its components.
    #[inline(always)]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Vec3 { x, y, z }
    }
    /// The unit vector +z.
    #[inline(always)]
    pub fn unit_z() -> Self {
        Vec3::new(T::ZERO, T::ZERO, T::ONE)
    }
    /// Dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product (right-handed).
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Euclidean length.
    #[inline(always)]
    pub fn length(self) -> T {
        self.dot(self).sqrt()
    }
    /// True when every component is finite.
    #[inline(always)]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
    /// The vector scaled to unit length, or `None` if it is zero or not
    /// finite. Scaled by its largest component first, so huge and subnormal
    /// vectors normalise too (their squared length would overflow or vanish).
    /// Inlined: returned through memory, its result was read back with
    /// loads wider than the stores that wrote it, which stall.
    #[inline(always)]
    pub fn try_normalize(self) -> Option<Self> {
        let m = self.x.abs().max_of(self.y.abs()).max_of(self.z.abs());
        if !(m > T::ZERO && self.is_finite()) {
            return None;
        }
        let v = Vec3::new(self.x / m, self.y / m, self.z / m);
        Some(v * (T::ONE / v.length()))
    }
    /// The same vector in another precision (rounded).
    #[inline(always)]
    pub fn cast<U: Real>(self) -> Vec3<U> {
        Vec3::new(
            U::from_f64(self.x.to_f64()),
            U::from_f64(self.y.to_f64()),
            U::from_f64(self.z.to_f64()),
        )
    }
    /// Expresses local coordinates `(x, y, z)` in the basis `(b1, b2, n)`.
    #[inline(always)]
    pub fn from_local(local: Self, b1: Self, b2: Self, n: Self) -> Self {
        b1 * local.x + b2 * local.y + n * local.z
    }
}

impl<T: Real> Add for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Real> Sub for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Real> Mul<T> for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: T) -> Self {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl<T: Real> Neg for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

/// Two unit vectors `(b1, b2)` completing the unit vector `n` to a
/// right-handed orthonormal basis (`b1 × b2 = n`).
///
/// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin, "Building an
/// Orthonormal Basis, Revisited", JCGT 6(1), 2017: branch-free but for the
/// sign, no singularity anywhere on the sphere, and exact for `n = ±z`
/// (`+z → (x, y)`, `−z → (x, −y)`). `n` must be unit length; `-0.0` in `n.z`
/// counts as negative.
#[inline(always)]
pub fn onb<T: Real>(n: Vec3<T>) -> (Vec3<T>, Vec3<T>) {
    let sign = T::ONE.copysign(n.z);
    let a = -T::ONE / (sign + n.z);
    let b = n.x * n.y * a;
    let b1 = Vec3::new(T::ONE + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let b2 = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    (b1, b2)
}

/// The unit direction at polar cosine `mu` and azimuth `phi` (radians) about
/// the unit vector `axis`: `sinθ cosφ b1 + sinθ sinφ b2 + μ axis` with
/// `(b1, b2) = onb(axis)` (the crate's direction convention). For an azimuth
/// drawn from a uniform, [`direction_about_turns`] is faster and more
/// accurate.
#[inline(always)]
pub fn direction_about<T: Real>(axis: Vec3<T>, mu: T, phi: T) -> Vec3<T> {
    direction_about_sin(axis, mu, sin_from_cos(mu), phi)
}

/// `sinθ = sqrt((1 − μ)(1 + μ))` for `θ ∈ [0, π]`; `(1 − μ)(1 + μ)` instead of
/// `1 − μ²` so nothing cancels as `|μ| → 1`.
#[inline(always)]
pub fn sin_from_cos<T: Real>(mu: T) -> T {
    ((T::ONE - mu) * (T::ONE + mu)).max_of(T::ZERO).sqrt()
}

/// [`direction_about`] with `sinθ` given: samplers that know `1 − μ` more
/// precisely than `μ` itself (a forward lobe in f32, where `cos θ` rounds to
/// 1 for θ below 2.4·10⁻⁴) keep the small angle in the direction.
#[inline(always)]
pub fn direction_about_sin<T: Real>(axis: Vec3<T>, mu: T, sin_theta: T, phi: T) -> Vec3<T> {
    let (sin_phi, cos_phi) = phi.sin_cos();
    from_polar(axis, mu, sin_theta, sin_phi, cos_phi)
}

/// The unit direction at polar cosine `mu` (with `sin_theta` as in
/// [`direction_about_sin`]) and azimuth `φ = 2π·turns` about the unit vector
/// `axis`, for `turns ∈ [0, 1]` (a uniform, as every sampler draws it; NaN
/// gives NaN). The azimuth's sine and cosine come from
/// [`crate::math::azimuth`]: reduced exactly in turns, within 1 ULP, and without a
/// library call.
#[inline(always)]
pub fn direction_about_turns<T: Real>(axis: Vec3<T>, mu: T, sin_theta: T, turns: T) -> Vec3<T> {
    let (sin_phi, cos_phi) = turns.sin_cos_2pi();
    from_polar(axis, mu, sin_theta, sin_phi, cos_phi)
}

/// `sinθ cosφ b1 + sinθ sinφ b2 + μ axis`, `(b1, b2) = onb(axis)`.
#[inline(always)]
fn from_polar<T: Real>(axis: Vec3<T>, mu: T, sin_theta: T, sin_phi: T, cos_phi: T) -> Vec3<T> {
    let (b1, b2) = onb(axis);
    Vec3::from_local(
        Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, mu),
        b1,
        b2,
        axis,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_basis(n: Vec3<f64>) {
        let (b1, b2) = onb(n);
        assert!((b1.length() - 1.0).abs() < 1e-15, "{n:?}");
        assert!((b2.length() - 1.0).abs() < 1e-15, "{n:?}");
        assert!(b1.dot(b2).abs() < 1e-15);
        assert!(b1.dot(n).abs() < 1e-15);
        let c = b1.cross(b2);
        assert!((c - n).length() < 1e-15, "{n:?} gives {c:?}");
    }

    #[test]
    fn basis_is_orthonormal_and_right_handed() {
        check_basis(Vec3::new(0.0, 0.0, 1.0));
        check_basis(Vec3::new(0.0, 0.0, -1.0));
        for i in 0..1000 {
            let z = -1.0 + 2.0 * (i as f64 + 0.5) / 1000.0;
            let phi = i as f64 * 2.399963;
            let s = (1.0 - z * z).sqrt();
            check_basis(Vec3::new(s * phi.cos(), s * phi.sin(), z));
        }
        // Close to -z, where the older Frisvad (2012) basis breaks down.
        check_basis(
            Vec3::new(1e-8, 0.0, -(1.0f64 - 1e-16).sqrt())
                .try_normalize()
                .unwrap(),
        );
    }

    #[test]
    fn basis_is_exact_on_z_axis() {
        let (b1, b2) = onb(Vec3::new(0.0f32, 0.0, 1.0));
        assert_eq!(
            (b1, b2),
            (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0))
        );
        let (b1, b2) = onb(Vec3::new(0.0f32, 0.0, -1.0));
        assert_eq!(b1.x, 1.0);
        assert_eq!((b1.y, b1.z), (0.0, 0.0));
        assert_eq!(b2, Vec3::new(0.0, -1.0, 0.0));
    }
}
