//! The last line of defence around a scene: a panic (a bug, or an
//! allocation the estimate let through that still failed) is caught where
//! the scene starts and becomes [`ProcessError::Bug`] for that scene alone,
//! so that the other scenes of the invocation, or the other runs of a
//! batch, still run and are written. Known failures stay the plain errors
//! of the solver crates; this catches only what nothing else reports.
//!
//! [`install_panic_hook`] makes panics inside [`isolated`] quiet (their
//! message and place go into the report instead of onto the terminal);
//! panics elsewhere print as usual.

use std::cell::RefCell;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;
use std::sync::atomic::{AtomicUsize, Ordering};

use elcon_lcp::Cancel;

use crate::error::ProcessError;

/// Scenes running inside [`isolated`] on any thread (a panic of a solver's
/// worker thread while one runs is reported through that scene).
static INSIDE: AtomicUsize = AtomicUsize::new(0);

static HOOK: Once = Once::new();

thread_local! {
    /// The last panic of this thread: message and place.
    static LAST: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Installs the panic hook (once per process): a panic while a scene runs
/// in [`isolated`] is recorded with its place for the scene's report and
/// not printed; any other panic prints as it would without the hook.
pub fn install_panic_hook() {
    HOOK.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if INSIDE.load(Ordering::SeqCst) == 0 {
                default(info);
                return;
            }
            let message = payload_text(info.payload());
            let text = match info.location() {
                Some(l) => format!("{message} (at {}:{}:{})", l.file(), l.line(), l.column()),
                None => message.to_string(),
            };
            LAST.with(|last| *last.borrow_mut() = Some(text));
        }));
    });
}

/// Runs `f` for scene `scene`; a panic inside it is returned as
/// [`ProcessError::Bug`] with the panic's message (and its place, with
/// [`install_panic_hook`]).
///
/// # Errors
/// `f`'s error, or [`ProcessError::Bug`].
pub fn isolated<T, E: From<ProcessError>>(
    scene: &str,
    f: impl FnOnce() -> Result<T, E>,
) -> Result<T, E> {
    INSIDE.fetch_add(1, Ordering::SeqCst);
    let outcome = catch_unwind(AssertUnwindSafe(f));
    INSIDE.fetch_sub(1, Ordering::SeqCst);
    outcome.unwrap_or_else(|payload| {
        let message = LAST
            .with(|last| last.borrow_mut().take())
            .unwrap_or_else(|| {
                payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_else(|| "(a panic without a message)".into())
            });
        Err(ProcessError::Bug {
            scene: scene.to_string(),
            message,
        }
        .into())
    })
}

/// Runs `f` for scene `scene` with `cancel` watched ([`Cancel::watch`]):
/// the solves inside stop when it is cancelled, and whatever error they
/// then return becomes [`ProcessError::Interrupted`] (a cancelled solve is
/// not a failure of the scene). A scene that finished before the cancel
/// keeps its result.
///
/// # Errors
/// `f`'s error, or [`ProcessError::Interrupted`].
pub fn interruptible<T, E: From<ProcessError>>(
    cancel: &Cancel,
    scene: &str,
    f: impl FnOnce() -> Result<T, E>,
) -> Result<T, E> {
    let interrupted = || {
        ProcessError::Interrupted {
            scene: scene.to_string(),
        }
        .into()
    };
    if cancel.is_cancelled() {
        return Err(interrupted());
    }
    cancel.watch(f).map_err(|e| {
        if cancel.is_cancelled() {
            interrupted()
        } else {
            e
        }
    })
}

/// A panic's message: its `&str` or `String` payload.
fn payload_text(payload: &(dyn std::any::Any + Send)) -> &str {
    payload
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("(a panic without a message)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_the_scenes_bug_report() {
        install_panic_hook();
        let e = isolated::<(), ProcessError>("s", || panic!("index out of bounds")).unwrap_err();
        let text = e.to_string();
        assert!(matches!(e, ProcessError::Bug { .. }));
        assert!(
            text.starts_with("scene `s`: internal error (this is a bug"),
            "{text}"
        );
        assert!(text.contains("index out of bounds (at "), "{text}");
        assert!(text.contains("isolate.rs:"), "{text}");
        // Errors and values pass through.
        assert_eq!(isolated::<_, ProcessError>("s", || Ok(3)).unwrap(), 3);
        let e = isolated::<(), _>("s", || Err(ProcessError::io("f".as_ref(), "no"))).unwrap_err();
        assert!(matches!(e, ProcessError::Io { .. }));
    }

    #[test]
    fn a_cancelled_run_is_interrupted_not_failed() {
        let cancel = Cancel::new();
        assert_eq!(
            interruptible::<_, ProcessError>(&cancel, "s", || Ok(1)).unwrap(),
            1
        );
        let e = interruptible::<(), _>(&cancel, "s", || {
            cancel.cancel();
            Err(ProcessError::io("f".as_ref(), "the solve was cancelled"))
        })
        .unwrap_err();
        assert!(matches!(e, ProcessError::Interrupted { .. }), "{e}");
        // Once cancelled, nothing more starts.
        let e = interruptible::<_, ProcessError>(&cancel, "t", || Ok(2)).unwrap_err();
        assert!(e.to_string().contains("scene `t`: interrupted"), "{e}");
    }
}
