//! result.json's `design` block: the family and its parameters, the
//! objective before and after, each load case re-analysed, the grids the
//! design went over and its verification on a finer one; and the design's
//! data for its plot ([`DesignRun`]).

use elcon_analysis::ContactProblem;
use elcon_design::{Evaluation, Profile};
use serde::Serialize;

use crate::subsurface::BodySubsurfaceJson;

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
    /// The re-analysis' warnings, as a standalone run of the case would
    /// give them (the contact reaching the zone's open edge: truncated).
    pub warnings: Vec<String>,
    /// Each body's stresses below the surface without the correction, when
    /// the scene asks for them (`outputs.subsurface`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subsurface_before: Option<[BodySubsurfaceJson; 2]>,
    /// The same with the correction.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subsurface_after: Option<[BodySubsurfaceJson; 2]>,
}

impl DesignCaseJson {
    /// Case `l`'s row under `load` with its reference intensity: p_max
    /// `before` and `after` the correction, the certificate and warnings
    /// after; no misalignment and no subsurface maxima (a scene's design
    /// stage adds them).
    pub fn of(
        l: usize,
        load: f64,
        reference: f64,
        before: &Evaluation,
        after: &Evaluation,
    ) -> Self {
        Self {
            load,
            misalignment: None,
            reference_intensity: reference,
            max_pressure_before: before.max_intensities[l],
            max_pressure_after: after.max_intensities[l],
            certificate_worst: after.solutions[l].certificate.worst(),
            certificate_holds: after.solutions[l].certificate.holds(),
            warnings: after.solutions[l]
                .warnings
                .iter()
                .map(ToString::to_string)
                .collect(),
            subsurface_before: None,
            subsurface_after: None,
        }
    }
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
    /// The worst p_max_l / r_l reached (what `minimized` = "pressure"
    /// minimizes).
    pub objective: f64,
    /// What the design minimized: "pressure", "von-mises" or "max-shear"
    /// (`design.objective`).
    pub minimized: String,
    /// A stress objective's worst stress over the cases (stress), on each
    /// case's depth grid; none for "pressure".
    pub worst_stress: Option<f64>,
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
    /// How the profile is defined between the stations it was designed
    /// at: its family's closed form, or the natural cubic spline through a
    /// free profile's knots.
    pub interpolation: String,
    /// The grids the design went over, coarse to fine, the last its own:
    /// each with the worst objective of the design on it.
    pub grids: Vec<DesignGridJson>,
    /// The design's profile evaluated on a grid finer than its own: its
    /// worst objective there agrees with `objective` to `grid_tolerance`
    /// (none with `design.refine = false`: not verified).
    pub verification: Option<DesignGridJson>,
    /// The relative agreement the verification is held to.
    pub grid_tolerance: Option<f64>,
    /// Seconds of the design stage.
    pub seconds: f64,
}

/// One grid of a design's sequence.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignGridJson {
    /// The grid ("18 x 80 cells", ...).
    pub grid: String,
    /// Its fineness: the scene's grid at spacing h / fineness.
    pub fineness: f64,
    /// Points of its largest load case.
    pub points: usize,
    /// The worst p_max_l / r_l over the cases on it.
    pub objective: f64,
    /// Seconds spent on it.
    pub seconds: f64,
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
