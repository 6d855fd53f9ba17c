"""Single V-grooves from Python: directions, the kaleidoscopic model (Eq. 4-9) vectorized, one
beam traced exactly, one validation case (a Table 1 cell)."""

from __future__ import annotations

from typing import Optional

import numpy as np

from . import _vgroove
from ._args import ArrayLike, integer, opt_integer, opt_real, real, reals
from ._ranges import fill_ranges

#: trace()'s fate codes, by value: 0 escaped, 1 blocked, 2 vertex hit, 3 bounce limit.
FATES = ("escaped", "blocked", "vertex_hit", "bounce_limit")
#: Facet codes of trace() and kaleidoscope(): the facet hit first (-1 in trace(): none).
LEFT, RIGHT = 0, 1


def direction(theta_deg: ArrayLike, phi_deg: ArrayLike = 0.0) -> np.ndarray:
    """Unit vectors at polar angle theta and azimuth phi.

    Parameters
    ----------
    theta_deg, phi_deg : array_like
        Angles in degrees; their shapes broadcast to S.

    Returns
    -------
    numpy.ndarray
        Shape S + (3,): (sin theta cos phi, sin theta sin phi, cos theta), from the angles in
        radians deg * (pi / 180), as the command line computes them (the same degrees give the
        same bits as ``vgroove brdf --theta-i-deg``). The light of the suites
        and of check_brdf is at azimuth 180 deg: ``direction(theta_i_deg, 180)``; in flatland the
        direction at signed angle t is ``direction(t, 180)`` = (-sin t, 0, cos t).

    Raises
    ------
    ValueError
        Complex or bool values.

    Examples
    --------
    >>> import vgroove
    >>> vgroove.direction(90, 0).round(12)
    array([1., 0., 0.])
    >>> vgroove.direction([0, 30], 180).shape
    (2, 3)
    """
    t, p = np.broadcast_arrays(reals(theta_deg, "theta_deg"), reals(phi_deg, "phi_deg"))
    flat = [np.ascontiguousarray(a).reshape(-1) for a in (t, p)]
    return _vgroove.direction(*flat).reshape(t.shape + (3,))


def output_deg(rad: ArrayLike) -> np.ndarray:
    """Radians to degrees rounded to 1e-9 deg, as every report and ``--json`` output prints them.

    Parameters
    ----------
    rad : array_like
        Angles in radians.

    Returns
    -------
    numpy.ndarray or float
        The same shape, in degrees, rounded to 1e-9 deg.

    Raises
    ------
    TypeError
        Values that are not numbers.

    Examples
    --------
    >>> import math, vgroove
    >>> float(vgroove.output_deg(math.pi / 6))
    30.0
    """
    return _vgroove.output_deg(rad)


def _groove_arrays(theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg):
    if theta_l_deg is None and theta_r_deg is None:
        v = 90.0 if theta_v_deg is None else theta_v_deg
        ti, v = np.broadcast_arrays(reals(theta_i_deg, "theta_i_deg"), reals(v, "theta_v_deg"))
        return ti.shape, [np.ascontiguousarray(a, dtype=float).ravel() for a in (ti, v)] + [None, None]
    if theta_l_deg is None or theta_r_deg is None:
        raise ValueError("theta_l_deg needs theta_r_deg" if theta_l_deg is not None else "theta_r_deg needs theta_l_deg")
    if theta_v_deg is not None:
        raise ValueError("theta_v_deg cannot be combined with theta_l_deg/theta_r_deg (the aperture follows from them)")
    ti, l, r = np.broadcast_arrays(*(reals(a, n) for a, n in ((theta_i_deg, "theta_i_deg"),
                                                             (theta_l_deg, "theta_l_deg"),
                                                             (theta_r_deg, "theta_r_deg"))))
    return ti.shape, [np.ascontiguousarray(ti).ravel(), None] + [np.ascontiguousarray(a).ravel() for a in (l, r)]


def _groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg):
    return (opt_real(theta_v_deg, "theta_v_deg"), opt_real(theta_l_deg, "theta_l_deg"),
            opt_real(theta_r_deg, "theta_r_deg"))


def kaleidoscope(theta_i_deg: ArrayLike, theta_v_deg: Optional[ArrayLike] = None, *,
                 theta_l_deg: Optional[ArrayLike] = None, theta_r_deg: Optional[ArrayLike] = None,
                 eq6_form: str = "corrected") -> dict:
    """The kaleidoscopic model of single V-grooves, vectorized (Lee et al. 2018, Eq. 4-6 symmetric,
    Eq. 7-9 nonsymmetric).

    Parameters
    ----------
    theta_i_deg : array_like
        Incident angles in [-$max_theta_i_deg, $max_theta_i_deg] deg.
    theta_v_deg : array_like, optional
        A symmetric groove's aperture in [$min_aperture_deg, 180] deg (default 90).
    theta_l_deg, theta_r_deg : array_like, optional
        A nonsymmetric groove's facet normals, in [-90, 0] and [0, 90] deg (Fig. 5).
    eq6_form : {"corrected", "printed"}
        Eq. 6 as corrected (docs/ERRATA.md, E1) or as printed.

    Returns
    -------
    dict
        The angles broadcast to S. Per facet hit first (last axis 2: 0 left, 1 right), S + (2,):
        ``lit`` (the light reaches the facet), ``k`` (Eq. 4, or k_b of Eq. 7), ``f_a`` (projected
        width of the unit facet), ``shadow`` (f_b / f_a: rays aimed at the facet that meet the
        other rim first). Per facet and zone, S + (2, 4) (symmetric grooves use zones 0: k - 1
        and 1: k reflections; unused zones are 0): ``n`` (reflections), ``G`` (share of the rays
        aimed at the facet, Eq. 6 / Eq. 9), ``fraction`` (share of the beam entering the opening:
        G f_a / sum of the lit facets' f_a (1 - shadow)), ``theta_o_deg`` (exit angle, Eq. 5 /
        Eq. 8, degrees, not rounded).

    Raises
    ------
    ValueError
        An angle out of range (naming the element), a nonsymmetric groove given by one facet, or
        with theta_v_deg too.

    Examples
    --------
    >>> import vgroove
    >>> m = vgroove.kaleidoscope(0, 90)
    >>> m["n"][:, 0].tolist(), m["fraction"][:, 0].tolist()
    ([2, 2], [0.5, 0.5])
    """
    shape, (ti, v, l, r) = _groove_arrays(theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg)
    out = _vgroove.kaleidoscope(ti, v, l, r, eq6_form)
    return {key: a.reshape(shape + a.shape[1:]) for key, a in out.items()}


def analytic(theta_i_deg: float, theta_v_deg: Optional[float] = None, *, theta_l_deg: Optional[float] = None,
             theta_r_deg: Optional[float] = None, eq6_form: str = "corrected") -> dict:
    """``vgroove analytic --json`` for one groove and one incident angle.

    Parameters
    ----------
    theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg, eq6_form
        As in :func:`kaleidoscope`, scalars.

    Returns
    -------
    dict
        "inputs", "bounces" (rows: first_facet, k, fraction of the beam entering the opening,
        theta_o_deg rounded to 1e-9 deg) and "facets" (k, f_a, G per bounce count, shadow; None
        for an unlit facet): the command line's JSON.

    Raises
    ------
    ValueError
        As :func:`kaleidoscope`.

    Examples
    --------
    >>> import vgroove
    >>> [(b["k"], b["fraction"]) for b in vgroove.analytic(0, 90)["bounces"]]
    [(2, 0.5), (2, 0.5)]
    """
    return _vgroove.analytic(real(theta_i_deg, "theta_i_deg"), *_groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg),
                             eq6_form)


def trace(theta_i_deg: float, rays: int = 1000, theta_v_deg: Optional[float] = None, *,
          theta_l_deg: Optional[float] = None, theta_r_deg: Optional[float] = None, sampling: str = "stratified",
          seed: int = 1, max_bounces: Optional[int] = None) -> dict:
    """Traces one parallel beam through one groove exactly (sim/tracer.h), ray by ray, as
    ``vgroove trace`` does.

    Parameters
    ----------
    theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg
        As in :func:`kaleidoscope`, scalars.
    rays : int
        Rays across the opening, in [1, $max_rays].
    sampling : {"stratified", "random"}
        At the midpoints of equal strata, or at seeded random points.
    seed : int
        In [0, 2^63 - 1].
    max_bounces : int, optional
        The bounce limit, in [1, $max_bounces]; None: the command line's, $default_max_bounces, or
        ceil(180 / theta_v_deg) + 1 where a narrower groove needs more, so that every ray can leave.

    Returns
    -------
    dict
        Per ray (arrays of length ``rays``): ``x`` (where it crosses the rim line; the apex is the
        origin, facets of unit length), ``first_facet`` (int8: 0 left, 1 right, -1 none), ``k``
        (reflections), ``fate`` (int8 codes of :data:`FATES`), ``exit_dir`` ((rays, 2): the 2D exit
        direction (x, y), 0 where the ray did not escape), ``theta_o_deg`` (its angle, degrees,
        not rounded; 0 where the ray did not escape). ``summary``: the dict ``vgroove trace
        --json`` prints (rows per (first facet, k), buckets).

    Raises
    ------
    ValueError
        An argument out of range (the command line's message).

    Examples
    --------
    >>> import vgroove
    >>> t = vgroove.trace(0, 100, 90)
    >>> sorted(set(t["k"].tolist())), t["summary"]["buckets"]["escaped"]
    ([2], 100)
    """
    return _vgroove.trace(real(theta_i_deg, "theta_i_deg"), integer(rays, "rays"),
                          *_groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg), sampling, integer(seed, "seed"),
                          opt_integer(max_bounces, "max_bounces"))


def groove_case(theta_i_deg: float, theta_v_deg: Optional[float] = None, *, theta_l_deg: Optional[float] = None,
                theta_r_deg: Optional[float] = None, rays: int = 1000, sampling: str = "stratified", seed: int = 1,
                max_bounces: Optional[int] = None, eq6_form: str = "corrected", probe_vertices: bool = False,
                stream: int = 0) -> dict:
    """One case of a single-groove suite (a cell of Table 1): the traced fractions per bounce count
    against Eq. 6 / Eq. 9.

    Parameters
    ----------
    theta_i_deg, theta_v_deg, theta_l_deg, theta_r_deg, eq6_form
        As in :func:`kaleidoscope`, scalars.
    rays : int
        Rays aimed at each lit facet, in [1, $max_rays].
    sampling, seed, max_bounces
        As in :func:`trace`.
    probe_vertices : bool
        Also aim rays at the groove's vertices (the stress suite's hard cases).
    stream : int
        The case's index in its suite (random sampling draws the rays of facet f from the stream
        (seed, stream, f)), so that a suite's case is reproduced exactly.

    Returns
    -------
    dict
        The case's entry of the report: "l1" (with the shadowed rays a bin of their own), per
        facet "l1", "k", "rays", ...

    Raises
    ------
    ValueError
        An argument out of range (the command line's message).

    Examples
    --------
    >>> import vgroove
    >>> round(vgroove.groove_case(30, 61, rays=1000, seed=2018)["l1"], 6)
    0.000709
    """
    return _vgroove.groove_case(real(theta_i_deg, "theta_i_deg"),
                                *_groove_scalars(theta_v_deg, theta_l_deg, theta_r_deg),
                                integer(rays, "rays"), sampling, integer(seed, "seed"),
                                opt_integer(max_bounces, "max_bounces"), eq6_form, probe_vertices,
                                integer(stream, "stream"))


for _f in (kaleidoscope, trace, groove_case):
    _f.__doc__ = fill_ranges(_f.__doc__)
