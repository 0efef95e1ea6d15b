//! A misaligned cylindrical roller: the peak pressure against misalignment
//! for an uncrowned roller and three crowns.
//!
//! Steel roller (E = 210 GPa, nu = 0.3), diameter 10 mm, effective length
//! 10 mm, on a flat steel raceway at 5 kN; Love patches on a rectangle grid
//! with the roller's axis along y, 40 cells along the roller and 9 across a
//! width of 3.2 Hertz half-widths. Units: millimetre, newton, megapascal.
//!
//! The misalignment is a prescribed rotation of the roller about the x axis
//! (`tilt_x`, across the rolling direction), from 0 to 1 mrad in steps of
//! 0.1 mrad: 1 mrad is about 3.4 minutes of arc, the order of what
//! cylindrical roller bearings are rated to tolerate. The rotation about y
//! stays free with zero moment (zero by the mirror symmetry about x = 0),
//! the load is applied at the middle.
//!
//! Profiles (drops along y, added to the cylinder's separation):
//! - uncrowned: a straight roller (edge peaks at its ends);
//! - Johns & Gohar's logarithmic crown for 5 kN;
//! - Lundberg's logarithmic crown for 5 kN (the same curve without the end
//!   modification, steeper toward the ends);
//! - a circular crown with the Johns-Gohar crown's end drop;
//! - the crown designed for the whole range: a free profile (one drop per
//!   axial station) minimizing the worst p_max / p0 over 1, 5 and 10 kN at
//!   every misalignment of the table (33 cases, each load on its own grid,
//!   p0 each load's aligned Hertz peak), by the case-decomposed descent
//!   (`elcon_design::design`), started from the Johns-Gohar and circular
//!   crowns so that it is no worse than either over the range. The range
//!   is one-sided (0 to 1 mrad): a roller misaligned both ways would list
//!   the negative angles too, and its designed crown would be symmetric.
//!
//! Prints, per profile and misalignment, p_max, p_max over the aligned
//! Hertz line-contact peak `p0 = 2 P' / (pi b)`, the moment about x that
//! holds the roller at its misalignment (the reaction, from the contact
//! forces), and the balance of the run: the load carried and the zero
//! moment about the free axis y, relative to the load (and the contact's
//! half-width b); then each profile's worst p_max / p0 over the 33 design
//! cases. Writes the table as CSV and a plot of p_max against misalignment
//! at 5 kN (one curve per profile) under `--out` (default
//! out/misaligned_roller). Its last line is
//! `misalignment=<rad> pmax_none=<MPa> pmax_log=<MPa> pmax_designed=<MPa>`
//! at 1 mrad and 5 kN (log: the Johns-Gohar crown).
//!
//! Run: `cargo run --release --example misaligned_roller -- [--out DIR]`

mod common;

use std::error::Error;
use std::fs;
use std::path::Path;

use elcon::analysis::references::HertzCylinders;
use elcon::analysis::{
    ContactProblem, ContactSolution, Geometry, Loading, Method, Options, Surface,
};
use elcon::design::{
    Axis, Design, DesignOptions, Family, LogCrown, LogEnd, Profile, Solver, design, evaluate,
};
use elcon::influence::{Body, Material, PointSet, combined_modulus};
use plotters::prelude::*;

const RADIUS: f64 = 5.0;
const LENGTH: f64 = 10.0;
const LOAD: f64 = 5e3;
/// The loads the crown is designed for (N).
const DESIGN_LOADS: [f64; 3] = [1e3, 5e3, 10e3];
const AXIAL_CELLS: usize = 40;
const WIDTH_CELLS: usize = 9;
/// Misalignment steps, 0.1 mrad each (an angle is `i / STEPS_PER_RAD`,
/// exact to the last digit), up to LARGEST = 1 mrad.
const STEPS: usize = 10;
const STEPS_PER_RAD: f64 = 1e4;
const LARGEST: f64 = STEPS as f64 / STEPS_PER_RAD;

/// A profile's name and its p_max at each misalignment.
type Row = (String, Vec<f64>);

/// A profile of the table, and its separation along y.
struct Named {
    name: &'static str,
    profile: Profile,
}

fn profiles(e_star: f64) -> Result<Vec<Named>, Box<dyn Error>> {
    let johns_gohar = LogCrown {
        design_load: LOAD,
        length: LENGTH,
        combined_modulus: e_star,
        radius: RADIUS,
        flat_length: 0.0,
        end: LogEnd::JohnsGohar,
    };
    let lundberg = LogCrown {
        end: LogEnd::Lundberg,
        ..johns_gohar
    };
    // The circular crown with the same drop at the roller's end.
    let half = 0.5 * LENGTH;
    let drop = johns_gohar.end_drop();
    let crown_radius = (half * half + drop * drop) / (2.0 * drop);
    Ok(vec![
        Named {
            name: "uncrowned",
            profile: Profile::none(),
        },
        Named {
            name: "circular",
            profile: Profile::CircularCrown {
                radius: crown_radius,
                flat_length: 0.0,
            },
        },
        Named {
            name: "Lundberg",
            profile: Profile::LogarithmicCrown(lundberg),
        },
        Named {
            name: "Johns-Gohar",
            profile: Profile::LogarithmicCrown(johns_gohar),
        },
    ])
}

/// The design cases: every load of [`DESIGN_LOADS`] on its own grid (1.6
/// of its Hertz half-width across) at every misalignment of the table, and
/// each case's aligned Hertz peak (its reference intensity).
fn design_cases(
    steel: &Material,
    e_star: f64,
    angles: &[f64],
) -> Result<(Vec<ContactProblem>, Vec<f64>), Box<dyn Error>> {
    let body = Body::uniform_patch(*steel);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: RADIUS }, Surface::Plane);
    let (mut cases, mut references) = (Vec::new(), Vec::new());
    for load in DESIGN_LOADS {
        let hertz = HertzCylinders::new(e_star, RADIUS, load / LENGTH)?;
        let points = PointSet::grid_rectangle(
            1.6 * hertz.half_width(),
            0.5 * LENGTH,
            WIDTH_CELLS,
            AXIAL_CELLS,
        )?;
        let aligned = ContactProblem::new(points, &body, &body, &geometry, Loading::load(load))?
            .with_body_edges(false, true);
        for &angle in angles {
            cases.push(aligned.with_loading(Loading::load(load).with_tilt_x(angle))?);
            references.push(hertz.peak_pressure());
        }
    }
    Ok((cases, references))
}

/// The free crown with the least worst p_max / p0 over `cases`, started
/// from `starts`.
fn designed_crown(
    cases: &[ContactProblem],
    references: &[f64],
    starts: Vec<Profile>,
) -> Result<Design, Box<dyn Error>> {
    Ok(design(
        cases,
        Axis::Y,
        Family::Free,
        &DesignOptions {
            reference_intensities: Some(references.to_vec()),
            starts,
            ..DesignOptions::default()
        },
    )?)
}

/// The roller at `misalignment` with `profile`, solved.
fn solve(
    base: &ContactProblem,
    profile: &Profile,
    misalignment: f64,
) -> Result<ContactSolution, Box<dyn Error>> {
    let points = base.points();
    let eps: Vec<f64> = (0..points.len())
        .map(|k| Ok(base.separation()[k] + profile.separation(points.y(k))?))
        .collect::<Result<_, Box<dyn Error>>>()?;
    let problem = base
        .with_separation(eps)?
        .with_loading(Loading::load(LOAD).with_tilt_x(misalignment))?;
    Ok(problem.solve(Method::BlockPivoting, &Options::default())?)
}

fn plot(path: &Path, angles: &[f64], rows: &[Row]) -> Result<(), Box<dyn Error>> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (720, 480)).into_drawing_area();
        root.fill(&WHITE)?;
        let top = rows
            .iter()
            .flat_map(|(_, v)| v.iter().copied())
            .fold(0.0, f64::max);
        let mut chart = ChartBuilder::on(&root)
            .caption("misaligned roller, 5 kN: peak pressure", ("sans-serif", 20))
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
            let points = angles.iter().zip(values).map(|(a, p)| (1e3 * a, *p));
            common::labelled_line(&mut chart, i, name, points)?;
        }
        common::legend_upper_left(&mut chart)?;
        root.present()?;
    }
    common::write_whole(path, svg)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = common::out_dir("out/misaligned_roller")?;
    fs::create_dir_all(&out)?;
    let steel = Material::new(210e3, 0.3)?;
    let e_star = combined_modulus(&steel, &steel);
    let hertz = HertzCylinders::new(e_star, RADIUS, LOAD / LENGTH)?;
    let b = hertz.half_width();
    let points = PointSet::grid_rectangle(1.6 * b, 0.5 * LENGTH, WIDTH_CELLS, AXIAL_CELLS)?;
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: RADIUS }, Surface::Plane);
    // Folded by the mirror about x = 0 (the roller's width), which every
    // misalignment about x and every crown along y keeps: built misaligned,
    // so that the mirror about y (which a misalignment breaks) is not used.
    let misaligned = Loading::load(LOAD).with_tilt_x(LARGEST);
    let base = ContactProblem::symmetric(points, &body, &body, &geometry, misaligned)?
        .with_body_edges(false, true);
    let p0 = hertz.peak_pressure();
    println!(
        "Misaligned roller: steel, D = {} mm, l = {LENGTH} mm, {LOAD} N on a flat steel raceway (mm, N, MPa)",
        2.0 * RADIUS
    );
    println!(
        "  {} points ({} unknowns folded); aligned Hertz line-contact peak p0 = {p0:.0} MPa",
        base.points().len(),
        base.entries("the unknowns count").expect("dense").nrows()
    );
    let angles: Vec<f64> = (0..=STEPS).map(|i| i as f64 / STEPS_PER_RAD).collect();
    let mut named_profiles = profiles(e_star)?;
    let (cases, references) = design_cases(&steel, e_star, &angles)?;
    add_designed_crown(&mut named_profiles, &cases, &references, angles.len())?;
    let (csv, rows) = pmax_table(&base, &named_profiles, &angles, p0, b)?;
    common::write_whole(&out.join("pmax.csv"), csv)?;
    plot(&out.join("pmax.svg"), &angles, &rows)?;
    println!("\nwrote {}/pmax.csv and pmax.svg", out.display());
    print_worst_over_the_cases(&cases, &references, &named_profiles)?;
    let last = |name: &str| {
        rows.iter()
            .find(|(n, _)| n == name)
            .and_then(|(_, v)| v.last().copied())
            .unwrap_or(f64::NAN)
    };
    println!(
        "misalignment={LARGEST:e} pmax_none={:.1} pmax_log={:.1} pmax_designed={:.1}",
        last("uncrowned"),
        last("Johns-Gohar"),
        last("designed")
    );
    Ok(())
}

/// Designs the free crown over `cases` (started from the Johns-Gohar and
/// circular crowns of `named_profiles`), prints how it went, and adds it to
/// `named_profiles` as "designed".
fn add_designed_crown(
    named_profiles: &mut Vec<Named>,
    cases: &[ContactProblem],
    references: &[f64],
    misalignments: usize,
) -> Result<(), Box<dyn Error>> {
    let starts = named_profiles
        .iter()
        .filter(|n| matches!(n.name, "Johns-Gohar" | "circular"))
        .map(|n| n.profile.clone())
        .collect();
    let started = std::time::Instant::now();
    let designed = designed_crown(cases, references, starts)?;
    let design_seconds = started.elapsed().as_secs_f64();
    if let Solver::Descent {
        iterations,
        analyses,
        ..
    } = &designed.solver
    {
        println!(
            "  designed crown: {} cases ({} loads x {} misalignments), worst p_max/p0 {:.4}, \
             {iterations} iterations, {analyses} analyses, {design_seconds:.2} s ({:?})",
            cases.len(),
            DESIGN_LOADS.len(),
            misalignments,
            designed.objective,
            designed.solver.method().name()
        );
    }
    named_profiles.push(Named {
        name: "designed",
        profile: designed.profile,
    });
    Ok(())
}

/// The table of each profile at each misalignment at [`LOAD`], printed:
/// returns it as CSV, and each profile's p_max at each angle (the plot's
/// rows).
fn pmax_table(
    base: &ContactProblem,
    named_profiles: &[Named],
    angles: &[f64],
    p0: f64,
    b: f64,
) -> Result<(String, Vec<Row>), Box<dyn Error>> {
    let mut csv = String::from(
        "profile,misalignment_rad,pmax_mpa,pmax_over_p0,moment_x_nmm,moment_y_nmm,load_n,load_centre_y_mm\n",
    );
    let mut rows = Vec::new();
    println!(
        "\n{:<12} {:>9} {:>10} {:>8} {:>13} {:>12}",
        "profile", "mrad", "p_max", "/ p0", "moment_x", "balance"
    );
    for named in named_profiles {
        let mut values = Vec::new();
        for &angle in angles {
            let sol = solve(base, &named.profile, angle)?;
            // The balance: the forces carry the load and, about the free
            // axis y, no moment (relative to the load and the contact's
            // half-width); the moment about x is the reaction that holds
            // the misalignment.
            let balance = ((sol.load - LOAD).abs() / LOAD).max(sol.moment_y.abs() / (LOAD * b));
            println!(
                "{:<12} {:>9.2} {:>10.1} {:>8.3} {:>13.4e} {:>12.1e}",
                named.name,
                1e3 * angle,
                sol.max_pressure,
                sol.max_pressure / p0,
                sol.moment_x,
                balance
            );
            csv.push_str(&format!(
                "{},{angle:e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}\n",
                named.name,
                sol.max_pressure,
                sol.max_pressure / p0,
                sol.moment_x,
                sol.moment_y,
                sol.load,
                sol.load_centre.1
            ));
            values.push(sol.max_pressure);
        }
        rows.push((named.name.to_string(), values));
    }
    Ok((csv, rows))
}

/// Prints each profile's worst p_max / p0 over the design cases.
fn print_worst_over_the_cases(
    cases: &[ContactProblem],
    references: &[f64],
    named_profiles: &[Named],
) -> Result<(), Box<dyn Error>> {
    println!(
        "\nworst p_max / p0 over the {} design cases (loads {:?} N x 0 to {} mrad):",
        cases.len(),
        DESIGN_LOADS,
        1e3 * LARGEST
    );
    for named in named_profiles {
        let e = evaluate(
            cases,
            Axis::Y,
            &named.profile,
            Method::BlockPivoting,
            &Options::default(),
        )?;
        println!("  {:<12} {:>8.4}", named.name, e.relative_worst(references));
    }
    Ok(())
}
