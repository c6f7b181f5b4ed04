//! Where each quantity sits in a measurement file's rows: the header's columns, and one row turned
//! into a [`Measurement`].

use crate::common::error::{ColumnProblem, MeasurementField};
use crate::common::limits;
use crate::observation::deflection::Frame;
use crate::observation::frames::DisplacementFrame;
use crate::observation::Measurement;
use crate::{Error, Result};
use nalgebra::{Vector3, Vector6};

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

pub(super) fn expected_header() -> String {
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
pub(super) struct Columns {
    pub(super) posture: usize,
    point: usize,
    q: [usize; 6],
    external: crate::io::external::Columns,
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
            .ok_or_else(|| crate::io::missing(self.line, name))
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
    pub(super) fn new(names: &[String], line: u64) -> Result<Self> {
        crate::io::known_names(names, line, known(), expected_columns)?;
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
        let external = crate::io::external::Columns::find(names, line)?;
        Ok(Self {
            posture,
            point,
            q,
            external,
            force,
            moment,
            displacement,
            wrench_frame,
            displacement_frame,
        })
    }

    /// The measurement of one row, whose field `i` is `field(i)`; `error(column, problem)`
    /// places a problem in the row.
    /// Every number is finite; axis angles lie within [`limits::ANGLE_DEG`] and positions within
    /// [`limits::LENGTH_MM`] (a position of `1e15` mm, say, would leave no digit of the
    /// displacement: a unit slip).
    fn measurement<'a>(
        &self,
        header: &[String],
        field: impl Fn(usize) -> &'a str,
        posture: usize,
        error: impl Fn(usize, ColumnProblem) -> Error,
    ) -> Result<Measurement> {
        let within = |i: usize, range: &limits::Range| -> Result<f64> {
            let field = trim(field(i));
            let v = field
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    error(
                        i,
                        ColumnProblem::NotANumber {
                            value: limits::short(field),
                        },
                    )
                })?;
            match range.contains(v) {
                true => Ok(v),
                false => Err(error(i, range.outside(&header[i], v))),
            }
        };
        let vector3 = |c: [usize; 3], range: &limits::Range| -> Result<Vector3<f64>> {
            Ok(Vector3::new(
                within(c[0], range)?,
                within(c[1], range)?,
                within(c[2], range)?,
            ))
        };
        let point_field = trim(field(self.point));
        let point = point_field
            .parse::<usize>()
            .ok()
            .filter(|p| *p >= 1)
            .ok_or_else(|| {
                error(
                    self.point,
                    ColumnProblem::NotAPoint {
                        value: limits::short(point_field),
                    },
                )
            })?;
        let mut q = Vector6::zeros();
        for (a, &c) in self.q.iter().enumerate() {
            q[a] = within(c, &limits::ANGLE_DEG)?.to_radians();
        }
        // Forces, moments and displacements have tighter limits, checked with the measurement
        // ([`crate::observation::Measurement`]); any finite number passes here.
        let any = &limits::Range::new(f64::MIN, f64::MAX, "");
        let force = vector3(self.force, any)?;
        let moment = self
            .moment
            .map_or(Ok(Vector3::zeros()), |m| vector3(m, any))?;
        let length = &limits::LENGTH_MM;
        let displacement_mm = match self.displacement {
            Displacement::Relative(d) => vector3(d, any)?,
            Displacement::Positions(l, u) => vector3(l, length)? - vector3(u, length)?,
        };
        let e = self.external.values(&field, &error)?;
        Ok(Measurement {
            posture,
            point: point - 1,
            q,
            e,
            wrench: Vector6::new(force.x, force.y, force.z, moment.x, moment.y, moment.z),
            displacement: displacement_mm * 1e-3,
        })
    }
}

/// `field.trim()`, without its search when the field starts and ends with ASCII that is not
/// whitespace (the usual number).
fn trim(field: &str) -> &str {
    let visible = |b: Option<&u8>| b.is_some_and(|b| b.is_ascii_graphic());
    match visible(field.as_bytes().first()) && visible(field.as_bytes().last()) {
        true => field,
        false => field.trim(),
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
        .chain(crate::io::external::NAMES)
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

/// A file's header and where each quantity sits in its rows: what names a row's columns in errors.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    header: Vec<String>,
    pub(super) columns: Columns,
}

impl Layout {
    /// The layout of `header`, read at `line`.
    pub fn new(header: Vec<String>, line: u64) -> Result<Self> {
        let columns = Columns::new(&header, line)?;
        Ok(Self { header, columns })
    }

    /// The measurement of one row, whose field `i` is `field(i)`, numbered `posture`;
    /// `error(column, problem)` places a problem in the row.
    pub(super) fn measurement<'a>(
        &self,
        field: impl Fn(usize) -> &'a str,
        posture: usize,
        error: impl Fn(usize, ColumnProblem) -> Error,
    ) -> Result<Measurement> {
        self.columns
            .measurement(&self.header, field, posture, error)
    }

    /// The number of fields of a row.
    pub(super) fn fields(&self) -> usize {
        self.header.len()
    }

    /// The frame of the wrench columns.
    pub fn wrench_frame(&self) -> Frame {
        self.columns.wrench_frame
    }

    /// The frame of the displacement columns.
    pub fn displacement_frame(&self) -> DisplacementFrame {
        self.columns.displacement_frame
    }

    /// The error at `line`, 0-based `column`.
    pub(super) fn at(&self, line: u64, column: usize, problem: ColumnProblem) -> Error {
        Error::Column {
            line,
            column: Some(column + 1),
            name: self.header[column].clone(),
            problem,
        }
    }

    /// Whether the file has moment columns (else the moments are zero).
    pub fn has_moments(&self) -> bool {
        self.columns.moment.is_some()
    }

    /// The names of the force columns in the header, comma-separated.
    pub fn force_columns(&self) -> String {
        self.names(&self.columns.force)
    }

    /// The names of the displacement columns in the header, comma-separated.
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

    /// Turns an [`Error::Measurement`] about measurement `number` (1-based) into an
    /// [`Error::Column`] naming its line (`line_of(number)`, 0 if unknown) and column; other
    /// errors pass through.
    pub fn explain(&self, error: Error, line_of: impl Fn(usize) -> Option<u64>) -> Error {
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
            MeasurementField::External => c.external.first().unwrap_or(c.q[5]),
        };
        let line = line_of(number).unwrap_or(0);
        self.at(line, column, ColumnProblem::Measurement { message })
    }
}

/// The error of a column `problem` at `line` (and `column`, 1-based, where known).
pub(super) fn problem(line: u64, column: Option<usize>, problem: ColumnProblem) -> Error {
    Error::Column {
        line,
        column,
        name: String::new(),
        problem,
    }
}
