"""Density and CDF of the edge cases of tests/models/edges.rs in 50-digit
arithmetic (mpmath): reads tests/data/edge_params.txt (written by
SK_BLESS=1 cargo test --release --test models edges::), writes
tests/data/edge_reference.txt. Run: python3 scripts/edge_reference.py

Models, with the parameters as the library stores them (exact doubles):
  gegenbauer a g  -- Reynolds & McCormick (JOSA 70, 1980): y = 1 + g^2 - 2 g mu,
      F = [y^-a - (1+g)^-2a] / [(1-g)^-2a - (1+g)^-2a]   (a != 0),
      F = ln((1+g)^2 / y) / ln((1+g)^2 / (1-g)^2)           (a = 0),
      dF/dmu = 2 g a y^(-a-1) / [(1-g)^-2a - (1+g)^-2a]    (a != 0).
  hg g  -- Henyey-Greenstein.
  fog g_hg g_d alpha w_d  -- (1 - w_d) HG(g_hg) + w_d Draine(g_d, alpha):
      alpha = 0 is a second HG lobe; g_d = 0 an even lobe, density
      (1 + alpha mu^2) / (2 + 2 alpha / 3), CDF
      (mu + 1 + alpha (mu^3 + 1) / 3) / (2 + 2 alpha / 3); otherwise
      Draine's density (1 - g^2)(1 + alpha mu^2) / (2 (1 + alpha (1 + 2 g^2)/3)
      y^(3/2)), its CDF by quadrature split where it bends.
      HG: density (1 - g^2) / (2 y^(3/2)), CDF (1 - g^2)/(2g) (1/sqrt(y) - 1/(1+g)).
  schlick k  -- Schlick's (1 - k^2) / (2 (1 - k mu)^2) per unit mu, CDF
      (1 - k)(1 + mu) / (2 (1 - k mu)).
  rayleigh_depolarized rho  -- Chandrasekhar's 3 (1 + 3 c + (1 - c) mu^2) /
      (8 (1 + 2 c)) per unit mu, c = rho / (2 - rho), CDF its integral from -1.
The pdf written is per steradian (the density of mu over 2 pi), as the
library's pdf.
"""
import mpmath as mp

mp.mp.dps = 50
MUS = [-1.0, -0.5, 0.0, 0.5, 1.0 - 1e-8, 1.0 - 2.0**-53, 1.0]


def gegenbauer(a, g, mu):
    y = 1 + g * g - 2 * g * mu
    if a == 0:
        l1 = mp.log((1 + g) ** 2 / (1 - g) ** 2)
        return 2 * g / y / l1, mp.log((1 + g) ** 2 / y) / l1
    lo, hi = (1 + g) ** (-2 * a), (1 - g) ** (-2 * a)
    return 2 * g * a * y ** (-a - 1) / (hi - lo), (y ** (-a) - lo) / (hi - lo)


def hg(g, mu):
    if g == 0:
        return mp.mpf(1) / 2, (mu + 1) / 2
    y = 1 + g * g - 2 * g * mu
    return (1 - g * g) / (2 * y ** mp.mpf(1.5)), (1 - g * g) / (2 * g) * (1 / mp.sqrt(y) - 1 / (1 + g))


def draine(g, alpha, mu):
    """Draine's density of mu and, by quadrature split where it bends, its CDF."""
    def dens(m):
        return (1 - g * g) * (1 + alpha * m * m) / (2 * (1 + alpha * (1 + 2 * g * g) / 3) * (1 + g * g - 2 * g * m) ** mp.mpf(1.5))
    pts = sorted(set([mp.mpf(-1)] + [x for x in (-1 + mp.mpf(10) ** -k for k in (12, 9, 6, 3)) if x < mu]
                     + [x for x in (1 - mp.mpf(10) ** -k for k in (3, 6, 9, 12)) if x < mu] + [mu]))
    return dens(mu), mp.quad(dens, pts)


def even_lobe(alpha, mu):
    k = 2 + 2 * alpha / 3
    return (1 + alpha * mu * mu) / k, (mu + 1 + alpha * (mu ** 3 + 1) / 3) / k


def model(words, mu):
    v = [mp.mpf(float(x)) for x in words[1:]]
    mu = mp.mpf(mu)
    if words[0] == "gegenbauer":
        return gegenbauer(v[0], v[1], mu)
    if words[0] == "hg":
        return hg(v[0], mu)
    if words[0] == "schlick":
        k = v[0]
        return (1 - k * k) / (2 * (1 - k * mu) ** 2), (1 - k) * (1 + mu) / (2 * (1 - k * mu))
    if words[0] == "rayleigh_depolarized":
        c = v[0] / (2 - v[0])
        norm = 8 * (1 + 2 * c)
        dens = 3 * (1 + 3 * c + (1 - c) * mu * mu) / norm
        cdf = (3 * (1 + 3 * c) * (mu + 1) + (1 - c) * (mu ** 3 + 1)) / norm
        return dens, cdf
    g_hg, g_d, alpha, w = v
    if alpha == 0:  # two HG lobes
        second = hg(g_d, mu)
    elif g_d == 0:  # the cos^2 lobe (Draine with g = 0)
        second = even_lobe(alpha, mu)
    else:  # a Draine lobe
        second = draine(g_d, alpha, mu)
    (p1, f1), (p2, f2) = hg(g_hg, mu), second
    return (1 - w) * p1 + w * p2, (1 - w) * f1 + w * f2


seen = set()
with open("tests/data/edge_params.txt") as f, open("tests/data/edge_reference.txt", "w") as out:
    out.write("# model parameters @ mu pdf cdf (pdf per steradian), 50 digits by mpmath\n")
    for line in f:
        described = line.split(" => ")[1].strip()
        if described in seen:
            continue
        seen.add(described)
        for mu in MUS:
            p, c = model(described.split(), mu)
            out.write("%s @ %r %s %s\n" % (described, mu, mp.nstr(p / (2 * mp.pi), 20), mp.nstr(c, 20)))
