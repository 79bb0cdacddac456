//! Henyey–Greenstein cosines in bulk on the f32 sampler's f64 path
//! ([`hg`](super::hg) module docs): `μ = A − B/(u' + k)²` over a slice,
//! `u' = u` for `g > 0` and `1 − u` for `g < 0`, each result rounded once to
//! f32, the same bits as the scalar sampler per element.
//!
//! The loop is bound by the f64 divider: with the C layer on x86-64 Linux it
//! is chosen when the program is loaded, the widest build the processor
//! runs (AVX and wider: four divisions per instruction instead of SSE2's
//! two; `crate::math::arch`).

#[cfg(ifunc)]
use super::HenyeyGreenstein;
#[cfg(ifunc)]
use crate::phase::function::dir_each;

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

/// The f32 direction loop (`HenyeyGreenstein::sample_dir_each`) over the
/// shortest array's length, in the widest build the processor runs: the
/// loop is bound by its f64 division and f32 arithmetic, and wider lanes
/// cut its time (`sk_phase_sample_dir_n` 6.6–7.2 → 4.2–4.3 ns per
/// direction with the AVX-512 build; Intel Xeon, family 6 model 167).
/// Inputs `w` x, y, z, `u1`, `u2`; outputs x, y, z, pdf.
#[cfg(ifunc)]
pub(super) fn dir_n(hg: &HenyeyGreenstein<f32>, ins: [&[f32]; 5], outs: [&mut [f32]; 4]) {
    let n = ins
        .iter()
        .map(|s| s.len())
        .chain(outs.iter().map(|s| s.len()))
        .min()
        .unwrap_or(0);
    let ins = ins.map(|s| s.as_ptr());
    let outs = outs.map(|s| s.as_mut_ptr());
    // SAFETY: every array holds at least n elements; the outputs are
    // exclusive borrows, distinct from the inputs and each other.
    #[allow(unsafe_code)]
    unsafe {
        hg_dir_n((hg as *const HenyeyGreenstein<f32>).cast(), &ins, &outs, n)
    }
}

#[cfg(ifunc)]
crate::math::arch::load_time_choice! {
    /// [`dir_n`] behind a symbol: the `HenyeyGreenstein<f32>` at `hg`, the
    /// five input arrays at `ins` and the four output arrays at `outs`,
    /// each valid for `n` elements, the outputs distinct from the inputs
    /// and each other.
    hg_dir_n: fn(hg: *const core::ffi::c_void, ins: *const [*const f32; 5], outs: *const [*mut f32; 4], n: usize) {
        // SAFETY: the symbol's contract.
        unsafe {
            let hg = &*hg.cast::<HenyeyGreenstein<f32>>();
            let ([a, b, c, d, e], [f, g, h, k]) = (*ins, *outs);
            let s = |p: *const f32| core::slice::from_raw_parts(p, n);
            let m = |p: *mut f32| core::slice::from_raw_parts_mut(p, n);
            dir_each([s(a), s(b), s(c)], [s(d), s(e)], [m(f), m(g), m(h)], m(k), |w, x, y| {
                hg.dir_pdf(w, x, y)
            })
        }
    }
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

    /// Every build of the f32 direction loop gives the scalar sampler's
    /// bits, where this processor runs it: both branches of the f64 path
    /// (g of either sign), the factored forms (|g| < 2⁻¹⁰) and the Dirac
    /// limit.
    #[test]
    fn every_direction_build_gives_the_scalar_bits() {
        use crate::math::geometry::Vec3;
        use crate::phase::PhaseFunction;
        use crate::phase::hg::HenyeyGreenstein;
        let n = 1031;
        let u = |i: usize, k: usize| ((i * k) % n) as f32 / (n - 1) as f32;
        let w: std::vec::Vec<[f32; 3]> = (0..n)
            .map(|i| {
                let z = 2.0 * u(i, 7) - 1.0;
                let (s, c) = (6.283_185_5 * u(i, 13)).sin_cos();
                let r = (1.0 - z * z).max(0.0).sqrt();
                [r * c, r * s, z]
            })
            .collect();
        let (u1, u2): (std::vec::Vec<f32>, std::vec::Vec<f32>) =
            (0..n).map(|i| (u(i, 1), u(i, 29))).unzip();
        let col = |k: usize| w.iter().map(|v| v[k]).collect::<std::vec::Vec<f32>>();
        let (wx, wy, wz) = (col(0), col(1), col(2));
        let ins = [
            wx.as_ptr(),
            wy.as_ptr(),
            wz.as_ptr(),
            u1.as_ptr(),
            u2.as_ptr(),
        ];
        for g in [0.7f32, -0.95, 3e-4, -1.0, 1.0] {
            let hg = HenyeyGreenstein::new(g).unwrap();
            for (needs, build) in super::hg_dir_n::BUILDS {
                if needs > detected() {
                    std::println!("{needs:?} not available: its build is not checked");
                    continue;
                }
                let mut out = [(); 4].map(|_| std::vec![7.0f32; n]);
                let outs = [0, 1, 2, 3].map(|k| out[k].as_mut_ptr());
                // SAFETY: valid, distinct arrays of n elements.
                #[allow(unsafe_code)]
                unsafe {
                    build((&hg as *const HenyeyGreenstein<f32>).cast(), &ins, &outs, n)
                };
                for i in 0..n {
                    let (d, p) = hg.sample_dir(Vec3::new(wx[i], wy[i], wz[i]), u1[i], u2[i]);
                    let got = [out[0][i], out[1][i], out[2][i], out[3][i]].map(f32::to_bits);
                    assert_eq!(
                        got,
                        [d.x, d.y, d.z, p].map(f32::to_bits),
                        "{needs:?} g {g} at {i}"
                    );
                }
            }
        }
    }
}
