//! `stiffid.figures`: the figures of a calibration, an identification or a plan as SVG strings,
//! drawn from its document by the same code as the command's reports ([`stiffid_figures`]), no
//! Matplotlib; [`svgs`] those of a compensation and of the study.

use crate::documents::json;
use crate::error::value;
use crate::scene::plan_postures;
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;
use stiffid::internal::view::MAX_POSTURES;
use stiffid_figures::Drawing;

/// The figures of ``document`` as a dict of SVG documents (str) keyed by the figure's name, in
/// the order the command's reports show them, byte for byte their ``figures/<name>.svg``:
///
/// - a calibration (the dict ``calibrate(...)`` returns, as ``calibrate --report``): ``errors``
///   (each reading's error before and after, held-out readings marked), ``residuals`` (their
///   distribution against the tracker's noise) and ``parameters_<unit>`` (fitted minus nominal
///   with 95% intervals);
/// - an identification (the dict ``identify(...)`` returns: the six drives or a model with
///   virtual springs, as ``identify --report``): ``measured`` (each measured displacement
///   coordinate against the predicted one), ``parameters`` (each parameter's 95% interval, % of
///   its stiffness), ``qq`` (the residuals' normal QQ plot against the noise), ``folds`` (with
///   cross-validation: each fold's stiffness against the full fit's), ``prediction`` (the
///   held-out scores of the prediction intervals) or, for a model comparison, ``models``
///   (held-out shares with one standard error);
/// - a plan (the dict ``plan(setup, ...)`` returns, with that ``setup``: the figures draw its
///   robot and cell, as ``select --report`` and ``plot``): ``postures`` (every posture, side and
///   top views) and ``posture_01``, ``posture_02``, ... (each alone, at the same scale).
///
/// A compensation's figures come with it (``compensate(..., figures=True)``), and so do the
/// study's (``reproduce(..., figures=True)``). Show one in Jupyter with
/// ``IPython.display.SVG(svg)``. The document's ``kind`` says which it is. ``InputError`` when
/// ``document`` is none of these, for a plan without its ``setup`` or of more than 500 postures.
#[pyfunction]
#[pyo3(signature = (document, setup=None))]
pub fn figures<'py>(
    py: Python<'py>,
    document: &Bound<'py, PyAny>,
    setup: Option<&Setup>,
) -> PyResult<Bound<'py, PyDict>> {
    let doc = json(document)?;
    let kind = doc.get("kind").and_then(Value::as_str).unwrap_or_default();
    if kind == "plan" {
        let setup = setup.ok_or_else(|| {
            value("setup: a plan's figures draw its robot in its cell: give the plan's setup")
        })?;
        let group = plan_postures(&doc, &setup.inner)?;
        if group.len() > MAX_POSTURES {
            return Err(value(format!(
                "document: a plan of {} postures; its figures are drawn for at most {MAX_POSTURES}",
                group.len()
            )));
        }
        return svgs(py, &stiffid_figures::postures::each(&setup.inner, &group));
    }
    let drawn = match kind {
        "calibrate" => stiffid_figures::calibrate::figures(&doc),
        _ if kind.starts_with("identify-") => stiffid_figures::identify::figures(&doc),
        _ => return Err(value(format!("document: its `kind` is {kind:?}; expected \"calibrate\", \"plan\" or \"identify-drives\", \"identify-springs\", \"identify-comparison\""))),
    }
    .map_err(|e| value(format!("document: {e}")))?;
    let drawings: Vec<Drawing> = (drawn.iter())
        .map(|f| Drawing::new(&f.name, &f.caption, &f.chart))
        .collect();
    svgs(py, &drawings)
}

/// Every drawing of `drawings` as SVG, keyed by its name, in order.
pub fn svgs<'py>(py: Python<'py>, drawings: &[Drawing]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    for d in drawings {
        let svg = py
            .detach(|| d.plot.svg())
            .map_err(|e| value(e.to_string()))?;
        out.set_item(&d.name, svg)?;
    }
    Ok(out)
}
