//! Tables over caller-owned memory.

use super::phase::{PhaseStore, load};
use super::verbs;
use super::{
    CVec, overlaps_len, sk_status, sk_vec3, sk_vec3_f64, slice_in, slice_out, write_result,
};
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::table::{Table, TableKind};

/// What a table holds (passed as uint32_t; other values give SK_ERR_METHOD).
#[repr(u32)]
#[derive(Clone, Copy, Debug)]
pub enum sk_table_kind {
    /// Frisvad's tabulated Rayleigh CDF: n + 1 values at cos theta = -1 + 2i/n.
    SK_TABLE_RAYLEIGH_CDF = 0,
    /// Inverse CDF of a phase function, cubic Hermite in u: 2(n + 1) values.
    SK_TABLE_INVERSE = 1,
    /// Inverse CDF of a measured phase function, cubic Hermite: 2(n + 1) values.
    SK_TABLE_MEASURED = 2,
}

same_values!(sk_table_kind = TableKind:
    SK_TABLE_RAYLEIGH_CDF = RayleighCdf,
    SK_TABLE_INVERSE = Inverse,
    SK_TABLE_MEASURED = Measured,
);

/// A table sampler (float) over the caller's memory, which must outlive it.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_table {
    /// The caller's buffer, filled by the constructor.
    pub data: *const f32,
    /// Resolution the table was built with.
    pub n: usize,
    /// An sk_table_kind.
    pub kind: super::enum_arg::sk_table_kind,
}

/// A table sampler (double); see `sk_table`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_table_f64 {
    /// The caller's buffer, filled by the constructor.
    pub data: *const f64,
    /// Resolution the table was built with.
    pub n: usize,
    /// An sk_table_kind.
    pub kind: super::enum_arg::sk_table_kind,
}

/// A C table type and its float.
pub(crate) trait TableStore: Copy {
    type T: Real;
    fn new(data: *const Self::T, n: usize, kind: TableKind) -> Self;
    fn parts(&self) -> (*const Self::T, usize, u32);
}

macro_rules! impl_table_store {
    ($c:ty, $t:ty) => {
        impl TableStore for $c {
            type T = $t;
            fn new(data: *const $t, n: usize, kind: TableKind) -> Self {
                Self {
                    data,
                    n,
                    kind: super::enum_arg::sk_table_kind(kind as u32),
                }
            }
            fn parts(&self) -> (*const $t, usize, u32) {
                (self.data, self.n, self.kind.0)
            }
        }
    };
}
impl_table_store!(sk_table, f32);
impl_table_store!(sk_table_f64, f64);

unsafe fn rayleigh_cdf<S: TableStore>(
    buf: *mut S::T,
    len: usize,
    n: usize,
    out: *mut S,
) -> sk_status {
    if buf.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let slice = match unsafe { slice_out(buf, len) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let r = Table::rayleigh_cdf(slice, n).map(|t| S::new(buf, t.n(), t.kind()));
    unsafe { write_result(out, r) }
}

unsafe fn inverse<S: TableStore, P: PhaseStore<T = S::T>>(
    p: *const P,
    buf: *mut S::T,
    len: usize,
    n: usize,
    out: *mut S,
) -> sk_status {
    if p.is_null() || buf.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let Some(phase) = (unsafe { load(p) }) else {
        return sk_status::SK_ERR_DOMAIN;
    };
    let slice = match unsafe { slice_out(buf, len) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let r = Table::inverse(phase, slice, n).map(|t| S::new(buf, t.n(), t.kind()));
    unsafe { write_result(out, r) }
}

#[allow(clippy::too_many_arguments)]
unsafe fn measured<S: TableStore>(
    cos_theta: *const S::T,
    pdf: *const S::T,
    m: usize,
    buf: *mut S::T,
    len: usize,
    n: usize,
    out: *mut S,
) -> sk_status {
    if cos_theta.is_null() || pdf.is_null() || buf.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let (x, p) = match unsafe { (slice_in(cos_theta, m), slice_in(pdf, m)) } {
        (Ok(x), Ok(p)) => (x, p),
        (Err(e), _) | (_, Err(e)) => return e,
    };
    // buf is written through a &mut slice: it must not share the data's memory.
    if overlaps_len(buf, len, cos_theta, m) || overlaps_len(buf, len, pdf, m) {
        return sk_status::SK_ERR_OVERLAP;
    }
    let slice = match unsafe { slice_out(buf, len) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let r = Table::measured(x, p, slice, n).map(|t| S::new(buf, t.n(), t.kind()));
    unsafe { write_result(out, r) }
}

/// The Rust table behind a C table, or None for NULL or malformed fields.
pub(crate) unsafe fn load_table<'a, S: TableStore>(t: *const S) -> Option<Table<'a, S::T>> {
    // SAFETY: a non-NULL t points to a table built by this library.
    let (data, n, kind) = unsafe { t.as_ref() }?.parts();
    let kind = TableKind::try_from(kind).ok()?;
    let len = kind.len(n)?;
    let data = unsafe { slice_in(data, len) }.ok()?;
    Table::from_data(data, n, kind).ok()
}

unsafe fn sample_cos<S: TableStore>(t: *const S, u: S::T) -> S::T {
    unsafe { load_table(t) }.map_or(S::T::NAN, |table| table.sample_cos(u))
}

unsafe fn pdf<S: TableStore>(t: *const S, cos_theta: S::T) -> S::T {
    unsafe { load_table(t) }.map_or(S::T::NAN, |table| table.pdf(cos_theta))
}

unsafe fn sample_dir<S: TableStore, V: CVec<T = S::T>>(
    t: *const S,
    w_in: V,
    u1: S::T,
    u2: S::T,
    pdf_out: *mut S::T,
) -> V {
    let (dir, pdf) = match unsafe { load_table(t) } {
        Some(table) => table.sample_dir(w_in.to_vec(), u1, u2),
        None => (Vec3::new(S::T::NAN, S::T::NAN, S::T::NAN), S::T::NAN),
    };
    // SAFETY: a non-NULL pdf_out is writable (module contract).
    if let Some(p) = unsafe { pdf_out.as_mut() } {
        *p = pdf;
    }
    V::from_vec(dir)
}

/// Number of floats (or doubles) a table of `kind` and resolution n needs;
/// 0 for an unknown kind, n = 0, or a count that overflows size_t.
#[unsafe(no_mangle)]
pub extern "C" fn sk_table_len(kind: super::enum_arg::sk_table_kind, n: usize) -> usize {
    TableKind::try_from(kind.0)
        .ok()
        .and_then(|k| k.len(n))
        .unwrap_or(0)
}

/// Frisvad's (2011) tabulated Rayleigh CDF with n >= 1 intervals, written to
/// buf (len floats, at least sk_table_len(SK_TABLE_RAYLEIGH_CDF, n) = n + 1).
/// SK_ERR_NULL for NULL buf or out; SK_ERR_SIZE for n = 0 or len too small.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_new_rayleigh_cdf(
    buf: *mut f32,
    len: usize,
    n: usize,
    out: *mut sk_table,
) -> sk_status {
    unsafe { rayleigh_cdf(buf, len, n, out) }
}

/// Double twin of `sk_table_new_rayleigh_cdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_new_rayleigh_cdf_f64(
    buf: *mut f64,
    len: usize,
    n: usize,
    out: *mut sk_table_f64,
) -> sk_status {
    unsafe { rayleigh_cdf(buf, len, n, out) }
}

/// Tabulates the inverse CDF of phase `p` at n >= 1 intervals into buf (len
/// floats, at least sk_table_len(SK_TABLE_INVERSE, n) = 2(n + 1)) for O(1)
/// cubic Hermite lookup with sk_table_sample_cos (monotone in u). SK_ERR_NULL
/// for NULL pointers; SK_ERR_DOMAIN for an unconstructed phase; SK_ERR_SIZE for
/// n = 0 or len too small.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_new_inverse(
    p: *const super::sk_phase,
    buf: *mut f32,
    len: usize,
    n: usize,
    out: *mut sk_table,
) -> sk_status {
    unsafe { inverse(p, buf, len, n, out) }
}

/// Double twin of `sk_table_new_inverse`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_new_inverse_f64(
    p: *const super::sk_phase_f64,
    buf: *mut f64,
    len: usize,
    n: usize,
    out: *mut sk_table_f64,
) -> sk_status {
    unsafe { inverse(p, buf, len, n, out) }
}

/// A sampler for a phase function measured at m >= 2 cosines: cos_theta
/// strictly increasing or strictly decreasing within [-1, 1], pdf finite and
/// non-negative with a positive integral, any scale (it is normalised). The
/// density is linear in cos theta between the points and zero outside their
/// range. buf holds len floats, at least 2(n + 1). SK_ERR_NULL for NULL
/// pointers; SK_ERR_SIZE for m < 2, n = 0 or len too small; SK_ERR_DOMAIN for
/// invalid data; SK_ERR_OVERLAP for a buf that shares memory with the data.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_new_measured(
    cos_theta: *const f32,
    pdf: *const f32,
    m: usize,
    buf: *mut f32,
    len: usize,
    n: usize,
    out: *mut sk_table,
) -> sk_status {
    unsafe { measured(cos_theta, pdf, m, buf, len, n, out) }
}

/// Double twin of `sk_table_new_measured`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_new_measured_f64(
    cos_theta: *const f64,
    pdf: *const f64,
    m: usize,
    buf: *mut f64,
    len: usize,
    n: usize,
    out: *mut sk_table_f64,
) -> sk_status {
    unsafe { measured(cos_theta, pdf, m, buf, len, n, out) }
}

/// cos theta for u in [0, 1] (clamped; NaN gives NaN) from a table; NaN for a
/// NULL or malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_sample_cos(t: *const sk_table, u: f32) -> f32 {
    unsafe { sample_cos(t, u) }
}

/// Double twin of `sk_table_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_sample_cos_f64(t: *const sk_table_f64, u: f64) -> f64 {
    unsafe { sample_cos(t, u) }
}

/// The density per steradian that sk_table_sample_cos draws from, at
/// cos_theta: the table's own (not the phase function it was built from),
/// so that a sample and its pdf agree exactly, as MIS needs. Frisvad's CDF
/// table: `(F[i+1] - F[i])` / (2 pi (2/n)) on interval i of cos theta. Hermite
/// tables: 1 / (2 pi n mu'(t)), where mu(t) is the interval's cubic (see
/// include/scatterkit_table.h) and t solves mu(t) = cos_theta; +inf where a
/// slope was limited to 0. 0 outside the range the table covers; NaN for
/// NaN or a NULL or malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_pdf(t: *const sk_table, cos_theta: f32) -> f32 {
    unsafe { pdf(t, cos_theta) }
}

/// Double twin of `sk_table_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_pdf_f64(t: *const sk_table_f64, cos_theta: f64) -> f64 {
    unsafe { pdf(t, cos_theta) }
}

/// A direction about w_in (unit): cos theta from sk_table_sample_cos(t, u1),
/// the azimuth 2 pi u2 (u2 clamped to [0, 1]). Writes its density per
/// steradian (sk_table_pdf) to pdf_out unless it is NULL. A NULL or
/// malformed table gives NaN (direction and pdf).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_sample_dir(
    t: *const sk_table,
    w_in: sk_vec3,
    u1: f32,
    u2: f32,
    pdf_out: *mut f32,
) -> sk_vec3 {
    unsafe { sample_dir(t, w_in, u1, u2, pdf_out) }
}

/// Double twin of `sk_table_sample_dir`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_sample_dir_f64(
    t: *const sk_table_f64,
    w_in: sk_vec3_f64,
    u1: f64,
    u2: f64,
    pdf_out: *mut f64,
) -> sk_vec3_f64 {
    unsafe { sample_dir(t, w_in, u1, u2, pdf_out) }
}

/// The table behind `t` for a batch: `SK_ERR_NULL` for NULL, `SK_ERR_SIZE`
/// for malformed fields (as the constructors report a short buffer).
unsafe fn table_for_batch<'a, S: TableStore>(t: *const S) -> Result<Table<'a, S::T>, sk_status> {
    if t.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { load_table(t) }.ok_or(sk_status::SK_ERR_SIZE)
}

unsafe fn sample_cos_n<S: TableStore>(
    t: *const S,
    u: *const S::T,
    out: *mut S::T,
    n: usize,
) -> sk_status {
    match unsafe { table_for_batch(t) } {
        Ok(table) => unsafe { verbs::cos_n(u, out, n, |v| table.sample_cos(v)) },
        Err(e) => e,
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn sample_dir_n<S: TableStore>(
    t: *const S,
    w: [*const S::T; 3],
    (u1, u2): (*const S::T, *const S::T),
    out: [*mut S::T; 3],
    pdf_out: *mut S::T,
    n: usize,
) -> sk_status {
    match unsafe { table_for_batch(t) } {
        Ok(table) => unsafe {
            verbs::dir_n((w, u1, u2), (out, pdf_out), n, |w_in, a, b| {
                table.sample_dir(w_in, a, b)
            })
        },
        Err(e) => e,
    }
}

unsafe fn moments<S: TableStore>(t: *const S, out: *mut S::T, n: usize) -> sk_status {
    match unsafe { table_for_batch(t) } {
        Ok(table) => unsafe {
            verbs::moments(out, n, |u| table.sample_cos(S::T::from_f64(u)).to_f64())
        },
        Err(e) => e,
    }
}

/// The CDF of the distribution sk_table_sample_cos draws from (the table's
/// own, exact for its interpolant) at cos_theta: 0 below the range the
/// table covers, 1 above. NaN for NaN or a NULL or malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_cdf(t: *const sk_table, cos_theta: f32) -> f32 {
    unsafe { load_table(t) }.map_or(f32::NAN, |table| table.cdf(cos_theta))
}

/// Double twin of `sk_table_cdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_cdf_f64(t: *const sk_table_f64, cos_theta: f64) -> f64 {
    unsafe { load_table(t) }.map_or(f64::NAN, |table| table.cdf(cos_theta))
}

/// The mean cosine of the distribution the table samples. NaN for a NULL
/// or malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_mean_cosine(t: *const sk_table) -> f32 {
    unsafe { load_table(t) }.map_or(f32::NAN, |table| table.mean_cosine())
}

/// Double twin of `sk_table_mean_cosine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_mean_cosine_f64(t: *const sk_table_f64) -> f64 {
    unsafe { load_table(t) }.map_or(f64::NAN, |table| table.mean_cosine())
}

/// `cos_out[i] = sk_table_sample_cos(t, u[i])` for `i < n`, bit for bit.
/// `u` and `cos_out` may be the same array; other overlaps give
/// SK_ERR_OVERLAP. SK_ERR_DOMAIN if any `u[i]` is NaN or outside [0, 1];
/// SK_ERR_NULL for NULL t, or NULL arrays with n > 0; SK_ERR_SIZE for a
/// malformed table or n floats that cannot exist. On error nothing is
/// written; n = 0 is SK_OK.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_sample_cos_n(
    t: *const sk_table,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(t, u, cos_out, n) }
}

/// Double twin of `sk_table_sample_cos_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_sample_cos_n_f64(
    t: *const sk_table_f64,
    u: *const f64,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(t, u, cos_out, n) }
}

/// Directions for n rays, structure of arrays, each bit for bit
/// sk_table_sample_dir's; arrays, overlaps and statuses as
/// sk_phase_sample_dir_n (SK_ERR_SIZE for a malformed table).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_table_sample_dir_n(
    t: *const sk_table,
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
    unsafe { sample_dir_n(t, w, (u1, u2), out, pdf_out, n) }
}

/// Double twin of `sk_table_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_table_sample_dir_n_f64(
    t: *const sk_table_f64,
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
    unsafe { sample_dir_n(t, w, (u1, u2), out, pdf_out, n) }
}

/// The Legendre moments chi_0 .. chi_{n-1} of the distribution the table
/// samples, chi_l = <P_l(cos theta)>, by quadrature over its inverse CDF,
/// into out. SK_ERR_NULL for NULL t or a NULL out with n > 0; SK_ERR_SIZE
/// for a malformed table or n values that cannot exist.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_legendre_moments(
    t: *const sk_table,
    out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { moments(t, out, n) }
}

/// Double twin of `sk_table_legendre_moments`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table_legendre_moments_f64(
    t: *const sk_table_f64,
    out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { moments(t, out, n) }
}
