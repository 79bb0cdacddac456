//! The one-sample Kolmogorov–Smirnov test.

use super::nan_max;

/// KS statistic `D = sup |F_n(x) − F(x)|` of `samples` against the CDF `f`
/// (sorts `samples`).
pub fn ks_statistic(samples: &mut [f64], f: impl Fn(f64) -> f64) -> f64 {
    samples.sort_by(f64::total_cmp);
    let n = samples.len() as f64;
    samples
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            let fx = f(x);
            nan_max((fx - i as f64 / n).abs(), ((i + 1) as f64 / n - fx).abs())
        })
        .fold(0.0, nan_max)
}

/// The asymptotic critical value of D for significance `alpha` and `n`
/// samples: `sqrt(−ln(α/2) / (2n))`.
pub fn ks_critical(alpha: f64, n: usize) -> f64 {
    (-(alpha / 2.0).ln() / (2.0 * n as f64)).sqrt()
}

/// KS for a sampler whose results are rounded to the floats of their
/// precision, where a narrow lobe puts whole atoms of probability on a few
/// floats near a pole (at `1 − g = 10⁻⁹` most of a Draine lobe lies
/// within one ulp of μ = 1), which [`ks_statistic`] counts as a jump of
/// the empirical CDF that `F` does not make. A correctly rounded sample
/// `v` comes from `(prev v, next v)`, so the empirical CDF at each
/// distinct `v` lies in `[F(prev v), F(next v)]` and its left limit in
/// `[F(prev v), F(v)]` up to sampling noise; `D` is the largest distance
/// outside those brackets (`prev`/`next` the neighbouring floats of the
/// samples' precision, given as `step(v, ±1)`; 0 for a continuous `F`
/// sampled exactly, where it reduces to the usual statistic). Sorts
/// `samples`.
pub fn ks_rounded(
    samples: &mut [f64],
    f: impl Fn(f64) -> f64,
    step: impl Fn(f64, i32) -> f64,
) -> f64 {
    samples.sort_by(f64::total_cmp);
    let n = samples.len();
    let mut d = 0.0f64;
    let mut i = 0;
    while i < n {
        let v = samples[i];
        // From `i + 1`: a NaN equals nothing, not even itself, and would
        // hold `i` in place.
        let mut j = i + 1;
        while j < n && samples[j] == v {
            j += 1;
        }
        // #{< v}/n and #{≤ v}/n.
        let (below, upto) = (i as f64 / n as f64, j as f64 / n as f64);
        let (lo, at, hi) = (f(step(v, -1)), f(v), f(step(v, 1)));
        for e in [lo - below, below - at, lo - upto, upto - hi] {
            d = nan_max(d, e);
        }
        i = j;
    }
    d
}
