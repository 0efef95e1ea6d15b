//! A batch's tables.
//!
//! In `<out>/<batch>/` (or `<batch>-shard-K-of-N`): results.json (a row
//! per run, by index, with the batch's hash and size), results.csv,
//! results.md and, where the runs have a closed-form reference,
//! error-time.svg (the chosen error against run time, log-log, one series
//! per method). docs/results.md lists the fields.

use std::fmt::Write as _;
use std::path::Path;

use serde::{Deserialize, Serialize};

use elcon_process::write_atomic;
use elcon_scene::ErrorMetric;

use elcon_analysis::Method;

use crate::discretization::VerdictJson;
use crate::error::ReportError;
use crate::result::RunResult;

/// A finished run's status.
const OK: &str = "ok";

/// One row of a batch's results table (the default: every value absent).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// Run index in the expanded sweep.
    pub index: usize,
    /// The overrides, `key=value, ...`.
    pub overrides: String,
    /// The run's scene name.
    pub scene: String,
    /// "ok" or "failed: reason".
    pub status: String,
    /// The method.
    pub method: Option<Method>,
    /// Candidate points N.
    pub points: Option<usize>,
    /// Pivots (index exchanges for block pivoting).
    pub pivots: Option<usize>,
    /// Assembly + solve + reference + design seconds.
    pub seconds_total: Option<f64>,
    /// Solve seconds.
    pub seconds_solve: Option<f64>,
    /// Approach (length).
    pub approach: Option<f64>,
    /// Largest pressure (intensity).
    pub max_pressure: Option<f64>,
    /// Worst certificate residual.
    pub certificate_worst: Option<f64>,
    /// Relative error of the approach.
    pub error_approach: Option<f64>,
    /// Relative error of the peak pressure.
    pub error_max_pressure: Option<f64>,
    /// Relative error of the contact extent.
    pub error_contact_extent: Option<f64>,
    /// L2 error of the pressure.
    pub error_pressure_l2: Option<f64>,
    /// Relative error of the load.
    pub error_load: Option<f64>,
    /// The approach's estimated discretization error, relative (converging
    /// or exact: result.json's `discretization`).
    #[serde(default)]
    pub estimated_error_approach: Option<f64>,
    /// The estimate's verdict for the approach.
    #[serde(default)]
    pub verdict_approach: Option<VerdictJson>,
    /// The peak pressure's estimated discretization error, relative.
    #[serde(default)]
    pub estimated_error_max_pressure: Option<f64>,
    /// The estimate's verdict for the peak pressure.
    #[serde(default)]
    pub verdict_max_pressure: Option<VerdictJson>,
    /// Iterations (block pivoting's blocks, the conjugate gradient's
    /// steps: the work of a method that spends no pivots).
    #[serde(default)]
    pub iterations: Option<usize>,
}

impl Row {
    /// The row of a run that finished, from its result: the same whether
    /// the result was just made or read back from its result.json (floats
    /// round-trip), so a row made as the run ends, one rebuilt from its
    /// directory on a resume and one merge checks agree to the last digit.
    pub fn ok(index: usize, overrides: String, r: &RunResult) -> Self {
        let errors = r.reference.as_ref().map(|x| &x.errors);
        let quantities = r.discretization.as_ref().map(|d| &d.quantities);
        Self {
            index,
            overrides,
            scene: r.scene.clone(),
            status: OK.into(),
            method: Some(r.header.method),
            points: Some(r.header.points),
            pivots: Some(r.header.statistics.pivots),
            iterations: Some(r.header.statistics.iterations),
            seconds_total: Some(r.seconds.total),
            seconds_solve: Some(r.seconds.solve),
            approach: Some(r.approach),
            max_pressure: Some(r.max_pressure),
            certificate_worst: Some(r.certificate.worst),
            error_approach: errors.and_then(|e| e.approach),
            error_max_pressure: errors.and_then(|e| e.max_pressure),
            error_contact_extent: errors.and_then(|e| e.contact_extent),
            error_pressure_l2: errors.and_then(|e| e.pressure_l2),
            error_load: errors.and_then(|e| e.load),
            estimated_error_approach: quantities.and_then(|q| q.approach.relative_error),
            verdict_approach: quantities.map(|q| q.approach.verdict),
            estimated_error_max_pressure: quantities.and_then(|q| q.max_pressure.relative_error),
            verdict_max_pressure: quantities.map(|q| q.max_pressure.verdict),
        }
    }

    /// Whether its run finished (`status` is "ok").
    pub fn is_ok(&self) -> bool {
        self.status == OK
    }

    /// The row of run `index` that failed with `e`.
    pub fn failed(
        index: usize,
        overrides: String,
        scene: String,
        e: &impl std::fmt::Display,
    ) -> Self {
        Self {
            index,
            overrides,
            scene,
            status: format!("failed: {e}"),
            ..Self::default()
        }
    }

    fn error(&self, metric: ErrorMetric) -> Option<f64> {
        match metric {
            ErrorMetric::Approach => self.error_approach,
            ErrorMetric::MaxPressure => self.error_max_pressure,
            ErrorMetric::ContactExtent => self.error_contact_extent,
            ErrorMetric::PressureL2 => self.error_pressure_l2,
            ErrorMetric::Load => self.error_load,
        }
    }

    /// The estimated discretization error of `metric`, where the row has
    /// one (the approach and the peak pressure).
    fn estimated(&self, metric: ErrorMetric) -> Option<f64> {
        match metric {
            ErrorMetric::Approach => self.estimated_error_approach,
            ErrorMetric::MaxPressure => self.estimated_error_max_pressure,
            _ => None,
        }
    }

    /// The estimated error as the Markdown table shows it: `1.2e-3`,
    /// `exact`, `n.r.` (not resolved), or empty.
    fn estimated_cell(error: Option<f64>, verdict: Option<VerdictJson>) -> String {
        match (verdict, error) {
            (Some(VerdictJson::Converging), None) | (Some(VerdictJson::NotEstimated) | None, _) => {
                String::new()
            }
            (Some(v), error) => v.short(error),
        }
    }
}

/// What results.json holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BatchOutcome {
    /// The batch's name.
    pub batch: String,
    /// The metric plotted against run time.
    pub error: ErrorMetric,
    /// The shard, "K/N", if one.
    pub shard: Option<String>,
    /// The batch's hash (elcon-runner's `Batch::hash`): shards of one batch share it.
    #[serde(default)]
    pub batch_hash: Option<String>,
    /// Runs of the whole sweep (all shards together).
    #[serde(default)]
    pub runs: Option<usize>,
    /// Runs of this table's slice that did not finish (an interrupted
    /// batch: running it again finishes them); absent when 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub pending: usize,
    /// One row per run, failed ones included, by index.
    pub rows: Vec<Row>,
}

impl BatchOutcome {
    /// The number of failed runs.
    pub fn failures(&self) -> usize {
        self.rows.iter().filter(|r| !r.is_ok()).count()
    }
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x:e}"))
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// results.json, results.csv, results.md and error-time.svg.
pub fn write_tables(o: &BatchOutcome, dir: &Path) -> Result<(), ReportError> {
    let json = serde_json::to_string_pretty(o).map_err(|e| ReportError::Json {
        path: dir.join("results.json"),
        reason: e.to_string(),
    })?;
    write_atomic(&dir.join("results.json"), json.as_bytes())?;
    let mut csv = String::from(
        "index,overrides,scene,status,method,points,pivots,seconds_total,seconds_solve,approach,max_pressure,\
         certificate_worst,error_approach,error_max_pressure,error_contact_extent,error_pressure_l2,error_load,\
         estimated_error_approach,verdict_approach,estimated_error_max_pressure,verdict_max_pressure,iterations\n",
    );
    let mut md = format!(
        "# Batch `{}`\n\n| # | overrides | method | N | pivots | iterations | seconds | certificate | error ({}) | est. error (peak) | est. error (approach) | status |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        o.batch, o.error
    );
    for r in &o.rows {
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.index,
            csv_field(&r.overrides),
            csv_field(&r.scene),
            csv_field(&r.status),
            r.method.map(Method::name).unwrap_or_default(),
            r.points.map_or(String::new(), |n| n.to_string()),
            r.pivots.map_or(String::new(), |n| n.to_string()),
            opt(r.seconds_total),
            opt(r.seconds_solve),
            opt(r.approach),
            opt(r.max_pressure),
            opt(r.certificate_worst),
            opt(r.error_approach),
            opt(r.error_max_pressure),
            opt(r.error_contact_extent),
            opt(r.error_pressure_l2),
            opt(r.error_load),
            opt(r.estimated_error_approach),
            csv_field(
                r.verdict_approach
                    .map(VerdictJson::name)
                    .unwrap_or_default()
            ),
            opt(r.estimated_error_max_pressure),
            csv_field(
                r.verdict_max_pressure
                    .map(VerdictJson::name)
                    .unwrap_or_default()
            ),
            r.iterations.map_or(String::new(), |n| n.to_string()),
        );
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.index,
            r.overrides,
            r.method.map(Method::name).unwrap_or_default(),
            r.points.map_or(String::new(), |n| n.to_string()),
            r.pivots.map_or(String::new(), |n| n.to_string()),
            r.iterations.map_or(String::new(), |n| n.to_string()),
            r.seconds_total.map_or(String::new(), |s| format!("{s:.4}")),
            r.certificate_worst
                .map_or(String::new(), |c| format!("{c:.1e}")),
            r.error(o.error)
                .map_or(String::new(), |e| format!("{e:+.3e}")),
            Row::estimated_cell(r.estimated_error_max_pressure, r.verdict_max_pressure),
            Row::estimated_cell(r.estimated_error_approach, r.verdict_approach),
            r.status.replace('|', "/").replace('\n', " "),
        );
    }
    write_atomic(&dir.join("results.csv"), csv.as_bytes())?;
    write_atomic(&dir.join("results.md"), md.as_bytes())?;
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for r in &o.rows {
        if let (Some(m), Some(t), Some(e)) = (&r.method, r.seconds_total, r.error(o.error)) {
            match series.iter_mut().find(|(name, _)| name == m.name()) {
                Some((_, pts)) => pts.push((t, e.abs())),
                None => series.push((m.to_string(), vec![(t, e.abs())])),
            }
        }
    }
    // Each method's estimated error beside its true one, where the metric
    // has an estimate.
    for r in &o.rows {
        if let (Some(m), Some(t), Some(e)) = (&r.method, r.seconds_total, r.estimated(o.error)) {
            let name = format!("{m} (estimated)");
            match series.iter_mut().find(|(n, _)| *n == name) {
                Some((_, pts)) => pts.push((t, e)),
                None => series.push((name, vec![(t, e)])),
            }
        }
    }
    if !series.is_empty() {
        let title = format!("{}: error against run time", o.batch);
        if let Ok(svg) = crate::plot::error_time(&title, o.error.name(), &series) {
            write_atomic(&dir.join("error-time.svg"), svg.as_bytes())?;
        }
    }
    Ok(())
}
