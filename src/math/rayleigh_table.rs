//! The built-in Rayleigh inverse table (`RayleighMethod::Table` of the
//! phase module, and the portable tier's Rayleigh sampler): the inverse
//! CDF at `n + 1` nodes and its slope, as the coefficients of a cubic
//! Hermite spline per interval, built at compile time in f64 from the
//! stable Cardano root (Frisvad 2011 §4's closed form, with `cardano_w`'s
//! seed and Halley steps).

/// Intervals of the table.
pub const TABLE_N: usize = 128;

/// `cardano_w` for f64 in a `const fn`: the table below is built at compile time.
const fn cardano_w_const(a: f64) -> f64 {
    let mut w = 0.999_001_297_444_754_6
        + a * (0.353_234_767_755_447_4
            + a * (-0.001_343_385_289_570_21 + a * -0.010_459_901_086_701_195));
    let mut k = 0;
    while k < 3 {
        let c = w * w * w;
        let h = c * c - 2.0 * a * c - 1.0;
        let cma = c - a;
        w -= 2.0 * w * h * cma / (12.0 * c * cma * cma - h * (5.0 * c - 2.0 * a));
        k += 1;
    }
    w
}

/// The built-in table: `μ_i = F⁻¹(i/n)` and `d_i = (dμ/du)/n = 1/(n · ⅜(1 + μ²))`
/// at the nodes, stored per interval as the cubic's coefficients
/// `[μ_i, d_i, c2_i, c3_i]` with `c2 = 3Δ − 2d_i − d_{i+1}`,
/// `c3 = d_i + d_{i+1} − 2Δ`, `Δ = μ_{i+1} − μ_i` (the cubic Hermite
/// spline), all in f64 at compile time, so a lookup only evaluates the cubic.
const fn rayleigh_table() -> [f64; 4 * TABLE_N] {
    let mut t = [0.0; 4 * TABLE_N];
    let mut i = 0;
    while i < TABLE_N {
        let ((y0, d0), (y1, d1)) = (node(i), node(i + 1));
        let dy = y1 - y0;
        t[4 * i] = y0;
        t[4 * i + 1] = d0;
        t[4 * i + 2] = 3.0 * dy - 2.0 * d0 - d1;
        t[4 * i + 3] = d0 + d1 - 2.0 * dy;
        i += 1;
    }
    t
}

/// `(μ_i, d_i)` at node `i` of the built-in table.
const fn node(i: usize) -> (f64, f64) {
    let s = 2.0 * (2.0 * (i as f64 / TABLE_N as f64) - 1.0);
    let w = cardano_w_const(if s < 0.0 { -s } else { s });
    let w2 = w * w;
    let mu = 2.0 * s * w2 / (w2 * w2 + w2 + 1.0);
    (mu, 1.0 / (TABLE_N as f64 * 0.375 * (1.0 + mu * mu)))
}

pub(crate) static RAYLEIGH_TABLE: [f64; 4 * TABLE_N] = rayleigh_table();

/// The same table rounded to f32, so f32 callers stay in f32.
pub static RAYLEIGH_TABLE_F32: [f32; 4 * TABLE_N] = {
    let mut t = [0.0f32; 4 * TABLE_N];
    let mut i = 0;
    while i < t.len() {
        t[i] = RAYLEIGH_TABLE[i] as f32;
        i += 1;
    }
    t
};
