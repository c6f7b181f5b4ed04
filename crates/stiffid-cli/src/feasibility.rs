//! The cell's feasibility checks of a group of postures, as text (their document:
//! [`stiffid::app::document::feasibility`]).

use stiffid::cell::{Check, Feasibility};

/// One line per posture: feasible with its smallest clearance, or the failing checks.
pub fn text(checks: &[Feasibility]) -> String {
    let mut s = format!("\nfeasibility in the cell (checks: {})\n", kinds(checks));
    for (i, f) in checks.iter().enumerate() {
        let mut clearance = f.min_clearance().map_or(String::new(), |c| {
            format!(", smallest clearance {:.1} mm", c * 1e3)
        });
        if let Some(c) = f.min_margin() {
            clearance += &format!(", nearest constraint {} {:.1} mm", c.kind, c.margin * 1e3);
        }
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
