//! Renders that Ctrl-C stops: the work runs on a thread of its own while
//! the calling thread runs Python's signal handlers.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;

use pyo3::prelude::*;

use crate::guard;

/// Runs `work` on a thread of its own while the calling thread, the GIL
/// released between checks, runs Python's signal handlers every 50 ms: a
/// Ctrl-C (KeyboardInterrupt, or whatever a handler raises) sets `cancel`,
/// waits for `work` to stop (the CPU ray caster stops between bands of
/// rows) and is raised; the scene is left as it was.
pub(crate) fn interruptible<T: Send>(
    py: Python<'_>,
    cancel: &AtomicBool,
    work: impl FnOnce() -> PyResult<T> + Send,
) -> PyResult<T> {
    let done: Mutex<Option<PyResult<T>>> = Mutex::new(None);
    let ready = Condvar::new();
    std::thread::scope(|s| {
        s.spawn(|| {
            let result = guard(work);
            *done.lock().expect("result lock") = Some(result);
            ready.notify_all();
        });
        let wait = |timeout: Option<Duration>| {
            py.detach(|| {
                let mut slot = done.lock().expect("result lock");
                loop {
                    if let Some(result) = slot.take() {
                        return Some(result);
                    }
                    match timeout {
                        Some(t) => {
                            let (next, waited) = ready.wait_timeout(slot, t).expect("result lock");
                            slot = next;
                            if waited.timed_out() {
                                return slot.take();
                            }
                        }
                        None => slot = ready.wait(slot).expect("result lock"),
                    }
                }
            })
        };
        loop {
            if let Some(result) = wait(Some(Duration::from_millis(50))) {
                return result;
            }
            if let Err(interrupt) = py.check_signals() {
                cancel.store(true, Ordering::Relaxed);
                let _ = wait(None);
                return Err(interrupt);
            }
        }
    })
}
