//! The portable tier in bulk: cosines `out[i] = f(u[i])` over the shorter
//! of two slices, and directions over structure-of-arrays slices, the
//! scalar functions' bits per element. With the C layer on
//! x86-64 Linux each loop is chosen when the program is loaded, the widest
//! build the processor runs (`crate::math::arch`); every build runs the
//! same IEEE operations in the same order (Rust contracts nothing), so the
//! bits are the same in all of them, and the header's.

use super::phase::{
    Hg, dirac, hg_pm_of, hg_sample_cos, hg_sample_cos_sin, is_dirac, isotropic_sample_cos_sin,
    rayleigh_pdf, rayleigh_sample_cos,
};
use super::turns::direction_about;
use crate::math::real::Real;

/// The phase functions the batches run ([`sample_dir_n`]; the C layer's
/// cosine batch too).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Model {
    /// Isotropic: `cos θ = 2u − 1`, about `w_in` like the others.
    Isotropic,
    /// Henyey–Greenstein with these constants.
    Hg(Hg),
    /// Rayleigh (the built-in table).
    Rayleigh,
}

/// Directions in bulk, structure of arrays: for each `i`, the direction
/// about the unit `(wx[i], wy[i], wz[i])` with `cos θ` from `u1[i]` and
/// azimuth `2π u2[i]`, to `out[..][i]`, and its density to `pdf[i]`: the
/// bits of [`hg_sample_dir`](super::hg_sample_dir),
/// [`rayleigh_sample_dir`](super::rayleigh_sample_dir), or for isotropic
/// [`direction_about`](super::direction_about) at
/// [`isotropic_sample_cos_sin`](super::isotropic_sample_cos_sin) with
/// density `1/(4π)`. The shortest slice bounds the loop. With the C layer
/// on x86-64 Linux the loop is the widest build the processor runs.
#[inline]
pub fn sample_dir_n(
    phase: &Model,
    w: [&[f32]; 3],
    u: [&[f32]; 2],
    out: [&mut [f32]; 3],
    pdf: &mut [f32],
) {
    #[cfg(ifunc)]
    {
        let n = [w[0].len(), w[1].len(), w[2].len(), u[0].len(), u[1].len()]
            .into_iter()
            .chain([out[0].len(), out[1].len(), out[2].len(), pdf.len()])
            .min()
            .unwrap_or(0);
        let [ox, oy, oz] = out;
        let ins = [
            w[0].as_ptr(),
            w[1].as_ptr(),
            w[2].as_ptr(),
            u[0].as_ptr(),
            u[1].as_ptr(),
        ];
        let outs = [
            ox.as_mut_ptr(),
            oy.as_mut_ptr(),
            oz.as_mut_ptr(),
            pdf.as_mut_ptr(),
        ];
        // SAFETY: every slice holds at least n elements; the outputs are
        // exclusive borrows, distinct from the inputs and each other.
        #[allow(unsafe_code)]
        unsafe {
            portable_dir_n(phase, &ins, &outs, n)
        }
    }
    #[cfg(not(ifunc))]
    dir_each(phase, w, u, out, pdf)
}

/// The direction loop, written once for every build (a loop per phase, so
/// that each vectorises).
#[inline(always)]
fn dir_each(phase: &Model, w: [&[f32]; 3], u: [&[f32]; 2], out: [&mut [f32]; 3], pdf: &mut [f32]) {
    match phase {
        Model::Hg(h) => dir_loop(|x| hg_sample_cos_sin(h, x), w, u, out, pdf),
        Model::Rayleigh => dir_loop(
            |x| {
                let mu = rayleigh_sample_cos(x);
                (mu, Real::sqrt((1.0 - mu) * (1.0 + mu)), rayleigh_pdf(mu))
            },
            w,
            u,
            out,
            pdf,
        ),
        Model::Isotropic => dir_loop(
            |x| {
                let (mu, s) = isotropic_sample_cos_sin(x);
                (mu, s, INV_4PI)
            },
            w,
            u,
            out,
            pdf,
        ),
    }
}

/// One phase's loop: `(cos θ, sin θ, density)` from `f(u1)`, the direction
/// about `w` at azimuth `2π u2`; the shortest slice bounds it.
#[inline(always)]
fn dir_loop(
    f: impl Fn(f32) -> (f32, f32, f32),
    w: [&[f32]; 3],
    u: [&[f32]; 2],
    out: [&mut [f32]; 3],
    pdf: &mut [f32],
) {
    let [ox, oy, oz] = out;
    let ins = w[0].iter().zip(w[1]).zip(w[2]).zip(u[0]).zip(u[1]);
    let outs = ox
        .iter_mut()
        .zip(oy.iter_mut())
        .zip(oz.iter_mut())
        .zip(pdf.iter_mut());
    for (((((&x, &y), &z), &a), &b), (((o1, o2), o3), o4)) in ins.zip(outs) {
        let (mu, s, q) = f(a);
        let d = direction_about([x, y, z], mu, s, b);
        (*o1, *o2, *o3, *o4) = (d[0], d[1], d[2], q);
    }
}

/// `1/(4π)` rounded to f32.
const INV_4PI: f32 = 0.079_577_47;

/// `out[i] = hg_sample_cos(p, u[i])`.
#[inline]
pub fn hg_sample_cos_n(p: &Hg, u: &[f32], out: &mut [f32]) {
    for (o, &x) in out.iter_mut().zip(u) {
        *o = hg_sample_cos(p, x);
    }
}

/// [`hg_sample_cos_n`] for `u` known to lie in `[0, 1]` (as the C layer
/// checks them; clamping would change nothing), the loop specialised for
/// the sign of `g`: the same bits with fewer operations per element. A `u`
/// outside `[0, 1]` gets the formula's value there, unclamped.
#[inline]
pub fn hg_sample_cos_n_in_range(p: &Hg, u: &[f32], out: &mut [f32]) {
    #[cfg(ifunc)]
    {
        let n = u.len().min(out.len());
        // SAFETY: `p` is a valid `Hg`, `u` and `out` valid for `n` elements
        // and distinct (a shared and an exclusive borrow).
        #[allow(unsafe_code)]
        unsafe {
            portable_hg_cos_n(p, u.as_ptr(), out.as_mut_ptr(), n)
        }
    }
    #[cfg(not(ifunc))]
    hg_each(p, u, out)
}

/// `out[i] = rayleigh_sample_cos(u[i])`.
#[inline]
pub fn rayleigh_sample_cos_n(u: &[f32], out: &mut [f32]) {
    #[cfg(ifunc)]
    {
        let n = u.len().min(out.len());
        // SAFETY: as in `hg_sample_cos_n`.
        #[allow(unsafe_code)]
        unsafe {
            portable_rayleigh_cos_n(u.as_ptr(), out.as_mut_ptr(), n)
        }
    }
    #[cfg(not(ifunc))]
    rayleigh_each(u, out)
}

/// `out[i] = 2u[i] − 1` (the isotropic cosine; `u` clamped, NaN kept).
#[inline]
pub fn isotropic_sample_cos_n(u: &[f32], out: &mut [f32]) {
    for (o, &x) in out.iter_mut().zip(u) {
        *o = isotropic_sample_cos_sin(x).0;
    }
}

/// The HG loop for `u ∈ [0, 1]`, written once for every build: the
/// scalar sampler's operations (`phase::hg_pm_of`, `phase::hg_mu`) without
/// the clamp, which leaves such `u` as they are, and with the sign of `g`
/// and the Dirac limit (`|g| = 1`) taken out of the loop (`±1 · x` is `±x`
/// exactly).
#[inline(always)]
fn hg_each(p: &Hg, u: &[f32], out: &mut [f32]) {
    if is_dirac(p) {
        for (o, &x) in out.iter_mut().zip(u) {
            *o = dirac(x, p.sign);
        }
        return;
    }
    let mu = |u1: f32, v1: f32| {
        let (pp, mm) = hg_pm_of(p, u1, v1);
        (pp - mm) / (pp + mm)
    };
    if p.sign > 0.0 {
        for (o, &x) in out.iter_mut().zip(u) {
            *o = mu(x, 1.0 - x);
        }
    } else {
        for (o, &x) in out.iter_mut().zip(u) {
            *o = -mu(1.0 - x, x);
        }
    }
}

/// The Rayleigh loop, written once for every build.
#[inline(always)]
fn rayleigh_each(u: &[f32], out: &mut [f32]) {
    for (o, &x) in out.iter_mut().zip(u) {
        *o = rayleigh_sample_cos(x);
    }
}

#[cfg(ifunc)]
crate::math::arch::load_time_choice! {
    /// [`hg_each`] from C: the constants at `p`, `n` uniforms in `[0, 1]`
    /// at `u` to `n` cosines at `out`, which must not overlap `u`.
    portable_hg_cos_n: fn(p: *const Hg, u: *const f32, out: *mut f32, n: usize) {
        // SAFETY: the symbol's contract.
        let (p, u, out) = unsafe {
            (&*p, core::slice::from_raw_parts(u, n), core::slice::from_raw_parts_mut(out, n))
        };
        hg_each(p, u, out)
    }
}

#[cfg(ifunc)]
crate::math::arch::load_time_choice! {
    /// [`rayleigh_each`] from C: `n` uniforms at `u` to `n` cosines at
    /// `out`, which must not overlap `u`.
    portable_rayleigh_cos_n: fn(u: *const f32, out: *mut f32, n: usize) {
        // SAFETY: the symbol's contract.
        let (u, out) = unsafe {
            (core::slice::from_raw_parts(u, n), core::slice::from_raw_parts_mut(out, n))
        };
        rayleigh_each(u, out)
    }
}

#[cfg(ifunc)]
crate::math::arch::load_time_choice! {
    /// [`dir_each`] from C: the phase at `phase`, the five input arrays
    /// (`w` x, y, z, `u1`, `u2`) and four output arrays (x, y, z, pdf) at
    /// `ins` and `outs`, each valid for `n` elements, outputs distinct from
    /// the inputs and each other.
    portable_dir_n: fn(phase: *const Model, ins: *const [*const f32; 5], outs: *const [*mut f32; 4], n: usize) {
        // SAFETY: the symbol's contract.
        unsafe {
            let ([a, b, c, d, e], [f, g, h, k]) = (*ins, *outs);
            let s = |p: *const f32| core::slice::from_raw_parts(p, n);
            let m = |p: *mut f32| core::slice::from_raw_parts_mut(p, n);
            dir_each(&*phase, [s(a), s(b), s(c)], [s(d), s(e)], [m(f), m(g), m(h)], m(k))
        }
    }
}

#[cfg(all(test, ifunc))]
mod tests {
    extern crate std;
    use super::*;
    use crate::math::arch::detected;

    /// Every build gives the scalar function's bits, where this processor
    /// runs it.
    #[test]
    fn all_builds_agree() {
        let u: std::vec::Vec<f32> = (0..=4099).map(|i| i as f32 / 4099.0).collect();
        for g in [0.7f32, -0.3, 0.0, 0.999_999, -0.999_999, 1.0, -1.0] {
            let p = Hg::new(g).unwrap();
            for (needs, build) in portable_hg_cos_n::BUILDS {
                if needs > detected() {
                    continue;
                }
                let mut got = std::vec![1.0f32; u.len()];
                // SAFETY: valid, distinct buffers; the build's level is present.
                #[allow(unsafe_code)]
                unsafe {
                    build(&p, u.as_ptr(), got.as_mut_ptr(), u.len())
                };
                for (&x, y) in u.iter().zip(&got) {
                    assert_eq!(
                        hg_sample_cos(&p, x).to_bits(),
                        y.to_bits(),
                        "{needs:?} g {g} u {x}"
                    );
                }
            }
        }
        for (needs, build) in portable_rayleigh_cos_n::BUILDS {
            if needs > detected() {
                continue;
            }
            let mut got = std::vec![1.0f32; u.len()];
            // SAFETY: as above.
            #[allow(unsafe_code)]
            unsafe {
                build(u.as_ptr(), got.as_mut_ptr(), u.len())
            };
            for (&x, y) in u.iter().zip(&got) {
                assert_eq!(
                    rayleigh_sample_cos(x).to_bits(),
                    y.to_bits(),
                    "{needs:?} u {x}"
                );
            }
        }
    }
}
