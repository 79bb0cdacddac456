//! Lorenz–Mie scattering by a homogeneous sphere, in f64, without
//! allocation: the series coefficients and the logarithmic derivative live
//! in the caller's buffer ([`buffer_len`]).
//!
//! Conventions (Bohren & Huffman, *Absorption and Scattering of Light by
//! Small Particles*, 1983, ch. 4): size parameter `x = 2π r n_medium / λ`,
//! relative refractive index `m = n + i k` with `k ≥ 0` for an absorbing
//! sphere (time dependence `e^{−iωt}`; Wiscombe's MIEV0 writes the same
//! sphere as `n − i k`).
//!
//! Method (Wiscombe, "Improved Mie scattering algorithms", Appl. Opt. 19,
//! 1980; Bohren & Huffman, §4.8 and appendix A):
//! * terms `N = x + 4x^{1/3} + 3` (`x ≤ 8`), `x + 4.05 x^{1/3} + 2`
//!   (`8 < x < 4200`), `x + 4x^{1/3} + 2` (larger): Wiscombe's count, with
//!   two terms more below `x = 8`, where his count (`+ 1`, made for single
//!   precision) truncates the series at a relative 10⁻⁷ in `g` and 3·10⁻⁸
//!   in `Q_ext` (MIEV0 cases 5 and 12, against the series summed in 40
//!   digits); then `⌈4x^{1/3}⌉ + 4` more for the backward amplitudes. His
//!   count converges `Q_ext`, `Q_sca` and `g`, but not the alternating sum
//!   `S(π) = Σ (2n+1)/2 (−1)^{n+1} (a_n − b_n)`: `Q_back` was truncated
//!   at a relative 2·10⁻¹⁰ at `x = 10`, 2·10⁻⁸ at 100, 1.7·10⁻⁶ at 1000
//!   and 1.2·10⁻⁸ at 5000 (against the series summed in 60 digits,
//!   `scripts/mie_backscatter_reference.py`, which scattnlay 2.4 agrees
//!   with; miepython 3.3 keeps Wiscombe's count and shares the error). It
//!   converges to 10⁻¹⁴ with 4, 8, 22 and 42 more terms there (`x^{1/3}`
//!   2.2, 4.6, 10 and 17.1);
//! * the logarithmic derivative `D_n(mx)` by downward recurrence
//!   `D_{n−1} = n/(mx) − 1/(D_n + n/(mx))` from
//!   `max(N, |mx|) + 8 (|mx|/2)^{1/3} + 16` (eight Airy widths past the
//!   turning point), which is stable for every `m` (the upward recurrence
//!   is not when `|mx|` is large or `k` is), carried as the remainder
//!   `R_n(z) = D_n(z) − (n + 1)/z`, `R_{n−1} = −z/(2n + 1 + z R_n)`
//!   (the same recurrence with the pole of the small-`z` limit taken out);
//! * the Riccati–Bessel functions `χ_n` by upward recurrence (the growing
//!   solution: stable), `ψ_n` upward while `n < x`, where it
//!   oscillates, and from `n ≥ x` by ratios, `ψ_n = ψ_{n−1} / (D_n(x) +
//!   n/x)`, with `D_n(x)` from its own downward recurrence: `ψ_n` decays
//!   there, and the upward recurrence, which subtracts nearly equal terms
//!   (`ψ_1 = sin x / x − cos x ≈ x²/3`), loses a digit per term at small
//!   `x` (`g` off by 10⁻¹⁰ at `x = 0.1`). The ratio is not used below
//!   `n = x`, where `ψ_{n−1}` can vanish (its first zero lies beyond
//!   `n + 1.8 n^{1/3}`) and the ratio cancels;
//! * `a_n = ((D_n/m + n/x) ψ_n − ψ_{n−1}) / ((D_n/m + n/x) ξ_n − ξ_{n−1})`,
//!   `b_n` likewise with `m D_n`; `a_n`'s numerator and denominator
//!   multiplied by `m²`, so that no `1/m²` enters. Where `ψ_n` is the
//!   ratio (`n ≥ x`), the numerators come from the remainders, `ψ_n ((n +
//!   1)(1 − m²)/x + m R_n(mx) − m² R_n(x))` and `ψ_n (m R_n(mx) −
//!   R_n(x))`: from the `D_n`, `b_n`'s difference is of order `x²(m² − 1)`
//!   of its terms, and `g`, which needs `b_1`, was off by a factor of 10³
//!   at `x = 10⁻⁹` and 10²⁵ at `x = 10⁻²⁰` (182 spheres from `x = 10⁻²⁰` to
//!   30 against 80 digits now agree within 1.2·10⁻¹²).

pub mod polydisperse;

use crate::error::Error;
use crate::math::numeric::newton_bracketed;

/// A complex number (f64): the refractive index and the series terms.
/// `repr(C)`: the C layer's `sk_complex_f64` is the same pair.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Complex {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Complex {
    /// `re + i im`.
    pub const fn new(re: f64, im: f64) -> Self {
        Complex { re, im }
    }
    fn add(self, o: Self) -> Self {
        Complex::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: Self) -> Self {
        Complex::new(self.re - o.re, self.im - o.im)
    }
    fn mul(self, o: Self) -> Self {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    fn scale(self, s: f64) -> Self {
        Complex::new(self.re * s, self.im * s)
    }
    fn conj(self) -> Self {
        Complex::new(self.re, -self.im)
    }
    /// `|z|²`.
    pub fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }
    /// `self / o`, scaled so that neither square overflows (Smith's method).
    fn div(self, o: Self) -> Self {
        if o.re.abs() >= o.im.abs() {
            let r = o.im / o.re;
            let d = o.re + o.im * r;
            Complex::new((self.re + self.im * r) / d, (self.im - self.re * r) / d)
        } else {
            let r = o.re / o.im;
            let d = o.re * r + o.im;
            Complex::new((self.re * r + self.im) / d, (self.im * r - self.re) / d)
        }
    }
}

/// One step down of `R_n(z) = D_n(z) − (n + 1)/z`, the logarithmic
/// derivative less its small-`z` pole: `R_{n−1} = −z/(2n + 1 + z R_n)`,
/// Bohren & Huffman's `D_{n−1} = n/z − 1/(D_n + n/z)` with the `(n + 1)/z`
/// and `n/z` taken out (`R_n ≈ −z/(2n + 3)` as `z → 0`, where `D_n`
/// itself is `(n + 1)/z` to within `z²`, so that differences of two `D_n`
/// kept only their rounding).
fn remainder_down(n: usize, z: Complex, r: Complex) -> Complex {
    let den = Complex::new((2 * n + 1) as f64, 0.0).add(z.mul(r));
    z.div(den).scale(-1.0)
}

/// The factors of term `n` (Bohren & Huffman, eq. 4.88, with `D_n(mx) =
/// (n + 1)/(mx) + R_n(mx)` and `R_n` from [`remainder_down`]): `b_n =
/// (t_b ψ_n − ψ_{n−1})/(t_b ξ_n − ξ_{n−1})` with `t_b = m D_n(mx) + n/x =
/// (2n + 1)/x + m R_n`, and `a_n` the same with `t_a = m² (D_n(mx)/m +
/// n/x) = (n + 1)/x + m R_n + m² n/x` and `m² ψ_{n−1}`, `m² ξ_{n−1}`:
/// numerator and denominator times `m²`, so that no `1/m²` enters (with
/// it, a tiny complex `m` gave both a large complex phase that cancelled in
/// the quotient and left `Re a_n` wrong in the eighth digit: `Q_abs < 0`).
struct Terms {
    n: usize,
    x: f64,
    m2: Complex,
    one_m2: Complex,
    /// `m R_n(mx)`.
    mr: Complex,
    a: Complex,
    b: Complex,
}

impl Terms {
    fn new(n: usize, x: f64, (m, m2, one_m2): (Complex, Complex, Complex), r: Complex) -> Self {
        let (nf, mr) = (n as f64, m.mul(r));
        let a = Complex::new((nf + 1.0) / x, 0.0)
            .add(mr)
            .add(m2.scale(nf / x));
        let b = Complex::new((2.0 * nf + 1.0) / x, 0.0).add(mr);
        Terms {
            n,
            x,
            m2,
            one_m2,
            mr,
            a,
            b,
        }
    }

    /// Where `ψ_n` is the ratio `ψ_{n−1}/(D_n(x) + n/x)`: the numerators
    /// over `ψ_n`, `t_a − m²(D_n(x) + n/x) = (n + 1)(1 − m²)/x + m R_n(mx)
    /// − m² R_n(x)` and `t_b − (D_n(x) + n/x) = m R_n(mx) − R_n(x)`, with
    /// `rx = R_n(x)`: the `(n + 1)/x` of the two `D_n` cancel exactly.
    /// Formed from the `D_n`, `b_n`'s lost two digits per decade of `x`
    /// below 1 (it is `x²(m² − 1)/(2n + 3)` of the terms), and `g`, which
    /// needs `b_1`, was off by a factor of 10³ at `x = 10⁻⁹`.
    fn ratio_numerators(&self, rx: f64) -> (Complex, Complex) {
        let a = self
            .one_m2
            .scale((self.n + 1) as f64 / self.x)
            .add(self.mr)
            .sub(self.m2.scale(rx));
        (a, self.mr.sub(Complex::new(rx, 0.0)))
    }
}

/// The size parameter `x = π d n_medium / λ` of a sphere of diameter `d`
/// in a medium of index `n_medium`, at vacuum wavelength `λ` (same length
/// unit as `d`).
pub fn size_parameter(diameter: f64, wavelength: f64, n_medium: f64) -> f64 {
    core::f64::consts::PI * diameter * n_medium / wavelength
}

/// The number of series terms for size parameter `x`: Wiscombe's count,
/// two more for `x ≤ 8`, and `⌈4x^{1/3}⌉ + 4` more for the backward
/// amplitudes (module docs).
pub fn terms(x: f64) -> usize {
    let c = libm::cbrt(x);
    let n = if x <= 8.0 {
        x + 4.0 * c + 3.0
    } else if x < 4200.0 {
        x + 4.05 * c + 2.0
    } else {
        x + 4.0 * c + 2.0
    };
    n as usize + libm::ceil(4.0 * c) as usize + 4
}

/// Where the downward recurrence for `D_n` starts: `max(N, |mx|) + 8
/// (|mx|/2)^{1/3} + 16`. For a nearly real `mx` the start error is damped
/// only where `n > |mx|`, by the Airy-type decay of the wanted solution
/// against the unwanted one over widths of `(|mx|/2)^{1/3}`: eight widths
/// bring it below 10⁻¹³. Bohren & Huffman's `+ 15` is under four widths at
/// `|mx| = 133` (MIEV0 case 10, `m = 1.33 + 10⁻⁵ i`, `x = 100`: `Q_ext`
/// wrong in the fifth digit) and leaves water at `x = 1000` wrong in the
/// third.
fn start(x: f64, m: Complex) -> usize {
    let mx = libm::sqrt(m.norm_sqr()) * x;
    ((terms(x) as f64).max(mx) + 8.0 * libm::cbrt(0.5 * mx)) as usize + 16
}

/// The number of [`Complex`] values [`Mie::new`] needs for `(x, m)`, or
/// `None` for input it rejects (see there).
pub fn buffer_len(x: f64, m: Complex) -> Option<usize> {
    valid(x, m).then(|| start(x, m) + 1 + 2 * (terms(x) + 1))
}

/// The largest `n`, `k` and `|m| x` accepted: the downward recurrence
/// starts near `|m| x`, so the buffer grows with it (about 3.5·10⁷ bytes at
/// the bound).
pub const MAX_INDEX: f64 = 1e3;
/// The largest `|m| x` accepted (see [`MAX_INDEX`]).
pub const MAX_MX: f64 = 2e6;
/// The smallest `|m|` accepted. The series breaks down (NaN efficiencies
/// and phase function) once `|m|²` or `|m x|²` underflows: from
/// `|m| = 10⁻¹⁵⁴` at `x ≥ 1`, `10⁻¹³⁵` at `x = 10⁻²⁰`.
pub const MIN_INDEX: f64 = 1e-100;

fn valid(x: f64, m: Complex) -> bool {
    // x from 10⁻²⁰ (below, the real parts of the coefficients, of order
    // x⁶, approach f64's underflow and the efficiencies would lose them)
    // to 10⁵ (a few hundred thousand terms); 0 < n ≤ 1000, 0 ≤ k ≤ 1000,
    // 10⁻¹⁰⁰ ≤ |m|, |m| x ≤ 2·10⁶. Not m = 1: a sphere of the medium's own
    // index does not scatter (Q_sca = 0), and its phase function, the
    // scattered intensity over Q_sca, is 0/0.
    let size = libm::sqrt(m.norm_sqr());
    (1e-20..=1e5).contains(&x)
        && m.re > 0.0
        && m.re <= MAX_INDEX
        && (0.0..=MAX_INDEX).contains(&m.im)
        && size >= MIN_INDEX
        && size * x <= MAX_MX
        && !(m.re == 1.0 && m.im == 0.0)
}

/// Efficiencies and asymmetry of one sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Efficiencies {
    /// Extinction efficiency `Q_ext` (cross section over `π r²`).
    pub q_ext: f64,
    /// Scattering efficiency `Q_sca`.
    pub q_sca: f64,
    /// Backscattering efficiency `Q_back = 4 |S1(180°)|² / x²`.
    pub q_back: f64,
    /// Asymmetry parameter `g = <cos θ>`.
    pub g: f64,
}

/// The series of one sphere in the caller's buffer: its efficiencies, and
/// the amplitude functions at any angle.
#[derive(Debug)]
pub struct Mie<'a> {
    x: f64,
    /// `a_1, b_1, a_2, b_2, …, a_N, b_N`.
    ab: &'a [Complex],
    /// The efficiencies and `g`.
    pub efficiencies: Efficiencies,
}

impl<'a> Mie<'a> {
    /// Solves the sphere of size parameter `x ∈ [10⁻²⁰, 10⁵]` and relative
    /// index `m` (`0 < n ≤ 1000`, `0 ≤ k ≤ 1000`, `|m| ≥ 10⁻¹⁰⁰`,
    /// `|m| x ≤ 2·10⁶`, `m ≠ 1`: a sphere of the medium's own index does not
    /// scatter, so it has no phase function) into `buf` (at least
    /// [`buffer_len`] values). [`Error::Domain`] for other input, and for a
    /// sphere the series cannot represent: scattering that underflows to 0
    /// (`m` within about 10⁻¹⁵⁰ of 1 at the smallest `x`) or terms that
    /// overflow (a complex `m` of modulus below about 10⁻⁶⁰ at `x =
    /// 10⁻²⁰`); [`Error::Size`] for a short buffer.
    pub fn new(x: f64, m: Complex, buf: &'a mut [Complex]) -> Result<Self, Error> {
        let len = buffer_len(x, m).ok_or(Error::Domain)?;
        let buf = buf.get_mut(..len).ok_or(Error::Size)?;
        let (nmx, n_terms) = (start(x, m), terms(x));
        let Some((d, ab)) = buf.split_at_mut_checked(nmx + 1) else {
            return Err(Error::Size);
        };
        // R_n(mx) = D_n(mx) − (n + 1)/(mx), downward from R_nmx = 0 (see
        // `remainder_down`).
        let mx = m.scale(x);
        if let Some(last) = d.last_mut() {
            *last = Complex::default();
        }
        for n in (1..=nmx).rev() {
            let rn = d.get(n).copied().unwrap_or_default();
            if let Some(slot) = d.get_mut(n - 1) {
                *slot = remainder_down(n, mx, rn);
            }
        }
        // R_n(x) for real x where ψ_n decays (n ≥ x), downward, parked
        // in the real parts of the b_n slots until step n overwrites them.
        // Its start: 8 (x/2)^{1/3} + 16 terms past N, where the start error
        // has decayed below 10⁻¹³ by n = x (as for the complex start, eight
        // Airy widths); the complex recurrence's start, past |m| x, would
        // cost up to half as many real steps again as there are terms.
        let first_ratio = (libm::ceil(x) as usize).max(1);
        let real_start = (n_terms + (8.0 * libm::cbrt(0.5 * x)) as usize + 16).min(nmx);
        let mut rx = 0.0;
        for n in (first_ratio + 1..=real_start).rev() {
            rx = -x / ((2 * n + 1) as f64 + x * rx); // R_{n−1}
            if let Some(b) = ab.get_mut(2 * (n - 2) + 1).filter(|_| n - 1 <= n_terms) {
                b.re = rx;
            }
        }
        // ψ and χ (ξ = ψ − iχ) upward.
        let (s, c) = (libm::sin(x), libm::cos(x));
        let (mut psi0, mut psi1) = (c, s); // ψ_{-1}, ψ_0
        let (mut chi0, mut chi1) = (-s, c); // χ_{-1}, χ_0
        // m² and 1 − m² = (1 − m)(1 + m) (no cancellation as m → 1).
        let one = Complex::new(1.0, 0.0);
        let (m2, one_m2) = (m.mul(m), one.sub(m).mul(one.add(m)));
        let (mut q_ext, mut q_sca, mut g_sum, mut back) = (0.0, 0.0, 0.0, Complex::default());
        let (mut prev_a, mut prev_b) = (Complex::default(), Complex::default());
        for n in 1..=n_terms {
            let nf = n as f64;
            let f = (2.0 * nf - 1.0) / x;
            let chi = f * chi1 - chi0;
            let rn = d.get(n).copied().unwrap_or_default();
            let t = Terms::new(n, x, (m, m2, one_m2), rn);
            let (psi, num_a, num_b) = if n >= first_ratio {
                let rxn = ab.get(2 * (n - 1) + 1).map_or(f64::NAN, |b| b.re);
                let psi = psi1 / ((2.0 * nf + 1.0) / x + rxn);
                let (num_a, num_b) = t.ratio_numerators(rxn);
                (psi, num_a.scale(psi), num_b.scale(psi))
            } else {
                let psi = f * psi1 - psi0;
                let num = |t: Complex, s: Complex| t.scale(psi).sub(s.scale(psi1));
                (psi, num(t.a, m2), num(t.b, one))
            };
            // t ξ_n − s ξ_{n−1} = num − i (t χ_n − s χ_{n−1}), the product
            // by i written out (as a product, an infinite t χ_n made ∞·0 =
            // NaN).
            let den = |num: Complex, t: Complex, s: Complex| {
                let c = t.scale(chi).sub(s.scale(chi1));
                Complex::new(num.re + c.im, num.im - c.re)
            };
            let an = num_a.div(den(num_a, t.a, m2));
            let bn = num_b.div(den(num_b, t.b, one));
            let w = 2.0 * nf + 1.0;
            q_ext += w * (an.re + bn.re);
            q_sca += w * (an.norm_sqr() + bn.norm_sqr());
            g_sum += w / (nf * (nf + 1.0)) * an.mul(bn.conj()).re;
            if n > 1 {
                let k = nf - 1.0;
                g_sum += k * (k + 2.0) / (k + 1.0)
                    * (prev_a.mul(an.conj()).re + prev_b.mul(bn.conj()).re);
            }
            let sign = if n % 2 == 0 { 1.0 } else { -1.0 };
            back = back.add(an.sub(bn).scale(w * sign));
            if let Some([a, b]) = ab.get_mut(2 * (n - 1)..2 * n) {
                (*a, *b) = (an, bn);
            }
            (prev_a, prev_b) = (an, bn);
            (psi0, psi1) = (psi1, psi);
            (chi0, chi1) = (chi1, chi);
        }
        let x2 = x * x;
        let q_sca_v = 2.0 / x2 * q_sca;
        let efficiencies = Efficiencies {
            q_ext: 2.0 / x2 * q_ext,
            q_sca: q_sca_v,
            q_back: back.norm_sqr() / x2,
            g: 4.0 / x2 * g_sum / q_sca_v,
        };
        // No scattering to normalise the phase function by (m so close to 1,
        // 1 + 10⁻³⁰⁰ i at x = 10⁻²⁰, that every |a_n|², |b_n|² underflows,
        // as m = 1 itself, refused by `valid`, scatters nothing), or a
        // series that overflowed (a tiny complex m at a small x).
        let e = efficiencies;
        if !(q_sca_v > 0.0
            && [e.q_ext, e.q_sca, e.q_back, e.g]
                .iter()
                .all(|v| v.is_finite()))
        {
            return Err(Error::Domain);
        }
        Ok(Mie {
            x,
            ab: ab.get(..2 * n_terms).unwrap_or(&[]),
            efficiencies,
        })
    }

    /// The size parameter.
    pub fn x(&self) -> f64 {
        self.x
    }

    /// The series coefficients `a_1, b_1, …, a_N, b_N`.
    pub fn coefficients(&self) -> &'a [Complex] {
        self.ab
    }

    /// A solved sphere from the parts of an earlier solve: its size
    /// parameter ([`x`](Self::x)), coefficients
    /// ([`coefficients`](Self::coefficients)) and efficiencies, as a caller
    /// that keeps the coefficients in its own buffer stores them (the C
    /// layer's `sk_mie_f64` does). Parts of different solves give a sphere that
    /// is safe to use but describes no particle.
    pub fn from_parts(x: f64, ab: &'a [Complex], efficiencies: Efficiencies) -> Self {
        Mie {
            x,
            ab,
            efficiencies,
        }
    }

    /// The amplitude functions `(S1, S2)` at `μ = cos θ` (Bohren & Huffman
    /// eq. 4.74), by the `π_n`, `τ_n` recurrences. NaN for NaN `μ`; `μ`
    /// outside `[−1, 1]` is clamped.
    pub fn amplitudes(&self, mu: f64) -> (Complex, Complex) {
        let nan = Complex::new(f64::NAN, f64::NAN);
        if mu.is_nan() {
            return (nan, nan);
        }
        let mu = mu.clamp(-1.0, 1.0);
        let (mut pi_prev, mut pi) = (0.0f64, 1.0f64); // π_0, π_1
        let (mut s1, mut s2) = (Complex::default(), Complex::default());
        for (i, pair) in self.ab.chunks_exact(2).enumerate() {
            let n = (i + 1) as f64;
            let tau = n * mu * pi - (n + 1.0) * pi_prev;
            let w = (2.0 * n + 1.0) / (n * (n + 1.0));
            let &[an, bn] = pair else { continue };
            s1 = s1.add(an.scale(w * pi).add(bn.scale(w * tau)));
            s2 = s2.add(an.scale(w * tau).add(bn.scale(w * pi)));
            // π_{n+1} = ((2n + 1) μ π_n − (n + 1) π_{n−1}) / n
            let next = ((2.0 * n + 1.0) * mu * pi - (n + 1.0) * pi_prev) / n;
            (pi_prev, pi) = (pi, next);
        }
        (s1, s2)
    }

    /// The unpolarised phase function per steradian at `μ`, normalised over
    /// the sphere: `(|S1|² + |S2|²) / (2 π x² Q_sca)`.
    pub fn phase(&self, mu: f64) -> f64 {
        let (s1, s2) = self.amplitudes(mu);
        (s1.norm_sqr() + s2.norm_sqr())
            / (core::f64::consts::TAU * self.x * self.x * self.efficiencies.q_sca)
    }
}

/// Share of the tabulation angles spaced uniformly in `θ`; the rest are
/// spaced logarithmically from the forward direction ([`table_angle`]).
const UNIFORM_SHARE: f64 = 0.5;

/// The `j`-th of `count ≥ 2` scattering angles (radians, increasing from
/// 0 to π) at which [`Mie::tabulate`] evaluates the phase function of a
/// sphere of size parameter `x`: `θ_j` solves `t(θ) = j/(count − 1)` for
/// the share of angles below `θ`,
/// `t(θ) = w θ/π + (1 − w) ln(1 + θ x) / ln(1 + π x)`, `w = ½`: half the
/// angles uniform in `θ`, half uniform in `ln(1 + θ x)`, which crowds them
/// into the forward peak (about `1/x` wide; a grid uniform in `μ` or `θ`
/// needs `O(x²)` or `O(x)` points to resolve it): the first step is about
/// `ln(1 + π x) / (½ x (count − 1))`, and a share `½ ln 2 / ln(1 + π x)`
/// of the angles lies within `θ < 1/x` (4 % at `x = 1000`).
pub fn table_angle(x: f64, j: usize, count: usize) -> f64 {
    use core::f64::consts::PI;
    let t = j as f64 / (count.max(2) - 1) as f64;
    let w = UNIFORM_SHARE;
    let l_pi = libm::log1p(PI * x);
    if l_pi <= 1e-12 || l_pi.is_nan() || t <= 0.0 || t >= 1.0 {
        // x → 0: ln(1 + θx)/ln(1 + πx) → θ/π, the grid is uniform.
        return PI * t.clamp(0.0, 1.0);
    }
    let share = |th: f64| w * th / PI + (1.0 - w) * libm::log1p(th * x) / l_pi;
    let slope = |th: f64| w / PI + (1.0 - w) * x / ((1.0 + th * x) * l_pi);
    newton_bracketed(|th| (share(th) - t, slope(th)), 0.0, PI, PI * t)
}

/// Table sizes for a sphere of size parameter `x`: `(angles, intervals)`
/// = `(max(4000, 16 x), max(16384, 64 x))`, for [`Mie::tabulate`] and
/// [`Table::measured`](crate::Table::measured). Measured against the exact
/// phase function (`docs/measured/mie_table.md`, water, `m = 1.333`): total-variation
/// distance 2.8·10⁻⁶ at `x = 10`, 2.5·10⁻⁴ at `x = 100`, 1.2·10⁻³ at
/// `x = 1000`; `max |F(μ(u)) − u|` 6.5·10⁻⁷, 1.1·10⁻⁵, 6.8·10⁻⁶. The phase function of a
/// large sphere oscillates with a period of about `π/x` in `θ`, and the
/// table grows with `x` to resolve it: `2(intervals + 1)` values.
pub fn table_sizes(x: f64) -> (usize, usize) {
    let scaled = |k: f64, min: usize| ((k * x) as usize).max(min);
    (scaled(16.0, 4000), scaled(64.0, 16384))
}

impl Mie<'_> {
    /// Tabulates the phase function for [`Table::measured`](crate::Table::measured):
    /// `cos_theta[j] = cos θ_j` ([`table_angle`], so decreasing from 1 to
    /// −1) and `pdf[j]` the phase function per steradian there. Both slices
    /// the same length, at least 2 and at most about `10⁷` ([`Error::Size`]
    /// otherwise, also when the angles are too many to give distinct
    /// cosines). The table
    /// built from them takes the density as linear in `cos θ` between the
    /// angles; its accuracy as a function of the two sizes is measured in
    /// `tests/models/mie_table.rs` and `docs/measured/mie_table.md`.
    pub fn tabulate(&self, cos_theta: &mut [f64], pdf: &mut [f64]) -> Result<(), Error> {
        let count = cos_theta.len();
        if count < 2 || pdf.len() != count {
            return Err(Error::Size);
        }
        for (j, (c, p)) in cos_theta.iter_mut().zip(pdf.iter_mut()).enumerate() {
            let theta = table_angle(self.x, j, count);
            *c = if j + 1 == count {
                -1.0
            } else {
                libm::cos(theta)
            };
            *p = self.phase(*c);
        }
        Ok(())
    }
}

/// The refractive index of liquid water at vacuum wavelength
/// `wavelength_um` µm in `[0.182, 1.129]` (`None` outside): the real part
/// from Daimon & Masumura's four-term Sellmeier fit at 21.5 °C
/// (Appl. Opt. 46, 3811, 2007, table 3: `n² − 1 = Σ B_i λ² / (λ² − C_i)`,
/// λ in µm; 1.3345 at 550 nm); the imaginary part is left at 0 — below
/// 1.13 µm it stays under 3·10⁻⁶ (Hale & Querry 1973), which changes a
/// 50 µm droplet's `Q_abs` by under 0.2 % of `Q_ext` and its phase function
/// by less.
pub fn water(wavelength_um: f64) -> Option<Complex> {
    const B: [f64; 4] = [
        5.689093832e-1,
        1.719708856e-1,
        2.062501582e-2,
        1.123965424e-1,
    ];
    const C: [f64; 4] = [
        5.110301794e-3,
        1.825180155e-2,
        2.624158904e-2,
        1.067505178e1,
    ];
    if !(0.182..=1.129).contains(&wavelength_um) {
        return None;
    }
    let l2 = wavelength_um * wavelength_um;
    let n2 = 1.0 + B.iter().zip(C).map(|(b, c)| b * l2 / (l2 - c)).sum::<f64>();
    Some(Complex::new(libm::sqrt(n2), 0.0))
}
