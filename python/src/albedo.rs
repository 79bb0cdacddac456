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
    /// node, the paths traced, and the albedo and its error at each fine
    /// node.
    #[allow(clippy::type_complexity)]
    fn _state(&self) -> (Vec<f64>, Vec<f64>, u64, Vec<f64>, Vec<f64>) {
        let (rho, se) = self.curve.nodes();
        let (fine, fine_se) = self.curve.fine_nodes().unwrap_or_default();
        (
            rho.to_vec(),
            se.to_vec(),
            self.curve.paths(),
            fine.to_vec(),
            fine_se.to_vec(),
        )
    }
    /// The curve of a [`_state`](Self::_state); `ValueError` for one that
    /// is not a curve's (node counts, values outside `[0, 1]` or not
    /// finite).
    #[staticmethod]
    #[allow(clippy::type_complexity)]
    fn _from_state(state: (Vec<f64>, Vec<f64>, u64, Vec<f64>, Vec<f64>)) -> PyResult<Self> {
        let (rho, se, paths, fine, fine_se) = state;
        let ok = |v: &[f64]| v.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x));
        match (
            <[f64; _]>::try_from(rho.as_slice()),
            <[f64; _]>::try_from(se.as_slice()),
            <[f64; _]>::try_from(fine.as_slice()),
            <[f64; _]>::try_from(fine_se.as_slice()),
        ) {
            (Ok(rho), Ok(se), Ok(fine), Ok(fine_se))
                if ok(&rho) && ok(&se) && ok(&fine) && ok(&fine_se) =>
            {
                Ok(PyAlbedo {
                    curve: AlbedoCurve::from_stored(rho, se, fine, fine_se, paths),
                })
            }
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
