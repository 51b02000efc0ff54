//! `uvfeat._core`: the Python face of `uvfeat-core`. This crate only converts types and errors;
//! every algorithm lives in the core crate.

mod arrays;
mod atlas;
mod error;
mod mesh;
mod output;
mod reference;
mod screen;
mod settings;
mod shapes;
mod unwrap;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SEVERAL_SHEETS", uvfeat_core::output::SEVERAL_SHEETS)?;
    m.add_class::<mesh::PyTopology>()?;
    m.add_class::<atlas::PyAtlas>()?;
    m.add_function(wrap_pyfunction!(shapes::shape, m)?)?;
    m.add_function(wrap_pyfunction!(unwrap::unwrap_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(screen::shaded_view_array, m)?)?;
    m.add_function(wrap_pyfunction!(screen::front_side_of, m)?)?;
    m.add_function(wrap_pyfunction!(atlas::atlas_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(atlas::surfel_grid_width, m)?)?;
    m.add_function(wrap_pyfunction!(settings::feature_names, m)?)?;
    m.add_function(wrap_pyfunction!(settings::default_options, m)?)?;
    m.add_function(wrap_pyfunction!(settings::paper_options, m)?)?;
    m.add_function(wrap_pyfunction!(settings::option_choices_by_name, m)?)?;
    m.add_class::<settings::PySettings>()?;
    m.add_class::<output::PyFeatureMaps>()?;
    m.add_function(wrap_pyfunction!(settings::compute_settings, m)?)?;
    m.add_function(wrap_pyfunction!(settings::sampling_settings, m)?)?;
    m.add_function(wrap_pyfunction!(settings::check_options, m)?)?;
    m.add_function(wrap_pyfunction!(output::vertex_feature_values, m)?)?;
    m.add_function(wrap_pyfunction!(output::sums_apply, m)?)?;
    m.add_function(wrap_pyfunction!(output::compute_maps, m)?)?;
    m.add_function(wrap_pyfunction!(output::neighbourhood_tile_arrays, m)?)?;
    m.add_class::<reference::PyReferenceMesh>()?;
    Ok(())
}
