//! The joints' error maps in the error model (module docs of [`super`], "Joint error maps").
//!
//! Joint `i` with a map of `H` harmonics turns by `q_i + e_i(q_i)`, `e_i(q) = sum_h a_h cos(h q)
//! + b_h sin(h q)` ([`crate::robot::ErrorMap`]), evaluated at the axis angle the chain stands at
//! (the commanded one plus the deflection under gravity). The coefficients are parameters of
//! kind [`Kind::Map`] (rad, priority 5), nominal the nominal robot's own map's (0 without); the
//! column of `a_h` is the point Jacobian's column of axis `i` (axis coordinates) times
//! `cos(h q_i)`, of `b_h` times `sin(h q_i)`.

use super::{ErrorModel, Kind, Parameter, Target};
use crate::robot::error_map::{self, ErrorMap};
use crate::{Error, Result};
use nalgebra::{DVector, Vector3, Vector6};

/// Which joints carry a fitted map, and where their coefficients are.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Maps {
    /// The harmonics of each joint's map, 0 for none.
    pub harmonics: [usize; 6],
    /// The index of each joint's first coefficient (`a_1..a_H`, then `b_1..b_H`).
    pub starts: [usize; 6],
}

impl ErrorModel {
    /// The model with an error map of `harmonics[i]` harmonics on joint `i` (0 for none): `2 H`
    /// parameters per mapped joint, `joint<i>.map.cos<h>` then `joint<i>.map.sin<h>`, after the
    /// parameters it has.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`maps`) when the model has maps already or a count exceeds
    /// [`error_map::MAX_HARMONICS`].
    pub fn with_maps(mut self, harmonics: [usize; 6]) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: "maps".into(),
            message,
        };
        if self.maps.is_some() {
            return Err(invalid("the model has maps already".into()));
        }
        if let Some(h) = harmonics.iter().find(|&&h| h > error_map::MAX_HARMONICS) {
            return Err(invalid(format!(
                "expected at most {} harmonics, got {h}",
                error_map::MAX_HARMONICS
            )));
        }
        let mut starts = [0; 6];
        for (joint, &count) in harmonics.iter().enumerate() {
            starts[joint] = self.parameters.len();
            let own = (self.robot.error_maps()).map(|m| &m[joint]);
            for sine in [false, true] {
                for harmonic in 1..=count {
                    let nominal = own
                        .and_then(|m| match sine {
                            false => m.cos().get(harmonic - 1),
                            true => m.sin().get(harmonic - 1),
                        })
                        .copied()
                        .unwrap_or(0.0);
                    self.parameters.push(Parameter {
                        name: format!(
                            "joint{}.map.{}{harmonic}",
                            joint + 1,
                            if sine { "sin" } else { "cos" }
                        ),
                        kind: Kind::Map,
                        target: Target::Map {
                            joint,
                            harmonic,
                            sine,
                        },
                        nominal,
                        priority: 5,
                    });
                }
            }
        }
        self.maps = (harmonics != [0; 6]).then_some(Maps { harmonics, starts });
        Ok(self)
    }

    /// The index of the first map coefficient: the maps' coefficients are the model's last
    /// parameters. `None` without maps.
    pub fn map_start(&self) -> Option<usize> {
        let maps = self.maps.as_ref()?;
        (0..6)
            .find(|&j| maps.harmonics[j] > 0)
            .map(|j| maps.starts[j])
    }

    /// The harmonics of each joint's fitted map (0 for none).
    pub fn map_harmonics(&self) -> [usize; 6] {
        self.maps.as_ref().map_or([0; 6], |m| m.harmonics)
    }

    /// The robot's error maps at `values`: a joint with a fitted map takes its coefficients
    /// (and the nominal robot's harmonics beyond them), every other joint the nominal robot's.
    ///
    /// # Errors
    /// Those of [`ErrorMap::new`] (a coefficient not finite or beyond its limit).
    pub(super) fn maps_at(&self, values: &DVector<f64>) -> Result<Option<[ErrorMap; 6]>> {
        let Some(maps) = &self.maps else {
            return Ok(None);
        };
        let own: [ErrorMap; 6] = self.robot.error_maps().cloned().unwrap_or_default();
        let mut out = own.clone();
        for (joint, &h) in maps.harmonics.iter().enumerate().filter(|(_, &h)| h > 0) {
            let s = maps.starts[joint];
            let fitted = ErrorMap::new(
                values.rows(s, h).iter().copied().collect(),
                values.rows(s + h, h).iter().copied().collect(),
            )?;
            let beyond = |v: &[f64]| {
                (0..v.len())
                    .map(|i| if i < h { 0.0 } else { v[i] })
                    .collect()
            };
            let rest = ErrorMap::new(beyond(own[joint].cos()), beyond(own[joint].sin()))?;
            out[joint] = fitted.plus(&rest);
        }
        Ok(Some(out))
    }

    /// Writes the map columns of the point whose axis-coordinate Jacobian columns are
    /// `columns[i]` (base frame, m/rad) at the axis angles `at` (rad) into `put(index, column)`.
    pub(super) fn map_columns(
        &self,
        columns: &[Vector3<f64>; 6],
        at: &Vector6<f64>,
        mut put: impl FnMut(usize, Vector3<f64>),
    ) {
        let Some(maps) = &self.maps else {
            return;
        };
        for (joint, &h) in maps.harmonics.iter().enumerate().filter(|(_, &h)| h > 0) {
            let (s1, c1) = at[joint].sin_cos();
            let (mut s, mut c) = (s1, c1);
            for k in 0..h {
                put(maps.starts[joint] + k, columns[joint] * c);
                put(maps.starts[joint] + h + k, columns[joint] * s);
                (s, c) = (s * c1 + c * s1, c * c1 - s * s1);
            }
        }
    }
}
