"""The cluster route (python/examples/dask_transmittance.py): the same
seeded transmittance computation in one process and on Dask LocalClusters of
1 and 4 worker processes gives the same bits (the medium travels to the
workers pickled). Skipped without ``dask[distributed]``; with
``SK_REQUIRE_ALL`` set (as the project's CI sets it) a skip is a failure."""

import importlib.util
import os
import unittest

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "dask_transmittance.py")


def _skip(why):
    if os.environ.get("SK_REQUIRE_ALL"):
        raise AssertionError("SKIPPED, but SK_REQUIRE_ALL is set: " + why)
    raise unittest.SkipTest(why)


class OnDask(unittest.TestCase):
    def test_one_and_four_workers_give_one_processs_bits(self):
        try:
            import distributed  # noqa: F401
        except ImportError:
            _skip("dask[distributed] is not installed (pip install 'dask[distributed]')")
        spec = importlib.util.spec_from_file_location("dask_transmittance", EXAMPLE)
        ex = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(ex)
        medium = ex.cloud(16)
        chunks, rays = 12, 2000
        here = ex.total([ex.chunk(medium, k, rays) for k in range(chunks)], rays)
        self.assertTrue(0.0 < here[0] < 1.0, here)
        for workers in (1, 4):
            mean, se, _ = ex.on_cluster(workers, medium, chunks, rays)
            self.assertEqual((mean, se), here, f"{workers} workers")


if __name__ == "__main__":
    unittest.main()
