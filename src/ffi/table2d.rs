//! 2-D tables (cos theta x a second variable) over caller-owned memory.

use super::phase::{PhaseStore, load};
use super::verbs;
use super::{CVec, sk_status, sk_vec3, sk_vec3_f64, slice_in, slice_out, write_result};
use crate::error::Error;
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::table::{Table, Table2d};

/// A 2-D table (float) over the caller's memory, which must outlive it: k
/// slices, each a Hermite inverse-CDF table of resolution n (2(n + 1)
/// floats, as SK_TABLE_INVERSE), at x_j = x0 + j dx.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_table2d {
    /// The slices, one after the other: 2k(n + 1) floats.
    pub data: *const f32,
    /// Resolution of each slice.
    pub n: usize,
    /// Number of slices (at least 1).
    pub k: usize,
    /// The variable at slice 0.
    pub x0: f32,
    /// Spacing of the slices in the variable (finite, positive).
    pub dx: f32,
}

/// A 2-D table (double); see `sk_table2d`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sk_table2d_f64 {
    /// The slices, one after the other: 2k(n + 1) doubles.
    pub data: *const f64,
    /// Resolution of each slice.
    pub n: usize,
    /// Number of slices (at least 1).
    pub k: usize,
    /// The variable at slice 0.
    pub x0: f64,
    /// Spacing of the slices in the variable (finite, positive).
    pub dx: f64,
}

/// A C 2-D table type and its float.
trait Table2dStore: Copy {
    type T: Real;
    fn new(data: *const Self::T, t: &Table2d<'_, Self::T>) -> Self;
    fn parts(&self) -> (*const Self::T, usize, usize, Self::T, Self::T);
}

macro_rules! impl_table2d_store {
    ($c:ty, $t:ty) => {
        impl Table2dStore for $c {
            type T = $t;
            fn new(data: *const $t, t: &Table2d<'_, $t>) -> Self {
                Self {
                    data,
                    n: t.n(),
                    k: t.k(),
                    x0: t.x0(),
                    dx: t.dx(),
                }
            }
            fn parts(&self) -> (*const $t, usize, usize, $t, $t) {
                (self.data, self.n, self.k, self.x0, self.dx)
            }
        }
    };
}
impl_table2d_store!(sk_table2d, f32);
impl_table2d_store!(sk_table2d_f64, f64);

/// The Rust table behind a C one, or None for NULL or malformed fields
/// (lengths and the axis are checked; the slices were checked when built).
unsafe fn load2d<'a, S: Table2dStore>(t: *const S) -> Option<Table2d<'a, S::T>> {
    // SAFETY: a non-NULL t points to a table built by this library.
    let (data, n, k, x0, dx) = unsafe { t.as_ref() }?.parts();
    let len = Table2d::<S::T>::len(n, k)?;
    let ok_axis = x0.is_finite() && dx.is_finite() && dx > S::T::ZERO;
    let data = unsafe { slice_in(data, len) }.ok()?;
    ok_axis.then(|| Table2d::from_parts(data, n, k, x0, dx))
}

unsafe fn from_data<S: Table2dStore>(
    data: *const S::T,
    len: usize,
    n: usize,
    k: usize,
    x0: S::T,
    dx: S::T,
    out: *mut S,
) -> sk_status {
    if data.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let slice = match unsafe { slice_in(data, len) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let r = Table2d::from_data(slice, n, k, x0, dx).map(|t| S::new(data, &t));
    unsafe { write_result(out, r) }
}

#[allow(clippy::too_many_arguments)]
unsafe fn inverse<S: Table2dStore, P: PhaseStore<T = S::T>>(
    phases: *const P,
    k: usize,
    buf: *mut S::T,
    len: usize,
    n: usize,
    x0: S::T,
    dx: S::T,
    out: *mut S,
) -> sk_status {
    if phases.is_null() || buf.is_null() || out.is_null() {
        return sk_status::SK_ERR_NULL;
    }
    let slice = match unsafe { slice_out(buf, len) } {
        Ok(s) => s,
        Err(e) => return e,
    };
    let r = Table2d::build(slice, n, k, x0, dx, |j, _, s| {
        // SAFETY: phases holds k values (contract); j < k.
        let phase = unsafe { load(phases.wrapping_add(j)) }.ok_or(Error::Domain)?;
        Table::inverse(phase, s, n).map(|_| ())
    })
    .map(|t| S::new(buf, &t));
    unsafe { write_result(out, r) }
}

unsafe fn sample_cos<S: Table2dStore>(t: *const S, x: S::T, u: S::T) -> S::T {
    unsafe { load2d(t) }.map_or(S::T::NAN, |t| t.sample_cos(x, u))
}

unsafe fn pdf<S: Table2dStore>(t: *const S, x: S::T, cos_theta: S::T) -> S::T {
    unsafe { load2d(t) }.map_or(S::T::NAN, |t| t.pdf(x, cos_theta))
}

unsafe fn sample_dir<S: Table2dStore, V: CVec<T = S::T>>(
    t: *const S,
    x: S::T,
    w_in: V,
    u1: S::T,
    u2: S::T,
    pdf_out: *mut S::T,
) -> V {
    let (dir, pdf) = match unsafe { load2d(t) } {
        Some(table) => table.sample_dir(x, w_in.to_vec(), u1, u2),
        None => (Vec3::new(S::T::NAN, S::T::NAN, S::T::NAN), S::T::NAN),
    };
    // SAFETY: a non-NULL pdf_out is writable (module contract).
    if let Some(p) = unsafe { pdf_out.as_mut() } {
        *p = pdf;
    }
    V::from_vec(dir)
}

/// Number of floats (or doubles) a 2-D table of k >= 1 slices of
/// resolution n >= 1 needs, 2k(n + 1); 0 for n = 0, k = 0 or overflow.
#[unsafe(no_mangle)]
pub extern "C" fn sk_table2d_len(n: usize, k: usize) -> usize {
    Table2d::<f32>::len(n, k).unwrap_or(0)
}

/// A 2-D table over data the caller filled slice by slice: slice j at
/// data + j 2(n + 1), written by sk_table_new_inverse or sk_table_new_measured
/// (for instance Mie at wavelength x0 + j dx) with the same n (for Mie,
/// size every slice for the largest size parameter among them, the
/// shortest wavelength or the largest sphere: sk_mie_table_len_f64 grows
/// with x, and a smaller n under-resolves the larger spheres). Checked:
/// SK_ERR_NULL for NULL data or out; SK_ERR_SIZE for n = 0, k = 0 or len
/// below sk_table2d_len(n, k); SK_ERR_DOMAIN for a non-finite x0, a dx
/// not finite and positive, or a slice whose nodes are not non-decreasing
/// within [-1, 1] with finite non-negative slopes at most 3 times each
/// neighbouring secant (as sk_table_new_measured limits them: the spline
/// then stays monotone and within its nodes). Lookup at (x, u):
/// s = (x - x0)/dx clamped to [0, k - 1], j = floor(s), w = s - j, and
/// mu = mu_j(u) + w (mu_{j+1}(u) - mu_j(u)) where w > 0: the neighbouring
/// slices' inverse CDFs blended at the same u (monotone in u; exactly a
/// slice at x = x_j); include/scatterkit_table.h has it header-only.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_new(
    data: *const f32,
    len: usize,
    n: usize,
    k: usize,
    x0: f32,
    dx: f32,
    out: *mut sk_table2d,
) -> sk_status {
    unsafe { from_data(data, len, n, k, x0, dx, out) }
}

/// Double twin of `sk_table2d_new`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_new_f64(
    data: *const f64,
    len: usize,
    n: usize,
    k: usize,
    x0: f64,
    dx: f64,
    out: *mut sk_table2d_f64,
) -> sk_status {
    unsafe { from_data(data, len, n, k, x0, dx, out) }
}

/// A 2-D table from k phase functions, `phases[j]` at x0 + j dx: each
/// slice the inverse CDF of its phase at n intervals (as
/// sk_table_new_inverse), written to buf (len floats, at least
/// sk_table2d_len(n, k)). SK_ERR_NULL for NULL pointers; SK_ERR_SIZE for
/// n = 0, k = 0 or a short buf; SK_ERR_DOMAIN for an unconstructed phase
/// or a bad axis (as sk_table2d_new).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_table2d_new_inverse(
    phases: *const super::sk_phase,
    k: usize,
    buf: *mut f32,
    len: usize,
    n: usize,
    x0: f32,
    dx: f32,
    out: *mut sk_table2d,
) -> sk_status {
    unsafe { inverse(phases, k, buf, len, n, x0, dx, out) }
}

/// Double twin of `sk_table2d_new_inverse`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_table2d_new_inverse_f64(
    phases: *const super::sk_phase_f64,
    k: usize,
    buf: *mut f64,
    len: usize,
    n: usize,
    x0: f64,
    dx: f64,
    out: *mut sk_table2d_f64,
) -> sk_status {
    unsafe { inverse(phases, k, buf, len, n, x0, dx, out) }
}

/// cos theta at the variable x (clamped to the slices' range) for u in
/// [0, 1] (clamped), O(1), monotone in u; bit for bit
/// sk_table2d_lookup of include/scatterkit_table.h. NaN for NaN x or u,
/// or a NULL or malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_sample_cos(t: *const sk_table2d, x: f32, u: f32) -> f32 {
    unsafe { sample_cos(t, x, u) }
}

/// Double twin of `sk_table2d_sample_cos`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_sample_cos_f64(
    t: *const sk_table2d_f64,
    x: f64,
    u: f64,
) -> f64 {
    unsafe { sample_cos(t, x, u) }
}

/// The density per steradian that sk_table2d_sample_cos draws from at x,
/// at cos_theta (the blended spline's own, as sk_table_pdf: a sample and
/// its pdf agree). 0 outside the range covered; +inf where the spline is
/// flat; NaN for NaN or a NULL or malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_pdf(t: *const sk_table2d, x: f32, cos_theta: f32) -> f32 {
    unsafe { pdf(t, x, cos_theta) }
}

/// Double twin of `sk_table2d_pdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_pdf_f64(
    t: *const sk_table2d_f64,
    x: f64,
    cos_theta: f64,
) -> f64 {
    unsafe { pdf(t, x, cos_theta) }
}

/// A direction about w_in (unit) at the variable x: cos theta from
/// sk_table2d_sample_cos(t, x, u1), the azimuth 2 pi u2 (clamped). Writes
/// its density (sk_table2d_pdf) to pdf_out unless NULL. A NULL or
/// malformed table gives NaN.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_sample_dir(
    t: *const sk_table2d,
    x: f32,
    w_in: sk_vec3,
    u1: f32,
    u2: f32,
    pdf_out: *mut f32,
) -> sk_vec3 {
    unsafe { sample_dir(t, x, w_in, u1, u2, pdf_out) }
}

/// Double twin of `sk_table2d_sample_dir`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_sample_dir_f64(
    t: *const sk_table2d_f64,
    x: f64,
    w_in: sk_vec3_f64,
    u1: f64,
    u2: f64,
    pdf_out: *mut f64,
) -> sk_vec3_f64 {
    unsafe { sample_dir(t, x, w_in, u1, u2, pdf_out) }
}

/// The table behind `t` for a batch: `SK_ERR_NULL` for NULL, `SK_ERR_SIZE`
/// for malformed fields.
unsafe fn table_for_batch<'a, S: Table2dStore>(
    t: *const S,
) -> Result<Table2d<'a, S::T>, sk_status> {
    if t.is_null() {
        return Err(sk_status::SK_ERR_NULL);
    }
    unsafe { load2d(t) }.ok_or(sk_status::SK_ERR_SIZE)
}

unsafe fn sample_cos_n<S: Table2dStore>(
    t: *const S,
    x: S::T,
    u: *const S::T,
    out: *mut S::T,
    n: usize,
) -> sk_status {
    match unsafe { table_for_batch(t) } {
        Ok(table) => unsafe { verbs::cos_n(u, out, n, |v| table.sample_cos(x, v)) },
        Err(e) => e,
    }
}

#[allow(clippy::too_many_arguments)]
unsafe fn sample_dir_n<S: Table2dStore>(
    t: *const S,
    x: S::T,
    w: [*const S::T; 3],
    (u1, u2): (*const S::T, *const S::T),
    out: [*mut S::T; 3],
    pdf_out: *mut S::T,
    n: usize,
) -> sk_status {
    match unsafe { table_for_batch(t) } {
        Ok(table) => unsafe {
            verbs::dir_n((w, u1, u2), (out, pdf_out), n, |w_in, a, b| {
                table.sample_dir(x, w_in, a, b)
            })
        },
        Err(e) => e,
    }
}

unsafe fn moments<S: Table2dStore>(t: *const S, x: S::T, out: *mut S::T, n: usize) -> sk_status {
    match unsafe { table_for_batch(t) } {
        Ok(table) => unsafe {
            verbs::moments(out, n, |u| table.sample_cos(x, S::T::from_f64(u)).to_f64())
        },
        Err(e) => e,
    }
}

/// The CDF of the distribution sk_table2d_sample_cos draws from at x, at
/// cos_theta (the blended spline's own). NaN for NaN or a NULL or
/// malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_cdf(t: *const sk_table2d, x: f32, cos_theta: f32) -> f32 {
    unsafe { load2d(t) }.map_or(f32::NAN, |t| t.cdf(x, cos_theta))
}

/// Double twin of `sk_table2d_cdf`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_cdf_f64(
    t: *const sk_table2d_f64,
    x: f64,
    cos_theta: f64,
) -> f64 {
    unsafe { load2d(t) }.map_or(f64::NAN, |t| t.cdf(x, cos_theta))
}

/// The mean cosine of the distribution the table samples at x. NaN for NaN
/// x or a NULL or malformed table.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_mean_cosine(t: *const sk_table2d, x: f32) -> f32 {
    unsafe { load2d(t) }.map_or(f32::NAN, |t| t.mean_cosine(x))
}

/// Double twin of `sk_table2d_mean_cosine`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_mean_cosine_f64(t: *const sk_table2d_f64, x: f64) -> f64 {
    unsafe { load2d(t) }.map_or(f64::NAN, |t| t.mean_cosine(x))
}

/// `cos_out[i] = sk_table2d_sample_cos(t, x, u[i])` for `i < n` (one x for
/// the batch), bit for bit; arrays, overlaps and statuses as
/// sk_table_sample_cos_n.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_sample_cos_n(
    t: *const sk_table2d,
    x: f32,
    u: *const f32,
    cos_out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(t, x, u, cos_out, n) }
}

/// Double twin of `sk_table2d_sample_cos_n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_sample_cos_n_f64(
    t: *const sk_table2d_f64,
    x: f64,
    u: *const f64,
    cos_out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { sample_cos_n(t, x, u, cos_out, n) }
}

/// Directions for n rays at one x, structure of arrays, each bit for bit
/// sk_table2d_sample_dir's; arrays, overlaps and statuses as
/// sk_table_sample_dir_n.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_table2d_sample_dir_n(
    t: *const sk_table2d,
    x: f32,
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
    unsafe { sample_dir_n(t, x, w, (u1, u2), out, pdf_out, n) }
}

/// Double twin of `sk_table2d_sample_dir_n`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn sk_table2d_sample_dir_n_f64(
    t: *const sk_table2d_f64,
    x: f64,
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
    unsafe { sample_dir_n(t, x, w, (u1, u2), out, pdf_out, n) }
}

/// The Legendre moments chi_0 .. chi_{n-1} of the distribution the table
/// samples at x, by quadrature over its inverse CDF, into out; statuses as
/// sk_table_legendre_moments.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_legendre_moments(
    t: *const sk_table2d,
    x: f32,
    out: *mut f32,
    n: usize,
) -> sk_status {
    unsafe { moments(t, x, out, n) }
}

/// Double twin of `sk_table2d_legendre_moments`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_table2d_legendre_moments_f64(
    t: *const sk_table2d_f64,
    x: f64,
    out: *mut f64,
    n: usize,
) -> sk_status {
    unsafe { moments(t, x, out, n) }
}
