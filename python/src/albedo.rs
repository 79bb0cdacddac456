//! The albedo of a layer against the single-scattering albedo.

use crate::phase::PyPhase;
use crate::{Array, map, refused};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;
use scatterkit::transport::albedo::{AlbedoCurve, Illumination, Layer};

/// The albedo of a layer as a function of the single-scattering albedo.
#[pyclass(name = "_AlbedoCurve", module = "scatterkit._scatterkit", frozen)]
#[derive(Debug)]
pub(crate) struct PyAlbedo {
    curve: AlbedoCurve,
}

#[pymethods]
impl PyAlbedo {
    /// `thickness` `None` for a semi-infinite layer; `mu0` `None` for
    /// diffuse light.
    #[new]
    fn new(
        py: Python<'_>,
        phase: PyRef<'_, PyPhase>,
        thickness: Option<f64>,
        mu0: Option<f64>,
        paths: u64,
        seed: u64,
    ) -> PyResult<Self> {
        let layer = thickness.map_or(Layer::SemiInfinite, Layer::Slab);
        let light = mu0.map_or(Illumination::Diffuse, Illumination::Directional);
        let model = &phase.model;
        let curve = py
            .detach(|| {
                let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
                model.with(|p| AlbedoCurve::simulate(p, layer, light, paths, &mut rng))
            })
            .map_err(|e| refused("AlbedoCurve(phase, thickness, mu0, paths)", e))?;
        Ok(PyAlbedo { curve })
    }
    /// What pickling keeps: the albedo and its standard error at each
    /// node, and the paths traced.
    fn _state(&self) -> (Vec<f64>, Vec<f64>, u64) {
        let (rho, se) = self.curve.nodes();
        (rho.to_vec(), se.to_vec(), self.curve.paths())
    }
    /// The curve of a [`_state`](Self::_state); `ValueError` for one that
    /// is not a curve's (node count, values outside `[0, 1]` or not
    /// finite).
    #[staticmethod]
    fn _from_state(state: (Vec<f64>, Vec<f64>, u64)) -> PyResult<Self> {
        let (rho, se, paths) = state;
        let ok = |v: &[f64]| v.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x));
        match (
            <[f64; _]>::try_from(rho.as_slice()),
            <[f64; _]>::try_from(se.as_slice()),
        ) {
            (Ok(rho), Ok(se)) if ok(&rho) && ok(&se) => Ok(PyAlbedo {
                curve: AlbedoCurve::from_nodes(rho, se, paths),
            }),
            _ => Err(pyo3::exceptions::PyValueError::new_err(
                "AlbedoCurve: not a pickled albedo curve",
            )),
        }
    }
    fn albedo<'py>(
        &self,
        py: Python<'py>,
        omega: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let c = self.curve;
        map(py, &omega, move |w| c.albedo(w))
    }
    fn std_error<'py>(
        &self,
        py: Python<'py>,
        omega: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let c = self.curve;
        map(py, &omega, move |w| c.std_error(w))
    }
    fn single_scattering_albedo<'py>(
        &self,
        py: Python<'py>,
        albedo: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let xs = albedo.as_slice()?;
        let c = self.curve;
        let out: Result<Vec<f64>, _> =
            py.detach(|| xs.iter().map(|&a| c.single_scattering_albedo(a)).collect());
        Ok(out
            .map_err(|e| {
                refused(
                    "single_scattering_albedo(A): A outside the curve's range",
                    e,
                )
            })?
            .into_pyarray(py))
    }
    #[getter]
    fn paths(&self) -> u64 {
        self.curve.paths()
    }
}
