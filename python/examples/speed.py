"""Speed of the Python package beside the alternatives a scientist has,
as ratios measured in one run (the best of five repeats each):

* 10^7 HG cosines from a numpy array of uniforms, against the same inverse
  CDF written in numpy (float64);
* the Mie phase function of a water droplet at x = 1000 over 10^4 angles,
  against miepython's (when miepython is installed);
* a transmittance estimate over 10^5 rays through a 64^3 grid, against the
  same loop timed inside Rust (what a Rust caller pays).

Run: python python/examples/speed.py (after pip install ./python).
"""

import platform
import time

import numpy as np

import scatterkit as sk


def best(f, repeats=5):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def processor():
    try:
        with open("/proc/cpuinfo") as f:
            info = f.read()
        field = lambda k: next(l.split(":", 1)[1].strip() for l in info.splitlines() if l.startswith(k))
        return f"{field('model name')} (family {field('cpu family')}, model {field('model')})"
    except (OSError, StopIteration):
        return platform.processor() or platform.machine()


def hg_numpy(g, u):
    # pbrt-v4's inverse CDF of HG, as a numpy user would write it.
    s = (1 - g * g) / (1 - g + 2 * g * u)
    return (1 + g * g - s * s) / (2 * g)


def main():
    print(f"processor: {processor()}; numpy {np.__version__}; Python {platform.python_version()}")
    rng = np.random.default_rng(1)

    u = rng.random(10_000_000)
    hg = sk.Phase.henyey_greenstein(0.7)
    t_sk = best(lambda: hg.sample_cos(u))
    t_np = best(lambda: hg_numpy(0.7, u))
    out = np.empty_like(u)
    t_into = best(lambda: hg.sample_cos(u, out=out))
    print(f"10^7 HG cosines: scatterkit {t_sk * 1e3:.1f} ms, numpy formula {t_np * 1e3:.1f} ms: "
          f"{t_sk / t_np:.2f}x (target <= 0.3x); into a preallocated array {t_into * 1e3:.1f} ms: "
          f"{t_into / t_np:.2f}x")

    mu = np.cos(np.linspace(0.0, np.pi, 10_000))
    x, m = 1000.0, sk.water_index(0.55)
    drop = sk.Mie(x, m)
    t_mie = best(lambda: drop.phase(mu))
    t_solve = best(lambda: sk.Mie(x, m), repeats=3)
    try:
        import miepython

        theta = np.arccos(mu)
        # miepython's phase function (its unpolarised intensity, normalised
        # to the albedo over 4 pi by default; only the time is compared).
        t_mp = best(lambda: miepython.i_unpolarized(m.conjugate(), x, mu, norm="albedo"), repeats=3)
        print(f"Mie x = 1000, 10^4 angles: scatterkit {t_mie * 1e3:.1f} ms "
              f"(+ {t_solve * 1e3:.1f} ms to solve), miepython {t_mp * 1e3:.1f} ms: "
              f"{(t_mie + t_solve) / t_mp:.2f}x (target <= 1.0x)")
        del theta
    except ImportError:
        print(f"Mie x = 1000, 10^4 angles: scatterkit {t_mie * 1e3:.1f} ms (+ {t_solve * 1e3:.1f} ms "
              "to solve); miepython not installed: SKIPPED")

    grid = rng.gamma(0.5, 2.0, size=(64, 64, 64))
    medium = sk.Medium(grid, 0.1, 2.0, sampling="cells")
    n = 100_000
    origins = np.column_stack([np.full(n, -0.5), rng.random((n, 2))])
    dirs = np.tile([1.0, 0.0, 0.0], (n, 1))
    t_py = best(lambda: medium.transmittance(origins, dirs, estimator="ratio", seed=1), repeats=3)
    o, d, t, _ = sk._rays(origins, dirs, np.inf)
    t_rs = min(medium._m.seconds_in_rust(o, d, t, "ratio", 1, 1 << 20) for _ in range(3))
    print(f"10^5 rays through 64^3, ratio tracking: from Python {t_py * 1e3:.1f} ms, "
          f"in Rust {t_rs * 1e3:.1f} ms: {t_py / t_rs:.2f}x (target <= 1.3x)")


if __name__ == "__main__":
    main()
