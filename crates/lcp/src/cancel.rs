//! Cancelling a solve in flight: a [`Cancel`] token that another thread
//! (a signal handler, a Python signal check, a batch's scheduler) sets, and
//! that every method polls at the head of each pivot or iteration. A
//! cancelled solve stops within one pivot or iteration and returns
//! [`LcpError::Cancelled`](crate::LcpError::Cancelled); the strategy makes
//! no fallback or retry after it.
//!
//! A token is watched by the thread that runs [`Cancel::watch`]: the solves
//! made on that thread inside the closure see it (the methods' iteration
//! loops run on the calling thread; faer's parallel kernels inside a pivot
//! are not interrupted). A thread with no token watched is never cancelled.

use std::cell::RefCell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A cancellation token: cheap to clone, every clone the same flag.
#[derive(Debug, Clone, Default)]
pub struct Cancel {
    flag: Arc<AtomicBool>,
}

thread_local! {
    /// The token the solves of this thread poll.
    static WATCHED: RefCell<Option<Arc<AtomicBool>>> = const { RefCell::new(None) };
}

impl Cancel {
    /// A token not yet cancelled.
    pub fn new() -> Self {
        Self::default()
    }

    /// A token on an existing flag (e.g. one a signal handler sets:
    /// `signal_hook::flag::register(SIGINT, flag)`).
    pub fn from_flag(flag: Arc<AtomicBool>) -> Self {
        Self { flag }
    }

    /// The flag itself, to hand to a signal handler.
    pub fn flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.flag)
    }

    /// Asks every solve watching this token to stop.
    pub fn cancel(&self) {
        self.flag.store(true, Ordering::SeqCst);
    }

    /// Whether [`Cancel::cancel`] was called (or the flag set).
    pub fn is_cancelled(&self) -> bool {
        self.flag.load(Ordering::Relaxed)
    }

    /// The token the current thread watches, if any: to hand to work this
    /// thread spreads over others (a pool's workers watch no token), which
    /// polls [`Cancel::is_cancelled`] itself.
    pub fn watched() -> Option<Cancel> {
        WATCHED.with(|w| {
            w.borrow()
                .as_ref()
                .map(|flag| Cancel::from_flag(Arc::clone(flag)))
        })
    }

    /// Whether the token the current thread watches is cancelled (false
    /// with no token watched): for stages between solves to poll.
    pub fn requested() -> bool {
        requested()
    }

    /// Runs `f` with this token watched by the current thread: the solves
    /// `f` makes on this thread stop when the token is cancelled. The
    /// thread's previous token is restored afterwards, also when `f`
    /// panics.
    pub fn watch<T>(&self, f: impl FnOnce() -> T) -> T {
        struct Restore(Option<Arc<AtomicBool>>);
        impl Drop for Restore {
            fn drop(&mut self) {
                let previous = self.0.take();
                WATCHED.with(|w| *w.borrow_mut() = previous);
            }
        }
        let previous = WATCHED.with(|w| w.borrow_mut().replace(self.flag()));
        let _restore = Restore(previous);
        f()
    }
}

/// Whether the token this thread watches is cancelled.
pub(crate) fn requested() -> bool {
    WATCHED.with(|w| {
        w.borrow()
            .as_ref()
            .is_some_and(|f| f.load(Ordering::Relaxed))
    })
}

/// A cancellation seen by a method: converts into the method's error type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Cancelled;

/// `Err(Cancelled)` when the watched token is cancelled: the one-line poll
/// at the head of each method's iteration loop.
pub(crate) fn check() -> Result<(), Cancelled> {
    if requested() { Err(Cancelled) } else { Ok(()) }
}

impl From<Cancelled> for crate::LcpError {
    fn from(_: Cancelled) -> Self {
        crate::LcpError::Cancelled
    }
}

impl From<Cancelled> for crate::statistics::Breakdown {
    fn from(_: Cancelled) -> Self {
        crate::statistics::Breakdown::Cancelled
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_token_is_seen_only_inside_watch_on_its_thread() {
        let token = Cancel::new();
        assert!(!requested());
        token.watch(|| {
            assert!(!requested());
            token.cancel();
            assert!(requested() && check().is_err());
            // Another thread does not watch it.
            std::thread::scope(|s| {
                s.spawn(|| assert!(!requested()));
            });
            // A nested token hides it, and it is back after.
            Cancel::new().watch(|| assert!(!requested()));
            assert!(requested());
        });
        assert!(!requested());
        assert!(token.is_cancelled());
    }

    #[test]
    fn a_cancelled_solve_returns_the_typed_error_by_every_method() {
        use crate::{BorderedLcp, LcpError, Method, Options};
        let m = faer::mat![[2.0, 1.0], [1.0, 2.0]];
        let contact = BorderedLcp::new(m, faer::col![0.0, 1.0])
            .unwrap()
            .with_border(faer::mat![[1.0], [1.0]], faer::col![3.0])
            .unwrap();
        let token = Cancel::new();
        token.cancel();
        for method in Method::ALL {
            let e = token.watch(|| contact.solve(method, &Options::default()));
            assert_eq!(e.unwrap_err(), LcpError::Cancelled, "{method}");
            // Outside the watch the same solve answers.
            assert!(contact.solve(method, &Options::default()).is_ok());
        }
    }
}
