//! The joints' error maps in the error model (module docs of [`super`], "Joint error maps").
//!
//! Joint `i` with a map of `H` harmonics turns by `q_i + e_i(q_i)`, `e_i(q) = sum_h a_h cos(h q)
//! + b_h sin(h q)` ([`stiffid_core::robot::ErrorMap`]), evaluated at the axis angle the chain stands at
//! (the commanded one plus the deflection under gravity). The coefficients are parameters of
//! kind [`Kind::Map`] (rad, priority 5), nominal the nominal robot's own map's (0 without); the
//! column of `a_h` is the point Jacobian's column of axis `i` (axis coordinates) times
//! `cos(h q_i)`, of `b_h` times `sin(h q_i)`. A joint's backlash term, half its backlash `beta`
//! (kind [`Kind::Map`], [`Target::Backlash`], after its coefficients), turns it by `+ beta d`,
//! `d` the reading's last motion's sign ([`super::Observation::direction`]): its column is the
//! same Jacobian column times `d`.

use super::{ErrorModel, Kind, Parameter, Target};
use nalgebra::{DVector, Vector3, Vector6};
use stiffid_core::robot::error_map::{self, ErrorMap};
use stiffid_core::{Error, Result};

/// The error maps a calibration fits: per joint its map's harmonics and whether it has a
/// backlash term.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct JointMaps {
    /// The harmonics of each joint's map, 0 for none.
    pub harmonics: [usize; 6],
    /// Whether each joint has a backlash term (half its backlash, [`Target::Backlash`]).
    pub backlash: [bool; 6],
}

impl JointMaps {
    /// No map and no backlash term.
    pub const NONE: JointMaps = JointMaps {
        harmonics: [0; 6],
        backlash: [false; 6],
    };

    /// Whether no joint has a map or a backlash term.
    pub fn is_none(&self) -> bool {
        *self == Self::NONE
    }

    /// Whether joint `joint` (0-based) has a map or a backlash term.
    pub(crate) fn has(&self, joint: usize) -> bool {
        self.harmonics[joint] > 0 || self.backlash[joint]
    }

    /// The coefficients they fit: `2 H` per map, one per backlash term.
    pub(crate) fn coefficients(&self) -> usize {
        let maps: usize = self.harmonics.iter().sum();
        2 * maps + self.backlash.iter().filter(|&&b| b).count()
    }

    /// Whether any joint has a backlash term.
    pub(crate) fn any_backlash(&self) -> bool {
        self.backlash.contains(&true)
    }

    /// These maps and `other` together: each joint's larger harmonic count, a backlash term
    /// where either has one.
    pub(crate) fn union(&self, other: &JointMaps) -> JointMaps {
        JointMaps {
            harmonics: std::array::from_fn(|j| self.harmonics[j].max(other.harmonics[j])),
            backlash: std::array::from_fn(|j| self.backlash[j] || other.backlash[j]),
        }
    }
}

impl From<[usize; 6]> for JointMaps {
    /// Maps of these harmonics, no backlash term.
    fn from(harmonics: [usize; 6]) -> Self {
        JointMaps {
            harmonics,
            backlash: [false; 6],
        }
    }
}

/// Which joints carry a fitted map, and where their coefficients are.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Maps {
    /// The maps and backlash terms fitted.
    pub terms: JointMaps,
    /// The index of each joint's first coefficient (`a_1..a_H`, then `b_1..b_H`, then its
    /// half backlash).
    pub starts: [usize; 6],
    /// The axis angles each fitted map holds over (rad; [`ErrorModel::with_map_ranges`]).
    pub ranges: Option<[(f64, f64); 6]>,
}

impl ErrorModel {
    /// The model with an error map of `harmonics[i]` harmonics on joint `i` (0 for none) and,
    /// where `backlash[i]`, its half backlash: `2 H` parameters per mapped joint,
    /// `joint<i>.map.cos<h>` then `joint<i>.map.sin<h>`, then `joint<i>.map.backlash`, after the
    /// parameters it has (an array of harmonics: no backlash term).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`maps`) when the model has maps already or a count exceeds
    /// [`error_map::MAX_HARMONICS`].
    pub fn with_maps(mut self, terms: impl Into<JointMaps>) -> Result<Self> {
        let terms = terms.into();
        let harmonics = terms.harmonics;
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
            if terms.backlash[joint] {
                self.parameters.push(Parameter {
                    name: format!("joint{}.map.backlash", joint + 1),
                    kind: Kind::Map,
                    target: Target::Backlash { joint },
                    nominal: own.map_or(0.0, ErrorMap::backlash),
                    priority: 5,
                });
            }
        }
        self.maps = (!terms.is_none()).then_some(Maps {
            terms,
            starts,
            ranges: None,
        });
        Ok(self)
    }

    /// The model whose fitted maps hold over the axis angles `ranges` (rad, per joint: the
    /// fitted postures' range) and taper to zero beyond them ([`stiffid_core::robot::error_map::taper`]):
    /// its robot's maps carry them ([`ErrorMap::with_range`]) and its map columns taper alike.
    /// Without maps, the model unchanged.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`error_map.range_deg`) when a range is not finite or reversed.
    pub fn with_map_ranges(mut self, ranges: [(f64, f64); 6]) -> Result<Self> {
        for &(lo, hi) in &ranges {
            ErrorMap::default().with_range(lo, hi)?;
        }
        if let Some(maps) = self.maps.as_mut() {
            maps.ranges = Some(ranges);
        }
        Ok(self)
    }

    /// The index of the first map coefficient: the maps' coefficients are the model's last
    /// parameters. `None` without maps.
    pub fn map_start(&self) -> Option<usize> {
        let maps = self.maps.as_ref()?;
        (0..6).find(|&j| maps.terms.has(j)).map(|j| maps.starts[j])
    }

    /// The robot's error maps at `values`: a joint with a fitted map takes its coefficients
    /// (and the nominal robot's harmonics beyond them), with a fitted backlash term its half
    /// backlash, every other joint and term the nominal robot's.
    ///
    /// # Errors
    /// Those of [`ErrorMap::new`] (a coefficient not finite or beyond its limit).
    pub(super) fn maps_at(&self, values: &DVector<f64>) -> Result<Option<[ErrorMap; 6]>> {
        let Some(maps) = &self.maps else {
            return Ok(None);
        };
        let own: [ErrorMap; 6] = self.robot.error_maps().cloned().unwrap_or_default();
        let mut out = own.clone();
        for joint in (0..6).filter(|&j| maps.terms.has(j)) {
            let (s, h) = (maps.starts[joint], maps.terms.harmonics[joint]);
            let fitted = ErrorMap::new(
                values.rows(s, h).iter().copied().collect(),
                values.rows(s + h, h).iter().copied().collect(),
            )
            .map_err(|e| diverged(joint, e))?;
            let beyond = |v: &[f64]| {
                (0..v.len())
                    .map(|i| if i < h { 0.0 } else { v[i] })
                    .collect()
            };
            let rest = ErrorMap::new(beyond(own[joint].cos()), beyond(own[joint].sin()))?;
            let backlash = match maps.terms.backlash[joint] {
                true => values[s + 2 * h],
                false => own[joint].backlash(),
            };
            let map = fitted.plus(&rest).with_backlash(backlash)?;
            out[joint] = match maps.ranges.map(|r| r[joint]) {
                Some((lo, hi)) => map.with_range(lo, hi)?,
                None => match own[joint].range() {
                    Some((lo, hi)) => map.with_range(lo, hi)?,
                    None => map,
                },
            };
        }
        Ok(Some(out))
    }

    /// Writes the map columns of the point whose axis-coordinate Jacobian columns are
    /// `columns[i]` (base frame, m/rad) at the axis angles `at` (rad) approached from
    /// `direction` ([`super::Observation::direction`]) into `put(index, column)`, the series'
    /// columns tapered beyond the maps' ranges as the maps are.
    pub(super) fn map_columns(
        &self,
        columns: &[Vector3<f64>; 6],
        at: &Vector6<f64>,
        direction: &Vector6<f64>,
        mut put: impl FnMut(usize, Vector3<f64>),
    ) {
        let Some(maps) = &self.maps else {
            return;
        };
        for joint in (0..6).filter(|&j| maps.terms.has(j)) {
            let h = maps.terms.harmonics[joint];
            let w = (maps.ranges).map_or(1.0, |r| error_map::taper(at[joint], r[joint]));
            let (s1, c1) = at[joint].sin_cos();
            let (mut s, mut c) = (s1, c1);
            for k in 0..h {
                put(maps.starts[joint] + k, columns[joint] * (w * c));
                put(maps.starts[joint] + h + k, columns[joint] * (w * s));
                (s, c) = (s * c1 + c * s1, c * c1 - s * s1);
            }
            if maps.terms.backlash[joint] {
                put(
                    maps.starts[joint] + 2 * h,
                    columns[joint] * direction[joint],
                );
            }
        }
    }
}

/// A fitted map out of its range ([`ErrorMap::new`]'s error `e`) said as what it is: the fit's
/// coefficients, not the input's, left the range, the readings not determining the map.
fn diverged(joint: usize, e: stiffid_core::Error) -> stiffid_core::Error {
    let message = match e {
        stiffid_core::Error::InvalidField { message, .. } => message,
        other => other.to_string(),
    };
    stiffid_core::Error::InvalidField {
        field: format!("joint[{}].error_map", joint + 1),
        message: format!("the fit's coefficients left their range ({message}): the readings do not determine this joint's map; fit without maps, or read postures spread over the axis' travel, approached from both directions"),
    }
}
