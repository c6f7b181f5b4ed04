//! The stiffness arguments of `validate`, `deflection` and `compensate`: the stiffness of every
//! parameter of the setup's model, as values or as a stiffness JSON file, to the library's
//! [`Compliance`].

use crate::arrays;
use crate::error::{self, raise};
use pyo3::prelude::*;
use pyo3::types::PyAny;
use std::path::PathBuf;
use stiffid::internal::common::limits;
use stiffid::internal::io::stiffness;
use stiffid::internal::model::{Compliance, ParameterKind};
use stiffid::Setup;

/// The compliance of every parameter of `setup`'s model from `obj`: the path of a stiffness JSON
/// file (as `identify(...)` and `stiffid identify --out` write it; its covariance when present),
/// checked against the model, or the stiffness values, one per parameter in the parameters' units
/// (Nm/rad; N/mm for translational springs), with `covariance` (the compliance covariance, SI,
/// `(n, n)`, the argument `compliance_covariance_rad2_per_nm2`) if given. `what` names the argument in errors.
pub fn compliance(
    setup: &Setup,
    obj: &Bound<'_, PyAny>,
    covariance: Option<&Bound<'_, PyAny>>,
    what: &str,
) -> PyResult<Compliance> {
    let model = setup.model();
    if let Ok(path) = obj.extract::<PathBuf>() {
        let name = path.display().to_string();
        let in_file = |e| error::raise_in(&name, e);
        let file = stiffness::parse(&error::read(&path)?).map_err(in_file)?;
        return file
            .compliance(model)
            .map_err(|e| error::raise_in(&name, e));
    }
    let n = model.len();
    let k = arrays::values(obj, what, n)?;
    let mut h = nalgebra::DVector::zeros(n);
    for (j, p) in model.parameters().iter().enumerate() {
        let range = match p.kind {
            ParameterKind::Translation => &limits::STIFFNESS_N_PER_MM,
            _ => &limits::STIFFNESS_NM_PER_RAD,
        };
        limits::check(&format!("{what}[{j}] ({})", p.name), &[k[j]], range).map_err(raise)?;
        h[j] = p.unit.per_si() / k[j];
    }
    let covariance = covariance.map(|c| covariance_of(c, n)).transpose()?;
    Ok(Compliance {
        h,
        covariance,
        prediction: None,
        own_weight: None,
        region: stiffid::internal::model::Region::NotIdentified,
        model_form: None,
    })
}

/// The `(n, n)` covariance of the compliance (SI) given as `compliance_covariance_rad2_per_nm2`:
/// finite, symmetric, positive semi-definite.
pub fn covariance_of(obj: &Bound<'_, PyAny>, n: usize) -> PyResult<nalgebra::DMatrix<f64>> {
    let name = "compliance_covariance_rad2_per_nm2";
    let m = arrays::square(obj, name, n)?;
    stiffness::check_covariance_of(&m, name).map_err(raise)?;
    Ok(m)
}

/// [`compliance`] of `obj` (no covariance), or the setup's nominal compliance of every parameter
/// when `obj` is `None` (`needed_by` says what needs it in the error for a setup without one).
pub fn given_or_nominal(
    setup: &Setup,
    obj: Option<&Bound<'_, PyAny>>,
    what: &str,
    needed_by: &str,
) -> PyResult<Compliance> {
    match obj {
        Some(k) => compliance(setup, k, None, what),
        None => setup.model_compliance(needed_by).map_err(raise),
    }
}
