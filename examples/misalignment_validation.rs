//! The misalignment rows of docs/validation.md: error against run time for
//! the closed forms with a moment or an eccentric load.
//!
//! - a rigid flat punch (a = 10 mm, steel, 10 kN) under half its lift-off
//!   moment (M_y = -P a / 6): the tilt against `3 m / (4 E* a^3)` and the
//!   approach against `P / (2 a E*)`, 10 to 40 cells per radius;
//! - spheres (R = 10 and 100 mm, steel, 100 N) with the load 4 cells off
//!   the apex: the tilt against `-e / R`, the peak against the aligned
//!   grid's (the translated discrete problem) and against Hertz;
//! - Example 2's beam section and foundation, L = 6 in, 50,000 lb at 0.5 in
//!   off centre (inside the kern of the nearly rigid beam), the beam free
//!   (bonded everywhere: the finite-beam closed form): the approach at the
//!   load, the tilt and the load intensity;
//! - the same section at L = 12 in, the load 3 in off centre: the far end
//!   lifts off a tensionless foundation; no closed form, so the change of
//!   the peak and of the contact length from the grid before.
//!
//! Seconds are the whole solve (block pivoting), assembly included, one run.
//!
//! Run: `cargo run --release --example misalignment_validation`

use std::error::Error;
use std::time::Instant;

use elcon::analysis::references::{BeamOnFoundation, FiniteBeam, FlatPunch, HertzSpheres};
use elcon::analysis::{
    ContactProblem, ContactSolution, Geometry, Loading, Method, Options, Surface,
};
use elcon::influence::{Beam, Body, Material, PointSet, combined_modulus};
use elcon_fixtures::scenes;

fn solved(problem: &ContactProblem) -> Result<ContactSolution, Box<dyn Error>> {
    let sol = problem.solve(Method::BlockPivoting, &Options::default())?;
    if !sol.certificate.holds() {
        return Err(format!("uncertified: {}", sol.certificate).into());
    }
    Ok(sol)
}

fn punch() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(210e9, 0.3)?;
    let (a, load) = (0.01, 1e4);
    let closed = FlatPunch::new(steel.plane_strain_modulus(), a)?;
    let m = 0.5 * closed.lift_off_moment(load);
    println!("\nFlat punch under M = P a / 6 (block pivoting)\n");
    println!("| cells per radius | N | seconds | tilt | approach | certificate |");
    println!("|---|---|---|---|---|---|");
    for cells in [10.0, 20.0, 40.0] {
        let t = Instant::now();
        // The shared punch (pressed by the approach the load gives), under
        // the load and the moment instead.
        let (pressed, _) = scenes::flat_punch(steel, a, cells, closed.approach(load));
        let problem = pressed.with_loading(Loading::load(load).with_moment_y(-m))?;
        let n = problem.points().len();
        let sol = solved(&problem)?;
        let seconds = t.elapsed().as_secs_f64();
        println!(
            "| {cells} | {n} | {seconds:.3} | {:+.2e} | {:+.2e} | {:.1e} |",
            sol.tilt_y / -closed.tilt(m) - 1.0,
            sol.approach / closed.approach(load) - 1.0,
            sol.certificate.worst()
        );
    }
    Ok(())
}

fn spheres() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(210e9, 0.3)?;
    let (r1, r2, load) = (0.01, 0.1, 100.0);
    let hertz = HertzSpheres::new(
        combined_modulus(&steel, &steel),
        1.0 / (1.0 / r1 + 1.0 / r2),
        load,
    )?;
    let a = hertz.contact_radius();
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: r1 },
        Surface::Sphere { radius: r2 },
    );
    let body = Body::uniform_patch(steel);
    println!("\nSpheres, the load 4 cells off the apex (block pivoting)\n");
    println!(
        "| cells per radius | N | seconds | tilt vs -e/R | peak vs aligned | peak vs Hertz | certificate |"
    );
    println!("|---|---|---|---|---|---|---|");
    for cells in [10.0, 20.0] {
        let h = a / cells;
        let e = 4.0 * h;
        let problem = |loading: Loading| {
            ContactProblem::new(
                PointSet::grid_disk(h, 1.4 * a + e)?,
                &body,
                &body,
                &geometry,
                loading,
            )
        };
        let aligned = solved(&problem(Loading::load(load))?)?;
        let t = Instant::now();
        let eccentric = problem(Loading::load(load).with_moment_y(-load * e))?;
        let sol = solved(&eccentric)?;
        let seconds = t.elapsed().as_secs_f64();
        println!(
            "| {cells} | {} | {seconds:.3} | {:+.1e} | {:+.1e} | {:+.2e} | {:.1e} |",
            eccentric.points().len(),
            sol.tilt_y / (-e / hertz.radius) - 1.0,
            sol.max_pressure / aligned.max_pressure - 1.0,
            sol.max_pressure / hertz.peak_pressure() - 1.0,
            sol.certificate.worst()
        );
    }
    Ok(())
}

/// Example 2's section and foundation, inch and pound.
fn beam(
    per_half: usize,
    length: f64,
    e: f64,
) -> Result<(ContactProblem, ContactSolution, f64), Box<dyn Error>> {
    let t = Instant::now();
    let points = PointSet::line(-0.5 * length, 0.5 * length, 2 * per_half)?;
    let n = points.len();
    let problem = ContactProblem::new(
        points,
        &Body::beam(Beam {
            youngs_modulus: 30e6,
            second_moment: 64.0 / 12.0,
            loaded_point: e,
        })?,
        &Body::winkler(1e7),
        &Geometry::Separation(vec![0.0; n]),
        Loading::load(5e4),
    )?;
    let sol = solved(&problem)?;
    Ok((problem, sol, t.elapsed().as_secs_f64()))
}

fn beams() -> Result<(), Box<dyn Error>> {
    let (length, e) = (6.0, 0.5);
    let exact = FiniteBeam::new(
        BeamOnFoundation {
            flexural_rigidity: 30e6 * 64.0 / 12.0,
            foundation_modulus: 1e7,
            length,
            load: 5e4,
        },
        e,
    )?;
    let peak = (0..=600)
        .map(|i| exact.load_intensity(-3.0 + 6.0 * i as f64 / 600.0))
        .fold(0.0, f64::max);
    println!("\nFree beam, L = 6 in, load 0.5 in off centre, bonded (block pivoting)\n");
    println!(
        "| points per half | N | seconds | approach | tilt | intensity (max, over the peak) | certificate |"
    );
    println!("|---|---|---|---|---|---|---|");
    for per_half in [10, 20, 40, 80] {
        let (problem, sol, seconds) = beam(per_half, length, e)?;
        let points = problem.points();
        let intensity = (0..points.len())
            .map(|k| (sol.pressures[k] - exact.load_intensity(points.x(k))).abs() / peak)
            .fold(0.0, f64::max);
        println!(
            "| {per_half} | {} | {seconds:.4} | {:+.2e} | {:+.2e} | {intensity:.2e} | {:.1e} |",
            points.len(),
            sol.approach / exact.deflection(e) - 1.0,
            sol.tilt_y / -exact.slope(e) - 1.0,
            sol.certificate.worst()
        );
    }
    println!(
        "\nFree beam, L = 12 in, load 3 in off centre, tensionless: the far end lifts (block pivoting)\n"
    );
    println!(
        "| points per half | N | seconds | points in contact | peak (lb/in) | change | contact length (in) | change |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut last: Option<(f64, f64)> = None;
    for per_half in [20, 40, 80, 160] {
        let (problem, sol, seconds) = beam(per_half, 12.0, 3.0)?;
        let (peak, extent) = (sol.max_pressure, sol.contact_measure);
        let change = |now: f64, before: Option<f64>| {
            before.map_or("-".to_string(), |b| format!("{:+.1e}", now / b - 1.0))
        };
        println!(
            "| {per_half} | {} | {seconds:.4} | {} | {peak:.1} | {} | {extent:.4} | {} |",
            problem.points().len(),
            sol.contact.len(),
            change(peak, last.map(|l| l.0)),
            change(extent, last.map(|l| l.1)),
        );
        last = Some((peak, extent));
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    punch()?;
    spheres()?;
    beams()?;
    Ok(())
}
