//! Mixtures of phase functions and tables.

use super::phase::{PhaseStore, load};
use super::slot::{self, Slot};
use super::table::{TableStore, load_table};
use super::verbs;
use super::{
    CVec, map_arrays, sk_phase, sk_phase_f64, sk_status, sk_table, sk_table_f64, sk_vec3,
    sk_vec3_f64, write_result,
};
use crate::math::real::Real;
use crate::mixture::{MAX_PARTS, Mixture, Part};
use crate::phase::{PhaseFunction, check_uniforms};

/// One component for sk_mixture_new: exactly one of phase and table
/// non-NULL, and its weight (finite, >= 0; the weights are normalised).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mixture_part {
    /// A phase function, or NULL.
    pub phase: *const sk_phase,
    /// A table, or NULL.
    pub table: *const sk_table,
    /// The component's weight: its share of the scattering coefficient.
    pub weight: f32,
}

/// One component for sk_mixture_new_f64; see `sk_mixture_part`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mixture_part_f64 {
    /// A phase function, or NULL.
    pub phase: *const sk_phase_f64,
    /// A table, or NULL.
    pub table: *const sk_table_f64,
    /// The component's weight.
    pub weight: f64,
}

/// A mixture of up to 8 phase functions and tables (sum of w_i p_i), as
/// sk_mixture_new built it: the components, their weights and what the
/// exact inverse needs, checked and prepared once, so that every call
/// loads it in constant time. A plain value: copy it freely; a table
/// component's data stays borrowed and must outlive it. Its contents are
/// private (a zeroed or never-built mixture gives NaN or SK_ERR_DOMAIN).
/// 4 KiB; the value it holds takes 2.4 KiB (f32) or 2.6 KiB (double), and
/// the rest is room for later releases.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mixture {
    /// Private storage; do not read or write.
    pub opaque: [u64; 512],
}

/// A mixture (double); see `sk_mixture`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mixture_f64 {
    /// Private storage; do not read or write.
    pub opaque: [u64; 512],
}

const _: () = assert!(MAX_PARTS == 8);

/// A C mixture type with its part, phase and table types.
pub(super) trait MixStore: Slot {
    type T: Real;
    /// The stored value is the mixture (both ways).
    fn mix(v: &Self::Value) -> &Mixture<'static, Self::T>;
    fn wrap(m: Mixture<'static, Self::T>) -> Self::Value;
    type P: PhaseStore<T = Self::T>;
    type Tb: TableStore<T = Self::T>;
    type Part: Copy;
    type V: CVec<T = Self::T>;
    fn part(p: &Self::Part) -> (*const Self::P, *const Self::Tb, Self::T);
}

macro_rules! impl_mix_store {
    ($m:ident, $part:ident, $p:ident, $tb:ident, $t:ty, $v:ty, $tag:expr, $words:expr) => {
        impl Slot for $m {
            type Value = Mixture<'static, $t>;
            const TAG: u32 = $tag;
            const ZEROED: Self = $m {
                opaque: [0; $words],
            };
        }
        impl MixStore for $m {
            type T = $t;
            type P = $p;
            type Tb = $tb;
            type Part = $part;
            type V = $v;
            fn mix<'b>(v: &'b Mixture<'static, $t>) -> &'b Mixture<'static, $t> {
                v
            }
            fn wrap(m: Mixture<'static, $t>) -> Mixture<'static, $t> {
                m
            }
            fn part(p: &$part) -> (*const $p, *const $tb, $t) {
                (p.phase, p.table, p.weight)
            }
        }
    };
}
impl_mix_store!(
    sk_mixture,
    sk_mixture_part,
    sk_phase,
    sk_table,
    f32,
    sk_vec3,
    0x534b_4d78,
    512
);
impl_mix_store!(
    sk_mixture_f64,
    sk_mixture_part_f64,
    sk_phase_f64,
    sk_table_f64,
    f64,
    sk_vec3_f64,
    0x534b_4d79,
    512
);

/// The mixture behind `m`, in constant time: `SK_ERR_NULL` for NULL,
/// `SK_ERR_DOMAIN` for one sk_mixture_new did not build.
pub(super) unsafe fn mixture_at<'a, S: MixStore>(
    m: *const S,
) -> Result<&'a Mixture<'static, S::T>, sk_status> {
    if m.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { slot::load(m) }
        .map(S::mix)
        .ok_or(sk_status::SK_ERR_DOMAIN)
}

unsafe fn new_mixture<S: MixStore>(parts: *const S::Part, n: usize, out: *mut S) -> sk_status {
    if parts.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    if n == 0 || n > MAX_PARTS {
        return sk_status::SK_ERR_SIZE;
    }
    // SAFETY: parts points to n readable parts (the caller's contract).
    let given = unsafe { core::slice::from_raw_parts(parts, n) };
    let filler = (Part::Phase(crate::phase::Phase::isotropic()), S::T::ZERO);
    let mut held = [filler; MAX_PARTS];
    for (slot, part) in held.iter_mut().zip(given) {
        let (p, t, w) = S::part(part);
        match unsafe { part_at(p, t) } {
            Ok(x) => *slot = (x, w),
            Err(e) => return e,
        }
    }
    // The weights are checked here; the f64 copies of the models and the
    // running sums the lobe choice reads are made once, here.
    let built = Mixture::new(held.get(..n).unwrap_or(&[]));
    unsafe { write_result(out, built.map(|m| slot::store::<S>(S::wrap(m)))) }
}

/// The component behind a (phase, table) pair of pointers, exactly one
/// non-NULL: `SK_ERR_NULL` for neither, `SK_ERR_DOMAIN` for both or an
/// unconstructed phase, `SK_ERR_SIZE` for a malformed table.
pub(super) unsafe fn part_at<'a, P: PhaseStore, Tb: TableStore<T = P::T>>(
    p: *const P,
    t: *const Tb,
) -> Result<Part<'a, P::T>, sk_status> {
    match (p.is_null(), t.is_null()) {
        (true, true) => Err(sk_status::SK_ERR_NULL),
        (false, false) => Err(sk_status::SK_ERR_DOMAIN),
        (false, true) => unsafe { load(p) }
            .map(|p| Part::Phase(*p))
            .ok_or(sk_status::SK_ERR_DOMAIN),
        (true, false) => unsafe { load_table(t) }
            .map(Part::Table)
            .ok_or(sk_status::SK_ERR_SIZE),
    }
}

/// `f` of the mixture, NaN when it does not load.
unsafe fn with<S: MixStore>(m: *const S, f: impl Fn(&Mixture<'_, S::T>) -> S::T) -> S::T {
    unsafe { mixture_at(m) }.map_or(S::T::NAN, f)
}

unsafe fn sample_dir<S: MixStore>(
    m: *const S,
    w_in: S::V,
    (u1, u2): (S::T, S::T),
    pdf_out: *mut S::T,
) -> S::V {
    let (d, pdf) = match unsafe { mixture_at(m) } {
        Ok(m) => m.sample_dir_by_lobe(w_in.to_vec(), u1, u2),
        Err(_) => {
            let nan = S::T::NAN;
            (crate::math::geometry::Vec3::new(nan, nan, nan), nan)
        }
    };
    if !pdf_out.is_null() {
        // SAFETY: a non-NULL out-pointer is writable (module contract).
        unsafe { pdf_out.write(pdf) };
    }
    S::V::from_vec(d)
}

/// The batch of `u` through the exact inverse (`exact = true`) or the lobe
/// choice.
unsafe fn sample_cos_n<S: MixStore>(
    m: *const S,
    u: *const S::T,
    cos_out: *mut S::T,
    n: usize,
    exact: bool,
) -> sk_status {
    let mix = match unsafe { mixture_at(m) } {
        Ok(mix) => mix,
        Err(e) => return e,
    };
    unsafe {
        map_arrays(u, cos_out, n, check_uniforms, |u, out| {
            for (o, &v) in out.iter_mut().zip(u) {
                *o = if exact {
                    mix.sample_cos(v)
                } else {
                    mix.sample_cos_by_lobe(v)
                };
            }
            Ok(())
        })
    }
}

/// Builds the mixture of `parts[0]` to `parts[n - 1]` into *out (weights normalised;
/// phases copied, tables borrowed). SK_ERR_NULL for NULL parts or out, or
/// a part with neither phase nor table; SK_ERR_SIZE for n = 0, n > 8 or a
/// malformed table; SK_ERR_DOMAIN for a part with both, an unconstructed
/// phase, or a weight negative or not finite, or all weights 0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_new(
    parts: *const sk_mixture_part,
    n: usize,
    out: *mut sk_mixture,
) -> sk_status {
    unsafe { new_mixture(parts, n, out) }
}

/// Double twin of `sk_mixture_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_new_f64(
    parts: *const sk_mixture_part_f64,
    n: usize,
    out: *mut sk_mixture_f64,
) -> sk_status {
    unsafe { new_mixture(parts, n, out) }
}

/// The mixture's density per steradian at cos_theta: sum of w_i p_i. NaN
/// for NULL or a mixture sk_mixture_new did not build.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_pdf(m: *const sk_mixture, cos_theta: f32) -> f32 {
    unsafe { with(m, |m| m.pdf(cos_theta)) }
}

/// Double twin of `sk_mixture_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_pdf_f64(m: *const sk_mixture_f64, cos_theta: f64) -> f64 {
    unsafe { with(m, |m| m.pdf(cos_theta)) }
}

/// The mixture's CDF at cos_theta, sum of w_i F_i (NaN as sk_mixture_pdf).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_cdf(m: *const sk_mixture, cos_theta: f32) -> f32 {
    unsafe { with(m, |m| m.cdf(cos_theta)) }
}

/// Double twin of `sk_mixture_cdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_cdf_f64(m: *const sk_mixture_f64, cos_theta: f64) -> f64 {
    unsafe { with(m, |m| m.cdf(cos_theta)) }
}

/// The mixture's mean cosine, sum of w_i g_i (NaN as sk_mixture_pdf).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_mean_cosine(m: *const sk_mixture) -> f32 {
    unsafe { with(m, |m| m.mean_cosine()) }
}

/// Double twin of `sk_mixture_mean_cosine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_mean_cosine_f64(m: *const sk_mixture_f64) -> f64 {
    unsafe { with(m, |m| m.mean_cosine()) }
}

/// cos theta by lobe choice: u (clamped to [0, 1]) picks the component by
/// weight and, rescaled into its share, samples it. Exact in distribution,
/// fast, not monotone in u. NaN for NaN u, NULL or a bad mixture.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_by_lobe(m: *const sk_mixture, u: f32) -> f32 {
    unsafe { with(m, |m| m.sample_cos_by_lobe(u)) }
}

/// Double twin of `sk_mixture_sample_cos_by_lobe`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_by_lobe_f64(
    m: *const sk_mixture_f64,
    u: f64,
) -> f64 {
    unsafe { with(m, |m| m.sample_cos_by_lobe(u)) }
}

/// cos theta by the exact inverse of the mixture's CDF: monotone in u (for
/// stratified or quasi-random uniforms), a safeguarded Newton solve in
/// double on the components' CDFs (about 1 us). NaN as
/// sk_mixture_sample_cos_by_lobe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos(m: *const sk_mixture, u: f32) -> f32 {
    unsafe { with(m, |m| m.sample_cos(u)) }
}

/// Double twin of `sk_mixture_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_f64(m: *const sk_mixture_f64, u: f64) -> f64 {
    unsafe { with(m, |m| m.sample_cos(u)) }
}

/// `cos_out[i] = sk_mixture_sample_cos(m, u[i])` for `i < n`. `u`
/// and `cos_out` may be the same array; other overlaps give
/// SK_ERR_OVERLAP. SK_ERR_DOMAIN if any `u[i]` is NaN or outside `[0, 1]`,
/// or the mixture is malformed; SK_ERR_NULL for NULL m, or NULL arrays
/// with n > 0; SK_ERR_SIZE if n floats cannot exist. On error nothing is
/// written; n = 0 is SK_OK.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_n(
    m: *const sk_mixture,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(m, u, cos_out, n, true) }
}

/// Double twin of `sk_mixture_sample_cos_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_n_f64(
    m: *const sk_mixture_f64,
    u: *const f64,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(m, u, cos_out, n, true) }
}

/// `cos_out[i] = sk_mixture_sample_cos_by_lobe(m, u[i])` for `i < n`;
/// statuses and overlaps as sk_mixture_sample_cos_n.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_by_lobe_n(
    m: *const sk_mixture,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(m, u, cos_out, n, false) }
}

/// Double twin of `sk_mixture_sample_cos_by_lobe_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_by_lobe_n_f64(
    m: *const sk_mixture_f64,
    u: *const f64,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(m, u, cos_out, n, false) }
}

/// A scattered direction about the unit vector w_in: cos theta by lobe
/// choice from u1, azimuth 2 pi u2; writes the mixture's density per
/// steradian there to pdf_out unless it is NULL. NaN (direction and pdf)
/// for NULL or a bad mixture.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_dir(
    m: *const sk_mixture,
    w_in: sk_vec3,
    u1: f32,
    u2: f32,
    pdf_out: *mut f32,
) -> sk_vec3 {
    unsafe { sample_dir(m, w_in, (u1, u2), pdf_out) }
}

/// Double twin of `sk_mixture_sample_dir`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_dir_f64(
    m: *const sk_mixture_f64,
    w_in: sk_vec3_f64,
    u1: f64,
    u2: f64,
    pdf_out: *mut f64,
) -> sk_vec3_f64 {
    unsafe { sample_dir(m, w_in, (u1, u2), pdf_out) }
}

#[allow(clippy::too_many_arguments)]
unsafe fn sample_dir_n<S: MixStore>(
    m: *const S,
    w: [*const S::T; 3],
    (u1, u2): (*const S::T, *const S::T),
    out: [*mut S::T; 3],
    pdf_out: *mut S::T,
    n: usize,
) -> sk_status {
    match unsafe { mixture_at(m) } {
        Ok(mix) => unsafe {
            verbs::dir_n((w, u1, u2), (out, pdf_out), n, |w_in, a, b| {
                mix.sample_dir_by_lobe(w_in, a, b)
            })
        },
        Err(e) => e,
    }
}

/// Directions for n rays, structure of arrays, each bit for bit
/// sk_mixture_sample_dir's (cos theta by lobe choice); arrays, overlaps and
/// statuses as sk_phase_sample_dir_n (SK_ERR_DOMAIN also for a mixture
/// sk_mixture_new did not build).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_mixture_sample_dir_n(
    m: *const sk_mixture,
    w_x: *const f32,
    w_y: *const f32,
    w_z: *const f32,
    u1: *const f32,
    u2: *const f32,
    out_x: *mut f32,
    out_y: *mut f32,
    out_z: *mut f32,
    pdf_out: *mut f32,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_n(m, w, (u1, u2), out, pdf_out, n) }
}

/// Double twin of `sk_mixture_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_mixture_sample_dir_n_f64(
    m: *const sk_mixture_f64,
    w_x: *const f64,
    w_y: *const f64,
    w_z: *const f64,
    u1: *const f64,
    u2: *const f64,
    out_x: *mut f64,
    out_y: *mut f64,
    out_z: *mut f64,
    pdf_out: *mut f64,
    n: usize,
) -> sk_status {
    let (w, out) = ([w_x, w_y, w_z], [out_x, out_y, out_z]);
    unsafe { sample_dir_n(m, w, (u1, u2), out, pdf_out, n) }
}
