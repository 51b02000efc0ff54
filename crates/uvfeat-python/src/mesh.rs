//! `Topology`: the once-per-mesh pre-processing (welding, charts, edge classes).

use crate::arrays::{rows, to_numpy};
use crate::error::guarded;
use numpy::{PyArrayDyn, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use uvfeat_core::mesh::{Topology, TriangleMesh};

#[pyclass(name = "Topology", module = "uvfeat._core", frozen)]
pub struct PyTopology {
    pub inner: Arc<Topology>,
}

#[pymethods]
impl PyTopology {
    #[new]
    #[pyo3(signature = (positions, faces, uvs, uv_faces, weld_tolerance = 0.0))]
    fn new(
        py: Python<'_>,
        positions: PyReadonlyArray2<'_, f64>,
        faces: PyReadonlyArray2<'_, i64>,
        uvs: PyReadonlyArray2<'_, f64>,
        uv_faces: PyReadonlyArray2<'_, i64>,
        weld_tolerance: f64,
    ) -> PyResult<Self> {
        let (p, f) = (rows::<f64, 3>(&positions, "positions")?, rows::<i64, 3>(&faces, "faces")?);
        let (uv, uvf) = (rows::<f64, 2>(&uvs, "uvs")?, rows::<i64, 3>(&uv_faces, "uv_faces")?);
        let inner = guarded(py, || {
            let mesh = TriangleMesh::new(p, f, uv, uvf)?;
            Topology::build(&mesh, weld_tolerance)
        })?;
        Ok(Self { inner: Arc::new(inner) })
    }

    #[getter]
    fn n_charts(&self) -> usize {
        self.inner.n_charts
    }

    #[getter]
    fn n_geometric_vertices(&self) -> usize {
        self.inner.n_geometric()
    }

    /// Geometric (welded) vertex id of every input vertex.
    #[getter]
    fn vertex_ids<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<i64>>> {
        let ids = self.inner.vertex_ids.iter().map(|&v| i64::from(v)).collect::<Vec<_>>();
        let n = ids.len();
        to_numpy(py, ids, &[n])
    }

    /// Chart id of every face (-1 for zero-area UV triangles).
    #[getter]
    fn face_chart<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<i32>>> {
        to_numpy(py, self.inner.face_chart.clone(), &[self.inner.face_chart.len()])
    }

    #[getter]
    fn diagnostics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = &self.inner.diagnostics;
        let out = PyDict::new(py);
        out.set_item("input_vertices", d.input_vertices)?;
        out.set_item("geometric_vertices", d.geometric_vertices)?;
        out.set_item("faces", self.inner.faces.len())?;
        out.set_item("charts", self.inner.n_charts)?;
        out.set_item("degenerate_uv_faces", d.degenerate_uv_faces)?;
        out.set_item("mirrored_uv_faces", d.mirrored_uv_faces)?;
        out.set_item("interior_edges", d.edges.interior)?;
        out.set_item("seam_edges", d.edges.seam)?;
        out.set_item("border_edges", d.edges.border)?;
        out.set_item("non_manifold_edges", d.edges.non_manifold)?;
        Ok(out)
    }
}
