//! Equiangular distance sampling toward a point (Kulla & Fajardo,
//! "Importance Sampling Techniques for Path Tracing in Participating
//! Media", EGSR 2012, §3): along a ray segment `[a, b]`, distances with
//! density `∝ 1/r²`, `r` the distance to the point (a light, say), which
//! cancels the light's inverse-square falloff in single scattering. With
//! `t₀` the foot of the perpendicular from the point to the ray and `Δ` its
//! length, the angle `θ = atan((t − t₀)/Δ)` is uniform between `θ_a` and
//! `θ_b`; so `t = t₀ + Δ tan θ` and
//! `pdf(t) = Δ / ((θ_b − θ_a)(Δ² + (t − t₀)²))`. Combine it with free-flight
//! sampling by multiple importance sampling (both pdfs are available).
//!
//! Both are written relative to the segment's start, so that a short
//! segment seen from afar (where `θ_a` and `θ_b` round to the same angle)
//! keeps its full precision: with `x_a = a − t₀`,
//! `θ_b − θ_a = atan2(Δ(b − a), Δ² + x_a x_b)`, and for `φ = θ − θ_a`,
//! `t = a + (Δ² + x_a²) / (Δ cot φ − x_a)` (the tangent's addition
//! formula divided by `sin φ`), neither of which subtracts two angles or
//! two distances near each other. In that form every operation after
//! `cot φ` is monotone, so the distance is monotone in `u` (tested over
//! every f32 `u` for nine segments).

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
    /// The angle the segment subtends, `θ_b − θ_a`, in `(0, π]`.
    span: T,
    /// The segment `[a, b]`.
    ends: (T, T),
}

impl<T: Real> Equiangular<T> {
    /// Equiangular sampling over `[t_min, t_max]` of `ray` (distances along
    /// its unit direction; `t_max` may be +∞) toward `point`.
    /// [`Error::Domain`] for a ray [`Ray`] does not accept, a non-finite
    /// point, an empty segment, a point on the ray's line (the density
    /// would be a spike) or so near it or so far from it that `Δ²`
    /// underflows or overflows, or a segment too short to subtend a
    /// representable angle or to have a representable density (its peak
    /// overflows: a length below about 1/MAX, 5.6·10⁻³⁰⁹ in f64 and
    /// 2.9·10⁻³⁹ in f32, at `Δ` = 1).
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
        let delta2 = c.dot(c);
        if delta2 <= T::ZERO || !delta2.is_finite() {
            return Err(Error::Domain);
        }
        let delta = delta2.sqrt();
        let (a, b) = (ray.t_min, ray.t_max);
        let (xa, xb) = (a - t0, b - t0);
        let (y, x) = (delta * (b - a), delta2 + xa * xb);
        let span = if y.is_finite() && x.is_finite() {
            y.atan2(x)
        } else {
            // An infinite or enormous segment: no cancellation to avoid.
            xb.atan2(delta) - xa.atan2(delta)
        };
        let e = Self::from_parts([t0, delta, span, a, b])?;
        // A segment of a few subnormals' length subtends a representable
        // angle, but its density, about 1/(b − a), overflows: +∞, and NaN
        // in the MIS weights it feeds. Checked here, once, not in
        // `from_parts`, which the C layer runs on every sample.
        if e.pdf(t0.max_of(a).min_of(b)).is_finite() {
            Ok(e)
        } else {
            Err(Error::Domain)
        }
    }

    /// The distance for a uniform `u` (clamped to `[0, 1]`; NaN stays
    /// NaN), within the segment; monotone in `u`.
    pub fn sample(&self, u: T) -> T {
        let (a, b) = self.ends;
        let phi = u.clamp01() * self.span;
        if phi == T::ZERO {
            return a;
        }
        let (s, c) = phi.sin_cos();
        if s < T::ZERO {
            // φ past π, which only rounding reaches: a segment so near the
            // point that its angle rounds up to the precision's π (f32's
            // lies above π). θ is then past π/2, beyond the segment's
            // end; with the sine's sign kept, the distance fell back
            // towards the foot.
            return b;
        }
        let xa = a - self.t0;
        // t − a = (Δ² + x_a²) / (Δ cot φ − x_a): the addition formula
        // divided by sin φ. Every step after cot φ is a correctly rounded
        // operation with a constant, each monotone in its argument, and
        // cot φ = cos φ / sin φ is monotone wherever sin and cos are, so
        // the distance cannot step back with u. (The undivided
        // `K sin φ/(Δ cos φ − x_a sin φ)` mixes two rounded terms that
        // move in opposite directions and stepped back by 1–3 ULP.)
        let den = self.delta * (c / s) - xa;
        // den ≤ 0 only where θ rounds onto π/2: the end of an infinite
        // segment.
        let t = if den <= T::ZERO {
            b
        } else {
            a + (self.delta * self.delta + xa * xa) / den
        };
        // Written so that a NaN passes through both bounds.
        b.min_of(a.max_of(t))
    }

    /// The density of distance `t` per unit length (0 outside the segment).
    pub fn pdf(&self, t: T) -> T {
        if !(t >= self.ends.0 && t <= self.ends.1) {
            return T::ZERO;
        }
        let x = t - self.t0;
        self.delta / (self.span * (self.delta * self.delta + x * x))
    }

    /// The stored state, `[t₀, Δ, θ_b − θ_a, a, b]`: the foot of the
    /// perpendicular and its length (world units along the ray), the angle
    /// the segment subtends (radians), and the segment. For storing it as
    /// plain data (the C layer does); [`from_parts`](Self::from_parts)
    /// reads it back.
    pub fn parts(&self) -> [T; 5] {
        [self.t0, self.delta, self.span, self.ends.0, self.ends.1]
    }

    /// The state back from [`parts`](Self::parts), checked so that values
    /// a caller stored cannot make [`sample`](Self::sample) leave the
    /// segment or [`pdf`](Self::pdf) answer NaN: [`Error::Domain`] unless
    /// `t₀` and `a` are finite, `Δ > 0` with `Δ²` finite and non-zero,
    /// `0 < θ_b − θ_a ≤ π` and `a < b`.
    pub fn from_parts([t0, delta, span, a, b]: [T; 5]) -> Result<Self, Error> {
        let d2 = delta * delta;
        let ok = t0.is_finite() && a.is_finite() && a < b && delta > T::ZERO;
        if ok && d2 > T::ZERO && d2.is_finite() && span > T::ZERO && span <= T::PI {
            Ok(Equiangular {
                t0,
                delta,
                span,
                ends: (a, b),
            })
        } else {
            Err(Error::Domain)
        }
    }
}
