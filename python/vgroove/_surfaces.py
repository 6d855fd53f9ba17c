"""Procedural rough surfaces from Python: the surface, the light traced in it tallied into the
suites' bins, and the model's lobe over the same bins (the dicts of the report JSON; vgroove.BRDF's
trace and lobe return the same as dataclasses)."""

from __future__ import annotations

from typing import Optional

from . import _vgroove
from ._args import ProgressFn, integer, opt_integer, progress as _progress, real
from ._ranges import fill_ranges

Microsurface = _vgroove.Microsurface


def microsurface(ndf: str = "ggx", alpha: float = 0.5, grooves: int = 250000, seed: int = 1,
                 dim: str = "3d") -> Microsurface:
    """A procedural rough surface of symmetric V-grooves whose facet normals follow an NDF
    (sim/microsurface.h in flatland, sim/microsurface3d.h in 3D).

    Parameters
    ----------
    ndf : {"ggx", "beckmann", "phong"}
        The facet normals' distribution.
    alpha : float
        Roughness in [$min_alpha, $max_alpha].
    grooves : int
        In [1, $max_grooves].
    seed : int
        In [0, 2^63 - 1]: the surfaces of the Fig. 11, furnace and check_brdf suites (same seed,
        same surface).
    dim : {"3d", "flatland"}

    Returns
    -------
    Microsurface
        Immutable; ``theta_m_deg`` (facet angles) and, in 3D, ``phi_a_deg`` (groove azimuths) are
        read-only arrays.

    Raises
    ------
    ValueError
        An argument out of range.

    Examples
    --------
    >>> import vgroove
    >>> s = vgroove.microsurface("ggx", 0.5, grooves=1000, seed=1, dim="flatland")
    >>> s
    vgroove.Microsurface(ndf="ggx", alpha=0.5, grooves=1000, seed=1, dim="flatland")
    >>> s.theta_m_deg.shape
    (1000,)
    """
    return _vgroove.microsurface(ndf, real(alpha, "alpha"), integer(grooves, "grooves"), integer(seed, "seed"), dim)


def trace_microsurface(surface: Microsurface, theta_i_deg: float, rays: int = 1000000, *, seed: Optional[int] = None,
                       sampling: str = "random", flatland_bins: int = 90, theta_bins: int = 30, phi_bins: int = 24,
                       max_k: int = 16, max_bounces: int = 100000, threads: int = 0,
                       progress: Optional[ProgressFn] = None) -> dict:
    """Traces rays from theta_i into the surface, each exactly in its groove, and tallies the
    escaped ones as the suites do.

    Parameters
    ----------
    surface : Microsurface
        From :func:`microsurface`.
    theta_i_deg : float
        The light's angle: 3D, its polar angle in [0, $max_surface_theta_i_deg] deg at azimuth 180 deg;
        flatland, signed, in [-$max_surface_theta_i_deg, $max_surface_theta_i_deg] (the suites' range).
    rays : int
        In [1, $max_rays].
    seed : int, optional
        The rays' stream; None: the surface's seed, as in the suites.
    sampling : {"random", "stratified"}
        Where the rays land (3D: random only).
    flatland_bins : int
        Flatland: theta_o bins over (-90, 90) deg, in [1, $max_flatland_bins].
    theta_bins, phi_bins : int
        3D: theta_o bins over [0, 90) deg in [1, $max_theta_bins]; phi_o bins centred on phi = 0 (the
        mirror side), even, in [2, $max_phi_bins].
    max_k : int
        The rows of the tally, k = 0..max_k and one for every k > max_k, in [$min_histogram_k,
        $max_histogram_k] (the "brdf" suites' max_k; it does not limit the tracing).
    max_bounces : int
        The tracer's bounce limit, in [1, $max_bounces].
    threads : int
        In [0, $max_threads] (0: all cores); the counts do not depend on it.
    progress : callable, optional
        ``progress(done, total)``, counting rays.

    Returns
    -------
    dict
        Counts (int): ``rays``, ``escaped``, ``blocked``, ``vertex_hit``, ``bounce_limit``,
        ``not_upward``, ``bounces``, ``max_k_seen``; ``by_k`` (the rows). Flatland: ``theta_o``
        (bins) and ``theta_o_by_k`` (rows x bins); 3D: ``hist`` (theta_bins x phi_bins) and
        ``hist_by_k``. Divide by ``rays`` for fractions of the incident flux.
        :meth:`vgroove.BRDF.trace` returns the same as a :class:`vgroove.SurfaceTrace`.

    Raises
    ------
    ValueError
        An argument out of range, or a tally that would need more memory than this process may
        use (refused before it starts, with the estimate in the message).

    Examples
    --------
    >>> import vgroove
    >>> s = vgroove.microsurface("ggx", 0.5, grooves=1000, seed=1, dim="flatland")
    >>> t = vgroove.trace_microsurface(s, 40, rays=1000, flatland_bins=9)
    >>> int(t["theta_o"].sum()) == t["escaped"]
    True
    """
    return _vgroove.trace_microsurface(surface, real(theta_i_deg, "theta_i_deg"), integer(rays, "rays"),
                                       opt_integer(seed, "seed"), sampling, integer(flatland_bins, "flatland_bins"),
                                       integer(theta_bins, "theta_bins"), integer(phi_bins, "phi_bins"),
                                       integer(max_k, "max_k"), integer(max_bounces, "max_bounces"),
                                       integer(threads, "threads"), _progress(progress))


def lobe(model: str, ndf: str, alpha: float, theta_i_deg: float, dim: str = "3d", *, flatland_bins: int = 90,
         theta_bins: int = 30, phi_bins: int = 24, max_k: int = 16, progress: Optional[ProgressFn] = None) -> dict:
    """The model's lobe integrated over the bins of :func:`trace_microsurface`, as fractions of
    the incident flux.

    Parameters
    ----------
    model : {"vgroove", "cook-torrance"}
        ``"vgroove"`` (analytic/brdf_flatland.h, analytic/lobe_3d.h; every order) or
        ``"cook-torrance"`` (also ``"cook_torrance"``; single scattering, V-cavity G: its albedo
        shows the energy it loses).
    ndf, alpha, theta_i_deg, dim, flatland_bins, theta_bins, phi_bins
        As in :func:`microsurface` and :func:`trace_microsurface`.
    max_k : int
        The rows k = 0..max_k and one for the orders beyond, as in :func:`trace_microsurface` (the
        lobe holds every order whatever it is).
    progress : callable, optional
        ``progress(done, total)``: the start (0 of 1) and the end (1 of 1).

    Returns
    -------
    dict
        ``by_k``, ``albedo`` and ``theta_o``/``theta_o_by_k`` (flatland) or ``hist``/``hist_by_k``
        (3D). :meth:`vgroove.BRDF.lobe` returns the same as a :class:`vgroove.Lobe`.

    Raises
    ------
    ValueError
        As :func:`trace_microsurface`.

    Examples
    --------
    >>> import vgroove
    >>> round(vgroove.lobe("cook-torrance", "ggx", 1.0, 0, flatland_bins=9, dim="flatland")["albedo"], 4)
    0.6095
    """
    return _vgroove.lobe(model, ndf, real(alpha, "alpha"), real(theta_i_deg, "theta_i_deg"), dim,
                         integer(flatland_bins, "flatland_bins"), integer(theta_bins, "theta_bins"),
                         integer(phi_bins, "phi_bins"), integer(max_k, "max_k"), _progress(progress))


for _f in (microsurface, trace_microsurface, lobe):
    _f.__doc__ = fill_ranges(_f.__doc__)
