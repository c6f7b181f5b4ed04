//! The stiffness of every parameter of a model in a document: named, with its kind and unit.

use super::finite;
use nalgebra::DVector;
use stiffid_core::model::Parameter;

pub use stiffid_core::io::stiffness::ParameterStiffness;

/// The parameters with their stiffness `1 / h` in their units, from the compliance `h` (SI).
pub fn stiffness(parameters: &[Parameter], h: &DVector<f64>) -> Vec<ParameterStiffness> {
    parameters
        .iter()
        .zip(h.iter())
        .map(|(p, h)| ParameterStiffness {
            name: p.name.clone(),
            kind: p.kind,
            unit: p.unit.symbol().into(),
            stiffness: finite(p.unit.per_si() / h),
            identified: None,
            ci95: None,
        })
        .collect()
}
