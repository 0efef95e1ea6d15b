//! Running a batch (or one shard of it): the runs go in parallel (rayon),
//! each made from its index when a thread takes it, each isolated (a
//! failure, a refusal or a panic is its row, the others still run), each
//! admitted only when its estimated peak memory fits beside the runs in
//! flight (a run over the whole ceiling is refused). Each run's directory
//! is written whole and journaled as it finishes, so a batch killed at any
//! point resumes without running again what finished (the journal module);
//! the tables are written at the end, or when the batch is interrupted.

use std::path::{Path, PathBuf};
use std::sync::{Condvar, Mutex};

use elcon_lcp::Cancel;
use rayon::prelude::*;

use elcon_process::{Ceiling, ProcessError, interruptible, isolated, lock_dir, replace_dir};
use elcon_report::{BatchOutcome, Row, RunResult, write_run_files, write_tables};
use elcon_scene::{Batch, BatchRun, sha256_hex};

use crate::error::RunError;
use crate::estimate::{BASELINE, Estimate};
use crate::journal::Journal;
use crate::run::run;
use crate::shard::Shard;

/// Reports a batch's progress (the command line draws a bar on a terminal
/// and plain lines otherwise).
pub trait Progress: Sync {
    /// Called once with the number of runs.
    fn start(&self, _total: usize) {}
    /// Called as each run ends, from any thread.
    fn finished(&self, _run: &BatchRun, _outcome: Result<&RunResult, &RunError>) {}
    /// A message for the user (waiting for another writer's lock).
    fn notice(&self, _message: &str) {}
}

/// No progress reporting.
impl Progress for () {}

/// How to run a batch.
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// Runs in parallel (default: one per core).
    pub jobs: Option<usize>,
    /// Only this slice of the sweep.
    pub shard: Option<Shard>,
    /// The memory the runs in flight may use together.
    pub ceiling: Ceiling,
    /// Cancelled (by a signal handler), the runs in flight stop and no
    /// new one starts; the tables of what finished are written.
    pub cancel: Cancel,
}

/// The memory the runs in flight share: a run takes its estimate before
/// it starts (waiting while the others hold too much) and gives it back
/// when it ends.
struct Budget {
    free: Mutex<u64>,
    returned: Condvar,
}

impl Budget {
    fn take(&self, bytes: u64) {
        let mut free = self.free.lock().unwrap_or_else(|e| e.into_inner());
        while *free < bytes {
            free = self.returned.wait(free).unwrap_or_else(|e| e.into_inner());
        }
        *free -= bytes;
    }

    fn give(&self, bytes: u64) {
        *self.free.lock().unwrap_or_else(|e| e.into_inner()) += bytes;
        self.returned.notify_all();
    }
}

/// What one run of a batch needs besides itself.
struct Shared<'a> {
    batch: &'a Batch,
    ceiling: &'a Ceiling,
    budget: Budget,
    cancel: &'a Cancel,
    /// The batch's directory.
    dir: &'a Path,
}

/// A run that finished: its result and the SHA-256 of its result.json as
/// written (what the journal records, and a resume checks).
struct Finished {
    result: RunResult,
    result_sha256: String,
}

/// One run, validated, estimated, admitted under the budget, solved,
/// written into its directory (staged beside it and renamed into place).
fn one_run(shared: &Shared<'_>, r: &BatchRun) -> Result<Finished, RunError> {
    let scene = shared.batch.scene(r)?;
    let estimate = Estimate::of(&scene)?;
    if !shared.ceiling.admits(estimate.peak_bytes) {
        return Err(estimate.refusal(&scene, shared.ceiling));
    }
    let share = estimate.peak_bytes.saturating_sub(BASELINE);
    shared.budget.take(share);
    let outcome = if shared.cancel.is_cancelled() {
        Err(ProcessError::Interrupted { scene: r.slug() }.into())
    } else {
        isolated(scene.name(), || {
            let result = run(&scene)?;
            let tmp = shared
                .dir
                .join(format!(".{}.{}.tmp", r.slug(), std::process::id()));
            let json = tmp.join("result.json");
            let written = std::fs::create_dir(&tmp)
                .map_err(|e| RunError::io(&tmp, e))
                .and_then(|()| write_run_files(&result, &tmp).map_err(RunError::from))
                .and_then(|()| std::fs::read(&json).map_err(|e| RunError::io(&json, e)))
                .and_then(|bytes| {
                    replace_dir(&tmp, &shared.dir.join(r.slug()))
                        .map(|()| sha256_hex(&bytes))
                        .map_err(RunError::from)
                });
            match written {
                Ok(result_sha256) => Ok(Finished {
                    result: result.result,
                    result_sha256,
                }),
                Err(e) => {
                    let _ = std::fs::remove_dir_all(&tmp);
                    Err(e)
                }
            }
        })
    };
    shared.budget.give(share);
    outcome
}

/// The directory a batch (or one shard of it) writes under `out`:
/// `out/<name>`, or `out/<name>-shard-K-of-N` for a shard.
pub fn batch_dir(batch: &Batch, out: &Path, shard: Option<Shard>) -> PathBuf {
    match shard {
        Some(s) => out.join(format!("{}-shard-{}-of-{}", batch.name, s.index, s.count)),
        None => out.join(&batch.name),
    }
}

/// A batch that ran (or was interrupted): its table and what was kept.
#[derive(Debug, Clone)]
pub struct BatchDone {
    /// The tables written (a row per finished run; `pending` the others).
    pub outcome: BatchOutcome,
    /// Finished runs kept from an earlier invocation into the same directory.
    pub kept: usize,
    /// Whether the batch was interrupted before every run finished.
    pub interrupted: bool,
}

/// Runs a batch (or one shard of it) into `out/<batch>` (see the journal,
/// `journal.jsonl`, for what makes it resumable): every run's outputs are renamed into
/// place whole and journaled as it finishes; the finished runs of an
/// earlier invocation of the same batch are kept, not run again. Failed and
/// refused runs are rows with their reason. When `options.cancel` is
/// cancelled (SIGINT, SIGTERM), the runs in flight stop, no new one
/// starts, and the tables of what finished are written (`pending` counts
/// the others); running the same batch again finishes it.
///
/// # Errors
/// [`RunError`] when the directory, the journal or the tables cannot
/// be written (run failures are rows, not errors).
pub fn run_batch(
    batch: &Batch,
    out: &Path,
    options: &BatchOptions,
    progress: &dyn Progress,
) -> Result<BatchDone, RunError> {
    let shard = options.shard;
    let target = batch_dir(batch, out, shard);
    let notice = |m: &str| progress.notice(m);
    let _lock = lock_dir(&target, &notice)?;
    let journal = Journal::open(&target, batch, shard, &notice)?;
    let slice = shard.unwrap_or(Shard { index: 1, count: 1 });
    let count = slice.len_of(batch.len());
    let todo: Vec<usize> = (0..count)
        .map(|j| slice.nth(j))
        .filter(|i| !journal.kept().contains_key(i))
        .collect();
    let kept = journal.kept().len();
    if kept > 0 {
        progress.notice(&format!(
            "resuming batch `{}` in {}: {kept} finished runs kept, {} to run",
            batch.name,
            target.display(),
            todo.len()
        ));
    }
    progress.start(todo.len());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.unwrap_or(0))
        .build()
        .map_err(|e| RunError::io(&target, e))?;
    let shared = Shared {
        batch,
        ceiling: &options.ceiling,
        budget: Budget {
            free: Mutex::new(options.ceiling.bytes.saturating_sub(BASELINE)),
            returned: Condvar::new(),
        },
        cancel: &options.cancel,
        dir: &target,
    };
    let fresh: Vec<Row> = pool.install(|| {
        todo.into_par_iter()
            .filter_map(|i| {
                // After an interrupt the runs not started are left at once
                // (a million of them in well under a second).
                if shared.cancel.is_cancelled() {
                    return None;
                }
                let r = batch.run(i)?;
                let slug = r.slug();
                let outcome = interruptible(shared.cancel, &slug, || {
                    isolated(&slug, || one_run(&shared, &r))
                });
                if outcome.as_ref().is_err_and(RunError::is_interrupted) {
                    return None;
                }
                progress.finished(&r, outcome.as_ref().map(|f| &f.result));
                let (row, sha) = match outcome {
                    Ok(f) => (
                        Row::ok(r.index, r.label(), &f.result),
                        Some(f.result_sha256),
                    ),
                    Err(e) => (Row::failed(r.index, r.label(), slug, &e), None),
                };
                if let Err(e) = journal.record(&row, sha) {
                    progress.notice(&format!("warning: {e}: run {i} will run again on a resume"));
                }
                Some(row)
            })
            .collect()
    });
    let mut rows: Vec<Row> = journal.kept().values().map(|e| e.row.clone()).collect();
    rows.extend(fresh);
    rows.sort_by_key(|r| r.index);
    let pending = count - rows.len();
    let outcome = BatchOutcome {
        batch: batch.name.clone(),
        error: batch.error,
        shard: shard.map(|s| s.to_string()),
        batch_hash: Some(batch.hash.clone()),
        runs: Some(batch.len()),
        pending,
        rows,
    };
    write_tables(&outcome, &target)?;
    Ok(BatchDone {
        outcome,
        kept,
        interrupted: pending > 0,
    })
}
