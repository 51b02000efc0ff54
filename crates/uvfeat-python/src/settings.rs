//! Settings of a feature computation: the options' public names, choices and defaults, read from
//! the core (`uvfeat_core::settings`), and Python values converted to validated settings.

use crate::error::to_py;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};
use uvfeat_core::features::Feature;
use uvfeat_core::settings::{named_options, option_choices, Choice, ComputeSettings, GivenValue, OptionValue};
use uvfeat_core::UvfeatError;

/// The value of `T` named `value`, or the core's error naming the valid ones.
pub(crate) fn named<T: Choice>(value: &str) -> PyResult<T> {
    T::named(value).map_err(to_py)
}

/// Features from their public names.
pub(crate) fn feature_list(names: &[String]) -> PyResult<Vec<Feature>> {
    names.iter().map(|f| Feature::from_name(f)).collect::<Result<Vec<_>, _>>().map_err(to_py)
}

fn to_dict<'py>(py: Python<'py>, options: Vec<(&'static str, OptionValue)>) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    for (name, value) in options {
        match value {
            OptionValue::Count(n) => out.set_item(name, n)?,
            OptionValue::Number(x) => out.set_item(name, x)?,
            OptionValue::Flag(on) => out.set_item(name, on)?,
            OptionValue::Text(text) => out.set_item(name, text)?,
        }
    }
    Ok(out)
}

fn defaults() -> ComputeSettings {
    ComputeSettings::new(vec![Feature::MeanCurvature], 1.0)
}

/// Every option of a feature computation with its default, in order.
#[pyfunction]
pub fn default_options(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    to_dict(py, named_options(&defaults()))
}

/// The options the paper's choices change, with the paper's values.
#[pyfunction]
pub fn paper_options(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let ours = named_options(&defaults());
    let mut paper = defaults();
    paper.use_paper_choices();
    let changed = named_options(&paper).into_iter().filter(|option| !ours.contains(option)).collect();
    to_dict(py, changed)
}

/// The names each choice option takes, the default first.
#[pyfunction]
pub fn option_choices_by_name(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for (name, names) in option_choices() {
        out.set_item(name, names)?;
    }
    Ok(out)
}

/// A Python value as an option value (`bool` before `int`, since Python's bools are ints).
pub(crate) fn given(name: &str, value: &Bound<'_, PyAny>) -> PyResult<GivenValue> {
    if value.is_instance_of::<PyBool>() {
        Ok(GivenValue::Flag(value.extract()?))
    } else if value.is_instance_of::<PyInt>() || value.is_instance_of::<PyFloat>() {
        Ok(GivenValue::Number(value.extract()?))
    } else if value.is_instance_of::<PyString>() {
        Ok(GivenValue::Text(value.extract()?))
    } else {
        let type_name = value.get_type().name()?.to_string();
        Err(to_py(UvfeatError::InvalidParameter {
            name: "options",
            reason: format!("option {name:?} takes a number, a bool or a name, got a {type_name}"),
        }))
    }
}

/// Every feature name, in output order.
#[pyfunction]
pub fn feature_names() -> Vec<&'static str> {
    Feature::ALL.map(Feature::name).to_vec()
}

/// Builds and validates core settings: `options` maps option names (those of
/// `default_options()`: the sample count, resolution, seed and adaptive flag included) to bool,
/// number or name values; options left out keep their defaults.
#[pyfunction]
#[pyo3(signature = (features, radius, options))]
pub fn compute_settings(features: Vec<String>, radius: f64, options: &Bound<'_, PyDict>) -> PyResult<PySettings> {
    let s = with_options(ComputeSettings::new(feature_list(&features)?, radius), options)?;
    s.validate().map_err(to_py)?;
    Ok(PySettings { inner: s })
}

/// Builds and validates the settings of neighbourhood sampling alone (no features: a
/// user-defined operator reads the samples), as [`compute_settings`] otherwise.
#[pyfunction]
#[pyo3(signature = (radius, options))]
pub fn sampling_settings(radius: f64, options: &Bound<'_, PyDict>) -> PyResult<PySettings> {
    let s = with_options(ComputeSettings::new(Vec::new(), radius), options)?;
    s.validate_sampling().map_err(to_py)?;
    Ok(PySettings { inner: s })
}

/// Validates options on their own, before there is a mesh or a radius.
#[pyfunction]
pub fn check_options(options: &Bound<'_, PyDict>) -> PyResult<()> {
    with_options(ComputeSettings::new(Vec::new(), f64::NAN), options)?.validate_options().map_err(to_py)
}

fn with_options(mut settings: ComputeSettings, options: &Bound<'_, PyDict>) -> PyResult<ComputeSettings> {
    for (key, value) in options.iter() {
        let name: String = key.extract()?;
        settings.set_option(&name, &given(&name, &value)?).map_err(to_py)?;
    }
    Ok(settings)
}

/// Validated settings of a feature computation.
#[pyclass(name = "ComputeSettings", module = "uvfeat._core", frozen)]
pub struct PySettings {
    pub inner: ComputeSettings,
}
