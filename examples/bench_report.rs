//! The scaling benchmark's report: reads criterion's estimates
//! (target/criterion/scaling/<method>/<N>/new/estimates.json) and the pivot
//! counts the bench wrote (target/criterion/elcon-scaling-<N>.json), and
//! prints a Markdown table (time, pivots, time per pivot, effective GFLOP/s,
//! ratio to the Cholesky of S) and each method's fitted exponent of time
//! against N; writes the log-log plot to docs/img/scaling.svg.
//!
//! Effective GFLOP/s: for the tableau methods, pivots x 2 x rows x columns
//! (the work of the rank-1 updates, delayed or not) over the time, and for
//! a tableau method that finished on the symmetric tableau (recorded
//! `symmetric_tableau`) pivots x N^2 (the lower triangle's);
//! for block pivoting and the Cholesky, N^3 / 3 (one Cholesky of S) over
//! the time.
//!
//! Run after `cargo bench --bench scaling`:
//! `cargo run --release --example bench_report`

use std::collections::BTreeMap;
use std::path::Path;

use plotters::prelude::*;

const SERIES: [&str; 5] = [
    "restricted-simplex",
    "lemke",
    "block-pivoting",
    "cholesky",
    "assembly",
];

fn mean_seconds(dir: &Path, series: &str, n: usize) -> Option<f64> {
    let path = dir
        .join("scaling")
        .join(series)
        .join(n.to_string())
        .join("new/estimates.json");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()?;
    v["mean"]["point_estimate"].as_f64().map(|ns| ns * 1e-9)
}

/// Least-squares slope of log t against log N.
fn exponent(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 2 {
        return None;
    }
    let xs: Vec<f64> = points.iter().map(|p| p.0.ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    let (mx, my) = (
        xs.iter().sum::<f64>() / xs.len() as f64,
        ys.iter().sum::<f64>() / ys.len() as f64,
    );
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    Some(sxy / sxx)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("target/criterion");
    let records = read_records(&dir)?;
    let mut sizes: Vec<usize> = records.keys().map(|k| k.1).collect();
    sizes.sort_unstable();
    sizes.dedup();
    if sizes.is_empty() {
        return Err("no benchmark results: run `cargo bench --bench scaling` first".into());
    }
    let curves = print_times(&dir, &sizes, &records);
    print_exponents(&curves);
    let out = root.join("docs/img/scaling.svg");
    plot(&out, &sizes, &curves)?;
    println!();
    println!("wrote {}", out.display());
    Ok(())
}

/// The records the bench wrote (elcon-scaling-<N>.json under `dir`), by
/// method and N.
fn read_records(
    dir: &Path,
) -> Result<BTreeMap<(String, usize), serde_json::Value>, Box<dyn std::error::Error>> {
    let mut records = BTreeMap::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if name.starts_with("elcon-scaling-") && name.ends_with(".json") {
            let list: Vec<serde_json::Value> =
                serde_json::from_str(&std::fs::read_to_string(&path)?)?;
            for r in list {
                let key = (
                    r["method"].as_str().unwrap_or("").to_string(),
                    r["n"].as_u64().unwrap_or(0) as usize,
                );
                records.insert(key, r);
            }
        }
    }
    Ok(records)
}

/// Prints the table of times, one row per series and size; returns each
/// series' (N, seconds).
fn print_times(
    dir: &Path,
    sizes: &[usize],
    records: &BTreeMap<(String, usize), serde_json::Value>,
) -> BTreeMap<&'static str, Vec<(f64, f64)>> {
    println!(
        "| method | N | seconds | pivots (iterations) | us / pivot | effective GFLOP/s | / Cholesky |"
    );
    println!("|---|---|---|---|---|---|---|");
    let mut curves: BTreeMap<&str, Vec<(f64, f64)>> = BTreeMap::new();
    for &n in sizes {
        let chol = mean_seconds(dir, "cholesky", n);
        for series in SERIES {
            let Some(t) = mean_seconds(dir, series, n) else {
                continue;
            };
            curves.entry(series).or_default().push((n as f64, t));
            let (pivots, gflops) =
                pivots_and_gflops(records.get(&(series.to_string(), n)), series, n, t);
            println!(
                "| {series} | {n} | {t:.3e} | {} | {} | {} | {} |",
                pivots.as_ref().map_or("-".into(), |p| p.1.clone()),
                pivots
                    .as_ref()
                    .map_or("-".into(), |p| format!("{:.2}", 1e6 * t / p.0.max(1.0))),
                if gflops.is_finite() {
                    format!("{gflops:.1}")
                } else {
                    "-".into()
                },
                chol.map_or("-".into(), |c| format!("{:.2}", t / c)),
            );
        }
    }
    curves
}

/// The pivots of `series` at `n` (the count and its label, with the
/// iterations where there are some) from its `record`, and its effective
/// GFLOP/s at `t` seconds.
fn pivots_and_gflops(
    record: Option<&serde_json::Value>,
    series: &str,
    n: usize,
    t: f64,
) -> (Option<(f64, String)>, f64) {
    let cube = (n as f64).powi(3) / 3.0;
    match record {
        Some(r) => {
            let p = r["pivots"].as_u64().unwrap_or(0) as f64;
            let rows = r["tableau_rows"].as_u64().unwrap_or(0) as f64;
            let cols = r["tableau_columns"].as_u64().unwrap_or(0) as f64;
            // The symmetric tableau (`Statistics::symmetric_tableau`)
            // updates only the lower triangle of its N x N swept
            // matrix: N^2 flops a pivot.
            let symmetric = r["symmetric_tableau"].as_bool() == Some(true);
            let work = if symmetric {
                p * rows * rows
            } else if rows > 0.0 {
                p * 2.0 * rows * cols
            } else {
                cube
            };
            let it = r["iterations"].as_u64().unwrap_or(0);
            let label = if it > 0 {
                format!("{p} ({it})")
            } else {
                format!("{p}")
            };
            (Some((p, label)), work / t * 1e-9)
        }
        None if series == "cholesky" => (None, cube / t * 1e-9),
        None => (None, f64::NAN),
    }
}

/// Prints each series' fitted exponent of time against N.
fn print_exponents(curves: &BTreeMap<&str, Vec<(f64, f64)>>) {
    println!();
    println!("| method | fitted exponent of time against N (N >= 500) | (all N) |");
    println!("|---|---|---|");
    for (series, points) in curves {
        let large: Vec<(f64, f64)> = points.iter().copied().filter(|p| p.0 >= 500.0).collect();
        println!(
            "| {series} | {} | {} |",
            exponent(&large).map_or("-".into(), |e| format!("{e:.2}")),
            exponent(points).map_or("-".into(), |e| format!("{e:.2}"))
        );
    }
}

/// The log-log plot of time against N, each series a line with its points,
/// to `out`.
fn plot(
    out: &Path,
    sizes: &[usize],
    curves: &BTreeMap<&str, Vec<(f64, f64)>>,
) -> Result<(), Box<dyn std::error::Error>> {
    let (n0, n1) = (
        sizes[0] as f64 / 1.3,
        *sizes.last().expect("sizes") as f64 * 1.3,
    );
    let all: Vec<f64> = curves.values().flatten().map(|p| p.1).collect();
    let (t0, t1) = all
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &t| (a.min(t), b.max(t)));
    let root_area = SVGBackend::new(out, (900, 560)).into_drawing_area();
    root_area.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root_area)
        .caption(
            "Hertz spheres on Love patches: time against N",
            ("sans-serif", 22),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d((n0..n1).log_scale(), (t0 / 1.5..t1 * 1.5).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("candidate points N")
        .y_desc("seconds")
        .draw()?;
    let colors = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(0, 0, 0),
        RGBColor(150, 150, 150),
    ];
    for (i, series) in SERIES.iter().enumerate() {
        let Some(points) = curves.get(series) else {
            continue;
        };
        let color = colors[i];
        let style = if *series == "cholesky" {
            color.stroke_width(3)
        } else {
            color.stroke_width(2)
        };
        chart
            .draw_series(LineSeries::new(points.clone(), style))?
            .label(if *series == "cholesky" {
                "faer Cholesky of S (floor)".to_string()
            } else {
                series.to_string()
            })
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart.draw_series(
            points
                .iter()
                .map(move |&p| Circle::new(p, 3, color.filled())),
        )?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root_area.present()?;
    Ok(())
}
