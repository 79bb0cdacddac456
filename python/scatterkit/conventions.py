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


# The largest table to_mitsuba_tabphase picks by itself: 2^18 + 1 values
# (about 4 MB of text).
_TABPHASE_MAX = 262145


def _tabphase_table(phase, n: int):
    """The density at ``n`` cosines evenly spaced over ``[-1, 1]``; a value at
    ``mu = +-1`` that is not finite (a pole, as Fournier-Forand's at 1, or
    a Dirac limit) is the density half a step in."""
    mu = np.linspace(-1.0, 1.0, n)
    values = np.asarray(phase.pdf(mu), dtype=np.float64)
    half = 1.0 / (n - 1)
    for end, inside in ((0, -1.0 + half), (-1, 1.0 - half)):
        if not np.isfinite(values[end]):
            values[end] = float(phase.pdf(inside))
    return mu, values


# Gauss-Legendre's three nodes and weights on [0, 1]: exact for polynomials
# of degree 5.
_GAUSS3 = (
    np.array([0.5 - 0.5 * np.sqrt(0.6), 0.5, 0.5 + 0.5 * np.sqrt(0.6)]),
    np.array([5.0, 8.0, 5.0]) / 18.0,
)


def _interpolant_errors(phase, x, values, mu_of, dmu_dx):
    """What a renderer evaluates from ``values`` linear in ``x`` between
    nodes, where ``mu = mu_of(x)``: the interpolant's integral over the sphere
    less 1 (``tabphase`` divides by it; ``scatterkit_native`` does not, and a
    render gains or loses that much per scattering), and the mean cosine of
    the normalised interpolant less the phase function's. Both integrals are
    exact where ``mu_of`` is a polynomial of degree 2 or less (degree 4 with
    the interpolant and ``|dmu/dx|``)."""
    if not np.all(np.isfinite(values)):
        return np.inf, np.inf
    t, w = _GAUSS3
    h = np.diff(x)[:, None]
    xs = x[:-1, None] + h * t
    p = values[:-1, None] + (values[1:] - values[:-1])[:, None] * t
    weight = w * h * np.abs(dmu_dx(xs)) * p
    m0, m1 = float(np.sum(weight)), float(np.sum(weight * mu_of(xs)))
    if not m0 > 0.0:
        return np.inf, np.inf
    return abs(2.0 * np.pi * m0 - 1.0), abs(m1 / m0 - float(phase.mean_cosine))


def _tabphase_errors(phase, mu, values):
    """:func:`_interpolant_errors` of ``tabphase``'s table, linear in ``mu``."""
    return _interpolant_errors(phase, mu, values, lambda x: x, np.ones_like)


def to_mitsuba_tabphase(phase, n=None, *, tolerance: float = 1e-3) -> str:
    """The ``values`` string of Mitsuba 3's ``tabphase`` plugin: the density at
    ``n`` cosines evenly spaced over ``[-1, 1]``, ``-1`` first, in Mitsuba's
    physics convention for this plugin (``cos theta = 1`` forward, as here).

    Mitsuba interpolates the values linearly and divides by the integral of
    that interpolant, so a table too coarse for a forward peak renders
    another phase function: at 1025 values, HG at ``g = 0.99`` integrates to
    9.9 and renders with a mean cosine of 0.998, and the fog of 10 um
    droplets (``g = 0.864``) with 0.967. The table is therefore checked: its
    interpolant's integral over the sphere within ``tolerance`` of 1, and
    the normalised interpolant's mean cosine within ``tolerance`` of the
    phase function's. A density that is not finite at ``mu = +-1`` (a pole)
    is tabulated half a step in.

    ``n=None`` takes the smallest ``2^k + 1`` values from 1025 to 262145
    that pass. ``ValueError`` for an ``n`` below 2 or one that fails (with
    its errors), and for a phase function no table of up to 262145 values
    represents (HG from ``g`` of about 0.99, the fog of droplets above about
    12 um, a Dirac limit, Fournier-Forand's pole): render those with
    :mod:`scatterkit.mitsuba`'s plugins, which sample the phase function
    itself, or ask for a larger ``n`` where the message names one.
    ``tolerance=math.inf`` accepts any table."""
    if not tolerance > 0.0:
        raise ValueError(f"to_mitsuba_tabphase: tolerance must be positive, not {tolerance!r}")
    sizes = [int(n)] if n is not None else [2**k + 1 for k in range(10, 19)]
    if sizes[0] < 2:
        raise ValueError("to_mitsuba_tabphase: n must be at least 2")
    for size in sizes:
        mu, values = _tabphase_table(phase, size)
        norm, g = _tabphase_errors(phase, mu, values)
        if norm <= tolerance and g <= tolerance:
            return ", ".join(f"{v:.9g}" for v in values)
    if n is not None:
        raise ValueError(
            f"to_mitsuba_tabphase: {size} values misrepresent {phase!r} in Mitsuba's linear "
            f"tabphase: its integral over the sphere is {norm:.3g} away from 1 and the mean cosine "
            f"Mitsuba renders {g:.3g} from the phase function's (tolerance {tolerance:g}); leave n "
            f"to the exporter (n=None)"
        )
    hint = ""
    if np.isfinite(norm) and np.isfinite(g):
        # Both errors fall as the square of the step.
        k = int(np.ceil(np.log2((size - 1) * np.sqrt(max(norm, g) / tolerance))))
        hint = f", or ask for n={2**k + 1} (about {2**k * 16 // 10**6} MB of text)"
    raise ValueError(
        f"to_mitsuba_tabphase: no table of up to {_TABPHASE_MAX} evenly spaced values represents "
        f"{phase!r} in Mitsuba's linear tabphase within {tolerance:g} (at {size}: integral off by "
        f"{norm:.3g}, mean cosine by {g:.3g}); render it with scatterkit.mitsuba's plugins{hint}"
    )


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
