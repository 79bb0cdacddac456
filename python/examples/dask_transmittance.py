"""Transmittance through a cloud over many rays, on a Dask cluster.

When a Monte Carlo run outgrows one process (transmittance over 10^9 rays,
an albedo curve at 10^8 paths, a slab at hundreds of wavelengths), split it
into chunks that each seed their own generator from the chunk's index:
every chunk then draws the same numbers wherever it runs, and the sums,
gathered in chunk order, are the same bits on one worker or on forty. The
medium goes to the workers once (``client.scatter``): scatterkit's objects
pickle.

Run: python python/examples/dask_transmittance.py [chunks] [rays_per_chunk]
Prints the mean transmittance from one process, from a LocalCluster of 1
and of 4 worker processes, and the speed-up (bounded by the cores).
"""

import os
import sys
import time

import numpy as np

import scatterkit as sk

SEED = 2026


def cloud(n: int = 48) -> sk.Medium:
    """A smooth cloud in the unit cube: a Gaussian blob with ripples."""
    x = (np.arange(n) + 0.5) / n
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    r2 = (X - 0.5) ** 2 + (Y - 0.5) ** 2 + (Z - 0.5) ** 2
    density = np.exp(-r2 / 0.05) * (1.0 + 0.3 * np.sin(12.0 * X) * np.cos(9.0 * Y))
    return sk.Medium(density, 2.0, 18.0, sampling="cells")


def chunk(medium: sk.Medium, k: int, rays: int):
    """Chunk ``k``: ``rays`` rays from random points on a sphere around the
    cloud towards random points inside it, their transmittance by ratio
    tracking; the generator seeded by ``(SEED, k)`` alone. Returns the sum
    and the sum of squares."""
    rng = np.random.default_rng([SEED, k])
    v = rng.normal(size=(rays, 3))
    origins = 0.5 + 1.5 * v / np.linalg.norm(v, axis=1, keepdims=True)
    dirs = rng.random((rays, 3)) - origins
    tr = medium.transmittance(origins, dirs, seed=SEED + k)
    return float(tr.sum()), float((tr * tr).sum())


def total(results, rays):
    """The mean and its standard error from the chunks' sums, in chunk order."""
    s = sum(r[0] for r in results)
    s2 = sum(r[1] for r in results)
    n = rays * len(results)
    mean = s / n
    return mean, ((s2 / n - mean * mean) / n) ** 0.5


def on_cluster(workers: int, medium: sk.Medium, chunks: int, rays: int):
    """The run on a LocalCluster of ``workers`` single-threaded processes:
    the mean, its standard error and the seconds it took (the cluster's
    start not counted)."""
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as lc:
        with Client(lc) as client:
            client.submit(int, 0).result()  # the workers are up
            t0 = time.perf_counter()
            m = client.scatter(medium, broadcast=True)
            futures = [client.submit(chunk, m, k, rays, pure=False) for k in range(chunks)]
            results = client.gather(futures)
            seconds = time.perf_counter() - t0
    return total(results, rays) + (seconds,)


def main():
    chunks = int(sys.argv[1]) if len(sys.argv) > 1 else 32
    rays = int(sys.argv[2]) if len(sys.argv) > 2 else 20_000
    medium = cloud()
    t0 = time.perf_counter()
    here = total([chunk(medium, k, rays) for k in range(chunks)], rays)
    t_here = time.perf_counter() - t0
    print(f"{chunks} chunks x {rays} rays; {os.cpu_count()} cores")
    print(f"one process:   T = {here[0]:.12f} +- {here[1]:.1e}  {t_here:.2f} s")
    times = {}
    for workers in (1, 4):
        mean, se, seconds = on_cluster(workers, medium, chunks, rays)
        times[workers] = seconds
        same = "same bits" if (mean, se) == here else "DIFFERENT"
        print(f"{workers} worker(s):   T = {mean:.12f} +- {se:.1e}  {seconds:.2f} s  ({same})")
        if (mean, se) != here:
            raise SystemExit(f"{workers} workers gave a different answer")
    print(f"speed-up, 4 workers over 1: {times[1] / times[4]:.2f}x")


if __name__ == "__main__":
    main()
