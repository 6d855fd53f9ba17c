# Type stubs of vgroove._vgroove, the C++ core under the package vgroove. Use the package's
# functions and vgroove.BRDF (units and conventions in their docstrings); these take flattened,
# already broadcast arrays (or one row for every item) and every option explicitly. Kept in step
# with the extension by tests/python/test_stubs.py (names and parameters).
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str
git_revision: str
ranges: dict[str, float]
BRDF_MAX_K: dict[tuple[str, str], int]
SAMPLER_MAX_K: int
NONSYMMETRIC_SAMPLER_MAX_K: int
audit_ranges: dict[str, int]

Progress = Optional[Callable[[int, int], Any]]

def direction(theta_deg: npt.NDArray[np.float64], phi_deg: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
def output_deg(rad: npt.ArrayLike) -> Any: ...

def kaleidoscope(theta_i_deg: npt.NDArray[np.float64], theta_v_deg: Optional[npt.NDArray[np.float64]],
                 theta_l_deg: Optional[npt.NDArray[np.float64]], theta_r_deg: Optional[npt.NDArray[np.float64]],
                 eq6_form: str) -> dict[str, np.ndarray]: ...
def analytic(theta_i_deg: float, theta_v_deg: Optional[float], theta_l_deg: Optional[float],
             theta_r_deg: Optional[float], eq6_form: str) -> dict[str, Any]: ...
def trace(theta_i_deg: float, rays: int, theta_v_deg: Optional[float], theta_l_deg: Optional[float],
          theta_r_deg: Optional[float], sampling: str, seed: int, max_bounces: Optional[int]) -> dict[str, Any]: ...
def groove_case(theta_i_deg: float, theta_v_deg: Optional[float], theta_l_deg: Optional[float],
                theta_r_deg: Optional[float], rays: int, sampling: str, seed: int, max_bounces: Optional[int],
                eq6_form: str, probe_vertices: bool, stream: int) -> dict[str, Any]: ...

class Microsurface:
    @property
    def dim(self) -> str: ...
    @property
    def ndf(self) -> str: ...
    @property
    def alpha(self) -> float: ...
    @property
    def grooves(self) -> int: ...
    @property
    def seed(self) -> int: ...
    @property
    def theta_m_deg(self) -> npt.NDArray[np.float64]: ...
    @property
    def phi_a_deg(self) -> Optional[npt.NDArray[np.float64]]: ...

def microsurface(ndf: str, alpha: float, grooves: int, seed: int, dim: str) -> Microsurface: ...
def trace_microsurface(surface: Microsurface, theta_i_deg: float, rays: int, seed: Optional[int], sampling: str,
                       flatland_bins: int, theta_bins: int, phi_bins: int, max_k: int, max_bounces: int,
                       threads: int, progress: Progress = None) -> dict[str, Any]: ...
def lobe(model: str, ndf: str, alpha: float, theta_i_deg: float, dim: str, flatland_bins: int, theta_bins: int,
         phi_bins: int, max_k: int, progress: Progress = None) -> dict[str, Any]: ...

def brdf_settings(model: str, ndf: str, alpha: float, dim: str, max_k: Optional[int], alpha_y: Optional[float],
                  partner: Optional[str], eta: Optional[complex], masking: Optional[str] = None) -> dict[str, Any]: ...
def brdf(model: str, ndf: str, alpha: float, wi: npt.NDArray[np.float64], wo: npt.NDArray[np.float64], per_k: int,
         max_k: Optional[int], dim: str, threads: int, alpha_y: Optional[float] = None, partner: Optional[str] = None,
         eta: Optional[complex] = None, masking: Optional[str] = None,
         progress: Progress = None) -> npt.NDArray[np.float64]: ...
def check_brdf(f: Union[Callable[[np.ndarray, np.ndarray], npt.ArrayLike], str], max_k: Optional[int], name: str,
               ndf: str, alpha: float, theta_i_deg: Sequence[float], rays: int, dim: str, grooves: int, seed: int,
               theta_bins: int, phi_bins: int, flatland_bins: int, sigmas: float, model_tolerance: float,
               quadrature_order: int, threads: int, progress: Progress = None, surface: str = "vgroove",
               field_size: int = 256, correlation_length: float = 8.0, fields: int = 4, eta: Optional[float] = None,
               side: str = "above") -> dict[str, Any]: ...
def dielectric_lobe(ndf: str, alpha: float, eta: float, theta_i_deg: float, dim: str, orders: int, flatland_bins: int,
                    theta_bins: int, phi_bins: int, progress: Progress = None) -> dict[str, Any]: ...
def dielectric_bsdf(ndf: str, alpha: float, eta: float, angles: npt.NDArray[np.float64], dim: str, orders: int,
                    threads: int, progress: Progress = None) -> dict[str, npt.NDArray[np.float64]]: ...

def validate(path: str, rays: Optional[int], threads: int, sampling: Optional[str], eq6_form: Optional[str],
             seed: Optional[int], model_table: Optional[str], verbose: bool, suite_json: Optional[str] = None,
             progress: Progress = None) -> dict[str, Any]: ...

def glass_energy(eta: Sequence[float], alpha: Sequence[float], mu: Sequence[float], ndf: Sequence[str],
                 dim: Sequence[str], side: Sequence[str], rays: int, grooves: int, seed: int, max_k: int, threads: int,
                 verbose: bool, reference: str = "vgroove", progress: Progress = None) -> dict[str, Any]: ...
def energy_audit(ndf: Sequence[str], alpha: Optional[Sequence[float]], mu: Optional[Sequence[float]],
                 alpha_points: int, mu_points: int, rays: int, seed: int, max_k: int, reference: Optional[str],
                 threads: int, verbose: bool, progress: Progress = None) -> dict[str, Any]: ...
def energy_lobe_shape(ndf: str, alpha: Sequence[float], theta_i_deg: Sequence[float], rays: int, grooves: int,
                      seed: int, theta_bins: int, phi_bins: int, sigmas: float, threads: int,
                      verbose: bool) -> dict[str, Any]: ...

def sample(model: str, ndf: str, alpha: float, wi: Optional[npt.NDArray[np.float64]],
           theta_i_deg: Optional[npt.NDArray[np.float64]], u: npt.NDArray[np.float64], strategy: str, max_k: int,
           tolerance: float, dim: str, threads: int, eta: Optional[complex] = None,
           progress: Progress = None) -> dict[str, np.ndarray]: ...
def pdf(model: str, ndf: str, alpha: float, wi: Optional[npt.NDArray[np.float64]],
        theta_i_deg: Optional[npt.NDArray[np.float64]], wo: npt.NDArray[np.float64], strategy: str, max_k: int,
        tolerance: float, dim: str, threads: int, progress: Progress = None) -> npt.NDArray[np.float64]: ...
def walter_sample(ndf: str, alpha: float, wi: Optional[npt.NDArray[np.float64]],
                  theta_i_deg: Optional[npt.NDArray[np.float64]], u: npt.NDArray[np.float64], eta: float,
                  masking: str, strategy_given: bool, max_k_given: bool, dim: str, threads: int,
                  progress: Progress = None) -> dict[str, np.ndarray]: ...
def walter_pdf(ndf: str, alpha: float, wi: Optional[npt.NDArray[np.float64]],
               theta_i_deg: Optional[npt.NDArray[np.float64]], wo: npt.NDArray[np.float64], eta: float,
               masking: str, strategy_given: bool, max_k_given: bool, dim: str, threads: int,
               progress: Progress = None) -> npt.NDArray[np.float64]: ...
def dielectric_pdf(ndf: str, alpha: float, eta: float, theta_i_deg: Optional[npt.NDArray[np.float64]],
                   wo: npt.NDArray[np.float64], dim: str, light_from: str = "above", threads: int = 0,
                   progress: Progress = None) -> npt.NDArray[np.float64]: ...
def dielectric_sample(ndf: str, alpha: float, eta: float, theta_i_deg: Optional[npt.NDArray[np.float64]],
                      u: npt.NDArray[np.float64], dim: str, light_from: str = "above", threads: int = 0,
                      progress: Progress = None) -> dict[str, np.ndarray]: ...
def uniforms(n: int, seed: int, a: int, b: int, dims: int) -> npt.NDArray[np.float64]: ...
