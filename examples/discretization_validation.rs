//! The discretization error estimate against the true error, where a
//! closed form gives the true one (docs/validation.md §4): each run solved,
//! then solved again on the coarser grids of its family
//! (`ProblemBuilder::discretization`), the estimated error of each quantity
//! printed beside its error against the closed form.
//!
//! - Hertz spheres, Conry & Seireg's Example 1 (steel, R = 1 and 10 in,
//!   100 lb, Love patches, zone 1.15 radii): 17 to 161 points across;
//! - Hertz cylinders in plane strain (hertz-cylinders.toml: steel, R = 10
//!   and 20 mm, 500 N/mm, datum 10 mm, zone 1.3): 21 to 401 across;
//! - a rigid flat punch (flat-punch.toml: a = 10 mm, aluminium, approach
//!   10 um): 10 to 40 cells per radius: the load against `2 a E* delta`,
//!   the peak pressure (singular at the rim) expected not converging;
//! - Hetenyi's beam (Example 2's beam and foundation, L = 8.9 in, 50,000
//!   lb at the centre): 20 to 160 points;
//! - a flat roller (a cylinder of R = 5 mm and length 10 mm on a plane,
//!   10 kN, its ends square): its peak at the ends expected not converging;
//! - spheres loaded off their axis (Example 1 with the load 0.1 a off the
//!   apex, the tilt free): against the Hertz solution translated to the
//!   load centre.
//!
//! The estimated error is Richardson's from the grids at h, 2h and 4h
//! (crates/analysis/src/discretization.rs); "est/true" is the ratio the
//! estimate should keep within 1/2 and 2.
//!
//! Run: `cargo run --release --example discretization_validation`

use std::error::Error;

use elcon::analysis::discretization::{Discretization, ErrorEstimate, Quantity};
use elcon::analysis::references::{BeamOnFoundation, FlatPunch, HertzCylinders, HetenyiBeam};
use elcon::analysis::{
    AnalysisError, ContactProblem, ContactSolution, Geometry, GridFamily, Loading, Method, Options,
    Surface, grid,
};
use elcon::influence::{Beam, Body, Material, combined_modulus};
use elcon_fixtures::scenes;

/// A sequence of grids, each a label and a family; `column` names what
/// the labels count.
struct Grids {
    column: &'static str,
    grids: Vec<(String, GridFamily)>,
}

/// The contact of `bodies` and `geometry` under `loading` (with
/// `body_edges`), solved on each grid of a sequence (block pivoting,
/// folded where symmetric) and its discretization error estimated.
struct Study<'a> {
    bodies: [&'a Body; 2],
    geometry: &'a Geometry,
    loading: Loading,
    body_edges: (bool, bool),
}

impl<'a> Study<'a> {
    /// The contact of `bodies` and `geometry` under `loading`, every edge
    /// of the candidate zone an open one.
    fn new(bodies: [&'a Body; 2], geometry: &'a Geometry, loading: Loading) -> Self {
        Self {
            bodies,
            geometry,
            loading,
            body_edges: (false, false),
        }
    }

    /// The same contact, the zone's extent along x (`along_x`), resp. y
    /// (`along_y`), the bodies' own (`ProblemBuilder::body_edges`).
    fn body_edges(self, along_x: bool, along_y: bool) -> Self {
        Self {
            body_edges: (along_x, along_y),
            ..self
        }
    }

    /// Prints the table `title`: on each of `grids`, a row per quantity
    /// of `truths` of the solution ([`rows`]).
    fn print(
        &self,
        title: &str,
        grids: Grids,
        truths: impl Fn(&ContactSolution) -> Vec<(Quantity, Option<f64>)>,
    ) -> Result<(), Box<dyn Error>> {
        println!("\n{title}\n");
        println!(
            "| {} | N | quantity | true error | estimated | est/true | order | verdict |",
            grids.column
        );
        println!("|---|---|---|---|---|---|---|---|");
        for (label, family) in grids.grids {
            let (sol, d) = self.run(&family)?;
            rows(&label, &sol, &d, &truths(&sol));
        }
        Ok(())
    }

    /// [`Study::print`] with the true errors of a Hertz contact's approach,
    /// peak pressure and extent against the closed form's `approach`,
    /// `peak` and `extent`.
    fn print_against_hertz(
        &self,
        title: &str,
        grids: Grids,
        (approach, peak, extent): (f64, f64, f64),
    ) -> Result<(), Box<dyn Error>> {
        self.print(title, grids, |sol| {
            vec![
                (Quantity::Approach, Some(sol.approach / approach - 1.0)),
                (Quantity::MaxPressure, Some(sol.max_pressure / peak - 1.0)),
                (
                    Quantity::ContactExtent,
                    Some(sol.contact_extent / extent - 1.0),
                ),
            ]
        })
    }

    /// Solves the problem on `family` and estimates its discretization
    /// error.
    fn run(
        &self,
        family: &GridFamily,
    ) -> Result<(ContactSolution, Discretization), Box<dyn Error>> {
        let [body1, body2] = self.bodies;
        let builder =
            ContactProblem::builder(family.points()?, body1, body2, self.geometry, self.loading)
                .method(Method::BlockPivoting)
                .body_edges(self.body_edges.0, self.body_edges.1);
        let problem = builder.clone().build()?;
        let options = Options::default();
        let solution = problem.solve(Method::BlockPivoting, &options)?;
        if !solution.certificate.holds() {
            return Err(format!("uncertified: {}", solution.certificate).into());
        }
        let d = builder.discretization(family, &solution, Method::BlockPivoting, &options)?;
        Ok((solution, d))
    }
}

/// The Hertz grids of `across` points across the contact, each labelled by
/// its count: `family` of each count.
fn hertz_grids(
    across: &[usize],
    family: impl Fn(usize) -> Result<GridFamily, AnalysisError>,
) -> Result<Grids, AnalysisError> {
    let grids = across.iter().map(|&n| Ok((n.to_string(), family(n)?)));
    Ok(Grids {
        column: "across",
        grids: grids.collect::<Result<_, AnalysisError>>()?,
    })
}

/// The rows of one grid (`label`, N = `sol`'s points), one a quantity of
/// `truths`: its true relative error (signed; `None`: no closed form), the
/// estimate's relative error, their ratio, the observed order and the
/// verdict.
fn rows(
    label: &str,
    sol: &ContactSolution,
    d: &Discretization,
    truths: &[(Quantity, Option<f64>)],
) {
    let n = sol.forces.len();
    for &(quantity, truth) in truths {
        let e = d.get(quantity).expect("every quantity is estimated");
        let estimated = e.relative_error();
        let show = |v: Option<f64>| v.map_or("-".into(), |v| format!("{v:.2e}"));
        let ratio = match (estimated, truth) {
            (Some(est), Some(t)) if t != 0.0 => format!("{:.2}", est / t.abs()),
            _ => "-".into(),
        };
        println!(
            "| {label} | {n} | {} | {} | {} | {ratio} | {} | {} |",
            quantity.name(),
            truth.map_or("-".into(), |t| format!("{t:+.2e}")),
            show(estimated),
            e.order.map_or("-".into(), |p| format!("{p:.2}")),
            verdict(e)
        );
    }
}

/// The verdict's name, `(fit)` after it where the estimate is the
/// least-squares fit over the grids between the nested ones.
fn verdict(e: &ErrorEstimate) -> String {
    match e.scatter {
        Some(_) if e.verdict.name() == "converging" => "converging (fit)".into(),
        _ => e.verdict.name().into(),
    }
}

fn spheres() -> Result<(), Box<dyn Error>> {
    let hertz = scenes::example1_hertz();
    let a = hertz.contact_radius();
    let (body, geometry) = scenes::example1_bodies();
    let study = Study::new([&body, &body], &geometry, Loading::load(100.0));
    let title = "Hertz spheres (Example 1, zone 1.15)";
    let grids = hertz_grids(&[17, 21, 41, 81, 161], |n| {
        grid::hertz_disk_family(a, n, 1.15)
    })?;
    study.print_against_hertz(title, grids, (hertz.approach(), hertz.peak_pressure(), a))
}

fn cylinders() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(210e3, 0.3)?;
    let d0 = 10.0;
    let hertz = HertzCylinders::new(combined_modulus(&steel, &steel), 1.0 / (0.1 + 0.05), 500.0)?;
    let (b, approach) = (hertz.half_width(), hertz.approach(d0)?);
    let body = Body::plane_strain(steel, d0);
    let geometry = Geometry::Surfaces(
        Surface::Cylinder { radius: 10.0 },
        Surface::Cylinder { radius: 20.0 },
    );
    let study = Study::new([&body, &body], &geometry, Loading::load(500.0));
    let title = "Hertz cylinders (plane strain, zone 1.3)";
    let grids = hertz_grids(&[21, 41, 101, 201, 401], |n| {
        grid::hertz_line_family(b, n, 1.3)
    })?;
    study.print_against_hertz(title, grids, (approach, hertz.peak_pressure(), b))
}

fn punch() -> Result<(), Box<dyn Error>> {
    let aluminium = Material::new(70e9, 0.33)?;
    let (a, delta) = (0.01, 1e-5);
    let closed = FlatPunch::new(aluminium.plane_strain_modulus(), a)?;
    let (elastic, rigid) = (Body::uniform_patch(aluminium), Body::rigid());
    let geometry = Geometry::Surfaces(Surface::Plane, Surface::Plane);
    let study =
        Study::new([&rigid, &elastic], &geometry, Loading::approach(delta)).body_edges(true, true);
    let title = "Rigid flat punch (flat-punch.toml, approach 10 um)";
    let grids = Grids {
        column: "cells per radius",
        grids: [10, 20, 40]
            .map(|cells| {
                let spacing = a / cells as f64;
                (cells.to_string(), GridFamily::Disk { spacing, radius: a })
            })
            .to_vec(),
    };
    study.print(title, grids, |sol| {
        vec![
            (Quantity::Load, Some(sol.load / closed.load(delta) - 1.0)),
            (Quantity::MaxPressure, None),
        ]
    })
}

fn beam() -> Result<(), Box<dyn Error>> {
    let (length, load) = (8.9, 50_000.0);
    let hetenyi = HetenyiBeam::new(BeamOnFoundation {
        flexural_rigidity: 30e6 * 64.0 / 12.0,
        foundation_modulus: 1e7,
        length,
        load,
    })?;
    let beam = Body::beam(Beam {
        youngs_modulus: 30e6,
        second_moment: 64.0 / 12.0,
        loaded_point: 0.0,
    })?;
    let foundation = Body::winkler(1e7);
    let geometry = Geometry::Surfaces(Surface::Plane, Surface::Plane);
    let study =
        Study::new([&beam, &foundation], &geometry, Loading::load(load)).body_edges(true, false);
    let title = "Hetenyi's beam (Example 2's beam, L = 8.9 in, 50,000 lb)";
    let (start, end) = (-0.5 * length, 0.5 * length);
    let grids = Grids {
        column: "points",
        grids: [20, 40, 80, 160]
            .map(|n| (n.to_string(), GridFamily::Line { start, end, n }))
            .to_vec(),
    };
    study.print(title, grids, |sol| {
        vec![
            (
                Quantity::Approach,
                Some(sol.approach / hetenyi.centre_deflection() - 1.0),
            ),
            (
                Quantity::MaxPressure,
                Some(sol.max_pressure / hetenyi.load_intensity(0.0) - 1.0),
            ),
        ]
    })
}

fn roller() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(210e3, 0.3)?;
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 5.0 }, Surface::Plane);
    let hertz = HertzCylinders::new(combined_modulus(&steel, &steel), 5.0, 10_000.0 / 10.0)?;
    let b = hertz.half_width();
    let study =
        Study::new([&body, &body], &geometry, Loading::load(10_000.0)).body_edges(false, true);
    let title = "Flat roller (R = 5 mm, 10 mm long, 10 kN; square ends)";
    let grids = Grids {
        column: "nx x ny",
        grids: [(11, 40), (21, 80), (41, 160)]
            .map(|(nx, ny)| {
                let family = GridFamily::Rectangle {
                    half_x: 1.6 * b,
                    half_y: 5.0,
                    nx,
                    ny,
                };
                (format!("{nx} x {ny}"), family)
            })
            .to_vec(),
    };
    study.print(title, grids, |_| {
        vec![(Quantity::MaxPressure, None), (Quantity::Approach, None)]
    })
}

fn eccentric() -> Result<(), Box<dyn Error>> {
    let hertz = scenes::example1_hertz();
    let (r, a) = (hertz.radius, hertz.contact_radius());
    let (body, geometry) = scenes::example1_bodies();
    // The load 0.1 a off the apex along x: M_y = -P e; Hertz translated to
    // e, tilted by -e / R, its approach delta - e^2 / (2R).
    let e = 0.1 * a;
    let study = Study::new(
        [&body, &body],
        &geometry,
        Loading::load(100.0).with_moment_y(-100.0 * e),
    );
    let title = "Spheres loaded 0.1 a off the apex (Example 1, zone 1.4, tilts free)";
    let grids = hertz_grids(&[41, 81], |n| grid::hertz_disk_family(a, n, 1.4))?;
    let approach = hertz.approach() - e * e / (2.0 * r);
    study.print(title, grids, |sol| {
        vec![
            (Quantity::Approach, Some(sol.approach / approach - 1.0)),
            (
                Quantity::MaxPressure,
                Some(sol.max_pressure / hertz.peak_pressure() - 1.0),
            ),
            (Quantity::TiltY, Some(sol.tilt_y / (-e / r) - 1.0)),
        ]
    })
}

fn main() -> Result<(), Box<dyn Error>> {
    spheres()?;
    eccentric()?;
    cylinders()?;
    punch()?;
    beam()?;
    roller()?;
    Ok(())
}
