//! `threads=`: the threads of a solve's products and vector passes, as the
//! command line's `--threads`. None: the global pool (the cores the process
//! may use, or `ELCON_THREADS` / `RAYON_NUM_THREADS` when set before the
//! first solve); a count: a pool of that many threads for this call. The
//! values do not depend on the count. Also the reading of a count given
//! from Python (`threads`, a batch's `jobs`), admitted by the policy the
//! command line applies (elcon-process: a few per core at most).

use elcon_process::Counted;
use elcon_process::threads::{admit_count, pool};
use pyo3::prelude::*;
use pyo3::types::PyBool;

use crate::errors::InputError;

/// A count given from Python as the argument `name`: `None` (the default,
/// which `default` describes), or a whole number of at least `least`. A
/// bool, a float, a string, a negative or a number beyond the machine's
/// range is an `InputError` naming the argument, not Python's `TypeError`
/// or `OverflowError`.
pub(crate) fn count(
    name: &str,
    value: Option<&Bound<'_, PyAny>>,
    least: usize,
    default: &str,
) -> PyResult<Option<usize>> {
    let Some(v) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    let whole = if v.is_instance_of::<PyBool>() {
        None
    } else {
        v.extract::<u64>()
            .ok()
            .and_then(|n| usize::try_from(n).ok())
    };
    whole.filter(|&n| n >= least).map(Some).ok_or_else(|| {
        let shown = v.repr().map_or_else(|_| "?".to_string(), |r| r.to_string());
        InputError::new_err(format!(
            "`{name}` = {shown}: must be a whole number >= {least} (None: {default})"
        ))
    })
}

/// The `threads` argument: a count of at least 1, or None.
pub(crate) fn threads(value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<usize>> {
    count("threads", value, 1, "the cores this process may use")?
        .map(|n| admitted(Counted::Threads, "threads", n))
        .transpose()
}

/// `jobs` (a batch's runs in parallel; 0 or None: one per core), admitted
/// by the policy.
pub(crate) fn jobs(value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<usize>> {
    count("jobs", value, 0, "one per core; 0 too")?
        .map(|n| match n {
            0 => Ok(0),
            n => admitted(Counted::Jobs, "jobs", n),
        })
        .transpose()
}

/// `n` as the process policy admits it for the argument `name`.
fn admitted(what: Counted, name: &str, n: usize) -> PyResult<usize> {
    admit_count(what, &format!("`{name}`"), n).map_err(|e| InputError::new_err(e.to_string()))
}

/// Runs `f` on `threads` threads (`None`: the global pool).
pub(crate) fn with_threads<T: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> PyResult<T> + Send,
) -> PyResult<T> {
    let Some(count) = threads else {
        return f();
    };
    let pool = pool(count).map_err(|e| InputError::new_err(e.to_string()))?;
    pool.install(f)
}
