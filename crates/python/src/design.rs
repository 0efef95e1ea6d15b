//! Designs: over contact problems (`design_problems`, each problem a load
//! case) or over a scene (`design_scene`, its design stage), both by the
//! scene's `[design]` keys.

use std::path::{Path, PathBuf};
use std::time::Instant;

use elcon_analysis::{ContactProblem, Method, Options};
use elcon_design::{Analysis, Profile, Roller, evaluate};
use elcon_process::Ceiling;
use elcon_report::{DesignGridJson, DesignJson, DesignOf, RelativeTo};
use elcon_scene::{DesignLayoutParts, DesignSpec, Scene};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::sections_text;
use crate::errors::{InputError, SolveError, design_error, guarded, parts_error, scene_error};
use crate::memory::ceiling;
use crate::problem::{Built, PyContactProblem, build_admitted};
use crate::scene::{run_prepared, scene_text};
use crate::signals::detach;

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
    sections_text(&[("design", Some(keys))])
}

/// The design's load cases: the problems given, a folded one built again
/// in full (a design reads every point) once it fits under `ceiling`.
fn unfolded_cases(
    py: Python<'_>,
    given: &[(ContactProblem, Option<Built>)],
    ceiling: &Ceiling,
) -> PyResult<Vec<ContactProblem>> {
    let mut cases = Vec::with_capacity(given.len());
    for (problem, built) in given {
        let case = match (built, problem.folding()) {
            (Some(b), Some(_)) => detach(py, |_| {
                guarded("design", || {
                    let builder = b
                        .builder(problem.points().clone(), problem.loading())
                        .fold(false);
                    build_admitted(builder, ceiling)
                })
            })??,
            _ => problem.clone(),
        };
        cases.push(case);
    }
    Ok(cases)
}

/// The design over `cases` by `spec`, as result.json's design block:
/// each case's p_max before and after, relative to `reference_intensities`
/// (1 each when not given); `roller_given` says whether the call gave the
/// logarithmic crown's roller (its failures name `roller.*`); `start` is
/// when the design began. Problems from arrays have no grid family to
/// refine: the design is made on their points, not verified on a finer
/// grid, and their stresses below the surface are a scene's (no Poisson's
/// ratios here).
fn design_json(
    spec: &DesignSpec,
    cases: &[ContactProblem],
    reference_intensities: Option<Vec<f64>>,
    roller_given: bool,
    start: Instant,
) -> PyResult<DesignJson> {
    let design_error = |e| design_error(e, roller_given);
    let method = cases
        .first()
        .map_or(Method::BlockPivoting, ContactProblem::default_method);
    let options = Options::default();
    let outcome = spec
        .request(reference_intensities.clone(), Some(method), &options)
        .run(cases)
        .map_err(design_error)?;
    let before = evaluate(
        cases,
        spec.axis(),
        &Profile::none(),
        &Analysis::new(method, &options),
    )
    .map_err(design_error)?;
    let references = reference_intensities
        .clone()
        .unwrap_or_else(|| vec![1.0; cases.len()]);
    let points = cases.iter().map(|c| c.points().len()).max().unwrap_or(0);
    let grid = DesignGridJson {
        grid: format!("{points} points"),
        fineness: 1.0,
        points,
        objective: outcome.evaluation.relative_worst(&references),
        seconds: start.elapsed().as_secs_f64(),
    };
    let of = DesignOf {
        family: spec.family(),
        axis: spec.axis(),
        relative_to: match reference_intensities {
            Some(_) => RelativeTo::Given,
            None => RelativeTo::Absolute,
        },
        references: &references,
        cases,
        before: &before,
        outcome: &outcome,
        grids: std::slice::from_ref(&grid),
        verification: None,
        grid_tolerance: None,
        profile_spacing: None,
        seconds: start.elapsed().as_secs_f64(),
    };
    let loads: Vec<f64> = cases
        .iter()
        .map(|c| c.loading().load_value().unwrap_or(f64::NAN))
        .collect();
    let rows = DesignJson::rows(&of, &loads);
    DesignJson::of(of, rows).map_err(design_error)
}

/// Designs a correction over the problems (each a load case under a load)
/// with the scene's `[design]` keys `keys`; returns the design as JSON
/// text of the scene's `DesignJson`.
#[pyfunction]
#[pyo3(signature = (problems, keys, reference_intensities=None, roller_dict=None))]
pub(crate) fn design_problems(
    py: Python<'_>,
    problems: Vec<PyRef<'_, PyContactProblem>>,
    keys: Bound<'_, PyDict>,
    reference_intensities: Option<Vec<f64>>,
    roller_dict: Option<Bound<'_, PyDict>>,
) -> PyResult<String> {
    let text = design_text(&keys)?;
    let roller = roller_dict.as_ref().map(roller).transpose()?;
    let roller_given = roller.is_some();
    let ceiling = ceiling()?;
    let start = Instant::now();
    let given: Vec<(ContactProblem, Option<Built>)> = problems
        .iter()
        .map(|p| (p.inner.clone(), p.built.clone()))
        .collect();
    drop(problems);
    let cases = unfolded_cases(py, &given, &ceiling)?;
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
    let json = detach(py, |_| {
        guarded("design", || {
            design_json(&spec, &cases, reference_intensities, roller_given, start)
        })
    })??;
    serde_json::to_string(&json).map_err(|e| SolveError::new_err(format!("the design: {e}")))
}

/// Runs a scene's design stage (a file or a dict), its `[design]`
/// replaced by `keys` when given; returns `{"json": the design's JSON text
/// (result.json's design block), "result": result.json's text}`.
#[pyfunction]
#[pyo3(signature = (path=None, scene=None, keys=None))]
pub(crate) fn design_scene<'py>(
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
    let run = run_prepared(py, scene, None)?;
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
