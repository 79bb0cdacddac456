"""scatterkit: light-scattering models and samplers over numpy arrays.

The Rust library scatterkit, from Python. Every function takes array-likes
(lists, scalars, numpy arrays of any shape), converts them to float64 as
numpy does, and returns arrays of the same shape (a float for a scalar).
Long work runs with the GIL released. Bad input raises ``ValueError`` with
the library's message; nothing crashes the interpreter.

Conventions (see :mod:`scatterkit.conventions` to convert from others):

* ``mu = cos(theta)``, ``theta`` the scattering angle: ``mu = +1`` is
  forward (no deflection), ``mu = -1`` backward.
* Phase functions are densities per steradian: the integral over the
  sphere is 1, so isotropic scattering is ``1/(4 pi)``.
* Legendre moments are ``chi_l = <P_l(mu)>`` (``chi_0 = 1``, ``chi_1 = g``),
  so ``p(mu) = sum_l (2l + 1) chi_l P_l(mu) / (4 pi)``.
* Uniforms lie in ``[0, 1]``; a ``numpy.random.Generator`` may stand in for
  them.

Contents: :class:`Phase` (every model and mixtures), :class:`Mie` (one
sphere, exact), :class:`AlbedoCurve` (the albedo of a layer against the
single-scattering albedo, and its inverse), :func:`water_index`,
:func:`size_parameter`, :class:`Medium` (a density grid: transmittance
estimators and delta tracking over arrays of rays),
:class:`RayleighPolarized` (Stokes vectors as arrays), :func:`fit` and
:func:`fit_mie` (the simplest model within a tolerance), and
:mod:`scatterkit.conventions`.
"""

from __future__ import annotations

from typing import NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _scatterkit as _sk
from ._real import real_array
from . import conventions

__all__ = [
    "Phase",
    "Mie",
    "AlbedoCurve",
    "Medium",
    "RayleighPolarized",
    "Fit",
    "fit",
    "fit_mie",
    "polydisperse",
    "Averages",
    "equiangular",
    "Table2d",
    "SpectralPhase",
    "water_index",
    "size_parameter",
    "get_include",
    "conventions",
]

__version__ = "0.2.0"

#: Anything numpy converts to an array of floats: a scalar, a list, an array.
ArrayLike = npt.ArrayLike
#: A float for a scalar argument, else an array of the argument's shape.
FloatOrArray = Union[float, np.ndarray]


def _flat(x, name):
    """``x`` as a contiguous 1-D float64 array, its shape and scalarness."""
    a = real_array(x, name)
    if a.dtype != np.float64:  # pragma: no cover - asarray converts or raises
        raise TypeError(f"{name}: expected real numbers")
    return np.ascontiguousarray(a.ravel()), a.shape, a.ndim == 0


def _shaped(out, shape, scalar):
    return float(out[0]) if scalar else out.reshape(shape)


def _uniforms(u, rng, size, name):
    """The uniforms given, or drawn from ``rng`` (a numpy Generator)."""
    if u is not None and rng is not None:
        raise ValueError(f"{name}: give u or rng, not both")
    if u is None:
        if rng is None:
            raise ValueError(f"{name}: give the uniforms u, or rng (a numpy.random.Generator)")
        return rng.random(size if size is not None else ())
    return u


def _uniform_pair(u1, u2, rng, size, name):
    """Both uniforms given, or ``size`` pairs drawn from ``rng``."""
    if (u1 is None) != (u2 is None):
        raise ValueError(f"{name}: give both u1 and u2, or rng")
    if u1 is None:
        if rng is None:
            raise ValueError(f"{name}: give u1 and u2, or rng (a numpy.random.Generator)")
        shape = size if size is not None else ()
        return rng.random(shape), rng.random(shape)
    if rng is not None:
        raise ValueError(f"{name}: give u1 and u2, or rng, not both")
    return u1, u2


class Phase:
    """A phase function: one of the library's models, a mixture of them, a
    Legendre series or a table.

    Build one with a class method (``Phase.henyey_greenstein(0.8)``, ...);
    every method takes cosines or uniforms as array-likes.

    >>> hg = Phase.henyey_greenstein(0.8)
    >>> round(hg.mean_cosine, 12)
    0.8
    """

    __slots__ = ("_p",)

    def __init__(self, compiled: _sk._Phase):
        if not isinstance(compiled, _sk._Phase):
            raise TypeError("build a Phase with one of its class methods, e.g. Phase.isotropic()")
        self._p = compiled

    def __reduce__(self):
        # Pickles (for multiprocessing, Dask, joblib) as its model's
        # parameters, a mixture's parts and weights as given, or a table's
        # data: unpickled, it gives the same bits.
        return (_phase_from_state, (self._p._state(),))

    # -- models -----------------------------------------------------------
    @classmethod
    def isotropic(cls) -> "Phase":
        """Isotropic scattering, ``1/(4 pi)`` per steradian."""
        return cls(_sk._Phase.isotropic())

    @classmethod
    def rayleigh(cls) -> "Phase":
        """Rayleigh scattering of unpolarised light, ``3(1 + mu^2)/(16 pi)``."""
        return cls(_sk._Phase.rayleigh())

    @classmethod
    def rayleigh_depolarized(cls, rho: float) -> "Phase":
        """Rayleigh scattering with depolarisation factor ``rho`` in ``[0, 1)``
        (air: about 0.0279), ``p ∝ 1 + 3 gamma + (1 - gamma) mu^2`` with
        ``gamma = rho/(2 - rho)``."""
        return cls(_sk._Phase.rayleigh_depolarized(float(rho)))

    @classmethod
    def henyey_greenstein(cls, g: float) -> "Phase":
        """Henyey–Greenstein with asymmetry ``g`` in ``[-1, 1]`` (the mean cosine).
        ``|g| = 1`` is the Dirac limit: every sample is ``cos θ = g``, the
        density ``inf`` there and 0 elsewhere."""
        return cls(_sk._Phase.henyey_greenstein(float(g)))

    @classmethod
    def two_lobe_hg(cls, g1: float, g2: float, w: float) -> "Phase":
        """Two Henyey–Greenstein lobes: ``w p_HG(g1) + (1 - w) p_HG(g2)``,
        ``g1, g2`` in ``[-1, 1]`` (``|g| = 1`` a Dirac lobe), ``w`` in ``[0, 1]``."""
        return cls(_sk._Phase.two_lobe_hg(float(g1), float(g2), float(w)))

    @classmethod
    def draine(cls, g: float, alpha: float) -> "Phase":
        """Draine's phase function (Draine 2003, eq. 4), ``p ∝ p_HG(g) (1 + alpha mu^2)``,
        ``g`` in ``(-1, 1)``, ``alpha >= 0``; note ``g`` is HG's parameter, not the mean cosine."""
        return cls(_sk._Phase.draine(float(g), float(alpha)))

    @classmethod
    def cornette_shanks(cls, g: float) -> "Phase":
        """Cornette–Shanks (1992): Draine's form at ``alpha = 1``, ``g`` in ``(-1, 1)``."""
        return cls(_sk._Phase.cornette_shanks(float(g)))

    @classmethod
    def fog(cls, g_hg: float, g_d: float, alpha: float, w_d: float) -> "Phase":
        """Jendersie & d'Eon's fog (2023): ``(1 - w_d) p_HG(g_hg) + w_d p_Draine(g_d, alpha)``."""
        return cls(_sk._Phase.fog(float(g_hg), float(g_d), float(alpha), float(w_d)))

    @classmethod
    def fog_diameter(cls, diameter_um: float) -> "Phase":
        """The fog of water droplets of ``diameter_um`` micrometres, ``0 < d <= 50``
        (Jendersie & d'Eon's fit to Mie theory)."""
        return cls(_sk._Phase.fog_diameter(float(diameter_um)))

    @classmethod
    def gegenbauer(cls, alpha: float, g: float) -> "Phase":
        """The Gegenbauer kernel (Reynolds & McCormick 1980),
        ``p ∝ (1 + g^2 - 2 g mu)^-(alpha + 1)``, ``-1/2 < alpha <= 1000``,
        ``g`` in ``(-1, 1)`` (``alpha = 1/2`` is HG)."""
        return cls(_sk._Phase.gegenbauer(float(alpha), float(g)))

    @classmethod
    def fournier_forand(cls, n: float, mu_j: float) -> "Phase":
        """Fournier–Forand (1994) for ocean particles of real relative index ``n``
        in ``(1, 1.8]`` with a Junge size distribution of slope ``mu_j`` in ``(3, 5)``."""
        return cls(_sk._Phase.fournier_forand(float(n), float(mu_j)))

    @classmethod
    def fournier_forand_backscatter(cls, b: float, n: float) -> "Phase":
        """Fournier–Forand from the backscatter fraction ``b`` in
        ``[sys.float_info.min, 1/2)`` (a smaller ``b`` would give a subnormal
        ``nu``, too few bits to give ``b`` back) and the index ``n`` in ``(1, 1.8]``,
        as oceanographers specify it (Mobley et al. 2002)."""
        return cls(_sk._Phase.fournier_forand_backscatter(float(b), float(n)))

    @classmethod
    def schlick(cls, k: float) -> "Phase":
        """Schlick's rational stand-in for HG (Blasi, Le Saëc & Schlick 1993),
        ``p = (1 - k^2) / (4 pi (1 - k mu)^2)``, ``k`` in ``(-1, 1)``; its mean
        cosine is not ``k``."""
        return cls(_sk._Phase.schlick(float(k)))

    @classmethod
    def modified_hg(cls, g: float, gamma: float) -> "Phase":
        """Tissue optics' modified HG (Bevilacqua & Depeursinge 1999),
        ``beta p_HG(g_HG) + (1 - beta) (3/4pi) cos^2``, set by its mean cosine
        ``g`` in ``(0, 1)`` and ``gamma = (1 - chi_2)/(1 - chi_1)``,
        ``0.6 < gamma <= 1 + g`` (the top, HG itself, taken with 4 machine
        epsilons of relative slack); ``ValueError`` outside that reach."""
        return cls(_sk._Phase.modified_hg(float(g), float(gamma)))

    @classmethod
    def modified_hg_delta(cls, g: float, delta: float) -> "Phase":
        """:meth:`modified_hg` set by ``g`` and ``delta = (1 - chi_3)/(1 - chi_1)``,
        ``1 < delta <= 1 + g + g^2`` (the top with the same slack)."""
        return cls(_sk._Phase.modified_hg_delta(float(g), float(delta)))

    @classmethod
    def two_lobe_hg_gamma(cls, g: float, gamma: float) -> "Phase":
        """HG with an isotropic lobe (Prahl's modified HG) set by ``g`` in
        ``(0, 1)`` and ``gamma``, ``1 < gamma <= 1 + g`` (the top, HG itself,
        taken with 4 machine epsilons of relative slack)."""
        return cls(_sk._Phase.two_lobe_hg_gamma(float(g), float(gamma)))

    @classmethod
    def two_lobe_hg_delta(cls, g: float, delta: float) -> "Phase":
        """:meth:`two_lobe_hg_gamma` set by ``g`` and ``delta``,
        ``1 < delta <= 1 + g + g^2`` (the top with the same slack)."""
        return cls(_sk._Phase.two_lobe_hg_delta(float(g), float(delta)))

    @classmethod
    def gegenbauer_gamma(cls, g: float, gamma: float) -> "Phase":
        """The Gegenbauer kernel with mean cosine ``g`` in ``(0, 1)`` and
        ``gamma``; the band reached at each ``g`` is measured in
        ``docs/guides/phase_functions.md``."""
        return cls(_sk._Phase.gegenbauer_gamma(float(g), float(gamma)))

    @classmethod
    def gegenbauer_delta(cls, g: float, delta: float) -> "Phase":
        """The Gegenbauer kernel with mean cosine ``g`` and ``delta``."""
        return cls(_sk._Phase.gegenbauer_delta(float(g), float(delta)))

    @classmethod
    def mixture(cls, parts: Sequence[Tuple["Phase", float]]) -> "Phase":
        """A mixture of models with weights: ``parts`` is a sequence of ``(Phase, weight)``
        (weights >= 0, normalised to sum 1; up to 8 parts, none itself a mixture).
        Sampling inverts the mixture's own CDF (monotone in ``u``)."""
        compiled = []
        for part in parts:
            try:
                phase, weight = part
            except (TypeError, ValueError):
                raise ValueError("mixture: each part is a (Phase, weight) pair") from None
            if not isinstance(phase, Phase):
                raise TypeError("mixture: each part's first item must be a Phase")
            compiled.append((phase._p, float(weight)))
        return cls(_sk._Phase.mixture(compiled))

    @classmethod
    def legendre_series(cls, chi: ArrayLike) -> "Phase":
        """The phase function ``sum (2l + 1) chi_l P_l(mu) / (4 pi)`` of the Legendre
        moments ``chi`` (``chi_0 = 1``; see :mod:`scatterkit.conventions` for
        coefficients that carry the ``2l + 1``), sampled by its exact inverse CDF.
        ``ValueError`` where the series goes negative."""
        c, _, _ = _flat(chi, "legendre_series")
        return cls(_sk._Phase.legendre_series(list(c)))

    @classmethod
    def table(cls, phase: "Phase", n: int = 256) -> "Phase":
        """An O(1) inverse-CDF table of ``phase`` at ``n`` intervals (cubic Hermite;
        the library's ``sk_table`` layout, which ``include/scatterkit_portable.h``
        looks up in GPU kernels): ``table_data`` is what to copy to the device."""
        if not isinstance(phase, Phase):
            raise TypeError("table: phase must be a Phase")
        return cls(_sk._Phase.table_of(phase._p, int(n)))

    @classmethod
    def table_measured(cls, cos_theta: ArrayLike, pdf: ArrayLike, n: int = 256) -> "Phase":
        """A table of a measured phase function: ``pdf`` (any scale) at
        ``cos_theta`` (at least 2 points, strictly monotone within ``[-1, 1]``),
        linear between the points and zero outside them."""
        c, _, _ = _flat(cos_theta, "table_measured")
        p, _, _ = _flat(pdf, "table_measured")
        return cls(_sk._Phase.table_measured(c, p, int(n)))

    @property
    def table_data(self) -> Optional[np.ndarray]:
        """A table's data (``2(n + 1)`` values: the nodes ``mu_i`` and slopes of
        its Hermite spline), or ``None`` for other phase functions."""
        return self._p.table_data()

    # -- evaluation -------------------------------------------------------
    @property
    def name(self) -> str:
        """The model's name (``"mixture"`` for a mixture)."""
        return self._p.name

    @property
    def mean_cosine(self) -> float:
        """The asymmetry parameter ``g = <mu>``."""
        return self._p.mean_cosine

    def pdf(self, mu: ArrayLike) -> FloatOrArray:
        """The density per steradian at each cosine ``mu`` in ``[-1, 1]``;
        within 8 ulp beyond +-1 (a dot product's rounding) it is read at +-1,
        and further out it is 0 (as the CDF is 0 or 1 there), as in C and
        Rust. ``TypeError`` for complex input."""
        x, shape, scalar = _flat(mu, "pdf")
        return _shaped(self._p.pdf(x), shape, scalar)

    def cdf(self, mu: ArrayLike) -> FloatOrArray:
        """The probability that the scattering cosine is at most ``mu``
        (``2 pi`` times the integral of the density from -1 to ``mu``)."""
        x, shape, scalar = _flat(mu, "cdf")
        return _shaped(self._p.cdf(x), shape, scalar)

    def sample_cos(self, u: Optional[ArrayLike] = None, *, rng: Optional[np.random.Generator] = None,
                   size=None, out: Optional[np.ndarray] = None) -> FloatOrArray:
        """Scattering cosines: the inverse CDF at uniforms ``u`` in ``[0, 1]``
        (monotone: ``u = 0`` gives -1), or at ``size`` uniforms drawn from ``rng``
        (a ``numpy.random.Generator``). ``out``, a C-contiguous, writeable
        float64 array of the uniforms' shape that shares no memory with them,
        receives them without a new allocation (and is returned). ``ValueError`` for a uniform outside ``[0, 1]`` or NaN (with
        ``out``, part of it may have been written then), for scalars as for
        arrays; C and Rust clamp such a ``u`` into ``[0, 1]`` and return NaN
        for NaN instead (their docs say so too). ``TypeError`` for complex
        input. Long arrays are split
        over the processor's cores, with the same results as one pass."""
        u = _uniforms(u, rng, size, "sample_cos")
        x, shape, scalar = _flat(u, "sample_cos")
        if out is not None:
            if not (isinstance(out, np.ndarray) and out.dtype == np.float64
                    and out.flags.c_contiguous and out.shape == tuple(shape)):
                raise ValueError("sample_cos: out must be a C-contiguous float64 array of u's shape")
            if not out.flags.writeable:
                raise ValueError("sample_cos: out must be writeable")
            # The uniforms are read while out is written: they may not share
            # memory (bounds are compared, so an overlap is never missed).
            if np.may_share_memory(out, x):
                raise ValueError("sample_cos: out must not share memory with u")
            self._p.sample_cos_into(x, out.reshape(-1))
            return out
        return _shaped(self._p.sample_cos(x), shape, scalar)

    def sample_cos_portable(self, u: ArrayLike) -> np.ndarray:
        """The cosines ``scatterkit_portable.h`` computes in float for an
        isotropic, Henyey–Greenstein or Rayleigh phase, bit for bit: what a
        kernel compiled with ``-I`` :func:`get_include` returns for the same
        float32 uniforms ``u`` (converted to float32; clamped to ``[0, 1]``
        as the header clamps, NaN gives NaN). A float32 array of ``u``'s
        shape; ``ValueError`` for any other model."""
        if np.iscomplexobj(u):
            raise TypeError("sample_cos_portable: u must be real numbers")
        a = np.ascontiguousarray(u, dtype=np.float32)
        return self._p.sample_cos_portable(a.reshape(-1)).reshape(a.shape)

    def sample_dir(self, w_in: ArrayLike, u1: Optional[ArrayLike] = None, u2: Optional[ArrayLike] = None, *,
                   rng: Optional[np.random.Generator] = None, size=None) -> Tuple[np.ndarray, FloatOrArray]:
        """Directions scattered from the unit direction ``w_in`` (3 values, the
        direction of travel): ``(dirs, pdf)``, ``dirs`` of shape ``shape + (3,)``
        and ``pdf`` the density per steradian of each. The uniforms ``u1`` (the
        polar angle) and ``u2`` (the azimuth), of one shape, or ``size`` pairs from
        ``rng``."""
        u1, u2 = _uniform_pair(u1, u2, rng, size, "sample_dir")
        w = real_array(w_in)
        if w.shape != (3,):
            raise ValueError("sample_dir: w_in must hold 3 values")
        a, shape, scalar = _flat(u1, "sample_dir")
        b, shape2, _ = _flat(u2, "sample_dir")
        if shape != shape2:
            raise ValueError("sample_dir: u1 and u2 must have one shape")
        d, pdf = self._p.sample_dir([float(v) for v in w], a, b)
        d = d.reshape(tuple(shape) + (3,))
        return (d, float(pdf[0])) if scalar else (d, pdf.reshape(shape))

    def legendre(self, n: int) -> np.ndarray:
        """The Legendre moments ``chi_0 ... chi_{n-1}`` (closed forms where the
        model has them, else quadrature over its inverse CDF); see
        :func:`scatterkit.conventions.legendre_with_2l1` for the other convention."""
        return self._p.legendre(int(n))

    def __repr__(self) -> str:
        return f"Phase.{self._p!r}"


def _phase_from_state(state) -> "Phase":
    return Phase(_sk._Phase._from_state(state))


def _albedo_from_state(state) -> "AlbedoCurve":
    c = AlbedoCurve.__new__(AlbedoCurve)
    c._c = _sk._AlbedoCurve._from_state(state)
    return c


def _rebuilt(cls, args, kwargs):
    return cls(*args, **kwargs)


class Mie:
    """One homogeneous sphere solved by Lorenz–Mie theory (exact; the library's
    series, no allocation beyond its coefficients).

    ``x`` is the size parameter ``pi d n_medium / wavelength`` in ``[1e-20, 1e5]``;
    ``m`` the complex refractive index relative to the medium, ``m = n + i k``
    with ``0 < n <= 1000``, ``0 <= k <= 1000`` (absorbing: ``k > 0``), ``|m| >= 1e-100``,
    ``|m| x <= 2e6``, and ``m != 1``: a sphere of the medium's own index does not
    scatter, so it has no phase function (``ValueError``).

    >>> s = Mie(10.0, 1.33)
    >>> 2.0 < s.q_ext < 2.2
    True
    """

    __slots__ = ("_s", "x", "m")

    def __init__(self, x: float, m: complex):
        m = complex(m)
        self.x = float(x)
        self.m = m
        self._s = _sk._Mie(self.x, m.real, m.imag)

    def __reduce__(self):
        return (Mie, (self.x, self.m))

    @property
    def q_ext(self) -> float:
        """Extinction efficiency (cross-section over ``pi r^2``)."""
        return self._s.q_ext

    @property
    def q_sca(self) -> float:
        """Scattering efficiency."""
        return self._s.q_sca

    @property
    def q_abs(self) -> float:
        """Absorption efficiency, ``q_ext - q_sca``."""
        return self._s.q_ext - self._s.q_sca

    @property
    def q_back(self) -> float:
        """Backscattering efficiency, ``4 |S1(180°)|^2 / x^2``."""
        return self._s.q_back

    @property
    def g(self) -> float:
        """Asymmetry parameter ``<cos theta>``."""
        return self._s.g

    @property
    def albedo(self) -> float:
        """Single-scattering albedo ``q_sca / q_ext``."""
        return self._s.q_sca / self._s.q_ext

    @property
    def terms(self) -> int:
        """The number of series terms kept."""
        return self._s.terms

    def phase(self, mu: ArrayLike) -> FloatOrArray:
        """The phase function per steradian (integral over the sphere 1) at each
        cosine ``mu``."""
        x, shape, scalar = _flat(mu, "phase")
        return _shaped(self._s.phase(x), shape, scalar)

    def amplitudes(self, mu: ArrayLike) -> Tuple[Union[complex, np.ndarray], Union[complex, np.ndarray]]:
        """The amplitude functions ``(S1, S2)`` (Bohren & Huffman's convention) at
        each cosine, as complex arrays."""
        x, shape, scalar = _flat(mu, "amplitudes")
        r1, i1, r2, i2 = self._s.amplitudes(x)
        s1, s2 = r1 + 1j * i1, r2 + 1j * i2
        if scalar:
            return complex(s1[0]), complex(s2[0])
        return s1.reshape(shape), s2.reshape(shape)

    def legendre(self, n: int, points: Optional[int] = None) -> np.ndarray:
        """The Legendre moments ``chi_0 ... chi_{n-1}`` of the phase function, by
        Gauss–Legendre quadrature over ``mu`` (``points`` nodes; by default enough
        for the series' highest degree and ``n``)."""
        n = int(n)
        if n < 1:
            raise ValueError("legendre(n): n must be at least 1")
        if points is None:
            points = max(2 * n, 4 * self.terms + 64)
        mu, w = np.polynomial.legendre.leggauss(int(points))
        p = self.phase(mu) * (2.0 * np.pi)
        return conventions.legendre_moments_of(mu, w * p, n)

    def __repr__(self) -> str:
        return f"Mie(x={self.x!r}, m={self.m!r})"


def get_include() -> str:
    """The folder of scatterkit's C headers inside the installed package, as
    ``numpy.get_include()`` gives numpy's: pass it as ``-I`` when compiling a
    kernel that includes ``scatterkit_portable.h`` (pyopencl, CuPy, a C
    extension). It holds ``scatterkit_portable.h`` (header-only: float
    samplers for OpenCL C, CUDA, HIP, C and C++), ``scatterkit_table.h``
    (the layout of the tables :meth:`Phase.table_data` returns) and the C
    library's ``scatterkit.h`` and ``scatterkit_inline.h``::

        import pyopencl as cl
        prg = cl.Program(ctx, src).build(
            options=["-I", scatterkit.get_include(),
                     "-cl-fp32-correctly-rounded-divide-sqrt"])
    """
    import os

    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "include")


def water_index(wavelength_um: float) -> Optional[complex]:
    """The complex refractive index of liquid water at ``wavelength_um``
    micrometres (the library's tabulated fit), or ``None`` outside its range."""
    r = _sk.water_index(float(wavelength_um))
    return None if r is None else complex(r[0], r[1])


def size_parameter(diameter: ArrayLike, wavelength: float, n_medium: float = 1.0) -> FloatOrArray:
    """``pi diameter n_medium / wavelength`` (diameter and wavelength in one unit)."""
    d, shape, scalar = _flat(diameter, "size_parameter")
    out = np.array([_sk.size_parameter(v, float(wavelength), float(n_medium)) for v in d])
    return _shaped(out, shape, scalar)


class AlbedoCurve:
    """The albedo of a layer (the fraction of light it reflects) against the
    single-scattering albedo ``omega`` of its medium, traced once by Monte Carlo
    at 65 nodes ``omega_k = 1 - (k/64)^2`` (and 10 more between the first two,
    where a thick slab bends) and interpolated monotonically.

    ``phase``: a :class:`Phase`; ``thickness``: the optical thickness of a slab,
    or ``None`` for a semi-infinite layer; ``mu0``: the cosine of a beam's angle
    from the normal, or ``None`` for diffuse light; ``paths`` paths from the
    generator seeded by ``seed`` (deterministic).
    """

    __slots__ = ("_c",)

    def __init__(self, phase: Phase, thickness: Optional[float] = None, mu0: Optional[float] = None,
                 paths: int = 100_000, seed: int = 0):
        if not isinstance(phase, Phase):
            raise TypeError("AlbedoCurve: phase must be a scatterkit.Phase")
        t = None if thickness is None else float(thickness)
        m = None if mu0 is None else float(mu0)
        self._c = _sk._AlbedoCurve(phase._p, t, m, int(paths), int(seed))

    def __reduce__(self):
        # The traced nodes, not the tracing: unpickling costs nothing.
        return (_albedo_from_state, (self._c._state(),))

    @property
    def paths(self) -> int:
        """The paths traced."""
        return self._c.paths

    def albedo(self, omega: ArrayLike) -> FloatOrArray:
        """The layer's albedo at single-scattering albedo ``omega`` in ``[0, 1]``."""
        x, shape, scalar = _flat(omega, "albedo")
        return _shaped(self._c.albedo(x), shape, scalar)

    def std_error(self, omega: ArrayLike) -> FloatOrArray:
        """The error of :meth:`albedo` at ``omega`` as one standard deviation:
        the Monte Carlo part and the interpolation's, in quadrature (as the C
        header's ``sk_albedo_curve_std_error_f64`` and Rust's
        ``AlbedoCurve::std_error``); NaN outside ``[0, 1]``."""
        x, shape, scalar = _flat(omega, "std_error")
        return _shaped(self._c.std_error(x), shape, scalar)

    def single_scattering_albedo(self, albedo: ArrayLike) -> FloatOrArray:
        """The inverse: the ``omega`` at which the layer's albedo is ``albedo``.
        ``ValueError`` outside the curve's range."""
        x, shape, scalar = _flat(albedo, "single_scattering_albedo")
        return _shaped(self._c.single_scattering_albedo(x), shape, scalar)


def _rays(origins, dirs, t_max):
    o = real_array(origins)
    d = real_array(dirs)
    if o.shape[-1:] != (3,) or d.shape[-1:] != (3,):
        raise ValueError("origins and dirs must have a last axis of 3 values")
    o, d = np.broadcast_arrays(o, d)
    shape = o.shape[:-1]
    t = np.broadcast_to(real_array(t_max), shape)
    flat = lambda a: np.ascontiguousarray(a, dtype=np.float64).ravel()
    return flat(o), flat(d), flat(t), shape


class Medium:
    """A heterogeneous medium: a density grid over a box, scaled by
    absorption and scattering coefficients, with majorant and minorant grids
    for tracking.

    ``density``: a 3-D array indexed ``[i, j, k]`` along x, y, z (values
    finite and >= 0), placed at the nodes of the box (``sampling="nodes"``:
    value ``i`` at ``lo + (hi - lo) i/(n - 1)``) or at cell centres
    (``"cells"``, as pbrt-v4 and OpenVDB place voxels), interpolated
    trilinearly, zero outside the box. ``sigma_a``, ``sigma_s``: per unit
    density and length, so ``sigma_t(p) = (sigma_a + sigma_s) density(p)``.
    ``lo``, ``hi``: the box in world units. ``majorant_cells``: the majorant
    grid's cells per axis (pbrt-v4 uses 16; at most 2^24 cells in all).
    """

    __slots__ = ("_m", "shape", "majorant_cells", "_args")

    def __init__(self, density: ArrayLike, sigma_a: float, sigma_s: float, *,
                 lo: Sequence[float] = (0.0, 0.0, 0.0), hi: Sequence[float] = (1.0, 1.0, 1.0),
                 sampling="nodes", majorant_cells=(16, 16, 16)):
        d = real_array(density)
        if d.ndim != 3:
            raise ValueError("Medium: density must be a 3-D array indexed [x, y, z]")
        if sampling not in ("nodes", "cells"):
            raise ValueError('Medium: sampling is "nodes" or "cells"')
        cells = tuple(int(c) for c in majorant_cells)
        if len(cells) != 3:
            raise ValueError("Medium: majorant_cells holds 3 counts")
        self.shape = d.shape
        self.majorant_cells = cells
        flat = np.ascontiguousarray(d.ravel(order="F"))  # x fastest
        lo3 = [float(v) for v in lo]
        hi3 = [float(v) for v in hi]
        self._m = _sk._Medium(flat, list(d.shape), float(sigma_a), float(sigma_s), lo3, hi3,
                              sampling == "cells", list(cells))
        self._args = ((d.copy(), float(sigma_a), float(sigma_s)),
                      dict(lo=tuple(lo3), hi=tuple(hi3), sampling=sampling, majorant_cells=cells))

    def __reduce__(self):
        # Rebuilt from its density and settings (the majorants are
        # recomputed, as they were built).
        return (_rebuilt, (Medium,) + self._args)

    def majorants(self) -> np.ndarray:
        """The majorant grid (per length unit), indexed ``[i, j, k]``."""
        return self._m.majorants().reshape(self.majorant_cells, order="F")

    def minorants(self) -> np.ndarray:
        """The minorant grid (per length unit), indexed ``[i, j, k]``."""
        return self._m.minorants().reshape(self.majorant_cells, order="F")

    def sigma_t(self, points: ArrayLike) -> FloatOrArray:
        """The extinction coefficient at world points (last axis 3 values)."""
        p = real_array(points)
        if p.shape[-1:] != (3,):
            raise ValueError("sigma_t: points must have a last axis of 3 values")
        out = self._m.sigma_t(np.ascontiguousarray(p).ravel())
        return out.reshape(p.shape[:-1]) if p.ndim > 1 else float(out[0])

    def transmittance(self, origins: ArrayLike, dirs: ArrayLike, t_max: ArrayLike = np.inf, *,
                      estimator: str = "ratio", seed: int = 0, budget: int = 1 << 20,
                      strata: int = 0) -> FloatOrArray:
        """One unbiased transmittance estimate per ray ``origins + t dirs``,
        ``t`` in ``[0, t_max]`` (``dirs`` need not be unit; ``t`` is a distance
        along their direction). Rays broadcast over the leading axes.

        ``estimator``: ``"ratio"`` (ratio tracking through the majorant grid),
        ``"residual"`` (residual ratio tracking with the minorants as control,
        its tentative collisions at twice the residual majorant),
        ``"delta"`` (delta tracking: 1 if the ray escapes, else 0),
        ``"ray_march"`` (unbiased ray marching, the power series) or
        ``"telescoping"``; each at the library's defaults (the marchers'
        strata placed by the majorants and minorants, as many as the
        library chooses per ray; ``strata`` sets the marchers' strata per march,
        or residual tracking's rate as a multiple of the residual majorant,
        1 for the published estimator; 0 is the default). ``seed`` seeds one generator for the whole batch
        (deterministic); ``budget`` caps the density evaluations per ray
        (``ValueError`` past it)."""
        o, d, t, shape = _rays(origins, dirs, t_max)
        if int(strata) < 0:
            raise ValueError("strata must be >= 0")
        out = self._m.transmittance(o, d, t, str(estimator), int(seed), int(budget), int(strata))
        return out.reshape(shape) if shape else float(out[0])

    def emission(self, source: ArrayLike, origins: ArrayLike, dirs: ArrayLike, t_max: ArrayLike = np.inf, *,
                 seed: int = 0, budget: int = 1 << 20) -> Tuple[FloatOrArray, FloatOrArray]:
        """The radiance emitted along each ray and reaching its origin,
        ``integral T(0, t) sigma_a(t) L_e(t) dt``, with the ray's transmittance:
        ``(radiance, tr)``, unbiased estimates (ratio tracking). ``source``: the
        emitted radiance ``L_e`` as a 3-D array indexed ``[x, y, z]`` over the
        medium's box, placed as the density is (any resolution), in the units
        of the result."""
        src = real_array(source)
        if src.ndim != 3:
            raise ValueError("emission: source must be a 3-D array indexed [x, y, z]")
        o, d, t, shape = _rays(origins, dirs, t_max)
        flat = np.ascontiguousarray(src.ravel(order="F"))
        l, tr = self._m.emission(o, d, t, flat, list(src.shape), int(seed), int(budget))
        return (l.reshape(shape), tr.reshape(shape)) if shape else (float(l[0]), float(tr[0]))

    def spectral_track(self, origins: ArrayLike, dirs: ArrayLike, sigma_a: ArrayLike, sigma_s: ArrayLike,
                       t_max: ArrayLike = np.inf, *, hero: Optional[ArrayLike] = None,
                       estimator: str = "delta", seed: int = 0, budget: int = 1 << 20):
        """Hero-wavelength tracking (pbrt-v4, section 14.2; Wilkie et al. 2014)
        for ``c`` wavelength channels at once (1 to 16): ``sigma_a``, ``sigma_s``
        are each channel's coefficients per unit density (the medium's own
        scalar coefficients are not used). ``hero``: the channel drawing the
        free paths, per ray or one for all; ``None`` draws it uniformly per ray
        (from ``seed``), as the balance heuristic over channels needs.

        Returns ``(t, event, weight, r_u, r_l)``: for ``estimator="delta"`` the
        distance and event (0 escaped, 1 scattered, 2 absorbed); for
        ``"ratio"`` the tentative-collision count and 0; and per channel (last
        axis ``c``) pbrt-v4's path weight and the delta-tracking and
        free-flight path densities over the hero's. ``weight[..., k] /
        r_l.mean(-1)`` is channel k's transmittance estimate from ratio
        tracking; ``weight / r_u.mean(-1)`` weighs delta tracking's events."""
        if estimator not in ("delta", "ratio"):
            raise ValueError('spectral_track: estimator is "delta" or "ratio"')
        sa = [float(v) for v in np.atleast_1d(real_array(sigma_a))]
        ss = [float(v) for v in np.atleast_1d(real_array(sigma_s))]
        o, d, t, shape = _rays(origins, dirs, t_max)
        n = t.size
        if hero is None:
            heroes = np.random.default_rng(seed).integers(0, max(len(sa), 1), size=n)
        else:
            heroes = np.broadcast_to(np.asarray(hero), shape).ravel()
        if np.any(heroes < 0):
            raise ValueError("spectral_track: a hero is negative")
        t_out, ev, w, ru, rl = self._m.spectral(o, d, t, sa, ss, [int(h) for h in heroes],
                                                estimator == "ratio", int(seed), int(budget))
        c = len(sa)
        per = tuple(shape) + (c,)
        ev = ev.astype(np.int8)
        return (t_out.reshape(shape), ev.reshape(shape), w.reshape(per), ru.reshape(per),
                rl.reshape(per))

    def delta_track(self, origins: ArrayLike, dirs: ArrayLike, t_max: ArrayLike = np.inf, *, seed: int = 0,
                    budget: int = 1 << 20):
        """Free-flight sampling by delta tracking per ray: ``(t, event)``, the
        distance to the real collision (or where the ray leaves the box, clipped
        to ``[0, t_max]``) and the event: 0 escaped, 1 scattered, 2 absorbed
        (chosen with probability ``sigma_s/sigma_t``)."""
        o, d, t, shape = _rays(origins, dirs, t_max)
        dist, ev = self._m.delta_track(o, d, t, int(seed), int(budget))
        ev = ev.astype(np.int8)
        return (dist.reshape(shape), ev.reshape(shape)) if shape else (float(dist[0]), int(ev[0]))


def _rows(shape, *parts):
    """Broadcasts (array, trailing width) pairs to one batch shape; flat copies."""
    arrays = [real_array(a) for a, _ in parts]
    for a, (_, w) in zip(arrays, parts):
        if w and a.shape[-1:] != (w,):
            raise ValueError(f"expected a last axis of {w} values, got shape {a.shape}")
    batch = np.broadcast_shapes(shape, *[a.shape[:-1] if w else a.shape for a, (_, w) in zip(arrays, parts)])
    out = []
    for a, (_, w) in zip(arrays, parts):
        full = batch + ((w,) if w else ())
        out.append(np.ascontiguousarray(np.broadcast_to(a, full)).ravel())
    return batch, out


class RayleighPolarized:
    """Rayleigh scattering of polarised light: the Mueller matrix (Chandrasekhar
    1950; Hansen & Travis 1974) with depolarisation factor ``rho`` in ``[0, 1)``,
    evaluated and sampled exactly for a given incident Stokes vector.

    A Stokes vector is 4 values ``(I, Q, U, V)`` with a reference direction
    (3 values, a unit vector perpendicular to the direction of travel):
    ``Q > 0`` is linear polarisation along the reference. Arguments broadcast
    over their leading axes: directions ``(..., 3)``, Stokes vectors
    ``(..., 4)``, references ``(..., 3)``.
    """

    __slots__ = ("_r", "rho")

    def __init__(self, rho: float = 0.0):
        self.rho = float(rho)
        self._r = _sk._RayleighPolarized(self.rho)

    def __reduce__(self):
        return (RayleighPolarized, (self.rho,))

    def mueller(self, mu: ArrayLike) -> Tuple[FloatOrArray, ...]:
        """``(P11, P12, P22, P33, P44)`` at each cosine: the normalised Mueller
        matrix (the mean of ``P11`` over the sphere is 1; the phase function
        per steradian is ``P11 / (4 pi)``)."""
        x, shape, scalar = _flat(mu, "mueller")
        cols = self._r.mueller(x)
        return tuple(_shaped(c, shape, scalar) for c in cols)

    def sample(self, k: ArrayLike, stokes: ArrayLike, reference: ArrayLike, u1: Optional[ArrayLike] = None,
               u2: Optional[ArrayLike] = None, *, rng: Optional[np.random.Generator] = None, size=None):
        """Scattered directions for light ``stokes`` (referred to ``reference``)
        travelling along the unit direction ``k``, drawn exactly from the
        polarised phase function: ``(dirs, stokes_out, reference_out, pdf)``,
        the scattered Stokes vectors keeping ``I`` and referred to the new
        scattering plane, and each direction's density per steradian. Uniforms
        ``u1``, ``u2`` in ``[0, 1]``, or ``size`` pairs from ``rng``."""
        u1, u2 = _uniform_pair(u1, u2, rng, size, "sample")
        batch, (kf, sf, rf, a, b) = _rows((), (k, 3), (stokes, 4), (reference, 3), (u1, 0), (u2, 0))
        d, so, ro, pdf = self._r.sample(kf, sf, rf, a, b)
        return (d.reshape(batch + (3,)), so.reshape(batch + (4,)), ro.reshape(batch + (3,)),
                pdf.reshape(batch) if batch else float(pdf[0]))

    def eval(self, k: ArrayLike, stokes: ArrayLike, reference: ArrayLike, w: ArrayLike,
             out_reference: ArrayLike) -> np.ndarray:
        """The Stokes vector scattered into the unit direction ``w`` per
        steradian, referred to ``out_reference`` (unit, perpendicular to ``w``):
        what next-event estimation adds towards a detector."""
        batch, (kf, sf, rf, wf, of) = _rows((), (k, 3), (stokes, 4), (reference, 3), (w, 3), (out_reference, 3))
        return self._r.eval(kf, sf, rf, wf, of).reshape(batch + (4,))

    def pdf(self, k: ArrayLike, stokes: ArrayLike, reference: ArrayLike, w: ArrayLike) -> FloatOrArray:
        """The density per steradian with which :meth:`sample` draws ``w``."""
        batch, (kf, sf, rf, wf) = _rows((), (k, 3), (stokes, 4), (reference, 3), (w, 3))
        out = self._r.pdf(kf, sf, rf, wf)
        return out.reshape(batch) if batch else float(out[0])


_CANDIDATES = ("isotropic", "henyey_greenstein", "rayleigh", "draine", "fog",
               "two_lobe_hg", "fournier_forand", "rayleigh_hg")


class Fit(NamedTuple):
    """What :func:`fit` and :func:`fit_mie` found."""

    phase: Optional[Phase]
    """The chosen model, ready to sample (``None`` when a table won: build it
    from the data)."""
    model: str
    """The chosen model's name, as the :class:`Phase` constructors and the keys
    of ``distances`` spell it (``"two_lobe_hg"``, ...; ``"mie_table"`` when a
    table won); ``repr(phase)`` names the same model."""
    distance: float
    """Its total-variation distance to the reference (0 to 1)."""
    within_tolerance: bool
    """Whether ``distance`` is within the tolerance (if no candidate is, the
    closest is returned)."""
    distances: dict
    """Every candidate's best-fit distance, by name (NaN where not fitted)."""


def _fit(r):
    compiled, model, distance, within, distances = r
    return Fit(None if compiled is None else Phase(compiled), model, distance, within,
               dict(zip(_CANDIDATES, distances)))


def fit(cos_theta: ArrayLike, pdf: ArrayLike, tolerance: float = 0.01, *, allow_table: bool = False) -> Fit:
    """The simplest model within ``tolerance`` (total variation, in ``(0, 1)``)
    of a measured or tabulated phase function: ``pdf`` at ``cos_theta`` (at
    least 2 points, strictly monotone within ``[-1, 1]``; any scale; linear
    between the points). Candidates, cheapest first: isotropic, HG, Rayleigh,
    Draine, two-lobe HG, Fournier–Forand, Rayleigh + HG, each fitted to the
    data; with ``allow_table`` a table of the data itself is the last."""
    c, _, _ = _flat(cos_theta, "fit")
    p, _, _ = _flat(pdf, "fit")
    return _fit(_sk.fit_measured(c, p, float(tolerance), bool(allow_table)))


def fit_mie(diameter_um: float, wavelength_um: float, m: Optional[complex] = None, tolerance: float = 0.01, *,
            allow_table: bool = False) -> Fit:
    """The simplest model within ``tolerance`` of the Mie phase function of
    droplets of ``diameter_um`` µm in air at vacuum wavelength ``wavelength_um``
    µm, relative index ``m`` (``None``: water, for 0.182 to 1.129 µm).
    Candidates as :func:`fit`, with the fog fit up to 50 µm."""
    if m is None:
        re, im = float("nan"), float("nan")
    else:
        m = complex(m)
        re, im = m.real, m.imag
    return _fit(_sk.fit_mie(float(diameter_um), float(wavelength_um), re, im,
                            float(tolerance), bool(allow_table)))


class Averages(NamedTuple):
    """Mie theory averaged over a size distribution (:func:`polydisperse`)."""

    c_ext: float
    """Mean extinction cross section per particle (the radius unit squared)."""
    c_sca: float
    """Mean scattering cross section per particle."""
    c_back: float
    """Mean backscattering cross section per particle."""
    g: float
    """Asymmetry parameter of the mixture."""
    area: float
    """Mean geometric cross section ``pi <r^2>``."""
    errors: tuple
    """Estimated relative errors of ``c_ext``, ``c_sca``, ``c_back`` and the
    absolute error of ``g``."""
    phase_error: float
    """Estimated largest relative error of ``phase``."""
    phase: np.ndarray
    """The phase function per steradian at the cosines asked for."""


_DISTRIBUTIONS = {"lognormal": (0, 2), "gamma": (1, 3), "junge": (2, 1)}


def polydisperse(distribution: Tuple, *, wavelength: float, m: complex, mu: ArrayLike = (),
                 r_min: Optional[float] = None, r_max: Optional[float] = None, n_medium: float = 1.0,
                 intervals: int = 256) -> Averages:
    """Mie theory averaged over a number distribution of sphere radii.

    ``distribution``: ``("lognormal", r_g, sigma_g)`` (median radius, geometric
    standard deviation > 1), ``("gamma", alpha, b, gamma)`` (Deirmendjian's
    modified gamma, ``n(r) ∝ r^alpha exp(-b r^gamma)``) or ``("junge", slope)``
    (``n(r) ∝ r^-slope``, which needs ``r_min`` and ``r_max``). Radii and the
    vacuum ``wavelength`` in one unit; ``m`` the spheres' index relative to the
    medium (``n + ik``), ``n_medium`` the medium's; ``mu`` the cosines at which
    to return the averaged phase function; ``intervals`` Simpson intervals in
    ``ln r`` (a multiple of 4). The range defaults to the distribution's own
    (where its density falls below 1e-12 of the peak)."""
    try:
        name, *params = distribution
        kind, count = _DISTRIBUTIONS[name]
    except (TypeError, ValueError, KeyError):
        raise ValueError('distribution is ("lognormal", r_g, sigma_g), ("gamma", alpha, b, gamma) '
                         'or ("junge", slope)') from None
    if len(params) != count:
        raise ValueError(f"{name} takes {count} parameters")
    p3 = [float(v) for v in params] + [0.0] * (3 - count)
    if r_min is None or r_max is None:
        rng = _sk.default_range(kind, p3)
        if rng is None:
            raise ValueError("give r_min and r_max (a Junge distribution has no natural range)")
        r_min = rng[0] if r_min is None else r_min
        r_max = rng[1] if r_max is None else r_max
    m = complex(m)
    x, shape, scalar = _flat(mu, "polydisperse")
    (c_ext, c_sca, c_back, g, area, errors, phase_error), phase = _sk.polydisperse(
        kind, p3, (float(r_min), float(r_max)), float(wavelength), float(n_medium),
        (m.real, m.imag), int(intervals), x)
    return Averages(c_ext, c_sca, c_back, g, area, tuple(errors), phase_error,
                    _shaped(np.asarray(phase), shape, scalar))


def equiangular(origins: ArrayLike, dirs: ArrayLike, point: ArrayLike, u: ArrayLike, t_min: ArrayLike = 0.0,
                t_max: ArrayLike = np.inf) -> Tuple[FloatOrArray, FloatOrArray]:
    """Equiangular sampling (Kulla & Fajardo 2012): distances along rays
    ``origins + t dirs`` (unit ``dirs``), ``t`` in ``[t_min, t_max]``, with
    density proportional to the inverse square distance to ``point`` (a light):
    ``(t, pdf)``, the density per unit length. Monotone in ``u``. Broadcasts
    over the leading axes."""
    batch, (o, d, p, uu, a, b) = _rows((), (origins, 3), (dirs, 3), (point, 3), (u, 0),
                                       (t_min, 0), (t_max, 0))
    t, pdf = _sk.equiangular(o, d, a, b, p, uu)
    if not batch:
        return float(t[0]), float(pdf[0])
    return t.reshape(batch), pdf.reshape(batch)


def _pair(x, v, name):
    a, b = np.broadcast_arrays(real_array(x), real_array(v))
    shape = a.shape
    return np.ascontiguousarray(a).ravel(), np.ascontiguousarray(b).ravel(), shape


class Table2d:
    """A phase function that varies with a parameter ``x`` (wavelength,
    particle size, ...): ``phases[j]`` tabulated as an inverse-CDF table of ``n``
    intervals at ``x_j = x0 + j dx``, blended linearly between slices (clamped
    outside). The layout of ``sk_table2d``, which GPU kernels look up with
    ``include/scatterkit_portable.h``."""

    __slots__ = ("_t", "_args")

    def __init__(self, phases: Sequence[Phase], x0: float, dx: float, n: int = 256):
        ps = list(phases)
        if not all(isinstance(p, Phase) for p in ps):
            raise TypeError("Table2d: phases must be Phase values")
        self._t = _sk._Table2d([p._p for p in ps], float(x0), float(dx), int(n))
        self._args = (ps, float(x0), float(dx), int(n))

    def __reduce__(self):
        return (Table2d, self._args)

    def _apply(self, f, x, v):
        a, b, shape = _pair(x, v, "Table2d")
        out = f(a, b)
        return out.reshape(shape) if shape else float(out[0])

    def pdf(self, x: ArrayLike, mu: ArrayLike) -> FloatOrArray:
        """The density per steradian at parameter ``x`` and cosine ``mu``."""
        return self._apply(self._t.pdf, x, mu)

    def cdf(self, x: ArrayLike, mu: ArrayLike) -> FloatOrArray:
        """The CDF at parameter ``x`` and cosine ``mu``."""
        return self._apply(self._t.cdf, x, mu)

    def sample_cos(self, x: ArrayLike, u: ArrayLike) -> FloatOrArray:
        """Cosines at parameter ``x`` from uniforms ``u`` in ``[0, 1]``."""
        return self._apply(self._t.sample_cos, x, u)

    def mean_cosine(self, x: ArrayLike) -> FloatOrArray:
        """The mean cosine at parameter ``x``."""
        a, shape, scalar = _flat(x, "mean_cosine")
        return _shaped(self._t.mean_cosine(a), shape, scalar)

    @property
    def data(self) -> np.ndarray:
        """The table's data, shape ``(k, 2(n + 1))``: what to copy to a device."""
        n, k, _, _ = self._t.shape
        return self._t.data().reshape(k, 2 * (n + 1))


class SpectralPhase:
    """A phase function per wavelength channel (1 to 16 models), sampled at a
    hero channel with every channel's density ratio, as hero-wavelength
    renderers need (Wilkie et al. 2014)."""

    __slots__ = ("_s", "_channels")

    def __init__(self, channels: Sequence[Phase]):
        cs = list(channels)
        if not all(isinstance(p, Phase) for p in cs):
            raise TypeError("SpectralPhase: channels must be Phase values")
        self._s = _sk._SpectralPhase([p._p for p in cs])
        self._channels = cs

    def __reduce__(self):
        return (SpectralPhase, (self._channels,))

    @property
    def channels(self) -> int:
        """The number of channels."""
        return self._s.channels

    def pdf(self, mu: ArrayLike) -> np.ndarray:
        """Every channel's density per steradian at each cosine: shape
        ``mu.shape + (channels,)``."""
        x, shape, _ = _flat(mu, "pdf")
        return self._s.pdf(x).reshape(tuple(shape) + (self.channels,))

    def sample_cos(self, hero: int, u: ArrayLike) -> Tuple[FloatOrArray, np.ndarray]:
        """Cosines drawn from channel ``hero``'s phase function at uniforms ``u``,
        and every channel's density over the hero's at each (shape
        ``u.shape + (channels,)``; the hero's column is 1)."""
        x, shape, scalar = _flat(u, "sample_cos")
        mu, ratio = self._s.sample_cos(int(hero), x)
        ratio = ratio.reshape(tuple(shape) + (self.channels,))
        return (float(mu[0]), ratio) if scalar else (mu.reshape(shape), ratio)
