//! Dense or matrix-free: Hertz spheres (Example 1's data, Love patches)
//! solved in full on disk grids of growing N, by block pivoting on the
//! dense S and by the conjugate gradient on the lattice operator (an FFT
//! convolution, O(N) memory), side by side: assembly and solve CPU seconds
//! (of every thread: on a machine busy with other work, less inflated than
//! the wall time),
//! CG iterations, the bytes each holds, the errors against Hertz and the
//! certificate. The dense side stops where S would pass 4 GB.
//!
//! ```sh
//! cargo run --release --example large_grid                # up to 128 cells per radius
//! cargo run --release --example large_grid -- --max 256   # N up to about 260,000
//! cargo run --release --example large_grid -- --h-over-a 64   # one size, the peers' case
//! cargo run --release --example large_grid -- --h-over-a 64 --threads 1   # on one thread
//! cargo run --release --example large_grid -- --h-over-a 128 --threads 1 --repeat 9   # medians of 9
//! cargo run --release --example large_grid -- --max 128 --plot docs/img/large-grid.svg
//! ```
//!
//! With `--h-over-a K` it solves one size only, the peers' Hertz case
//! (Love patches of side h = a/K on the disk of radius 1.3 a, unfolded,
//! `solver.method = "auto"`'s choice for that N), and prints as its last
//! line `n=<N> method=<name> seconds=<assembly+solve>
//! err_delta=<approach error against Hertz> certificate=<worst residual>
//! peak_rss_mb=<MB> products=<operator products> floor_seconds=<products x
//! one product's CPU seconds + preconditioner applications x one
//! application's> threads=<rayon threads> cpu_seconds=<the CPU
//! time of assembly and solve, all threads> iterations=<CG iterations>
//! preconditioner_applications=<its count>
//! preconditioner_products=<one application's CPU time in products>
//! repeat=<solves> times_floor=<each repeat's seconds (one thread) or
//! cpu_seconds (several) over its floor, the median>` (`--repeat R`: the
//! solve and the floor's measure take turns R times, and the times are
//! their medians: on a machine whose speed drifts, both drift alike, and
//! a repeat's ratio to the floor measured on either side of it (the mean
//! of the unit costs before and after) drifts least;
//! `--no-floor`: the floor is not
//! measured and prints as 0, as does times_floor, so that a profiler sees the solves alone;
//! `--no-preconditioner`: the
//! conjugate gradient without its
//! preconditioner, `Options::preconditioner`; peak_rss_mb the process's
//! peak resident memory after the first solve, VmHWM; products 0 for a
//! dense solve; CPU times in
//! steps of 10 ms, a measure that a machine busy with other work inflates
//! less than the wall time; on one thread of an idle machine the CPU and
//! the wall time agree, and `cpu_seconds / floor_seconds` is how far the
//! solve is from its floor).
//!
//! The table is docs/performance.md's "Dense or matrix-free"; the
//! crossover sets `elcon_analysis::AUTO_DENSE_LIMIT`.

mod common;

use std::time::Instant;

use elcon::analysis::{ContactProblem, Method, Options};
use elcon::influence::{LatticeOperator, PointSet};
use elcon_fixtures::{benchmark, scenes};

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

/// One solve of [`one_size`] and its floor's measure: wall seconds,
/// CPU seconds, the floor (CPU seconds), and one preconditioner
/// application's CPU time in products.
struct Run {
    seconds: f64,
    cpu: f64,
    floor: f64,
    relative: f64,
}

/// One size, the peers' case: h = a / `cells` on the disk of 1.3 a, the
/// method `"auto"` picks for it. A matrix-free solve also reports its
/// operator products and its floor, the products times one product's
/// CPU seconds on the same threads (to compare with `cpu_seconds`). With
/// `repeat` above 1 the solve and the floor's measure take turns that
/// many times and the times printed are their medians (a machine whose
/// speed drifts from minute to minute moves both alike); each solve's
/// floor takes the unit costs measured on either side of it.
fn one_size(cells: f64, repeat: usize) {
    let hertz = benchmark::reference();
    let a = hertz.contact_radius();
    let mut runs: Vec<Run> = Vec::new();
    let mut peak = f64::NAN;
    let mut last = None;
    let mut previous = None;
    let options = Options {
        preconditioner: !std::env::args().any(|a| a == "--no-preconditioner"),
        ..Options::default()
    };
    let measure_floor = !std::env::args().any(|a| a == "--no-floor");
    for _ in 0..repeat.max(1) {
        let points = PointSet::grid_disk(a / cells, 1.3 * a).expect("grid");
        let dense = points.len() <= elcon::analysis::AUTO_DENSE_LIMIT;
        let (start, cpu_start) = (Instant::now(), common::cpu_seconds());
        let (build, method) = if dense {
            (ContactProblem::new as scenes::Build, Method::BlockPivoting)
        } else {
            (
                ContactProblem::lattice as scenes::Build,
                Method::ConjugateGradient,
            )
        };
        // The problem holds the points (a grid's, 2 bytes a point): no copy
        // of them is kept beside it, which the peak would count.
        let problem = benchmark::held(build, points);
        let sol = problem.solve(method, &options).expect("solve");
        let seconds = start.elapsed().as_secs_f64();
        let cpu = common::cpu_seconds() - cpu_start;
        // The first solve's peak, before the floor's products take a
        // workspace.
        if runs.is_empty() {
            peak = peak_rss_mb();
        }
        let after = if measure_floor {
            (
                product_seconds(&problem),
                preconditioner_seconds(problem.points(), sol.statistics.preconditionings()),
            )
        } else {
            (0.0, 0.0)
        };
        // The unit costs measured just before this solve (after the last
        // one) and just after it, averaged: a drift of the machine's speed
        // across the solve cancels to first order. The first solve has
        // only the measure after it.
        let before = previous.replace(after).unwrap_or(after);
        let (product, preconditioning) = (0.5 * (before.0 + after.0), 0.5 * (before.1 + after.1));
        let floor = sol.statistics.products() as f64 * product
            + sol.statistics.preconditionings() as f64 * preconditioning;
        let relative = if product > 0.0 {
            preconditioning / product
        } else {
            0.0
        };
        runs.push(Run {
            seconds,
            cpu,
            floor,
            relative,
        });
        last = Some((sol, method));
    }
    let (sol, method) = last.expect("one run at least");
    let median = |of: &dyn Fn(&Run) -> f64| {
        let mut v: Vec<f64> = runs.iter().map(of).collect();
        v.sort_by(f64::total_cmp);
        let m = v.len() / 2;
        if v.len() % 2 == 1 {
            v[m]
        } else {
            0.5 * (v[m - 1] + v[m])
        }
    };
    let (seconds, cpu) = (median(&|r| r.seconds), median(&|r| r.cpu));
    let (floor, relative) = (median(&|r| r.floor), median(&|r| r.relative));
    // Each repeat's time over its own floor, measured on either side of
    // it: the drift of the machine's speed between repeats cancels.
    let threads = rayon::current_num_threads();
    let times_floor = median(&|r| match (threads, r.floor > 0.0) {
        (_, false) => 0.0,
        (1, true) => r.seconds / r.floor,
        (_, true) => r.cpu / r.floor,
    });
    let n = sol.forces.len();
    let products = sol.statistics.products();
    let preconditionings = sol.statistics.preconditionings();
    let (corrections, columns) = (sol.statistics.corrections(), sol.statistics.columns());
    println!(
        "n={n} method={} seconds={seconds:.4} err_delta={:+.3e} certificate={:.1e} peak_rss_mb={:.1} products={products} corrections={corrections} columns={columns} floor_seconds={floor:.4} threads={} cpu_seconds={cpu:.2} iterations={} preconditioner_applications={preconditionings} preconditioner_products={:.3} repeat={} times_floor={times_floor:.3}",
        method.name(),
        sol.approach / hertz.approach() - 1.0,
        sol.certificate.worst(),
        peak,
        threads,
        sol.statistics.iterations(),
        relative,
        runs.len(),
    );
}

/// The CPU seconds (all threads) of one application of the lattice
/// operator's preconditioner on `points`, the mean over applications that
/// take at least [`FLOOR_CPU`] (0 when the solve applied none).
fn preconditioner_seconds(points: &PointSet, applications: usize) -> f64 {
    if applications == 0 {
        return 0.0;
    }
    let (body, _) = benchmark::bodies();
    let kernel = elcon::influence::LatticeKernel::new(points, &[&body, &body]).expect("lattice");
    let preconditioner = kernel
        .preconditioner()
        .expect("memory")
        .expect("a half-space kernel");
    let mut workspace = kernel.workspace().expect("memory");
    let n = points.len();
    let (r, mut z) = (vec![1.0; n], vec![0.0; n]);
    kernel.precondition_with(&r, &mut z, &preconditioner, &mut workspace);
    let (start, mut count) = (common::cpu_seconds(), 0);
    while common::cpu_seconds() - start < FLOOR_CPU {
        kernel.precondition_with(&r, &mut z, &preconditioner, &mut workspace);
        count += 1;
    }
    (common::cpu_seconds() - start) / count as f64
}

/// CPU seconds of products the floor's measure takes at least.
const FLOOR_CPU: f64 = 0.3;

/// The CPU seconds (all threads) of one product `S x` of `problem`'s
/// operator, the mean over products that take at least [`FLOOR_CPU`] (0
/// for a dense problem, whose solve reads S's entries).
fn product_seconds(problem: &ContactProblem) -> f64 {
    use elcon::lcp::{Operator, PodBuffer, PodStack};
    let products = problem.products();
    let n = products.size();
    let (x, mut y) = (vec![1.0; n], vec![0.0; n]);
    let mut scratch = PodBuffer::new(products.apply_scratch());
    products.apply(&x, &mut y, PodStack::new(&mut scratch));
    let (start, mut count) = (common::cpu_seconds(), 0);
    while common::cpu_seconds() - start < FLOOR_CPU {
        products.apply(&x, &mut y, PodStack::new(&mut scratch));
        count += 1;
    }
    (common::cpu_seconds() - start) / count as f64
}

fn main() {
    if let Some(threads) = std::env::args()
        .skip_while(|a| a != "--threads")
        .nth(1)
        .and_then(|v| v.parse::<usize>().ok())
    {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .expect("the thread pool");
    }
    if let Some(k) = std::env::args()
        .skip_while(|a| a != "--h-over-a")
        .nth(1)
        .and_then(|v| v.parse::<f64>().ok())
    {
        let repeat = std::env::args()
            .skip_while(|a| a != "--repeat")
            .nth(1)
            .and_then(|v| v.parse::<usize>().ok())
            .unwrap_or(1);
        one_size(k, repeat);
        return;
    }
    let max: f64 = std::env::args()
        .skip_while(|a| a != "--max")
        .nth(1)
        .and_then(|v| v.parse().ok())
        .unwrap_or(128.0);
    let (hertz, (body, _)) = (benchmark::reference(), benchmark::bodies());
    let a = hertz.contact_radius();
    println!(
        "| cells per radius | N | dense: assembly + block pivoting, CPU s | dense S, MB | matrix-free: operator + CG, CPU s | CG iterations | operator, MB | approach error | peak error | CG certificate |"
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
            let start = common::cpu_seconds();
            let sol = benchmark::held(ContactProblem::new, points.clone())
                .solve(Method::BlockPivoting, &Options::default())
                .expect("dense solve");
            Some((common::cpu_seconds() - start, sol.approach))
        } else {
            None
        };
        let operator_bytes =
            LatticeOperator::estimate_bytes(&points, &[&body, &body]).expect("lattice");
        let start = common::cpu_seconds();
        let sol = benchmark::held(ContactProblem::lattice, points)
            .solve(Method::ConjugateGradient, &Options::default())
            .expect("matrix-free solve");
        let seconds = common::cpu_seconds() - start;
        if let Some((_, approach)) = dense {
            assert!(
                (approach / sol.approach - 1.0).abs() < 1e-8,
                "the two agree"
            );
        }
        println!(
            "| {cells} | {n} | {} | {} | {seconds:.2} | {} | {:.1} | {:+.2e} | {:+.2e} | {:.1e} |",
            dense.map_or("-".into(), |(s, _)| format!("{s:.2}")),
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

/// A peer's stored runs in the fitted box (docs/peers/*-fitted.md): (cells
/// of its square grid, setup + solve CPU seconds: the solve's wall time
/// times its `cpu/wall`, as the machine's other work inflates the wall
/// time of each system differently).
fn peer(path: &str) -> Vec<(f64, f64)> {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .lines()
        .filter(|l| l.starts_with('{'))
        .filter_map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).ok()?;
            let n = v["n"].as_f64()?;
            let cpu = v["cpu/wall"].as_f64()?;
            Some((
                n * n,
                (v["t_setup_s"].as_f64()? + v["t_solve_s"].as_f64()?) * cpu,
            ))
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
            "Tamaas, fitted box (docs/peers/tamaas-fitted.md)",
            peer("docs/peers/tamaas-fitted.md"),
        ),
        (
            "ContactMechanics, fitted box (docs/peers/cm-fitted.md)",
            peer("docs/peers/cm-fitted.md"),
        ),
    ];
    // CPU seconds come in clock ticks of 10 ms: a run under one tick has
    // no measured time and is left out rather than drawn at zero.
    let series = series.map(|(name, s)| {
        (
            name,
            s.into_iter().filter(|p| p.1 >= 0.01).collect::<Vec<_>>(),
        )
    });
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
            .y_desc("CPU seconds (assembly or setup, and solve)")
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
