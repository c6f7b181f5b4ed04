//! A compensated program's segments: its points grouped by line, in order, with the largest
//! force, deflection before and after, and standard deviation of each line.

use super::Segment;
use stiffid_machining::process::Process;

/// The segments of a compensated program: its points grouped by line, in order.
pub(super) fn segments(c: &stiffid_machining::Report, process: &Process) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::new();
    for ((p, r), op) in c.points.iter().zip(&c.results).zip(&c.operations) {
        let force = r.wrench.fixed_rows::<3>(0).norm();
        let before = r.deflection.fixed_rows::<3>(0).norm();
        let std = r.translation_norm_std;
        match out.last_mut() {
            Some(s) if s.line == p.line => {
                s.points += 1;
                s.force = s.force.max(force);
                s.deflection_before = s.deflection_before.max(before);
                s.deflection_after = s.deflection_after.max(r.residual_position);
                s.deflection_std = s.deflection_std.zip(std).map(|(a, b)| a.max(b));
            }
            _ => out.push(Segment {
                line: p.line,
                operation: op.map(|i| process.operations[i].name.clone()),
                points: 1,
                force,
                deflection_before: before,
                deflection_after: r.residual_position,
                deflection_std: std,
            }),
        }
    }
    out
}
