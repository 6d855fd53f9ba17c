"""vgroove: exact V-groove tracing and the kaleidoscopic BRDF of Lee et al. 2018, from Python.

The same C++ libraries as the ``vgroove`` command line (sim, analytic, validation), with NumPy
arrays in and out. Long calls run without the GIL on worker threads and stop on Ctrl-C
(KeyboardInterrupt); mistakes in the input raise ValueError with a one-line message naming the
value, as the command line does (there: exit status 2).

Conventions (those of the command line and the report JSON; see sim/geometry.h,
analytic/kaleidoscope.h, analytic/brdf_3d.h, analytic/ndf.h):

* Angles are in **degrees** and named ``*_deg``, measured from the macrosurface normal n,
  counter-clockwise positive. ``theta_i_deg > 0``: light from the upper left; a flat mirror gives
  ``theta_o = -theta_i``. A symmetric groove is given by its aperture ``theta_v_deg`` in
  [{min_aperture_deg:g}, 180]; a nonsymmetric one by the angles of its facets' normals, ``theta_l_deg`` in
  [-90, 0] and ``theta_r_deg`` in [0, 90] (Lee et al. 2018, Fig. 5), aperture
  ``180 + theta_l_deg - theta_r_deg``. Degrees become radians as ``deg * (pi / 180)``, as the
  command line does, so the same inputs give the same bits. Single grooves take ``theta_i_deg``
  in [-{max_theta_i_deg:g}, {max_theta_i_deg:g}].
* Directions are unit vectors (arrays ``(..., 3)``) in the frame n = (0, 0, 1), both pointing
  away from the surface: ``wi`` towards the light, ``wo`` towards the viewer. The direction at
  polar angle theta and azimuth phi is (sin theta cos phi, sin theta sin phi, cos theta)
  (:func:`direction`). In flatland the directions lie in the plane y = 0: the one at signed angle
  t is (-sin t, 0, cos t). A direction is a unit vector when |len - 1| <= {unit_tolerance:g} (and,
  in flatland, |y| <= {unit_tolerance:g}): float32 rounding is within it. Directions within 1e-9 of
  unit length are used as given, the others divided by their length.
* BRDF values are in 1/sr (3D) or 1/rad (flatland), with F = 1 (a perfect mirror, white light).
* NDFs: ``"ggx"``, ``"beckmann"``, ``"phong"`` (Phong exponent 2/alpha^2 - 2); roughness alpha in
  [{min_alpha:g}, {max_alpha:g}].
* Numbers may be Python or NumPy scalars (np.int64, np.float32, ...); bools and complex values are
  refused (ValueError), as are complex arrays (their imaginary part would be lost).
* Seeds are integers in [0, 2^63 - 1]; the same seed gives the same bits on any thread count.
"""

from __future__ import annotations

from typing import Callable, Optional, Sequence, Union

import numbers
import operator

import numpy as np

from . import _vgroove

#: The ranges the module enforces (validation/ranges.h, the command line's).
RANGES: dict = dict(_vgroove.ranges)
__doc__ = __doc__.format(**RANGES)

__all__ = [
    "__version__", "git_revision", "FATES", "LEFT", "RIGHT", "direction", "output_deg",
    "kaleidoscope", "analytic", "trace", "groove_case",
    "Microsurface", "microsurface", "trace_microsurface", "lobe",
    "brdf", "check_brdf", "validate", "sample", "pdf", "uniforms", "SAMPLER_MAX_K", "NONSYMMETRIC_SAMPLER_MAX_K",
]

__version__: str = _vgroove.__version__
#: The git revision the module was built from (as in every report's "git").
git_revision: str = _vgroove.git_revision
#: trace()'s fate codes, by value: 0 escaped, 1 blocked, 2 vertex hit, 3 bounce limit.
FATES = ("escaped", "blocked", "vertex_hit", "bounce_limit")
#: Facet codes of trace() and kaleidoscope(): the facet hit first (-1 in trace(): none).
LEFT, RIGHT = 0, 1

Microsurface = _vgroove.Microsurface

ArrayLike = Union[float, Sequence[float], np.ndarray]


def _real(x, name):
    """x as a float: Python and NumPy real scalars (and 0-d real arrays); bools, complex values and
    everything else raise ValueError naming the argument."""
    if isinstance(x, np.ndarray) and x.ndim == 0:
        x = x[()]
    if isinstance(x, (bool, np.bool_)):
        raise ValueError(f"{name} = {x!r} must be a real number, not a bool")
    if isinstance(x, (complex, np.complexfloating)):
        raise ValueError(f"{name} = {x!r} must be a real number, not complex (its imaginary part would be lost)")
    if not isinstance(x, numbers.Real):
        raise ValueError(f"{name} = {x!r} must be a real number")
    return float(x)


def _opt_real(x, name):
    return None if x is None else _real(x, name)


def _integer(x, name):
    """x as an int: Python and NumPy integers (and 0-d integer arrays); bools, floats and
    everything else raise ValueError naming the argument. The range is checked by the extension."""
    if isinstance(x, np.ndarray) and x.ndim == 0:
        x = x[()]
    if isinstance(x, (bool, np.bool_)):
        raise ValueError(f"{name} = {x!r} must be an integer, not a bool")
    if not isinstance(x, numbers.Integral):
        raise ValueError(f"{name} = {x!r} must be an integer")
    return operator.index(x)


def _opt_integer(x, name):
    return None if x is None else _integer(x, name)


def _reals(x, name):
    """x as a float array: real numbers only (complex and bool arrays raise ValueError naming the
    argument)."""
    a = np.asarray(x)
    if a.dtype.kind == "c":
        raise ValueError(f"{name} has complex values (dtype {a.dtype}): give real numbers (the imaginary part would "
                         "be lost)")
    if a.dtype.kind not in "iuf":
        if a.dtype.kind == "b" or a.dtype.kind == "O" and any(isinstance(v, (bool, np.bool_)) for v in a.flat):
            raise ValueError(f"{name} has bools (dtype {a.dtype}): give real numbers")
        if a.dtype.kind == "O" and any(isinstance(v, (complex, np.complexfloating)) for v in a.flat):
            raise ValueError(f"{name} has complex values (dtype {a.dtype}): give real numbers (the imaginary part "
                             "would be lost)")
        try:
            return a.astype(float)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must hold real numbers (dtype {a.dtype})") from None
    return a.astype(float, copy=False)


def direction(theta_deg: ArrayLike, phi_deg: ArrayLike = 0.0) -> np.ndarray:
    """Unit vectors at polar angle theta and azimuth phi (degrees), shape broadcast + (3,):
    (sin theta cos phi, sin theta sin phi, cos theta). The light of the suites and of check_brdf
    is at azimuth 180 deg: ``direction(theta_i_deg, 180)``."""
    t = np.radians(_reals(theta_deg, "theta_deg"))
    p = np.radians(_reals(phi_deg, "phi_deg"))
    t, p = np.broadcast_arrays(t, p)
    return np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)


def output_deg(rad: ArrayLike) -> np.ndarray:
    """Radians to degrees rounded to 1e-9 deg, as every report and ``--json`` output prints them."""
    return _vgroove.output_deg(rad)


def _groove_arrays(theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg):
    if theta_l_deg is None and theta_r_deg is None:
        v = 90.0 if theta_v_deg is None else theta_v_deg
        ti, v = np.broadcast_arrays(_reals(theta_i_deg, "theta_i_deg"), _reals(v, "theta_v_deg"))
        return ti.shape, [np.ascontiguousarray(a, dtype=float).ravel() for a in (ti, v)] + [None, None]
    if theta_l_deg is None or theta_r_deg is None:
        raise ValueError("theta_l_deg needs theta_r_deg" if theta_l_deg is not None else "theta_r_deg needs theta_l_deg")
    if theta_v_deg is not None:
        raise ValueError("theta_v_deg cannot be combined with theta_l_deg/theta_r_deg (the aperture follows from them)")
    ti, l, r = np.broadcast_arrays(*(_reals(a, n) for a, n in ((theta_i_deg, "theta_i_deg"),
                                                              (theta_l_deg, "theta_l_deg"),
                                                              (theta_r_deg, "theta_r_deg"))))
    return ti.shape, [np.ascontiguousarray(ti).ravel(), None] + [np.ascontiguousarray(a).ravel() for a in (l, r)]


def _groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg):
    return (_opt_real(theta_v_deg, "theta_v_deg"), _opt_real(theta_l_deg, "theta_l_deg"),
            _opt_real(theta_r_deg, "theta_r_deg"))


def kaleidoscope(theta_i_deg: ArrayLike, theta_v_deg: Optional[ArrayLike] = None, *,
                 theta_l_deg: Optional[ArrayLike] = None, theta_r_deg: Optional[ArrayLike] = None,
                 eq6_form: str = "corrected") -> dict:
    """The kaleidoscopic model of single V-grooves (Lee et al. 2018, Eq. 4-6 symmetric, Eq. 7-9
    nonsymmetric), vectorized: the angles broadcast against each other (shape S).

    Per facet hit first (last axis 2: 0 left, 1 right), arrays of shape S + (2,): ``lit`` (the
    light reaches the facet), ``k`` (Eq. 4, or k_b of Eq. 7), ``f_a`` (projected width of the unit
    facet), ``shadow`` (f_b / f_a: rays aimed at the facet that meet the other rim first). Per
    facet and zone (S + (2, 4); symmetric grooves use zones 0: k - 1 and 1: k reflections;
    unused zones are 0): ``n`` (reflections), ``G`` (share of the rays aimed at the facet, Eq. 6 /
    Eq. 9), ``fraction`` (share of the beam entering the opening: G f_a / sum of the lit facets'
    f_a (1 - shadow)), ``theta_o_deg`` (exit angle, Eq. 5 / Eq. 8, degrees, not rounded).
    ``eq6_form``: "corrected" (docs/ERRATA.md, E1) or "printed"."""
    shape, (ti, v, l, r) = _groove_arrays(theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg)
    out = _vgroove.kaleidoscope(ti, v, l, r, eq6_form)
    return {key: a.reshape(shape + a.shape[1:]) for key, a in out.items()}


def analytic(theta_i_deg: float, theta_v_deg: Optional[float] = None, *, theta_l_deg: Optional[float] = None,
             theta_r_deg: Optional[float] = None, eq6_form: str = "corrected") -> dict:
    """``vgroove analytic --json`` for one groove and one incident angle, as a dict: "inputs",
    "bounces" (rows: first_facet, k, fraction of the beam entering the opening, theta_o_deg rounded
    to 1e-9 deg) and "facets" (k, f_a, G per bounce count, shadow; None for an unlit facet)."""
    return _vgroove.analytic(_real(theta_i_deg, "theta_i_deg"), *_groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg),
                             eq6_form)


def trace(theta_i_deg: float, rays: int = 1000, theta_v_deg: Optional[float] = None, *,
          theta_l_deg: Optional[float] = None, theta_r_deg: Optional[float] = None, sampling: str = "stratified",
          seed: int = 1, max_bounces: Optional[int] = None) -> dict:
    """Traces one parallel beam through one groove exactly (sim/tracer.h), ray by ray, as
    ``vgroove trace`` does: ``rays`` rays across the opening, at the midpoints of equal strata
    (``sampling="stratified"``) or at seeded random points (``"random"``).

    Per ray (arrays of length ``rays``): ``x`` (where it crosses the rim line; the apex is the
    origin, facets of unit length), ``first_facet`` (int8: 0 left, 1 right, -1 none), ``k``
    (reflections), ``fate`` (int8 codes of :data:`FATES`), ``exit_dir`` ((rays, 2): the 2D exit
    direction (x, y), 0 where the ray did not escape), ``theta_o_deg`` (its angle, degrees, not
    rounded; 0 where the ray did not escape). ``summary``: the dict ``vgroove trace --json``
    prints (rows per (first facet, k), buckets). ``max_bounces``: the bounce limit, by default
    (None) the command line's: 100000, or ceil(180 / theta_v_deg) + 1 where a narrower groove needs
    more, so that every ray can leave."""
    return _vgroove.trace(_real(theta_i_deg, "theta_i_deg"), _integer(rays, "rays"),
                          *_groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg), sampling, _integer(seed, "seed"),
                          _opt_integer(max_bounces, "max_bounces"))


def groove_case(theta_i_deg: float, theta_v_deg: Optional[float] = None, *, theta_l_deg: Optional[float] = None,
                theta_r_deg: Optional[float] = None, rays: int = 1000, sampling: str = "stratified", seed: int = 1,
                max_bounces: Optional[int] = None, eq6_form: str = "corrected", probe_vertices: bool = False,
                stream: int = 0) -> dict:
    """One case of a single-groove suite (a cell of Table 1): ``rays`` rays aimed at each lit
    facet, traced, and their fractions per bounce count against Eq. 6 / Eq. 9 (L1, with the
    shadowed rays a bin of their own). Returns the case's entry of the report ("l1", per facet
    "l1", "k", "rays", ...). ``stream`` is the case's index in its suite (random sampling draws the
    rays of facet f from the stream (seed, stream, f)), so a suite's case is reproduced exactly.
    ``max_bounces`` as in :func:`trace` (by default the command line's limit for the groove)."""
    return _vgroove.groove_case(_real(theta_i_deg, "theta_i_deg"),
                                *_groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg),
                                _integer(rays, "rays"), sampling, _integer(seed, "seed"),
                                _opt_integer(max_bounces, "max_bounces"), eq6_form, probe_vertices,
                                _integer(stream, "stream"))


def microsurface(ndf: str = "ggx", alpha: float = 0.5, grooves: int = 250000, seed: int = 1,
                 dim: str = "3d") -> Microsurface:
    """A procedural rough surface of ``grooves`` symmetric V-grooves whose facet normals follow the
    NDF (sim/microsurface.h for ``dim="flatland"``, sim/microsurface3d.h for ``"3d"``): the
    surfaces of the Fig. 11, furnace and check_brdf suites (same seed, same surface). Its
    ``theta_m_deg`` (facet angles) and, in 3D, ``phi_a_deg`` (groove azimuths) are arrays."""
    return _vgroove.microsurface(ndf, _real(alpha, "alpha"), _integer(grooves, "grooves"), _integer(seed, "seed"), dim)


def trace_microsurface(surface: Microsurface, theta_i_deg: float, rays: int = 1000000, *, seed: Optional[int] = None,
                       sampling: str = "random", flatland_bins: int = 90, theta_bins: int = 30, phi_bins: int = 24,
                       max_k: int = 16, max_bounces: int = 100000, threads: int = 0) -> dict:
    """Traces ``rays`` rays from theta_i into the surface, each exactly in its groove, and tallies
    the escaped ones as the suites do (seed: the rays' stream, by default the surface's seed, as
    in the suites). Counts (int): ``rays``, ``escaped``, ``blocked``, ``vertex_hit``,
    ``bounce_limit``, ``not_upward``, ``bounces``, ``max_k_seen``; ``by_k`` (rows k = 0..max_k, the
    last row every k > max_k). Flatland: ``theta_o`` (bins over (-90, 90) deg, signed as
    everywhere) and ``theta_o_by_k`` (rows x bins). 3D (the light at azimuth 180 deg, theta_i in
    [0, 90)): ``hist`` (theta_bins over [0, 90) deg x phi_bins centred on phi = 0, the mirror
    side) and ``hist_by_k``. Divide by ``rays`` for fractions of the incident flux. The chunks of
    rays run on ``threads`` threads (0: all cores); the counts do not depend on it. Bins and max_k
    take the "brdf" suites' ranges (max_k in [0, 1000]; the histogram's cells are bounded by the
    memory check: a call that would need more memory than this process may use is refused
    before it starts, with the estimate in the message); max_bounces in [1, 10^8]."""
    return _vgroove.trace_microsurface(surface, _real(theta_i_deg, "theta_i_deg"), _integer(rays, "rays"),
                                       _opt_integer(seed, "seed"), sampling, _integer(flatland_bins, "flatland_bins"),
                                       _integer(theta_bins, "theta_bins"), _integer(phi_bins, "phi_bins"),
                                       _integer(max_k, "max_k"), _integer(max_bounces, "max_bounces"),
                                       _integer(threads, "threads"))


def lobe(model: str, ndf: str, alpha: float, theta_i_deg: float, dim: str = "3d", *, flatland_bins: int = 90,
         theta_bins: int = 30, phi_bins: int = 24, max_k: int = 16) -> dict:
    """The model's lobe integrated over the bins of :func:`trace_microsurface`, as fractions of the
    incident flux: ``model="vgroove"`` (analytic/brdf_flatland.h, analytic/lobe_3d.h; rows per k
    as in the tally) or ``"cook-torrance"`` (also spelled ``"cook_torrance"``; single scattering,
    V-cavity G: its albedo shows the energy it loses). Keys: ``by_k``, ``albedo`` and
    ``theta_o``/``theta_o_by_k`` (flatland) or ``hist``/``hist_by_k`` (3D). Bins, max_k and the
    memory check as in :func:`trace_microsurface`."""
    return _vgroove.lobe(model, ndf, _real(alpha, "alpha"), _real(theta_i_deg, "theta_i_deg"), dim,
                         _integer(flatland_bins, "flatland_bins"), _integer(theta_bins, "theta_bins"),
                         _integer(phi_bins, "phi_bins"), _integer(max_k, "max_k"))


def _directions(wi, wo):
    wi, wo = _reals(wi, "wi"), _reals(wo, "wo")
    if wi.shape[-1:] != (3,) or wo.shape[-1:] != (3,):
        raise ValueError(f"wi and wo must be arrays of unit vectors, shape (..., 3); got {wi.shape} and {wo.shape}")
    shape = np.broadcast_shapes(wi.shape, wo.shape)[:-1]
    wi, wo = (np.ascontiguousarray(np.broadcast_to(w, shape + (3,))).reshape(-1, 3) for w in (wi, wo))
    return shape, wi, wo


def brdf(model: str, ndf: str, alpha: float, wi: np.ndarray, wo: np.ndarray, per_k: bool = False, *,
         max_k: int = 16, dim: str = "3d", threads: int = 0) -> np.ndarray:
    """A BRDF over arrays of directions ``wi``, ``wo`` (unit vectors, shapes broadcast to S + (3,)):

    * ``model="vgroove"``: Lee et al. 2018, Eq. 16-17 (3D, analytic/brdf_3d.h) or its flatland
      analogue (analytic/brdf_flatland.h), the sum over k = 1..max_k; ``per_k=True`` gives the
      terms, shape S + (max_k,). Evaluating the 3D sum costs the same for any max_k; its albedo
      reaches 1 at high roughness only with a large max_k (e.g. 10**6). The flatland sum costs
      O(max_k^2) per direction (0.4 s at max_k 4096): max_k at most 4096 there.
    * ``model="vgroove-nonsymmetric"``: Eq. 21-23 with the independent partner law of Eq. 20
      (analytic/brdf_nonsymmetric.h; isotropic; Phong needs alpha < sqrt(2)), O(max_k^2) per
      direction: max_k at most 1024.
    * ``model="cook-torrance"`` (also spelled ``"cook_torrance"``): Eq. 1-3 with the V-cavity G
      (the k = 1 term), shape S (+ (1,)).

    The models and max_k ranges are ``vgroove brdf --model``'s, with its messages; max_k's default
    here is 16 for every model (the command line's: all orders in 3D, 4096 in flatland, 64 for the
    nonsymmetric model).

    Values in 1/sr (3D) or 1/rad (flatland, directions in the plane y = 0), F = 1, 0 below the
    horizon. The directions are evaluated on ``threads`` threads (0: all cores) without the GIL."""
    shape, a, b = _directions(wi, wo)
    out = _vgroove.brdf(model, ndf, _real(alpha, "alpha"), a, b, per_k, _integer(max_k, "max_k"), dim,
                        _integer(threads, "threads"))
    return out.reshape(shape + out.shape[1:])


def check_brdf(f: Union[Callable[[np.ndarray, np.ndarray], np.ndarray], str], ndf: str = "ggx", alpha: float = 0.5,
               theta_i_deg: Sequence[float] = (0, 20, 40, 60, 80), rays: int = 1000000, *, dim: str = "3d",
               grooves: int = 250000, seed: int = 1, theta_bins: int = 30, phi_bins: int = 24,
               flatland_bins: int = 90, sigmas: float = 5.0, model_tolerance: float = 1e-4,
               quadrature_order: int = 4, threads: int = 0, name: str = "check_brdf", max_k: int = 16) -> dict:
    """Holds a BRDF against vgroove's exact simulation (validation/check_brdf.h; same verdict,
    thresholds and report as the C++ API ``vgroove::validation::check_brdf``).

    ``f(wi, wo) -> values``: a vectorized callable; wi and wo are float arrays of shape (n, 3)
    (unit vectors, the frame above, the light at azimuth 180 deg), it returns n values in 1/sr
    (1/rad in flatland) with F = 1. It is called with the nodes of one cell's Gauss-Legendre rule
    at a time (quadrature_order^2 directions in 3D, quadrature_order in flatland): at least once
    per bin and incident angle, more where cells are split (validation/check_brdf.h, BrdfBatchFn).
    ``f`` may also be the name of a model of :func:`brdf` (with
    ``max_k`` in its range): the built-in models, evaluated in C++. Ctrl-C stops the check within
    one evaluation of f (f is not called again).

    Per theta_i: the procedural surface of (ndf, alpha, grooves, seed) is traced with ``rays``
    rays into the bins (3D: theta_bins over [0, 90) deg x phi_bins; flatland: flatland_bins), the
    model is integrated over the same bins (Gauss-Legendre, quadrature_order per axis), and the
    L1 distances of the normalized lobes and of the flux fractions, and the albedo, are compared
    with what a correct model shows at this sample count (+ sigmas standard deviations +
    model_tolerance). Returns the report: "cases" (per theta_i: errors, thresholds, worst bins,
    pass), "pass", provenance."""
    return _vgroove.check_brdf(f, _integer(max_k, "max_k"), name, ndf, _real(alpha, "alpha"),
                               [float(t) for t in np.atleast_1d(_reals(theta_i_deg, "theta_i_deg"))],
                               _integer(rays, "rays"), dim, _integer(grooves, "grooves"), _integer(seed, "seed"),
                               _integer(theta_bins, "theta_bins"), _integer(phi_bins, "phi_bins"),
                               _integer(flatland_bins, "flatland_bins"), _real(sigmas, "sigmas"),
                               _real(model_tolerance, "model_tolerance"),
                               _integer(quadrature_order, "quadrature_order"),
                               _integer(threads, "threads"))


def validate(path: str, *, rays: Optional[int] = None, threads: int = 0, sampling: Optional[str] = None,
             eq6_form: Optional[str] = None, seed: Optional[int] = None, model_table: Optional[str] = None,
             verbose: bool = False) -> dict:
    """Runs a suite file as ``vgroove validate PATH [--rays ...]`` does and returns its report (the
    JSON ``--out`` writes, as a dict; "pass" says whether every threshold held). Overrides: rays
    (per lit facet, or per case for rough surfaces), threads (0: all cores; the figures do not
    depend on it), sampling and eq6_form (single-groove suites), seed, model_table (a foreign
    model's bin-integrated lobes for a "brdf" suite: ``vgroove validate --model-table``).
    ``verbose`` prints the command line's table."""
    return _vgroove.validate(str(path), _opt_integer(rays, "rays"), _integer(threads, "threads"), sampling, eq6_form,
                             _opt_integer(seed, "seed"),
                             None if model_table is None else str(model_table), verbose)


def _light(wi, theta_i_deg):
    """The light as the extension takes it: flattened rows of wi, or of theta_i_deg."""
    if (wi is None) == (theta_i_deg is None):
        raise ValueError("give the light as either wi (unit vectors) or theta_i_deg, not both or neither")
    if wi is not None:
        wi = _reals(wi, "wi")
        if wi.shape[-1:] != (3,):
            raise ValueError(f"wi must be an array of unit vectors, shape (..., 3); got {wi.shape}")
        return wi.shape[:-1], wi, None
    t = _reals(theta_i_deg, "theta_i_deg")
    return t.shape, None, t


SAMPLER_MAX_K = _vgroove.SAMPLER_MAX_K
NONSYMMETRIC_SAMPLER_MAX_K = _vgroove.NONSYMMETRIC_SAMPLER_MAX_K


def _sampler_max_k(max_k: Optional[int], model: str) -> int:
    """max_k as given, or the model's default (``vgroove sample --max-k``'s)."""
    if max_k is None:
        return NONSYMMETRIC_SAMPLER_MAX_K if model == "vgroove-nonsymmetric" else SAMPLER_MAX_K
    return _integer(max_k, "max_k")


def sample(ndf: str, alpha: float, u: np.ndarray, *, wi: Optional[np.ndarray] = None,
           theta_i_deg: Optional[ArrayLike] = None, strategy: str = "vndf", max_k: Optional[int] = None,
           dim: str = "3d", model: str = "vgroove", tolerance: float = 1e-9, threads: int = 0) -> dict:
    """Importance-samples the V-groove BRDF (Lee et al. 2018, Sec. 6): one exit direction per row of
    uniform numbers ``u`` (each in [0, 1); :func:`uniforms` gives vgroove's streams).

    ``model="vgroove"``: symmetric grooves (analytic/sampling_3d.h, analytic/sampling_flatland.h),
    four numbers per sample, ``u`` of shape S + (4,). ``model="vgroove-nonsymmetric"``: Eq. 21-23
    with the independent partner law of Eq. 20 (analytic/sampling_nonsymmetric.h), five numbers
    per sample (S + (5,)); its pdf, and so each sample's pdf and weight, is an adaptive integral
    over the partner's tilt to ``tolerance`` (relative, per piece) and costs about a millisecond
    (`vgroove sample --model vgroove-nonsymmetric` uses 1e-6); Phong needs alpha <= 1.

    The light: ``wi`` (unit vectors towards the light, S + (3,) broadcast; flatland: in the plane
    y = 0) or ``theta_i_deg`` (angles, broadcast to S; the suites' light at azimuth 180 deg, the
    bits ``vgroove sample --theta-i-deg`` uses), in the command line's range [0, 89.9] deg
    (flatland: signed, [-89.9, 89.9]); a direction ``wi`` is held to it by its angle from the
    normal rounded to 1e-9 deg. ``strategy``: how the facet met first is drawn:
    "vndf" (the V-cavity's visible normals: samples the BRDF exactly, weight 1 with F = 1),
    "printed" (the paper's |s.n| D(s)), "smith-vndf" (GGX), "bounded-vndf" (GGX, 3D). Paths of more
    than ``max_k`` reflections (in [1, 100000]) return zero weight and say so in ``beyond_max_k``.
    Its default (None) is ``vgroove sample --max-k``'s: 16384 (``SAMPLER_MAX_K``), which loses fewer
    than one sample in 10^7 for GGX and Beckmann at any alpha and Phong up to alpha 1
    (analytic/sampling_3d.h), and 256 (``NONSYMMETRIC_SAMPLER_MAX_K``) for the nonsymmetric model,
    whose pdf costs O(max_k).

    Returns arrays over S: ``wo`` (S + (3,), unit vectors; the mirror direction on a zero-weight
    return), ``k`` (int32 reflections; 0: no direction), ``pdf`` (density of wo per steradian, per
    radian in flatland; 0 on a zero-weight return), ``weight`` (rho cos(theta_o) / pdf, F = 1) and
    ``beyond_max_k`` (bool: a zero-weight return because the drawn path has more than max_k
    reflections; its mean is the share lost to max_k).
    Runs on ``threads`` threads (0: all cores) without the GIL; the values do not depend on it."""
    m = 5 if model == "vgroove-nonsymmetric" else 4
    u = _reals(u, "u")
    if u.shape[-1:] != (m,):
        raise ValueError(f"u must be an array of uniform numbers, shape (..., {m}); got {u.shape}")
    lshape, wi_, ti = _light(wi, theta_i_deg)
    shape = np.broadcast_shapes(u.shape[:-1], lshape)
    u = np.ascontiguousarray(np.broadcast_to(u, shape + (m,))).reshape(-1, m)
    if wi_ is not None:
        wi_ = np.ascontiguousarray(np.broadcast_to(wi_, shape + (3,))).reshape(-1, 3)
    else:
        ti = np.ascontiguousarray(np.broadcast_to(ti, shape)).reshape(-1)
    out = _vgroove.sample(model, ndf, _real(alpha, "alpha"), wi_, ti, u, strategy, _sampler_max_k(max_k, model),
                          _real(tolerance, "tolerance"), dim, _integer(threads, "threads"))
    return {key: a.reshape(shape + a.shape[1:]) for key, a in out.items()}


def pdf(ndf: str, alpha: float, wo: np.ndarray, *, wi: Optional[np.ndarray] = None,
        theta_i_deg: Optional[ArrayLike] = None, strategy: str = "vndf", max_k: Optional[int] = None,
        dim: str = "3d", model: str = "vgroove", tolerance: float = 1e-9, threads: int = 0) -> np.ndarray:
    """The density of the directions :func:`sample` produces, at ``wo`` (unit vectors, S + (3,);
    flatland: in the plane y = 0), per steradian (per radian in flatland): the sum over every path
    of k <= max_k reflections that ends at wo (analytic/sampling_3d.h). The light and the options
    as in :func:`sample` (``model``: "vgroove" or "vgroove-nonsymmetric"). 0 below the horizon; +inf
    exactly at the mirror direction in 3D (where the BRDF diverges too). With ``strategy="vndf"``
    the symmetric model's pdf equals rho(wi, wo) cos(theta_o) (F = 1)."""
    wo = _reals(wo, "wo")
    if wo.shape[-1:] != (3,):
        raise ValueError(f"wo must be an array of unit vectors, shape (..., 3); got {wo.shape}")
    lshape, wi_, ti = _light(wi, theta_i_deg)
    shape = np.broadcast_shapes(wo.shape[:-1], lshape)
    wo = np.ascontiguousarray(np.broadcast_to(wo, shape + (3,))).reshape(-1, 3)
    if wi_ is not None:
        wi_ = np.ascontiguousarray(np.broadcast_to(wi_, shape + (3,))).reshape(-1, 3)
    else:
        ti = np.ascontiguousarray(np.broadcast_to(ti, shape)).reshape(-1)
    return _vgroove.pdf(model, ndf, _real(alpha, "alpha"), wi_, ti, wo, strategy, _sampler_max_k(max_k, model),
                        _real(tolerance, "tolerance"), dim, _integer(threads, "threads")).reshape(shape)


def uniforms(n: int, seed: int = 1, stream: Sequence[int] = (0, 0), dims: int = 4) -> np.ndarray:
    """``n`` rows of ``dims`` uniform numbers in [0, 1) from vgroove's deterministic stream
    sim::Rng(seed, stream[0], stream[1]) (sim/rng.h), drawn row after row. ``vgroove sample --seed S``
    draws its samples' four numbers from the stream (S, (0x5a3d, 0)) in 3D and (S, (0x5a3d, 1)) in
    flatland."""
    if len(stream) != 2:
        raise ValueError(f"stream = {tuple(stream)!r} must be two integers")
    return _vgroove.uniforms(_integer(n, "n"), _integer(seed, "seed"), _integer(stream[0], "stream[0]"),
                             _integer(stream[1], "stream[1]"), _integer(dims, "dims"))
