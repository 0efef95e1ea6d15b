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


def test_the_stresses_below_the_surface_come_as_arrays_beside_result_json(tmp_path):
    import tomllib

    scene = tomllib.loads((SCENES / "hertz-cylinders.toml").read_text())
    scene["outputs"] = {"subsurface": True}
    result = elcon.run(scene)
    assert elcon.run(SCENES / "hertz-cylinders.toml").subsurface is None
    block = result.subsurface
    assert block["stress_unit"] == result.to_dict()["units"]["pressure"]
    for name in ("body1", "body2"):
        body = block[name]
        assert body["applicable"]
        section = body["section"]
        n, m = len(section["x"]), len(section["depth"])
        for component in ("sigma_x", "sigma_z", "tau_xz", "von_mises", "tresca"):
            assert section[component].shape == (n, m), component
        # The block's maximum is the section's, refined between its depths.
        largest = section["von_mises"].max()
        assert largest <= body["von_mises"]["value"] * (1 + 1e-12)
        assert largest > 0.97 * body["von_mises"]["value"]
        # Johnson's line contact: the largest shear 0.30 p0 at 0.786 b.
        p0 = result.max_pressure
        assert body["tresca"]["value"] / p0 == pytest.approx(0.3003, rel=0.01)
        assert body["profile"]["von_mises"].shape == (1, m)


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
    import tomllib

    # On the scene's own grid (not refined): the arrays are its points.
    as_dict = tomllib.loads((SCENES / "example2-beam-design.toml").read_text())
    as_dict["design"]["refine"] = False
    scene = elcon.run(as_dict)
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
    # The correction is a callable profile: at the points, an array of
    # their shape, its smallest drop 0; at one position, a float.
    drops = d.profile(scene.x)
    assert drops.shape == (len(scene.x),) and drops.dtype == np.float64
    assert drops.min() == pytest.approx(0.0, abs=1e-15)
    assert d.profile.family == "quadratic" and d.profile.knots is None
    block = d.to_dict()["profile"]
    assert isinstance(d.profile(1.0), float)
    assert d.profile(1.0) == pytest.approx(block["a"] + block["b"] + block["c"], rel=1e-14)
    assert d.profile(scene.x.reshape(4, -1)).shape == (4, len(scene.x) // 4)
    # A scene's run gives its designed profile too (none without [design]).
    assert scene.profile.to_dict() == scene.to_dict()["design"]["profile"]
    np.testing.assert_allclose(scene.profile(scene.x), drops, rtol=1e-9, atol=1e-12 * drops.max())
    assert elcon.run(SCENES / "example1-spheres.toml").profile is None


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


# --- The scene's own checks, from Python (issue 26 item 5, issue 31) ---


def beam_line(n=80):
    """Example 2's beam on its foundation: 80 cells over 8.9 in."""
    return (np.arange(n) + 0.5) * 8.9 / n - 4.45


def test_body_dicts_are_parsed_and_checked_by_the_scenes_parser():
    x = beam_line()
    n = len(x)
    h = 8.9 / n
    foundation = {"model": "winkler", "modulus": 1e7}
    with pytest.raises(elcon.InputError, match=r"`body1.youngs_modulus` = -30000000: must be > 0"):
        elcon.ContactProblem(x, np.zeros(n), h,
                             body1={"model": "beam", "youngs_modulus": -30e6,
                                    "second_moment": -64 / 12},
                             body2=foundation, load=5e4)
    # An unknown key is refused by the schema, naming it.
    with pytest.raises(elcon.InputError, match="unknown field `loaded_pt`"):
        elcon.ContactProblem(x, np.zeros(n), h,
                             body1={"model": "beam", "youngs_modulus": 30e6,
                                    "second_moment": 64 / 12, "loaded_pt": 3.0},
                             body2=foundation, load=5e4)
    # A key of another model, as a scene refuses it.
    with pytest.raises(elcon.InputError, match=r"`body2.poissons_ratio`.*not a parameter"):
        elcon.ContactProblem(x, np.zeros(n), h,
                             body1={"model": "beam", "youngs_modulus": 30e6, "second_moment": 1.0},
                             body2={"model": "winkler", "modulus": 1e7, "poissons_ratio": 0.3},
                             load=5e4)
    # NaN reaches the scene's check, which names the field.
    with pytest.raises(elcon.InputError, match=r"`body2.modulus` = NaN: must be a finite number"):
        elcon.ContactProblem(x, np.zeros(n), h,
                             body1={"model": "beam", "youngs_modulus": 30e6, "second_moment": 1.0},
                             body2={"model": "winkler", "modulus": float("nan")}, load=5e4)
    # width and depth (the scene's keys): I = w d^3 / 12, the same beam.
    by_moment = elcon.ContactProblem(
        x, np.zeros(n), h, body1={"model": "beam", "youngs_modulus": 30e6,
                                  "second_moment": 4.0 ** 3 / 12},
        body2=foundation, load=5e4).solve()
    by_section = elcon.ContactProblem(
        x, np.zeros(n), h, body1={"model": "beam", "youngs_modulus": 30e6, "width": 1.0,
                                  "depth": 4.0},
        body2=foundation, load=5e4).solve()
    assert np.array_equal(by_moment.force, by_section.force)
    # The bodies against the grid: a beam's loaded point on the beam.
    with pytest.raises(elcon.InputError, match=r"`body1.loaded_point` = 9: is outside the beam"):
        elcon.ContactProblem(x, np.zeros(n), h,
                             body1={"model": "beam", "youngs_modulus": 30e6, "second_moment": 1.0,
                                    "loaded_point": 9.0},
                             body2=foundation, load=5e4)


def test_a_beams_x_is_a_line_grid_as_the_scene_lays_it_out():
    # The scene's rule, by the scene's check: x increasing by the spacing.
    # Uneven x with one spacing would give each point a cell of the wrong
    # width (p_max +12 %); unsorted x is said to be unsorted.
    x = beam_line()
    n = len(x)
    h = 8.9 / n
    beam = {"model": "beam", "youngs_modulus": 30e6, "second_moment": 64.0 / 12.0}
    foundation = {"model": "winkler", "modulus": 1e7}
    uneven = np.sign(x) * np.abs(x) ** 1.3 / 4.45 ** 0.3
    with pytest.raises(elcon.InputError, match=r"`points` = x\[1\] = .*not the spacing 0.11125.*a line grid"):
        elcon.ContactProblem(uneven, np.zeros(n), h, body1=beam, body2=foundation, load=5e4)
    swapped = x.copy()
    swapped[[3, 4]] = swapped[[4, 3]]
    with pytest.raises(elcon.InputError, match=r"x\[4\] = .*is not above x\[3\]"):
        elcon.ContactProblem(swapped, np.zeros(n), h, body1=beam, body2=foundation, load=5e4)
    with pytest.raises(elcon.InputError, match=r"is not above x\[0\]"):
        elcon.ContactProblem(x[::-1], np.zeros(n), h, body1=beam, body2=foundation, load=5e4)
    # The same points in order solve.
    assert elcon.ContactProblem(x, np.zeros(n), h, body1=beam, body2=foundation,
                                load=5e4).solve().certificate["holds"]


def test_surfaces_and_a_layout_are_parsed_by_the_scenes_parsers():
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    spheres = {"surface1": {"shape": "sphere", "radius": 1.0},
               "surface2": {"shape": "sphere", "radius": 10.0}}
    h = 0.0025
    # The layout as a scene's [points], the surfaces as its [geometry].
    from_layout = elcon.ContactProblem(body1=steel, body2=steel, geometry=spheres,
                                       points={"grid": "disk", "spacing": h, "radius": 0.04},
                                       load=100.0)
    solved = from_layout.solve()
    assert solved.certificate["holds"]
    # The same points and separations as arrays: the same solution.
    r = 1.0 / (1.0 / 1.0 + 1.0 / 10.0)
    separation = (solved.x ** 2 + solved.y ** 2) / (2 * r)
    assert np.allclose(solved.separation, separation, rtol=1e-12, atol=1e-18)
    from_arrays = elcon.ContactProblem(solved.x, solved.separation, h, y=solved.y, body1=steel,
                                       body2=steel, load=100.0).solve()
    assert np.allclose(from_arrays.force, solved.force, rtol=0, atol=1e-9 * solved.force.max())
    # A sphere on a line, refused as the scene refuses it.
    with pytest.raises(elcon.InputError, match=r"`geometry.surface1.shape` = \"sphere\""):
        elcon.ContactProblem(np.linspace(-1, 1, 11), None, 0.2,
                             body1={"model": "plane-strain", "youngs_modulus": 30e6,
                                    "poissons_ratio": 0.3, "reference_distance": 10.0},
                             body2={"model": "rigid"}, geometry=spheres, load=1.0)
    with pytest.raises(elcon.InputError, match=r"`geometry.surface1.radius`"):
        elcon.ContactProblem(body1=steel, body2=steel, load=1.0,
                             geometry={"surface1": {"shape": "sphere", "radius": 0.0}},
                             points={"grid": "disk", "spacing": h, "radius": 0.04})
    with pytest.raises(elcon.InputError, match=r"`points.nx`"):
        elcon.ContactProblem(body1=steel, body2=steel, load=1.0, geometry=spheres,
                             points={"grid": "rectangle", "half_x": 1.0, "half_y": 1.0, "nx": 0,
                                     "ny": 3})
    with pytest.raises(elcon.InputError, match="not both"):
        elcon.ContactProblem(solved.x, solved.separation, h, y=solved.y, body1=steel, body2=steel,
                             geometry=spheres, load=100.0)


def test_storage_auto_runs_a_large_grid_from_arrays_matrix_free():
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    h = 0.0005
    i, j = np.meshgrid(np.arange(250) - 124.5, np.arange(240) - 119.5, indexing="ij")
    x, y = (i * h).ravel(), (j * h).ravel()
    spheres = {"surface1": {"shape": "sphere", "radius": 1.0},
               "surface2": {"shape": "sphere", "radius": 10.0}}
    problem = elcon.ContactProblem(x, None, h, y=y, body1=steel, body2=steel, geometry=spheres,
                                   load=100.0)
    assert len(problem) == 60000
    # Points on a regular grid are a lattice: "auto" holds S matrix-free
    # above 2000 unknowns, and solve() takes the conjugate gradient.
    assert problem.storage == "lattice"
    assert problem.default_method == "conjugate-gradient"
    solved = problem.solve()
    d = solved.to_dict()
    assert d["method"] == "conjugate-gradient" and d["influence"] == "matrix-free"
    assert solved.certificate["holds"]
    # The pivoting methods read S's entries, which it does not hold.
    with pytest.raises(elcon.InputError, match="matrix-free"):
        problem.solve("block-pivoting")
    # Each storage by name; a beam has no lattice operator.
    small = elcon.ContactProblem(x[:9], None, h, y=y[:9], body1=steel, body2=steel,
                                 geometry=spheres, load=1.0, storage="dense")
    assert small.storage == "dense" and small.default_method == "block-pivoting"
    with pytest.raises(elcon.InputError, match=r"`storage` = \"sparse\": one of auto, dense"):
        elcon.ContactProblem(x[:9], None, h, y=y[:9], body1=steel, body2=steel, load=1.0,
                             storage="sparse")
    assert elcon.storages() == ["auto", "dense", "folded", "lattice"]
    with pytest.raises(elcon.InputError, match=r"`storage`: \"lattice\" cannot hold an S given as a matrix"):
        elcon.ContactProblem(x[:4], np.zeros(4), h, y=y[:4], influence=np.eye(4), load=1.0,
                             storage="lattice")


def test_a_problems_dict_is_result_jsons_serialization():
    scene = elcon.run(SCENES / "example1-spheres.toml").to_dict()
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    spheres = {"surface1": {"shape": "sphere", "radius": 1.0},
               "surface2": {"shape": "sphere", "radius": 10.0}}
    r = elcon.run(SCENES / "example1-spheres.toml")
    dx = np.diff(np.unique(r.x)).min()
    solved = elcon.ContactProblem(r.x, None, dx, y=r.y, body1=steel, body2=steel,
                                  geometry=spheres, load=100.0).solve().to_dict()
    # result.json's solution fields, in result.json's order, by the same
    # serde type (SolutionJson).
    fields = ["approach", "tilt", "moment", "load_centre", "load", "max_pressure",
              "contact_points", "contact_extent", "certificate", "warnings"]
    assert [k for k in solved if k in fields] == fields
    assert [k for k in scene if k in fields] == fields
    assert set(solved["certificate"]) == set(scene["certificate"])
    # The same header, seconds and solution, by the same types: a problem's
    # keys are result.json's but for the scene's own blocks.
    scene_only = {"scene", "file", "description", "units", "discretization", "subsurface",
                  "reference", "design", "inputs"}
    assert set(solved) == set(scene) - scene_only
    assert set(solved["seconds"]) == set(scene["seconds"])
    assert set(solved["statistics"]) == set(scene["statistics"])
    assert solved["points"] == scene["points"] and solved["dimension"] == "surface"
    assert solved["storage"] == "folded" and solved["symmetry"] == scene["symmetry"]
    assert solved["max_pressure"] == pytest.approx(scene["max_pressure"], rel=1e-12)


def roller_with_design(tmp_path, design_toml):
    """The crowned roller's scene with its [design] replaced."""
    text = (SCENES / "crowned-roller.toml").read_text()
    head = text[: text.index("[design]")]
    tail = text[text.index("[outputs]"):]
    path = tmp_path / "roller.toml"
    path.write_text(head + design_toml + "\n" + tail)
    return path


def cli_design(tmp_path, scene):
    out = tmp_path / "out"
    subprocess.run([str(cli()), "run", str(scene), "--out", str(out)], check=True,
                   capture_output=True)
    return json.loads((out / "crowned-roller" / "result.json").read_text())["design"]


def assert_as_written(design, written, *case_fields):
    """``design`` is the CLI's ``written`` design block (but for times): its
    objective, parameters and profile, and each case's ``case_fields``."""
    assert without_times(design.to_dict()) == without_times(written)
    assert design.objective == written["objective"]
    assert design.parameters == written["parameters"]
    assert design.profile.to_dict() == written["profile"]
    for field in case_fields:
        assert [c[field] for c in design.cases] == [c[field] for c in written["cases"]], field


def test_design_over_the_crowned_roller_equals_the_clis_result_json(tmp_path):
    # The free profile: the scene's own [design].
    written = cli_design(tmp_path, SCENES / "crowned-roller.toml")
    free = elcon.design(SCENES / "crowned-roller.toml")
    assert_as_written(free, written, "max_pressure_after")
    assert free.family == "free" and free.certificates_hold
    # Its profile: the natural cubic spline through the 40 stations of the
    # scene's grid, and profile.csv the same profile's values, to the bit.
    assert free.profile.interpolation == "natural-cubic-spline"
    assert free.profile.knots.shape == free.profile.drops.shape == (40,)
    assert np.array_equal(free.profile(free.profile.knots), free.profile.drops)
    csv = tmp_path / "out" / "crowned-roller" / "profile.csv"
    assert csv.read_text().startswith("# y_mm,drop_mm\n")
    samples = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert (samples[0, 0], samples[-1, 0]) == (-5.0, 5.0)
    assert len(samples) == 10 * 80 + 1   # ten to a station of its 18 x 80 design grid
    assert np.array_equal(free.profile(samples[:, 0]), samples[:, 1])
    assert written["profile_spacing"] == pytest.approx(10.0 / 800, rel=1e-15)
    # A logarithmic crown: the [design] keys as keywords, and the same keys
    # in the scene's file through the CLI.
    keys = dict(family="logarithmic-crown", loads=[1000.0, 5000.0, 10000.0],
                relative_to="hertz", axis="y", end="lundberg")
    scene = roller_with_design(
        tmp_path, '[design]\nfamily = "logarithmic-crown"\nloads = [1000.0, 5000.0, 10000.0]\n'
        'relative_to = "hertz"\naxis = "y"\nend = "lundberg"\n')
    written = cli_design(tmp_path / "log", scene)
    crown = elcon.design(SCENES / "crowned-roller.toml", **keys)
    assert_as_written(crown, written, "max_pressure_before", "max_pressure_after")
    assert crown.method == "set"
    # The scene as a dict, likewise.
    import tomllib

    as_dict = tomllib.loads((SCENES / "crowned-roller.toml").read_text())
    assert without_times(elcon.design(as_dict, **keys).to_dict()) == without_times(written)
    # Over problems built from the same bodies, surfaces and layout, the
    # roller is derived as the scene derives it: the same crown and the
    # same re-analyses.
    steel = {"model": "uniform-patch", "youngs_modulus": 210e3, "poissons_ratio": 0.3}
    cylinder = {"surface1": {"shape": "cylinder", "radius": 5.0}, "surface2": {"shape": "plane"}}
    layout = {"grid": "rectangle", "zone": 1.6, "half_y": 5.0, "nx": 9, "ny": 40}
    problems = [elcon.ContactProblem(body1=steel, body2=steel, geometry=cylinder, points=layout,
                                     load=load) for load in (1000.0, 5000.0, 10000.0)]
    references = [c["reference_intensity"] for c in written["cases"]]
    over = elcon.design(problems, family="logarithmic-crown", axis="y", end="lundberg",
                        reference_intensities=references)
    assert over.parameters == written["parameters"]
    assert over.profile.to_dict() == written["profile"]
    assert over.profile_spacing is None   # no profile.csv over problems
    assert over.max_intensities == [c["max_pressure_after"] for c in written["cases"]]
    assert over.objective == written["objective"]


def test_every_family_from_problems_with_the_scenes_names_and_errors():
    problem = elcon.ContactProblem(
        beam_line(), np.zeros(80), 8.9 / 80,
        body1={"model": "beam", "youngs_modulus": 30e6, "second_moment": 64.0 / 12.0},
        body2={"model": "winkler", "modulus": 1e7}, load=50000.0)
    quadratic = elcon.design([problem], family="quadratic")
    cubic = elcon.design([problem], family="polynomial", degree=3)
    free = elcon.design([problem], family="free")
    crown = elcon.design([problem], family="circular-crown", radius_range=[1e2, 1e6])
    log = elcon.design([problem], family="logarithmic-crown",
                       roller={"combined_modulus": 30e6, "radius": 1.0, "length": 8.9})
    assert quadratic.family == "quadratic" and cubic.family == "polynomial (degree 3)"
    assert free.family == "free" and crown.method == "search" and log.method == "set"
    assert cubic.objective <= quadratic.objective * (1 + 1e-9)
    assert free.objective <= cubic.objective * (1 + 1e-9)
    for d in (quadratic, cubic, free, crown, log):
        assert d.certificates_hold and d.axis == "x" and d.relative_to == "absolute"
    # The designed profiles improve on none (a crown, searched or set, is a
    # crown: on a centrally loaded beam it raises the middle's peak).
    assert crown.objective > crown.objective_before
    for d in (quadratic, cubic, free):
        assert d.objective <= d.objective_before * (1 + 1e-9)
    # The scene's errors, naming the key.
    with pytest.raises(elcon.InputError, match=r"`design.degree` = -2: must be at least 0"):
        elcon.design([problem], family="polynomial", degree=-2)
    with pytest.raises(elcon.InputError, match=r"`design.degree`.*only for family"):
        elcon.design([problem], family="free", degree=2)
    with pytest.raises(elcon.InputError, match=r"`design.radius_range`.*required"):
        elcon.design([problem], family="circular-crown")
    with pytest.raises(elcon.InputError, match="unknown variant `cubic`"):
        elcon.design([problem], family="cubic")
    with pytest.raises(elcon.InputError, match="unknown field `radius`"):
        elcon.design([problem], family="circular-crown", radius=3.0)
    with pytest.raises(elcon.InputError, match=r"`design.family` = \"logarithmic-crown\""):
        elcon.design([problem], family="logarithmic-crown")
    # On a line, the profile runs along x (as the scene refuses axis = "y").
    with pytest.raises(elcon.InputError, match=r"`design.axis` = \"y\": a line grid lies along x"):
        elcon.design([problem], family="free", axis="y")
    # The problems are the cases: loads and relative_to belong to a scene.
    with pytest.raises(elcon.InputError, match=r"`design.loads`"):
        elcon.design([problem], family="free", loads=[1.0])
    with pytest.raises(elcon.InputError, match=r"`design.profile_spacing`.*writes no file"):
        elcon.design([problem], family="free", profile_spacing=0.1)
    # A free profile from problems is linear between its stations, flat
    # beyond them.
    assert free.profile.interpolation == "linear"
    knots, drops = free.profile.knots, free.profile.drops
    assert free.profile(knots[0] - 1.0) == drops[0]
    middle = 0.5 * (knots[3] + knots[4])
    assert free.profile(middle) == pytest.approx(0.5 * (drops[3] + drops[4]), rel=1e-14)
    with pytest.raises(elcon.InputError, match=r"`s`: positions must be finite"):
        free.profile([0.0, float("nan")])
    # A design that fails names the scene's key, as `elcon run` does: a
    # crown radius below the beam's half-length (4.45 in).
    with pytest.raises(elcon.DesignError,
                       match=r"^`design.radius_range` \(a crown radius searched in it\) = "
                             r"[0-9.e+-]+: the crown is asked beyond its radius") as failed:
        elcon.design([problem], family="circular-crown", radius_range=[1.0, 2.0])
    assert "circular_crown" not in str(failed.value)
    # A design load whose Hertz width passes the crowned length: refused
    # by the scene's parser before the design, naming the call's key.
    with pytest.raises(elcon.InputError, match=r"`design.design_load` = 1000000000000: the Hertz "
                       r"half-width at this load exceeds the crowned half-length") as failed:
        elcon.design([problem], family="logarithmic-crown", design_load=1e12,
                     roller={"combined_modulus": 30e6, "radius": 1.0, "length": 8.9})
    assert "log_crown" not in str(failed.value)
    # The roller given by the call is named by the call's key, not the
    # scene's grid.
    assert "roller.length" in str(failed.value) and "half_y" not in str(failed.value)


def test_python_is_as_safe_as_the_cli(tmp_path, monkeypatch):
    # (a) A scene too big for the memory available is refused before its
    # assembly, with the estimate (here the ceiling is set by the variable).
    monkeypatch.setenv("ELCON_MEMORY_LIMIT", "1G")
    import time
    import tomllib

    punch = tomllib.loads((SCENES / "flat-punch.toml").read_text())
    punch["points"]["spacing"] = 0.01 / 80
    punch["solver"] = {"method": "block-pivoting", "symmetry": "none"}
    start = time.monotonic()
    with pytest.raises(elcon.SolveError, match=r"too big for the memory available.*ELCON_MEMORY_LIMIT"):
        elcon.run(punch)
    assert time.monotonic() - start < 5.0
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    i, j = np.meshgrid(np.arange(150), np.arange(140), indexing="ij")
    with pytest.raises(elcon.SolveError, match=r"too big for the memory available.*storage=\"lattice\""):
        elcon.ContactProblem((i * 1e-3).ravel(), None, 1e-3, y=(j * 1e-3).ravel(), body1=steel,
                             body2=steel, load=1.0, storage="dense")
    monkeypatch.delenv("ELCON_MEMORY_LIMIT")
    # (b) Arrays of any dtype and layout; 2-D where 1-D is expected refused.
    n, h, k = 10, 0.1, 2.0e6
    x = (np.arange(n) - 0.5 * (n - 1)) * h
    s = np.eye(n) / (k * h)
    reference = elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=500.0).solve("lemke")
    grid = np.zeros((n, 3))
    grid[:, 1] = x
    spread = np.zeros((2 * n, 2 * n))
    spread[::2, ::2] = s
    for xs, sep, infl in [
        (grid[:, 1], np.zeros(n, dtype=np.int64), np.asfortranarray(s)),  # a column, ints, Fortran
        (np.repeat(x, 2)[::2], np.zeros(2 * n)[::2], spread[::2, ::2]),  # strided views
        (list(x), [0] * n, s.tolist()),  # lists
    ]:
        got = elcon.ContactProblem(xs, sep, h, influence=infl, load=500.0).solve("lemke")
        assert np.array_equal(got.force, reference.force)
    with pytest.raises(elcon.InputError, match=r"`x`: must be one-dimensional.*\(2, 5\)"):
        elcon.ContactProblem(x.reshape(2, 5), np.zeros(n), h, influence=s, load=1.0)
    with pytest.raises(elcon.InputError, match=r"`separation`: must be one-dimensional"):
        elcon.ContactProblem(x, np.zeros((n, 1)), h, influence=s, load=1.0)
    with pytest.raises(elcon.InputError, match=r"`influence`: must be an \(N, N\) array"):
        elcon.ContactProblem(x, np.zeros(n), h, influence=np.ones(n), load=1.0)
    # (c) Negative counts are input errors.
    with pytest.raises(elcon.InputError, match=r"`jobs` = -2"):
        elcon.batch(SCENES / "convergence.toml", jobs=-2, out=tmp_path)
    # (d) NaN in a scene dict: the field named, not a JSON parser's column.
    scene = tomllib.loads((SCENES / "example1-spheres.toml").read_text())
    scene["loading"]["load"] = float("nan")
    with pytest.raises(elcon.SceneError, match=r"`loading.load` = NaN"):
        elcon.run(scene)
    scene["loading"]["load"] = None
    with pytest.raises(elcon.SceneError, match=r"`loading.load` = None"):
        elcon.run(scene)
    # (e) A design over a beam and a sphere at once.
    beam = elcon.ContactProblem(
        beam_line(20), np.zeros(20), 8.9 / 20,
        body1={"model": "beam", "youngs_modulus": 30e6, "second_moment": 1.0},
        body2={"model": "winkler", "modulus": 1e7}, load=10.0)
    sphere = elcon.ContactProblem(
        body1=steel, body2=steel, points={"grid": "disk", "spacing": 0.01, "radius": 0.05},
        geometry={"surface1": {"shape": "sphere", "radius": 1.0}}, load=10.0)
    with pytest.raises(elcon.InputError, match=r"`problems\[1\]`: is a surface.*problems\[0\] is a line"):
        elcon.design([beam, sphere])
    # (g) A cell whose compliance overflows: said so, not the engine's `m`.
    xs = np.arange(5) * 1e-300
    i, j = np.meshgrid(xs, xs, indexing="ij")
    with pytest.raises(elcon.InputError,
                       match=r"`body1`, `body2` and `spacing` = \(1e-300, 1e-300\).*"
                             r"not in one consistent unit system"):
        elcon.ContactProblem(i.ravel(), np.zeros(25), 1e-300, y=j.ravel(), body1=steel,
                             body2=steel, load=1.0).solve()
    # A modulus below the normal floating-point range: the scene's check.
    with pytest.raises(elcon.InputError,
                       match=r"`body1.youngs_modulus` = 1e-308: must be at least 2.2e-308"):
        elcon.ContactProblem(i.ravel() * 1e300, np.zeros(25), 1.0, y=j.ravel() * 1e300,
                             body1={**steel, "youngs_modulus": 1e-308}, body2=steel, load=1.0)


def test_threads_change_nothing_of_a_matrix_free_solve():
    # Example 1's spheres on about 5,000 points, matrix-free: the same
    # forces to the bit on one thread and on three; a count below 1 is an
    # input error.
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    h = 0.0005
    i = np.arange(-40, 41)
    x, y = [v.ravel() * h for v in np.meshgrid(i, i, indexing="ij")]
    keep = np.hypot(x, y) <= 40 * h
    x, y = x[keep], y[keep]
    separation = (x**2 + y**2) / (2 * (1.0 * 10.0 / 11.0))
    problem = elcon.ContactProblem(
        x, separation, h, y=y, body1=steel, body2=steel, load=100.0, storage="lattice"
    )
    one = problem.solve("conjugate-gradient", threads=1)
    three = problem.solve("conjugate-gradient", threads=3)
    assert one.certificate["holds"]
    assert np.array_equal(one.force, three.force)
    with pytest.raises(elcon.InputError):
        problem.solve("conjugate-gradient", threads=0)


def test_hertz_ellipse_and_quadrics_by_keyword_match_the_ball_bearing_scene():
    # The ball-bearing example's reference, from the function and from the scene.
    e_star = 210e3 / (2 * (1 - 0.3 ** 2))
    ball = (3.969, 3.969, 0.0)
    race = (15.5, -0.52 * 7.938, 0.0)
    h = elcon.hertz_ellipse(e_star, 1000.0, ball, race, x=[0.0, 0.0], y=[0.0, 5.0])
    scene = elcon.run(SCENES / "ball-bearing.toml")
    ref = scene.reference
    assert ref["kind"] == "hertz-ellipse"
    assert h["semi_major"] == pytest.approx(ref["semi_axes"][0], rel=1e-12)
    assert h["semi_minor"] == pytest.approx(ref["semi_axes"][1], rel=1e-12)
    assert h["approach"] == pytest.approx(ref["approach"], rel=1e-12)
    assert h["angle"] == pytest.approx(90.0)
    assert h["pressure"][0] == pytest.approx(h["peak_pressure"], rel=1e-15)
    assert h["pressure"][1] == 0.0
    # A sphere's limit: Hertz's circle, a^3 = 3 P R / (4 E*).
    circle = elcon.hertz_ellipse(e_star, 100.0, (1.0, 1.0, 0.0))
    assert circle["semi_major"] == pytest.approx((3 * 100.0 / (4 * e_star)) ** (1 / 3), rel=1e-14)
    assert circle["eccentricity"] == 0.0
    # A cylinder alone is a line contact: refused.
    with pytest.raises(elcon.InputError, match="curvature"):
        elcon.hertz_ellipse(e_star, 100.0, (1.0, float("inf"), 0.0))
    # The quadric by keyword through the scene's parser, on the ellipse grid.
    steel = {"model": "uniform-patch", "youngs_modulus": 210e3, "poissons_ratio": 0.3}
    geometry = {"surface1": {"shape": "sphere", "radius": 3.969},
                "surface2": {"shape": "quadric", "radius_x": 15.5, "radius_y": -4.12776}}
    solved = elcon.ContactProblem(body1=steel, body2=steel, geometry=geometry,
                                  points={"grid": "ellipse", "across": 31, "zone": 1.2},
                                  load=1000.0).solve()
    assert solved.approach == pytest.approx(scene.approach, rel=1e-12)


def test_a_height_map_array_adds_to_the_surfaces_and_bad_maps_are_refused():
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    sphere = {"surface1": {"shape": "sphere", "radius": 1.0}}
    points = {"grid": "disk", "spacing": 0.0025, "radius": 0.04}
    plain = elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                                 load=100.0).solve()
    # A uniform 1e-4 map adds 1e-4 to every separation and to the approach.
    z = np.full((5, 7), 1e-4)
    lifted = elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                                  load=100.0, height_map=z,
                                  height_map_spacing=(0.02, 0.02)).solve()
    assert np.allclose(lifted.separation, plain.separation + 1e-4, rtol=0, atol=1e-15)
    assert lifted.approach == pytest.approx(plain.approach + 1e-4, rel=1e-9)
    # A hole, a map that does not cover the disk: elcon-analysis's checks.
    holed = z.copy()
    holed[2, 3] = np.nan
    with pytest.raises(elcon.InputError, match="row 2, column 3"):
        elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                             load=100.0, height_map=holed, height_map_spacing=(0.02, 0.02))
    with pytest.raises(elcon.InputError, match="does not cover"):
        elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                             load=100.0, height_map=z, height_map_spacing=(0.001, 0.001))
    with pytest.raises(elcon.InputError, match="height_map_spacing"):
        elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                             load=100.0, height_map=z)


def test_a_height_map_array_is_interpolated_cubically_by_name(tmp_path):
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    sphere = {"surface1": {"shape": "sphere", "radius": 1.0}}
    points = {"grid": "disk", "spacing": 0.0025, "radius": 0.04}
    plain = elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                                 load=100.0)
    # A quadratic map, 25 x 25 heights 0.01 apart: away from its natural
    # edges (the disk lies 8 nodes in) the cubic spline reproduces it
    # between the nodes, where the bilinear one does not.
    xs = -0.12 + 0.01 * np.arange(25)
    ys = -0.12 + 0.01 * np.arange(25)
    gx, gy = np.meshgrid(xs, ys)
    quadratic = lambda x, y: 0.05 * x * x - 0.03 * x * y + 0.02 * y * y
    z = quadratic(gx, gy)
    exact = plain.solve().separation
    made = {}
    for name in (None, "linear", "cubic"):
        kwargs = {} if name is None else {"height_map_interpolation": name}
        made[name] = elcon.ContactProblem(
            body1=steel, body2=steel, geometry=sphere, points=points, load=100.0,
            height_map=z, height_map_spacing=(0.01, 0.01), **kwargs).solve()
    cubic = made["cubic"]
    added = quadratic(np.asarray(cubic.x), np.asarray(cubic.y))
    scale = np.abs(z).max()
    assert np.allclose(cubic.separation, exact + added, rtol=0, atol=1e-6 * scale)
    assert np.array_equal(made[None].separation, made["linear"].separation)
    assert np.abs(made["linear"].separation - exact - added).max() > 1e-4 * scale
    with pytest.raises(elcon.InputError, match=r"`height_map_interpolation` = \"spline\": one of linear, cubic"):
        elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                             load=100.0, height_map=z, height_map_spacing=(0.01, 0.01),
                             height_map_interpolation="spline")
    with pytest.raises(elcon.InputError, match="go with `height_map`"):
        elcon.ContactProblem(body1=steel, body2=steel, geometry=sphere, points=points,
                             load=100.0, height_map_interpolation="cubic")
    # A profile file in `geometry`, read by the scene's parser.
    crown = tmp_path / "crown.csv"
    crown.write_text("".join(f"{float(y)!r}, {0.01 * float(y) ** 3!r}\n" for y in ys))
    profiled = {}
    for name in ("linear", "cubic"):
        geometry = dict(sphere, profile={"file": str(crown), "interpolation": name})
        profiled[name] = elcon.ContactProblem(body1=steel, body2=steel, geometry=geometry,
                                              points=points, load=100.0).solve()
    gap = np.abs(profiled["cubic"].separation - profiled["linear"].separation).max()
    assert gap > 1e-3 * 0.01 * 0.06**3
    with pytest.raises(elcon.InputError, match="geometry.profile.interpolation"):
        elcon.ContactProblem(body1=steel, body2=steel, points=points, load=100.0,
                             geometry=dict(sphere, profile={"file": str(crown),
                                                            "interpolation": "spline"}))


def test_ctrl_c_ends_a_long_solve_with_keyboard_interrupt():
    # Example 1 unfolded at 71 across by Lemke's method: 5089 points, about
    # 10 s of pivots. SIGINT a second into the pivots stops the solve at its
    # next pivot (the solver polls the cancel token the signal check sets)
    # and raises KeyboardInterrupt, not the solve's result a while later.
    import signal
    import threading
    import tomllib

    slow = tomllib.loads((SCENES / "example1-spheres.toml").read_text())
    slow["points"]["across"] = 71
    slow["solver"]["method"] = "lemke"
    slow["solver"]["symmetry"] = "none"
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            elcon.run(slow)
    finally:
        timer.cancel()
    # Nothing is left running: the next run is answered as usual.
    assert elcon.run(SCENES / "example1-spheres.toml").load > 0


def test_a_design_for_the_von_mises_stress_over_a_scene_and_refused_over_problems():
    import tomllib

    scene = tomllib.loads((SCENES / "example1-spheres.toml").read_text())
    scene["points"] = {"grid": "disk", "spacing": 0.002, "radius": 0.02}
    scene["solver"] = {"symmetry": "none"}
    scene.pop("outputs", None)
    d = elcon.design(scene, family="quadratic", refine=False, objective="von-mises")
    assert d.minimized == "von-mises" and d.method == "descent"
    assert d.worst_stress > 0 and d.certificates_hold
    # Problems from arrays carry no body to take a field from: the design
    # crate's refusal, naming the key.
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    i = np.arange(-10, 11) * 0.002
    x, y = [v.ravel() for v in np.meshgrid(i, i, indexing="ij")]
    problem = elcon.ContactProblem(x, (x**2 + y**2) / 2.0, 0.002, y=y, body1=steel,
                                   body2=steel, load=100.0)
    with pytest.raises(elcon.ElconError, match="objective"):
        elcon.design([problem], axis="y", objective="von-mises")


def test_a_contact_problem_under_a_moment_keeps_to_the_small_rotation_theory():
    # Example 1's spheres from arrays on a disk of 1.3 Hertz radii: the load
    # centre at 0.1 a runs; at 0.9 a the contact leans on the points' edge,
    # which the result's warnings say (arrays cannot declare where the body
    # ends); a moment that turns the body past 0.1 rad is refused.
    steel = {"model": "uniform-patch", "youngs_modulus": 30e6, "poissons_ratio": 0.3}
    radius = 1.0 * 10.0 / 11.0
    a = (3 * 100.0 * radius / (4 * 30e6 / (2 * (1 - 0.3**2)))) ** (1 / 3)   # Hertz
    h = a / 10
    i = np.arange(-13, 14)
    x, y = [v.ravel() * h for v in np.meshgrid(i, i, indexing="ij")]
    keep = np.hypot(x, y) <= 1.3 * a + 1e-12
    x, y = x[keep], y[keep]
    separation = (x**2 + y**2) / (2 * radius)

    def solved(moment, load=100.0):
        return elcon.ContactProblem(x, separation, h, y=y, body1=steel, body2=steel,
                                    load=load, moment_x=moment).solve()

    assert solved(0.1 * a * 100.0).certificate["holds"]
    leaning = solved(0.9 * a * 100.0)
    assert any("edge" in w for w in leaning.warnings), leaning.warnings
    # Rigid bodies on a soft diagonal influence: a moment tips the flat
    # line by more than 0.1 rad, beyond the linearized rotation.
    n, h1 = 20, 0.05
    xs = (np.arange(n) - 0.5 * (n - 1)) * h1
    soft = np.eye(n) * 10.0
    with pytest.raises(elcon.SolveError, match="beyond the small-rotation theory"):
        elcon.ContactProblem(xs, np.zeros(n), h1, influence=soft, load=1.0,
                             moment_y=-0.4).solve()


def test_a_problem_s_loading_and_threads_pass_the_scene_s_and_the_command_line_s_checks():
    # The loading goes through the scene's parser: a prescribed rotation is
    # bounded as a scene's is, with the scene's message, and a tilt with a
    # moment about the same axis is refused as a scene refuses it.
    n, h = 8, 0.1
    x = (np.arange(n) - 3.5) * h
    s = np.eye(n)
    with pytest.raises(elcon.InputError, match=r"`loading.tilt_x` = 0.5: at most 0.1 rad in size"):
        elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=1.0, tilt_x=0.5)
    with pytest.raises(elcon.InputError, match=r"loading.moment_y.*loading.tilt_y.*not both"):
        elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=1.0, tilt_y=0.01, moment_y=2.0)
    with pytest.raises(elcon.InputError, match=r"give exactly one of load"):
        elcon.ContactProblem(x, np.zeros(n), h, influence=s)
    # Threads and jobs are bounded per core as on the command line.
    problem = elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=1.0, tilt_y=0.01)
    with pytest.raises(elcon.InputError, match=r"`threads` = 1000000: at most 4 threads per core"):
        problem.solve("lemke", threads=10**6)
    with pytest.raises(elcon.InputError, match=r"`jobs` = 1000000: at most 4 runs per core"):
        elcon.batch(SCENES / "convergence.toml", jobs=10**6, out="unused")


def test_every_argument_is_converted_or_refused_naming_it():
    # Numbers of any real type, arrays of any real dtype: the same problem.
    # Everything else (strings, shapes, bools, complex, counts out of range)
    # is an InputError naming the argument, never TypeError, ValueError or
    # OverflowError.
    n, h, k = 8, 0.25, 2.0**21
    x = (np.arange(n) - 3.5) * h  # x and S exact in float32
    s = np.eye(n) / (k * h)
    reference = elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=500.0).solve("lemke")
    narrow = elcon.ContactProblem(x.astype(np.float32), np.zeros(n, dtype=np.int32),
                                  np.float32(h), influence=s.astype(np.float32),
                                  load=np.int16(500)).solve("lemke")
    assert np.array_equal(narrow.force, reference.force)
    problem = elcon.ContactProblem(x, np.zeros(n), h, influence=s, load=500.0)
    refused = [
        (r"`spacing` = 'a'", dict(spacing="a")),
        (r"`spacing`: must be h or \(dx, dy\); got 3", dict(spacing=(h, h, h))),
        (r"`load` = 'a'", dict(load="a")),
        (r"`load` = array", dict(load=np.array([500.0, 1.0]))),
        (r"`load` = True", dict(load=True)),
        (r"`tilt_y` = \(1\+1j\)", dict(tilt_y=1 + 1j)),
        (r"`x`: not an array of real numbers", dict(x=x + 1j)),
        (r"`x`: not an array of numbers", dict(x=["a"] * n)),
        (r"`storage` = 3: must be a name", dict(storage=3)),
        (r"`body1` = 3: must be a dict", dict(body1=3)),
        (r"`height_map_spacing`: must be two numbers.*got 3", dict(
            height_map=np.zeros((3, 3)), height_map_spacing=(1.0, 2.0, 3.0))),
        (r"`height_map`: must be a 2-D array", dict(height_map=np.zeros(3))),
        (r"`influence`\[2, 3\] = NaN: must be a finite number",
         dict(influence=np.where(np.arange(n * n).reshape(n, n) == 19, np.nan, s))),
    ]
    for message, change in refused:
        given = dict(x=x, separation=np.zeros(n), spacing=h, influence=s, load=500.0)
        given.update(change)
        with pytest.raises(elcon.InputError, match=message):
            elcon.ContactProblem(**given)
    with pytest.raises(elcon.InputError, match=r"`method` = 3: must be a name"):
        problem.solve(3)
    for threads in ("2", 2**70, True, -1, 1.5):
        with pytest.raises(elcon.InputError, match=r"`threads` = .*: must be a whole number >= 1"):
            problem.solve("lemke", threads=threads)
    with pytest.raises(elcon.InputError, match=r"`threads` = 1180591620717411303424"):
        elcon.run(SCENES / "example1-spheres.toml", threads=2**70)
    assert problem.solve("lemke", threads=np.int64(1)).force.tolist() == reference.force.tolist()
    for jobs in (2**70, -1, "1"):
        with pytest.raises(elcon.InputError, match=r"`jobs` = .*: must be a whole number >= 0"):
            elcon.batch(SCENES / "convergence.toml", jobs=jobs, out="unused")
    with pytest.raises(elcon.InputError, match=r"`path` = 3: must be a path"):
        elcon.batch(3)
    # The design's and Hertz's arguments.
    with pytest.raises(elcon.InputError, match=r"`problems`: a list of elcon.ContactProblem"):
        elcon.design(3)
    with pytest.raises(elcon.InputError, match=r"`roller` = 3: must be a dict"):
        elcon.design([problem], family="logarithmic-crown", roller=3)
    with pytest.raises(elcon.InputError, match=r"`reference_intensities`: must be one-dim"):
        elcon.design([problem], reference_intensities=np.ones((1, 1)))
    with pytest.raises(elcon.InputError, match=r"`design.degree` = 1180591620717411303424"):
        elcon.design([problem], family="polynomial", degree=2**70)
    with pytest.raises(elcon.InputError, match=r"`surface1`: must be \(radius_x, radius_y, angle\)"):
        elcon.hertz_ellipse(1e5, 1.0, np.ones((3, 1)))
    with pytest.raises(elcon.InputError, match=r"`surface1`: .*got 2 numbers"):
        elcon.hertz_ellipse(1e5, 1.0, (1.0, 1.0))
    with pytest.raises(elcon.InputError, match=r"`x`: must be one-dimensional.*\(2, 2\)"):
        elcon.hertz_ellipse(1e5, 1.0, (1.0, 1.0, 0.0), x=np.zeros((2, 2)), y=np.zeros((2, 2)))
    with pytest.raises(elcon.InputError, match=r"`load` = 'a'"):
        elcon.hertz_ellipse(1e5, "a", (1.0, 1.0, 0.0))


def test_check_validates_and_estimates_a_scene_without_solving(monkeypatch):
    import tomllib

    scene = tomllib.loads((SCENES / "example1-spheres.toml").read_text())
    checked = elcon.check(scene)
    assert checked == elcon.check(SCENES / "example1-spheres.toml")
    assert checked["name"] == "example1-spheres"
    assert checked["points"] == elcon.run(scene).to_dict()["points"]
    assert checked["unknowns"] <= checked["points"] and checked["peak_bytes"] > 0
    assert checked["estimate"] and isinstance(checked["warnings"], list)
    # The refusals of `run`, before its solve.
    scene["body1"]["youngs_modulu"] = 30e6
    with pytest.raises(elcon.SceneError, match="unknown field `youngs_modulu`"):
        elcon.check(scene)
    del scene["body1"]["youngs_modulu"]
    monkeypatch.setenv("ELCON_MEMORY_LIMIT", "1M")
    with pytest.raises(elcon.SolveError, match="too big for the memory available"):
        elcon.check(scene)
    with pytest.raises(elcon.InputError, match="check\\(\\) takes a scene's path"):
        elcon.check(3)


# --- A fuzz of run and check from Python (ELCON_FUZZ=1 to run it) ---

_EXTREMES = [0, -1, 1, 3, 0.5, 1e308, -1e308, 1e-308, 5e-324, float("nan"), float("inf"),
             float("-inf"), 2**63 - 1, -(2**63), 2**70, "", "x", "plane", "sphere", [], {},
             True, None, [1.0, 2.0], [-1.0, 1e300], np.float32("nan"), np.int64(-7),
             np.array([1.0, 2.0]), np.zeros((2, 2)), 1 + 2j, object()]


def _leaves(d, path=()):
    """The paths of a nested dict's values (lists' items included)."""
    items = d.items() if isinstance(d, dict) else enumerate(d)
    for k, v in items:
        yield path + (k,)
        if isinstance(v, (dict, list)):
            yield from _leaves(v, path + (k,))


def _mutate(scene, rng):
    """One random edit of ``scene`` (in place): a value set to an extreme,
    scaled or negated, or to a string; a key dropped, renamed (a typo, or
    another section's key) or a section duplicated under another name."""
    paths = list(_leaves(scene))
    path = paths[rng.integers(len(paths))]
    parent = scene
    for k in path[:-1]:
        parent = parent[k]
    key = path[-1]
    value = parent[key]
    # Scaling a number keeps most scenes valid, so that the solves see
    # extreme values too: it is drawn as often as the other edits together.
    kind = rng.choice(7, p=[0.15, 0.5, 0.07, 0.07, 0.07, 0.04, 0.1])
    if kind == 0:
        parent[key] = _EXTREMES[rng.integers(len(_EXTREMES))]
    elif kind == 1 and isinstance(value, (int, float)) and not isinstance(value, bool):
        parent[key] = value * [-1, 0, 1e-300, 1e300, 10, 0.1][rng.integers(6)]
    elif kind == 2 and isinstance(parent, dict):
        del parent[key]
    elif kind == 3 and isinstance(parent, dict):
        typo = key[:-1] if len(key) > 1 and rng.integers(2) else key + "s"
        parent[typo] = parent.pop(key)
    elif kind == 4 and isinstance(parent, dict):
        other = [p[-1] for p in paths if isinstance(p[-1], str) and p[-1] != key]
        if other:
            parent[other[rng.integers(len(other))]] = parent.pop(key)
    elif kind == 5 and isinstance(parent, list):
        del parent[key]
    else:
        parent[key] = str(value)


@pytest.mark.skipif(os.environ.get("ELCON_FUZZ") != "1", reason="set ELCON_FUZZ=1 to fuzz")
def test_fuzz_run_and_check_raise_only_elcons_errors():
    # Mutated example scenes through check, and through run when the check
    # passes and the estimate is small: every case ends in a result or an
    # ElconError subclass, never a PanicException, another exception or a
    # panic caught at the boundary (a SolveError saying "internal error").
    # ELCON_FUZZ_SEED and ELCON_FUZZ_CASES explore further.
    import collections
    import copy
    import tomllib

    seed = int(os.environ.get("ELCON_FUZZ_SEED", "20261"))
    cases = int(os.environ.get("ELCON_FUZZ_CASES", "300"))
    rng = np.random.default_rng(seed)
    scenes = []
    for path in sorted(SCENES.glob("*.toml")):
        text = path.read_text()
        if "[batch]" not in text:
            scenes.append(tomllib.loads(text))
    counts = collections.Counter()
    solve_errors = collections.Counter()
    failures = []
    for case in range(cases):
        scene = copy.deepcopy(scenes[rng.integers(len(scenes))])
        for _ in range(1 + rng.integers(2)):
            _mutate(scene, rng)
        try:
            checked = elcon.check(scene)
            counts["check: valid"] += 1
            if checked["seconds"] < 0.5 and checked["points"] <= 5000:
                result = elcon.run(scene)
                counts["run: result"] += 1
                assert isinstance(result, elcon.Result)
        except elcon.ElconError as e:
            counts[type(e).__name__] += 1
            if "internal error" in str(e):  # a panic caught at the boundary
                failures.append((case, type(e).__name__, str(e)[:300], repr(scene)[:300]))
            elif isinstance(e, elcon.SolveError):
                solve_errors[str(e)[:120]] += 1
        except BaseException as e:  # a PanicException is a BaseException
            if isinstance(e, KeyboardInterrupt):
                raise
            failures.append((case, type(e).__name__, str(e)[:300], repr(scene)[:300]))
    print(f"\nfuzz seed {seed}, {cases} cases: {dict(counts)}; {len(failures)} failures")
    print(f"solve errors: {dict(solve_errors)}")
    assert not failures, failures[:5]


def test_confine_refuses_data_files_outside_its_directory(tmp_path):
    # The confinement is the process's: tried in a child interpreter.
    inside = tmp_path / "inside"
    inside.mkdir()
    crown = (SCENES / "data" / "measured-crown.csv").read_bytes()
    (inside / "crown.csv").write_bytes(crown)
    (tmp_path / "outside.csv").write_bytes(crown)
    text = (SCENES / "measured-crown.toml").read_text()
    for name, file in [("ok", "crown.csv"), ("out", "../outside.csv")]:
        scene = text.replace('file = "data/measured-crown.csv"', f'file = "{file}"')
        (inside / f"{name}.toml").write_text(scene)
    script = f"""
import sys, elcon
elcon.confine({str(inside)!r})
elcon.check({str(inside / 'ok.toml')!r})
try:
    elcon.check({str(inside / 'out.toml')!r})
except elcon.SceneError as e:
    assert 'geometry.profile.file' in str(e) and 'confined' in str(e), str(e)
else:
    sys.exit('a file outside the confinement was read')
try:
    elcon.confine({str(tmp_path)!r})
except elcon.InputError as e:
    assert 'already confined' in str(e), str(e)
else:
    sys.exit('the confinement was widened')
"""
    import sys
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


def test_a_bearing_scene_runs_as_the_cli_runs_it_with_its_elements_as_arrays(tmp_path):
    scene = SCENES / "ball-bearing-radial.toml"
    r = elcon.run(scene)
    assert isinstance(r, elcon.BearingResult)
    assert r.load.shape == (9,) and r.load.dtype == np.float64
    assert r.angle[0] == 0.0 and r.load[0] == r.load.max()
    assert r.certificate["holds"] and r.loaded == 3
    # The same answer as the command line's result.json.
    subprocess.run([cli(), "run", scene, "--out", tmp_path], check=True, capture_output=True)
    cli_json = json.loads((tmp_path / "ball-bearing-radial" / "result.json").read_text())
    assert without_times(r.to_dict()) == without_times(cli_json)
    # A dict with the same keys, and the core's own messages for bad data.
    d = {
        "units": {"length": "mm", "force": "N", "pressure": "MPa"},
        "material": {"youngs_modulus": 210e3, "poissons_ratio": 0.3},
        "bearing": {
            "type": "roller", "roller_diameter": 9.0, "roller_length": 9.0,
            "crown": {"shape": "circular", "drop": 0.008, "flat": 4.5},
            "inner_raceway_diameter": 57.0, "outer_raceway_diameter": 75.03,
            "rollers": 20, "radial_load": 8000.0, "misalignment": 0.001,
        },
    }
    roller = elcon.run(d)
    assert roller.tilt.shape == (20,) and roller.tilt[0] > 0.0
    assert elcon.check(d)["zones"] == 40
    d["bearing"]["rollers"] = 0
    with pytest.raises(elcon.SceneError, match="bearing.rollers"):
        elcon.run(d)
