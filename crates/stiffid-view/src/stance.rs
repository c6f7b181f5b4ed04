//! A posture as a document records it for its scene: a label, the axis angles and the external
//! axes' values at the edges' units, so that a front end can draw the scene of a document it
//! holds (`stiffid.scene(setup, document=...)`) as the command's report draws it.

use nalgebra::Vector6;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_core::{Error, Robot};

/// One posture of a document's scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Stance {
    /// What it is: a posture's label, or the path point it stands at.
    pub label: String,
    /// Axis angles, deg.
    pub q_deg: [f64; 6],
    /// The external axes' values by their columns' names (`e1_mm`, `e2_deg`, ...); none without
    /// external axes.
    #[serde(flatten)]
    pub external: BTreeMap<String, f64>,
}

impl Stance {
    /// The posture `q` (rad) at the external values `e` (SI, the cell's order) of `axes`
    /// (none when `e` is empty: all at zero).
    pub fn new(
        axes: Option<&ExternalAxes>,
        label: String,
        q: &Vector6<f64>,
        e: &ExternalValues,
    ) -> Self {
        let external = match axes.filter(|_| !e.is_empty()) {
            None => BTreeMap::new(),
            Some(axes) => (axes.column_names().into_iter())
                .zip(axes.to_display(e.as_slice()))
                .collect(),
        };
        Stance {
            label,
            q_deg: q.map(f64::to_degrees).into(),
            external,
        }
    }

    /// The axis angles, rad.
    pub(crate) fn q(&self) -> Vector6<f64> {
        Vector6::from(self.q_deg).map(f64::to_radians)
    }

    /// The external values (SI, the cell's order) of `robot`'s axes; empty without external
    /// axes.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`field`) when an axis's column is missing.
    pub(crate) fn external_si(&self, robot: &Robot, field: &str) -> stiffid_core::Result<Vec<f64>> {
        let Some(axes) = robot.external() else {
            return Ok(Vec::new());
        };
        let display = (axes.column_names().iter())
            .map(|c| {
                self.external
                    .get(c)
                    .copied()
                    .ok_or_else(|| Error::InvalidField {
                        field: field.to_string(),
                        message: format!(
                            "posture '{}' has no `{c}`: expected the cell's external axes' values",
                            stiffid_core::common::limits::short(&self.label)
                        ),
                    })
            })
            .collect::<stiffid_core::Result<Vec<f64>>>()?;
        Ok(axes.to_si(&display))
    }
}

/// Postures' axis angles (rad) and their external values (SI, one list each, or none).
pub type Postures = (Vec<Vector6<f64>>, Vec<Vec<f64>>);

/// The axis angles (rad) and external values (SI) of `stances`, for [`super::scene`]: no
/// external values (all at zero) when no stance has any.
///
/// # Errors
/// Those of `Stance::external_si` when some stance has external values.
pub fn postures(robot: &Robot, stances: &[Stance], field: &str) -> stiffid_core::Result<Postures> {
    let q = stances.iter().map(Stance::q).collect();
    if stances.iter().all(|s| s.external.is_empty()) {
        return Ok((q, Vec::new()));
    }
    let e = (stances.iter())
        .map(|s| s.external_si(robot, field))
        .collect::<stiffid_core::Result<Vec<_>>>()?;
    Ok((q, e))
}
