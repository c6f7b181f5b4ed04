//! The program written back with corrected positions (module docs of [`super`], "What is written").

use super::{GCode, Motion};
use crate::{Error, Result};
use nalgebra::Vector3;
use std::ops::Range;

impl GCode {
    /// The program with each point at `positions[i]` (part frame, m) (module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`positions`) for another number of positions than points or a
    /// position that is not finite.
    pub fn write(&self, positions: &[Vector3<f64>]) -> Result<String> {
        if positions.len() != self.points.len()
            || positions.iter().any(|p| !p.iter().all(|v| v.is_finite()))
        {
            return Err(Error::InvalidField {
                field: "positions".into(),
                message: format!(
                    "expected {} finite positions, one per point",
                    self.points.len()
                ),
            });
        }
        let mut out = String::with_capacity(self.text.len() * 2);
        let mut at = 0;
        // The position the controller is at, as written (for incremental blocks).
        let mut written = Vector3::zeros();
        for b in &self.blocks {
            out.push_str(&self.text[at..b.line.start]);
            let scale = if b.inch { 25.4e-3 } else { 1e-3 };
            let mut words = |p: &Vector3<f64>| {
                let v = if b.incremental {
                    (p - written) / scale
                } else {
                    p / scale
                };
                written = *p;
                format!("X{:.6} Y{:.6} Z{:.6}", v.x, v.y, v.z)
            };
            let ending = match self.text[b.line.end..].starts_with("\r\n") {
                true => "\r\n",
                false => "\n",
            };
            if let Some(dwell) = &b.cycle {
                let mut drop = b.drop.clone();
                drop.sort_by_key(|r| r.start);
                let mut from = b.line.start;
                for r in &drop {
                    out.push_str(&self.text[from..r.start]);
                    from = r.end;
                }
                out.push_str(&self.text[from..b.line.end]);
                for (j, (p, point)) in positions[b.points.clone()]
                    .iter()
                    .zip(&self.points[b.points.clone()])
                    .enumerate()
                {
                    out.push_str(ending);
                    out.push_str(match point.motion {
                        Motion::Rapid => "G0 ",
                        Motion::Feed => "G1 ",
                    });
                    out.push_str(&words(p));
                    if let Some((_, p_word)) = dwell.as_ref().filter(|(after, _)| *after == j) {
                        out.push_str(ending);
                        out.push_str("G4 ");
                        out.push_str(p_word);
                    }
                }
                at = b.line.end;
                continue;
            }
            let first = words(&positions[b.points.start]);
            let mut line = String::new();
            let mut from = b.line.start;
            let mut edits: Vec<(Range<usize>, &str)> =
                b.drop.iter().map(|r| (r.clone(), "")).collect();
            if let Some(g) = &b.arc_word {
                edits.push((g.clone(), "G1"));
            }
            edits.sort_by_key(|(r, _)| r.start);
            let insert = edits
                .iter()
                .find(|(_, t)| t.is_empty())
                .map_or(b.line.end, |(r, _)| r.start);
            for (r, t) in &edits {
                line.push_str(&self.text[from..r.start]);
                if r.start == insert {
                    line.push_str(&first);
                }
                line.push_str(t);
                from = r.end;
            }
            line.push_str(&self.text[from..b.line.end]);
            if insert == b.line.end {
                line.push(' ');
                line.push_str(&first);
            }
            out.push_str(&line);
            for p in &positions[b.points.start + 1..b.points.end] {
                out.push_str(ending);
                out.push_str(&words(p));
            }
            at = b.line.end;
        }
        out.push_str(&self.text[at..]);
        Ok(out)
    }
}
