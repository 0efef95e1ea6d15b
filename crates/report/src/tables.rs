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

use crate::error::ReportError;
use crate::result::RunResult;

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
    pub method: Option<String>,
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
    pub verdict_approach: Option<String>,
    /// The peak pressure's estimated discretization error, relative.
    #[serde(default)]
    pub estimated_error_max_pressure: Option<f64>,
    /// The estimate's verdict for the peak pressure.
    #[serde(default)]
    pub verdict_max_pressure: Option<String>,
    /// Iterations (block pivoting's blocks, the conjugate gradient's
    /// steps: the work of a method that spends no pivots).
    #[serde(default)]
    pub iterations: Option<usize>,
}

impl Row {
    /// The row of a run that finished: read from its result.json as
    /// written ([`Row::from_result_json`]), so a row made as the run ends,
    /// one rebuilt from its directory on a resume and one merge checks are
    /// the same to the last digit.
    pub fn ok(index: usize, overrides: String, r: &RunResult) -> Self {
        let value = serde_json::to_value(r).unwrap_or_default();
        Self::from_result_json(index, overrides, &value).unwrap_or_else(|e| Self {
            index,
            scene: r.scene.clone(),
            status: format!("failed: result.json: {e}"),
            ..Self::default()
        })
    }

    /// The row of run `index` from its result.json (parsed).
    ///
    /// # Errors
    /// The first field result.json lacks or holds with the wrong type.
    pub fn from_result_json(
        index: usize,
        overrides: String,
        v: &serde_json::Value,
    ) -> Result<Self, String> {
        let at = |path: &str| path.split('.').try_fold(v, |v, k| v.get(k));
        let num = |path: &str| at(path).and_then(serde_json::Value::as_f64);
        let need = |path: &str| num(path).ok_or_else(|| format!("no number `{path}`"));
        let count = |path: &str| {
            at(path)
                .and_then(serde_json::Value::as_u64)
                .map(|n| n as usize)
                .ok_or_else(|| format!("no count `{path}`"))
        };
        let text = |path: &str| at(path).and_then(|s| s.as_str().map(str::to_string));
        Ok(Self {
            index,
            overrides,
            scene: text("scene").ok_or("no `scene`")?,
            status: "ok".into(),
            method: Some(text("method").ok_or("no `method`")?),
            points: Some(count("points")?),
            pivots: Some(count("statistics.pivots")?),
            iterations: Some(count("statistics.iterations")?),
            seconds_total: Some(need("seconds.total")?),
            seconds_solve: Some(need("seconds.solve")?),
            approach: Some(need("approach")?),
            max_pressure: Some(need("max_pressure")?),
            certificate_worst: Some(need("certificate.worst")?),
            error_approach: num("reference.errors.approach"),
            error_max_pressure: num("reference.errors.max_pressure"),
            error_contact_extent: num("reference.errors.contact_extent"),
            error_pressure_l2: num("reference.errors.pressure_l2"),
            error_load: num("reference.errors.load"),
            estimated_error_approach: num("discretization.quantities.approach.relative_error"),
            verdict_approach: text("discretization.quantities.approach.verdict"),
            estimated_error_max_pressure: num(
                "discretization.quantities.max_pressure.relative_error",
            ),
            verdict_max_pressure: text("discretization.quantities.max_pressure.verdict"),
        })
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
    /// `exact`, `n.c.` (not converging), or empty.
    fn estimated_cell(error: Option<f64>, verdict: Option<&String>) -> String {
        match verdict.map(String::as_str) {
            Some("exact") => "exact".into(),
            Some("not converging") => "n.c.".into(),
            Some("converging") => error.map_or(String::new(), |e| format!("{e:.1e}")),
            _ => String::new(),
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
        self.rows.iter().filter(|r| r.status != "ok").count()
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
            r.method.clone().unwrap_or_default(),
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
            csv_field(r.verdict_approach.as_deref().unwrap_or_default()),
            opt(r.estimated_error_max_pressure),
            csv_field(r.verdict_max_pressure.as_deref().unwrap_or_default()),
            r.iterations.map_or(String::new(), |n| n.to_string()),
        );
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.index,
            r.overrides,
            r.method.clone().unwrap_or_default(),
            r.points.map_or(String::new(), |n| n.to_string()),
            r.pivots.map_or(String::new(), |n| n.to_string()),
            r.iterations.map_or(String::new(), |n| n.to_string()),
            r.seconds_total.map_or(String::new(), |s| format!("{s:.4}")),
            r.certificate_worst
                .map_or(String::new(), |c| format!("{c:.1e}")),
            r.error(o.error)
                .map_or(String::new(), |e| format!("{e:+.3e}")),
            Row::estimated_cell(
                r.estimated_error_max_pressure,
                r.verdict_max_pressure.as_ref()
            ),
            Row::estimated_cell(r.estimated_error_approach, r.verdict_approach.as_ref()),
            r.status.replace('|', "/").replace('\n', " "),
        );
    }
    write_atomic(&dir.join("results.csv"), csv.as_bytes())?;
    write_atomic(&dir.join("results.md"), md.as_bytes())?;
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for r in &o.rows {
        if let (Some(m), Some(t), Some(e)) = (&r.method, r.seconds_total, r.error(o.error)) {
            match series.iter_mut().find(|(name, _)| name == m) {
                Some((_, pts)) => pts.push((t, e.abs())),
                None => series.push((m.clone(), vec![(t, e.abs())])),
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
