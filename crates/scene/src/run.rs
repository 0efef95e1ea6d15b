//! Running a scene: assemble `S = A(1) + A(2)` and eps, solve the contact
//! problem (`Y = S F + eps - alpha e`, `e^T F = P`, `F, Y >= 0`,
//! `F_k Y_k = 0`) with the scene's method, compare with the closed form
//! that applies, and run the design stage if the scene has one. The result
//! is what result.json holds (schema in docs/results.md).

use std::time::Instant;

use elcon_analysis::{ContactProblem, ContactSolution, Loading, Normal};
use elcon_design::{Analysis, Evaluation, Profile, axial_stations, evaluate};
use elcon_influence::Dimension;
use serde::Serialize;

use crate::error::SceneError;
use crate::scene::{DesignSpec, Reference, RelativeTo, Scene, Units};

/// A folded problem's symmetry, as written. A mirror of
/// `elcon_influence::Folding` rather than a `Serialize` on it: result.json
/// writes the group by name and the folding's size, which the folding
/// computes, not stores.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SymmetryJson {
    /// The reflections ("mirror x, mirror y", ...).
    pub group: String,
    /// The group's order.
    pub order: usize,
    /// Unknowns of the folded problem (one per orbit).
    pub unknowns: usize,
}

/// Wall-clock seconds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Seconds {
    /// Assembling S and eps.
    pub assembly: f64,
    /// The engine's solve, certificate included.
    pub solve: f64,
    /// The whole run (assembly, solve, reference, design).
    pub total: f64,
}

/// Relative errors against the closed form, signed (computed / reference - 1),
/// except `pressure_l2` (a norm ratio). Absent where not meaningful.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Errors {
    /// Approach.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approach: Option<f64>,
    /// Largest pressure (intensity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure: Option<f64>,
    /// Contact radius or half-width.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_extent: Option<f64>,
    /// Load (under displacement control).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load: Option<f64>,
    /// `||p - p_ref||_2 / ||p_ref||_2` over the points.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_l2: Option<f64>,
}

/// The closed form's values and the errors against it: gathered from the
/// closed form and the solution, not the copy of one type.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferenceJson {
    /// "hertz-spheres", "hertz-cylinders", "flat-punch", "hetenyi-beam".
    pub kind: String,
    /// Reference approach (length).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approach: Option<f64>,
    /// Reference peak pressure (intensity unit).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_pressure: Option<f64>,
    /// Reference contact radius or half-width (length).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_extent: Option<f64>,
    /// Reference load (force).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load: Option<f64>,
    /// Relative errors.
    pub errors: Errors,
    /// What limits the comparison, where something does (Hetenyi's bonded
    /// beam against a tensionless foundation that lifted off).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// One load case of a design, before and after: gathered from the
/// evaluations before and after the design, not the copy of one type.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignCaseJson {
    /// The load (force).
    pub load: f64,
    /// The prescribed misalignment (rad), when the design has
    /// `misalignments`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub misalignment: Option<f64>,
    /// The reference intensity r_l the objective divides by.
    pub reference_intensity: f64,
    /// p_max without the correction.
    pub max_pressure_before: f64,
    /// p_max with it (re-analysed).
    pub max_pressure_after: f64,
    /// The re-analysis' certificate, worst residual.
    pub certificate_worst: f64,
    /// Whether it holds.
    pub certificate_holds: bool,
}

/// The design stage's result: the scene's design section by name and
/// elcon-design's outcome, not the copy of one type.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignJson {
    /// The family.
    pub family: String,
    /// The axial coordinate, "x" or "y".
    pub axis: String,
    /// "absolute", "mean" or "hertz".
    pub relative_to: String,
    /// The profile's parameters by name (a, b, c; c0..cd; radius; design_load...).
    pub parameters: std::collections::BTreeMap<String, f64>,
    /// The objective reached: the worst p_max_l / r_l.
    pub objective: f64,
    /// The same before the correction.
    pub objective_before: f64,
    /// Per load case.
    pub cases: Vec<DesignCaseJson>,
    /// The correction as a table: (axial position, drop), lengths.
    pub table: Vec<(f64, f64)>,
    /// How the linear family's problem was solved: "program" or
    /// "descent" (`design.method`, "auto" resolved); "search" for a
    /// circular crown, "set" for a logarithmic one.
    pub method: String,
    /// How each start ended (linear families).
    pub starts: Vec<String>,
    /// Seconds of the design stage.
    pub seconds: f64,
}

/// A solution's fields as result.json writes them, from the approach to
/// the warnings: what a scene's run and a problem solved from Python
/// (`elcon.ContactProblem.solve`) both write, by one serialization.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolutionJson {
    /// The approach alpha (length).
    pub approach: f64,
    /// The rotations of body 1 about the x and y axes through the load
    /// point (radians; 0 where symmetry makes them so).
    pub tilt: XY,
    /// The moments of the contact forces about the load point (force
    /// length): `sum F (y - y0)`, `-sum F (x - x0)`.
    pub moment: XY,
    /// Where the resultant of the contact forces acts (length).
    pub load_centre: XY,
    /// The load e^T F (force).
    pub load: f64,
    /// The largest load intensity max F_k / A_k (intensity unit).
    pub max_pressure: f64,
    /// Points in contact.
    pub contact_points: usize,
    /// Contact radius (surface) or half-width (line), the edge resolved within
    /// the outermost cells (`ContactSolution::contact_extent`; length).
    pub contact_extent: f64,
    /// Residuals from the original data.
    pub certificate: elcon_analysis::ContactCertificate,
    /// Warnings (truncated zone, uncertain contact).
    pub warnings: Vec<String>,
}

impl SolutionJson {
    /// The fields of `solution`, its warnings after `warnings` (a scene's
    /// own, from validation).
    pub fn of(solution: &ContactSolution, warnings: &[String]) -> Self {
        Self {
            approach: solution.approach,
            tilt: XY {
                x: solution.tilt_x,
                y: solution.tilt_y,
            },
            moment: XY {
                x: solution.moment_x,
                y: solution.moment_y,
            },
            load_centre: XY {
                x: solution.load_centre.0,
                y: solution.load_centre.1,
            },
            load: solution.load,
            max_pressure: solution.max_pressure,
            contact_points: solution.contact.len(),
            contact_extent: solution.contact_extent,
            certificate: solution.certificate,
            warnings: warnings
                .iter()
                .cloned()
                .chain(solution.warnings.iter().map(|w| w.to_string()))
                .collect(),
        }
    }
}

/// What result.json holds (docs/results.md documents every field).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunResult {
    /// The scene's name.
    pub scene: String,
    /// The scene file.
    pub file: String,
    /// Its description.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Unit labels.
    pub units: Units,
    /// The engine's method.
    pub method: String,
    /// How S was held: "dense" or "matrix-free" (`solver.method`).
    pub influence: String,
    /// "surface" or "line".
    pub dimension: String,
    /// Number of candidate points N.
    pub points: usize,
    /// The mirror symmetry the problem was folded with, if it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub symmetry: Option<SymmetryJson>,
    /// The engine's statistics (serialized by elcon-lcp's `serde` feature).
    pub statistics: elcon_lcp::Statistics,
    /// Seconds.
    pub seconds: Seconds,
    /// The solution's fields (approach through warnings), written in
    /// place: result.json has them at this level, and `RunResult` derefs
    /// to them (`result.approach`).
    #[serde(flatten)]
    pub solution: SolutionJson,
    /// The closed-form comparison, where one applies.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceJson>,
    /// The design stage, if the scene has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<DesignJson>,
}

/// A pair of components about x and y.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct XY {
    /// About (or along) x.
    pub x: f64,
    /// About (or along) y.
    pub y: f64,
}

impl std::ops::Deref for RunResult {
    type Target = SolutionJson;

    /// The solution's fields, read in place (`result.max_pressure`).
    fn deref(&self) -> &SolutionJson {
        &self.solution
    }
}

/// A run's result with what the outputs need beyond result.json.
#[derive(Debug, Clone)]
pub struct Run {
    /// The scene.
    pub scene: Scene,
    /// The contact problem as solved.
    pub problem: ContactProblem,
    /// Its solution.
    pub solution: ContactSolution,
    /// Reference pressure at each point, where a closed form applies.
    pub reference_pressures: Option<Vec<f64>>,
    /// The design stage's profile and evaluations (before, after), if any.
    pub design: Option<DesignRun>,
    /// The written result.
    pub result: RunResult,
}

/// The design stage's data for plots.
#[derive(Debug, Clone)]
pub struct DesignRun {
    /// The correction.
    pub profile: Profile,
    /// Every case without correction.
    pub before: Evaluation,
    /// Every case with it.
    pub after: Evaluation,
    /// The load cases' problems.
    pub cases: Vec<ContactProblem>,
}

fn run_error(scene: &Scene, e: impl std::fmt::Display) -> SceneError {
    SceneError::Run {
        scene: scene.name().to_string(),
        reason: e.to_string(),
    }
}

/// Runs a validated scene.
///
/// # Errors
/// [`SceneError::Run`] naming the scene when the assembly, the solve, or the
/// design stage fails.
pub fn run(scene: &Scene) -> Result<Run, SceneError> {
    let start = Instant::now();
    crate::faults::panic_point(scene.name());
    let problem = scene
        .builder(scene.points().clone(), scene.loading())
        .build()
        .map_err(|e| run_error(scene, e))?;
    let solution = problem
        .solve(scene.method(), scene.options())
        .map_err(|e| run_error(scene, e))?;
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
    let result = RunResult {
        scene: scene.name().to_string(),
        file: scene.file().display().to_string(),
        description: scene.description().map(String::from),
        units: scene.units().clone(),
        method: scene.method().name().to_string(),
        influence: problem.storage().held_as().to_string(),
        dimension: match scene.points().dimension() {
            Dimension::Surface => "surface".into(),
            Dimension::Line => "line".into(),
        },
        points: scene.points().len(),
        symmetry: problem.folding().map(|f| SymmetryJson {
            group: f.group().to_string(),
            order: f.order(),
            unknowns: f.len(),
        }),
        statistics: solution.statistics.clone(),
        seconds: Seconds {
            assembly: problem.assembly_seconds(),
            solve: solution.solve_seconds,
            total: start.elapsed().as_secs_f64(),
        },
        solution: SolutionJson::of(&solution, scene.warnings()),
        reference,
        design: design_json,
    };
    Ok(Run {
        scene: scene.clone(),
        problem,
        solution,
        reference_pressures,
        design,
        result,
    })
}

/// The closed form's values, errors, and per-point reference pressures.
fn compare(
    reference: &Reference,
    problem: &ContactProblem,
    sol: &ContactSolution,
    loading: Loading,
) -> (ReferenceJson, Option<Vec<f64>>) {
    let rel = |x: f64, r: f64| x / r - 1.0;
    let points = problem.points();
    let l2 = |p_ref: &[f64]| {
        let (mut num, mut den) = (0.0, 0.0);
        for (p, q) in sol.pressures.iter().zip(p_ref) {
            num += (p - q) * (p - q);
            den += q * q;
        }
        (num / den).sqrt()
    };
    let mut json = ReferenceJson {
        kind: reference.kind().to_string(),
        approach: None,
        max_pressure: None,
        contact_extent: None,
        load: None,
        errors: Errors::default(),
        note: None,
    };
    let pressures = match *reference {
        Reference::HertzSpheres(h) => {
            let p: Vec<f64> = (0..points.len())
                .map(|k| h.pressure(points.radius(k)))
                .collect();
            json.approach = Some(h.approach());
            json.max_pressure = Some(h.peak_pressure());
            json.contact_extent = Some(h.contact_radius());
            json.errors.max_pressure = Some(rel(sol.max_pressure, h.peak_pressure()));
            json.errors.contact_extent = Some(rel(sol.contact_extent, h.contact_radius()));
            json.errors.pressure_l2 = Some(l2(&p));
            match loading.normal {
                Normal::Load(_) => json.errors.approach = Some(rel(sol.approach, h.approach())),
                Normal::Approach(_) => {
                    json.load = Some(h.load);
                    json.errors.load = Some(rel(sol.load, h.load));
                }
            }
            Some(p)
        }
        Reference::HertzCylinders { hertz, datum } => {
            let p: Vec<f64> = (0..points.len())
                .map(|k| hertz.pressure(points.x(k)))
                .collect();
            json.max_pressure = Some(hertz.peak_pressure());
            json.contact_extent = Some(hertz.half_width());
            json.errors.max_pressure = Some(rel(sol.max_pressure, hertz.peak_pressure()));
            json.errors.contact_extent = Some(rel(sol.contact_extent, hertz.half_width()));
            json.errors.pressure_l2 = Some(l2(&p));
            if let Some(d0) = datum
                && let Ok(a) = hertz.approach(d0)
            {
                json.approach = Some(a);
                json.errors.approach = Some(rel(sol.approach, a));
            }
            Some(p)
        }
        Reference::FlatPunch(punch) => {
            json.contact_extent = Some(punch.radius);
            match loading.normal {
                Normal::Approach(d) => {
                    let p = punch.load(d);
                    json.load = Some(p);
                    json.errors.load = Some(rel(sol.load, p));
                }
                Normal::Load(p) => {
                    let d = punch.approach(p);
                    json.approach = Some(d);
                    json.errors.approach = Some(rel(sol.approach, d));
                }
            }
            // The pressure is singular at the edge: no peak or L2 comparison.
            None
        }
        Reference::Hetenyi(beam) => {
            let p: Vec<f64> = (0..points.len())
                .map(|k| beam.load_intensity(points.x(k)))
                .collect();
            json.approach = Some(beam.centre_deflection());
            json.max_pressure = Some(beam.load_intensity(0.0));
            json.errors.approach = Some(rel(sol.approach, beam.centre_deflection()));
            json.errors.max_pressure = Some(rel(sol.max_pressure, beam.load_intensity(0.0)));
            json.errors.pressure_l2 = Some(l2(&p));
            if sol.contact.len() < points.len() {
                json.note = Some(format!(
                    "Hetenyi's solution is that of a bonded foundation; this tensionless one \
                     lifted off at {} of {} points, so the errors measure the lift-off as well \
                     as the discretization",
                    points.len() - sol.contact.len(),
                    points.len()
                ));
            }
            Some(p)
        }
    };
    (json, pressures)
}

/// The reference intensity r_l of a load case.
fn reference_intensity(scene: &Scene, case: &ContactProblem, load: f64) -> Result<f64, SceneError> {
    let spec = scene.design().expect("a design stage");
    Ok(match spec.relative_to() {
        RelativeTo::Absolute => 1.0,
        RelativeTo::Mean => load / case.points().total_measure(),
        // Validation refuses relative_to = "hertz" without a Hertz contact.
        RelativeTo::Hertz => scene
            .hertz(load)
            .ok_or_else(|| {
                run_error(
                    scene,
                    "design.relative_to = \"hertz\" needs a Hertz contact at every design load",
                )
            })?
            .peak_pressure(),
    })
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
/// correction the family's method finds.
fn design_stage(
    scene: &Scene,
    problem: &ContactProblem,
    solution: &ContactSolution,
) -> Result<(DesignJson, DesignRun), SceneError> {
    let spec = scene.design().expect("a design stage");
    let start = Instant::now();
    let (cases, known, references) = design_cases(scene, spec, problem, solution)?;
    let fail = |e: elcon_design::DesignError| run_error(scene, e);
    let before = evaluate(
        &cases,
        spec.axis(),
        &Profile::none(),
        &Analysis::new(scene.method(), scene.options()).with_known(&known),
    )
    .map_err(fail)?;
    let (profile, after, starts, method) = find_design(scene, spec, &cases, &references)?;
    let objective = after.relative_worst(&references);
    let objective_before = before.relative_worst(&references);
    let (positions, _) = axial_stations(cases.iter().map(ContactProblem::points), spec.axis());
    let table = profile.table(&positions).map_err(fail)?;
    let json = DesignJson {
        family: spec.family().describe(),
        axis: match spec.axis() {
            elcon_design::Axis::X => "x".into(),
            elcon_design::Axis::Y => "y".into(),
        },
        relative_to: match spec.relative_to() {
            RelativeTo::Absolute => "absolute".into(),
            RelativeTo::Mean => "mean".into(),
            RelativeTo::Hertz => "hertz".into(),
        },
        parameters: profile.parameters(),
        objective,
        objective_before,
        cases: spec
            .case_loadings()
            .into_iter()
            .enumerate()
            .map(|(l, (load, misalignment))| DesignCaseJson {
                load,
                misalignment,
                reference_intensity: references[l],
                max_pressure_before: before.max_intensities[l],
                max_pressure_after: after.max_intensities[l],
                certificate_worst: after.solutions[l].certificate.worst(),
                certificate_holds: after.solutions[l].certificate.holds(),
            })
            .collect(),
        table,
        method: method.into(),
        starts,
        seconds: start.elapsed().as_secs_f64(),
    };
    Ok((
        json,
        DesignRun {
            profile,
            before,
            after,
            cases,
        },
    ))
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
) -> Result<DesignCases<'a>, SceneError> {
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
            // Held as the scene's problem is, unfolded: the design reads
            // every point.
            None => scene.builder(points, loading).fold(false).build(),
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

/// The correction of the spec's family, found as its family is
/// (`elcon_design::DesignRequest`), with its evaluation, how each start
/// ended and the method's name.
fn find_design(
    scene: &Scene,
    spec: &DesignSpec,
    cases: &[ContactProblem],
    references: &[f64],
) -> Result<(Profile, Evaluation, Vec<String>, &'static str), SceneError> {
    let outcome = spec
        .request(Some(references.to_vec()), scene.method(), scene.options())
        .run(cases)
        .map_err(|e| run_error(scene, e))?;
    let starts = outcome.found.starts();
    Ok((
        outcome.profile,
        outcome.evaluation,
        starts,
        outcome.found.method(),
    ))
}
