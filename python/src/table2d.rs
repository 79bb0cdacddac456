//! 2-D tables: a phase function that varies with a parameter (wavelength,
//! size), tabulated at evenly spaced values and blended between them.

use crate::phase::{ByRef, PyPhase};
use crate::{Array, filled, refused, uniforms_ok};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use scatterkit::{Table, Table2d};

/// A 2-D inverse-CDF table, owning its data.
#[pyclass(name = "_Table2d", module = "scatterkit._scatterkit", frozen)]
#[derive(Debug)]
pub(crate) struct PyTable2d {
    data: Vec<f64>,
    n: usize,
    k: usize,
    x0: f64,
    dx: f64,
}

impl PyTable2d {
    fn table(&self) -> Table2d<'_, f64> {
        Table2d::from_data(&self.data, self.n, self.k, self.x0, self.dx)
            .expect("checked when built")
    }
}

/// Checks `x` and `v` have one length; applies `f(x_i, v_i)`.
fn pairs<'py>(
    py: Python<'py>,
    x: &PyReadonlyArray1<'py, f64>,
    v: &PyReadonlyArray1<'py, f64>,
    f: impl Fn(f64, f64) -> f64 + Send + Sync,
) -> PyResult<Array<'py>> {
    let (xs, vs) = (x.as_slice()?, v.as_slice()?);
    if xs.len() != vs.len() {
        return Err(PyValueError::new_err("x and its partner differ in length"));
    }
    let out = filled(py, xs.len(), |o| {
        for ((o, &a), &b) in o.iter_mut().zip(xs).zip(vs) {
            *o = f(a, b);
        }
        Ok::<(), std::convert::Infallible>(())
    })?;
    let Ok(out) = out;
    Ok(out)
}

#[pymethods]
impl PyTable2d {
    /// Slice `j` is the inverse-CDF table of `phases[j]` at `n` intervals,
    /// for the parameter `x0 + j dx`.
    #[new]
    fn new(
        py: Python<'_>,
        phases: Vec<PyRef<'_, PyPhase>>,
        x0: f64,
        dx: f64,
        n: usize,
    ) -> PyResult<Self> {
        let k = phases.len();
        let len = Table2d::<f64>::len(n, k)
            .filter(|_| n <= 1 << 16)
            .ok_or_else(|| {
                PyValueError::new_err("Table2d: n in 1 ..= 65536 and at least one phase")
            })?;
        let models: Vec<_> = phases.iter().map(|p| p.model.clone()).collect();
        let data = py
            .detach(|| {
                let mut buf = vec![0.0; len];
                let built = Table2d::build(&mut buf, n, k, x0, dx, |j, _, slice| {
                    let m = models.get(j).ok_or(scatterkit::Error::Size)?;
                    m.with(|p| Table::inverse(&ByRef(p), slice, n).map(|_| ()))
                })
                .map(|_| ());
                built.map(|()| buf)
            })
            .map_err(|e| refused("Table2d(phases, x0, dx, n)", e))?;
        Ok(PyTable2d { data, n, k, x0, dx })
    }
    fn pdf<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        mu: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let t = self.table();
        pairs(py, &x, &mu, |a, b| t.pdf(a, b))
    }
    fn cdf<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        mu: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let t = self.table();
        pairs(py, &x, &mu, |a, b| t.cdf(a, b))
    }
    fn sample_cos<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        u: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        if !uniforms_ok(u.as_slice()?) {
            return Err(PyValueError::new_err("sample_cos: u must lie in [0, 1]"));
        }
        let t = self.table();
        pairs(py, &x, &u, |a, b| t.sample_cos(a, b))
    }
    fn mean_cosine<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let t = self.table();
        crate::map(py, &x, |a| t.mean_cosine(a))
    }
    /// The data: `k` slices of `2(n + 1)` values, one after the other.
    fn data<'py>(&self, py: Python<'py>) -> Array<'py> {
        self.data.clone().into_pyarray(py)
    }
    #[getter]
    fn shape(&self) -> (usize, usize, f64, f64) {
        (self.n, self.k, self.x0, self.dx)
    }
}
