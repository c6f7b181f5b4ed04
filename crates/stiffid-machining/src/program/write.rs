//! A program's targets read and written back: [`JointProgram`]'s methods.

use super::{at, points, whole_pulses, JointProgram, JointTarget, DECIMALS};

/// A program written back: its text, its data file's (KRL's `.dat`), and each program of the
/// backup it calls that moves, its file's name as given and its text.
pub type Written = (String, Option<String>, Vec<(String, String)>);
use stiffid_core::{Error, Result};

impl JointProgram {
    /// The program with the axis angles of target `i` replaced by `q_deg[i]` (deg) where they
    /// differ from the ones read; the external values and every other byte as read.
    ///
    /// # Errors
    /// Those of [`JointProgram::write_with_external`].
    pub fn write(&self, q_deg: &[[f64; 6]]) -> Result<String> {
        let external: Vec<Vec<Option<f64>>> =
            self.targets.iter().map(|t| t.external.clone()).collect();
        self.write_with_external(q_deg, &external)
    }

    /// The program with the axis angles of target `i` replaced by `q_deg[i]` (deg) and its
    /// external values by `external[i]` (mm or deg, in the order of [`JointProgram::axes`]) where
    /// they differ from the ones read; every other byte as read. A value the target does not
    /// give (`None` in [`JointTarget::external`]) stays `None`: nothing is added to a target.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`q_deg`, `external`) when a list has another length than the
    /// targets, a row of `external` another shape than the target's values, or a value is not
    /// finite; [`Error::Program`] naming the line where two motions to one declared point would
    /// take different values, or of a Cartesian target of a program not resolved
    /// ([`crate::program::cartesian::resolve`]); [`Error::InvalidField`] (`data`) for a program whose data file
    /// changes, which only `JointProgram::write_pair` writes.
    pub fn write_with_external(
        &self,
        q_deg: &[[f64; 6]],
        external: &[Vec<Option<f64>>],
    ) -> Result<String> {
        match self.write_pair(q_deg, external)? {
            (program, None) => Ok(program),
            (program, Some(data)) if Some(data.as_str()) == self.data() => Ok(program),
            _ => Err(Error::InvalidField {
                field: "data".into(),
                message: "targets of the program live in its data file (KRL's .dat), which changes with them: write both (JointProgram::write_pair)".into(),
            }),
        }
    }

    /// The data file's text as read (KRL's `.dat`), if one was.
    pub(crate) fn data(&self) -> Option<&str> {
        self.data_at.map(|at| &self.text[at..])
    }

    /// The program and its data file (when one was read: KRL's `.dat`), the targets written as
    /// [`JointProgram::write_with_external`] does: every number of a target in its file, every
    /// other byte of both as read.
    ///
    /// # Errors
    /// Those of [`JointProgram::write_with_external`] but the data file's.
    pub(crate) fn write_pair(
        &self,
        q_deg: &[[f64; 6]],
        external: &[Vec<Option<f64>>],
    ) -> Result<(String, Option<String>)> {
        let (program, data, _) = self.write_files(q_deg, external)?;
        Ok((program, data))
    }

    /// `JointProgram::write_pair`, and each program of the backup it calls that moves
    /// ([`JointProgram::called_in`]): its file's name as given and its text, compensated in
    /// place.
    ///
    /// # Errors
    /// Those of `JointProgram::write_pair`.
    pub fn write_files(
        &self,
        q_deg: &[[f64; 6]],
        external: &[Vec<Option<f64>>],
    ) -> Result<Written> {
        if q_deg.len() != self.targets.len() || q_deg.iter().flatten().any(|v| !v.is_finite()) {
            return Err(Error::InvalidField {
                field: "q_deg".into(),
                message: format!(
                    "expected {} rows of 6 finite axis angles, one per target",
                    self.targets.len()
                ),
            });
        }
        let shaped = |(t, e): (&JointTarget, &Vec<Option<f64>>)| {
            e.len() == t.external.len()
                && e.iter()
                    .zip(&t.external)
                    .all(|(a, b)| a.is_some() == b.is_some() && a.is_none_or(|v| v.is_finite()))
        };
        if external.len() != self.targets.len() || !self.targets.iter().zip(external).all(shaped) {
            return Err(Error::InvalidField {
                field: "external".into(),
                message: format!(
                    "expected {} rows of finite external values, one per target, each with a value exactly where the target read has one ({})",
                    self.targets.len(),
                    self.axes.join(", ")
                ),
            });
        }
        // Each number to write: its span, the target, its text, whether it changed.
        let mut edits: Vec<points::Edit> = Vec::with_capacity(6 * self.targets.len());
        for (i, t) in self.targets.iter().enumerate().filter(|(_, t)| !t.held) {
            let values = |j: usize| {
                let e = external[j].iter().map(|v| v.unwrap_or(0.0));
                q_deg[j].iter().copied().chain(e).collect::<Vec<f64>>()
            };
            let (now, read) = (values(i), self.read_values(i));
            if let Some(c) = &t.cartesian {
                let writer = self.writer.as_ref().ok_or_else(|| {
                    at(t.line, "a Cartesian target not resolved with the setup's controller (program::cartesian::resolve)".into())
                })?;
                let q = nalgebra::Vector6::from(q_deg[i]).map(f64::to_radians);
                if let Some(why) = writer.stale_flags(self.dialect, c, &q) {
                    return Err(at(t.line, why));
                }
                // The pose moves with the arm and with its track.
                let changed = now != read;
                for (span, text) in writer.texts(self.dialect, c, (&q, &external[i])) {
                    edits.push((span, i, text, changed));
                }
            }
            let joint = t.cartesian.is_none();
            let spans = t.spans.iter().map(|s| joint.then(|| s.clone()));
            let spans = spans.chain(t.external_spans.iter().cloned());
            for (k, span) in spans.enumerate() {
                let Some(span) = span else { continue };
                let (value, changed) = match (t.incremental, i.checked_sub(1)) {
                    (true, Some(p)) => {
                        let (before, before_read) = (values(p), self.read_values(p));
                        (
                            now[k] - before[k],
                            now[k] != read[k] || before[k] != before_read[k],
                        )
                    }
                    _ => (now[k], now[k] != read[k]),
                };
                edits.push((span, i, self.number(k, value), changed));
            }
        }
        points::split(self, &mut edits)?;
        edits.sort_by_key(|e| e.0.start);
        let mut out = String::with_capacity(self.text.len() + self.targets.len() * 24);
        let mut at = 0;
        // Where each file after the program's begins (its data file's, each called program's)
        // and how much the text before it grew.
        let mut files: Vec<(usize, isize)> = (self.data_at.into_iter())
            .chain(self.called.iter().map(|(_, a)| *a))
            .map(|a| (a, 0))
            .collect();
        for (j, (span, i, text, changed)) in edits.iter().enumerate() {
            if let Some((_, first, other, _)) = edits[..j].last().filter(|e| e.0 == *span) {
                if other != text {
                    let (a, b) = (&self.targets[*first], &self.targets[*i]);
                    return Err(Error::Program {
                        line: b.line,
                        message: differ((a.line, b.line, b.origin), other, text),
                    });
                }
                continue;
            }
            let shared_change = edits[j..].iter().take_while(|e| e.0 == *span).any(|e| e.3);
            if *changed || shared_change {
                out.push_str(&self.text[at..span.start]);
                out.push_str(text);
                at = span.end;
                for (_, grown) in files.iter_mut().filter(|(a, _)| span.end <= *a) {
                    *grown += text.len() as isize - span.len() as isize;
                }
            }
        }
        out.push_str(&self.text[at..]);
        Ok(self.finished(self.split_files(out, &files)))
    }

    /// Each file of `written` finished as its language needs, from its text as read
    /// ([`super::controller::Controller::written`]).
    fn finished(&self, (program, data, called): Written) -> Written {
        let controller = self.dialect.controller();
        let program_end = (self.data_at.into_iter())
            .chain(self.called.iter().map(|(_, a)| *a))
            .next()
            .unwrap_or(self.text.len());
        let program = controller.written(&self.text[..program_end], program);
        let end = |k: usize| self.called.get(k + 1).map_or(self.text.len(), |c| c.1);
        let called = (called.into_iter().enumerate())
            .map(|(k, (name, t))| {
                let read = &self.text[self.called[k].1..end(k)];
                (name, controller.written(read, t))
            })
            .collect();
        (program, data, called)
    }

    /// The text written `out` split into its files: the program's, its data file's, each called
    /// program's (`files`: where each file after the program's began in the text read, and how
    /// much the text before it grew).
    fn split_files(&self, mut out: String, files: &[(usize, isize)]) -> Written {
        let mut called = Vec::with_capacity(self.called.len());
        for (k, (name, _)) in self.called.iter().enumerate().rev() {
            let (start, grown) = files[files.len() - self.called.len() + k];
            let text = out.split_off((start as isize + grown) as usize);
            called.push((name.clone(), text));
        }
        called.reverse();
        let data = (self.data_at.map(|d| files[0].1 + d as isize))
            .map(|start| out.split_off(start as usize));
        (out, data, called)
    }

    /// Per value (the six axes, then the external ones), the pulses per degree or mm of a value
    /// written in whole encoder pulses (INFORM), `None` for a decimal value.
    pub fn pulses(&self) -> &[Option<f64>] {
        &self.pulses
    }

    /// Value `k` of a target (the six axes, then the external ones) as the program writes it:
    /// [`DECIMALS`] decimals, or a whole number of pulses (INFORM's pulse form).
    fn number(&self, k: usize, value: f64) -> String {
        match self.pulses.get(k).copied().flatten() {
            Some(per_unit) => whole_pulses(value, per_unit).to_string(),
            None => format!("{value:.DECIMALS$}"),
        }
    }

    /// Target `i`'s six axis values then its external ones (absent ones as 0), as read.
    fn read_values(&self, i: usize) -> Vec<f64> {
        let t = &self.targets[i];
        let q = self.read_deg.get(i).unwrap_or(&t.q_deg);
        let e = t.external.iter().map(|v| v.unwrap_or(0.0));
        q.iter().copied().chain(e).collect()
    }

    /// The program with other axis angles in its targets than `read`'s (the same program as
    /// read), whose read values it keeps: a value written back is compared with the program's
    /// text, not with the angles it holds now.
    pub(crate) fn with_read_kept(mut self, read: &JointProgram) -> Self {
        self.read_deg = (read.targets.iter().enumerate())
            .map(|(i, t)| *read.read_deg.get(i).unwrap_or(&t.q_deg))
            .collect();
        self
    }
}

/// Why two visits (on lines `a` and `b`) of the point of line `origin` cannot be written: their
/// compensated texts `other` and `text` differ.
fn differ((a, b, origin): (u64, u64, u64), other: &str, text: &str) -> String {
    match a == b {
        // A loop read once per value of its variable.
        true => format!("the motion of line {b} runs more than once (a loop read once per value of its variable) and its runs' compensated targets differ ({other} and {text}); one line holds one target: give each run its own point (an array of points, the motion to its element by the loop's variable)"),
        false => format!("the motions of lines {a} and {b} go to the one point of line {origin}, but their compensated targets differ ({other} and {text}): give each visit its own point"),
    }
}
