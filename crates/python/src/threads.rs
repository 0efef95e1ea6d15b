//! `threads=`: the threads of a solve's products and vector passes, as the
//! command line's `--threads`. None: the global pool (the cores the process
//! may use, or `ELCON_THREADS` / `RAYON_NUM_THREADS` when set before the
//! first solve); a count: a pool of that many threads for this call. The
//! values do not depend on the count.

use pyo3::prelude::*;

use crate::errors::InputError;

/// Runs `f` on `threads` threads (`None`: the global pool).
pub(crate) fn with_threads<T: Send>(
    threads: Option<i64>,
    f: impl FnOnce() -> PyResult<T> + Send,
) -> PyResult<T> {
    let Some(count) = threads else {
        return f();
    };
    let count = usize::try_from(count)
        .ok()
        .filter(|&c| c >= 1)
        .ok_or_else(|| {
            InputError::new_err(format!(
                "`threads` = {count}: must be a whole number >= 1 (None: the cores this process may use)"
            ))
        })?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(count)
        .build()
        .map_err(|e| InputError::new_err(format!("a pool of {count} threads: {e}")))?;
    pool.install(f)
}
