//! `elcon merge`: joins the tables of a batch's shards after checking that
//! they are the shards of one batch, each once, together every run once,
//! and that each row holds its run's own result.json.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use elcon_process::Staging;
use elcon_report::{BatchOutcome, Row, RunResult, write_tables};
use elcon_scene::sha256_hex;

use crate::error::RunError;
use crate::journal::{Entry, JOURNAL};
use crate::shard::Shard;

/// One shard directory's table, read, and its journal's record of each
/// finished run's result.json (SHA-256, by run index).
struct Part {
    dir: PathBuf,
    table: BatchOutcome,
    shard: Option<(usize, usize)>,
    recorded: BTreeMap<usize, String>,
}

fn merge_error(what: impl Into<String>) -> RunError {
    RunError::Merge {
        reason: what.into(),
    }
}

/// Reads `dir/results.json`.
fn read_part(dir: &Path) -> Result<Part, RunError> {
    let path = dir.join("results.json");
    let text = std::fs::read_to_string(&path).map_err(|e| RunError::io(&path, e))?;
    let table: BatchOutcome = serde_json::from_str(&text).map_err(|e| RunError::io(&path, e))?;
    let shard = match &table.shard {
        None => None,
        Some(s) => {
            let parsed = s
                .parse::<Shard>()
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
        recorded: recorded(dir),
    })
}

/// The SHA-256 of each finished run's result.json as `dir`'s journal
/// recorded it (the last line of a run counts; none without a journal).
fn recorded(dir: &Path) -> BTreeMap<usize, String> {
    let text = std::fs::read_to_string(dir.join(JOURNAL)).unwrap_or_default();
    let mut shas = BTreeMap::new();
    for entry in text
        .lines()
        .skip(1)
        .filter_map(|l| serde_json::from_str::<Entry>(l).ok())
    {
        match entry.result_sha256 {
            Some(sha) if entry.row.is_ok() => shas.insert(entry.row.index, sha),
            _ => shas.remove(&entry.row.index),
        };
    }
    shas
}

/// Checks that `parts` are every shard of one batch, once each.
fn check_parts(parts: &[Part]) -> Result<(usize, usize), RunError> {
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
fn check_rows(parts: &[Part], runs: usize, count: usize) -> Result<(), RunError> {
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
        let expected = Shard { index: k, count }.len_of(runs);
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
/// result.json (in the run's directory beside the table), that the file is
/// the one its shard's journal recorded (the same SHA-256), and that runs
/// which read the same data file read the same bytes: a table or a
/// result.json edited by hand, a run whose directory was replaced, or
/// shards run before and after a data file was edited, are refused.
fn check_values(parts: &[Part]) -> Result<(), RunError> {
    let mut read: BTreeMap<PathBuf, (String, PathBuf)> = BTreeMap::new();
    for p in parts {
        for r in p.table.rows.iter().filter(|r| r.is_ok()) {
            let refuse = |why: String| {
                merge_error(format!(
                    "{}: row {} (scene `{}`) {why}; merge takes the shard directories as `elcon \
                     batch` wrote them",
                    p.dir.display(),
                    r.index,
                    r.scene
                ))
            };
            let result = own_result(p, r).map_err(&refuse)?;
            let own = Row::ok(r.index, r.overrides.clone(), &result);
            if own != *r {
                return Err(refuse(format!(
                    "does not hold its run's values: {}",
                    differing(r, &own)
                )));
            }
            for input in result.inputs.iter().flat_map(|i| &i.files) {
                let first = read
                    .entry(input.path.clone())
                    .or_insert_with(|| (input.sha256.clone(), p.dir.join(&r.scene)));
                if first.0 != input.sha256 {
                    return Err(refuse(format!(
                        "read {} ({}) with other contents than {} did: the file changed between \
                         the runs; run the shards again from the same files",
                        input.path.display(),
                        input.field,
                        first.1.display()
                    )));
                }
            }
        }
    }
    Ok(())
}

/// Row `r`'s result.json in part `p`, if it is the one the journal
/// recorded; else why not.
fn own_result(p: &Part, r: &Row) -> Result<RunResult, String> {
    let plain = !r.scene.is_empty() && !r.scene.starts_with('.') && !r.scene.contains(['/', '\\']);
    let path = p.dir.join(&r.scene).join("result.json");
    if !plain {
        return Err(format!("its run's {} cannot be read", path.display()));
    }
    let bytes = std::fs::read(&path).map_err(|e| format!("its run's {}: {e}", path.display()))?;
    match p.recorded.get(&r.index) {
        Some(sha) if *sha == sha256_hex(&bytes) => {}
        Some(_) => {
            return Err(format!(
                "its run's {} is not the one {JOURNAL} recorded (edited or replaced since)",
                path.display()
            ));
        }
        None => {
            return Err(format!(
                "has no record in {JOURNAL} of its run's result.json"
            ));
        }
    }
    RunResult::from_bytes(&bytes, &path).map_err(|e| format!("its run's {e}"))
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
/// [`RunError::Process`] for a directory without a readable results.json or
/// an `out` that is not merge's own; [`RunError::Merge`] when the
/// directories are not every shard of one batch, each once, or rows
/// conflict.
pub fn merge(
    dirs: &[PathBuf],
    out: &Path,
    notice: &dyn Fn(&str),
) -> Result<BatchOutcome, RunError> {
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
fn check_out(dirs: &[PathBuf], out: &Path) -> Result<(), RunError> {
    let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let target = absolute(out);
    if let Some(d) = dirs.iter().find(|d| absolute(d).starts_with(&target)) {
        return Err(RunError::io(
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
                return Err(RunError::io(
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
