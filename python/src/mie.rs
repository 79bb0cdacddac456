//! Exact Lorenz–Mie theory for one sphere.

use crate::{Array, refused};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use scatterkit::mie::polydisperse::{Polydisperse, SizeDistribution};
use scatterkit::mie::{self, Complex, Mie};

/// One sphere solved by Lorenz–Mie theory.
#[pyclass(name = "_Mie", module = "scatterkit._scatterkit", frozen)]
#[derive(Debug)]
pub(crate) struct PyMie {
    x: f64,
    ab: Vec<Complex>,
    eff: mie::Efficiencies,
}

impl PyMie {
    fn series(&self) -> Mie<'_> {
        Mie::from_parts(self.x, &self.ab, self.eff)
    }
}

#[pymethods]
impl PyMie {
    #[new]
    fn new(py: Python<'_>, x: f64, m_re: f64, m_im: f64) -> PyResult<Self> {
        let m = Complex::new(m_re, m_im);
        let len = mie::buffer_len(x, m).ok_or_else(|| {
            PyValueError::new_err("Mie(x, m): x must be in [1e-20, 1e5], Re m in (0, 1000], Im m in [0, 1000], |m| >= 1e-100, |m| x <= 2e6, and m != 1 (a sphere of the medium's index does not scatter)")
        })?;
        let (ab, eff) = py
            .detach(|| {
                // The series keeps its coefficients somewhere in the buffer
                // (the rest is scratch): copy them out.
                let mut buf = vec![Complex::new(0.0, 0.0); len];
                Mie::new(x, m, &mut buf).map(|s| (s.coefficients().to_vec(), s.efficiencies))
            })
            .map_err(|e| refused("Mie(x, m)", e))?;
        Ok(PyMie { x, ab, eff })
    }
    #[getter]
    fn q_ext(&self) -> f64 {
        self.eff.q_ext
    }
    #[getter]
    fn q_sca(&self) -> f64 {
        self.eff.q_sca
    }
    #[getter]
    fn q_back(&self) -> f64 {
        self.eff.q_back
    }
    #[getter]
    fn g(&self) -> f64 {
        self.eff.g
    }
    #[getter]
    fn terms(&self) -> usize {
        self.ab.len() / 2
    }
    /// The phase function per steradian at each cosine.
    fn phase<'py>(&self, py: Python<'py>, mu: PyReadonlyArray1<'py, f64>) -> PyResult<Array<'py>> {
        let xs = mu.as_slice()?;
        let s = self.series();
        let out: Vec<f64> = py.detach(|| xs.iter().map(|&v| s.phase(v)).collect());
        Ok(out.into_pyarray(py))
    }
    /// `S1, S2` at each cosine, as four arrays (real and imaginary parts).
    #[allow(clippy::type_complexity)]
    fn amplitudes<'py>(
        &self,
        py: Python<'py>,
        mu: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Array<'py>, Array<'py>, Array<'py>, Array<'py>)> {
        let xs = mu.as_slice()?;
        let s = self.series();
        let v: Vec<(Complex, Complex)> =
            py.detach(|| xs.iter().map(|&c| s.amplitudes(c)).collect());
        let part = |f: fn(&(Complex, Complex)) -> f64| {
            v.iter().map(f).collect::<Vec<f64>>().into_pyarray(py)
        };
        Ok((
            part(|z| z.0.re),
            part(|z| z.0.im),
            part(|z| z.1.re),
            part(|z| z.1.im),
        ))
    }
}

/// The complex refractive index of water at a wavelength in µm, or None
/// outside the fit's range.
#[pyfunction]
pub(crate) fn water_index(wavelength_um: f64) -> Option<(f64, f64)> {
    mie::water(wavelength_um).map(|m| (m.re, m.im))
}

/// The size parameter `π d n_medium / λ`.
#[pyfunction]
pub(crate) fn size_parameter(diameter: f64, wavelength: f64, n_medium: f64) -> f64 {
    mie::size_parameter(diameter, wavelength, n_medium)
}

/// The averages over a size distribution: `(c_ext, c_sca, c_back, g, area,
/// errors[4], phase_error)` and the phase function at `mu`.
type Averaged = ((f64, f64, f64, f64, f64, [f64; 4], f64), Vec<f64>);

/// Mie theory averaged over a size distribution (`kind` 0 lognormal
/// `(r_g, σ_g, –)`, 1 modified gamma `(α, b, γ)`, 2 Junge `(slope, –, –)`).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub(crate) fn polydisperse(
    py: Python<'_>,
    kind: u32,
    params: [f64; 3],
    r_range: (f64, f64),
    wavelength: f64,
    n_medium: f64,
    m: (f64, f64),
    intervals: usize,
    mu: PyReadonlyArray1<'_, f64>,
) -> PyResult<Averaged> {
    let distribution = distribution(kind, params);
    let p = Polydisperse {
        distribution,
        r_min: r_range.0,
        r_max: r_range.1,
        wavelength,
        n_medium,
        m: Complex::new(m.0, m.1),
        intervals,
    };
    let len = p
        .buffer_len()
        .ok_or_else(|| refused("polydisperse(...)", scatterkit::Error::Domain))?;
    let mu = mu.as_slice()?;
    py.detach(|| {
        let mut phase = vec![0.0; mu.len()];
        let mut scratch = vec![0.0; mu.len()];
        let mut buf = vec![Complex::new(0.0, 0.0); len];
        p.average(mu, &mut phase, &mut scratch, &mut buf).map(|a| {
            (
                (
                    a.c_ext,
                    a.c_sca,
                    a.c_back,
                    a.g,
                    a.area,
                    a.errors,
                    a.phase_error,
                ),
                phase,
            )
        })
    })
    .map_err(|e| refused("polydisperse(distribution, r_min, r_max, wavelength, m)", e))
}

/// The default radius range of a distribution (None for Junge).
#[pyfunction]
pub(crate) fn default_range(kind: u32, params: [f64; 3]) -> Option<(f64, f64)> {
    distribution(kind, params).default_range()
}

/// The distribution `kind` names (0 lognormal, 1 modified gamma, else
/// Junge) with its parameters.
fn distribution(kind: u32, params: [f64; 3]) -> SizeDistribution {
    match kind {
        0 => SizeDistribution::LogNormal {
            median_radius: params[0],
            sigma_g: params[1],
        },
        1 => SizeDistribution::ModifiedGamma {
            alpha: params[0],
            b: params[1],
            gamma: params[2],
        },
        _ => SizeDistribution::Junge { slope: params[0] },
    }
}
