//! Henyey–Greenstein cosines in bulk on the f32 sampler's f64 path
//! ([`hg`](super::hg) module docs): `μ = A − B/(u' + k)²` over a slice,
//! `u' = u` for `g > 0` and `1 − u` for `g < 0`, each result rounded once to
//! f32, the same bits as the scalar sampler per element.
//!
//! The loop is bound by the f64 divider: with the C layer on x86-64 Linux it
//! is chosen when the program is loaded, the widest build the processor
//! runs (AVX and wider: four divisions per instruction instead of SSE2's
//! two; `crate::math::arch`).

/// The f64 path's constants for a batch: `k`, `A` and `B` with the sign of
/// `g` (the `hg` module's `wide` values 0–2), and whether `u' = 1 − u`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Wide {
    pub(super) kab: [f64; 3],
    pub(super) mirror: bool,
}

/// `out[i] = A − B/(u'[i] + k)²` rounded to f32, for `u` already in
/// `[0, 1]`; the shorter slice bounds the loop.
#[inline]
pub(super) fn cos_n(w: Wide, u: &[f32], out: &mut [f32]) {
    #[cfg(ifunc)]
    {
        let n = u.len().min(out.len());
        // SAFETY: `u` and `out` are valid for `n` elements and do not overlap
        // (a shared and an exclusive borrow).
        #[allow(unsafe_code)]
        unsafe {
            hg_wide_cos_n(&w.kab, w.mirror, u.as_ptr(), out.as_mut_ptr(), n)
        }
    }
    #[cfg(not(ifunc))]
    hg_wide_cos_each(w.kab, w.mirror, u, out)
}

#[cfg(ifunc)]
crate::math::arch::load_time_choice! {
    /// [`hg_wide_cos_each`] from C: `(k, A, B)` at `kab`, the mirror, and
    /// `n` uniforms in `[0, 1]` at `u` to `n` cosines at `out`, which must
    /// not overlap `u`.
    hg_wide_cos_n: fn(kab: *const [f64; 3], mirror: bool, u: *const f32, out: *mut f32, n: usize) {
        // SAFETY: the symbol's contract.
        let (kab, u, out) = unsafe {
            (*kab, core::slice::from_raw_parts(u, n), core::slice::from_raw_parts_mut(out, n))
        };
        hg_wide_cos_each(kab, mirror, u, out)
    }
}

/// `t = u' + k` and `q = B/t²` on the f64 path (module docs): the one place
/// the scalar sampler (`hg`'s `wide_t`) and the batch form them, so that their
/// bits agree by construction.
#[inline(always)]
pub(super) fn wide_tq(k: f64, b: f64, u1: f64) -> (f64, f64) {
    let t = u1 + k;
    (t, b / (t * t))
}

/// The loop itself, written once for every build: the branch on the mirror
/// outside, so that the compiler vectorises each arm.
#[inline(always)]
fn hg_wide_cos_each(kab: [f64; 3], mirror: bool, u: &[f32], out: &mut [f32]) {
    let [k, a, b] = kab;
    // The scalar sampler's operations (`hg`'s `wide_cos`): `A − B/(u' + k)²`.
    let cos = |u1: f64| (a - wide_tq(k, b, u1).1) as f32;
    if mirror {
        for (o, &x) in out.iter_mut().zip(u) {
            *o = cos(1.0 - x as f64);
        }
    } else {
        for (o, &x) in out.iter_mut().zip(u) {
            *o = cos(x as f64);
        }
    }
}

#[cfg(all(test, ifunc))]
mod tests {
    extern crate std;
    use super::hg_wide_cos_n::BUILDS;
    use crate::math::arch::detected;

    /// Every build gives the bits of the SSE2 build, where this processor
    /// runs it.
    #[test]
    fn all_builds_agree() {
        let u: std::vec::Vec<f32> = (0..=4099).map(|i| i as f32 / 4099.0).collect();
        for (kab, mirror) in [
            ([0.2142857, 1.0499999, 0.0474], false),
            ([3.0, 3.1, 0.5], true),
        ] {
            let mut want = std::vec![0.0f32; u.len()];
            // SAFETY: valid, distinct buffers of u.len() elements.
            #[allow(unsafe_code)]
            unsafe {
                BUILDS[0].1(&kab, mirror, u.as_ptr(), want.as_mut_ptr(), u.len())
            };
            for (needs, build) in BUILDS {
                if needs > detected() {
                    std::println!("{needs:?} not available: its build is not checked");
                    continue;
                }
                let mut got = std::vec![1.0f32; u.len()];
                // SAFETY: as above; the build's level is present.
                #[allow(unsafe_code)]
                unsafe {
                    build(&kab, mirror, u.as_ptr(), got.as_mut_ptr(), u.len())
                };
                assert!(
                    want.iter()
                        .zip(&got)
                        .all(|(x, y)| x.to_bits() == y.to_bits())
                );
            }
        }
    }
}
