//! Bearing scenes from Python: `run` and `check` of a scene with a
//! `[bearing]` table (a file or a dict), read by the scene crate's own
//! parser and run as `elcon run` runs it; the elements' columns as numpy
//! arrays.

use std::path::Path;

use elcon_process::isolated;
use elcon_runner::{BearingEstimate, RunError, run_bearing};
use elcon_scene::BearingScene;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{SolveError, guarded, scene_error};
use crate::memory::ceiling;
use crate::signals::detach;
use crate::threads::with_threads;

/// Runs the bearing scene `text` (from `file`) on `threads`; returns
/// `{"json": result.json's text, "bearing": the type, and the elements'
/// arrays "angle", "load", "max_pressure_inner", "max_pressure_outer",
/// "displacement", "tilt"}`.
pub(crate) fn run<'py>(
    py: Python<'py>,
    file: &Path,
    text: &str,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = guarded("scene", || {
        BearingScene::from_str(file, text).map_err(scene_error)
    })?;
    let ceiling = ceiling()?;
    let name = scene.name().to_string();
    let run = detach(py, |cancel| {
        with_threads(threads, || {
            cancel.watch(|| {
                isolated::<_, RunError>(&name, || run_bearing(&scene, &ceiling))
                    .map_err(scene_error)
            })
        })
    })??;
    let json = serde_json::to_string_pretty(&run.result)
        .map_err(|e| SolveError::new_err(format!("result.json: {e}")))?;
    let d = PyDict::new(py);
    d.set_item("json", json)?;
    d.set_item("bearing", run.result.bearing.clone())?;
    let column = |f: fn(&elcon_report::ElementJson) -> f64| -> Vec<f64> {
        run.result.elements.iter().map(f).collect()
    };
    for (key, values) in [
        ("angle", column(|e| e.angle)),
        ("load", column(|e| e.load)),
        ("max_pressure_inner", column(|e| e.max_pressure_inner)),
        ("max_pressure_outer", column(|e| e.max_pressure_outer)),
        ("displacement", column(|e| e.displacement)),
        ("tilt", column(|e| e.tilt)),
    ] {
        d.set_item(key, PyArray1::from_vec(py, values))?;
    }
    Ok(d)
}

/// Checks the bearing scene `text` as `elcon check` does; returns its
/// name, the estimate's summary, points per contact, zones and peak bytes.
pub(crate) fn check<'py>(py: Python<'py>, file: &Path, text: &str) -> PyResult<Bound<'py, PyDict>> {
    let ceiling = ceiling()?;
    let (scene, estimate) = guarded("scene", || {
        let scene = BearingScene::from_str(file, text).map_err(scene_error)?;
        let estimate = BearingEstimate::of(&scene);
        estimate.admit(&scene, &ceiling).map_err(scene_error)?;
        Ok((scene, estimate))
    })?;
    let d = PyDict::new(py);
    d.set_item("name", scene.name())?;
    d.set_item("estimate", estimate.summary())?;
    d.set_item("points", estimate.points)?;
    d.set_item("zones", estimate.zones)?;
    d.set_item("peak_bytes", estimate.peak_bytes)?;
    d.set_item("warnings", Vec::<String>::new())?;
    Ok(d)
}
