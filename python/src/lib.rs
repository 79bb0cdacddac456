//! `scatterkit._scatterkit`: the compiled half of the Python package. It
//! takes and returns contiguous 1-D float64 numpy arrays (the Python half,
//! `scatterkit/__init__.py`, converts array-likes, restores shapes and
//! holds the docstrings users read), runs the library's kernels with the
//! GIL released, and turns the library's errors into `ValueError`.

mod albedo;
mod choose;
mod medium;
mod mie;
mod phase;
mod spectral;
mod stokes;
mod table2d;

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

pub(crate) type Array<'py> = Bound<'py, PyArray1<f64>>;

/// The library's error as Python's `ValueError`, with what was refused.
pub(crate) fn refused(what: &str, e: scatterkit::Error) -> PyErr {
    PyValueError::new_err(format!("{what}: {e}"))
}

/// A new array of `n` values filled by `f` with the GIL released. The
/// array is numpy's own allocation (which asks the kernel for huge pages
/// on large arrays), so a large result costs fewer page faults than a
/// `Vec` handed over.
pub(crate) fn filled<'py, E: Send>(
    py: Python<'py>,
    n: usize,
    f: impl FnOnce(&mut [f64]) -> Result<(), E> + Send,
) -> PyResult<Result<Array<'py>, E>> {
    let out = PyArray1::<f64>::zeros(py, n, false);
    let r = {
        let mut rw = out.readwrite();
        let slice = rw.as_slice_mut()?;
        py.detach(|| f(slice))
    };
    Ok(r.map(|()| out))
}

/// Runs `f` over matching chunks of `u` and `out` on up to as many threads
/// as the processor has, for long arrays (at least 2¹⁶ values per thread);
/// the first error wins. The chunks are the same values as one call would
/// see, so the results are the same bits.
pub(crate) fn par_chunks<E: Send>(
    u: &[f64],
    out: &mut [f64],
    f: impl Fn(&[f64], &mut [f64]) -> Result<(), E> + Sync,
) -> Result<(), E> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = threads.min(u.len() >> 16).max(1);
    if threads == 1 || u.len() != out.len() {
        return f(u, out);
    }
    let chunk = u.len().div_ceil(threads);
    std::thread::scope(|scope| {
        let handles: Vec<_> = u
            .chunks(chunk)
            .zip(out.chunks_mut(chunk))
            .map(|(a, b)| {
                let f = &f;
                scope.spawn(move || f(a, b))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect::<Result<Vec<()>, E>>()
            .map(|_| ())
    })
}

/// Whether every value lies in `[0, 1]` (NaN fails): the library's own
/// check of uniforms.
pub(crate) fn uniforms_ok(u: &[f64]) -> bool {
    scatterkit::phase::check_uniforms(u).is_ok()
}

/// Whether `v` has unit length within 10⁻⁶ (NaN fails).
pub(crate) fn is_unit(v: scatterkit::Vec3<f64>) -> bool {
    let n = (v.x * v.x + v.y * v.y + v.z * v.z).sqrt();
    (n - 1.0).abs() <= 1e-6
}

/// Applies `f` to every element of `x` with the GIL released.
pub(crate) fn map<'py>(
    py: Python<'py>,
    x: &PyReadonlyArray1<'py, f64>,
    f: impl Fn(f64) -> f64 + Send + Sync,
) -> PyResult<Array<'py>> {
    let xs = x.as_slice()?;
    let out = filled(py, xs.len(), |o| {
        for (o, &v) in o.iter_mut().zip(xs) {
            *o = f(v);
        }
        Ok::<(), std::convert::Infallible>(())
    })?;
    let Ok(out) = out;
    Ok(out)
}

/// The compiled module.
#[pymodule]
fn _scatterkit(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<phase::PyPhase>()?;
    m.add_class::<mie::PyMie>()?;
    m.add_class::<albedo::PyAlbedo>()?;
    m.add_class::<medium::PyMedium>()?;
    m.add_class::<stokes::PyRayleighPolarized>()?;
    m.add_class::<table2d::PyTable2d>()?;
    m.add_class::<spectral::PySpectralPhase>()?;
    m.add_function(wrap_pyfunction!(mie::water_index, m)?)?;
    m.add_function(wrap_pyfunction!(mie::size_parameter, m)?)?;
    m.add_function(wrap_pyfunction!(choose::fit_measured, m)?)?;
    m.add_function(wrap_pyfunction!(mie::polydisperse, m)?)?;
    m.add_function(wrap_pyfunction!(medium::equiangular, m)?)?;
    m.add_function(wrap_pyfunction!(mie::default_range, m)?)?;
    m.add_function(wrap_pyfunction!(choose::fit_mie, m)?)?;
    Ok(())
}
