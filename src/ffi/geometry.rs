//! The orthonormal basis.

use super::{CVec, sk_vec3, sk_vec3_f64};

unsafe fn onb_into<V: CVec>(n: V, b1: *mut V, b2: *mut V) {
    if b1.is_null() || b2.is_null() {
        return;
    }
    let (a, b) = crate::math::geometry::onb(n.to_vec());
    // SAFETY: non-NULL out-pointers are writable (module contract).
    unsafe {
        b1.write(V::from_vec(a));
        b2.write(V::from_vec(b));
    }
}

/// Completes the unit vector `n` to a right-handed orthonormal basis
/// `(b1, b2, n)` (Duff et al. 2017: no singularity, exact for n = +-z). Writes
/// nothing if either out-pointer is NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_onb(n: sk_vec3, b1: *mut sk_vec3, b2: *mut sk_vec3) {
    unsafe { onb_into(n, b1, b2) }
}

/// Double twin of `sk_onb`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sk_onb_f64(n: sk_vec3_f64, b1: *mut sk_vec3_f64, b2: *mut sk_vec3_f64) {
    unsafe { onb_into(n, b1, b2) }
}
