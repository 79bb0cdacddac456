//! The choosers: the cheapest model within a tolerance of Mie theory or
//! of measured data.

use crate::phase::{Model, PyPhase};
use crate::refused;
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use scatterkit::choose::mie::{MieChoice, WORK_LEN, buffer_len, choose_measured, choose_mie};
use scatterkit::mie::Complex;

/// What a chooser found: the model ready to sample (None for the table),
/// its name, its total-variation distance, whether that is within the
/// tolerance, and every candidate's distance in the chooser's order.
type Found = (Option<PyPhase>, String, f64, bool, Vec<f64>);

fn found(c: MieChoice) -> Found {
    (
        c.phase.map(|p| PyPhase {
            model: Model::One(p),
        }),
        snake(&format!("{:?}", c.model)),
        c.distance,
        c.within_tolerance,
        c.distances.to_vec(),
    )
}

/// The cheapest model within `tolerance` of measured `(cos θ, pdf)` data.
#[pyfunction]
pub(crate) fn fit_measured(
    py: Python<'_>,
    cos_theta: PyReadonlyArray1<'_, f64>,
    pdf: PyReadonlyArray1<'_, f64>,
    tolerance: f64,
    allow_table: bool,
) -> PyResult<Found> {
    let (c, p) = (cos_theta.as_slice()?, pdf.as_slice()?);
    py.detach(|| {
        let mut work = vec![0.0; WORK_LEN];
        choose_measured(c, p, tolerance, allow_table, &mut work)
    })
    .map(found)
    .map_err(|e| refused("fit(cos_theta, pdf, tolerance)", e))
}

/// The cheapest model within `tolerance` of the Mie phase function of
/// droplets (`m_re`, `m_im` NaN: water at the wavelength).
#[pyfunction]
pub(crate) fn fit_mie(
    py: Python<'_>,
    diameter_um: f64,
    wavelength_um: f64,
    m_re: f64,
    m_im: f64,
    tolerance: f64,
    allow_table: bool,
) -> PyResult<Found> {
    let m = (!m_re.is_nan()).then(|| Complex::new(m_re, m_im));
    let len = buffer_len(diameter_um, wavelength_um, m).ok_or_else(|| {
        refused(
            "fit_mie(diameter_um, wavelength_um, m)",
            scatterkit::Error::Domain,
        )
    })?;
    py.detach(|| {
        let mut buf = vec![Complex::new(0.0, 0.0); len];
        let mut work = vec![0.0; WORK_LEN];
        choose_mie(
            diameter_um,
            wavelength_um,
            m,
            tolerance,
            allow_table,
            &mut buf,
            &mut work,
        )
    })
    .map(found)
    .map_err(|e| refused("fit_mie(diameter_um, wavelength_um, m, tolerance)", e))
}

/// A model's name as the `Phase` constructors and `Fit.distances` spell it:
/// `TwoLobeHg` is `two_lobe_hg`.
fn snake(camel: &str) -> String {
    let mut s = String::new();
    for (i, c) in camel.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                s.push('_');
            }
            s.push(c.to_ascii_lowercase());
        } else {
            s.push(c);
        }
    }
    s
}
