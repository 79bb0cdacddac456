//! Heterogeneous media: a density grid with its majorant and minorant
//! grids, and every transmittance estimator and free-flight sampler over
//! arrays of rays.

use crate::{Array, refused};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;
use scatterkit::medium::Event;
use scatterkit::medium::equiangular::Equiangular;
use scatterkit::medium::ray_march::{Placement, Series, march_grid_within};
use scatterkit::medium::residual::Extrema;
use scatterkit::medium::spectral::{Ratios, Spectrum};
use scatterkit::{Error, Grid, Majorants, Ray, Sampling, Vec3};

/// A density grid over a box, with its majorants and minorants, owned.
#[pyclass(name = "_Medium", module = "scatterkit._scatterkit", frozen)]
#[derive(Debug)]
pub(crate) struct PyMedium {
    density: Vec<f64>,
    n: [usize; 3],
    sigma: (f64, f64),
    max_density: f64,
    bounds: (Vec3<f64>, Vec3<f64>),
    sampling: Sampling,
    m: [usize; 3],
    max: Vec<f64>,
    min: Vec<f64>,
}

/// The estimators `transmittance` takes by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Estimator {
    Delta,
    Ratio,
    Residual,
    RayMarch,
    Telescoping,
}

impl Estimator {
    fn parse(name: &str) -> PyResult<Self> {
        Ok(match name {
            "delta" => Estimator::Delta,
            "ratio" => Estimator::Ratio,
            "residual" => Estimator::Residual,
            "ray_march" => Estimator::RayMarch,
            "telescoping" => Estimator::Telescoping,
            _ => {
                return Err(PyValueError::new_err(format!(
                    "transmittance: estimator {name:?} is not one of \"delta\", \"ratio\", \
                     \"residual\", \"ray_march\", \"telescoping\""
                )));
            }
        })
    }
}

impl PyMedium {
    fn grid(&self) -> Grid<'_, f64> {
        Grid::from_parts(
            &self.density,
            self.n,
            self.sigma.0,
            self.sigma.1,
            self.max_density,
            self.bounds,
            self.sampling,
        )
        .expect("checked when built")
    }

    fn extrema(&self) -> Extrema<'_, f64> {
        let (lo, hi) = self.bounds;
        let max = Majorants::from_parts(&self.max, self.m, lo, hi).expect("built");
        let min = Majorants::from_parts(&self.min, self.m, lo, hi).expect("built");
        Extrema::new(max, min).expect("built together")
    }
}

/// The rays of `origins`, `dirs` (3 values each) and `t_max`, checked for
/// length.
fn rays(origins: &[f64], dirs: &[f64], t_max: &[f64]) -> PyResult<Vec<Ray<f64>>> {
    if origins.len() != dirs.len() || origins.len() != 3 * t_max.len() {
        return Err(PyValueError::new_err(
            "origins and dirs must be (n, 3) arrays and t_max n values",
        ));
    }
    Ok(origins
        .chunks_exact(3)
        .zip(dirs.chunks_exact(3))
        .zip(t_max)
        .map(|((o, d), &t)| Ray::new(Vec3::new(o[0], o[1], o[2]), Vec3::new(d[0], d[1], d[2]), t))
        .collect())
}

/// One transmittance estimate along `ray` by `how`; `strata`: the
/// marchers' strata or residual tracking's rate, 0 the library's choice.
fn estimate(
    how: Estimator,
    grid: &Grid<'_, f64>,
    ext: &Extrema<'_, f64>,
    ray: Ray<f64>,
    (strata, budget): (u32, u32),
    rng: &mut Xoshiro256PlusPlus,
) -> Result<f64, Error> {
    let maj = ext.majorants();
    match how {
        Estimator::Delta => maj
            .delta_track(grid, ray, budget, rng)
            .map(|t| f64::from(u8::from(t.event == Event::Escaped))),
        Estimator::Ratio => maj.ratio_track(grid, ray, budget, rng).map(|t| t.tr),
        Estimator::Residual => {
            let coefficients = |p| grid.coefficients_at(p);
            ext.residual_ratio_track_rate(coefficients, ray, strata, budget, rng)
                .map(|t| t.tr)
        }
        Estimator::RayMarch | Estimator::Telescoping => {
            // Strata placed by the majorants and minorants, as many as the
            // library chooses for `strata` 0.
            let series = if how == Estimator::RayMarch {
                Series::Power
            } else {
                Series::Telescoping
            };
            let place = Placement {
                max: maj,
                min: Some(ext.minorants()),
            };
            march_grid_within(series, place, grid, ray, strata, budget, rng).map(|t| t.tr)
        }
    }
}

#[pymethods]
impl PyMedium {
    /// `density`: nx·ny·nz values, x fastest; `cells`: the majorant grid.
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        density: PyReadonlyArray1<'_, f64>,
        n: [usize; 3],
        sigma_a: f64,
        sigma_s: f64,
        lo: [f64; 3],
        hi: [f64; 3],
        cell_centred: bool,
        cells: [usize; 3],
    ) -> PyResult<Self> {
        let density = density.as_slice()?.to_vec();
        let (lo, hi) = (
            Vec3::new(lo[0], lo[1], lo[2]),
            Vec3::new(hi[0], hi[1], hi[2]),
        );
        let sampling = if cell_centred {
            Sampling::Cells
        } else {
            Sampling::Nodes
        };
        // At most 2²⁴ majorant cells (256 per axis): the two grids are
        // allocated here, and an allocation that fails would abort Python.
        let count = scatterkit::majorant::majorant_len(cells)
            .filter(|&c| c <= 1 << 24)
            .ok_or_else(|| {
                PyValueError::new_err(
                    "Medium: majorant cells must be positive, at most 2^24 in all",
                )
            })?;
        py.detach(|| {
            let grid = Grid::new(&density, n[0], n[1], n[2], sigma_a, sigma_s)?
                .with_box(lo, hi)?
                .with_sampling(sampling);
            let (mut max, mut min) = (vec![0.0; count], vec![0.0; count]);
            Extrema::build(&grid, cells, &mut max, &mut min)?;
            Ok::<_, Error>((max, min))
        })
        .map(|(max, min)| PyMedium {
            n,
            sigma: (sigma_a, sigma_s),
            // Every value is finite and >= 0: Grid::new checked them.
            max_density: density.iter().copied().fold(0.0, f64::max),
            density,
            bounds: (lo, hi),
            sampling,
            m: cells,
            max,
            min,
        })
        .map_err(|e| refused("Medium(density, sigma_a, sigma_s, lo, hi, cells)", e))
    }

    /// The majorants (per length unit), x fastest.
    fn majorants<'py>(&self, py: Python<'py>) -> Array<'py> {
        self.max.clone().into_pyarray(py)
    }

    /// The minorants (per length unit), x fastest.
    fn minorants<'py>(&self, py: Python<'py>) -> Array<'py> {
        self.min.clone().into_pyarray(py)
    }

    /// `σ_t` at points (3 values each).
    fn sigma_t<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Array<'py>> {
        let p = points.as_slice()?;
        if p.len() % 3 != 0 {
            return Err(PyValueError::new_err(
                "sigma_t: points must be an (n, 3) array",
            ));
        }
        let grid = self.grid();
        let out: Vec<f64> = py.detach(|| {
            p.chunks_exact(3)
                .map(|q| grid.sigma_t(Vec3::new(q[0], q[1], q[2])))
                .collect()
        });
        Ok(out.into_pyarray(py))
    }

    /// One transmittance estimate per ray by the named estimator.
    #[allow(clippy::too_many_arguments)]
    fn transmittance<'py>(
        &self,
        py: Python<'py>,
        origins: PyReadonlyArray1<'py, f64>,
        dirs: PyReadonlyArray1<'py, f64>,
        t_max: PyReadonlyArray1<'py, f64>,
        estimator: &str,
        seed: u64,
        budget: u32,
        strata: u32,
    ) -> PyResult<Array<'py>> {
        let how = Estimator::parse(estimator)?;
        let rays = rays(origins.as_slice()?, dirs.as_slice()?, t_max.as_slice()?)?;
        let (grid, ext) = (self.grid(), self.extrema());
        let out: Result<Vec<f64>, Error> = py.detach(|| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            rays.iter()
                .map(|&ray| estimate(how, &grid, &ext, ray, (strata, budget), &mut rng))
                .collect()
        });
        Ok(out
            .map_err(|e| refused(&format!("transmittance(estimator={estimator:?})"), e))?
            .into_pyarray(py))
    }

    /// The seconds the estimator's loop over the rays takes inside Rust,
    /// without the conversions of the Python call: the benchmark's
    /// reference for the same call made from Rust (`examples/speed.py`).
    #[allow(clippy::too_many_arguments)]
    fn seconds_in_rust(
        &self,
        py: Python<'_>,
        origins: PyReadonlyArray1<'_, f64>,
        dirs: PyReadonlyArray1<'_, f64>,
        t_max: PyReadonlyArray1<'_, f64>,
        estimator: &str,
        seed: u64,
        budget: u32,
    ) -> PyResult<f64> {
        let how = Estimator::parse(estimator)?;
        let rays = rays(origins.as_slice()?, dirs.as_slice()?, t_max.as_slice()?)?;
        let (grid, ext) = (self.grid(), self.extrema());
        let start = std::time::Instant::now();
        let sum: Result<f64, Error> = py.detach(|| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            rays.iter()
                .map(|&ray| estimate(how, &grid, &ext, ray, (0, budget), &mut rng))
                .sum()
        });
        let seconds = start.elapsed().as_secs_f64();
        sum.map_err(|e| refused("seconds_in_rust", e))?;
        Ok(seconds)
    }

    /// The emitted radiance along each ray (and the ray's transmittance):
    /// `source` is an emission grid of `ns` values (x fastest) over the
    /// medium's box, sampled as the density is.
    #[allow(clippy::too_many_arguments)]
    fn emission<'py>(
        &self,
        py: Python<'py>,
        origins: PyReadonlyArray1<'py, f64>,
        dirs: PyReadonlyArray1<'py, f64>,
        t_max: PyReadonlyArray1<'py, f64>,
        source: PyReadonlyArray1<'py, f64>,
        ns: [usize; 3],
        seed: u64,
        budget: u32,
    ) -> PyResult<(Array<'py>, Array<'py>)> {
        let rays = rays(origins.as_slice()?, dirs.as_slice()?, t_max.as_slice()?)?;
        let src = source.as_slice()?;
        let (lo, hi) = self.bounds;
        let emitter = Grid::new(src, ns[0], ns[1], ns[2], 0.0, 1.0)
            .and_then(|g| g.with_box(lo, hi))
            .map(|g| g.with_sampling(self.sampling))
            .map_err(|e| refused("emission: the source grid", e))?;
        let (grid, ext) = (self.grid(), self.extrema());
        let out: Result<Vec<(f64, f64)>, Error> = py.detach(|| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            let maj = ext.majorants();
            rays.iter()
                .map(|&ray| {
                    maj.emission_track(&grid, |p| emitter.density(p), ray, budget, &mut rng)
                        .map(|e| (e.radiance, e.tr))
                })
                .collect()
        });
        let (l, tr): (Vec<f64>, Vec<f64>) =
            out.map_err(|e| refused("emission", e))?.into_iter().unzip();
        Ok((l.into_pyarray(py), tr.into_pyarray(py)))
    }

    /// Hero-wavelength delta tracking (`ratio` false) or ratio tracking
    /// (`ratio` true) per ray: per-channel coefficients per unit density,
    /// the hero per ray; the distances (or the tentative-collision counts
    /// for ratio tracking), the events and per channel (`n·c`, row-major)
    /// the weights and the ratios `r_u`, `r_l`.
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
    fn spectral<'py>(
        &self,
        py: Python<'py>,
        origins: PyReadonlyArray1<'py, f64>,
        dirs: PyReadonlyArray1<'py, f64>,
        t_max: PyReadonlyArray1<'py, f64>,
        sigma_a: Vec<f64>,
        sigma_s: Vec<f64>,
        heroes: Vec<usize>,
        ratio: bool,
        seed: u64,
        budget: u32,
    ) -> PyResult<(Array<'py>, Array<'py>, Array<'py>, Array<'py>, Array<'py>)> {
        let rays = rays(origins.as_slice()?, dirs.as_slice()?, t_max.as_slice()?)?;
        if heroes.len() != rays.len() {
            return Err(PyValueError::new_err("spectral: one hero per ray"));
        }
        let c = sigma_a.len();
        let grid = self.grid();
        let mut dens = vec![0.0; self.max.len()];
        let maj = Majorants::build_density(&grid, self.m, &mut dens)
            .map_err(|e| refused("spectral: density majorants", e))?;
        type Row = (f64, f64, Vec<f64>, Vec<f64>, Vec<f64>);
        let out: Result<Vec<Row>, Error> = py.detach(|| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            rays.iter()
                .zip(&heroes)
                .map(|(&ray, &hero)| {
                    let spectrum = Spectrum {
                        sigma_a: &sigma_a,
                        sigma_s: &sigma_s,
                        hero,
                    };
                    let (mut w, mut ru, mut rl) = (vec![0.0; c], vec![0.0; c], vec![0.0; c]);
                    let mut ratios = Ratios {
                        weight: &mut w,
                        r_u: &mut ru,
                        r_l: &mut rl,
                    };
                    let (t, ev) = if ratio {
                        let steps = maj.ratio_track_spectral(
                            &grid,
                            &spectrum,
                            ray,
                            budget,
                            &mut rng,
                            &mut ratios,
                        )?;
                        (f64::from(steps), 0.0)
                    } else {
                        let tr = maj.delta_track_spectral(
                            &grid,
                            &spectrum,
                            ray,
                            budget,
                            &mut rng,
                            &mut ratios,
                        )?;
                        (tr.t, f64::from(tr.event as u32))
                    };
                    Ok((t, ev, w, ru, rl))
                })
                .collect()
        });
        let rows = out.map_err(|e| refused("spectral tracking", e))?;
        let (mut t, mut ev) = (
            Vec::with_capacity(rows.len()),
            Vec::with_capacity(rows.len()),
        );
        let (mut w, mut ru, mut rl) = (Vec::new(), Vec::new(), Vec::new());
        for (a, b, x, y, z) in rows {
            t.push(a);
            ev.push(b);
            w.extend(x);
            ru.extend(y);
            rl.extend(z);
        }
        Ok((
            t.into_pyarray(py),
            ev.into_pyarray(py),
            w.into_pyarray(py),
            ru.into_pyarray(py),
            rl.into_pyarray(py),
        ))
    }

    /// Delta tracking per ray: the distance to the real collision (or
    /// where the ray leaves), and the event (0 escaped, 1 scattered, 2
    /// absorbed).
    fn delta_track<'py>(
        &self,
        py: Python<'py>,
        origins: PyReadonlyArray1<'py, f64>,
        dirs: PyReadonlyArray1<'py, f64>,
        t_max: PyReadonlyArray1<'py, f64>,
        seed: u64,
        budget: u32,
    ) -> PyResult<(Array<'py>, Array<'py>)> {
        let rays = rays(origins.as_slice()?, dirs.as_slice()?, t_max.as_slice()?)?;
        let (grid, ext) = (self.grid(), self.extrema());
        let out: Result<Vec<(f64, f64)>, Error> = py.detach(|| {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            let maj = ext.majorants();
            rays.iter()
                .map(|&ray| {
                    maj.delta_track(&grid, ray, budget, &mut rng)
                        .map(|t| (t.t, f64::from(t.event as u32)))
                })
                .collect()
        });
        let out = out.map_err(|e| refused("delta_track", e))?;
        let (t, ev): (Vec<f64>, Vec<f64>) = out.into_iter().unzip();
        Ok((t.into_pyarray(py), ev.into_pyarray(py)))
    }
}

/// Equiangular sampling per ray toward a point: the distances (within
/// `[t_min, t_max]`) and their densities per unit length.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub(crate) fn equiangular<'py>(
    py: Python<'py>,
    origins: PyReadonlyArray1<'py, f64>,
    dirs: PyReadonlyArray1<'py, f64>,
    t_min: PyReadonlyArray1<'py, f64>,
    t_max: PyReadonlyArray1<'py, f64>,
    points: PyReadonlyArray1<'py, f64>,
    u: PyReadonlyArray1<'py, f64>,
) -> PyResult<(Array<'py>, Array<'py>)> {
    let (t0, p, u) = (t_min.as_slice()?, points.as_slice()?, u.as_slice()?);
    let rays = rays(origins.as_slice()?, dirs.as_slice()?, t_max.as_slice()?)?;
    if t0.len() != rays.len() || p.len() != 3 * rays.len() || u.len() != rays.len() {
        return Err(PyValueError::new_err(
            "equiangular: one t_min, point (3 values) and uniform per ray",
        ));
    }
    let out: Result<Vec<(f64, f64)>, Error> = py.detach(|| {
        rays.iter()
            .zip(t0)
            .zip(p.chunks_exact(3).zip(u))
            .map(|((&ray, &a), (q, &x))| {
                let e = Equiangular::new(ray.segment(a, ray.t_max), Vec3::new(q[0], q[1], q[2]))?;
                let t = e.sample(x);
                Ok((t, e.pdf(t)))
            })
            .collect()
    });
    let (t, pdf): (Vec<f64>, Vec<f64>) = out
        .map_err(|e| refused("equiangular(origins, dirs, t_min, t_max, points, u)", e))?
        .into_iter()
        .unzip();
    Ok((t.into_pyarray(py), pdf.into_pyarray(py)))
}
