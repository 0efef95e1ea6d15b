//! result.json: a run's header (how the problem was held and solved, with
//! the engine's statistics), its seconds, its solution's fields, and the
//! blocks of the discretization error estimate, the stresses below the
//! surface, the closed-form comparison and the design (docs/results.md
//! documents every field); and [`Run`], what the writers need beyond
//! result.json.
//!
//! Every block is built by one constructor (`Header::of`, `SolutionJson::of`,
//! ...) that the command line and the Python package both call, and every
//! type serializes and deserializes: a resumed batch and `elcon merge` read
//! result.json back into these types, never by paths into untyped JSON.

use std::path::Path;

use elcon_analysis::{ContactProblem, ContactSolution, Method, Storage};
use elcon_influence::Dimension;
use elcon_scene::{Scene, Units};
use serde::{Deserialize, Serialize};

use crate::design::{DesignJson, DesignRun};
use crate::discretization::DiscretizationJson;
use crate::error::ReportError;
use crate::reference::{ReferenceJson, XY};
use crate::solve::{CertificateJson, Holding, StatisticsJson};
use crate::subsurface::SubsurfaceJson;

/// A folded problem's symmetry, as written: the group by name and the
/// folding's size, which `elcon_influence::Folding` computes, not stores.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SymmetryJson {
    /// The reflections ("mirror x, mirror y", ...).
    pub group: String,
    /// The group's order.
    pub order: usize,
    /// Unknowns of the folded problem (one per orbit).
    pub unknowns: usize,
}

/// How a problem was held and solved: the first fields of result.json after
/// the scene's, and of a problem solved from Python.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// The engine's method.
    pub method: Method,
    /// How S was held: "dense" (every entry) or "matrix-free".
    pub influence: Holding,
    /// The storage: "dense", "folded" or "lattice".
    pub storage: Storage,
    /// "surface" or "line".
    #[serde(with = "dimension")]
    pub dimension: Dimension,
    /// Number of candidate points N.
    pub points: usize,
    /// The mirror symmetry the problem was folded with, if it was.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub symmetry: Option<SymmetryJson>,
    /// The engine's statistics.
    pub statistics: StatisticsJson,
}

impl Header {
    /// The header of `problem` solved into `solution` by `method`.
    pub fn of(problem: &ContactProblem, solution: &ContactSolution, method: Method) -> Self {
        let storage = problem.storage();
        Self {
            method,
            influence: Holding::of(storage),
            storage,
            dimension: problem.points().dimension(),
            points: problem.points().len(),
            symmetry: problem.folding().map(|f| SymmetryJson {
                group: f.group().to_string(),
                order: f.order(),
                unknowns: f.len(),
            }),
            statistics: StatisticsJson::of(&solution.statistics),
        }
    }
}

/// A [`Dimension`] by its name in result.json: "surface" or "line".
mod dimension {
    use elcon_influence::Dimension;
    use serde::{Deserialize, Deserializer, Serializer};

    /// The names, in the order of `Dimension`'s variants.
    const NAMES: [&str; 2] = ["line", "surface"];

    pub(super) fn serialize<S: Serializer>(d: &Dimension, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(match d {
            Dimension::Line => NAMES[0],
            Dimension::Surface => NAMES[1],
        })
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Dimension, D::Error> {
        let name = String::deserialize(d)?;
        match name.as_str() {
            "line" => Ok(Dimension::Line),
            "surface" => Ok(Dimension::Surface),
            _ => Err(serde::de::Error::unknown_variant(&name, &NAMES)),
        }
    }
}

/// Wall-clock seconds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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

impl Seconds {
    /// The seconds of a solve alone (assembly and solve; no estimate, no
    /// stresses): a problem solved from Python.
    pub fn of_solve(problem: &ContactProblem, solution: &ContactSolution) -> Self {
        let (assembly, solve) = (problem.assembly_seconds(), solution.solve_seconds);
        Self {
            assembly,
            solve,
            error_estimate: 0.0,
            subsurface: 0.0,
            total: assembly + solve,
        }
    }
}

/// A solution's fields as result.json writes them, from the approach to
/// the warnings: what a scene's run and a problem solved from Python
/// (`elcon.ContactProblem.solve`) both write, by one serialization.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
    pub certificate: CertificateJson,
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
            certificate: CertificateJson::of(&solution.certificate),
            warnings: warnings
                .iter()
                .cloned()
                .chain(solution.warnings.iter().map(|w| w.to_string()))
                .collect(),
        }
    }
}

/// A problem solved outside a scene (from Python's `ContactProblem`): the
/// header, the seconds and the solution's fields, each result.json's own.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProblemResult {
    /// How it was held and solved.
    #[serde(flatten)]
    pub header: Header,
    /// Seconds of the assembly and of the solve.
    pub seconds: Seconds,
    /// The solution's fields.
    #[serde(flatten)]
    pub solution: SolutionJson,
}

impl ProblemResult {
    /// `problem` solved into `solution` by `method`.
    pub fn of(problem: &ContactProblem, solution: &ContactSolution, method: Method) -> Self {
        Self {
            header: Header::of(problem, solution, method),
            seconds: Seconds::of_solve(problem, solution),
            solution: SolutionJson::of(solution, &[]),
        }
    }
}

/// What result.json holds (docs/results.md documents every field).
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// The scene's name.
    pub scene: String,
    /// The scene file.
    pub file: String,
    /// Its description.
    pub description: Option<String>,
    /// Unit labels.
    pub units: Units,
    /// How the problem was held and solved.
    #[serde(flatten)]
    pub header: Header,
    /// Seconds.
    pub seconds: Seconds,
    /// The solution's fields (approach through warnings), written in
    /// place: result.json has them at this level, and `RunResult` derefs
    /// to them (`result.approach`).
    #[serde(flatten)]
    pub solution: SolutionJson,
    /// The discretization error estimate (`solver.error_estimate`, on by
    /// default).
    pub discretization: Option<DiscretizationJson>,
    /// The stresses below the surface (`outputs.subsurface = true`).
    pub subsurface: Option<SubsurfaceJson>,
    /// The closed-form comparison, where one applies.
    pub reference: Option<ReferenceJson>,
    /// The design stage, if the scene has one.
    pub design: Option<DesignJson>,
    /// What the run read: the elcon that ran it and the data files, each
    /// with the SHA-256 of its bytes (a resumed batch runs again a run
    /// whose files changed).
    pub inputs: Option<InputsJson>,
}

/// result.json's `inputs`: the elcon version that ran the scene and the
/// data files it read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputsJson {
    /// The elcon version.
    pub elcon: String,
    /// The data files read (height maps, profiles, separation files),
    /// each with its key, resolved path, SHA-256 and size.
    pub files: Vec<elcon_scene::DataInput>,
}

impl InputsJson {
    /// The inputs of `scene`, run by this elcon.
    pub fn of(scene: &elcon_scene::Scene) -> Self {
        Self {
            elcon: env!("CARGO_PKG_VERSION").to_string(),
            files: scene.inputs().to_vec(),
        }
    }
}

impl std::ops::Deref for RunResult {
    type Target = SolutionJson;

    /// The solution's fields, read in place (`result.max_pressure`).
    fn deref(&self) -> &SolutionJson {
        &self.solution
    }
}

impl RunResult {
    /// result.json's text, as written.
    ///
    /// # Errors
    /// [`ReportError::Json`] naming `path` (the file it is for) when it
    /// cannot be serialized.
    pub fn to_json(&self, path: &Path) -> Result<String, ReportError> {
        serde_json::to_string_pretty(self).map_err(|e| ReportError::json(path, e))
    }

    /// Reads a result.json back.
    ///
    /// # Errors
    /// [`ReportError::Json`] naming the file when it cannot be read or is
    /// not a result.json.
    pub fn read(path: &Path) -> Result<Self, ReportError> {
        let bytes = std::fs::read(path).map_err(|e| ReportError::json(path, e))?;
        Self::from_bytes(&bytes, path)
    }

    /// A result.json's bytes, read (`path` names it in the error).
    ///
    /// # Errors
    /// [`ReportError::Json`] naming `path` when the bytes are not a
    /// result.json.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Self, ReportError> {
        serde_json::from_slice(bytes).map_err(|e| ReportError::json(path, e))
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
