"""What vgroove.BRDF's methods return: frozen dataclasses with the same fields in flatland and 3D,
their arrays read-only, and ``as_dict()`` giving the dict (the keys of the report JSON) that the
functions :func:`vgroove.trace_microsurface`, :func:`vgroove.lobe` and :func:`vgroove.sample` return."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np


def _frozen(a):
    a = np.asarray(a)
    a.setflags(write=False)
    return a


def _hist_keys(dim):
    return ("theta_o", "theta_o_by_k") if dim == "flatland" else ("hist", "hist_by_k")


@dataclass(frozen=True)
class SurfaceTrace:
    """Light traced in a procedural V-groove surface, tallied into a lobe's bins (counts of rays).

    Attributes
    ----------
    dim : str
        ``"3d"`` or ``"flatland"``.
    rays, escaped, blocked, vertex_hit, bounce_limit, not_upward, bounces, max_k_seen : int
        The rays traced, their fates (they add up to ``rays``), the reflections of all of them and
        the most reflections one ray made.
    by_k : numpy.ndarray
        Rays per reflection count, rows k = 0..k_rows and a last row for every k > k_rows.
    hist : numpy.ndarray
        Escaped rays per exit bin: flatland ``(flatland_bins,)`` over theta_o in (-90, 90) deg; 3D
        ``(theta_bins, phi_bins)``, theta_o over [0, 90) deg and phi_o centred on 0 (the mirror side).
    hist_by_k : numpy.ndarray
        The same per row of ``by_k``: shape ``(k_rows + 2,) + hist.shape``.

    Examples
    --------
    >>> import vgroove
    >>> t = vgroove.BRDF("vgroove", "ggx", 0.5, dim="flatland").trace(30, rays=1000, grooves=1000)
    >>> t.rays == t.escaped + t.blocked + t.vertex_hit + t.bounce_limit + t.not_upward
    True
    >>> sorted(t.as_dict())[:4]
    ['blocked', 'bounce_limit', 'bounces', 'by_k']
    """

    dim: str
    rays: int
    escaped: int
    blocked: int
    vertex_hit: int
    bounce_limit: int
    not_upward: int
    bounces: int
    max_k_seen: int
    by_k: np.ndarray
    hist: np.ndarray
    hist_by_k: np.ndarray

    @classmethod
    def from_dict(cls, d: dict, dim: str) -> "SurfaceTrace":
        """The trace from the dict :func:`vgroove.trace_microsurface` returns for a surface of ``dim``."""
        h, hk = _hist_keys(dim)
        counts = {k: int(d[k]) for k in ("rays", "escaped", "blocked", "vertex_hit", "bounce_limit", "not_upward",
                                         "bounces", "max_k_seen")}
        return cls(dim=dim, by_k=_frozen(d["by_k"]), hist=_frozen(d[h]), hist_by_k=_frozen(d[hk]), **counts)

    def as_dict(self) -> dict:
        """The dict :func:`vgroove.trace_microsurface` returns (flatland: ``theta_o``,
        ``theta_o_by_k``; 3D: ``hist``, ``hist_by_k``)."""
        h, hk = _hist_keys(self.dim)
        d = {k: getattr(self, k) for k in ("rays", "escaped", "blocked", "vertex_hit", "bounce_limit", "not_upward",
                                           "bounces", "max_k_seen", "by_k")}
        d[h], d[hk] = self.hist, self.hist_by_k
        return d


@dataclass(frozen=True)
class Lobe:
    """A BRDF integrated over the bins of a :class:`SurfaceTrace`: fractions of the incident flux.

    Attributes
    ----------
    dim : str
        ``"3d"`` or ``"flatland"``.
    by_k : numpy.ndarray
        Flux per reflection count, rows k = 0..k_rows and a last row for the orders beyond.
    hist : numpy.ndarray
        Flux per exit bin, every order (the bins of :class:`SurfaceTrace`).
    hist_by_k : numpy.ndarray
        The same per row of ``by_k``.
    albedo : float
        The flux leaving in all (the sum of ``by_k``).

    Examples
    --------
    >>> import vgroove
    >>> lobe = vgroove.BRDF("cook-torrance", "ggx", 1.0).lobe(0, theta_bins=9, phi_bins=8)
    >>> lobe.hist.shape, round(lobe.albedo, 4)
    ((9, 8), 0.375)
    """

    dim: str
    by_k: np.ndarray
    hist: np.ndarray
    hist_by_k: np.ndarray
    albedo: float

    @classmethod
    def from_dict(cls, d: dict, dim: str) -> "Lobe":
        """The lobe from the dict :func:`vgroove.lobe` returns for ``dim``."""
        h, hk = _hist_keys(dim)
        return cls(dim=dim, by_k=_frozen(d["by_k"]), hist=_frozen(d[h]), hist_by_k=_frozen(d[hk]),
                   albedo=float(d["albedo"]))

    def as_dict(self) -> dict:
        """The dict :func:`vgroove.lobe` returns (flatland: ``theta_o``, ``theta_o_by_k``; 3D:
        ``hist``, ``hist_by_k``; and ``by_k``, ``albedo``)."""
        h, hk = _hist_keys(self.dim)
        return {"by_k": self.by_k, h: self.hist, hk: self.hist_by_k, "albedo": self.albedo}


@dataclass(frozen=True)
class SampleBatch:
    """Directions drawn by a BRDF's importance sampler, one per row of uniform numbers (shape S).

    Attributes
    ----------
    wo : numpy.ndarray
        Exit directions, S + (3,), unit vectors (the mirror direction on a zero-weight return).
    k : numpy.ndarray
        Reflections of each drawn path (int32; 0: no direction).
    pdf : numpy.ndarray
        Density of ``wo`` per steradian (per radian in flatland); 0 on a zero-weight return.
    weight : numpy.ndarray
        rho cos(theta_o) / pdf, Fresnel included when the BRDF has one.
    beyond_max_k : numpy.ndarray or None
        bool: a zero-weight return because the drawn path has more than max_k reflections (None
        for ``"walter"``, single scattering).
    transmitted : numpy.ndarray or None
        ``"walter"`` only: bool, the draw refracted into the far medium (``wo`` below the surface).

    Examples
    --------
    >>> import vgroove
    >>> b = vgroove.BRDF().sample(vgroove.direction(30, 180), vgroove.uniforms(1000))
    >>> b.wo.shape, bool(abs(b.weight.mean() - 1) < 1e-12)
    ((1000, 3), True)
    """

    wo: np.ndarray
    k: np.ndarray
    pdf: np.ndarray
    weight: np.ndarray
    beyond_max_k: Optional[np.ndarray] = None
    transmitted: Optional[np.ndarray] = None

    @classmethod
    def from_dict(cls, d: dict) -> "SampleBatch":
        """The batch from the dict :func:`vgroove.sample` returns."""
        return cls(**{k: _frozen(a) for k, a in d.items() if k in _SAMPLE_KEYS})

    def as_dict(self) -> dict:
        """The dict :func:`vgroove.sample` returns."""
        return {k: getattr(self, k) for k in _SAMPLE_KEYS if getattr(self, k) is not None}


#: The keys of :func:`vgroove.sample`'s dict, in its order (``beyond_max_k`` for the V-groove
#: samplers, ``transmitted`` for ``"walter"``).
_SAMPLE_KEYS = ("wo", "k", "pdf", "weight", "beyond_max_k", "transmitted")
