//! Pearson's chi² test of a direction sampler against its pdf, in the style of
//! Mitsuba 3's `chi2.py`: histogram samples over (cos θ, φ) about `w_in`,
//! integrate the pdf over the same cells, pool cells with expected count < 5,
//! and compare the p-value with a significance level corrected (Šidák) for
//! the number of chi² tests in the suite.
//!
//! The azimuth frame here is built by Gram–Schmidt, independently of the
//! crate's `onb`, so a frame bug in the crate cannot cancel against the test.

/// Significance level of the whole suite, fixed before any result was seen.
pub const SIGNIFICANCE: f64 = 0.01;
/// An upper bound on the number of chi² tests in the suite, for the Šidák
/// correction (each test is held to `1 − (1 − 0.01)^(1/1000) ≈ 1.0·10⁻⁵`).
pub const TESTS_IN_SUITE: f64 = 1000.0;
/// Cells in cos θ and in φ.
pub const N_MU: usize = 50;
pub const N_PHI: usize = 20;

/// The per-test threshold on the p-value.
pub fn threshold() -> f64 {
    1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / TESTS_IN_SUITE)
}

#[derive(Debug)]
pub struct Chi2 {
    pub stat: f64,
    pub dof: usize,
    pub p_value: f64,
    /// Samples that fell in cells the pdf gives zero probability, and
    /// directions that are not unit vectors (NaN among them).
    pub impossible: u64,
}

impl Chi2 {
    pub fn passes(&self) -> bool {
        self.impossible == 0 && self.p_value > threshold()
    }
}

fn norm(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A frame about `w` by Gram–Schmidt against the least-aligned axis.
fn frame(w: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let helper = if w[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let d = dot(helper, w);
    let b1 = norm([
        helper[0] - d * w[0],
        helper[1] - d * w[1],
        helper[2] - d * w[2],
    ]);
    (b1, cross(w, b1))
}

/// Adaptive Simpson integration of `f` over `[a, b]` to absolute tolerance
/// `tol` (depth at most 30 below each of 16 starting spans).
pub fn integrate(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    /// One interval: its ends and the values of `f` at its ends and middle.
    #[derive(Clone, Copy)]
    struct Span {
        a: f64,
        b: f64,
        fa: f64,
        fm: f64,
        fb: f64,
    }
    fn simpson(s: Span) -> f64 {
        (s.b - s.a) / 6.0 * (s.fa + 4.0 * s.fm + s.fb)
    }
    fn rec(f: &dyn Fn(f64) -> f64, s: Span, whole: f64, tol: f64, depth: u32) -> f64 {
        let m = 0.5 * (s.a + s.b);
        let left = Span {
            a: s.a,
            b: m,
            fa: s.fa,
            fm: f(0.5 * (s.a + m)),
            fb: s.fm,
        };
        let right = Span {
            a: m,
            b: s.b,
            fa: s.fm,
            fm: f(0.5 * (m + s.b)),
            fb: s.fb,
        };
        let (l, r) = (simpson(left), simpson(right));
        let delta = l + r - whole;
        // (A span one float wide has no finer halves: its midpoint rounds
        // onto an end. Halving it anyway, an infinite end value made both
        // halves NaN down to the depth limit, 2³⁰ evaluations.)
        let unresolved = !(s.a < m && m < s.b);
        // A non-finite difference (an infinite or NaN value of `f`) stays
        // so at every depth: returned at once, the caller's check fails in
        // a moment instead of after 2³⁰ evaluations (a mutated Schlick
        // norm of 1/k, infinite at k = 0, held the contract for minutes).
        let hopeless = !delta.is_finite();
        if depth == 0 || unresolved || hopeless || delta.abs() <= 15.0 * tol {
            l + r + delta / 15.0
        } else {
            rec(f, left, l, tol / 2.0, depth - 1) + rec(f, right, r, tol / 2.0, depth - 1)
        }
    }
    // Started on 16 equal spans, not one: from one, the first halvings
    // can agree by chance on a function whose bump falls between their
    // points, and the recursion stops there (a Schlick lobe at
    // 1 − k = 1.2·10⁻⁷ on the log scale of `checks::graded`: its mean
    // cosine 2.3·10⁻⁸ off, the CDF's mass right).
    const SPANS: usize = 16;
    let at = |i: usize| a + (b - a) * (i as f64 / SPANS as f64);
    (0..SPANS)
        .map(|i| {
            let (x0, x1) = (at(i), if i + 1 == SPANS { b } else { at(i + 1) });
            let s = Span {
                a: x0,
                b: x1,
                fa: f(x0),
                fm: f(0.5 * (x0 + x1)),
                fb: f(x1),
            };
            rec(f, s, simpson(s), tol / SPANS as f64, 30)
        })
        .sum()
}

/// Runs the test: `sample()` returns unit directions, `pdf(μ)` is the density
/// per steradian as a function of `μ = dot(w, w_in)`.
pub fn chi2_directions(
    pdf: &dyn Fn(f64) -> f64,
    w_in: [f64; 3],
    n_samples: usize,
    sample: impl FnMut() -> [f64; 3],
) -> Chi2 {
    let p_mu = |lo, hi| std::f64::consts::TAU * integrate(pdf, lo, hi, 1e-10);
    chi2_directions_by_cells(&p_mu, w_in, n_samples, sample)
}

/// As [`chi2_directions`], with the probability of each `cos θ` cell
/// `P(lo < μ ≤ hi)` given directly (from a CDF: for densities that are
/// infinite at an end, which quadrature cannot take).
pub fn chi2_directions_by_cells(
    p_mu: &dyn Fn(f64, f64) -> f64,
    w_in: [f64; 3],
    n_samples: usize,
    mut sample: impl FnMut() -> [f64; 3],
) -> Chi2 {
    let w_in = norm(w_in);
    let (b1, b2) = frame(w_in);
    let mut observed = vec![0u64; N_MU * N_PHI];
    let mut not_unit = 0;
    for _ in 0..n_samples {
        let w = sample();
        // A NaN would land in cell (0, 0) (`NaN as usize` is 0) and a few
        // of them pass unseen: a direction that is not a unit vector
        // (f32's are within 10⁻⁶) counts as impossible.
        let off = (dot(w, w) - 1.0).abs();
        if off > 1e-5 || off.is_nan() {
            not_unit += 1;
            continue;
        }
        let mu = dot(w, w_in).clamp(-1.0, 1.0);
        let phi = dot(w, b2).atan2(dot(w, b1)) + std::f64::consts::PI;
        let i = (((mu + 1.0) * 0.5 * N_MU as f64) as usize).min(N_MU - 1);
        let j = ((phi / std::f64::consts::TAU * N_PHI as f64) as usize).min(N_PHI - 1);
        observed[i * N_PHI + j] += 1;
    }
    let mut expected = vec![0.0; N_MU * N_PHI];
    for i in 0..N_MU {
        let (lo, hi) = (
            -1.0 + 2.0 * i as f64 / N_MU as f64,
            -1.0 + 2.0 * (i + 1) as f64 / N_MU as f64,
        );
        let p = p_mu(lo, hi);
        for j in 0..N_PHI {
            expected[i * N_PHI + j] = n_samples as f64 * p / N_PHI as f64;
        }
    }
    let mut c = pearson(&observed, &expected);
    c.impossible += not_unit;
    c
}

/// Pearson's statistic with cells of expected count < 5 pooled into one.
pub fn pearson(observed: &[u64], expected: &[f64]) -> Chi2 {
    let (mut stat, mut cells) = (0.0, 0usize);
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    let mut impossible = 0;
    for (&o, &e) in observed.iter().zip(expected) {
        if e <= 0.0 {
            impossible += o;
        } else if e < 5.0 {
            pool_o += o as f64;
            pool_e += e;
        } else {
            stat += (o as f64 - e).powi(2) / e;
            cells += 1;
        }
    }
    if pool_e >= 5.0 {
        stat += (pool_o - pool_e).powi(2) / pool_e;
        cells += 1;
    }
    let dof = cells.saturating_sub(1).max(1);
    Chi2 {
        stat,
        dof,
        p_value: gamma_q(dof as f64 / 2.0, stat / 2.0),
        impossible,
    }
}

/// ln Γ(x), Lanczos (g = 7, n = 9), x > 0.
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, &c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Upper regularised incomplete gamma `Q(a, x)`: the chi² p-value for
/// `a = dof/2`, `x = stat/2` (series below `a + 1`, continued fraction above).
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let gln = ln_gamma(a);
    if x < a + 1.0 {
        let (mut sum, mut del, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - gln).exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (-x + a * x.ln() - gln).exp() * h
    }
}
