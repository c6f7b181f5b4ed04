//! The region of axis angles a compliance was identified from, and whether a posture lies
//! outside it: a prediction there extrapolates.
//!
//! ## The region
//! The identification postures' range of every axis, `[min_i q_i, max_i q_i]` over the postures
//! the stiffness (or the calibration) was fitted to, widened by a margin at both ends
//! (`MARGIN_DEG`, 5 degrees, unless the stiffness file states another). A posture extrapolates
//! when any of its six axis angles lies outside its widened range.
//!
//! Why per axis: the model's compliance is constant, but what it misses is not (a joint's
//! stiffness that changes with its angle, a balancer's spring, the reducer's position, a
//! link's compliance under a load path the postures never took); each axis' range is what the
//! data could say anything about, and a posture beyond it on any axis is one the fit and its
//! prediction intervals (which assume a new posture drawn like the measured ones,
//! [`crate::model::prediction`]) never saw. The box is generous: a posture inside it may still
//! combine angles no measured posture combined. The margin keeps a posture a few degrees past the
//! outermost measured one (a taught posture's spread, rounding) from being flagged; it is not a
//! claim that the model holds 5 degrees further.
//!
//! Joint 1 counts like the others: a load fixed in the base frame turns with the arm, so the
//! drives' torques do not depend on it, but the base, the reducer and the cell do.

use crate::common::limits::{JointBox, Violation};
use crate::common::warning::{Warning, WarningKind};
use nalgebra::Vector6;

/// The margin that widens the identification postures' range of every axis, deg.
pub(crate) const MARGIN_DEG: f64 = 5.0;

/// The largest margin a stiffness file may state, deg.
pub(crate) const MAX_MARGIN_DEG: f64 = 360.0;

/// What a compliance says about the postures it was identified from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Region {
    /// Not identified from postures (the setup's nominal stiffness, values given directly):
    /// nothing to check.
    #[default]
    NotIdentified,
    /// Identified, but its stiffness file does not record from which postures (a file written
    /// before stiffness files carried the region): not checked, and said once
    /// (`unrecorded_warning`).
    Unrecorded,
    /// The axis ranges of the postures it was identified from.
    Postures(PostureRange),
}

/// The range of every axis over the postures a compliance was identified from, and the margin
/// that widens it (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PostureRange {
    /// The identification postures' range: per axis, the smallest and largest angle, rad.
    pub range: JointBox,
    /// The margin added at both ends of every axis, rad (>= 0).
    pub margin: f64,
    /// The number of postures.
    pub postures: usize,
}

impl PostureRange {
    /// The range of `postures` (axis angles, rad) with the default margin `MARGIN_DEG`;
    /// `None` without postures.
    pub fn of<'a>(postures: impl IntoIterator<Item = &'a Vector6<f64>>) -> Option<Self> {
        let mut n = 0;
        let mut lower = Vector6::repeat(f64::INFINITY);
        let mut upper = Vector6::repeat(f64::NEG_INFINITY);
        for q in postures {
            n += 1;
            lower = lower.inf(q);
            upper = upper.sup(q);
        }
        (n > 0).then(|| PostureRange {
            range: JointBox::new(lower, upper),
            margin: MARGIN_DEG.to_radians(),
            postures: n,
        })
    }

    /// Every axis of `q` (rad) outside the widened range, with its value and the identification
    /// postures' own range (without the margin), rad; empty inside.
    pub fn outside(&self, q: &Vector6<f64>) -> Vec<Violation> {
        let widened = self.range.widened(self.margin);
        (0..6)
            .filter(|&i| !(q[i] >= widened.lower[i] && q[i] <= widened.upper[i]))
            .map(|axis| Violation {
                axis,
                value: q[axis],
                lower: self.range.lower[axis],
                upper: self.range.upper[axis],
            })
            .collect()
    }

    /// `axis 2 at 95.00 deg (identified over 10.00 .. 80.00)` for each of `outside`.
    pub(crate) fn describe(&self, outside: &[Violation]) -> String {
        let each: Vec<String> = outside
            .iter()
            .map(|v| {
                format!(
                    "axis {} at {:.2} deg (identified over {:.2} .. {:.2})",
                    v.axis + 1,
                    v.value.to_degrees(),
                    v.lower.to_degrees(),
                    v.upper.to_degrees()
                )
            })
            .collect();
        each.join(", ")
    }
}

impl Region {
    /// The axes of `q` (rad) outside the region ([`PostureRange::outside`]); `None` when there
    /// is no region to check.
    pub fn outside(&self, q: &Vector6<f64>) -> Option<Vec<Violation>> {
        match self {
            Region::Postures(r) => Some(r.outside(q)),
            _ => None,
        }
    }

    /// The warning that the region is not recorded, when it is not ([`Region::Unrecorded`]).
    pub fn unrecorded_warning(&self) -> Option<Warning> {
        matches!(self, Region::Unrecorded).then(unrecorded_warning)
    }
}

/// The warning for a stiffness file that does not record its identification postures' region:
/// nothing is checked.
pub(crate) fn unrecorded_warning() -> Warning {
    Warning::new(
        WarningKind::Extrapolation,
        "the stiffness file does not record the postures it was identified from (no `region`: a nominal stiffness written by hand, or a file from an older stiffid), so no posture is checked for extrapolation; a file from `identify --out` records them",
    )
}

/// The warning for postures (or path points) outside `region`: `subject` says which and how
/// many with its verb (`the posture lies`, `3 of 20 postures lie`), `flagged` names the first few
/// (an empty name for the one posture of `subject`) with the axes outside, `more` counts the
/// others.
pub fn extrapolation_warning(
    region: &PostureRange,
    subject: &str,
    flagged: &[(String, Vec<Violation>)],
    more: usize,
) -> Warning {
    let shown: Vec<String> = flagged
        .iter()
        .map(|(name, axes)| match name.is_empty() {
            true => region.describe(axes),
            false => format!("{name}: {}", region.describe(axes)),
        })
        .collect();
    let more = match more {
        0 => String::new(),
        n => format!("; and {n} more"),
    };
    Warning::new(
        WarningKind::Extrapolation,
        format!(
            "{subject} outside the region the stiffness was identified from (each axis' range over its {} postures, widened by {:.1} deg): the prediction extrapolates there, and its standard deviation and interval do not cover it ({}{more})",
            region.postures,
            region.margin.to_degrees(),
            shown.join("; ")
        ),
    )
}

/// `lies` for one, `lie` for more: the verb after `k of n postures`.
pub fn lie(n: usize) -> &'static str {
    match n {
        1 => "lies",
        _ => "lie",
    }
}

/// How many flagged postures or points a warning names.
pub const NAMED: usize = 5;
