//! Stokes vectors and their reference frames, for polarised transport.
//!
//! A Stokes vector `(I, Q, U, V)` describes light travelling along a unit
//! direction `k` with respect to a unit **reference vector** `e1 ⊥ k`; with
//! `e2 = k × e1` the frame `(e1, e2, k)` is right-handed. `Q = I₁ − I₂` is
//! the excess of light polarised along `e1` over `e2`, `U` the same for the
//! diagonals `(e1 ± e2)/√2`, and `V` the circular part (Chandrasekhar,
//! *Radiative Transfer*, 1960, §15; Hansen & Travis, Space Sci. Rev. 16,
//! 1974, §2). The vector carries its `e1`; `k` is the ray's direction,
//! which the caller holds.
//!
//! Turning the reference about `k` by `α`, `e1′ = cos α e1 + sin α e2`,
//! changes `Q′ = cos 2α Q + sin 2α U`, `U′ = −sin 2α Q + cos 2α U` and
//! leaves `I`, `V` (Mitsuba 3's `rotate_stokes_basis` convention).

use crate::error::Error;
use crate::math::double_double::Dd;
use crate::math::geometry::{Vec3, onb};
use crate::math::real::Real;

/// A Stokes vector with its reference vector `e1` (unit, perpendicular to
/// the direction of travel; module docs). `I ≥ 0` in any radiometric unit,
/// `Q`, `U`, `V` in the same unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stokes<T> {
    /// Intensity.
    pub i: T,
    /// Linear polarisation along `e1` minus along `e2`.
    pub q: T,
    /// Linear polarisation along `(e1 + e2)/√2` minus along `(e1 − e2)/√2`.
    pub u: T,
    /// Circular polarisation.
    pub v: T,
    /// The reference vector `e1`.
    pub reference: Vec3<T>,
}

impl<T: Real> Stokes<T> {
    /// A Stokes vector, checked: every value finite, `I ≥ 0`, `Q² + U² +
    /// V² ≤ I²` up to a relative `10⁻⁶` (rounding of a physical vector),
    /// and `reference` of unit length within `10⁻⁴`. [`Error::Domain`]
    /// otherwise. That `reference` is perpendicular to the direction is the
    /// caller's to keep (the direction is not part of the vector).
    pub fn new(i: T, q: T, u: T, v: T, reference: Vec3<T>) -> Result<Self, Error> {
        let s = Stokes {
            i,
            q,
            u,
            v,
            reference,
        };
        let (i, q, u, v) = (i.to_f64(), q.to_f64(), u.to_f64(), v.to_f64());
        let finite = [i, q, u, v].iter().all(|x| x.is_finite()) && reference.is_finite();
        let len = reference.length().to_f64();
        if finite
            && i >= 0.0
            && q * q + u * u + v * v <= i * i * (1.0 + 1e-6)
            && (len - 1.0).abs() <= 1e-4
        {
            Ok(s)
        } else {
            Err(Error::Domain)
        }
    }
    /// Unpolarised light of intensity `i` with reference `reference`.
    pub fn unpolarized(i: T, reference: Vec3<T>) -> Self {
        Stokes {
            i,
            q: T::ZERO,
            u: T::ZERO,
            v: T::ZERO,
            reference,
        }
    }
    /// The same vector with its polarised part `(Q, U, V)` scaled down,
    /// where rounding put it above `I`, to length `I` (computed in f64):
    /// every vector the library returns is physical, so it is accepted as
    /// an input again. Repeated scatterings with little depolarisation drive
    /// light towards full polarisation, where f32 rounding alone took
    /// `Q² + U² + V²` past `I²` by up to `10⁻⁴` relative.
    pub(crate) fn clamped(self) -> Self {
        let (i, q, u, v) = (
            self.i.to_f64(),
            self.q.to_f64(),
            self.u.to_f64(),
            self.v.to_f64(),
        );
        let p2 = q * q + u * u + v * v;
        // Only a polarised part above I is scaled: NaN anywhere is left as
        // it is, for the caller to see.
        if p2.partial_cmp(&(i * i)) != Some(core::cmp::Ordering::Greater) {
            return self;
        }
        let k = if i > 0.0 { i / p2.sqrt() } else { 0.0 };
        Stokes {
            q: T::from_f64(q * k),
            u: T::from_f64(u * k),
            v: T::from_f64(v * k),
            ..self
        }
    }
    /// The degree of polarisation `sqrt(Q² + U² + V²)/I` (0 for `I = 0`).
    pub fn degree_of_polarization(&self) -> T {
        if self.i > T::ZERO {
            (self.q * self.q + self.u * self.u + self.v * self.v).sqrt() / self.i
        } else {
            T::ZERO
        }
    }
    /// The same light referred to `new_reference` (unit, perpendicular to
    /// the direction of travel `k`): `Q`, `U` turned by the angle from the
    /// old reference to the new one about `k` (module docs). The angle comes
    /// from the components of `new_reference` along `e1` and `e2 = k × e1`,
    /// normalised, so a reference slightly off unit length or off
    /// perpendicular is projected, not propagated. The polarised part stays
    /// within `I` (rounding is clamped, as every output of the library is).
    pub fn rotate_to(&self, k: Vec3<T>, new_reference: Vec3<T>) -> Self {
        let e2 = k.cross(self.reference);
        let (c, s) = (new_reference.dot(self.reference), new_reference.dot(e2));
        let (c2, s2) = double_angle(c, s);
        Stokes {
            i: self.i,
            q: c2 * self.q + s2 * self.u,
            u: c2 * self.u - s2 * self.q,
            v: self.v,
            reference: new_reference,
        }
        .clamped()
    }
}

/// `(cos 2α, sin 2α)` from `(r cos α, r sin α)` for any `r > 0`;
/// `(1, 0)` for `r = 0` (no rotation where the angle is undefined).
#[inline(always)]
pub(crate) fn double_angle<T: Real>(c: T, s: T) -> (T, T) {
    let r2 = c * c + s * s;
    if r2 > T::ZERO {
        ((c * c - s * s) / r2, T::TWO * c * s / r2)
    } else {
        (T::ONE, T::ZERO)
    }
}

/// The meridian reference of direction `k`: the unit vector along
/// increasing polar angle, `∂k/∂θ = (cos θ cos φ, cos θ sin φ, −sin θ)`,
/// lying in the plane of `k` and the z axis (the convention of
/// plane-parallel radiative transfer, where `Q > 0` is polarisation in the
/// meridian plane). Along `k = ±z` the plane is undefined and
/// `hint_azimuth` (radians) gives `φ`.
pub fn meridian_reference<T: Real>(k: Vec3<T>, hint_azimuth: T) -> Vec3<T> {
    let rho = (k.x * k.x + k.y * k.y).sqrt();
    let (s, c) = if rho > T::ZERO {
        (k.y / rho, k.x / rho)
    } else {
        hint_azimuth.sin_cos()
    };
    Vec3::new(k.z * c, k.z * s, -rho)
}

/// A reference vector for `k` when the caller has no preferred one: the
/// first vector of the crate's basis [`onb`]`(k)` (continuous except
/// across `k.z = 0⁻`).
pub fn implicit_reference<T: Real>(k: Vec3<T>) -> Vec3<T> {
    onb(k).0
}

/// `a × b` with each component rounded once from its exact value (the
/// products and their difference in double-double): the normal of a
/// scattering plane keeps its direction to a few ULP however small the
/// angle between `a` and `b`, where the plain cross product keeps it only
/// to `ε / angle`.
pub(crate) fn cross_exact<T: Real>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    let d = |p: T, q: T, r: T, s: T| {
        let e = Dd::product(p.to_f64(), q.to_f64()) - Dd::product(r.to_f64(), s.to_f64());
        T::from_f64(e.hi + e.lo)
    };
    Vec3::new(
        d(a.y, b.z, a.z, b.y),
        d(a.z, b.x, a.x, b.z),
        d(a.x, b.y, a.y, b.x),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_by_a_quarter_turn_flips_q_and_u() {
        let k = Vec3::new(0.0, 0.0, 1.0);
        let s = Stokes::new(1.0, 0.6, 0.2, 0.1, Vec3::new(1.0, 0.0, 0.0)).unwrap();
        let r = s.rotate_to(k, Vec3::new(0.0, 1.0, 0.0));
        assert!((r.q + 0.6).abs() < 1e-15 && (r.u + 0.2).abs() < 1e-15 && r.v == 0.1);
        // 45°: Q → U.
        let h = core::f64::consts::FRAC_1_SQRT_2;
        let r = s.rotate_to(k, Vec3::new(h, h, 0.0));
        assert!((r.q - 0.2).abs() < 1e-15 && (r.u + 0.6).abs() < 1e-15);
    }

    #[test]
    fn exact_cross_keeps_tiny_angles() {
        let a = Vec3::new(0.3f64, 0.4, (1.0f64 - 0.25).sqrt());
        let b = Vec3::new(a.x + 1e-9, a.y, a.z);
        let t = b.x - a.x; // exact
        let c = cross_exact(a, b);
        // a × (a + t x̂) = t (a × x̂) = t (0, a.z, −a.y).
        assert!((c.y / (t * a.z) - 1.0).abs() < 1e-6 && (c.z / (-t * a.y) - 1.0).abs() < 1e-6);
    }
}
