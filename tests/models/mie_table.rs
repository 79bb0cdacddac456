//! Sampling Mie: the phase function tabulated at `Mie::tabulate`'s angles
//! and inverted by `Table::measured`, against the exact Mie phase function.
//!
//! For each size parameter and pair of sizes (angles tabulated, table
//! intervals): the largest `|F(μ(u)) − u|` over `u` (F the exact CDF, μ(u)
//! the table's sample) and the total-variation distance `½ ∫ |p_table −
//! p| dω`, written to `docs/measured/mie_table.md` by `SK_BLESS=1`. At the sizes
//! `mie::table_sizes` recommends, `|F(μ(u)) − u| ≤ 10⁻³` and `TV ≤ 2·10⁻³`
//! for x up to 1000. (The first bound tried, TV ≤ 10⁻³ with 4000 angles
//! and 4096 intervals at every x, failed at x = 100 and 1000: the sizes
//! must grow with x, as the table shows.) And a chi² test of the sampler
//! against the exact Mie CDF in 50 equiprobable bins, 10⁶ samples, at the
//! suite's significance.

use crate::common;
use crate::common::nan_max;

use common::chi2::{pearson, threshold};
use common::rng;
use rand_core::Rng;
use scatterkit::mie::{Complex, Mie, buffer_len, table_sizes};
use scatterkit::{Table, TableKind};

/// The exact phase function on a fine grid in θ, and its CDF in `μ`
/// (from the forward direction): `F(θ) = 2π ∫_0^θ p sin θ' dθ'`.
struct Reference {
    theta: Vec<f64>,
    pdf: Vec<f64>,
    /// Mass from θ = 0 (the table's `u` runs from μ = −1, so its CDF is
    /// `1 − forward`).
    forward: Vec<f64>,
}

impl Reference {
    fn new(mie: &Mie, x: f64) -> Reference {
        // Steps of 0.01/x, at least 20 000 over [0, π].
        let steps = ((std::f64::consts::PI * x / 0.01) as usize).max(20_000);
        let h = std::f64::consts::PI / steps as f64;
        let theta: Vec<f64> = (0..=steps).map(|i| i as f64 * h).collect();
        let pdf: Vec<f64> = theta.iter().map(|t| mie.phase(t.cos())).collect();
        let mut forward = vec![0.0; steps + 1];
        for i in 1..=steps {
            let f = |k: usize| pdf[k] * theta[k].sin();
            forward[i] = forward[i - 1] + std::f64::consts::TAU * 0.5 * h * (f(i - 1) + f(i));
        }
        let total = forward[steps];
        assert!((total - 1.0).abs() < 1e-4, "normalisation {total}");
        forward.iter_mut().for_each(|v| *v /= total);
        Reference {
            theta,
            pdf,
            forward,
        }
    }
    /// The CDF from μ = −1 at μ (linear in θ between grid points).
    fn cdf(&self, mu: f64) -> f64 {
        let t = mu.clamp(-1.0, 1.0).acos();
        let h = self.theta[1];
        let i = ((t / h) as usize).min(self.theta.len() - 2);
        let w = (t - self.theta[i]) / h;
        1.0 - (self.forward[i] * (1.0 - w) + self.forward[i + 1] * w)
    }
}

struct Accuracy {
    cdf_error: f64,
    tv: f64,
}

fn accuracy(reference: &Reference, table: &Table<f64>) -> Accuracy {
    let mut cdf_error = 0.0f64;
    let points = 200_000;
    for k in 0..=points {
        let u = k as f64 / points as f64;
        cdf_error = nan_max(cdf_error, (reference.cdf(table.sample_cos(u)) - u).abs());
    }
    let h = reference.theta[1];
    let mut tv = 0.0;
    for (i, (&t, &p)) in reference.theta.iter().zip(&reference.pdf).enumerate() {
        let w = if i == 0 || i + 1 == reference.theta.len() {
            0.5
        } else {
            1.0
        };
        tv += w * (table.pdf(t.cos()) - p).abs() * t.sin();
    }
    Accuracy {
        cdf_error,
        tv: 0.5 * std::f64::consts::TAU * tv * h,
    }
}

/// TV of the density linear in μ between the tabulated angles (what the
/// angles alone allow, before the inversion).
fn angles_tv(reference: &Reference, c: &[f64], p: &[f64]) -> f64 {
    // Normalise the linear density as Table::measured does.
    let area: f64 = (1..c.len())
        .map(|j| 0.5 * (c[j - 1] - c[j]) * (p[j - 1] + p[j]))
        .sum();
    let lin = |mu: f64| {
        let j = c.partition_point(|&v| v > mu).clamp(1, c.len() - 1);
        let w = (mu - c[j]) / (c[j - 1] - c[j]);
        (p[j] + w * (p[j - 1] - p[j])) / (std::f64::consts::TAU * area)
    };
    let h = reference.theta[1];
    let mut tv = 0.0;
    for (&t, &q) in reference.theta.iter().zip(&reference.pdf) {
        tv += (lin(t.cos()) - q).abs() * t.sin();
    }
    0.5 * std::f64::consts::TAU * tv * h
}

fn sphere(x: f64) -> Vec<Complex> {
    vec![Complex::default(); buffer_len(x, WATER).unwrap()]
}

const WATER: Complex = Complex::new(1.333, 1e-8);

fn build(mie: &Mie, angles: usize, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut c, mut p) = (vec![0.0; angles], vec![0.0; angles]);
    mie.tabulate(&mut c, &mut p).unwrap();
    (c, p, vec![0.0; TableKind::Measured.len(n).unwrap()])
}

#[test]
fn table_accuracy_against_exact_mie() {
    let mut doc = String::from(
        "| x | angles | intervals | max abs F(mu(u)) - u | TV | TV of the angles alone |\n\
         |---|---:|---:|---:|---:|---:|\n",
    );
    for x in [10.0, 100.0, 1000.0] {
        let mut buf = sphere(x);
        let mie = Mie::new(x, WATER, &mut buf).unwrap();
        let reference = Reference::new(&mie, x);
        let recommended = table_sizes(x);
        let mut sizes = vec![
            (1000, 1024),
            (4000, 4096),
            (16000, 16384),
            (16000, 65536),
            (64000, 65536),
        ];
        if !sizes.contains(&recommended) {
            sizes.push(recommended);
        }
        for (angles, n) in sizes {
            let (c, p, mut tbuf) = build(&mie, angles, n);
            let table = Table::measured(&c, &p, &mut tbuf, n).unwrap();
            let a = accuracy(&reference, &table);
            let floor = angles_tv(&reference, &c, &p);
            let mark = if (angles, n) == recommended {
                " (table_sizes)"
            } else {
                ""
            };
            doc += &format!(
                "| {x} | {angles} | {n}{mark} | {:.1e} | {:.1e} | {floor:.1e} |\n",
                a.cdf_error, a.tv
            );
            if (angles, n) == recommended {
                assert!(a.cdf_error <= 1e-3, "x {x}: |F(mu(u)) - u| {}", a.cdf_error);
                assert!(a.tv <= 2e-3, "x {x}: TV {}", a.tv);
            }
        }
    }
    println!("{doc}");
    if std::env::var_os("SK_BLESS").is_some() {
        let doc = format!(
            "# Mie tables: accuracy against size\n\nGenerated by `SK_BLESS=1 cargo test --release \
             --test models mie_table::`; do not edit. A water sphere (`m = 1.333 + 10⁻⁸ i`) of size \
             parameter `x`: its phase function tabulated at `angles` angles (`Mie::tabulate`, \
             `sk_mie_tabulate_f64`) and inverted into a table of `intervals` intervals \
             (`Table::measured`, `sk_table_new_measured_f64`), against the exact phase function on \
             a grid of steps `0.01/x` in θ. `F` is the exact CDF, `μ(u)` the table's sample; \
             TV is `½ ∫ |p_table − p| dω`; the last column is the distance of the density \
             linear between the angles, before the inversion. The phase function of a large \
             sphere oscillates with period about `π/x` in θ: the sizes must grow with `x`.\n\n{doc}"
        );
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/measured/mie_table.md");
        std::fs::write(path, doc).unwrap();
    }
}

#[test]
fn chi2_of_the_mie_table_sampler() {
    let bins = 50;
    for x in [30.0, 300.0] {
        let mut buf = sphere(x);
        let mie = Mie::new(x, WATER, &mut buf).unwrap();
        let reference = Reference::new(&mie, x);
        let (angles, n) = table_sizes(x);
        let (c, p, mut tbuf) = build(&mie, angles, n);
        let table = Table::measured(&c, &p, &mut tbuf, n).unwrap();
        let mut r = rng(0x3141_5926 + x as u64);
        let samples = 1_000_000;
        let mut observed = vec![0u64; bins];
        for _ in 0..samples {
            let u = (r.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            let f = reference.cdf(table.sample_cos(u));
            // NaN would land in bin 0 (`NaN as usize` is 0).
            assert!((0.0..=1.0).contains(&f), "x = {x}, u = {u}: F = {f}");
            observed[((f * bins as f64) as usize).min(bins - 1)] += 1;
        }
        let expected = vec![samples as f64 / bins as f64; bins];
        let res = pearson(&observed, &expected);
        println!("x {x}: {res:?}");
        assert!(res.p_value > threshold(), "x {x}: {res:?}");
    }
}
