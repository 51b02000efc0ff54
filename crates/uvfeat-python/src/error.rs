//! The one place where core errors and panics become Python exceptions (classes defined in
//! `uvfeat/errors.py`).

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use uvfeat_core::UvfeatError;

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
    }
}

/// Runs a core call with the GIL released, turning errors into exceptions and a panic into a
/// `RuntimeError` (a panic must never reach Python as a `BaseException`).
pub fn guarded<T: Send>(py: Python<'_>, f: impl FnOnce() -> Result<T, UvfeatError> + Send) -> PyResult<T> {
    let outcome = py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)));
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
