//! The one place where core errors and panics become Python exceptions (classes defined in
//! `uvfeat/errors.py`).

use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::time::Duration;
use uvfeat_core::{cancel, UvfeatError};

/// How often a waiting call looks for Ctrl-C (Python runs signal handlers in the main thread, so a
/// call that holds it in native code must look itself).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Stack of the thread a call runs on: the main thread's usual 8 MiB.
const COMPUTING_STACK: usize = 8 << 20;

pyo3::import_exception!(uvfeat.errors, InvalidMeshError);
pyo3::import_exception!(uvfeat.errors, UVError);
pyo3::import_exception!(uvfeat.errors, InvalidParameterError);
pyo3::import_exception!(uvfeat.errors, ResolutionTooLargeError);

/// Maps a core error to the Python exception class that names its kind.
pub fn to_py(err: UvfeatError) -> PyErr {
    let msg = err.to_string();
    match err {
        UvfeatError::NoUvs | UvfeatError::NonFiniteUv { .. } | UvfeatError::UvOutOfRange { .. } => {
            UVError::new_err(msg)
        }
        UvfeatError::AllUvDegenerate { .. } => UVError::new_err(msg),
        UvfeatError::EmptyMesh { .. }
        | UvfeatError::NonFinitePosition { .. }
        | UvfeatError::IndexOutOfRange { .. }
        | UvfeatError::ShapeMismatch { .. }
        | UvfeatError::FrameVertexCount { .. }
        | UvfeatError::DegenerateMesh { .. } => InvalidMeshError::new_err(msg),
        UvfeatError::ResolutionTooLarge { .. } => ResolutionTooLargeError::new_err(msg),
        UvfeatError::InvalidResolution { .. }
        | UvfeatError::InvalidParameter { .. }
        | UvfeatError::PointOutOfDomain { .. } => InvalidParameterError::new_err(msg),
        UvfeatError::Cancelled => PyKeyboardInterrupt::new_err(msg),
    }
}

/// Runs a core call with the GIL released, turning errors into exceptions and a panic into a
/// `RuntimeError` (a panic must never reach Python as a `BaseException`).
///
/// The call runs on a thread of its own while this one waits for it and runs Python's signal
/// handlers every [`SIGNAL_POLL`]: on Ctrl-C (a handler raising, `KeyboardInterrupt` by default)
/// the core is asked to stop ([`cancel`]), its result is dropped and the handler's exception is
/// raised; the next call starts afresh.
pub fn guarded<T: Send>(py: Python<'_>, f: impl FnOnce() -> Result<T, UvfeatError> + Send) -> PyResult<T> {
    let mut interrupted = None;
    let outcome = std::thread::scope(|scope| -> PyResult<_> {
        let (sender, mut receiver) = channel();
        std::thread::Builder::new()
            .name("uvfeat".into())
            // As much stack as the main thread the call used to run on.
            .stack_size(COMPUTING_STACK)
            .spawn_scoped(scope, move || sender.send(catch_unwind(AssertUnwindSafe(f))))
            .map_err(|error| PyRuntimeError::new_err(format!("cannot start a computing thread: {error}")))?;
        loop {
            // The receiver goes with the wait (it may not be shared with the detached thread).
            let (back, received) = py.detach(move || {
                let received = receiver.recv_timeout(SIGNAL_POLL);
                (receiver, received)
            });
            receiver = back;
            match received {
                Ok(outcome) => break Ok(outcome),
                // Handlers run until the first one raises; a later signal stays pending for Python,
                // which handles it once this call has returned (running it here would drop its
                // exception: a second Ctrl-C, or a handler's SystemExit).
                Err(RecvTimeoutError::Timeout) if interrupted.is_none() => {
                    if let Err(error) = py.check_signals() {
                        interrupted = Some(error);
                        cancel::request();
                    }
                }
                Err(RecvTimeoutError::Timeout) => {}
                // The thread sends before it ends, panic or not; nothing else drops the sender.
                Err(RecvTimeoutError::Disconnected) => unreachable!("the computing thread ended without a result"),
            }
        }
    })?;
    if let Some(error) = interrupted {
        cancel::clear();
        return Err(error);
    }
    match outcome {
        Ok(result) => result.map_err(to_py),
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(PyRuntimeError::new_err(format!("internal error in uvfeat (please report): {what}")))
        }
    }
}
