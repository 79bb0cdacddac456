"""Backscatter and extinction of large spheres (x = 1000, 5000) summed in
60-digit arithmetic (mpmath), beside this library, scattnlay and miepython:
which code is right where they disagree at x = 5000. Run:
    pip install scatterkit scattnlay miepython mpmath   (scatterkit from ./python)
    python3 scripts/mie_backscatter_reference.py
The series (Bohren & Huffman 1983, sec. 4.4 and 4.8): D_n(mx) by downward
recurrence from N + 60, psi_n and chi_n by upward recurrence (at 60 digits
the growth of the error beyond n = x, about 10^5 over the last terms, costs
nothing), N = x + 4.05 x^(1/3) + 2 terms plus 80 (Wiscombe 1980; 42 more converge Q_back to 1e-14 at x = 5000); m = n + ik
absorbs (miepython writes n - ik, and is given that). Q_back = 4|S1(pi)|^2/x^2
with S1(pi) = sum (2n+1)/2 (-1)^(n+1) (a_n - b_n).
"""
import warnings

import mpmath as mp

mp.mp.dps = 60


def series(x, m, extra=80):
    x, m = mp.mpf(x), mp.mpc(m)
    n_max = int(x + 4.05 * x ** (mp.mpf(1) / 3) + 2) + extra
    mx = m * x
    # Downward from well above both n_max and |mx| (Wiscombe 1980).
    start = int(max(n_max, abs(mx)) + 8 * (abs(mx) / 2) ** (mp.mpf(1) / 3)) + 60
    d = [mp.mpc(0)] * (start + 1)
    for n in range(start, 0, -1):
        d[n - 1] = n / mx - 1 / (d[n] + n / mx)
    psi0, psi1 = mp.sin(x), mp.sin(x) / x - mp.cos(x)
    chi0, chi1 = mp.cos(x), mp.cos(x) / x + mp.sin(x)
    qe, s1 = mp.mpf(0), mp.mpc(0)
    for n in range(1, n_max + 1):
        psi, chi = psi1, chi1
        xi, xi0 = psi - 1j * chi, psi0 - 1j * chi0
        da, db = d[n] / m + n / x, m * d[n] + n / x
        a = (da * psi - psi0) / (da * xi - xi0)
        b = (db * psi - psi0) / (db * xi - xi0)
        qe += (2 * n + 1) * mp.re(a + b)
        s1 += mp.mpf(2 * n + 1) / 2 * (-1) ** (n + 1) * (a - b)
        psi0, psi1 = psi1, (2 * n + 1) / x * psi1 - psi0
        chi0, chi1 = chi1, (2 * n + 1) / x * chi1 - chi0
    return 2 * qe / x ** 2, 4 * abs(s1) ** 2 / x ** 2


def main():
    import miepython
    import numpy as np
    import scattnlay
    import scatterkit

    warnings.filterwarnings("ignore")
    print("| x | m | Q_back, 60 digits | scatterkit | scattnlay | miepython |")
    print("|---|---|---|---|---|---|")
    for x in (1000.0, 5000.0):
        for m in (1.33 + 0j, 1.33 + 1e-8j, 1.33 + 0.001j, 1.5 + 0.01j):
            qe, qb = series(x, m)
            sk = scatterkit.Mie(x, m).q_back
            snl = float(scattnlay.scattnlay(np.array([x]), np.array([m]))[4])
            mpy = float(miepython.efficiencies_mx(complex(m.real, -m.imag), x)[2])
            rel = lambda v: "%.1e" % (abs(v / float(qb) - 1))
            print("| %g | %s | %s | %s | %s | %s |" % (x, m, mp.nstr(qb, 13), rel(sk), rel(snl), rel(mpy)))


if __name__ == "__main__":
    main()
