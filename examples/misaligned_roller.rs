//! A misaligned cylindrical roller: a crown designed for a range of loads
//! and misalignments, carried to a grid it holds on, against the standard
//! crowns tuned over the same cases.
//!
//! Steel roller (E = 210 GPa, nu = 0.3), diameter 10 mm, effective length
//! 10 mm, on a flat steel raceway; Love patches on a rectangle grid with
//! the roller's axis along y, each load's grid 9 x 40 cells across 3.2 of
//! its Hertz half-widths and along the roller (the scene's grid; finer
//! grids are this one at 2, 3, 4, ... times the cells). Units: millimetre,
//! newton, megapascal.
//!
//! The 33 design cases: 1, 5 and 10 kN, each at every misalignment from 0
//! to 1 mrad in steps of 0.1 mrad (a prescribed rotation of the roller
//! about x: 1 mrad is about 3.4 minutes of arc, the order cylindrical
//! roller bearings are rated to tolerate); the objective is the worst
//! p_max / p0 over them, p0 each load's aligned Hertz line-contact peak
//! `2 P' / (pi b)`.
//!
//! Profiles (drops along y, added to the cylinder's separation):
//! - uncrowned: a straight roller (edge peaks at its ends);
//! - circular: a circular crown, its radius and a slope (a pre-tilt) tuned
//!   over the cases;
//! - Johns-Gohar: the logarithmic crown, its design load and a slope tuned;
//! - Fujiwara-Kawase: the three-parameter logarithmic crown (load
//!   coefficient K1, crowned share K2, end drop z_m) and a slope, tuned;
//! - designed: the free profile (a natural cubic spline through the 40
//!   stations of the scene's grid) of least worst p_max / p0, designed by
//!   the case-decomposed descent over grids of growing fineness until it
//!   holds on the next finer grid (`DesignRequest::run_converged`), the
//!   roller's ends kept out of contact.
//!
//! The crowns are tuned on the scene's grid (a coordinate search, golden
//! sections over each parameter in turn), then polished on the design's
//! own grid, where every profile is compared; each is also evaluated on
//! the design's verification grid (the next finer), so the table says
//! which profiles hold there.
//!
//! Prints the design's grids, the comparison table (worst p_max / p0 over
//! the 33 cases on the design grid and on the verification grid; the
//! largest von Mises stress below the surface over the cases on the design
//! grid, its depth and the case it is in; and each profile's tuned
//! parameters), then p_max at 10 kN against misalignment
//! for every profile on the design grid, then the designed crown read
//! straight between the rows of a table of it (its values at the design
//! grid's stations, and profile.csv's samples) on grids three and six
//! times finer than the design's; writes that table as CSV and a
//! plot of it under `--out` (default out/misaligned_roller). Its last line
//! is `misalignment=<rad> pmax_none=<MPa> pmax_log=<MPa>
//! pmax_designed=<MPa> grid=<nx>x<ny> verified=<p/p0>` at 1 mrad and 10 kN
//! (log: the tuned Fujiwara-Kawase crown, the strongest standard profile;
//! verified: the designed crown's worst p_max / p0 on the verification
//! grid).
//!
//! Run: `cargo run --release --example misaligned_roller -- [--out DIR]`

mod common;

use std::error::Error;
use std::fs;
use std::path::Path;
use std::time::Instant;

use elcon::analysis::subsurface::{Peak, Subsurface, SubsurfaceOptions};
use elcon::analysis::{ContactProblem, Loading, Options, Storage};
use elcon::design::{
    Analysis, Axis, Converged, DesignError, DesignFamily, DesignRequest, Evaluation, Family,
    GridSequence, LogCrown, LogEnd, Objective, Profile, Sampling, axial_stations, evaluate,
};
use elcon::influence::combined_modulus;
use elcon_fixtures::design_cases::{self, ROLLER_LENGTH, ROLLER_RADIUS};
use plotters::prelude::*;

/// The loads the crown is designed for (N); the table's load is the last.
const LOADS: [f64; 3] = [1e3, 5e3, 10e3];
const WIDTH_CELLS: f64 = 9.0;
const AXIAL_CELLS: f64 = 40.0;
/// Misalignment steps, 0.1 mrad each (an angle is `i / STEPS_PER_RAD`,
/// exact to the last digit), up to LARGEST = 1 mrad.
const STEPS: usize = 10;
const STEPS_PER_RAD: f64 = 1e4;
const LARGEST: f64 = STEPS as f64 / STEPS_PER_RAD;
/// Golden-section steps of a parameter's search on the scene's grid, and
/// of its polish on the design's.
const TUNE_STEPS: usize = 12;
const POLISH_STEPS: usize = 4;

/// The roller's load cases at one grid, each load's S shared by its
/// misalignments.
struct Roller {
    /// Each load's aligned problem on the grid.
    bases: Vec<ContactProblem>,
    /// Each case's aligned Hertz peak p0, load by load.
    references: Vec<f64>,
    /// The grid's cells across and along.
    cells: (usize, usize),
}

fn angles() -> Vec<f64> {
    (0..=STEPS).map(|i| i as f64 / STEPS_PER_RAD).collect()
}

impl Roller {
    /// The cases on the scene's grid refined `fineness` times, S held as
    /// elcon-analysis decides (matrix-free above 2000 points).
    fn new(fineness: f64) -> Result<Self, Box<dyn Error>> {
        let cells = (
            (WIDTH_CELLS * fineness).round() as usize,
            (AXIAL_CELLS * fineness).round() as usize,
        );
        let (mut bases, mut references) = (Vec::new(), Vec::new());
        for load in LOADS {
            let (base, hertz) = design_cases::aligned_roller(load, cells, Storage::Auto)?;
            bases.push(base);
            references.extend(std::iter::repeat_n(hertz.peak_pressure(), STEPS + 1));
        }
        Ok(Self {
            bases,
            references,
            cells,
        })
    }

    /// Every case, each misalignment less `slope` (a profile with the line
    /// `slope y` added is the roller pre-tilted by `-slope`).
    fn cases(&self, slope: f64) -> Result<Vec<ContactProblem>, DesignError> {
        let mut cases = Vec::new();
        for base in &self.bases {
            let load = base.loading().load_value().unwrap_or(0.0);
            for angle in angles() {
                let loading = Loading::load(load).with_tilt_x(angle - slope);
                cases.push(
                    base.with_loading(loading)
                        .map_err(|source| DesignError::Analysis {
                            stage: format!("{load} N at {angle} rad"),
                            source,
                        })?,
                );
            }
        }
        Ok(cases)
    }

    /// Every case of `profile` (with the line `slope y`), and its
    /// certified analysis by the cases' default method.
    fn evaluated(
        &self,
        profile: &Profile,
        slope: f64,
    ) -> Result<(Vec<ContactProblem>, Evaluation), Box<dyn Error>> {
        let cases = self.cases(slope)?;
        let method = cases[0].default_method();
        let e = evaluate(
            &cases,
            Axis::Y,
            profile,
            &Analysis::new(method, &Options::default()),
        )?;
        Ok((cases, e))
    }

    /// The worst p_max / p0 of `profile` (with the line `slope y`) over
    /// the cases, and each case's p_max.
    fn worst(&self, profile: &Profile, slope: f64) -> Result<(f64, Vec<f64>), Box<dyn Error>> {
        let (_, e) = self.evaluated(profile, slope)?;
        Ok((e.relative_worst(&self.references), e.max_intensities))
    }

    /// The largest von Mises stress below the surface over the cases of
    /// `profile` (with the line `slope y`), where it is, and at which load
    /// and misalignment: roller and raceway alike (the same steel).
    fn von_mises(&self, profile: &Profile, slope: f64) -> Result<(Peak, f64, f64), Box<dyn Error>> {
        let (cases, e) = self.evaluated(profile, slope)?;
        let (body, _) = design_cases::roller_bodies();
        let mut worst = (
            Peak {
                value: 0.0,
                x: 0.0,
                y: 0.0,
                z: 0.0,
            },
            0.0,
            0.0,
        );
        for (l, (case, solution)) in cases.iter().zip(&e.solutions).enumerate() {
            let options = SubsurfaceOptions::default();
            if let Subsurface::Stresses(s) =
                Subsurface::of(case.points(), solution, &body, &options)
                && s.von_mises.value > worst.0.value
            {
                let angle = angles()[l % (STEPS + 1)];
                worst = (s.von_mises, LOADS[l / (STEPS + 1)], angle);
            }
        }
        Ok(worst)
    }
}

/// A crown tuned over the cases: its profile from its parameters, the
/// search's bracket of each (log-spaced where positive), the slope last.
struct Crown {
    name: &'static str,
    make: fn(&[f64]) -> Profile,
    /// `(low, high, log)` of each parameter.
    bracket: Vec<(f64, f64, bool)>,
    /// Where the search starts.
    start: Vec<f64>,
}

fn log_crown(design_load: f64, flat_length: f64, end: LogEnd) -> Profile {
    let steel = design_cases::roller_steel();
    Profile::LogarithmicCrown(LogCrown {
        design_load,
        length: ROLLER_LENGTH,
        combined_modulus: combined_modulus(&steel, &steel),
        radius: ROLLER_RADIUS,
        flat_length,
        end,
    })
}

fn crowns() -> Vec<Crown> {
    vec![
        Crown {
            name: "circular",
            make: |p| Profile::CircularCrown {
                radius: p[0],
                flat_length: 0.0,
            },
            bracket: vec![(200.0, 5e4, true), (0.0, LARGEST, false)],
            start: vec![1500.0, 0.5 * LARGEST],
        },
        Crown {
            name: "Johns-Gohar",
            make: |p| log_crown(p[0], 0.0, LogEnd::JohnsGohar),
            bracket: vec![(1e3, 4e4, true), (0.0, LARGEST, false)],
            start: vec![1e4, 0.5 * LARGEST],
        },
        Crown {
            name: "Fujiwara-Kawase",
            make: |p| {
                let end = LogEnd::FujiwaraKawase {
                    k1: p[0],
                    end_drop: p[2],
                };
                log_crown(1e4, (1.0 - p[1]) * ROLLER_LENGTH, end)
            },
            bracket: vec![
                (0.2, 5.0, true),
                (0.3, 1.0, false),
                (2e-3, 5e-2, true),
                (0.0, LARGEST, false),
            ],
            start: vec![1.0, 1.0, 1e-2, 0.5 * LARGEST],
        },
    ]
}

/// The minimum of `f` over `x[i]` in its bracket, the others held, by
/// `steps` golden sections (in log x where the bracket says); the current
/// `x[i]` is kept when no probe does better.
fn golden(
    f: &mut dyn FnMut(&[f64]) -> f64,
    x: &mut [f64],
    i: usize,
    (lo, hi, log): (f64, f64, bool),
    steps: usize,
) -> f64 {
    let (to, from) = if log {
        (f64::ln as fn(f64) -> f64, f64::exp as fn(f64) -> f64)
    } else {
        ((|v| v) as fn(f64) -> f64, (|v| v) as fn(f64) -> f64)
    };
    let (current, at_current) = (x[i], f(x));
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (to(lo), to(hi));
    let mut at = |x: &mut [f64], u: f64| {
        x[i] = from(u);
        f(x)
    };
    let (mut c, mut d) = (b - ratio * (b - a), a + ratio * (b - a));
    let (mut fc, mut fd) = (at(x, c), at(x, d));
    for _ in 0..steps {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - ratio * (b - a);
            fc = at(x, c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + ratio * (b - a);
            fd = at(x, d);
        }
    }
    let (best, value) = if fc < fd { (c, fc) } else { (d, fd) };
    if value < at_current {
        x[i] = from(best);
        value
    } else {
        x[i] = current;
        at_current
    }
}

/// The crown's parameters (slope last) of least worst p_max / p0 on
/// `roller`, from `start`: each parameter by `steps` golden sections in
/// turn, `rounds` times over (within `narrow` of the current values when
/// below 1); with the worst.
fn tune(
    crown: &Crown,
    roller: &Roller,
    start: &[f64],
    (narrow, steps, rounds): (f64, usize, usize),
) -> (Vec<f64>, f64) {
    let params = crown.bracket.len();
    let mut objective = |x: &[f64]| {
        roller
            .worst(&(crown.make)(&x[..params - 1]), x[params - 1])
            .map_or(f64::INFINITY, |(w, _)| w)
    };
    let mut x = start.to_vec();
    let mut best = f64::INFINITY;
    for _ in 0..rounds {
        for (i, &(lo, hi, log)) in crown.bracket.iter().enumerate() {
            // Around the current value on the design's grid (`narrow` < 1).
            let bracket = if narrow < 1.0 {
                let width = narrow * (hi - lo);
                if log {
                    (x[i] * (1.0 - narrow), x[i] * (1.0 + narrow), true)
                } else {
                    ((x[i] - width).max(lo), (x[i] + width).min(hi), false)
                }
            } else {
                (lo, hi, log)
            };
            best = golden(&mut objective, &mut x, i, bracket, steps);
        }
    }
    (x, best)
}

/// A profile of the comparison: its name, profile, slope and tuned
/// parameters.
struct Named {
    name: &'static str,
    profile: Profile,
    slope: f64,
    parameters: String,
}

/// The designed crown, converged over grids, with the grids' objectives
/// printed as they are done.
fn designed_crown(references: &[f64]) -> Result<Converged, Box<dyn Error>> {
    let request = DesignRequest {
        reference_intensities: Some(references.to_vec()),
        ..DesignRequest::new(DesignFamily::Linear(Family::Free), Axis::Y)
    };
    let started = Instant::now();
    let converged = request.run_converged(
        &GridSequence::default(),
        |fineness| {
            let roller = Roller::new(fineness).map_err(|e| DesignError::Incompatible {
                field: "grids",
                reason: e.to_string(),
            })?;
            Ok(Some(roller.cases(0.0)?))
        },
        |level| {
            println!(
                "  grid x{:<3} {:>6} points a case: {:<9} worst p_max/p0 {:.4}  ({:.2} s)",
                level.fineness,
                level.points,
                if level.designed {
                    "designed"
                } else {
                    "evaluated"
                },
                level.objective,
                level.seconds
            )
        },
    )?;
    println!(
        "  designed and verified in {:.2} s",
        started.elapsed().as_secs_f64()
    );
    Ok(converged)
}

/// The crown designed for the worst von Mises stress below the surface
/// over the cases on the pressure design's grid, started from the pressure
/// design and through its knots; every case certified.
fn von_mises_crown(
    design: &Roller,
    pressure: &Profile,
    references: &[f64],
) -> Result<Profile, Box<dyn Error>> {
    let Profile::Spline { positions, .. } = pressure else {
        return Err("the pressure design is not a spline".into());
    };
    let request = DesignRequest {
        reference_intensities: Some(references.to_vec()),
        knots: Some(positions.clone()),
        starts: vec![pressure.clone()],
        own_starts: false,
        objective: Objective::VonMises,
        bodies: vec![design_cases::roller_bodies().0],
        ..DesignRequest::new(DesignFamily::Linear(Family::Free), Axis::Y)
    };
    let started = Instant::now();
    let outcome = request.run(&design.cases(0.0)?)?;
    if !outcome
        .evaluation
        .solutions
        .iter()
        .all(|s| s.certificate.holds())
    {
        return Err("a case of the von Mises design is not certified".into());
    }
    if let elcon::design::Found::Designed {
        value,
        worst_stress,
        ..
    } = &outcome.found
    {
        println!(
            "  designed for von Mises on {}x{} in {:.2} s: worst von Mises / p0 {value:.4}, {:.0} MPa on the depth grid, every case certified",
            design.cells.0,
            design.cells.1,
            started.elapsed().as_secs_f64(),
            worst_stress.unwrap_or(f64::NAN)
        );
    }
    Ok(outcome.profile)
}

/// Every crown tuned on the scene's grid, then polished on the design's;
/// Fujiwara and Kawase's started where it is Johns and Gohar's tuned crown
/// (K1 its design load over 10 kN, K2 = 1, z_m its end drop), so that it
/// ends no worse.
fn tuned_crowns(coarse: &Roller, design: &Roller) -> Vec<Named> {
    let mut tuned: Vec<(f64, f64)> = Vec::new();
    crowns()
        .iter()
        .map(|crown| {
            let start = match (crown.name, tuned.last()) {
                ("Fujiwara-Kawase", Some(&(load, slope))) => {
                    let end_drop = match log_crown(load, 0.0, LogEnd::JohnsGohar) {
                        Profile::LogarithmicCrown(c) => c.end_drop(),
                        _ => 1e-2,
                    };
                    vec![load / 1e4, 1.0, end_drop, slope]
                }
                _ => crown.start.clone(),
            };
            let (x, _) = tune(crown, coarse, &start, (1.0, TUNE_STEPS, 2));
            let (x, _) = tune(crown, design, &x, (0.25, POLISH_STEPS, 1));
            let params = crown.bracket.len();
            tuned.push((x[0], x[params - 1]));
            Named {
                name: crown.name,
                profile: (crown.make)(&x[..params - 1]),
                slope: x[params - 1],
                parameters: format!(
                    "{:?}",
                    x.iter().map(|v| format!("{v:.4e}")).collect::<Vec<_>>()
                ),
            }
        })
        .collect()
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = common::out_dir("out/misaligned_roller")?;
    fs::create_dir_all(&out)?;
    println!(
        "Misaligned roller: steel, D = {} mm, l = {ROLLER_LENGTH} mm, on a flat steel raceway (mm, N, MPa); \
         {} cases: {LOADS:?} N x 0 to {} mrad",
        2.0 * ROLLER_RADIUS,
        LOADS.len() * (STEPS + 1),
        1e3 * LARGEST
    );
    let coarse = Roller::new(1.0)?;
    println!("\nthe designed crown over grids (x1 = 9 x 40 cells):");
    let converged = designed_crown(&coarse.references)?;
    let design_fineness = converged.levels.last().map_or(1.0, |l| l.fineness);
    let verification = converged.verification.expect("a verified design");
    let design = Roller::new(design_fineness)?;
    let finer = Roller::new(verification.fineness)?;
    let mut named = vec![Named {
        name: "uncrowned",
        profile: Profile::none(),
        slope: 0.0,
        parameters: String::new(),
    }];
    named.extend(tuned_crowns(&coarse, &design));
    named.push(Named {
        name: "designed",
        profile: converged.outcome.profile.clone(),
        slope: 0.0,
        parameters: "free: natural cubic spline through 40 knots".into(),
    });
    println!("\nthe crown designed for the worst von Mises stress:");
    named.push(Named {
        name: "designed (vM)",
        profile: von_mises_crown(&design, &converged.outcome.profile, &design.references)?,
        slope: 0.0,
        parameters: "free: the same knots, started from the pressure design".into(),
    });
    let rows = comparison(&named, &design, &finer)?;
    read_linearly(&converged, &design, design_fineness)?;
    common::write_whole(&out.join("pmax.csv"), rows.csv)?;
    plot(&out.join("pmax.svg"), &rows.lines)?;
    if let Profile::Spline { positions, drops } = &converged.outcome.profile {
        let mut csv = format!(
            "# natural cubic spline, end slopes carried on; worst p_max/p0 {:.6} on {}x{}\ny_mm,drop_mm\n",
            converged.levels.last().map_or(f64::NAN, |l| l.objective),
            design.cells.0,
            design.cells.1
        );
        for (y, d) in positions.iter().zip(drops) {
            csv.push_str(&format!("{y:.17e},{d:.17e}\n"));
        }
        common::write_whole(&out.join("designed_profile.csv"), csv)?;
    }
    println!(
        "\nwrote {}/pmax.csv, pmax.svg and designed_profile.csv",
        out.display()
    );
    let at_largest = |name: &str| {
        rows.lines
            .iter()
            .find(|(n, _)| n == name)
            .and_then(|(_, v)| v.last().copied())
            .unwrap_or(f64::NAN)
    };
    println!(
        "misalignment={LARGEST:e} pmax_none={:.1} pmax_log={:.1} pmax_designed={:.1} grid={}x{} verified={:.4}",
        at_largest("uncrowned"),
        at_largest("Fujiwara-Kawase"),
        at_largest("designed"),
        design.cells.0,
        design.cells.1,
        verification.objective
    );
    Ok(())
}

/// The comparison's outputs: the CSV of p_max against misalignment at the
/// largest load, and each profile's line of it.
struct Rows {
    csv: String,
    lines: Vec<(String, Vec<f64>)>,
}

/// Prints the comparison over the 33 cases (design grid, verification
/// grid) and p_max against misalignment at the largest load on the design
/// grid.
/// The designed crown as a workshop reads a table of it, straight between
/// its rows, on grids three and six times finer than the design's (three:
/// the finer grid of docs/peers/verify_misaligned_roller.py): its values at
/// the design grid's stations, and profile.csv's samples (`Sampling`, ten
/// to a station), against the spline itself; each its worst p_max / p0
/// and its difference from the design's objective.
fn read_linearly(
    converged: &Converged,
    design: &Roller,
    design_fineness: f64,
) -> Result<(), Box<dyn Error>> {
    let spline = &converged.outcome.profile;
    let points = design.bases.iter().map(ContactProblem::points);
    let (stations, _) = axial_stations(points, Axis::Y);
    let linear = |positions: Vec<f64>| -> Result<Profile, DesignError> {
        let rows = spline.table(&positions)?;
        let (positions, drops) = rows.into_iter().unzip();
        Ok(Profile::Free { positions, drops })
    };
    let at_stations = linear(stations.clone())?;
    let sampled = linear(Sampling::new(&stations, None)?.positions())?;
    let objective = converged.levels.last().map_or(f64::NAN, |l| l.objective);
    for factor in [3.0, 6.0] {
        let finer = Roller::new(factor * design_fineness)?;
        println!(
            "\nthe designed crown read straight between rows, on {}x{} cells (design: {objective:.4}):",
            finer.cells.0, finer.cells.1
        );
        for (name, profile) in [
            ("the stations' values", &at_stations),
            ("profile.csv's samples", &sampled),
            ("the spline itself", spline),
        ] {
            let (worst, _) = finer.worst(profile, 0.0)?;
            println!(
                "{name:<24} {worst:.4} ({:+.2} %)",
                100.0 * (worst / objective - 1.0)
            );
        }
    }
    Ok(())
}

fn comparison(named: &[Named], design: &Roller, finer: &Roller) -> Result<Rows, Box<dyn Error>> {
    println!(
        "\n{:<16} {:>12} {:>12} {:>10} {:>9} {:>13} {:>10} {:>9}  parameters (slope last, rad)",
        "profile",
        format!("{}x{}", design.cells.0, design.cells.1),
        format!("{}x{}", finer.cells.0, finer.cells.1),
        "vM MPa",
        "depth mm",
        "at kN, mrad",
        "vM finer",
        "depth"
    );
    let mut csv = String::from("profile,misalignment_rad,pmax_mpa,pmax_over_p0\n");
    let mut lines = Vec::new();
    let last = LOADS.len() - 1;
    let per_load = STEPS + 1;
    for n in named {
        let (worst, pmax) = design.worst(&n.profile, n.slope)?;
        let (verified, _) = finer.worst(&n.profile, n.slope)?;
        let (vm, load, angle) = design.von_mises(&n.profile, n.slope)?;
        let (vm_finer, _, _) = finer.von_mises(&n.profile, n.slope)?;
        println!(
            "{:<16} {:>12.4} {:>12.4} {:>10.0} {:>9.4} {:>13} {:>10.0} {:>9.4}  {}",
            n.name,
            worst,
            verified,
            vm.value,
            vm.z,
            format!("{:.0}, {:.1}", load / 1e3, angle * 1e3),
            vm_finer.value,
            vm_finer.z,
            n.parameters
        );
        let values: Vec<f64> = pmax[last * per_load..].to_vec();
        for (angle, p) in angles().iter().zip(&values) {
            let p0 = design.references[last * per_load];
            csv.push_str(&format!("{},{angle:e},{p:.6e},{:.6e}\n", n.name, p / p0));
        }
        lines.push((n.name.to_string(), values));
    }
    println!(
        "\np_max (MPa) at {} N against misalignment (mrad), design grid:",
        LOADS[last]
    );
    print!("{:<16}", "profile");
    for angle in angles() {
        print!(" {:>7.1}", 1e3 * angle);
    }
    println!();
    for (name, values) in &lines {
        print!("{name:<16}");
        for v in values {
            print!(" {v:>7.0}");
        }
        println!();
    }
    Ok(Rows { csv, lines })
}

fn plot(path: &Path, rows: &[(String, Vec<f64>)]) -> Result<(), Box<dyn Error>> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (720, 480)).into_drawing_area();
        root.fill(&WHITE)?;
        let top = rows
            .iter()
            .flat_map(|(_, v)| v.iter().copied())
            .fold(0.0, f64::max);
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "misaligned roller, {} N: peak pressure",
                    LOADS[LOADS.len() - 1]
                ),
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..1e3 * LARGEST, 0.0..1.1 * top)?;
        chart
            .configure_mesh()
            .x_desc("misalignment (mrad)")
            .y_desc("p_max (MPa)")
            .draw()?;
        for (i, (name, values)) in rows.iter().enumerate() {
            let points = angles().into_iter().zip(values).map(|(a, p)| (1e3 * a, *p));
            common::labelled_line(&mut chart, i, name, points)?;
        }
        common::legend_upper_left(&mut chart)?;
        root.present()?;
    }
    common::write_whole(path, svg)?;
    Ok(())
}
