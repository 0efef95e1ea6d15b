//! Conry & Seireg (1971), Example 1: two steel spheres pressed together,
//! checked against Hertz theory.
//!
//! Data as printed in the paper: steel (E = 30e6 psi, nu = 0.3), radii 1 in
//! and 10 in, load P = 100 lb. Units: inch, pound, psi.
//!
//! 1. The paper's model: Boussinesq point forces, a_kj = (1 - nu^2) /
//!    (pi E d_kj), on a square grid with 11 points across the Hertz contact
//!    diameter, candidate points out to 1.4 a; self-term = the centre
//!    deflection of the point's own cell under uniform pressure. Solved with
//!    the paper's restricted-entry simplex and with Lemke's method.
//! 2. Love's uniform pressure on square cells, 21, 41 and 81 points across
//!    the diameter (candidate disk 1.15 a), solved with block principal
//!    pivoting (21 across also with both tableau methods).
//!
//! For each: points, pivots, seconds, approach, peak pressure and contact
//! radius with their relative errors against Hertz. The last line is
//! `approach=<in> hertz=<in> rel_error=<fraction>` for the finest grid.
//!
//! Run: `cargo run --release --example conry_seireg_example1`

use elcon::analysis::references::{HertzSpheres, combined_radius};
use elcon::analysis::{
    AnalysisError, ContactProblem, ContactSolution, Geometry, Loading, Method, Options, Surface,
};
use elcon::influence::{Body, Material, PointSet, combined_modulus};

/// Young's modulus of steel, psi.
const E_STEEL: f64 = 30e6;
/// Poisson's ratio of steel.
const NU_STEEL: f64 = 0.3;
/// Sphere radii, in.
const R1: f64 = 1.0;
const R2: f64 = 10.0;
/// Normal load, lb.
const LOAD: f64 = 100.0;

fn main() -> Result<(), AnalysisError> {
    let steel = Material::new(E_STEEL, NU_STEEL)?;
    let hertz = HertzSpheres::new(
        combined_modulus(&steel, &steel),
        combined_radius(R1, R2),
        LOAD,
    )?;
    let a = hertz.contact_radius();
    println!(
        "Conry & Seireg (1971) Example 1: steel spheres R1 = {R1} in, R2 = {R2} in, P = {LOAD} lb"
    );
    println!(
        "Hertz: contact radius a = {a:.6e} in, approach = {:.6e} in, peak pressure = {:.6e} psi",
        hertz.approach(),
        hertz.peak_pressure()
    );
    println!("paper: approach 0.000281 in (its model) against 0.000283 in (Hertz)");
    println!();
    println!(
        "{:<26} {:>3} {:<18} {:>6} {:>6} {:>9} {:>12} {:>10} {:>12} {:>10} {:>11} {:>10}",
        "model",
        "n/d",
        "method",
        "points",
        "pivots",
        "seconds",
        "approach in",
        "err",
        "peak psi",
        "err",
        "radius in",
        "err"
    );
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: R1 },
        Surface::Sphere { radius: R2 },
    );
    let mut finest = None;
    let runs: [(&str, usize, f64, Body, &[Method]); 4] = [
        (
            "Boussinesq point forces",
            11,
            1.4,
            Body::point_force(steel),
            &[Method::RestrictedSimplex, Method::Lemke],
        ),
        (
            "Love uniform patches",
            21,
            1.15,
            Body::uniform_patch(steel),
            &[
                Method::RestrictedSimplex,
                Method::Lemke,
                Method::BlockPivoting,
            ],
        ),
        (
            "Love uniform patches",
            41,
            1.15,
            Body::uniform_patch(steel),
            &[Method::BlockPivoting],
        ),
        (
            "Love uniform patches",
            81,
            1.15,
            Body::uniform_patch(steel),
            &[Method::BlockPivoting],
        ),
    ];
    for (model, across, zone, body, methods) in runs {
        // `across` points span the Hertz diameter: spacing 2a / (across - 1).
        let spacing = 2.0 * a / (across - 1) as f64;
        let points = PointSet::grid_disk(spacing, zone * a)?;
        let problem = ContactProblem::new(points, &body, &body, &geometry, Loading::load(LOAD))?;
        for &method in methods {
            let sol = problem.solve(method, &Options::default())?;
            print_row(model, across, method, &problem, &sol, &hertz);
            for w in &sol.warnings {
                println!("    warning: {w}");
            }
            finest = Some(sol.approach);
        }
    }
    let approach = finest.expect("at least one run");
    println!();
    println!(
        "approach={approach:.6e} hertz={:.6e} rel_error={:.3e}",
        hertz.approach(),
        approach / hertz.approach() - 1.0
    );
    Ok(())
}

fn print_row(
    model: &str,
    across: usize,
    method: Method,
    problem: &ContactProblem,
    sol: &ContactSolution,
    hertz: &HertzSpheres,
) {
    let rel = |x: f64, r: f64| x / r - 1.0;
    println!(
        "{:<26} {:>3} {:<18} {:>6} {:>6} {:>9.4} {:>12.6e} {:>+10.2e} {:>12.6e} {:>+10.2e} {:>11.5e} {:>+10.2e}",
        model,
        across,
        method.name(),
        problem.points().len(),
        sol.statistics.pivots(),
        problem.assembly_seconds() + sol.solve_seconds,
        sol.approach,
        rel(sol.approach, hertz.approach()),
        sol.max_pressure,
        rel(sol.max_pressure, hertz.peak_pressure()),
        sol.contact_extent,
        rel(sol.contact_extent, hertz.contact_radius()),
    );
    assert!(
        sol.certificate.holds(),
        "every returned solution is certified"
    );
}
