//! The cell's feasibility checks of a group of postures, as text, from their document
//! ([`stiffid::app::document::feasibility`]).

use stiffid::app::document::feasibility::{Posture, Violation};

/// One line per posture: feasible with its smallest clearance, or the failing checks.
pub fn text(postures: &[Posture]) -> String {
    let checks = postures
        .first()
        .map_or(String::new(), |p| p.checks.join(", "));
    let mut s = format!("\nfeasibility in the cell (checks: {checks})\n");
    for p in postures {
        let mut clearance = p
            .min_clearance_mm
            .map_or(String::new(), |c| format!(", smallest clearance {c:.1} mm"));
        if let (Some(check), Some(margin)) = (p.min_margin_check, p.min_margin_mm) {
            clearance += &format!(", nearest constraint {check} {margin:.1} mm");
        }
        s += &match p.feasible {
            true => format!("  posture {}: feasible{clearance}\n", p.posture),
            false => {
                let failing: Vec<String> = p.violations.iter().map(describe).collect();
                format!(
                    "  posture {}: INFEASIBLE: {}\n",
                    p.posture,
                    failing.join("; ")
                )
            }
        };
    }
    s
}

/// `floor (tool - floor, margin -12.3 mm)`.
fn describe(v: &Violation) -> String {
    let margin = match (v.margin_deg, v.margin_mm) {
        (Some(deg), _) => format!("{deg:.2} deg"),
        (None, mm) => format!("{:.1} mm", mm.unwrap_or(f64::NAN)),
    };
    format!(
        "{} ({} - {}, margin {margin})",
        v.check, v.between[0], v.between[1]
    )
}
