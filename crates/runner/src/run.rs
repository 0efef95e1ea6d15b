//! Running a scene: assemble `S = A(1) + A(2)` and eps, solve the contact
//! problem (`Y = S F + eps - alpha e`, `e^T F = P`, `F, Y >= 0`,
//! `F_k Y_k = 0`) with the scene's method, estimate its discretization
//! error on coarser grids (`error_estimate`), compare with the
//! closed form that applies, compute the stresses below the surface when
//! asked (`subsurface`), and run the design stage if the scene has
//! one. The result
//! is what result.json holds (schema in docs/results.md).

use std::time::Instant;

use elcon_analysis::zone::Zone;
use elcon_analysis::{AnalysisError, ContactSolution, Normal, Tilt};
use elcon_lcp::{Cancel, LcpError};
use elcon_num::{Num, rounded};
use elcon_process::{ProcessError, faults};
use elcon_report::{DiscretizationJson, Header, InputsJson, Run, RunResult, Seconds, SolutionJson};
use elcon_scene::{MAX_STRAIN, Scene, approach_strain};

use crate::compare::compare;
use crate::design_stage::design_stage;
use crate::error::{RunError, run_error};
use crate::error_estimate::discretization;
use crate::subsurface::subsurface;

/// Refuses the answer of a moment-loaded scene whose solved rotation lies
/// outside the small-rotation theory the model rests on
/// (`elcon_analysis::rotation::small_rotation`: beyond its
/// `MAX_ROTATION`, or the contact pushed against the zone's edge).
/// The message names the tilts or moments as written (`loading.tilt_x`,
/// `loading.moment_y`, ...) and the zone's keys.
fn small_rotation(scene: &Scene, solution: &ContactSolution) -> Result<(), RunError> {
    let loading = scene.loading();
    elcon_analysis::rotation::small_rotation(&loading, solution).map_err(|why| {
        run_error(
            scene,
            format!(
                "{}: {why} (points.zone or points.radius)",
                rotation_fields(&loading)
            ),
        )
    })
}

/// The tilts and moments a loading gives, as a user wrote them:
/// "`loading.tilt_x` = 0.1, `loading.moment_y` = 5".
fn rotation_fields(loading: &elcon_analysis::Loading) -> String {
    let named = |axis: &str, t: Tilt| match t {
        Tilt::Prescribed { angle } if angle != 0.0 => {
            Some(format!("`loading.tilt_{axis}` = {}", Num(angle)))
        }
        Tilt::Free { moment } if moment != 0.0 => {
            Some(format!("`loading.moment_{axis}` = {}", Num(moment)))
        }
        _ => None,
    };
    [named("x", loading.tilt_x), named("y", loading.tilt_y)]
        .into_iter()
        .flatten()
        .collect::<Vec<_>>()
        .join(", ")
}

/// Refuses the answer of a load-controlled scene whose solved approach is
/// beyond [`MAX_STRAIN`] of the candidate zone's smaller extent, or
/// on an ellipse grid of the zone across the Hertz ellipse's minor axis
/// whatever its turn (`Scene::approach_extent`, as `check` measures
/// Hertz's approach): the mean pressure over the zone can be small
/// against E* while the contact sinks half a roller's length into a soft
/// body.
fn small_approach(scene: &Scene, solution: &ContactSolution) -> Result<(), RunError> {
    let Normal::Load(load) = scene.loading().normal else {
        return Ok(());
    };
    let extent = scene.approach_extent();
    let Some(s) = approach_strain(solution.approach, extent) else {
        return Ok(());
    };
    let length = scene.units().length();
    Err(run_error(
        scene,
        format!(
            "`loading.load` = {}: the solved approach, {} {length}, is {s:.1e} times {}, {} \
             {length}: beyond the small strain (at most {}) of the linear elasticity the \
             influence models rest on; give a smaller load or stiffer bodies (youngs_modulus, \
             modulus), or check their units",
            Num(load),
            rounded(solution.approach),
            extent.what,
            rounded(extent.length),
            MAX_STRAIN
        ),
    ))
}

/// A failed solve's error. Under a moment the engine's failures that mean
/// "no solution" (a ray, an infeasible or unbounded tableau, a broken-down
/// attempt, a certificate that does not hold) say that the contact cannot
/// carry the moment: the message says so in the scene's terms (the
/// moments as written, the load centre against the candidate zone, what
/// to change), with the engine's own words on a second line.
fn solve_error(scene: &Scene, e: AnalysisError) -> RunError {
    let loading = scene.loading();
    let moment = |t: Tilt| match t {
        Tilt::Free { moment } if moment != 0.0 => Some(moment),
        _ => None,
    };
    let (mx, my) = (moment(loading.tilt_x), moment(loading.tilt_y));
    let no_solution = matches!(
        &e,
        AnalysisError::Engine(
            LcpError::RayTermination { .. }
                | LcpError::Infeasible { .. }
                | LcpError::Unbounded { .. }
                | LcpError::BrokeDown { .. }
                | LcpError::Inaccurate { .. }
        )
    );
    if !no_solution || (mx.is_none() && my.is_none()) {
        return run_error(scene, e);
    }
    let moments: Vec<String> = [("moment_x", mx), ("moment_y", my)]
        .into_iter()
        .filter_map(|(name, m)| m.map(|m| format!("`loading.{name}` = {}", Num(m))))
        .collect();
    let zone = Zone::of(scene.points());
    let centre = match loading.load_value() {
        Some(load) => {
            let c = (0.0 - my.unwrap_or(0.0) / load, mx.unwrap_or(0.0) / load);
            let depth = zone.depth(c);
            let place = if depth > 0.0 {
                format!("{} inside", rounded(depth))
            } else {
                "on".to_string()
            };
            format!(
                "the load centre (the moment over the load) at (x, y) = ({}, {}) lies {place} \
                 the outline of the candidate zone ({}), too near its edge for the bodies' \
                 pressure to balance the moment",
                rounded(c.0),
                rounded(c.1),
                zone.describe()
            )
        }
        None => format!(
            "under the approach given, no contact inside the candidate zone ({}) balances the \
             moment",
            zone.describe()
        ),
    };
    run_error(
        scene,
        format!(
            "{} cannot be carried by the contact: {centre}. Give a smaller moment, or a larger \
             zone (points.zone or points.radius)\n  the solver: {e}",
            moments.join(" and ")
        ),
    )
}

/// Runs a validated scene.
///
/// # Errors
/// [`RunError::Run`] naming the scene when the assembly, the solve, or the
/// design stage fails.
pub fn run(scene: &Scene) -> Result<Run, RunError> {
    let start = Instant::now();
    faults::panic_point(scene.name());
    let builder = scene.builder(scene.points().clone(), scene.loading());
    let problem = builder.clone().build().map_err(|e| run_error(scene, e))?;
    let solution = problem
        .solve(scene.method(), scene.options())
        .map_err(|e| solve_error(scene, e))?;
    small_rotation(scene, &solution)?;
    small_approach(scene, &solution)?;
    // The coarser grids' problems are built and dropped one at a time,
    // each a sixteenth (surface) or a quarter (line) of S at most.
    let discretization = scene
        .error_estimate()
        .then(|| discretization(scene, &builder, &solution));
    drop(builder);
    // A stage an interrupt cut short (a grid's solve cancelled reads as a
    // failed grid; a cancelled subsurface sweep as no stresses) ends the
    // run as interrupted, never as a result.
    unless_interrupted(scene)?;
    let (fields, subsurface_json) = subsurface(scene, problem.points(), &solution).unzip();
    unless_interrupted(scene)?;
    let (reference, reference_pressures) = match scene.reference() {
        Some(r) => {
            let (json, p) = compare(r, &problem, &solution, scene.loading());
            (Some(json), p)
        }
        None => (None, None),
    };
    let (design_json, design) = match scene.design() {
        Some(_) => Some(design_stage(scene, &problem, &solution)?),
        None => None,
    }
    .unzip();
    unless_interrupted(scene)?;
    let result = RunResult {
        scene: scene.name().to_string(),
        file: scene.file().display().to_string(),
        description: scene.description().map(String::from),
        units: scene.units().clone(),
        header: Header::of(&problem, &solution, scene.method()),
        seconds: Seconds {
            assembly: problem.assembly_seconds(),
            solve: solution.solve_seconds,
            error_estimate: discretization
                .as_ref()
                .map_or(0.0, DiscretizationJson::extra_seconds),
            subsurface: subsurface_json.as_ref().map_or(0.0, |s| s.seconds),
            total: start.elapsed().as_secs_f64(),
        },
        solution: SolutionJson::of(&solution, &warnings(scene, discretization.as_ref())),
        discretization,
        subsurface: subsurface_json,
        reference,
        design: design_json,
        inputs: Some(InputsJson::of(scene)),
    };
    Ok(Run {
        scene: scene.clone(),
        problem,
        solution,
        reference_pressures,
        design,
        subsurface: fields,
        result,
    })
}

/// [`ProcessError::Interrupted`] when the interrupt this thread watches
/// was given (SIGINT, SIGTERM): between stages, which do not all return
/// an error when cut short.
fn unless_interrupted(scene: &Scene) -> Result<(), RunError> {
    match Cancel::requested() {
        true => Err(ProcessError::Interrupted {
            scene: scene.name().to_string(),
        }
        .into()),
        false => Ok(()),
    }
}

/// The scene's warnings, then what in its input limits the estimate's
/// quantities (a surface interpolated with slope kinks).
fn warnings(scene: &Scene, discretization: Option<&DiscretizationJson>) -> Vec<String> {
    let limits = discretization.map_or(&[][..], |d| &d.limits[..]);
    scene.warnings().iter().chain(limits).cloned().collect()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn spheres(loading: &str) -> Scene {
        let text = include_str!("../tests/scenes/common/spheres.toml")
            .replace("load = 100.0", loading)
            .replace("across = 41", "across = 11");
        Scene::from_str(Path::new("t.toml"), &text).unwrap()
    }

    fn ray() -> AnalysisError {
        AnalysisError::Engine(LcpError::RayTermination {
            size: 97,
            pivot: 40,
            entering: "w[77]".into(),
        })
    }

    #[test]
    fn a_moment_the_contact_cannot_carry_is_said_in_the_scene_s_terms() {
        let s = spheres("load = 100.0\nmoment_x = 1.0\nmoment_y = -0.5");
        let e = solve_error(&s, ray()).to_string();
        assert!(
            e.starts_with(
                "scene `t`: `loading.moment_x` = 1 and `loading.moment_y` = -0.5 cannot be \
                 carried by the contact: the load centre (the moment over the load) at (x, y) = \
                 (0.005, 0.01) lies "
            ),
            "{e}"
        );
        assert!(
            e.contains("inside the outline of the candidate zone (x from"),
            "{e}"
        );
        assert!(
            e.contains("Give a smaller moment, or a larger zone (points.zone"),
            "{e}"
        );
        // The engine's words follow on a line of their own.
        let (_, engine) = e.split_once('\n').unwrap();
        assert!(
            engine.starts_with("  the solver: the contact solve failed: ray termination"),
            "{e}"
        );
        // A certificate that does not hold is translated alike.
        let inaccurate = AnalysisError::Engine(LcpError::Inaccurate {
            size: 97,
            pivots: 0,
            iterations: 40,
            certificate: Box::new(elcon_lcp::Certificate {
                min_z: 0.0,
                min_w: -0.49,
                min_u: 0.0,
                complementarity: 0.0,
                equality: 0.39,
                z_scale: 1.0,
                w_scale: 1.0,
                tolerance: 1e-12,
                finite: true,
            }),
        });
        assert!(
            solve_error(&s, inaccurate)
                .to_string()
                .contains("cannot be carried by the contact")
        );
    }

    #[test]
    fn other_failures_keep_the_engine_s_words() {
        // No moment: the engine's message as it is.
        let e = solve_error(&spheres("load = 100.0"), ray()).to_string();
        assert!(
            e.starts_with("scene `t`: the contact solve failed: ray termination"),
            "{e}"
        );
        // A pivot limit under a moment is not the moment's fault.
        let s = spheres("load = 100.0\nmoment_x = 1.0");
        let limit = AnalysisError::Engine(LcpError::PivotLimit { size: 97, limit: 3 });
        let e = solve_error(&s, limit).to_string();
        assert!(
            e.starts_with("scene `t`: the contact solve failed: pivot limit"),
            "{e}"
        );
    }

    #[test]
    fn a_conjugate_gradient_breakdown_counts_iterations_and_names_the_scene_key() {
        // The engine advises on a tableau; a scene has no tableau key, so
        // the message names the scene's key that helps.
        let broke = AnalysisError::Engine(LcpError::BrokeDown {
            method: "conjugate-gradient".into(),
            size: 227,
            pivots: 0,
            iterations: 1,
            reason: "a direction of non-positive curvature".into(),
            advice: elcon_lcp::TABLEAU_ADVICE,
        });
        let e = solve_error(&spheres("load = 100.0"), broke).to_string();
        assert!(
            e.contains("conjugate-gradient broke down after 1 iteration (size 227)"),
            "{e}"
        );
        assert!(e.contains("`solver.method`"), "{e}");
        assert!(!e.contains("::") && !e.contains("tableau"), "{e}");
    }
}
