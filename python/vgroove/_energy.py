"""energy_lobe_shape(): the compensated lobes' shape beyond energy, as ``vgroove energy --lobe-shape``
computes it (validation/energy_lobe_shape.h); glass_energy(): rough glass tables, as ``vgroove energy
--eta`` computes them (validation/glass_energy.h); energy_audit(): the compensation formulas against
exact multiple scattering, as ``vgroove energy --audit [--reference heightfield]`` computes it
(validation/energy_audit.h); each report as a dict."""

from __future__ import annotations

from typing import Optional, Sequence, Union

import numpy as np

from . import _vgroove
from ._args import ProgressFn, integer, progress as _progress, real, reals, text
from ._ranges import fill_ranges


def energy_lobe_shape(ndf: str = "ggx", alpha: Sequence[float] = (0.5, 1.0),
                      theta_i_deg: Sequence[float] = (0, 40, 70), rays: int = 200000, *, grooves: int = 100000,
                      seed: int = 1, theta_bins: int = 15, phi_bins: int = 12, sigmas: float = 5.0, threads: int = 0,
                      verbose: bool = False) -> dict:
    """The energy compensation formulas' lobes against exact multiple scattering, by their shape.

    With F = 1 the compensated BRDFs take three lobes: "single" (f_ss alone), "kulla_conty"
    (f_ss + Kulla-Conty's f_ms) and "view_scaled" (f_ss / E(mu_o): Turquin, Filament, Bevy and
    Cycles at F0 = 1). Each is held against the traced procedural V-groove surface (f_ss:
    Cook-Torrance with the V-cavity G) and the 3D Smith random walk (f_ss: Smith height-correlated),
    binned alike, by check_brdf's metric: the L1 distance of the normalized lobes and of the flux
    fractions, and the albedo, beside the noise a correct lobe shows at this sample count. Controls
    (the V-groove model on its surface, f_ss on each reference's k = 1 lobe) must be within it.

    Parameters
    ----------
    ndf : str
        "ggx" or "beckmann" (the walk needs Smith's Lambda).
    alpha : sequence of float
        Roughnesses, each in [$min_alpha, $max_alpha].
    theta_i_deg : sequence of float
        Incidences, each in [0, $max_surface_theta_i_deg].
    rays : int
        Rays traced and walks per incidence, in [1, $max_rays].
    grooves : int
        Grooves of the traced surface, in [1, $max_grooves].
    seed : int
        In [0, 2^63 - 1]: the surface, the rays and the walks.
    theta_bins, phi_bins : int
        The lobes' bins over theta_o in [0, 90) deg and phi_o (even, centred on the mirror azimuth).
    sigmas : float
        Standard deviations allowed beyond the expected error.
    threads : int
        In [0, $max_threads] (0: all cores); the rows do not depend on it.
    verbose : bool
        Print the command line's table.

    Returns
    -------
    dict
        The report ``vgroove energy --lobe-shape --out`` writes: "rows" (reference, lobe, alpha,
        theta_i_deg, l1 and l1_threshold, l1_flux and its threshold, albedo_sim, albedo_model,
        within_noise), "controls_pass" and the albedo table's interpolation error.

    Raises
    ------
    ValueError
        The command line's message for the same input, naming the argument and its range.

    Examples
    --------
    >>> import vgroove
    >>> r = vgroove.energy_lobe_shape(alpha=[0.5], theta_i_deg=[60], rays=20000, grooves=20000)
    >>> r["controls_pass"], len(r["rows"])
    (True, 9)
    >>> vgroove.energy_lobe_shape(alpha=[0.005])
    Traceback (most recent call last):
    ...
    ValueError: alpha = 0.005 is out of range [0.01, 2]
    """
    return _vgroove.energy_lobe_shape(
        ndf, [float(a) for a in np.atleast_1d(reals(alpha, "alpha"))],
        [float(t) for t in np.atleast_1d(reals(theta_i_deg, "theta_i_deg"))], integer(rays, "rays"),
        integer(grooves, "grooves"), integer(seed, "seed"), integer(theta_bins, "theta_bins"),
        integer(phi_bins, "phi_bins"), real(sigmas, "sigmas"), integer(threads, "threads"), bool(verbose))


energy_lobe_shape.__doc__ = fill_ranges(energy_lobe_shape.__doc__)


def energy_audit(ndf: Union[str, Sequence[str]] = ("ggx", "beckmann"), alpha: Optional[Sequence[float]] = None,
                 mu: Optional[Sequence[float]] = None, *, alpha_points: int = 8, mu_points: int = 8,
                 rays: int = 100000, seed: int = 1, max_k: int = 16, reference: Optional[str] = None,
                 threads: int = 0, verbose: bool = False, progress: Optional[ProgressFn] = None) -> dict:
    """The energy compensation formulas engines ship (Kulla-Conty, Turquin, Cycles, Filament, Bevy,
    Fdez-Aguera) against exact multiple scattering over mu x alpha x reflectance, as ``vgroove
    energy --audit`` runs it: the references are the V-groove model (quadrature) and the 3D Smith
    random walk, and with ``reference="heightfield"`` (``--reference heightfield``) the random
    Gaussian heightfields traced exactly as a third (4 fields of 256^2 cells, rays // 4 rays per
    field and cell, correlation length 8 cells).

    Parameters
    ----------
    ndf : str or sequence of str
        "ggx", "beckmann" or both (the walk needs Smith's Lambda in closed form).
    alpha, mu : sequence of float, optional
        The grid's roughnesses, each in [$min_alpha, $max_alpha], and mu = cos theta_i, each in
        [$min_mu, 1]; None: alpha_points (mu_points) midpoints (j + 1/2)/n of (0, 1].
    alpha_points, mu_points : int
        In [1, $max_alpha_points] and [1, $max_mu_points].
    rays : int
        Walk paths per cell, in [1, $max_audit_paths]; with the heightfields rays // 4 (at least 1)
        rays per field and cell.
    seed : int
        In [0, 2^63 - 1]: the walks' and the fields' streams.
    max_k : int
        Bounce orders tabulated one by one, in [1, $max_audit_k].
    reference : {None, "heightfield"}
        None: the V-groove model and the Smith walk; "heightfield" adds the random heightfields.
    threads : int
        In [0, $max_threads] (0: all cores); the report's values do not depend on it.
    verbose : bool
        Print the command line's table.
    progress : callable, optional
        ``progress(done, total)``, counting the run's work items.

    Returns
    -------
    dict
        The report ``vgroove energy --audit --out`` writes for the same arguments (its "spec" a suite
        for :func:`vgroove.validate`), with the same values: "cells" (per reference, NDF, alpha and
        mu: E per k and per channel, each formula's albedo and error), "summary", "checks" and
        "pass" (the references' checks held).

    Raises
    ------
    ValueError
        The command line's message for the same input, naming the argument (its flag without the
        dashes, "energy_audit" for ``--audit``) and its range.

    Examples
    --------
    >>> import vgroove
    >>> vgroove.energy_audit(max_k=65)
    Traceback (most recent call last):
    ...
    ValueError: max_k = 65 is out of range [1, $max_audit_k] with energy_audit
    """
    ndfs = [ndf] if isinstance(ndf, str) else list(ndf)
    for n in ndfs:
        text(n, "ndf")

    def axis(values, name):
        return None if values is None else [float(v) for v in np.atleast_1d(reals(values, name))]

    return _vgroove.energy_audit(ndfs, axis(alpha, "alpha"), axis(mu, "mu"), integer(alpha_points, "alpha_points"),
                                 integer(mu_points, "mu_points"), integer(rays, "rays"), integer(seed, "seed"),
                                 integer(max_k, "max_k"), text(reference, "reference"), integer(threads, "threads"),
                                 bool(verbose), progress=_progress(progress))


energy_audit.__doc__ = fill_ranges(energy_audit.__doc__, dict(_vgroove.audit_ranges))


def glass_energy(eta: Sequence[float], alpha: Sequence[float] = (0.1, 0.5, 1.0), mu: Sequence[float] = (1.0, 0.5),
                 *, ndf: Union[str, Sequence[str]] = "ggx", dim: Union[str, Sequence[str]] = "3d",
                 side: Union[str, Sequence[str]] = ("above", "below"), rays: int = 100000, grooves: int = 10000,
                 seed: int = 1, max_k: int = 16, threads: int = 0, verbose: bool = False,
                 reference: str = "vgroove", progress: Optional[ProgressFn] = None) -> dict:
    """Exact energy tables of rough glass, as ``vgroove energy --eta`` computes them
    (validation/glass_energy.h): E_R and E_T of V-groove surfaces between two dielectrics, per
    number of interactions k, for light from either side.

    Parameters
    ----------
    eta : sequence of float
        n2 / n1 (the index below the surface over the index above it), each in
        [$min_glass_eta, $max_glass_eta], not 1.
    alpha : sequence of float
        Roughnesses, each in [$min_alpha, $max_alpha].
    mu : sequence of float
        Cosines of the light's angle from the normal of its own side, each in [$min_mu, 1].
    ndf : str or sequence of str
        "ggx", "beckmann".
    dim : str or sequence of str
        "3d" (patches of parallel grooves, azimuth uniform per ray), "flatland".
    side : str or sequence of str
        "above" (light in medium 1), "below" (light in medium 2, from far below).
    rays : int
        Rays per cell, in [1, $max_energy_rays].
    grooves : int
        Grooves of each surface, in [1, $max_glass_grooves].
    seed : int
        In [0, 2^63 - 1]: the surfaces and the rays.
    max_k : int
        Orders tabulated one by one (a last row holds k > max_k), in [1, $max_energy_k].
    threads : int
        In [0, $max_threads] (0: all cores); the counts do not depend on it.
    verbose : bool
        Print the command line's table.
    reference : {"vgroove", "smith_walk"}
        The traced V-groove surfaces, or Heitz et al. 2016's dielectric Smith random walk (3D and
        flatland; ``vgroove energy --eta --reference smith_walk``; grooves not used).
    progress : callable, optional
        ``progress(done, total)``, counting work units.

    Returns
    -------
    dict
        The JSON ``vgroove energy --eta --out`` writes: "grid", "definitions", "arrays" (E_R, E_T,
        se_R, se_T, bounce_limit, vertex indexed [ndf][dim][side][eta][alpha][mu]; E_R_by_k and
        E_T_by_k with a last axis of rows k), "averages" (hemispherical, traced cosine-weighted)
        and "reciprocity" (T_avg(above) against eta^2 T_avg(below) in 3D, eta^1 in flatland).

    Raises
    ------
    ValueError
        The command line's message for the same input, naming the argument and its range.

    Examples
    --------
    >>> import vgroove
    >>> t = vgroove.glass_energy([1.5], [0.01], [1.0], side="above", rays=20000, grooves=500)
    >>> round(t["arrays"]["E_R"]["values"][0], 2)  # Fresnel's 0.04 at normal incidence
    0.04
    >>> vgroove.glass_energy([1.0])
    Traceback (most recent call last):
    ...
    ValueError: eta = 1 is no interface (light passes straight through): leave it out
    """
    names = lambda v: [v] if isinstance(v, str) else [text(x, "list item") for x in v]  # noqa: E731
    return _vgroove.glass_energy(
        [float(x) for x in np.atleast_1d(reals(eta, "eta"))], [float(a) for a in np.atleast_1d(reals(alpha, "alpha"))],
        [float(m) for m in np.atleast_1d(reals(mu, "mu"))], names(ndf), names(dim), names(side),
        integer(rays, "rays"), integer(grooves, "grooves"), integer(seed, "seed"), integer(max_k, "max_k"),
        integer(threads, "threads"), bool(verbose), text(reference, "reference"), progress=_progress(progress))


glass_energy.__doc__ = fill_ranges(glass_energy.__doc__)
