//! The program written back with corrected positions (module docs of [`super`], "What is written").

use super::{Block, GCode, Motion};
use nalgebra::Vector3;
use std::ops::Range;
use stiffid_core::{Error, Result};

impl GCode {
    /// The program with each point at `positions[i]` (part frame, m) (module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`positions`) for another number of positions than points or a
    /// position that is not finite.
    pub fn write(&self, positions: &[Vector3<f64>]) -> Result<String> {
        self.written(positions, None)
    }

    /// [`GCode::write`] with each point's mapped external axes at `external[i]` (mm for `U V W`,
    /// deg for `A B C`, in the order of [`GCode::external`]) (module docs).
    ///
    /// # Errors
    /// Those of [`GCode::write`]; [`Error::InvalidField`] (`external`) for another number of
    /// rows than points, a row of another length than the letters mapped, or a value that is
    /// not finite.
    pub(crate) fn write_with_external(
        &self,
        positions: &[Vector3<f64>],
        external: &[Vec<f64>],
    ) -> Result<String> {
        let letters = self.external.0.len();
        if external.len() != self.points.len()
            || (external.iter()).any(|e| e.len() != letters || !e.iter().all(|v| v.is_finite()))
        {
            return Err(Error::InvalidField {
                field: "external".into(),
                message: format!(
                    "expected {} rows of {letters} finite external values, one per point",
                    self.points.len()
                ),
            });
        }
        self.written(positions, Some(external))
    }

    /// The program written (module docs): the external values too when given.
    fn written(&self, positions: &[Vector3<f64>], external: Option<&[Vec<f64>]>) -> Result<String> {
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
        let mut words = Words {
            positions,
            external,
            letters: &self.external.0,
            written: self.start.unwrap_or_default(),
            written_e: vec![0.0; self.external.0.len()],
        };
        let mut out = String::with_capacity(self.text.len() * 2);
        let mut at = 0;
        for b in &self.blocks {
            self.push_dropping(at..b.line.start, &mut out);
            let mut drop = b.drop.clone();
            let within = |r: &&Range<usize>| r.start >= b.line.start && r.end <= b.line.end;
            drop.extend(self.dropped.iter().filter(within).cloned());
            if external.is_some() {
                drop.extend(b.external_words.iter().cloned());
            }
            let ending = match self.text[b.line.end..].starts_with("\r\n") {
                true => "\r\n",
                false => "\n",
            };
            match &b.cycle {
                _ if b.verbatim => {
                    out.push_str(&self.text[b.line.clone()]);
                    if b.points.end > b.points.start {
                        words.written = self.points[b.points.end - 1].position;
                    }
                }
                Some(dwell) => self.write_cycle(b, drop, dwell, ending, &mut words, &mut out),
                None => self.write_motion(b, &drop, ending, &mut words, &mut out),
            }
            at = b.line.end;
        }
        self.push_dropping(at..self.text.len(), &mut out);
        Ok(out)
    }

    /// The text of `range` with the dropped words in it left out ([`GCode::dropped`]).
    fn push_dropping(&self, range: Range<usize>, out: &mut String) {
        let mut from = range.start;
        let inside = |r: &&Range<usize>| r.start >= range.start && r.end <= range.end;
        for r in self.dropped.iter().filter(inside) {
            let r = blanks_before(&self.text, r, from);
            out.push_str(&self.text[from..r.start]);
            from = r.end;
        }
        out.push_str(&self.text[from..range.end]);
    }

    /// A canned cycle's block: its own words kept, each point a `G0`/`G1` block of its own, the
    /// dwell `G4 P..` after the bottom.
    fn write_cycle(
        &self,
        b: &Block,
        mut drop: Vec<Range<usize>>,
        dwell: &Option<(Vec<usize>, String)>,
        ending: &str,
        words: &mut Words,
        out: &mut String,
    ) {
        drop.sort_by_key(|r| r.start);
        let mut from = b.line.start;
        for r in &drop {
            let r = blanks_before(&self.text, r, from);
            out.push_str(&self.text[from..r.start]);
            from = r.end;
        }
        out.push_str(&self.text[from..b.line.end]);
        for (j, (k, point)) in (b.points.clone())
            .zip(&self.points[b.points.clone()])
            .enumerate()
        {
            out.push_str(ending);
            out.push_str(match point.motion {
                Motion::Rapid => "G0 ",
                Motion::Feed => "G1 ",
            });
            out.push_str(&words.point(k, b));
            if let Some((_, p_word)) = dwell.as_ref().filter(|(after, _)| after.contains(&j)) {
                out.push_str(ending);
                out.push_str("G4 ");
                out.push_str(p_word);
            }
        }
    }

    /// A block of a straight or circular move: its first point's words where the dropped words
    /// were (an arc's `G2`/`G3` as `G1`), the arc's further points on blocks of their own.
    fn write_motion(
        &self,
        b: &Block,
        drop: &[Range<usize>],
        ending: &str,
        words: &mut Words,
        out: &mut String,
    ) {
        let first = words.point(b.points.start, b);
        let mut line = String::new();
        let mut from = b.line.start;
        let mut edits: Vec<(Range<usize>, &str)> = drop.iter().map(|r| (r.clone(), "")).collect();
        if let Some(g) = &b.arc_word {
            edits.push((g.clone(), "G1"));
        }
        edits.sort_by_key(|(r, _)| r.start);
        let insert = edits
            .iter()
            .find(|(_, t)| t.is_empty())
            .map_or(b.line.end, |(r, _)| r.start);
        for (r, t) in &edits {
            // A word dropped, not replaced, takes the blanks before it along.
            let r = match t.is_empty() && r.start != insert {
                true => blanks_before(&self.text, r, from),
                false => r.clone(),
            };
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
        for k in b.points.start + 1..b.points.end {
            out.push_str(ending);
            out.push_str(&words.point(k, b));
        }
    }
}

/// `r` (a dropped word's bytes in `text`) widened to the spaces and tabs before it, back to
/// `floor` at most: the written block keeps no blanks where words were, and a program
/// compensated again gains none.
fn blanks_before(text: &str, r: &Range<usize>, floor: usize) -> Range<usize> {
    let before = &text[floor..r.start];
    r.start - (before.len() - before.trim_end_matches([' ', '\t']).len())..r.end
}

/// The words of each point written, and where the controller is as written (for incremental
/// blocks).
struct Words<'a> {
    positions: &'a [Vector3<f64>],
    external: Option<&'a [Vec<f64>]>,
    letters: &'a [char],
    written: Vector3<f64>,
    written_e: Vec<f64>,
}

impl Words<'_> {
    /// Point `k`'s `X Y Z` and external axes' words in block `b`'s units and distance mode.
    fn point(&mut self, k: usize, b: &Block) -> String {
        let scale = if b.inch { 25.4e-3 } else { 1e-3 };
        let p = &self.positions[k];
        let v = if b.incremental {
            // The block's first point carries the offset's change the controller moves by.
            let take_up = if k == b.points.start { b.take_up } else { 0.0 };
            (b.to_program.rotation * (p - self.written) + Vector3::z() * take_up) / scale
        } else {
            (b.to_program * nalgebra::Point3::from(*p)).coords / scale
        };
        self.written = *p;
        let mut text = format!("X{:.6} Y{:.6} Z{:.6}", v.x, v.y, v.z);
        for (j, l) in self.letters.iter().enumerate() {
            let Some(e) = self.external.map(|e| e[k][j]) else {
                break;
            };
            let unit = match (l, b.inch) {
                ('U' | 'V' | 'W', true) => 25.4,
                _ => 1.0,
            };
            let value = if b.incremental {
                e - self.written_e[j]
            } else {
                e
            };
            self.written_e[j] = e;
            text.push_str(&format!(" {l}{:.6}", value / unit));
        }
        text
    }
}
