"""vgroove: exact V-groove tracing and the kaleidoscopic BRDF of Lee et al. 2018, from Python.

The same C++ libraries as the ``vgroove`` command line (sim, analytic, validation), with NumPy
arrays in and out. :class:`BRDF` holds one BRDF (evaluated, sampled, integrated over the suites'
bins, and the surface it models traced exactly); the functions beside it make the same calls.
Long calls run without the GIL on worker threads, stop on Ctrl-C (KeyboardInterrupt) and report
to ``progress(done, total)`` (:func:`tqdm_progress`); mistakes in the input raise ValueError with
a one-line message naming the argument and its range, as the command line does (there: exit
status 2). Results equal the command line's and the C++ library's for the same inputs, to the
last bit.

Conventions (those of the command line and the report JSON; see sim/geometry.h,
analytic/kaleidoscope.h, analytic/brdf_3d.h, analytic/ndf.h):

* Angles are in **degrees** and named ``*_deg``, measured from the macrosurface normal n,
  counter-clockwise positive. ``theta_i_deg > 0``: light from the upper left; a flat mirror gives
  ``theta_o = -theta_i``. A symmetric groove is given by its aperture ``theta_v_deg`` in
  [$min_aperture_deg, 180]; a nonsymmetric one by the angles of its facets' normals, ``theta_l_deg`` in
  [-90, 0] and ``theta_r_deg`` in [0, 90] (Lee et al. 2018, Fig. 5), aperture
  ``180 + theta_l_deg - theta_r_deg``. Degrees become radians as ``deg * (pi / 180)``, as the
  command line does, so the same inputs give the same bits. Single grooves take ``theta_i_deg``
  in [-$max_theta_i_deg, $max_theta_i_deg]; rough surfaces (lobes, traces, samplers, check_brdf) in
  [0, $max_surface_theta_i_deg] (flatland: signed, in [-$max_surface_theta_i_deg, $max_surface_theta_i_deg]).
* Directions are unit vectors (arrays ``(..., 3)``) in the frame n = (0, 0, 1), both pointing
  away from the surface: ``wi`` towards the light, ``wo`` towards the viewer; every function and
  method takes ``wi`` first. The direction at polar angle theta and azimuth phi is (sin theta
  cos phi, sin theta sin phi, cos theta) (:func:`direction`). In flatland the directions lie in
  the plane y = 0: the one at signed angle t is (-sin t, 0, cos t). A direction is a unit vector
  when |len - 1| <= $unit_tolerance (and, in flatland, |y| <= $unit_tolerance): float32 rounding
  is within it. Directions within 1e-9 of unit length are used as given, the others divided by
  their length.
* BRDF values are in 1/sr (3D) or 1/rad (flatland), with F = 1 (a perfect mirror, white light)
  unless a :class:`BRDF` has ``eta``.
* NDFs: ``"ggx"``, ``"beckmann"``, ``"phong"`` (Phong exponent 2/alpha^2 - 2); roughness alpha in
  [$min_alpha, $max_alpha].
* max_k, the orders summed: None gives the model's default, the same on every face
  (:data:`BRDF_MAX_K`; samplers :data:`SAMPLER_MAX_K`); in :func:`lobe` and
  :func:`trace_microsurface` max_k counts the rows of the tally, in [$min_histogram_k, $max_histogram_k].
* Numbers may be Python or NumPy scalars (np.int64, np.float32, ...); bools and complex values are
  refused (ValueError), as are complex arrays (their imaginary part would be lost).
* Seeds are integers in [0, 2^63 - 1]; the same seed gives the same bits on any thread count
  (threads in [0, $max_threads], 0: all cores).
"""

from __future__ import annotations

import glob as _glob
import os as _os
import sys as _sys

try:
    import numpy as _np  # noqa: F401
except ImportError as _e:
    raise ImportError(
        f"vgroove needs NumPy, which this Python ({_sys.executable}, {_sys.version.split()[0]}) cannot import "
        f"({_e}): install it for this interpreter (Debian: apt-get install python3-numpy, for /usr/bin/python3; "
        "a venv made with `python3 -m venv --system-site-packages` sees Debian's)") from None

try:
    from . import _vgroove
except ImportError as _e:
    import importlib.machinery as _machinery
    _here = _os.path.dirname(_os.path.abspath(__file__))
    _built = sorted(_os.path.basename(p) for p in _glob.glob(_os.path.join(_here, "_vgroove*"))
                    if not p.endswith(".pyi"))
    _wanted = _machinery.EXTENSION_SUFFIXES[0]
    if not _built:
        _why = ("its extension module vgroove._vgroove is not there (built with -DVGROOVE_PYTHON=ON when pybind11-dev "
                "and python3-dev are installed; not in sanitizer builds)")
    elif not set(_built) & {"_vgroove" + s for s in _machinery.EXTENSION_SUFFIXES}:
        _why = (f"its extension module is {', '.join(_built)}, built for another Python: this one "
                f"({_sys.executable}, {_sys.version.split()[0]}) loads _vgroove{_wanted}; run the Python it was built "
                "for (scripts/setup.sh builds for /usr/bin/python3) or build it for this one "
                f"(-DPython3_EXECUTABLE={_sys.executable}, or pip install .)")
    else:
        _why = f"its extension module {', '.join(_built)} does not load: {_e}"
    raise ImportError(f"vgroove in {_here} cannot be imported: {_why}") from None

from ._ranges import RANGES, fill_ranges as _fill_ranges
from ._grooves import FATES, LEFT, RIGHT, analytic, direction, groove_case, kaleidoscope, output_deg, trace
from ._surfaces import Microsurface, lobe, microsurface, trace_microsurface
from ._brdfs import BRDF_MAX_K, brdf, check_brdf, dielectric_bsdf, dielectric_lobe
from ._sampling import NONSYMMETRIC_SAMPLER_MAX_K, SAMPLER_MAX_K, pdf, sample, uniforms
from ._suites import validate
from ._energy import energy_audit, energy_lobe_shape, glass_energy
from ._results import Lobe, SampleBatch, SurfaceTrace
from ._brdf import BRDF
from ._progress import TqdmProgress, tqdm_progress

__doc__ = _fill_ranges(__doc__)

__version__: str = _vgroove.__version__
#: The git revision the module was built from (as in every report's "git").
git_revision: str = _vgroove.git_revision

__all__ = [
    "__version__", "git_revision", "RANGES", "FATES", "LEFT", "RIGHT",
    "direction", "output_deg", "kaleidoscope", "analytic", "trace", "groove_case",
    "Microsurface", "microsurface", "trace_microsurface", "lobe",
    "BRDF", "Lobe", "SampleBatch", "SurfaceTrace", "BRDF_MAX_K", "SAMPLER_MAX_K", "NONSYMMETRIC_SAMPLER_MAX_K",
    "brdf", "check_brdf", "dielectric_lobe", "dielectric_bsdf", "validate", "energy_audit", "energy_lobe_shape",
    "glass_energy", "sample", "pdf",
    "uniforms", "tqdm_progress",
    "TqdmProgress",
]

# The public objects say they are vgroove's (repr, pickling, doctests of `vgroove`).
for _name in __all__:
    _obj = globals()[_name]
    if callable(_obj) and getattr(_obj, "__module__", "").startswith("vgroove._") and _name != "Microsurface":
        try:
            _obj.__module__ = __name__
        except (AttributeError, TypeError):
            pass
del _name, _obj
