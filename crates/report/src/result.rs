//! result.json: a run's header (scene, units, method, storage, points,
//! statistics, seconds), its solution's fields, and the blocks of the
//! discretization error estimate, the stresses below the surface, the
//! closed-form comparison and the design (docs/results.md documents every
//! field); and [`Run`], what the writers need beyond result.json.

use elcon_analysis::{ContactProblem, ContactSolution};
use elcon_scene::{Scene, Units};
use serde::Serialize;

use crate::design::{DesignJson, DesignRun};
use crate::discretization::DiscretizationJson;
use crate::reference::{ReferenceJson, XY};
use crate::subsurface::SubsurfaceJson;

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
    /// The discretization error estimate: building and solving the
    /// coarser grids (0 when it is off).
    pub error_estimate: f64,
    /// The stresses below the surface (0 unless `outputs.subsurface`).
    pub subsurface: f64,
    /// The whole run (assembly, solve, error estimate, subsurface,
    /// reference, design).
    pub total: f64,
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
    /// The discretization error estimate (`solver.error_estimate`, on by
    /// default).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub discretization: Option<DiscretizationJson>,
    /// The stresses below the surface (`outputs.subsurface = true`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subsurface: Option<SubsurfaceJson>,
    /// The closed-form comparison, where one applies.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceJson>,
    /// The design stage, if the scene has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<DesignJson>,
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
    /// Each body's stresses below the surface, when the scene asks.
    pub subsurface: Option<[elcon_analysis::subsurface::Subsurface; 2]>,
    /// The written result.
    pub result: RunResult,
}
