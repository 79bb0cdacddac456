"""Every public callable of the package with bad input, one argument at a
time: whatever it does, it may only raise an ``Exception`` (``ValueError``,
``TypeError``, ``OverflowError``, ...), never a ``BaseException`` that is not
one (pyo3's ``PanicException``, which ``except Exception`` misses), and never
crash the interpreter (a crash ends the run, and the test with it).

Each call takes valid arguments (small and cheap) with one replaced by each
of the bad inputs below (at least 50 for every argument): NaN and infinities,
huge and negative numbers, complex numbers, strings, None, empty, ragged and
wrongly shaped lists and arrays, arrays of the wrong dtype (complex, object,
strings, datetimes, integers, float32), read-only, non-contiguous and
Fortran-ordered arrays, and aliasing (``out`` the same array as ``u``).
Counts (``n``, ``paths``, ``intervals``) are not given huge valid values: a
call asked for 2^40 paths may run as asked.
"""

import math
import unittest

import numpy as np

import scatterkit as sk
from scatterkit import conventions as cv
from scatterkit import mitsuba as skmi

NAN, INF = math.nan, math.inf


def _read_only():
    a = np.linspace(0.1, 0.9, 5)
    a.setflags(write=False)
    return a


def _bad_values():
    a2 = np.arange(12.0).reshape(3, 4)
    return [
        NAN, INF, -INF, 1e308, -1e308, 5e-324, -0.0, 0, -1, 1.5, -3.0, 2, 1e30, -1e30,
        True, complex(1, 1), 1j, "x", b"x", None, object(), [], [[]], [NAN], [1, "a"],
        [[1, 2], [3]], (1, 2, 3), {}, {1, 2}, range(5), np.array(NAN), np.array([NAN, INF]),
        np.array([1 + 1j]), np.zeros((2, 3)), np.zeros(0), np.zeros((0, 3)), np.array(["a"]),
        np.array([None], dtype=object), np.float32([0.5]), np.int64([1]), np.uint8([1]),
        np.bool_([True]), _read_only(), np.linspace(0, 1, 10)[::2], np.asfortranarray(a2),
        np.ones((3, 3, 3)), np.full(5, 1e308), np.array([[0.5]]), np.array(["2020-01-01"], dtype="datetime64[D]"),
        np.ma.masked_array([0.5, 0.2], mask=[True, False]), np.full(3, -0.5), np.array([-1.0, 2.0]),
        np.array([1e-320]), memoryview(b"abc"), float("nan") * np.ones((2, 2, 2)),
    ]


BAD = _bad_values()
COUNT_NAMES = {"n", "paths", "intervals", "points", "hero"}


class Call:
    """A callable with valid positional and keyword arguments."""

    def __init__(self, name, f, args=(), kwargs=None):
        self.name, self.f, self.args, self.kwargs = name, f, list(args), dict(kwargs or {})


def _calls():
    hg = sk.Phase.henyey_greenstein(0.7)
    mie = sk.Mie(5.0, 1.33 + 0.001j)
    med = sk.Medium(np.ones((4, 4, 4)), 0.2, 0.8)
    rp = sk.RayleighPolarized(0.03)
    t2 = sk.Table2d([sk.Phase.henyey_greenstein(0.2), hg], 0.0, 1.0, 16)
    sp = sk.SpectralPhase([hg, sk.Phase.isotropic()])
    curve = sk.AlbedoCurve(hg, 1.0, 0.5, paths=500)
    mu = np.linspace(-1, 1, 5)
    u = np.linspace(0.05, 0.95, 5)
    o, d = np.array([[0.5, 0.5, -1.0]]), np.array([[0.0, 0.0, 1.0]])
    k, s, r = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.5, 0.0, 0.0]), np.array([1.0, 0.0, 0.0])
    w = np.array([0.0, 1.0, 0.0])
    P = sk.Phase
    calls = [
        Call("Phase.isotropic", P.isotropic),
        Call("Phase.rayleigh", P.rayleigh),
        Call("Phase.rayleigh_depolarized", P.rayleigh_depolarized, [0.03]),
        Call("Phase.henyey_greenstein", P.henyey_greenstein, [0.7]),
        Call("Phase.two_lobe_hg", P.two_lobe_hg, [0.8, -0.3, 0.9]),
        Call("Phase.draine", P.draine, [0.7, 1.0]),
        Call("Phase.cornette_shanks", P.cornette_shanks, [0.7]),
        Call("Phase.fog", P.fog, [0.9, 0.5, 10.0, 0.4]),
        Call("Phase.fog_diameter", P.fog_diameter, [10.0]),
        Call("Phase.gegenbauer", P.gegenbauer, [0.5, 0.7]),
        Call("Phase.fournier_forand", P.fournier_forand, [1.1, 3.5]),
        Call("Phase.fournier_forand_backscatter", P.fournier_forand_backscatter, [0.02, 1.1]),
        Call("Phase.mixture", P.mixture, [[(hg, 0.5), (P.isotropic(), 0.5)]]),
        Call("Phase.legendre_series", P.legendre_series, [[1.0, 0.5, 0.2]]),
        Call("Phase.table", P.table, [hg], {"n": 16}),
        Call("Phase.table_measured", P.table_measured, [mu, np.ones(5)], {"n": 16}),
        Call("Phase.pdf", hg.pdf, [mu]),
        Call("Phase.cdf", hg.cdf, [mu]),
        Call("Phase.sample_cos", hg.sample_cos, [u]),
        Call("Phase.sample_cos out", hg.sample_cos, [u], {"out": np.empty(5)}),
        Call("Phase.sample_cos rng", hg.sample_cos, [], {"rng": np.random.default_rng(1), "size": 4}),
        Call("Phase.sample_cos_portable", hg.sample_cos_portable, [u]),
        Call("Phase.sample_dir", hg.sample_dir, [k, 0.3, 0.6]),
        Call("Phase.legendre", hg.legendre, [4]),
        Call("Mie", sk.Mie, [5.0, 1.33 + 0.001j]),
        Call("Mie.phase", mie.phase, [mu]),
        Call("Mie.amplitudes", mie.amplitudes, [mu]),
        Call("Mie.legendre", mie.legendre, [4]),
        Call("water_index", sk.water_index, [0.55]),
        Call("size_parameter", sk.size_parameter, [10.0, 0.55]),
        Call("AlbedoCurve", sk.AlbedoCurve, [hg, 1.0, 0.5], {"paths": 200}),
        Call("AlbedoCurve.albedo", curve.albedo, [0.9]),
        Call("AlbedoCurve.std_error", curve.std_error, [0.9]),
        Call("AlbedoCurve.single_scattering_albedo", curve.single_scattering_albedo, [0.3]),
        Call("Medium", sk.Medium, [np.ones((4, 4, 4)), 0.2, 0.8]),
        Call("Medium.sigma_t", med.sigma_t, [np.array([[0.5, 0.5, 0.5]])]),
        Call("Medium.transmittance", med.transmittance, [o, d, 3.0]),
        Call("Medium.emission", med.emission, [np.ones((4, 4, 4)), o, d, 3.0]),
        Call("Medium.spectral_track", med.spectral_track, [o, d, [0.1, 0.2], [0.5, 0.9]]),
        Call("Medium.delta_track", med.delta_track, [o, d, 3.0]),
        Call("RayleighPolarized", sk.RayleighPolarized, [0.03]),
        Call("RayleighPolarized.mueller", rp.mueller, [mu]),
        Call("RayleighPolarized.sample", rp.sample, [k, s, r, 0.3, 0.6]),
        Call("RayleighPolarized.eval", rp.eval, [k, s, r, w, np.array([1.0, 0.0, 0.0])]),
        Call("RayleighPolarized.pdf", rp.pdf, [k, s, r, w]),
        Call("fit", sk.fit, [mu, hg.pdf(mu)]),
        Call("fit_mie", sk.fit_mie, [2.0, 0.55, 1.33 + 0j]),
        Call("polydisperse", sk.polydisperse, [("lognormal", 1.0, 0.3)],
             {"wavelength": 0.55, "m": 1.33 + 0j, "intervals": 8, "r_min": 0.5, "r_max": 2.0}),
        Call("equiangular", sk.equiangular, [o, d, np.array([1.0, 0.0, 0.0]), 0.5]),
        Call("Table2d", sk.Table2d, [[hg, P.isotropic()], 0.0, 1.0, 16]),
        Call("Table2d.pdf", t2.pdf, [0.5, mu]),
        Call("Table2d.cdf", t2.cdf, [0.5, mu]),
        Call("Table2d.sample_cos", t2.sample_cos, [0.5, u]),
        Call("Table2d.mean_cosine", t2.mean_cosine, [0.5]),
        Call("SpectralPhase", sk.SpectralPhase, [[hg, P.isotropic()]]),
        Call("SpectralPhase.pdf", sp.pdf, [mu]),
        Call("SpectralPhase.sample_cos", sp.sample_cos, [0, u]),
        Call("Phase.schlick", P.schlick, [0.5]),
        Call("Phase.modified_hg", P.modified_hg, [0.6, 1.4]),
        Call("Phase.modified_hg_delta", P.modified_hg_delta, [0.6, 1.8]),
        Call("Phase.two_lobe_hg_gamma", P.two_lobe_hg_gamma, [0.6, 1.4]),
        Call("Phase.two_lobe_hg_delta", P.two_lobe_hg_delta, [0.6, 1.8]),
        Call("Phase.gegenbauer_gamma", P.gegenbauer_gamma, [0.6, 1.5]),
        Call("Phase.gegenbauer_delta", P.gegenbauer_delta, [0.6, 2.0]),
        Call("conventions.legendre_with_2l1", cv.legendre_with_2l1, [[1.0, 1.5]]),
        Call("conventions.legendre_without_2l1", cv.legendre_without_2l1, [[1.0, 0.5]]),
        Call("conventions.legendre_moments_of", cv.legendre_moments_of, [mu, hg.pdf(mu), 3]),
        Call("conventions.legendre_series", cv.legendre_series, [[1.0, 0.5], mu]),
        Call("conventions.convert_normalization", cv.convert_normalization, [hg.pdf(mu), "sr", "4pi"]),
        Call("conventions.mu_from_angle", cv.mu_from_angle, [30.0], {"degrees": True}),
        Call("conventions.angle_from_mu", cv.angle_from_mu, [0.5], {"degrees": True}),
        Call("conventions.to_mitsuba_tabphase", cv.to_mitsuba_tabphase, [hg], {"n": 9, "tolerance": INF}),
        Call("conventions.to_mcx_invcdf", cv.to_mcx_invcdf, [hg], {"n": 10}),
        # scatterkit.mitsuba's calls that need no Mitsuba (the rest register
        # plugins; python/tests/test_mitsuba.py covers them).
        Call("mitsuba.phase_from_properties", skmi.phase_from_properties, [{"model": "draine", "g": 0.5, "alpha": 1.0}]),
        Call("mitsuba.native", skmi.native, [hg], {"n": 8, "density_points": 9}),
        Call("mitsuba.register_phase", skmi.register_phase, ["x", hg]),
    ]
    return calls


def _variants(call):
    """The call with one argument replaced by each bad value, and (for
    ``out``) aliased with its input."""
    for i in range(len(call.args)):
        for bad in BAD:
            args = list(call.args)
            args[i] = bad
            yield f"{call.name} arg {i} = {bad!r}"[:160], args, call.kwargs
    for key in call.kwargs:
        for bad in BAD:
            if key in COUNT_NAMES and isinstance(bad, (int, float)) and not isinstance(bad, bool) \
                    and bad == bad and 1e6 < abs(bad) < 2.0 ** 64:
                continue  # a huge valid count runs as long as asked
            kwargs = dict(call.kwargs)
            kwargs[key] = bad
            yield f"{call.name} {key} = {bad!r}"[:160], call.args, kwargs
    if "out" in call.kwargs and call.args:
        a = np.linspace(0.1, 0.9, 5)
        yield f"{call.name} out aliasing u", [a], {**call.kwargs, "out": a}


class NeverPanics(unittest.TestCase):
    def test_every_public_callable_with_bad_input(self):
        calls = _calls()
        self.assertGreaterEqual(len(BAD), 50)
        names = {c.name.split(" ")[0] for c in calls}
        public = set(sk.__all__) - {"Fit", "Averages", "conventions", "get_include"}
        for n in public:
            self.assertTrue(any(x == n or x.startswith(n + ".") for x in names), f"{n} is not fuzzed")
        failures, counted = [], 0
        for call in calls:
            for label, args, kwargs in _variants(call):
                counted += 1
                try:
                    call.f(*args, **kwargs)
                except Exception:
                    pass
                except BaseException as e:  # PanicException and the like
                    failures.append(f"{label}: {type(e).__name__}: {e}"[:300])
        print(f"{counted} bad calls over {len(calls)} callables")
        self.assertEqual(failures, [], "\n".join(failures[:20]))


if __name__ == "__main__":
    unittest.main()
