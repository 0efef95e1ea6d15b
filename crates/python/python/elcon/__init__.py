"""elcon: elastic bodies in contact by mathematical programming.

Conry & Seireg's (1971) contact analysis and design, from Python, with
numpy arrays in and out:

- ``elcon.run(path_or_dict)`` runs a scene (a TOML file, or a dict with the
  same keys and the same validation) and returns a :class:`Result`; a
  bearing scene (a ``[bearing]`` table: a radial ball or cylindrical roller
  bearing as a system of contacts) returns a :class:`BearingResult`;
  ``elcon.check(path_or_dict)`` validates and estimates it without solving;
- ``elcon.ContactProblem(...)`` builds a problem from arrays or a layout
  (points, separations or surfaces, and S given or assembled from body
  models, held dense, folded or matrix-free) and ``.solve()`` returns a
  :class:`Result`;
- ``elcon.design(problems_or_scene, ...)`` designs a profile correction
  over several problems (load cases), or runs a scene's design stage;
- ``elcon.batch(path, jobs=...)`` runs a batch and returns its table;
- ``elcon.hertz_ellipse(...)`` is Hertz's elliptical contact of two
  quadrics (the semi-axes, the approach, the peak pressure, the pressure
  at given points).

Body, surface, layout and design dicts are a scene's sections: they are
parsed and checked by the scene crate's own parsers, with its messages
(the field named). Every solve is estimated against the same memory
ceiling as the command line before anything large is allocated, and a
failure inside the crates reaches Python as an ``elcon.ElconError``.

Units are any consistent set (the scene's ``[units]``); arrays of any
dtype and layout are taken, one value per candidate point, and returned as
float64. Errors are ``elcon.SceneError`` (a scene that is not valid:
file:line:col and the field), ``elcon.InputError`` (arrays, dicts or
parameters given to ContactProblem or design that are not valid or do not
go together), ``elcon.SolveError`` (a solve that failed, or a problem too
big for the memory) and ``elcon.DesignError``, all ``elcon.ElconError``.
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Union

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

from . import _elcon
from ._elcon import DesignError, ElconError, InputError, SceneError, SolveError

__all__ = [
    "run",
    "check",
    "batch",
    "design",
    "ContactProblem",
    "Result",
    "BearingResult",
    "Design",
    "Profile",
    "methods",
    "storages",
    "hertz_ellipse",
    "confine",
    "ElconError",
    "SceneError",
    "InputError",
    "SolveError",
    "DesignError",
]

_ARRAYS = ("x", "y", "force", "pressure", "gap", "separation")


class _Fields:
    """A JSON object's fields (``self._dict``) read as attributes."""

    _dict: Dict[str, Any]

    def __getattr__(self, name: str) -> Any:
        try:
            return self.__dict__["_dict"][name]
        except KeyError:
            raise AttributeError(name) from None


class Result(_Fields):
    """A certified contact solution.

    Scalars: ``approach``, ``load``, ``max_pressure`` (floats), ``tilt``,
    ``moment`` (dicts with ``x`` and ``y``), ``certificate`` (a dict:
    ``equilibrium``, ``min_force``, ``min_gap``, ``complementarity``,
    ``worst``, ``tolerance``, ``holds``), ``warnings`` (a list of strings)
    and ``statistics`` (a dict, with the engine's ``attempts``).

    Arrays (numpy float64, shape ``(N,)``, one value per candidate point):
    ``x``, ``y``, ``force``, ``pressure``, ``gap``, ``separation`` (the
    initial separation).

    ``subsurface`` (a scene with ``[outputs] subsurface = true``; None
    otherwise): per body (``"body1"``, ``"body2"``) result.json's block
    (``applicable``, ``von_mises``, ``tresca``, ``orthogonal_xz``,
    ``orthogonal_yz``: each ``value``, ``x``, ``y``, ``depth``) with, for a
    body that has a field, ``section`` and ``profile``: dicts of ``x``
    (shape ``(n,)``), ``depth`` (``(m,)``), ``y`` and the stresses
    ``sigma_x``, ``sigma_y``, ``sigma_z``, ``tau_xy``, ``tau_xz``,
    ``tau_yz``, ``von_mises``, ``tresca``, each of shape ``(n, m)`` (the
    scene's pressure unit, tension positive).

    ``to_dict()`` is the run's result.json (for a scene) or the solution's
    fields with the same names (for a ContactProblem); ``profile`` a
    scene's designed profile (a :class:`Profile`; None without
    ``[design]``).
    """

    x: np.ndarray
    y: np.ndarray
    force: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    separation: np.ndarray

    def __init__(self, raw: Dict[str, Any]):
        self._json: str = raw["json"]
        self._dict: Dict[str, Any] = json.loads(self._json)
        for name in _ARRAYS:
            array = np.asarray(raw[name], dtype=np.float64)
            array.setflags(write=False)
            setattr(self, name, array)
        self._subsurface: Optional[Dict[str, Any]] = raw.get("subsurface")

    @property
    def subsurface(self) -> Optional[Dict[str, Any]]:
        """The stresses below the surface, when the scene asked for them."""
        block = self._dict.get("subsurface")
        if block is None:
            return None
        bodies: Dict[str, Any] = {"stress_unit": block["stress_unit"]}
        arrays = self._subsurface or {}
        for name in ("body1", "body2"):
            body = dict(block[name])
            if arrays.get(name) is not None:
                body.update(arrays[name])
            bodies[name] = body
        return bodies

    def to_dict(self) -> Dict[str, Any]:
        """The result as a dict: for a scene, equal to its result.json."""
        return json.loads(self._json)

    @property
    def profile(self) -> Optional["Profile"]:
        """The designed profile of a scene with ``[design]`` (a
        :class:`Profile`, callable on positions); None otherwise."""
        block = self._dict.get("design")
        return None if block is None else Profile(block["profile"])

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


_ELEMENT_ARRAYS = ("angle", "load", "max_pressure_inner", "max_pressure_outer", "displacement", "tilt")


class BearingResult(_Fields):
    """A certified bearing solution: every contact of every rolling element
    solved as one system (docs/results.md, "Bearing results").

    Arrays (numpy float64, one value per rolling element, element 0 at the
    load's direction): ``angle`` (degrees), ``load``, ``max_pressure_inner``,
    ``max_pressure_outer``, ``displacement`` (radial, outward) and ``tilt``
    (radians; 0 for balls).

    Fields of result.json as attributes: ``ring_displacement`` (a dict
    ``x``, ``y``, ``z``), ``loaded``, ``load_zone``, ``life`` (a dict, or
    None outside mm and N), ``reference`` (the Hertz springs or the slicing
    model), ``certificate``, ``grid``, ``seconds``...; ``to_dict()`` is the
    whole result.json.
    """

    angle: np.ndarray
    load: np.ndarray
    max_pressure_inner: np.ndarray
    max_pressure_outer: np.ndarray
    displacement: np.ndarray
    tilt: np.ndarray

    def __init__(self, raw: Dict[str, Any]):
        self._json: str = raw["json"]
        self._dict: Dict[str, Any] = json.loads(self._json)
        for name in _ELEMENT_ARRAYS:
            array = np.asarray(raw[name], dtype=np.float64)
            array.setflags(write=False)
            setattr(self, name, array)

    def to_dict(self) -> Dict[str, Any]:
        """The result as a dict, equal to its result.json."""
        return json.loads(self._json)

    def __repr__(self) -> str:
        return (
            f"BearingResult({self._dict['bearing']}, elements={len(self.load)}, "
            f"loaded={self._dict['loaded']}, max_load={float(self.load.max()):.6e}, "
            f"certificate_holds={self._dict['certificate']['holds']})"
        )


def _result(raw: Dict[str, Any]) -> Union[Result, BearingResult]:
    """A run's answer as its class: a bearing's or a contact's."""
    return BearingResult(raw) if "bearing" in raw else Result(raw)


def run(
    scene: Union[str, os.PathLike, Dict[str, Any]], threads: Optional[int] = None
) -> Union[Result, BearingResult]:
    """Runs a scene: a TOML file's path, or a dict with the same keys, on
    ``threads`` threads (default: the cores this process may use; the
    answer does not depend on the count).

    A dict is written as the same TOML a file would hold, so it is validated
    by the same rules, with the same messages (its file named ``<dict>``);
    NaN and infinities reach the scene's checks, which name the field.

    As ``elcon run`` does, the scene's cost is estimated first and a scene
    too big for the memory available is refused (``SolveError``, with the
    estimate and the ceiling) before anything large is allocated.

    Raises ``SceneError`` for a scene that is not valid, ``SolveError`` for a
    solve that failed or a scene too big for the memory available.
    """
    if isinstance(scene, dict):
        return _result(_elcon.run_scene(scene=scene, threads=threads))
    if isinstance(scene, (str, os.PathLike)):
        return _result(_elcon.run_scene(path=os.fspath(scene), threads=threads))
    raise InputError("run() takes a scene's path (a .toml file) or a dict of its keys")


def check(scene: Union[str, os.PathLike, Dict[str, Any]]) -> Dict[str, Any]:
    """Checks a scene (a TOML file's path, or a dict with the same keys) as
    ``elcon check`` does: parsed, validated and its cost estimated against
    the memory ceiling, without solving.

    Returns a dict: ``name``, ``estimate`` (the estimate's summary, as
    ``elcon check`` prints it), ``points``, ``unknowns``, ``peak_bytes``,
    ``seconds`` (the estimate's figures) and ``warnings`` (a list of
    strings). Raises what ``run`` raises before its solve: ``SceneError``
    for a scene that is not valid, ``SolveError`` for one too big for the
    memory available.
    """
    if isinstance(scene, dict):
        return dict(_elcon.check_scene(scene=scene))
    if isinstance(scene, (str, os.PathLike)):
        return dict(_elcon.check_scene(path=os.fspath(scene)))
    raise InputError("check() takes a scene's path (a .toml file) or a dict of its keys")


_SHAPES = {1: "must be one-dimensional, one value per point (shape (N,))",
           2: "must be an (N, N) array"}


def _array(value: Any, name: str, ndim: int, shape: Optional[str] = None) -> Optional[np.ndarray]:
    """``value`` as a contiguous float64 array (any real dtype or layout)
    of ``ndim`` dimensions (1: a vector, 2: a matrix), or InputError naming
    ``name`` and the shape expected (``shape``, else the usual one)."""
    if value is None:
        return None
    if isinstance(value, (str, bytes, dict)) or np.iscomplexobj(value):
        raise InputError(f"`{name}`: not an array of real numbers (got {type(value).__name__})")
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise InputError(f"`{name}`: not an array of numbers ({e})") from None
    if array.ndim != ndim:
        raise InputError(f"`{name}`: {shape or _SHAPES[ndim]}; got shape {array.shape}")
    return np.ascontiguousarray(array)


def _number(value: Any, name: str, required: bool = False) -> Optional[float]:
    """``value`` as a float (any real number: int, float, numpy's scalars
    and 0-d arrays), or None when it may be left out; InputError naming
    ``name`` otherwise. The value's range is the crates' to check."""
    if value is None:
        if required:
            raise InputError(f"`{name}`: required, a number")
        return None
    if (isinstance(value, (bool, np.bool_, str, bytes)) or np.iscomplexobj(value)
            or np.ndim(value) != 0):
        raise InputError(f"`{name}` = {value!r}: must be a number")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"`{name}` = {value!r}: must be a number") from None


def _numbers(value: Any, name: str, count: int, shape: str,
             required: bool = False) -> Optional[tuple]:
    """``count`` floats (``shape`` says which), or None when it may be left
    out; InputError naming ``name`` otherwise."""
    if value is None:
        if required:
            raise InputError(f"`{name}`: required, {shape}")
        return None
    array = _array(value, name, 1, f"must be {shape}")
    if len(array) != count:
        raise InputError(f"`{name}`: must be {shape}; got {len(array)} numbers")
    return tuple(float(v) for v in array)


def _pair(value: Any, name: str) -> Optional[tuple]:
    """Two floats (along x, along y), or None."""
    return _numbers(value, name, 2, "two numbers (along x, along y)")


def _path(value: Any, name: str) -> str:
    """A path (a string or an os.PathLike); InputError naming ``name``."""
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise InputError(f"`{name}` = {value!r}: must be a path (a string or a pathlib.Path)")


def _name(value: Any, name: str) -> Optional[str]:
    """A name (a string), or None; InputError naming ``name`` otherwise."""
    if value is None or isinstance(value, str):
        return value
    raise InputError(f"`{name}` = {value!r}: must be a name (a string)")


def _section(value: Any, name: str) -> Optional[Dict[str, Any]]:
    """A dict of a scene's section, or None; InputError naming ``name``."""
    if value is None or isinstance(value, dict):
        return value
    raise InputError(f"`{name}` = {value!r}: must be a dict of a scene's [{name}] keys")


class ContactProblem:
    """A contact problem from numpy arrays, or from a layout.

    Parameters
    ----------
    x, y:
        The candidate points' coordinates (length), shape ``(N,)``; leave
        ``y`` out for a line (a beam, a plane-strain contact). Any dtype
        and layout is taken (converted to float64). Points on a regular
        grid of the spacing are recognized as a lattice (so the
        matrix-free storage applies to them).
    separation:
        The initial separation at each point (length), shape ``(N,)``; or
        give ``geometry`` instead (default: two planes, zero separation).
    spacing:
        The cell size: ``h`` or ``(dx, dy)`` (length). A point's measure is
        its cell's area (its length on a line): pressure = force / measure.
    points:
        Instead of ``x``, ``y`` and ``spacing``: a layout as a scene's
        ``[points]`` (``{"grid": "rectangle", "half_x": ..., "half_y":
        ..., "nx": ..., "ny": ...}``, ``{"grid": "disk", "spacing": ...,
        "radius": ...}``, ``{"grid": "line", "start": ..., "end": ..., "n":
        ...}``, or relative to the Hertz contact with ``across``/``zone``),
        parsed and checked by the scene's parser.
    influence:
        S as an ``(N, N)`` array (length per force): deflection at k per
        unit force at j, both bodies together. Or give ``body1`` and
        ``body2`` instead.
    body1, body2:
        Dicts as a scene's ``[body1]``: ``{"model": "uniform-patch",
        "youngs_modulus": E, "poissons_ratio": nu}``; models ``rigid``,
        ``uniform-patch``, ``point-force``, ``plane-strain``
        (``reference_distance``), ``winkler`` (``modulus``), ``beam``
        (``youngs_modulus``, ``second_moment`` or ``width`` and ``depth``,
        ``loaded_point``). Parsed and checked by the scene's own parser: an
        unknown key or a value out of range raises ``InputError`` naming
        the field (``body1.youngs_modulus``).
    geometry:
        A dict as a scene's ``[geometry]``: ``{"surface1": {"shape":
        "sphere", "radius": R1}, "surface2": {"shape": "plane"}}`` (or
        ``{"separation": [...]}``), instead of ``separation``. A quadric
        by keyword: ``{"shape": "quadric", "radius_x": Rx, "radius_y": Ry,
        "angle": degrees}`` (an omitted radius straight, a negative one
        concave).
    height_map, height_map_spacing, height_map_origin, height_map_interpolation:
        Heights added to the surfaces: a 2-D array ``Z[j, i]`` at ``(x0 + i
        dx, y0 + j dy)`` (rows along x, as ``numpy.meshgrid`` lays them
        out), its spacing ``(dx, dy)`` (required) and origin ``(x0, y0)``
        (default: the map centred on the origin), interpolated to the
        points as ``height_map_interpolation`` says: ``"linear"`` (the
        default: bilinearly) or ``"cubic"`` (the natural bicubic spline, a
        slope and curvature continuous across the nodes, so that the peak
        pressure converges as the points are refined; a scene's
        ``interpolation``). Checked by elcon-analysis (a NaN, fewer than
        2 x 2 values, a map that does not cover the points raise
        ``InputError``).
    load, approach:
        Load control (force) or displacement control (length): one of them.
    tilt_x, tilt_y, moment_x, moment_y:
        The rotations of body 1 about the x and y axes through the origin
        (where the load acts): prescribed (radians), or free with a moment
        about the origin (force length; default 0: the load acts at the
        origin). The gap changes by ``tilt_x y - tilt_y x``; ``moment_x``
        balances ``sum F y`` and ``moment_y`` balances ``-sum F x``. On a
        line only ``tilt_y`` / ``moment_y`` apply.
    storage:
        How S is held (from bodies): ``"auto"`` (default: folded when the
        problem is mirror symmetric; matrix-free above 2000 unknowns on a
        lattice without a beam; else dense), ``"dense"``, ``"folded"``,
        ``"lattice"`` (matrix-free, solved by the conjugate gradient).

    The problem's cost is estimated before S is assembled and a problem too
    big for the memory available raises ``SolveError``.
    """

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
        height_map: Optional[npt.ArrayLike] = None,
        height_map_spacing: Optional[Sequence[float]] = None,
        height_map_origin: Optional[Sequence[float]] = None,
        height_map_interpolation: Optional[str] = None,
    ):
        if spacing is not None and np.ndim(spacing) == 0:
            h = _number(spacing, "spacing")
            spacing = (h, h)
        else:
            spacing = _numbers(spacing, "spacing", 2, "h or (dx, dy)")
        self._inner = _elcon.ContactProblem(
            _array(x, "x", 1),
            _array(separation, "separation", 1),
            spacing,
            y=_array(y, "y", 1),
            influence=_array(influence, "influence", 2),
            body1=_section(body1, "body1"),
            body2=_section(body2, "body2"),
            load=_number(load, "load"),
            approach=_number(approach, "approach"),
            tilt_x=_number(tilt_x, "tilt_x"),
            tilt_y=_number(tilt_y, "tilt_y"),
            moment_x=_number(moment_x, "moment_x", required=True),
            moment_y=_number(moment_y, "moment_y", required=True),
            geometry=_section(geometry, "geometry"),
            points=_section(points, "points"),
            storage_name=_name(storage, "storage"),
            height_map=_array(height_map, "height_map", 2, "must be a 2-D array z[j, i]"),
            height_map_spacing=_pair(height_map_spacing, "height_map_spacing"),
            height_map_origin=_pair(height_map_origin, "height_map_origin"),
            height_map_interpolation=_name(height_map_interpolation, "height_map_interpolation"),
        )

    def __len__(self) -> int:
        return len(self._inner)

    @property
    def storage(self) -> str:
        """How S is held: ``"dense"``, ``"folded"`` or ``"lattice"``."""
        return self._inner.storage

    @property
    def default_method(self) -> str:
        """The method ``solve()`` uses when given none: block pivoting on a
        dense or folded S, the conjugate gradient matrix-free."""
        return self._inner.default_method

    def solve(self, method: Optional[str] = None, threads: Optional[int] = None) -> Result:
        """Solves with ``method`` (``elcon.methods()``; default: the
        problem's own, ``default_method``) on ``threads`` threads (default:
        the cores this process may use; the answer does not depend on the
        count); the GIL is released."""
        return Result(self._inner.solve(_name(method, "method"), threads))


class Profile:
    """A designed profile ``y(s)``: the drop at the axial position ``s``
    (the scene's coordinate along the design's axis, its length unit), as
    result.json's ``design.profile`` defines it, evaluated by elcon-design
    itself (the code that designed and verified it).

    Call it on a number or an array of any shape: ``profile(0.0)`` is a
    float, ``profile(s)`` an array of ``s``'s shape. ``family`` is
    ``"free"``, ``"quadratic"``, ``"polynomial"``, ``"circular-crown"`` or
    ``"logarithmic-crown"``; a free profile has ``knots`` and ``drops``
    (float64 arrays) and ``interpolation`` (``"natural-cubic-spline"``,
    carried on along its end slopes beyond the end knots, or
    ``"linear"``, flat beyond them); a family has ``None`` there and its
    coefficients in ``to_dict()``.
    """

    def __init__(self, block: Dict[str, Any]):
        self._block = json.loads(json.dumps(block))
        self._inner = _elcon.Profile(json.dumps(block))
        knots = self._inner.knots()
        self.knots: Optional[np.ndarray] = None if knots is None else knots[0]
        self.drops: Optional[np.ndarray] = None if knots is None else knots[1]
        for array in (self.knots, self.drops):
            if array is not None:
                array.setflags(write=False)

    def __call__(self, s: npt.ArrayLike) -> Union[float, np.ndarray]:
        if isinstance(s, (str, bytes, dict)) or np.iscomplexobj(s):
            raise InputError(f"`s`: not a real number or array (got {type(s).__name__})")
        try:
            array = np.asarray(s, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise InputError(f"`s`: not a number or an array of numbers ({e})") from None
        drops = self._inner.drops_at(np.ascontiguousarray(array.ravel()))
        if array.ndim == 0:
            return float(drops[0])
        return drops.reshape(array.shape)

    @property
    def family(self) -> str:
        """The family (the block's ``family``)."""
        return self._inner.family

    @property
    def interpolation(self) -> Optional[str]:
        """A free profile's interpolation between its knots; None for a family."""
        return self._block.get("interpolation")

    def to_dict(self) -> Dict[str, Any]:
        """The profile as a dict: result.json's ``design.profile``."""
        return json.loads(json.dumps(self._block))

    def __repr__(self) -> str:
        if self.knots is not None:
            return (f"Profile(family='free', interpolation='{self.interpolation}', "
                    f"knots={len(self.knots)})")
        return f"Profile(family='{self.family}')"


class Design(_Fields):
    """A certified design, as result.json's ``design`` block: ``family``,
    ``axis``, ``relative_to``, ``parameters`` (the profile's, by name),
    ``objective`` (the worst p_max over the cases, over each case's
    reference intensity), ``objective_before``, ``cases`` (per case: load,
    reference intensity, p_max before and after, certificate),
    ``method`` ("program", "descent", "search" or "set"), ``starts``,
    ``seconds``. ``profile`` is the correction itself, a :class:`Profile`:
    ``design.profile(s)`` is its drop at the axial positions ``s``, and
    ``design.profile.knots`` a free profile's knots. Also
    ``max_intensities`` (p_max per case, corrected), ``max_intensity``
    (their largest) and ``certificates_hold``."""

    def __init__(self, raw: str):
        self._dict = json.loads(raw)
        self.profile = Profile(self._dict["profile"])

    @property
    def max_intensities(self) -> List[float]:
        """The corrected p_max of each case."""
        return [c["max_pressure_after"] for c in self._dict["cases"]]

    @property
    def max_intensity(self) -> float:
        """The largest corrected p_max over the cases."""
        return max(self.max_intensities)

    @property
    def certificates_hold(self) -> bool:
        """Whether every case's re-analysis is certified."""
        return all(c["certificate_holds"] for c in self._dict["cases"])

    def to_dict(self) -> Dict[str, Any]:
        """The design as a dict: result.json's design block."""
        return json.loads(json.dumps(self._dict))


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
) -> Design:
    """Designs a profile correction, by the scene's ``[design]`` keys.

    Over a scene (``problems`` a scene's path or dict): the scene's design
    stage, its ``[design]`` replaced by the keys given (kept when none
    are), run as ``elcon run`` runs it; the result is the scene's
    result.json design block. Every key of a scene's ``[design]`` applies
    (``family``, ``degree``, ``axis``, ``loads``, ``relative_to``,
    ``max_constant``, ``radius_range``, ``flat_length``, ``design_load``,
    ``method``, ``end``, ``misalignments``, ``objective``: ``"pressure"``,
    ``"von-mises"`` or ``"max-shear"``, the worst stress below the surface
    of the scene's elastic bodies).

    Over problems (a list of ``ContactProblem``, each a load case under a
    load): the family's keys (``family``, default ``"quadratic"``;
    ``degree``, ``axis``, ``method``, ``max_constant``, ``radius_range``,
    ``flat_length``, ``design_load``, ``end``), checked by the scene's
    parser; each case's p_max is measured against
    ``reference_intensities`` (default 1). A logarithmic crown is set for
    a roller: derived as a scene derives it when the first problem was
    built from two half-space bodies, a cylinder and a rectangle
    ``points`` layout, else given as ``roller={"combined_modulus": E*,
    "radius": R, "length": L}``.

    The families: ``quadratic``, ``polynomial`` (``degree``), ``free``,
    ``circular-crown`` (``radius_range``, ``flat_length``),
    ``logarithmic-crown`` (``design_load``, ``flat_length``, ``end``).
    Raises ``InputError`` (``SceneError`` over a scene) for keys that are
    not valid, ``DesignError`` when the design fails.
    """
    keys = dict(design_keys)
    for name, value in (("axis", axis), ("family", family), ("degree", degree),
                        ("method", method)):
        if value is not None:
            keys[name] = value
    if isinstance(problems, (str, os.PathLike, dict)):
        if reference_intensities is not None or roller is not None:
            raise InputError(
                "over a scene, the cases' references are `relative_to` and the roller is the "
                "scene's: give `reference_intensities` and `roller` only with problems"
            )
        if isinstance(problems, dict):
            raw = _elcon.design_scene(scene=problems, keys=keys)
        else:
            raw = _elcon.design_scene(path=os.fspath(problems), keys=keys)
        return Design(raw["json"])
    try:
        problems = list(problems)
    except TypeError:
        raise InputError(
            "`problems`: a list of elcon.ContactProblem, or a scene's path or dict"
        ) from None
    for i, p in enumerate(problems):
        if not isinstance(p, ContactProblem):
            raise InputError(f"`problems[{i}]`: not an elcon.ContactProblem")
    keys.setdefault("family", "quadratic")
    refs = _array(reference_intensities, "reference_intensities", 1,
                  "must be one-dimensional, one value per problem")
    inner = [p._inner for p in problems]
    return Design(_elcon.design_problems(
        inner, keys, None if refs is None else refs.tolist(), _section(roller, "roller")))


def batch(
    path: Union[str, os.PathLike], jobs: Optional[int] = None, out: Union[str, os.PathLike] = "out"
) -> Any:
    """Runs a batch file into ``out`` (its tables and every run's outputs, as
    ``elcon batch`` writes them) and returns its runs' table: a pandas
    DataFrame if pandas is installed, else a list of dicts."""
    outcome = json.loads(_elcon.run_batch(_path(path, "path"), _path(out, "out"), jobs))
    rows = outcome["rows"]
    try:
        import pandas  # noqa: F401
    except ImportError:
        return rows
    return pandas.DataFrame(rows)


def hertz_ellipse(
    combined_modulus: float,
    load: float,
    surface1: Sequence[float],
    surface2: Optional[Sequence[float]] = None,
    x: Optional[npt.ArrayLike] = None,
    y: Optional[npt.ArrayLike] = None,
) -> Dict[str, Any]:
    """Hertz's elliptical contact of two quadrics under ``load``.

    Each surface is ``(radius_x, radius_y, angle)``: its principal radii
    along the direction ``angle`` degrees from x and across it
    (``float("inf")`` straight, negative concave; a sphere ``(R, R, 0)``);
    ``combined_modulus`` is E*. Returns ``semi_major``, ``semi_minor``,
    ``angle`` (of the major axis, degrees from x), ``approach``,
    ``peak_pressure``, ``eccentricity`` (solved to rounding from the
    complete elliptic integrals), ``equivalent_radius`` (``sqrt(a b)``)
    and, with the points ``x``, ``y``, ``pressure`` there (a numpy array).
    A gap that does not curve both ways raises ``InputError``.
    """
    quadric = "(radius_x, radius_y, angle)"
    xs, ys = _array(x, "x", 1), _array(y, "y", 1)
    d = _elcon.hertz_ellipse(
        _number(combined_modulus, "combined_modulus", required=True),
        _number(load, "load", required=True),
        _numbers(surface1, "surface1", 3, quadric, required=True),
        _numbers(surface2, "surface2", 3, quadric),
        None if xs is None else xs.tolist(),
        None if ys is None else ys.tolist(),
    )
    if "pressure" in d:
        d["pressure"] = np.asarray(d["pressure"], dtype=np.float64)
    return d


def confine(directory: Union[str, os.PathLike]) -> None:
    """Read data files (height maps, profiles, separation files) only from
    inside ``directory``, for every scene this process runs afterwards: a
    file whose resolved path (symbolic links followed, ``..`` removed) is
    outside it is refused with a SceneError naming the key. For a service
    that runs scenes it did not write; ``elcon --confine DIR`` on the
    command line. Once per process: it cannot be widened or lifted.

    Raises InputError when ``directory`` is not a directory, or the
    process is already confined to another.
    """
    _elcon.confine(os.fspath(directory))


def methods() -> List[str]:
    """The solve methods, by name."""
    return list(_elcon.methods())


def storages() -> List[str]:
    """The storages of S a ContactProblem takes, by name."""
    return list(_elcon.storages())
