//! The cell's feasibility checks of a group of postures, as text and JSON.

use nalgebra::Vector6;
use schemars::JsonSchema;
use serde::Serialize;
use stiffid::cell::{Check, Checker, Feasibility};
use stiffid::Setup;

/// One posture's checks under `feasibility` in `stiffid evaluate --json`.
#[derive(Debug, Serialize, JsonSchema)]
pub struct PostureJson {
    /// 1-based position in the group.
    pub posture: usize,
    /// Whether every check passes.
    pub feasible: bool,
    /// The smallest distance between bodies (and lines) that must not touch, mm; `null` without
    /// `[cell]` or `[tracker]`.
    pub min_clearance_mm: Option<f64>,
    /// The failing checks.
    pub violations: Vec<ViolationJson>,
}

/// One failing check.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ViolationJson {
    /// The check, e.g. `self-collision`.
    pub check: &'static str,
    /// How far it fails, as a negative margin: mm for lengths...
    pub margin_mm: Option<f64>,
    /// ...deg for angles (bounds, incidence).
    pub margin_deg: Option<f64>,
    /// The tightest pair, e.g. `["link 3", "floor"]`.
    pub between: [String; 2],
}

/// The feasibility of every posture of a group.
pub fn of_group(setup: &Setup, group: &[Vector6<f64>]) -> Vec<Feasibility> {
    let checker = Checker::new(setup);
    group.iter().map(|q| checker.feasibility(q)).collect()
}

/// The JSON of [`of_group`].
pub fn json(checks: &[Feasibility]) -> Vec<PostureJson> {
    checks
        .iter()
        .enumerate()
        .map(|(i, f)| PostureJson {
            posture: i + 1,
            feasible: f.feasible(),
            min_clearance_mm: f.min_clearance().map(|c| c * 1e3),
            violations: f
                .violations()
                .map(|c| ViolationJson {
                    check: c.kind.key(),
                    margin_mm: (!c.kind.is_angle()).then_some(c.margin * 1e3),
                    margin_deg: c.kind.is_angle().then(|| c.margin.to_degrees()),
                    between: [c.between.0.clone(), c.between.1.clone()],
                })
                .collect(),
        })
        .collect()
}

/// One line per posture: feasible with its smallest clearance, or the failing checks.
pub fn text(checks: &[Feasibility]) -> String {
    let mut s = format!("\nfeasibility in the cell (checks: {})\n", kinds(checks));
    for (i, f) in checks.iter().enumerate() {
        let clearance = f.min_clearance().map_or(String::new(), |c| {
            format!(", smallest clearance {:.1} mm", c * 1e3)
        });
        s += &match f.feasible() {
            true => format!("  posture {}: feasible{clearance}\n", i + 1),
            false => {
                let failing: Vec<String> = f.violations().map(describe).collect();
                format!("  posture {}: INFEASIBLE: {}\n", i + 1, failing.join("; "))
            }
        };
    }
    s
}

fn kinds(checks: &[Feasibility]) -> String {
    checks.first().map_or(String::new(), |f| {
        let k: Vec<&str> = f.checks.iter().map(|c| c.kind.key()).collect();
        k.join(", ")
    })
}

/// `floor (tool - floor, margin -12.3 mm)`.
fn describe(c: &Check) -> String {
    let margin = match c.kind.is_angle() {
        true => format!("{:.2} deg", c.margin.to_degrees()),
        false => format!("{:.1} mm", c.margin * 1e3),
    };
    format!(
        "{} ({} - {}, margin {margin})",
        c.kind, c.between.0, c.between.1
    )
}
