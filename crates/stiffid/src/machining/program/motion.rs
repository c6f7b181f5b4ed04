//! Which targets a robot program reaches by a joint motion (`PTP`, `MoveJ`, `J`), where the arm
//! may change configuration, and which by a linear one (`LIN`, `MoveL`, `L`), along which it
//! cannot.

use super::JointProgram;

/// The motion instructions that move the axes from target to target (the tool's path between
/// them is not a line): KRL `PTP` and `SPTP`, RAPID `MoveJ` and `MoveAbsJ`, LS `J`, INFORM
/// `MOVJ`.
const JOINT: [&str; 6] = ["PTP", "SPTP", "MOVEJ", "MOVEABSJ", "J", "MOVJ"];

impl JointProgram {
    /// Whether each target is reached by a joint motion ([`JOINT`]), read from its motion
    /// instruction's first word (an LS line's number before it skipped); one per target.
    pub fn joint_moves(&self) -> Vec<bool> {
        let lines: Vec<&str> = self.text.lines().collect();
        (self.targets.iter())
            .map(|t| {
                let text = lines.get(t.line as usize - 1).copied().unwrap_or("");
                is_joint(text)
            })
            .collect()
    }
}

/// Whether a motion instruction's line is a joint motion.
fn is_joint(line: &str) -> bool {
    let line = line.trim_start();
    // An LS line starts with its number: `   1:J P[1] 100% FINE ;`.
    let line = match line.split_once(':') {
        Some((n, rest)) if !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) => rest,
        _ => line,
    };
    let word: String = (line.trim_start().chars())
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    JOINT.contains(&word.to_ascii_uppercase().as_str())
}

#[cfg(test)]
mod tests {
    use super::is_joint;

    #[test]
    fn joint_and_linear_motions() {
        for joint in [
            "PTP {A1 0, A2 -90}",
            "  SPTP P1",
            "MoveAbsJ\\Conc [[0,0,0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;",
            "    MoveJ p10, v100, z10, tspindle\\WObj:=wpart;",
            "   1:J P[1] 100% FINE    ;",
            "MOVJ C00000 VJ=50.00",
        ] {
            assert!(is_joint(joint), "{joint}");
        }
        for linear in [
            "LIN {A1 0}",
            "SLIN P2",
            "MoveL p20, v100, z1, tspindle;",
            "  12:L P[2] 100mm/sec CNT100    ;",
            "MOVL C00001 V=100.0",
        ] {
            assert!(!is_joint(linear), "{linear}");
        }
    }
}
