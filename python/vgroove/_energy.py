"""energy_lobe_shape(): the compensated lobes' shape beyond energy, as ``vgroove energy --lobe-shape``
computes it (validation/energy_lobe_shape.h), the report as a dict."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from . import _vgroove
from ._args import integer, real, reals
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
