"""Every object a user builds pickles (as multiprocessing, Dask and joblib
send it to another process) and comes back giving the same bits: the
phase functions of every constructor (a fit's included), tables, mixtures,
Legendre series, Mie spheres, albedo curves (their traced nodes, not a new
tracing), media, polarised Rayleigh, 2-D tables and per-wavelength phase
functions. A state that is not one is a ValueError."""

import pickle
import unittest

import numpy as np

import scatterkit as sk

U = np.linspace(0.0, 1.0, 1001)
MU = np.linspace(-1.0, 1.0, 1001)


def _phases():
    hg = sk.Phase.henyey_greenstein(0.7)
    mu = np.linspace(-1.0, 1.0, 401)
    return [
        sk.Phase.isotropic(),
        sk.Phase.rayleigh(),
        sk.Phase.rayleigh_depolarized(0.03),
        hg,
        sk.Phase.two_lobe_hg(0.8, -0.3, 0.9),
        sk.Phase.draine(0.5, 2.0),
        sk.Phase.cornette_shanks(0.6),
        sk.Phase.fog(0.9, 0.4, 20.0, 0.3),
        sk.Phase.fog_diameter(10.0),
        sk.Phase.gegenbauer(1.0, 0.5),
        sk.Phase.fournier_forand(1.1, 3.5),
        sk.Phase.fournier_forand_backscatter(0.01, 1.1),
        sk.Phase.schlick(0.5),
        sk.Phase.modified_hg(0.6, 1.4),
        sk.Phase.two_lobe_hg_delta(0.6, 1.8),
        sk.Phase.gegenbauer_gamma(0.6, 1.5),
        # Weights that do not sum to 1: normalised again on unpickling, they
        # must come out bit for bit.
        sk.Phase.mixture([(sk.Phase.rayleigh(), 0.3), (hg, 0.1), (sk.Phase.draine(0.2, 1.0), 0.7)]),
        sk.Phase.legendre_series([1.0, 0.5, 0.2]),
        sk.Phase.table(sk.Phase.fog_diameter(5.0), 128),
        sk.Phase.table_measured(mu, hg.pdf(mu), 64),
        sk.fit(mu, sk.Phase.fog_diameter(3.0).pdf(mu), tolerance=0.2).phase,
    ]


def _same(a, b):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


class Pickling(unittest.TestCase):
    def test_phase_functions_come_back_bit_for_bit(self):
        for p in _phases():
            q = pickle.loads(pickle.dumps(p))
            self.assertIsInstance(q, sk.Phase)
            self.assertEqual(repr(q), repr(p))
            for f in ("pdf", "cdf"):
                self.assertTrue(_same(getattr(q, f)(MU), getattr(p, f)(MU)), f"{p!r}.{f}")
            self.assertTrue(_same(q.sample_cos(U), p.sample_cos(U)), repr(p))
            self.assertEqual(q.mean_cosine, p.mean_cosine)

    def test_other_objects_come_back(self):
        m = sk.Mie(12.0, complex(1.33, 0.01))
        self.assertTrue(_same(pickle.loads(pickle.dumps(m)).phase(MU), m.phase(MU)))

        curve = sk.AlbedoCurve(sk.Phase.henyey_greenstein(0.8), thickness=2.0, paths=20_000, seed=3)
        c = pickle.loads(pickle.dumps(curve))
        w = np.linspace(0.0, 1.0, 101)
        self.assertTrue(_same(c.albedo(w), curve.albedo(w)))
        self.assertTrue(_same(c.std_error(w), curve.std_error(w)))
        self.assertEqual(c.paths, curve.paths)

        x = np.linspace(0.0, 1.0, 6)
        density = np.add.outer(np.add.outer(x, x), x)
        med = sk.Medium(density, 0.5, 1.5, lo=(0, 0, 0), hi=(2, 1, 1), sampling="cells", majorant_cells=(4, 2, 2))
        m2 = pickle.loads(pickle.dumps(med))
        o = np.array([[-1.0, 0.5, 0.5], [1.0, -1.0, 0.3]])
        d = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.1]])
        self.assertTrue(_same(m2.transmittance(o, d, seed=4), med.transmittance(o, d, seed=4)))
        self.assertTrue(_same(m2.majorants(), med.majorants()))

        r = sk.RayleighPolarized(0.03)
        self.assertTrue(all(_same(a, b) for a, b in zip(pickle.loads(pickle.dumps(r)).mueller(MU), r.mueller(MU))))

        t = sk.Table2d([sk.Phase.henyey_greenstein(g) for g in (0.1, 0.5, 0.9)], 0.4, 0.1, 64)
        self.assertTrue(_same(pickle.loads(pickle.dumps(t)).data, t.data))

        s = sk.SpectralPhase([sk.Phase.henyey_greenstein(0.3), sk.Phase.rayleigh()])
        self.assertTrue(_same(pickle.loads(pickle.dumps(s)).pdf(MU), s.pdf(MU)))

    def test_a_state_that_is_not_one_is_a_value_error(self):
        from scatterkit import _scatterkit as _sk

        for state in (
            ("one", [999], [[0.5]], [], [], 0, 0),
            ("one", [], [], [], [], 0, 0),
            ("mix", [1], [[0.5]], [], [], 0, 0),
            ("table", [], [], [], [0.0, 1.0], 5, 1),
            ("table", [], [], [], [np.nan] * 4, 1, 1),
            ("table", [], [], [], [0.0] * 4, 1, 7),
            ("nothing", [], [], [], [], 0, 0),
        ):
            with self.assertRaises(ValueError, msg=str(state)):
                _sk._Phase._from_state(state)
        for state in (
            ([0.5] * 3, [0.0] * 3, 1, [0.5] * 10, [0.0] * 10),
            ([2.0] * 65, [0.0] * 65, 1, [0.5] * 10, [0.0] * 10),
            ([0.5] * 65, [0.0] * 65, 1, [0.5] * 9, [0.0] * 9),
            ([0.5] * 65, [0.0] * 65, 1, [np.nan] * 10, [0.0] * 10),
        ):
            with self.assertRaises(ValueError, msg=str(state)):
                _sk._AlbedoCurve._from_state(state)
        with self.assertRaises((TypeError, ValueError)):  # the coarse nodes alone
            _sk._AlbedoCurve._from_state(([0.5] * 65, [0.0] * 65, 1))


if __name__ == "__main__":
    unittest.main()
