"""Mie efficiencies and amplitudes summed in 40-digit arithmetic (mpmath),
with the Riccati-Bessel functions taken from mpmath's besselj/bessely rather
than recurrences: the reference values in tests/mie.rs. Slow; run by hand:
python3 scripts/mie_reference.py
"""
import mpmath as mp, sys
mp.mp.dps = 40
def mie(x, m, N=None):
    x = mp.mpf(x); m = mp.mpc(m)
    if N is None: N = int(x + 4*x**(mp.mpf(1)/3) + 2) + 10
    mx = m*x
    # direct Riccati-Bessel via spherical bessel in mpmath
    def psi(n, z): return z*mp.sqrt(mp.pi/(2*z))*mp.besselj(n+mp.mpf(1)/2, z)
    def chi(n, z): return -z*mp.sqrt(mp.pi/(2*z))*mp.bessely(n+mp.mpf(1)/2, z)
    qe=qs=gs=0; ab=[]
    for n in range(1, N+1):
        px = psi(n,x); pxp = psi(n-1,x) - n/x*px
        xix = px - 1j*chi(n,x); xixp = (psi(n-1,x)-1j*chi(n-1,x)) - n/x*xix
        pm = psi(n,mx); pmp = psi(n-1,mx) - n/mx*pm
        a = (m*pm*pxp - px*pmp)/(m*pm*xixp - xix*pmp)
        b = (pm*pxp - m*px*pmp)/(pm*xixp - m*xix*pmp)
        ab.append((a,b))
    for i,(a,b) in enumerate(ab):
        n=i+1
        qe += (2*n+1)*mp.re(a+b); qs += (2*n+1)*(abs(a)**2+abs(b)**2)
        gs += (2*n+1)/(n*(n+1))*mp.re(a*mp.conj(b))
        if i+1 < len(ab):
            a1,b1 = ab[i+1]
            gs += n*(n+2)/(n+1)*mp.re(a*mp.conj(a1)+b*mp.conj(b1))
    return 2/x**2*qe, 2/x**2*qs, 4/x**2*gs
for x,n,k in [(0.099,0.75,0),(0.101,0.75,0),(0.055,1.5,1),(0.056,1.5,1),
              (10,0.75,0),(1,1.5,1),(100,1.33,1e-5),(1,10,10),(100,10,10),
              (1000,1.333,1e-8)]:  # the last takes minutes
    qe,qs,gqs = mie(x, mp.mpc(n,k))
    print(x,n,k, mp.nstr(qe,12), mp.nstr(qs,12), mp.nstr(gqs,12))
print("angles")
def amps(x, m, mus):
    x = mp.mpf(x); m = mp.mpc(m)
    N = int(x + 4*x**(mp.mpf(1)/3) + 2) + 10
    mx = m*x
    def psi(n, z): return z*mp.sqrt(mp.pi/(2*z))*mp.besselj(n+mp.mpf(1)/2, z)
    def chi(n, z): return -z*mp.sqrt(mp.pi/(2*z))*mp.bessely(n+mp.mpf(1)/2, z)
    ab=[]
    for n in range(1, N+1):
        px = psi(n,x); pxp = psi(n-1,x) - n/x*px
        xix = px - 1j*chi(n,x); xixp = (psi(n-1,x)-1j*chi(n-1,x)) - n/x*xix
        pm = psi(n,mx); pmp = psi(n-1,mx) - n/mx*pm
        ab.append(((m*pm*pxp - px*pmp)/(m*pm*xixp - xix*pmp), (pm*pxp - m*px*pmp)/(pm*xixp - m*xix*pmp)))
    out=[]
    for mu in mus:
        mu = mp.mpf(mu); pp, p = 0, 1; s1=s2=0
        for i,(a,b) in enumerate(ab):
            n=i+1; tau = n*mu*p - (n+1)*pp; w = mp.mpf(2*n+1)/(n*(n+1))
            s1 += w*(a*p+b*tau); s2 += w*(a*tau+b*p)
            pp, p = p, ((2*n+1)*mu*p-(n+1)*pp)/n
        out.append((s1,s2))
    return out
for x,m in [(0.099,0.75),(0.101,0.75)]:
    (s1,s2), = amps(x, m, [-1])
    print(x, mp.nstr(s1,10), mp.nstr(abs(s1)**2,10))
