//! Mixtures of phase functions and tables.

use super::phase::{PhaseStore, load};
use super::table::{TableStore, load_table};
use super::{
    CVec, map_arrays, sk_phase, sk_phase_f64, sk_status, sk_table, sk_table_f64, sk_vec3,
    sk_vec3_f64,
};
use crate::math::real::Real;
use crate::mixture::{MAX_PARTS, Mixture, Part, lobe};
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

/// A mixture of up to 8 phase functions and tables (sum of w_i p_i). A plain
/// value holding copies of the components: build it with sk_mixture_new,
/// then copy it freely; a table component's data stays borrowed and must
/// outlive it. Its fields are private.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mixture {
    /// Private: the number of components.
    pub n: u32,
    /// Private: 1 where component i is a table.
    pub is_table: [u32; 8],
    /// Private: the weights as given.
    pub weight: [f32; 8],
    /// Private: the running sums of the normalised weights.
    pub end: [f32; 8],
    /// Private: the phase components.
    pub phase: [sk_phase; 8],
    /// Private: the table components.
    pub table: [sk_table; 8],
}

/// A mixture (double); see `sk_mixture`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_mixture_f64 {
    /// Private: the number of components.
    pub n: u32,
    /// Private: 1 where component i is a table.
    pub is_table: [u32; 8],
    /// Private: the weights as given.
    pub weight: [f64; 8],
    /// Private: the running sums of the normalised weights.
    pub end: [f64; 8],
    /// Private: the phase components.
    pub phase: [sk_phase_f64; 8],
    /// Private: the table components.
    pub table: [sk_table_f64; 8],
}

const _: () = assert!(MAX_PARTS == 8);

/// A C mixture type with its part, phase and table types.
pub(super) trait MixStore: Copy {
    type T: Real;
    type P: PhaseStore<T = Self::T>;
    type Tb: TableStore<T = Self::T>;
    type Part: Copy;
    type V: CVec<T = Self::T>;
    #[allow(clippy::type_complexity)]
    fn fields(&self) -> (u32, &[u32; 8], &[Self::T; 8], &[Self::P; 8], &[Self::Tb; 8]);
    fn part(p: &Self::Part) -> (*const Self::P, *const Self::Tb, Self::T);
    fn empty() -> Self;
    fn set(&mut self, i: usize, phase: Option<Self::P>, table: Option<Self::Tb>, w: Self::T);
    fn finish(&mut self, n: usize, end: [Self::T; 8]);
    fn end(&self) -> &[Self::T; 8];
}

macro_rules! impl_mix_store {
    ($m:ident, $part:ident, $p:ident, $tb:ident, $t:ty, $v:ty) => {
        impl MixStore for $m {
            type T = $t;
            type P = $p;
            type Tb = $tb;
            type Part = $part;
            type V = $v;
            fn fields(&self) -> (u32, &[u32; 8], &[$t; 8], &[$p; 8], &[$tb; 8]) {
                (
                    self.n,
                    &self.is_table,
                    &self.weight,
                    &self.phase,
                    &self.table,
                )
            }
            fn part(p: &$part) -> (*const $p, *const $tb, $t) {
                (p.phase, p.table, p.weight)
            }
            fn empty() -> Self {
                $m {
                    n: 0,
                    is_table: [0; 8],
                    weight: [0.0; 8],
                    end: [0.0; 8],
                    phase: [<$p as PhaseStore>::ZEROED; 8],
                    table: [$tb {
                        data: core::ptr::null(),
                        n: 0,
                        kind: 0,
                    }; 8],
                }
            }
            fn finish(&mut self, n: usize, end: [$t; 8]) {
                (self.n, self.end) = (n as u32, end);
            }
            fn end(&self) -> &[$t; 8] {
                &self.end
            }
            fn set(&mut self, i: usize, phase: Option<$p>, table: Option<$tb>, w: $t) {
                if let (Some(slot), Some(flag), Some(weight)) = (
                    self.phase.get_mut(i),
                    self.is_table.get_mut(i),
                    self.weight.get_mut(i),
                ) {
                    *weight = w;
                    match (phase, table) {
                        (Some(p), _) => (*slot, *flag) = (p, 0),
                        (_, Some(t)) => {
                            *flag = 1;
                            if let Some(s) = self.table.get_mut(i) {
                                *s = t;
                            }
                        }
                        _ => {}
                    }
                }
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
    sk_vec3
);
impl_mix_store!(
    sk_mixture_f64,
    sk_mixture_part_f64,
    sk_phase_f64,
    sk_table_f64,
    f64,
    sk_vec3_f64
);

type Parts<'a, T> = [(Part<'a, T>, T); MAX_PARTS];

/// The components behind `m` and how many: `Err` for NULL, a count out of
/// range, or a component that does not load.
unsafe fn view<'a, S: MixStore>(m: *const S) -> Result<(Parts<'a, S::T>, usize), sk_status> {
    // SAFETY: a non-NULL m points to a mixture (module contract).
    let m = unsafe { m.as_ref() }.ok_or(sk_status::SK_ERR_NULL)?;
    let (n, is_table, weight, phase, table) = m.fields();
    let n = n as usize;
    if n == 0 || n > MAX_PARTS {
        return Err(sk_status::SK_ERR_SIZE);
    }
    let filler = (Part::Phase(crate::phase::Phase::isotropic()), S::T::ZERO);
    let mut parts = [filler; MAX_PARTS];
    let rows = parts.iter_mut().zip(
        is_table
            .iter()
            .zip(weight.iter().zip(phase.iter().zip(table.iter()))),
    );
    for (slot, (&t, (&w, (p, tb)))) in rows.take(n) {
        let part = if t == 1 {
            Part::Table(unsafe { load_table(tb) }.ok_or(sk_status::SK_ERR_SIZE)?)
        } else {
            Part::Phase(*unsafe { load(p) }.ok_or(sk_status::SK_ERR_DOMAIN)?)
        };
        *slot = (part, w);
    }
    Ok((parts, n))
}

/// The narrow Rust mixture behind `m` (no f64 copies), or the status of
/// what stopped it.
pub(super) unsafe fn mixture_at<'a, S: MixStore>(
    m: *const S,
) -> Result<Mixture<'a, S::T>, sk_status> {
    let (parts, n) = unsafe { view(m) }?;
    Mixture::new_narrow(parts.get(..n).unwrap_or(&[])).map_err(sk_status::from)
}

/// The light Rust mixture behind `m` (no f64 copies), or `None`.
unsafe fn light<'a, S: MixStore>(m: *const S) -> Option<Mixture<'a, S::T>> {
    unsafe { mixture_at(m) }.ok()
}

unsafe fn new_mixture<S: MixStore>(parts: *const S::Part, n: usize, out: *mut S) -> sk_status {
    if parts.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    if n == 0 || n > MAX_PARTS {
        return sk_status::SK_ERR_SIZE;
    }
    let mut m = S::empty();
    // SAFETY: parts points to n readable parts (the caller's contract).
    let given = unsafe { core::slice::from_raw_parts(parts, n) };
    for (i, part) in given.iter().enumerate() {
        let (p, t, w) = S::part(part);
        match unsafe { part_at(p, t) } {
            Ok(Part::Phase(_)) => m.set(i, Some(unsafe { *p }), None, w),
            Ok(Part::Table(_)) => m.set(i, None, Some(unsafe { *t }), w),
            Err(e) => return e,
        }
    }
    // The weights are checked by building the mixture, which also gives
    // the running sums the lobe choice reads.
    m.finish(n, [S::T::ZERO; 8]);
    let built = match unsafe { view(&m) } {
        Ok((ps, k)) => Mixture::new_narrow(ps.get(..k).unwrap_or(&[])).map(|x| x.ends()),
        Err(e) => return e,
    };
    match built {
        Ok(end) => {
            m.finish(n, end);
            // SAFETY: out checked non-NULL above.
            unsafe { out.write(m) };
            sk_status::SK_OK
        }
        Err(e) => e.into(),
    }
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

/// The lobe choice straight from the C value: the component whose share
/// of `[0, 1]` holds `u`, loaded alone and sampled at `u` rescaled (as
/// [`Mixture::sample_cos_by_lobe`], bit for bit).
unsafe fn by_lobe<S: MixStore>(m: *const S, u: S::T) -> S::T {
    // SAFETY: a non-NULL m points to a mixture (module contract).
    let Some(mix) = (unsafe { m.as_ref() }) else {
        return S::T::NAN;
    };
    let (n, is_table, _, phase, table) = mix.fields();
    let n = (n as usize).min(MAX_PARTS);
    let Some((i, v)) = lobe(mix.end().get(..n).unwrap_or(&[]), u) else {
        return S::T::NAN;
    };
    match (is_table.get(i), phase.get(i), table.get(i)) {
        (Some(1), _, Some(t)) => unsafe { load_table(t) }.map_or(S::T::NAN, |t| t.sample_cos(v)),
        (Some(_), Some(p), _) => unsafe { load(p) }.map_or(S::T::NAN, |p| p.sample_cos(v)),
        _ => S::T::NAN,
    }
}

/// `f` of the light mixture, NaN when it does not load.
unsafe fn with<S: MixStore>(m: *const S, f: impl Fn(&Mixture<'_, S::T>) -> S::T) -> S::T {
    unsafe { light(m) }.map_or(S::T::NAN, |m| f(&m))
}

/// The exact inverse, from the full mixture.
unsafe fn exact<S: MixStore>(m: *const S, u: S::T) -> S::T {
    let Ok((parts, n)) = (unsafe { view::<S>(m) }) else {
        return S::T::NAN;
    };
    match Mixture::new(parts.get(..n).unwrap_or(&[])) {
        Ok(m) => m.sample_cos(u),
        Err(_) => S::T::NAN,
    }
}

unsafe fn sample_dir<S: MixStore>(
    m: *const S,
    w_in: S::V,
    (u1, u2): (S::T, S::T),
    pdf_out: *mut S::T,
) -> S::V {
    let (d, pdf) = match unsafe { light(m) } {
        Some(m) => m.sample_dir_by_lobe(w_in.to_vec(), u1, u2),
        None => {
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

/// The batch of `u` through the exact inverse (`exact = true`, the full
/// mixture built once for the batch) or the lobe choice.
unsafe fn sample_cos_n<S: MixStore>(
    m: *const S,
    u: *const S::T,
    cos_out: *mut S::T,
    n: usize,
    exact: bool,
) -> sk_status {
    if m.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Ok((parts, k)) = (unsafe { view::<S>(m) }) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    let parts = parts.get(..k).unwrap_or(&[]);
    let built = if exact {
        Mixture::new(parts)
    } else {
        Mixture::new_narrow(parts)
    };
    let Ok(mix) = built else {
        return sk_status::SK_ERR_DOMAIN;
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

/// Builds the mixture of parts[0 .. n] into *out (weights normalised;
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
    unsafe { by_lobe(m, u) }
}

/// Double twin of `sk_mixture_sample_cos_by_lobe`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_by_lobe_f64(
    m: *const sk_mixture_f64,
    u: f64,
) -> f64 {
    unsafe { by_lobe(m, u) }
}

/// cos theta by the exact inverse of the mixture's CDF: monotone in u (for
/// stratified or quasi-random uniforms), a safeguarded Newton solve in
/// double on the components' CDFs (about 1 us). NaN as
/// sk_mixture_sample_cos_by_lobe.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos(m: *const sk_mixture, u: f32) -> f32 {
    unsafe { exact(m, u) }
}

/// Double twin of `sk_mixture_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_mixture_sample_cos_f64(m: *const sk_mixture_f64, u: f64) -> f64 {
    unsafe { exact(m, u) }
}

/// `cos_out[i] = sk_mixture_sample_cos(m, u[i])` for `i < n`, the mixture
/// built once for the batch (the single call rebuilds it each time). `u`
/// and `cos_out` may be the same array; other overlaps give
/// SK_ERR_DOMAIN. SK_ERR_DOMAIN if any `u[i]` is NaN or outside `[0, 1]`,
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
