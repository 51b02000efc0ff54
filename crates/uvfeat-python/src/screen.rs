//! The core's shaded pictures of per-vertex values (behind `uvfeat.render`), as arrays.

use crate::arrays::{flatten, rows, to_numpy};
use crate::error::guarded;
use numpy::{PyArrayDyn, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uvfeat_core::render::{front_side, shaded_view, ColourScale, Front, ViewFrame};

/// `(height / s, width / s, 4)` RGBA picture of `values` per vertex on `faces`, whose vertices are
/// at view coordinates `view` (x right, y up, z towards the viewer), through `palette` over
/// `[low, high]`; `left`, `top` and `scale` place the rasterised `height x width` pixels, `s` the
/// supersampling; `front` is 0 (both sides seen), 1 (counter-clockwise side) or -1.
#[pyfunction(name = "shaded_view")]
#[allow(clippy::too_many_arguments)]
pub fn shaded_view_array<'py>(
    py: Python<'py>,
    view: PyReadonlyArray2<'_, f64>,
    faces: PyReadonlyArray2<'_, i64>,
    values: PyReadonlyArray1<'_, f64>,
    palette: PyReadonlyArray2<'_, f64>,
    range: (f64, f64),
    corner: (f64, f64),
    scale: f64,
    size: (usize, usize),
    supersampling: usize,
    front: i32,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let front = match front {
        0 => Front::Both,
        1 => Front::CounterClockwise,
        -1 => Front::Clockwise,
        other => return Err(PyValueError::new_err(format!("front must be -1, 0 or 1, got {other}"))),
    };
    let (view, faces) = (rows::<f64, 3>(&view, "view")?, rows::<i64, 3>(&faces, "faces")?);
    let (values, palette) = (values.as_slice()?, rows::<f64, 3>(&palette, "palette")?);
    let colours = ColourScale { palette, low: range.0, high: range.1 };
    let frame = ViewFrame { left: corner.0, top: corner.1, scale, height: size.0, width: size.1, supersampling };
    let picture = guarded(py, || shaded_view(view, faces, values, &colours, &frame, front))?;
    let s = supersampling.max(1);
    to_numpy(py, flatten(&picture), &[size.0.div_ceil(s), size.1.div_ceil(s), 4])
}

/// The side of `faces` a picture shows: 0 (both: the mesh is open), 1 (the counter-clockwise
/// side: closed, wound outwards) or -1 (closed, wound inwards).
#[pyfunction(name = "front_side")]
pub fn front_side_of(
    py: Python<'_>,
    positions: PyReadonlyArray2<'_, f64>,
    faces: PyReadonlyArray2<'_, i64>,
) -> PyResult<i32> {
    let (positions, faces) = (rows::<f64, 3>(&positions, "positions")?, rows::<i64, 3>(&faces, "faces")?);
    Ok(match guarded(py, || front_side(positions, faces))? {
        Front::Both => 0,
        Front::CounterClockwise => 1,
        Front::Clockwise => -1,
    })
}
