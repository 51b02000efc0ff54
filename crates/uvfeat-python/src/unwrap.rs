//! The core's automatic atlas, as arrays.

use crate::arrays::{flatten, rows, to_numpy};
use crate::error::guarded;
use numpy::{PyArrayDyn, PyReadonlyArray2};
use pyo3::prelude::*;
use uvfeat_core::unwrap::{unwrap, UnwrapOptions};

type UnwrapArrays<'py> = (Bound<'py, PyArrayDyn<f64>>, Bound<'py, PyArrayDyn<i64>>, usize);

/// Normal-cone charts packed into `[0, 1]^2`; returns `(uvs, uv_faces, n_charts)`. An option left
/// as `None` takes the core's default.
#[pyfunction(name = "unwrap")]
#[pyo3(signature = (positions, faces, resolution = None, padding = None, max_angle = None))]
pub fn unwrap_arrays<'py>(
    py: Python<'py>,
    positions: PyReadonlyArray2<'_, f64>,
    faces: PyReadonlyArray2<'_, i64>,
    resolution: Option<usize>,
    padding: Option<f64>,
    max_angle: Option<f64>,
) -> PyResult<UnwrapArrays<'py>> {
    let (p, f) = (rows::<f64, 3>(&positions, "positions")?, rows::<i64, 3>(&faces, "faces")?);
    let defaults = UnwrapOptions::default();
    let options = UnwrapOptions {
        max_angle_degrees: max_angle.unwrap_or(defaults.max_angle_degrees),
        resolution: resolution.unwrap_or(defaults.resolution),
        padding: padding.unwrap_or(defaults.padding),
    };
    let atlas = guarded(py, || unwrap(p, f, &options))?;
    let (n_uvs, n_faces) = (atlas.uvs.len(), atlas.uv_faces.len());
    Ok((
        to_numpy(py, flatten(&atlas.uv_rows()), &[n_uvs, 2])?,
        to_numpy(py, flatten(&atlas.uv_face_rows()), &[n_faces, 3])?,
        atlas.n_charts,
    ))
}
