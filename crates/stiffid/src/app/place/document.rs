//! The document of the place job ([`crate::app::place`]): `stiffid place --json`, Python's
//! `stiffid.place(...)`.

use super::{Evaluation, Report};
use crate::app::document::units;
use nalgebra::{Isometry3, Vector3};
use serde::Serialize;
use stiffid_core::common::choice::Choice;

/// The place document.
///
/// A view of the report ([`Report::document`]), built as it is written: its lengths and angles
/// are the report's, in SI, written in the units their keys name by the unit adapters
/// ([`units`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "place")]
#[cfg_attr(feature = "schema", schemars(description = "The place document."))]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("place")))]
pub struct Document<'a> {
    /// What the placement minimised: `max` (the path's largest error bound) or `sum`.
    pub objective: &'static str,
    /// The placement chosen.
    pub placed: Placement<'a>,
    /// The setup's own placement.
    pub own: Placement<'a>,
    /// The placement a reach check alone picks (the largest smallest distance to the joint
    /// limits over the region).
    pub reach_only: Placement<'a>,
    /// The objective's fall from the own placement to the chosen one, percent of the own
    /// (positive: better); `null` when the own placement is not feasible.
    pub gain_vs_own_pct: Option<f64>,
    /// The objective's fall from the reach-only placement to the chosen one, percent of the
    /// reach-only one (positive: better).
    pub gain_vs_reach_only_pct: f64,
    /// Placements evaluated (the program compensated at each).
    pub evaluations: usize,
    /// What to look at before trusting the placement: other turns of the part within 0.5% of
    /// the chosen one's objective, more than 2 deg from it (the program does not pin the turn).
    pub warnings: &'a [stiffid_core::common::warning::Warning],
}

/// One placement of the part and its figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Placement<'a> {
    /// The part frame's origin in the robot base frame (`[workpiece] base_from_part`): m, written
    /// in mm.
    #[serde(rename = "xyz_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub xyz: Vector3<f64>,
    /// Its orientation, fixed-axis roll, pitch, yaw, deg.
    pub rpy_deg: [f64; 3],
    /// Whether every point is reachable and passes the checks; `false` only for the own
    /// placement, its figures then `null`.
    pub feasible: bool,
    /// Why not, when not feasible.
    pub reason: Option<&'a str>,
    /// The path's largest error bound: m, written in mm.
    #[serde(rename = "peak_bound_mm", serialize_with = "units::mm_option")]
    pub peak_bound: Option<f64>,
    /// The mean of the points' bounds: m, written in mm.
    #[serde(rename = "mean_bound_mm", serialize_with = "units::mm_option")]
    pub mean_bound: Option<f64>,
    /// The program line of the largest bound.
    pub worst_line: Option<u64>,
    /// The smallest distance of an axis angle to its joint limits over the path: rad, written in
    /// deg.
    #[serde(rename = "min_limit_margin_deg", serialize_with = "units::deg_option")]
    pub min_limit_margin: Option<f64>,
    /// The largest condition number of the TCP Jacobian over the path.
    pub max_condition: Option<f64>,
    /// The smallest clearance of the cell's bodies over the path: m, written in mm; `null` without
    /// a cell.
    #[serde(rename = "min_clearance_mm", serialize_with = "units::mm_option")]
    pub min_clearance: Option<f64>,
}

impl<'a> Placement<'a> {
    /// The placement `base_from_part`, with none of the figures.
    fn at(base_from_part: &Isometry3<f64>) -> Self {
        let [r, p, y] = stiffid_core::robot::file::rpy(&base_from_part.rotation);
        Placement {
            xyz: base_from_part.translation.vector,
            rpy_deg: [r, p, y].map(|a| a.to_degrees() + 0.0),
            feasible: false,
            reason: None,
            peak_bound: None,
            mean_bound: None,
            worst_line: None,
            min_limit_margin: None,
            max_condition: None,
            min_clearance: None,
        }
    }

    fn feasible(e: &Evaluation) -> Self {
        Placement {
            feasible: true,
            peak_bound: Some(e.peak),
            mean_bound: Some(e.sum / e.points as f64),
            worst_line: Some(e.worst_line),
            min_limit_margin: Some(e.limit_margin),
            max_condition: Some(e.condition),
            min_clearance: e.clearance,
            ..Placement::at(&e.base_from_part)
        }
    }
}

impl<'a> Document<'a> {
    /// The document of `report` ([`Report::document`]).
    pub(crate) fn new(report: &'a Report) -> Self {
        let gain =
            |from: &Evaluation| 100.0 * (1.0 - report.cost(&report.placed) / report.cost(from));
        let own_placement = match &report.own {
            Ok(e) => Placement::feasible(e),
            Err(reason) => Placement {
                reason: Some(reason),
                ..Placement::at(&report.own_frame)
            },
        };
        Document {
            objective: report.objective.name(),
            placed: Placement::feasible(&report.placed),
            own: own_placement,
            reach_only: Placement::feasible(&report.reach),
            gain_vs_own_pct: report.own.as_ref().ok().map(gain),
            gain_vs_reach_only_pct: gain(&report.reach),
            evaluations: report.evaluations,
            warnings: &report.warnings,
        }
    }
}
