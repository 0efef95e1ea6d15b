//! Conry & Seireg (1971), Example 2: the initial separation that makes the
//! load distribution of a steel beam on an elastic foundation as uniform as
//! possible.
//!
//! Data as printed: beam length 8.9 in, width 1.0 in, depth 4.0 in, steel
//! (E = 30e6 psi), foundation modulus k = 1e7 lb/in per in, tensionless (a
//! point may lift off). The load is not legible in the seed: a central
//! concentrated load P, 50,000 lb unless `--load` says otherwise. The beam
//! is referenced at its loaded point with its rotation there held (each half
//! a cantilever from the centre), 40 points per half unless `--per-half`.
//! Units: inch, pound; load intensities in lb/in.
//!
//! Prints the load intensity with no separation, with the optimal quadratic
//! separation (the paper's design: minimize p_max over a, b, c) and with the
//! separation for a uniform pressure (the seed's Fig. 6 comparison); p_max
//! of each and its ratio to P/L; the optimal (a, b, c); writes the three
//! distributions and separations as CSV under `--out` (default
//! out/example2). The last line is
//! `pmax_none=<lb/in> pmax_quadratic=<lb/in> ratio=<pmax_quadratic/pmax_none>`.
//!
//! Run: `cargo run --release --example conry_seireg_example2 -- [--load P] [--per-half N] [--out DIR]`

mod common;

use std::error::Error;
use std::fs;
use std::path::{Path, PathBuf};

use elcon::analysis::{ContactProblem, Geometry, Loading, Method, Options};
use elcon::design::{
    Axis, Design, DesignOptions, Evaluation, Family, Profile, design, evaluate, fit_profile,
    uniform_target,
};
use elcon::influence::{Beam, Body, PointSet};

const LENGTH: f64 = 8.9;
const WIDTH: f64 = 1.0;
const DEPTH: f64 = 4.0;
const E_STEEL: f64 = 30e6;
const FOUNDATION: f64 = 1e7;

struct Args {
    load: f64,
    per_half: usize,
    out: PathBuf,
}

fn args() -> Result<Args, Box<dyn Error>> {
    let mut a = Args {
        load: 50_000.0,
        per_half: 40,
        out: PathBuf::from("out/example2"),
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let value = it.next().ok_or(format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--load" => a.load = value.parse().map_err(|e| format!("--load {value}: {e}"))?,
            "--per-half" => {
                a.per_half = value
                    .parse()
                    .map_err(|e| format!("--per-half {value}: {e}"))?
            }
            "--out" => a.out = PathBuf::from(value),
            other => {
                return Err(format!("unknown option {other} (--load, --per-half, --out)").into());
            }
        }
    }
    if !(a.load.is_finite() && a.load > 0.0) {
        return Err(format!("--load must be finite and > 0 (lb), got {}", a.load).into());
    }
    if a.per_half < 2 {
        return Err("--per-half must be at least 2".into());
    }
    Ok(a)
}

fn main() -> Result<(), Box<dyn Error>> {
    let a = args()?;
    let n = 2 * a.per_half;
    let second_moment = WIDTH * DEPTH.powi(3) / 12.0;
    let points = PointSet::line(-0.5 * LENGTH, 0.5 * LENGTH, n)?;
    let case = ContactProblem::new(
        points,
        &Body::beam(Beam {
            youngs_modulus: E_STEEL,
            second_moment,
            loaded_point: 0.0,
        })?,
        &Body::winkler(FOUNDATION),
        &Geometry::Separation(vec![0.0; n]),
        Loading::load(a.load),
    )?;
    let mean = a.load / LENGTH;
    println!("Conry & Seireg (1971) Example 2: beam on an elastic foundation (inch, pound)");
    println!(
        "L = {LENGTH} in, w = {WIDTH} in, d = {DEPTH} in, E = {E_STEEL:e} psi, I = {second_moment:.4} in^4, \
         k = {FOUNDATION:e} lb/in/in, P = {} lb central, {n} points ({} per half); P/L = {mean:.2} lb/in",
        a.load, a.per_half
    );
    let separations = Separations::of(&case)?;
    separations.print_distributions(&case);
    separations.print_summary(mean, n);
    fs::create_dir_all(&a.out)?;
    separations.write_csv(&case, &a.out)?;
    println!(
        "wrote none.csv, quadratic.csv, uniform.csv under {}",
        a.out.display()
    );
    let (none, quadratic) = (&separations.none, &separations.quadratic);
    println!(
        "pmax_none={:.6e} pmax_quadratic={:.6e} ratio={:.6}",
        none.worst,
        quadratic.max_intensity,
        quadratic.max_intensity / none.worst
    );
    Ok(())
}

/// The beam with each separation of the comparison.
struct Separations {
    /// No separation.
    none: Evaluation,
    /// The paper's design: the optimal quadratic.
    quadratic: Design,
    /// The separation for a uniform pressure.
    uniform: Evaluation,
    /// The paper's curve-fitting alternative: the uniform-pressure
    /// separation fitted by a quadratic, without regard to the resulting
    /// loads.
    fitted: Evaluation,
}

impl Separations {
    /// Each separation on `case`, designed or fitted and analysed.
    fn of(case: &ContactProblem) -> Result<Separations, Box<dyn Error>> {
        let cases = [case.clone()];
        let xs = case.points().xs().to_vec();
        let analyse = |profile: &Profile| {
            evaluate(
                &cases,
                Axis::X,
                profile,
                Method::BlockPivoting,
                &Options::default(),
            )
        };
        let none = analyse(&Profile::none())?;
        let quadratic = design(
            &cases,
            Axis::X,
            Family::Quadratic,
            &DesignOptions::default(),
        )?;
        let target = uniform_target(case)?;
        let uniform = analyse(&Profile::Free {
            positions: xs.clone(),
            drops: target.correction.clone(),
        })?;
        let fitted = analyse(&fit_profile(Family::Quadratic, &xs, &target.correction)?)?;
        Ok(Separations {
            none,
            quadratic,
            uniform,
            fitted,
        })
    }

    /// Prints the load intensity and the separation along the beam.
    fn print_distributions(&self, case: &ContactProblem) {
        let xs = case.points().xs();
        let (none, quadratic, uniform) = (&self.none, &self.quadratic, &self.uniform);
        println!();
        println!(
            "{:>8} {:>13} {:>13} {:>13} {:>13} {:>13}",
            "x in", "p none", "p quadratic", "p uniform", "y quadratic", "y uniform"
        );
        println!(
            "{:>8} {:>13} {:>13} {:>13} {:>13} {:>13}",
            "", "lb/in", "lb/in", "lb/in", "in", "in"
        );
        for k in 0..xs.len() {
            println!(
                "{:>8.4} {:>13.2} {:>13.2} {:>13.2} {:>13.4e} {:>13.4e}",
                xs[k],
                none.solutions[0].pressures[k],
                quadratic.evaluation.solutions[0].pressures[k],
                uniform.solutions[0].pressures[k],
                quadratic.evaluation.corrections[0][k],
                uniform.corrections[0][k],
            );
        }
    }

    /// Prints p_max of each separation against the mean `mean` on `n`
    /// points, the optimal quadratic and the design's starts.
    fn print_summary(&self, mean: f64, n: usize) {
        let rows = [
            ("no separation", &self.none),
            ("optimal quadratic", &self.quadratic.evaluation),
            ("uniform-pressure separation", &self.uniform),
            ("quadratic fit of the uniform", &self.fitted),
        ];
        println!();
        for (name, e) in rows {
            let s = &e.solutions[0];
            println!(
                "{name:<28} p_max = {:>10.2} lb/in   p_max/(P/L) = {:.4}   points in contact {:>3}/{n}   approach {:.4e} in   certificate {:.1e}",
                e.worst,
                e.worst / mean,
                s.contact.len(),
                s.approach,
                s.certificate.worst()
            );
        }
        if let Profile::Quadratic { a: qa, b, c } = self.quadratic.profile {
            println!(
                "optimal quadratic y = a x^2 + b x + c: a = {qa:.6e} 1/in, b = {b:.3e}, c = {c:.6e} in"
            );
        }
        for s in &self.quadratic.starts {
            println!(
                "  design start '{}': {} ({} pivots)",
                s.label,
                match &s.result {
                    Ok(p) => format!("p_max {p:.4} lb/in"),
                    Err(e) => format!("failed: {e}"),
                },
                s.pivots
            );
        }
    }

    /// Writes the distributions and separations without, with the optimal
    /// quadratic and with the uniform-pressure separation as CSV under `out`.
    fn write_csv(&self, case: &ContactProblem, out: &Path) -> Result<(), Box<dyn Error>> {
        let xs = case.points().xs();
        for (file, e) in [
            ("none.csv", &self.none),
            ("quadratic.csv", &self.quadratic.evaluation),
            ("uniform.csv", &self.uniform),
        ] {
            let s = &e.solutions[0];
            let mut csv = String::from(
                "x_in,length_in,force_lb,load_intensity_lb_per_in,gap_in,separation_in\n",
            );
            for k in 0..xs.len() {
                csv.push_str(&format!(
                    "{},{},{},{},{},{}\n",
                    xs[k],
                    case.points().measure(k),
                    s.forces[k],
                    s.pressures[k],
                    s.gaps[k],
                    e.corrections[0][k]
                ));
            }
            common::write_whole(&out.join(file), &csv)?;
        }
        Ok(())
    }
}
