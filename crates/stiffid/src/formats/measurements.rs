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
//! Columns may come in any order; lines starting with `#` are comments. [`parse`] keeps the
//! quantities in the file's frames ([`MeasurementFile::wrench_frame`],
//! [`MeasurementFile::displacement_frame`]); [`MeasurementFile::to_base_frame`] turns them into the
//! base frame ([`crate::identify::frames`]).

use crate::deflection::Frame;
use crate::error::{ColumnProblem, MeasurementField};
use crate::identify::frames::{self, DisplacementFrame};
use crate::observation::Measurement;
use crate::{Error, Result, Setup};
use nalgebra::{Vector3, Vector6};
use std::collections::HashMap;

const POSTURE: &str = "posture";
const POINT: &str = "point";
const Q: [&str; 6] = ["q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg"];
const FORCE: [&str; 3] = ["fx_n", "fy_n", "fz_n"];
const FORCE_TOOL: [&str; 3] = ["fx_tool_n", "fy_tool_n", "fz_tool_n"];
const MOMENT: [&str; 3] = ["mx_nm", "my_nm", "mz_nm"];
const MOMENT_TOOL: [&str; 3] = ["mx_tool_nm", "my_tool_nm", "mz_tool_nm"];
const DISPLACEMENT: [&str; 3] = ["dx_mm", "dy_mm", "dz_mm"];
const DISPLACEMENT_TRACKER: [&str; 3] = ["dx_tracker_mm", "dy_tracker_mm", "dz_tracker_mm"];
const LOADED: [&str; 3] = ["x_loaded_mm", "y_loaded_mm", "z_loaded_mm"];
const UNLOADED: [&str; 3] = ["x_unloaded_mm", "y_unloaded_mm", "z_unloaded_mm"];
const LOADED_TRACKER: [&str; 3] = [
    "x_loaded_tracker_mm",
    "y_loaded_tracker_mm",
    "z_loaded_tracker_mm",
];
const UNLOADED_TRACKER: [&str; 3] = [
    "x_unloaded_tracker_mm",
    "y_unloaded_tracker_mm",
    "z_unloaded_tracker_mm",
];

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
    /// The header, to name columns in errors.
    header: Vec<String>,
    /// Where each quantity is in a row.
    columns: Columns,
}

/// Parses the text of a measurement file (see the module docs). Rows are parsed into one reused
/// record; a label is stored once however many rows carry it.
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
/// use stiffid::formats::measurements;
/// let text = include_str!(concat!(
///     env!("CARGO_MANIFEST_DIR"),
///     "/../../examples/data/fanuc-r2000ic-165f/measurements.csv"
/// ));
/// let mut file = measurements::parse(text)?;
/// assert_eq!((file.measurements.len(), file.labels.len()), (43, 43));
/// file.to_base_frame(&stiffid::setup::builtin("fanuc-r2000ic-165f")?)?;
/// # Ok::<(), stiffid::Error>(())
/// ```
pub fn parse(text: &str) -> Result<MeasurementFile> {
    let mut reader = csv::ReaderBuilder::new()
        // Fields are trimmed where they are read: cheaper than trimming whole records.
        .trim(csv::Trim::Headers)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header_record = reader.headers().map_err(|e| unreadable(1, &e))?.clone();
    let line_of_header = header_record.position().map_or(1, |p| p.line());
    let header: Vec<String> = header_record.iter().map(str::to_string).collect();
    if header.iter().all(|h| h.is_empty()) {
        return Err(problem(
            line_of_header,
            None,
            ColumnProblem::Empty {
                expected: expected_header(),
            },
        ));
    }
    let columns = Columns::new(&header, line_of_header)?;
    commented_rows(text, header.len())?;
    // At most one row per line: reserved once, no reallocation of a large vector.
    let rows = text.bytes().filter(|b| *b == b'\n').count() + 1;
    let mut file = MeasurementFile {
        measurements: Vec::with_capacity(rows),
        labels: Vec::new(),
        lines: Vec::with_capacity(rows),
        wrench_frame: columns.wrench_frame,
        displacement_frame: columns.displacement_frame,
        header,
        columns,
    };
    // Sized for a label per row (the worst case): no rehashing of a growing map.
    let mut labels = Labels {
        index: HashMap::with_capacity(rows),
        last: (String::new(), 0),
    };
    let mut record = csv::StringRecord::new();
    loop {
        let line = reader.position().line();
        match reader.read_record(&mut record) {
            Ok(false) => break,
            Ok(true) => {}
            Err(e) => return Err(unreadable(line, &e)),
        }
        let line = record.position().map_or(line, |p| p.line());
        file.push(&record, line, &mut labels)?;
    }
    if file.measurements.is_empty() {
        return Err(problem(
            line_of_header,
            None,
            ColumnProblem::NoRows {
                what: "measurement row",
            },
        ));
    }
    file.labels = vec![String::new(); labels.index.len()];
    for (label, i) in labels.index {
        file.labels[i] = label.into();
    }
    Ok(file)
}

impl MeasurementFile {
    fn push(&mut self, record: &csv::StringRecord, line: u64, labels: &mut Labels) -> Result<()> {
        if record.len() != self.header.len() {
            return Err(problem(
                line,
                None,
                ColumnProblem::FieldCount {
                    expected: self.header.len(),
                    got: record.len(),
                },
            ));
        }
        let label = record[self.columns.posture].trim();
        if label.is_empty() {
            return Err(self.at(line, self.columns.posture, ColumnProblem::EmptyLabel));
        }
        let posture = labels.number(label);
        let measurement = self
            .columns
            .measurement(record, posture, |c, p| self.at(line, c, p))?;
        self.measurements.push(measurement);
        self.lines.push(line);
        Ok(())
    }

    /// The error at `line`, 0-based `column`.
    fn at(&self, line: u64, column: usize, problem: ColumnProblem) -> Error {
        Error::Column {
            line,
            column: Some(column + 1),
            name: self.header[column].clone(),
            problem,
        }
    }

    /// Turns the measurements into the robot base frame, in place: wrenches rotated with each
    /// posture's flange orientation, displacements with the setup's tracker transform
    /// ([`frames::to_base`]); afterwards both frames are [`Frame::Base`] and
    /// [`DisplacementFrame::Base`].
    ///
    /// # Errors
    /// Those of [`frames::to_base`].
    pub fn to_base_frame(&mut self, setup: &Setup) -> Result<()> {
        frames::to_base(
            setup,
            &mut self.measurements,
            self.wrench_frame,
            self.displacement_frame,
        )?;
        self.wrench_frame = Frame::Base;
        self.displacement_frame = DisplacementFrame::Base;
        Ok(())
    }

    /// The names of the force columns in this file's header, comma-separated.
    pub fn force_columns(&self) -> String {
        self.names(&self.columns.force)
    }

    /// The names of the displacement columns in this file's header, comma-separated.
    pub fn displacement_columns(&self) -> String {
        match self.columns.displacement {
            Displacement::Relative(d) => self.names(&d),
            Displacement::Positions(l, u) => self.names(&[l, u].concat()),
        }
    }

    fn names(&self, columns: &[usize]) -> String {
        let names: Vec<&str> = columns.iter().map(|&c| self.header[c].as_str()).collect();
        names.join(",")
    }

    /// Turns an [`Error::Measurement`] about one of these measurements into an [`Error::Column`]
    /// naming its line and column; other errors pass through.
    pub fn explain(&self, error: Error) -> Error {
        let Error::Measurement {
            number,
            field,
            message,
        } = error
        else {
            return error;
        };
        let c = &self.columns;
        let column = match field {
            MeasurementField::Posture => c.posture,
            MeasurementField::Point => c.point,
            MeasurementField::Axis(a) => c.q[a.min(5)],
            MeasurementField::Force => c.force[0],
            MeasurementField::Moment => c.moment.map_or(c.force[0], |m| m[0]),
            MeasurementField::Displacement => match c.displacement {
                Displacement::Relative(d) => d[0],
                Displacement::Positions(l, _) => l[0],
            },
        };
        let line = self.lines.get(number.wrapping_sub(1)).copied().unwrap_or(0);
        self.at(line, column, ColumnProblem::Measurement { message })
    }
}

/// The posture labels seen so far and their numbers, in order of first appearance.
struct Labels {
    index: HashMap<Box<str>, usize>,
    /// The previous row's label and number (rows of one posture usually follow each other).
    last: (String, usize),
}

impl Labels {
    /// The number of `label`, a new one if it was not seen before (one hash per row whose
    /// label differs from the previous row's).
    fn number(&mut self, label: &str) -> usize {
        if self.last.0 != label {
            let next = self.index.len();
            self.last.1 = *self.index.entry(label.into()).or_insert(next);
            self.last.0.clear();
            self.last.0.push_str(label);
        }
        self.last.1
    }
}

fn problem(line: u64, column: Option<usize>, problem: ColumnProblem) -> Error {
    Error::Column {
        line,
        column,
        name: String::new(),
        problem,
    }
}

fn unreadable(line: u64, e: &csv::Error) -> Error {
    problem(
        line,
        None,
        ColumnProblem::Unreadable {
            message: e.to_string(),
        },
    )
}

/// Fails on a comment line (`#` first) that holds as many fields as the header: a measurement
/// row whose posture label starts with `#` would otherwise be dropped without a word.
fn commented_rows(text: &str, fields: usize) -> Result<()> {
    let row = text.lines().enumerate().find(|(_, l)| {
        l.trim_start().starts_with('#') && l.split(',').count() == fields && fields > 1
    });
    match row {
        None => Ok(()),
        Some((i, _)) => Err(problem(
            i as u64 + 1,
            None,
            ColumnProblem::Unreadable {
                message: format!(
                    "a comment line ('#' first) with the {fields} fields of a measurement row: a posture label may not start with '#'"
                ),
            },
        )),
    }
}

fn expected_header() -> String {
    let mut names = vec![POSTURE, POINT];
    names.extend(Q);
    names.extend(FORCE);
    names.extend(DISPLACEMENT);
    names.join(",")
}

fn expected_columns() -> String {
    format!(
        "{} (moments {} optional; {} and {} in the tool frame; {} in the tracker frame; or {} and {} instead of the d columns)",
        expected_header(),
        MOMENT.join(","),
        FORCE_TOOL.join(","),
        MOMENT_TOOL.join(","),
        DISPLACEMENT_TRACKER.join(","),
        LOADED.join(","),
        UNLOADED.join(",")
    )
}

/// Where each quantity sits in a row (0-based field indices).
#[derive(Debug, Clone, PartialEq)]
struct Columns {
    posture: usize,
    point: usize,
    q: [usize; 6],
    force: [usize; 3],
    moment: Option<[usize; 3]>,
    displacement: Displacement,
    wrench_frame: Frame,
    displacement_frame: DisplacementFrame,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Displacement {
    Relative([usize; 3]),
    Positions([usize; 3], [usize; 3]),
}

/// Finds columns in a header, with errors at the header's line.
struct Header<'a> {
    names: &'a [String],
    line: u64,
}

impl Header<'_> {
    fn find(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|h| h == name)
    }

    fn any(&self, names: &[&str]) -> bool {
        names.iter().any(|n| self.find(n).is_some())
    }

    fn need(&self, name: &str) -> Result<usize> {
        self.find(name)
            .ok_or_else(|| super::missing(self.line, name))
    }

    fn need3(&self, names: [&str; 3]) -> Result<[usize; 3]> {
        Ok([
            self.need(names[0])?,
            self.need(names[1])?,
            self.need(names[2])?,
        ])
    }

    /// The columns of one quantity given in one of two frames (`None` if neither is there).
    fn one_of<F: Copy>(&self, first: (&[&str], F), second: (&[&str], F)) -> Result<Option<F>> {
        match (self.any(first.0), self.any(second.0)) {
            (true, true) => Err(problem(
                self.line,
                None,
                ColumnProblem::Conflict {
                    first: first.0.join(","),
                    second: second.0.join(","),
                },
            )),
            (true, false) => Ok(Some(first.1)),
            (false, true) => Ok(Some(second.1)),
            (false, false) => Ok(None),
        }
    }
}

impl Columns {
    fn new(names: &[String], line: u64) -> Result<Self> {
        super::known_names(names, line, known(), expected_columns)?;
        let h = Header { names, line };
        let posture = h.need(POSTURE)?;
        let point = h.need(POINT)?;
        let mut q = [0; 6];
        for (a, name) in Q.iter().enumerate() {
            q[a] = h.need(name)?;
        }
        let wrench_frame = h
            .one_of((&FORCE, Frame::Base), (&FORCE_TOOL, Frame::Tool))?
            .unwrap_or(Frame::Base);
        let (force_names, moment_names) = match wrench_frame {
            Frame::Base => (FORCE, MOMENT),
            Frame::Tool => (FORCE_TOOL, MOMENT_TOOL),
        };
        let other_moment = match wrench_frame {
            Frame::Base => MOMENT_TOOL,
            Frame::Tool => MOMENT,
        };
        h.one_of((&force_names, ()), (&other_moment, ()))?;
        let force = h.need3(force_names)?;
        let moment = match h.any(&moment_names) {
            true => Some(h.need3(moment_names)?),
            false => None,
        };
        let (displacement, displacement_frame) = displacement(&h)?;
        Ok(Self {
            posture,
            point,
            q,
            force,
            moment,
            displacement,
            wrench_frame,
            displacement_frame,
        })
    }

    /// The measurement of one row; `error(column, problem)` places a problem in the row.
    fn measurement(
        &self,
        record: &csv::StringRecord,
        posture: usize,
        error: impl Fn(usize, ColumnProblem) -> Error,
    ) -> Result<Measurement> {
        let number = |i: usize| -> Result<f64> {
            let field = record[i].trim();
            field
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    error(
                        i,
                        ColumnProblem::NotANumber {
                            value: crate::limits::short(field),
                        },
                    )
                })
        };
        let vector3 = |c: [usize; 3]| -> Result<Vector3<f64>> {
            Ok(Vector3::new(number(c[0])?, number(c[1])?, number(c[2])?))
        };
        let point_field = record[self.point].trim();
        let point = point_field
            .parse::<usize>()
            .ok()
            .filter(|p| *p >= 1)
            .ok_or_else(|| {
                error(
                    self.point,
                    ColumnProblem::NotAPoint {
                        value: crate::limits::short(point_field),
                    },
                )
            })?;
        let mut q = Vector6::zeros();
        for (a, &c) in self.q.iter().enumerate() {
            q[a] = number(c)?.to_radians();
        }
        let force = vector3(self.force)?;
        let moment = self.moment.map_or(Ok(Vector3::zeros()), vector3)?;
        let displacement_mm = match self.displacement {
            Displacement::Relative(d) => vector3(d)?,
            Displacement::Positions(l, u) => vector3(l)? - vector3(u)?,
        };
        Ok(Measurement {
            posture,
            point: point - 1,
            q,
            wrench: Vector6::new(force.x, force.y, force.z, moment.x, moment.y, moment.z),
            displacement: displacement_mm * 1e-3,
        })
    }
}

/// The displacement columns and their frame.
fn displacement(h: &Header) -> Result<(Displacement, DisplacementFrame)> {
    use DisplacementFrame::{Base, Tracker};
    let relative = h.one_of((&DISPLACEMENT, Base), (&DISPLACEMENT_TRACKER, Tracker))?;
    let base_positions = [LOADED, UNLOADED].concat();
    let tracker_positions = [LOADED_TRACKER, UNLOADED_TRACKER].concat();
    let positions = h.one_of((&base_positions, Base), (&tracker_positions, Tracker))?;
    match (relative, positions) {
        (Some(_), Some(_)) => Err(problem(
            h.line,
            None,
            ColumnProblem::Conflict {
                first: DISPLACEMENT.join(","),
                second: "the loaded and unloaded positions".into(),
            },
        )),
        (None, Some(frame)) => {
            let (l, u) = match frame {
                Base => (LOADED, UNLOADED),
                Tracker => (LOADED_TRACKER, UNLOADED_TRACKER),
            };
            Ok((Displacement::Positions(h.need3(l)?, h.need3(u)?), frame))
        }
        (Some(Tracker), None) => Ok((
            Displacement::Relative(h.need3(DISPLACEMENT_TRACKER)?),
            Tracker,
        )),
        _ => Ok((Displacement::Relative(h.need3(DISPLACEMENT)?), Base)),
    }
}

fn known() -> impl Iterator<Item = &'static str> + Clone {
    [POSTURE, POINT]
        .into_iter()
        .chain(Q)
        .chain(FORCE)
        .chain(MOMENT)
        .chain(FORCE_TOOL)
        .chain(MOMENT_TOOL)
        .chain(DISPLACEMENT)
        .chain(DISPLACEMENT_TRACKER)
        .chain(LOADED)
        .chain(UNLOADED)
        .chain(LOADED_TRACKER)
        .chain(UNLOADED_TRACKER)
}
