//! `uvfeat._core`: the Python face of `uvfeat-core`. This crate only converts types and errors;
//! every algorithm lives in the core crate.

mod arrays;
mod atlas;
mod error;
mod features;
mod options;
mod reference;
mod shapes;
mod topology;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<topology::PyTopology>()?;
    m.add_class::<atlas::PyAtlas>()?;
    m.add_function(wrap_pyfunction!(shapes::shape, m)?)?;
    m.add_function(wrap_pyfunction!(atlas::buffer_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(options::feature_names, m)?)?;
    m.add_function(wrap_pyfunction!(options::default_options, m)?)?;
    m.add_function(wrap_pyfunction!(options::paper_options, m)?)?;
    m.add_function(wrap_pyfunction!(options::option_choices_by_name, m)?)?;
    m.add_class::<features::PySettings>()?;
    m.add_class::<features::PyFeatureMaps>()?;
    m.add_function(wrap_pyfunction!(features::compute_settings, m)?)?;
    m.add_function(wrap_pyfunction!(features::compute_maps, m)?)?;
    m.add_function(wrap_pyfunction!(features::neighbourhood_tile_arrays, m)?)?;
    m.add_class::<reference::PyReferenceMesh>()?;
    Ok(())
}
