//! The setup's elastostatic model in Python: its parameters with their nominal stiffness
//! ([`stiffid::app::document::parameters`]) and a setup with another `[model]` table
//! ([`stiffid::internal::model::parse_fragment`]).

use crate::error::raise;
use nalgebra::DVector;
use pyo3::prelude::*;
use pyo3::types::PyList;
use stiffid::app::document::parameters;
use stiffid::Setup;

/// The parameters of `setup`'s model with their nominal stiffness (`None` where the setup has
/// none), as the documents list them.
pub fn parameters<'py>(py: Python<'py>, setup: &Setup) -> PyResult<Bound<'py, PyList>> {
    let model = setup.model();
    let h = setup
        .model_nominal_compliance()
        .unwrap_or_else(|| DVector::from_element(model.len(), f64::NAN));
    let document = parameters::stiffness(&model.parameters(), &h);
    Ok(crate::documents::to_object(py, &document)?.cast_into::<PyList>()?)
}

/// `setup` with the virtual springs of the `[model]` fragment `toml` (named `source_name`).
pub fn with_model(setup: &Setup, toml: &str, source_name: &str) -> PyResult<Setup> {
    let springs = stiffid::internal::model::parse_fragment(toml, source_name, setup.robot())
        .map_err(raise)?;
    let built = setup.to_builder().with_virtual_springs(springs).build();
    built.map_err(|e| crate::error::raise_in(source_name, e))
}
