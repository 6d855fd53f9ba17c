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
  [1e-6, 180]; a nonsymmetric one by the angles of its facets' normals, ``theta_l_deg`` in
  [-90, 0] and ``theta_r_deg`` in [0, 90] (Lee et al. 2018, Fig. 5), aperture
  ``180 + theta_l_deg - theta_r_deg``. Degrees become radians as ``deg * (pi / 180)``, as the
  command line does, so the same inputs give the same bits.
* Directions are unit vectors (arrays ``(..., 3)``) in the frame n = (0, 0, 1), both pointing
  away from the surface: ``wi`` towards the light, ``wo`` towards the viewer. The direction at
  polar angle theta and azimuth phi is (sin theta cos phi, sin theta sin phi, cos theta)
  (:func:`direction`). In flatland the directions lie in the plane y = 0: the one at signed angle
  t is (-sin t, 0, cos t).
* BRDF values are in 1/sr (3D) or 1/rad (flatland), with F = 1 (a perfect mirror, white light).
* NDFs: ``"ggx"``, ``"beckmann"``, ``"phong"`` (Phong exponent 2/alpha^2 - 2); roughness alpha in
  (0, 2].
* Seeds are integers in [0, 2^63 - 1]; the same seed gives the same bits on any thread count.
"""

from __future__ import annotations

from typing import Callable, Optional, Sequence, Union

import numpy as np

from . import _vgroove

__all__ = [
    "__version__", "git_revision", "FATES", "LEFT", "RIGHT", "direction", "output_deg",
    "kaleidoscope", "analytic", "trace", "groove_case",
    "Microsurface", "microsurface", "trace_microsurface", "lobe",
    "brdf", "check_brdf", "validate",
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


def direction(theta_deg: ArrayLike, phi_deg: ArrayLike = 0.0) -> np.ndarray:
    """Unit vectors at polar angle theta and azimuth phi (degrees), shape broadcast + (3,):
    (sin theta cos phi, sin theta sin phi, cos theta). The light of the suites and of check_brdf
    is at azimuth 180 deg: ``direction(theta_i_deg, 180)``."""
    t = np.radians(np.asarray(theta_deg, dtype=float))
    p = np.radians(np.asarray(phi_deg, dtype=float))
    t, p = np.broadcast_arrays(t, p)
    return np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)


def output_deg(rad: ArrayLike) -> np.ndarray:
    """Radians to degrees rounded to 1e-9 deg, as every report and ``--json`` output prints them."""
    return _vgroove.output_deg(rad)


def _groove_arrays(theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg):
    if theta_l_deg is None and theta_r_deg is None:
        v = 90.0 if theta_v_deg is None else theta_v_deg
        ti, v = np.broadcast_arrays(np.asarray(theta_i_deg, dtype=float), np.asarray(v, dtype=float))
        return ti.shape, [np.ascontiguousarray(a, dtype=float).ravel() for a in (ti, v)] + [None, None]
    if theta_l_deg is None or theta_r_deg is None:
        raise ValueError("theta_l_deg needs theta_r_deg" if theta_l_deg is not None else "theta_r_deg needs theta_l_deg")
    if theta_v_deg is not None:
        raise ValueError("theta_v_deg cannot be combined with theta_l_deg/theta_r_deg (the aperture follows from them)")
    ti, l, r = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (theta_i_deg, theta_l_deg, theta_r_deg)))
    return ti.shape, [np.ascontiguousarray(ti).ravel(), None] + [np.ascontiguousarray(a).ravel() for a in (l, r)]


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
    return _vgroove.analytic(float(theta_i_deg), theta_v_deg, theta_l_deg, theta_r_deg, eq6_form)


def trace(theta_i_deg: float, rays: int = 1000, theta_v_deg: Optional[float] = None, *,
          theta_l_deg: Optional[float] = None, theta_r_deg: Optional[float] = None, sampling: str = "stratified",
          seed: int = 1, max_bounces: int = 100000) -> dict:
    """Traces one parallel beam through one groove exactly (sim/tracer.h), ray by ray, as
    ``vgroove trace`` does: ``rays`` rays across the opening, at the midpoints of equal strata
    (``sampling="stratified"``) or at seeded random points (``"random"``).

    Per ray (arrays of length ``rays``): ``x`` (where it crosses the rim line; the apex is the
    origin, facets of unit length), ``first_facet`` (int8: 0 left, 1 right, -1 none), ``k``
    (reflections), ``fate`` (int8 codes of :data:`FATES`), ``exit_dir`` ((rays, 2): the 2D exit
    direction (x, y), 0 where the ray did not escape), ``theta_o_deg`` (its angle, degrees, not
    rounded; 0 where the ray did not escape). ``summary``: the dict ``vgroove trace --json``
    prints (rows per (first facet, k), buckets)."""
    return _vgroove.trace(float(theta_i_deg), rays, theta_v_deg, theta_l_deg, theta_r_deg, sampling, seed,
                          max_bounces)


def groove_case(theta_i_deg: float, theta_v_deg: Optional[float] = None, *, theta_l_deg: Optional[float] = None,
                theta_r_deg: Optional[float] = None, rays: int = 1000, sampling: str = "stratified", seed: int = 1,
                max_bounces: int = 100000, eq6_form: str = "corrected", probe_vertices: bool = False,
                stream: int = 0) -> dict:
    """One case of a single-groove suite (a cell of Table 1): ``rays`` rays aimed at each lit
    facet, traced, and their fractions per bounce count against Eq. 6 / Eq. 9 (L1, with the
    shadowed rays a bin of their own). Returns the case's entry of the report ("l1", per facet
    "l1", "k", "rays", ...). ``stream`` is the case's index in its suite (random sampling draws the
    rays of facet f from the stream (seed, stream, f)), so a suite's case is reproduced exactly."""
    return _vgroove.groove_case(float(theta_i_deg), theta_v_deg, theta_l_deg, theta_r_deg, rays, sampling, seed,
                                max_bounces, eq6_form, probe_vertices, stream)


def microsurface(ndf: str = "ggx", alpha: float = 0.5, grooves: int = 250000, seed: int = 1,
                 dim: str = "3d") -> Microsurface:
    """A procedural rough surface of ``grooves`` symmetric V-grooves whose facet normals follow the
    NDF (sim/microsurface.h for ``dim="flatland"``, sim/microsurface3d.h for ``"3d"``): the
    surfaces of the Fig. 11, furnace and check_brdf suites (same seed, same surface). Its
    ``theta_m_deg`` (facet angles) and, in 3D, ``phi_a_deg`` (groove azimuths) are arrays."""
    return _vgroove.microsurface(ndf, float(alpha), grooves, seed, dim)


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
    rays run on ``threads`` threads (0: all cores); the counts do not depend on it."""
    return _vgroove.trace_microsurface(surface, float(theta_i_deg), rays, seed, sampling, flatland_bins, theta_bins,
                                       phi_bins, max_k, max_bounces, threads)


def lobe(model: str, ndf: str, alpha: float, theta_i_deg: float, dim: str = "3d", *, flatland_bins: int = 90,
         theta_bins: int = 30, phi_bins: int = 24, max_k: int = 16) -> dict:
    """The model's lobe integrated over the bins of :func:`trace_microsurface`, as fractions of the
    incident flux: ``model="vgroove"`` (analytic/brdf_flatland.h, analytic/lobe_3d.h; rows per k
    as in the tally) or ``"cook_torrance"`` (single scattering, V-cavity G: its albedo shows the
    energy it loses). Keys: ``by_k``, ``albedo`` and ``theta_o``/``theta_o_by_k`` (flatland) or
    ``hist``/``hist_by_k`` (3D)."""
    return _vgroove.lobe(model, ndf, float(alpha), float(theta_i_deg), dim, flatland_bins, theta_bins, phi_bins,
                         max_k)


def _directions(wi, wo):
    wi, wo = np.asarray(wi, dtype=float), np.asarray(wo, dtype=float)
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
      terms, shape S + (max_k,). Evaluating the sum costs the same for any max_k; its albedo
      reaches 1 at high roughness only with a large max_k (e.g. 10**6).
    * ``model="cook_torrance"``: Eq. 1-3 with the V-cavity G (the k = 1 term), shape S (+ (1,)).

    Values in 1/sr (3D) or 1/rad (flatland, directions in the plane y = 0), F = 1, 0 below the
    horizon. The directions are evaluated on ``threads`` threads (0: all cores) without the GIL."""
    shape, a, b = _directions(wi, wo)
    out = _vgroove.brdf(model, ndf, float(alpha), a, b, per_k, max_k, dim, threads)
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
    (1/rad in flatland) with F = 1. It is called once per incident angle with every quadrature
    node of that angle's bins. ``f`` may also be "vgroove" or "cook_torrance" (with ``max_k``):
    the built-in models, evaluated in C++.

    Per theta_i: the procedural surface of (ndf, alpha, grooves, seed) is traced with ``rays``
    rays into the bins (3D: theta_bins over [0, 90) deg x phi_bins; flatland: flatland_bins), the
    model is integrated over the same bins (Gauss-Legendre, quadrature_order per axis), and the
    L1 distances of the normalized lobes and of the flux fractions, and the albedo, are compared
    with what a correct model shows at this sample count (+ sigmas standard deviations +
    model_tolerance). Returns the report: "cases" (per theta_i: errors, thresholds, worst bins,
    pass), "pass", provenance."""
    return _vgroove.check_brdf(f, max_k, name, ndf, float(alpha), [float(t) for t in np.atleast_1d(theta_i_deg)],
                               rays, dim, grooves, seed, theta_bins, phi_bins, flatland_bins, float(sigmas),
                               float(model_tolerance), quadrature_order, threads)


def validate(path: str, *, rays: Optional[int] = None, threads: int = 0, sampling: Optional[str] = None,
             eq6_form: Optional[str] = None, seed: Optional[int] = None, model_table: Optional[str] = None,
             verbose: bool = False) -> dict:
    """Runs a suite file as ``vgroove validate PATH [--rays ...]`` does and returns its report (the
    JSON ``--out`` writes, as a dict; "pass" says whether every threshold held). Overrides: rays
    (per lit facet, or per case for rough surfaces), threads (0: all cores; the figures do not
    depend on it), sampling and eq6_form (single-groove suites), seed, model_table (a foreign
    model's bin-integrated lobes for a "brdf" suite: ``vgroove validate --model-table``).
    ``verbose`` prints the command line's table."""
    return _vgroove.validate(str(path), rays, threads, sampling, eq6_form, seed,
                             None if model_table is None else str(model_table), verbose)
