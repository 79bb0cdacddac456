//! Polarised Rayleigh scattering with Stokes vectors, over arrays.

use crate::{Array, is_unit, refused, uniforms_ok};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use scatterkit::{Error, RayleighPolarized, Stokes, Vec3};

/// Polarised Rayleigh scattering with depolarisation factor `rho`.
#[pyclass(name = "_RayleighPolarized", module = "scatterkit._scatterkit", frozen)]
#[derive(Debug)]
pub(crate) struct PyRayleighPolarized {
    model: RayleighPolarized<f64>,
}

fn v3(c: &[f64]) -> Vec3<f64> {
    Vec3::new(c[0], c[1], c[2])
}

/// Checks that `k`, `s` (4 per row) and `r` (3 per row) describe one
/// count of rows; the count.
fn rows(k: &[f64], s: &[f64], r: &[f64]) -> PyResult<usize> {
    let n = k.len() / 3;
    if k.len() % 3 != 0 || s.len() != 4 * n || r.len() != 3 * n {
        return Err(PyValueError::new_err(
            "directions (n, 3), Stokes vectors (n, 4) and references (n, 3) must agree",
        ));
    }
    Ok(n)
}

/// The Stokes vectors of the rows, checked.
fn stokes(s: &[f64], r: &[f64]) -> Result<Vec<Stokes<f64>>, Error> {
    s.chunks_exact(4)
        .zip(r.chunks_exact(3))
        .map(|(s, r)| Stokes::new(s[0], s[1], s[2], s[3], v3(r)))
        .collect()
}

#[pymethods]
impl PyRayleighPolarized {
    #[new]
    fn new(rho: f64) -> PyResult<Self> {
        RayleighPolarized::new(rho)
            .map(|model| PyRayleighPolarized { model })
            .map_err(|e| refused("RayleighPolarized(rho)", e))
    }

    /// `P11, P12, P22, P33, P44` at each cosine, as five arrays.
    #[allow(clippy::type_complexity)]
    fn mueller<'py>(
        &self,
        py: Python<'py>,
        mu: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Array<'py>, Array<'py>, Array<'py>, Array<'py>, Array<'py>)> {
        let m = mu.as_slice()?;
        let rows: Vec<_> = m.iter().map(|&c| self.model.mueller(c)).collect();
        let col = |f: fn(&scatterkit::phase::RayleighMueller<f64>) -> f64| {
            rows.iter().map(f).collect::<Vec<f64>>().into_pyarray(py)
        };
        Ok((
            col(|r| r.p11),
            col(|r| r.p12),
            col(|r| r.p22),
            col(|r| r.p33),
            col(|r| r.p44),
        ))
    }

    /// Samples per row: the directions (3n), the Stokes vectors (4n) and
    /// their references (3n), and the densities (n).
    #[allow(clippy::type_complexity)]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        k: PyReadonlyArray1<'py, f64>,
        s: PyReadonlyArray1<'py, f64>,
        r: PyReadonlyArray1<'py, f64>,
        u1: PyReadonlyArray1<'py, f64>,
        u2: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<(Array<'py>, Array<'py>, Array<'py>, Array<'py>)> {
        let (k, s, r, a, b) = (
            k.as_slice()?,
            s.as_slice()?,
            r.as_slice()?,
            u1.as_slice()?,
            u2.as_slice()?,
        );
        let n = rows(k, s, r)?;
        if a.len() != n || b.len() != n {
            return Err(PyValueError::new_err(
                "sample: one pair of uniforms per row",
            ));
        }
        if !(uniforms_ok(a) && uniforms_ok(b) && k.chunks_exact(3).all(|c| is_unit(v3(c)))) {
            return Err(PyValueError::new_err(
                "sample: directions must be unit vectors and uniforms lie in [0, 1]",
            ));
        }
        let sv = stokes(s, r).map_err(|e| refused("sample: a Stokes vector", e))?;
        let model = &self.model;
        let (d, so, ro, pdf) = py.detach(|| {
            let (mut d, mut so, mut ro, mut pdf) = (
                Vec::with_capacity(3 * n),
                Vec::with_capacity(4 * n),
                Vec::with_capacity(3 * n),
                Vec::with_capacity(n),
            );
            for (((kk, st), &x), &y) in k.chunks_exact(3).zip(&sv).zip(a).zip(b) {
                let out = model.sample(v3(kk), st, x, y);
                d.extend([out.dir.x, out.dir.y, out.dir.z]);
                let t = out.stokes;
                so.extend([t.i, t.q, t.u, t.v]);
                ro.extend([t.reference.x, t.reference.y, t.reference.z]);
                pdf.push(out.pdf);
            }
            (d, so, ro, pdf)
        });
        Ok((
            d.into_pyarray(py),
            so.into_pyarray(py),
            ro.into_pyarray(py),
            pdf.into_pyarray(py),
        ))
    }

    /// The scattered Stokes vectors (4n) into directions `w`, referred to
    /// `out_r`, per steradian.
    #[allow(clippy::too_many_arguments)]
    fn eval<'py>(
        &self,
        py: Python<'py>,
        k: PyReadonlyArray1<'py, f64>,
        s: PyReadonlyArray1<'py, f64>,
        r: PyReadonlyArray1<'py, f64>,
        w: PyReadonlyArray1<'py, f64>,
        out_r: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let (k, s, r, w, o) = (
            k.as_slice()?,
            s.as_slice()?,
            r.as_slice()?,
            w.as_slice()?,
            out_r.as_slice()?,
        );
        let n = rows(k, s, r)?;
        if w.len() != 3 * n || o.len() != 3 * n {
            return Err(PyValueError::new_err(
                "eval: one direction and one reference per row",
            ));
        }
        let sv = stokes(s, r).map_err(|e| refused("eval: a Stokes vector", e))?;
        let model = &self.model;
        let out: Vec<f64> = py.detach(|| {
            k.chunks_exact(3)
                .zip(&sv)
                .zip(w.chunks_exact(3).zip(o.chunks_exact(3)))
                .flat_map(|((kk, st), (ww, oo))| {
                    let t = model.eval(v3(kk), st, v3(ww), v3(oo));
                    [t.i, t.q, t.u, t.v]
                })
                .collect()
        });
        Ok(out.into_pyarray(py))
    }

    /// The density per steradian with which `sample` draws `w` (n).
    fn pdf<'py>(
        &self,
        py: Python<'py>,
        k: PyReadonlyArray1<'py, f64>,
        s: PyReadonlyArray1<'py, f64>,
        r: PyReadonlyArray1<'py, f64>,
        w: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let (k, s, r, w) = (k.as_slice()?, s.as_slice()?, r.as_slice()?, w.as_slice()?);
        let n = rows(k, s, r)?;
        if w.len() != 3 * n {
            return Err(PyValueError::new_err("pdf: one direction per row"));
        }
        let sv = stokes(s, r).map_err(|e| refused("pdf: a Stokes vector", e))?;
        let model = &self.model;
        let out: Vec<f64> = py.detach(|| {
            k.chunks_exact(3)
                .zip(&sv)
                .zip(w.chunks_exact(3))
                .map(|((kk, st), ww)| model.pdf(v3(kk), st, v3(ww)))
                .collect()
        });
        Ok(out.into_pyarray(py))
    }
}
