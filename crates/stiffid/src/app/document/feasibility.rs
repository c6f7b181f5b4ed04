//! The cell's feasibility checks of a group of postures ([`stiffid_core::cell::Checker`]) in documents:
//! `feasibility` of the evaluate document, the skipped postures of a pool.

use serde::{Serialize, Serializer};
use stiffid_core::cell::{Check, Feasibility};

/// One posture's checks in the cell.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Posture {
    /// 1-based position in the group.
    pub posture: usize,
    /// Whether every check passes.
    pub feasible: bool,
    /// The checks made, e.g. `floor`, `self-collision` (those the setup's cell asks for).
    pub checks: Vec<&'static str>,
    /// The smallest distance between bodies (and lines) that must not touch, mm; `null` without
    /// `[cell]` or `[tracker]`.
    pub min_clearance_mm: Option<f64>,
    /// The smallest margin to a constraint of the cell's lengths (floor, obstacles,
    /// self-collision, rope, line of sight, `[constraints]`: every check but the bounds and the
    /// incidence), mm: how far the posture is from its nearest constraint; `null` without them.
    pub min_margin_mm: Option<f64>,
    /// The check of `min_margin_mm`, e.g. `line-of-sight`.
    pub min_margin_check: Option<&'static str>,
    /// The failing checks.
    pub violations: Vec<Violation>,
}

/// One failing check.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Violation {
    /// The check, e.g. `self-collision`.
    pub check: &'static str,
    /// How far it fails, as a negative margin: mm for lengths...
    pub margin_mm: Option<f64>,
    /// ...deg for angles (bounds, incidence).
    pub margin_deg: Option<f64>,
    /// The tightest pair, e.g. `["link 3", "floor"]`.
    pub between: [String; 2],
}

/// The documents of the feasibility of each posture of a group, in order.
pub(crate) fn postures(checks: &[Feasibility]) -> Vec<Posture> {
    checks
        .iter()
        .enumerate()
        .map(|(i, f)| Posture {
            posture: i + 1,
            feasible: f.feasible(),
            checks: f.checks.iter().map(|c| c.kind.key()).collect(),
            min_clearance_mm: f.min_clearance().map(super::mm),
            min_margin_mm: f.min_margin().map(|c| super::mm(c.margin)),
            min_margin_check: f.min_margin().map(|c| c.kind.key()),
            violations: f.violations().map(violation).collect(),
        })
        .collect()
}

/// Each posture's checks in the cell, written as [`postures`] has them. Schema: `Vec<Posture>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn each<S: Serializer>(checks: &[Feasibility], s: S) -> Result<S::Ok, S::Error> {
    postures(checks).serialize(s)
}

fn violation(c: &Check) -> Violation {
    Violation {
        check: c.kind.key(),
        margin_mm: (!c.kind.is_angle()).then_some(super::mm(c.margin)),
        margin_deg: c.kind.is_angle().then(|| c.margin.to_degrees()),
        between: [c.between.0.clone(), c.between.1.clone()],
    }
}

/// A failed check of the cell in words: its kind, the tightest pair and by how much it fails (mm
/// or deg), e.g. `floor (tool - floor) fails by 12 mm`.
pub(crate) fn describe(c: &Check) -> String {
    let by = match c.kind.is_angle() {
        true => format!("{:.1} deg", -c.margin.to_degrees()),
        false => format!("{:.0} mm", -c.margin * 1e3),
    };
    let (a, b) = &c.between;
    let pair = match a == b {
        true => a.clone(),
        false => format!("{a} - {b}"),
    };
    format!("{} ({pair}) fails by {by}", c.kind)
}
