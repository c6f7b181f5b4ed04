//! The document of the place job ([`crate::app::place`]): `stiffid place --json`, Python's
//! `stiffid.place(...)`.

use super::{Evaluation, Report};
use crate::app::document::mm;
use serde::Serialize;
use stiffid_core::common::choice::Choice;

/// The place document.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "place")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("place")))]
pub struct Document {
    /// What the placement minimised: `max` (the path's largest error bound) or `sum`.
    pub objective: String,
    /// The placement chosen.
    pub placed: Placement,
    /// The setup's own placement.
    pub own: Placement,
    /// The placement a reach check alone picks (the largest smallest distance to the joint
    /// limits over the region).
    pub reach_only: Placement,
    /// The objective's fall from the own placement to the chosen one, percent of the own
    /// (positive: better); `null` when the own placement is not feasible.
    pub gain_vs_own_pct: Option<f64>,
    /// The objective's fall from the reach-only placement to the chosen one, percent of the
    /// reach-only one (positive: better).
    pub gain_vs_reach_only_pct: f64,
    /// Placements evaluated (the program compensated at each).
    pub evaluations: usize,
}

/// One placement of the part and its figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Placement {
    /// The part frame's origin in the robot base frame, mm (`[workpiece] base_from_part`).
    pub xyz_mm: [f64; 3],
    /// Its orientation, fixed-axis roll, pitch, yaw, deg.
    pub rpy_deg: [f64; 3],
    /// Whether every point is reachable and passes the checks; `false` only for the own
    /// placement, its figures then `null`.
    pub feasible: bool,
    /// Why not, when not feasible.
    pub reason: Option<String>,
    /// The path's largest error bound, mm.
    pub peak_bound_mm: Option<f64>,
    /// The mean of the points' bounds, mm.
    pub mean_bound_mm: Option<f64>,
    /// The program line of the largest bound.
    pub worst_line: Option<u64>,
    /// The smallest distance of an axis angle to its joint limits over the path, deg.
    pub min_limit_margin_deg: Option<f64>,
    /// The largest condition number of the TCP Jacobian over the path.
    pub max_condition: Option<f64>,
    /// The smallest clearance of the cell's bodies over the path, mm; `null` without a cell.
    pub min_clearance_mm: Option<f64>,
}

impl Placement {
    fn feasible(e: &Evaluation) -> Self {
        let (r, p, y) = e.base_from_part.rotation.euler_angles();
        Placement {
            xyz_mm: (e.base_from_part.translation.vector * 1e3).into(),
            rpy_deg: [r, p, y].map(|a| a.to_degrees() + 0.0),
            feasible: true,
            reason: None,
            peak_bound_mm: Some(mm(e.peak)),
            mean_bound_mm: Some(mm(e.sum / e.points as f64)),
            worst_line: Some(e.worst_line),
            min_limit_margin_deg: Some(e.limit_margin.to_degrees()),
            max_condition: Some(e.condition),
            min_clearance_mm: e.clearance.map(mm),
        }
    }
}

impl Document {
    /// The document of `report`; `own` is the setup's own part frame (for an own placement that
    /// is not feasible).
    pub fn new(report: &Report, own: &nalgebra::Isometry3<f64>) -> Self {
        let gain =
            |from: &Evaluation| 100.0 * (1.0 - report.cost(&report.placed) / report.cost(from));
        let own_placement = match &report.own {
            Ok(e) => Placement::feasible(e),
            Err(reason) => {
                let (r, p, y) = own.rotation.euler_angles();
                Placement {
                    xyz_mm: (own.translation.vector * 1e3).into(),
                    rpy_deg: [r, p, y].map(|a| a.to_degrees() + 0.0),
                    feasible: false,
                    reason: Some(reason.clone()),
                    peak_bound_mm: None,
                    mean_bound_mm: None,
                    worst_line: None,
                    min_limit_margin_deg: None,
                    max_condition: None,
                    min_clearance_mm: None,
                }
            }
        };
        Document {
            objective: report.objective.name().into(),
            placed: Placement::feasible(&report.placed),
            own: own_placement,
            reach_only: Placement::feasible(&report.reach),
            gain_vs_own_pct: report.own.as_ref().ok().map(gain),
            gain_vs_reach_only_pct: gain(&report.reach),
            evaluations: report.evaluations,
        }
    }
}
