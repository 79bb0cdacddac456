//! Polarised Rayleigh scattering with depolarisation `ρ`: the Mueller
//! matrix, the Stokes vector scattered into a direction, and an exact
//! sampler whose direction density follows the incident polarisation.
//!
//! **Matrix** (Hansen & Travis, Space Sci. Rev. 16, 1974, eq. 2.15),
//! normalised to a mean of 1 over the sphere, with `c = cos Θ`,
//! `Δ = (1 − ρ)/(1 + ρ/2)`, `Δ′ = (1 − 2ρ)/(1 − ρ)`:
//! `P11 = ¾Δ(1 + c²) + (1 − Δ)`, `P12 = −¾Δ(1 − c²)`, `P22 = ¾Δ(1 + c²)`,
//! `P33 = (3/2)Δc`, `P44 = (3/2)ΔΔ′c`, the rest 0 (the constants formed in
//! double-double and rounded once). It acts on the incident
//! Stokes vector referred to the scattering plane (`e1` in the plane) and
//! gives the scattered one referred to the plane too, with reference
//! `∂ω/∂Θ`. `P11/4π` is [`RayleighDepolarized`]'s density. `1 − c²` is
//! formed as `(1 − |c|)(1 + |c|)` for `|c| ≥ ½`, which does not cancel at
//! `|c| → 1`.
//!
//! **Sampler.** For incident light with `q = Q/I`, `u = U/I` referred to
//! the reference `e1`, the scattered intensity is `I (P11 + P12 q_φ)/4π`
//! with `q_φ = q cos 2φ + u sin 2φ`, `φ` the azimuth of the scattering
//! plane from `e1`. Integrating over `c` (`∫P11 = 2`, `∫P12 = −Δ`) leaves
//! the azimuth's density `[1 − (Δ/2)(q cos 2φ + u sin 2φ)]/2π =
//! [1 − e cos(2φ − 2χ)]/2π`, `e = Δp/2 ≤ ½` (`p = √(q² + u²)`, `2χ =
//! atan2(u, q)`). Its CDF set to `u₂` is Kepler's equation `x − e sin x =
//! M` with `x = 2φ − 2χ`, `M = 4πu₂ − 2χ + e sin 2χ`, solved by Newton
//! after reducing `M` to `[−π, π]` (the left side gains `2π` with `x`).
//! Given `φ`, `cos Θ` has density `∝ A + Bc²`, `A = ¾Δ(1 − q_φ) + 1 −
//! Δ`, `B = ¾Δ(1 + q_φ)`, whose CDF is the depressed cubic `x³ + 3a x =
//! 2b`, `a = A/B`, `b = (2u₁ − 1)(3a + 1)/2`, solved like
//! [`RayleighDepolarized`]'s (for `a > 10⁸`, where `a³` would overflow in
//! f32, the two-term series `x₀ − x₀³/3a`, `x₀ = (2u₁ − 1)(1 + 1/3a)`, whose
//! error is `O(a⁻²)`). The intensity weight is exactly 1 and the new Stokes
//! vector is `I · PS/(PS)₁`, so `|Q|, |U|, |V| ≤ I`. The azimuth is
//! measured from the first vector of [`onb`]`(k)`, as every direction
//! sampler of the crate measures it; for unpolarised input (`p = 0`) the
//! sampler is [`RayleighDepolarized`]'s, bit for bit. Sampling `Θ` first
//! instead would give a Kepler-like equation with `e` up to 1, singular at
//! 90°.

use super::RayleighDepolarized;
use super::function::PhaseFunction;
use crate::error::Error;
use crate::math::double_double::Dd;
use crate::math::geometry::{Vec3, direction_about_turns, onb, sin_from_cos};
use crate::math::numeric::depressed_cubic_root;
use crate::math::real::Real;
use crate::stokes::{Stokes, cross_exact, double_angle};

/// The non-zero elements of the normalised Rayleigh Mueller matrix at one
/// scattering angle (module docs); dimensionless, mean of `p11` over the
/// sphere 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayleighMueller<T> {
    /// `P11`.
    pub p11: T,
    /// `P12 = P21`.
    pub p12: T,
    /// `P22`.
    pub p22: T,
    /// `P33`.
    pub p33: T,
    /// `P44`.
    pub p44: T,
}

/// A sampled scattering: direction, the scattered Stokes vector (referred
/// to the new scattering plane) and the density of the direction per
/// steradian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StokesSample<T> {
    /// The scattered unit direction.
    pub dir: Vec3<T>,
    /// The Stokes vector carried on: `I` times the sample's weight.
    pub stokes: Stokes<T>,
    /// The density of `dir` per steradian.
    pub pdf: T,
}

/// Polarised Rayleigh scattering with depolarisation factor `ρ ∈ [0, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayleighPolarized<T> {
    depol: RayleighDepolarized<T>,
    /// `¾Δ`, `1 − Δ`, `(3/2)Δ`, `(3/2)ΔΔ′` and `Δ/2`.
    k34: T,
    one_minus: T,
    k32: T,
    k44: T,
    half_delta: T,
}

impl<T: Real> RayleighPolarized<T> {
    /// Fails with [`Error::Domain`] unless `0 ≤ rho < 1` (NaN fails).
    pub fn new(rho: T) -> Result<Self, Error> {
        let depol = RayleighDepolarized::new(rho)?;
        // The constants in double-double, rounded once: each is then within
        // half a unit of the last place, and the elements within 2 ULP.
        let r = rho.to_f64();
        let delta = Dd::sum(1.0, -r) / Dd::sum(1.0, 0.5 * r);
        let delta_p = Dd::sum(1.0, -2.0 * r) / Dd::sum(1.0, -r);
        let k32 = Dd::from(1.5) * delta;
        let t = |d: Dd| T::from_f64(d.hi);
        Ok(RayleighPolarized {
            depol,
            k34: t(Dd::from(0.75) * delta),
            one_minus: t(Dd::from(1.0) - delta),
            k32: t(k32),
            k44: t(k32 * delta_p),
            half_delta: t(Dd::from(0.5) * delta),
        })
    }
    /// The depolarisation factor `ρ`.
    pub fn rho(&self) -> T {
        self.depol.rho()
    }
    /// The scalar phase function `P11/4π` ([`RayleighDepolarized`]).
    pub fn scalar(&self) -> RayleighDepolarized<T> {
        self.depol
    }
    /// The matrix at `cos Θ = cos_theta ∈ [−1, 1]` (module docs), each
    /// element evaluated in double-double and rounded once (within 1 ULP;
    /// the samplers use a faster form within a few).
    pub fn mueller(&self, cos_theta: T) -> RayleighMueller<T> {
        let r = self.rho().to_f64();
        let c = Dd::from(cos_theta.to_f64());
        let one = Dd::from(1.0);
        let delta = Dd::sum(1.0, -r) / Dd::sum(1.0, 0.5 * r);
        let delta_p = Dd::sum(1.0, -2.0 * r) / Dd::sum(1.0, -r);
        let k34 = Dd::from(0.75) * delta;
        let p22 = k34 * (one + c * c);
        let k32c = Dd::from(1.5) * delta * c;
        let t = |d: Dd| T::from_f64(d.hi);
        RayleighMueller {
            p11: t(p22 + (one - delta)),
            p12: t(Dd::from(0.0) - k34 * (one - c * c)),
            p22: t(p22),
            p33: t(k32c),
            p44: t(k32c * delta_p),
        }
    }

    /// The matrix from the constants in `T` (a few ULP): the samplers'.
    #[inline(always)]
    fn mueller_fast(&self, c: T) -> RayleighMueller<T> {
        let p22 = self.k34 * (T::ONE + c * c);
        // 1 − c²: as (1 − |c|)(1 + |c|) where 1 − |c| is exact (|c| ≥ ½),
        // which does not cancel as |c| → 1; directly below.
        let a = c.abs();
        let sin2 = if a >= T::HALF {
            (T::ONE - a) * (T::ONE + a)
        } else {
            T::ONE - c * c
        };
        RayleighMueller {
            p11: p22 + self.one_minus,
            p12: -(self.k34 * sin2),
            p22,
            p33: self.k32 * c,
            p44: self.k44 * c,
        }
    }

    /// The incident `(q, u)` per unit intensity turned into the
    /// scattering plane, and `(I, Q, U, V)` scattered per unit incident
    /// intensity (`P S`, not yet over `4π`), with `P11`.
    #[inline]
    fn in_plane(&self, mu: T, s: &Stokes<T>, qb: T, ub: T, cos2: T, sin2: T) -> (T, [T; 4]) {
        let m = self.mueller_fast(mu);
        let vn = if s.i > T::ZERO { s.v / s.i } else { T::ZERO };
        let q_r = cos2 * qb + sin2 * ub;
        let u_r = cos2 * ub - sin2 * qb;
        // P11 + P12 q_r ≥ 0 (|P12| ≤ P11, |q_r| ≤ 1), but at its zero (ρ = 0,
        // fully polarised light, 90° along the field) it rounded to
        // −1.8·10⁻¹⁷: a negative density, and an I < 0 that eval returned
        // and would then refuse as input. Held at 0 (NaN passes).
        let i = m.p11 + m.p12 * q_r;
        let ps = [
            if i < T::ZERO { T::ZERO } else { i },
            m.p12 + m.p22 * q_r,
            m.p33 * u_r,
            m.p44 * vn,
        ];
        (m.p11, ps)
    }

    /// The scattering plane of `k → w`: `(cos Θ, e⊥)` with `e⊥` the unit
    /// normal `k × w/|k × w|` (the exact cross product within 1/64 rad of
    /// forward or backward), or `fallback` where the
    /// plane is undefined (`w = ±k`; there the matrix does not depend on
    /// it).
    fn plane(k: Vec3<T>, w: Vec3<T>, fallback: Vec3<T>) -> (T, Vec3<T>) {
        // The plain cross product's direction is good to ε/|n|: enough
        // above |n| = 1/64; below, the exact one.
        let mut n = k.cross(w);
        if n.length() < T::from_f64(1.0 / 64.0) {
            n = cross_exact(k, w);
        }
        let len = n.length();
        let e_perp = if len > T::ZERO && len.is_finite() {
            n * (T::ONE / len)
        } else {
            fallback
        };
        (k.dot(w).clamp_unit(), e_perp)
    }

    /// The Stokes vector scattered from light `s` travelling along `k`
    /// into the unit direction `w`, per steradian (the matrix over `4π`),
    /// referred to `out_reference` (unit, perpendicular to `w`): what
    /// next-event estimation adds towards a detector. `s.reference` must be
    /// perpendicular to `k`. The polarised part is clamped to `I` where
    /// rounding would put it above.
    pub fn eval(&self, k: Vec3<T>, s: &Stokes<T>, w: Vec3<T>, out_reference: Vec3<T>) -> Stokes<T> {
        let e2 = k.cross(s.reference);
        let (mu, e_perp) = Self::plane(k, w, e2);
        // The plane's reference e∥ = e⊥ × k is at angle α from e1 with
        // cos α = e⊥·e2, sin α = −e⊥·e1.
        let (cos2, sin2) = double_angle(e_perp.dot(e2), -e_perp.dot(s.reference));
        let (qn, un) = per_unit(s);
        let (_, [i, q, u, v]) = self.in_plane(mu, s, qn, un, cos2, sin2);
        let scale = T::INV_4PI * s.i.max_of(T::ZERO);
        let out = Stokes {
            i: scale * i,
            q: scale * q,
            u: scale * u,
            v: scale * v,
            reference: e_perp.cross(w),
        };
        out.rotate_to(w, out_reference)
    }

    /// The density per steradian with which [`sample`](Self::sample) draws
    /// `w` for light `s` along `k`: `(P11 + P12 q_φ)/4π` (module docs).
    pub fn pdf(&self, k: Vec3<T>, s: &Stokes<T>, w: Vec3<T>) -> T {
        let e2 = k.cross(s.reference);
        let (mu, e_perp) = Self::plane(k, w, e2);
        let (cos2, sin2) = double_angle(e_perp.dot(e2), -e_perp.dot(s.reference));
        let (qn, un) = per_unit(s);
        self.in_plane(mu, s, qn, un, cos2, sin2).1[0] * T::INV_4PI
    }

    /// Draws the scattered direction of light `s` along the unit direction
    /// `k` from `u1`, `u2 ∈ [0, 1]` (clamped): the exact sampler of the
    /// module docs. The returned Stokes vector keeps `I` and refers to the
    /// new scattering plane (reference `∂ω/∂Θ`); the density is the
    /// direction's. Monotone in each uniform. The polarised part is clamped
    /// to `I` where rounding would put it above (as in every Stokes vector
    /// the library returns), so the output is always a valid input.
    pub fn sample(&self, k: Vec3<T>, s: &Stokes<T>, u1: T, u2: T) -> StokesSample<T> {
        let (u1, u2) = (u1.clamp01(), u2.clamp01());
        let (b1, b2) = onb(k);
        let (qb, ub) = self.in_basis(k, s, b1);
        let p = (qb * qb + ub * ub).sqrt();
        let (mu, dir, phi, pdf);
        if p > T::ZERO {
            phi = self.azimuth(qb, ub, p, u2);
            let (sp, cp) = phi;
            let (cos2, sin2) = twice(phi);
            mu = self.cos_given(cos2 * qb + sin2 * ub, u1);
            let sin_theta = sin_from_cos(mu);
            let local = Vec3::new(sin_theta * cp, sin_theta * sp, mu);
            dir = Vec3::from_local(local, b1, b2, k);
            pdf = None;
        } else {
            // Unpolarised (linear part): the depolarised sampler exactly.
            mu = self.depol.sample_cos(u1);
            dir = direction_about_turns(k, mu, sin_from_cos(mu), u2);
            phi = u2.sin_cos_2pi();
            pdf = Some(self.depol.pdf(mu));
        }
        let (cos2, sin2) = twice(phi);
        let (_, [i, q, u, v]) = self.in_plane(mu, s, qb, ub, cos2, sin2);
        let ratio = |x: T| if i > T::ZERO { s.i * (x / i) } else { T::ZERO };
        StokesSample {
            dir,
            stokes: Stokes {
                i: s.i,
                q: ratio(q),
                u: ratio(u),
                v: ratio(v),
                reference: perpendicular(b1, b2, phi).cross(dir),
            }
            .clamped(),
            pdf: pdf.unwrap_or(i * T::INV_4PI),
        }
    }

    /// Scalar sampling with matrix weighting, for callers who sample the
    /// direction from `P11` alone (as [`RayleighDepolarized::sample_dir`],
    /// bit for bit) and carry the polarisation as a weight: the returned
    /// Stokes vector is `I · P S / P11` referred to the new scattering
    /// plane, so its `I` changes by `(P11 + P12 q_φ)/P11`. The density is
    /// `P11/4π`. Unbiased, but its weights' variance grows with the number
    /// of scatterings where the exact sampler's does not. The polarised part
    /// is clamped to `I` where rounding would put it above.
    pub fn sample_scalar(&self, k: Vec3<T>, s: &Stokes<T>, u1: T, u2: T) -> StokesSample<T> {
        let (u1, u2) = (u1.clamp01(), u2.clamp01());
        let (b1, b2) = onb(k);
        let (qb, ub) = self.in_basis(k, s, b1);
        let mu = self.depol.sample_cos(u1);
        let dir = direction_about_turns(k, mu, sin_from_cos(mu), u2);
        let phi = u2.sin_cos_2pi();
        let (cos2, sin2) = twice(phi);
        let (p11, [i, q, u, v]) = self.in_plane(mu, s, qb, ub, cos2, sin2);
        let w = |x: T| s.i * (x / p11);
        StokesSample {
            dir,
            stokes: Stokes {
                i: w(i),
                q: w(q),
                u: w(u),
                v: w(v),
                reference: perpendicular(b1, b2, phi).cross(dir),
            }
            .clamped(),
            pdf: self.depol.pdf(mu),
        }
    }

    /// `(q, u)` per unit intensity referred to `b1` instead of `s`'s
    /// reference (both perpendicular to `k`).
    #[inline]
    fn in_basis(&self, k: Vec3<T>, s: &Stokes<T>, b1: Vec3<T>) -> (T, T) {
        let (qn, un) = per_unit(s);
        let e2 = k.cross(s.reference);
        let (c2, s2) = double_angle(b1.dot(s.reference), b1.dot(e2));
        (c2 * qn + s2 * un, c2 * un - s2 * qn)
    }

    /// `(sin φ, cos φ)` of the azimuth from `b1` for `u2`, by Kepler's
    /// equation (module docs); `p = √(q² + u²) > 0`.
    fn azimuth(&self, qb: T, ub: T, p: T, u2: T) -> (T, T) {
        let p = p.min_of(T::ONE);
        let e = self.half_delta * p;
        let two_chi = ub.atan2(qb);
        let m = T::from_f64(4.0) * T::PI * u2 - two_chi + e * (ub / p).clamp_unit();
        // M ∈ [−π − ½, 5π + ½]: reduce by whole turns to [−π, π].
        let turns = (m / T::TAU + T::from_f64(1.5)).to_index();
        let shift = T::TAU * (T::from_index(turns) - T::ONE);
        let x = kepler(e, m - shift) + shift;
        (T::HALF * (x + two_chi)).sin_cos()
    }

    /// `cos Θ` for `u1` given `q_φ` (module docs).
    #[inline]
    fn cos_given(&self, q_phi: T, u1: T) -> T {
        if q_phi == T::ZERO {
            return self.depol.sample_cos(u1);
        }
        let a_coef = self.k34 * (T::ONE - q_phi) + self.one_minus;
        let b_coef = self.k34 * (T::ONE + q_phi);
        let x = T::TWO * u1 - T::ONE;
        if x == T::ZERO {
            // The median of a density even in c is 0. The cubic's root
            // would be 0/0 where A = 0 too (ρ = 0, light polarised in the
            // scattering plane: q_φ = 1), a NaN direction with fully
            // polarised light at u1 = ½.
            return T::ZERO;
        }
        let mu = if b_coef <= a_coef * T::from_f64(1e-8) {
            let inv3a = b_coef / (T::from_f64(3.0) * a_coef);
            let x0 = x * (T::ONE + inv3a);
            x0 - x0 * x0 * x0 * inv3a
        } else {
            let a = a_coef / b_coef;
            let b = T::HALF * x * (T::from_f64(3.0) * a + T::ONE);
            depressed_cubic_root::<T, false>(a, a * a, b)
        };
        mu.clamp_unit()
    }
}

/// `(cos 2φ, sin 2φ)` from `(sin φ, cos φ)`.
#[inline(always)]
fn twice<T: Real>((sp, cp): (T, T)) -> (T, T) {
    (cp * cp - sp * sp, T::TWO * sp * cp)
}

/// The normal of the scattering plane at azimuth `φ` (given as `(sin φ,
/// cos φ)`) from `b1`: `−sin φ b1 + cos φ b2`.
#[inline(always)]
fn perpendicular<T: Real>(b1: Vec3<T>, b2: Vec3<T>, (sp, cp): (T, T)) -> Vec3<T> {
    b2 * cp - b1 * sp
}

/// `(Q/I, U/I)`, or `(0, 0)` for `I ≤ 0`.
#[inline(always)]
fn per_unit<T: Real>(s: &Stokes<T>) -> (T, T) {
    if s.i > T::ZERO {
        (s.q / s.i, s.u / s.i)
    } else {
        (T::ZERO, T::ZERO)
    }
}

/// The root of Kepler's equation `x − e sin x = m` for `0 ≤ e ≤ ½`, `m ∈
/// [−π, π]`: Newton's method from `m + e sin m/(1 − e cos m)`. The left
/// side is increasing with slope at least `1 − e ≥ ½`, so every step
/// converges; the loop stops when a step is below the rounding of `x`.
pub(crate) fn kepler<T: Real>(e: T, m: T) -> T {
    let (sm, cm) = m.sin_cos();
    let mut x = m + e * sm / (T::ONE - e * cm);
    for _ in 0..12 {
        let (s, c) = x.sin_cos();
        let dx = (x - e * s - m) / (T::ONE - e * c);
        x -= dx;
        if dx.is_nan() || dx.abs() <= T::EPSILON * x.abs() {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `cos_given` switches from the cubic's root to its series where
    /// `b ≤ 10⁻⁸ a` (`q_φ` within about 10⁻⁸ of −1); the two sides agree
    /// across the switch (a mutation of the series went unnoticed: the
    /// branch covers a sliver of azimuths too thin for a χ² test).
    #[test]
    fn the_series_meets_the_cubic_where_they_switch() {
        for rho in [0.0f64, 0.03, 0.3] {
            let r = RayleighPolarized::new(rho).unwrap();
            // b = 10⁻⁸ a at q = −1 + ε, with a ≈ 2 k34 + one_minus.
            let eps = 1e-8 * (2.0 * r.k34 + r.one_minus) / r.k34;
            let (series, cubic) = (-1.0 + 0.9 * eps, -1.0 + 1.1 * eps);
            for i in 0..=100 {
                let u = i as f64 / 100.0;
                let (a, b) = (r.cos_given(series, u), r.cos_given(cubic, u));
                assert!((a - b).abs() < 1e-7, "rho {rho} u {u}: {a} against {b}");
            }
        }
    }

    /// The samplers' matrix is within a few ulp of the double-double one
    /// (each element relative to itself), also as `|cos Θ| → 1`, where
    /// `1 − cos²Θ` taken directly cancels (a mutation swapping the two
    /// forms of `sin²Θ` went unnoticed: the error is below every χ²
    /// test's reach).
    #[test]
    fn the_samplers_matrix_is_within_a_few_ulp() {
        fn check<T: Real>() {
            let digits = if core::mem::size_of::<T>() == 8 {
                53
            } else {
                24
            };
            let poles = (1..digits).flat_map(|k| {
                let x = T::ONE - T::from_f64(2f64.powi(-k));
                [x, -x]
            });
            let grid = (0..=2000).map(|i| T::from_f64(-1.0 + i as f64 / 1000.0));
            for rho in [0.0, 0.03, 0.3] {
                let r = RayleighPolarized::<T>::new(T::from_f64(rho)).unwrap();
                for c in poles.clone().chain(grid.clone()) {
                    let (fast, exact) = (r.mueller_fast(c), r.mueller(c));
                    let pairs = [
                        (fast.p11, exact.p11),
                        (fast.p12, exact.p12),
                        (fast.p22, exact.p22),
                        (fast.p33, exact.p33),
                        (fast.p44, exact.p44),
                    ];
                    for (j, (f, e)) in pairs.into_iter().enumerate() {
                        let ulps = (f - e).abs().to_f64() / (T::EPSILON * e.abs()).to_f64();
                        assert!(
                            f == e || ulps <= 8.0,
                            "rho {rho} cos {c:?} element {j}: {ulps} ulp"
                        );
                    }
                }
            }
        }
        check::<f32>();
        check::<f64>();
    }

    /// `cos_given` against Newton's method on its own equation, `aμ +
    /// bμ³/3 = x(a + b/3)` with `x = 2u − 1`, on both sides of the switch
    /// to the series (`b ≤ 10⁻⁸ a`): within 10⁻¹⁵.
    /// `the_series_meets_the_cubic_where_they_switch` only holds the two
    /// routes together within 10⁻⁷, where the series' own
    /// terms are below 10⁻⁸: mutations of them went unnoticed.
    #[test]
    fn cos_given_solves_its_cubic_on_both_sides_of_the_series() {
        for rho in [0.0f64, 0.03, 0.3] {
            let r = RayleighPolarized::new(rho).unwrap();
            for ratio in [1e-12, 1e-10, 3e-9, 0.9e-8, 1.1e-8, 1e-7, 1e-4] {
                // q_φ near −1 with b = ratio·a.
                let q = (ratio * r.one_minus + (ratio - 1.0) * r.k34) / ((1.0 + ratio) * r.k34);
                let (a, b) = (r.k34 * (1.0 - q) + r.one_minus, r.k34 * (1.0 + q));
                for i in 0..=200 {
                    let u = i as f64 / 200.0;
                    let x = 2.0 * u - 1.0;
                    let mut mu = x;
                    for _ in 0..50 {
                        mu -= (a * mu + b * mu * mu * mu / 3.0 - x * (a + b / 3.0))
                            / (a + b * mu * mu);
                    }
                    let got = r.cos_given(q, u);
                    assert!(
                        (got - mu).abs() <= 1e-15,
                        "rho {rho} b/a {ratio} u {u}: {got} against {mu}"
                    );
                }
            }
        }
    }

    #[test]
    fn kepler_residual_is_at_rounding_in_f32() {
        for &e in &[0.0f32, 1e-6, 0.1, 0.3, 0.5] {
            for i in 0..=1000 {
                let m = -core::f32::consts::PI + core::f32::consts::TAU * i as f32 / 1000.0;
                let x = kepler(e, m);
                // The residual in f64 of the f32 root: at most 2 ULP of x.
                let r = x as f64 - e as f64 * libm::sin(x as f64) - m as f64;
                let ulp = f32::EPSILON as f64 * x.abs().max(m.abs()) as f64;
                assert!(r.abs() <= 2.0 * ulp, "e {e} m {m}: {r:e}");
            }
        }
    }

    /// Fully polarised light with ρ = 0 where the sampled azimuth lands on
    /// the plane of polarisation (`q_φ = 1`, so `A = 0`, at the `u2` that
    /// put it there for Q = ±I along the basis) and `u1 = ½`: a unit
    /// direction at `cos Θ = 0` with a finite density. The cubic's root
    /// was 0/0 there, a NaN direction and density with no error; in float
    /// a generator's `u1 = ½` comes once in 2²⁴ draws.
    fn median_on_the_plane<T: Real>() {
        let r = RayleighPolarized::<T>::new(T::ZERO).unwrap();
        let h = T::from_f64(core::f64::consts::FRAC_1_SQRT_2);
        let ks = [
            Vec3::new(T::ZERO, T::ZERO, T::ONE),
            Vec3::new(T::ONE, T::ZERO, T::ZERO),
            Vec3::new(h, h, T::ZERO),
        ];
        for k in ks {
            let k = k * (T::ONE / k.length());
            // The basis's own reference, and the meridian one (with it, U
            // polarised light along (1, 1, 0) rounded the density to
            // −1.8·10⁻¹⁷ at u = (½, ¼)).
            let (b1, _) = onb(k);
            let refs = [b1, crate::stokes::meridian_reference(k, T::from_f64(0.3))];
            let pol = [(T::ONE, T::ZERO), (-T::ONE, T::ZERO), (T::ZERO, T::ONE)];
            for (reference, (q, u)) in refs.into_iter().flat_map(|r| pol.map(|p| (r, p))) {
                let s = Stokes::new(T::ONE, q, u, T::ZERO, reference).unwrap();
                for u2 in [0.0, 0.25, 0.5, 0.75, 1.0] {
                    let x = r.sample(k, &s, T::HALF, T::from_f64(u2));
                    let len = x.dir.length().to_f64();
                    assert!(
                        (len - 1.0).abs() < 1e-6,
                        "{k:?} q {q:?} u2 {u2}: {:?}",
                        x.dir
                    );
                    assert!(
                        x.dir.dot(k).abs() < T::from_f64(1e-6),
                        "{k:?} q {q:?} u2 {u2}"
                    );
                    assert!(x.pdf.is_finite() && x.pdf >= T::ZERO, "{:?}", x.pdf);
                    let st = x.stokes;
                    assert!(
                        [st.i, st.q, st.u, st.v].iter().all(|v| v.is_finite()),
                        "{st:?}"
                    );
                    // At the null of the dipole pattern the density and the
                    // intensity round to 0, never below (a negative I would
                    // be refused as the next input).
                    let pdf = r.pdf(k, &s, x.dir);
                    assert!(pdf >= T::ZERO, "{k:?} q {q:?} u {u:?} u2 {u2}: {pdf:?}");
                    let (reference, _) = onb(x.dir);
                    let e = r.eval(k, &s, x.dir, reference);
                    assert!(Stokes::new(e.i, e.q, e.u, e.v, reference).is_ok(), "{e:?}");
                }
            }
        }
    }

    #[test]
    fn the_median_on_the_plane_of_polarisation_is_a_direction() {
        median_on_the_plane::<f32>();
        median_on_the_plane::<f64>();
    }

    #[test]
    fn kepler_residual_is_at_rounding() {
        for &e in &[0.0f64, 1e-6, 0.1, 0.3, 0.5] {
            for i in 0..=1000 {
                let m = -core::f64::consts::PI + core::f64::consts::TAU * i as f64 / 1000.0;
                let x = kepler(e, m);
                let r = x - e * libm::sin(x) - m;
                let ulp = f64::EPSILON * x.abs().max(m.abs());
                assert!(r.abs() <= 2.0 * ulp, "e {e} m {m}: {r:e}");
            }
        }
    }
}
