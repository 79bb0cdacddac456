"""Fit measured scattering data to the simplest phase function.

The data: a volume scattering function tabulated against the scattering
angle in degrees, normalised to 4 pi (as ocean-optics tables are: Petzold's
San Diego harbour measurements have this shape; here a Fournier–Forand
function with a little noise stands in for them, so the example runs
without a data file). ``scatterkit.fit`` converts nothing: give it the
cosines and the density at any scale.

Run: python python/examples/fit_measured.py [tolerance]
"""

import sys

import numpy as np

import scatterkit as sk
from scatterkit import conventions as cv


def measured():
    angle = np.concatenate([np.geomspace(0.1, 10.0, 40), np.linspace(12.0, 180.0, 85)])
    truth = sk.Phase.fournier_forand_backscatter(0.0183, 1.1)
    mu = cv.mu_from_angle(angle, degrees=True)
    vsf = cv.convert_normalization(truth.pdf(mu), "sr", "4pi")
    noise = np.random.default_rng(4).normal(1.0, 0.02, angle.size)
    return angle, vsf * noise


def main():
    tolerance = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
    angle, vsf = measured()
    mu = cv.mu_from_angle(angle, degrees=True)
    order = np.argsort(mu)  # fit wants the cosines increasing
    found = sk.fit(mu[order], vsf[order], tolerance)
    print(f"tolerance {tolerance}: chose {found.model} ({found.phase!r}), "
          f"total-variation distance {found.distance:.4f}, within: {found.within_tolerance}")
    for name, d in sorted(found.distances.items(), key=lambda kv: np.nan_to_num(kv[1], nan=9.0)):
        print(f"  {name:18s} {d:.4f}")
    if found.phase is not None:
        print(f"mean cosine {found.phase.mean_cosine:.4f}; "
              f"backscatter fraction {found.phase.cdf(0.0):.4f}")


if __name__ == "__main__":
    main()
