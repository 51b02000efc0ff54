//! The core's screen rasteriser (behind `uvfeat.render`), as arrays.

use crate::arrays::{flatten, rows, to_numpy};
use crate::error::guarded;
use numpy::{PyArrayDyn, PyReadonlyArray2};
use pyo3::prelude::*;
use uvfeat_core::output::rasterise_screen;

type FragmentArrays<'py> = (Bound<'py, PyArrayDyn<i64>>, Bound<'py, PyArrayDyn<f64>>);

/// Z-buffer rasterisation of `faces` with corners `screen` in pixel units (x right, y down, z
/// towards the viewer): `(face, weights)` per pixel of the `height x width` picture, face -1 where
/// nothing is drawn.
#[pyfunction(name = "rasterise_screen")]
pub fn rasterise_screen_arrays<'py>(
    py: Python<'py>,
    screen: PyReadonlyArray2<'_, f64>,
    faces: PyReadonlyArray2<'_, i64>,
    height: usize,
    width: usize,
) -> PyResult<FragmentArrays<'py>> {
    let (points, triangles) = (rows::<f64, 3>(&screen, "screen")?, rows::<i64, 3>(&faces, "faces")?);
    let fragments = guarded(py, || rasterise_screen(points, triangles, height, width))?;
    Ok((
        to_numpy(py, fragments.face, &[height, width])?,
        to_numpy(py, flatten(&fragments.weights), &[height, width, 3])?,
    ))
}
