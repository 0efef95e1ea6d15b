//! The exception classes, one per kind of error, and the mappings of the
//! crates' errors onto them (their messages the crates' own).

use elcon_analysis::AnalysisError;
use elcon_process::isolated;
use elcon_runner::{DesignCaller, RunError, design_reason};
use elcon_scene::SceneError as RustSceneError;
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

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

/// Adds the exception classes to the module `m`.
pub(crate) fn add_classes(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ElconError", py.get_type::<ElconError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("DesignError", py.get_type::<DesignError>())?;
    Ok(())
}

/// A scene error as its Python class: input errors (syntax, invalid values)
/// are `SceneError`, run failures `SolveError`.
pub(crate) fn scene_error(e: impl Into<RunError>) -> PyErr {
    let e = e.into();
    if e.is_input_error() {
        SceneError::new_err(e.to_string())
    } else {
        SolveError::new_err(e.to_string())
    }
}

/// A scene crate's error about the parts given to `ContactProblem` or
/// `design` (keyword arguments, not a scene): input errors are
/// `InputError`, the rest `SolveError`.
pub(crate) fn parts_error(e: RustSceneError) -> PyErr {
    if e.is_input_error() {
        InputError::new_err(e.to_string())
    } else {
        SolveError::new_err(e.to_string())
    }
}

/// The value of the engine's matrix that is not finite, when `e` says S
/// held one: S is assembled from finite, validated moduli and cell sizes,
/// so a cell's compliance overflowed (or S was given so).
pub(crate) fn overflowed(e: &AnalysisError) -> Option<f64> {
    match e {
        AnalysisError::Engine(elcon_lcp::LcpError::NonFinite {
            field: "m", value, ..
        }) => Some(*value),
        _ => None,
    }
}

/// The error of a problem whose S overflowed (`value`): `fields` names
/// what S came from, as the user gave it.
pub(crate) fn overflow_error(fields: &str, value: f64) -> PyErr {
    InputError::new_err(format!(
        "{fields}: S assembled from them has a non-finite entry ({value}): a cell's compliance \
         is outside floating-point range, so the moduli, the spacing and the load are not in \
         one consistent unit system"
    ))
}

/// An analysis error as its Python class (an S that overflowed said so,
/// as input).
pub(crate) fn analysis_error(e: AnalysisError) -> PyErr {
    if let Some(value) = overflowed(&e) {
        return overflow_error("the bodies' moduli and the cell size", value);
    }
    match e {
        AnalysisError::InvalidInput { .. }
        | AnalysisError::SizeMismatch { .. }
        | AnalysisError::NonFinite { .. }
        | AnalysisError::NonFiniteEntry { .. }
        | AnalysisError::Incompatible { .. }
        | AnalysisError::NeedsEntries { .. }
        | AnalysisError::Table { .. }
        | AnalysisError::Influence(_) => InputError::new_err(e.to_string()),
        _ => SolveError::new_err(e.to_string()),
    }
}

/// A design error over problems as its Python class, said as a scene's
/// design stage says it ([`design_reason`]): a parameter
/// elcon-design names by its own name is named by the argument or the
/// scene's key the user gave (`design.radius_range`); the roller's
/// parameters by `roller.*` when `roller_given` (else, derived from the
/// problems' bodies, geometry and points, by the scene's keys).
pub(crate) fn design_error(e: elcon_design::DesignError, roller_given: bool) -> PyErr {
    DesignError::new_err(design_reason(&e, DesignCaller::Problems { roller_given }))
}

/// Runs `f` inside `elcon_process::isolated`: a panic becomes a `SolveError`
/// naming `what` ("internal error"), never a Python `PanicException`.
pub(crate) fn guarded<T>(what: &str, f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    isolated::<_, RunError>(what, || Ok(f()))
        .unwrap_or_else(|e| Err(SolveError::new_err(e.to_string())))
}
