//! Analytic meshes of the core, as arrays.

use crate::arrays::{flatten, to_numpy};
use numpy::PyArrayDyn;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use uvfeat_core::shapes;

type ShapeArrays<'py> = (
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<i64>>,
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<i64>>,
);

/// Builds an analytic mesh by name; returns `(positions, faces, uvs, uv_faces)`.
#[pyfunction]
#[pyo3(signature = (name, sizes, counts, mirrored = false))]
pub fn shape<'py>(
    py: Python<'py>,
    name: &str,
    sizes: Vec<f64>,
    counts: Vec<usize>,
    mirrored: bool,
) -> PyResult<ShapeArrays<'py>> {
    let size = |k: usize| sizes.get(k).copied().unwrap_or(1.0);
    let count = |k: usize| counts.get(k).copied().unwrap_or(32);
    let mesh = match name {
        "uv_sphere" => shapes::uv_sphere(size(0), count(0), count(1)),
        "ellipsoid" => shapes::ellipsoid([size(0), size(1), size(2)], count(0), count(1)),
        "torus" => shapes::torus(size(0), size(1), count(0), count(1)),
        "cylinder" => shapes::cylinder(size(0), size(1), count(0), count(1)),
        "plane" => shapes::plane(size(0), count(0)),
        "split_plane" => shapes::split_plane(count(0), mirrored),
        other => return Err(PyValueError::new_err(format!("unknown shape {other:?}"))),
    };
    let (nv, nf, nu) = (mesh.positions.len(), mesh.faces.len(), mesh.uvs.len());
    Ok((
        to_numpy(py, flatten(&mesh.positions), &[nv, 3])?,
        to_numpy(py, flatten(&mesh.faces), &[nf, 3])?,
        to_numpy(py, flatten(&mesh.uvs), &[nu, 2])?,
        to_numpy(py, flatten(&mesh.uv_faces), &[nf, 3])?,
    ))
}
