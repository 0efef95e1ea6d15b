//! Running a batch (or one shard of it): the runs go in parallel (rayon),
//! each made from its index when a thread takes it, each isolated (a
//! failure, a refusal or a panic is its row, the others still run), each
//! admitted only when its estimated peak memory fits beside the runs in
//! flight (a run over the whole ceiling is refused). The batch directory is
//! written as a unit ([`Staging`]) with every run's outputs and the tables.

use std::path::Path;
use std::sync::{Condvar, Mutex};

use rayon::prelude::*;

use crate::batch::{Batch, BatchRun};
use crate::error::SceneError;
use crate::estimate::{BASELINE, Estimate};
use crate::isolate::isolated;
use crate::memory::Ceiling;
use crate::output::{Staging, write_run_files};
use crate::run::{RunResult, run};
use crate::shard::Shard;
use crate::tables::{BatchOutcome, Row, write_tables};

/// Reports a batch's progress (the command line draws a bar on a terminal
/// and plain lines otherwise).
pub trait Progress: Sync {
    /// Called once with the number of runs.
    fn start(&self, _total: usize) {}
    /// Called as each run ends, from any thread.
    fn finished(&self, _run: &BatchRun, _outcome: Result<&RunResult, &SceneError>) {}
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

/// One run, validated, estimated, admitted under the budget, solved and
/// written into `dir`.
fn one_run(
    batch: &Batch,
    r: &BatchRun,
    ceiling: &Ceiling,
    budget: &Budget,
    dir: &Path,
) -> Result<RunResult, SceneError> {
    let scene = batch.scene(r)?;
    let estimate = Estimate::of(&scene)?;
    if !ceiling.admits(estimate.peak_bytes) {
        return Err(estimate.refusal(&scene, ceiling));
    }
    let share = estimate.peak_bytes.saturating_sub(BASELINE);
    budget.take(share);
    let outcome = isolated(scene.name(), || {
        let result = run(&scene)?;
        write_run_files(&result, &dir.join(r.slug()))?;
        Ok(result.result)
    });
    budget.give(share);
    outcome
}

/// Runs a batch (or one shard of it), writing every run's outputs and the
/// batch tables under `out` as one directory. Failed and refused runs are
/// rows with their reason; the others are written regardless.
///
/// # Errors
/// [`SceneError::Io`] when the directory or the tables cannot be written
/// (run failures are rows, not errors).
pub fn run_batch(
    batch: &Batch,
    out: &Path,
    options: &BatchOptions,
    progress: &dyn Progress,
) -> Result<BatchOutcome, SceneError> {
    let shard = options.shard;
    let target = batch.output_dir(out, shard);
    let staging = Staging::begin(&target, &|m| progress.notice(m))?;
    let whole = Shard { index: 1, count: 1 };
    let slice = shard.unwrap_or(whole);
    let count = slice.len_of(batch.len());
    progress.start(count);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.unwrap_or(0))
        .build()
        .map_err(|e| SceneError::io(&target, e))?;
    let budget = Budget {
        free: Mutex::new(options.ceiling.bytes.saturating_sub(BASELINE)),
        returned: Condvar::new(),
    };
    let dir = staging.path();
    let mut rows: Vec<Row> = pool.install(|| {
        (0..count)
            .into_par_iter()
            .filter_map(|j| batch.run(slice.nth(j)))
            .map(|r| {
                let outcome = isolated(&r.slug(), || {
                    one_run(batch, &r, &options.ceiling, &budget, dir)
                });
                progress.finished(&r, outcome.as_ref());
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
        error: batch.error,
        shard: shard.map(|s| s.to_string()),
        batch_hash: Some(batch.hash.clone()),
        runs: Some(batch.len()),
        rows,
    };
    write_tables(&outcome, dir)?;
    staging.commit()?;
    Ok(outcome)
}
