//! Cube roots (libm-style names).

use crate::math::cbrt;

/// Cube root: Kahan seed + two Lancaster steps; within 1 ULP of the correctly
/// rounded result on every float. +-0, +-inf and NaN are returned as they are.
#[unsafe(no_mangle)]
pub extern "C" fn sk_cbrt(x: f32) -> f32 {
    cbrt::cbrt_f32(x)
}

/// Cube root with one Lancaster step: relative error about 2e-5.
#[unsafe(no_mangle)]
pub extern "C" fn sk_cbrt_fast(x: f32) -> f32 {
    cbrt::cbrt_fast_f32(x)
}

/// Cube root of a double: Kahan seed + three Lancaster steps; about 1 ULP on
/// every double. +-0, +-inf and NaN are returned as they are.
#[unsafe(no_mangle)]
pub extern "C" fn sk_cbrt_f64(x: f64) -> f64 {
    cbrt::cbrt_f64(x)
}

/// Cube root of a double with two Lancaster steps: relative error about 1e-14.
#[unsafe(no_mangle)]
pub extern "C" fn sk_cbrt_fast_f64(x: f64) -> f64 {
    cbrt::cbrt_fast_f64(x)
}
