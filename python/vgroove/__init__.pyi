# Type stubs of the package vgroove (its pure-Python part: __init__.py and the modules it imports
# from). Kept in step with the code by tests/python/test_stubs.py: every public name, parameter,
# default and field here is the runtime's, and the reverse.
import os
from dataclasses import dataclass
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _vgroove

ArrayLike = Union[float, Sequence[float], np.ndarray]
ProgressFn = Callable[[int, int], Any]

__version__: str
git_revision: str
RANGES: dict[str, float]
FATES: tuple[str, str, str, str]
LEFT: int
RIGHT: int
BRDF_MAX_K: dict[tuple[str, str], int]
SAMPLER_MAX_K: int
NONSYMMETRIC_SAMPLER_MAX_K: int

Microsurface = _vgroove.Microsurface

def direction(theta_deg: ArrayLike, phi_deg: ArrayLike = 0.0) -> np.ndarray: ...
def output_deg(rad: ArrayLike) -> np.ndarray: ...
def kaleidoscope(theta_i_deg: ArrayLike, theta_v_deg: Optional[ArrayLike] = None, *,
                 theta_l_deg: Optional[ArrayLike] = None, theta_r_deg: Optional[ArrayLike] = None,
                 eq6_form: str = "corrected") -> dict[str, np.ndarray]: ...
def analytic(theta_i_deg: float, theta_v_deg: Optional[float] = None, *, theta_l_deg: Optional[float] = None,
             theta_r_deg: Optional[float] = None, eq6_form: str = "corrected") -> dict[str, Any]: ...
def trace(theta_i_deg: float, rays: int = 1000, theta_v_deg: Optional[float] = None, *,
          theta_l_deg: Optional[float] = None, theta_r_deg: Optional[float] = None, sampling: str = "stratified",
          seed: int = 1, max_bounces: Optional[int] = None) -> dict[str, Any]: ...
def groove_case(theta_i_deg: float, theta_v_deg: Optional[float] = None, *, theta_l_deg: Optional[float] = None,
                theta_r_deg: Optional[float] = None, rays: int = 1000, sampling: str = "stratified", seed: int = 1,
                max_bounces: Optional[int] = None, eq6_form: str = "corrected", probe_vertices: bool = False,
                stream: int = 0) -> dict[str, Any]: ...

def microsurface(ndf: str = "ggx", alpha: float = 0.5, grooves: int = 250000, seed: int = 1,
                 dim: str = "3d") -> Microsurface: ...
def trace_microsurface(surface: Microsurface, theta_i_deg: float, rays: int = 1000000, *, seed: Optional[int] = None,
                       sampling: str = "random", flatland_bins: int = 90, theta_bins: int = 30, phi_bins: int = 24,
                       max_k: int = 16, max_bounces: int = 100000, threads: int = 0,
                       progress: Optional[ProgressFn] = None) -> dict[str, Any]: ...
def lobe(model: str, ndf: str, alpha: float, theta_i_deg: float, dim: str = "3d", *, flatland_bins: int = 90,
         theta_bins: int = 30, phi_bins: int = 24, max_k: int = 16,
         progress: Optional[ProgressFn] = None) -> dict[str, Any]: ...

def brdf(model: str, ndf: str, alpha: float, wi: npt.ArrayLike, wo: npt.ArrayLike, per_k: Union[bool, int] = False,
         *, max_k: Optional[int] = None, dim: str = "3d", eta: Optional[complex] = None,
         masking: Optional[str] = None, threads: int = 0, progress: Optional[ProgressFn] = None) -> np.ndarray: ...
def check_brdf(f: Union[Callable[[np.ndarray, np.ndarray], npt.ArrayLike], str], ndf: str = "ggx", alpha: float = 0.5,
               theta_i_deg: Sequence[float] = (0, 20, 40, 60, 80), rays: int = 1000000, *, dim: str = "3d",
               grooves: int = 250000, seed: int = 1, theta_bins: int = 30, phi_bins: int = 24,
               flatland_bins: int = 90, sigmas: float = 5.0, model_tolerance: float = 1e-4,
               quadrature_order: int = 4, threads: int = 0, name: str = "check_brdf", max_k: Optional[int] = None,
               progress: Optional[ProgressFn] = None, surface: str = "vgroove", field_size: int = 256,
               correlation_length: float = 8.0, fields: int = 4, eta: Optional[float] = None,
               side: str = "above") -> dict[str, Any]: ...
def validate(suite: Union[str, os.PathLike[str], dict[str, Any]], *, rays: Optional[int] = None, threads: int = 0,
             sampling: Optional[str] = None, eq6_form: Optional[str] = None, seed: Optional[int] = None,
             model_table: Optional[str] = None, verbose: bool = False,
             progress: Optional[ProgressFn] = None) -> dict[str, Any]: ...

def dielectric_lobe(ndf: str, alpha: float, eta: float, theta_i_deg: float = 0.0, per_k: Union[bool, int] = False, *,
                    dim: str = "3d", flatland_bins: int = 90, theta_bins: int = 18, phi_bins: int = 24,
                    progress: Optional[ProgressFn] = None) -> dict[str, Any]: ...
def dielectric_bsdf(ndf: str, alpha: float, eta: float, theta_i_deg: ArrayLike, theta_o_deg: ArrayLike,
                    per_k: Union[bool, int] = False, *, phi_i_deg: ArrayLike = 0.0, phi_o_deg: ArrayLike = 180.0,
                    dim: str = "3d", threads: int = 0, progress: Optional[ProgressFn] = None) -> dict[str, Any]: ...
def glass_energy(eta: Sequence[float], alpha: Sequence[float] = (0.1, 0.5, 1.0), mu: Sequence[float] = (1.0, 0.5),
                 *, ndf: Union[str, Sequence[str]] = "ggx", dim: Union[str, Sequence[str]] = "3d",
                 side: Union[str, Sequence[str]] = ("above", "below"), rays: int = 100000, grooves: int = 10000,
                 seed: int = 1, max_k: int = 16, threads: int = 0, verbose: bool = False,
                 reference: str = "vgroove", progress: Optional[ProgressFn] = None) -> dict[str, Any]: ...
def energy_audit(ndf: Union[str, Sequence[str]] = ("ggx", "beckmann"), alpha: Optional[Sequence[float]] = None,
                 mu: Optional[Sequence[float]] = None, *, alpha_points: int = 8, mu_points: int = 8,
                 rays: int = 100000, seed: int = 1, max_k: int = 16, reference: Optional[str] = None,
                 threads: int = 0, verbose: bool = False, progress: Optional[ProgressFn] = None) -> dict[str, Any]: ...
def energy_lobe_shape(ndf: str = "ggx", alpha: Sequence[float] = (0.5, 1.0),
                      theta_i_deg: Sequence[float] = (0, 40, 70), rays: int = 200000, *, grooves: int = 100000,
                      seed: int = 1, theta_bins: int = 15, phi_bins: int = 12, sigmas: float = 5.0, threads: int = 0,
                      verbose: bool = False) -> dict[str, Any]: ...

def sample(ndf: str, alpha: float, u: npt.ArrayLike, *, wi: Optional[npt.ArrayLike] = None,
           theta_i_deg: Optional[ArrayLike] = None, strategy: Optional[str] = None, max_k: Optional[int] = None,
           dim: str = "3d", model: str = "vgroove", tolerance: float = 1e-9, threads: int = 0,
           eta: Optional[float] = None, masking: Optional[str] = None,
           progress: Optional[ProgressFn] = None) -> dict[str, np.ndarray]: ...
def pdf(ndf: str, alpha: float, wo: npt.ArrayLike, *, wi: Optional[npt.ArrayLike] = None,
        theta_i_deg: Optional[ArrayLike] = None, strategy: Optional[str] = None, max_k: Optional[int] = None,
        dim: str = "3d", model: str = "vgroove", tolerance: float = 1e-9, threads: int = 0,
        eta: Optional[float] = None, masking: Optional[str] = None,
        progress: Optional[ProgressFn] = None) -> np.ndarray: ...
def uniforms(n: int, seed: int = 1, stream: Sequence[int] = (0, 0), dims: int = 4) -> np.ndarray: ...

@dataclass(frozen=True)
class SurfaceTrace:
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
    def from_dict(cls, d: dict[str, Any], dim: str) -> SurfaceTrace: ...
    def as_dict(self) -> dict[str, Any]: ...

@dataclass(frozen=True)
class Lobe:
    dim: str
    by_k: np.ndarray
    hist: np.ndarray
    hist_by_k: np.ndarray
    albedo: float
    @classmethod
    def from_dict(cls, d: dict[str, Any], dim: str) -> Lobe: ...
    def as_dict(self) -> dict[str, Any]: ...

@dataclass(frozen=True)
class SampleBatch:
    wo: np.ndarray
    k: np.ndarray
    pdf: np.ndarray
    weight: np.ndarray
    beyond_max_k: Optional[np.ndarray] = ...
    transmitted: Optional[np.ndarray] = ...
    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> SampleBatch: ...
    def as_dict(self) -> dict[str, np.ndarray]: ...

class BRDF:
    def __init__(self, model: str = "vgroove", ndf: str = "ggx", alpha: float = 0.5, *,
                 alpha_y: Optional[float] = None, partner: Optional[str] = None, max_k: Optional[int] = None,
                 eta: Optional[complex] = None, masking: Optional[str] = None, dim: str = "3d") -> None: ...
    @property
    def model(self) -> str: ...
    @property
    def ndf(self) -> str: ...
    @property
    def alpha(self) -> float: ...
    @property
    def alpha_y(self) -> Optional[float]: ...
    @property
    def partner(self) -> Optional[str]: ...
    @property
    def eta(self) -> Optional[complex]: ...
    @property
    def masking(self) -> Optional[str]: ...
    @property
    def dim(self) -> str: ...
    @property
    def max_k(self) -> int: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def eval(self, wi: npt.ArrayLike, wo: npt.ArrayLike, *, threads: int = 0,
             progress: Optional[ProgressFn] = None) -> np.ndarray: ...
    def sample(self, wi: npt.ArrayLike, u: npt.ArrayLike, *, strategy: Optional[str] = None,
               tolerance: float = 1e-9, threads: int = 0, progress: Optional[ProgressFn] = None) -> SampleBatch: ...
    def pdf(self, wi: npt.ArrayLike, wo: npt.ArrayLike, *, strategy: Optional[str] = None,
            tolerance: float = 1e-9, threads: int = 0, progress: Optional[ProgressFn] = None) -> np.ndarray: ...
    def lobe(self, theta_i_deg: float, *, theta_bins: int = 30, phi_bins: int = 24, flatland_bins: int = 90,
             k_rows: int = 16, progress: Optional[ProgressFn] = None) -> Lobe: ...
    def albedo(self, wi: npt.ArrayLike, *, theta_bins: int = 30, phi_bins: int = 24, flatland_bins: int = 90,
               k_rows: int = 16, progress: Optional[ProgressFn] = None) -> np.ndarray: ...
    def trace(self, theta_i_deg: float, rays: int = 1000000, *, grooves: int = 250000, seed: int = 1,
              sampling: str = "random", theta_bins: int = 30, phi_bins: int = 24, flatland_bins: int = 90,
              k_rows: int = 16, max_bounces: int = 100000, threads: int = 0,
              progress: Optional[ProgressFn] = None) -> SurfaceTrace: ...

class TqdmProgress:
    bar: Optional[Any]
    def __call__(self, done: int, total: int) -> None: ...

def tqdm_progress(**kwargs: Any) -> TqdmProgress: ...
