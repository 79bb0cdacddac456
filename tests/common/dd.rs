//! Double-double arithmetic (~106-bit significand): the higher-precision
//! reference the accuracy tests measure f32 and f64 results against.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

impl Dd {
    pub const fn new(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
    pub fn abs(self) -> Dd {
        if self.hi < 0.0 { -self } else { self }
    }
    pub fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::new(0.0);
        }
        let s = Dd::new(self.hi.sqrt());
        s + (self - s * s) / (s * 2.0)
    }
    pub fn cbrt(self) -> Dd {
        if self.hi == 0.0 {
            return Dd::new(0.0);
        }
        let mut y = Dd::new(self.hi.cbrt());
        for _ in 0..2 {
            y = y + (self - y * y * y) / (y * y * 3.0);
        }
        y
    }
}

impl From<f64> for Dd {
    fn from(x: f64) -> Dd {
        Dd::new(x)
    }
}

impl Add for Dd {
    type Output = Dd;
    fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let r = quick_two_sum(s, e + t);
        quick_two_sum(r.hi, r.lo + f)
    }
}

impl Neg for Dd {
    type Output = Dd;
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for Dd {
    type Output = Dd;
    fn sub(self, o: Dd) -> Dd {
        self + (-o)
    }
}

impl Mul for Dd {
    type Output = Dd;
    fn mul(self, o: Dd) -> Dd {
        let p = self.hi * o.hi;
        let e = self.hi.mul_add(o.hi, -p);
        quick_two_sum(p, e + (self.hi * o.lo + self.lo * o.hi))
    }
}

impl Div for Dd {
    type Output = Dd;
    fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self - o * q1;
        let q2 = r.hi / o.hi;
        let r = r - o * q2;
        let q3 = r.hi / o.hi;
        quick_two_sum(q1, q2) + Dd::new(q3)
    }
}

macro_rules! scalar_ops {
    ($($tr:ident $f:ident),*) => {$(
        impl $tr<f64> for Dd {
            type Output = Dd;
            fn $f(self, o: f64) -> Dd { self.$f(Dd::new(o)) }
        }
    )*};
}
scalar_ops!(Add add, Sub sub, Mul mul, Div div);

/// Rayleigh's inverse CDF (Cardano, `μ = w − 1/w`), in double-double, using
/// the odd symmetry so `s + sqrt(s² + 1)` never cancels.
pub fn rayleigh_inverse(u: f64) -> f64 {
    let s = (Dd::new(u) * 2.0 - 1.0) * 2.0;
    let a = s.abs();
    let w = (a + (a * a + 1.0).sqrt()).cbrt();
    let mu = w - Dd::new(1.0) / w;
    if s.hi < 0.0 {
        -mu.to_f64()
    } else {
        mu.to_f64()
    }
}

/// Depolarised Rayleigh's inverse CDF by Cardano in double-double:
/// `x³ + 3a x = 2b`, `x = w − a/w`.
pub fn rayleigh_depolarized_inverse(rho: f64, u: f64) -> f64 {
    let gamma = Dd::new(rho) / (Dd::new(2.0) - rho);
    let omg = Dd::new(1.0) - gamma;
    let a = (gamma * 3.0 + 1.0) / omg;
    let b = (gamma * 2.0 + 1.0) * (Dd::new(u) * 2.0 - 1.0) * 2.0 / omg;
    let babs = b.abs();
    let w = (babs + (babs * babs + a * a * a).sqrt()).cbrt();
    let x = w - a / w;
    if b.hi < 0.0 { -x.to_f64() } else { x.to_f64() }
}

/// Henyey–Greenstein's inverse CDF, the textbook formula
/// `μ = (1 + g² − s²)/(2g)`, `s = (1 − g²)/(1 − g + 2gu)`, in double-double
/// (its cancellation for small g costs digits we can afford); `2u − 1` at g = 0.
pub fn hg_inverse(g: f64, u: f64) -> f64 {
    let (g, u) = (Dd::new(g), Dd::new(u));
    if g.hi == 0.0 {
        return (u * 2.0 - 1.0).to_f64();
    }
    let one = Dd::new(1.0);
    let s = (one - g * g) / (one - g + g * u * 2.0);
    ((one + g * g - s * s) / (g * 2.0))
        .to_f64()
        .clamp(-1.0, 1.0)
}

/// Draine's CDF (the cancellation-free form of `src/phase/draine.rs`) in double-double.
pub fn draine_cdf(g: f64, alpha: f64, mu: Dd) -> Dd {
    let one = Dd::new(1.0);
    let gd = Dd::new(g);
    let d = if g >= 0.0 {
        (one - gd) * (one - gd) + gd * (one - mu) * 2.0
    } else {
        (one + gd) * (one + gd) - gd * (one + mu) * 2.0
    };
    let s = d.sqrt();
    let s0 = one + gd;
    let e = (one + mu) / (s + s0);
    let se = s0 * e;
    let i0 = e * 2.0 / (s * s0);
    let poly = Dd::new(3.0) - se * 6.0 + se * se * 4.0 - gd * se * e * e * 2.0;
    let i2 = e * 2.0 * poly / (s * s0 * 3.0);
    let c = one + Dd::new(alpha) * (one + gd * gd * 2.0) / 3.0;
    let n = (one - gd) * (one + gd) / (c * 2.0);
    n * (i0 + Dd::new(alpha) * i2)
}

/// Density of μ for Draine, `N (1 + αμ²)/s³`, in double-double.
pub fn draine_density(g: f64, alpha: f64, mu: Dd) -> Dd {
    let one = Dd::new(1.0);
    let gd = Dd::new(g);
    let s = (one + gd * gd - gd * mu * 2.0).sqrt();
    let c = one + Dd::new(alpha) * (one + gd * gd * 2.0) / 3.0;
    let n = (one - gd) * (one + gd) / (c * 2.0);
    n * (one + Dd::new(alpha) * mu * mu) / (s * s * s)
}

/// Draine's inverse CDF in double-double: bisection on the dd CDF to 2⁻⁶⁰,
/// then two Newton steps in dd; for u > 1/2 the mirror problem
/// `F_{−g}(−μ) = 1 − u`, so the residual is always taken in the small tail.
pub fn draine_inverse(g: f64, alpha: f64, u: f64) -> f64 {
    let (g, target, sign) = if u > 0.5 {
        (-g, Dd::new(1.0) - u, -1.0)
    } else {
        (g, Dd::new(u), 1.0)
    };
    if target.hi <= 0.0 {
        return -sign;
    }
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    for _ in 0..62 {
        let mid = 0.5 * (lo + hi);
        if draine_cdf(g, alpha, Dd::new(mid)) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mut x = Dd::new(0.5 * (lo + hi));
    for _ in 0..2 {
        let r = draine_cdf(g, alpha, x) - target;
        let f = draine_density(g, alpha, x);
        if f.hi > 0.0 {
            x = x - r / f;
        }
    }
    sign * x.to_f64().clamp(-1.0, 1.0)
}

/// The fog mixture's inverse CDF in double-double (bisection on the dd CDF).
pub fn fog_inverse(g_hg: f64, g_d: f64, alpha: f64, w: f64, u: f64) -> f64 {
    let (sg, target, sign) = if u > 0.5 {
        (-1.0, Dd::new(1.0) - u, -1.0)
    } else {
        (1.0, Dd::new(u), 1.0)
    };
    if target.hi <= 0.0 {
        return -sign;
    }
    let cdf =
        |x: Dd| draine_cdf(sg * g_hg, 0.0, x) * (1.0 - w) + draine_cdf(sg * g_d, alpha, x) * w;
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    for _ in 0..62 {
        let mid = 0.5 * (lo + hi);
        if cdf(Dd::new(mid)) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    sign * (0.5 * (lo + hi))
}
