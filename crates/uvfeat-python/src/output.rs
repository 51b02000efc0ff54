//! Feature maps of a computation (per-texel maps, diagnostics, per-vertex values) and neighbourhood
//! tiles for user-defined operators.

use crate::arrays::{flatten, to_numpy};
use crate::atlas::PyAtlas;
use crate::error::guarded;
use crate::settings::{named, PySettings};
use numpy::{PyArrayDyn, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use uvfeat_core::output::{
    neighbourhood_tile, per_corner, per_vertex, per_vertex_directions, vertex_values, vertex_values_at_radii,
    FeatureMaps,
};
use uvfeat_core::sampling::SampleCounts;
use uvfeat_core::settings::{ComputeSettings, VertexQuery};

/// UVs and geometric vertices of the atlas corners, and one array of values per feature.
type CornerArrays<'py> = (Bound<'py, PyArrayDyn<f64>>, Bound<'py, PyArrayDyn<i64>>, Vec<Bound<'py, PyArrayDyn<f32>>>);

/// Maps of one computation (one radius).
#[pyclass(name = "FeatureMaps", module = "uvfeat._core", frozen)]
pub struct PyFeatureMaps {
    inner: FeatureMaps,
    settings: ComputeSettings,
}

#[pymethods]
impl PyFeatureMaps {
    #[getter]
    fn resolution(&self) -> usize {
        self.inner.resolution
    }

    #[getter]
    fn features(&self) -> Vec<&'static str> {
        self.inner.features.iter().map(|f| f.name()).collect()
    }

    /// (W_c, W_c) map of the k-th feature.
    fn values<'py>(&self, py: Python<'py>, k: usize) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.map(py, self.inner.values[k].clone())
    }

    /// (W_c, W_c) standard errors of the k-th feature, or None when not requested.
    fn standard_errors<'py>(&self, py: Python<'py>, k: usize) -> PyResult<Option<Bound<'py, PyArrayDyn<f32>>>> {
        self.inner.standard_errors.as_ref().map(|e| self.map(py, e[k].clone())).transpose()
    }

    #[getter]
    fn chart<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<i32>>> {
        self.map(py, self.inner.chart.clone())
    }

    #[getter]
    fn n_valid<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<u32>>> {
        self.map(py, self.inner.n_valid.clone())
    }

    #[getter]
    fn n_missing<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<u32>>> {
        self.map(py, self.inner.n_missing.clone())
    }

    #[getter]
    fn n_border<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<u32>>> {
        self.map(py, self.inner.n_border.clone())
    }

    #[getter]
    fn second_stage<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<bool>>> {
        self.map(py, self.inner.second_stage.clone())
    }

    /// (W_c, W_c, 2, 3) principal directions `[d1, d2]` of the fit, or None unless method "fit".
    #[getter]
    fn principal_directions<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArrayDyn<f32>>>> {
        let w = self.inner.resolution;
        self.inner
            .directions
            .as_ref()
            .map(|d| to_numpy(py, d.iter().flatten().flatten().copied().collect(), &[w, w, 2, 3]))
            .transpose()
    }

    /// (W_c, W_c) relative RMS residual of the fit, or None unless method "fit".
    #[getter]
    fn fit_residual<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArrayDyn<f32>>>> {
        self.inner.fit_residual.as_ref().map(|r| self.map(py, r.clone())).transpose()
    }

    /// (W_c, W_c) neighbourhood area over pi r^2 (about 1 for one sheet, 2 for both sides of a
    /// thin part; NaN off the charts).
    #[getter]
    fn area_ratio<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.map(py, self.inner.area_ratio.clone())
    }

    /// (W_c, W_c) the area one sheet of the surface holds in each texel's ball, over pi r^2 (1 on
    /// a smooth mesh, more on a rough one; NaN off the charts): the unit of the several-sheets flag.
    #[getter]
    fn sheet_area<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.map(py, self.inner.sheet_area.clone())
    }

    /// (n_vertices, 2, 3) principal directions of the fit, evaluated at every vertex.
    fn per_vertex_directions<'py>(&self, py: Python<'py>, atlas: &PyAtlas) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let (settings, core) = (&self.settings, atlas.core());
        let directions = guarded(py, || per_vertex_directions(core, settings))?;
        let n = directions.len();
        to_numpy(py, directions.into_iter().flatten().flatten().collect(), &[n, 2, 3])
    }

    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = &self.inner.summary;
        let out = PyDict::new(py);
        out.set_item("texels", s.texels)?;
        out.set_item("second_stage_fraction", s.second_stage_fraction)?;
        out.set_item("clamped_fraction", s.clamped_fraction)?;
        out.set_item("missing_fraction", s.missing_fraction)?;
        out.set_item("truncated_texels", s.truncated_texels)?;
        out.set_item("several_sheet_texels", s.several_sheet_texels)?;
        out.set_item("mean_valid_samples", s.mean_valid)?;
        Ok(out)
    }

    /// The UV `(n_corners, 2)` and geometric vertex `(n_corners,)` of every atlas corner and, per
    /// feature, its chart-masked texture lookup (list of `(n_corners,)` arrays, NaN where none).
    fn per_corner<'py>(&self, py: Python<'py>, atlas: &PyAtlas) -> PyResult<CornerArrays<'py>> {
        let (maps, core) = (&self.inner, atlas.core());
        let (uvs, vertex, values) = guarded(py, || Ok(per_corner(core, maps)))?;
        let n = uvs.len();
        let uvs = to_numpy(py, uvs.iter().flat_map(|uv| uv.to_array()).collect(), &[n, 2])?;
        let vertex = to_numpy(py, vertex.into_iter().map(i64::from).collect(), &[n])?;
        Ok((uvs, vertex, values.into_iter().map(|v| to_numpy(py, v, &[n])).collect::<PyResult<_>>()?))
    }

    /// Per-vertex values of every feature (list of (n_vertices,) arrays), by texture lookup or
    /// direct evaluation.
    fn per_vertex<'py>(
        &self,
        py: Python<'py>,
        atlas: &PyAtlas,
        query: &str,
    ) -> PyResult<Vec<Bound<'py, PyArrayDyn<f32>>>> {
        let query: VertexQuery = named(query)?;
        let (maps, settings, core) = (&self.inner, &self.settings, atlas.core());
        let values = guarded(py, || per_vertex(core, maps, settings, query))?;
        values
            .into_iter()
            .map(|v| {
                let n = v.len();
                to_numpy(py, v, &[n])
            })
            .collect()
    }
}

impl PyFeatureMaps {
    fn map<'py, T: numpy::Element>(&self, py: Python<'py>, data: Vec<T>) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
        let w = self.inner.resolution;
        to_numpy(py, data, &[w, w])
    }
}

/// Runs a feature computation on an atlas (GIL released, parallel).
#[pyfunction]
pub fn compute_maps(py: Python<'_>, atlas: &PyAtlas, settings: &PySettings) -> PyResult<PyFeatureMaps> {
    let (core, s) = (atlas.core(), &settings.inner);
    let inner = guarded(py, || FeatureMaps::compute(core, s))?;
    Ok(PyFeatureMaps { inner, settings: settings.inner.clone() })
}

/// Whether `settings` are evaluated at the vertices from the surfels' moments on `atlas` (the
/// core's choice of integration) rather than read from maps.
#[pyfunction]
pub fn sums_apply(atlas: &PyAtlas, settings: &PySettings) -> bool {
    uvfeat_core::output::sums_apply(atlas.core(), &settings.inner)
}

/// One array of values per feature, the surfels each vertex summed, and those of them a mesh
/// border passes through.
type VertexArrays<'py> = (Vec<Bound<'py, PyArrayDyn<f32>>>, Bound<'py, PyArrayDyn<u32>>, Bound<'py, PyArrayDyn<u32>>);

/// Every feature at every input vertex, evaluated at the vertices from the surfels' moments (GIL
/// released, parallel); with `radii`, one radius per input vertex instead of the settings' radius.
#[pyfunction]
#[pyo3(signature = (atlas, settings, radii=None))]
pub fn vertex_feature_values<'py>(
    py: Python<'py>,
    atlas: &PyAtlas,
    settings: &PySettings,
    radii: Option<PyReadonlyArray1<'_, f64>>,
) -> PyResult<VertexArrays<'py>> {
    let (core, s) = (atlas.core(), &settings.inner);
    let radii = radii.as_ref().map(|r| r.as_slice()).transpose()?;
    let at_vertices = guarded(py, || match radii {
        Some(radii) => vertex_values_at_radii(core, s, radii),
        None => vertex_values(core, s),
    })?;
    let n = at_vertices.counts.len();
    let arrays = at_vertices.values.into_iter().map(|v| to_numpy(py, v, &[n])).collect::<PyResult<_>>()?;
    let count = |get: fn(&SampleCounts) -> u32| to_numpy(py, at_vertices.counts.iter().map(get).collect(), &[n]);
    Ok((arrays, count(|c| c.valid)?, count(|c| c.border)?))
}

type TileArrays<'py> = (
    Bound<'py, PyArrayDyn<u32>>,
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<f64>>,
    Bound<'py, PyArrayDyn<bool>>,
);

/// Neighbourhood samples of texels `start..stop` of the computation texture:
/// `(texels (T,), centres (T,3), centre_normals (T,3), positions (T,N,3), normals (T,N,3),
/// areas (T,N), valid (T,N))`.
#[pyfunction]
pub fn neighbourhood_tile_arrays<'py>(
    py: Python<'py>,
    atlas: &PyAtlas,
    settings: &PySettings,
    start: usize,
    stop: usize,
) -> PyResult<TileArrays<'py>> {
    let (core, s) = (atlas.core(), &settings.inner);
    let w = s.resolution;
    let range = start.min(w * w)..stop.min(w * w);
    let tile = guarded(py, || neighbourhood_tile(core, s, range))?;
    let (t, n) = (tile.texels.len(), tile.samples);
    Ok((
        to_numpy(py, tile.texels, &[t])?,
        to_numpy(py, flatten(&tile.centres), &[t, 3])?,
        to_numpy(py, flatten(&tile.centre_normals), &[t, 3])?,
        to_numpy(py, flatten(&tile.positions), &[t, n, 3])?,
        to_numpy(py, flatten(&tile.normals), &[t, n, 3])?,
        to_numpy(py, tile.areas, &[t, n])?,
        to_numpy(py, tile.valid, &[t, n])?,
    ))
}
