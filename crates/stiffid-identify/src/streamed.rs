//! Least-squares identification from a measurement file of any size, read once, chunk by chunk
//! ([`Reader`]), and never held whole.
//!
//! 1. Every chunk is turned into the base frame, checked and reduced by QR in blocks
//!    (`InBlocks`); what each row reports (label, line, measuring point) is kept, and what its
//!    residual needs besides its posture's axis angles (which `InBlocks` keeps): its wrench
//!    (the forces alone when the file has no moment columns and gives the wrench in the base
//!    frame: the moments are then zero) and its displacement.
//! 2. After the solve, the residuals `delta - Psi h` of every row are computed from what was
//!    kept (`residuals`), in place of the displacements.
//!
//! The result equals [`least_squares`](super::least_squares) on the whole parsed file to the
//! bit (the same blocks, merged in the same order; the same residual of each row), whatever the
//! number of threads. Memory (about 100 MB per million rows with forces alone, 125 MB with
//! moments, plus 80-140 bytes per distinct posture): two chunks of text and their rows, the
//! labels, the axis angles of each posture (for [`stiffid_core::observation::Check`]) and per row its
//! line, posture, measuring point, wrench and displacement.

use super::{residuals, Identification, InBlocks, BLOCK};
use nalgebra::{Vector3, Vector6};
use rayon::prelude::*;
use std::io::BufRead;
use stiffid_core::io::measurements::{Chunk, Labels, Layout, Reader};
use stiffid_core::observation::deflection::Frame;
use stiffid_core::observation::frames;
use stiffid_core::observation::Measurement;
use stiffid_core::{Result, Setup};

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
    /// The axis angles of each posture (rad), by posture number.
    pub angles: Vec<Vector6<f64>>,
    /// The external axes' values of each posture (SI), by posture number.
    pub external: Vec<stiffid_core::robot::external::ExternalValues>,
    /// The file's header and columns.
    pub layout: Layout,
}

impl Rows {
    /// The label of measurement `i`'s posture.
    pub fn label(&self, i: usize) -> &str {
        self.labels.get(self.postures[i])
    }
}

/// Identifies the joint stiffness from the measurement file that `source` reads, as
/// [`least_squares`](super::least_squares) on the parsed file in the base frame.
///
/// # Errors
/// Those of [`Reader::new`] and [`Reader::for_each_chunk`], and those of `InBlocks` explained
/// as [`stiffid_core::Error::Column`] (line and column of the measurement).
pub fn least_squares<R: BufRead + Send>(
    setup: &Setup,
    source: R,
) -> Result<(Identification, Rows)> {
    let mut reader = Reader::new(source)?;
    let layout = reader.layout().clone();
    let mut blocks = InBlocks::new(setup.arm());
    let mut rows = Rows {
        labels: Labels::default(),
        postures: Vec::new(),
        lines: Vec::new(),
        points: Vec::new(),
        angles: Vec::new(),
        external: Vec::new(),
        layout: layout.clone(),
    };
    let mut kept = Kept::new(&layout);
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
        kept.push(&chunk.measurements);
        Ok(())
    })?;
    rows.labels = reader.into_labels();
    rows.angles = (0..rows.labels.len())
        .map(|p| *blocks.angles(p).expect("every posture was checked"))
        .collect();
    rows.external = (0..rows.labels.len())
        .map(|p| *blocks.external(p).expect("every posture was checked"))
        .collect();
    let solved = blocks.solve()?;
    let h = solved.solution.h;
    let mut all = std::mem::take(&mut kept.displacements);
    let mut predicted = vec![0.0; all.len()];
    all.par_chunks_mut(3 * BLOCK)
        .zip(predicted.par_chunks_mut(3 * BLOCK))
        .enumerate()
        .for_each(|(b, (block, fitted))| {
            let first = b * BLOCK;
            let measurements: Vec<Measurement> = (first..first + block.len() / 3)
                .map(|i| {
                    let posture = rows.postures[i];
                    Measurement {
                        posture,
                        point: rows.points[i],
                        q: *blocks.angles(posture).expect("every posture was checked"),
                        e: *blocks.external(posture).expect("every posture was checked"),
                        wrench: kept.wrench(i),
                        displacement: Vector3::from_column_slice(&block[3 * (i - first)..][..3]),
                    }
                })
                .collect();
            let (r, p) = residuals(setup.arm(), &h, &measurements);
            block.copy_from_slice(&r);
            fitted.copy_from_slice(&p);
        });
    Ok((solved.finish((all, predicted)), rows))
}

/// What the residual of each row needs besides its posture's axis angles and measuring point:
/// the wrench (base frame; its forces alone when the moments are zero) and the displacement.
struct Kept {
    /// Numbers of the wrench kept per row: 3 (forces, zero moments) or 6.
    width: usize,
    wrenches: Vec<f64>,
    displacements: Vec<f64>,
}

impl Kept {
    fn new(layout: &Layout) -> Self {
        let zero_moments = !layout.has_moments() && layout.wrench_frame() == Frame::Base;
        Self {
            width: if zero_moments { 3 } else { 6 },
            wrenches: Vec::new(),
            displacements: Vec::new(),
        }
    }

    fn push(&mut self, measurements: &[Measurement]) {
        for m in measurements {
            self.wrenches
                .extend_from_slice(&m.wrench.as_slice()[..self.width]);
            self.displacements
                .extend_from_slice(m.displacement.as_slice());
        }
    }

    /// The wrench of row `i`.
    fn wrench(&self, i: usize) -> Vector6<f64> {
        let mut w = Vector6::zeros();
        w.as_mut_slice()[..self.width]
            .copy_from_slice(&self.wrenches[self.width * i..][..self.width]);
        w
    }
}

/// Turns the measurements of `chunk` into the base frame ([`frames::to_base`]).
fn to_base_frame(setup: &Setup, layout: &Layout, chunk: &mut Chunk) -> Result<()> {
    let (wrench, displacement) = (layout.wrench_frame(), layout.displacement_frame());
    chunk
        .measurements
        .par_chunks_mut(BLOCK)
        .try_for_each(|part| frames::to_base(setup, part, wrench, displacement))
}
