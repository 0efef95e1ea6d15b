//! Batch files: a base scene and groups of sweeps. Each group is the
//! cartesian product of its keys' values; every combination is the base
//! scene with those keys overridden (dotted paths, `"points.across" = [11,
//! 21]`). The runs are never listed: run i is decoded from its index
//! ([`Batch::run`]: the groups in order, within a group the index in mixed
//! radix, the last key the fastest digit), so a sweep of any size up to
//! [`MAX_RUNS`] costs memory for the runs in flight only, and a shard picks
//! its runs by index (elcon-runner's shards).
//!
//! Running a batch is `run_batch` (the crate root); its tables and `elcon merge`
//! are in the tables module.

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use crate::ctx::{Ctx, parse, read_text};
use crate::error::{Location, SceneError};
use crate::scene::{MAX_SLUG, Scene};
use crate::schema::{BatchFile, ErrorMetric};

/// The most runs a batch file's sweep may have. A batch's tables hold one
/// row per run, in memory while they are written and on disk (about half a
/// kilobyte a row in results.json): a million rows is about 0.5 GB. A
/// larger study is several batch files.
pub(crate) const MAX_RUNS: usize = 1_000_000;

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
    pub error: ErrorMetric,
    /// SHA-256 of the batch file's and the base scene's text (hex): the
    /// shards of one batch carry the same, and `elcon merge` checks it.
    pub hash: String,
    /// The base scene, parsed once; each run edits a copy.
    base: toml_edit::DocumentMut,
    groups: Vec<Group>,
    /// Runs of the whole sweep.
    total: usize,
}

/// One `[[batch.group]]`: its sweeps and where its runs start.
#[derive(Debug, Clone)]
struct Group {
    sweeps: Vec<(String, Vec<toml::Value>)>,
    /// Index of the group's first run.
    first: usize,
    /// Its runs: the product of the sweeps' lengths.
    runs: usize,
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

    /// A directory-safe name: `007-points.across-41_solver.method-lemke`;
    /// above `MAX_SLUG` (120) bytes, its first part and a hash of the whole
    /// (`007-loading.load-...-h1a2b3c4d5e6f`), so every name fits a file
    /// system's limit (255 bytes) and two runs never share one.
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
        let whole = format!("{:03}-{body}", self.index);
        if whole.len() <= MAX_SLUG {
            return whole;
        }
        let digest: String = Sha256::digest(whole.as_bytes())[..6]
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect();
        // ASCII only, so any byte index is a character boundary.
        format!("{}-h{digest}", &whole[..MAX_SLUG - 14])
    }
}

/// A value as labels and directory names show it: a string bare, a
/// number in its shortest round-trip form (`1e300`, not 301 digits).
fn display(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Float(x) => format!("{x:?}"),
        other => other.to_string(),
    }
}

impl Batch {
    /// Reads and validates a batch file and its base scene.
    ///
    /// # Errors
    /// As [`Scene::from_file`], for the batch file and the base scene; a
    /// sweep key that does not lead to a value, values that are not a
    /// non-empty array, or a sweep of more than `MAX_RUNS` (1,000,000) runs is
    /// [`SceneError::Invalid`].
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        Self::from_text(path, &read_text(path)?)
    }

    /// Validates a batch given as text (read from `path`, which names it
    /// and places its base scene).
    ///
    /// # Errors
    /// As [`Batch::from_file`], without the batch file's I/O.
    pub fn from_text(path: &Path, text: &str) -> Result<Self, SceneError> {
        let text = text.to_string();
        let raw: BatchFile = parse(path, &text)?;
        let ctx = Ctx::new(path, &text);
        let b = raw.batch;
        let name = match &b.name {
            Some(n) => {
                let v = n.get_ref();
                if v.trim().is_empty() || v.contains(['/', '\\']) || v.starts_with('.') {
                    return Err(ctx.invalid(
                        n.span(),
                        "batch.name",
                        format!("\"{v}\""),
                        "names the output directory: not empty, no path separators, no leading '.' \
                         (elcon's temporary siblings and locks start with one)",
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
        // A base scene that cannot be read is the batch file's error, at
        // the key that names it.
        let base_text = read_text(&scene_file).map_err(|e| match e {
            SceneError::Io { path, reason } => ctx.invalid(
                b.scene.span(),
                "batch.scene",
                format!("\"{}\"", b.scene.get_ref()),
                format!("the base scene {} cannot be read: {reason}", path.display()),
            ),
            other => other,
        })?;
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
        let error = b
            .error
            .as_ref()
            .map_or_else(ErrorMetric::default, |e| *e.get_ref());
        let (groups, total) = groups(&ctx, &b.group)?;
        let batch = Self {
            name,
            file: path.to_path_buf(),
            scene_file,
            error,
            hash: hash(&text, &base_text),
            base,
            groups,
            total,
        };
        batch.check_keys()?;
        Ok(batch)
    }

    /// Every key must apply to the base scene: each is tried once with its
    /// first value (values are checked per run).
    fn check_keys(&self) -> Result<(), SceneError> {
        for group in &self.groups {
            for (key, values) in &group.sweeps {
                let probe = BatchRun {
                    index: group.first,
                    overrides: vec![(key.clone(), values[0].clone())],
                };
                self.text(&probe, |reason| SceneError::Invalid {
                    file: self.file.clone(),
                    at: Location { line: 1, column: 1 },
                    field: "batch.group".into(),
                    value: probe.label(),
                    reason,
                })?;
            }
        }
        Ok(())
    }

    /// Runs of the whole sweep.
    pub fn len(&self) -> usize {
        self.total
    }

    /// Whether the sweep has no run (never, for a validated batch).
    pub fn is_empty(&self) -> bool {
        self.total == 0
    }

    /// Run `index` of the sweep (groups in file order, each the cartesian
    /// product of its keys, the last key varying fastest), or `None` past
    /// the end.
    pub fn run(&self, index: usize) -> Option<BatchRun> {
        let group = self
            .groups
            .iter()
            .find(|g| (g.first..g.first + g.runs).contains(&index))?;
        let mut i = index - group.first;
        let mut overrides = vec![(String::new(), toml::Value::Boolean(false)); group.sweeps.len()];
        for (slot, (key, values)) in group.sweeps.iter().enumerate().rev() {
            overrides[slot] = (key.clone(), values[i % values.len()].clone());
            i /= values.len();
        }
        Some(BatchRun { index, overrides })
    }

    /// The runs, in order, made one at a time.
    pub fn runs(&self) -> impl Iterator<Item = BatchRun> + '_ {
        (0..self.total).filter_map(|i| self.run(i))
    }

    /// A few runs that together take every value of every key at least
    /// once (in each group, run j sets key k to its value j mod its
    /// length): what `elcon check` validates of a sweep too large to check
    /// run by run.
    pub fn covering_runs(&self) -> Vec<BatchRun> {
        let mut out = Vec::new();
        for g in &self.groups {
            let widest = g.sweeps.iter().map(|(_, v)| v.len()).max().unwrap_or(1);
            for j in 0..widest {
                let mut index = 0;
                for (_, values) in &g.sweeps {
                    index = index * values.len() + j % values.len();
                }
                out.extend(self.run(g.first + index));
            }
        }
        out
    }

    /// The base scene's text with the run's overrides applied (formatting
    /// and the line of every other key kept); an override that does not
    /// apply is refused as `refuse` says it.
    fn text(
        &self,
        run: &BatchRun,
        refuse: impl Fn(String) -> SceneError,
    ) -> Result<String, SceneError> {
        let mut doc = self.base.clone();
        for (key, value) in &run.overrides {
            let parts: Vec<&str> = key.split('.').collect();
            let mut table = doc.as_table_mut() as &mut dyn toml_edit::TableLike;
            for part in &parts[..parts.len() - 1] {
                let item = table.entry(part).or_insert(toml_edit::table());
                table = item.as_table_like_mut().ok_or_else(|| {
                    refuse(format!(
                        "`{key}`: `{part}` is not a table in the base scene"
                    ))
                })?;
            }
            let v: toml_edit::Value = value
                .to_string()
                .parse()
                .map_err(|e| refuse(format!("`{key}`: {e}")))?;
            table.insert(parts[parts.len() - 1], toml_edit::Item::Value(v));
        }
        Ok(doc.to_string())
    }

    /// The validated scene of a run, named `<batch>/<run slug>`.
    ///
    /// # Errors
    /// As [`Scene::from_str`]; messages name the base scene, the run and its
    /// overrides.
    pub fn scene(&self, run: &BatchRun) -> Result<Scene, SceneError> {
        let text = self.text(run, |reason| SceneError::Layout {
            scene: run.slug(),
            reason,
        })?;
        let label = PathBuf::from(format!(
            "{} [run {}: {}]",
            self.scene_file.display(),
            run.index,
            run.label()
        ));
        Ok(Scene::from_str(&label, &text)?.renamed(run.slug()))
    }
}

/// Whether the TOML text is a batch (it has a `[batch]` table) rather than
/// a scene: how the command line tells the two apart. Text that does not
/// parse is not a batch (reading it as a scene reports the syntax error).
pub fn is_batch_text(text: &str) -> bool {
    text.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("batch"))
}

/// SHA-256 (hex) of a batch file's text, its base scene's and the elcon
/// version that runs them: shards merge only when all three are the same
/// (another version may give other digits for the same scene).
fn hash(batch: &str, scene: &str) -> String {
    let mut h = Sha256::new();
    for part in [batch, scene, env!("CARGO_PKG_VERSION")] {
        h.update((part.len() as u64).to_le_bytes());
        h.update(part.as_bytes());
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// The groups of sweeps, and the sweep's size (at most [`MAX_RUNS`]).
fn groups(
    ctx: &Ctx<'_>,
    group: &toml::Spanned<Vec<toml::Spanned<toml::Table>>>,
) -> Result<(Vec<Group>, usize), SceneError> {
    if group.get_ref().is_empty() {
        return Err(ctx.invalid(
            group.span(),
            "batch.group",
            "[]",
            "give at least one [[batch.group]] of sweeps",
        ));
    }
    let mut groups = Vec::new();
    // The size as a float too, to name it when it overflows.
    let (mut total, mut size) = (Some(0usize), 0.0f64);
    for (g, spanned) in group.get_ref().iter().enumerate() {
        let mut sweeps = Vec::new();
        let (mut runs, mut approx) = (Some(1usize), 1.0f64);
        for (key, values) in spanned.get_ref() {
            let field = format!("batch.group[{g}].\"{key}\"");
            if key.split('.').any(|part| part.trim().is_empty()) {
                return Err(ctx.invalid(
                    spanned.span(),
                    field,
                    format!("{key:?}"),
                    "a key path is a scene's section and key names joined by single dots \
                     (\"points.across\", \"geometry.surface1.radius\"); this one has an empty \
                     name (a doubled dot, or a dot at an end)",
                ));
            }
            let toml::Value::Array(values) = values else {
                return Err(ctx.invalid(
                    spanned.span(),
                    field,
                    values,
                    "a sweep is an array of values",
                ));
            };
            if values.is_empty() {
                return Err(ctx.invalid(spanned.span(), field, "[]", "give at least one value"));
            }
            runs = runs.and_then(|r| r.checked_mul(values.len()));
            approx *= values.len() as f64;
            sweeps.push((key.clone(), values.clone()));
        }
        size += approx;
        total = total.zip(runs).and_then(|(t, r)| t.checked_add(r));
        match (total, runs) {
            (Some(first_after), Some(runs)) if first_after <= MAX_RUNS => groups.push(Group {
                sweeps,
                first: first_after - runs,
                runs,
            }),
            _ => {
                let whole: f64 = size
                    + group.get_ref()[g + 1..]
                        .iter()
                        .map(|t| {
                            t.get_ref()
                                .values()
                                .map(|v| v.as_array().map_or(1.0, |a| a.len() as f64))
                                .product::<f64>()
                        })
                        .sum::<f64>();
                return Err(ctx.invalid(
                    group.span(),
                    "batch.group",
                    format!("{} runs", count(whole)),
                    format!(
                        "a sweep has at most {} runs (its tables hold a row per run); \
                         split the study into several batch files",
                        count(MAX_RUNS as f64)
                    ),
                ));
            }
        }
    }
    Ok((groups, total.unwrap_or(0)))
}

/// A run count for messages: exact with thousands separators below 1e15,
/// else in scientific notation.
pub(crate) fn count(n: f64) -> String {
    use elcon_num::thousands;
    if n < 1e15 {
        thousands(n as u64)
    } else {
        format!("{n:.3e}")
    }
}
