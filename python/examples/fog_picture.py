"""What the fog phase function buys, rendered in Mitsuba 3: a bank of fog of
10 µm water droplets seen with the sun behind the viewer, rendered three
times with scatterkit's native Mitsuba plugin (scalar_rgb):

  1. Henyey-Greenstein at the droplets' asymmetry g (what renderers use),
  2. Jendersie & d'Eon's fog fit for the droplet diameter,
  3. Mie theory for the same droplets (radii lognormal about d/2 with
     sigma_g = 1.2, as docs/measured/fog_vs_mie.md compares them; one size
     alone rings with interference a real fog's spread of sizes and
     wavelengths washes out), tabulated.

The view is centred on the antisolar point, so the glory (scattering angle
180 degrees) sits in the middle and the fogbow (about 140 degrees) is a ring
about 40 degrees out. HG has neither. Writes one PNG of the three panels
side by side and prints each panel's render time.

Needs Mitsuba 3 and nanobind's headers (pip install mitsuba nanobind) and a
C++17 compiler. Run: python python/examples/fog_picture.py [out.png] [spp]
"""

import sys
import time

import numpy as np

import scatterkit as sk

DIAMETER_UM = 10.0
WAVELENGTH_UM = 0.55
WIDTH, HEIGHT = 300, 240


def scene(mi, phase, spp):
    """The fog bank (a box 10 units deep, 2 units away, optical depth 0.6
    along the view) in front of a camera looking at the antisolar point."""
    t = mi.ScalarTransform4f()
    return mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "volpath", "max_depth": 32},
            "sensor": {
                "type": "perspective",
                "fov": 100,
                "to_world": t.look_at(origin=[0, 0, 0], target=[0, 0, 1], up=[0, 1, 0]),
                "film": {
                    "type": "hdrfilm",
                    "width": WIDTH,
                    "height": HEIGHT,
                    "pixel_format": "luminance",
                    "rfilter": {"type": "box"},
                },
                "sampler": {"type": "independent", "sample_count": spp},
            },
            # Light travelling along +z: the sun is behind the camera.
            "sun": {"type": "directional", "direction": [0.0, 0.0, 1.0], "irradiance": 1.0},
            "fog": {
                "type": "cube",
                "to_world": t.translate([0.0, 0.0, 7.0]).scale([40.0, 40.0, 5.0]),
                "bsdf": {"type": "null"},
                "interior": {"type": "homogeneous", "albedo": 1.0, "sigma_t": 0.06, "phase": phase},
            },
        }
    )


def main():
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    import scatterkit.mitsuba as skmi

    out = sys.argv[1] if len(sys.argv) > 1 else "fog_hg_fit_mie.png"
    spp = int(sys.argv[2]) if len(sys.argv) > 2 else 256
    skmi.register_native()
    # Mie of the droplets at cosines crowded towards the forward peak.
    s = np.linspace(0.0, 1.0, 16385)
    mu = np.clip(1.0 - 2.0 * s * s, -1.0, 1.0)[::-1]
    fog = sk.polydisperse(
        ("lognormal", DIAMETER_UM / 2.0, 1.2), wavelength=WAVELENGTH_UM, m=sk.water_index(WAVELENGTH_UM), mu=mu
    )
    mie = sk.Phase.table_measured(mu, fog.phase, 2048)
    panels = [
        (f"HG g = {fog.g:.3f}", {"model": "henyey_greenstein", "g": fog.g}),
        (f"fog fit, d = {DIAMETER_UM:g} um", {"model": "fog_diameter", "diameter_um": DIAMETER_UM}),
        ("Mie (tabulated)", mie),
    ]
    images = []
    for label, props in panels:
        sc = scene(mi, skmi.native(props), spp)
        t0 = time.perf_counter()
        img = np.array(mi.render(sc, seed=1), dtype=np.float64)[..., 0]
        print(f"{label}: {time.perf_counter() - t0:.1f} s ({WIDTH}x{HEIGHT}, {spp} spp, scalar_rgb)")
        images.append(img)
    # One exposure for all three: the fog fit's median at mid-grey.
    scale = 0.18 / max(np.median(images[1]), 1e-12)
    gap = np.zeros((HEIGHT, 6))
    row = np.concatenate([images[0], gap, images[1], gap, images[2]], axis=1) * scale
    rgb = np.repeat(row[..., None], 3, axis=2).astype(np.float32)
    bmp = mi.Bitmap(rgb, mi.Bitmap.PixelFormat.RGB)
    bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True).write(out)
    print(f"wrote {out}: left {panels[0][0]}, middle {panels[1][0]}, right {panels[2][0]}")


if __name__ == "__main__":
    main()
