"""Conversions between the conventions phase-function codes use, and exporters.

scatterkit's own conventions: ``mu = cos(theta)`` with ``mu = +1`` forward;
densities per steradian (integral over the sphere 1); Legendre moments
``chi_l = <P_l(mu)>`` with ``p = sum (2l + 1) chi_l P_l / (4 pi)``.

Others in use, and what converts:

* **Legendre coefficients with the (2l + 1) factor** (``beta_l = (2l + 1) chi_l``,
  ``p = sum beta_l P_l / (4 pi)``: Mishchenko's expansion coefficients, AT3D's
  and SHDOM's tables): :func:`legendre_with_2l1`, :func:`legendre_without_2l1`.
  Mixing the two up gives a phase function that goes negative.
* **Normalisation** (:func:`convert_normalization`): ``"sr"`` integrates to 1 over
  the sphere (scatterkit, pbrt, Mitsuba); ``"4pi"`` to ``4 pi`` over the sphere,
  the same as to 2 over ``mu`` (DISORT, libRadtran, most atmospheric and ocean
  codes; isotropic is 1); ``"mu"`` to 1 over ``mu`` in ``[-1, 1]`` (a density in
  the cosine; isotropic is 1/2).
* **Angles** (:func:`mu_from_angle`, :func:`angle_from_mu`): the scattering angle
  from the forward direction (``0`` = forward, scatterkit), or measured from the
  backward direction (``0`` = back to the source, as lidar and radar codes and
  graphics conventions with the incident direction pointing away do):
  ``backward=True``.

Exporters: :func:`to_mitsuba_tabphase`, :func:`to_mcx_invcdf`, :func:`to_csv`.
"""

from __future__ import annotations

import numpy as np

from ._real import real_array

__all__ = [
    "legendre_with_2l1",
    "legendre_without_2l1",
    "legendre_moments_of",
    "legendre_series",
    "convert_normalization",
    "mu_from_angle",
    "angle_from_mu",
    "to_mitsuba_tabphase",
    "to_mcx_invcdf",
    "to_csv",
]

_FACTORS = {"sr": 1.0, "4pi": 4.0 * np.pi, "mu": 2.0 * np.pi}


def legendre_with_2l1(chi):
    """``beta_l = (2l + 1) chi_l``: moments ``<P_l>`` to expansion coefficients."""
    chi = real_array(chi)
    return chi * (2.0 * np.arange(chi.shape[-1]) + 1.0)


def legendre_without_2l1(beta):
    """``chi_l = beta_l / (2l + 1)``: expansion coefficients to moments ``<P_l>``."""
    beta = real_array(beta)
    return beta / (2.0 * np.arange(beta.shape[-1]) + 1.0)


def legendre_moments_of(mu, weighted_pdf, n):
    """``chi_l = sum_j weighted_pdf_j P_l(mu_j)`` for ``l < n``: the moments from
    quadrature nodes ``mu`` and weights already multiplied by ``2 pi p(mu)``
    (so that ``chi_0`` is the quadrature of the normalisation, 1 when resolved)."""
    mu = real_array(mu)
    wp = real_array(weighted_pdf)
    out = np.empty(int(n))
    p_prev, p = np.ones_like(mu), mu.copy()
    out[0] = wp.sum()
    if n > 1:
        out[1] = (wp * p).sum()
    for l in range(1, int(n) - 1):
        p_prev, p = p, ((2 * l + 1) * mu * p - l * p_prev) / (l + 1)
        out[l + 1] = (wp * p).sum()
    return out


def legendre_series(chi, mu):
    """The density per steradian ``sum (2l + 1) chi_l P_l(mu) / (4 pi)`` of moments ``chi``."""
    beta = legendre_with_2l1(chi)
    return np.polynomial.legendre.legval(real_array(mu), beta) / (4.0 * np.pi)


def convert_normalization(values, source: str, target: str):
    """Phase-function values from one normalisation to another: ``"sr"``,
    ``"4pi"`` (the same values as normalised to 2 over ``mu``) or ``"mu"``
    (module docs)."""
    try:
        f = _FACTORS[target] / _FACTORS[source]
    except KeyError:
        raise ValueError(f"normalisations are {sorted(_FACTORS)}, not {source!r} -> {target!r}") from None
    return real_array(values) * f


def mu_from_angle(angle, *, degrees: bool = False, backward: bool = False):
    """``mu = cos(theta)`` of a scattering angle measured from the forward
    direction, or from the backward one with ``backward=True`` (``mu = -cos``)."""
    a = real_array(angle)
    if degrees:
        a = np.radians(a)
    mu = np.cos(a)
    return -mu if backward else mu


def angle_from_mu(mu, *, degrees: bool = False, backward: bool = False):
    """The scattering angle of ``mu`` (inverse of :func:`mu_from_angle`), in
    ``[0, pi]`` (or degrees)."""
    m = np.clip(real_array(mu), -1.0, 1.0)
    a = np.arccos(-m if backward else m)
    return np.degrees(a) if degrees else a


def to_mitsuba_tabphase(phase, n: int = 1025) -> str:
    """The ``values`` string of Mitsuba 3's ``tabphase`` plugin: the density at
    ``n`` cosines evenly spaced over ``[-1, 1]``, ``-1`` first, in Mitsuba's
    physics convention for this plugin (``cos theta = 1`` forward, as here;
    Mitsuba normalises the table and interpolates it linearly, so a forward peak
    needs ``n`` large enough to resolve it)."""
    n = int(n)
    if n < 2:
        raise ValueError("to_mitsuba_tabphase: n must be at least 2")
    values = phase.pdf(np.linspace(-1.0, 1.0, n))
    return ", ".join(f"{v:.9g}" for v in values)


def to_mcx_invcdf(phase, n: int = 1000):
    """MCX's ``cfg.invcdf`` (mcxlab, pmcx; ``Domain.InverseCDF`` in its JSON
    input): ``m`` scattering cosines, ``m = n`` for an even ``n`` and
    ``n + 1`` for an odd one, at the uniforms ``k/(m + 1)``, ``k = 1 ... m``.

    That is where MCX reads them. Its host code (``mcx_set_field`` in
    ``mcxlab.cpp``, the ``InverseCDF`` reader in ``mcx_utils.c``) puts -1
    before the ``m`` values and 1 after them (``nphase = m + 2``), then pads
    an odd ``nphase`` with one more 1 (``cfg->nphase += (cfg->nphase &
    0x1)``); its kernel (``mcx_core.cu``) draws ``x = u (nphase - 1)`` and
    interpolates linearly between entries ``floor(x)`` and ``floor(x) + 1``,
    so entry ``j`` sits at ``u = j/(nphase - 1)``. An even ``m`` is never
    padded, and value ``k`` then sits at ``u = k/(m + 1)``; an odd ``m``
    would be padded, putting mass ``1/(m + 2)`` at ``cos θ = 1`` and every
    node at the wrong ``u``."""
    n = int(n)
    if n < 2:
        raise ValueError("to_mcx_invcdf: n must be at least 2")
    m = n + (n & 1)
    return phase.sample_cos(np.arange(1, m + 1) / (m + 1))


def _mcx_table(invcdf):
    """The table MCX's kernel reads for ``cfg.invcdf`` (see
    :func:`to_mcx_invcdf`): -1, the values, 1, and one more 1 when the count
    so far is odd."""
    values = real_array(invcdf)
    nphase = values.size + 2
    nphase += nphase & 1
    table = np.ones(nphase)
    table[0] = -1.0
    table[1 : values.size + 1] = values
    return table


def to_csv(phase, path, n: int = 1801, *, degrees: bool = True) -> None:
    """A plain CSV at ``path``: columns ``angle`` (from forward, degrees unless
    ``degrees=False``), ``mu``, ``pdf_sr`` (per steradian) and ``pdf_4pi``, over
    ``n`` angles evenly spaced from 0 to 180°."""
    n = int(n)
    if n < 2:
        raise ValueError("to_csv: n must be at least 2")
    angle = np.linspace(0.0, 180.0 if degrees else np.pi, n)
    mu = mu_from_angle(angle, degrees=degrees)
    p = phase.pdf(mu)
    table = np.column_stack([angle, mu, p, convert_normalization(p, "sr", "4pi")])
    np.savetxt(path, table, delimiter=",", header="angle,mu,pdf_sr,pdf_4pi", comments="", fmt="%.10g")
