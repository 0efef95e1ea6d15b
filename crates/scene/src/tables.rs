//! A batch's tables, and `elcon merge`, which joins the tables of a
//! batch's shards after checking that they are the shards of one batch,
//! each once, together every run once.
//!
//! In `<out>/<batch>/` (or `<batch>-shard-K-of-N`): results.json (a row
//! per run, by index, with the batch's hash and size), results.csv,
//! results.md and, where the runs have a closed-form reference,
//! error-time.svg (the chosen error against run time, log-log, one series
//! per method). docs/results.md lists the fields.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::SceneError;
use crate::output::{Staging, write_atomic};
use crate::run::RunResult;
use crate::schema::ErrorMetric;

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
    pub(crate) fn ok(index: usize, overrides: String, r: &RunResult) -> Self {
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
    pub(crate) fn from_result_json(
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

    pub(crate) fn failed(index: usize, overrides: String, scene: String, e: &SceneError) -> Self {
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
    /// The batch's hash ([`crate::Batch::hash`]): shards of one batch share it.
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

/// One shard directory's table, read.
struct Part {
    dir: PathBuf,
    table: BatchOutcome,
    shard: Option<(usize, usize)>,
}

fn merge_error(what: impl Into<String>) -> SceneError {
    SceneError::Merge {
        reason: what.into(),
    }
}

/// Reads `dir/results.json`.
fn read_part(dir: &Path) -> Result<Part, SceneError> {
    let path = dir.join("results.json");
    let text = std::fs::read_to_string(&path).map_err(|e| SceneError::io(&path, e))?;
    let table: BatchOutcome = serde_json::from_str(&text).map_err(|e| SceneError::io(&path, e))?;
    let shard = match &table.shard {
        None => None,
        Some(s) => {
            let parsed = s
                .parse::<crate::Shard>()
                .map_err(|e| merge_error(format!("{}: shard {e}", path.display())))?;
            Some((parsed.index, parsed.count))
        }
    };
    if table.pending > 0 {
        return Err(merge_error(format!(
            "{}: unfinished: {} of its runs did not run (the batch was interrupted); run the same \
             `elcon batch` command again to finish it",
            path.display(),
            table.pending
        )));
    }
    if table.batch_hash.is_none() || table.runs.is_none() {
        return Err(merge_error(format!(
            "{}: has no batch hash or sweep size (written by an older elcon): run the shards again",
            path.display()
        )));
    }
    Ok(Part {
        dir: dir.to_path_buf(),
        table,
        shard,
    })
}

/// Checks that `parts` are every shard of one batch, once each.
fn check_parts(parts: &[Part]) -> Result<(usize, usize), SceneError> {
    let first = &parts[0];
    for p in &parts[1..] {
        if p.table.batch != first.table.batch {
            return Err(merge_error(format!(
                "{} is from batch `{}`, {} from batch `{}`",
                p.dir.display(),
                p.table.batch,
                first.dir.display(),
                first.table.batch
            )));
        }
        if p.table.batch_hash != first.table.batch_hash || p.table.runs != first.table.runs {
            return Err(merge_error(format!(
                "{} and {} are from different versions of batch `{}` (the batch file or its base \
                 scene changed between the shards: hashes differ); run every shard from the same files",
                p.dir.display(),
                first.dir.display(),
                p.table.batch
            )));
        }
    }
    let runs = first.table.runs.unwrap_or(0);
    let count = first.shard.map_or(1, |(_, n)| n);
    let mut seen: BTreeMap<usize, &Path> = BTreeMap::new();
    for p in parts {
        let (k, n) = p.shard.unwrap_or((1, 1));
        if n != count || p.shard.is_some() != first.shard.is_some() {
            return Err(merge_error(format!(
                "shard counts differ: {} is {}, {} is {}",
                p.dir.display(),
                p.table.shard.as_deref().unwrap_or("the whole batch"),
                first.dir.display(),
                first.table.shard.as_deref().unwrap_or("the whole batch"),
            )));
        }
        if let Some(other) = seen.insert(k, &p.dir) {
            return Err(merge_error(format!(
                "shard {k}/{count} is given twice: {} and {}",
                other.display(),
                p.dir.display()
            )));
        }
    }
    let missing: Vec<String> = (1..=count)
        .filter(|k| !seen.contains_key(k))
        .map(|k| format!("{k}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(merge_error(format!(
            "shards missing: {} (every shard of the batch is needed)",
            missing.join(", ")
        )));
    }
    Ok((runs, count))
}

/// Checks that each part's rows are its shard's runs, each once.
fn check_rows(parts: &[Part], runs: usize, count: usize) -> Result<(), SceneError> {
    let mut owner: BTreeMap<usize, &Path> = BTreeMap::new();
    for p in parts {
        let k = p.shard.map_or(1, |(k, _)| k);
        for r in &p.table.rows {
            if r.index >= runs || r.index % count != k - 1 {
                return Err(merge_error(format!(
                    "{}: row {} does not belong to shard {k}/{count} of a sweep of {runs} runs",
                    p.dir.display(),
                    r.index
                )));
            }
            if let Some(other) = owner.insert(r.index, &p.dir) {
                return Err(merge_error(format!(
                    "two rows with index {}: in {} and in {}",
                    r.index,
                    other.display(),
                    p.dir.display()
                )));
            }
        }
        let expected = crate::Shard { index: k, count }.len_of(runs);
        if p.table.rows.len() != expected {
            return Err(merge_error(format!(
                "{}: {} rows, but shard {k}/{count} of {runs} runs has {expected}",
                p.dir.display(),
                p.table.rows.len()
            )));
        }
    }
    Ok(())
}

/// Checks that each finished row holds the values of its run's own
/// result.json (in the run's directory beside the table): a table edited
/// by hand, or of a run whose directory was replaced, is refused.
fn check_values(parts: &[Part]) -> Result<(), SceneError> {
    for p in parts {
        for r in p.table.rows.iter().filter(|r| r.status == "ok") {
            let plain =
                !r.scene.is_empty() && !r.scene.starts_with('.') && !r.scene.contains(['/', '\\']);
            let path = p.dir.join(&r.scene).join("result.json");
            let rebuilt = plain
                .then(|| std::fs::read_to_string(&path).ok())
                .flatten()
                .ok_or_else(|| format!("its run's {} cannot be read", path.display()))
                .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()))
                .and_then(|v| Row::from_result_json(r.index, r.overrides.clone(), &v));
            let differs = match rebuilt {
                Ok(own) if own == *r => continue,
                Ok(own) => differing(r, &own),
                Err(e) => e,
            };
            return Err(merge_error(format!(
                "{}: row {} (scene `{}`) does not hold its run's values: {differs}; merge takes \
                 the shard directories as `elcon batch` wrote them",
                p.dir.display(),
                r.index,
                r.scene
            )));
        }
    }
    Ok(())
}

/// The first field in which `row` differs from `own` (its run's), named.
fn differing(row: &Row, own: &Row) -> String {
    let (a, b) = (
        serde_json::to_value(row).unwrap_or_default(),
        serde_json::to_value(own).unwrap_or_default(),
    );
    let first = a.as_object().and_then(|a| {
        a.iter()
            .find(|(k, v)| b.get(k.as_str()) != Some(v))
            .map(|(k, v)| {
                format!(
                    "`{k}` is {v} in the table, {} in result.json",
                    b[k.as_str()]
                )
            })
    });
    first.unwrap_or_else(|| "the rows differ".into())
}

/// Joins the results.json of a batch's shard directories (or of one whole
/// batch) into one table under `out`, written as a unit; `notice` hears
/// that another writer of `out` is waited for.
///
/// # Errors
/// [`SceneError::Io`] for a directory without a readable results.json or
/// an `out` that is not merge's own; [`SceneError::Merge`] when the
/// directories are not every shard of one batch, each once, or rows
/// conflict.
pub fn merge(
    dirs: &[PathBuf],
    out: &Path,
    notice: &dyn Fn(&str),
) -> Result<BatchOutcome, SceneError> {
    if dirs.is_empty() {
        return Err(merge_error("no directory to merge"));
    }
    check_out(dirs, out)?;
    let parts = dirs
        .iter()
        .map(|d| read_part(d))
        .collect::<Result<Vec<_>, _>>()?;
    let (runs, count) = check_parts(&parts)?;
    check_rows(&parts, runs, count)?;
    check_values(&parts)?;
    let first = &parts[0].table;
    let mut merged = BatchOutcome {
        batch: first.batch.clone(),
        error: first.error,
        shard: None,
        batch_hash: first.batch_hash.clone(),
        runs: Some(runs),
        pending: 0,
        rows: parts.iter().flat_map(|p| p.table.rows.clone()).collect(),
    };
    merged.rows.sort_by_key(|r| r.index);
    let staging = Staging::begin(out, notice)?;
    write_tables(&merged, staging.path())?;
    staging.commit()?;
    Ok(merged)
}

/// The files merge writes.
const TABLE_FILES: [&str; 4] = [
    "results.json",
    "results.csv",
    "results.md",
    "error-time.svg",
];

/// `out` is replaced as a whole: it must not hold a shard, and if it
/// exists, only what merge writes.
fn check_out(dirs: &[PathBuf], out: &Path) -> Result<(), SceneError> {
    let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let target = absolute(out);
    if let Some(d) = dirs.iter().find(|d| absolute(d).starts_with(&target)) {
        return Err(SceneError::io(
            out,
            format!(
                "holds the shard {}: give merge a directory of its own",
                d.display()
            ),
        ));
    }
    if let Ok(entries) = std::fs::read_dir(out) {
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if !TABLE_FILES.contains(&name.as_str()) {
                return Err(SceneError::io(
                    out,
                    format!(
                        "exists and holds `{name}`, which merge did not write (merge replaces the \
                         directory as a whole): give a new directory"
                    ),
                ));
            }
        }
    }
    Ok(())
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
pub(crate) fn write_tables(o: &BatchOutcome, dir: &Path) -> Result<(), SceneError> {
    let json = serde_json::to_string_pretty(o).map_err(|e| SceneError::io(dir, e))?;
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
