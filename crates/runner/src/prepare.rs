//! What `elcon check` and `elcon run` share: a scene validated, its cost
//! estimated and compared with the memory ceiling. `run` adds the solve and
//! nothing else, so a scene `check` passes is one `run` starts solving (it
//! may still fail in the solve: no solution, a pivot limit).
//!
//! For a batch, `check` validates every run when the sweep has at most
//! [`CHECK_EVERY_RUN`] runs (or when asked), else a covering set (every
//! value of every key at least once), and says which it did; `batch`
//! validates every run as it runs it.

use elcon_lcp::Cancel;
use rayon::prelude::*;

use elcon_process::{Ceiling, isolated};
use elcon_scene::{Batch, BatchRun, Scene};

use crate::error::RunError;
use crate::estimate::Estimate;

/// `elcon check` validates every run of a sweep up to this size; above it,
/// a covering set of runs unless `--every-run` is given.
pub(crate) const CHECK_EVERY_RUN: usize = 10_000;

/// A scene ready to solve.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The validated scene.
    pub scene: Scene,
    /// Its cost, within the ceiling.
    pub estimate: Estimate,
}

/// Estimates a validated scene and compares the estimate with `ceiling`.
///
/// # Errors
/// [`RunError::TooBig`] over the ceiling; [`RunError::Run`] when a
/// design load's points cannot be laid out.
pub fn prepare(scene: Scene, ceiling: &Ceiling) -> Result<Prepared, RunError> {
    let estimate = Estimate::of(&scene)?;
    if !ceiling.admits(estimate.peak_bytes) {
        return Err(estimate.refusal(&scene, ceiling));
    }
    Ok(Prepared { scene, estimate })
}

/// The failures `check_batch` keeps to report (the rest are counted).
pub(crate) const REPORTED_FAILURES: usize = 20;

/// What `elcon check` found in a batch.
#[derive(Debug, Clone, Default)]
pub struct BatchCheck {
    /// Runs of the whole sweep.
    pub runs: usize,
    /// Runs validated.
    pub checked: usize,
    /// Whether every run was validated (else a covering set).
    pub every_run: bool,
    /// Runs that failed.
    pub failed: usize,
    /// The first `REPORTED_FAILURES` (20) of them by index, with why.
    pub failures: Vec<(BatchRun, RunError)>,
    /// The largest estimate among the valid runs checked.
    pub largest: Option<Estimate>,
    /// The estimated seconds of the runs checked, summed.
    pub seconds: f64,
    /// Whether an interrupt stopped the check before every run was
    /// checked (`checked` counts those that were).
    pub interrupted: bool,
}

impl BatchCheck {
    /// Counts one run's outcome.
    fn add(mut self, (run, outcome): (BatchRun, Result<Estimate, RunError>)) -> Self {
        self.checked += 1;
        match outcome {
            Ok(e) => {
                self.seconds += e.seconds;
                if self
                    .largest
                    .as_ref()
                    .is_none_or(|l| e.peak_bytes > l.peak_bytes)
                {
                    self.largest = Some(e);
                }
            }
            Err(e) => {
                self.failed += 1;
                self.failures.push((run, e));
                self.trim();
            }
        }
        self
    }

    /// Joins the counts of two parts of the sweep.
    fn join(mut self, other: Self) -> Self {
        self.checked += other.checked;
        self.failed += other.failed;
        self.seconds += other.seconds;
        self.failures.extend(other.failures);
        self.trim();
        if let Some(o) = other.largest
            && self
                .largest
                .as_ref()
                .is_none_or(|l| o.peak_bytes > l.peak_bytes)
        {
            self.largest = Some(o);
        }
        self
    }

    fn trim(&mut self) {
        if self.failures.len() > REPORTED_FAILURES {
            self.failures.sort_by_key(|(r, _)| r.index);
            self.failures.truncate(REPORTED_FAILURES);
        }
    }
}

/// Checks a batch's runs as `elcon batch` would before solving each: every
/// run if `every_run` or the sweep has at most `CHECK_EVERY_RUN` (10,000) runs,
/// else [`Batch::covering_runs`]. Memory: the runs in flight and the
/// failures reported, whatever the sweep's size. When `cancel` is
/// cancelled (SIGINT, SIGTERM) no further run is checked: the check ends
/// within the runs in flight, `interrupted`.
pub fn check_batch(
    batch: &Batch,
    ceiling: &Ceiling,
    every_run: bool,
    cancel: &Cancel,
) -> BatchCheck {
    let all = every_run || batch.len() <= CHECK_EVERY_RUN;
    let one = |r: BatchRun| {
        let outcome = isolated(&r.slug(), || {
            batch
                .scene(&r)
                .map_err(RunError::from)
                .and_then(|s| prepare(s, ceiling))
                .map(|p| p.estimate)
        });
        (r, outcome)
    };
    let fresh = BatchCheck::default;
    let mut check = if all {
        (0..batch.len())
            .into_par_iter()
            .filter(|_| !cancel.is_cancelled())
            .filter_map(|i| batch.run(i))
            .map(one)
            .fold(fresh, BatchCheck::add)
            .reduce(fresh, BatchCheck::join)
    } else {
        batch
            .covering_runs()
            .into_par_iter()
            .filter(|_| !cancel.is_cancelled())
            .map(one)
            .fold(fresh, BatchCheck::add)
            .reduce(fresh, BatchCheck::join)
    };
    check.runs = batch.len();
    check.every_run = all;
    check.interrupted = cancel.is_cancelled();
    check.failures.sort_by_key(|(r, _)| r.index);
    check
}
