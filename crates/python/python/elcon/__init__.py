"""elcon: elastic bodies in contact by mathematical programming.

Conry & Seireg's (1971) contact analysis and design, from Python, with
numpy arrays in and out:

- ``elcon.run(path_or_dict)`` runs a scene (a TOML file, or a dict with the
  same keys and the same validation) and returns a :class:`Result`;
- ``elcon.ContactProblem(...)`` builds a problem from arrays (points,
  separations, and S given or assembled from body models) and ``.solve()``
  returns a :class:`Result`;
- ``elcon.design(problems, ...)`` designs a profile correction over
  several problems (load cases);
- ``elcon.batch(path, jobs=...)`` runs a batch and returns its table.

Units are any consistent set (the scene's ``[units]``); arrays are float64,
one value per candidate point. Errors are ``elcon.SceneError`` (a scene
that is not valid: file:line:col and the field), ``elcon.InputError``
(arrays or parameters that do not go together), ``elcon.SolveError`` (a
solve that failed, or a problem too big for the memory) and
``elcon.DesignError``, all ``elcon.ElconError``.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _elcon
from ._elcon import DesignError, ElconError, InputError, SceneError, SolveError

__all__ = [
    "run",
    "batch",
    "design",
    "ContactProblem",
    "Result",
    "Design",
    "methods",
    "ElconError",
    "SceneError",
    "InputError",
    "SolveError",
    "DesignError",
]

_ARRAYS = ("x", "y", "force", "pressure", "gap", "separation")


class Result:
    """A certified contact solution.

    Scalars: ``approach``, ``load``, ``max_pressure`` (floats), ``tilt``,
    ``moment`` (dicts with ``x`` and ``y``), ``certificate`` (a dict:
    ``equilibrium``, ``min_force``, ``min_gap``, ``complementarity``,
    ``worst``, ``tolerance``, ``holds``), ``warnings`` (a list of strings)
    and ``statistics`` (a dict, with the engine's ``attempts``).

    Arrays (numpy float64, shape ``(N,)``, one value per candidate point):
    ``x``, ``y``, ``force``, ``pressure``, ``gap``, ``separation`` (the
    initial separation).

    ``to_dict()`` is the run's result.json (for a scene) or the solution's
    fields with the same names (for a ContactProblem).
    """

    def __init__(self, raw: Dict[str, Any]):
        self._json: str = raw["json"]
        self._dict: Dict[str, Any] = json.loads(self._json)
        for name in _ARRAYS:
            array = np.asarray(raw[name], dtype=np.float64)
            array.setflags(write=False)
            setattr(self, name, array)

    def to_dict(self) -> Dict[str, Any]:
        """The result as a dict: for a scene, equal to its result.json."""
        return json.loads(self._json)

    def __getattr__(self, name: str) -> Any:
        try:
            return self.__dict__["_dict"][name]
        except KeyError:
            raise AttributeError(name) from None

    @property
    def approach(self) -> float:
        """The approach alpha (length)."""
        return self._dict["approach"]

    @property
    def load(self) -> float:
        """The load e^T F (force)."""
        return self._dict["load"]

    @property
    def max_pressure(self) -> float:
        """The largest load intensity (force per area; per length on a line)."""
        return self._dict["max_pressure"]

    @property
    def tilt(self) -> Dict[str, float]:
        """The rotations of body 1 about x and y (radians)."""
        return self._dict["tilt"]

    @property
    def moment(self) -> Dict[str, float]:
        """The moments of the contact forces about the load point."""
        return self._dict["moment"]

    @property
    def certificate(self) -> Dict[str, Any]:
        """The residuals from the original data, and whether they hold."""
        return self._dict["certificate"]

    @property
    def warnings(self) -> List[str]:
        """Warnings: a truncated zone, an uncertain contact."""
        return self._dict["warnings"]

    @property
    def statistics(self) -> Dict[str, Any]:
        """The engine's statistics, attempt by attempt."""
        return self._dict["statistics"]

    def __repr__(self) -> str:
        return (
            f"Result(points={len(self.x)}, approach={self.approach:.6e}, "
            f"load={self.load:.6e}, max_pressure={self.max_pressure:.6e}, "
            f"certificate_holds={self.certificate['holds']})"
        )


def run(scene: Union[str, os.PathLike, Dict[str, Any]]) -> Result:
    """Runs a scene: a TOML file's path, or a dict with the same keys.

    A dict is written as the same TOML a file would hold, so it is validated
    by the same rules, with the same messages (its file named ``<dict>``).

    Raises ``SceneError`` for a scene that is not valid, ``SolveError`` for a
    solve that failed or a scene too big for the memory available.
    """
    if isinstance(scene, dict):
        text = _elcon.toml_from_json(json.dumps(scene))
        return Result(_elcon.run_scene(text=text, name="<dict>"))
    if isinstance(scene, (str, os.PathLike)):
        return Result(_elcon.run_scene(path=os.fspath(scene)))
    raise InputError("run() takes a scene's path (a .toml file) or a dict of its keys")


class ContactProblem:
    """A contact problem from numpy arrays.

    Parameters
    ----------
    x, y:
        The candidate points' coordinates (length), shape ``(N,)``; leave
        ``y`` out for a line (a beam, a plane-strain contact).
    separation:
        The initial separation at each point (length), shape ``(N,)``.
    spacing:
        The cell size: ``h`` or ``(dx, dy)`` (length). A point's measure is
        its cell's area (its length on a line): pressure = force / measure.
    influence:
        S as an ``(N, N)`` array (length per force): deflection at k per
        unit force at j, both bodies together. Or give ``body1`` and
        ``body2`` instead.
    body1, body2:
        Dicts as a scene's ``[body1]``: ``{"model": "uniform-patch",
        "youngs_modulus": E, "poissons_ratio": nu}``; models ``rigid``,
        ``uniform-patch``, ``point-force``, ``plane-strain``
        (``reference_distance``), ``winkler`` (``modulus``), ``beam``
        (``youngs_modulus``, ``second_moment``, ``loaded_point``).
    load, approach:
        Load control (force) or displacement control (length): one of them.
    tilt_x, tilt_y, moment_x, moment_y:
        The rotations of body 1 about the x and y axes through the origin
        (where the load acts): prescribed (radians), or free with a moment
        about the origin (force length; default 0: the load acts at the
        origin). The gap changes by ``tilt_x y - tilt_y x``; ``moment_x``
        balances ``sum F y`` and ``moment_y`` balances ``-sum F x``. On a
        line only ``tilt_y`` / ``moment_y`` apply.
    """

    def __init__(
        self,
        x: Sequence[float],
        separation: Sequence[float],
        spacing: Union[float, Sequence[float]],
        y: Optional[Sequence[float]] = None,
        influence: Optional[np.ndarray] = None,
        body1: Optional[Dict[str, Any]] = None,
        body2: Optional[Dict[str, Any]] = None,
        load: Optional[float] = None,
        approach: Optional[float] = None,
        tilt_x: Optional[float] = None,
        tilt_y: Optional[float] = None,
        moment_x: float = 0.0,
        moment_y: float = 0.0,
    ):
        spacing = (float(spacing), float(spacing)) if np.ndim(spacing) == 0 else tuple(
            float(v) for v in spacing
        )
        if len(spacing) != 2:
            raise InputError("`spacing`: h or (dx, dy)")
        as_array = lambda v: None if v is None else np.ascontiguousarray(v, dtype=np.float64)
        self._inner = _elcon.ContactProblem(
            as_array(x),
            as_array(separation),
            spacing,
            y=as_array(y),
            influence=as_array(influence),
            body1=body1,
            body2=body2,
            load=load,
            approach=approach,
            tilt_x=tilt_x,
            tilt_y=tilt_y,
            moment_x=moment_x,
            moment_y=moment_y,
        )

    def __len__(self) -> int:
        return len(self._inner)

    def solve(self, method: str = "block-pivoting") -> Result:
        """Solves with ``method`` (``elcon.methods()``); the GIL is released."""
        return Result(self._inner.solve(method))


class Design:
    """A certified design: ``objective`` (the worst p_max over the cases,
    over each case's reference intensity), ``max_intensities`` (per case),
    ``positions`` and ``drops`` (the correction at the axial stations,
    arrays), ``method`` ("program" or "descent"), ``starts``."""

    def __init__(self, raw: str):
        self._dict = json.loads(raw)
        table = np.asarray(self._dict["table"], dtype=np.float64).reshape(-1, 2)
        self.positions = table[:, 0].copy()
        self.drops = table[:, 1].copy()

    def __getattr__(self, name: str) -> Any:
        try:
            return self.__dict__["_dict"][name]
        except KeyError:
            raise AttributeError(name) from None

    def to_dict(self) -> Dict[str, Any]:
        """The design as a dict."""
        return dict(self._dict)


def design(
    problems: Sequence[ContactProblem],
    axis: str = "x",
    family: str = "quadratic",
    degree: Optional[int] = None,
    method: str = "auto",
    reference_intensities: Optional[Sequence[float]] = None,
) -> Design:
    """The correction of ``family`` (``quadratic``, ``polynomial`` with
    ``degree``, ``free``) along ``axis`` that minimizes the worst load
    intensity over the problems (each a load case under a load), by the
    paper's program or the case-decomposed descent (``method``: ``auto``,
    ``program``, ``descent``). Raises ``DesignError`` when it fails."""
    inner = [p._inner for p in problems]
    refs = None if reference_intensities is None else [float(r) for r in reference_intensities]
    return Design(_elcon.design(inner, axis, family, degree, method, refs))


def batch(path: Union[str, os.PathLike], jobs: Optional[int] = None, out: Union[str, os.PathLike] = "out"):
    """Runs a batch file into ``out`` (its tables and every run's outputs, as
    ``elcon batch`` writes them) and returns its runs' table: a pandas
    DataFrame if pandas is installed, else a list of dicts."""
    outcome = json.loads(_elcon.run_batch(os.fspath(path), os.fspath(out), jobs))
    rows = outcome["rows"]
    try:
        import pandas  # noqa: F401
    except ImportError:
        return rows
    return pandas.DataFrame(rows)


def methods() -> List[str]:
    """The solve methods, by name."""
    return list(_elcon.methods())
