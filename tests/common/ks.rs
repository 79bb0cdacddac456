//! The one-sample Kolmogorov–Smirnov test.

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
            (fx - i as f64 / n)
                .abs()
                .max(((i + 1) as f64 / n - fx).abs())
        })
        .fold(0.0, f64::max)
}

/// The asymptotic critical value of D for significance `alpha` and `n`
/// samples: `sqrt(−ln(α/2) / (2n))`.
pub fn ks_critical(alpha: f64, n: usize) -> f64 {
    (-(alpha / 2.0).ln() / (2.0 * n as f64)).sqrt()
}
