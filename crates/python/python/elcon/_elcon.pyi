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
    path: Optional[str] = None, text: Optional[str] = None, name: str = "<dict>"
) -> Dict[str, Any]: ...
def toml_from_json(json: str) -> str: ...
def run_batch(path: str, out: str, jobs: Optional[int] = None) -> str: ...
def design(
    problems: Sequence["ContactProblem"],
    axis: str = "x",
    family: str = "quadratic",
    degree: Optional[int] = None,
    method_name: str = "auto",
    reference_intensities: Optional[Sequence[float]] = None,
) -> str: ...
def methods() -> List[str]: ...
def is_file(path: str) -> bool: ...

class ContactProblem:
    def __init__(
        self,
        x: npt.NDArray[np.float64],
        separation: npt.NDArray[np.float64],
        spacing: Tuple[float, float],
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
    ) -> None: ...
    def __len__(self) -> int: ...
    def solve(self, method_name: str = "block-pivoting") -> Dict[str, Any]: ...
