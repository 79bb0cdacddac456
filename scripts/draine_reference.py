"""Draine's phase function (Draine 2003, ApJ 598, eq. 4) near its poles as
g -> 1, in 60-digit arithmetic (mpmath): writes
tests/data/draine_near_poles.txt, read by tests/models/draine.rs.
Run: python3 scripts/draine_reference.py

With y = 1 + g^2 - 2 g x, a = 1 + g^2, b = 2 g and
c = 1 + alpha (1 + 2 g^2) / 3, the density of mu = cos(theta) is
  f(mu) = (1 - g^2) (1 + alpha mu^2) / (2 c y^(3/2)),
and its CDF the closed form of the integral from -1 (w = a - b x):
  int w^(-3/2) dx      = (2 / b) w^(-1/2),
  int x^2 w^(-3/2) dx  = -(1 / b^3) (-2 a^2 w^(-1/2) - 4 a w^(1/2) + (2/3) w^(3/2)),
differences taken at 60 digits (at 1 - g = 1e-10 they cancel to 20 digits
below the terms). The pdf written is per steradian (f over 2 pi), as the
library's pdf. Parameters and mu are exact doubles (Python floats); mu runs
over points within ulps of -1 and +1 and a few interior points.
"""
import mpmath as mp

mp.mp.dps = 60

GS = [0.9999, 1 - 1e-6, 1 - 1e-8, 1 - 3e-9, 1 - 1e-10]
ALPHAS = [1.0, 12.0, 0.5]
ULP = 2.0 ** -53


def mus():
    out = [-1.0, 1.0, 0.0, 0.5, -0.5, 1 - 1e-8, -1 + 1e-8]
    for k in (1, 2, 3, 5, 17, 1000):
        out.append(1.0 - k * ULP)
        out.append(-1.0 + 2 * k * ULP)
    return out


def draine(g, alpha, mu):
    g, alpha, mu = mp.mpf(g), mp.mpf(alpha), mp.mpf(mu)
    a, b = 1 + g * g, 2 * g
    c = 1 + alpha * (1 + 2 * g * g) / 3
    n = (1 - g * g) / (2 * c)

    def j0(x):
        return (2 / b) * (a - b * x) ** mp.mpf(-0.5)

    def j2(x):
        w = a - b * x
        return -(1 / b ** 3) * (-2 * a * a * w ** mp.mpf(-0.5) - 4 * a * w ** mp.mpf(0.5) + mp.mpf(2) / 3 * w ** mp.mpf(1.5))

    pdf = n * (1 + alpha * mu * mu) / (a - b * mu) ** mp.mpf(1.5) / (2 * mp.pi)
    cdf = n * ((j0(mu) - j0(-1)) + alpha * (j2(mu) - j2(-1)))
    return pdf, cdf


def main():
    lines = ["# g alpha mu pdf cdf (pdf per steradian), 60-digit mpmath, scripts/draine_reference.py"]
    for g in GS:
        for sign in (1, -1):
            for alpha in ALPHAS:
                for mu in mus():
                    pdf, cdf = draine(sign * g, alpha, mu)
                    lines.append("%r %r %r %s %s" % (sign * g, alpha, mu, mp.nstr(pdf, 25), mp.nstr(cdf, 25)))
    with open("tests/data/draine_near_poles.txt", "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
