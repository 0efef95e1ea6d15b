//! The stresses below the surface against Hertz's closed forms
//! (docs/validation.md §5), with their discretization error against run
//! time: each grid solved (block pivoting up to 41 across, the matrix-free
//! conjugate gradient above), then each body's field
//! (`elcon_analysis::subsurface`) and its maxima.
//!
//! - Hertz spheres, Conry & Seireg's Example 1 (steel, R = 1 and 10 in,
//!   100 lb, Love patches, zone 1.15 radii): the largest shear (Tresca)
//!   against 0.3100 p0 at 0.4803 a (nu = 0.3, the axis' closed form's own
//!   maximum), the largest von Mises stress against the axis' maximum, and
//!   the von Mises stress along the axis (its largest error over the
//!   profile's depths, relative to p0);
//! - Hertz cylinders in plane strain (steel, R = 5 mm on a plane, 1 kN/mm,
//!   zone 1.5): the largest shear against 0.3005 p0 at 0.7861 b, the
//!   orthogonal shear against 0.2500 p0 at z = 0.5 b, x = 0.866 b
//!   (McEwen), and the whole section against McEwen's field (largest
//!   error over it, relative to p0).
//!
//! Seconds are the field's (both maxima searches, section and profile),
//! beside the contact solve's, on the pool's threads (all cores).
//!
//! Run: `cargo run --release --example subsurface_validation`

use std::error::Error;
use std::time::Instant;

use elcon::analysis::references::{HertzCylinders, HertzSpheres};
use elcon::analysis::subsurface::reference::{hertz_line, hertz_point_axis};
use elcon::analysis::subsurface::{BodyStresses, Subsurface, SubsurfaceOptions};
use elcon::analysis::{ContactProblem, Geometry, Loading, Method, Options, Surface, grid};
use elcon::influence::{Body, Material, Stress, combined_modulus};

/// The largest of `f` over depths up to `span`, and where (5e-5 steps).
fn largest(f: impl Fn(f64) -> f64, span: f64) -> (f64, f64) {
    (1..=(span / 5e-5) as usize)
        .map(|i| (f(i as f64 * 5e-5), i as f64 * 5e-5))
        .fold((0.0, 0.0), |b, c| if c.0 > b.0 { c } else { b })
}

/// Solves `problem` (block pivoting when small, CG above) and returns the
/// field of `body` below it with the seconds of the solve and the field.
fn field(
    problem: &ContactProblem,
    body: &Body,
) -> Result<(BodyStresses, f64, f64), Box<dyn Error>> {
    let method = if problem.points().len() <= 5000 {
        Method::BlockPivoting
    } else {
        Method::ConjugateGradient
    };
    let start = Instant::now();
    let solution = problem.solve(method, &Options::default())?;
    let solve = start.elapsed().as_secs_f64();
    if !solution.certificate.holds() {
        return Err(format!("uncertified: {}", solution.certificate).into());
    }
    let start = Instant::now();
    let s = Subsurface::of(
        problem.points(),
        &solution,
        body,
        &SubsurfaceOptions::default(),
    );
    let seconds = start.elapsed().as_secs_f64();
    match s {
        Subsurface::Stresses(b) => Ok((*b, solve, seconds)),
        Subsurface::NotApplicable(why) => Err(why.into()),
    }
}

fn spheres() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(30e6, 0.3)?;
    let hertz = HertzSpheres::new(combined_modulus(&steel, &steel), 1.0 / 1.1, 100.0)?;
    let (a, p0) = (hertz.contact_radius(), hertz.peak_pressure());
    let (tau, tau_z) = largest(|z| hertz_point_axis(z, 1.0, 0.3).tresca(), 2.0);
    let (vm, vm_z) = largest(|z| hertz_point_axis(z, 1.0, 0.3).von_mises(), 2.0);
    println!(
        "\nHertz spheres (Example 1, zone 1.15): tau_max {tau:.4} p0 at {tau_z:.4} a, von Mises {vm:.4} p0 at {vm_z:.4} a\n"
    );
    println!(
        "| across | N | Tresca error | its depth error (a) | von Mises error | axis profile error (p0) | solve s | field s |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    );
    for across in [21, 41, 81, 161, 321] {
        let points = grid::hertz_disk(a, across, 1.15)?;
        let n = points.len();
        let problem =
            ContactProblem::builder(points, &body, &body, &geometry, Loading::load(100.0))
                .build()?;
        let (s, solve, seconds) = field(&problem, &body)?;
        let profile = s
            .profile
            .depths
            .iter()
            .zip(&s.profile.stresses)
            .map(|(z, st)| {
                (st.von_mises() / p0 - hertz_point_axis(*z / a, 1.0, 0.3).von_mises()).abs()
            })
            .fold(0.0f64, f64::max);
        println!(
            "| {across} | {n} | {:+.2e} | {:+.3} | {:+.2e} | {profile:.2e} | {solve:.3} | {seconds:.3} |",
            s.tresca.value / p0 / tau - 1.0,
            s.tresca.z / a - tau_z,
            s.von_mises.value / p0 / vm - 1.0,
        );
    }
    Ok(())
}

fn cylinders() -> Result<(), Box<dyn Error>> {
    let steel = Material::new(210e3, 0.3)?;
    let hertz = HertzCylinders::new(combined_modulus(&steel, &steel), 5.0, 1000.0)?;
    let (b, p0) = (hertz.half_width(), hertz.peak_pressure());
    let (tau, tau_z) = largest(|z| hertz_line(0.0, z, 1.0, 0.3).tresca(), 2.0);
    println!(
        "\nHertz cylinders (plane strain, zone 1.5): tau_max {tau:.4} p0 at {tau_z:.4} b; tau_xz 0.2500 p0 at 0.5 b, x = 0.866 b\n"
    );
    println!(
        "| across | Tresca error | its depth error (b) | tau_xz error | its depth, x error (b) | section error (p0) | solve s | field s |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let body = Body::plane_strain(steel, 100.0);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 5.0 }, Surface::Plane);
    for across in [21, 41, 81, 161, 321] {
        let points = grid::hertz_line(b, across, 1.5)?;
        let problem =
            ContactProblem::builder(points, &body, &body, &geometry, Loading::load(1000.0))
                .build()?;
        let (s, solve, seconds) = field(&problem, &body)?;
        let rows = s.section.depths.len();
        let section = (0..s.section.xs.len() * rows)
            .map(|k| {
                let (x, z) = (s.section.xs[k / rows], s.section.depths[k % rows]);
                let got: &Stress = &s.section.stresses[k];
                let exact = hertz_line(x / b, z / b, 1.0, 0.3);
                [(got.xx, exact.xx), (got.zz, exact.zz), (got.xz, exact.xz)]
                    .iter()
                    .map(|(g, e)| (g / p0 - e).abs())
                    .fold(0.0f64, f64::max)
            })
            .fold(0.0f64, f64::max);
        println!(
            "| {across} | {:+.2e} | {:+.3} | {:+.2e} | {:+.3}, {:+.3} | {section:.2e} | {solve:.3} | {seconds:.3} |",
            s.tresca.value / p0 / tau - 1.0,
            s.tresca.z / b - tau_z,
            s.orthogonal_xz.value.abs() / p0 / 0.25 - 1.0,
            s.orthogonal_xz.z / b - 0.5,
            s.orthogonal_xz.x.abs() / b - 0.866,
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    spheres()?;
    cylinders()
}
