//! The verbs every phase-like handle speaks, written once: the batch forms
//! of `sample_cos` and `sample_dir`, a direction with its density, and
//! Legendre moments by quadrature. Each handle supplies its own scalar
//! sampler; the batches are bit for bit its scalar calls.

use super::{CVec, SOA_BLOCK, check_soa, map_arrays, sk_status, slice_out, soa_blocks};
use crate::math::geometry::Vec3;
use crate::math::real::Real;
use crate::phase::check_uniforms;
use crate::phase::moments::legendre_moments_of;

/// `cos_out[i] = f(u[i])` for `i < n`, the uniforms checked in `[0, 1]`
/// first (`SK_ERR_DOMAIN`, nothing written), `u` and `cos_out` the same
/// array or disjoint (`SK_ERR_OVERLAP`).
pub(crate) unsafe fn cos_n<T: Real>(
    u: *const T,
    cos_out: *mut T,
    n: usize,
    f: impl Fn(T) -> T,
) -> sk_status {
    unsafe {
        map_arrays(u, cos_out, n, check_uniforms, |u, out| {
            for (o, &v) in out.iter_mut().zip(u) {
                *o = f(v);
            }
            Ok(())
        })
    }
}

/// Directions for `n` rays, structure of arrays, block by block: the
/// arrays checked (`pdf_out` may be NULL; an output may be the same array
/// as an input, other overlaps are `SK_ERR_OVERLAP`; NULLs, sizes), the
/// uniforms checked in `[0, 1]` (`SK_ERR_DOMAIN`), nothing written unless
/// all pass; then `run(inputs, outputs, len)` fills each block of 64 (the
/// inputs w_x, w_y, w_z, u1, u2; the outputs x, y, z, pdf).
pub(crate) unsafe fn dir_blocks<T: Real>(
    ins: ([*const T; 3], *const T, *const T),
    (out, pdf_out): ([*mut T; 3], *mut T),
    n: usize,
    run: impl FnMut(&[[T; SOA_BLOCK]; 5], &mut [[T; SOA_BLOCK]; 4], usize),
) -> sk_status {
    let [ox, oy, oz] = out;
    let outputs = [(ox, false), (oy, false), (oz, false), (pdf_out, true)];
    unsafe { checked_blocks(ins, outputs, n, run) }
}

/// [`dir_blocks`] for any list of outputs `(array, may be NULL)`: the
/// checks, then `run` per block.
unsafe fn checked_blocks<T: Real, const O: usize>(
    (w, u1, u2): ([*const T; 3], *const T, *const T),
    outputs: [(*mut T, bool); O],
    n: usize,
    run: impl FnMut(&[[T; SOA_BLOCK]; 5], &mut [[T; SOA_BLOCK]; O], usize),
) -> sk_status {
    let inputs = [w[0], w[1], w[2], u1, u2];
    if let Err(e) = check_soa(&inputs, &outputs, n) {
        return e;
    }
    if n == 0 {
        return sk_status::SK_OK;
    }
    // SAFETY: checked above: u1 and u2 hold n elements.
    let (a, b) = unsafe {
        (
            core::slice::from_raw_parts(u1, n),
            core::slice::from_raw_parts(u2, n),
        )
    };
    if let Err(e) = check_uniforms(a).and_then(|()| check_uniforms(b)) {
        return e.into();
    }
    unsafe { soa_blocks(inputs, outputs.map(|(p, _)| p), n, run) };
    sk_status::SK_OK
}

/// [`dir_block_slices`] with each direction's `cos θ` too: `run(w, [u1,
/// u2], out, cos, pdf)`; `cos_out` must not be NULL, `pdf_out` may be.
pub(crate) unsafe fn dir_cos_block_slices<T: Real>(
    ins: ([*const T; 3], *const T, *const T),
    (out, cos_out, pdf_out): ([*mut T; 3], *mut T, *mut T),
    n: usize,
    mut run: impl FnMut([&[T]; 3], [&[T]; 2], [&mut [T]; 3], &mut [T], &mut [T]),
) -> sk_status {
    let [ox, oy, oz] = out;
    let outputs = [
        (ox, false),
        (oy, false),
        (oz, false),
        (cos_out, false),
        (pdf_out, true),
    ];
    let adapt = |i: &[[T; SOA_BLOCK]; 5], o: &mut [[T; SOA_BLOCK]; 5], len: usize| {
        let [ix, iy, iz, a, b] = i.each_ref().map(|x| x.get(..len).unwrap_or(&[]));
        let [ox, oy, oz, cos, pdf] = o.each_mut().map(|x| x.get_mut(..len).unwrap_or(&mut []));
        run([ix, iy, iz], [a, b], [ox, oy, oz], cos, pdf);
    };
    unsafe { checked_blocks(ins, outputs, n, adapt) }
}

/// [`dir_blocks`] with each block handed over as slices of its length:
/// `run(w, [u1, u2], out, pdf)`, for loops written over slices.
pub(crate) unsafe fn dir_block_slices<T: Real>(
    ins: ([*const T; 3], *const T, *const T),
    outs: ([*mut T; 3], *mut T),
    n: usize,
    mut run: impl FnMut([&[T]; 3], [&[T]; 2], [&mut [T]; 3], &mut [T]),
) -> sk_status {
    let adapt = |i: &[[T; SOA_BLOCK]; 5], o: &mut [[T; SOA_BLOCK]; 4], len: usize| {
        let [ix, iy, iz, a, b] = i.each_ref().map(|x| x.get(..len).unwrap_or(&[]));
        let [ox, oy, oz, pdf] = o.each_mut().map(|x| x.get_mut(..len).unwrap_or(&mut []));
        run([ix, iy, iz], [a, b], [ox, oy, oz], pdf);
    };
    unsafe { dir_blocks(ins, outs, n, adapt) }
}

/// [`dir_blocks`] with `f(w_in, u1, u2)` giving each direction and its
/// density.
pub(crate) unsafe fn dir_n<T: Real>(
    ins: ([*const T; 3], *const T, *const T),
    outs: ([*mut T; 3], *mut T),
    n: usize,
    f: impl Fn(Vec3<T>, T, T) -> (Vec3<T>, T),
) -> sk_status {
    let run = |i: &[[T; SOA_BLOCK]; 5], o: &mut [[T; SOA_BLOCK]; 4], len: usize| {
        for k in 0..len.min(SOA_BLOCK) {
            let w_in = Vec3::new(i[0][k], i[1][k], i[2][k]);
            let (d, pdf) = f(w_in, i[3][k], i[4][k]);
            (o[0][k], o[1][k], o[2][k], o[3][k]) = (d.x, d.y, d.z, pdf);
        }
    };
    unsafe { dir_blocks(ins, outs, n, run) }
}

/// One direction about `w_in` from `f` (NaN for `None`: a NULL or bad
/// handle), its density written through a non-NULL `pdf_out`.
pub(crate) unsafe fn dir_one<V: CVec>(found: Option<(Vec3<V::T>, V::T)>, pdf_out: *mut V::T) -> V {
    let nan = V::T::NAN;
    let (d, pdf) = found.unwrap_or((Vec3::new(nan, nan, nan), nan));
    // SAFETY: a non-NULL pdf_out is writable (module contract).
    if let Some(p) = unsafe { pdf_out.as_mut() } {
        *p = pdf;
    }
    V::from_vec(d)
}

/// The Legendre moments `χ_0 … χ_{n−1}` of the distribution whose inverse
/// CDF is `mu` (a function of `u` in f64), by quadrature over `u`, into
/// `out`. `SK_ERR_NULL` for a NULL `out` with `n > 0`.
pub(crate) unsafe fn moments<T: Real>(out: *mut T, n: usize, mu: impl Fn(f64) -> f64) -> sk_status {
    match unsafe { slice_out(out, n) } {
        Ok(out) => {
            legendre_moments_of(mu, 0, out);
            sk_status::SK_OK
        }
        Err(e) => e,
    }
}
