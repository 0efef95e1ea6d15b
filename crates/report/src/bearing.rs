//! A bearing run's outputs: result.json (the balls' loads and peak
//! pressures, the ring's displacement, the load zone, the rating life, the
//! Hertz-spring model beside them, the certificate over every zone and
//! body), elements.csv (a row per ball), and two plots: the load around
//! the bearing (each ball's load drawn outward from the pitch circle, at
//! equal scales) and the most loaded ball's inner contact pressure map.
//! docs/results.md documents every field.

use std::path::Path;

use plotters::prelude::*;
use serde::{Deserialize, Serialize};

use elcon_elements::bearing::BearingSolution;
use elcon_elements::life::RatingLife;
use elcon_process::{faults, write_atomic, write_atomic_with};
use elcon_scene::{BearingScene, BearingSpec, Units};

use crate::error::ReportError;
use crate::plot::{COLORS, MapOf, SIZE, padded, pressure_map_of, svg};
use crate::plot_parts::{Colours, Key, Map, err, map};
use crate::result::InputsJson;

/// One ball's row of result.json's `elements`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ElementJson {
    /// The ball's angle from the load's direction (degrees).
    pub angle: f64,
    /// Its load Q (force).
    pub load: f64,
    /// Its inner contact's largest pressure.
    pub max_pressure_inner: f64,
    /// Its outer contact's largest pressure.
    pub max_pressure_outer: f64,
    /// Its radial motion (length, outward).
    pub displacement: f64,
    /// Its tilt about its rolling direction (radians; 0 for a ball).
    pub tilt: f64,
    /// A roller's largest pressure in the end cells of its inner contact:
    /// the edge pressure a slicing model does not see.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end_pressure_inner: Option<f64>,
    /// The stresses below its inner contact (`[outputs] subsurface`, loaded
    /// elements).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub subsurface_inner: Option<StressPeaksJson>,
    /// The stresses below its outer contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub subsurface_outer: Option<StressPeaksJson>,
}

/// The largest stresses below a contact (the scene's pressure unit) and
/// their depths (its length unit).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StressPeaksJson {
    /// The largest von Mises stress.
    pub von_mises: f64,
    /// Its depth.
    pub von_mises_depth: f64,
    /// The largest shear (Tresca).
    pub tresca: f64,
    /// Its depth.
    pub tresca_depth: f64,
}

/// A displacement in the bearing's axes (length).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Xyz {
    /// Along the load (x).
    pub x: f64,
    /// Across it in the bearing's plane (y).
    pub y: f64,
    /// Along the bearing's axis (z).
    pub z: f64,
}

/// The rating life in result.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LifeJson {
    /// The bearing's basic rating life L10 (millions of revolutions).
    pub l10: f64,
    /// The inner raceway's life (millions of revolutions).
    pub inner_life: f64,
    /// The outer raceway's life (millions of revolutions).
    pub outer_life: f64,
    /// The inner raceway's capacity Q_ci (N).
    pub inner_capacity: f64,
    /// The outer raceway's capacity Q_co (N).
    pub outer_capacity: f64,
    /// The method and where it is written.
    pub method: String,
}

/// The reference model beside the system's answer: the Hertz springs of a
/// ball bearing, the slicing model of a roller bearing.
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceModelJson {
    /// What it is.
    pub model: String,
    /// The ring's displacement along the load (length).
    pub ring_displacement: f64,
    /// The most loaded ball's load (force).
    pub max_load: f64,
    /// The balls that carry load.
    pub loaded: usize,
    /// `system / reference - 1` for the most loaded element's load.
    pub max_load_difference: f64,
    /// The slicing model's largest slice pressure (Hertz's line contact on
    /// each slice; a roller bearing's).
    pub max_pressure: Option<f64>,
}

/// A reference model's answer as the report takes it.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceModel {
    /// What it is.
    pub model: String,
    /// The ring's displacement (length).
    pub ring_displacement: f64,
    /// Each element's load (force).
    pub loads: Vec<f64>,
    /// Its largest pressure, where it has one.
    pub max_pressure: Option<f64>,
}

/// A roller crown designed over the bearing's own rollers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CrownDesignJson {
    /// The family (`"free"`, `"quadratic"`).
    pub family: String,
    /// Rounds of design and re-solve.
    pub rounds: usize,
    /// The last round's cases: each loaded roller's `load` and `tilt`.
    pub cases: Vec<CrownCaseJson>,
    /// The design's objective: its worst peak pressure over the cases.
    pub objective: f64,
    /// The largest inner-contact pressure of the bearing with its crown as
    /// given.
    pub max_pressure_before: f64,
    /// The same with the designed crown (the elements' rows are this
    /// bearing's).
    pub max_pressure_after: f64,
    /// The crown made: `(position along the roller, drop)` at the design's
    /// stations, read linearly between them (also profile.csv).
    pub crown: Vec<[f64; 2]>,
}

/// One case of a crown design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CrownCaseJson {
    /// The roller.
    pub roller: usize,
    /// Its load (force).
    pub load: f64,
    /// Its inner contact's tilt (radians).
    pub tilt: f64,
}

/// The certificate over every zone and body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SystemCertificateJson {
    /// The largest body equilibrium residual, relative.
    pub equilibrium: f64,
    /// The worst zone's worst residual, relative.
    pub zones: f64,
    /// That zone's name.
    pub worst_zone: String,
    /// Whether every part holds.
    pub holds: bool,
}

/// The grid of every contact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BearingGridJson {
    /// Points over each axis of the Hertz contact of `5 F_r / Z`.
    pub across: usize,
    /// Cells along a roller (a roller bearing's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub along: Option<usize>,
    /// How far the grid reaches in those semi-axes.
    pub zone: f64,
    /// Candidate points per contact.
    pub points: usize,
    /// Contact zones (two per ball).
    pub zones: usize,
}

/// The seconds of a bearing run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BearingSeconds {
    /// Building the system (the two zone templates' S).
    pub assembly: f64,
    /// The system's solve.
    pub solve: f64,
    /// Everything.
    pub total: f64,
}

/// What a bearing run's result.json holds.
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BearingResult {
    /// The scene's name.
    pub scene: String,
    /// The scene file.
    pub file: String,
    /// Its description.
    pub description: Option<String>,
    /// Unit labels.
    pub units: Units,
    /// The bearing's type ("ball", "roller").
    pub bearing: String,
    /// The inner ring's misalignment (radians; a roller bearing's).
    pub misalignment: Option<f64>,
    /// The diametral clearance used (length).
    pub diametral_clearance: f64,
    /// The radial load (force).
    pub radial_load: f64,
    /// Every contact's grid.
    pub grid: BearingGridJson,
    /// Ball by ball, from ball 0 at the load's direction.
    pub elements: Vec<ElementJson>,
    /// The inner ring's displacement.
    pub ring_displacement: Xyz,
    /// The balls that carry load.
    pub loaded: usize,
    /// The load zone's half angle: the largest angle of a loaded ball
    /// (degrees).
    pub load_zone: f64,
    /// The most loaded ball's inner contact: its ellipse's semi-axes
    /// (length), when resolved.
    pub contact_ellipse_inner: Option<[f64; 2]>,
    /// The basic rating life (mm and N only).
    pub life: Option<LifeJson>,
    /// The crown designed over the bearing's rollers (`[design]`).
    pub crown_design: Option<CrownDesignJson>,
    /// The reference model's answer.
    pub reference: ReferenceModelJson,
    /// The certificate.
    pub certificate: SystemCertificateJson,
    /// Newton steps on the bodies' motions.
    pub iterations: usize,
    /// Zone solves made.
    pub zone_solves: usize,
    /// Seconds.
    pub seconds: BearingSeconds,
    /// What the run read.
    pub inputs: InputsJson,
}

/// A bearing run: the scene, its solution and result.json's contents.
#[derive(Debug, Clone)]
pub struct BearingRun {
    /// The scene.
    pub scene: BearingScene,
    /// The solution.
    pub solution: BearingSolution,
    /// The system's zone problems' points (ball j's inner zone is 2 j).
    pub points: Vec<elcon_influence::PointSet>,
    /// result.json.
    pub result: BearingResult,
}

impl BearingResult {
    /// result.json of `scene` solved into `solution`, with the life and the
    /// springs' answer.
    pub fn of(
        scene: &BearingScene,
        solution: &BearingSolution,
        life: Option<&RatingLife>,
        reference: &ReferenceModel,
        seconds: BearingSeconds,
        points: usize,
    ) -> Self {
        let spec = scene.spec();
        let s = &solution.system;
        let most = &solution.elements[0];
        let (across, zone, along, misalignment) = match spec {
            BearingSpec::Ball { grid, .. } => (grid.across, grid.zone, None, None),
            BearingSpec::Roller { grid, bearing } => (
                grid.across,
                grid.zone,
                Some(grid.along),
                Some(bearing.misalignment),
            ),
        };
        let worst_zone = s.certificate.worst_zone;
        Self {
            scene: scene.name().to_string(),
            file: scene.file().display().to_string(),
            description: scene.description().map(String::from),
            units: scene.units().clone(),
            bearing: scene.kind().name().to_string(),
            misalignment,
            diametral_clearance: spec.clearance(),
            radial_load: spec.radial_load(),
            grid: BearingGridJson {
                across,
                along,
                zone,
                points,
                zones: s.zones.len(),
            },
            elements: ElementJson::rows(solution, along),
            ring_displacement: Xyz {
                x: solution.ring_displacement[0],
                y: solution.ring_displacement[1],
                z: solution.ring_displacement[2],
            },
            loaded: solution.loaded,
            load_zone: load_zone(solution),
            contact_ellipse_inner: s.zones[0]
                .contact_ellipse
                .as_ref()
                .filter(|_| most.load > 0.0)
                .map(|e| [e.semi_major, e.semi_minor]),
            life: life.map(LifeJson::of),
            reference: ReferenceModelJson::of(reference, solution),
            certificate: SystemCertificateJson {
                equilibrium: s.certificate.equilibrium,
                zones: s.certificate.zones,
                worst_zone: format!("zone {worst_zone}"),
                holds: s.certificate.holds(),
            },
            iterations: s.iterations,
            zone_solves: s.zone_solves,
            seconds,
            inputs: InputsJson {
                elcon: env!("CARGO_PKG_VERSION").to_string(),
                files: scene.inputs().to_vec(),
            },
            crown_design: None,
        }
    }
}

impl ElementJson {
    /// A row per element of `solution`; a roller's end pressure where its
    /// contacts have `along` cells along it.
    fn rows(solution: &BearingSolution, along: Option<usize>) -> Vec<Self> {
        let zones = &solution.system.zones;
        solution
            .elements
            .iter()
            .enumerate()
            .map(|(j, e)| ElementJson {
                angle: e.angle,
                load: e.load,
                max_pressure_inner: e.max_pressure_inner,
                max_pressure_outer: e.max_pressure_outer,
                displacement: e.displacement,
                tilt: e.tilt,
                end_pressure_inner: along
                    .map(|n| elcon_elements::roller::end_pressure(&zones[2 * j].pressures, n)),
                subsurface_inner: None,
                subsurface_outer: None,
            })
            .collect()
    }
}

impl LifeJson {
    /// The block of a rating life.
    fn of(l: &RatingLife) -> Self {
        Self {
            l10: l.l10,
            inner_life: l.inner_life,
            outer_life: l.outer_life,
            inner_capacity: l.inner_capacity,
            outer_capacity: l.outer_capacity,
            method: "Lundberg-Palmgren raceway capacities (ISO 281's basis, as ISO/TS 16281 \
                     applies them to element loads), without the life modification factor"
                .into(),
        }
    }
}

impl ReferenceModelJson {
    /// The block of `reference` beside the system's `solution`.
    fn of(reference: &ReferenceModel, solution: &BearingSolution) -> Self {
        let largest = |loads: &mut dyn Iterator<Item = f64>| loads.fold(0.0f64, f64::max);
        let max_load = largest(&mut reference.loads.iter().copied());
        let system = largest(&mut solution.elements.iter().map(|e| e.load));
        Self {
            model: reference.model.clone(),
            ring_displacement: reference.ring_displacement,
            max_load,
            loaded: reference.loads.iter().filter(|q| **q > 0.0).count(),
            max_load_difference: system / max_load - 1.0,
            max_pressure: reference.max_pressure,
        }
    }
}

/// The load zone's half angle: the largest angle from the load's
/// direction of a loaded element (degrees).
fn load_zone(solution: &BearingSolution) -> f64 {
    solution
        .elements
        .iter()
        .filter(|e| e.load > 0.0)
        .map(|e| {
            if e.angle > 180.0 {
                360.0 - e.angle
            } else {
                e.angle
            }
        })
        .fold(0.0f64, f64::max)
}

/// Writes a bearing run's files into `dir`: result.json, elements.csv and,
/// unless switched off, load_distribution.svg and pressure_inner.svg.
///
/// # Errors
/// [`ReportError`] for a file that could not be written.
pub fn write_bearing_files(run: &BearingRun, dir: &Path) -> Result<(), ReportError> {
    let json = serde_json::to_string_pretty(&run.result).map_err(|e| ReportError::Json {
        path: dir.join("result.json"),
        reason: e.to_string(),
    })?;
    write_atomic(&dir.join("result.json"), json.as_bytes())?;
    faults::write_delay();
    write_atomic_with(&dir.join("elements.csv"), |w| elements_csv(run, w))?;
    faults::write_delay();
    if let Some(d) = &run.result.crown_design {
        let rows: Vec<(f64, f64)> = d.crown.iter().map(|r| (r[0], r[1])).collect();
        write_atomic_with(&dir.join("profile.csv"), |w| {
            crate::profile::profile_csv("y", run.scene.units().length(), &rows, w)
        })?;
        faults::write_delay();
    }
    if !run.scene.plots() {
        return Ok(());
    }
    let u = run.scene.units();
    let most = (0..run.solution.elements.len())
        .max_by(|&a, &b| {
            let e = &run.solution.elements;
            e[a].load.total_cmp(&e[b].load)
        })
        .unwrap_or(0);
    let zone = &run.solution.system.zones[2 * most];
    let name = format!(
        "{}: {} {most} inner contact",
        run.scene.name(),
        run.scene.kind().name()
    );
    for (file, svg) in [
        ("load_distribution.svg", load_distribution(run)),
        (
            "pressure_inner.svg",
            pressure_map_of(&MapOf {
                name: &name,
                points: &run.points[2 * most],
                pressures: &zone.pressures,
                centre: zone.load_centre,
                length: u.length(),
                intensity: u.pressure(),
            }),
        ),
    ] {
        let svg = svg.map_err(|e| ReportError::Plot {
            path: dir.join(file),
            reason: e.to_string(),
        })?;
        write_atomic(&dir.join(file), svg.as_bytes())?;
        faults::write_delay();
    }
    Ok(())
}

/// elements.csv: a row per ball.
fn elements_csv(run: &BearingRun, w: &mut dyn std::io::Write) -> std::io::Result<()> {
    let u = run.scene.units();
    writeln!(
        w,
        "# angle_deg,load_{f},max_pressure_inner_{p},max_pressure_outer_{p},displacement_{l}",
        f = u.force(),
        p = u.pressure(),
        l = u.length()
    )?;
    for e in &run.result.elements {
        writeln!(
            w,
            "{},{},{},{},{}",
            e.angle, e.load, e.max_pressure_inner, e.max_pressure_outer, e.displacement
        )?;
    }
    Ok(())
}

/// The load around the bearing at equal scales: the pitch circle, each
/// ball at its angle, a bar outward from it as long as its load (the
/// largest a third of the pitch radius), coloured by load, and the radial
/// load's direction.
fn load_distribution(run: &BearingRun) -> Result<String, ReportError> {
    let u = run.scene.units();
    let pitch = 0.5 * run.scene.spec().pitch_diameter();
    let elements = &run.solution.elements;
    let top = elements
        .iter()
        .fold(0.0f64, |a, e| a.max(e.load))
        .max(f64::MIN_POSITIVE);
    let scale = pitch / 3.0 / top;
    let reach = padded(
        -(pitch + pitch / 3.0 + 0.1 * pitch),
        pitch + pitch / 3.0 + 0.1 * pitch,
    );
    let spec = Map {
        title: format!(
            "{}: {} loads (largest {} {}; bars outward from the pitch circle)",
            run.scene.name(),
            run.scene.kind().name(),
            elcon_num::plain(top),
            u.force()
        ),
        x: reach,
        y: reach,
        names: ("x", "y"),
        unit: u.length().to_string(),
        colours: Colours {
            label: format!("element load ({})", u.force()),
            top,
        },
        legend: vec![
            ("pitch circle".to_string(), Key::Line(RGBColor(96, 96, 96))),
            ("radial load's direction".to_string(), Key::Line(COLORS[1])),
        ],
    };
    svg((SIZE.0, SIZE.1 + 120), |root| {
        map(root, &spec, |chart| {
            let circle: Vec<(f64, f64)> = (0..=360)
                .map(|d| {
                    let a = (d as f64).to_radians();
                    (pitch * a.cos(), pitch * a.sin())
                })
                .collect();
            chart
                .draw_series(std::iter::once(PathElement::new(
                    circle,
                    RGBColor(96, 96, 96).stroke_width(1),
                )))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(0.0, 0.0), (0.6 * pitch, 0.0)],
                    COLORS[1].stroke_width(3),
                )))
                .map_err(err)?;
            for e in elements {
                let a = e.angle.to_radians();
                let (c, s) = (a.cos(), a.sin());
                let outer = pitch + e.load * scale;
                let colour = spec.colours.of(e.load);
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(pitch * c, pitch * s), (outer * c, outer * s)],
                        colour.stroke_width(8),
                    )))
                    .map_err(err)?;
                chart
                    .draw_series(std::iter::once(Circle::new(
                        (pitch * c, pitch * s),
                        5,
                        BLACK.filled(),
                    )))
                    .map_err(err)?;
                if e.load > 0.0 {
                    let at = outer + 0.04 * pitch;
                    chart
                        .draw_series(std::iter::once(Text::new(
                            format!("{} {}", elcon_num::plain(e.load), u.force()),
                            (at * c, at * s),
                            ("sans-serif", crate::plot_parts::TICK_FONT),
                        )))
                        .map_err(err)?;
                }
            }
            Ok(())
        })?;
        Ok(())
    })
}
