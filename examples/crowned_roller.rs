//! A crowned cylindrical roller on a flat raceway: the axial pressure
//! profile without a crown (edge peaks), with a circular crown, with a
//! logarithmic crown, and with the crown designed to minimize the worst
//! p_max over three loads.
//!
//! Steel roller (E = 210 GPa, nu = 0.3), diameter 10 mm, effective length
//! 10 mm, on a flat steel raceway; loads 1, 5 and 10 kN. Love patches on a
//! rectangular grid, long in the axial direction y (40 cells along the
//! roller, 9 across a width of 3.2 Hertz half-widths of each load). Units:
//! millimetre, newton, megapascal.
//!
//! - circular crown: the radius that minimizes the worst p_max over the
//!   loads (a one-parameter search, every sample a certified analysis);
//! - logarithmic crown: Johns & Gohar's profile for the largest load;
//! - designed crown: a free profile (one drop per axial station), the
//!   paper's min-max design extended to the three loads at once, started
//!   from the uncorrected roller and from both crowns.
//!
//! "Worst p_max over the loads" is taken relative to each load's Hertz
//! line-contact peak (the pressure a perfect crown would give): a crown must
//! work from light to full load, and in absolute terms the heaviest load
//! alone would decide. Both the search and the design use these references.
//!
//! Prints the axial pressure at the largest load (the largest pressure
//! across the width at each axial station) for each profile, and a table of
//! p_max per load and profile; writes both as CSV under `--out` (default
//! out/crowned_roller).
//!
//! Run: `cargo run --release --example crowned_roller -- [--out DIR]`

mod common;

use std::error::Error;
use std::fs;

use elcon::analysis::references::HertzCylinders;
use elcon::analysis::{ContactProblem, Loading, Method, Options};
use elcon::design::{
    Analysis, Axis, CrownSearch, Design, DesignOptions, Evaluation, Family, LogCrown, LogEnd,
    Profile, SearchOptions, crown_search, design, evaluate,
};
use elcon::influence::{PointSet, combined_modulus};
use elcon_fixtures::design_cases::{ROLLER_LENGTH, ROLLER_RADIUS, roller_bodies, roller_steel};

const LOADS: [f64; 3] = [1e3, 5e3, 10e3];
const AXIAL_CELLS: usize = 40;
const WIDTH_CELLS: usize = 9;

/// The largest pressure across the width at each axial station.
fn axial_profile(case: &ContactProblem, e: &Evaluation, l: usize) -> Vec<(f64, f64)> {
    let points = case.points();
    let mut stations: Vec<(f64, f64)> = Vec::new();
    for k in 0..points.len() {
        let y = points.y(k);
        let p = e.solutions[l].pressures[k];
        match stations.iter_mut().find(|(s, _)| (s - y).abs() < 1e-12) {
            Some((_, m)) => *m = m.max(p),
            None => stations.push((y, p)),
        }
    }
    stations.sort_by(|a, b| a.0.total_cmp(&b.0));
    stations
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = common::out_dir("out/crowned_roller")?;
    let steel = roller_steel();
    let e_star = combined_modulus(&steel, &steel);
    let (body, geometry) = roller_bodies();
    // No body edges declared (the zone open at the ends), unlike the
    // design cases' roller (design_cases::aligned_roller).
    let (mut cases, mut hertz) = (Vec::new(), Vec::new());
    for &load in &LOADS {
        let line = HertzCylinders::new(e_star, ROLLER_RADIUS, load / ROLLER_LENGTH)?;
        let points = PointSet::grid_rectangle(
            1.6 * line.half_width(),
            0.5 * ROLLER_LENGTH,
            WIDTH_CELLS,
            AXIAL_CELLS,
        )?;
        cases.push(ContactProblem::new(
            points,
            &body,
            &body,
            &geometry,
            Loading::load(load),
        )?);
        hertz.push(line.peak_pressure());
    }
    println!(
        "Crowned roller: steel, D = {} mm, l = {ROLLER_LENGTH} mm, on a flat steel raceway (mm, N, MPa)",
        2.0 * ROLLER_RADIUS
    );
    for ((case, load), peak) in cases.iter().zip(LOADS).zip(&hertz) {
        println!(
            "  load {load:>6} N: {} points; Hertz line-contact peak {peak:.0} MPa",
            case.points().len(),
        );
    }
    let crowns = Crowns::of(&cases, e_star, &hertz)?;
    crowns.print()?;
    let csv = crowns.axial_table(&cases[2])?;
    let table = crowns.pmax_table(&hertz);
    fs::create_dir_all(&out)?;
    common::write_whole(&out.join("axial_pressure.csv"), &csv)?;
    common::write_whole(&out.join("pmax.csv"), &table)?;
    println!(
        "wrote axial_pressure.csv and pmax.csv under {}",
        out.display()
    );
    Ok(())
}

/// The roller's four profiles over the loads.
struct Crowns {
    /// The uncorrected roller.
    none: Evaluation,
    /// The searched circular crown.
    circular: CrownSearch,
    /// Johns & Gohar's crown for the largest load.
    log_crown: LogCrown,
    /// The roller with `log_crown`.
    logarithmic: Evaluation,
    /// The designed free profile.
    designed: Design,
    /// The seconds the design took.
    design_seconds: f64,
}

impl Crowns {
    /// Each profile on `cases`, the circular crown and the design relative
    /// to the Hertz peaks `hertz`.
    fn of(cases: &[ContactProblem], e_star: f64, hertz: &[f64]) -> Result<Crowns, Box<dyn Error>> {
        let method = Method::BlockPivoting;
        let opts = Options::default();
        let none = evaluate(
            cases,
            Axis::Y,
            &Profile::none(),
            &Analysis::new(method, &opts),
        )?;
        let circular = crown_search(
            cases,
            Axis::Y,
            |radius| {
                Ok(Profile::CircularCrown {
                    radius,
                    flat_length: 0.0,
                })
            },
            50.0,
            1e5,
            &SearchOptions {
                reference_intensities: Some(hertz.to_vec()),
                ..SearchOptions::default()
            },
        )?;
        let log_crown = LogCrown {
            design_load: LOADS[2],
            length: ROLLER_LENGTH,
            combined_modulus: e_star,
            radius: ROLLER_RADIUS,
            flat_length: 0.0,
            end: LogEnd::JohnsGohar,
        };
        let logarithmic = evaluate(
            cases,
            Axis::Y,
            &Profile::LogarithmicCrown(log_crown),
            &Analysis::new(method, &opts),
        )?;
        let started = std::time::Instant::now();
        let designed = design(
            cases,
            Axis::Y,
            Family::Free,
            &DesignOptions {
                reference_intensities: Some(hertz.to_vec()),
                // Part 2 ends at a local minimum; starting also from the two
                // crowns guarantees the design is no worse than either.
                starts: vec![
                    circular.profile.clone(),
                    Profile::LogarithmicCrown(log_crown),
                ],
                ..DesignOptions::default()
            },
        )?;
        let design_seconds = started.elapsed().as_secs_f64();
        Ok(Crowns {
            none,
            circular,
            log_crown,
            logarithmic,
            designed,
            design_seconds,
        })
    }

    /// The profiles by name, in the tables' order.
    fn profiles(&self) -> [(&'static str, &Evaluation); 4] {
        [
            ("no crown", &self.none),
            ("circular crown", &self.circular.evaluation),
            ("logarithmic crown", &self.logarithmic),
            ("designed crown", &self.designed.evaluation),
        ]
    }

    /// Prints each crown: its size, its end drop, and how the design went.
    fn print(&self) -> Result<(), Box<dyn Error>> {
        let (circular, designed) = (&self.circular, &self.designed);
        println!();
        println!(
            "circular crown: radius {:.1} mm (searched, {} analyses), end drop {:.2} um",
            circular.parameter,
            circular.samples.len(),
            1e3 * circular.profile.separation(0.5 * ROLLER_LENGTH)?
        );
        println!(
            "logarithmic crown (Johns-Gohar, design load {} N): end drop {:.2} um",
            LOADS[2],
            1e3 * self.log_crown.end_drop()
        );
        println!(
            "designed crown (free profile, {} stations, worst p_max/Hertz over the loads): end drop {:.2} um, {:?} method, {:.2} s for {} starts",
            designed.stations.len(),
            1e3 * designed
                .profile
                .separation(designed.stations[designed.stations.len() - 1])?,
            designed.solver.method().name(),
            self.design_seconds,
            designed.starts.len()
        );
        for start in &designed.starts {
            match &start.result {
                Ok(v) => println!(
                    "  start '{}': worst p_max/Hertz {v:.4}, {} pivots",
                    start.label, start.pivots
                ),
                Err(e) => println!("  start '{}' failed: {e}", start.label),
            }
        }
        Ok(())
    }

    /// Prints the axial pressure of each profile on `largest` (the case of
    /// the largest load) and each crown's drop; returns them as CSV.
    fn axial_table(&self, largest: &ContactProblem) -> Result<String, Box<dyn Error>> {
        let profiles = self.profiles();
        println!();
        println!(
            "axial pressure at {} N (largest across the width), MPa; drop of each crown, um",
            LOADS[2]
        );
        print!("{:>7}", "y mm");
        for (name, _) in &profiles {
            print!(" {name:>17}");
        }
        println!(" {:>9} {:>9} {:>9}", "circ um", "log um", "design um");
        let columns: Vec<Vec<(f64, f64)>> = profiles
            .iter()
            .map(|(_, e)| axial_profile(largest, e, 2))
            .collect();
        let mut csv = String::from(
            "y_mm,p_none_mpa,p_circular_mpa,p_logarithmic_mpa,p_designed_mpa,drop_circular_mm,drop_logarithmic_mm,drop_designed_mm\n",
        );
        for (i, &(y, _)) in columns[0].iter().enumerate() {
            print!("{y:>7.3}");
            for c in &columns {
                print!(" {:>17.1}", c[i].1);
            }
            let drops = [
                self.circular.profile.separation(y)?,
                Profile::LogarithmicCrown(self.log_crown).separation(y)?,
                self.designed.profile.separation(y)?,
            ];
            println!(
                " {:>9.3} {:>9.3} {:>9.3}",
                1e3 * drops[0],
                1e3 * drops[1],
                1e3 * drops[2]
            );
            csv.push_str(&format!(
                "{y},{},{},{},{},{},{},{}\n",
                columns[0][i].1,
                columns[1][i].1,
                columns[2][i].1,
                columns[3][i].1,
                drops[0],
                drops[1],
                drops[2]
            ));
        }
        Ok(csv)
    }

    /// Prints p_max per load and profile, and the worst relative to the
    /// Hertz peaks `hertz`; returns the table as CSV.
    fn pmax_table(&self, hertz: &[f64]) -> String {
        println!();
        println!(
            "p_max per load and profile, MPa; last column the worst p_max / Hertz line-contact peak"
        );
        print!("{:<18}", "profile");
        for load in LOADS {
            print!(" {:>10}", format!("{load} N"));
        }
        println!(" {:>10}", "worst/Hertz");
        let mut table = String::from("profile,load_n,p_max_mpa,hertz_line_peak_mpa\n");
        for (name, e) in &self.profiles() {
            print!("{name:<18}");
            let mut worst_ratio = 0.0f64;
            for (l, load) in LOADS.iter().enumerate() {
                print!(" {:>10.1}", e.max_intensities[l]);
                worst_ratio = worst_ratio.max(e.max_intensities[l] / hertz[l]);
                table.push_str(&format!(
                    "{name},{load},{},{}\n",
                    e.max_intensities[l], hertz[l]
                ));
                assert!(e.solutions[l].certificate.holds());
            }
            println!(" {worst_ratio:>10.3}");
        }
        table
    }
}
