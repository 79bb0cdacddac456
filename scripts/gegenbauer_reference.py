"""Gegenbauer-kernel inverse CDF in 50-digit arithmetic (mpmath): the
reference values of tests/models/gegenbauer.rs, written to
tests/data/gegenbauer_reference.txt (|g| up to 0.999, f64 and f32) and
tests/data/gegenbauer_reference_poles.txt (1 - |g| from 1e-4 to 1e-10,
where the inverse takes its Newton step; f64, with sin theta).
Run: python3 scripts/gegenbauer_reference.py

Reynolds & McCormick (JOSA 70, 1980): with y = 1 + g^2 - 2 g mu,
F(mu) = [y^-a - (1+g)^-2a] / [(1-g)^-2a - (1+g)^-2a]  (a != 0),
F(mu) = ln((1+g)^2 / y) / ln((1+g)^2/(1-g)^2)          (a = 0),
so y(u) is explicit and mu = (1 + g^2 - y) / (2 g). Parameters are the
exact binary values of the doubles (and floats) the test passes.
"""
import struct
import mpmath as mp

mp.mp.dps = 50
ALPHAS = [-0.49, -0.25, -1e-3, 0.0, 1e-3, 0.5, 1.0, 2.5, 10.0, 100.0, 1000.0]
GS = [-0.999, -0.9, -0.5, -1e-3, -1e-8, 1e-8, 1e-3, 0.3, 0.9, 0.99, 0.999]
US = [0.0, 1e-12, 1e-6, 1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999, 1 - 1e-6, 1 - 1e-12, 1.0]


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def inverse(a, g, u):
    a, g, u = mp.mpf(a), mp.mpf(g), mp.mpf(u)
    if a == 0:
        y = (1 + g) ** 2 * mp.exp(-u * mp.log((1 + g) ** 2 / (1 - g) ** 2))
    else:
        lo, hi = (1 + g) ** (-2 * a), (1 - g) ** (-2 * a)
        y = ((1 - u) * lo + u * hi) ** (-1 / a)  # no cancellation
    return (1 + g * g - y) / (2 * g)


with open("tests/data/gegenbauer_reference.txt", "w") as f:
    f.write("# alpha g u mu (f64 parameters) | mu for the f32-rounded alpha, g, u\n")
    for a in ALPHAS:
        for g in GS:
            for u in US:
                m64 = inverse(a, g, u)
                m32 = inverse(f32(a), f32(g), f32(u))
                f.write("%r %r %r %s %s\n" % (a, g, u, mp.nstr(m64, 20), mp.nstr(m32, 20)))


# Kernels peaked at a pole: 1 - |g| from 1e-4 (where the inverse's
# logarithm passes 16 and it takes a Newton step) to 1e-10; alpha as above
# and the guide's forward-peak worst case (47). sin theta = sqrt((1 - mu)(1 + mu)).
POLE_ALPHAS = ALPHAS + [0.1, 47.0]
POLE_GS = [sign * (1 - e) for e in (1e-4, 1e-6, 1e-8, 1e-10) for sign in (1, -1)]
with open("tests/data/gegenbauer_reference_poles.txt", "w") as f:
    f.write("# alpha g u mu sin_theta (f64 parameters)\n")
    for a in POLE_ALPHAS:
        for g in POLE_GS:
            for u in US:
                # The ends exactly (50 digits leave 1 + mu ~ 1e-50 there).
                m = mp.mpf(-1) if u == 0 else mp.mpf(1) if u == 1 else inverse(a, g, u)
                s = mp.sqrt(max((1 - m) * (1 + m), mp.mpf(0)))
                f.write("%r %r %r %s %s\n" % (a, g, u, mp.nstr(m, 25), mp.nstr(s, 25)))
