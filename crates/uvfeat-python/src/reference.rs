//! The object-space reference (DESIGN.md §5.1): a prepared mesh and per-vertex features.

use crate::arrays::{rows, to_numpy};
use crate::error::guarded;
use crate::settings::{feature_list, named};
use numpy::{PyArrayDyn, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use uvfeat_core::reference::{ReferenceMesh, ReferenceSettings};

/// A mesh welded and connected for the reference (the untimed half-edge step).
#[pyclass(name = "ReferenceMesh", module = "uvfeat._core", frozen)]
pub struct PyReferenceMesh {
    inner: ReferenceMesh,
}

type PerVertex<'py> = (Vec<Bound<'py, PyArrayDyn<f64>>>, Bound<'py, PyArrayDyn<u32>>);

#[pymethods]
impl PyReferenceMesh {
    #[new]
    fn new(py: Python<'_>, positions: PyReadonlyArray2<'_, f64>, faces: PyReadonlyArray2<'_, i64>) -> PyResult<Self> {
        let (p, f) = (rows::<f64, 3>(&positions, "positions")?, rows::<i64, 3>(&faces, "faces")?);
        Ok(Self { inner: guarded(py, || ReferenceMesh::new(p, f))? })
    }

    /// Number of welded vertices.
    #[getter]
    fn n_welded_vertices(&self) -> usize {
        self.inner.connectivity().n_vertices()
    }

    /// (n,) exact geodesic distances from input vertex `source`, `inf` beyond `max_distance`.
    fn geodesic_distances<'py>(
        &self,
        py: Python<'py>,
        source: i64,
        max_distance: f64,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let inner = &self.inner;
        let d = guarded(py, || inner.geodesic_distances(source, max_distance))?;
        let n = d.len();
        to_numpy(py, d, &[n])
    }

    /// `(values, samples)`: one (n,) float64 array per feature and the (n,) sample counts, at
    /// every input vertex or at `vertices` (GIL released, parallel).
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (features, radius, gaussian_method, volume_weighting, rho_min, flat_tol, method, vertices=None))]
    fn compute<'py>(
        &self,
        py: Python<'py>,
        features: Vec<String>,
        radius: f64,
        gaussian_method: &str,
        volume_weighting: &str,
        rho_min: f64,
        flat_tol: f64,
        method: &str,
        vertices: Option<PyReadonlyArray1<'_, i64>>,
    ) -> PyResult<PerVertex<'py>> {
        let mut settings = ReferenceSettings::new(feature_list(&features)?, radius);
        settings.gaussian_method = named(gaussian_method)?;
        settings.volume_weighting = named(volume_weighting)?;
        settings.rho_min_fraction = rho_min;
        settings.flat_tol = flat_tol;
        settings.method = named(method)?;
        let vertices = vertices.map(|v| v.as_slice().map(<[i64]>::to_vec)).transpose()?;
        let inner = &self.inner;
        let result = guarded(py, || inner.compute(&settings, vertices.as_deref()))?;
        let n = result.samples.len();
        let values = result.values.into_iter().map(|v| to_numpy(py, v, &[n])).collect::<PyResult<Vec<_>>>()?;
        Ok((values, to_numpy(py, result.samples, &[n])?))
    }
}
