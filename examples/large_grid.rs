//! Dense or matrix-free: Hertz spheres (Example 1's data, Love patches)
//! solved in full on disk grids of growing N, by block pivoting on the
//! dense S and by the conjugate gradient on the lattice operator (an FFT
//! convolution, O(N) memory), side by side: assembly and solve seconds,
//! CG iterations, the bytes each holds, the errors against Hertz and the
//! certificate. The dense side stops where S would pass 4 GB.
//!
//! ```sh
//! cargo run --release --example large_grid                # up to 128 cells per radius
//! cargo run --release --example large_grid -- --max 256   # N up to about 260,000
//! cargo run --release --example large_grid -- --h-over-a 64   # one size, the peers' case
//! cargo run --release --example large_grid -- --max 128 --plot docs/img/large-grid.svg
//! ```
//!
//! With `--h-over-a K` it solves one size only, the peers' Hertz case
//! (Love patches of side h = a/K on the disk of radius 1.3 a, unfolded,
//! `solver.method = "auto"`'s choice for that N), and prints as its last
//! line `n=<N> method=<name> seconds=<assembly+solve>
//! err_delta=<approach error against Hertz> certificate=<worst residual>
//! peak_rss_mb=<MB>` (the process's peak resident memory, VmHWM).
//!
//! The table is docs/performance.md's "Dense or matrix-free"; the
//! crossover sets `elcon_scene::AUTO_DENSE_LIMIT`.

mod common;
#[path = "../benches/hertz.rs"]
mod hertz;

use std::time::Instant;

use elcon::analysis::{ContactProblem, Method, Options};
use elcon::influence::{LatticeOperator, PointSet};

/// S above this many bytes is not built (the dense column is left empty).
const DENSE_CEILING: f64 = 4e9;

/// The process's peak resident memory (VmHWM of /proc/self/status), MB.
fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|t| {
            let line = t.lines().find(|l| l.starts_with("VmHWM:"))?;
            line.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(f64::NAN, |kib| kib * 1024.0 / 1e6)
}

/// One size, the peers' case: h = a / `cells` on the disk of 1.3 a, the
/// method `"auto"` picks for it.
fn one_size(cells: f64) {
    let hertz = hertz::reference();
    let a = hertz.contact_radius();
    let points = PointSet::grid_disk(a / cells, 1.3 * a).expect("grid");
    let n = points.len();
    let dense = n <= elcon::scene::AUTO_DENSE_LIMIT;
    let start = Instant::now();
    let (build, method) = if dense {
        (ContactProblem::new as hertz::Build, Method::BlockPivoting)
    } else {
        (
            ContactProblem::lattice as hertz::Build,
            Method::ConjugateGradient,
        )
    };
    let sol = hertz::held(build, points)
        .solve(method, &Options::default())
        .expect("solve");
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "n={n} method={} seconds={seconds:.4} err_delta={:+.3e} certificate={:.1e} peak_rss_mb={:.1}",
        method.name(),
        sol.approach / hertz.approach() - 1.0,
        sol.certificate.worst(),
        peak_rss_mb()
    );
}

fn main() {
    if let Some(k) = std::env::args()
        .skip_while(|a| a != "--h-over-a")
        .nth(1)
        .and_then(|v| v.parse::<f64>().ok())
    {
        one_size(k);
        return;
    }
    let max: f64 = std::env::args()
        .skip_while(|a| a != "--max")
        .nth(1)
        .and_then(|v| v.parse().ok())
        .unwrap_or(128.0);
    let (hertz, (body, _)) = (hertz::reference(), hertz::bodies());
    let a = hertz.contact_radius();
    println!(
        "| cells per radius | N | dense: assembly + block pivoting, s | dense S, MB | matrix-free: operator + CG, s | CG iterations | operator, MB | approach error | peak error | CG certificate |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let plot_to = std::env::args()
        .skip_while(|a| a != "--plot")
        .nth(1)
        .map(std::path::PathBuf::from);
    let mut timings = Timings::default();
    let mut cells = 8.0;
    while cells <= max {
        let points = PointSet::grid_disk(a / cells, 1.25 * a).expect("grid");
        let n = points.len();
        let dense_bytes = 8.0 * (n as f64) * (n as f64);
        let dense = if dense_bytes <= DENSE_CEILING {
            let start = Instant::now();
            let sol = hertz::held(ContactProblem::new, points.clone())
                .solve(Method::BlockPivoting, &Options::default())
                .expect("dense solve");
            Some((start.elapsed().as_secs_f64(), sol.approach))
        } else {
            None
        };
        let operator_bytes =
            LatticeOperator::estimate_bytes(&points, &[&body, &body]).expect("lattice");
        let start = Instant::now();
        let sol = hertz::held(ContactProblem::lattice, points)
            .solve(Method::ConjugateGradient, &Options::default())
            .expect("matrix-free solve");
        let seconds = start.elapsed().as_secs_f64();
        if let Some((_, approach)) = dense {
            assert!(
                (approach / sol.approach - 1.0).abs() < 1e-8,
                "the two agree"
            );
        }
        println!(
            "| {cells} | {n} | {} | {} | {seconds:.3} | {} | {:.1} | {:+.2e} | {:+.2e} | {:.1e} |",
            dense.map_or("-".into(), |(s, _)| format!("{s:.3}")),
            if dense.is_some() {
                format!("{:.0}", dense_bytes / 1e6)
            } else {
                format!("({:.0})", dense_bytes / 1e6)
            },
            sol.statistics.iterations(),
            operator_bytes as f64 / 1e6,
            sol.approach / hertz.approach() - 1.0,
            sol.max_pressure / hertz.pressure(0.0) - 1.0,
            sol.certificate.worst(),
        );
        if let Some((s, _)) = dense {
            timings.dense.push((n as f64, s));
        }
        timings.matrix_free.push((n as f64, seconds));
        cells *= 2.0;
    }
    if let Some(path) = plot_to {
        plot(&path, &timings).expect("plot");
        println!("wrote {}", path.display());
    }
}

/// Seconds against N of each family.
#[derive(Default)]
struct Timings {
    dense: Vec<(f64, f64)>,
    matrix_free: Vec<(f64, f64)>,
}

/// A peer's stored runs (docs/peers/*-large.md): (cells of its square grid,
/// setup + solve seconds).
fn peer(path: &str) -> Vec<(f64, f64)> {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .lines()
        .filter(|l| l.starts_with('{'))
        .filter_map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).ok()?;
            let n = v["n"].as_f64()?;
            Some((n * n, v["t_setup_s"].as_f64()? + v["t_solve_s"].as_f64()?))
        })
        .collect()
}

/// Time against N, log-log: elcon's two families and the FFT peers.
fn plot(path: &std::path::Path, t: &Timings) -> Result<(), Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    let series = [
        ("elcon, dense S, block pivoting", t.dense.clone()),
        (
            "elcon, matrix-free, conjugate gradient",
            t.matrix_free.clone(),
        ),
        (
            "Tamaas (docs/peers/tamaas-large.md)",
            peer("docs/peers/tamaas-large.md"),
        ),
        (
            "ContactMechanics (docs/peers/cm-large.md)",
            peer("docs/peers/cm-large.md"),
        ),
    ];
    let all: Vec<(f64, f64)> = series.iter().flat_map(|(_, s)| s.iter().copied()).collect();
    let (n0, n1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.0), b.max(p.0))
    });
    let (t0, t1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption("Hertz spheres: seconds against N", ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (n0 * 0.8..n1 * 1.25).log_scale(),
                (t0 * 0.8..t1 * 1.25).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("N (points; the peers' square grids: cells)")
            .y_desc("seconds (assembly or setup, and solve)")
            .draw()?;
        for (i, (name, points)) in series.iter().enumerate() {
            let colour = common::labelled_line(&mut chart, i, name, points.iter().copied())?;
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
        }
        common::legend_upper_left(&mut chart)?;
        root.present()?;
    }
    std::fs::write(path, svg)?;
    Ok(())
}
