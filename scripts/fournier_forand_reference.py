"""Fournier-Forand inverse CDF and density in 50-digit arithmetic
(mpmath): the reference values of tests/models/fournier_forand.rs, written
to tests/data/fournier_forand_reference.txt (inverse) and
tests/data/fournier_forand_density.txt (density). Run:
python3 scripts/fournier_forand_reference.py

The density per steradian is the published one (Fournier & Forand 1994):
p = [nu (1-delta) - (1 - delta^nu)
     + (delta (1 - delta^nu) - nu (1-delta)) / s] / (4 pi (1-delta)^2 delta^nu)
    + (d180^-nu - 1)/(d180 - 1) (3 mu^2 - 1) / (16 pi),
at mu = 1 - 2s for s from 1e-16 to 1 (log-spaced), mu_J down to 3 + 2^-51
(nu -> 0), every parameter the exact double the test passes.

The published forward CDF (Fournier & Jonasz 1999), with s = sin^2(theta/2),
delta = 4 s / (3 (n-1)^2), nu = (3 - mu_J)/2, c = (d180^-nu - 1)/(d180 - 1):
F_fwd = [1 - delta^(nu+1) - (1 - delta^nu) s] / ((1 - delta) delta^nu)
        + c mu (1 - mu^2) / 8,
evaluated at 50 digits (away from delta = 1 exactly) and inverted by
bisection in s; P(cos <= mu) = 1 - F_fwd.
"""
import struct
import mpmath as mp

mp.mp.dps = 50
NS = [1.01, 1.05, 1.1, 1.2, 1.5, 1.8]
MUJ = [3.01, 3.5, 4.0, 4.5, 4.99]
US = [0.0, 1e-12, 1e-6, 1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999, 1 - 1e-6, 1 - 1e-12, 1.0]


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def fwd(n, nu, s):
    if s == 0:
        return mp.mpf(0)
    k = 4 / (3 * (n - 1) ** 2)
    d = k * s
    mu = 1 - 2 * s
    d180 = k
    c = (d180 ** (-nu) - 1) / (d180 - 1)
    if abs(d - 1) < mp.mpf(10) ** -30:
        d = d + mp.mpf(10) ** -29  # the removable point: nudge
    main = (1 - d ** (nu + 1) - (1 - d ** nu) * s) / ((1 - d) * d ** nu)
    return main + c * mu * (1 - mu * mu) / 8


def inverse(n, muj, u):
    n, u = mp.mpf(n), mp.mpf(u)
    nu = (3 - mp.mpf(muj)) / 2
    if u <= 0:
        return mp.mpf(-1)
    if u >= 1:
        return mp.mpf(1)
    t = 1 - u
    lo, hi = mp.mpf(0), mp.mpf(1)
    for _ in range(200):
        mid = (lo + hi) / 2
        if fwd(n, nu, mid) < t:
            lo = mid
        else:
            hi = mid
    return 1 - (lo + hi)


with open("tests/data/fournier_forand_reference.txt", "w") as f:
    f.write("# n mu_J u mu (f64 parameters) | mu for the f32-rounded n, mu_J, u\n")
    for n in NS:
        for m in MUJ:
            for u in US:
                r64 = inverse(n, m, u)
                r32 = inverse(f32(n), f32(m), f32(u))
                f.write("%r %r %r %s %s\n" % (n, m, u, mp.nstr(r64, 20), mp.nstr(r32, 20)))


NS_D = [1.01, 1.1, 1.2, 1.8]
MUJ_D = [3.0 + 2.0**-51, 3.0 + 1e-9, 3.001, 3.5, 4.0, 4.5, 4.999]


def density(n, muj, mu):
    n, mu = mp.mpf(n), mp.mpf(mu)
    nu = (3 - mp.mpf(muj)) / 2
    s = (1 - mu) / 2
    k = 4 / (3 * (n - 1) ** 2)
    d = k * s
    main = (nu * (1 - d) - (1 - d**nu) + (d * (1 - d**nu) - nu * (1 - d)) / s) / (
        4 * mp.pi * (1 - d) ** 2 * d**nu
    )
    return main + (k ** (-nu) - 1) / (k - 1) * (3 * mu * mu - 1) / (16 * mp.pi)


with open("tests/data/fournier_forand_density.txt", "w") as f:
    f.write("# n mu_J mu pdf (per steradian; n, mu_J, mu exact doubles)\n")
    for n in NS_D:
        for m in MUJ_D:
            k = 4 / (3 * (mp.mpf(n) - 1) ** 2)
            for i in range(41):
                mu = 1.0 - 2.0 * 10.0 ** (-16.0 + 16.0 * i / 40.0)
                if mu < -1.0 or abs(k * (1 - mp.mpf(mu)) / 2 - 1) < mp.mpf(10) ** -30:
                    continue
                f.write("%r %r %r %s\n" % (n, m, mu, mp.nstr(density(n, m, mu), 20)))


def one_minus_mean(n, muj):
    """1 - <mu> = 2 pi int (1 - mu) p dmu of the published density (its
    normalisation gives the 1), split at the removable point delta = 1."""
    k = 4 / (3 * (mp.mpf(n) - 1) ** 2)

    def f(mu):
        s = (1 - mu) / 2
        if s <= 0:
            return mp.mpf(0)
        if abs(k * s - 1) < mp.mpf(10) ** -30:
            mu = mu + mp.mpf(10) ** -29
        return (1 - mu) * density(n, muj, mu)

    mu1 = 1 - 2 / k
    pts = [-1, mu1, 1] if mu1 > -1 else [-1, 1]
    return 2 * mp.pi * mp.quad(f, pts)


with open("tests/data/fournier_forand_mean_cosine.txt", "w") as f:
    f.write("# n mu_J 1-<mu> (n, mu_J exact doubles; nu = (3 - mu_J)/2)\n")
    for n in NS_D + [1.0 + 2.0**-40]:
        for m in MUJ_D:
            f.write("%r %r %s\n" % (n, m, mp.nstr(one_minus_mean(n, m), 25)))
