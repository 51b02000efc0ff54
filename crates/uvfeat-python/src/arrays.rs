//! NumPy <-> Rust conversion at the edge (array contract: float64 (n, 3) positions, int64 (m, 3)
//! faces, C-contiguous; outputs are new arrays).

use numpy::ndarray::{Array, IxDyn};
use numpy::{Element, IntoPyArray, PyArrayDyn, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Rows of an `(n, N)` C-contiguous array as fixed-size arrays.
pub fn rows<T: Element + Copy, const N: usize>(array: &PyReadonlyArray2<'_, T>, name: &str) -> PyResult<Vec<[T; N]>> {
    let shape = array.shape();
    if shape[1] != N || !array.is_c_contiguous() {
        return Err(PyValueError::new_err(format!(
            "{name} must be a C-contiguous array of shape (n, {N}), got shape {shape:?}"
        )));
    }
    let flat = array.as_slice()?;
    Ok(flat.chunks_exact(N).map(|c| std::array::from_fn(|k| c[k])).collect())
}

/// A new NumPy array of `shape` from flat row-major data.
pub fn to_numpy<'py, T: Element>(
    py: Python<'py>,
    data: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let array = Array::from_shape_vec(IxDyn(shape), data).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

/// Flattens fixed-size rows into one vector.
pub fn flatten<T: Copy, const N: usize>(rows: &[[T; N]]) -> Vec<T> {
    rows.iter().flatten().copied().collect()
}
