//! The fog and two-lobe HG with a Dirac lobe: an HG lobe at `|g| = 1`
//! (the HG lobe at `|g_HG| = 1`, or the first lobe of a two-lobe HG,
//! `α = 0`, at `|g_D| = 1`), which transport codes pass for a background
//! medium. Such a mixture is up to two point masses at `μ = ±1` and at
//! most one continuous lobe `C` of weight `w_C`:
//! `F(μ) = m₋·[μ ≥ −1] + w_C F_C(μ) + m₊·[μ ≥ 1]`, whose exact inverse is
//! `−1` for `u ≤ m₋`, `+1` for `u > 1 − m₊`, and `F_C⁻¹((u − m₋)/w_C)`
//! between. The density is each lobe's, weighted, a lobe of weight 0
//! adding nothing (not `0·∞`); the paper's lobe choice is the fog's own.

use super::super::draine::Draine;
use super::super::function::PhaseFunction;
use super::super::hg::HenyeyGreenstein;
use crate::math::real::Real;

/// One lobe of the mixture: HG (`α = 0`, Dirac at `|g| = 1`) or Draine.
#[derive(Clone, Copy)]
enum Lobe<T> {
    Hg(HenyeyGreenstein<T>),
    Draine(Draine<T>),
}

impl<T: Real> Lobe<T> {
    fn new(g: T, alpha: T) -> Self {
        if alpha == T::ZERO {
            Lobe::Hg(HenyeyGreenstein::from_g(g))
        } else {
            Lobe::Draine(Draine::lobe(g, alpha))
        }
    }
    /// The pole this lobe sits on, if it is a Dirac lobe.
    fn pole(&self, g: T) -> Option<T> {
        match self {
            Lobe::Hg(_) if g == T::ONE || g == -T::ONE => Some(g),
            _ => None,
        }
    }
    fn pdf(&self, mu: T) -> T {
        match self {
            Lobe::Hg(h) => h.pdf(mu),
            Lobe::Draine(d) => d.pdf(mu),
        }
    }
    fn cdf(&self, mu: T) -> T {
        match self {
            Lobe::Hg(h) => h.cdf(mu),
            Lobe::Draine(d) => d.cdf(mu),
        }
    }
    fn sample_cos_sin(&self, u: T) -> (T, T) {
        match self {
            Lobe::Hg(h) => h.sample_cos_sin(u),
            Lobe::Draine(d) => d.sample_cos_sin(u),
        }
    }
}

/// A fog `(1 − w_D) HG(g_HG) + w_D Draine(g_D, α)` one of whose lobes is a
/// Dirac lobe, as two weighted lobes.
pub(super) struct DiracFog<T> {
    /// `(weight, lobe, g)`: the HG lobe, then the Draine lobe.
    lobes: [(T, Lobe<T>, T); 2],
}

/// Whether a fog with these parameters has a Dirac lobe (module docs).
pub(super) fn has_dirac_lobe<T: Real>(g_hg: T, g_d: T, alpha: T) -> bool {
    let pole = |g: T| g == T::ONE || g == -T::ONE;
    pole(g_hg) || (alpha == T::ZERO && pole(g_d))
}

impl<T: Real> DiracFog<T> {
    pub(super) fn new(g_hg: T, g_d: T, alpha: T, w_d: T) -> Self {
        DiracFog {
            lobes: [
                (T::ONE - w_d, Lobe::new(g_hg, T::ZERO), g_hg),
                (w_d, Lobe::new(g_d, alpha), g_d),
            ],
        }
    }

    /// `Σ w_i f_i`, a lobe of weight 0 left out.
    fn weighted(&self, f: impl Fn(&Lobe<T>) -> T) -> T {
        self.lobes
            .iter()
            .filter(|(w, _, _)| *w > T::ZERO)
            .fold(T::ZERO, |acc, (w, lobe, _)| acc + *w * f(lobe))
    }

    /// The density per steradian: `+∞` at a pole with mass.
    pub(super) fn pdf(&self, mu: T) -> T {
        self.weighted(|l| l.pdf(mu))
    }

    /// The CDF, steps included.
    pub(super) fn cdf(&self, mu: T) -> T {
        self.weighted(|l| l.cdf(mu)).clamp01()
    }

    /// The masses at `−1` and `+1` and the continuous lobe with its weight.
    fn split(&self) -> (T, T, Option<(T, &Lobe<T>)>) {
        let (mut minus, mut plus, mut cont) = (T::ZERO, T::ZERO, None);
        for (w, lobe, g) in &self.lobes {
            match lobe.pole(*g) {
                Some(p) if p > T::ZERO => plus += *w,
                Some(_) => minus += *w,
                None if *w > T::ZERO => cont = Some((*w, lobe)),
                None => {}
            }
        }
        (minus, plus, cont)
    }

    /// The exact inverse of the CDF at `u` (clamped; NaN gives NaN), with
    /// `sin θ` (module docs).
    pub(super) fn sample_cos_sin(&self, u: T) -> (T, T) {
        let u = u.clamp01();
        if u.is_nan() {
            return (u, u);
        }
        let (minus, plus, cont) = self.split();
        if minus > T::ZERO && u <= minus {
            return (-T::ONE, T::ZERO);
        }
        if plus > T::ZERO && u > T::ONE - plus {
            return (T::ONE, T::ZERO);
        }
        match cont {
            Some((w, lobe)) => lobe.sample_cos_sin(((u - minus) / w).clamp01()),
            None if plus > T::ZERO => (T::ONE, T::ZERO),
            None => (-T::ONE, T::ZERO),
        }
    }
}
