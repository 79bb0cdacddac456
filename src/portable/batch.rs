//! The portable tier in bulk: `out[i] = f(u[i])` over the shorter of two
//! slices, the scalar function's bits per element. With the C layer on
//! x86-64 Linux each loop is chosen when the program is loaded, the widest
//! build the processor runs (`crate::math::arch`); every build runs the
//! same IEEE operations in the same order (Rust contracts nothing), so the
//! bits are the same in all of them, and the header's.

use super::phase::{Hg, hg_pm_of, hg_sample_cos, isotropic_sample_cos_sin, rayleigh_sample_cos};

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
/// taken out of the loop (`±1 · x` is `±x` exactly).
#[inline(always)]
fn hg_each(p: &Hg, u: &[f32], out: &mut [f32]) {
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
        for g in [0.7f32, -0.3, 0.0, 0.999_999, -0.999_999] {
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
