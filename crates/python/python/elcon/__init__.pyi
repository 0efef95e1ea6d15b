"""Type stubs of elcon's user-facing API (see elcon/__init__.py)."""

import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._elcon import DesignError as DesignError
from ._elcon import ElconError as ElconError
from ._elcon import InputError as InputError
from ._elcon import SceneError as SceneError
from ._elcon import SolveError as SolveError

class Result:
    x: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64]
    force: npt.NDArray[np.float64]
    pressure: npt.NDArray[np.float64]
    gap: npt.NDArray[np.float64]
    separation: npt.NDArray[np.float64]
    @property
    def approach(self) -> float: ...
    @property
    def load(self) -> float: ...
    @property
    def max_pressure(self) -> float: ...
    @property
    def tilt(self) -> Dict[str, float]: ...
    @property
    def moment(self) -> Dict[str, float]: ...
    @property
    def certificate(self) -> Dict[str, Any]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def statistics(self) -> Dict[str, Any]: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def __getattr__(self, name: str) -> Any: ...

class ContactProblem:
    def __init__(
        self,
        x: Sequence[float],
        separation: Sequence[float],
        spacing: Union[float, Sequence[float]],
        y: Optional[Sequence[float]] = None,
        influence: Optional[npt.ArrayLike] = None,
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
    def solve(self, method: str = "block-pivoting") -> Result: ...

class Design:
    positions: npt.NDArray[np.float64]
    drops: npt.NDArray[np.float64]
    def to_dict(self) -> Dict[str, Any]: ...
    def __getattr__(self, name: str) -> Any: ...

def run(scene: Union[str, os.PathLike, Dict[str, Any]]) -> Result: ...
def design(
    problems: Sequence[ContactProblem],
    axis: str = "x",
    family: str = "quadratic",
    degree: Optional[int] = None,
    method: str = "auto",
    reference_intensities: Optional[Sequence[float]] = None,
) -> Design: ...
def batch(
    path: Union[str, os.PathLike], jobs: Optional[int] = None, out: Union[str, os.PathLike] = "out"
) -> Any: ...
def methods() -> List[str]: ...
