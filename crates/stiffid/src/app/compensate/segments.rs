//! A compensated program as the report holds it ([`ProgramReport`]), and its segments: its points
//! grouped by line, in order, with the largest force, deflection before and after, and standard
//! deviation of each line ([`Segment`]).

use super::dynamics;
#[cfg(doc)]
use super::Input;
use crate::app::document::units;
use stiffid_core::io::Encoding;
use stiffid_machining::process::Process;
use stiffid_machining::program::generate;
use stiffid_machining::Language;

/// A compensated program.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramReport {
    /// Its language.
    pub language: Language,
    /// The language of the compensated program.
    pub output: Language,
    /// The process file's name.
    pub process: String,
    /// The program, compensated, in its own format (robot programs with the compensated axis
    /// angles and every other byte as read, G-code with the compensated positions), or a G-code
    /// path as a new robot program of the compensated targets (its main program when it is
    /// split).
    pub text: String,
    /// A generated program's sub-programs, in call order (empty unless it is split): each
    /// written to a file of its name next to the main program's.
    pub subprograms: Vec<generate::File>,
    /// For a KRL program read with its `.dat` ([`Input::Program`]'s `data`): the `.dat`
    /// compensated (its `DEFDAT` renamed with the program's `DEF`); for a G-code path written as
    /// a KRL program, its points' `.dat` ([`generate::File`]'s `data`). To be written beside the
    /// program under its stem with `.dat`, together with it.
    pub data: Option<String>,
    /// Each segment's force and deflection, in program order.
    pub segments: Vec<Segment>,
    /// Each operation's drilling surge or milling frequencies (`dynamics::operations`); empty
    /// without a mass model.
    pub dynamics: Vec<dynamics::OperationDynamics>,
    /// The encoding the program was read in, which its files are written in
    /// ([`ProgramReport::bytes`]).
    pub encoding: Encoding,
}

impl ProgramReport {
    /// `text`, one of the program's files (its `text`, `data` or a sub-program's), as the bytes
    /// to write: in the encoding the program was read in ([`Encoding::encode`]; the job has
    /// checked every file holds only its characters).
    pub fn bytes(&self, text: &str) -> Vec<u8> {
        (self.encoding.encode(text)).unwrap_or_else(|_| text.as_bytes().to_vec())
    }

    /// Checks every file of the program can be written in its encoding.
    ///
    /// # Errors
    /// [`stiffid_core::Error::InvalidField`] naming `out_name` and the first character the
    /// encoding has no byte for (a name or remark from the setup in a Latin-1 program).
    pub(crate) fn check_encoding(&self, out_name: &str) -> stiffid_core::Result<()> {
        let subprograms = self.subprograms.iter();
        let texts = [Some(&self.text), self.data.as_ref()].into_iter().flatten();
        let texts = texts.chain(
            subprograms
                .flat_map(|f| [Some(&f.text), f.data.as_ref()])
                .flatten(),
        );
        for t in texts {
            self.encoding
                .encode(t)
                .map_err(|message| stiffid_core::Error::InvalidField {
                    field: out_name.to_string(),
                    message,
                })?;
        }
        Ok(())
    }
}

/// One segment of a program: the points of one line (a G-code block's arc points, a robot
/// program's target).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[cfg_attr(
    feature = "schema",
    schemars(
        rename = "SegmentDocument",
        description = "One segment of a program: the points of one line (a G-code block's arc points, a robot\nprogram's target)."
    )
)]
pub struct Segment {
    /// The program line, 1-based.
    pub line: u64,
    /// The operation that cuts there (its name), `null` for a rapid move or a block no operation
    /// covers.
    pub operation: Option<String>,
    /// Path points of the segment.
    pub points: usize,
    /// The largest force on the tool over the segment (the process's and the tool's weight), N.
    #[serde(rename = "force_n")]
    pub force: f64,
    /// The largest TCP deflection under the force, uncompensated: m, written in mm.
    #[serde(rename = "deflection_before_mm", serialize_with = "units::mm")]
    pub deflection_before: f64,
    /// The largest TCP deflection left after compensation (the residual): m, written in mm.
    #[serde(rename = "deflection_after_mm", serialize_with = "units::mm")]
    pub deflection_after: f64,
    /// With a compliance covariance: the largest standard deviation of the uncompensated
    /// deflection's length (what compensation cannot remove); else `null`: m, written in mm.
    #[serde(rename = "deflection_std_mm", serialize_with = "units::mm_option")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub deflection_std: Option<f64>,
}

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
