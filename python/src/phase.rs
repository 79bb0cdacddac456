//! Phase functions: every model of the library and mixtures of them.

use crate::{Array, filled, is_unit, map, par_chunks, refused, uniforms_ok};
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadwriteArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use scatterkit::mixture::{Mixture, Part};
use scatterkit::phase::legendre::LegendreSeries;
use scatterkit::phase::moments::{legendre_moments, legendre_moments_by_quadrature};
use scatterkit::phase::{check_uniforms, support};
use scatterkit::{HenyeyGreenstein, Phase, PhaseFunction, Table, TableKind, Vec3};

/// A phase function: one of the library's models, a mixture of them, a
/// Legendre series or a table, owning what it borrows in the library.
#[derive(Clone, Debug)]
pub(crate) enum Model {
    One(Phase<f64>),
    /// The mixture and the weights as given (pickling rebuilds from them,
    /// so that the normalised weights come out bit for bit).
    Mix(Box<Mixture<'static, f64>>, Vec<f64>),
    /// Legendre moments `χ_0 … χ_{n−1}`, checked when built.
    Series(Vec<f64>),
    /// A table's data, its resolution and kind, checked when built.
    Table(Vec<f64>, usize, TableKind),
}

/// A table as a phase function (the library's `Table` has the methods but
/// not the trait).
struct TableView<'a>(Table<'a, f64>);

impl PhaseFunction<f64> for TableView<'_> {
    fn pdf(&self, mu: f64) -> f64 {
        self.0.pdf(mu)
    }
    fn cdf(&self, mu: f64) -> f64 {
        self.0.cdf(mu)
    }
    fn sample_cos(&self, u: f64) -> f64 {
        self.0.sample_cos(u)
    }
    fn mean_cosine(&self) -> f64 {
        self.0.mean_cosine()
    }
    fn sample_dir(&self, w: Vec3<f64>, u1: f64, u2: f64) -> (Vec3<f64>, f64) {
        self.0.sample_dir(w, u1, u2)
    }
}

/// A phase function behind a reference, sized (for the library's generic
/// builders).
pub(crate) struct ByRef<'a>(pub(crate) &'a (dyn PhaseFunction<f64> + Sync));

impl PhaseFunction<f64> for ByRef<'_> {
    fn pdf(&self, mu: f64) -> f64 {
        self.0.pdf(mu)
    }
    fn cdf(&self, mu: f64) -> f64 {
        self.0.cdf(mu)
    }
    fn sample_cos(&self, u: f64) -> f64 {
        self.0.sample_cos(u)
    }
    fn mean_cosine(&self) -> f64 {
        self.0.mean_cosine()
    }
}

impl Model {
    /// Runs `f` on the model as the library's phase-function trait.
    pub(crate) fn with<R>(&self, f: impl FnOnce(&(dyn PhaseFunction<f64> + Sync)) -> R) -> R {
        match self {
            Model::One(p) => f(p),
            Model::Mix(m, _) => f(&**m),
            Model::Series(chi) => {
                let s = LegendreSeries::unchecked(chi).expect("checked when built");
                f(&s)
            }
            Model::Table(data, n, kind) => {
                let t = Table::from_data(data, *n, *kind).expect("checked when built");
                f(&TableView(t))
            }
        }
    }
    fn mean_cosine(&self) -> f64 {
        self.with(|p| p.mean_cosine())
    }
    fn moments(&self, out: &mut [f64]) {
        match self {
            Model::One(p) => legendre_moments(p, out),
            _ => self.with(|p| legendre_moments_by_quadrature(p, out)),
        }
    }
}

/// HG cosines in bulk: the library's f64 sampler per element, the loop
/// compiled for AVX2 too and chosen where the processor has it (the
/// division-bound loop then runs four lanes wide: 0.62 ns per cosine
/// instead of 1.55 on an AMD EPYC Zen 4), with the same bits (the same
/// operations; Rust does not fuse multiply-adds).
fn hg_cos_n(
    h: &HenyeyGreenstein<f64>,
    u: &[f64],
    out: &mut [f64],
) -> Result<(), scatterkit::Error> {
    if u.len() != out.len() {
        return Err(scatterkit::Error::Size);
    }
    check_uniforms(u)?;
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2 (detected just above).
        unsafe { hg_cos_each_avx2(h, u, out) };
        return Ok(());
    }
    h.sample_cos_each_in_range(u, out);
    Ok(())
}

/// The loop of `hg_cos_n` compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn hg_cos_each_avx2(h: &HenyeyGreenstein<f64>, u: &[f64], out: &mut [f64]) {
    for (o, &x) in out.iter_mut().zip(u) {
        *o = h.sample_cos_in_range(x);
    }
}

/// What pickling keeps of a phase function (see `PyPhase::_state`).
type State = (
    String,
    Vec<u32>,
    Vec<Vec<f64>>,
    Vec<f64>,
    Vec<f64>,
    usize,
    u8,
);

/// The compiled phase function behind `scatterkit.Phase`.
#[pyclass(
    name = "_Phase",
    module = "scatterkit._scatterkit",
    frozen,
    skip_from_py_object
)]
#[derive(Clone, Debug)]
pub(crate) struct PyPhase {
    pub(crate) model: Model,
}

fn phase(r: Result<Phase<f64>, scatterkit::Error>, what: &str) -> PyResult<PyPhase> {
    r.map(|p| PyPhase {
        model: Model::One(p),
    })
    .map_err(|e| refused(what, e))
}

#[pymethods]
impl PyPhase {
    #[staticmethod]
    fn isotropic() -> Self {
        PyPhase {
            model: Model::One(Phase::isotropic()),
        }
    }
    #[staticmethod]
    fn rayleigh() -> Self {
        PyPhase {
            model: Model::One(Phase::rayleigh()),
        }
    }
    #[staticmethod]
    fn rayleigh_depolarized(rho: f64) -> PyResult<Self> {
        phase(
            Phase::rayleigh_depolarized(rho),
            "rayleigh_depolarized(rho)",
        )
    }
    #[staticmethod]
    fn henyey_greenstein(g: f64) -> PyResult<Self> {
        phase(Phase::henyey_greenstein(g), "henyey_greenstein(g)")
    }
    #[staticmethod]
    fn two_lobe_hg(g1: f64, g2: f64, w: f64) -> PyResult<Self> {
        phase(Phase::two_lobe_hg(g1, g2, w), "two_lobe_hg(g1, g2, w)")
    }
    #[staticmethod]
    fn draine(g: f64, alpha: f64) -> PyResult<Self> {
        phase(Phase::draine(g, alpha), "draine(g, alpha)")
    }
    #[staticmethod]
    fn cornette_shanks(g: f64) -> PyResult<Self> {
        phase(Phase::cornette_shanks(g), "cornette_shanks(g)")
    }
    #[staticmethod]
    fn fog(g_hg: f64, g_d: f64, alpha: f64, w_d: f64) -> PyResult<Self> {
        phase(
            Phase::fog(g_hg, g_d, alpha, w_d),
            "fog(g_hg, g_d, alpha, w_d)",
        )
    }
    #[staticmethod]
    fn fog_diameter(diameter_um: f64) -> PyResult<Self> {
        phase(
            Phase::fog_diameter(diameter_um),
            "fog_diameter(diameter_um)",
        )
    }
    #[staticmethod]
    fn gegenbauer(alpha: f64, g: f64) -> PyResult<Self> {
        phase(Phase::gegenbauer(alpha, g), "gegenbauer(alpha, g)")
    }
    #[staticmethod]
    fn fournier_forand(n: f64, mu_j: f64) -> PyResult<Self> {
        phase(Phase::fournier_forand(n, mu_j), "fournier_forand(n, mu_j)")
    }
    #[staticmethod]
    fn fournier_forand_backscatter(b: f64, n: f64) -> PyResult<Self> {
        phase(
            Phase::fournier_forand_backscatter(b, n),
            "fournier_forand_backscatter(b, n)",
        )
    }
    /// A Legendre series from moments `χ_0 = 1, χ_1, …` (refused where the
    /// series goes negative).
    #[staticmethod]
    fn legendre_series(chi: Vec<f64>) -> PyResult<Self> {
        LegendreSeries::new(&chi).map_err(|e| refused("legendre_series(chi)", e))?;
        Ok(PyPhase {
            model: Model::Series(chi),
        })
    }
    /// The inverse-CDF table of `phase` at `n` intervals.
    #[staticmethod]
    fn table_of(py: Python<'_>, phase: PyRef<'_, PyPhase>, n: usize) -> PyResult<Self> {
        let len = TableKind::Inverse
            .len(n)
            .filter(|_| n <= 1 << 20)
            .ok_or_else(|| PyValueError::new_err("table(phase, n): n must be in 1 ..= 2^20"))?;
        let data = phase.model.with(|p| {
            py.detach(|| {
                let mut buf = vec![0.0; len];
                let built = Table::inverse(&ByRef(p), &mut buf, n).map(|_| ());
                built.map(|()| buf)
            })
        });
        let data = data.map_err(|e| refused("table(phase, n)", e))?;
        Ok(PyPhase {
            model: Model::Table(data, n, TableKind::Inverse),
        })
    }
    /// The table of a measured phase function at `n` intervals.
    #[staticmethod]
    fn table_measured(
        cos_theta: PyReadonlyArray1<'_, f64>,
        pdf: PyReadonlyArray1<'_, f64>,
        n: usize,
    ) -> PyResult<Self> {
        let len = TableKind::Measured
            .len(n)
            .filter(|_| n <= 1 << 20)
            .ok_or_else(|| {
                PyValueError::new_err("table_measured(..., n): n must be in 1 ..= 2^20")
            })?;
        let mut buf = vec![0.0; len];
        Table::measured(cos_theta.as_slice()?, pdf.as_slice()?, &mut buf, n)
            .map_err(|e| refused("table_measured(cos_theta, pdf, n)", e))?;
        Ok(PyPhase {
            model: Model::Table(buf, n, TableKind::Measured),
        })
    }
    /// The table's data (Hermite nodes `μ_i, dμ/du_i`), or None.
    fn table_data<'py>(&self, py: Python<'py>) -> Option<Array<'py>> {
        match &self.model {
            Model::Table(data, ..) => Some(data.clone().into_pyarray(py)),
            _ => None,
        }
    }
    #[staticmethod]
    fn schlick(k: f64) -> PyResult<Self> {
        phase(
            scatterkit::phase::schlick::Schlick::new(k).map(Phase::Schlick),
            "schlick(k)",
        )
    }
    #[staticmethod]
    fn modified_hg(g: f64, gamma: f64) -> PyResult<Self> {
        phase(Phase::modified_hg(g, gamma), "modified_hg(g, gamma)")
    }
    #[staticmethod]
    fn modified_hg_delta(g: f64, delta: f64) -> PyResult<Self> {
        phase(
            Phase::modified_hg_delta(g, delta),
            "modified_hg_delta(g, delta)",
        )
    }
    #[staticmethod]
    fn two_lobe_hg_gamma(g: f64, gamma: f64) -> PyResult<Self> {
        phase(
            Phase::two_lobe_hg_gamma(g, gamma),
            "two_lobe_hg_gamma(g, gamma)",
        )
    }
    #[staticmethod]
    fn two_lobe_hg_delta(g: f64, delta: f64) -> PyResult<Self> {
        phase(
            Phase::two_lobe_hg_delta(g, delta),
            "two_lobe_hg_delta(g, delta)",
        )
    }
    #[staticmethod]
    fn gegenbauer_gamma(g: f64, gamma: f64) -> PyResult<Self> {
        phase(
            Phase::gegenbauer_gamma(g, gamma),
            "gegenbauer_gamma(g, gamma)",
        )
    }
    #[staticmethod]
    fn gegenbauer_delta(g: f64, delta: f64) -> PyResult<Self> {
        phase(
            Phase::gegenbauer_delta(g, delta),
            "gegenbauer_delta(g, delta)",
        )
    }
    /// A mixture of single models (not of mixtures) with weights.
    #[staticmethod]
    fn mixture(parts: Vec<(PyRef<'_, PyPhase>, f64)>) -> PyResult<Self> {
        let mut held = Vec::with_capacity(parts.len());
        for (p, w) in &parts {
            match &p.model {
                Model::One(one) => held.push((Part::Phase(*one), *w)),
                _ => {
                    return Err(PyValueError::new_err(
                        "mixture: each part must be one of the models (not a mixture, series or table)",
                    ));
                }
            }
        }
        let weights = parts.iter().map(|(_, w)| *w).collect();
        Mixture::new(&held)
            .map(|m| PyPhase {
                model: Model::Mix(Box::new(m), weights),
            })
            .map_err(|e| refused("mixture(parts)", e))
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> &'static str {
        match &self.model {
            Model::One(p) if two_lobe(p).is_some() => "two_lobe_hg",
            Model::One(p) => p.name(),
            Model::Mix(..) => "mixture",
            Model::Series(_) => "Legendre series",
            Model::Table(..) => "table",
        }
    }
    #[getter]
    fn mean_cosine(&self) -> f64 {
        self.model.mean_cosine()
    }
    fn pdf<'py>(&self, py: Python<'py>, mu: PyReadonlyArray1<'py, f64>) -> PyResult<Array<'py>> {
        // Outside [−1, 1] as the library's Phase: 0 (within 8 ulp, ±1).
        let at = |p: &dyn PhaseFunction<f64>, x: f64| support(x).map_or(0.0, |m| p.pdf(m));
        self.model.with(|p| map(py, &mu, |x| at(p, x)))
    }
    fn cdf<'py>(&self, py: Python<'py>, mu: PyReadonlyArray1<'py, f64>) -> PyResult<Array<'py>> {
        self.model.with(|p| map(py, &mu, |x| p.cdf(x)))
    }
    fn sample_cos<'py>(
        &self,
        py: Python<'py>,
        u: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let us = u.as_slice()?;
        if let Model::One(Phase::HenyeyGreenstein(h)) = &self.model {
            return filled(py, us.len(), |out| {
                par_chunks(us, out, |a, b| hg_cos_n(h, a, b))
            })?
            .map_err(|e| refused("sample_cos(u): u must lie in [0, 1]", e));
        }
        self.model
            .with(|p| {
                filled(py, us.len(), |out| {
                    par_chunks(us, out, |a, b| p.sample_cos_n(a, b))
                })
            })?
            .map_err(|e| refused("sample_cos(u): u must lie in [0, 1]", e))
    }
    /// The portable f32 tier's cosines (`include/scatterkit_portable.h`,
    /// bit for bit) for an isotropic, HG or Rayleigh phase, at float32
    /// uniforms in `[0, 1]` (clamped as the header clamps; NaN gives NaN).
    fn sample_cos_portable<'py>(
        &self,
        py: Python<'py>,
        u: PyReadonlyArray1<'py, f32>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f32>>> {
        use numpy::PyArrayMethods;
        use scatterkit::portable;
        let model = match &self.model {
            Model::One(Phase::HenyeyGreenstein(h)) => portable::Hg::new(h.g() as f32)
                .map(portable::Model::Hg)
                .ok_or_else(|| {
                    PyValueError::new_err("sample_cos_portable: g does not round to [-1, 1]")
                })?,
            Model::One(Phase::Isotropic(_)) => portable::Model::Isotropic,
            Model::One(Phase::Rayleigh(_)) => portable::Model::Rayleigh,
            _ => {
                return Err(PyValueError::new_err(
                    "sample_cos_portable: the portable tier's batch holds isotropic, \
                     Henyey-Greenstein and Rayleigh only",
                ));
            }
        };
        let us = u.as_slice()?;
        let out = numpy::PyArray1::<f32>::zeros(py, us.len(), false);
        {
            let mut rw = out.readwrite();
            let o = rw.as_slice_mut()?;
            py.detach(|| match &model {
                portable::Model::Hg(h) => portable::hg_sample_cos_n(h, us, o),
                portable::Model::Rayleigh => portable::rayleigh_sample_cos_n(us, o),
                portable::Model::Isotropic => portable::isotropic_sample_cos_n(us, o),
            });
        }
        Ok(out)
    }
    /// `sample_cos` into a caller's array (same length as `u`).
    fn sample_cos_into(
        &self,
        py: Python<'_>,
        u: PyReadonlyArray1<'_, f64>,
        mut out: PyReadwriteArray1<'_, f64>,
    ) -> PyResult<()> {
        let us = u.as_slice()?;
        let o = out.as_slice_mut()?;
        if us.len() != o.len() {
            return Err(PyValueError::new_err(
                "sample_cos(u, out): out as long as u",
            ));
        }
        let r = match &self.model {
            Model::One(Phase::HenyeyGreenstein(h)) => {
                py.detach(|| par_chunks(us, o, |a, b| hg_cos_n(h, a, b)))
            }
            m => m.with(|p| py.detach(|| par_chunks(us, o, |a, b| p.sample_cos_n(a, b)))),
        };
        r.map_err(|e| {
            refused(
                "sample_cos(u, out): u must lie in [0, 1], out as long as u",
                e,
            )
        })
    }
    /// Directions about `w_in` (unit, 3 values) from `u1`, `u2`: the
    /// directions as 3n values (x, y, z per row) and their densities.
    fn sample_dir<'py>(
        &self,
        py: Python<'py>,
        w_in: [f64; 3],
        u1: PyReadonlyArray1<'py, f64>,
        u2: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Array<'py>, Array<'py>)> {
        let (a, b) = (u1.as_slice()?, u2.as_slice()?);
        if a.len() != b.len() {
            return Err(PyValueError::new_err(
                "sample_dir: u1 and u2 differ in length",
            ));
        }
        let w = Vec3::new(w_in[0], w_in[1], w_in[2]);
        if !is_unit(w) {
            return Err(PyValueError::new_err(
                "sample_dir: w_in must be a unit vector",
            ));
        }
        if !(uniforms_ok(a) && uniforms_ok(b)) {
            return Err(PyValueError::new_err(
                "sample_dir: u1 and u2 must lie in [0, 1]",
            ));
        }
        let (dirs, pdf) = self.model.with(|m| {
            py.detach(|| {
                let mut dirs = Vec::with_capacity(3 * a.len());
                let mut pdf = Vec::with_capacity(a.len());
                for (&x, &y) in a.iter().zip(b) {
                    let (d, p) = m.sample_dir(w, x, y);
                    dirs.extend([d.x, d.y, d.z]);
                    pdf.push(p);
                }
                (dirs, pdf)
            })
        });
        Ok((dirs.into_pyarray(py), pdf.into_pyarray(py)))
    }
    /// The Legendre moments `χ_0 … χ_{n−1}`.
    fn legendre<'py>(&self, py: Python<'py>, n: usize) -> PyResult<Array<'py>> {
        if n == 0 || n > 1 << 16 {
            return Err(PyValueError::new_err(
                "legendre(n): n must be in 1 ..= 65536",
            ));
        }
        let m = &self.model;
        let out = py.detach(|| {
            let mut out = vec![0.0; n];
            m.moments(&mut out);
            out
        });
        Ok(out.into_pyarray(py))
    }
    /// What pickling keeps: `(kind, tags, params, weights, data, n,
    /// table kind)`, `kind` one of "one" (a model: its tag and parameters),
    /// "mix" (each part's tag and parameters, and the weights as given),
    /// "series" (the moments in `data`) or "table" (`data`, `n` and the
    /// table kind). [`_from_state`](Self::_from_state) rebuilds it.
    fn _state(&self) -> State {
        let one = |p: &Phase<f64>| {
            let (tag, n, v) = p.params();
            (tag, v[..n].to_vec())
        };
        match &self.model {
            Model::One(p) => {
                let (tag, v) = one(p);
                ("one".into(), vec![tag], vec![v], vec![], vec![], 0, 0)
            }
            Model::Mix(m, weights) => {
                let (tags, params) = (0..m.len())
                    .filter_map(|i| match m.part(i) {
                        Some(Part::Phase(p)) => Some(one(&p)),
                        _ => None,
                    })
                    .unzip();
                ("mix".into(), tags, params, weights.clone(), vec![], 0, 0)
            }
            Model::Series(chi) => ("series".into(), vec![], vec![], vec![], chi.clone(), 0, 0),
            Model::Table(data, n, kind) => {
                let data = data.clone();
                (
                    "table".into(),
                    vec![],
                    vec![],
                    vec![],
                    data,
                    *n,
                    *kind as u8,
                )
            }
        }
    }
    /// The phase function of a [`_state`](Self::_state), through the same
    /// checks as building it; `ValueError` for a state that is not one.
    #[staticmethod]
    fn _from_state(state: State) -> PyResult<Self> {
        let (kind, tags, params, weights, data, n, table_kind) = state;
        let bad = || PyValueError::new_err("Phase: not a pickled phase function");
        let model = |tag: u32, p: &[f64]| {
            Phase::from_params(tag, p).map_err(|e| refused("Phase (unpickled)", e))
        };
        let model = match kind.as_str() {
            "one" if tags.len() == 1 && params.len() == 1 => {
                Model::One(model(tags[0], &params[0])?)
            }
            "mix" if tags.len() == params.len() && tags.len() == weights.len() => {
                let mut held = Vec::with_capacity(tags.len());
                for ((&tag, p), &w) in tags.iter().zip(&params).zip(&weights) {
                    held.push((Part::Phase(model(tag, p)?), w));
                }
                let m = Mixture::new(&held).map_err(|e| refused("Phase (unpickled)", e))?;
                Model::Mix(Box::new(m), weights)
            }
            "series" => {
                LegendreSeries::new(&data).map_err(|e| refused("Phase (unpickled)", e))?;
                Model::Series(data)
            }
            "table" => {
                let kind = match table_kind {
                    1 => TableKind::Inverse,
                    2 => TableKind::Measured,
                    _ => return Err(bad()),
                };
                let whole = kind.len(n).is_some_and(|len| len == data.len()) && n <= 1 << 20;
                if !(whole && data.iter().all(|x| x.is_finite())) {
                    return Err(bad());
                }
                Model::Table(data, n, kind)
            }
            _ => return Err(bad()),
        };
        Ok(PyPhase { model })
    }
    fn __repr__(&self) -> String {
        match &self.model {
            Model::One(p) if two_lobe(p).is_some() => {
                let [g1, g2, w] = two_lobe(p).unwrap_or_default();
                format!("two_lobe_hg({g1}, {g2}, {w})")
            }
            Model::One(p) => {
                let (_, n, v) = p.params();
                let v: Vec<String> = v.iter().take(n).map(|x| format!("{x}")).collect();
                format!("{}({})", p.name(), v.join(", "))
            }
            Model::Mix(m, _) => format!("mixture of {} parts", m.len()),
            Model::Series(chi) => format!("Legendre series of {} moments", chi.len()),
            Model::Table(_, n, kind) => format!("table ({kind:?}, {n} intervals)"),
        }
    }
}

/// `(g1, g2, w)` of a two-lobe HG, which the library keeps as a fog with
/// `α = 0` (`fog(g_hg, g_d, 0, w_d)` is `two_lobe_hg(g_d, g_hg, w_d)`), so
/// that it prints and names itself as it was built (and as `fit` reports it).
fn two_lobe(p: &scatterkit::Phase<f64>) -> Option<[f64; 3]> {
    let (_, _, v) = p.params();
    (p.name() == "fog" && v[2] == 0.0).then_some([v[1], v[0], v[3]])
}
