"""The portable header from Python, as a kernel author uses it: a kernel
compiled by pyopencl with ``-I scatterkit.get_include()`` and run on the
OpenCL device (pocl on the CPU in CI) returns the library's bits
(``Phase.sample_cos_portable``) over 2^20 + 6 uniforms per model.

Skipped without pyopencl or an OpenCL device; with ``SK_REQUIRE_ALL`` set
(as the project's CI sets it) a skip is a failure instead."""

import os
import unittest

import numpy as np

import scatterkit as sk

KERNEL = r"""
#include "scatterkit_portable.h"

__kernel void hg_cos(float g, __global const float *u, __global float *mu) {
    uint i = get_global_id(0);
    skp_hg h;
    skp_hg_new(g, &h);
    mu[i] = skp_hg_sample_cos(h, u[i]);
}

__kernel void rayleigh_cos(__global const float *u, __global float *mu) {
    uint i = get_global_id(0);
    mu[i] = skp_rayleigh_sample_cos(u[i]);
}

__kernel void isotropic_cos(__global const float *u, __global float *mu) {
    uint i = get_global_id(0);
    float s;
    mu[i] = skp_isotropic_sample_cos_sin(u[i], &s);
}
"""


def _skip(why):
    if os.environ.get("SK_REQUIRE_ALL"):
        raise AssertionError("SKIPPED, but SK_REQUIRE_ALL is set: " + why)
    raise unittest.SkipTest(why)


def _bits(a):
    """The float32 bits, NaN canonical."""
    b = np.asarray(a, dtype=np.float32).view(np.uint32).copy()
    b[np.isnan(a)] = 0x7FC00000
    return b


class HeaderFromPython(unittest.TestCase):
    def test_get_include_holds_the_headers(self):
        inc = sk.get_include()
        for h in ("scatterkit_portable.h", "scatterkit_table.h", "scatterkit.h", "scatterkit_inline.h"):
            self.assertTrue(os.path.isfile(os.path.join(inc, h)), h)
        with open(os.path.join(inc, "scatterkit_portable.h")) as f:
            self.assertIn("skp_hg_sample_dir", f.read())

    def test_a_pyopencl_kernel_returns_the_librarys_bits(self):
        try:
            import pyopencl as cl
        except ImportError:
            _skip("pyopencl is not installed (pip install pyopencl)")
        try:
            ctx = cl.Context([p.get_devices()[0] for p in cl.get_platforms() if p.get_devices()][:1])
        except Exception as e:  # no platform, no device
            _skip(f"no OpenCL device: {e}")
        queue = cl.CommandQueue(ctx)
        prg = cl.Program(ctx, KERNEL).build(
            options=["-I", sk.get_include(), "-cl-fp32-correctly-rounded-divide-sqrt"]
        )
        special = np.array([0.0, 1.0, 2.0, -1.0, np.nan, 0.99999994], dtype=np.float32)
        u = np.concatenate([np.arange(1 << 20, dtype=np.float32) / np.float32(1 << 20), special])
        mf = cl.mem_flags
        ub = cl.Buffer(ctx, mf.READ_ONLY | mf.COPY_HOST_PTR, hostbuf=u)
        ob = cl.Buffer(ctx, mf.WRITE_ONLY, u.nbytes)
        got = np.empty_like(u)

        def run(kernel, *args):
            kernel(queue, u.shape, None, *args, ub, ob)
            cl.enqueue_copy(queue, got, ob).wait()
            return got.copy()

        hg_cos = cl.Kernel(prg, "hg_cos")
        cases = [(g, sk.Phase.henyey_greenstein(g)) for g in (0.7, -0.3, 0.0, 0.999, 1.0, -1.0)]
        for g, phase in cases:
            dev = run(hg_cos, np.float32(g))
            want = phase.sample_cos_portable(u)
            self.assertTrue(np.array_equal(_bits(dev), _bits(want)), f"HG g = {g}")
        for name, phase in (("rayleigh_cos", sk.Phase.rayleigh()), ("isotropic_cos", sk.Phase.isotropic())):
            dev = run(cl.Kernel(prg, name))
            self.assertTrue(np.array_equal(_bits(dev), _bits(phase.sample_cos_portable(u))), phase.name)
        # Within the header's stated bound of the library's accurate sampler.
        hg = sk.Phase.henyey_greenstein(0.7)
        inside = u[: 1 << 20]
        self.assertLessEqual(float(np.max(np.abs(hg.sample_cos_portable(inside) - hg.sample_cos(inside.astype(np.float64))))), 2e-7)


if __name__ == "__main__":
    unittest.main()
