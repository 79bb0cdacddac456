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
