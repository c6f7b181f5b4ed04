//! Raw tracker readings: CSV, one row per posture, measuring point and (optionally) load step, the
//! robot's axis angles and the laser tracker's reading of that measuring point, units in the
//! header.
//!
//! ```text
//! posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm
//! posture,point,q1_deg,...,q6_deg,load_step,fx_n,fy_n,fz_n,x_tracker_mm,y_tracker_mm,z_tracker_mm
//! ```
//! - `posture`: a label; rows of one posture share it and their axis angles.
//! - `point`: the measuring point, numbered from 1 as in the setup's `measuring_points_mm`; each
//!   point at most once per posture unless the file has load steps.
//! - `q1_deg..q6_deg`: axis angles, deg, within the robot's joint limits.
//! - External axes (a cell with a track or a positioner, [`crate::robot::external`]): one
//!   column per axis after the joint columns, named `e1_mm`, `e2_deg`, ... in the cell's order
//!   ([`crate::robot::ExternalAxes::column_names`]: mm for a linear axis, deg for a rotary
//!   one), each value within its axis's travel; required when the cell has external axes, a
//!   column of an axis the cell lacks refused.
//! - A reflector fixed in the cell: on the positioner's table (a point of the part, read at
//!   several positioner angles to calibrate the positioner's axes), or, in a cell without a
//!   positioner, on a fixed part or fixture (a fixed point of the cell, read once or at several
//!   postures' readings): `point` is `T1`, `T2`, ... (`T` and the reflector's number, from 1)
//!   instead of a measuring point's number; the row's axis angles are the arm's at the time (not
//!   used for the reflector), its positioner columns say where the table stood. Not in a file
//!   with load steps.
//! - `x_tracker_mm..z_tracker_mm`: the tracker's reading of the measuring point, tracker frame,
//!   mm, within [`crate::common::limits::LENGTH_MM`]; or `x_mm,y_mm,z_mm` in the robot base frame (a
//!   tracker already registered).
//! - Load steps (optional, for identification: `stiffid_identify::steps`): `load_step` (the step's number,
//!   an integer in `0..=1000`, 0 unloaded) or `load_n` (the nominal load, N, within
//!   `[0, 1e7]` N, 0 unloaded), with the wrench at the loading point
//!   `fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm]` in the base frame or `fx_tool_n,...[,mx_tool_nm,...]` in
//!   the tool (flange) frame (moments optional, zero when absent; forces and moments within
//!   [`crate::common::limits::WRENCH`]). Load and force columns come together.
//! - Directions (optional, a backlash term's): `dir1..dir6`, one posture's alike (`direction`).
//!
//! Columns may come in any order; lines starting with `#` are comments. At most
//! [`MAX_READINGS`] rows. `stiffid_metrology::register` turns the unloaded readings into the tracker's
//! transform, `stiffid_identify::steps` the loaded ones into displacements.

pub(crate) mod direction;
mod name;
pub use name::point_name;

use crate::io::external::{self, external_like};
use crate::robot::external::ExternalValues;

use crate::common::error::ColumnProblem;
use crate::common::limits::{self, short};
use crate::observation::deflection::Frame;
use crate::observation::frames::DisplacementFrame;
use crate::{Error, Result, Robot};
use nalgebra::{Vector3, Vector6};
use std::collections::HashMap;

/// Most rows a readings file may hold.
pub const MAX_READINGS: usize = 100_000;

/// Most reflectors fixed in the cell (`T1` ...) a readings file names.
pub(crate) const MAX_TABLE_REFLECTORS: usize = crate::common::limits::MAX_TABLE_REFLECTORS;

/// Largest load step number (`load_step`).
pub(crate) const MAX_LOAD_STEP: u32 = 1000;

const POSTURE: &str = "posture";
const POINT: &str = "point";
const Q: [&str; 6] = ["q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg"];
const TRACKER: [&str; 3] = ["x_tracker_mm", "y_tracker_mm", "z_tracker_mm"];
const BASE: [&str; 3] = ["x_mm", "y_mm", "z_mm"];
const LOAD_STEP: &str = "load_step";
const LOAD_N: &str = "load_n";
const FORCE: [&str; 3] = ["fx_n", "fy_n", "fz_n"];
const MOMENT: [&str; 3] = ["mx_nm", "my_nm", "mz_nm"];
const FORCE_TOOL: [&str; 3] = ["fx_tool_n", "fy_tool_n", "fz_tool_n"];
const MOMENT_TOOL: [&str; 3] = ["mx_tool_nm", "my_tool_nm", "mz_tool_nm"];

/// The load of a reading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Load {
    /// A load step's number (`load_step`), 0 unloaded.
    Step(u32),
    /// A nominal load (`load_n`), N, 0 unloaded.
    Newtons(f64),
}

impl Load {
    /// Whether this is the unloaded state (step 0, or 0 N).
    pub fn is_zero(self) -> bool {
        match self {
            Load::Step(s) => s == 0,
            Load::Newtons(n) => n == 0.0,
        }
    }

    /// The value that orders loads: the step number, or the load in N.
    pub fn level(self) -> f64 {
        match self {
            Load::Step(s) => f64::from(s),
            Load::Newtons(n) => n,
        }
    }
}

/// One row: a measuring point at a posture (under a load step), read by the tracker (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// The posture, 0-based in order of first appearance ([`Readings::labels`]).
    pub posture: usize,
    /// The measuring point, 0-based.
    pub point: usize,
    /// Axis angles, rad.
    pub q: Vector6<f64>,
    /// The external axes' values, SI (m, rad), the cell's order; empty without external axes.
    pub e: ExternalValues,
    /// Whether `point` is a reflector fixed in the cell (`T1`, `T2`, ...: on the positioner's
    /// table, or on a fixed part), 0-based, rather than a measuring point of the tool.
    pub table: bool,
    /// The reading of the measuring point, m, in [`Readings::frame`].
    pub position: Vector3<f64>,
    /// The load step; `None` when the file has no load columns.
    pub load: Option<Load>,
    /// The wrench `[f; m]` at the loading point, N and Nm, in [`Readings::wrench_frame`]; zero
    /// when the file has no force columns.
    pub wrench: Vector6<f64>,
    /// The sign of each joint's last motion before the reading (-1.0 or 1.0, `dir1..dir6`);
    /// `None` when the file has no direction columns.
    pub direction: Option<Vector6<f64>>,
}

impl Reading {
    /// Whether the reading is unloaded: no load columns, or load 0.
    pub fn unloaded(&self) -> bool {
        self.load.is_none_or(Load::is_zero)
    }
}

/// The rows of a readings file and where each came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Readings {
    /// One per row, in file order.
    pub readings: Vec<Reading>,
    /// The posture labels: `labels[r.posture]`.
    pub labels: Vec<String>,
    /// The line of each reading (1-based).
    pub lines: Vec<u64>,
    /// The frame of the positions: the tracker's (`x_tracker_mm`) or the robot base
    /// (`x_mm`).
    pub frame: DisplacementFrame,
    /// The frame of the wrench columns (base without force columns).
    pub wrench_frame: Frame,
    /// Whether the file has load steps (`load_step` or `load_n` and the force columns).
    pub has_loads: bool,
    /// The names of the force and of the position columns in the header, comma-separated.
    pub columns: [String; 2],
    /// How many reflectors fixed in the cell the rows read: the largest `T<k>`.
    pub tables: usize,
}

/// The header's column names, in the documented order, without load steps.
pub fn header() -> String {
    let mut names = vec![POSTURE, POINT];
    names.extend(Q);
    names.extend(TRACKER);
    names.join(",")
}

/// The header's column names with load steps, in the documented order.
pub fn header_with_loads() -> String {
    let mut names = vec![POSTURE, POINT];
    names.extend(Q);
    names.push(LOAD_STEP);
    names.extend(FORCE);
    names.extend(TRACKER);
    names.join(",")
}

fn expected_columns() -> String {
    format!(
        "{} (or {} in the base frame; load steps: {LOAD_STEP} or {LOAD_N} with {} [{}] or {} [{}])",
        header(),
        BASE.join(","),
        FORCE.join(","),
        MOMENT.join(","),
        FORCE_TOOL.join(","),
        MOMENT_TOOL.join(",")
    )
}

/// Whether a header line (CSV) names a load column (`load_step` or `load_n`): a readings file
/// with load steps rather than a measurement file.
pub fn has_load_column(header_line: &str) -> bool {
    header_line
        .split(',')
        .map(|f| f.trim().trim_matches('"'))
        .any(|f| f == LOAD_STEP || f == LOAD_N)
}

/// Parses a readings file (module docs) for `robot`, whose tool has `points` measuring points.
///
/// # Errors
/// [`Error::Column`] naming the line, the column and the [`ColumnProblem`]: unknown (with a
/// suggestion), repeated, missing or conflicting columns, a row with another field count, a value
/// that is not a finite number, an empty label, a point that is not 1..=`points`, an angle outside
/// the joint limits, a coordinate outside [`limits::LENGTH_MM`], a load step that is not an integer
/// in `0..=1000`, a load outside `[0, 1e7]` N, a force or moment outside
/// [`limits::WRENCH`], a posture label at two sets of axis angles, a point read twice in one
/// posture (without load steps), no rows or more than [`MAX_READINGS`].
///
/// # Examples
/// ```
/// use stiffid_core::io::readings;
/// let robot = stiffid_core::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
/// let text = format!("{}\nA,1,0,0,-90,0,0,0,1000,2000,300\n", readings::header());
/// let r = readings::parse(&text, &robot, 4).unwrap();
/// assert_eq!((r.readings[0].point, r.readings[0].position.x), (0, 1.0));
/// ```
pub fn parse(text: &str, robot: &Robot, points: usize) -> Result<Readings> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let mut lines = super::LineCount::with_comments(text.as_bytes());
    let names: Vec<String> = reader
        .headers()
        .map_err(|e| unreadable(1, &e))?
        .iter()
        .map(str::to_string)
        .collect();
    let header_line = lines.at(0);
    if names.iter().all(|n| n.is_empty()) {
        let expected = header();
        return Err(problem(
            header_line,
            None,
            "",
            ColumnProblem::Empty { expected },
        ));
    }
    let columns = Columns::new(&names, header_line, robot)?;
    let mut out = Readings {
        readings: Vec::new(),
        labels: Vec::new(),
        lines: Vec::new(),
        frame: columns.frame,
        wrench_frame: columns.wrench_frame,
        has_loads: columns.load.is_some(),
        columns: columns.names(&names),
        tables: 0,
    };
    let mut numbers = Numbers::default();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| lines.at(p.byte()));
            unreadable(line, &e)
        })?;
        let line = record.position().map_or(0, |p| lines.at(p.byte()));
        if out.readings.len() == MAX_READINGS {
            let what = "readings";
            let too_many = ColumnProblem::TooMany {
                limit: MAX_READINGS,
                what,
            };
            return Err(problem(line, None, "", too_many));
        }
        let row = Row {
            record: &record,
            line,
            names: &names,
        };
        let reading = columns.reading(&row, robot, points, &mut out, &mut numbers)?;
        if reading.table {
            out.tables = out.tables.max(reading.point + 1);
        }
        out.readings.push(reading);
        out.lines.push(line);
    }
    if out.readings.is_empty() {
        let what = "reading row";
        return Err(problem(
            header_line,
            None,
            "",
            ColumnProblem::NoRows { what },
        ));
    }
    Ok(out)
}

/// Where each quantity sits in a row (0-based field indices).
struct Columns {
    posture: usize,
    point: usize,
    q: [usize; 6],
    /// The external axes' columns, the cell's order.
    e: external::Columns,
    position: [usize; 3],
    frame: DisplacementFrame,
    load: Option<(usize, bool)>,
    force: Option<[usize; 3]>,
    moment: Option<[usize; 3]>,
    wrench_frame: Frame,
    /// The direction columns (`dir1..dir6`), if any.
    direction: Option<[usize; 6]>,
}

/// One record, its line and the header's names: what places an error.
struct Row<'a> {
    record: &'a csv::StringRecord,
    line: u64,
    names: &'a [String],
}

impl Row<'_> {
    fn error(&self, column: usize, problem: ColumnProblem) -> Error {
        Error::Column {
            line: self.line,
            column: Some(column + 1),
            name: self.names[column].clone(),
            problem,
        }
    }

    fn field(&self, column: usize) -> &str {
        self.record.get(column).unwrap_or("")
    }

    fn number(&self, column: usize) -> Result<f64> {
        let field = self.field(column);
        field
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                let value = short(field);
                self.error(column, ColumnProblem::NotANumber { value })
            })
    }

    /// The number in `column`, within `range`.
    fn within(&self, column: usize, range: &limits::Range) -> Result<f64> {
        let v = self.number(column)?;
        match range.contains(v) {
            true => Ok(v),
            false => Err(self.error(column, range.outside(&self.names[column], v))),
        }
    }

    fn vector3(&self, columns: [usize; 3], range: &limits::Range) -> Result<Vector3<f64>> {
        Ok(Vector3::new(
            self.within(columns[0], range)?,
            self.within(columns[1], range)?,
            self.within(columns[2], range)?,
        ))
    }
}

/// A row's axis angles (rad), external axis values and directions.
type Posture = (Vector6<f64>, ExternalValues, Option<Vector6<f64>>);

/// What earlier rows said about each posture and point ([`Columns::posture_index`]).
#[derive(Default)]
struct Numbers {
    /// The posture number of each label.
    labels: HashMap<String, usize>,
    /// The axis angles, external axis values and directions of each posture and the line that
    /// gave them.
    angles: Vec<(Posture, u64)>,
    /// The line of each (posture, point, table) read (without load steps).
    read: HashMap<(usize, usize, bool), u64>,
}

fn known() -> impl Iterator<Item = &'static str> + Clone {
    [POSTURE, POINT, LOAD_STEP, LOAD_N]
        .into_iter()
        .chain(Q)
        .chain(TRACKER)
        .chain(BASE)
        .chain(FORCE)
        .chain(MOMENT)
        .chain(FORCE_TOOL)
        .chain(MOMENT_TOOL)
        .chain(direction::DIR)
}

impl Columns {
    fn new(names: &[String], line: u64, robot: &Robot) -> Result<Self> {
        let e = external::Columns::against(names, line, robot.external())?;
        let others: Vec<&String> = names.iter().filter(|n| !external_like(n)).collect();
        super::known_names(&others, line, known(), expected_columns)?;
        let find = |name: &str| names.iter().position(|n| n == name);
        let any = |set: &[&str]| set.iter().any(|n| find(n).is_some());
        let need = |name: &str| find(name).ok_or_else(|| super::missing(line, name));
        let need3 = |set: [&str; 3]| -> Result<[usize; 3]> {
            Ok([need(set[0])?, need(set[1])?, need(set[2])?])
        };
        let conflict = |first: &[&str], second: &[&str]| {
            problem(
                line,
                None,
                "",
                ColumnProblem::Conflict {
                    first: first.join(","),
                    second: second.join(","),
                },
            )
        };
        let posture = need(POSTURE)?;
        let point = need(POINT)?;
        let q = [
            need(Q[0])?,
            need(Q[1])?,
            need(Q[2])?,
            need(Q[3])?,
            need(Q[4])?,
            need(Q[5])?,
        ];
        let (position, frame) = match (any(&TRACKER), any(&BASE)) {
            (true, true) => return Err(conflict(&TRACKER, &BASE)),
            (false, true) => (need3(BASE)?, DisplacementFrame::Base),
            _ => (need3(TRACKER)?, DisplacementFrame::Tracker),
        };
        let load = match (find(LOAD_STEP), find(LOAD_N)) {
            (Some(_), Some(_)) => return Err(conflict(&[LOAD_STEP], &[LOAD_N])),
            (Some(c), None) => Some((c, true)),
            (None, Some(c)) => Some((c, false)),
            (None, None) => None,
        };
        let base_wrench = [FORCE, MOMENT].concat();
        let tool_wrench = [FORCE_TOOL, MOMENT_TOOL].concat();
        let wrench_frame = match (any(&base_wrench), any(&tool_wrench)) {
            (true, true) => return Err(conflict(&base_wrench, &tool_wrench)),
            (false, true) => Frame::Tool,
            _ => Frame::Base,
        };
        let (force_names, moment_names) = match wrench_frame {
            Frame::Base => (FORCE, MOMENT),
            Frame::Tool => (FORCE_TOOL, MOMENT_TOOL),
        };
        let (force, moment) = match load {
            None if any(&base_wrench) || any(&tool_wrench) => {
                return Err(super::missing(line, LOAD_STEP))
            }
            None => (None, None),
            Some(_) => (
                Some(need3(force_names)?),
                match any(&moment_names) {
                    true => Some(need3(moment_names)?),
                    false => None,
                },
            ),
        };
        Ok(Self {
            direction: direction::columns(names, line)?,
            posture,
            point,
            q,
            e,
            position,
            frame,
            load,
            force,
            moment,
            wrench_frame,
        })
    }

    /// The names of the force and of the position columns.
    fn names(&self, names: &[String]) -> [String; 2] {
        let join = |c: &[usize]| {
            let list: Vec<&str> = c.iter().map(|&i| names[i].as_str()).collect();
            list.join(",")
        };
        [
            self.force.map_or_else(String::new, |f| join(&f)),
            join(&self.position),
        ]
    }

    /// The reading of one row; `so_far` holds the rows before it (labels numbered there).
    fn reading(
        &self,
        row: &Row,
        robot: &Robot,
        points: usize,
        so_far: &mut Readings,
        numbers: &mut Numbers,
    ) -> Result<Reading> {
        if row.record.len() != row.names.len() {
            let count = ColumnProblem::FieldCount {
                expected: row.names.len(),
                got: row.record.len(),
            };
            return Err(problem(row.line, None, "", count));
        }
        let label = row.field(self.posture);
        if label.is_empty() {
            return Err(row.error(self.posture, ColumnProblem::EmptyLabel));
        }
        let (point, table) = self.point(row, points)?;
        if table && self.load.is_some() {
            let message = "a reflector fixed in the cell in a file with load steps: load steps read the tool's measuring points; locate the part in a second step, `calibrate --update` of the calibrated robot file with unloaded readings of the arm and the reflectors (the guide's \"Locating the part after a calibration with load steps\")".to_string();
            return Err(row.error(self.point, ColumnProblem::Measurement { message }));
        }
        let mut q = Vector6::zeros();
        for (a, &c) in self.q.iter().enumerate() {
            q[a] = row.number(c)?.to_radians();
        }
        if let Some(v) = robot.limits().first_violation(&q) {
            let outside = v.outside(Q[v.axis].into(), "the robot's limits");
            return Err(row.error(self.q[v.axis], outside));
        }
        let e = self.external(row, robot)?;
        let position = row.vector3(self.position, &limits::LENGTH_MM)? * 1e-3;
        let load = self
            .load
            .map(|(c, step)| self.load(row, c, step))
            .transpose()?;
        let wrench = self.wrench(row)?;
        let direction = direction::values(row, self.direction)?;
        let at = (q, e, direction);
        let posture = self.posture_index(row, label, at, (point, table), so_far, numbers)?;
        Ok(Reading {
            posture,
            point,
            q,
            e,
            table,
            position,
            load,
            wrench,
            direction,
        })
    }

    fn load(&self, row: &Row, column: usize, step: bool) -> Result<Load> {
        if !step {
            let range = limits::Range::new(0.0, limits::LOAD_N.max, "N");
            return Ok(Load::Newtons(row.within(column, &range)?));
        }
        let field = row.field(column);
        match field.parse::<u32>() {
            Ok(s) if s <= MAX_LOAD_STEP => Ok(Load::Step(s)),
            _ => Err(row.error(
                column,
                ColumnProblem::Measurement {
                    message: format!(
                        "'{}' is not a load step (an integer from 0, unloaded, to {MAX_LOAD_STEP})",
                        short(field)
                    ),
                },
            )),
        }
    }

    fn wrench(&self, row: &Row) -> Result<Vector6<f64>> {
        let range = &limits::WRENCH;
        let force = self
            .force
            .map_or(Ok(Vector3::zeros()), |c| row.vector3(c, range))?;
        let moment = self
            .moment
            .map_or(Ok(Vector3::zeros()), |c| row.vector3(c, range))?;
        Ok(Vector6::new(
            force.x, force.y, force.z, moment.x, moment.y, moment.z,
        ))
    }

    /// The external axes' values of a row (SI), each within its axis's travel.
    fn external(&self, row: &Row, robot: &Robot) -> Result<ExternalValues> {
        let e = (self.e).values(|c| row.field(c), |c, p| row.error(c, p))?;
        let Some(axes) = robot.external() else {
            return Ok(e);
        };
        for (k, (axis, si)) in axes.axes().iter().zip(e.as_slice()).enumerate() {
            let slack = 1e-9 * (axis.upper - axis.lower);
            if *si < axis.lower - slack || *si > axis.upper + slack {
                let c = self.e.column(k);
                return Err(row.error(
                    c,
                    ColumnProblem::Outside {
                        name: row.names[c].clone(),
                        value: axis.to_display(*si),
                        within: "the axis's travel",
                        lower: axis.to_display(axis.lower),
                        upper: axis.to_display(axis.upper),
                    },
                ));
            }
        }
        Ok(e)
    }

    /// The point of a row, 0-based, and whether it is a reflector fixed in the cell (`T1`,
    /// `T2`, ...).
    fn point(&self, row: &Row, points: usize) -> Result<(usize, bool)> {
        let field = row.field(self.point);
        if let Some(k) = field.strip_prefix(['T', 't']) {
            return match k.parse::<usize>() {
                Ok(k) if (1..=MAX_TABLE_REFLECTORS).contains(&k) => Ok((k - 1, true)),
                _ => Err(row.error(
                    self.point,
                    ColumnProblem::Measurement {
                        message: format!(
                            "'{}' is not a reflector fixed in the cell (T1 to T{MAX_TABLE_REFLECTORS}) nor a measuring point 1 to {points}",
                            short(field)
                        ),
                    },
                )),
            };
        }
        match field.parse::<usize>() {
            Ok(p) if (1..=points).contains(&p) => Ok((p - 1, false)),
            Ok(p) if p >= 1 => Err(row.error(
                self.point,
                ColumnProblem::Outside {
                    name: POINT.into(),
                    value: p as f64,
                    within: "the setup's measuring points",
                    lower: 1.0,
                    upper: points as f64,
                },
            )),
            _ => Err(row.error(
                self.point,
                ColumnProblem::NotAPoint {
                    value: short(field),
                },
            )),
        }
    }

    /// The posture number of `label`: a new one, or that of earlier rows with the same angles
    /// and external axis values (and, without load steps, another point).
    fn posture_index(
        &self,
        row: &Row,
        label: &str,
        at: Posture,
        (point, table): (usize, bool),
        so_far: &mut Readings,
        numbers: &mut Numbers,
    ) -> Result<usize> {
        let Some(&index) = numbers.labels.get(label) else {
            let index = so_far.labels.len();
            so_far.labels.push(label.to_string());
            numbers.labels.insert(label.to_string(), index);
            numbers.angles.push((at, row.line));
            if self.load.is_none() {
                numbers.read.insert((index, point, table), row.line);
            }
            return Ok(index);
        };
        let ((angles, values, directions), line) = &numbers.angles[index];
        let other = (*angles != at.0).then_some("axis angles");
        let other = other.or((*values != at.1).then_some("external axis values"));
        let message = if let Some(what) = other.or((*directions != at.2).then_some("directions")) {
            format!("posture '{}' has other {what} on line {line}", short(label))
        } else if self.load.is_some() {
            return Ok(index);
        } else if let Some(line) = numbers.read.insert((index, point, table), row.line) {
            format!(
                "{}{} of posture '{}' is read on line {line} already",
                if table { "table reflector T" } else { "point " },
                point + 1,
                short(label)
            )
        } else {
            return Ok(index);
        };
        Err(row.error(self.posture, ColumnProblem::Measurement { message }))
    }
}

fn problem(line: u64, column: Option<usize>, name: &str, problem: ColumnProblem) -> Error {
    Error::Column {
        line,
        column,
        name: name.into(),
        problem,
    }
}

fn unreadable(line: u64, e: &csv::Error) -> Error {
    let message = super::csv_message(e);
    problem(line, None, "", ColumnProblem::Unreadable { message })
}
