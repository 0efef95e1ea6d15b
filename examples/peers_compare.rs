//! elcon on the peers' discrete problems (docs/peers/), for the side by
//! side comparison in docs/performance.md.
//!
//! 1. The BEM peers' Hertz case (Tamaas, ContactMechanics): Love patches of
//!    side h = a/16 and a/32, the apex on a cell centre. Their domain is a
//!    square 4a wide, ours the disk r <= 1.3a: the contact and the discrete
//!    answer are the same (the errors agree to the digits printed).
//! 2. The dense QP peers' problem (Clarabel, OSQP, quadprog): the grid of
//!    1.3a / 24 in the disk r <= 1.3a, N = 1793, every method.
//!
//! Times are assembly of S plus the solve (certificate included), the best
//! of 5, in full (N unknowns) and folded by the problem's symmetry (one
//! unknown per orbit of the square grid's 8 reflections).
//!
//! Run: `cargo run --release --example peers_compare`

use std::time::Instant;

use elcon::analysis::{ContactProblem, Method, Options};
use elcon::influence::PointSet;
use elcon_fixtures::benchmark;

fn run(
    points: &PointSet,
    method: Method,
    fold: bool,
    repeat: usize,
) -> (f64, f64, f64, usize, f64) {
    let reference = benchmark::reference();
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..repeat {
        let t = Instant::now();
        let build = if fold {
            ContactProblem::symmetric
        } else {
            ContactProblem::new
        };
        let problem = benchmark::held(build, points.clone());
        let sol = problem.solve(method, &Options::default()).expect("solves");
        best = best.min(t.elapsed().as_secs_f64());
        let unknowns = problem
            .entries("the unknowns count")
            .expect("dense")
            .nrows();
        last = Some((sol, unknowns));
    }
    let (sol, unknowns) = last.expect("ran");
    (
        best,
        sol.approach / reference.approach() - 1.0,
        sol.max_pressure / reference.peak_pressure() - 1.0,
        unknowns,
        sol.certificate.worst(),
    )
}

fn main() {
    let a = benchmark::hertz_radius();
    println!("## BEM peers' case: Love patches, h = a/16 and a/32 (ours: disk r <= 1.3a)");
    println!(
        "| h/a | N | unknowns | method | assembly + solve s | err_delta | err_p0 | certificate |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for cells in [16.0, 32.0] {
        let points = PointSet::grid_disk(a / cells, 1.3 * a).expect("grid");
        for fold in [false, true] {
            let (t, ed, ep, unknowns, cert) = run(&points, Method::BlockPivoting, fold, 5);
            println!(
                "| 1/{cells} | {} | {unknowns} | block-pivoting{} | {t:.4} | {ed:+.2e} | {ep:+.2e} | {cert:.1e} |",
                points.len(),
                if fold { ", folded" } else { "" }
            );
        }
    }
    println!();
    println!("## Dense QP peers' case: grid 1.3a/24 in r <= 1.3a");
    println!("| N | unknowns | method | assembly + solve s | err_alpha_hertz | certificate |");
    println!("|---|---|---|---|---|---|");
    let points = PointSet::grid_disk(1.3 * a / 24.0, 1.3 * a).expect("grid");
    for fold in [false, true] {
        for method in Method::ALL {
            let (t, ed, _, unknowns, cert) = run(&points, method, fold, 5);
            println!(
                "| {} | {unknowns} | {method}{} | {t:.4} | {ed:+.3e} | {cert:.1e} |",
                points.len(),
                if fold { ", folded" } else { "" }
            );
        }
    }
}
