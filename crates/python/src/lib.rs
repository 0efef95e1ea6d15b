//! `elcon._elcon`: the Rust side of the Python package.
//!
//! Thin bindings over the crates: a scene from a file or a dict, run
//! (`run_scene`) or checked as `elcon check` checks it (`check_scene`), a batch (`run_batch`), a contact problem from numpy
//! arrays or from a layout (`ContactProblem`: points, separations, and S
//! given or assembled from body models) and a design over such problems or
//! over a scene (`design_problems`, `design_scene`), and the designed
//! profile read back from its result.json block and evaluated by
//! elcon-design (`Profile`). Python's dicts become
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
//! `elcon_process::isolated`, so a Rust panic reaches Python as a
//! `SolveError` ("internal error"), never as a `PanicException`. Errors are
//! one exception class per kind, their messages the crates' own.
//!
//! Ctrl-C during a solve raises KeyboardInterrupt within about a tenth of
//! a second: the work runs on a worker thread whose solves poll a cancel
//! token, which the calling thread sets when Python's signal check says so
//! (the `signals` module).

mod bearing;
mod bodies;
mod convert;
mod design;
mod errors;
mod memory;
mod problem;
mod profile;
mod scene;
mod signals;
mod subsurface;
mod threads;

use pyo3::prelude::*;

/// The module.
#[pymodule]
fn _elcon(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Panics inside `isolated` are reported through the error, not printed.
    elcon_process::install_panic_hook();
    errors::add_classes(m)?;
    m.add_class::<problem::PyContactProblem>()?;
    m.add_class::<profile::PyProfile>()?;
    m.add_function(wrap_pyfunction!(scene::run_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::run_batch, m)?)?;
    m.add_function(wrap_pyfunction!(scene::check_scene, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_problems, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_scene, m)?)?;
    m.add_function(wrap_pyfunction!(problem::methods, m)?)?;
    m.add_function(wrap_pyfunction!(problem::storages, m)?)?;
    m.add_function(wrap_pyfunction!(scene::is_file, m)?)?;
    m.add_function(wrap_pyfunction!(scene::confine, m)?)?;
    m.add_function(wrap_pyfunction!(bodies::hertz_ellipse, m)?)?;
    Ok(())
}
