//! Measurement files: CSV, one row per posture and measuring point, units in the header.
//!
//! ```text
//! posture,point,q1_deg,...,q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm],dx_mm,dy_mm,dz_mm
//! ```
//! - `posture`: a label; rows of one posture share it (and their axis angles). Labels are numbered
//!   in order of first appearance ([`Measurement::posture`]); any number of them.
//! - `point`: the measuring point, numbered from 1 as in the setup's `measuring_points_mm`.
//! - `q1_deg..q6_deg`: axis angles, deg.
//! - `fx_n..mz_nm`: the wrench that acts on the robot at the loading point, N and Nm, base frame;
//!   or `fx_tool_n,fy_tool_n,fz_tool_n[,mx_tool_nm,my_tool_nm,mz_tool_nm]` in the tool (flange)
//!   frame, e.g. an F/T sensor's reading. The moment columns are optional (all three or none; none
//!   means zero) and in the frame of the forces.
//! - `dx_mm..dz_mm`: translation of the measuring point, loaded minus unloaded, base frame, mm; or
//!   `dx_tracker_mm,dy_tracker_mm,dz_tracker_mm` in the laser tracker's frame (the setup's
//!   `[tracker] base_from_tracker`); or instead the positions `x_loaded_mm,y_loaded_mm,z_loaded_mm,
//!   x_unloaded_mm,y_unloaded_mm,z_unloaded_mm` (or `x_loaded_tracker_mm`, ...), which are
//!   subtracted.
//!
//! Columns may come in any order; lines starting with `#` are comments; a field may be quoted but
//! may not span lines. [`parse`] keeps the quantities in the file's frames
//! ([`MeasurementFile::wrench_frame`], [`MeasurementFile::displacement_frame`]);
//! [`MeasurementFile::to_base_frame`] turns them into the base frame ([`crate::observation::frames`]).
//!
//! [`Reader`] reads a file of any size from a [`BufRead`] chunk by chunk (`Reader::next_chunk`):
//! the text is never whole, and the lines of a chunk are parsed in parallel (pieces of
//! `PIECE_BYTES` at line boundaries, results in file order: the same whatever the number of
//! threads). [`parse`] is the reader over a `&str`.

mod columns;
pub mod plain;

pub use columns::Layout;

use crate::common::error::ColumnProblem;
use crate::observation::deflection::Frame;
use crate::observation::frames::{self, DisplacementFrame};
use crate::observation::Measurement;
use crate::{Error, Result, Setup};
use columns::{expected_header, problem};
use rayon::prelude::*;
use std::collections::hash_map::{Entry, HashMap};
use std::hash::{BuildHasherDefault, Hasher};
use std::io::BufRead;

/// Bytes of text parsed by one task: a chunk's text is cut into pieces of about this size, each
/// ending at a line end, parsed in parallel.
pub(crate) const PIECE_BYTES: usize = 1 << 19;

/// Pieces per chunk ([`Reader::next_chunk`]): a chunk holds about 4 MiB of text.
const PIECES: usize = 4;

/// The measurements of a file and where each came from.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasurementFile {
    /// One per row, SI units, point 0-based, in the file's frames.
    pub measurements: Vec<Measurement>,
    /// The posture labels; `labels[m.posture]` is the label of measurement `m`.
    pub labels: Vec<String>,
    /// The line of each measurement in the text (1-based).
    pub lines: Vec<u64>,
    /// The frame of the wrench columns.
    pub wrench_frame: Frame,
    /// The frame of the displacement columns.
    pub displacement_frame: DisplacementFrame,
    /// The header and its columns, to name columns in errors.
    pub layout: Layout,
}

/// Parses the text of a measurement file (see the module docs): a [`Reader`] over the text, its
/// chunks collected. A label is stored once however many rows carry it.
///
/// # Errors
/// [`Error::Column`] naming the line, the column and the [`ColumnProblem`]: an empty file, no rows,
/// an unknown (with a suggestion), repeated, missing or conflicting column, a row with the wrong
/// number of fields, a field that is not a finite number, an empty label or a measuring point that
/// is not 1, 2, ...
///
/// # Examples
/// The FANUC R-2000iC/165F data of the repository, turned into the base frame of its setup:
/// ```
/// use stiffid_core::io::measurements;
/// let text = include_str!(concat!(
///     env!("CARGO_MANIFEST_DIR"),
///     "/../../examples/data/fanuc-r2000ic-165f/measurements.csv"
/// ));
/// let mut file = measurements::parse(text)?;
/// assert_eq!((file.measurements.len(), file.labels.len()), (43, 43));
/// file.to_base_frame(&stiffid_core::setup::builtin("fanuc-r2000ic-165f")?)?;
/// # Ok::<(), stiffid_core::Error>(())
/// ```
pub fn parse(text: &str) -> Result<MeasurementFile> {
    let mut reader = Reader::new(text.as_bytes())?;
    let (mut measurements, mut lines) = (Vec::new(), Vec::new());
    while let Some(chunk) = reader.next_chunk()? {
        measurements.extend(chunk.measurements);
        lines.extend(chunk.lines);
    }
    let layout = reader.layout().clone();
    Ok(MeasurementFile {
        measurements,
        labels: reader.into_labels().iter().map(str::to_string).collect(),
        lines,
        wrench_frame: layout.wrench_frame(),
        displacement_frame: layout.displacement_frame(),
        layout,
    })
}

impl MeasurementFile {
    /// Turns the measurements into the robot base frame, in place: wrenches rotated with each
    /// posture's flange orientation, displacements with the setup's tracker transform
    /// ([`frames::file_to_base`]); afterwards both frames are [`Frame::Base`] and
    /// [`DisplacementFrame::Base`].
    ///
    /// # Errors
    /// Those of [`frames::file_to_base`].
    pub fn to_base_frame(&mut self, setup: &Setup) -> Result<()> {
        frames::file_to_base(
            setup,
            &mut self.measurements,
            &mut self.wrench_frame,
            &mut self.displacement_frame,
        )
    }

    /// Turns an [`Error::Measurement`] about one of these measurements into an [`Error::Column`]
    /// naming its line and column ([`Layout::explain`]); other errors pass through.
    pub fn explain(&self, error: Error) -> Error {
        self.layout
            .explain(error, |n| self.lines.get(n.wrapping_sub(1)).copied())
    }
}

/// Some consecutive rows of a measurement file (`Reader::next_chunk`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Chunk {
    /// One per row, SI units, point 0-based, in the file's frames; postures numbered over the
    /// whole file in order of first appearance.
    pub measurements: Vec<Measurement>,
    /// The line of each measurement (1-based).
    pub lines: Vec<u64>,
    /// The number of measurements in the chunks before this one.
    pub first: usize,
}

impl Chunk {
    /// The line of measurement `number` (1-based, counted over the whole file) if it is in this
    /// chunk: for [`Layout::explain`].
    pub fn line_of(&self, number: usize) -> Option<u64> {
        let i = number.checked_sub(self.first + 1)?;
        self.lines.get(i).copied()
    }
}

/// Reads a measurement file chunk by chunk from any [`BufRead`] (module docs): the memory is that
/// of one chunk (about `PIECES x PIECE_BYTES` of text and its rows) and of the posture labels.
pub struct Reader<R> {
    text: Text<R>,
    layout: Layout,
    /// The line of the header.
    header_line: u64,
    numbering: Numbering,
    /// The rows of the pieces of text being read (buffers kept from chunk to chunk).
    parsed: Vec<Parsed>,
}

/// The source, the lines read so far and the pieces of text of the chunk being read, each with
/// the line it starts at (buffers kept from chunk to chunk): what reading and parsing needs.
struct Text<R> {
    source: R,
    line: u64,
    pieces: Vec<(u64, Vec<u8>)>,
}

/// The measurements collected into chunks so far and their posture labels.
#[derive(Default)]
struct Numbering {
    rows: usize,
    labels: Labels,
}

impl<R: BufRead> Reader<R> {
    /// Reads the header (the first line that is neither empty nor a `#` comment).
    ///
    /// # Errors
    /// As [`parse`] for the header: an empty file, unknown, repeated, missing or conflicting
    /// columns; [`ColumnProblem::Unreadable`] when the source fails.
    pub fn new(mut source: R) -> Result<Self> {
        let mut text = Vec::new();
        let mut line = 0;
        loop {
            text.clear();
            let read = source
                .read_until(b'\n', &mut text)
                .map_err(|e| unreadable(line + 1, &e.to_string()))?;
            line += 1;
            let blank = text.iter().all(|b| matches!(b, b'\n' | b'\r'));
            if read == 0 || !(blank || text.first() == Some(&b'#')) {
                break;
            }
        }
        let header: Vec<String> = csv::ReaderBuilder::new()
            .trim(csv::Trim::Headers)
            .flexible(true)
            .from_reader(text.as_slice())
            .headers()
            .map_err(|e| unreadable(line, &e.to_string()))?
            .iter()
            .map(str::to_string)
            .collect();
        if header.iter().all(|h| h.is_empty()) {
            return Err(problem(
                line,
                None,
                ColumnProblem::Empty {
                    expected: expected_header(),
                },
            ));
        }
        Ok(Self {
            text: Text {
                source,
                line,
                pieces: Vec::new(),
            },
            layout: Layout::new(header, line)?,
            header_line: line,
            numbering: Numbering::default(),
            parsed: Vec::new(),
        })
    }

    /// The header and its columns.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The next rows, `None` at the end of the source.
    ///
    /// # Errors
    /// As [`parse`], for the first bad row of the chunk (in file order); [`ColumnProblem::NoRows`]
    /// at the end of a source without rows; [`ColumnProblem::Unreadable`] when the source fails.
    pub(crate) fn next_chunk(&mut self) -> Result<Option<Chunk>> {
        let mut chunk = Chunk::default();
        Ok(self.read_chunk(&mut chunk)?.then_some(chunk))
    }

    /// Reads the next rows into `chunk` (its buffers reused); `false` at the end of the source.
    fn read_chunk(&mut self, chunk: &mut Chunk) -> Result<bool> {
        loop {
            let pieces = self.text.parse(&self.layout, &mut self.parsed)?;
            self.numbering.collect(&mut self.parsed[..pieces], chunk)?;
            match (chunk.measurements.is_empty(), pieces == 0) {
                (true, true) => return self.end().map(|()| false),
                // Only comments and blank lines: read on.
                (true, false) => {}
                (false, _) => return Ok(true),
            }
        }
    }

    /// At the end of the source: [`ColumnProblem::NoRows`] if there were no rows.
    fn end(&self) -> Result<()> {
        match self.numbering.rows {
            0 => Err(problem(
                self.header_line,
                None,
                ColumnProblem::NoRows {
                    what: "measurement row",
                },
            )),
            _ => Ok(()),
        }
    }

    /// The posture labels of the rows read so far; [`Labels::get`]`(m.posture)` is the label of
    /// measurement `m`.
    pub fn into_labels(self) -> Labels {
        self.numbering.labels.into_list()
    }
}

impl<R: BufRead + Send> Reader<R> {
    /// Calls `each` with every chunk (`Reader::next_chunk`), in file order; the next chunk's
    /// text is read and parsed while the current one's postures are numbered and `each` works on
    /// it (in parallel, with rayon), so at most two chunks are held.
    ///
    /// # Errors
    /// The first of `each`'s, then those of `Reader::next_chunk`, in file order: an error in a
    /// chunk comes before a reading error in the next one.
    pub fn for_each_chunk(
        &mut self,
        mut each: impl FnMut(&mut Chunk) -> Result<()> + Send,
    ) -> Result<()> {
        let (mut chunk, mut ahead) = (Chunk::default(), Vec::new());
        let mut pieces = self.text.parse(&self.layout, &mut self.parsed)?;
        while pieces > 0 {
            let Self {
                text,
                layout,
                numbering,
                parsed,
                ..
            } = self;
            let (read, done) = rayon::join(
                || text.parse(layout, &mut ahead),
                || {
                    numbering.collect(&mut parsed[..pieces], &mut chunk)?;
                    match chunk.measurements.is_empty() {
                        true => Ok(()),
                        false => each(&mut chunk),
                    }
                },
            );
            done?;
            pieces = read?;
            std::mem::swap(&mut self.parsed, &mut ahead);
        }
        self.end()
    }
}

impl<R: BufRead> Text<R> {
    /// Reads up to [`PIECES`] pieces of text and parses them in parallel into `parsed`; returns
    /// how many (none at the end of the source).
    fn parse(&mut self, layout: &Layout, parsed: &mut Vec<Parsed>) -> Result<usize> {
        let n = self.read_pieces()?;
        parsed.resize_with(n.max(parsed.len()), Parsed::default);
        self.pieces[..n]
            .par_iter()
            .zip(parsed[..n].par_iter_mut())
            .for_each(|((line, text), parsed)| parsed.fill(layout, text, *line));
        Ok(n)
    }

    /// Reads up to [`PIECES`] pieces of text into `self.pieces`, each with the line it starts
    /// at; returns how many (none at the end).
    fn read_pieces(&mut self) -> Result<usize> {
        for n in 0..PIECES {
            if self.pieces.len() == n {
                self.pieces.push((0, Vec::with_capacity(PIECE_BYTES + 256)));
            }
            let (start, piece) = &mut self.pieces[n];
            piece.clear();
            let line = self.line;
            read_piece(&mut self.source, piece)
                .map_err(|e| unreadable(line + 1, &e.to_string()))?;
            if piece.is_empty() {
                return Ok(n);
            }
            self.line += piece.iter().filter(|b| **b == b'\n').count() as u64;
            *start = line + 1;
        }
        Ok(PIECES)
    }
}

impl Numbering {
    /// The rows of some parsed pieces, in file order, into `chunk` (cleared first), postures
    /// numbered in order of first appearance; the first error of a piece.
    fn collect(&mut self, parsed: &mut [Parsed], chunk: &mut Chunk) -> Result<()> {
        chunk.measurements.clear();
        chunk.lines.clear();
        chunk.first = self.rows;
        for piece in parsed {
            let mut start = 0;
            for (mut measurement, line, end) in piece.rows.drain(..) {
                measurement.posture = self.labels.number(&piece.labels[start..end]);
                start = end;
                chunk.measurements.push(measurement);
                chunk.lines.push(line);
            }
            if let Some(e) = piece.error.take() {
                return Err(e);
            }
        }
        self.rows += chunk.measurements.len();
        Ok(())
    }
}

/// Appends about [`PIECE_BYTES`] of `source` to `piece`, up to and including a line end (or the
/// end of the source).
fn read_piece(source: &mut impl BufRead, piece: &mut Vec<u8>) -> std::io::Result<()> {
    loop {
        let available = source.fill_buf()?;
        if available.is_empty() {
            return Ok(());
        }
        let take = available.len().min(PIECE_BYTES - piece.len());
        piece.extend_from_slice(&available[..take]);
        source.consume(take);
        if piece.len() >= PIECE_BYTES {
            source.read_until(b'\n', piece)?;
            return Ok(());
        }
    }
}

/// The rows of one piece of text, parsed (postures not numbered yet), until its first error.
#[derive(Default)]
pub struct Parsed {
    /// The measurement, its line and the end of its label in `labels`.
    pub rows: Vec<(Measurement, u64, usize)>,
    /// The rows' labels, one after the other.
    pub labels: String,
    /// The first error, which ends the rows.
    pub error: Option<Error>,
}

impl Parsed {
    /// Parses `text`, whose first line is line `first` of the file, into `self` (its buffers
    /// reused): split directly when its lines are plain ([`plain`]), else by the `csv` crate.
    pub fn fill(&mut self, layout: &Layout, text: &[u8], first: u64) {
        if !plain::parse(layout, text, first, self) {
            *self = Self::by_csv(layout, text, first);
        }
    }

    /// Parses `text` with the `csv` crate (quoted fields, errors).
    pub fn by_csv(layout: &Layout, text: &[u8], first: u64) -> Self {
        let mut parsed = Self {
            rows: Vec::with_capacity(text.len() / 64),
            labels: String::new(),
            error: None,
        };
        // Comment lines are dropped here, not by `csv` (whose line count drifts over many of
        // them); `kept[i]` is the line in `text` (1-based) of line i + 1 of what is parsed.
        let filtered = without_comments(text);
        let (body, kept) = match &filtered {
            Some((body, kept)) => (body.as_slice(), Some(kept)),
            None => (text, None),
        };
        let at = |csv_line: u64| {
            let line = kept.map_or(Some(csv_line), |k| k.get(csv_line as usize - 1).copied());
            first - 1 + line.unwrap_or_else(|| text.split(|b| *b == b'\n').count() as u64)
        };
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .from_reader(body);
        let mut record = csv::StringRecord::new();
        let mut error = None;
        let mut lines = super::LineCount::new(body);
        loop {
            let line = at(lines.at(reader.position().byte()));
            let row = match reader.read_record(&mut record) {
                Ok(false) => break,
                Ok(true) => {
                    let line = record.position().map_or(line, |p| at(lines.at(p.byte())));
                    parsed.row(layout, &record, line).map_err(|e| (line, e))
                }
                Err(e) => Err((line, unreadable(line, &super::csv_message(&e)))),
            };
            if let Err(e) = row {
                error = Some(e);
                break;
            }
        }
        // A commented row before the first bad row (or with none) is the first error.
        let commented = commented_row(text, layout.fields(), first);
        if let Some((line, e)) = commented.filter(|c| error.as_ref().is_none_or(|e| c.0 < e.0)) {
            let after = parsed.rows.iter().position(|r| r.1 > line);
            parsed.rows.truncate(after.unwrap_or(parsed.rows.len()));
            parsed
                .labels
                .truncate(parsed.rows.last().map_or(0, |r| r.2));
            error = Some((line, e));
        }
        parsed.error = error.map(|e| e.1);
        parsed
    }

    fn row(&mut self, layout: &Layout, record: &csv::StringRecord, line: u64) -> Result<()> {
        if record.len() != layout.fields() {
            return Err(problem(
                line,
                None,
                ColumnProblem::FieldCount {
                    expected: layout.fields(),
                    got: record.len(),
                },
            ));
        }
        let posture = layout.columns.posture;
        let label = record[posture].trim();
        if label.is_empty() {
            return Err(layout.at(line, posture, ColumnProblem::EmptyLabel));
        }
        if label.contains(['\n', '\r']) {
            let message = "a quoted label spans lines: a field may not hold a line break".into();
            return Err(layout.at(line, posture, ColumnProblem::Unreadable { message }));
        }
        let measurement = layout.measurement(|i| &record[i], 0, |c, p| layout.at(line, c, p))?;
        self.labels.push_str(label);
        self.rows.push((measurement, line, self.labels.len()));
        Ok(())
    }
}

/// Posture labels numbered in order of first appearance, stored one after the other (no
/// allocation per label), with an index from a 64-bit hash of a label to its number.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Labels {
    text: String,
    /// The end of each label in `text`.
    ends: Vec<usize>,
    /// The number of the first label with each 32-bit hash ([`fx_hash`]; 8 bytes per entry).
    index: HashMap<u32, u32, BuildHasherDefault<Prehashed>>,
    /// Labels whose hash an earlier label has (compared in full), and those numbered beyond
    /// `u32::MAX`.
    collided: HashMap<Box<str>, usize>,
    /// The previous row's number (rows of one posture usually follow each other).
    last: Option<usize>,
}

impl Labels {
    /// The number of labels.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// Label `i` (numbered from 0).
    ///
    /// # Panics
    /// If `i >= len()`.
    pub fn get(&self, i: usize) -> &str {
        &self.text[span(&self.ends, i)]
    }

    /// The labels, in order of their numbers.
    pub fn iter(&self) -> impl Iterator<Item = &str> {
        (0..self.len()).map(|i| self.get(i))
    }

    /// Frees the index: the labels can be read, no longer numbered.
    fn into_list(mut self) -> Self {
        self.index = HashMap::default();
        self.collided = HashMap::new();
        self.text.shrink_to_fit();
        self.ends.shrink_to_fit();
        self
    }

    /// The number of `label`, a new one if it was not seen before.
    fn number(&mut self, label: &str) -> usize {
        if let Some(last) = self.last.filter(|l| self.get(*l) == label) {
            return last;
        }
        let next = self.len();
        let (text, ends) = (&self.text, &self.ends);
        let same = |i: usize| text[span(ends, i)] == *label;
        let n = match self.index.entry(fx_hash(label.as_bytes()) as u32) {
            Entry::Vacant(e) if next <= u32::MAX as usize => {
                e.insert(next as u32);
                next
            }
            Entry::Occupied(e) if same(*e.get() as usize) => *e.get() as usize,
            _ => *self.collided.entry(label.into()).or_insert(next),
        };
        if n == next {
            self.text.push_str(label);
            self.ends.push(self.text.len());
        }
        self.last = Some(n);
        n
    }
}

/// Where label `i` is in the text of [`Labels`].
fn span(ends: &[usize], i: usize) -> std::ops::Range<usize> {
    i.checked_sub(1).map_or(0, |p| ends[p])..ends[i]
}

/// Labels numbered in order of first appearance (a repeated one keeps its first number).
impl<S: AsRef<str>> FromIterator<S> for Labels {
    fn from_iter<I: IntoIterator<Item = S>>(labels: I) -> Self {
        let mut all = Labels::default();
        for label in labels {
            all.number(label.as_ref());
        }
        all.into_list()
    }
}

/// A hasher for keys that are hashes already ([`fx_hash`]): passes a `u32` through.
#[derive(Default)]
struct Prehashed(u64);

impl Hasher for Prehashed {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        self.0 = fx_hash(bytes);
    }

    fn write_u32(&mut self, n: u32) {
        // Both halves: the table takes its bucket from the low bits, its tag from the top ones.
        self.0 = u64::from(n) << 32 | u64::from(n);
    }
}

/// The Fx hash (rustc's, Firefox's) of some bytes, 8 at a time, finished by MurmurHash3's
/// `fmix64` (so that the low bits, which pick the bucket, depend on every byte): fast for short
/// keys; collisions are resolved by comparing labels ([`Labels`]).
fn fx_hash(bytes: &[u8]) -> u64 {
    const K: u64 = 0x517c_c1b7_2722_0a95;
    let mut h = bytes.len() as u64;
    for word in bytes.chunks(8) {
        let mut w = [0u8; 8];
        w[..word.len()].copy_from_slice(word);
        h = (h.rotate_left(5) ^ u64::from_le_bytes(w)).wrapping_mul(K);
    }
    h ^= h >> 33;
    h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
    h ^= h >> 33;
    h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    h ^ (h >> 33)
}

fn unreadable(line: u64, message: &str) -> Error {
    problem(
        line,
        None,
        ColumnProblem::Unreadable {
            message: message.into(),
        },
    )
}

/// `text` without its comment lines (`#` first) and the line (1-based) of each line kept; `None`
/// when it has none.
fn without_comments(text: &[u8]) -> Option<(Vec<u8>, Vec<u64>)> {
    if !(text.first() == Some(&b'#') || text.windows(2).any(|w| w == b"\n#")) {
        return None;
    }
    let (mut body, mut kept) = (Vec::with_capacity(text.len()), Vec::new());
    for (i, line) in text.split_inclusive(|b| *b == b'\n').enumerate() {
        if line.first() != Some(&b'#') {
            body.extend_from_slice(line);
            kept.push(i as u64 + 1);
        }
    }
    Some((body, kept))
}

/// The first comment line (`#` first) of `text` (whose first line is line `first`) that holds as
/// many fields as the header: a measurement row whose posture label starts with `#` would
/// otherwise be dropped without a word.
fn commented_row(text: &[u8], fields: usize, first: u64) -> Option<(u64, Error)> {
    let (i, _) = text.split(|b| *b == b'\n').enumerate().find(|(_, l)| {
        let l = l.trim_ascii_start();
        l.first() == Some(&b'#') && l.split(|b| *b == b',').count() == fields && fields > 1
    })?;
    let line = first + i as u64;
    let message = format!(
        "a comment line ('#' first) with the {fields} fields of a measurement row: a posture label may not start with '#'"
    );
    Some((line, unreadable(line, &message)))
}
