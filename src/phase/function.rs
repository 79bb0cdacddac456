//! The trait every phase function implements ([`PhaseFunction`]), with the
//! default batch loops, and the check of uniforms the batch calls share.

use crate::error::Error;
use crate::math::geometry::{Vec3, direction_about_turns, sin_from_cos};
use crate::math::real::Real;

/// A phase function over the cosine of the scattering angle.
pub trait PhaseFunction<T: Real> {
    /// Density per steradian at `cos_theta` (domain `[-1, 1]`; outside it
    /// a model's own formula is evaluated as is, while [`Phase`](crate::Phase)
    /// reads it where [`support`] says: 0 beyond 8 ulp outside).
    fn pdf(&self, cos_theta: T) -> T;
    /// `P(cos θ ≤ cos_theta)`, in `[0, 1]`; arguments outside `[-1, 1]` are
    /// clamped.
    fn cdf(&self, cos_theta: T) -> T;
    /// The inverse of [`cdf`](Self::cdf): maps `u ∈ [0, 1]` to `cos θ`.
    /// `u` outside `[0, 1]` is clamped, NaN gives NaN (as in C; the Python
    /// package raises `ValueError` for both instead).
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

    /// The density per steradian at the angle `(cos θ, sin θ)` that
    /// [`sample_cos_sin`](Self::sample_cos_sin) gives: [`pdf`](Self::pdf)`(cos
    /// θ)` but for a density infinite at a pole (Fournier–Forand's forward
    /// pole), where a `cos θ` rounded to ±1 would give ∞ and `sin θ` still
    /// places the angle.
    #[inline]
    fn pdf_cos_sin(&self, cos_theta: T, sin_theta: T) -> T {
        let _ = sin_theta;
        self.pdf(cos_theta)
    }

    /// A direction scattered from the unit propagation direction `w_in`:
    /// `cos θ = sample_cos(u1)`, azimuth `2π u2` in the basis
    /// [`onb`](crate::math::geometry::onb)`(w_in)`, the polar angle from
    /// [`sample_cos_sin`](Self::sample_cos_sin). Returns the direction and
    /// its density per steradian ([`pdf_cos_sin`](Self::pdf_cos_sin) at
    /// that angle).
    #[inline]
    fn sample_dir(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        let (mu, sin_theta) = self.sample_cos_sin(u1);
        let dir = direction_about_turns(w_in, mu, sin_theta, u2.clamp01());
        (dir, self.pdf_cos_sin(mu, sin_theta))
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
    /// over the shortest slice's length. The closed-form samplers are
    /// branch-free, so the compiler vectorises their loops.
    #[inline]
    fn sample_dir_each(
        &self,
        w_in: [&[T]; 3],
        u1: &[T],
        u2: &[T],
        out: [&mut [T]; 3],
        pdf_out: &mut [T],
    ) {
        dir_each(w_in, [u1, u2], out, pdf_out, |w, a, b| {
            self.sample_dir(w, a, b)
        });
    }
}

/// The loop of [`PhaseFunction::sample_dir_each`]: `out[i], pdf_out[i] =
/// dir(w_in[i], u1[i], u2[i])` over the shortest slice's length. A model
/// whose `sample_dir` the compiler might leave out of line in the loop (and
/// so not vectorise it) passes an always-inlined body of its own.
#[inline(always)]
pub(crate) fn dir_each<T: Real>(
    w_in: [&[T]; 3],
    [u1, u2]: [&[T]; 2],
    out: [&mut [T]; 3],
    pdf_out: &mut [T],
    dir: impl Fn(Vec3<T>, T, T) -> (Vec3<T>, T),
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
        let (d, p) = dir(Vec3::new(wx[i], wy[i], wz[i]), u1[i], u2[i]);
        ox[i] = d.x;
        oy[i] = d.y;
        oz[i] = d.z;
        pdf[i] = p;
    }
}

/// Code generic over the model, run on the model inside a
/// [`Phase`](super::Phase) by [`Phase::visit`](super::Phase::visit).
pub trait PhaseVisitor<T: Real> {
    /// What the visit returns.
    type Output;
    /// Runs on the model `m`.
    fn visit<M: PhaseFunction<T>>(self, m: &M) -> Self::Output;
}

/// [`Error::Domain`] if any `u` is NaN or outside `[0, 1]`.
#[inline]
pub fn check_uniforms<T: Real>(u: &[T]) -> Result<(), Error> {
    #[cfg(ifunc)]
    let ok = match T::as_f32s(u) {
        // SAFETY: `u` is valid for `u.len()` reads.
        #[allow(unsafe_code)]
        Some(u) => unsafe { all_unit_f32(u.as_ptr(), u.len()) },
        None => all_unit(u),
    };
    #[cfg(not(ifunc))]
    let ok = all_unit(u);
    if ok { Ok(()) } else { Err(Error::Domain) }
}

#[cfg(ifunc)]
crate::math::arch::load_time_choice! {
    /// [`all_unit`] from C: `true` if every one of the `n` floats at `u`
    /// lies in `[0, 1]`; `u` valid for `n` reads.
    all_unit_f32: fn(u: *const f32, n: usize) -> bool {
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

#[cfg(test)]
mod check_tests {
    /// The bit-pattern test of `all_unit` agrees with the rule for every
    /// 4099th f32 pattern and every pattern near 0, 1, −0, +∞ and NaN, once
    /// and twice in a slice, and the f64 loop for each as a double.
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
            let rule = (0.0..=1.0).contains(&x);
            assert_eq!(super::all_unit(&[0.5, x, 0.25]), rule, "{b:#x}");
            // Twice: a fold that cancels bad values in pairs (a sign bit
            // or a flag toggled by `^`) would take these.
            assert_eq!(super::all_unit(&[x, 0.5, x]), rule, "{b:#x} twice");
            let wide = x as f64;
            assert_eq!(super::all_unit(&[wide, 0.5, wide]), rule, "{b:#x} in f64");
        }
    }
}

#[cfg(all(test, ifunc))]
mod tests {
    extern crate std;
    use super::all_unit_f32::BUILDS;
    use crate::math::arch::detected;

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

/// Where a density of `μ = cos θ` is read ([`Phase`](crate::Phase)'s
/// `pdf`, the C layer's `sk_phase_pdf`, the Python package's `pdf`):
/// `μ` itself in `[−1, 1]` (and NaN); `±1` for a `μ` within 8 ulp beyond
/// it, where the dot product of two unit vectors rounds; `None` further
/// out, where the density is 0, as the CDF is 0 or 1 there. (Each model's
/// own formula, read outside `[−1, 1]`, gave NaN on one side and a value
/// on the other.)
#[inline(always)]
pub fn support<T: Real>(mu: T) -> Option<T> {
    if mu.abs() <= T::ONE || mu.is_nan() {
        Some(mu)
    } else if mu.abs() <= T::ONE + T::from_f64(8.0) * T::EPSILON {
        Some(T::ONE.copysign(mu))
    } else {
        None
    }
}
