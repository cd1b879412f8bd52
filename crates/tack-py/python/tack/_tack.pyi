"""Type stubs of the compiled extension ``tack._tack`` (use the public API in ``tack``)."""

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
GIT_REVISION: str
MAX_THREADS: int

class TackError(ValueError):
    """Invalid input: the message names the field, the value and the allowed range."""

class SceneError(TackError):
    """A scene that cannot be read, parsed or validated."""

class SolverError(TackError):
    """The solver refused its input."""

class ResultFileError(TackError):
    """A result file that cannot be written or read."""

class InternalError(RuntimeError):
    """A bug in tack (a Rust panic caught before it reached Python)."""

class Result:
    """A run's result: curve, summary, snapshots, surface, provenance."""

    @property
    def curve(self) -> Dict[str, npt.NDArray[Any]]:
        """1-D arrays per step: approach, force, area, n_bonded, n_clusters, iterations,
        active_set_iterations, converged, mean_pressure, full_contact, time (where present), then
        the adhesion law's columns (n_cohesive under the Dugdale and smooth laws)."""
    @property
    def law_columns(self) -> Dict[str, str]:
        """{name: what it counts} of the adhesion law's columns of ``curve``."""
    @property
    def summary(self) -> Dict[str, Any]:
        """pull_off_force, f_jkr, pull_off_ratio, johnson_alpha, alpha_star, then extras."""
    @property
    def snapshots(self) -> Dict[int, Dict[str, Any]]:
        """{step: {"pressure": 2-D float array, "bonded": 2-D bool array, "approach": float}}."""
    @property
    def surface(self) -> Optional[Dict[str, Any]]:
        """{"heights": 2-D array, "dx": float[, "gamma": 2-D array]}, or None."""
    @property
    def provenance(self) -> Dict[str, Any]:
        """tack_version, git_revision, command_line, scene, created, seed."""
    @property
    def pull_off_force(self) -> float: ...
    @property
    def pull_off_ratio(self) -> float: ...
    @property
    def pull_off_step(self) -> Optional[int]: ...
    @property
    def wall_time(self) -> Optional[float]: ...
    @property
    def scene(self) -> str: ...
    @property
    def richardson(self) -> Optional[Dict[str, Any]]:
        """fine, coarse, extrapolated, error_estimate, order, ratio, aliased_rms; or None."""
    def write(self, path: Union[str, os.PathLike[str]]) -> None:
        """Writes the HDF5 result file atomically (``path``: str or os.PathLike, else
        TypeError)."""
    def __len__(self) -> int: ...

class ContactResult:
    """Equilibrium of non-adhesive contact at one approach."""

    @property
    def pressure(self) -> npt.NDArray[np.float64]: ...
    @property
    def gap(self) -> npt.NDArray[np.float64]: ...
    @property
    def approach(self) -> float: ...
    @property
    def force(self) -> float: ...
    @property
    def mean_pressure(self) -> float: ...
    @property
    def area(self) -> float: ...
    @property
    def n_contact(self) -> int: ...
    @property
    def iterations(self) -> int: ...
    @property
    def residual(self) -> float: ...
    @property
    def converged(self) -> bool: ...
    @property
    def full_contact(self) -> bool:
        """Periodic grids only: approach >= mean(heights), every gap closed; the state in which
        contact has just become full (least mean pressure keeping every element compressive),
        the same for every approach beyond the mean, computed in closed form."""

def run_scene(
    *,
    path: Optional[Union[str, os.PathLike[str]]] = ...,
    text: Optional[str] = ...,
    base_dir: Optional[Union[str, os.PathLike[str]]] = ...,
    overrides: Optional[Dict[str, Any]] = ...,
    richardson: bool = ...,
    threads: Optional[int] = ...,
    progress: Optional[Callable[[Dict[str, Any]], Any]] = ...,
) -> Result: ...
def pull_off(
    heights: npt.NDArray[np.float64],
    *,
    dx: float,
    e_star: float,
    gamma: float,
    gamma_map: Optional[npt.NDArray[np.float64]] = ...,
    periodic: bool = ...,
    radius: Optional[float] = ...,
    max_approach: Optional[float] = ...,
    unload_step: Optional[float] = ...,
    coarse_unload_step: Optional[float] = ...,
    refine_pull_off: bool = ...,
    kappa: Optional[float] = ...,
    model: str = ...,
    sigma0: Optional[float] = ...,
    range: Optional[float] = ...,
    snapshots: Any = ...,
    threads: Optional[int] = ...,
    progress: Optional[Callable[[Dict[str, Any]], Any]] = ...,
    thickness: Optional[float] = ...,
    poisson: Optional[float] = ...,
    interface: Optional[str] = ...,
    richardson: bool = ...,
    load_step: Optional[float] = ...,
    prony: Optional[Sequence[Tuple[float, float]]] = ...,
    speed: Optional[float] = ...,
    unload_speed: Optional[float] = ...,
    dwell: Optional[float] = ...,
    dwell_steps: Optional[int] = ...,
) -> Result: ...
def read(path: Union[str, os.PathLike[str]]) -> Result: ...
def contact(
    heights: npt.NDArray[np.float64],
    *,
    dx: float,
    e_star: float,
    approaches: Sequence[float],
    periodic: bool = ...,
    tolerance: Optional[float] = ...,
    max_iterations: Optional[int] = ...,
    threads: Optional[int] = ...,
    thickness: Optional[float] = ...,
    poisson: Optional[float] = ...,
    interface: Optional[str] = ...,
) -> List[ContactResult]: ...
def rough(
    nx: int,
    ny: int,
    *,
    dx: float,
    rms: float,
    hurst: float,
    seed: int = ...,
    q0: Optional[float] = ...,
    q1: Optional[float] = ...,
) -> npt.NDArray[np.float64]: ...
def sphere(nx: int, ny: int, *, dx: float, radius: float) -> npt.NDArray[np.float64]: ...
def power_law(
    nx: int, ny: int, *, dx: float, c: float, exponent: float
) -> npt.NDArray[np.float64]: ...
def ellipsoid(
    nx: int, ny: int, *, dx: float, radius_x: float, radius_y: float
) -> npt.NDArray[np.float64]: ...
def gamma_pattern(
    nx: int,
    ny: int,
    *,
    dx: float,
    kind: str,
    gamma_a: float,
    gamma_b: float = ...,
    period: float = ...,
    fraction: float = ...,
    contrast: float = ...,
    correlation_length: float = ...,
    seed: int = ...,
) -> npt.NDArray[np.float64]: ...
def coordinates(
    nx: int, ny: int, *, dx: float
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
def band(nx: int, ny: int, *, dx: float) -> Tuple[float, float]: ...
def _panic_for_tests() -> None: ...
def hertz_force(e_star: float, radius: float, d: float) -> float: ...
def hertz_contact_radius(radius: float, d: float) -> float: ...
def hertz_max_pressure(e_star: float, radius: float, d: float) -> float: ...
def jkr_pull_off_force(gamma: float, radius: float) -> float: ...
def jkr_pull_off_approach(e_star: float, gamma: float, radius: float) -> float: ...
def jkr_pull_off_radius(e_star: float, gamma: float, radius: float) -> float: ...
def jkr_approach_scale(e_star: float, gamma: float, radius: float) -> float: ...
def jkr_force_from_radius(e_star: float, gamma: float, radius: float, a: float) -> float: ...
def jkr_approach_from_radius(e_star: float, gamma: float, radius: float, a: float) -> float: ...
def jkr_force_from_approach(e_star: float, gamma: float, radius: float, d: float) -> float: ...
def kendall_pull_off(e_star: float, gamma: float, a: float) -> float: ...
def power_law_pull_off_force(e_star: float, gamma: float, c: float, exponent: float) -> float: ...
def johnson_alpha(e_star: float, gamma: float, h: float, wavelength: float) -> float: ...
def westergaard_p_star(e_star: float, h: float, wavelength: float) -> float: ...
def johnson_2d_p_star(e_star: float, h: float, wavelength: float) -> float: ...
def lambda_fit(alpha: float) -> float: ...
def alpha_star(e_star: float, gamma: float, h: float, hurst: float, q0: float, q1: float) -> float: ...
def rms_height_from_alpha_star(
    e_star: float, gamma: float, alpha_star: float, hurst: float, q0: float, q1: float
) -> float: ...
def lambda_star(alpha_star: float) -> float: ...
def critical_stress(e_star: float, gamma: float, dx: float, kappa: float) -> float: ...
MAUGIS_LAMBDA_CRITICAL: float
def maugis_lambda(e_star: float, gamma: float, radius: float, sigma0: float) -> float: ...
def maugis_pull_off_force(e_star: float, gamma: float, radius: float, sigma0: float) -> float: ...
def maugis_pull_off_hat(lam: float) -> float: ...
def maugis_dissipated_energy(e_star: float, gamma: float, radius: float, sigma0: float) -> float: ...
def maugis_force_contact(
    e_star: float, gamma: float, radius: float, sigma0: float, d: float
) -> float: ...
def maugis_force_separated(
    e_star: float, gamma: float, radius: float, sigma0: float, d: float
) -> float: ...
def maugis_jump_out_approach(e_star: float, gamma: float, radius: float, sigma0: float) -> float: ...
def maugis_jump_out_force(e_star: float, gamma: float, radius: float, sigma0: float) -> float: ...
def maugis_jump_in_approach(e_star: float, gamma: float, radius: float, sigma0: float) -> float: ...
def maugis_jump_in_force(e_star: float, gamma: float, radius: float, sigma0: float) -> float: ...
