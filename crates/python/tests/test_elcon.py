"""The Python package against the command line and the crates.

Run from the checkout after `pip install ./crates/python` (and `cargo build
--release`, which the CLI comparison runs): `pytest crates/python/tests`.
"""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import elcon

ROOT = Path(__file__).resolve().parents[3]
SCENES = ROOT / "examples" / "scenes"


def cli() -> Path:
    """The elcon binary the Rust build left (the CI builds it first)."""
    binary = Path(os.environ.get("ELCON_BIN", ROOT / "target" / "release" / "elcon"))
    assert binary.exists(), f"{binary} not built: run `cargo build --release` first"
    return binary


def without_times(d):
    """A result.json without its run times (they differ from run to run,
    at every level: the run's, each attempt's) and the file's name."""
    if isinstance(d, dict):
        return {k: without_times(v) for k, v in d.items() if k not in ("seconds", "file")}
    if isinstance(d, list):
        return [without_times(v) for v in d]
    return d


def test_example1_equals_the_clis_result_json_to_the_last_digit(tmp_path):
    scene = SCENES / "example1-spheres.toml"
    subprocess.run([str(cli()), "run", str(scene), "--out", str(tmp_path)], check=True,
                   capture_output=True)
    written = json.loads((tmp_path / "example1-spheres" / "result.json").read_text())
    result = elcon.run(scene)
    assert without_times(result.to_dict()) == without_times(written)
    assert result.approach == written["approach"]
    assert result.max_pressure == written["max_pressure"]
    assert result.certificate["holds"]


def test_arrays_have_the_documented_shapes_and_dtypes():
    result = elcon.run(SCENES / "example1-spheres.toml")
    n = result.to_dict()["points"]
    for name in ("x", "y", "force", "pressure", "gap", "separation"):
        array = getattr(result, name)
        assert isinstance(array, np.ndarray)
        assert array.dtype == np.float64 and array.shape == (n,), name
        assert not array.flags.writeable, name
    assert result.force.sum() == pytest.approx(result.load, rel=1e-12)
    # Complementarity at every point, from the arrays.
    scale = result.force.max() * max(result.gap.max(), 1e-300)
    assert np.all(result.force * result.gap <= 1e-9 * scale)
    assert set(result.tilt) == {"x", "y"} and set(result.moment) == {"x", "y"}
    assert isinstance(result.warnings, list)
    assert result.statistics["attempts"]


def test_a_scene_dict_runs_like_its_file():
    import tomllib

    scene = SCENES / "example1-spheres.toml"
    as_dict = tomllib.loads(scene.read_text())
    from_dict = elcon.run(as_dict)
    from_file = elcon.run(scene)
    a, b = without_times(from_dict.to_dict()), without_times(from_file.to_dict())
    assert a == b


def test_a_contact_problem_from_arrays_equals_the_scene():
    result = elcon.run(SCENES / "example1-spheres.toml")
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    dx = np.diff(np.unique(result.x)).min()
    problem = elcon.ContactProblem(
        result.x, result.separation, dx, y=result.y, body1=steel, body2=steel, load=100.0
    )
    assert len(problem) == len(result.x)
    solved = problem.solve("block-pivoting")
    assert solved.certificate["holds"]
    # The scene solved the problem folded by its symmetry, the arrays in
    # full: the same discrete solution, to rounding.
    scale = result.force.max()
    assert np.max(np.abs(solved.force - result.force)) <= 1e-9 * scale
    assert solved.approach == pytest.approx(result.approach, rel=1e-12)


def test_an_influence_matrix_given_as_an_array():
    # A Winkler bed under a flat rigid punch: S diagonal, the pressure
    # uniform. The points centred on the origin, where the load acts (the
    # rotation is free, with no moment about it).
    n, h, k, load = 10, 0.1, 2.0e6, 500.0
    x = (np.arange(n) - 0.5 * (n - 1)) * h
    s = np.eye(n) / (k * h)
    problem = elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=load)
    solved = problem.solve("lemke")
    assert np.allclose(solved.pressure, load / (n * h), rtol=1e-12)
    assert solved.approach == pytest.approx(load / (n * h) / k, rel=1e-12)
    # Off the origin, the rotation held (tilt_y = 0): the same answer.
    shifted = elcon.ContactProblem(x + 1.0, np.zeros(n), h, influence=s, load=load, tilt_y=0.0)
    assert np.allclose(shifted.solve("lemke").pressure, load / (n * h), rtol=1e-12)
    # A moment about y balances -sum F x: a negative one loads the +x side.
    tipped = elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=load,
                                  moment_y=-0.01 * load).solve()
    assert tipped.pressure[-1] > tipped.pressure[0]
    assert tipped.moment["y"] == pytest.approx(-0.01 * load, rel=1e-9)


def test_the_design_from_arrays_equals_the_scenes():
    scene = elcon.run(SCENES / "example2-beam-design.toml")
    expected = scene.to_dict()["design"]["objective"]
    beam = {"model": "beam", "youngs_modulus": 30e6, "second_moment": 64.0 / 12.0}
    foundation = {"model": "winkler", "modulus": 1e7}
    problem = elcon.ContactProblem(
        scene.x, np.zeros(len(scene.x)), 8.9 / len(scene.x), body1=beam, body2=foundation,
        load=50000.0,
    )
    d = elcon.design([problem], axis="x", family="quadratic")
    assert d.objective == pytest.approx(expected, rel=1e-12)
    assert d.certificates_hold
    assert d.positions.shape == d.drops.shape == (len(scene.x),)
    assert d.drops.min() == pytest.approx(0.0, abs=1e-15)


def test_bad_input_raises_its_class_with_the_field_named():
    import tomllib

    scene = tomllib.loads((SCENES / "example1-spheres.toml").read_text())
    scene["body1"]["poissons_ratio"] = 0.7
    with pytest.raises(elcon.SceneError, match=r"`body1.poissons_ratio`"):
        elcon.run(scene)
    scene["body1"]["poissons_ratio"] = "0.3"
    with pytest.raises(elcon.SceneError, match=r"`body1.poissons_ratio`"):
        elcon.run(scene)
    with pytest.raises(elcon.SceneError):
        elcon.run(SCENES / "no-such-scene.toml")
    x = np.linspace(0.0, 1.0, 5)
    with pytest.raises(elcon.InputError, match="load"):
        elcon.ContactProblem(x, np.zeros(5), 0.25, influence=np.eye(5))
    with pytest.raises(elcon.InputError, match="separation|influence"):
        elcon.ContactProblem(x, np.zeros(4), 0.25, influence=np.eye(5), load=1.0)
    with pytest.raises(elcon.InputError, match=r"`body1.model`"):
        elcon.ContactProblem(x, np.zeros(5), 0.25, body1={"model": "jelly"},
                             body2={"model": "rigid"}, load=1.0)
    problem = elcon.ContactProblem(x, np.zeros(5), 0.25, influence=np.eye(5), load=1.0)
    with pytest.raises(elcon.InputError, match=r"`method`"):
        problem.solve("newton")
    moved = elcon.ContactProblem(x, np.zeros(5), 0.25, influence=np.eye(5), approach=1e-3)
    with pytest.raises(elcon.DesignError, match="displacement controlled"):
        elcon.design([moved])
    assert issubclass(elcon.SceneError, elcon.ElconError)
    assert issubclass(elcon.SolveError, elcon.ElconError)


def test_a_batch_returns_its_table(tmp_path):
    base = (SCENES / "example1-spheres.toml").read_text()
    (tmp_path / "base.toml").write_text(base)
    (tmp_path / "sweep.toml").write_text(
        '[batch]\nname = "sweep"\nscene = "base.toml"\n'
        '[[batch.group]]\n"loading.load" = [50.0, 100.0]\n'
    )
    rows = elcon.batch(tmp_path / "sweep.toml", jobs=1, out=tmp_path / "out")
    if not isinstance(rows, list):
        rows = rows.to_dict("records")
    assert [r["status"] for r in rows] == ["ok", "ok"]
    assert (tmp_path / "out" / "sweep" / "results.json").exists()
