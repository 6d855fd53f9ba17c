"""Importance sampling of the V-groove BRDF (Lee et al. 2018, Sec. 6), of Walter et al. 2007's
rough dielectric BSDF and of the kaleidoscopic dielectric model over arrays, the density of the
directions the first two draw, and the uniform numbers of vgroove's deterministic streams
(sim/rng.h). vgroove.BRDF.sample and vgroove.BRDF.pdf make the same calls with the light first (the
V-groove models)."""

from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

from . import _vgroove
from ._args import ArrayLike, ProgressFn, integer, progress as _progress, real, reals, text
from ._ranges import fill_ranges

#: The symmetric samplers' default max_k (analytic/sampling_3d.h, kSamplerMaxK; ``vgroove sample``'s).
SAMPLER_MAX_K: int = _vgroove.SAMPLER_MAX_K
#: The nonsymmetric sampler's default max_k (analytic/sampling_nonsymmetric.h; its pdf costs O(max_k)).
NONSYMMETRIC_SAMPLER_MAX_K: int = _vgroove.NONSYMMETRIC_SAMPLER_MAX_K


def _sampler_max_k(max_k: Optional[int], model: str) -> int:
    """max_k as given, or the model's default (``vgroove sample --max-k``'s)."""
    if max_k is None:
        return NONSYMMETRIC_SAMPLER_MAX_K if model == "vgroove-nonsymmetric" else SAMPLER_MAX_K
    return integer(max_k, "max_k")


#: The dielectric's eta = n_far / n_near when ``model="walter"`` or ``"vgroove-dielectric"`` is given
#: none (``vgroove sample --eta``'s).
_WALTER_ETA = 1.5


def _walter_args(model, strategy, max_k, eta, masking):
    """Walter's eta and G2 for the extension, whether strategy and max_k were given (the extension
    refuses them with walter), and the other models' refusal of eta and masking (``vgroove
    sample``'s messages; tests/python/test_sample_walter.py holds them equal). None for the other
    models."""
    if model != "walter":
        if eta is not None and model != "vgroove-dielectric":
            raise ValueError(f"eta applies to model walter and vgroove-dielectric only (model = \"{model}\")")
        if masking is not None:
            raise ValueError(f"masking applies to model walter only (model = \"{model}\")")
        return None
    eta = _WALTER_ETA if eta is None else real(eta, "eta")
    masking = "smith_separable" if masking is None else text(masking, "masking")
    return eta, masking, strategy is not None, max_k is not None


def _dielectric_eta(strategy, max_k, eta, wi):
    """The kaleidoscopic dielectric model's eta (None: 1.5), with ``vgroove sample --model
    vgroove-dielectric``'s refusals of strategy and max_k (the extension checks eta's range with
    its message); the light only as theta_i_deg (the command line's --theta-i-deg)."""
    if strategy is not None:
        raise ValueError("strategy applies to model vgroove and vgroove-nonsymmetric only (vgroove-dielectric "
                         "draws its grooves from the NDF and its chains by their energy)")
    if max_k is not None:
        raise ValueError("max_k applies to model vgroove and vgroove-nonsymmetric only (vgroove-dielectric takes "
                         "every chain of grooves with k <= 32)")
    if wi is not None:
        raise ValueError("wi does not apply to model vgroove-dielectric: give the light as theta_i_deg (at "
                         "azimuth 180 deg, as vgroove sample --theta-i-deg)")
    return _WALTER_ETA if eta is None else real(eta, "eta")


def _light(wi, theta_i_deg):
    """The light as the extension takes it: (batch shape, wi, theta_i_deg) with wi an array
    (..., 3) or theta_i_deg an array of angles."""
    if (wi is None) == (theta_i_deg is None):
        raise ValueError("give the light as either wi (unit vectors) or theta_i_deg, not both or neither")
    if wi is not None:
        wi = reals(wi, "wi")
        if wi.shape[-1:] != (3,):
            raise ValueError(f"wi must be an array of unit vectors, shape (..., 3); got {wi.shape}")
        return wi.shape[:-1], wi, None
    t = reals(theta_i_deg, "theta_i_deg")
    return t.shape, None, t


def _light_rows(wi, ti, shape):
    """The light flattened to rows over `shape`: one row (or angle) when it is the same for all."""
    if wi is not None:
        if wi.size == 3:
            return np.ascontiguousarray(wi.reshape(1, 3)), None
        return np.ascontiguousarray(np.broadcast_to(wi, shape + (3,))).reshape(-1, 3), None
    if ti.size == 1:
        return None, np.ascontiguousarray(ti.reshape(1))
    return None, np.ascontiguousarray(np.broadcast_to(ti, shape)).reshape(-1)


def sample(ndf: str, alpha: float, u: np.ndarray, *, wi: Optional[np.ndarray] = None,
           theta_i_deg: Optional[ArrayLike] = None, strategy: Optional[str] = None, max_k: Optional[int] = None,
           dim: str = "3d", model: str = "vgroove", tolerance: float = 1e-9, threads: int = 0,
           eta: Optional[float] = None, masking: Optional[str] = None,
           progress: Optional[ProgressFn] = None) -> dict:
    """Importance-samples the V-groove BRDF (Lee et al. 2018, Sec. 6), with ``model="walter"``
    Walter et al. 2007's rough dielectric BSDF, or with ``model="vgroove-dielectric"`` the
    kaleidoscopic dielectric model: one exit direction per row of uniform numbers
    (:meth:`vgroove.BRDF.sample` takes the light first and returns a :class:`vgroove.SampleBatch`).

    Parameters
    ----------
    ndf : {"ggx", "beckmann", "phong"}
    alpha : float
        Roughness in [$min_alpha, $max_alpha].
    u : array_like, shape (..., 4), (..., 5) or (..., 3)
        Uniform numbers in [0, 1) (:func:`uniforms` gives vgroove's streams): four per sample for
        ``model="vgroove"``, five for ``"vgroove-nonsymmetric"``, three for ``"walter"`` (the
        facet, then the branch: ``vgroove sample --model walter --seed S`` draws them from the
        stream (S, (0x5a3d, 2))), five for ``"vgroove-dielectric"`` in 3d and four in flatland
        (``vgroove sample --model vgroove-dielectric --seed S``: the streams (S, (0x5a3d, 3)) and
        (S, (0x5a3d, 4))).
    wi : array_like, shape (..., 3), optional
        Unit vectors towards the light (flatland: in the plane y = 0), held to the range of
        theta_i_deg by the angle from the normal rounded to 1e-9 deg. Not with
        ``model="vgroove-dielectric"``.
    theta_i_deg : array_like, optional
        Or the light's angles (the suites' light at azimuth 180 deg, the bits ``vgroove sample
        --theta-i-deg`` uses), in [0, $max_surface_theta_i_deg] deg (flatland: signed, in
        [-$max_surface_theta_i_deg, $max_surface_theta_i_deg]). Exactly one of wi and theta_i_deg; the batch shapes broadcast to S.
    strategy : {"vndf", "printed", "smith-vndf", "bounded-vndf"}, optional
        How the facet met first is drawn: the V-cavity's visible normals (samples the BRDF
        exactly, weight 1 with F = 1), the paper's |s.n| D(s), Smith's VNDF (GGX), bounded VNDF
        (GGX, 3D). None: "vndf". Not with ``model="walter"``, whose facets come from the Smith
        VNDF (GGX) or |m.n| D(m) (Beckmann, Phong), nor ``"vgroove-dielectric"``.
    max_k : int, optional
        Paths of more reflections return zero weight (``beyond_max_k``), in [1, $max_sampler_k];
        None: ``vgroove sample --max-k``'s default, $sampler_max_k (:data:`SAMPLER_MAX_K`: fewer
        than one sample in 10^7 lost for GGX and Beckmann at any alpha and Phong up to alpha 1,
        analytic/sampling_3d.h), $nonsymmetric_sampler_max_k for the nonsymmetric model, whose pdf
        costs O(max_k). Not with ``model="walter"`` (single scattering) nor
        ``"vgroove-dielectric"`` (every chain of grooves with k <= 32).
    dim : {"3d", "flatland"}
        ``model="walter"``: "3d" only.
    model : {"vgroove", "vgroove-nonsymmetric", "walter", "vgroove-dielectric"}
        Symmetric grooves (analytic/sampling_3d.h, sampling_flatland.h), Eq. 21-23 with the
        independent partner law of Eq. 20 (analytic/sampling_nonsymmetric.h; Phong needs alpha <= 1),
        Walter's dielectric (analytic/walter_sampling.h: the light in the near medium, a facet
        drawn, reflected with probability F, else refracted) or V-grooves between two dielectrics
        (analytic/sampling_dielectric.h: the groove from the NDF, the facet by the width of the
        beam it takes, one chain's end by its energy; 3d and flatland).
    tolerance : float
        The nonsymmetric pdf's relative tolerance per piece, in [1e-12, 0.01] (about a
        millisecond a sample at 1e-9; ``vgroove sample`` uses 1e-6).
    threads : int
        In [0, $max_threads] (0: all cores), without the GIL; the values do not depend on it.
    eta : float, optional
        ``model="walter"`` and ``"vgroove-dielectric"`` only: n_far / n_near, in (0,
        $max_fresnel_eta], not 1 (None: 1.5; below 1: the light inside the denser medium).
    masking : {"smith", "smith_separable", "vcavity"}, optional
        ``model="walter"`` only: the G2 of the weights (None: smith_separable; the Smith ones need
        ggx or beckmann).
    progress : callable, optional
        ``progress(done, total)``, counting samples.

    Returns
    -------
    dict
        Arrays over S: ``wo`` (S + (3,), unit vectors; the mirror direction on a zero-weight
        return), ``k`` (int32 reflections; 0: no direction), ``pdf`` (density of wo per steradian,
        per radian in flatland; 0 on a zero-weight return), ``weight`` (rho cos(theta_o) / pdf,
        F = 1) and ``beyond_max_k`` (bool: a zero-weight return because the drawn path has more
        than max_k reflections; its mean is the share lost to max_k). With ``model="walter"``:
        ``wo`` (on either side, wo[..., 2] < 0 transmitted; the normal where no direction),
        ``k`` (1, or 0: the facet gives no direction), ``pdf`` (per steradian, 0 where no
        direction), ``weight`` (f |cos theta_o| / pdf with the G2 ``masking``; its mean is the
        albedo R + T) and ``transmitted`` (bool: the refracted branch gave wo). With
        ``model="vgroove-dielectric"``: ``wo`` (wo[..., 2] < 0 transmitted; flatland in the plane
        y = 0; the normal where no direction), ``k`` (the chain's interactions; 0: no direction:
        transmitted light heading back up, a groove of k > 32, rounding), ``weight`` (1, or 0 where
        no direction: the draws' density is the model's BSDF |cos theta_o|, so the mean weight is
        R + T and the draws binned are :func:`vgroove.dielectric_lobe`'s bins) and ``reflected``
        (bool); their density is :func:`pdf`'s.

    Raises
    ------
    ValueError
        ``vgroove sample``'s messages for the same input, with the argument's name.

    Examples
    --------
    >>> import vgroove
    >>> x = vgroove.sample("ggx", 0.5, vgroove.uniforms(1000, seed=1), theta_i_deg=30)
    >>> x["wo"].shape, bool(abs(x["weight"].mean() - 1) < 1e-12)
    ((1000, 3), True)
    >>> g = vgroove.sample("ggx", 0.5, vgroove.uniforms(1000, seed=1, dims=3), theta_i_deg=30, model="walter", eta=1.5)
    >>> bool(g["transmitted"].any() and (g["wo"][g["transmitted"], 2] < 0).all())
    True
    >>> d = vgroove.sample("ggx", 0.3, vgroove.uniforms(1000, seed=1, stream=(0x5a3d, 3), dims=5), theta_i_deg=40,
    ...                    model="vgroove-dielectric", eta=1.5)
    >>> bool((d["weight"][d["k"] > 0] == 1).all() and (d["wo"][~d["reflected"] & (d["k"] > 0), 2] < 0).all())
    True
    """
    walter = _walter_args(model, strategy, max_k, eta, masking)
    dielectric = model == "vgroove-dielectric"
    if dielectric:
        eta = _dielectric_eta(strategy, max_k, eta, wi)
        m = 4 if dim == "flatland" else 5
    else:
        m = 3 if model == "walter" else 5 if model == "vgroove-nonsymmetric" else 4
    u = reals(u, "u")
    if u.shape[-1:] != (m,):
        raise ValueError(f"u must be an array of uniform numbers, shape (..., {m}); got {u.shape}")
    lshape, wi_, ti = _light(wi, theta_i_deg)
    shape = np.broadcast_shapes(u.shape[:-1], lshape)
    u = np.ascontiguousarray(np.broadcast_to(u, shape + (m,))).reshape(-1, m)
    wi_, ti = _light_rows(wi_, ti, shape)
    if dielectric:
        out = _vgroove.dielectric_sample(ndf, real(alpha, "alpha"), eta, ti, u, dim,
                                         threads=integer(threads, "threads"), progress=_progress(progress))
    elif walter is not None:
        out = _vgroove.walter_sample(ndf, real(alpha, "alpha"), wi_, ti, u, *walter, dim, integer(threads, "threads"),
                                     progress=_progress(progress))
    else:
        out = _vgroove.sample(model, ndf, real(alpha, "alpha"), wi_, ti, u, "vndf" if strategy is None else strategy,
                              _sampler_max_k(max_k, model), real(tolerance, "tolerance"), dim,
                              integer(threads, "threads"), progress=_progress(progress))
    return {key: a.reshape(shape + a.shape[1:]) for key, a in out.items()}


def pdf(ndf: str, alpha: float, wo: np.ndarray, *, wi: Optional[np.ndarray] = None,
        theta_i_deg: Optional[ArrayLike] = None, strategy: Optional[str] = None, max_k: Optional[int] = None,
        dim: str = "3d", model: str = "vgroove", tolerance: float = 1e-9, threads: int = 0,
        eta: Optional[float] = None, masking: Optional[str] = None,
        progress: Optional[ProgressFn] = None) -> np.ndarray:
    """The density of the directions :func:`sample` produces (:meth:`vgroove.BRDF.pdf` takes the
    light first).

    Parameters
    ----------
    ndf, alpha
        As in :func:`sample`.
    wo : array_like, shape (..., 3)
        Unit vectors towards the viewer (flatland: in the plane y = 0).
    wi, theta_i_deg, strategy, max_k, dim, model, tolerance, threads, eta, masking
        As in :func:`sample`; the shapes broadcast to S.
    progress : callable, optional
        ``progress(done, total)``, counting directions.

    Returns
    -------
    numpy.ndarray
        Shape S: per steradian (per radian in flatland), the sum over every path of k <= max_k
        reflections that ends at wo (analytic/sampling_3d.h); 0 below the horizon, +inf exactly
        at the mirror direction in 3D (where the BRDF diverges too). With ``strategy="vndf"`` the
        symmetric model's pdf equals rho(wi, wo) cos(theta_o) (F = 1). With ``model="walter"``
        over the whole sphere (wo[..., 2] < 0: transmitted), per steradian. With
        ``model="vgroove-dielectric"`` over the whole sphere (circle in flatland) as :func:`sample`
        draws it: f |cos theta_o| of the model's BSDF (analytic/kaleidoscope_dielectric_point.h,
        :func:`vgroove.dielectric_bsdf`'s ``pdf``), integrating to R + T (the rest are the
        sampler's zero-weight draws); 0 on the horizon.

    Raises
    ------
    ValueError
        As :func:`sample`.

    Examples
    --------
    >>> import vgroove
    >>> p = vgroove.pdf("ggx", 0.5, vgroove.direction(40, 0), theta_i_deg=30, max_k=64)
    >>> rho = vgroove.brdf("vgroove", "ggx", 0.5, vgroove.direction(30, 180), vgroove.direction(40, 0), max_k=64)
    >>> bool(abs(p - rho * vgroove.direction(40, 0)[2]) < 1e-12 * p)
    True
    """
    walter = _walter_args(model, strategy, max_k, eta, masking)
    dielectric = model == "vgroove-dielectric"
    if dielectric:
        eta = _dielectric_eta(strategy, max_k, eta, wi)
    wo = reals(wo, "wo")
    if wo.shape[-1:] != (3,):
        raise ValueError(f"wo must be an array of unit vectors, shape (..., 3); got {wo.shape}")
    lshape, wi_, ti = _light(wi, theta_i_deg)
    shape = np.broadcast_shapes(wo.shape[:-1], lshape)
    wo = np.ascontiguousarray(np.broadcast_to(wo, shape + (3,))).reshape(-1, 3)
    wi_, ti = _light_rows(wi_, ti, shape)
    if dielectric:
        return _vgroove.dielectric_pdf(ndf, real(alpha, "alpha"), eta, ti, wo, dim, threads=integer(threads, "threads"),
                                       progress=_progress(progress)).reshape(shape)
    if walter is not None:
        return _vgroove.walter_pdf(ndf, real(alpha, "alpha"), wi_, ti, wo, *walter, dim, integer(threads, "threads"),
                                   progress=_progress(progress)).reshape(shape)
    return _vgroove.pdf(model, ndf, real(alpha, "alpha"), wi_, ti, wo, "vndf" if strategy is None else strategy,
                        _sampler_max_k(max_k, model), real(tolerance, "tolerance"), dim, integer(threads, "threads"),
                        progress=_progress(progress)).reshape(shape)


def uniforms(n: int, seed: int = 1, stream: Sequence[int] = (0, 0), dims: int = 4) -> np.ndarray:
    """Uniform numbers in [0, 1) from vgroove's deterministic stream sim::Rng(seed, stream[0],
    stream[1]) (sim/rng.h), drawn row after row.

    Parameters
    ----------
    n : int
        Rows, in [0, $max_rays].
    seed : int
        In [0, 2^63 - 1].
    stream : (int, int)
        ``vgroove sample --seed S`` draws its samples' four numbers from the stream (S, (0x5a3d,
        0)) in 3D and (S, (0x5a3d, 1)) in flatland; with ``--model walter`` three numbers from
        (S, (0x5a3d, 2)); with ``--model vgroove-dielectric`` five from (S, (0x5a3d, 3)) in 3D and
        four from (S, (0x5a3d, 4)) in flatland.
    dims : int
        Numbers per row, in [1, 64].

    Returns
    -------
    numpy.ndarray
        Shape (n, dims).

    Raises
    ------
    ValueError
        An argument out of range.

    Examples
    --------
    >>> import vgroove
    >>> u = vgroove.uniforms(3, seed=1)
    >>> u.shape, bool(((u >= 0) & (u < 1)).all())
    ((3, 4), True)
    """
    if len(stream) != 2:
        raise ValueError(f"stream = {tuple(stream)!r} must be two integers")
    return _vgroove.uniforms(integer(n, "n"), integer(seed, "seed"), integer(stream[0], "stream[0]"),
                             integer(stream[1], "stream[1]"), integer(dims, "dims"))


for _f in (sample, pdf, uniforms):
    _f.__doc__ = fill_ranges(_f.__doc__, dict(sampler_max_k=SAMPLER_MAX_K,
                                              nonsymmetric_sampler_max_k=NONSYMMETRIC_SAMPLER_MAX_K))
