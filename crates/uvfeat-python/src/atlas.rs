//! `Atlas`: rasterised parametric-space buffers of a mesh (per-frame `update`).

use crate::arrays::{flatten, rows, to_numpy};
use crate::error::guarded;
use crate::mesh::PyTopology;
use crate::settings::named;
use glam::{DMat2, DVec2, DVec3};
use half::f16;
use numpy::{PyArrayDyn, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use uvfeat_core::lookup::surface_point;
use uvfeat_core::relocation::{cross_seam, locate, Located};
use uvfeat_core::settings::Choice;
use uvfeat_core::{Atlas, AtlasOptions, Precision};

#[pyclass(name = "Atlas", module = "uvfeat._core")]
pub struct PyAtlas {
    inner: Atlas,
}

fn positions_of(array: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<DVec3>> {
    Ok(rows::<f64, 3>(array, "positions")?.iter().map(|p| DVec3::from_array(*p)).collect())
}

type Matrix = [[f64; 2]; 2];

fn matrix(m: DMat2) -> Matrix {
    // Row-major, as NumPy users read it.
    [[m.x_axis.x, m.y_axis.x], [m.x_axis.y, m.y_axis.y]]
}

/// Bytes an atlas of `n_faces` faces takes at `resolution` (buffers and per-face tables).
#[pyfunction]
pub fn atlas_bytes(resolution: usize, n_faces: usize) -> u64 {
    uvfeat_core::atlas::atlas_bytes(resolution, n_faces)
}

/// The surfel grid for balls of `radius` summed over about `per_ball` surfels on charts of
/// `surface_area` over `uv_area` (`uvfeat_core::sampling::surfel_grid_width`).
#[pyfunction]
pub fn surfel_grid_width(surface_area: f64, uv_area: f64, radius: f64, per_ball: f64, largest: usize) -> usize {
    uvfeat_core::sampling::surfel_grid_width(surface_area, uv_area, radius, per_ball, largest)
}

#[pymethods]
impl PyAtlas {
    #[new]
    #[pyo3(signature = (topology, positions, resolution = 1024, precision = "f32", memory_budget = 8u64 << 30, coverage_on_first_use = false))]
    fn new(
        py: Python<'_>,
        topology: &PyTopology,
        positions: PyReadonlyArray2<'_, f64>,
        resolution: usize,
        precision: &str,
        memory_budget: u64,
        coverage_on_first_use: bool,
    ) -> PyResult<Self> {
        let precision = named::<Precision>(precision)?;
        let options = AtlasOptions { resolution, precision, memory_budget, coverage_on_first_use };
        let positions = positions_of(&positions)?;
        let topology = topology.inner.clone();
        let inner = guarded(py, || Atlas::new(topology, &positions, &options))?;
        Ok(Self { inner })
    }

    /// Re-evaluates the buffers for new positions (same vertices as the mesh).
    fn update(&mut self, py: Python<'_>, positions: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let positions = positions_of(&positions)?;
        let inner = &mut self.inner;
        guarded(py, || inner.update(&positions))
    }

    #[getter]
    fn resolution(&self) -> usize {
        self.inner.resolution()
    }

    #[getter]
    fn precision(&self) -> &'static str {
        self.inner.precision.name()
    }

    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.vector_buffer(py, &self.inner.buffers().position)
    }

    #[getter]
    fn normal<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.vector_buffer(py, &self.inner.buffers().normal)
    }

    #[getter]
    fn sigma<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let r = self.inner.resolution();
        to_numpy(py, flatten(&self.inner.buffers().sigma), &[r, r, 2])
    }

    #[getter]
    fn theta<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.texel_map(py, self.inner.buffers().theta.clone())
    }

    #[getter]
    fn chart<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<i32>>> {
        self.texel_map(py, self.inner.coverage().chart.clone())
    }

    #[getter]
    fn face<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<i32>>> {
        self.texel_map(py, self.inner.coverage().face.clone())
    }

    #[getter]
    fn border_side<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<i32>>> {
        self.texel_map(py, self.inner.coverage().border_side.clone())
    }

    #[getter]
    fn border<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<bool>>> {
        self.texel_map(py, self.inner.coverage().border_side.iter().map(|&s| s >= 0).collect())
    }

    #[getter]
    fn adjacent_chart<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<i32>>> {
        let sides = &self.inner.topology.sides;
        let adjacent = self
            .inner
            .coverage()
            .border_side
            .iter()
            .map(|&s| usize::try_from(s).map_or(-1, |s| sides[s].adjacent_chart))
            .collect();
        self.texel_map(py, adjacent)
    }

    #[getter]
    fn diagnostics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = &self.inner.coverage().diagnostics;
        let out = PyDict::new(py);
        out.set_item("resolution", self.inner.resolution())?;
        out.set_item("covered_texels", d.covered_texels)?;
        out.set_item("border_texels", d.border_texels)?;
        out.set_item("gutter_texels", d.gutter_texels)?;
        out.set_item("conflicts", d.conflicts)?;
        out.set_item("overlapping_texels", d.overlapping_texels)?;
        out.set_item("charts_without_texels", d.charts_without_texels)?;
        Ok(out)
    }

    /// DESIGN.md §1.5 `locate`: `(status, chart, uv, M_path, jumps)`; status is "inside", "border"
    /// (off the surface) or "missing".
    #[pyo3(signature = (start, chart, target, max_jumps = 32))]
    fn locate(
        &self,
        start: [f64; 2],
        chart: i32,
        target: [f64; 2],
        max_jumps: u32,
    ) -> (&'static str, i32, Option<[f64; 2]>, Option<Matrix>, u32) {
        match locate(&self.inner, DVec2::from_array(start), chart, DVec2::from_array(target), max_jumps) {
            Located::Inside { chart, uv, m_path, jumps, .. } => {
                ("inside", chart, Some(uv.to_array()), Some(matrix(m_path)), jumps)
            }
            Located::Border => ("border", -1, None, None, 0),
            Located::Missing => ("missing", -1, None, None, 0),
        }
    }

    /// Maps `uv` in a border texel of `chart` across its seam: `(chart, uv, M, side)` or None.
    fn cross_seam(&self, uv: [f64; 2], chart: i32) -> Option<(i32, [f64; 2], Matrix, usize)> {
        cross_seam(&self.inner, DVec2::from_array(uv), chart).map(|c| (c.chart, c.uv.to_array(), matrix(c.m), c.side))
    }

    /// The transition map of boundary side `side`: `(origin_from, origin_to, M)` or None.
    fn seam_map(&self, side: usize) -> Option<([f64; 2], [f64; 2], Matrix)> {
        let map = (*self.inner.seam_maps().get(side)?)?;
        Some((map.origin_from.to_array(), map.origin_to.to_array(), matrix(map.m)))
    }

    /// The reverse side of boundary side `side` (-1 when it is not a seam).
    fn reverse_side(&self, side: usize) -> i32 {
        self.inner.topology.sides.get(side).map_or(-1, |s| s.reverse)
    }

    /// Surface position, normal and face at `uv` in `chart` (exact triangle lookup), or None.
    fn surface_point(&self, uv: [f64; 2], chart: i32) -> Option<([f64; 3], [f64; 3], u32)> {
        surface_point(&self.inner, DVec2::from_array(uv), chart)
            .map(|s| (s.position.to_array(), s.normal.to_array(), s.face))
    }
}

impl PyAtlas {
    /// The core atlas.
    pub fn core(&self) -> &Atlas {
        &self.inner
    }

    fn texel_map<'py, T: numpy::Element>(&self, py: Python<'py>, data: Vec<T>) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
        let r = self.inner.resolution();
        to_numpy(py, data, &[r, r])
    }

    fn vector_buffer<'py>(&self, py: Python<'py>, data: &[[f32; 3]]) -> PyResult<Bound<'py, PyAny>> {
        let r = self.inner.resolution();
        let flat = flatten(data);
        Ok(match self.inner.precision {
            Precision::F32 => to_numpy(py, flat, &[r, r, 3])?.into_any(),
            Precision::F16 => to_numpy(py, flat.into_iter().map(f16::from_f32).collect(), &[r, r, 3])?.into_any(),
        })
    }
}
