//! Scenes and batches: `run_scene` and `run_batch`, run as `elcon run` and
//! `elcon batch` run them.

use std::path::{Path, PathBuf};

use elcon_process::isolated;
use elcon_runner::RunError;
use elcon_scene::{Scene, read_text};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{arrays, toml_table, toml_text};
use crate::errors::{InputError, SceneError, SolveError, guarded, scene_error};
use crate::memory::ceiling;
use crate::signals::detach;
use crate::subsurface::subsurface_arrays;
use crate::threads::with_threads;

/// A scene's text: read from `path` as the command line reads it (once,
/// at most `elcon_scene::MAX_INPUT_BYTES`, UTF-8), or a dict written as TOML.
pub(crate) fn scene_text(
    path: Option<PathBuf>,
    scene: Option<&Bound<'_, PyDict>>,
) -> PyResult<(PathBuf, String)> {
    match (path, scene) {
        (Some(p), None) => {
            let text = read_text(&p).map_err(|e| SceneError::new_err(e.to_string()))?;
            Ok((p, text))
        }
        (None, Some(d)) => {
            let text = toml_table(d, "")
                .and_then(|t| toml_text(&t))
                .map_err(|e| SceneError::new_err(format!("<dict>: {}", e.value(d.py()))))?;
            Ok((PathBuf::from("<dict>"), text))
        }
        _ => Err(InputError::new_err(
            "give a scene's path or its dict, one of them",
        )),
    }
}

/// Runs a validated scene as `elcon run` does: estimated against the
/// memory ceiling first, the run isolated (a panic becomes an error).
pub(crate) fn run_prepared(
    py: Python<'_>,
    scene: Scene,
    threads: Option<usize>,
) -> PyResult<elcon_report::Run> {
    let ceiling = ceiling()?;
    let name = scene.name().to_string();
    // The token is watched on the thread that runs the solve: inside the
    // pool of `threads` when one is given.
    detach(py, |cancel| {
        with_threads(threads, || {
            cancel.watch(|| {
                isolated::<_, RunError>(&name, || {
                    let prepared = elcon_runner::prepare(scene, &ceiling)?;
                    elcon_runner::run(&prepared.scene)
                })
                .map_err(scene_error)
            })
        })
    })?
}

/// Runs a scene (a file, or a dict with a scene's keys) on `threads`
/// threads (default: the global pool); a bearing scene (a `[bearing]`
/// table) as `crate::bearing::run` does; otherwise returns
/// `{"json": result.json's text, "x": ..., "y": ..., "force": ...,
/// "pressure": ..., "gap": ..., "separation": ...}`, and `"subsurface"`
/// (each body's section and profile arrays) when the scene asks for the
/// stresses below the surface.
#[pyfunction]
#[pyo3(signature = (path=None, scene=None, threads=None))]
pub(crate) fn run_scene<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    scene: Option<Bound<'py, PyDict>>,
    threads: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let threads = crate::threads::threads(threads.as_ref())?;
    let (file, text) = scene_text(path, scene.as_ref())?;
    if elcon_scene::is_bearing_text(&text) {
        return crate::bearing::run(py, &file, &text, threads);
    }
    let scene = guarded("scene", || {
        Scene::from_str(&file, &text).map_err(scene_error)
    })?;
    let run = run_prepared(py, scene, threads)?;
    let json = serde_json::to_string_pretty(&run.result)
        .map_err(|e| SolveError::new_err(format!("result.json: {e}")))?;
    let d = arrays(
        py,
        run.problem.points(),
        &run.solution,
        run.problem.separation(),
    )?;
    d.set_item("json", json)?;
    if let Some(fields) = &run.subsurface {
        d.set_item("subsurface", subsurface_arrays(py, fields)?)?;
    }
    Ok(d)
}

/// Runs a batch file into `out`; returns its results.json text.
#[pyfunction]
#[pyo3(signature = (path, out, jobs=None))]
pub(crate) fn run_batch(
    py: Python<'_>,
    path: PathBuf,
    out: PathBuf,
    jobs: Option<Bound<'_, PyAny>>,
) -> PyResult<String> {
    let jobs = crate::threads::jobs(jobs.as_ref())?;
    let batch = guarded("batch", || {
        elcon_scene::Batch::from_file(&path).map_err(scene_error)
    })?;
    let ceiling = ceiling()?;
    // The batch's runs watch the token the signal check cancels: on
    // Ctrl-C the runs in flight stop, the tables of what finished are
    // written, and KeyboardInterrupt is raised; the same call again
    // finishes the batch.
    let done = detach(py, |cancel| {
        let options = elcon_runner::BatchOptions {
            jobs,
            shard: None,
            ceiling,
            cancel: cancel.clone(),
        };
        isolated::<_, RunError>("batch", || {
            elcon_runner::run_batch(&batch, &out, &options, &())
        })
    })?
    .map_err(scene_error)?;
    serde_json::to_string(&done.outcome)
        .map_err(|e| SolveError::new_err(format!("results.json: {e}")))
}

/// Checks a scene (a file, or a dict with a scene's keys) as `elcon check`
/// does: parsed, validated and estimated against the memory ceiling, not
/// run. Returns `{"name": the scene's name, "estimate": the estimate's
/// summary, "points", "unknowns", "peak_bytes", "seconds": the estimate's
/// figures, "warnings": the scene's warnings}`.
#[pyfunction]
#[pyo3(signature = (path=None, scene=None))]
pub(crate) fn check_scene<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    scene: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (file, text) = scene_text(path, scene.as_ref())?;
    if elcon_scene::is_bearing_text(&text) {
        return crate::bearing::check(py, &file, &text);
    }
    let ceiling = ceiling()?;
    let prepared = guarded("scene", || {
        let scene = Scene::from_str(&file, &text).map_err(scene_error)?;
        elcon_runner::prepare(scene, &ceiling).map_err(scene_error)
    })?;
    let e = &prepared.estimate;
    let d = PyDict::new(py);
    d.set_item("name", prepared.scene.name())?;
    d.set_item("estimate", e.summary())?;
    d.set_item("points", e.points)?;
    d.set_item("unknowns", e.unknowns)?;
    d.set_item("peak_bytes", e.peak_bytes)?;
    d.set_item("seconds", e.seconds)?;
    d.set_item("warnings", prepared.scene.warnings().to_vec())?;
    Ok(d)
}

/// Whether `path` exists (used by the Python side to tell a path from TOML
/// text given as a string).
#[pyfunction]
pub(crate) fn is_file(path: &str) -> bool {
    Path::new(path).is_file()
}

/// Confines the data files every scene of this process reads (height
/// maps, profiles, separation files) to `directory`, as `elcon --confine`
/// does: a file whose resolved path leaves it is refused. Once per
/// process; it cannot be widened or lifted.
#[pyfunction]
pub(crate) fn confine(directory: PathBuf) -> PyResult<()> {
    elcon_scene::confine_data_files(&directory).map_err(|e| InputError::new_err(e.to_string()))
}
