//! The design stage of a scene: every load case of `[design]` (each load
//! at each misalignment) built as the scene's problem is, analysed without
//! the correction, then the correction elcon-design finds for the
//! section's request (`elcon_design::DesignRequest`) with every case
//! re-analysed and certified; result.json's `design` block, and the
//! profile sampled for profile.csv.

use std::time::Instant;

use elcon_analysis::{ContactProblem, ContactSolution, Loading, Normal};
use elcon_design::{Analysis, DesignError, Profile, Sampling, axial_stations, evaluate};
use elcon_num::Num;
use elcon_report::{
    BodySubsurfaceJson, DesignCaseJson, DesignGridJson, DesignJson, DesignOf, DesignRun,
};
use elcon_scene::{DesignFamily, DesignSpec, RelativeTo, Scene};

use crate::design_keys::{DesignCaller, design_reason};
use crate::design_load::design_load;
use crate::error::{RunError, run_error};
use crate::subsurface::subsurface_of;

/// The reference intensity r_l of a load case.
fn reference_intensity(scene: &Scene, case: &ContactProblem, load: f64) -> Result<f64, RunError> {
    let spec = scene.design().expect("a design stage");
    Ok(match spec.relative_to() {
        RelativeTo::Absolute => 1.0,
        RelativeTo::Mean => load / case.points().total_measure(),
        // Validation refuses relative_to = "hertz" without a Hertz contact.
        RelativeTo::Hertz => scene.hertz_peak_pressure(load).ok_or_else(|| {
            run_error(
                scene,
                "design.relative_to = \"hertz\" needs a Hertz contact at every design load",
            )
        })?,
    })
}

/// Both bodies' subsurface maxima below one case's solution, when the
/// scene asks for the stresses.
fn case_subsurface(
    scene: &Scene,
    case: &ContactProblem,
    solution: &ContactSolution,
) -> Option<[BodySubsurfaceJson; 2]> {
    let options = scene.outputs().subsurface()?;
    let fields = subsurface_of(scene, case.points(), solution, options);
    let models = scene.bodies().each_ref().map(|b| b.model());
    Some([0, 1].map(|i| BodySubsurfaceJson::of(&fields[i], models[i])))
}

/// A design case's loading: the load, and the misalignment as a prescribed
/// rotation about the axis across the profile (`tilt_x` for a profile
/// along y, `tilt_y` along x), or the rotations free without a moment.
fn case_loading(axis: elcon_design::Axis, load: f64, misalignment: Option<f64>) -> Loading {
    match (misalignment, axis) {
        (None, _) => Loading::load(load),
        (Some(angle), elcon_design::Axis::Y) => Loading::load(load).with_tilt_x(angle),
        (Some(angle), elcon_design::Axis::X) => Loading::load(load).with_tilt_y(angle),
    }
}

/// The design stage: every load case analysed without and with the
/// correction the family's method finds, carried over finer grids until it
/// holds on one (`elcon_design::sequence`); both analyses on the design's
/// own (last) grid.
pub(crate) fn design_stage(
    scene: &Scene,
    problem: &ContactProblem,
    solution: &ContactSolution,
) -> Result<(DesignJson, DesignRun), RunError> {
    let spec = scene.design().expect("a design stage");
    let start = Instant::now();
    let (first, known, references) = design_cases(scene, spec, problem, solution)?;
    let fail = |e: DesignError| design_failure(scene, e);
    let reanalysis = scene.method_choice().given();
    let request = spec.request(Some(references.clone()), reanalysis, scene.options());
    let converged = match spec.sequence() {
        Some(sequence) => {
            let mut first = Some(first);
            request.run_converged(
                sequence,
                |fineness| match first.take() {
                    Some(cases) => Ok(Some(cases)),
                    None => refined_cases(scene, spec, fineness),
                },
                |_| {},
            )
        }
        None => on_scene_grid(&request, first),
    }
    .map_err(fail)?;
    let own_grid = converged.levels.last().map(|l| l.fineness) == Some(1.0);
    let none = vec![None; known.len()];
    let known = if own_grid { known } else { none };
    let cases = converged.cases;
    let method = request.method_for(&cases);
    let before = evaluate(
        &cases,
        spec.axis(),
        &Profile::none(),
        &Analysis::new(method, scene.options()).with_known(&known),
    )
    .map_err(fail)?;
    let grid = |level: &elcon_design::Level| DesignGridJson {
        grid: grid_name(scene, spec, level.fineness),
        fineness: level.fineness,
        points: level.points,
        objective: level.objective,
        seconds: level.seconds,
    };
    let grids: Vec<DesignGridJson> = converged.levels.iter().map(grid).collect();
    let verification = converged.verification.as_ref().map(grid);
    let outcome = converged.outcome;
    let (sampling, samples) = sampled(spec, &cases, &outcome.profile).map_err(fail)?;
    let of = DesignOf {
        family: spec.family(),
        axis: spec.axis(),
        relative_to: spec.relative_to().into(),
        references: &references,
        cases: &cases,
        before: &before,
        outcome: &outcome,
        grids: &grids,
        verification: verification.as_ref(),
        grid_tolerance: spec.sequence().map(|s| s.tolerance),
        profile_spacing: Some(sampling.spacing),
        seconds: start.elapsed().as_secs_f64(),
    };
    let after = &outcome.evaluation;
    let rows = spec
        .case_loadings()
        .into_iter()
        .enumerate()
        .map(|(l, (load, misalignment))| DesignCaseJson {
            misalignment,
            subsurface_before: case_subsurface(scene, &cases[l], &before.solutions[l]),
            subsurface_after: case_subsurface(scene, &cases[l], &after.solutions[l]),
            ..DesignCaseJson::of(l, load, references[l], &before, after)
        })
        .collect();
    let json = DesignJson::of(of, rows).map_err(fail)?;
    Ok((
        json,
        DesignRun {
            profile: outcome.profile,
            samples,
            before,
            after: outcome.evaluation,
            cases,
        },
    ))
}

/// The design's profile sampled for profile.csv: over the cells of its
/// own grid's stations, at `design.profile_spacing` or by default
/// `elcon_design::SAMPLES_PER_STATION` samples to a station.
fn sampled(
    spec: &DesignSpec,
    cases: &[ContactProblem],
    profile: &Profile,
) -> Result<(Sampling, Vec<(f64, f64)>), DesignError> {
    let (stations, _) = axial_stations(cases.iter().map(ContactProblem::points), spec.axis());
    let sampling = Sampling::new(&stations, spec.profile_spacing())?;
    let samples = profile.table(&sampling.positions())?;
    Ok((sampling, samples))
}

/// A design's failure as the scene's error: [`design_reason`] with the
/// scene's keys.
fn design_failure(scene: &Scene, e: DesignError) -> RunError {
    let mut reason = design_reason(&e, DesignCaller::Scene);
    if let DesignError::NotConverged { objectives, .. } = &e {
        reason.push_str(&growing_hint(scene, objectives));
    }
    run_error(scene, reason)
}

/// What to change when a design's worst objective grew on every finer
/// grid: no grid will do, the profile leaves a peak the grids sharpen (an
/// edge, a point load); the keys that set the profile's reach.
fn growing_hint(scene: &Scene, objectives: &[f64]) -> String {
    let growing = objectives.len() >= 3 && objectives.windows(2).all(|w| w[1] > w[0]);
    if !growing {
        return String::new();
    }
    let keys = match scene.design().map(|d| d.family()) {
        Some(DesignFamily::LogarithmicCrown { design_load, .. }) => format!(
            "`design.design_load` = {} sets the crown's depth: give about the heaviest design \
             load",
            Num(*design_load)
        ),
        _ => "the loads (loading.load, design.loads), the bodies' stiffness (youngs_modulus, \
              modulus) or the family (design.family, design.max_constant)"
            .to_string(),
    };
    format!(
        ". The worst objective grew on every finer grid, so more points will not help: the \
         profile leaves a peak each finer grid resolves higher (an edge, a concentrated load); \
         change {keys}"
    )
}

/// The design on the scene's grid alone (`design.refine = false`): one
/// level, not verified.
fn on_scene_grid(
    request: &elcon_design::DesignRequest,
    cases: Vec<ContactProblem>,
) -> Result<elcon_design::Converged, elcon_design::DesignError> {
    let start = Instant::now();
    let outcome = request.run(&cases)?;
    let references = request
        .reference_intensities
        .clone()
        .unwrap_or_else(|| vec![1.0; cases.len()]);
    let level = elcon_design::Level {
        fineness: 1.0,
        points: cases.iter().map(|c| c.points().len()).max().unwrap_or(0),
        objective: outcome.evaluation.relative_worst(&references),
        seconds: start.elapsed().as_secs_f64(),
        designed: true,
    };
    Ok(elcon_design::Converged {
        outcome,
        cases,
        levels: vec![level],
        verification: None,
    })
}

/// The grid of the scene's first design load at `fineness`, in words.
fn grid_name(scene: &Scene, spec: &DesignSpec, fineness: f64) -> String {
    let load = spec.loads().first().copied().unwrap_or(0.0);
    scene
        .grid_for(load, fineness)
        .map_or_else(|_| format!("fineness {}", Num(fineness)), |g| g.to_string())
}

/// The design's load cases on the grid of `fineness` (each design load's
/// grid refined: `Scene::grid_for`), S held as elcon-analysis decides for
/// that size (matrix-free on a large lattice) and shared by a load's
/// misalignments; `None` when a case would exceed `design.max_points`.
fn refined_cases(
    scene: &Scene,
    spec: &DesignSpec,
    fineness: f64,
) -> Result<Option<Vec<ContactProblem>>, elcon_design::DesignError> {
    let layout = |reason: String| elcon_design::DesignError::Incompatible {
        field: "points",
        reason,
    };
    let mut cases = Vec::new();
    // Each load's problem, shared by its misalignments.
    let mut bases: Vec<(f64, ContactProblem)> = Vec::new();
    for (load, misalignment) in spec.case_loadings() {
        let base = match bases.iter().position(|(l, _)| *l == load) {
            Some(i) => &bases[i].1,
            None => {
                let builder =
                    design_load(scene, load, fineness).map_err(|e| layout(e.to_string()))?;
                if spec
                    .sequence()
                    .is_some_and(|s| builder.points().len() > s.max_points)
                {
                    return Ok(None);
                }
                let base =
                    builder
                        .build()
                        .map_err(|source| elcon_design::DesignError::Analysis {
                            stage: format!(
                                "load {} on the grid of fineness {}",
                                Num(load),
                                Num(fineness)
                            ),
                            source,
                        })?;
                bases.push((load, base));
                &bases[bases.len() - 1].1
            }
        };
        let loading = case_loading(spec.axis(), load, misalignment);
        cases.push(base.with_loading(loading).map_err(|source| {
            elcon_design::DesignError::Analysis {
                stage: match misalignment {
                    Some(angle) => format!("load {} misaligned by {} rad", Num(load), Num(angle)),
                    None => format!("load {}", Num(load)),
                },
                source,
            }
        })?);
    }
    Ok(Some(cases))
}

/// The design's load cases (each load at each misalignment), the solutions
/// already known (the scene's own analysis, where a case is it) and the
/// reference intensities.
type DesignCases<'a> = (
    Vec<ContactProblem>,
    Vec<Option<&'a ContactSolution>>,
    Vec<f64>,
);

/// See [`DesignCases`]: on the scene's own points a problem solved in full
/// shares its S, and a design load's S is shared by its misalignments.
fn design_cases<'a>(
    scene: &Scene,
    spec: &DesignSpec,
    problem: &ContactProblem,
    solution: &'a ContactSolution,
) -> Result<DesignCases<'a>, RunError> {
    let mut cases = Vec::new();
    let mut known = Vec::new();
    let mut references = Vec::new();
    for (load, misalignment) in spec.case_loadings() {
        let points = scene.points_for(load)?;
        // On the scene's own points, a problem solved in full shares its S
        // (a folded one has no full S to share); at the scene's own load its
        // solution is the uncorrected analysis. A design load's own S is
        // shared by its misalignments.
        let own = problem.folding().is_none() && points == *problem.points();
        let loading = case_loading(spec.axis(), load, misalignment);
        let shared = cases
            .iter()
            .find(|c: &&ContactProblem| c.points() == &points)
            .or(own.then_some(problem));
        let case = match shared {
            Some(c) => c.with_loading(loading),
            None => design_load(scene, load, 1.0)?
                .build()
                .and_then(|base| base.with_loading(loading)),
        }
        .map_err(|e| run_error(scene, e))?;
        let solved = misalignment.is_none()
            && matches!(problem.loading().normal, Normal::Load(p) if own && p == load);
        known.push(solved.then_some(solution));
        references.push(reference_intensity(scene, &case, load)?);
        cases.push(case);
    }
    Ok((cases, known, references))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use elcon_scene::scene_with_design;

    use super::*;

    #[test]
    fn a_design_that_grows_on_every_grid_names_the_keys_that_set_its_reach() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/crowned-roller.toml");
        let text = std::fs::read_to_string(&path).unwrap();
        let log = "[design]\nfamily = \"logarithmic-crown\"\ndesign_load = 20.0\naxis = \"y\"\n";
        let scene = scene_with_design(&path, &text, log).unwrap();
        let hint = growing_hint(&scene, &[1.6, 2.1, 2.4]);
        assert!(hint.contains("`design.design_load` = 20"), "{hint}");
        assert!(hint.contains("more points will not help"), "{hint}");
        // Objectives that settle, or too few to tell, say nothing more.
        assert!(growing_hint(&scene, &[1.6, 1.5, 1.55]).is_empty());
        assert!(growing_hint(&scene, &[1.6, 2.1]).is_empty());
        let free = scene_with_design(&path, &text, "[design]\nfamily = \"free\"\n").unwrap();
        assert!(growing_hint(&free, &[1.0, 2.0, 3.0]).contains("design.family"));
    }
}
