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

use elcon::analysis::discretization::{Discretization, Quantity};
use elcon::analysis::references::{BeamOnFoundation, FlatPunch, HertzCylinders, HetenyiBeam};
use elcon::analysis::{
    ContactProblem, ContactSolution, Geometry, GridFamily, Loading, Method, Options, Surface, grid,
};
use elcon::influence::{Beam, Body, Material, combined_modulus};
use elcon_fixtures::scenes;

/// Solves the problem of `bodies` and `geometry` under `loading` on
/// `family` (block pivoting, folded where symmetric) and estimates its
/// discretization error.
fn run(
    family: &GridFamily,
    bodies: [&Body; 2],
    geometry: &Geometry,
    loading: Loading,
    body_edges: (bool, bool),
) -> Result<(ContactSolution, Discretization), Box<dyn Error>> {
    let builder =
        ContactProblem::builder(family.points()?, bodies[0], bodies[1], geometry, loading)
            .method(Method::BlockPivoting)
            .body_edges(body_edges.0, body_edges.1);
    let problem = builder.clone().build()?;
    let options = Options::default();
    let solution = problem.solve(Method::BlockPivoting, &options)?;
    if !solution.certificate.holds() {
        return Err(format!("uncertified: {}", solution.certificate).into());
    }
    let d = builder.discretization(family, &solution, Method::BlockPivoting, &options)?;
    Ok((solution, d))
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
            e.verdict.name()
        );
    }
}

/// The true errors of a Hertz contact's approach, peak pressure and extent
/// against the closed form's `approach`, `peak` and `extent`.
fn against_hertz(
    sol: &ContactSolution,
    (approach, peak, extent): (f64, f64, f64),
) -> [(Quantity, Option<f64>); 3] {
    [
        (Quantity::Approach, Some(sol.approach / approach - 1.0)),
        (Quantity::MaxPressure, Some(sol.max_pressure / peak - 1.0)),
        (
            Quantity::ContactExtent,
            Some(sol.contact_extent / extent - 1.0),
        ),
    ]
}

fn header(title: &str, grid: &str) {
    println!("\n{title}\n");
    println!("| {grid} | N | quantity | true error | estimated | est/true | order | verdict |");
    println!("|---|---|---|---|---|---|---|---|");
}

fn spheres() -> Result<(), Box<dyn Error>> {
    let hertz = scenes::example1_hertz();
    let a = hertz.contact_radius();
    let (body, geometry) = scenes::example1_bodies();
    header("Hertz spheres (Example 1, zone 1.15)", "across");
    for across in [17, 21, 41, 81, 161] {
        let family = grid::hertz_disk_family(a, across, 1.15)?;
        let (sol, d) = run(
            &family,
            [&body, &body],
            &geometry,
            Loading::load(100.0),
            (false, false),
        )?;
        let truths = against_hertz(&sol, (hertz.approach(), hertz.peak_pressure(), a));
        rows(&across.to_string(), &sol, &d, &truths);
    }
    Ok(())
}

fn cylinders() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(210e3, 0.3)?;
    let d0 = 10.0;
    let hertz = HertzCylinders::new(combined_modulus(&steel, &steel), 1.0 / (0.1 + 0.05), 500.0)?;
    let b = hertz.half_width();
    let body = Body::plane_strain(steel, d0);
    let geometry = Geometry::Surfaces(
        Surface::Cylinder { radius: 10.0 },
        Surface::Cylinder { radius: 20.0 },
    );
    header("Hertz cylinders (plane strain, zone 1.3)", "across");
    for across in [21, 41, 101, 201, 401] {
        let family = grid::hertz_line_family(b, across, 1.3)?;
        let (sol, d) = run(
            &family,
            [&body, &body],
            &geometry,
            Loading::load(500.0),
            (false, false),
        )?;
        let truths = against_hertz(&sol, (hertz.approach(d0)?, hertz.peak_pressure(), b));
        rows(&across.to_string(), &sol, &d, &truths);
    }
    Ok(())
}

fn punch() -> Result<(), Box<dyn Error>> {
    let aluminium = Material::new(70e9, 0.33)?;
    let (a, delta) = (0.01, 1e-5);
    let closed = FlatPunch::new(aluminium.plane_strain_modulus(), a)?;
    let (elastic, rigid) = (Body::uniform_patch(aluminium), Body::rigid());
    let geometry = Geometry::Surfaces(Surface::Plane, Surface::Plane);
    header(
        "Rigid flat punch (flat-punch.toml, approach 10 um)",
        "cells per radius",
    );
    for cells in [10, 20, 40] {
        let family = GridFamily::Disk {
            spacing: a / cells as f64,
            radius: a,
        };
        let (sol, d) = run(
            &family,
            [&rigid, &elastic],
            &geometry,
            Loading::approach(delta),
            (true, true),
        )?;
        let truths = [
            (Quantity::Load, Some(sol.load / closed.load(delta) - 1.0)),
            (Quantity::MaxPressure, None),
        ];
        rows(&cells.to_string(), &sol, &d, &truths);
    }
    Ok(())
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
    header(
        "Hetenyi's beam (Example 2's beam, L = 8.9 in, 50,000 lb)",
        "points",
    );
    for n in [20, 40, 80, 160] {
        let family = GridFamily::Line {
            start: -0.5 * length,
            end: 0.5 * length,
            n,
        };
        let (sol, d) = run(
            &family,
            [&beam, &foundation],
            &geometry,
            Loading::load(load),
            (true, false),
        )?;
        let truths = [
            (
                Quantity::Approach,
                Some(sol.approach / hetenyi.centre_deflection() - 1.0),
            ),
            (
                Quantity::MaxPressure,
                Some(sol.max_pressure / hetenyi.load_intensity(0.0) - 1.0),
            ),
        ];
        rows(&n.to_string(), &sol, &d, &truths);
    }
    Ok(())
}

fn roller() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(210e3, 0.3)?;
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 5.0 }, Surface::Plane);
    let hertz = HertzCylinders::new(combined_modulus(&steel, &steel), 5.0, 10_000.0 / 10.0)?;
    let b = hertz.half_width();
    header(
        "Flat roller (R = 5 mm, 10 mm long, 10 kN; square ends)",
        "nx x ny",
    );
    for (nx, ny) in [(11, 40), (21, 80), (41, 160)] {
        let family = GridFamily::Rectangle {
            half_x: 1.6 * b,
            half_y: 5.0,
            nx,
            ny,
        };
        let (sol, d) = run(
            &family,
            [&body, &body],
            &geometry,
            Loading::load(10_000.0),
            (false, true),
        )?;
        let truths = [(Quantity::MaxPressure, None), (Quantity::Approach, None)];
        rows(&format!("{nx} x {ny}"), &sol, &d, &truths);
    }
    Ok(())
}

fn eccentric() -> Result<(), Box<dyn Error>> {
    let hertz = scenes::example1_hertz();
    let (r, a) = (hertz.radius, hertz.contact_radius());
    let (body, geometry) = scenes::example1_bodies();
    // The load 0.1 a off the apex along x: M_y = -P e; Hertz translated to
    // e, tilted by -e / R, its approach delta - e^2 / (2R).
    let e = 0.1 * a;
    let loading = Loading::load(100.0).with_moment_y(-100.0 * e);
    header(
        "Spheres loaded 0.1 a off the apex (Example 1, zone 1.4, tilts free)",
        "across",
    );
    for across in [41, 81] {
        let family = grid::hertz_disk_family(a, across, 1.4)?;
        let (sol, d) = run(&family, [&body, &body], &geometry, loading, (false, false))?;
        let approach = hertz.approach() - e * e / (2.0 * r);
        let truths = [
            (Quantity::Approach, Some(sol.approach / approach - 1.0)),
            (
                Quantity::MaxPressure,
                Some(sol.max_pressure / hertz.peak_pressure() - 1.0),
            ),
            (Quantity::TiltY, Some(sol.tilt_y / (-e / r) - 1.0)),
        ];
        rows(&across.to_string(), &sol, &d, &truths);
    }
    Ok(())
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
