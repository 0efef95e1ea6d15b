//! Ctrl-C during a solve: the work runs off the GIL on a worker thread
//! with a [`Cancel`] token watched, while the calling thread checks
//! Python's signals every [`POLL`] (with the GIL, as Python's own loops
//! do). On KeyboardInterrupt (or any exception a signal handler raises)
//! the token is cancelled, the solvers stop at their next pivot or
//! iteration, and the exception is raised once the worker has ended: no
//! thread is left running, no file half written.

use std::sync::{Condvar, Mutex};
use std::time::Duration;

use elcon_lcp::Cancel;
use pyo3::prelude::*;

use crate::errors::SolveError;

/// How often the calling thread checks Python's signals.
const POLL: Duration = Duration::from_millis(50);

/// The worker's stack: the main thread's usual 8 MiB (the solvers'
/// recursion depth is not bounded by the default 2 MiB of a thread).
const STACK: usize = 8 << 20;

/// Runs `work` without the GIL on a worker thread, its token watched
/// ([`Cancel::watch`]), and raises KeyboardInterrupt (after cancelling the
/// work and waiting for it) when Python's signals say so.
///
/// # Errors
/// The signal handler's exception; a `SolveError` when the worker thread
/// cannot start.
pub(crate) fn detach<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&Cancel) -> T + Send,
) -> PyResult<T> {
    let cancel = Cancel::new();
    let done: (Mutex<Option<std::thread::Result<T>>>, Condvar) = (Mutex::new(None), Condvar::new());
    std::thread::scope(|scope| {
        let worker = std::thread::Builder::new()
            .name("elcon-solve".into())
            .stack_size(STACK)
            .spawn_scoped(scope, || {
                let value = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    cancel.watch(|| work(&cancel))
                }));
                *done.0.lock().unwrap_or_else(|e| e.into_inner()) = Some(value);
                done.1.notify_all();
            })
            .map_err(|e| SolveError::new_err(format!("cannot start the solve's thread: {e}")))?;
        let mut interrupt: Option<PyErr> = None;
        loop {
            let finished = py.detach(|| {
                let guard = done.0.lock().unwrap_or_else(|e| e.into_inner());
                let (guard, _) = done
                    .1
                    .wait_timeout_while(guard, POLL, |v| v.is_none())
                    .unwrap_or_else(|e| e.into_inner());
                guard.is_some()
            });
            if finished {
                break;
            }
            if interrupt.is_none()
                && let Err(e) = py.check_signals()
            {
                cancel.cancel();
                interrupt = Some(e);
            }
        }
        let _ = worker.join();
        let value = done
            .0
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
            .unwrap_or_else(|| Err(Box::new("the solve's thread ended without a value")));
        if let Some(e) = interrupt {
            return Err(e);
        }
        value.map_err(|_| {
            SolveError::new_err(
                "internal error (this is a bug; please report it): the solve's thread panicked",
            )
        })
    })
}
