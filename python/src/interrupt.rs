//! Ctrl-C during one long call (`simulate`, `lyapunov`): the work runs on
//! its own thread while the calling thread waits without the GIL and looks
//! for a pending signal every [`POLL`], so KeyboardInterrupt is raised
//! within about that time, and a panic of the work never reaches Python as
//! a `PanicException` (it becomes a `RunError`).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use pyo3::prelude::*;

use crate::errors::run_error;

/// How often the waiting thread looks for Ctrl-C: well under the 0.1 s a
/// user notices, long against the cost of taking the GIL.
const POLL: Duration = Duration::from_millis(20);

/// The payload of the unwind that stops cancelled work ([`Cancel::check`]).
struct Cancelled;

/// The flag a cancelled call sets; work that can stop early checks it.
#[derive(Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// Stops the work (by unwinding to [`run`]'s thread, without the panic
    /// hook: nothing is printed) if the call was cancelled.
    pub fn check(&self) {
        if self.0.load(Ordering::Relaxed) {
            std::panic::resume_unwind(Box::new(Cancelled));
        }
    }
}

/// Runs `work` on a thread of its own and waits for it, raising the
/// pending KeyboardInterrupt (or other signal handler error) within
/// [`POLL`] of Ctrl-C. Work that checks its [`Cancel`] then stops; work
/// that cannot (a Lyapunov run) finishes on its thread, its result
/// dropped.
pub fn run<T: Send + 'static>(py: Python<'_>, work: impl FnOnce(&Cancel) -> T + Send + 'static) -> PyResult<T> {
    let cancel = Cancel::default();
    let (tx, rx) = channel();
    let flag = cancel.clone();
    std::thread::Builder::new()
        .name("rocking-run".into())
        .spawn(move || {
            let done = catch_unwind(AssertUnwindSafe(|| work(&flag)));
            // The caller may be gone (interrupted): nobody to tell then.
            let _ = tx.send(done);
        })
        .map_err(|e| run_error(&anyhow::anyhow!("starting the run's thread: {e}")))?;
    // Shared with the GIL-free waits (a receiver alone is not Sync).
    let rx = Mutex::new(rx);
    loop {
        match py.detach(|| rx.lock().unwrap_or_else(PoisonError::into_inner).recv_timeout(POLL)) {
            Ok(Ok(value)) => return Ok(value),
            Ok(Err(panic)) => {
                let what = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "a panic".to_string());
                return Err(run_error(&anyhow::anyhow!("internal error: {what}")));
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(run_error(&anyhow::anyhow!(
                    "internal error: the run's thread ended without a result"
                )));
            }
            Err(RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    cancel.0.store(true, Ordering::Relaxed);
                    return Err(e);
                }
            }
        }
    }
}
