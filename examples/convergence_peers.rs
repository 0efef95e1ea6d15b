//! The convergence batch's error against run time with the peers' points
//! on the same axes: elcon's three methods from a `batch` run of
//! examples/scenes/convergence.toml, Tamaas and ContactMechanics from their
//! stored runs in docs/peers/ (the same Hertz spheres on Love patches, the
//! FFT-based peers' square domain 4a wide, h = a/16 and a/32; their times
//! are setup plus solve, measured on the machine docs/peers/env.txt
//! describes), and beside elcon's true error its estimated discretization
//! error (result.json's `discretization`: the approach and the peak
//! pressure have one).
//!
//! Run, from the checkout:
//!
//! ```sh
//! cargo run --release -- batch examples/scenes/convergence.toml --out out --jobs 1
//! cargo run --release --example convergence_peers -- [--error max_pressure|approach|pressure_l2] [--out docs/img/convergence-error-time.svg]
//! ```

use std::error::Error;
use std::path::PathBuf;

/// A peer's stored runs: one JSON object per line of its docs/peers file.
fn peer(path: &str, error: &str) -> Result<Vec<(f64, f64)>, Box<dyn Error>> {
    let key = match error {
        "pressure_l2" => "err_L2",
        "approach" => "err_delta",
        "max_pressure" => "err_p0",
        "contact_extent" => "err_a",
        other => return Err(format!("no peer error for {other}").into()),
    };
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut points = Vec::new();
    for line in text.lines().filter(|l| l.starts_with('{')) {
        let v: serde_json::Value = serde_json::from_str(line)?;
        let t = v["t_setup_s"].as_f64().unwrap_or(0.0) + v["t_solve_s"].as_f64().unwrap_or(0.0);
        if let Some(e) = v[key].as_f64() {
            points.push((t, e.abs()));
        }
    }
    Ok(points)
}

fn main() -> Result<(), Box<dyn Error>> {
    let (mut error, mut out) = (
        "max_pressure".to_string(),
        PathBuf::from("docs/img/convergence-error-time.svg"),
    );
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match (flag.as_str(), it.next()) {
            ("--error", Some(e)) => error = e,
            ("--out", Some(o)) => out = PathBuf::from(o),
            _ => return Err(format!("unknown option {flag} (--error, --out)").into()),
        }
    }
    let results: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string("out/convergence/results.json")
            .map_err(|e| format!("out/convergence/results.json: {e} (run the batch first)"))?,
    )?;
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for row in results["rows"]
        .as_array()
        .ok_or("results.json has no rows")?
    {
        let (Some(m), Some(t), Some(e)) = (
            row["method"].as_str(),
            row["seconds_total"].as_f64(),
            row[format!("error_{error}").as_str()].as_f64(),
        ) else {
            continue;
        };
        let name = format!("elcon {m}");
        match series.iter_mut().find(|(n, _)| *n == name) {
            Some((_, pts)) => pts.push((t, e.abs())),
            None => series.push((name, vec![(t, e.abs())])),
        }
        // The estimated discretization error beside the true one (every
        // method has the same solution, so one method's estimate).
        if m == "block-pivoting"
            && let Some(est) = row[format!("estimated_error_{error}").as_str()].as_f64()
        {
            let name = "elcon's estimate (block-pivoting)".to_string();
            match series.iter_mut().find(|(n, _)| *n == name) {
                Some((_, pts)) => pts.push((t, est)),
                None => series.push((name, vec![(t, est)])),
            }
        }
    }
    for (name, path) in [
        ("Tamaas (PKR, dcfft)", "docs/peers/tamaas.md"),
        ("ContactMechanics (CG)", "docs/peers/cm.md"),
    ] {
        series.push((name.to_string(), peer(path, &error)?));
    }
    let svg = elcon::report::error_time(
        "Hertz spheres: error against run time, elcon and the peers",
        &error,
        &series,
    )?;
    elcon::process::write_atomic(&out, svg.as_bytes())?;
    for (name, pts) in &series {
        println!("{name}: {} points", pts.len());
    }
    println!("wrote {}", out.display());
    Ok(())
}
