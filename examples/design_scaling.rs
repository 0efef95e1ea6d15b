//! Design at scale: the paper's program against the case-decomposed
//! descent, on Example 2's beam (quadratic correction, one case, growing
//! grids) and on a crowned roller (free profile, growing numbers of load
//! and misalignment cases).
//!
//! Prints, per problem, each method's objective, its seconds and (for the
//! descent) its iterations and analyses, and the two objectives' relative
//! difference. The program is skipped where it would need more than
//! `--program-limit` points over all cases together (default 1200: its
//! tableau grows with their square).
//!
//! Run: `cargo run --release --example design_scaling -- [--study beam|roller|both] [--program-limit N]`

use std::error::Error;
use std::time::Instant;

use elcon::analysis::{ContactProblem, Loading};
use elcon::design::{Axis, Design, DesignMethod, Family, Solver, design};
use elcon_fixtures::design_cases;

/// Example 2's beam: steel, 8.9 in x 1 in x 4 in, on a Winkler foundation
/// of 1e7 lb/in/in, 50,000 lb at the middle, `per_half` points per half.
fn beam(per_half: usize) -> ContactProblem {
    design_cases::example2(2 * per_half, 0.0, Loading::load(5e4))
}

/// The roller of examples/misaligned_roller (steel, D = 10 mm, l = 10 mm,
/// 40 x 9 Love patches per load) under `loads` x `misalignments` cases
/// (N; rad, a prescribed rotation about x), with each case's aligned Hertz
/// peak as its reference intensity.
fn roller(loads: &[f64], misalignments: &[f64]) -> (Vec<ContactProblem>, Vec<f64>) {
    design_cases::misaligned_roller(loads, misalignments, (9, 40))
}

/// One design, timed.
fn run(
    cases: &[ContactProblem],
    axis: Axis,
    family: Family,
    method: DesignMethod,
    references: Option<Vec<f64>>,
) -> Result<(Design, f64), Box<dyn Error>> {
    let start = Instant::now();
    let d = design(
        cases,
        axis,
        family,
        &design_cases::options(method, references),
    )?;
    Ok((d, start.elapsed().as_secs_f64()))
}

fn describe(d: &Design, seconds: f64) -> String {
    match &d.solver {
        Solver::Program { statistics, .. } => format!(
            "{:.10e} {seconds:>8.3} s  {} pivots",
            d.objective,
            statistics.pivots()
        ),
        Solver::Descent {
            iterations,
            analyses,
            stop,
            ..
        } => format!(
            "{:.10e} {seconds:>8.3} s  {iterations} iterations, {analyses} analyses, {stop:?}",
            d.objective
        ),
    }
}

fn compare(
    label: &str,
    cases: &[ContactProblem],
    axis: Axis,
    family: Family,
    references: Option<Vec<f64>>,
    program_limit: usize,
) -> Result<(), Box<dyn Error>> {
    let points: usize = cases.iter().map(|c| c.points().len()).sum();
    let (descent, ds) = run(
        cases,
        axis,
        family,
        DesignMethod::Descent,
        references.clone(),
    )?;
    println!("{label:<28} descent  {}", describe(&descent, ds));
    if points <= program_limit {
        let (program, ps) = run(cases, axis, family, DesignMethod::Program, references)?;
        let relative = (descent.objective - program.objective) / program.objective;
        println!(
            "{label:<28} program  {}  (descent - program) / program = {relative:.2e}",
            describe(&program, ps)
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let (mut study, mut program_limit) = ("both".to_string(), 1200usize);
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match (flag.as_str(), it.next()) {
            ("--study", Some(s)) => study = s,
            ("--program-limit", Some(n)) => program_limit = n.parse()?,
            _ => return Err(format!("unknown option {flag} (--study, --program-limit)").into()),
        }
    }
    if study == "beam" || study == "both" {
        println!("Example 2's beam, quadratic correction: objective (lb/in), time");
        for per_half in [10, 40, 100, 200, 400] {
            let case = beam(per_half);
            let label = format!("{per_half} points per half");
            compare(
                &label,
                &[case],
                Axis::X,
                Family::Quadratic,
                None,
                program_limit,
            )?;
        }
    }
    if study == "roller" || study == "both" {
        println!("Roller, free profile: worst p_max / Hertz over the cases, time");
        let misalignments: Vec<f64> = (0..10).map(|i| i as f64 * 1e-4).collect();
        for (loads, angles) in [
            (&[5e3][..], &misalignments[..1]),
            (&[1e3, 5e3, 10e3][..], &misalignments[..1]),
            (&[5e3][..], &misalignments[..]),
            (&[1e3, 5e3, 10e3][..], &misalignments[..]),
        ] {
            let (cases, references) = roller(loads, angles);
            let label = format!("{} loads x {} misalignments", loads.len(), angles.len());
            compare(
                &label,
                &cases,
                Axis::Y,
                Family::Free,
                Some(references),
                program_limit,
            )?;
        }
    }
    Ok(())
}
