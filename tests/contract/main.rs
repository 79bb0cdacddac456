//! The contract every phase model keeps, run over the registry of every
//! model (`registry.rs`), in f32 and f64: the constructor refuses exactly
//! its bad parameters, the density is normalised and its mean cosine right,
//! `cdf` integrates `pdf` (in f64; the f32 density and CDF follow the f64
//! ones at every f32 argument), the inverse is monotone and inverts `cdf`,
//! sampled directions follow the density (chi² over the sphere),
//! `sample_dir` reports the density of what it drew, the batch and in-range
//! forms give `sample_cos`'s bits, the density is read at the pole within 8
//! ulp beyond it and is 0 further out, the reported parameters rebuild the
//! model (another count refused), f32 follows f64, and golden bits hold; a
//! cast to f32 keeps a parameter below 1 below it. The last test shows the
//! checks catch a sampler that is wrong by a 2 % slope. `reach.rs` finds
//! each constructor's accepted range to the bit, holds it to the docs, and
//! runs the checks at its ends; `media_reach.rs` does the same for the
//! media's constructors and calls.

#[path = "../common/mod.rs"]
mod common;

mod batch;
mod checks;
mod media_reach;
mod properties;
#[macro_use]
mod registry;
mod reach;
mod table;

use checks::Check;
use registry::{Model, models};
use scatterkit::{Error, Phase, PhaseFunction, Real};

/// `(model, parameter set)` for every set of every model.
fn cases() -> Vec<(Model, &'static [f64])> {
    models()
        .into_iter()
        .flat_map(|m| m.sets.iter().map(move |&s| (m, s)))
        .collect()
}

/// Runs `check` on every case (in parallel) and fails listing every
/// failure.
fn on_every_case(what: &str, check: impl Fn(&Model, &[f64]) -> Check + Sync) {
    let cases = cases();
    let failures: Vec<String> = common::map_parallel(&cases, |(m, set)| {
        check(m, set)
            .err()
            .map(|e| format!("{} {set:?}: {e}", m.name))
    })
    .into_iter()
    .flatten()
    .collect();
    assert!(failures.is_empty(), "{what}:\n{}", failures.join("\n"));
}

/// `a` for f32 and `b` for f64, each failure marked with its precision.
fn both(a: Check, b: Check) -> Check {
    a.map_err(|e| format!("f32: {e}"))
        .and(b.map_err(|e| format!("f64: {e}")))
}

/// Both precisions of a case.
fn built(m: &Model, set: &[f64]) -> (Phase<f32>, Phase<f64>) {
    // The f64 model from the f32-rounded parameters, so the two describe
    // the same density.
    let rounded: Vec<f64> = set.iter().map(|&x| x as f32 as f64).collect();
    ((m.f32)(set).unwrap(), (m.f64)(&rounded).unwrap())
}

#[test]
fn the_registry_holds_every_model() {
    let names: Vec<&str> = models().iter().map(|m| m.name).collect();
    for want in [
        "isotropic",
        "rayleigh",
        "depolarised rayleigh",
        "henyey-greenstein",
        "draine",
        "cornette-shanks",
        "fog",
        "two-lobe hg",
        "gegenbauer",
        "fournier-forand",
        "schlick",
    ] {
        assert!(names.contains(&want), "{want} is not registered");
    }
    // Every model of the library's registry (the tags 1..=LAST_TAG) is
    // reached by some model! line, so a model added to the library without
    // one fails here.
    let mut tags = std::collections::BTreeSet::new();
    for m in models() {
        for set in m.sets {
            let p = (m.f64)(set).unwrap();
            tags.insert(p.tag());
        }
    }
    let all: std::collections::BTreeSet<u32> = (1..=Phase::<f64>::LAST_TAG).collect();
    assert_eq!(tags, all, "a model of the registry has no model! line");
}

#[test]
fn constructors_accept_the_sets_and_refuse_the_bad_ones() {
    for m in models() {
        for set in m.sets {
            assert!(
                (m.f32)(set).is_ok() && (m.f64)(set).is_ok(),
                "{} {set:?}",
                m.name
            );
        }
        for set in m.bad {
            assert_eq!(
                (m.f32)(set).err(),
                Some(Error::Domain),
                "{} f32 {set:?}",
                m.name
            );
            assert_eq!(
                (m.f64)(set).err(),
                Some(Error::Domain),
                "{} f64 {set:?}",
                m.name
            );
        }
    }
}

#[test]
fn densities_are_normalised_with_their_mean_cosine() {
    on_every_case("normalisation", |m, s| {
        let (a, b) = built(m, s);
        both(
            checks::f32_density_follows_f64(&a, &b),
            checks::normalised(&b),
        )
    });
}

#[test]
fn cdf_integrates_the_density() {
    on_every_case("cdf", |m, s| {
        let (a, b) = built(m, s);
        let _ = a;
        checks::cdf_is_integral(&b)
    });
}

#[test]
fn inverses_are_monotone_and_invert_the_cdf() {
    on_every_case("inverse", |m, s| {
        let (a, b) = built(m, s);
        both(
            checks::inverse_monotone(&a, m.mu_tol.0),
            checks::inverse_monotone(&b, m.mu_tol.1),
        )
    });
}

#[test]
fn batches_and_in_range_forms_give_the_scalar_bits() {
    on_every_case("batch forms", |m, s| {
        let (a, b) = built(m, s);
        both(checks::batch_forms_agree(&a), checks::batch_forms_agree(&b))
    });
}

#[test]
fn densities_read_the_poles_within_8_ulp_and_nothing_beyond() {
    on_every_case("support", |m, s| {
        let (a, b) = built(m, s);
        both(checks::pdf_support(&a), checks::pdf_support(&b))
    });
}

#[test]
fn params_rebuild_the_model_and_other_counts_are_refused() {
    on_every_case("params", |m, s| {
        let (a, b) = built(m, s);
        both(checks::params_rebuild(&a), checks::params_rebuild(&b))
    });
}

/// A parameter that must stay below 1 in magnitude, cast to f32 from an
/// f64 that rounds onto ±1 there, becomes the largest f32 below 1 (`1 −
/// 2⁻²⁴`), with its sign, in every model that has one.
#[test]
fn a_cast_keeps_a_parameter_below_one_at_the_largest_float_below_it() {
    let near = 1.0 - 1e-9;
    let top = 1.0 - f32::EPSILON as f64 / 2.0;
    let cases = [
        (Phase::henyey_greenstein(near), 0, top),
        (Phase::henyey_greenstein(-near), 0, -top),
        (Phase::draine(-near, 2.0), 0, -top),
        (Phase::gegenbauer(0.5, near), 1, top),
        (Phase::rayleigh_depolarized(near), 0, top),
        (
            scatterkit::phase::schlick::Schlick::new(-near).map(Phase::from),
            0,
            -top,
        ),
        (Phase::fog(near, -near, 1.0, 0.5), 0, top),
        (Phase::fog(near, -near, 1.0, 0.5), 1, -top),
    ];
    for (p, i, want) in cases {
        let p = p.unwrap();
        let (_, n, q) = p.cast::<f32>().params();
        assert!(i < n, "{p:?}");
        assert_eq!(q[i] as f64, want, "{p:?}, parameter {i}");
    }
}

/// A Gegenbauer `α` just above −½ whose f32 rounds onto −½ (outside the
/// domain) becomes an f32 just above it, which the f32 constructor takes.
#[test]
fn a_cast_keeps_the_gegenbauer_alpha_above_minus_one_half() {
    for a in [-0.5 + 1e-9, -0.5 + 1e-8] {
        let p = Phase::gegenbauer(a, 0.3).unwrap();
        let (_, _, q) = p.cast::<f32>().params();
        assert!(q[0] > -0.5 && q[0] < -0.499_999_7, "{a}: α {}", q[0]);
        assert!(Phase::<f32>::gegenbauer(q[0], q[1]).is_ok(), "{a}: {q:?}");
    }
}

#[test]
fn directions_follow_the_density_over_the_sphere() {
    on_every_case("chi²", |m, s| {
        let (a, b) = built(m, s);
        let cdf64 = |mu: f64| b.cdf(mu);
        both(
            checks::chi2_sphere(&a, &cdf64, 1000),
            checks::chi2_sphere(&b, &cdf64, 2000),
        )
    });
}

#[test]
fn sample_dir_reports_the_density_of_its_direction() {
    on_every_case("sample_dir", |m, s| {
        let (a, b) = built(m, s);
        both(
            checks::sample_dir_consistent(&a, &b, 1e-4),
            checks::sample_dir_consistent(&b, &b, 1e-9),
        )
    });
}

#[test]
fn f32_follows_f64() {
    on_every_case("f32 against f64", |m, s| {
        let (a, b) = built(m, s);
        checks::f32_follows_f64(&a, &b, 1e-6)
    });
}

#[test]
fn golden_bits_hold() {
    for m in models() {
        let (name, set) = m.golden;
        let (a, b) = ((m.f32)(set).unwrap(), (m.f64)(set).unwrap());
        if let Err(e) = checks::golden_bits(&a, &b, name) {
            panic!("{}: {e}", m.name);
        }
    }
}

/// A model whose sampler is wrong by a slope `k`: `μ(u + k u (1 − u))` in
/// place of `μ(u)`, with the inner model's density and CDF.
struct Sloped<P>(P, f64);

impl<T: Real, P: PhaseFunction<T>> PhaseFunction<T> for Sloped<P> {
    fn pdf(&self, mu: T) -> T {
        self.0.pdf(mu)
    }
    fn cdf(&self, mu: T) -> T {
        self.0.cdf(mu)
    }
    fn sample_cos(&self, u: T) -> T {
        let k = T::from_f64(self.1);
        self.0.sample_cos(u + k * u * (T::ONE - u))
    }
    fn mean_cosine(&self) -> T {
        self.0.mean_cosine()
    }
}

/// The contract fails a sampler sloped by 2 %, for a smooth model and a
/// sharply peaked one: the inverse's check and the golden bits each catch
/// it, and the checks of the density alone, which the slope does not
/// touch, still pass. Chi² over the sphere (10⁶ samples in 1000 cells)
/// catches a 10 % slope in both precisions; a 2 % one moves a cell by a
/// fraction of its standard deviation, and it need not.
#[test]
fn the_contract_catches_a_sloped_sampler() {
    for m in models()
        .into_iter()
        .filter(|m| ["henyey-greenstein", "fournier-forand"].contains(&m.name))
    {
        let (name, set) = m.golden;
        let (a, b) = ((m.f32)(set).unwrap(), (m.f64)(set).unwrap());
        let (sa, sb) = (Sloped(a, 0.02), Sloped(b, 0.02));
        let cdf64 = |mu: f64| b.cdf(mu);
        assert!(
            checks::normalised(&sb).is_ok(),
            "{}: the density is untouched",
            m.name
        );
        assert!(
            checks::inverse_monotone(&sa, m.mu_tol.0).is_err(),
            "{}: inverse f32",
            m.name
        );
        assert!(
            checks::inverse_monotone(&sb, m.mu_tol.1).is_err(),
            "{}: inverse f64",
            m.name
        );
        assert!(
            checks::golden_bits(&sa, &sb, name).is_err(),
            "{}: golden",
            m.name
        );
        let (ta, tb) = (Sloped(a, 0.1), Sloped(b, 0.1));
        assert!(
            checks::chi2_sphere(&ta, &cdf64, 1000).is_err(),
            "{}: chi² f32",
            m.name
        );
        assert!(
            checks::chi2_sphere(&tb, &cdf64, 2000).is_err(),
            "{}: chi² f64",
            m.name
        );
    }
}
