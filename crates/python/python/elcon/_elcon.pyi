"""Type stubs of the Rust extension (elcon._elcon); the user-facing API is
elcon/__init__.py, which wraps these."""

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

class ElconError(Exception): ...
class SceneError(ElconError): ...
class InputError(ElconError): ...
class SolveError(ElconError): ...
class DesignError(ElconError): ...

def run_scene(
    path: Optional[str] = None,
    scene: Optional[Dict[str, Any]] = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]: ...
def check_scene(
    path: Optional[str] = None, scene: Optional[Dict[str, Any]] = None
) -> Dict[str, Any]: ...
def run_batch(path: str, out: str, jobs: Optional[int] = None) -> str: ...
def design_problems(
    problems: Sequence["ContactProblem"],
    keys: Dict[str, Any],
    reference_intensities: Optional[Sequence[float]] = None,
    roller_dict: Optional[Dict[str, float]] = None,
) -> str: ...
def design_scene(
    path: Optional[str] = None,
    scene: Optional[Dict[str, Any]] = None,
    keys: Optional[Dict[str, Any]] = None,
) -> Dict[str, str]: ...
def methods() -> List[str]: ...
def storages() -> List[str]: ...
def is_file(path: str) -> bool: ...
def confine(directory: str) -> None: ...
def hertz_ellipse(
    combined_modulus: float,
    load: float,
    surface1: Tuple[float, float, float],
    surface2: Optional[Tuple[float, float, float]] = None,
    x: Optional[List[float]] = None,
    y: Optional[List[float]] = None,
) -> Dict[str, Any]: ...

class ContactProblem:
    def __init__(
        self,
        x: Optional[npt.NDArray[np.float64]] = None,
        separation: Optional[npt.NDArray[np.float64]] = None,
        spacing: Optional[Tuple[float, float]] = None,
        y: Optional[npt.NDArray[np.float64]] = None,
        influence: Optional[npt.NDArray[np.float64]] = None,
        body1: Optional[Dict[str, Any]] = None,
        body2: Optional[Dict[str, Any]] = None,
        load: Optional[float] = None,
        approach: Optional[float] = None,
        tilt_x: Optional[float] = None,
        tilt_y: Optional[float] = None,
        moment_x: float = 0.0,
        moment_y: float = 0.0,
        geometry: Optional[Dict[str, Any]] = None,
        points: Optional[Dict[str, Any]] = None,
        storage_name: str = "auto",
        height_map: Optional[npt.NDArray[np.float64]] = None,
        height_map_spacing: Optional[Tuple[float, float]] = None,
        height_map_origin: Optional[Tuple[float, float]] = None,
        height_map_interpolation: Optional[str] = None,
    ) -> None: ...
    def __len__(self) -> int: ...
    @property
    def storage(self) -> str: ...
    @property
    def default_method(self) -> str: ...
    def solve(
        self, method_name: Optional[str] = None, threads: Optional[int] = None
    ) -> Dict[str, Any]: ...

class Profile:
    def __init__(self, block: str) -> None: ...
    def drops_at(self, s: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    @property
    def family(self) -> str: ...
    def knots(
        self,
    ) -> Optional[Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]: ...
