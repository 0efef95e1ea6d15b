//! Batch runs: a base scene and groups of sweeps. Each group is the
//! cartesian product of its keys' values; every combination is the base
//! scene with those keys overridden (dotted paths, `"points.across" = [11,
//! 21]`). Runs go in parallel (rayon); a failed run is reported and the
//! others still run and are written. `--shard K/N` runs every N-th run from
//! the K-th, so a cluster's job array can split a sweep; [`merge`] joins the
//! shards' tables.
//!
//! Outputs in `<out>/<batch>/` (or `<batch>-shard-K-of-N`): each run's
//! outputs in its own directory, and results.json, results.csv,
//! results.md and, where the runs have a closed-form reference,
//! error-time.svg (error against run time, log-log, one series per method).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{Location, SceneError};
use crate::output::{write_atomic, write_run};
use crate::run::{RunResult, run};
use crate::scene::{Ctx, Scene, parse};
use crate::schema::BatchFile;

/// The error metrics a batch can plot against run time.
const METRICS: [&str; 5] = [
    "approach",
    "max_pressure",
    "contact_extent",
    "pressure_l2",
    "load",
];

/// A validated batch file.
#[derive(Debug, Clone)]
pub struct Batch {
    /// The batch's name (default: the file's stem).
    pub name: String,
    /// The batch file.
    pub file: PathBuf,
    /// The base scene file.
    pub scene_file: PathBuf,
    /// The error plotted against run time (default "approach").
    pub error: String,
    /// The base scene, parsed once; each run edits a copy.
    base: toml_edit::DocumentMut,
    groups: Vec<Vec<(String, Vec<toml::Value>)>>,
}

/// One run of a batch: its index and the keys it overrides.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchRun {
    /// Position in the expanded sweep, from 0.
    pub index: usize,
    /// (key, value) overrides, in the group's key order.
    pub overrides: Vec<(String, toml::Value)>,
}

impl BatchRun {
    /// `key=value, ...` as written in tables.
    pub fn label(&self) -> String {
        self.overrides
            .iter()
            .map(|(k, v)| format!("{k}={}", display(v)))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// A directory-safe name: `007-points.across-41_solver.method-lemke`.
    pub fn slug(&self) -> String {
        let body: String = self
            .overrides
            .iter()
            .map(|(k, v)| format!("{k}-{}", display(v)))
            .collect::<Vec<_>>()
            .join("_")
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_') {
                    c
                } else {
                    '-'
                }
            })
            .collect();
        format!("{:03}-{body}", self.index)
    }
}

fn display(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// The K-th of N slices of a sweep (1-based K).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, from 1.
    pub index: usize,
    /// N.
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| format!("`{s}`: a shard is K/N, e.g. 2/8"))?;
        let index: usize = k
            .trim()
            .parse()
            .map_err(|_| format!("`{s}`: K must be a whole number"))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| format!("`{s}`: N must be a whole number"))?;
        if count == 0 || index == 0 || index > count {
            return Err(format!("`{s}`: need 1 <= K <= N"));
        }
        Ok(Self { index, count })
    }
}

impl Shard {
    /// Whether run `i` (from 0) belongs to this shard.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }
}

/// Reports a batch's progress (the command line draws a bar on a terminal
/// and plain lines otherwise).
pub trait Progress: Sync {
    /// Called once with the number of runs.
    fn start(&self, _total: usize) {}
    /// Called as each run ends, from any thread.
    fn finished(&self, _run: &BatchRun, _outcome: Result<&RunResult, &SceneError>) {}
}

/// No progress reporting.
impl Progress for () {}

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
}

impl Row {
    fn ok(index: usize, overrides: String, r: &RunResult) -> Self {
        let e = r.reference.as_ref().map(|x| &x.errors);
        Self {
            index,
            overrides,
            scene: r.scene.clone(),
            status: "ok".into(),
            method: Some(r.method.clone()),
            points: Some(r.points),
            pivots: Some(r.statistics.pivots),
            seconds_total: Some(r.seconds.total),
            seconds_solve: Some(r.seconds.solve),
            approach: Some(r.approach),
            max_pressure: Some(r.max_pressure),
            certificate_worst: Some(r.certificate.worst),
            error_approach: e.and_then(|e| e.approach),
            error_max_pressure: e.and_then(|e| e.max_pressure),
            error_contact_extent: e.and_then(|e| e.contact_extent),
            error_pressure_l2: e.and_then(|e| e.pressure_l2),
            error_load: e.and_then(|e| e.load),
        }
    }

    fn failed(index: usize, overrides: String, scene: String, e: &SceneError) -> Self {
        Self {
            index,
            overrides,
            scene,
            status: format!("failed: {e}"),
            ..Self::default()
        }
    }

    fn error(&self, metric: &str) -> Option<f64> {
        match metric {
            "approach" => self.error_approach,
            "max_pressure" => self.error_max_pressure,
            "contact_extent" => self.error_contact_extent,
            "pressure_l2" => self.error_pressure_l2,
            _ => self.error_load,
        }
    }
}

/// What results.json holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BatchOutcome {
    /// The batch's name.
    pub batch: String,
    /// The metric plotted against run time.
    pub error: String,
    /// The shard, "K/N", if one.
    pub shard: Option<String>,
    /// One row per run, failed ones included, by index.
    pub rows: Vec<Row>,
}

impl BatchOutcome {
    /// The number of failed runs.
    pub fn failures(&self) -> usize {
        self.rows.iter().filter(|r| r.status != "ok").count()
    }
}

impl Batch {
    /// Reads and validates a batch file and its base scene.
    ///
    /// # Errors
    /// As [`Scene::from_file`], for the batch file and the base scene; a
    /// sweep key that does not lead to a value, or values that are not a
    /// non-empty array, is [`SceneError::Invalid`].
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::io(path, e))?;
        let raw: BatchFile = parse(path, &text)?;
        let ctx = Ctx {
            file: path,
            text: &text,
        };
        let b = raw.batch;
        let name = match &b.name {
            Some(n) => {
                let v = n.get_ref();
                if v.trim().is_empty() || v.contains(['/', '\\']) || v == "." || v == ".." {
                    return Err(ctx.invalid(
                        n.span(),
                        "batch.name",
                        format!("\"{v}\""),
                        "names the output directory: not empty, no path separators",
                    ));
                }
                v.clone()
            }
            None => path
                .file_stem()
                .map_or_else(|| "batch".into(), |s| s.to_string_lossy().into_owned()),
        };
        let scene_file = path
            .parent()
            .unwrap_or(Path::new("."))
            .join(b.scene.get_ref());
        let base_text =
            std::fs::read_to_string(&scene_file).map_err(|e| SceneError::io(&scene_file, e))?;
        // The base scene must be valid on its own.
        Scene::from_str(&scene_file, &base_text)?;
        let base: toml_edit::DocumentMut =
            base_text
                .parse()
                .map_err(|e: toml_edit::TomlError| SceneError::Syntax {
                    file: scene_file.clone(),
                    at: Location::of(&base_text, e.span().map_or(0, |s| s.start)),
                    message: e.message().trim().to_string(),
                })?;
        let error = match &b.error {
            Some(e) if METRICS.contains(&e.get_ref().as_str()) => e.get_ref().clone(),
            Some(e) => {
                return Err(ctx.invalid(
                    e.span(),
                    "batch.error",
                    format!("\"{}\"", e.get_ref()),
                    format!("one of {}", METRICS.join(", ")),
                ));
            }
            None => "approach".into(),
        };
        if b.group.get_ref().is_empty() {
            return Err(ctx.invalid(
                b.group.span(),
                "batch.group",
                "[]",
                "give at least one [[batch.group]] of sweeps",
            ));
        }
        let mut groups = Vec::new();
        for (g, group) in b.group.get_ref().iter().enumerate() {
            let mut sweeps = Vec::new();
            for (key, values) in group.get_ref() {
                let field = format!("batch.group[{g}].\"{key}\"");
                let toml::Value::Array(values) = values else {
                    return Err(ctx.invalid(
                        group.span(),
                        field,
                        values,
                        "a sweep is an array of values",
                    ));
                };
                if values.is_empty() {
                    return Err(ctx.invalid(group.span(), field, "[]", "give at least one value"));
                }
                sweeps.push((key.clone(), values.clone()));
            }
            groups.push(sweeps);
        }
        let batch = Self {
            name,
            file: path.to_path_buf(),
            scene_file,
            error,
            base,
            groups,
        };
        // Every key must apply to the base scene (values are checked per run).
        for run in batch.runs() {
            batch.text(&run).map_err(|reason| SceneError::Invalid {
                file: path.to_path_buf(),
                at: Location { line: 1, column: 1 },
                field: "batch.group".into(),
                value: run.label(),
                reason,
            })?;
        }
        Ok(batch)
    }

    /// Every run of the sweep, in order: groups in file order, each the
    /// cartesian product of its keys (the last key varying fastest).
    pub fn runs(&self) -> Vec<BatchRun> {
        let mut out = Vec::new();
        for group in &self.groups {
            let total: usize = group.iter().map(|(_, v)| v.len()).product();
            for mut i in 0..total {
                let mut overrides = vec![(String::new(), toml::Value::Boolean(false)); group.len()];
                for (slot, (key, values)) in group.iter().enumerate().rev() {
                    overrides[slot] = (key.clone(), values[i % values.len()].clone());
                    i /= values.len();
                }
                out.push(BatchRun {
                    index: out.len(),
                    overrides,
                });
            }
        }
        out
    }

    /// The base scene's text with the run's overrides applied (formatting
    /// and the line of every other key kept).
    fn text(&self, run: &BatchRun) -> Result<String, String> {
        let mut doc = self.base.clone();
        for (key, value) in &run.overrides {
            let parts: Vec<&str> = key.split('.').collect();
            let mut table = doc.as_table_mut() as &mut dyn toml_edit::TableLike;
            for part in &parts[..parts.len() - 1] {
                let item = table.entry(part).or_insert(toml_edit::table());
                table = item
                    .as_table_like_mut()
                    .ok_or_else(|| format!("`{key}`: `{part}` is not a table in the base scene"))?;
            }
            let v: toml_edit::Value = value
                .to_string()
                .parse()
                .map_err(|e| format!("`{key}`: {e}"))?;
            table.insert(parts[parts.len() - 1], toml_edit::Item::Value(v));
        }
        Ok(doc.to_string())
    }

    /// The directory a batch (or one shard of it) writes under `out`:
    /// `out/<name>`, or `out/<name>-shard-K-of-N` for a shard.
    pub fn output_dir(&self, out: &Path, shard: Option<Shard>) -> PathBuf {
        match shard {
            Some(s) => out.join(format!("{}-shard-{}-of-{}", self.name, s.index, s.count)),
            None => out.join(&self.name),
        }
    }

    /// The validated scene of a run, named `<batch>/<run slug>`.
    ///
    /// # Errors
    /// As [`Scene::from_str`]; messages name the base scene, the run and its
    /// overrides.
    pub fn scene(&self, run: &BatchRun) -> Result<Scene, SceneError> {
        let text = self.text(run).map_err(|reason| SceneError::Run {
            scene: run.slug(),
            reason,
        })?;
        let label = PathBuf::from(format!(
            "{} [run {}: {}]",
            self.scene_file.display(),
            run.index,
            run.label()
        ));
        let mut scene = Scene::from_str(&label, &text)?;
        scene.name = run.slug();
        Ok(scene)
    }
}

/// Runs a batch (or one shard of it) with `jobs` threads (default: all),
/// writing every run's outputs and the batch tables under `out`. Failed runs
/// are rows with their reason; the others are written regardless.
///
/// # Errors
/// [`SceneError::Io`] when the tables cannot be written (run failures are
/// rows, not errors).
pub fn run_batch(
    batch: &Batch,
    out: &Path,
    jobs: Option<usize>,
    shard: Option<Shard>,
    progress: &dyn Progress,
) -> Result<BatchOutcome, SceneError> {
    let dir = batch.output_dir(out, shard);
    let runs: Vec<BatchRun> = batch
        .runs()
        .into_iter()
        .filter(|r| shard.is_none_or(|s| s.contains(r.index)))
        .collect();
    progress.start(runs.len());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.unwrap_or(0))
        .build()
        .map_err(|e| SceneError::io(&dir, e))?;
    let mut rows: Vec<Row> = pool.install(|| {
        runs.par_iter()
            .map(|r| {
                let outcome = batch.scene(r).and_then(|scene| {
                    let result = run(&scene)?;
                    write_run(&result, &dir)?;
                    Ok(result.result)
                });
                progress.finished(r, outcome.as_ref());
                match outcome {
                    Ok(res) => Row::ok(r.index, r.label(), &res),
                    Err(e) => Row::failed(r.index, r.label(), r.slug(), &e),
                }
            })
            .collect()
    });
    rows.sort_by_key(|r| r.index);
    let outcome = BatchOutcome {
        batch: batch.name.clone(),
        error: batch.error.clone(),
        shard: shard.map(|s| format!("{}/{}", s.index, s.count)),
        rows,
    };
    write_tables(&outcome, &dir)?;
    Ok(outcome)
}

/// Joins the results.json of shard (or any batch) directories into one
/// table under `out`.
///
/// # Errors
/// [`SceneError::Io`] for a directory without a readable results.json, or
/// shards of different batches.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<BatchOutcome, SceneError> {
    let mut merged: Option<BatchOutcome> = None;
    for d in dirs {
        let path = d.join("results.json");
        let text = std::fs::read_to_string(&path).map_err(|e| SceneError::io(&path, e))?;
        let part: BatchOutcome =
            serde_json::from_str(&text).map_err(|e| SceneError::io(&path, e))?;
        match &mut merged {
            None => merged = Some(part),
            Some(m) if m.batch == part.batch => m.rows.extend(part.rows),
            Some(m) => {
                return Err(SceneError::io(
                    &path,
                    format!("is from batch `{}`, not `{}`", part.batch, m.batch),
                ));
            }
        }
    }
    let mut merged = merged.ok_or_else(|| SceneError::io(out, "no directory to merge"))?;
    merged.rows.sort_by_key(|r| r.index);
    merged.rows.dedup_by_key(|r| r.index);
    merged.shard = None;
    write_tables(&merged, out)?;
    Ok(merged)
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
fn write_tables(o: &BatchOutcome, dir: &Path) -> Result<(), SceneError> {
    let json = serde_json::to_string_pretty(o).map_err(|e| SceneError::io(dir, e))?;
    write_atomic(&dir.join("results.json"), json.as_bytes())?;
    let mut csv = String::from(
        "index,overrides,scene,status,method,points,pivots,seconds_total,seconds_solve,approach,max_pressure,\
         certificate_worst,error_approach,error_max_pressure,error_contact_extent,error_pressure_l2,error_load\n",
    );
    let mut md = format!(
        "# Batch `{}`\n\n| # | overrides | method | N | pivots | seconds | certificate | error ({}) | status |\n|---|---|---|---|---|---|---|---|---|\n",
        o.batch, o.error
    );
    for r in &o.rows {
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
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
        );
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.index,
            r.overrides,
            r.method.clone().unwrap_or_default(),
            r.points.map_or(String::new(), |n| n.to_string()),
            r.pivots.map_or(String::new(), |n| n.to_string()),
            r.seconds_total.map_or(String::new(), |s| format!("{s:.4}")),
            r.certificate_worst
                .map_or(String::new(), |c| format!("{c:.1e}")),
            r.error(&o.error)
                .map_or(String::new(), |e| format!("{e:+.3e}")),
            r.status.replace('|', "/"),
        );
    }
    write_atomic(&dir.join("results.csv"), csv.as_bytes())?;
    write_atomic(&dir.join("results.md"), md.as_bytes())?;
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for r in &o.rows {
        if let (Some(m), Some(t), Some(e)) = (&r.method, r.seconds_total, r.error(&o.error)) {
            match series.iter_mut().find(|(name, _)| name == m) {
                Some((_, pts)) => pts.push((t, e.abs())),
                None => series.push((m.clone(), vec![(t, e.abs())])),
            }
        }
    }
    if !series.is_empty() {
        let title = format!("{}: error against run time", o.batch);
        if let Ok(svg) = crate::plot::error_time(&title, &o.error, &series) {
            write_atomic(&dir.join("error-time.svg"), svg.as_bytes())?;
        }
    }
    Ok(())
}
