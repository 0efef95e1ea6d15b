//! result.json's `design` block: the family and its parameters, the
//! profile itself ([`ProfileJson`]), the objective before and after, each
//! load case re-analysed, the grids the design went over and its
//! verification on a finer one; and the design's data for its plot and
//! profile.csv ([`DesignRun`]).

use elcon_analysis::ContactProblem;
use elcon_design::{
    Axis, DesignError, DesignFamily, DesignMethod, Evaluation, Found, Objective, Outcome, Profile,
};
use serde::{Deserialize, Serialize};

use crate::profile::ProfileJson;
use crate::subsurface::BodySubsurfaceJson;

/// What each load case's p_max is divided by (its reference intensity
/// r_l), as the design block names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RelativeTo {
    /// `r_l = 1`: the worst p_max itself.
    Absolute,
    /// The mean intensity `P / sum A_k` of each load.
    Mean,
    /// Each load's Hertz peak.
    Hertz,
    /// Intensities given by the caller (Python's `reference_intensities`).
    Given,
}

impl RelativeTo {
    /// Every reference, in the order messages list them.
    pub const ALL: [RelativeTo; 4] = [
        RelativeTo::Absolute,
        RelativeTo::Mean,
        RelativeTo::Hertz,
        RelativeTo::Given,
    ];

    /// Its name: "absolute", "mean", "hertz" or "given".
    pub const fn name(self) -> &'static str {
        match self {
            RelativeTo::Absolute => "absolute",
            RelativeTo::Mean => "mean",
            RelativeTo::Hertz => "hertz",
            RelativeTo::Given => "given",
        }
    }
}

elcon_num::named!(RelativeTo, "reference");
elcon_num::named_serde!(RelativeTo);

impl From<elcon_scene::RelativeTo> for RelativeTo {
    fn from(r: elcon_scene::RelativeTo) -> Self {
        match r {
            elcon_scene::RelativeTo::Absolute => RelativeTo::Absolute,
            elcon_scene::RelativeTo::Mean => RelativeTo::Mean,
            elcon_scene::RelativeTo::Hertz => RelativeTo::Hertz,
        }
    }
}

/// How a design was found: a linear family's program or descent, a
/// circular crown's search, a logarithmic crown set in closed form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FoundBy {
    /// The paper's program (every case a block of one tableau).
    Program,
    /// The case-decomposed descent.
    Descent,
    /// A circular crown's radius searched.
    Search,
    /// A logarithmic crown set from its design load.
    Set,
}

impl FoundBy {
    /// Every way, in the order messages list them.
    pub const ALL: [FoundBy; 4] = [
        FoundBy::Program,
        FoundBy::Descent,
        FoundBy::Search,
        FoundBy::Set,
    ];

    /// Its name: "program", "descent", "search" or "set".
    pub const fn name(self) -> &'static str {
        match self {
            FoundBy::Program => "program",
            FoundBy::Descent => "descent",
            FoundBy::Search => "search",
            FoundBy::Set => "set",
        }
    }

    /// How `found` was found.
    pub fn of(found: &Found) -> Self {
        match found {
            Found::Designed {
                method: DesignMethod::Program,
                ..
            } => FoundBy::Program,
            Found::Designed { .. } => FoundBy::Descent,
            Found::Searched { .. } => FoundBy::Search,
            // `Found::Set`; a new kind of `Found` gets its own name here.
            _ => FoundBy::Set,
        }
    }
}

elcon_num::named!(FoundBy, "design solver");
elcon_num::named_serde!(FoundBy);

/// One load case of a design, before and after: gathered from the
/// evaluations before and after the design, not the copy of one type.
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignCaseJson {
    /// The load (force).
    pub load: f64,
    /// The prescribed misalignment (rad), when the design has
    /// `misalignments`.
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
    pub subsurface_before: Option<[BodySubsurfaceJson; 2]>,
    /// The same with the correction.
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignJson {
    /// The family, as a scene names it ("polynomial (degree 4)").
    pub family: String,
    /// The axial coordinate, "x" or "y".
    pub axis: Axis,
    /// What each case's p_max is divided by.
    pub relative_to: RelativeTo,
    /// The profile's parameters by name (a, b, c; c0..cd; radius; design_load...).
    pub parameters: std::collections::BTreeMap<String, f64>,
    /// The worst p_max_l / r_l reached (what `minimized` = "pressure"
    /// minimizes).
    pub objective: f64,
    /// What the design minimized: "pressure", "von-mises" or "max-shear"
    /// (`design.objective`).
    pub minimized: Objective,
    /// A stress objective's worst stress over the cases (stress), on each
    /// case's depth grid; none for "pressure".
    pub worst_stress: Option<f64>,
    /// The same before the correction.
    pub objective_before: f64,
    /// Per load case.
    pub cases: Vec<DesignCaseJson>,
    /// The correction itself: a free profile's knots, drops and
    /// interpolation, or a family's coefficients.
    pub profile: ProfileJson,
    /// The spacing of profile.csv's samples (length); none where no
    /// profile.csv is written (Python's design over problems).
    pub profile_spacing: Option<f64>,
    /// How the linear family's problem was solved: "program" or
    /// "descent" (`design.method`, "auto" resolved); "search" for a
    /// circular crown, "set" for a logarithmic one.
    pub method: FoundBy,
    /// How each start ended (linear families).
    pub starts: Vec<String>,
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

/// What a design block is made of: the request (family, axis, reference),
/// the cases before and after (`outcome`), each case's row, the grids the
/// design went over, and its seconds. [`DesignJson::of`] derives the rest.
#[derive(Debug, Clone, Copy)]
pub struct DesignOf<'a> {
    /// The family designed.
    pub family: &'a DesignFamily,
    /// The axial coordinate.
    pub axis: Axis,
    /// What each case's p_max is divided by.
    pub relative_to: RelativeTo,
    /// The reference intensities r_l, one per case.
    pub references: &'a [f64],
    /// The load cases, on the design's own grid.
    pub cases: &'a [ContactProblem],
    /// Every case without the correction.
    pub before: &'a Evaluation,
    /// The correction and every case with it.
    pub outcome: &'a Outcome,
    /// The grids the design went over, coarse to fine, the last its own.
    pub grids: &'a [DesignGridJson],
    /// Its evaluation on a finer grid, when it was verified.
    pub verification: Option<&'a DesignGridJson>,
    /// The agreement the verification is held to.
    pub grid_tolerance: Option<f64>,
    /// The spacing of profile.csv's samples, when one is written.
    pub profile_spacing: Option<f64>,
    /// Seconds of the design.
    pub seconds: f64,
}

impl DesignJson {
    /// The design block of `d`, each case's row `rows[l]` (see
    /// [`DesignCaseJson::of`]; a scene's adds its misalignment and its
    /// stresses below the surface).
    ///
    /// # Errors
    /// [`ProfileJson::of`]'s, for a profile result.json has no form for.
    pub fn of(d: DesignOf<'_>, rows: Vec<DesignCaseJson>) -> Result<Self, DesignError> {
        let outcome = d.outcome;
        Ok(Self {
            family: d.family.describe(),
            axis: d.axis,
            relative_to: d.relative_to,
            parameters: outcome.profile.parameters(),
            objective: outcome.evaluation.relative_worst(d.references),
            minimized: outcome.found.minimized(),
            worst_stress: outcome.found.worst_stress(),
            objective_before: d.before.relative_worst(d.references),
            cases: rows,
            profile: ProfileJson::of(&outcome.profile)?,
            profile_spacing: d.profile_spacing,
            method: FoundBy::of(&outcome.found),
            starts: outcome.found.starts(),
            grids: d.grids.to_vec(),
            verification: d.verification.cloned(),
            grid_tolerance: d.grid_tolerance,
            seconds: d.seconds,
        })
    }

    /// Each case's row of `d` as it comes from the evaluations (load,
    /// reference, p_max before and after, the certificate after), `loads`
    /// one per case.
    pub fn rows(d: &DesignOf<'_>, loads: &[f64]) -> Vec<DesignCaseJson> {
        loads
            .iter()
            .enumerate()
            .map(|(l, &load)| {
                DesignCaseJson::of(l, load, d.references[l], d.before, &d.outcome.evaluation)
            })
            .collect()
    }
}

/// One grid of a design's sequence.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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

/// The design stage's data for its plot and profile.csv.
#[derive(Debug, Clone)]
pub struct DesignRun {
    /// The correction.
    pub profile: Profile,
    /// profile.csv's rows: the correction's (axial position, drop) at
    /// each sample (`elcon_design::Sampling`), lengths.
    pub samples: Vec<(f64, f64)>,
    /// Every case without correction.
    pub before: Evaluation,
    /// Every case with it.
    pub after: Evaluation,
    /// The load cases' problems.
    pub cases: Vec<ContactProblem>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_way_of_finding_a_design_keeps_elcon_design_s_name() {
        for (found, by) in [
            (Found::Searched { analyses: 3 }, FoundBy::Search),
            (
                Found::Set {
                    end: elcon_design::LogEnd::Lundberg,
                },
                FoundBy::Set,
            ),
        ] {
            assert_eq!(FoundBy::of(&found), by);
            assert_eq!(by.name(), found.method());
        }
        assert_eq!(
            "descent".parse::<FoundBy>().unwrap().name(),
            DesignMethod::Descent.name()
        );
        assert_eq!(
            "program".parse::<FoundBy>().unwrap().name(),
            DesignMethod::Program.name()
        );
    }
}
