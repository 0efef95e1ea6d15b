//! A bearing scene's run: its memory estimated against the ceiling, the
//! bearing built into a system of contacts (elcon-elements) and solved,
//! certified over every zone and body, with the Hertz-spring model beside
//! it and the rating life from the balls' loads.

use std::time::Instant;

use elcon_analysis::system::SystemSettings;
use elcon_design::bearing::roller_crown;
use elcon_design::{DesignOptions, Family};
use elcon_elements::ElementsError;
use elcon_elements::bearing::BearingSolution;
use elcon_elements::bearing::BearingSystem;
use elcon_elements::life::RatingLife;
use elcon_elements::roller::RollerBearing;
use elcon_elements::roller::Slicing;
use elcon_process::{Ceiling, faults, human};
use elcon_report::{
    BearingResult, BearingRun, BearingSeconds, CrownCaseJson, CrownDesignJson, ReferenceModel,
};
use elcon_scene::{BearingScene, BearingSpec, CrownFamily};

use crate::error::RunError;

/// The memory a bearing scene needs and what `check` prints of it.
#[derive(Debug, Clone, PartialEq)]
pub struct BearingEstimate {
    /// Candidate points per contact.
    pub points: usize,
    /// Contact zones.
    pub zones: usize,
    /// The peak memory (bytes).
    pub peak_bytes: u64,
}

impl BearingEstimate {
    /// The estimate of `scene` on this process's threads.
    pub fn of(scene: &BearingScene) -> Self {
        let (points, peak_bytes) = scene.memory(rayon::current_num_threads());
        Self {
            points,
            zones: 2 * scene.spec().elements(),
            peak_bytes,
        }
    }

    /// One line for `check`.
    pub fn summary(&self) -> String {
        format!(
            "{} contact zones of {} points each, peak memory about {}",
            self.zones,
            self.points,
            human(self.peak_bytes)
        )
    }

    /// Refuses a scene over `ceiling`, saying what helps.
    ///
    /// # Errors
    /// [`RunError::TooBig`] when the estimate exceeds the ceiling.
    pub fn admit(&self, scene: &BearingScene, ceiling: &Ceiling) -> Result<(), RunError> {
        if ceiling.admits(self.peak_bytes) {
            return Ok(());
        }
        Err(RunError::TooBig {
            scene: scene.name().to_string(),
            needed: format!(
                "{} (two contact templates of {} points held dense, and a zone's solve per thread)",
                human(self.peak_bytes),
                self.points
            ),
            ceiling: ceiling.to_string(),
            hints: "fewer points across each contact (points.across, points.along), or \
                    fewer threads (--threads), or a machine with more memory"
                .into(),
        })
    }
}

/// Runs a validated bearing scene within `ceiling`.
///
/// # Errors
/// [`RunError::TooBig`] over the ceiling; [`RunError::Run`] naming the
/// scene when the system cannot be built or solved; an interrupt as
/// [`RunError::Process`].
pub fn run_bearing(scene: &BearingScene, ceiling: &Ceiling) -> Result<BearingRun, RunError> {
    let start = Instant::now();
    faults::panic_point(scene.name());
    BearingEstimate::of(scene).admit(scene, ceiling)?;
    let failed = |e: &dyn std::fmt::Display| RunError::Run {
        scene: scene.name().to_string(),
        reason: e.to_string(),
    };
    let interrupted = |e: &elcon_elements::ElementsError| {
        matches!(
            e,
            elcon_elements::ElementsError::Analysis(elcon_analysis::AnalysisError::Engine(
                elcon_lcp::LcpError::Cancelled
            ))
        )
    };
    let mut system = system_of(scene.spec()).map_err(|e| failed(&e))?;
    let assembly = start.elapsed().as_secs_f64();
    let cancelled = |e: ElementsError| match interrupted(&e) {
        true => RunError::Process(elcon_process::ProcessError::Interrupted {
            scene: scene.name().to_string(),
        }),
        false => failed(&e),
    };
    let (spec, solution, design) = match (scene.spec(), scene.crown_design()) {
        (BearingSpec::Roller { bearing, grid }, Some(family)) => {
            let (crowned, solution, json) =
                crown_design(bearing, grid, family).map_err(|e| failed(&e))?;
            let spec = BearingSpec::Roller {
                bearing: crowned,
                grid: *grid,
            };
            system = system_of(&spec).map_err(|e| failed(&e))?;
            (spec, solution, Some(json))
        }
        (spec, _) => {
            let solution = system
                .solve(&SystemSettings::default())
                .map_err(cancelled)?;
            (spec.clone(), solution, None)
        }
    };
    let solve = start.elapsed().as_secs_f64() - assembly;
    let loads: Vec<f64> = solution.elements.iter().map(|e| e.load).collect();
    let (reference, life) = references(scene, &spec, &loads).map_err(|e| failed(&e))?;
    let points: Vec<_> = system
        .system
        .zones()
        .iter()
        .map(|z| z.problem.points().clone())
        .collect();
    let seconds = BearingSeconds {
        assembly,
        solve,
        total: start.elapsed().as_secs_f64(),
    };
    let mut result = BearingResult::of(
        scene,
        &solution,
        life.as_ref(),
        &reference,
        seconds,
        points[0].len(),
    );
    result.crown_design = design;
    if scene.subsurface() {
        stresses_below(&spec, &solution, &points, &mut result);
    }
    Ok(BearingRun {
        scene: scene.clone(),
        solution,
        points,
        result,
    })
}

/// The bearing's system of contacts.
fn system_of(spec: &BearingSpec) -> Result<BearingSystem, ElementsError> {
    match spec {
        BearingSpec::Ball { bearing, grid } => bearing.system(grid),
        BearingSpec::Roller { bearing, grid } => bearing.system(grid),
    }
}

/// The reference model beside the system (the Hertz springs of a ball
/// bearing, the slicing model of a roller bearing: mm and N only) and the
/// rating life from the elements' `loads` (mm and N only).
fn references(
    scene: &BearingScene,
    spec: &BearingSpec,
    loads: &[f64],
) -> Result<(ReferenceModel, Option<RatingLife>), ElementsError> {
    let rated = scene.rates_life();
    Ok(match spec {
        BearingSpec::Ball { bearing, .. } => {
            let springs = bearing.springs()?.solve()?;
            let reference = ReferenceModel {
                model: "discrete Hertz springs (Harris & Kotzalas, ch. 7)".into(),
                ring_displacement: springs.ring_displacement,
                loads: springs.loads,
                max_pressure: None,
            };
            let life = rated.then(|| RatingLife::of(bearing, loads)).transpose()?;
            (reference, life)
        }
        BearingSpec::Roller { bearing, grid } => {
            let slicing = Slicing {
                bearing: bearing.clone(),
                slices: grid.along,
            }
            .solve()?;
            let reference = ReferenceModel {
                model: "ISO/TS 16281 slicing with Palmgren's line-contact stiffness (mm, N)".into(),
                ring_displacement: slicing.ring_displacement,
                max_pressure: Some(slicing.max_pressures.iter().fold(0.0f64, |a, p| a.max(*p))),
                loads: slicing.loads,
            };
            let life = rated
                .then(|| RatingLife::of_rollers(bearing, loads))
                .transpose()?;
            (reference, life)
        }
    })
}

/// The rollers' crown designed over the bearing's own loaded rollers: the
/// crowned bearing, its solution and result.json's block.
fn crown_design(
    bearing: &RollerBearing,
    grid: &elcon_elements::roller::RollerGrid,
    family: CrownFamily,
) -> Result<(RollerBearing, BearingSolution, CrownDesignJson), elcon_design::DesignError> {
    let family_of = match family {
        CrownFamily::Free => Family::Free,
        CrownFamily::Quadratic => Family::Quadratic,
    };
    let c = roller_crown(bearing, grid, family_of, &DesignOptions::default())?;
    let (before, after) = c.max_pressures();
    let rows = match &c.crown {
        elcon_elements::roller::Crown::Table(rows) => rows.iter().map(|&(s, d)| [s, d]).collect(),
        _ => Vec::new(),
    };
    let json = CrownDesignJson {
        family: family.name().to_string(),
        rounds: c.rounds,
        cases: c
            .cases
            .iter()
            .map(|k| CrownCaseJson {
                roller: k.roller,
                load: k.load,
                tilt: k.tilt,
            })
            .collect(),
        objective: c.design.objective,
        max_pressure_before: before,
        max_pressure_after: after,
        crown: rows,
    };
    let crowned = RollerBearing {
        crown: c.crown.clone(),
        ..bearing.clone()
    };
    Ok((crowned, c.after, json))
}

/// The stresses below each loaded element's two contacts, into its row:
/// rings and elements are one material, so one field per contact.
fn stresses_below(
    spec: &BearingSpec,
    solution: &BearingSolution,
    points: &[elcon_influence::PointSet],
    result: &mut BearingResult,
) {
    use elcon_analysis::subsurface::{Subsurface, SubsurfaceOptions};
    let material = match spec {
        BearingSpec::Ball { bearing, .. } => bearing.material,
        BearingSpec::Roller { bearing, .. } => bearing.material,
    };
    let body = elcon_analysis::Body::uniform_patch(material);
    let options = SubsurfaceOptions::default();
    let peaks =
        |z: usize| match Subsurface::of(&points[z], &solution.system.zones[z], &body, &options) {
            Subsurface::Stresses(s) => Some(elcon_report::StressPeaksJson {
                von_mises: s.von_mises.value,
                von_mises_depth: s.von_mises.z,
                tresca: s.tresca.value,
                tresca_depth: s.tresca.z,
            }),
            Subsurface::NotApplicable(_) => None,
        };
    for (j, row) in result.elements.iter_mut().enumerate() {
        if row.load > 0.0 {
            row.subsurface_inner = peaks(2 * j);
            row.subsurface_outer = peaks(2 * j + 1);
        }
    }
}
