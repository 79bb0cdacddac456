//! Equiangular distance sampling toward a point (Kulla & Fajardo,
//! "Importance Sampling Techniques for Path Tracing in Participating
//! Media", EGSR 2012, §3): along a ray segment `[a, b]`, distances with
//! density `∝ 1/r²`, `r` the distance to the point (a light, say), which
//! cancels the light's inverse-square falloff in single scattering. With
//! `t₀` the foot of the perpendicular from the point to the ray and `Δ` its
//! length, the angle `θ = atan((t − t₀)/Δ)` is uniform between
//! `θ_a = atan((a − t₀)/Δ)` and `θ_b`; so `t = t₀ + Δ tan θ` and
//! `pdf(t) = Δ / ((θ_b − θ_a)(Δ² + (t − t₀)²))`. Combine it with free-flight
//! sampling by multiple importance sampling (both pdfs are available).

use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::medium::Ray;

/// Equiangular sampling of one ray segment toward one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equiangular<T> {
    /// The foot of the perpendicular, along the unit direction.
    t0: T,
    /// The distance from the point to the ray's line (> 0).
    delta: T,
    /// The angles of the segment's ends, `θ_a < θ_b`.
    theta: (T, T),
    /// The segment `[a, b]`.
    ends: (T, T),
}

impl<T: Real> Equiangular<T> {
    /// Equiangular sampling over `[t_min, t_max]` of `ray` (distances along
    /// its unit direction; `t_max` may be +∞) toward `point`.
    /// [`Error::Domain`] for a ray [`Ray`] does not accept, a non-finite
    /// point, an empty segment, or a point on the ray's line (the density
    /// would be a spike).
    pub fn new(ray: Ray<T>, point: Vec3<T>) -> Result<Self, Error> {
        let (o, d) = ray.checked()?;
        if !point.is_finite() || ray.t_max <= ray.t_min {
            return Err(Error::Domain);
        }
        let v = point - o;
        let t0 = v.dot(d);
        // |v × d| rather than sqrt(|v|² − t0²), which cancels for a point
        // near the line far along it.
        let c = v.cross(d);
        let delta = c.dot(c).sqrt();
        if delta <= T::ZERO || !delta.is_finite() {
            return Err(Error::Domain);
        }
        let angle = |t: T| (t - t0).atan2(delta);
        Ok(Equiangular {
            t0,
            delta,
            theta: (angle(ray.t_min), angle(ray.t_max)),
            ends: (ray.t_min, ray.t_max),
        })
    }

    /// The distance for a uniform `u` (clamped to `[0, 1]`; NaN stays
    /// NaN), within the segment; monotone in `u`.
    pub fn sample(&self, u: T) -> T {
        let (ta, tb) = self.theta;
        let theta = ta + u.clamp01() * (tb - ta);
        let (s, c) = theta.sin_cos();
        let t = self.t0 + self.delta * (s / c);
        // Written so that a NaN passes through both bounds.
        self.ends.1.min_of(self.ends.0.max_of(t))
    }

    /// The density of distance `t` per unit length (0 outside the segment).
    pub fn pdf(&self, t: T) -> T {
        if !(t >= self.ends.0 && t <= self.ends.1) {
            return T::ZERO;
        }
        let x = t - self.t0;
        self.delta / ((self.theta.1 - self.theta.0) * (self.delta * self.delta + x * x))
    }
}
