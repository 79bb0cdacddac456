//! Tables over caller-owned memory.

use super::phase::{PhaseStore, load};
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
    pub kind: u32,
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
    pub kind: u32,
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
                    kind: kind as u32,
                }
            }
            fn parts(&self) -> (*const $t, usize, u32) {
                (self.data, self.n, self.kind)
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
pub extern "C" fn sk_table_len(kind: u32, n: usize) -> usize {
    TableKind::try_from(kind)
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
