"""A figure of the analytic phase functions beside Mie theory for fog
droplets: the Mie phase function of water droplets of a few diameters at
0.55 µm, the fog fit of Jendersie & d'Eon for each, and Henyey–Greenstein
with Mie's asymmetry. Needs matplotlib (pip install matplotlib).

Run: python python/examples/phase_vs_mie.py [output.png]
"""

import sys

import numpy as np

import scatterkit as sk


def main():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = sys.argv[1] if len(sys.argv) > 1 else "phase_vs_mie.png"
    angle = np.linspace(0.0, 180.0, 3601)
    mu = np.cos(np.radians(angle))
    m = sk.water_index(0.55)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
    for ax, d in zip(axes, (2.0, 10.0, 30.0)):
        drop = sk.Mie(sk.size_parameter(d, 0.55), m)
        ax.semilogy(angle, drop.phase(mu), color="black", lw=0.8, label="Mie")
        ax.semilogy(angle, sk.Phase.fog_diameter(d).pdf(mu), label="fog fit (Jendersie & d'Eon)")
        ax.semilogy(angle, sk.Phase.henyey_greenstein(drop.g).pdf(mu), "--", label=f"HG, g = {drop.g:.3f}")
        ax.set_title(f"water droplet, d = {d:g} µm, λ = 0.55 µm")
        ax.set_xlabel("scattering angle (degrees)")
    axes[0].set_ylabel("phase function (per steradian)")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
