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
        x: Optional[npt.ArrayLike] = None,
        separation: Optional[npt.ArrayLike] = None,
        spacing: Optional[Union[float, Sequence[float]]] = None,
        y: Optional[npt.ArrayLike] = None,
        influence: Optional[npt.ArrayLike] = None,
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
        storage: str = "auto",
    ) -> None: ...
    def __len__(self) -> int: ...
    @property
    def storage(self) -> str: ...
    @property
    def default_method(self) -> str: ...
    def solve(self, method: Optional[str] = None) -> Result: ...

class Design:
    positions: npt.NDArray[np.float64]
    drops: npt.NDArray[np.float64]
    @property
    def max_intensities(self) -> List[float]: ...
    @property
    def max_intensity(self) -> float: ...
    @property
    def certificates_hold(self) -> bool: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def __getattr__(self, name: str) -> Any: ...

def run(scene: Union[str, os.PathLike, Dict[str, Any]]) -> Result: ...
def design(
    problems: Union[Sequence[ContactProblem], str, os.PathLike, Dict[str, Any]],
    axis: Optional[str] = None,
    family: Optional[str] = None,
    degree: Optional[int] = None,
    method: Optional[str] = None,
    reference_intensities: Optional[Sequence[float]] = None,
    *,
    roller: Optional[Dict[str, float]] = None,
    **design_keys: Any,
) -> Design: ...
def batch(
    path: Union[str, os.PathLike], jobs: Optional[int] = None, out: Union[str, os.PathLike] = "out"
) -> Any: ...
def methods() -> List[str]: ...
def storages() -> List[str]: ...
