//! NumPy <-> Rust conversion at the edge (array contract: float64 (n, 3) positions, int64 (m, 3)
//! faces, C-contiguous; outputs are new arrays).

use numpy::ndarray::{Array, IxDyn};
use numpy::{Element, IntoPyArray, PyArrayDyn, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Rows of an `(n, N)` C-contiguous array as fixed-size arrays, borrowed from NumPy (a copy of a
/// 5M-face mesh's arrays was 360 MB at the peak of building its topology).
pub fn rows<'a, T: Element + Copy, const N: usize>(
    array: &'a PyReadonlyArray2<'_, T>,
    name: &str,
) -> PyResult<&'a [[T; N]]> {
    let shape = array.shape();
    if shape[1] != N || !array.is_c_contiguous() {
        return Err(PyValueError::new_err(format!(
            "{name} must be a C-contiguous array of shape (n, {N}), got shape {shape:?}"
        )));
    }
    let flat = array.as_slice()?;
    // SAFETY: `[T; N]` has the size of `N` values of `T` and the alignment of `T`, and a
    // C-contiguous `(n, N)` array is `n * N` consecutive values.
    Ok(unsafe { std::slice::from_raw_parts(flat.as_ptr().cast::<[T; N]>(), flat.len() / N) })
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
