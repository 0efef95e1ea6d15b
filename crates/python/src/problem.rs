//! `ContactProblem`: a contact problem from numpy arrays or a layout (the
//! candidate points, their separations, and S given as an array or
//! assembled from two bodies' models), and its solve.

use std::path::Path;

use elcon_analysis::{
    ContactProblem, Dimension, Geometry, Loading, Method, Options, PointSet, ProblemBuilder,
    Storage, Surface,
};
use elcon_influence::Cell;
use elcon_process::Ceiling;
use elcon_report::ProblemResult;
use elcon_scene::{BodySpec, PointsSpec};
use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{arrays, sections_text};
use crate::errors::{
    InputError, SolveError, analysis_error, guarded, overflow_error, overflowed, parts_error,
};
use crate::memory::{admit, ceiling};
use crate::signals::detach;
use crate::threads::{threads, with_threads};

/// The names of the solve methods.
#[pyfunction]
pub(crate) fn methods() -> Vec<&'static str> {
    Method::ALL.iter().map(|m| m.name()).collect()
}

/// The names of the storages of S.
#[pyfunction]
pub(crate) fn storages() -> Vec<&'static str> {
    Storage::ALL.iter().map(|s| s.name()).collect()
}

/// The error of a `key` given a `name` that is none of `names`.
fn not_one_of(key: &str, name: &str, names: &[&str]) -> PyErr {
    InputError::new_err(format!("`{key}` = \"{name}\": one of {}", names.join(", ")))
}

/// The solve method by its scene name.
fn method(name: &str) -> PyResult<Method> {
    name.parse()
        .map_err(|_| not_one_of("method", name, &methods()))
}

/// The storage by its name.
fn storage(name: &str) -> PyResult<Storage> {
    name.parse()
        .map_err(|_| not_one_of("storage", name, &storages()))
}

/// What a problem assembled from bodies was built from: enough to plan a
/// solve by another method, to build it again unfolded for a design, and
/// to derive a logarithmic crown's roller.
#[derive(Debug, Clone)]
pub(crate) struct Built {
    /// The two bodies, as the scene validated them.
    pub(crate) bodies: [BodySpec; 2],
    /// The surfaces or the separations.
    pub(crate) geometry: Geometry,
    /// The layout, when the points were given as one.
    pub(crate) points_spec: Option<PointsSpec>,
}

impl Built {
    /// A builder of the problem over `points` under `loading` from these
    /// bodies and this geometry.
    pub(crate) fn builder(&self, points: PointSet, loading: Loading) -> ProblemBuilder<'_> {
        ContactProblem::builder(
            points,
            self.bodies[0].body(),
            self.bodies[1].body(),
            &self.geometry,
            loading,
        )
    }
}

/// Builds the problem of `builder` once its estimate fits under `ceiling`.
pub(crate) fn build_admitted(
    builder: ProblemBuilder<'_>,
    ceiling: &Ceiling,
) -> PyResult<ContactProblem> {
    admit(&builder.plan().map_err(analysis_error)?, ceiling)?;
    builder.build().map_err(analysis_error)
}

/// A contact problem from arrays or a layout: the candidate points, their
/// separations, and S (given as an N x N array, or assembled from two
/// bodies' models).
#[pyclass(module = "elcon._elcon", name = "ContactProblem")]
pub(crate) struct PyContactProblem {
    pub(crate) inner: ContactProblem,
    pub(crate) built: Option<Built>,
}

/// The `[loading]` section of the keyword arguments, for the scene's own
/// parser and checks (the rotation bound among them): `load` or
/// `approach`, and about x and y each a prescribed `tilt` or a `moment`
/// (a moment of 0 beside a tilt is the default, left out).
fn loading_section<'py>(
    py: Python<'py>,
    load: Option<f64>,
    approach: Option<f64>,
    (tilt_x, tilt_y): (Option<f64>, Option<f64>),
    (moment_x, moment_y): (f64, f64),
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    if let Some(p) = load {
        d.set_item("load", p)?;
    }
    if let Some(a) = approach {
        d.set_item("approach", a)?;
    }
    for (axis, tilt, moment) in [("x", tilt_x, moment_x), ("y", tilt_y, moment_y)] {
        if let Some(angle) = tilt {
            d.set_item(format!("tilt_{axis}"), angle)?;
        }
        if tilt.is_none() || moment != 0.0 {
            d.set_item(format!("moment_{axis}"), moment)?;
        }
    }
    Ok(d)
}

/// The points given as coordinates (`x`, and `y` on a surface, with
/// `spacing`), or `None` when they are laid out by a `points` dict
/// (`layout`).
fn listed_points(
    x: Option<&PyReadonlyArray1<'_, f64>>,
    y: Option<&PyReadonlyArray1<'_, f64>>,
    spacing: Option<(f64, f64)>,
    layout: bool,
) -> PyResult<Option<PointSet>> {
    match (x, layout) {
        (Some(x), false) => {
            let xs = x.as_array().to_vec();
            let (dimension, ys) = match y {
                Some(y) => (Dimension::Surface, y.as_array().to_vec()),
                None => (Dimension::Line, Vec::new()),
            };
            let (dx, dy) = spacing.ok_or_else(|| {
                InputError::new_err("`spacing`: required with `x` (h or (dx, dy))")
            })?;
            PointSet::from_points(dimension, xs, ys, Cell { dx, dy })
                .map(Some)
                .map_err(|e| InputError::new_err(format!("`x`, `y`, `spacing`: {e}")))
        }
        (None, true) => {
            if y.is_some() || spacing.is_some() {
                return Err(InputError::new_err(
                    "`points` lays the points out: give no `y` or `spacing` with it",
                ));
            }
            Ok(None)
        }
        _ => Err(InputError::new_err(
            "give the points as `x` (and `y` on a surface) with `spacing`, or as a \
             layout `points={\"grid\": ...}`, one of them",
        )),
    }
}

/// The separations' source: the array `separation`, or the `[geometry]`
/// the scene's parser read (`parsed`), or two planes when neither is given.
fn geometry_of(
    separation: Option<PyReadonlyArray1<'_, f64>>,
    parsed: Option<Geometry>,
) -> PyResult<Geometry> {
    match (separation, parsed) {
        (Some(s), None) => Ok(Geometry::Separation(s.as_array().to_vec())),
        (None, Some(g)) => Ok(g),
        (None, None) => Ok(Geometry::Surfaces(Surface::Plane, Surface::Plane)),
        (Some(_), Some(_)) => Err(InputError::new_err(
            "give the separations as `separation` (an array) or `geometry`, not both",
        )),
    }
}

impl PyContactProblem {
    /// The problem with S given as the array `s`, held dense.
    fn from_influence(
        s: &PyReadonlyArray2<'_, f64>,
        storage: Storage,
        points: PointSet,
        geometry: Geometry,
        loading: Loading,
    ) -> PyResult<Self> {
        storage.of_given_matrix().map_err(analysis_error)?;
        let s = s.as_array();
        let eps = match geometry {
            Geometry::Separation(eps) => eps,
            surfaces => elcon_analysis::separations(&points, &surfaces).map_err(analysis_error)?,
        };
        let m = faer::Mat::from_fn(s.nrows(), s.ncols(), |i, j| s[(i, j)]);
        let inner = guarded("ContactProblem", || {
            ContactProblem::from_parts(points, m, eps, loading).map_err(analysis_error)
        })?;
        Ok(Self { inner, built: None })
    }

    /// The problem with S assembled from the bodies of `built` in
    /// `storage`, once its estimate fits under `ceiling`.
    fn from_bodies(
        py: Python<'_>,
        points: PointSet,
        built: Built,
        loading: Loading,
        storage: Storage,
        ceiling: &Ceiling,
    ) -> PyResult<Self> {
        let inner = detach(py, |_| {
            guarded("ContactProblem", || {
                build_admitted(built.builder(points, loading).storage(storage), ceiling)
            })
        })??;
        Ok(Self {
            inner,
            built: Some(built),
        })
    }
}

impl PyContactProblem {
    /// What S came from, by the arguments' names (for a message).
    fn sources(&self) -> String {
        let cell = self.inner.points().cell();
        match &self.built {
            Some(Built {
                points_spec: Some(_),
                ..
            }) => "`body1`, `body2` and the `points` layout's cells".to_string(),
            Some(_) => format!(
                "`body1`, `body2` and `spacing` = ({:e}, {:e})",
                cell.dx, cell.dy
            ),
            None => "`influence` (S as given)".to_string(),
        }
    }
}

#[pymethods]
impl PyContactProblem {
    /// See `elcon.ContactProblem` (python/elcon/__init__.py).
    #[new]
    #[pyo3(signature = (x=None, separation=None, spacing=None, y=None, influence=None, body1=None, body2=None, load=None, approach=None, tilt_x=None, tilt_y=None, moment_x=0.0, moment_y=0.0, geometry=None, points=None, storage_name="auto", height_map=None, height_map_spacing=None, height_map_origin=None, height_map_interpolation=None))]
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
        height_map: Option<PyReadonlyArray2<'_, f64>>,
        height_map_spacing: Option<(f64, f64)>,
        height_map_origin: Option<(f64, f64)>,
        height_map_interpolation: Option<&str>,
    ) -> PyResult<Self> {
        let storage = storage(storage_name)?;
        let loading = loading_section(py, load, approach, (tilt_x, tilt_y), (moment_x, moment_y))?;
        let listed = listed_points(x.as_ref(), y.as_ref(), spacing, points.is_some())?;
        // Bodies, surfaces, a layout and the loading: the scene's sections,
        // checked by the scene's parsers.
        let text = sections_text(&[
            ("body1", body1.as_ref()),
            ("body2", body2.as_ref()),
            ("geometry", geometry.as_ref()),
            ("points", points.as_ref()),
            ("loading", Some(&loading)),
        ])?;
        let parts = guarded("ContactProblem", || {
            elcon_scene::problem_parts(Path::new("<ContactProblem>"), &text, listed)
                .map_err(parts_error)
        })?;
        let loading = parts.loading;
        let geometry = crate::bodies::with_height_map(
            geometry_of(separation, parts.geometry)?,
            height_map,
            height_map_spacing,
            height_map_origin,
            height_map_interpolation,
        )?;
        let ceiling = ceiling()?;
        match (influence, parts.bodies) {
            (Some(s), None) => Self::from_influence(&s, storage, parts.points, geometry, loading),
            (None, Some(bodies)) => {
                let built = Built {
                    bodies,
                    geometry,
                    points_spec: parts.points_spec,
                };
                Self::from_bodies(py, parts.points, built, loading, storage, &ceiling)
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

    /// Solves by `method_name` (default: the problem's own method) on
    /// `threads` threads (default: the global pool); returns `{"json": the solution's fields, arrays...}`.
    #[pyo3(signature = (method_name=None, threads=None))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        method_name: Option<&str>,
        threads: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let threads = self::threads(threads.as_ref())?;
        let m = match method_name {
            Some(name) => method(name)?,
            None => self.inner.default_method(),
        };
        self.inner.check_method(m).map_err(analysis_error)?;
        let ceiling = ceiling()?;
        let problem = &self.inner;
        let built = &self.built;
        let sources = self.sources();
        // The token is watched on the thread that runs the solve: inside
        // the pool of `threads` when one is given.
        let solution = detach(py, |cancel| {
            with_threads(threads, || {
                cancel.watch(|| {
                    guarded("ContactProblem.solve", || {
                        if let Some(b) = built {
                            let plan = b
                                .builder(problem.points().clone(), problem.loading())
                                .storage(problem.storage())
                                .method(m)
                                .plan()
                                .map_err(analysis_error)?;
                            admit(&plan, &ceiling)?;
                        }
                        problem
                            .solve(m, &Options::default())
                            .map_err(|e| match overflowed(&e) {
                                Some(value) => overflow_error(&sources, value),
                                None => analysis_error(e),
                            })
                    })
                })
            })
        })??;
        // The small-rotation theory's bound on the solved rotation, as a
        // scene's run applies it. A contact reaching the points' edge stays
        // the warning the result carries: points from arrays (a foundation
        // loaded whole, an influence matrix given) may end where the body
        // ends, which a scene declares and arrays cannot.
        if let Err(why @ elcon_analysis::rotation::RotationRefusal::Beyond { .. }) =
            elcon_analysis::rotation::small_rotation(&problem.loading(), &solution)
        {
            return Err(SolveError::new_err(format!("ContactProblem.solve: {why}")));
        }
        let json = ProblemResult::of(problem, &solution, m);
        let text = serde_json::to_string(&json)
            .map_err(|e| SolveError::new_err(format!("the solution's fields: {e}")))?;
        let d = arrays(py, problem.points(), &solution, problem.separation())?;
        d.set_item("json", text)?;
        Ok(d)
    }
}
