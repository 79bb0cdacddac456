//! A phase function per wavelength channel, sampled at a hero channel.

use crate::phase::{Model, PyPhase};
use crate::{Array, refused, uniforms_ok};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use scatterkit::Phase;
use scatterkit::mixture::Part;
use scatterkit::mixture::spectral::SpectralPhase;

/// One model per channel, owned.
#[pyclass(name = "_SpectralPhase", module = "scatterkit._scatterkit", frozen)]
#[derive(Debug)]
pub(crate) struct PySpectralPhase {
    channels: Vec<Phase<f64>>,
}

impl PySpectralPhase {
    fn spectral(&self) -> SpectralPhase<'_, f64> {
        let parts: Vec<Part<'_, f64>> = self.channels.iter().map(|p| Part::Phase(*p)).collect();
        SpectralPhase::new(&parts).expect("checked when built")
    }
}

#[pymethods]
impl PySpectralPhase {
    #[new]
    fn new(channels: Vec<PyRef<'_, PyPhase>>) -> PyResult<Self> {
        let mut models = Vec::with_capacity(channels.len());
        for c in &channels {
            match &c.model {
                Model::One(p) => models.push(*p),
                _ => {
                    return Err(PyValueError::new_err(
                        "SpectralPhase: each channel must be one of the models",
                    ));
                }
            }
        }
        let parts: Vec<Part<'_, f64>> = models.iter().map(|p| Part::Phase(*p)).collect();
        SpectralPhase::new(&parts)
            .map_err(|e| refused("SpectralPhase(channels): 1 to 16 channels", e))?;
        Ok(PySpectralPhase { channels: models })
    }
    /// Every channel's density at each cosine: `n·c` values, row-major.
    fn pdf<'py>(&self, py: Python<'py>, mu: PyReadonlyArray1<'py, f64>) -> PyResult<Array<'py>> {
        let m = mu.as_slice()?;
        let s = self.spectral();
        let c = s.len();
        let out: Result<Vec<f64>, _> = py.detach(|| {
            let mut out = vec![0.0; m.len() * c];
            for (row, &x) in out.chunks_exact_mut(c).zip(m) {
                s.pdf(x, row)?;
            }
            Ok(out)
        });
        Ok(out.map_err(|e| refused("pdf", e))?.into_pyarray(py))
    }
    /// Cosines from channel `hero` at `u`, and every channel's density
    /// over the hero's at each (`n·c` values, row-major).
    fn sample_cos<'py>(
        &self,
        py: Python<'py>,
        hero: usize,
        u: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Array<'py>, Array<'py>)> {
        let us = u.as_slice()?;
        if !uniforms_ok(us) {
            return Err(PyValueError::new_err("sample_cos: u must lie in [0, 1]"));
        }
        let s = self.spectral();
        let c = s.len();
        let out: Result<(Vec<f64>, Vec<f64>), _> = py.detach(|| {
            let (mut mu, mut ratio) = (Vec::with_capacity(us.len()), vec![0.0; us.len() * c]);
            for (row, &x) in ratio.chunks_exact_mut(c).zip(us) {
                mu.push(s.sample_cos(hero, x, row)?);
            }
            Ok((mu, ratio))
        });
        let (mu, ratio) =
            out.map_err(|e| refused("sample_cos(hero, u): hero must name a channel", e))?;
        Ok((mu.into_pyarray(py), ratio.into_pyarray(py)))
    }
    #[getter]
    fn channels(&self) -> usize {
        self.channels.len()
    }
}
