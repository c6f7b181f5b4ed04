//! `stiffid.identify(..., compare_models=True)`: the model-comparison job
//! ([`stiffid::app::identify::comparison`]), its document as `stiffid identify --compare-models --json`
//! writes it, plus the selection path as arrays and names.

use crate::documents;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stiffid::app::identify::comparison::Report;
use stiffid::internal::identify::compare::document::{Document, ModelDoc};

/// The comparison's document as `stiffid identify --compare-models --json` writes it, with the
/// table of the selection path (key `table`) and the recommended model as a `[model]` fragment
/// (key `fragment`).
pub fn compare_models<'py>(
    py: Python<'py>,
    report: &Report,
    document: &Document,
) -> PyResult<Bound<'py, PyDict>> {
    let d = documents::to_python(py, document, &[])?;
    d.set_item("table", table(py, document)?)?;
    d.set_item("fragment", report.fragment())?;
    Ok(d)
}

/// The models of the selection path, one entry per model in every array: `added` (the spring
/// added at that step, `None` for the setup's model), `springs` (lists of names), `parameters`
/// (int), `in_sample_explained`, `held_out_explained`, `held_out_explained_std_error`,
/// `held_out_rms_delta_b_mm`, `aic`, `bic`,
/// `noise_ratio` (float, NaN where the document has `null`), `physical`, `identified`,
/// `recommended` (bool).
fn table<'py>(py: Python<'py>, document: &Document) -> PyResult<Bound<'py, PyDict>> {
    let models = &document.models;
    let t = PyDict::new(py);
    let floats = |f: &dyn Fn(&ModelDoc) -> Option<f64>| {
        models
            .iter()
            .map(|m| f(m).unwrap_or(f64::NAN))
            .collect::<Vec<f64>>()
            .into_pyarray(py)
    };
    let flags = |f: &dyn Fn(&ModelDoc) -> bool| {
        models.iter().map(f).collect::<Vec<bool>>().into_pyarray(py)
    };
    let added: Vec<Option<String>> = models.iter().map(|m| m.added.clone()).collect();
    let springs: Vec<Vec<String>> = models.iter().map(|m| m.springs.clone()).collect();
    t.set_item("added", added)?;
    t.set_item("springs", springs)?;
    let parameters: Vec<i64> = models.iter().map(|m| m.parameters as i64).collect();
    t.set_item("parameters", parameters.into_pyarray(py))?;
    t.set_item(
        "in_sample_explained",
        floats(&|m| Some(m.in_sample_explained)),
    )?;
    t.set_item("held_out_explained", floats(&|m| m.held_out_explained))?;
    t.set_item(
        "held_out_explained_std_error",
        floats(&|m| m.held_out_explained_std_error),
    )?;
    t.set_item(
        "held_out_rms_delta_b_mm",
        floats(&|m| m.held_out_rms_delta_b_mm),
    )?;
    t.set_item("aic", floats(&|m| m.aic))?;
    t.set_item("bic", floats(&|m| m.bic))?;
    t.set_item("noise_ratio", floats(&|m| m.noise_ratio))?;
    t.set_item("physical", flags(&|m| m.physical))?;
    t.set_item("identified", flags(&|m| m.identified))?;
    t.set_item("recommended", flags(&|m| m.recommended))?;
    Ok(t)
}
