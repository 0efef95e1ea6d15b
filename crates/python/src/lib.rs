//! `elcon._elcon`: the Rust side of the Python package.
//!
//! Thin bindings over the crates: a scene from a file or from TOML text
//! (`run_scene`), a batch (`run_batch`), a contact problem from numpy
//! arrays (`ContactProblem`: points, separations, and S given or assembled
//! from body models) and a design over such problems (`design`). Results
//! cross as JSON text (the same serialization as result.json) beside numpy
//! arrays of the per-point values; `python/elcon/__init__.py` wraps them
//! in the user-facing classes. Every solve releases the GIL. Errors are
//! one exception class per kind, their messages the crates' own (a scene's
//! with file:line:col and the field).

use std::path::{Path, PathBuf};

use elcon_analysis::{
    AnalysisError, Body, ContactSolution, Dimension, Loading, Material, Method, Options, PointSet,
};
use elcon_design::{Axis, DesignMethod, DesignOptions, Family};
use elcon_influence::{Beam, Cell};
use elcon_scene::{Scene, SceneError as RustSceneError};
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyDict;

create_exception!(
    _elcon,
    ElconError,
    PyException,
    "Base class of elcon's errors."
);
create_exception!(
    _elcon,
    SceneError,
    ElconError,
    "A scene or batch that is not valid: the message names the file, line, column and field."
);
create_exception!(
    _elcon,
    InputError,
    ElconError,
    "Arrays or parameters given to ContactProblem or design that do not go together."
);
create_exception!(
    _elcon,
    SolveError,
    ElconError,
    "A valid problem whose solve failed, or that is too big for the memory available."
);
create_exception!(_elcon, DesignError, ElconError, "A design that failed.");

/// A scene error as its Python class: input errors (syntax, invalid values)
/// are `SceneError`, run failures `SolveError`.
fn scene_error(e: RustSceneError) -> PyErr {
    if e.is_input_error() {
        SceneError::new_err(e.to_string())
    } else {
        SolveError::new_err(e.to_string())
    }
}

/// An analysis error as its Python class.
fn analysis_error(e: AnalysisError) -> PyErr {
    match e {
        AnalysisError::InvalidInput { .. }
        | AnalysisError::SizeMismatch { .. }
        | AnalysisError::Incompatible { .. } => InputError::new_err(e.to_string()),
        _ => SolveError::new_err(e.to_string()),
    }
}

/// The per-point arrays of a solution, and the separations.
fn arrays<'py>(
    py: Python<'py>,
    points: &PointSet,
    solution: &ContactSolution,
    separation: &[f64],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("x", PyArray1::from_slice(py, &points.xs()))?;
    d.set_item("y", PyArray1::from_slice(py, &points.ys()))?;
    d.set_item("force", PyArray1::from_slice(py, &solution.forces))?;
    d.set_item("pressure", PyArray1::from_slice(py, &solution.pressures))?;
    d.set_item("gap", PyArray1::from_slice(py, &solution.gaps))?;
    d.set_item("separation", PyArray1::from_slice(py, separation))?;
    Ok(d)
}

/// Runs a scene (a file, or TOML text named `name` in messages); returns
/// `{"json": result.json's text, "x": ..., "y": ..., "force": ...,
/// "pressure": ..., "gap": ..., "separation": ...}`.
#[pyfunction]
#[pyo3(signature = (path=None, text=None, name="<dict>"))]
fn run_scene<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    text: Option<String>,
    name: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let (file, text) = match (path, text) {
        (Some(p), None) => {
            let text = std::fs::read_to_string(&p)
                .map_err(|e| SceneError::new_err(format!("{}: {e}", p.display())))?;
            (p, text)
        }
        (None, Some(t)) => (PathBuf::from(name), t),
        _ => {
            return Err(InputError::new_err(
                "give a scene's path or its text, not both",
            ));
        }
    };
    let scene = Scene::from_str(&file, &text).map_err(scene_error)?;
    let run = py
        .detach(|| elcon_scene::run(&scene))
        .map_err(scene_error)?;
    let json = serde_json::to_string_pretty(&run.result)
        .map_err(|e| SolveError::new_err(e.to_string()))?;
    let d = arrays(
        py,
        run.problem.points(),
        &run.solution,
        run.problem.separation(),
    )?;
    d.set_item("json", json)?;
    Ok(d)
}

/// TOML text from JSON text (a dict's `json.dumps`): scene dicts become the
/// same TOML a file would hold, so they pass the same validation.
#[pyfunction]
fn toml_from_json(json: &str) -> PyResult<String> {
    let value: serde_json::Value =
        serde_json::from_str(json).map_err(|e| SceneError::new_err(e.to_string()))?;
    toml::to_string(&value).map_err(|e| {
        SceneError::new_err(format!(
            "the scene dict cannot be written as TOML ({e}): keys are strings, values \
             numbers, strings, booleans, lists or dicts (no None)"
        ))
    })
}

/// Runs a batch file into `out`; returns its results.json text.
#[pyfunction]
#[pyo3(signature = (path, out, jobs=None))]
fn run_batch(py: Python<'_>, path: PathBuf, out: PathBuf, jobs: Option<usize>) -> PyResult<String> {
    let batch = elcon_scene::Batch::from_file(&path).map_err(scene_error)?;
    let options = elcon_scene::BatchOptions {
        jobs,
        shard: None,
        ceiling: elcon_scene::Ceiling::of_this_process(None).map_err(SceneError::new_err)?,
    };
    let outcome = py
        .detach(|| elcon_scene::run_batch(&batch, &out, &options, &()))
        .map_err(scene_error)?;
    serde_json::to_string(&outcome).map_err(|e| SolveError::new_err(e.to_string()))
}

/// A body from its model's keyword arguments (as a scene's `[body1]`).
fn body(spec: &Bound<'_, PyDict>, which: &str) -> PyResult<Body> {
    let get = |key: &str| -> PyResult<Option<f64>> {
        spec.get_item(key)?
            .map(|v| v.extract::<f64>())
            .transpose()
            .map_err(|_| InputError::new_err(format!("`{which}.{key}`: must be a number")))
    };
    let need = |key: &str| -> PyResult<f64> {
        get(key)?.ok_or_else(|| InputError::new_err(format!("`{which}.{key}`: required")))
    };
    let model: String = spec
        .get_item("model")?
        .ok_or_else(|| InputError::new_err(format!("`{which}.model`: required")))?
        .extract()
        .map_err(|_| InputError::new_err(format!("`{which}.model`: must be a string")))?;
    let material = || -> PyResult<Material> {
        Material::new(need("youngs_modulus")?, need("poissons_ratio")?)
            .map_err(|e| InputError::new_err(format!("`{which}`: {e}")))
    };
    Ok(match model.as_str() {
        "rigid" => Body::rigid(),
        "uniform-patch" => Body::uniform_patch(material()?),
        "point-force" => Body::point_force(material()?),
        "plane-strain" => Body::plane_strain(material()?, need("reference_distance")?),
        "winkler" => Body::winkler(need("modulus")?),
        "beam" => Body::beam(Beam {
            youngs_modulus: need("youngs_modulus")?,
            second_moment: need("second_moment")?,
            loaded_point: get("loaded_point")?.unwrap_or(0.0),
        })
        .map_err(|e| InputError::new_err(format!("`{which}`: {e}")))?,
        other => {
            return Err(InputError::new_err(format!(
                "`{which}.model` = \"{other}\": one of rigid, uniform-patch, point-force, \
                 plane-strain, winkler, beam"
            )));
        }
    })
}

/// The solve method by its scene name.
fn method(name: &str) -> PyResult<Method> {
    Method::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        InputError::new_err(format!(
            "`method` = \"{name}\": one of {}",
            names.join(", ")
        ))
    })
}

/// A contact problem from arrays: the candidate points, their separations,
/// and S (given as an N x N array, or assembled from two bodies' models).
#[pyclass(module = "elcon._elcon", name = "ContactProblem")]
struct PyContactProblem {
    inner: elcon_analysis::ContactProblem,
}

#[pymethods]
impl PyContactProblem {
    /// See `elcon.ContactProblem` (python/elcon/__init__.py).
    #[new]
    #[pyo3(signature = (x, separation, spacing, y=None, influence=None, body1=None, body2=None, load=None, approach=None, tilt_x=None, tilt_y=None, moment_x=0.0, moment_y=0.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        x: PyReadonlyArray1<'_, f64>,
        separation: PyReadonlyArray1<'_, f64>,
        spacing: (f64, f64),
        y: Option<PyReadonlyArray1<'_, f64>>,
        influence: Option<PyReadonlyArray2<'_, f64>>,
        body1: Option<Bound<'_, PyDict>>,
        body2: Option<Bound<'_, PyDict>>,
        load: Option<f64>,
        approach: Option<f64>,
        tilt_x: Option<f64>,
        tilt_y: Option<f64>,
        moment_x: f64,
        moment_y: f64,
    ) -> PyResult<Self> {
        let xs = x.as_array().to_vec();
        let (dimension, ys) = match &y {
            Some(y) => (Dimension::Surface, y.as_array().to_vec()),
            None => (Dimension::Line, Vec::new()),
        };
        let cell = Cell {
            dx: spacing.0,
            dy: spacing.1,
        };
        let points = PointSet::from_points(dimension, xs, ys, cell)
            .map_err(|e| InputError::new_err(format!("`x`, `y`, `spacing`: {e}")))?;
        let loading = match (load, approach) {
            (Some(p), None) => Loading::load(p),
            (None, Some(a)) => Loading::approach(a),
            _ => {
                return Err(InputError::new_err(
                    "give `load` or `approach`, one of them",
                ));
            }
        };
        let loading = match (tilt_x, moment_x) {
            (Some(angle), 0.0) => loading.with_tilt_x(angle),
            (Some(_), _) => {
                return Err(InputError::new_err(
                    "`tilt_x` and `moment_x`: give one of them (a prescribed rotation has its \
                     moment as a result)",
                ));
            }
            (None, m) => loading.with_moment_x(m),
        };
        let loading = match (tilt_y, moment_y) {
            (Some(angle), 0.0) => loading.with_tilt_y(angle),
            (Some(_), _) => {
                return Err(InputError::new_err(
                    "`tilt_y` and `moment_y`: give one of them (a prescribed rotation has its \
                     moment as a result)",
                ));
            }
            (None, m) => loading.with_moment_y(m),
        };
        let eps = separation.as_array().to_vec();
        let inner = match (influence, body1, body2) {
            (Some(s), None, None) => {
                let s = s.as_array();
                let (rows, cols) = (s.nrows(), s.ncols());
                let m = faer::Mat::from_fn(rows, cols, |i, j| s[(i, j)]);
                elcon_analysis::ContactProblem::from_parts(points, m, eps, loading)
            }
            (None, Some(b1), Some(b2)) => {
                let (b1, b2) = (body(&b1, "body1")?, body(&b2, "body2")?);
                let geometry = elcon_analysis::Geometry::Separation(eps);
                py.detach(|| {
                    elcon_analysis::ContactProblem::new(points, &b1, &b2, &geometry, loading)
                })
            }
            _ => {
                return Err(InputError::new_err(
                    "give `influence` (an N x N array) or `body1` and `body2`, not both",
                ));
            }
        }
        .map_err(analysis_error)?;
        Ok(Self { inner })
    }

    /// Number of candidate points.
    fn __len__(&self) -> usize {
        self.inner.points().len()
    }

    /// Solves; returns `{"json": the solution's fields, arrays...}`.
    #[pyo3(signature = (method_name="block-pivoting"))]
    fn solve<'py>(&self, py: Python<'py>, method_name: &str) -> PyResult<Bound<'py, PyDict>> {
        let m = method(method_name)?;
        let problem = &self.inner;
        let solution = py
            .detach(|| problem.solve(m, &Options::default()))
            .map_err(analysis_error)?;
        let d = arrays(py, problem.points(), &solution, problem.separation())?;
        d.set_item("json", solution_json(&solution, m).to_string())?;
        Ok(d)
    }
}

/// A solution's fields with result.json's names.
fn solution_json(s: &ContactSolution, m: Method) -> serde_json::Value {
    serde_json::json!({
        "method": m.name(),
        "points": s.forces.len(),
        "approach": s.approach,
        "tilt": { "x": s.tilt_x, "y": s.tilt_y },
        "moment": { "x": s.moment_x, "y": s.moment_y },
        "load_centre": { "x": s.load_centre.0, "y": s.load_centre.1 },
        "load": s.load,
        "max_pressure": s.max_pressure,
        "contact_points": s.contact.len(),
        "contact_extent": s.contact_extent,
        "certificate": serde_json::to_value(s.certificate).unwrap_or_default(),
        "statistics": serde_json::to_value(&s.statistics).unwrap_or_default(),
        "seconds": { "assembly": s.assembly_seconds, "solve": s.solve_seconds },
        "warnings": s.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>(),
    })
}

/// Designs the correction of `family` over the problems (each under a
/// load); returns the design as JSON text.
#[pyfunction]
#[pyo3(signature = (problems, axis="x", family="quadratic", degree=None, method_name="auto", reference_intensities=None))]
fn design(
    py: Python<'_>,
    problems: Vec<PyRef<'_, PyContactProblem>>,
    axis: &str,
    family: &str,
    degree: Option<usize>,
    method_name: &str,
    reference_intensities: Option<Vec<f64>>,
) -> PyResult<String> {
    let axis = match axis {
        "x" => Axis::X,
        "y" => Axis::Y,
        other => {
            return Err(InputError::new_err(format!(
                "`axis` = \"{other}\": one of x, y"
            )));
        }
    };
    let family = match (family, degree) {
        ("quadratic", None) => Family::Quadratic,
        ("free", None) => Family::Free,
        ("polynomial", Some(degree)) => Family::Polynomial { degree },
        ("polynomial", None) => {
            return Err(InputError::new_err("`degree`: required for a polynomial"));
        }
        (other, _) => {
            return Err(InputError::new_err(format!(
                "`family` = \"{other}\" (degree only with polynomial): one of quadratic, polynomial, free"
            )));
        }
    };
    let method = DesignMethod::of(method_name).ok_or_else(|| {
        let names: Vec<&str> = DesignMethod::ALL.iter().map(|m| m.name()).collect();
        InputError::new_err(format!(
            "`method` = \"{method_name}\": one of {}",
            names.join(", ")
        ))
    })?;
    let cases: Vec<elcon_analysis::ContactProblem> =
        problems.iter().map(|p| p.inner.clone()).collect();
    let options = DesignOptions {
        method,
        reference_intensities,
        ..DesignOptions::default()
    };
    let d = py
        .detach(|| elcon_design::design(&cases, axis, family, &options))
        .map_err(|e| DesignError::new_err(e.to_string()))?;
    let table = d
        .profile
        .table(&d.stations)
        .map_err(|e| DesignError::new_err(e.to_string()))?;
    let json = serde_json::json!({
        "family": d.profile.family(),
        "method": d.solver.method().name(),
        "objective": d.objective,
        "max_intensity": d.max_intensity,
        "max_intensities": d.evaluation.max_intensities,
        "table": table,
        "certificates_hold": d.evaluation.solutions.iter().all(|s| s.certificate.holds()),
        "starts": d.starts.iter().map(|s| match &s.result {
            Ok(v) => format!("{}: objective {v:.6e}", s.label),
            Err(e) => format!("{}: failed: {e}", s.label),
        }).collect::<Vec<_>>(),
    });
    Ok(json.to_string())
}

/// The names of the solve methods.
#[pyfunction]
fn methods() -> Vec<&'static str> {
    Method::ALL.iter().map(|m| m.name()).collect()
}

/// Whether `path` exists (used by the Python side to tell a path from TOML
/// text given as a string).
#[pyfunction]
fn is_file(path: &str) -> bool {
    Path::new(path).is_file()
}

/// The module.
#[pymodule]
fn _elcon(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ElconError", py.get_type::<ElconError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("DesignError", py.get_type::<DesignError>())?;
    m.add_class::<PyContactProblem>()?;
    m.add_function(wrap_pyfunction!(run_scene, m)?)?;
    m.add_function(wrap_pyfunction!(toml_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(run_batch, m)?)?;
    m.add_function(wrap_pyfunction!(design, m)?)?;
    m.add_function(wrap_pyfunction!(methods, m)?)?;
    m.add_function(wrap_pyfunction!(is_file, m)?)?;
    Ok(())
}
