//! The thread and job policy the command line and the Python package share:
//! how many threads a solve may use (`--threads`, `ELCON_THREADS`, Python's
//! `threads=`) and how many runs of a batch go in parallel (`--jobs`,
//! Python's `jobs=`). Each is at least 1 and at most a few per core
//! ([`MAX_THREADS_PER_CORE`], [`MAX_JOBS_PER_CORE`]): a solve already uses
//! every core, so more only add memory and contention. A solve's values do
//! not depend on its thread count.

use crate::error::{Counted, ProcessError};

/// `--jobs` may ask for at most this many runs per core: runs solve on
/// all cores already, so more only add memory and contention.
pub const MAX_JOBS_PER_CORE: usize = 4;

/// `--threads` (or `ELCON_THREADS`) may ask for at most this many threads
/// per core: a solve's threads share the cores, and 100,000 of them took
/// minutes to start.
pub const MAX_THREADS_PER_CORE: usize = 4;

/// The environment variable that sets a solve's threads when `--threads`
/// is not given.
pub const THREADS_VARIABLE: &str = "ELCON_THREADS";

/// The cores this process may use (its CPU affinity and cgroup quota, as
/// `std::thread::available_parallelism` reads them; 1 when unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `given` threads or jobs, as `source` gave them, once the policy admits
/// them: at least 1, at most [`MAX_THREADS_PER_CORE`] or
/// [`MAX_JOBS_PER_CORE`] per core.
///
/// # Errors
/// [`ProcessError::Count`] naming `source`, the count and the bound.
pub fn admit_count(what: Counted, source: &str, given: usize) -> Result<usize, ProcessError> {
    let per_core = match what {
        Counted::Threads => MAX_THREADS_PER_CORE,
        Counted::Jobs => MAX_JOBS_PER_CORE,
    };
    let cores = cores();
    if given == 0 || given > per_core * cores {
        return Err(ProcessError::Count {
            what,
            given_by: source.to_string(),
            given,
            per_core,
            cores,
        });
    }
    Ok(given)
}

/// The threads of a solve: `given` (`--threads`), else [`THREADS_VARIABLE`]
/// read by `variable` (the environment, in a program), else `None` (rayon's
/// default: the cores the process may use); admitted by [`admit_count`].
///
/// # Errors
/// [`ProcessError::Variable`] for a variable that is not a count;
/// [`ProcessError::Count`] for a count the policy refuses.
pub fn solve_threads(
    given: Option<usize>,
    variable: impl Fn(&str) -> Option<String>,
) -> Result<Option<usize>, ProcessError> {
    let count = match (given, variable(THREADS_VARIABLE)) {
        (Some(n), _) => n,
        (None, Some(v)) => v.trim().parse().map_err(|_| ProcessError::Variable {
            name: THREADS_VARIABLE,
            value: v.clone(),
            reason: "not a count of threads".into(),
        })?,
        (None, None) => return Ok(None),
    };
    let source = format!("--threads / {THREADS_VARIABLE}");
    admit_count(Counted::Threads, &source, count).map(Some)
}

/// A pool of `count` threads, for one call (Python's `threads=`) or, by
/// `build_global`, the process's.
///
/// # Errors
/// [`ProcessError::Pool`] when the threads cannot be started.
pub fn pool(count: usize) -> Result<rayon::ThreadPool, ProcessError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(count)
        .build()
        .map_err(|e| ProcessError::Pool {
            reason: format!("{count} threads: {e}"),
        })
}

/// Bounds the threads of the global rayon pool by `count` (see
/// [`solve_threads`]); `None` leaves rayon's default.
///
/// # Errors
/// [`ProcessError::Pool`] when the pool cannot be built (or was built
/// already).
pub fn set_global_threads(count: Option<usize>) -> Result<(), ProcessError> {
    let Some(count) = count else {
        return Ok(());
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(count)
        .build_global()
        .map_err(|e| ProcessError::Pool {
            reason: e.to_string(),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_at_least_one_and_a_few_per_core() {
        let cores = cores();
        assert_eq!(admit_count(Counted::Jobs, "--jobs", 1).unwrap(), 1);
        let most = MAX_THREADS_PER_CORE * cores;
        assert_eq!(admit_count(Counted::Threads, "t", most).unwrap(), most);
        let e = admit_count(Counted::Threads, "`threads`", most + 1).unwrap_err();
        assert!(e.to_string().contains("threads per core"), "{e}");
        assert!(e.to_string().starts_with("`threads` = "), "{e}");
        let e = admit_count(Counted::Jobs, "--jobs", 0).unwrap_err();
        assert!(e.to_string().contains("at least 1 run in parallel"), "{e}");
        let e = admit_count(Counted::Threads, "--threads", 0).unwrap_err();
        assert!(e.to_string().contains("at least 1"), "{e}");
    }

    #[test]
    fn the_variable_counts_when_no_count_is_given() {
        let env = |v: &'static str| move |name: &str| (name == THREADS_VARIABLE).then(|| v.into());
        assert_eq!(solve_threads(None, env("2")).unwrap(), Some(2));
        assert_eq!(solve_threads(Some(1), env("2")).unwrap(), Some(1));
        assert_eq!(solve_threads(None, |_| None).unwrap(), None);
        let e = solve_threads(None, env("many")).unwrap_err();
        assert_eq!(e.to_string(), "ELCON_THREADS=many: not a count of threads");
        let e = solve_threads(None, env("100000")).unwrap_err();
        assert!(matches!(e, ProcessError::Count { .. }), "{e}");
    }

    #[test]
    fn a_pool_has_the_threads_asked_for() {
        assert_eq!(pool(3).unwrap().current_num_threads(), 3);
    }
}
