//! `elcon._elcon`: the Rust side of the Python package.
//!
//! Thin bindings over the crates: a scene from a file or a dict
//! (`run_scene`), a batch (`run_batch`), a contact problem from numpy
//! arrays or from a layout (`ContactProblem`: points, separations, and S
//! given or assembled from body models) and a design over such problems or
//! over a scene (`design_problems`, `design_scene`). Python's dicts become
//! the TOML a scene holds and go through the scene crate's own parsers and
//! checks (`elcon_scene::problem_parts`, `elcon_scene::design_over`,
//! `elcon_scene::scene_with_design`), so a body, a surface or a design key
//! is checked once, with one message naming the field. Results cross as
//! JSON text of the scene crate's serde types (result.json's
//! `SolutionJson`, `DesignJson`) beside numpy arrays of the per-point
//! values; `python/elcon/__init__.py` wraps them in the user-facing
//! classes.
//!
//! Every solve releases the GIL and is estimated against the memory
//! ceiling the command line uses before anything of size N x N is
//! allocated. Every call into the crates runs inside
//! `elcon_scene::isolated`, so a Rust panic reaches Python as a
//! `SolveError` ("internal error"), never as a `PanicException`. Errors are
//! one exception class per kind, their messages the crates' own.

use std::path::{Path, PathBuf};
use std::time::Instant;

use elcon_analysis::{
    AnalysisError, ContactProblem, ContactSolution, Dimension, Geometry, Loading, Method, Options,
    PointSet, Storage, Surface,
};
use elcon_design::{Analysis, Axis, Profile, Roller, axial_stations, evaluate};
use elcon_influence::Cell;
use elcon_scene::{
    BASELINE, BodySpec, Ceiling, DesignCaseJson, DesignJson, DesignLayoutParts, PointsSpec, Scene,
    SceneError as RustSceneError, SolutionJson, SymmetryJson, human, isolated,
};
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde::Serialize;

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

/// A scene crate's error about the parts given to `ContactProblem` or
/// `design` (keyword arguments, not a scene): input errors are
/// `InputError`, the rest `SolveError`.
fn parts_error(e: RustSceneError) -> PyErr {
    if e.is_input_error() {
        InputError::new_err(e.to_string())
    } else {
        SolveError::new_err(e.to_string())
    }
}

/// An analysis error as its Python class. A non-finite entry of the
/// engine's matrix (S itself, assembled from finite, validated moduli and
/// cell sizes) means the cell's compliance overflowed: said so, as input.
fn analysis_error(e: AnalysisError) -> PyErr {
    if let AnalysisError::Engine(elcon_lcp::LcpError::NonFinite {
        field: "m", value, ..
    }) = &e
    {
        return InputError::new_err(format!(
            "S, assembled from the bodies' moduli and the cell size, has a non-finite entry \
             ({value}): a cell's compliance is outside floating-point range, so the moduli, \
             the spacing and the load are not in one consistent unit system ({e})"
        ));
    }
    match e {
        AnalysisError::InvalidInput { .. }
        | AnalysisError::SizeMismatch { .. }
        | AnalysisError::NonFinite { .. }
        | AnalysisError::Incompatible { .. }
        | AnalysisError::NeedsEntries { .. }
        | AnalysisError::Influence(_) => InputError::new_err(e.to_string()),
        _ => SolveError::new_err(e.to_string()),
    }
}

/// Runs `f` inside `elcon_scene::isolated`: a panic becomes a `SolveError`
/// naming `what` ("internal error"), never a Python `PanicException`.
fn guarded<T>(what: &str, f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    isolated(what, || Ok(f())).unwrap_or_else(|e| Err(SolveError::new_err(e.to_string())))
}

/// The memory ceiling of this process, as the command line computes it
/// (`ELCON_MEMORY_LIMIT` lowers it).
fn ceiling() -> PyResult<Ceiling> {
    Ceiling::of_this_process(None).map_err(SceneError::new_err)
}

/// Refuses a solve whose estimate (`plan`) does not fit under `ceiling`,
/// saying what would help.
fn admit(plan: &elcon_analysis::Plan, ceiling: &Ceiling) -> PyResult<()> {
    let e = &plan.estimate;
    let peak = (e.solve_bytes.max(0.0) as u64).saturating_add(BASELINE);
    if ceiling.admits(peak) {
        return Ok(());
    }
    let mut hints = Vec::new();
    for relief in e.reliefs() {
        match relief {
            elcon_analysis::Relief::MatrixFree => hints.push(
                "storage=\"lattice\" (matrix-free: points on a regular grid, no beam) with \
                 method=\"conjugate-gradient\"",
            ),
            elcon_analysis::Relief::FewerMatrices => {
                hints.push("method=\"block-pivoting\" (fewer matrices)")
            }
            _ => {}
        }
    }
    hints.push("fewer points");
    Err(SolveError::new_err(format!(
        "too big for the memory available: N = {} points ({} unknowns) needs about {} ({}); \
         the ceiling is {}. What helps: {}",
        e.points,
        e.unknowns,
        human(peak),
        e.holding(),
        ceiling,
        hints.join("; ")
    )))
}

/// A Python value as the TOML value a scene would hold: dicts as tables,
/// lists, tuples and numpy arrays as arrays, numbers (numpy's too),
/// strings and booleans as themselves. NaN and infinities pass (the
/// scene's checks refuse them by field); `None` and other objects are
/// refused naming the key (`path`).
fn toml_value(v: &Bound<'_, PyAny>, path: &str) -> Result<toml::Value, String> {
    if v.is_none() {
        return Err(format!(
            "`{path}` = None: a scene has no None; leave the key out"
        ));
    }
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if v.is_instance_of::<PyInt>() {
        return v
            .extract::<i64>()
            .map(toml::Value::Integer)
            .map_err(|_| format!("`{path}` = {v}: a whole number beyond 64 bits"));
    }
    if let Ok(f) = v.cast::<PyFloat>() {
        return Ok(toml::Value::Float(f.value()));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(toml::Value::String(s.to_string()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return toml_table(d, path).map(toml::Value::Table);
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, item) in v.try_iter().map_err(|e| e.to_string())?.enumerate() {
            let item = item.map_err(|e| e.to_string())?;
            items.push(toml_value(&item, &format!("{path}[{i}]"))?);
        }
        return Ok(toml::Value::Array(items));
    }
    // numpy arrays and scalars: their Python values.
    if let Ok(list) = v.call_method0("tolist")
        && !list.is(v)
    {
        return toml_value(&list, path);
    }
    if let Ok(i) = v.extract::<i64>() {
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(f) = v.extract::<f64>() {
        return Ok(toml::Value::Float(f));
    }
    let kind = v
        .get_type()
        .name()
        .map_or_else(|_| "value".to_string(), |n| n.to_string());
    Err(format!(
        "`{path}`: a {kind} has no form in a scene (numbers, strings, booleans, lists and dicts)"
    ))
}

/// A dict as a TOML table; `path` prefixes its keys in messages.
fn toml_table(d: &Bound<'_, PyDict>, path: &str) -> Result<toml::Table, String> {
    let mut table = toml::Table::new();
    for (k, v) in d.iter() {
        let key: String = k.extract().map_err(|_| {
            format!("`{path}`: the key {k} is not a string (a scene's keys are names)")
        })?;
        let full = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        table.insert(key, toml_value(&v, &full)?);
    }
    Ok(table)
}

/// TOML text of `table`.
fn toml_text(table: &toml::Table) -> Result<String, String> {
    toml::to_string(table).map_err(|e| format!("cannot be written as TOML: {e}"))
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

/// A scene's text: read from `path`, or a dict written as TOML.
fn scene_text(
    path: Option<PathBuf>,
    scene: Option<&Bound<'_, PyDict>>,
) -> PyResult<(PathBuf, String)> {
    match (path, scene) {
        (Some(p), None) => {
            let text = std::fs::read_to_string(&p)
                .map_err(|e| SceneError::new_err(format!("{}: {e}", p.display())))?;
            Ok((p, text))
        }
        (None, Some(d)) => {
            let text = toml_table(d, "")
                .and_then(|t| toml_text(&t))
                .map_err(|e| SceneError::new_err(format!("<dict>: {e}")))?;
            Ok((PathBuf::from("<dict>"), text))
        }
        _ => Err(InputError::new_err(
            "give a scene's path or its dict, one of them",
        )),
    }
}

/// Runs a validated scene as `elcon run` does: estimated against the
/// memory ceiling first, the run isolated (a panic becomes an error).
fn run_prepared(py: Python<'_>, scene: Scene) -> PyResult<elcon_scene::Run> {
    let ceiling = ceiling()?;
    let name = scene.name().to_string();
    py.detach(|| {
        isolated(&name, || {
            let prepared = elcon_scene::prepare(scene, &ceiling)?;
            elcon_scene::run(&prepared.scene)
        })
    })
    .map_err(scene_error)
}

/// Runs a scene (a file, or a dict with a scene's keys); returns
/// `{"json": result.json's text, "x": ..., "y": ..., "force": ...,
/// "pressure": ..., "gap": ..., "separation": ...}`.
#[pyfunction]
#[pyo3(signature = (path=None, scene=None))]
fn run_scene<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    scene: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (file, text) = scene_text(path, scene.as_ref())?;
    let scene = guarded("scene", || {
        Scene::from_str(&file, &text).map_err(scene_error)
    })?;
    let run = run_prepared(py, scene)?;
    let json = serde_json::to_string_pretty(&run.result)
        .map_err(|e| SolveError::new_err(format!("result.json: {e}")))?;
    let d = arrays(
        py,
        run.problem.points(),
        &run.solution,
        run.problem.separation(),
    )?;
    d.set_item("json", json)?;
    Ok(d)
}

/// Runs a batch file into `out`; returns its results.json text.
#[pyfunction]
#[pyo3(signature = (path, out, jobs=None))]
fn run_batch(py: Python<'_>, path: PathBuf, out: PathBuf, jobs: Option<i64>) -> PyResult<String> {
    let jobs = match jobs {
        Some(j) => Some(usize::try_from(j).map_err(|_| {
            InputError::new_err(format!(
                "`jobs` = {j}: must be a whole number >= 1 (None or 0: one per core)"
            ))
        })?),
        None => None,
    };
    let batch = guarded("batch", || {
        elcon_scene::Batch::from_file(&path).map_err(scene_error)
    })?;
    let options = elcon_scene::BatchOptions {
        jobs,
        shard: None,
        ceiling: ceiling()?,
    };
    let outcome = py
        .detach(|| {
            isolated("batch", || {
                elcon_scene::run_batch(&batch, &out, &options, &())
            })
        })
        .map_err(scene_error)?;
    serde_json::to_string(&outcome).map_err(|e| SolveError::new_err(format!("results.json: {e}")))
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

/// The storage by its name.
fn storage(name: &str) -> PyResult<Storage> {
    Storage::of(name).ok_or_else(|| {
        let names: Vec<&str> = Storage::ALL.iter().map(|s| s.name()).collect();
        InputError::new_err(format!(
            "`storage` = \"{name}\": one of {}",
            names.join(", ")
        ))
    })
}

/// What a problem assembled from bodies was built from: enough to plan a
/// solve by another method, to build it again unfolded for a design, and
/// to derive a logarithmic crown's roller.
#[derive(Debug, Clone)]
struct Built {
    /// The two bodies, as the scene validated them.
    bodies: [BodySpec; 2],
    /// The surfaces or the separations.
    geometry: Geometry,
    /// The layout, when the points were given as one.
    points_spec: Option<PointsSpec>,
}

/// A contact problem from arrays or a layout: the candidate points, their
/// separations, and S (given as an N x N array, or assembled from two
/// bodies' models).
#[pyclass(module = "elcon._elcon", name = "ContactProblem")]
struct PyContactProblem {
    inner: ContactProblem,
    built: Option<Built>,
}

/// The loading from the keyword arguments.
fn loading(
    load: Option<f64>,
    approach: Option<f64>,
    tilt_x: Option<f64>,
    tilt_y: Option<f64>,
    moment_x: f64,
    moment_y: f64,
) -> PyResult<Loading> {
    let loading = match (load, approach) {
        (Some(p), None) => Loading::load(p),
        (None, Some(a)) => Loading::approach(a),
        _ => {
            return Err(InputError::new_err(
                "give `load` or `approach`, one of them",
            ));
        }
    };
    let both = |axis: &str| {
        InputError::new_err(format!(
            "`tilt_{axis}` and `moment_{axis}`: give one of them (a prescribed rotation has its \
             moment as a result)"
        ))
    };
    let loading = match (tilt_x, moment_x) {
        (Some(angle), 0.0) => loading.with_tilt_x(angle),
        (Some(_), _) => return Err(both("x")),
        (None, m) => loading.with_moment_x(m),
    };
    Ok(match (tilt_y, moment_y) {
        (Some(angle), 0.0) => loading.with_tilt_y(angle),
        (Some(_), _) => return Err(both("y")),
        (None, m) => loading.with_moment_y(m),
    })
}

#[pymethods]
impl PyContactProblem {
    /// See `elcon.ContactProblem` (python/elcon/__init__.py).
    #[new]
    #[pyo3(signature = (x=None, separation=None, spacing=None, y=None, influence=None, body1=None, body2=None, load=None, approach=None, tilt_x=None, tilt_y=None, moment_x=0.0, moment_y=0.0, geometry=None, points=None, storage_name="auto"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        x: Option<PyReadonlyArray1<'_, f64>>,
        separation: Option<PyReadonlyArray1<'_, f64>>,
        spacing: Option<(f64, f64)>,
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
        geometry: Option<Bound<'_, PyDict>>,
        points: Option<Bound<'_, PyDict>>,
        storage_name: &str,
    ) -> PyResult<Self> {
        let storage = storage(storage_name)?;
        let loading = loading(load, approach, tilt_x, tilt_y, moment_x, moment_y)?;
        // The points given as coordinates.
        let listed = match (&x, &points) {
            (Some(x), None) => {
                let xs = x.as_array().to_vec();
                let (dimension, ys) = match &y {
                    Some(y) => (Dimension::Surface, y.as_array().to_vec()),
                    None => (Dimension::Line, Vec::new()),
                };
                let (dx, dy) = spacing.ok_or_else(|| {
                    InputError::new_err("`spacing`: required with `x` (h or (dx, dy))")
                })?;
                Some(
                    PointSet::from_points(dimension, xs, ys, Cell { dx, dy })
                        .map_err(|e| InputError::new_err(format!("`x`, `y`, `spacing`: {e}")))?,
                )
            }
            (None, Some(_)) => {
                if y.is_some() || spacing.is_some() {
                    return Err(InputError::new_err(
                        "`points` lays the points out: give no `y` or `spacing` with it",
                    ));
                }
                None
            }
            _ => {
                return Err(InputError::new_err(
                    "give the points as `x` (and `y` on a surface) with `spacing`, or as a \
                     layout `points={\"grid\": ...}`, one of them",
                ));
            }
        };
        // Bodies, surfaces and a layout: the scene's sections, checked by
        // the scene's parsers.
        let mut sections = toml::Table::new();
        for (name, dict) in [
            ("body1", &body1),
            ("body2", &body2),
            ("geometry", &geometry),
            ("points", &points),
        ] {
            if let Some(d) = dict {
                let t = toml_table(d, name).map_err(InputError::new_err)?;
                sections.insert(name.into(), toml::Value::Table(t));
            }
        }
        let text = toml_text(&sections).map_err(InputError::new_err)?;
        let parts = guarded("ContactProblem", || {
            elcon_scene::problem_parts(Path::new("<ContactProblem>"), &text, listed, loading)
                .map_err(parts_error)
        })?;
        let points = parts.points;
        let geometry = match (separation, parts.geometry) {
            (Some(s), None) => Geometry::Separation(s.as_array().to_vec()),
            (None, Some(g)) => g,
            (None, None) => Geometry::Surfaces(Surface::Plane, Surface::Plane),
            (Some(_), Some(_)) => {
                return Err(InputError::new_err(
                    "give the separations as `separation` (an array) or `geometry`, not both",
                ));
            }
        };
        let ceiling = ceiling()?;
        match (influence, parts.bodies) {
            (Some(s), None) => {
                if !matches!(storage, Storage::Auto | Storage::Dense) {
                    return Err(InputError::new_err(format!(
                        "`storage` = \"{storage}\": an S given as an array is held dense; \
                         give \"auto\" or \"dense\", or the bodies for the other storages"
                    )));
                }
                let s = s.as_array();
                let eps = match geometry {
                    Geometry::Separation(eps) => eps,
                    surfaces => {
                        elcon_analysis::separations(&points, &surfaces).map_err(analysis_error)?
                    }
                };
                let m = faer::Mat::from_fn(s.nrows(), s.ncols(), |i, j| s[(i, j)]);
                let inner = guarded("ContactProblem", || {
                    ContactProblem::from_parts(points, m, eps, loading).map_err(analysis_error)
                })?;
                Ok(Self { inner, built: None })
            }
            (None, Some(bodies)) => {
                let inner = py.detach(|| {
                    guarded("ContactProblem", || {
                        let builder = ContactProblem::builder(
                            points,
                            bodies[0].body(),
                            bodies[1].body(),
                            &geometry,
                            loading,
                        )
                        .storage(storage);
                        admit(&builder.plan().map_err(analysis_error)?, &ceiling)?;
                        builder.build().map_err(analysis_error)
                    })
                })?;
                Ok(Self {
                    inner,
                    built: Some(Built {
                        bodies,
                        geometry,
                        points_spec: parts.points_spec,
                    }),
                })
            }
            _ => Err(InputError::new_err(
                "give `influence` (an N x N array) or `body1` and `body2`, not both",
            )),
        }
    }

    /// Number of candidate points.
    fn __len__(&self) -> usize {
        self.inner.points().len()
    }

    /// How S is held: "dense", "folded" or "lattice".
    #[getter]
    fn storage(&self) -> &'static str {
        self.inner.storage().name()
    }

    /// The method `solve()` uses when given none.
    #[getter]
    fn default_method(&self) -> &'static str {
        self.inner.default_method().name()
    }

    /// Solves by `method_name` (default: the problem's own method);
    /// returns `{"json": the solution's fields, arrays...}`.
    #[pyo3(signature = (method_name=None))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        method_name: Option<&str>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let m = match method_name {
            Some(name) => method(name)?,
            None => self.inner.default_method(),
        };
        self.inner.check_method(m).map_err(analysis_error)?;
        let ceiling = ceiling()?;
        let problem = &self.inner;
        let built = &self.built;
        let solution = py.detach(|| {
            guarded("ContactProblem.solve", || {
                if let Some(b) = built {
                    let plan = ContactProblem::builder(
                        problem.points().clone(),
                        b.bodies[0].body(),
                        b.bodies[1].body(),
                        &b.geometry,
                        problem.loading(),
                    )
                    .storage(problem.storage())
                    .method(m)
                    .plan()
                    .map_err(analysis_error)?;
                    admit(&plan, &ceiling)?;
                }
                problem
                    .solve(m, &Options::default())
                    .map_err(analysis_error)
            })
        })?;
        let json = ProblemJson::of(problem, &solution, m);
        let text = serde_json::to_string(&json)
            .map_err(|e| SolveError::new_err(format!("the solution's fields: {e}")))?;
        let d = arrays(py, problem.points(), &solution, problem.separation())?;
        d.set_item("json", text)?;
        Ok(d)
    }
}

/// A problem's solution as `ContactProblem.solve` returns it: how it was
/// held and solved, then result.json's solution fields (the scene crate's
/// `SolutionJson`, the same serialization as a scene's run).
#[derive(Debug, Serialize)]
struct ProblemJson {
    /// The engine's method.
    method: &'static str,
    /// How S was held: "dense" or "matrix-free" (result.json's word).
    influence: &'static str,
    /// The storage: "dense", "folded" or "lattice".
    storage: &'static str,
    /// "surface" or "line".
    dimension: &'static str,
    /// Candidate points N.
    points: usize,
    /// The mirror symmetry the problem was folded with, if it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    symmetry: Option<SymmetryJson>,
    /// The engine's statistics.
    statistics: elcon_lcp::Statistics,
    /// Seconds of the assembly and of the solve.
    seconds: ProblemSeconds,
    /// result.json's solution fields.
    #[serde(flatten)]
    solution: SolutionJson,
}

/// Wall-clock seconds of a problem's assembly and solve.
#[derive(Debug, Serialize)]
struct ProblemSeconds {
    /// Assembling S and eps.
    assembly: f64,
    /// The engine's solve, certificate included.
    solve: f64,
}

impl ProblemJson {
    fn of(problem: &ContactProblem, solution: &ContactSolution, method: Method) -> Self {
        Self {
            method: method.name(),
            influence: problem.storage().held_as(),
            storage: problem.storage().name(),
            dimension: match problem.points().dimension() {
                Dimension::Surface => "surface",
                Dimension::Line => "line",
            },
            points: problem.points().len(),
            symmetry: problem.folding().map(|f| SymmetryJson {
                group: f.group().to_string(),
                order: f.order(),
                unknowns: f.len(),
            }),
            statistics: solution.statistics.clone(),
            seconds: ProblemSeconds {
                assembly: problem.assembly_seconds(),
                solve: solution.solve_seconds,
            },
            solution: SolutionJson::of(solution, &[]),
        }
    }
}

/// A logarithmic crown's roller from `{"combined_modulus", "radius",
/// "length"}` (elcon-design checks the values, naming each).
fn roller(d: &Bound<'_, PyDict>) -> PyResult<Roller> {
    const KEYS: [&str; 3] = ["combined_modulus", "radius", "length"];
    for k in d.keys() {
        let k = k.to_string();
        if !KEYS.contains(&k.as_str()) {
            return Err(InputError::new_err(format!(
                "`roller.{k}`: not a key of a roller (it takes: {})",
                KEYS.join(", ")
            )));
        }
    }
    let get = |key: &str| -> PyResult<f64> {
        d.get_item(key)?
            .ok_or_else(|| InputError::new_err(format!("`roller.{key}`: required")))?
            .extract::<f64>()
            .map_err(|_| InputError::new_err(format!("`roller.{key}`: must be a number")))
    };
    Ok(Roller {
        combined_modulus: get("combined_modulus")?,
        radius: get("radius")?,
        length: get("length")?,
    })
}

/// The `[design]` table of `keys` (the scene's design keys) as TOML text.
fn design_text(keys: &Bound<'_, PyDict>) -> PyResult<String> {
    let table = toml_table(keys, "design").map_err(InputError::new_err)?;
    let mut section = toml::Table::new();
    section.insert("design".into(), toml::Value::Table(table));
    toml_text(&section).map_err(InputError::new_err)
}

/// A design error as its Python class.
fn design_error(e: elcon_design::DesignError) -> PyErr {
    DesignError::new_err(e.to_string())
}

/// Designs a correction over the problems (each a load case under a load)
/// with the scene's `[design]` keys `keys`; returns the design as JSON
/// text of the scene's `DesignJson`.
#[pyfunction]
#[pyo3(signature = (problems, keys, reference_intensities=None, roller_dict=None))]
fn design_problems(
    py: Python<'_>,
    problems: Vec<PyRef<'_, PyContactProblem>>,
    keys: Bound<'_, PyDict>,
    reference_intensities: Option<Vec<f64>>,
    roller_dict: Option<Bound<'_, PyDict>>,
) -> PyResult<String> {
    let text = design_text(&keys)?;
    let roller = roller_dict.as_ref().map(roller).transpose()?;
    let ceiling = ceiling()?;
    let start = Instant::now();
    let given: Vec<(ContactProblem, Option<Built>)> = problems
        .iter()
        .map(|p| (p.inner.clone(), p.built.clone()))
        .collect();
    drop(problems);
    // A folded problem is built again in full: a design reads every point.
    let mut cases = Vec::with_capacity(given.len());
    for (problem, built) in &given {
        let case = match (built, problem.folding()) {
            (Some(b), Some(_)) => py.detach(|| {
                guarded("design", || {
                    let builder = ContactProblem::builder(
                        problem.points().clone(),
                        b.bodies[0].body(),
                        b.bodies[1].body(),
                        &b.geometry,
                        problem.loading(),
                    )
                    .fold(false);
                    admit(&builder.plan().map_err(analysis_error)?, &ceiling)?;
                    builder.build().map_err(analysis_error)
                })
            })?,
            _ => problem.clone(),
        };
        cases.push(case);
    }
    let layout = given.first().and_then(|(_, built)| {
        let b = built.as_ref()?;
        Some(DesignLayoutParts {
            bodies: &b.bodies,
            geometry: &b.geometry,
            points_spec: b.points_spec.as_ref()?,
        })
    });
    let spec = guarded("design", || {
        elcon_scene::design_over(Path::new("<design>"), &text, &cases, layout, roller)
            .map_err(parts_error)
    })?;
    let json = py.detach(|| {
        guarded("design", || {
            let method = cases
                .first()
                .map_or(Method::BlockPivoting, ContactProblem::default_method);
            let options = Options::default();
            let axis = spec.axis();
            let outcome = spec
                .request(reference_intensities.clone(), Some(method), &options)
                .run(&cases)
                .map_err(design_error)?;
            let before = evaluate(
                &cases,
                axis,
                &Profile::none(),
                &Analysis::new(method, &options),
            )
            .map_err(design_error)?;
            let references = reference_intensities
                .clone()
                .unwrap_or_else(|| vec![1.0; cases.len()]);
            let (positions, _) = axial_stations(cases.iter().map(ContactProblem::points), axis);
            let after = &outcome.evaluation;
            let table = outcome.profile.table(&positions).map_err(design_error)?;
            Ok(DesignJson {
                family: spec.family().describe(),
                axis: match axis {
                    Axis::X => "x".into(),
                    Axis::Y => "y".into(),
                },
                relative_to: if reference_intensities.is_some() {
                    "given".into()
                } else {
                    "absolute".into()
                },
                parameters: outcome.profile.parameters(),
                objective: after.relative_worst(&references),
                objective_before: before.relative_worst(&references),
                cases: cases
                    .iter()
                    .enumerate()
                    .map(|(l, c)| DesignCaseJson {
                        load: c.loading().load_value().unwrap_or(f64::NAN),
                        misalignment: None,
                        reference_intensity: references[l],
                        max_pressure_before: before.max_intensities[l],
                        max_pressure_after: after.max_intensities[l],
                        certificate_worst: after.solutions[l].certificate.worst(),
                        certificate_holds: after.solutions[l].certificate.holds(),
                    })
                    .collect(),
                table,
                method: outcome.found.method().into(),
                starts: outcome.found.starts(),
                seconds: start.elapsed().as_secs_f64(),
            })
        })
    })?;
    serde_json::to_string(&json).map_err(|e| SolveError::new_err(format!("the design: {e}")))
}

/// Runs a scene's design stage (a file or a dict), its `[design]`
/// replaced by `keys` when given; returns `{"json": the design's JSON text
/// (result.json's design block), "result": result.json's text}`.
#[pyfunction]
#[pyo3(signature = (path=None, scene=None, keys=None))]
fn design_scene<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    scene: Option<Bound<'py, PyDict>>,
    keys: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (file, text) = scene_text(path, scene.as_ref())?;
    let design = match &keys {
        Some(k) if !k.is_empty() => Some(design_text(k)?),
        _ => None,
    };
    let scene = guarded("scene", || {
        match &design {
            Some(d) => elcon_scene::scene_with_design(&file, &text, d),
            None => Scene::from_str(&file, &text),
        }
        .map_err(scene_error)
    })?;
    if scene.design().is_none() {
        return Err(InputError::new_err(format!(
            "{}: the scene has no [design] section and no design keys were given (family=...)",
            file.display()
        )));
    }
    let run = run_prepared(py, scene)?;
    let d = PyDict::new(py);
    let design = run
        .result
        .design
        .as_ref()
        .ok_or_else(|| SolveError::new_err("the scene's run has no design block"))?;
    d.set_item(
        "json",
        serde_json::to_string(design)
            .map_err(|e| SolveError::new_err(format!("the design: {e}")))?,
    )?;
    d.set_item(
        "result",
        serde_json::to_string(&run.result)
            .map_err(|e| SolveError::new_err(format!("result.json: {e}")))?,
    )?;
    Ok(d)
}

/// The names of the solve methods.
#[pyfunction]
fn methods() -> Vec<&'static str> {
    Method::ALL.iter().map(|m| m.name()).collect()
}

/// The names of the storages of S.
#[pyfunction]
fn storages() -> Vec<&'static str> {
    Storage::ALL.iter().map(|s| s.name()).collect()
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
    // Panics inside `isolated` are reported through the error, not printed.
    elcon_scene::install_panic_hook();
    let py = m.py();
    m.add("ElconError", py.get_type::<ElconError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("DesignError", py.get_type::<DesignError>())?;
    m.add_class::<PyContactProblem>()?;
    m.add_function(wrap_pyfunction!(run_scene, m)?)?;
    m.add_function(wrap_pyfunction!(run_batch, m)?)?;
    m.add_function(wrap_pyfunction!(design_problems, m)?)?;
    m.add_function(wrap_pyfunction!(design_scene, m)?)?;
    m.add_function(wrap_pyfunction!(methods, m)?)?;
    m.add_function(wrap_pyfunction!(storages, m)?)?;
    m.add_function(wrap_pyfunction!(is_file, m)?)?;
    Ok(())
}
