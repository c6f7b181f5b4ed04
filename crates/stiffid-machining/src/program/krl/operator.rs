//! A motion to a target the geometric operator computes in the motion itself (`LIN XP1:{X 10,
//! Y 0, Z -5, A 0, B 0, C 0}`, `PTP XBASE:XOFF:XP1`; KSS 8.x SI manual, "Geometric operator"):
//! the product of its operands, left to right, computed as an assignment's is
//! ([`super::assign`]), each operand a point of known value or a literal frame with all six
//! members. The result takes the right operand's type: a frame on the right gives a `FRAME`
//! (no `S`, `T`), a point its `S`, `T` too. Compensated, the motion names a new point declared
//! beside the program's others (`LIN XP1_S12`, the motion's line in its name), which replaces
//! the expression.

use super::assign::{merged, pose, set_pose, Item, Members, Values, Writer};
use super::motion::Found;
use crate::program::JointTarget;
use nalgebra::Isometry3;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

impl Writer<'_> {
    /// The motion `code` on `line` (its first byte `start` in the text, its word `first`) of
    /// `routine` when its target is an operator expression: its target, or why the run gives
    /// it; `None` for any other motion.
    ///
    /// # Errors
    /// A word after the expression that is no approximation (`super::motion::check_after`).
    pub(super) fn operated(
        &mut self,
        (line, start): (u64, usize),
        code: &str,
        first: &str,
        (routine, values): (usize, &Values),
    ) -> Result<Option<Found>> {
        if !matches!(first, "PTP" | "LIN" | "SPTP" | "SLIN") {
            return Ok(None);
        }
        let from = code.len() - code.trim_start()[first.len()..].len();
        let (operands, end) = operands(code, from);
        if operands.len() < 2 {
            return Ok(None);
        }
        super::motion::check_after(line, first, &code[end..])?;
        let begin = from + (code[from..].len() - code[from..].trim_start().len());
        let expression = code[begin..end].trim_end();
        let name = match operands[0].starts_with('{') {
            true => "P".to_string(),
            false => operands[0].to_ascii_uppercase(),
        };
        let computed = self
            .product(&operands, routine, values)
            .and_then(|m| self.target(line, &name, m));
        Ok(Some(match computed {
            Ok((_, t)) => {
                let reference = start + begin..start + begin + expression.len();
                let t: JointTarget = t.moved_to(line, false).named_at(reference);
                Found::Targets(vec![t])
            }
            Err(why) => Found::RunTime(
                format!(
                    "{first} {}: the geometric operator {why}",
                    short(expression)
                ),
                None,
            ),
        }))
    }

    /// The product of `operands` (points or literal frames) left to right, typed as the right
    /// operand.
    fn product(
        &self,
        operands: &[&str],
        routine: usize,
        values: &Values,
    ) -> std::result::Result<Members, String> {
        let mut frame = Isometry3::identity();
        let mut last = None;
        for o in operands {
            let m = match o.starts_with('{') {
                true => super::assign::members("", o).ok_or_else(|| {
                    format!(
                        "reads the aggregate '{}', which stiffid does not read",
                        short(o)
                    )
                })?,
                false => (self.current(&o.to_ascii_uppercase(), routine, values))
                    .map_err(|why| format!("reads its operand {why}"))?,
            };
            frame *= pose(&m).ok_or_else(|| format!("reads '{}', which is not a Cartesian value with all of X, Y, Z, A, B and C (write every member of a literal frame)", short(o)))?;
            last = Some(m);
        }
        let last = last.ok_or("reads nothing")?;
        let point = last.items.iter().any(|(k, _)| k == "S" || k == "T");
        let mut out = match (point, last.kind.as_str()) {
            (true, "") => merged("POS", None, &last, false),
            (true, kind) => merged(kind, None, &last, false),
            (false, _) => Members {
                kind: "FRAME".into(),
                items: Vec::<(String, Item)>::new(),
            },
        };
        set_pose(&mut out, &frame);
        Ok(out)
    }
}

/// The operands of the expression at or after byte `from` of `code` (names, or aggregates
/// `{..}`, linked by `:`), and the byte after it.
fn operands(code: &str, from: usize) -> (Vec<&str>, usize) {
    let (mut out, mut at) = (Vec::new(), from);
    loop {
        let rest = &code[at..];
        let skip = rest.len() - rest.trim_start().len();
        let begin = at + skip;
        let len = match code[begin..].starts_with('{') {
            true => code[begin..]
                .find('}')
                .map_or(code.len() - begin, |c| c + 1),
            false => code[begin..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '_' | '$' | '[' | ']')))
                .unwrap_or(code.len() - begin),
        };
        if len == 0 {
            return (out, at);
        }
        out.push(&code[begin..begin + len]);
        at = begin + len;
        let after = &code[at..];
        match after.trim_start().strip_prefix(':') {
            Some(next) => at = code.len() - next.len(),
            None => return (out, at),
        }
    }
}
