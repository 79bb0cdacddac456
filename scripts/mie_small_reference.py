"""Q_ext, Q_sca and g of spheres from x = 1e-20 to 30, summed in 80-digit
arithmetic (mpmath) with the Riccati-Bessel functions from mpmath's
besselj/bessely (no recurrences): tests/data/mie_small_spheres.txt, which
tests/models/mie.rs reads. The small sizes are where forming a_n and b_n
from logarithmic derivatives cancels: b_n is of order x^2 (m^2 - 1) of its
terms, and g needs b_1. Run (about a minute):
    pip install mpmath
    python3 scripts/mie_small_reference.py > tests/data/mie_small_spheres.txt
Conventions: Bohren & Huffman 1983, sec. 4.4; m = n + ik absorbs.
"""
import mpmath as mp

mp.mp.dps = 80

XS = ["1e-20", "1e-12", "1e-9", "1e-7", "1e-5", "1e-3", "0.01", "0.1", "0.5", "1", "2", "5", "10", "30"]
MS = [(1.0001, 0), (1.01, 0), (1.33, 1e-9), (1.5, 0), (1.5, 0.01), (1.5, 1), (2, 1), (1.5, 10), (10, 10),
      (0.75, 0), (0.5, 0), (0.2, 3), (3.5, 0.001)]


def psi(n, z):
    return z * mp.sqrt(mp.pi / (2 * z)) * mp.besselj(n + mp.mpf(1) / 2, z)


def chi(n, z):
    return -z * mp.sqrt(mp.pi / (2 * z)) * mp.bessely(n + mp.mpf(1) / 2, z)


def efficiencies(x, m):
    """(Q_ext, Q_sca, g), the series to N = x + 4 x^(1/3) + 12 terms."""
    terms = int(x + 4 * x ** (mp.mpf(1) / 3) + 2) + 10
    mx = m * x
    ab = []
    for n in range(1, terms + 1):
        px, pm = psi(n, x), psi(n, mx)
        dpx, dpm = psi(n - 1, x) - n / x * px, psi(n - 1, mx) - n / mx * pm
        xi = px - 1j * chi(n, x)
        dxi = (psi(n - 1, x) - 1j * chi(n - 1, x)) - n / x * xi
        a = (m * pm * dpx - px * dpm) / (m * pm * dxi - xi * dpm)
        b = (pm * dpx - m * px * dpm) / (pm * dxi - m * xi * dpm)
        ab.append((a, b))
    q_ext = q_sca = g_sum = 0
    for i, (a, b) in enumerate(ab):
        n = i + 1
        q_ext += (2 * n + 1) * mp.re(a + b)
        q_sca += (2 * n + 1) * (abs(a) ** 2 + abs(b) ** 2)
        g_sum += (2 * n + 1) / mp.mpf(n * (n + 1)) * mp.re(a * mp.conj(b))
        if i + 1 < len(ab):
            a1, b1 = ab[i + 1]
            g_sum += mp.mpf(n * (n + 2)) / (n + 1) * mp.re(a * mp.conj(a1) + b * mp.conj(b1))
    return 2 / x**2 * q_ext, 2 / x**2 * q_sca, 2 * g_sum / q_sca


print("# x n k Q_ext Q_sca g (m = n + ik; 20 digits)")
for xs in XS:
    for n, k in MS:
        q_ext, q_sca, g = efficiencies(mp.mpf(xs), mp.mpc(n, k))
        print(xs, repr(n), repr(k), *(mp.nstr(v, 20) for v in (q_ext, q_sca, g)), flush=True)
