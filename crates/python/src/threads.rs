//! `threads=`: the threads of a solve's products and vector passes, as the
//! command line's `--threads`. None: the global pool (the cores the process
//! may use, or `ELCON_THREADS` / `RAYON_NUM_THREADS` when set before the
//! first solve); a count: a pool of that many threads for this call. The
//! values do not depend on the count. Also the reading of a count given
//! from Python (`threads`, a batch's `jobs`).

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
    count("threads", value, 1, "the cores this process may use")
}

/// Runs `f` on `threads` threads (`None`: the global pool).
pub(crate) fn with_threads<T: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> PyResult<T> + Send,
) -> PyResult<T> {
    let Some(count) = threads else {
        return f();
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(count)
        .build()
        .map_err(|e| InputError::new_err(format!("a pool of {count} threads: {e}")))?;
    pool.install(f)
}
