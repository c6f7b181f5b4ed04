//! The points of the compensate document as the job's sink receives them. A path of any length
//! in bounded memory: each point's values kept outside memory as they come ([`Points`]), then
//! the JSON document written with its `points` read back one by one ([`Document::write_json`]);
//! the front end gives the storage (a temporary file) and the output, and no JSON text is
//! spliced. Or the document's rows kept in memory ([`Rows`]), for a front end that returns the
//! document whole (Python's). Either way each point of a chunk is made its values by
//! [`chunk_values`].

use crate::app::compensate::document::{header, values, Document, Row};
use serde::ser::{Error as _, SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};
use serde_json::{Map, Value};
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::io::{Read, Write};
use stiffid_machining::compensate::{Compensated, PathPoint};
use stiffid_machining::dynamics::Dynamics;

/// The values of each point of a chunk the job's sink receives ([`crate::app::compensate::run`]:
/// the chunk's first point's index `first`, 0-based, its points, results and dynamics), in order:
/// one per column of [`header`] ([`values`]), what a [`Points`] or [`Rows`] keeps and the CSV
/// writes.
pub fn chunk_values<'a>(
    first: usize,
    points: &'a [PathPoint],
    results: &'a [Compensated],
    dynamics: &'a [Dynamics],
) -> impl Iterator<Item = Vec<Option<f64>>> + 'a {
    (points.iter().zip(results).zip(dynamics).enumerate())
        .map(move |(k, ((p, r), d))| values(first + k, p.line, r, d))
}

/// The points of a compensate document as they come, written to `W`: each point's values (one per
/// column of [`header`]) as 8 little-endian bytes each, an empty cell as NaN (which JSON writes as
/// `null`, as it writes an empty cell).
pub struct Points<W: Write> {
    out: W,
    columns: usize,
}

impl<W: Write> Points<W> {
    /// Points written to `out`.
    pub fn new(out: W) -> Self {
        Self {
            out,
            columns: header().len(),
        }
    }

    /// Writes one point's values ([`crate::app::compensate::document::values`]).
    ///
    /// # Errors
    /// Those of writing to `W`; `InvalidInput` when `values` is not one value per column.
    pub fn push(&mut self, values: &[Option<f64>]) -> std::io::Result<()> {
        if values.len() != self.columns {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!("{} values for {} columns", values.len(), self.columns),
            ));
        }
        let mut bytes = Vec::with_capacity(8 * values.len());
        for v in values {
            bytes.extend_from_slice(&v.unwrap_or(f64::NAN).to_le_bytes());
        }
        self.out.write_all(&bytes)
    }

    /// The storage written to.
    pub fn into_inner(self) -> W {
        self.out
    }
}

/// The rows of a compensate document's `points` as they come, kept in memory: each point's
/// values made the row the document holds (one value per column of [`header`], `null` for an
/// empty cell), as [`Document::write_json`] writes what a [`Points`] stored.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rows(Vec<Row>);

impl Rows {
    /// Adds one point's values ([`crate::app::compensate::document::values`]).
    pub fn push(&mut self, values: &[Option<f64>]) {
        self.0.push(Row::new(values));
    }

    /// The rows, in the order pushed: the document's `points`.
    pub fn into_points(self) -> Vec<Row> {
        self.0
    }
}

impl Document<'_> {
    /// Writes the document to `out` as pretty JSON with a final line break, `kind` first and the
    /// other keys in alphabetical order (as [`serde_json::Value`] orders them), its `points` (empty in `self`) read one by
    /// one from `points`: what a [`Points`] wrote. The same bytes as the document holding those
    /// points, written whole.
    ///
    /// # Errors
    /// Those of writing to `out` or reading `points`; `points` that end inside a point.
    pub fn write_json<R: Read, O: Write>(&self, points: R, mut out: O) -> serde_json::Result<()> {
        let Value::Object(document) = serde_json::to_value(self)? else {
            return Err(serde_json::Error::custom("the document is not an object"));
        };
        let streamed = Streamed {
            document: &document,
            points: RefCell::new(points),
            columns: header(),
        };
        serde_json::to_writer_pretty(&mut out, &streamed)?;
        out.write_all(b"\n").map_err(serde_json::Error::io)
    }
}

/// The document's keys with `points` read from `R`.
struct Streamed<'a, R> {
    document: &'a Map<String, Value>,
    points: RefCell<R>,
    columns: Vec<String>,
}

impl<R: Read> Serialize for Streamed<'_, R> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.document.len()))?;
        if let Some(kind) = self.document.get("kind") {
            map.serialize_entry("kind", kind)?;
        }
        for (key, value) in self.document {
            match key.as_str() {
                "kind" => {}
                "points" => map.serialize_entry(key, &Stored(self))?,
                _ => map.serialize_entry(key, value)?,
            }
        }
        map.end()
    }
}

/// The `points` array, read point by point.
struct Stored<'s, 'a, R>(&'s Streamed<'a, R>);

impl<R: Read> Serialize for Stored<'_, '_, R> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let columns = &self.0.columns;
        let mut reader = self.0.points.borrow_mut();
        let mut seq = serializer.serialize_seq(None)?;
        let mut bytes = vec![0u8; 8 * columns.len()];
        while read_point(&mut *reader, &mut bytes).map_err(S::Error::custom)? {
            let row: BTreeMap<&str, Option<f64>> = columns
                .iter()
                .zip(bytes.chunks_exact(8))
                .map(|(c, b)| {
                    let v = f64::from_le_bytes(b.try_into().unwrap_or([0; 8]));
                    (c.as_str(), (!v.is_nan()).then_some(v))
                })
                .collect();
            seq.serialize_element(&row)?;
        }
        seq.end()
    }
}

/// Fills `bytes` with the next point: `false` at the end of the points.
fn read_point(reader: &mut impl Read, bytes: &mut [u8]) -> std::io::Result<bool> {
    let mut filled = 0;
    while filled < bytes.len() {
        match reader.read(&mut bytes[filled..]) {
            Ok(0) if filled == 0 => return Ok(false),
            Ok(0) => {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::UnexpectedEof,
                    "the points end inside a point",
                ))
            }
            Ok(n) => filled += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(true)
}
