"""vgroove.BRDF: one BRDF, its settings checked once, evaluated, sampled and integrated over the
suites' bins, and the exact simulation of the surface it models; the same library calls as the
functions :func:`vgroove.brdf`, :func:`vgroove.sample`, :func:`vgroove.pdf`,
:func:`vgroove.lobe` and :func:`vgroove.trace_microsurface` (and the command line), with one
argument order (the light ``wi`` first, then ``wo`` or the uniform numbers)."""

from __future__ import annotations

from typing import Optional

import numpy as np

from . import _args
from . import _vgroove
from ._ranges import RANGES, fill_ranges
from ._results import Lobe, SampleBatch, SurfaceTrace
from ._sampling import _sampler_max_k, _WALTER_ETA

_MODELS = ("vgroove", "vgroove-nonsymmetric", "cook-torrance", "walter")


class BRDF:
    """A BRDF of vgroove: the multiple-scattering V-groove model of Lee et al. 2018 or Cook-Torrance;
    or Walter et al. 2007's rough dielectric BSDF.

    Parameters
    ----------
    model : {"vgroove", "vgroove-nonsymmetric", "cook-torrance", "walter"}
        ``"vgroove"``: symmetric grooves, Eq. 16-17 (3D, analytic/brdf_3d.h; flatland,
        analytic/brdf_flatland.h). ``"vgroove-nonsymmetric"``: Eq. 21-23 with the partner law of
        Eq. 20 (analytic/brdf_nonsymmetric.h). ``"cook-torrance"`` (also ``"cook_torrance"``): Eq.
        1-3 with the V-cavity G, single scattering. ``"walter"``: Walter et al. 2007, Eq. 20-21
        (analytic/walter.h), reflection and transmission, single scattering: :meth:`eval`, :meth:`sample`
        and :meth:`pdf` (analytic/walter_sampling.h); not binned.
    ndf : {"ggx", "beckmann", "phong"}
        The facet normals' distribution (Phong exponent 2/alpha^2 - 2).
    alpha : float
        Roughness in [$min_alpha, $max_alpha]; with ``alpha_y``, the roughness along the x axis.
    alpha_y : float, optional
        ``"vgroove-nonsymmetric"`` in 3D, GGX and Beckmann only: the roughness along y, in
        [$min_alpha, $max_alpha] (anisotropic, analytic/ndf_anisotropic.h; azimuths measured from x).
    partner : {"independent", "symmetric"}, optional
        ``"vgroove-nonsymmetric"`` only: the partner facet's tilt drawn independently (Eq. 20, the
        default; Phong needs alpha < sqrt(2)) or equal to the first's (Eq. 24: the symmetric model).
    max_k : int, optional
        The orders summed, k = 1..max_k. None: the model's default, the same on every face (the
        command line, C++ ``analytic::default_max_k``, Python; :data:`vgroove.BRDF_MAX_K`): every
        order ($all_orders) for ``"vgroove"`` in 3D, whose sum costs the same for any max_k;
        $flatland_max_k in flatland (one pass over the facet solutions, a few us a direction for any
        max_k) and $nonsymmetric_max_k for ``"vgroove-nonsymmetric"``, whose sum costs O(max_k^2)
        per direction (about 1 ms at 64). Ranges: [1, 2^31 - 1], at most $max_flatland_k in flatland and $max_nonsymmetric_k
        for the nonsymmetric model. The samplers' default is $sampler_max_k
        ($nonsymmetric_sampler_max_k for the nonsymmetric model; their pdf costs O(max_k)), in [1,
        $max_sampler_k]. :meth:`lobe`, :meth:`albedo` and :meth:`trace` hold every order when
        max_k is None, else the orders up to max_k (at most $max_histogram_k).
    eta : complex, optional
        A conductor's Fresnel term per reflection, index eta + i kappa (``0.2+3j``; a real number:
        kappa = 0), real part in (0, $max_fresnel_eta], kappa in [0, $max_fresnel_kappa]; 3D only. None:
        F = 1 (a perfect mirror). It scales :meth:`eval` and the weights of :meth:`sample`; the
        directions drawn and :meth:`pdf` do not depend on it; :meth:`lobe`, :meth:`albedo` and
        :meth:`trace` take F = 1 only. With ``"walter"``: the dielectric's real eta = n_far / n_near
        in (0, $max_fresnel_eta] (None: 1.5), the light in the near medium (eta < 1: from inside the
        denser one), 3D or flatland.
    masking : {"smith", "smith_separable", "vcavity"}, optional
        ``"walter"`` only: the G2, Smith height-correlated, separable (None: Walter's Eq. 23) or the
        V-cavity's; the Smith ones need GGX or Beckmann.
    dim : {"3d", "flatland"}
        3D (values per steradian) or flatland (directions in the plane y = 0, per radian).

    Raises
    ------
    ValueError
        One line naming the argument and its range (the command line's message for the same
        input), e.g. ``alpha = 2.5 is out of range [0.01, 2]``.

    Notes
    -----
    Directions are unit vectors (arrays (..., 3)) in the frame n = (0, 0, 1), both pointing away
    from the surface: ``wi`` towards the light, ``wo`` towards the viewer (:func:`vgroove.direction`);
    shapes broadcast. Every method runs without the GIL on ``threads`` threads (0: all cores; the
    values do not depend on it), stops on Ctrl-C and takes ``progress``, a callable
    ``progress(done, total)`` (:func:`vgroove.tqdm_progress`). The values equal the functions' and
    the command line's for the same inputs, to the last bit.

    Examples
    --------
    >>> import vgroove
    >>> f = vgroove.BRDF("vgroove", "ggx", 0.5)
    >>> wi, wo = vgroove.direction(30, 180), vgroove.direction(40, 0)
    >>> round(float(f.eval(wi, wo)), 6)
    0.884746
    >>> f
    vgroove.BRDF(model="vgroove", ndf="ggx", alpha=0.5, dim="3d")
    >>> f.max_k
    1000000
    >>> vgroove.BRDF("vgroove", "ggx", 2.5)
    Traceback (most recent call last):
    ...
    ValueError: alpha = 2.5 is out of range [0.01, 2]
    """

    __slots__ = ("_model", "_ndf", "_alpha", "_alpha_y", "_partner", "_max_k", "_max_k_given", "_eta", "_masking",
                 "_dim")

    def __init__(self, model: str = "vgroove", ndf: str = "ggx", alpha: float = 0.5, *,
                 alpha_y: Optional[float] = None, partner: Optional[str] = None, max_k: Optional[int] = None,
                 eta: Optional[complex] = None, masking: Optional[str] = None, dim: str = "3d") -> None:
        model = _args.text(model, "model")
        ndf = _args.text(ndf, "ndf")
        dim = _args.text(dim, "dim")
        alpha = _args.real(alpha, "alpha")
        alpha_y = _args.opt_real(alpha_y, "alpha_y")
        partner = _args.text(partner, "partner")
        max_k = _args.opt_integer(max_k, "max_k")
        eta = _args.opt_complex(eta, "eta")
        masking = _args.text(masking, "masking")
        s = _vgroove.brdf_settings(model, ndf, alpha, dim, max_k, alpha_y, partner, eta, masking)
        self._model, self._ndf, self._dim = s["model"], s["ndf"], s["dim"]
        self._alpha, self._alpha_y, self._partner, self._eta, self._masking = alpha, alpha_y, partner, eta, masking
        self._max_k, self._max_k_given = int(s["max_k"]), max_k is not None

    # The settings, read-only.
    model = property(lambda self: self._model, doc="The model's name, as the command line spells it.")
    ndf = property(lambda self: self._ndf, doc="The NDF's name.")
    alpha = property(lambda self: self._alpha, doc="The roughness (along x with alpha_y).")
    alpha_y = property(lambda self: self._alpha_y, doc="The roughness along y, or None (isotropic).")
    partner = property(lambda self: self._partner, doc="The nonsymmetric model's partner law, or None (independent).")
    eta = property(lambda self: self._eta,
                   doc="The conductor's index eta + i kappa (walter: the dielectric's n_far / n_near), or None.")
    masking = property(lambda self: self._masking, doc="Walter's G2 as given, or None (smith_separable).")
    dim = property(lambda self: self._dim, doc="\"3d\" or \"flatland\".")
    max_k = property(lambda self: self._max_k, doc="The orders :meth:`eval` sums (the model's default when not given).")

    def _key(self):
        return (self._model, self._ndf, self._alpha, self._alpha_y, self._partner,
                self._max_k if self._max_k_given else None, self._eta, self._masking, self._dim)

    def __eq__(self, other):
        return isinstance(other, BRDF) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def __repr__(self) -> str:
        parts = [f'model="{self._model}"', f'ndf="{self._ndf}"', f"alpha={self._alpha!r}"]
        for name in ("alpha_y", "partner", "eta", "masking"):
            v = getattr(self, "_" + name)
            if v is not None:
                parts.append(f'{name}="{v}"' if isinstance(v, str) else f"{name}={v!r}")
        if self._max_k_given:
            parts.append(f"max_k={self._max_k}")
        parts.append(f'dim="{self._dim}"')
        return "vgroove.BRDF(" + ", ".join(parts) + ")"

    def eval(self, wi: _args.ArrayLike, wo: _args.ArrayLike, *, threads: int = 0,
             progress: Optional[_args.ProgressFn] = None) -> np.ndarray:
        """The BRDF's value for each pair of directions.

        Parameters
        ----------
        wi, wo : array_like, shape (..., 3)
            Unit vectors (``|len - 1| <= $unit_tolerance``) towards the light and towards the
            viewer; their shapes broadcast to S + (3,). Flatland: in the plane y = 0.
        threads : int
            Worker threads in [0, $max_threads] (0: all cores).
        progress : callable, optional
            ``progress(done, total)``, counting directions.

        Returns
        -------
        numpy.ndarray
            Shape S: values in 1/sr (3D) or 1/rad (flatland), the sum over k = 1..max_k (with F
            when the BRDF has ``eta``); 0 where wi or wo is at or below the horizon; +inf exactly
            at the mirror direction of the multiple-scattering terms (integrable; never NaN).

        Raises
        ------
        ValueError
            A direction that is not a unit vector (naming the first such row), shapes that do not
            broadcast, threads out of range.

        Examples
        --------
        >>> import numpy as np, vgroove
        >>> f = vgroove.BRDF("cook-torrance", "beckmann", 0.3)
        >>> wo = vgroove.direction(np.array([10.0, 30.0, 50.0]), 0)
        >>> f.eval(vgroove.direction(30, 180), wo).round(4)
        array([0.7802, 1.1789, 1.1954])
        >>> bool(f.eval(wo[1], vgroove.direction(30, 180)) == f.eval(vgroove.direction(30, 180), wo[1]))
        True
        """
        wi, wo = _args.vectors(wi, "wi"), _args.vectors(wo, "wo")
        shape = np.broadcast_shapes(wi.shape, wo.shape)[:-1]
        out = _vgroove.brdf(self._model, self._ndf, self._alpha, _args.rows(wi, shape, 3), _args.rows(wo, shape, 3), 0,
                            self._max_k, self._dim, _args.integer(threads, "threads"), self._alpha_y, self._partner,
                            self._eta, self._masking, _args.progress(progress))
        return out.reshape(shape)

    def _walter_call(self, what, strategy):
        """Walter's arguments for the extension's walter_sample and walter_pdf: eta, masking and
        whether strategy or max_k was given (the extension refuses both with walter)."""
        eta = _WALTER_ETA if self._eta is None else self._eta.real
        masking = "smith_separable" if self._masking is None else self._masking
        return eta, masking, strategy is not None, self._max_k_given

    def _sampler(self, what):
        if self._model == "cook-torrance":
            raise ValueError(f"{what}: model = \"{self._model}\" has no sampler here (models \"vgroove\", "
                             "\"vgroove-nonsymmetric\", \"walter\")")
        if self._alpha_y is not None or self._partner == "symmetric":
            raise ValueError(f"{what}: the nonsymmetric sampler takes the isotropic, independent partner law only "
                             "(alpha_y None, partner \"independent\")")
        return self._max_k if self._max_k_given else None

    def sample(self, wi: _args.ArrayLike, u: _args.ArrayLike, *, strategy: Optional[str] = None,
               tolerance: float = 1e-9, threads: int = 0,
               progress: Optional[_args.ProgressFn] = None) -> SampleBatch:
        """Importance-samples the BRDF (Lee et al. 2018, Sec. 6): one exit direction per row of ``u``.

        Parameters
        ----------
        wi : array_like, shape (..., 3)
            Unit vectors towards the light, polar angle in [0, $max_surface_theta_i_deg] deg (flatland:
            signed, in [-$max_surface_theta_i_deg, $max_surface_theta_i_deg]), held to it by the angle rounded to 1e-9 deg.
        u : array_like, shape (..., 4), (..., 5) or (..., 3)
            Uniform numbers in [0, 1) (:func:`vgroove.uniforms`), four per sample (five for
            ``"vgroove-nonsymmetric"``, three for ``"walter"``: the facet, then the branch); the
            batch shapes of wi and u broadcast to S.
        strategy : {"vndf", "printed", "smith-vndf", "bounded-vndf"}, optional
            How the facet met first is drawn: the V-cavity's visible normals (samples the BRDF
            exactly: weight 1 with F = 1), the paper's |s.n| D(s), Smith's VNDF (GGX), bounded VNDF
            (GGX, 3D); ``vgroove sample --strategy``. None: "vndf". Not with ``"walter"`` (its
            facets come from the Smith visible normals, analytic/walter_sampling.h).
        tolerance : float
            ``"vgroove-nonsymmetric"``: the pdf's relative tolerance per piece, in [1e-12, 0.01].
        threads : int
            Worker threads in [0, $max_threads] (0: all cores).
        progress : callable, optional
            ``progress(done, total)``, counting samples.

        Returns
        -------
        SampleBatch
            ``wo``, ``k``, ``pdf``, ``weight`` and ``beyond_max_k`` over S (:class:`SampleBatch`;
            ``"walter"``: ``transmitted`` in place of ``beyond_max_k``, ``wo`` in both hemispheres);
            ``as_dict()`` is what :func:`vgroove.sample` returns.

        Raises
        ------
        ValueError
            ``model="cook-torrance"`` (no sampler), the anisotropic or symmetric-partner
            nonsymmetric model, a light out of range, u outside [0, 1), strategy unknown or not
            defined for the NDF and dimension, max_k out of [1, $max_sampler_k].

        Examples
        --------
        >>> import numpy as np, vgroove
        >>> f = vgroove.BRDF("vgroove", "ggx", 0.5)
        >>> b = f.sample(vgroove.direction(30, 180), vgroove.uniforms(4, seed=7))
        >>> b.k.tolist()
        [1, 1, 1, 5]
        >>> bool(np.allclose(f.pdf(vgroove.direction(30, 180), b.wo), b.pdf, rtol=1e-9))
        True
        """
        max_k = self._sampler("sample")
        u = _args.reals(u, "u")
        m = 3 if self._model == "walter" else 5 if self._model == "vgroove-nonsymmetric" else 4
        if u.shape[-1:] != (m,):
            raise ValueError(f"u must be an array of uniform numbers, shape (..., {m}); got {u.shape}")
        wi = _args.vectors(wi, "wi")
        shape = np.broadcast_shapes(u.shape[:-1], wi.shape[:-1])
        u = np.ascontiguousarray(np.broadcast_to(u, shape + (m,))).reshape(-1, m)
        if self._model == "walter":
            out = _vgroove.walter_sample(self._ndf, self._alpha, _args.rows(wi, shape, 3), None, u,
                                         *self._walter_call("sample", strategy), self._dim,
                                         _args.integer(threads, "threads"), progress=_args.progress(progress))
            return SampleBatch.from_dict({key: a.reshape(shape + a.shape[1:]) for key, a in out.items()})
        out = _vgroove.sample(self._model, self._ndf, self._alpha, _args.rows(wi, shape, 3), None, u,
                              _args.text("vndf" if strategy is None else strategy, "strategy"),
                              _sampler_max_k(max_k, self._model),
                              _args.real(tolerance, "tolerance"), self._dim, _args.integer(threads, "threads"),
                              self._eta, _args.progress(progress))
        return SampleBatch.from_dict({key: a.reshape(shape + a.shape[1:]) for key, a in out.items()})

    def pdf(self, wi: _args.ArrayLike, wo: _args.ArrayLike, *, strategy: Optional[str] = None,
            tolerance: float = 1e-9, threads: int = 0,
            progress: Optional[_args.ProgressFn] = None) -> np.ndarray:
        """The density of the directions :meth:`sample` draws, at ``wo``.

        Parameters
        ----------
        wi : array_like, shape (..., 3)
            Unit vectors towards the light, as in :meth:`sample`.
        wo : array_like, shape (..., 3)
            Unit vectors towards the viewer; the shapes broadcast to S + (3,).
        strategy, tolerance, threads
            As in :meth:`sample`.
        progress : callable, optional
            ``progress(done, total)``, counting directions.

        Returns
        -------
        numpy.ndarray
            Shape S: the density per steradian (per radian in flatland), the sum over every path
            of k <= max_k reflections that ends at wo; 0 below the horizon, +inf exactly at the
            mirror direction in 3D. With ``strategy="vndf"`` it equals eval(wi, wo) cos(theta_o)
            for F = 1 (the same max_k). ``"walter"``: over both hemispheres (``wo`` below the
            surface: the transmitted branch).

        Raises
        ------
        ValueError
            As :meth:`sample`.

        Examples
        --------
        >>> import vgroove
        >>> f = vgroove.BRDF("vgroove", "ggx", 0.5, max_k=64)
        >>> wi, wo = vgroove.direction(30, 180), vgroove.direction(40, 0)
        >>> p, rho = float(f.pdf(wi, wo)), float(f.eval(wi, wo))
        >>> abs(p - rho * wo[2]) < 1e-12 * p
        True
        """
        max_k = self._sampler("pdf")
        wi, wo = _args.vectors(wi, "wi"), _args.vectors(wo, "wo")
        shape = np.broadcast_shapes(wi.shape, wo.shape)[:-1]
        wo = np.ascontiguousarray(np.broadcast_to(wo, shape + (3,))).reshape(-1, 3)
        if self._model == "walter":
            return _vgroove.walter_pdf(self._ndf, self._alpha, _args.rows(wi, shape, 3), None, wo,
                                       *self._walter_call("pdf", strategy), self._dim,
                                       _args.integer(threads, "threads"),
                                       progress=_args.progress(progress)).reshape(shape)
        return _vgroove.pdf(self._model, self._ndf, self._alpha, _args.rows(wi, shape, 3), None, wo,
                            _args.text("vndf" if strategy is None else strategy, "strategy"), _sampler_max_k(max_k, self._model),
                            _args.real(tolerance, "tolerance"), self._dim, _args.integer(threads, "threads"),
                            _args.progress(progress)).reshape(shape)

    def _binned(self, what, truncates=True):
        """The orders a lobe or albedo holds: None (every order) or the BRDF's max_k when given.
        A trace is the surface's: every order whatever max_k says (truncates=False)."""
        if self._model == "vgroove-nonsymmetric":
            raise ValueError(f"{what}: model = \"vgroove-nonsymmetric\" is not binned here (models \"vgroove\", "
                             "\"cook-torrance\"; its lobes: `vgroove validate` with a nonsymmetric_brdf suite)")
        if self._model == "walter":
            raise ValueError(f"{what}: model = \"walter\" is not binned here (models \"vgroove\", \"cook-torrance\"; "
                             "Walter's BSDF is evaluated by eval)")
        if self._eta is not None:
            raise ValueError(f"{what}: eta = {self._eta!r}: lobes, albedos and traces are computed with F = 1 "
                             "(make the BRDF without eta)")
        if not truncates or not self._max_k_given or self._model != "vgroove":
            return None
        if self._max_k > RANGES["max_histogram_k"]:
            raise ValueError(f"{what}: max_k = {self._max_k} is out of range [1, {RANGES['max_histogram_k']}] "
                             "(the orders a lobe resolves; leave max_k None for every order)")
        return self._max_k

    def lobe(self, theta_i_deg: float, *, theta_bins: int = 30, phi_bins: int = 24, flatland_bins: int = 90,
             k_rows: int = 16, progress: Optional[_args.ProgressFn] = None) -> Lobe:
        """The BRDF integrated over the bins of exit directions the suites use: fractions of the flux.

        Parameters
        ----------
        theta_i_deg : float
            The light's polar angle in [0, $max_surface_theta_i_deg] deg at azimuth 180 deg (flatland:
            signed, in [-$max_surface_theta_i_deg, $max_surface_theta_i_deg]).
        theta_bins, phi_bins : int
            3D: theta_o bins over [0, 90) deg in [1, $max_theta_bins], phi_o bins centred on phi = 0 (the
            mirror side), even, in [2, $max_phi_bins].
        flatland_bins : int
            Flatland: theta_o bins over (-90, 90) deg, in [1, $max_flatland_bins].
        k_rows : int
            Rows k = 0..k_rows of ``by_k`` and ``hist_by_k``, in [$min_histogram_k, $max_histogram_k], and a last row for the orders
            beyond (every order, or those up to the BRDF's max_k when given).
        progress : callable, optional
            ``progress(done, total)``: the start (0 of 1) and the end (1 of 1).

        Returns
        -------
        Lobe
            ``by_k``, ``hist``, ``hist_by_k``, ``albedo`` (:class:`Lobe`; ``as_dict()`` is what
            :func:`vgroove.lobe` returns). Cook-Torrance: its single-scattering lobe, albedo < 1.

        Raises
        ------
        ValueError
            ``model="vgroove-nonsymmetric"``, ``eta`` given, bins, k_rows or theta_i_deg out of
            range, or a lobe that would need more memory than this process may use (the estimate
            in the message).

        Examples
        --------
        >>> import vgroove
        >>> lobe = vgroove.BRDF("vgroove", "ggx", 0.5, dim="flatland").lobe(40, flatland_bins=18)
        >>> lobe.hist.shape, round(lobe.albedo, 12)
        ((18,), 1.0)
        >>> round(float(lobe.by_k[1] + lobe.by_k[2]), 4)
        0.9817
        """
        max_k = self._binned("lobe")
        theta_i_deg = _args.real(theta_i_deg, "theta_i_deg")
        k_rows = _k_rows(k_rows)
        rows = k_rows if max_k is None else max_k
        d = _vgroove.lobe(self._model, self._ndf, self._alpha, theta_i_deg, self._dim,
                          _args.integer(flatland_bins, "flatland_bins"), _args.integer(theta_bins, "theta_bins"),
                          _args.integer(phi_bins, "phi_bins"), rows, _args.progress(progress))
        if max_k is not None:
            d = _truncated(d, self._dim, max_k, k_rows)
        return Lobe.from_dict(d, self._dim)

    def albedo(self, wi: _args.ArrayLike, *, theta_bins: int = 30, phi_bins: int = 24, flatland_bins: int = 90,
               k_rows: int = 16, progress: Optional[_args.ProgressFn] = None) -> np.ndarray:
        """The directional albedo: the flux the BRDF sends anywhere, int eval(wi, wo) cos(theta_o) d wo.

        Parameters
        ----------
        wi : array_like, shape (..., 3)
            Unit vectors towards the light (polar angle in [0, $max_surface_theta_i_deg] deg; flatland:
            signed, in [-$max_surface_theta_i_deg, $max_surface_theta_i_deg]). The model is isotropic: each distinct angle is integrated once.
        theta_bins, phi_bins, flatland_bins, k_rows : int
            The bins and rows of the lobe whose total this is (:meth:`lobe`; the same bits as
            ``lobe(...).albedo``): the total is exact to rounding whatever they are (with these,
            within 3e-14 of 1 for vgroove; the cost hardly depends on them); a suite's bins and
            max_k reproduce its ``albedo_model`` to the last bit.
        progress : callable, optional
            ``progress(done, total)``, counting the distinct angles.

        Returns
        -------
        numpy.ndarray
            Shape S. ``"vgroove"`` with every order conserves energy: 1 to ~1e-13; Cook-Torrance
            loses what its single scattering does not send out.

        Raises
        ------
        ValueError
            As :meth:`lobe`; a direction that is not a unit vector or out of range.

        Examples
        --------
        >>> import numpy as np, vgroove
        >>> wi = vgroove.direction(np.array([0.0, 60.0]), 180)
        >>> vgroove.BRDF("vgroove", "ggx", 1.0).albedo(wi).round(12)
        array([1., 1.])
        >>> vgroove.BRDF("cook-torrance", "ggx", 1.0).albedo(wi).round(4)
        array([0.375 , 0.6531])
        """
        max_k = self._binned("albedo")
        wi = _args.vectors(wi, "wi")
        norm = np.linalg.norm(wi, axis=-1)
        bad = ~(np.abs(norm - 1.0) <= RANGES["unit_tolerance"])
        if bad.any():
            j = int(np.flatnonzero(bad.ravel())[0])
            raise ValueError(f"wi[{j}] = {tuple(wi.reshape(-1, 3)[j].tolist())} is not a unit vector "
                             f"(|len - 1| <= {RANGES['unit_tolerance']:g})")
        if self._dim == "flatland":
            if not (np.abs(wi[..., 1]) <= RANGES["unit_tolerance"]).all():
                raise ValueError("wi must lie in the plane y = 0 in flatland (|y| <= "
                                 f"{RANGES['unit_tolerance']:g}; flatland directions: (-sin t, 0, cos t))")
            theta = np.asarray(_vgroove.output_deg(np.arctan2(-wi[..., 0], wi[..., 2])), dtype=float)
            lo, hi = -RANGES["max_surface_theta_i_deg"], RANGES["max_surface_theta_i_deg"]
        else:
            theta = np.asarray(_vgroove.output_deg(np.arctan2(np.hypot(wi[..., 0], wi[..., 1]), wi[..., 2])), dtype=float)
            lo, hi = 0.0, RANGES["max_surface_theta_i_deg"]
        out = ~((theta >= lo) & (theta <= hi))
        if out.any():
            j = int(np.flatnonzero(out.ravel())[0])
            raise ValueError(f"wi[{j}] = {tuple(wi.reshape(-1, 3)[j].tolist())} is {theta.ravel()[j]:g} deg from the "
                             f"normal, out of range [{lo:g}, {hi:g}]")
        angles, inverse = np.unique(theta.ravel(), return_inverse=True)
        progress = _args.progress(progress)
        values = np.empty(len(angles))
        rows = _k_rows(k_rows) if max_k is None else max_k
        for j, t in enumerate(angles):
            if progress is not None:
                progress(j, len(angles))
            d = _vgroove.lobe(self._model, self._ndf, self._alpha, float(t), self._dim,
                              _args.integer(flatland_bins, "flatland_bins"), _args.integer(theta_bins, "theta_bins"),
                              _args.integer(phi_bins, "phi_bins"), rows)
            values[j] = d["albedo"] if max_k is None else float(np.sum(d["by_k"][1:max_k + 1]))
        if progress is not None:
            progress(len(angles), len(angles))
        return values[inverse].reshape(theta.shape)

    def trace(self, theta_i_deg: float, rays: int = 1000000, *, grooves: int = 250000, seed: int = 1,
              sampling: str = "random", theta_bins: int = 30, phi_bins: int = 24, flatland_bins: int = 90,
              k_rows: int = 16, max_bounces: int = 100000, threads: int = 0,
              progress: Optional[_args.ProgressFn] = None) -> SurfaceTrace:
        """The exact simulation of the surface this BRDF models, in the bins of :meth:`lobe`.

        A procedural surface of ``grooves`` symmetric V-grooves whose facet normals follow the NDF
        (:func:`vgroove.microsurface`: the surfaces of the Fig. 11 suites, same seed, same surface)
        is made and ``rays`` rays from theta_i are traced in it, each exactly in its groove
        (:func:`vgroove.trace_microsurface`). Divide the counts by ``rays`` to compare them with
        :meth:`lobe`; Cook-Torrance is a model of the same surface.

        Parameters
        ----------
        theta_i_deg : float
            As in :meth:`lobe`.
        rays : int
            Rays in [1, $max_rays].
        grooves : int
            Grooves of the surface, in [1, $max_grooves].
        seed : int
            The surface's and the rays' seed, in [0, 2^63 - 1].
        sampling : {"random", "stratified"}
            Where the rays land (flatland may stratify; 3D lands them at random points).
        theta_bins, phi_bins, flatland_bins, k_rows
            As in :meth:`lobe`.
        max_bounces : int
            The tracer's bounce limit, in [1, $max_bounces].
        threads : int
            Worker threads in [0, $max_threads] (0: all cores); the counts do not depend on it.
        progress : callable, optional
            ``progress(done, total)``, counting rays.

        Returns
        -------
        SurfaceTrace
            Counts of rays (:class:`SurfaceTrace`; ``as_dict()`` is what
            :func:`vgroove.trace_microsurface` returns).

        Raises
        ------
        ValueError
            ``model="vgroove-nonsymmetric"``, ``eta`` given, an argument out of range, or a tally
            that would need more memory than this process may use.

        Examples
        --------
        >>> import vgroove
        >>> f = vgroove.BRDF("vgroove", "ggx", 0.5, dim="flatland")
        >>> t = f.trace(40, rays=100000, grooves=50000, flatland_bins=18)
        >>> lobe = f.lobe(40, flatland_bins=18)
        >>> round(float(abs(t.hist / t.rays - lobe.hist).sum()), 4)
        0.0101
        """
        self._binned("trace", truncates=False)
        k_rows = _k_rows(k_rows)
        surface = _vgroove.microsurface(self._ndf, self._alpha, _args.integer(grooves, "grooves"),
                                        _args.integer(seed, "seed"), self._dim)
        d = _vgroove.trace_microsurface(surface, _args.real(theta_i_deg, "theta_i_deg"), _args.integer(rays, "rays"),
                                        None, _args.text(sampling, "sampling"),
                                        _args.integer(flatland_bins, "flatland_bins"),
                                        _args.integer(theta_bins, "theta_bins"), _args.integer(phi_bins, "phi_bins"),
                                        k_rows, _args.integer(max_bounces, "max_bounces"),
                                        _args.integer(threads, "threads"), _args.progress(progress))
        return SurfaceTrace.from_dict(d, self._dim)


def _k_rows(k_rows):
    k_rows = _args.integer(k_rows, "k_rows")
    if not RANGES["min_histogram_k"] <= k_rows <= RANGES["max_histogram_k"]:
        raise ValueError(f"k_rows = {k_rows} is out of range [{RANGES['min_histogram_k']}, "
                         f"{RANGES['max_histogram_k']}]")
    return k_rows


def _truncated(d, dim, max_k, k_rows):
    """A lobe or tally with rows k = 0..max_k (and the rest) cut to the orders k <= max_k: rows
    0..min(k_rows, max_k), the last row the orders k_rows < k <= max_k, the totals over k <= max_k."""
    h, hk = ("theta_o", "theta_o_by_k") if dim == "flatland" else ("hist", "hist_by_k")
    by_k, by_k_hist = np.asarray(d["by_k"]), np.asarray(d[hk])
    r = min(k_rows, max_k)
    out = dict(d)
    out["by_k"] = np.concatenate([by_k[:r + 1], [by_k[r + 1:max_k + 1].sum()]])
    out[hk] = np.concatenate([by_k_hist[:r + 1], by_k_hist[r + 1:max_k + 1].sum(axis=0)[None]])
    out[h] = by_k_hist[:max_k + 1].sum(axis=0)
    if "albedo" in d:
        out["albedo"] = float(by_k[:max_k + 1].sum())
    return out


def _format_docs(ranges):
    """The docstrings above with the ranges of validation/ranges.h (and the default orders) filled in."""
    values = dict(ranges)
    values.update(all_orders=_vgroove.BRDF_MAX_K[("vgroove", "3d")],
                  flatland_max_k=_vgroove.BRDF_MAX_K[("vgroove", "flatland")],
                  nonsymmetric_max_k=_vgroove.BRDF_MAX_K[("vgroove-nonsymmetric", "3d")],
                  sampler_max_k=_vgroove.SAMPLER_MAX_K,
                  nonsymmetric_sampler_max_k=_vgroove.NONSYMMETRIC_SAMPLER_MAX_K)
    for obj in (BRDF, BRDF.eval, BRDF.sample, BRDF.pdf, BRDF.lobe, BRDF.albedo, BRDF.trace):
        obj.__doc__ = fill_ranges(obj.__doc__, values)


_format_docs(RANGES)
