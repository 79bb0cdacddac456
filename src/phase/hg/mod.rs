//! Henyey–Greenstein (Henyey & Greenstein, ApJ 93, 1941):
//! `p(μ) = (1/4π) (1 − g²) / (1 + g² − 2gμ)^{3/2}`, mean cosine `g`.
//!
//! The textbook inverse `μ = (1 + g² − s²)/(2g)`, `s = (1 − g²)/(1 − g + 2gu)`
//! divides by `g` and cancels as `g → 0` (f32: 10⁻³ error at `g = 10⁻⁴`) and is
//! 0/0 at `|g| → 1`. Factoring `1 ± μ` exactly gives two forms with only
//! positive factors and no division by `g`, with `d = 1 − g + 2gu`
//! (`= (1 + g) − 2g(1 − u)`, the form used for `g < 0`):
//!
//! * `1 + μ = 2u (1 + g)² (1 − g + gu) / d²`
//! * `1 − μ = 2(1 − u) (1 − g)² (1 + gu) / d²`
//!
//! Each is accurate to a few ULP in relative terms; we take `μ = −1 + (1 + μ)`
//! while that correction is below 1 (μ ≤ 0) and `μ = 1 − (1 − μ)` otherwise, so
//! the absolute error is a few ULP of 1 on the whole open interval `|g| < 1`,
//! with no threshold on `g` and no jump between the forms beyond that.
//!
//! **The f32 sampler in double precision.** Where double precision runs in
//! hardware at the speed of single (x86, x86-64, AArch64), the f32 sampler
//! widens `u` to f64 and evaluates the textbook inverse there, rearranged
//! for a short chain. With `g' = |g|`, `k = (1 − g')/(2g')` and
//! `t = d/(2g') = u' + k` (`u' = u` for `g > 0`, `u' = 1 − u` for `g < 0`,
//! the mirror `μ(g, u) = −μ(−g, 1 − u)`), the inverse is
//! `μ = ±(A − B/t²)` with `A = (1 + g'²)/(2g')` and
//! `B = (1 − g'²)²/(8g'³)`: one addition, one square, one division and one
//! subtraction per sample instead of two factored forms and a selection.
//! `u'` is exact in f64 and `t` a sum of two non-negative terms, so `t`
//! carries about one rounding; the cancellation in `A − B/t²` (`B/t²` is
//! up to `A + 1`) then costs a few `ε·A`, below `3·10⁻¹³` absolute for
//! `g' ≥ 2⁻¹⁰`, and the one rounding to f32 leaves `μ` within half an ULP
//! plus that of the exact value. Below `2⁻¹⁰` the factored forms run in
//! f64. `sin θ` comes from the factors,
//! `sin θ = 2 sqrt(u(1 − u)(1 − g' + g'u')(1 + g'u'))·s²/(1 − g'²)` with
//! `s = (1 − g'²)/d` (its square formed in f64, the root taken in f32),
//! which keeps its relative precision at both poles, and the density from
//! `d³` as in f64. The path is monotone in `u`: each
//! step (`u' + k`, the square of a positive number, a positive constant over
//! it, a constant minus that, the rounding to f32) is a monotone function
//! rounded correctly, and rounding preserves order (`tests/models/hg_and_depolarised.rs` checks
//! every float `u` for eight g by hand, a sixteenth of them in runs of 2²⁰
//! neighbours in `cargo test`). On targets without fast doubles
//! (Cortex-M and the like) the f32 sampler keeps to f32 and the factored
//! forms above.

mod batch;

use super::function::{PhaseFunction, dir_each};
use super::model::{Lobes, Model, exactly, open};
use crate::error::Error;
use crate::math::geometry::{Vec3, direction_about_turns};
use crate::math::real::{PackedF64, Real};

/// Whether the f32 sampler computes in f64 (module docs): on processors whose
/// double precision runs in hardware at the speed of single.
const WIDE: bool = crate::math::log::WIDE;

/// How many f64 constants the model keeps for that path: none where the f32
/// sampler does not take it, so firmware builds neither store nor clear them.
const WIDE_LEN: usize = if WIDE { 5 } else { 0 };

/// Below this `|g|` the f64 path of the f32 sampler takes the factored forms:
/// the rearranged textbook inverse's error, a few `ε (1 + g²)/(2|g|)`, would
/// pass `3·10⁻¹³`.
const WIDE_G_MIN: f64 = 1.0 / 1024.0;

/// Henyey–Greenstein with asymmetry `g ∈ [−1, 1]`; `g > 0` scatters forward.
/// Holds `g` and the constants every sample needs, computed once.
///
/// `|g| = 1` is the Dirac limit, which transport codes give a background
/// medium: every sample is `cos θ = g` (`sin θ = 0`, the direction `±w_in`)
/// for every `u` but NaN; the density is `+∞` at `cos θ = g` and 0
/// elsewhere (HG's density as `|g| → 1`, point by point), a sampled
/// direction's density is `+∞`, and the CDF is the step `μ ≥ g`. The
/// portable header's `skp_hg_new(±1)` gives the same answers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein<T> {
    g: T,
    /// `1 − g` and `1 + g`.
    omg: T,
    opg: T,
    /// `1/(4π (1 − g²)²)`: the density of a sample is this times `d³`.
    pdf_k: T,
    /// The f32 sampler's f64 path (module docs): `k`, `±A`, `±B` (the sign
    /// of g), `4g'/(1 − g'²)` for `sin θ` and `8g'³/(4π (1 − g'²)²)` for the
    /// density, in f64; all zero for `|g| < 2⁻¹⁰` (the factored forms).
    wide: PackedF64<WIDE_LEN>,
}

impl<T: Real> HenyeyGreenstein<T> {
    /// Fails with [`Error::Domain`] unless `−1 ≤ g ≤ 1` (NaN and ±∞ fail);
    /// `|g| = 1` is the Dirac limit (type docs).
    pub fn new(g: T) -> Result<Self, Error> {
        if g >= -T::ONE && g <= T::ONE {
            Ok(Self::from_g(g))
        } else {
            Err(Error::Domain)
        }
    }
    /// The constants for a `g` already known to lie in `[−1, 1]` (at
    /// `|g| = 1` the density constant is `+∞` and the f64 path's `B` is 0,
    /// so the f32 sampler takes the factored forms, which `factors` makes
    /// exact there).
    pub(crate) fn from_g(g: T) -> Self {
        let (omg, opg) = (T::ONE - g, T::ONE + g);
        let omg2 = omg * opg;
        HenyeyGreenstein {
            g,
            omg,
            opg,
            pdf_k: T::INV_4PI / (omg2 * omg2),
            // Only the f32 model on a target with fast doubles needs them
            // (elsewhere no double-precision code is linked).
            wide: if wide_path::<T>() {
                wide_constants(g.to_f64())
            } else {
                PackedF64::ZERO
            },
        }
    }
    /// The asymmetry parameter `g`.
    pub fn g(&self) -> T {
        self.g
    }
    /// `F⁻¹(u)` for asymmetry `g ∈ (−1, 1)` by the factored forms in `T`
    /// (module docs) on every target, `u` clamped to `[0, 1]`, without
    /// building the model: one division and no constant beyond `1 ± g`, for
    /// lobe samplers that meet a different `g` at every sample (the model's
    /// density and f64-path constants would cost four divisions more).
    #[inline(always)]
    pub(crate) fn sample_cos_factored(g: T, u: T) -> T {
        // Only the fields `factors` reads are meaningful in this value, and
        // it does not leave this function.
        let lobe = HenyeyGreenstein {
            g,
            omg: T::ONE - g,
            opg: T::ONE + g,
            pdf_k: T::NAN,
            wide: PackedF64::ZERO,
        };
        let (opm, omm, _) = lobe.factors(u.clamp01());
        Self::cos_from(opm, omm)
    }
    /// `(1 + μ, 1 − μ)` for `μ = F⁻¹(u)` (module docs).
    #[inline(always)]
    pub(super) fn one_plus_minus_mu(&self, u: T) -> (T, T) {
        let (opm, omm, _) = self.factors(u.clamp01());
        (opm, omm)
    }

    /// Whether `|g| = 1`, the Dirac limit (type docs).
    #[inline(always)]
    fn is_dirac(&self) -> bool {
        self.omg == T::ZERO || self.opg == T::ZERO
    }

    /// `(1 + μ, 1 − μ, d)` for `u ∈ [0, 1]` (not clamped here), with
    /// `d = 1 − g + 2gu` (module docs). At `|g| = 1` the forms are `0/0`
    /// where `d = 0`, so the Dirac limit's exact factors are returned
    /// instead (`1 ± μ = 1 ± g`, and `d = 1`, which with the density
    /// constant `+∞` gives density `+∞`), NaN for a NaN `u`.
    #[inline(always)]
    fn factors(&self, u: T) -> (T, T, T) {
        if self.is_dirac() {
            let z = if u.is_nan() { u } else { T::ZERO };
            return (self.opg + z, self.omg + z, T::ONE + z);
        }
        let g = self.g;
        let v = T::ONE - u;
        // d = 1 − g + 2gu, 1 − g + gu and 1 + gu, each written as a sum of
        // non-negative terms for the sign of g: for g < 0, `1 − g + 2gu`
        // cancels as u → 1 and g → −1, but `(1 + g) − 2g(1 − u)` does not.
        let (d, a, b) = if g >= T::ZERO {
            let gu = g * u;
            (self.omg + (gu + gu), self.omg + gu, T::ONE + gu)
        } else {
            let gv = g * v;
            (self.opg - (gv + gv), T::ONE - gv, self.opg - gv)
        };
        let inv_d2 = T::ONE / (d * d);
        // The factors in this order (not 2(1 ± g)² taken once): it is the
        // order whose rounding the accuracy figures were measured with.
        let (omg, opg) = (self.omg, self.opg);
        (
            T::TWO * u * opg * opg * a * inv_d2,
            T::TWO * v * omg * omg * b * inv_d2,
            d,
        )
    }

    /// The f64 path for `u ∈ [0, 1]` (module docs): `(u', t, q)` with
    /// `t = u' + k` and `q = ±B/t²`, so that `μ = ±A − q`; `None` for
    /// `|g| < 2⁻¹⁰`.
    #[inline(always)]
    fn wide_t(&self, u: f64) -> Option<(f64, f64, f64)> {
        let (k, b) = (self.wide.get(0), self.wide.get(2));
        if b == 0.0 {
            return None;
        }
        // u' is exact (1 − u of an f32 u), k ≥ 0: t is rounded once.
        let u1 = if self.g > T::ZERO { u } else { 1.0 - u };
        let (t, q) = batch::wide_tq(k, b, u1);
        Some((u1, t, q))
    }

    /// The f64 path's constants for [`batch`], if the f32 sampler
    /// takes that path (`None` for f64, without fast doubles, and for
    /// `|g| < 2⁻¹⁰`).
    #[inline(always)]
    fn wide_batch(&self) -> Option<batch::Wide> {
        let b = self.wide.get(2);
        (wide_path::<T>() && b != 0.0).then(|| batch::Wide {
            kab: [self.wide.get(0), self.wide.get(1), b],
            mirror: self.g <= T::ZERO,
        })
    }

    /// The constants of the f32 sampler's f64 path, `[k, A, B]`, and whether
    /// `u` is mirrored, where the f32 sampler takes that path (`None`
    /// elsewhere): `cos θ = A − B/(u' + k)²` evaluated in f64 and rounded
    /// once to f32, with `u' = 1 − u` if mirrored and `u` otherwise. With
    /// them a loop of one's own (a GPU kernel, the header-only sampler of
    /// `include/scatterkit_inline.h`) returns the sampler's bits.
    pub fn f64_path_constants(&self) -> Option<([f64; 3], bool)> {
        self.wide_batch().map(|w| (w.kab, w.mirror))
    }

    /// `cos θ` on the f64 path for `u ∈ [0, 1]`.
    #[inline(always)]
    fn wide_cos(&self, u: f64) -> f64 {
        match self.wide_t(u) {
            Some((_, _, q)) => self.wide.get(1) - q,
            None => HenyeyGreenstein::<f64>::from_g(self.g.to_f64()).sample_cos_in_range(u),
        }
    }

    /// `(cos θ, sin² θ, density)` on the f64 path for `u ∈ [0, 1]`.
    #[inline(always)]
    fn wide_cos_sin2_d(&self, u: f64) -> (f64, f64, f64) {
        let Some((u1, t, q)) = self.wide_t(u) else {
            return HenyeyGreenstein::<f64>::from_g(self.g.to_f64()).factored_cos_sin2_d(u);
        };
        // sin θ of the mirrored problem (g', u') is the same.
        let g = self.g.to_f64().abs();
        let gu = g * u1;
        let ab = ((1.0 - g) + gu) * (1.0 + gu);
        // sin θ = E q sqrt(u(1 − u) a b) with E q = 2 s²/(1 − g'²), E = 4g'/(1 − g'²).
        let eq = self.wide.get(3) * q;
        let sin2 = (eq * eq) * ((u * (1.0 - u)) * ab);
        (self.wide.get(1) - q, sin2, self.wide.get(4) * (t * t * t))
    }

    /// `(cos θ, sin² θ, density)` by the factored forms in `T`, for
    /// `u ∈ [0, 1]`.
    #[inline(always)]
    fn factored_cos_sin2_d(&self, u: T) -> (T, T, T) {
        let (opm, omm, d) = self.factors(u);
        (Self::cos_from(opm, omm), opm * omm, self.pdf_k * d * d * d)
    }

    /// `(cos θ, sin θ, density)` for `u ∈ [0, 1]`, the density from the
    /// sampler's own `d` (see `sample_dir`).
    #[inline(always)]
    fn cos_sin_d(&self, u: T) -> (T, T, T) {
        let (mu, sin2, pdf) = if wide_path::<T>() {
            // sin² θ rounded to f32 and its root taken there: within an ULP
            // of the exact sin θ, at a quarter of the cost of f64 roots in a
            // vectorised batch.
            let (mu, sin2, pdf) = self.wide_cos_sin2_d(u.to_f64());
            (T::from_f64(mu), T::from_f64(sin2), T::from_f64(pdf))
        } else {
            self.factored_cos_sin2_d(u)
        };
        (mu, sin2.max_of(T::ZERO).sqrt(), pdf)
    }

    /// This sampler in f32 when `T` is f32 (its fields as they are), for
    /// the f32 batch's load-time-chosen builds; `None` for f64.
    #[cfg(ifunc)]
    fn as_f32(&self) -> Option<HenyeyGreenstein<f32>> {
        T::as_f32s(&[]).map(|_| HenyeyGreenstein {
            g: self.g.to_f64() as f32,
            omg: self.omg.to_f64() as f32,
            opg: self.opg.to_f64() as f32,
            pdf_k: self.pdf_k.to_f64() as f32,
            wide: self.wide,
        })
    }

    /// [`PhaseFunction::sample_dir`]'s body: the direction and its density.
    #[inline(always)]
    fn dir_pdf(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        let (mu, sin_theta, pdf) = self.cos_sin_d(u1.clamp01());
        let dir = direction_about_turns(w_in, mu, sin_theta, u2.clamp01());
        (dir, pdf)
    }

    /// `cos θ` from `(1 + μ, 1 − μ)`: `−1 + (1 + μ)` while that correction
    /// is below 1, else `1 − (1 − μ)`, so the absolute error stays a few ULP
    /// of 1 at both poles.
    #[inline(always)]
    fn cos_from(opm: T, omm: T) -> T {
        if opm < T::ONE {
            opm - T::ONE
        } else {
            T::ONE - omm
        }
    }

    /// `1 + g² − 2gμ`, written as a sum of non-negative terms so it does not
    /// cancel at `μ → sign(g)`, `|g| → 1`.
    #[inline(always)]
    fn denom(&self, mu: T) -> T {
        let g = self.g;
        if g >= T::ZERO {
            (T::ONE - g) * (T::ONE - g) + T::TWO * g * (T::ONE - mu)
        } else {
            (T::ONE + g) * (T::ONE + g) - T::TWO * g * (T::ONE + mu)
        }
    }
}

/// The Dirac limit's density from `1 + g² − 2gμ = q` (`2(1 ∓ μ)` there):
/// `+∞` at the peak (`q = 0`), 0 elsewhere, NaN for `q < 0` (`|μ| > 1`) or
/// NaN.
#[inline(always)]
fn dirac_density<T: Real>(q: T) -> T {
    if q > T::ZERO {
        T::ZERO
    } else if q == T::ZERO {
        T::INFINITY
    } else {
        T::NAN
    }
}

/// True for f32 on a target with fast doubles: where HG-based f32 samplers
/// compute in f64 (module docs).
#[inline(always)]
pub(super) fn wide_path<T: Real>() -> bool {
    WIDE && core::mem::size_of::<T>() == 4
}

/// The f64 path's constants (module docs) for `g` in f64.
fn wide_constants(g: f64) -> PackedF64<WIDE_LEN> {
    let a = g.abs();
    if a < WIDE_G_MIN {
        return PackedF64::ZERO;
    }
    let (c, h) = ((1.0 - a) * (1.0 + a), 0.5 / a);
    let sign = if g > 0.0 { 1.0 } else { -1.0 };
    PackedF64::first_of([
        (1.0 - a) * h,
        sign * (1.0 + a * a) * h,
        sign * (c * c) * (h * h * h),
        4.0 * a / c,
        8.0 * (a * a * a) * core::f64::consts::FRAC_1_PI / (4.0 * c * c),
    ])
}

impl<T: Real> PhaseFunction<T> for HenyeyGreenstein<T> {
    /// At `|g| = 1`: `+∞` at `cos θ = g`, 0 elsewhere in `[−1, 1]`.
    #[inline]
    fn pdf(&self, cos_theta: T) -> T {
        let g = self.g;
        let d = self.denom(cos_theta);
        if self.is_dirac() {
            return dirac_density(d);
        }
        T::INV_4PI * (T::ONE - g) * (T::ONE + g) / (d * d.sqrt())
    }
    /// `F(μ) = (1 − g)(1 + μ) / (s (1 + g + s))`, `s = sqrt(1 + g² − 2gμ)`:
    /// the textbook `(1 − g²)/(2g) (1/s − 1/(1 + g))` with the `1/g` cancelled
    /// analytically. At `|g| = 1` the step: 1 for `cos θ ≥ g`, else 0.
    #[inline]
    fn cdf(&self, cos_theta: T) -> T {
        let g = self.g;
        let mu = cos_theta.clamp_unit();
        if self.is_dirac() && !mu.is_nan() {
            return if mu >= g { T::ONE } else { T::ZERO };
        }
        let s = self.denom(mu).sqrt();
        let whole = s * (T::ONE + g + s);
        let f = (T::ONE - g) * (T::ONE + mu) / whole;
        if f > T::HALF {
            // Above ½, one minus the upper tail: `whole − (1 − g)(1 + μ)`
            // is `(1 + g)(s + g − μ)` (as `s² = (g − μ)² + 1 − μ²`), and
            // for `μ > g` the factor `s + g − μ` is `(1 − μ²)/(s + μ − g)`,
            // free of its cancellation. The tail is accurate to a few ulps
            // of itself, so `1 − tail` rises with μ; `f` there stepped back
            // by up to five ulps of 1 as g → −1 (one minus a product of
            // roundings). `s + (μ − g)` adds two non-negative terms: as
            // `(s + μ) − g` it cancelled where s is small (μ and g near 1:
            // the tail 2.8·10⁻¹¹ off at g = 0.999999, μ = 1 − 2⁻⁵³).
            let gap = if mu > g {
                (T::ONE - mu) * (T::ONE + mu) / (s + (mu - g))
            } else {
                s + (g - mu)
            };
            (T::ONE - (T::ONE + g) * gap / whole).clamp01()
        } else {
            f.clamp01()
        }
    }
    #[inline]
    fn sample_cos(&self, u: T) -> T {
        self.sample_cos_in_range(u.clamp01())
    }
    /// On the f64 path, one loop over the slice that the compiler
    /// vectorises (the `batch` module), with the same bits as
    /// [`sample_cos_in_range`](Self::sample_cos_in_range) per element.
    #[inline]
    fn sample_cos_each_in_range(&self, u: &[T], cos_out: &mut [T]) {
        if let Some(w) = self.wide_batch() {
            if let Some((u, out)) = T::as_f32_io(u, cos_out) {
                return batch::cos_n(w, u, out);
            }
        }
        for (c, &ui) in cos_out.iter_mut().zip(u) {
            *c = self.sample_cos_in_range(ui);
        }
    }
    #[inline]
    fn sample_cos_in_range(&self, u: T) -> T {
        if wide_path::<T>() {
            return T::from_f64(self.wide_cos(u.to_f64()));
        }
        let (opm, omm, _) = self.factors(u);
        Self::cos_from(opm, omm)
    }
    /// `sin θ = sqrt((1 + μ)(1 − μ))` from the factors `1 ± μ`, each accurate
    /// relative to itself (in f64 on the f64 path: module docs).
    #[inline]
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        let (mu, sin, _) = self.cos_sin_d(u.clamp01());
        (mu, sin)
    }
    /// The density comes from the sampler's own `d`: with
    /// `1 + g² − 2gμ = ((1 − g²)/d)²`, `p = d³ / (4π (1 − g²)²)`, with no
    /// square root or division.
    // Out of line, as the compiler had left it: inlined into the C layer's
    // dispatch (once its body became `dir_pdf`), `sk_phase_sample_dir`
    // took 20–22 ns instead of 14–15 from a program built with
    // `-march=native` (14–15 from `-O2` either way; Intel Xeon, family 6
    // model 167): an f32 → f64 conversion merges into its destination
    // register, and inlined, the first one was no longer preceded by a
    // zeroing, so it waited on whatever the caller had last left there.
    #[inline(never)]
    fn sample_dir(&self, w_in: Vec3<T>, u1: T, u2: T) -> (Vec3<T>, T) {
        self.dir_pdf(w_in, u1, u2)
    }
    /// The loop with [`sample_dir`](PhaseFunction::sample_dir)'s body
    /// inlined into it, so that it vectorises: the default loop called
    /// `sample_dir` out of line at each element in the C library's build
    /// (15.5 ns per direction from C, the scalar call's time; 6.3–7.2 ns
    /// inlined, Intel Xeon, family 6 model 167). In f32 with the C layer on
    /// x86-64 Linux, the widest build the processor runs, chosen when the
    /// program is loaded (4.2–4.3 ns there).
    fn sample_dir_each(
        &self,
        w_in: [&[T]; 3],
        u1: &[T],
        u2: &[T],
        out: [&mut [T]; 3],
        pdf_out: &mut [T],
    ) {
        let [ox, oy, oz] = out;
        #[cfg(ifunc)]
        if let Some(hg) = self.as_f32() {
            let f = T::as_f32s;
            let ins = (f(w_in[0]), f(w_in[1]), f(w_in[2]), f(u1), f(u2));
            let outs = (
                T::as_f32s_mut(ox),
                T::as_f32s_mut(oy),
                T::as_f32s_mut(oz),
                T::as_f32s_mut(pdf_out),
            );
            if let (
                (Some(a), Some(b), Some(c), Some(d), Some(e)),
                (Some(x), Some(y), Some(z), Some(p)),
            ) = (ins, outs)
            {
                return batch::dir_n(&hg, [a, b, c, d, e], [x, y, z, p]);
            }
        }
        dir_each(w_in, [u1, u2], [ox, oy, oz], pdf_out, |w, a, b| {
            self.dir_pdf(w, a, b)
        });
    }
    #[inline(always)]
    fn mean_cosine(&self) -> T {
        self.g
    }
}

impl<T: Real> Model<T> for HenyeyGreenstein<T> {
    type In<U: Real> = HenyeyGreenstein<U>;
    const PARAMS: usize = 1;
    fn params(&self) -> [T; 4] {
        [self.g, T::ZERO, T::ZERO, T::ZERO]
    }
    fn from_params(p: &[T]) -> Result<Self, Error> {
        let [g] = exactly(p)?;
        Self::new(g)
    }
    fn cast<U: Real>(&self) -> HenyeyGreenstein<U> {
        HenyeyGreenstein::from_g(open(self.g))
    }
    /// Draine with `α = 0`.
    fn lobes(&self) -> Option<Lobes> {
        Some(((self.g.to_f64(), 0.0), (0.0, 0.0), 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The f32 factored forms, which targets without fast doubles take: on
    /// x86-64 the samplers do not reach them, so they are checked here
    /// against the f64 sampler (itself within 6·10⁻¹⁶ of a double-double
    /// reference, `tests/models/hg_and_depolarised.rs`). The bound is the 2.83·10⁻⁷ these forms
    /// were measured at over the same g before the f64 path existed.
    #[test]
    fn f32_factored_forms_stay_accurate() {
        let gs = [
            0.0, 1e-8, -1e-4, 0.01, 0.5, -0.5, 0.9, -0.9, 0.999, -0.999999,
        ];
        for g in gs {
            let h = HenyeyGreenstein::<f32>::from_g(g as f32);
            let r = HenyeyGreenstein::<f64>::from_g(g as f32 as f64);
            let mut worst = 0.0f64;
            for k in 0..=20_000 {
                let u = k as f32 / 20_000.0;
                let (opm, omm, _) = h.factors(u);
                let mu = HenyeyGreenstein::<f32>::cos_from(opm, omm) as f64;
                let e = (mu - r.sample_cos(u as f64)).abs();
                assert!((-1.0..=1.0).contains(&mu), "g = {g}, u = {u}: {mu}");
                worst = worst.max(e);
            }
            assert!(worst <= 3e-7, "g = {g}: {worst:e}");
        }
    }

    /// The f64 path agrees with the f64 sampler to the rounding to f32, on
    /// both sides of the 2⁻¹⁰ threshold and for both signs of g.
    #[test]
    fn f64_path_rounds_the_f64_sampler() {
        if !wide_path::<f32>() {
            return;
        }
        for g in [
            9e-4f32,
            -9e-4,
            1.0 / 1024.0,
            -1.0 / 1024.0,
            0.3,
            -0.7,
            0.999_999,
        ] {
            let h = HenyeyGreenstein::<f32>::from_g(g);
            let r = HenyeyGreenstein::<f64>::from_g(g as f64);
            for k in 0..=20_000 {
                let u = k as f32 / 20_000.0;
                let exact = r.sample_cos(u as f64);
                let got = h.sample_cos(u) as f64;
                // Half an ULP of f32 at |μ| ≤ 1, and the f64 path's 3·10⁻¹³.
                let half_ulp = exact.abs() * f32::EPSILON as f64 / 2.0;
                assert!(
                    (got - exact).abs() <= half_ulp + 3e-13,
                    "g = {g}, u = {u}: {got} vs {exact}"
                );
                // sin θ within 2 ULP of f32 relative to itself (its square
                // rounded, then a correctly rounded root).
                let (_, sin) = h.sample_cos_sin(u);
                let sin_exact = r.sample_cos_sin(u as f64).1;
                let tol = 2.0 * f32::EPSILON as f64 * sin_exact + f64::MIN_POSITIVE;
                assert!(
                    (sin as f64 - sin_exact).abs() <= tol,
                    "g = {g}, u = {u}: sin {sin} vs {sin_exact}"
                );
            }
        }
    }
}
