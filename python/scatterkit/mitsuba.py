"""scatterkit's phase functions as Mitsuba 3 phase plugins.

Mitsuba 3 (``pip install mitsuba``) takes phase functions written in Python
through ``mitsuba.register_phase``; this module registers scatterkit's models
that way, so that a scene dict or XML file names them like Mitsuba's own::

    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    import scatterkit.mitsuba as skmi
    skmi.register()                      # the "scatterkit" plugin
    phase = mi.load_dict({"type": "scatterkit", "model": "fog_diameter",
                          "diameter_um": 10.0})

``register()`` adds the plugin ``"scatterkit"`` for the variant set at the
time (call it again after each ``mi.set_variant``). Its ``model`` string names
a :class:`scatterkit.Phase` constructor and the other properties are that
constructor's parameters, by the same names (floats):

==========================  ===============================================
``model``                   parameters
==========================  ===============================================
``isotropic``               (none)
``henyey_greenstein``       ``g``
``rayleigh``                (none)
``rayleigh_depolarized``    ``rho``
``draine``                  ``g``, ``alpha``
``cornette_shanks``         ``g``
``fog``                     ``g_hg``, ``g_d``, ``alpha``, ``w_d``
``fog_diameter``            ``diameter_um``
``fournier_forand``         ``n``, ``mu_j``
``two_lobe_hg``             ``g1``, ``g2``, ``w``
``gegenbauer``              ``alpha``, ``g``
``schlick``                 ``k``
``modified_hg``             ``g``, ``gamma`` (``modified_hg_delta``:
                            ``g``, ``delta``)
``two_lobe_hg_gamma``       ``g``, ``gamma`` (``two_lobe_hg_delta``:
                            ``g``, ``delta``)
``gegenbauer_gamma``        ``g``, ``gamma`` (``gegenbauer_delta``:
                            ``g``, ``delta``)
``mie``                     ``x``, ``m_re``, ``m_im`` (0 if absent): one
                            sphere's Mie phase function (size parameter
                            ``x``, relative index ``m_re + i m_im``) as a
                            table of ``n`` intervals (default 1024)
==========================  ===============================================

Anything else a :class:`scatterkit.Phase` can be (mixtures, tables of
measured data, a size distribution's averaged Mie phase from
:func:`scatterkit.polydisperse`, Legendre series) goes in as a built object:
``register_phase("my_fog", phase)`` adds a plugin ``"my_fog"`` that samples
that object, for dicts (``{"type": "my_fog"}``) and XML
(``<phase type="my_fog"/>``) alike.

Conventions: Mitsuba's ``wi`` points away from the scattering point (towards
where the light came from), so the scattering cosine of an outgoing ``wo`` is
``mu = -dot(wi, wo)``; the plugins evaluate scatterkit's density per steradian
at that ``mu`` and sample ``wo`` by scatterkit's inverse CDF (``sample2.x``
the polar angle, ``sample2.y`` the azimuth), with weight 1. The cosine is
formed and the density evaluated in double precision; a dot product that
rounding carried past ``[-1, 1]`` is read at ``+-1``.

Variants: in scalar variants each call goes to scatterkit's scalar API. In
the JIT variants (``llvm_*``, ``cuda_*``) each call hands the whole wavefront
to scatterkit's array functions, which needs the arrays' values: Dr.Jit must
run loops and calls in wavefront mode, not record them symbolically
(:func:`wavefront` sets that; a plugin called inside a symbolic recording
raises a ``RuntimeError`` saying so).

Speed: a Python plugin costs Python's call overhead per scattering (tens of
times Mitsuba's own ``hg`` per render in ``scalar_rgb``), and wavefront mode
is itself tens of times slower than Mitsuba's default symbolic mode. For
render times like Mitsuba's own plugins, :func:`register_native` compiles the
native plugin ``"scatterkit_native"`` (C++ against the headers Mitsuba's wheel
ships, sampling through scatterkit's portable header) for the scalar
variants; :func:`native` turns the same properties, or any built
:class:`scatterkit.Phase`, into its dict.
"""

from __future__ import annotations

import contextlib
import ctypes
import hashlib
import inspect
import os
import platform
import re
import subprocess
from pathlib import Path
from typing import Dict, Iterator, Optional, Union

import numpy as np

from . import Mie, Phase
from .conventions import _interpolant_errors

__all__ = [
    "register",
    "register_phase",
    "register_native",
    "build_native",
    "native",
    "NATIVE_ANALYTIC",
    "phase_from_properties",
    "wavefront",
    "MODELS",
]

#: The ``model`` strings of the ``"scatterkit"`` plugin and their parameters.
MODELS: Dict[str, tuple] = {
    "isotropic": (),
    "henyey_greenstein": ("g",),
    "rayleigh": (),
    "rayleigh_depolarized": ("rho",),
    "draine": ("g", "alpha"),
    "cornette_shanks": ("g",),
    "fog": ("g_hg", "g_d", "alpha", "w_d"),
    "fog_diameter": ("diameter_um",),
    "fournier_forand": ("n", "mu_j"),
    "two_lobe_hg": ("g1", "g2", "w"),
    "gegenbauer": ("alpha", "g"),
    "schlick": ("k",),
    "modified_hg": ("g", "gamma"),
    "modified_hg_delta": ("g", "delta"),
    "two_lobe_hg_gamma": ("g", "gamma"),
    "two_lobe_hg_delta": ("g", "delta"),
    "gegenbauer_gamma": ("g", "gamma"),
    "gegenbauer_delta": ("g", "delta"),
    "mie": ("x", "m_re", "m_im", "n"),
}

# Each entry must match its constructor's parameters (checked here, once).
for _model, _params in MODELS.items():
    if _model != "mie":
        _want = tuple(inspect.signature(getattr(Phase, _model)).parameters)
        assert _want == _params, (_model, _want)


def _mitsuba():
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("scatterkit.mitsuba needs Mitsuba 3: pip install mitsuba") from e
    if mi.variant() is None:
        raise RuntimeError("scatterkit.mitsuba: call mitsuba.set_variant(...) first")
    return mi, dr


def _forward_cosines(k: int):
    """``k`` cosines crowded towards the forward peak, ``mu = 1 - 2 s^2`` at
    ``s`` even in ``[0, 1]`` (``mu = 1`` first), and those ``s``: the grid of
    the Mie table's values and of the native plugin's density table."""
    s = np.linspace(0.0, 1.0, k)
    return np.clip(1.0 - 2.0 * s * s, -1.0, 1.0), s


def _mie_phase(x: float, m: complex, n: int) -> Phase:
    """One sphere's Mie phase function as an inverse-CDF table of ``n``
    intervals, from its values at ``8 n + 1`` of :func:`_forward_cosines`."""
    mu = _forward_cosines(8 * n + 1)[0][::-1]
    return Phase.table_measured(mu, Mie(x, m).phase(mu), n)


def phase_from_properties(props) -> Phase:
    """The :class:`scatterkit.Phase` a ``"scatterkit"`` plugin's properties
    name (``props`` a ``mitsuba.Properties`` or a ``dict``). ``ValueError``
    for an unknown model, a missing parameter or one the constructor
    refuses."""
    get = props.get if isinstance(props, dict) else (lambda k, d=None: props[k] if props.has_property(k) else d)
    model = get("model")
    if model not in MODELS:
        raise ValueError(f"scatterkit plugin: model must be one of {sorted(MODELS)}, not {model!r}")
    if model == "mie":
        x, m_re = get("x"), get("m_re")
        if x is None or m_re is None:
            raise ValueError("scatterkit plugin: model 'mie' needs x and m_re")
        n = int(get("n", 1024))
        return _mie_phase(float(x), complex(float(m_re), float(get("m_im", 0.0))), n)
    args = []
    for p in MODELS[model]:
        v = get(p)
        if v is None:
            raise ValueError(f"scatterkit plugin: model {model!r} needs {', '.join(MODELS[model])}")
        args.append(float(v))
    return getattr(Phase, model)(*args)


def _cosines(mi, dr, wi, wo):
    """``mu = -dot(wi, wo)`` in double precision, as a NumPy array (or a
    float in scalar variants), clamped into ``[-1, 1]``."""
    if dr.is_jit_v(mi.Float):
        a = [np.asarray(c.numpy(), dtype=np.float64) for c in (wi.x, wi.y, wi.z)]
        b = [np.asarray(c.numpy(), dtype=np.float64) for c in (wo.x, wo.y, wo.z)]
        return np.clip(-(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]), -1.0, 1.0)
    mu = -(float(wi.x) * float(wo.x) + float(wi.y) * float(wo.y) + float(wi.z) * float(wo.z))
    return min(1.0, max(-1.0, mu))


def _uniforms(u):
    """Uniforms as scatterkit takes them: in ``[0, 1]``, NaN (an inactive
    lane's leftovers) read as 0."""
    return np.clip(np.nan_to_num(u, nan=0.0), 0.0, 1.0)


def _check_not_symbolic(dr):
    if dr.flag(dr.JitFlag.SymbolicScope):
        raise RuntimeError(
            "scatterkit.mitsuba: a scatterkit phase function needs the values of its "
            "arguments, which a symbolic loop or call does not have; render inside "
            "`with scatterkit.mitsuba.wavefront():` (or set drjit's SymbolicLoops and "
            "SymbolicCalls flags to False)"
        )


def _plugin_class(mi, dr):
    """The plugin class for the current variant."""

    jit = dr.is_jit_v(mi.Float)

    class ScatterkitPhase(mi.PhaseFunction):
        """A scatterkit phase function inside Mitsuba (see the module)."""

        def __init__(self, props, phase: Phase):
            mi.PhaseFunction.__init__(self, props)
            self.phase = phase
            flag = mi.PhaseFunctionFlags.Isotropic if phase.name == "isotropic" else mi.PhaseFunctionFlags.Anisotropic
            self.m_flags = flag
            self.m_components = [flag]

        def sample(self, ctx, mei, sample1, sample2, active=True):
            back = -mei.wi  # the direction of travel
            # The density at the sampled cosine itself, in double: not
            # through eval_pdf, which would rebuild the cosine from the
            # rounded float direction (and, in JIT variants, copy both
            # directions out again).
            if jit:
                _check_not_symbolic(dr)
                dr.eval(sample2)
                u1 = _uniforms(np.asarray(sample2.x.numpy(), dtype=np.float64))
                mu64 = np.asarray(self.phase.sample_cos(u1), dtype=np.float64)
                mu, pdf = mi.Float(mu64), mi.Float(np.asarray(self.phase.pdf(mu64), dtype=np.float64))
            else:
                mu64 = float(self.phase.sample_cos(float(_uniforms(float(sample2.x)))))
                mu, pdf = mi.Float(mu64), mi.Float(float(self.phase.pdf(mu64)))
            sin_t = dr.safe_sqrt((1.0 - mu) * (1.0 + mu))
            s, c = dr.sincos(dr.two_pi * sample2.y)
            wo = mi.Frame3f(back).to_world(mi.Vector3f(sin_t * c, sin_t * s, mu))
            return wo, mi.Spectrum(1.0), pdf

        def eval_pdf(self, ctx, mei, wo, active=True):
            if jit:
                _check_not_symbolic(dr)
                dr.eval(mei.wi, wo)
            mu = _cosines(mi, dr, mei.wi, wo)
            p = self.phase.pdf(mu)
            pdf = mi.Float(np.asarray(p, dtype=np.float64)) if jit else mi.Float(float(p))
            return mi.Spectrum(pdf), pdf

        def to_string(self):
            return f"ScatterkitPhase[{self.phase!r}]"

    return ScatterkitPhase


def register(name: str = "scatterkit") -> None:
    """Registers the plugin ``name`` (default ``"scatterkit"``), whose
    ``model`` property names the phase function (see the module), for the
    current Mitsuba variant."""
    mi, dr = _mitsuba()
    cls = _plugin_class(mi, dr)
    mi.register_phase(name, lambda props: cls(props, phase_from_properties(props)))


def register_phase(name: str, phase: Phase) -> None:
    """Registers the plugin ``name`` that samples the built ``phase`` (any
    :class:`scatterkit.Phase`), for the current Mitsuba variant; ``TypeError``
    if ``phase`` is not one."""
    if not isinstance(phase, Phase):
        raise TypeError(f"register_phase: phase must be a scatterkit.Phase, not {type(phase).__name__}")
    mi, dr = _mitsuba()
    cls = _plugin_class(mi, dr)
    mi.register_phase(name, lambda props: cls(props, phase))


@contextlib.contextmanager
def wavefront() -> Iterator[None]:
    """Dr.Jit's loops and calls in wavefront mode for the ``with`` block (the
    JIT variants need it for scatterkit's plugins; see the module), restored
    afterwards."""
    import drjit as dr

    flags = (dr.JitFlag.SymbolicLoops, dr.JitFlag.SymbolicCalls)
    old = [dr.flag(f) for f in flags]
    try:
        for f in flags:
            dr.set_flag(f, False)
        yield
    finally:
        for f, v in zip(flags, old):
            dr.set_flag(f, v)


# ---- the native plugin (scalar variants) ------------------------------------

#: The models the native plugin evaluates in closed form (the portable
#: header's); every other phase function goes in as tables.
NATIVE_ANALYTIC = ("isotropic", "henyey_greenstein", "rayleigh", "draine", "cornette_shanks", "fog", "two_lobe_hg",
                   "schlick")

_SOURCE = Path(__file__).with_name("mitsuba_native.cpp")


def _arch_flags():
    """The instruction-set flags Mitsuba's x86-64 wheels are built with
    (AVX2 and FMA: Dr.Jit's arrays are laid out by them, so a plugin built
    without them reads every returned vector wrongly)."""
    return ["-march=x86-64-v3"] if platform.machine() in ("x86_64", "AMD64") else []


def build_native(directory: Optional[Union[str, os.PathLike]] = None) -> Path:
    """Compiles the native plugin for the installed Mitsuba (once: the
    library is named by a hash of the source, the flags and Mitsuba's
    version) into ``directory`` (default ``$SCATTERKIT_CACHE``, else
    ``~/.cache/scatterkit``) and returns
    its path. Needs a C++17 compiler (``$CXX``, else ``c++``) and nanobind's
    headers, which Mitsuba's headers include (``pip install nanobind``);
    ``RuntimeError`` with the compiler's message if the build fails."""
    import drjit
    import mitsuba

    from . import get_include

    try:
        import nanobind
    except ImportError as e:
        raise ImportError("scatterkit.mitsuba.build_native needs nanobind's headers: pip install nanobind") from e
    mi_dir = Path(mitsuba.__file__).parent
    dr_dir = Path(drjit.__file__).parent
    cxx = os.environ.get("CXX", "c++")
    flags = ["-std=c++17", "-O2", "-fPIC", "-shared", "-fvisibility=hidden", "-fno-strict-aliasing"] + _arch_flags()
    key = hashlib.sha256(
        _SOURCE.read_bytes() + Path(get_include(), "scatterkit_portable.h").read_bytes() + repr((flags, cxx, mitsuba.__version__)).encode()
    ).hexdigest()[:16]
    if directory is None:
        directory = os.environ.get("SCATTERKIT_CACHE") or Path.home() / ".cache" / "scatterkit"
    out_dir = Path(directory)
    out_dir.mkdir(parents=True, exist_ok=True)
    out = out_dir / f"scatterkit_mitsuba_{key}.so"
    if out.exists():
        return out
    cmd = [cxx, *flags]
    cmd += ["-I" + str(p) for p in (mi_dir / "include", dr_dir / "include", nanobind.include_dir(), get_include())]
    cmd += [str(_SOURCE), "-o", str(out) + ".tmp"]
    cmd += ["-L" + str(mi_dir), "-lmitsuba", "-L" + str(dr_dir), "-ldrjit-core"]
    cmd += ["-Wl,-rpath," + str(mi_dir), "-Wl,-rpath," + str(dr_dir)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("building the native Mitsuba plugin failed:\n" + " ".join(cmd) + "\n" + r.stderr)
    os.replace(str(out) + ".tmp", out)
    return out


def register_native(directory: Optional[Union[str, os.PathLike]] = None) -> None:
    """Builds (see :func:`build_native`) and registers the native plugin
    ``"scatterkit_native"`` for Mitsuba's scalar variants (``scalar_rgb``,
    ``scalar_spectral``); its dicts come from :func:`native`."""
    lib = ctypes.CDLL(str(build_native(directory)), mode=ctypes.RTLD_GLOBAL)
    lib.scatterkit_mitsuba_register()


def _floats(values) -> str:
    return ", ".join(f"{float(v):.9g}" for v in np.asarray(values, dtype=np.float64).ravel())


def _native_density(phase: Phase, k: int):
    """The native plugin's density table: the model's density at ``k`` of
    :func:`_forward_cosines` (a density infinite at ``mu = 1``, as
    Fournier-Forand's, takes the value half a step in), and ``s``."""
    mu, s = _forward_cosines(k)
    density = np.asarray(phase.pdf(mu), dtype=np.float64)
    if not np.isfinite(density[0]):
        density[0] = phase.pdf(1.0 - 0.5 * s[1] * s[1])
    return density, s


def native(
    phase: Union[Phase, dict], n: int = 1024, density_points: Optional[int] = None, *, tolerance: float = 1e-3
) -> dict:
    """The ``"scatterkit_native"`` dict of a phase function: ``phase`` a
    built :class:`scatterkit.Phase` or the ``"scatterkit"`` plugin's
    properties (a dict with ``model``). The models in
    :data:`NATIVE_ANALYTIC` (and the fog of a droplet diameter) go as their
    parameters; any other as an inverse-CDF table of ``n`` intervals for
    sampling with the model's density at ``density_points`` cosines
    ``mu = 1 - 2 s^2`` (``s`` even in ``[0, 1]``, crowded at the forward
    peak) for evaluation: the plugin weights each sample by the density
    over the table's, so a render is unbiased for that density table
    whatever the inverse table's error. What it renders is the density
    table, linear in ``s`` and not normalised: a table whose integral over
    the sphere is ``1 + e`` scales every scattering by ``1 + e``. The table
    is checked: ``e`` and the error of its mean cosine within ``tolerance``
    (``density_points=None`` takes the smallest ``2^k + 1`` from 4097 to
    262145 that passes; at 4097 a mixture of Rayleigh and HG at
    ``g = 0.999`` integrates to 1.0095). ``ValueError`` for one that
    fails."""
    if isinstance(phase, dict):
        props = dict(phase)
        props.pop("type", None)
        model = props.get("model")
        if model in NATIVE_ANALYTIC:
            phase_from_properties(props)  # the same checks as the Python plugin
            return {"type": "scatterkit_native", **{k: (v if k == "model" else float(v)) for k, v in props.items()}}
        phase = phase_from_properties(props)
    if not isinstance(phase, Phase):
        raise TypeError(f"native: phase must be a scatterkit.Phase or a dict, not {type(phase).__name__}")
    fog = re.fullmatch(r"Phase\.fog\(([^,]+), ([^,]+), ([^,]+), ([^,]+)\)", repr(phase))
    if fog:
        g_hg, g_d, alpha, w_d = (float(x) for x in fog.groups())
        return {"type": "scatterkit_native", "model": "fog", "g_hg": g_hg, "g_d": g_d, "alpha": alpha, "w_d": w_d}
    if not tolerance > 0.0:
        raise ValueError(f"native: tolerance must be positive, not {tolerance!r}")
    sizes = [int(density_points)] if density_points is not None else [2**k + 1 for k in range(12, 19)]
    if sizes[0] < 2:
        raise ValueError("native: density_points must be at least 2")
    for size in sizes:
        density, s = _native_density(phase, size)
        norm, g = _interpolant_errors(phase, s, density, lambda x: 1.0 - 2.0 * x * x, lambda x: 4.0 * x)
        if norm <= tolerance and g <= tolerance:
            break
    else:
        raise ValueError(
            f"native: a density table of {size} points misrepresents {phase!r}: its integral over the "
            f"sphere is {norm:.3g} away from 1 (each scattering scaled by that much) and its mean cosine "
            f"{g:.3g} from the phase function's (tolerance {tolerance:g}); "
            + ("leave density_points to native()" if density_points is not None else "use the \"scatterkit\" plugin")
        )
    table = phase if phase.table_data is not None else Phase.table(phase, int(n))
    return {
        "type": "scatterkit_native",
        "model": "table",
        "table": _floats(table.table_data),
        "density": _floats(density),
    }
