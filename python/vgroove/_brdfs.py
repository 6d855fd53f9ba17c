"""BRDFs over arrays of directions, and a BRDF of the user's held against the exact simulation
(validation/check_brdf.h)."""

from __future__ import annotations

from typing import Callable, Optional, Sequence, Union

import numpy as np

from . import _args, _vgroove
from ._args import (ProgressFn, integer, opt_complex, opt_integer, progress as _progress, real, reals, rows, text,
                    vectors)
from ._ranges import fill_ranges

#: The orders each model sums when max_k is not given, by (model, dim): the one table of every face
#: (analytic/brdf_model.h, analytic::default_max_k; ``vgroove brdf --max-k``, vgroove.BRDF, brdf()).
BRDF_MAX_K: dict = dict(_vgroove.BRDF_MAX_K)
#: The orders per_k=True reports when max_k is not given (``vgroove brdf --per-k``'s --per-k-max).
PER_K_ORDERS = 16


def brdf(model: str, ndf: str, alpha: float, wi: np.ndarray, wo: np.ndarray, per_k: Union[bool, int] = False, *,
         max_k: Optional[int] = None, dim: str = "3d", eta: Optional[complex] = None, masking: Optional[str] = None,
         threads: int = 0, progress: Optional[ProgressFn] = None) -> np.ndarray:
    """A BRDF over arrays of directions: ``vgroove brdf`` vectorized (:class:`vgroove.BRDF` holds
    the same with the nonsymmetric model's options and Fresnel).

    Parameters
    ----------
    model : {"vgroove", "vgroove-nonsymmetric", "cook-torrance", "walter"}
        ``"vgroove"``: Lee et al. 2018, Eq. 16-17 (3D, analytic/brdf_3d.h) or its flatland analogue
        (analytic/brdf_flatland.h). ``"vgroove-nonsymmetric"``: Eq. 21-23 with the independent
        partner law of Eq. 20 (isotropic; Phong needs alpha < sqrt(2)). ``"cook-torrance"`` (also
        ``"cook_torrance"``): Eq. 1-3 with the V-cavity G (the k = 1 term). ``"walter"``: Walter
        et al. 2007's rough dielectric BSDF (analytic/walter.h, k = 1): wi above the interface
        (z > 0), wo on either side (z < 0: transmitted into the far medium).
    ndf : {"ggx", "beckmann", "phong"}
    alpha : float
        Roughness in [$min_alpha, $max_alpha].
    wi, wo : array_like, shape (..., 3)
        Unit vectors towards the light and the viewer; shapes broadcast to S + (3,). Flatland: in
        the plane y = 0.
    per_k : bool or int
        False: the sums. True: the orders k = 1..max_k each on its own (1..$per_k_orders when
        max_k is None); an int: that many orders.
    max_k : int, optional
        The orders summed; None: the model's default, the same on every face (:data:`BRDF_MAX_K`:
        every order in 3D, $flatland_max_k in flatland, $nonsymmetric_max_k for the nonsymmetric
        model, whose sum costs O(max_k^2) per direction, about 1 ms at 64). Ranges: [1, 2^31 -
        1], at most $max_flatland_k in flatland and $max_nonsymmetric_k for the nonsymmetric model.
    dim : {"3d", "flatland"}
    eta : complex, optional
        As :class:`vgroove.BRDF`'s: a conductor's Fresnel term (3D), or with ``"walter"`` the
        dielectric's real n_far / n_near (None: 1.5).
    masking : {"smith", "smith_separable", "vcavity"}, optional
        ``"walter"`` only: its G2 (None: smith_separable, Walter's Eq. 23).
    threads : int
        In [0, $max_threads] (0: all cores), without the GIL.
    progress : callable, optional
        ``progress(done, total)``, counting directions.

    Returns
    -------
    numpy.ndarray
        Shape S (per_k: S + (orders,); Cook-Torrance and Walter S + (1,)): values in 1/sr (3D) or
        1/rad (flatland), F = 1 (without eta), 0 below the horizon (but Walter's transmission).

    Raises
    ------
    ValueError
        ``vgroove brdf``'s messages for the same input, with the argument's name.

    Examples
    --------
    >>> import vgroove
    >>> wi, wo = vgroove.direction(30, 180), vgroove.direction(40, 0)
    >>> round(float(vgroove.brdf("vgroove", "ggx", 0.5, wi, wo)), 6)
    0.884746
    >>> vgroove.brdf("vgroove", "ggx", 0.5, wi, wo, per_k=True).shape
    (16,)
    """
    wi, wo = vectors(wi, "wi"), vectors(wo, "wo")
    shape = np.broadcast_shapes(wi.shape, wo.shape)[:-1]
    max_k = opt_integer(max_k, "max_k")
    if isinstance(per_k, (bool, np.bool_)):
        orders = (PER_K_ORDERS if max_k is None else max_k) if per_k else 0
    else:
        orders = integer(per_k, "per_k")
    out = _vgroove.brdf(model, ndf, real(alpha, "alpha"), rows(wi, shape, 3), rows(wo, shape, 3), orders, max_k, dim,
                        integer(threads, "threads"), eta=opt_complex(eta, "eta"), masking=text(masking, "masking"),
                        progress=_progress(progress))
    return out.reshape(shape + out.shape[1:])


def check_brdf(f: Union[Callable[[np.ndarray, np.ndarray], np.ndarray], str], ndf: str = "ggx", alpha: float = 0.5,
               theta_i_deg: Sequence[float] = (0, 20, 40, 60, 80), rays: int = 1000000, *, dim: str = "3d",
               grooves: int = 250000, seed: int = 1, theta_bins: int = 30, phi_bins: int = 24,
               flatland_bins: int = 90, sigmas: float = 5.0, model_tolerance: float = 1e-4,
               quadrature_order: int = 4, threads: int = 0, name: str = "check_brdf", max_k: Optional[int] = None,
               progress: Optional[ProgressFn] = None, surface: str = "vgroove", field_size: int = 256,
               correlation_length: float = 8.0, fields: int = 4, eta: Optional[float] = None,
               side: str = "above") -> dict:
    """Holds a BRDF against vgroove's exact simulation (validation/check_brdf.h; same verdict,
    thresholds and report as the C++ API ``vgroove::validation::check_brdf``).

    Per theta_i the procedural surface of (ndf, alpha, grooves, seed) is traced with ``rays`` rays
    into the bins, the BRDF is integrated over the same bins (Gauss-Legendre, quadrature_order
    per axis), and the L1 distances of the normalized lobes and of the flux fractions, and the
    albedo, are compared with what a correct model shows at this sample count (+ sigmas standard
    deviations + model_tolerance).

    Parameters
    ----------
    f : callable or str
        ``f(wi, wo) -> values``, vectorized: wi and wo float arrays (n, 3) (unit vectors, the light
        at azimuth 180 deg), n values in 1/sr (1/rad in flatland) with F = 1. It is called with
        the nodes of one cell's Gauss-Legendre rule at a time (quadrature_order^2 directions in
        3D, quadrature_order in flatland), at least once per bin and incident angle. Or the name
        of a model of :func:`brdf`, evaluated in C++ (``max_k`` as there). Ctrl-C stops the check
        within one evaluation of f (f is not called again).
    ndf, alpha
        The traced surface's NDF and roughness in [$min_alpha, $max_alpha].
    theta_i_deg : sequence of float
        Incident angles, each in [0, $max_surface_theta_i_deg].
    rays : int
        Per theta_i, in [1, $max_rays].
    dim : {"3d", "flatland"}
    grooves, seed
        The surface (:func:`vgroove.microsurface`).
    theta_bins, phi_bins, flatland_bins
        The bins (:func:`vgroove.trace_microsurface`).
    sigmas, model_tolerance, quadrature_order
        The thresholds' standard deviations, the integration's target error, nodes per axis.
    threads : int
        In [0, $max_threads] (0: all cores); the report does not depend on it.
    name : str
        Names the report.
    max_k : int, optional
        With a model's name: as in :func:`brdf`.
    progress : callable, optional
        ``progress(done, total)``: the start (0 of 1) and the end (1 of 1).
    surface : {"vgroove", "heightfield"}
        The traced surface: the procedural V-grooves above, or ``fields`` random heightfields of
        the NDF (beckmann or ggx) and alpha, traced exactly in 3D (the surface Smith's models
        assume), the rays split evenly among them; the noise per bin is then the fields' spread.
    field_size, correlation_length, fields
        With surface "heightfield": cells per side (a power of two in [16, 65536] whose field fits
        memory: refused otherwise), the correlation length in cells ([2, field_size / 8]), and
        independent fields in [2, 1000].
    eta : float, optional
        A rough-glass BSDF instead: the same V-grooves between two dielectrics, eta = n2 / n1 in
        [$min_glass_eta, $max_glass_eta], not 1, traced with Fresnel and Snell at every hit
        (validation/check_bsdf.h). f is then called for wo in both hemispheres (wo[:, 2] < 0:
        below the surface) in flux form (f |cos theta_o| d omega_o is the share of the incident
        flux leaving into d omega_o, as :func:`brdf` ``"walter"``), and each case holds, besides
        both hemispheres as one lobe, "lobes": the reflected and the transmitted lobe apart (albedos
        R and T with their binomial sd and thresholds, L1 of each normalized lobe and of its flux
        fractions). None: the conductor check above. Surface "vgroove" only.
    side : {"above", "below"}
        With eta: the side the light comes from (below: wi[:, 2] < 0, inside the glass); theta_o
        is measured from the normal of the side the light leaves into.

    Returns
    -------
    dict
        The report: "cases" (per theta_i: errors, thresholds, worst bins, pass), "pass",
        provenance.

    Raises
    ------
    ValueError
        An argument out of range; f not callable, or returning the wrong shape (the exception f
        raises is raised as it is).

    Examples
    --------
    >>> import vgroove
    >>> ct = lambda wi, wo: vgroove.brdf("cook-torrance", "ggx", 1.0, wi, wo)
    >>> r = vgroove.check_brdf(ct, "ggx", 1.0, [0], rays=20000, grooves=5000, theta_bins=6, phi_bins=4)
    >>> r["pass"], round(r["cases"][0]["albedo_model"], 2)
    (False, 0.37)
    """
    return _vgroove.check_brdf(f, opt_integer(max_k, "max_k"), name, ndf, real(alpha, "alpha"),
                               [float(t) for t in np.atleast_1d(reals(theta_i_deg, "theta_i_deg"))],
                               integer(rays, "rays"), dim, integer(grooves, "grooves"), integer(seed, "seed"),
                               integer(theta_bins, "theta_bins"), integer(phi_bins, "phi_bins"),
                               integer(flatland_bins, "flatland_bins"), real(sigmas, "sigmas"),
                               real(model_tolerance, "model_tolerance"), integer(quadrature_order, "quadrature_order"),
                               integer(threads, "threads"), _progress(progress), surface,
                               integer(field_size, "field_size"), real(correlation_length, "correlation_length"),
                               integer(fields, "fields"), None if eta is None else real(eta, "eta"), side)


def dielectric_lobe(ndf: str, alpha: float, eta: float, theta_i_deg: float = 0.0, per_k: Union[bool, int] = False, *,
                    dim: str = "3d", flatland_bins: int = 90, theta_bins: int = 18, phi_bins: int = 24,
                    progress: Optional[ProgressFn] = None) -> dict:
    """The kaleidoscopic dielectric model's lobe over an NDF: the fractions of the incident flux
    reflected into each bin above and transmitted into each bin below (analytic/
    kaleidoscope_dielectric_lobe.h; ``vgroove brdf --model vgroove-dielectric``, whose JSON holds the
    same numbers with the default bins).

    Parameters
    ----------
    ndf : {"ggx", "beckmann", "phong"}
    alpha : float
        Roughness in [$min_alpha, $max_alpha].
    eta : float
        n_far / n_near in (0, $max_fresnel_eta], the light in the near medium (below 1: from inside
        the denser medium); 1: no interface, everything transmitted straight on.
    theta_i_deg : float
        The light: 3D polar angle in [0, 90) (at azimuth 180); flatland signed in (-90, 90).
    per_k : bool or int
        False: the sums only. True: also the lobes per interaction count k, rows k = 0..16 and one
        for every k > 16 (``--per-k``); an int n in [0, 1000] (0: as False): rows 0..n and one for k > n
        (``--per-k --per-k-max n``).
    dim : {"3d", "flatland"}
    flatland_bins, theta_bins, phi_bins
        The bins (the defaults are ``vgroove brdf``'s, app/cmd_brdf.cpp): flatland_bins equal bins
        over (-90, 90) deg (at most $max_flatland_bins); in 3D theta_bins over [0, 90) deg from the
        exit side's normal (at most $max_theta_bins) x phi_bins (even, at most $max_phi_bins)
        centred on phi = 0, the light at phi = 180 deg.
    progress : callable, optional
        ``progress(done, total)``: the start (0 of 1) and the end (1 of 1). Ctrl-C is raised when
        the lobe is done (the library takes no cancel flag).

    Returns
    -------
    dict
        ``reflected``, ``transmitted``: arrays of shape (flatland_bins,) or (theta_bins, phi_bins),
        flux fractions per bin, angles from the exit side's normal; with per_k ``reflected_by_k``,
        ``transmitted_by_k`` of shape (rows,) + that; ``albedo_r``, ``albedo_t``,
        ``shadow_or_unknown`` (not binned: albedo_r + albedo_t + shadow_or_unknown = 1), ``upward``
        and ``unresolved`` (parts of it), ``error_estimate``; the bin edges in degrees,
        ``theta_edges_deg`` (and ``phi_edges_deg`` in 3D).

    Raises
    ------
    ValueError
        An argument out of range, named as here, with ``vgroove brdf``'s range.

    Examples
    --------
    >>> import vgroove
    >>> L = vgroove.dielectric_lobe("ggx", 0.3, 1.5, 30, dim="flatland", flatland_bins=18)
    >>> L["reflected"].shape, round(L["albedo_r"] + L["albedo_t"] + L["shadow_or_unknown"], 12)
    ((18,), 1.0)
    """
    if isinstance(per_k, (bool, np.bool_)):
        orders = PER_K_ORDERS if per_k else 0
    else:
        orders = integer(per_k, "per_k")
    d = _vgroove.dielectric_lobe(text(ndf, "ndf"), real(alpha, "alpha"), real(eta, "eta"),
                                 real(theta_i_deg, "theta_i_deg"), text(dim, "dim"), orders,
                                 integer(flatland_bins, "flatland_bins"), integer(theta_bins, "theta_bins"),
                                 integer(phi_bins, "phi_bins"), _progress(progress))
    # The command line's edges (app/cmd_brdf.cpp): -90 + b * 180 / bins; 3D b * 90 / theta_bins and
    # (b - 1/2) * 360 / phi_bins.
    if dim == "flatland":
        d["theta_edges_deg"] = np.array([-90.0 + b * (180.0 / flatland_bins) for b in range(flatland_bins + 1)])
    else:
        d["theta_edges_deg"] = np.array([b * (90.0 / theta_bins) for b in range(theta_bins + 1)])
        dp = 360.0 / phi_bins
        d["phi_edges_deg"] = np.array([b * dp - 0.5 * dp for b in range(phi_bins + 1)])
    return d


def dielectric_bsdf(ndf: str, alpha: float, eta: float, theta_i_deg: _args.ArrayLike, theta_o_deg: _args.ArrayLike,
                    per_k: Union[bool, int] = False, *, phi_i_deg: _args.ArrayLike = 0.0,
                    phi_o_deg: _args.ArrayLike = 180.0, dim: str = "3d", threads: int = 0,
                    progress: Optional[ProgressFn] = None) -> dict:
    """The kaleidoscopic dielectric model's BSDF at points (analytic/kaleidoscope_dielectric_point.h;
    ``vgroove brdf --model vgroove-dielectric --theta-o-deg``, whose JSON holds the same numbers to
    the last bit): f(i, o) reflected and transmitted, summed over the interaction counts k up to 32,
    and the density of the sampler's directions.

    Parameters
    ----------
    ndf : {"ggx", "beckmann", "phong"}
    alpha : float
        Roughness in [$min_alpha, $max_alpha].
    eta : float
        n_far / n_near in (0, $max_fresnel_eta], the light in the near medium, above the interface
        (below 1: from inside the denser medium).
    theta_i_deg, theta_o_deg, phi_i_deg, phi_o_deg : array_like
        The directions in degrees, the command line's: the light's polar angle in [0, 90) (flatland
        signed, (-90, 90)); the viewer's in [0, 180] less 90 (flatland [-180, 180] less +-90), over
        90 transmitted, below the interface (the horizon, where f = density / |cos theta_o| is not
        defined, is refused); the azimuths in [-360, 360] (3D only; phi_o = phi_i + 180 is the
        mirror side). Flatland: theta_o past 90 is measured from the lower normal, the
        straight-through direction of theta_i is theta_i - 180 sign(theta_i). The four broadcast
        to one shape S.
    per_k : bool or int
        False: f only. True: also f per interaction count, rows k = 0..16 and one for every k > 16
        (``--per-k``); an int n in [0, 1000] (0: as False): rows 0..n and one for k > n (``--per-k
        --per-k-max n``). The rows sum to f.
    dim : {"3d", "flatland"}
    threads : int
        In [0, $max_threads] (0: all cores), without the GIL.
    progress : callable, optional
        ``progress(done, total)``, counting points.

    Returns
    -------
    dict
        ``value``: f, shape S, in 1/sr (flatland 1/rad); ``pdf``: f |cos theta_o|, shape S, the
        density of the directions the model's sampler draws (analytic/sampling_dielectric.h; it
        integrates to albedo_r + albedo_t); with per_k ``by_k``, shape S + (rows,).

    Raises
    ------
    ValueError
        An argument out of range, named as here (``theta_o_deg[j]``: row j of the flattened
        broadcast), with ``vgroove brdf``'s range.

    Examples
    --------
    >>> import vgroove
    >>> b = vgroove.dielectric_bsdf("ggx", 0.3, 1.5, 30, [35, 160], phi_o_deg=180)
    >>> b["value"].shape, bool((b["value"] > 0).all())
    ((2,), True)
    """
    if isinstance(per_k, (bool, np.bool_)):
        orders = PER_K_ORDERS if per_k else 0
    else:
        orders = integer(per_k, "per_k")
    parts = [reals(theta_i_deg, "theta_i_deg"), reals(phi_i_deg, "phi_i_deg"), reals(theta_o_deg, "theta_o_deg"),
             reals(phi_o_deg, "phi_o_deg")]
    shape = np.broadcast_shapes(*(a.shape for a in parts))
    angles = np.ascontiguousarray(np.stack([np.broadcast_to(a, shape).ravel() for a in parts], axis=-1),
                                  dtype=np.float64).reshape(-1, 4)
    d = _vgroove.dielectric_bsdf(text(ndf, "ndf"), real(alpha, "alpha"), real(eta, "eta"), angles, text(dim, "dim"),
                                 orders, integer(threads, "threads"), _progress(progress))
    out = {"value": d["value"].reshape(shape), "pdf": d["pdf"].reshape(shape)}
    if "by_k" in d:
        out["by_k"] = d["by_k"].reshape(shape + d["by_k"].shape[1:])
    return out


for _f in (brdf, check_brdf, dielectric_lobe, dielectric_bsdf):
    _f.__doc__ = fill_ranges(_f.__doc__, dict(per_k_orders=PER_K_ORDERS,
                                              flatland_max_k=BRDF_MAX_K[("vgroove", "flatland")],
                                              nonsymmetric_max_k=BRDF_MAX_K[("vgroove-nonsymmetric", "3d")]))
