//! The stiffness of every parameter of a model in a document: named, with its kind and unit.

use super::finite;
use nalgebra::DVector;
use serde::Serialize;
use stiffid_core::model::{Parameter, ParameterKind};

/// One parameter's stiffness, in its unit: the key `stiffness` with `unit` beside it, as the
/// stiffness file has it ([`stiffid_core::io::stiffness::ParameterStiffness`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ParameterStiffness {
    /// `k1` .. `k6` for the drives, the virtual spring's name otherwise.
    pub name: String,
    /// `drive`, `rotation` or `translation`.
    pub kind: ParameterKind,
    /// `Nm/rad` (drives, rotations) or `N/mm` (translations).
    pub unit: &'static str,
    /// The stiffness in `unit`; `null` if not finite.
    pub stiffness: Option<f64>,
}

/// The parameters with their stiffness `1 / h` in their units, from the compliance `h` (SI).
pub fn stiffness(parameters: &[Parameter], h: &DVector<f64>) -> Vec<ParameterStiffness> {
    parameters
        .iter()
        .zip(h.iter())
        .map(|(p, h)| ParameterStiffness {
            name: p.name.clone(),
            kind: p.kind,
            unit: p.unit.symbol(),
            stiffness: finite(p.unit.per_si() / h),
        })
        .collect()
}
