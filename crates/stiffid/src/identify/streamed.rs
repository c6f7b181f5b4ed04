//! Least-squares identification from a measurement file of any size: the file is read twice,
//! chunk by chunk ([`Reader`]), and never held whole.
//!
//! 1. Every chunk is turned into the base frame, checked and reduced by QR in blocks
//!    ([`InBlocks`]); what each row reports (label, line, measuring point) is kept.
//! 2. After the solve, the file is read again and the residuals `delta - Psi h` of every row are
//!    computed ([`residuals`]).
//!
//! The result equals [`least_squares`](super::least_squares) on the whole parsed file to the
//! bit (the same blocks, merged in the same order), whatever the number of threads. Memory
//! (about 50 MB per million rows, plus 80-140 bytes per distinct posture): one chunk of text and
//! its rows, the labels, the axis angles of each posture (for [`crate::observation::Check`]) and
//! per row its line, posture, measuring point and three residuals.

use super::{residuals, Identification, InBlocks};
use crate::error::ColumnProblem;
use crate::formats::measurements::{Chunk, Labels, Layout, Reader};
use crate::identify::frames;
use crate::{Error, Result, Setup};
use rayon::prelude::*;
use std::io::BufRead;

/// Where each measurement of a file came from: what a report names a row by.
#[derive(Debug, Clone, PartialEq)]
pub struct Rows {
    /// The posture labels; `labels.get(postures[i])` is the label of measurement `i`.
    pub labels: Labels,
    /// The posture of each measurement, numbered in order of first appearance.
    pub postures: Vec<usize>,
    /// The line of each measurement (1-based).
    pub lines: Vec<u64>,
    /// The measuring point of each measurement, 0-based.
    pub points: Vec<usize>,
    /// The file's header and columns.
    pub layout: Layout,
}

impl Rows {
    /// The label of measurement `i`'s posture.
    pub fn label(&self, i: usize) -> &str {
        self.labels.get(self.postures[i])
    }
}

/// Identifies the joint stiffness from the measurement file that `open` gives (each call a new
/// reader from the start of the same file; it is called twice), as
/// [`least_squares`](super::least_squares) on the parsed file in the base frame.
///
/// # Errors
/// Those of [`Reader::new`] and [`Reader::next_chunk`], and those of [`InBlocks`] explained as
/// [`Error::Column`] (line and column of the measurement); [`ColumnProblem::Unreadable`] when
/// `open` fails or the file changed between the two readings.
pub fn least_squares<R: BufRead + Send>(
    setup: &Setup,
    mut open: impl FnMut() -> std::io::Result<R>,
) -> Result<(Identification, Rows)> {
    let mut reader = Reader::new(open().map_err(unreadable)?)?;
    let layout = reader.layout().clone();
    let mut blocks = InBlocks::new(setup);
    let mut rows = Rows {
        labels: Labels::default(),
        postures: Vec::new(),
        lines: Vec::new(),
        points: Vec::new(),
        layout: layout.clone(),
    };
    reader.for_each_chunk(|chunk| {
        to_base_frame(setup, &layout, chunk)?;
        blocks
            .push(&chunk.measurements)
            .map_err(|e| layout.explain(e, |n| chunk.line_of(n)))?;
        rows.postures
            .extend(chunk.measurements.iter().map(|m| m.posture));
        rows.points
            .extend(chunk.measurements.iter().map(|m| m.point));
        rows.lines.extend_from_slice(&chunk.lines);
        Ok(())
    })?;
    rows.labels = reader.into_labels();
    let solved = blocks.solve()?;
    let h = solved.solution.h;
    let mut again = Reader::new(open().map_err(unreadable)?)?.unlabelled();
    let mut all = Vec::with_capacity(3 * rows.lines.len());
    again.for_each_chunk(|chunk| {
        to_base_frame(setup, &layout, chunk)?;
        all.extend(residuals(setup, &h, &chunk.measurements));
        Ok(())
    })?;
    if all.len() != 3 * rows.lines.len() {
        return Err(unreadable(std::io::Error::other(
            "the file changed while it was read",
        )));
    }
    Ok((solved.finish(all), rows))
}

/// Turns the measurements of `chunk` into the base frame ([`frames::to_base`]).
fn to_base_frame(setup: &Setup, layout: &Layout, chunk: &mut Chunk) -> Result<()> {
    let (wrench, displacement) = (layout.wrench_frame(), layout.displacement_frame());
    chunk
        .measurements
        .par_chunks_mut(super::BLOCK)
        .try_for_each(|part| frames::to_base(setup, part, wrench, displacement))
}

fn unreadable(e: std::io::Error) -> Error {
    Error::Column {
        line: 1,
        column: None,
        name: String::new(),
        problem: ColumnProblem::Unreadable {
            message: e.to_string(),
        },
    }
}
