//! Machining path files: CSV, one row per path point, units in the header.
//!
//! ```text
//! q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm][,frame]
//! x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm][,frame]
//! ... [,e1_mm,e2_deg,...]
//! ```
//! - Either the axis angles `q1_deg..q6_deg` (deg) of each point, or its TCP pose: position
//!   `x_mm,y_mm,z_mm` (base frame, mm) and orientation `rx_deg,ry_deg,rz_deg`, fixed-axis
//!   roll-pitch-yaw as in URDF (`R = Rz(rz) Ry(ry) Rx(rx)`), reached by inverse kinematics.
//! - The wrench at the TCP: `fx_n,fy_n,fz_n` (N) and optionally `mx_nm,my_nm,mz_nm` (Nm; all
//!   three or none, none means zero).
//! - `frame` (optional): `base` or `tool`, the frame of the wrench; an empty cell or no column
//!   takes the default the caller gives.
//! - A cell with external axes ([`stiffid_core::robot::external`]: a track, a positioner): one column
//!   per axis in the cell's order, `e1_mm` for a linear axis, `e2_deg` for a rotary one
//!   ([`stiffid_core::io::external`]), the values the axes hold at the point (compensated as given,
//!   [`crate::cell::on_carriage`]). A pose is then a point of the part: in the cell
//!   frame at `e = 0`, carried by the positioner (the cell frame itself without one), never the
//!   moving base's; a `base` wrench is in the cell frame.
//!
//! - `feed_mm_s` (optional): the feed of the move to the point, mm/s in (0, 10 000]; an empty
//!   cell: no feed for that move (nor for the first point). The compensate job keeps every axis
//!   of the free variables' moves within its largest speed at it ([`feeds`]); without the
//!   column no speed is checked.
//!
//! Columns may come in any order; lines starting with `#` are comments. At most `MAX_POINTS`
//! rows. Errors name the line and column ([`Error::Column`]).

use crate::compensate::{PathPoint, Target};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector6};
use stiffid_core::common::error::ColumnProblem;
use stiffid_core::common::limits::{self, short};
use stiffid_core::observation::deflection::Frame;
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_core::{Error, Result};

/// The most path points a file may hold.
pub(crate) const MAX_POINTS: usize = 1_000_000;

const Q: [&str; 6] = ["q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg"];
const POSE: [&str; 6] = ["x_mm", "y_mm", "z_mm", "rx_deg", "ry_deg", "rz_deg"];
const FORCE: [&str; 3] = ["fx_n", "fy_n", "fz_n"];
const MOMENT: [&str; 3] = ["mx_nm", "my_nm", "mz_nm"];
const FRAME: &str = "frame";
const FEED: &str = "feed_mm_s";

/// The accepted feed of a path file's `feed_mm_s`, mm/s: above 0, at most 10 000.
pub(crate) const FEED_MM_S: limits::Range = limits::Range::new(0.0, 1e4, "mm/s");

/// The error at `line`, in no column.
fn problem(line: u64, problem: ColumnProblem) -> Error {
    Error::Column {
        line,
        column: None,
        name: String::new(),
        problem,
    }
}

/// Where each quantity sits in a row (0-based field indices).
struct Columns {
    target: [usize; 6],
    pose: bool,
    force: [usize; 3],
    moment: Option<[usize; 3]>,
    frame: Option<usize>,
    feed: Option<usize>,
}

/// Parses a path file (module docs) of a robot without external axes; `default_frame` is the
/// wrench frame of rows without one. A cell's path: [`points`] with its axes.
///
/// # Errors
/// [`Error::Column`] naming the line, the column and the [`ColumnProblem`]: an unknown (with a
/// suggestion), repeated or missing column, both or neither of the axis-angle and pose columns, a
/// row with another number of fields than the header, a value that is not a finite number (the
/// value shown, shortened), a frame other than `base` or `tool`, an external axis column
/// ([`stiffid_core::io::external::Columns::against`]: the robot has none), no rows, or more than
/// `MAX_POINTS`.
///
/// # Examples
/// ```
/// use stiffid_core::observation::deflection::Frame;
/// let text = "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n\n0,0,-90,0,30,0,0,0,-500\n";
/// let points = stiffid_machining::path::parse(text, Frame::Base).unwrap();
/// assert_eq!((points.len(), points[0].line, points[0].wrench[2]), (1, 2, -500.0));
/// ```
pub fn parse(text: &str, default_frame: Frame) -> Result<Vec<PathPoint>> {
    points(text, default_frame, None)?.collect()
}

/// The points of a path file one by one, parsed as they are asked for: [`parse`] without the
/// whole path in memory (for [`crate::compensate::stream`]). The header is checked at once.
/// `cell` holds the robot's external axes (`None` for a robot without): one column per axis, named
/// as the cell names it (`e1_mm` for a linear axis, `e2_deg` for a rotary one); the values are
/// checked against the axes' travels where the points meet the robot
/// ([`crate::cell::on_carriage`]).
///
/// # Errors
/// The header's at once; each row's, and the row limit and the empty file, as an item (as
/// [`parse`]); the external axis columns' ([`stiffid_core::io::external::Columns::against`]: a column
/// of an axis the cell lacks or in the other unit, an axis of the cell without its column).
pub fn points<'t>(
    text: &'t str,
    default_frame: Frame,
    cell: Option<&ExternalAxes>,
) -> Result<impl Iterator<Item = Result<PathPoint>> + use<'t>> {
    let mut reader = reader(text);
    let header = reader.headers().map_err(|e| unreadable(1, &e))?.clone();
    // Lines counted from the text: csv's own count is one too low after a `\r\n` line end.
    let mut lines = stiffid_core::io::LineCount::with_comments(text.as_bytes());
    let header_line = header.position().map_or(1, |p| lines.at(p.byte()));
    let names: Vec<String> = header.iter().map(str::to_string).collect();
    let columns = {
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        columns(&names, header_line)?
    };
    let external = stiffid_core::io::external::Columns::against(&names, header_line, cell)?;
    let mut records = reader.into_records();
    let mut count = 0usize;
    let mut done = false;
    Ok(std::iter::from_fn(move || {
        if done {
            return None;
        }
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let next = match records.next() {
            None if count == 0 => Some(Err(problem(
                header_line,
                ColumnProblem::NoRows { what: "path point" },
            ))),
            None => None,
            Some(record) => Some(row(
                record,
                &mut lines,
                &names,
                (&columns, &external),
                count,
                default_frame,
            )),
        };
        count += 1;
        done = !matches!(next, Some(Ok(_)));
        next
    }))
}

/// One row: its point, or the error naming its line.
fn row(
    record: csv::Result<csv::StringRecord>,
    lines: &mut stiffid_core::io::LineCount,
    names: &[&str],
    (columns, external): (&Columns, &stiffid_core::io::external::Columns),
    before: usize,
    default_frame: Frame,
) -> Result<PathPoint> {
    let (record, line) = located(record, lines)?;
    if record.len() != names.len() {
        let count = ColumnProblem::FieldCount {
            expected: names.len(),
            got: record.len(),
        };
        return Err(problem(line, count));
    }
    if before == MAX_POINTS {
        let too_many = ColumnProblem::TooMany {
            limit: MAX_POINTS,
            what: "path points",
        };
        return Err(problem(line, too_many));
    }
    let mut point = point(columns, names, &record, line, default_frame)?;
    point.external = external.values(|i| &record[i], |i, p| at(names, line, i, p))?;
    Ok(point)
}

/// A path file's CSV reader: fields trimmed, rows of any length (checked against the header
/// row by row), `#` lines skipped.
fn reader(text: &str) -> csv::Reader<&[u8]> {
    csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes())
}

/// A record read and its line, or the error naming the line where it could not be read.
fn located(
    record: csv::Result<csv::StringRecord>,
    lines: &mut stiffid_core::io::LineCount,
) -> Result<(csv::StringRecord, u64)> {
    let record = record.map_err(|e| {
        let line = e.position().map_or(0, |p| lines.at(p.byte()));
        unreadable(line, &e)
    })?;
    let line = record.position().map_or(0, |p| lines.at(p.byte()));
    Ok((record, line))
}

fn unreadable(line: u64, e: &csv::Error) -> Error {
    let message = stiffid_core::io::csv_message(e);
    problem(line, ColumnProblem::Unreadable { message })
}

fn expected_columns() -> String {
    format!(
        "{} or {}, {}, optional {}, {FRAME}, {FEED} and external axes e1_mm or e1_deg, ...",
        Q.join(","),
        POSE.join(","),
        FORCE.join(","),
        MOMENT.join(",")
    )
}

fn columns(names: &[&str], line: u64) -> Result<Columns> {
    let known = Q.iter().chain(&POSE).chain(&FORCE).chain(&MOMENT);
    let known = (known.copied().chain([FRAME, FEED])).chain(stiffid_core::io::external::NAMES);
    stiffid_core::io::known_names(names, line, known, expected_columns)?;
    let find = |n: &str| names.iter().position(|h| *h == n);
    let all = |set: &[&str]| -> Result<Option<Vec<usize>>> {
        let found: Vec<Option<usize>> = set.iter().map(|n| find(n)).collect();
        match found.iter().position(Option::is_none) {
            None => Ok(Some(found.into_iter().flatten().collect())),
            Some(_) if found.iter().all(Option::is_none) => Ok(None),
            Some(i) => Err(stiffid_core::io::missing(line, set[i])),
        }
    };
    let (target, is_pose) = match (all(&Q)?, all(&POSE)?) {
        (Some(q), None) => (q, false),
        (None, Some(p)) => (p, true),
        (q, _) => {
            let (first, second) = (Q.join(","), POSE.join(","));
            return Err(problem(
                line,
                match q {
                    Some(_) => ColumnProblem::Conflict { first, second },
                    None => ColumnProblem::Neither { first, second },
                },
            ));
        }
    };
    let force = all(&FORCE)?.ok_or_else(|| stiffid_core::io::missing(line, FORCE[0]))?;
    let as3 = |v: Vec<usize>| [v[0], v[1], v[2]];
    Ok(Columns {
        target: [
            target[0], target[1], target[2], target[3], target[4], target[5],
        ],
        pose: is_pose,
        force: as3(force),
        moment: all(&MOMENT)?.map(as3),
        frame: find(FRAME),
        feed: find(FEED),
    })
}

/// The error in field `i` (0-based) of a row at `line`.
fn at(names: &[&str], line: u64, i: usize, problem: ColumnProblem) -> Error {
    Error::Column {
        line,
        column: Some(i + 1),
        name: names[i].into(),
        problem,
    }
}

fn number(record: &csv::StringRecord, names: &[&str], i: usize, line: u64) -> Result<f64> {
    let text = &record[i];
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(at(
            names,
            line,
            i,
            ColumnProblem::NotANumber { value: short(text) },
        )),
    }
}

fn point(
    c: &Columns,
    names: &[&str],
    record: &csv::StringRecord,
    line: u64,
    default_frame: Frame,
) -> Result<PathPoint> {
    let get = |i: usize| number(record, names, i, line);
    // Each value within its range ([`limits`]): positions within LENGTH_MM, angles within
    // ANGLE_DEG, forces and moments within WRENCH.
    let within = |i: usize, range: &limits::Range| -> Result<f64> {
        let v = get(i)?;
        match range.contains(v) {
            true => Ok(v),
            false => Err(at(names, line, i, range.outside(names[i], v))),
        }
    };
    let t: Vec<f64> = c
        .target
        .iter()
        .enumerate()
        .map(|(k, &i)| match (c.pose, k < 3) {
            (true, true) => within(i, &limits::LENGTH_MM),
            _ => within(i, &limits::ANGLE_DEG),
        })
        .collect::<Result<_>>()?;
    let target = match c.pose {
        false => Target::Posture(Vector6::from_iterator(t.iter().map(|v| v.to_radians()))),
        true => Target::Pose(Isometry3::from_parts(
            Translation3::new(t[0] * 1e-3, t[1] * 1e-3, t[2] * 1e-3),
            UnitQuaternion::from_euler_angles(
                t[3].to_radians(),
                t[4].to_radians(),
                t[5].to_radians(),
            ),
        )),
    };
    let mut wrench = Vector6::zeros();
    for (k, &i) in c.force.iter().enumerate() {
        wrench[k] = within(i, &limits::WRENCH)?;
    }
    if let Some(m) = &c.moment {
        for (k, &i) in m.iter().enumerate() {
            wrench[3 + k] = within(i, &limits::WRENCH)?;
        }
    }
    if let Some(i) = c.feed {
        feed(record, names, i, line)?;
    }
    let frame = match c.frame.map(|i| &record[i]) {
        None | Some("") => default_frame,
        Some("base") => Frame::Base,
        Some("tool") => Frame::Tool,
        Some(other) => {
            let choice = ColumnProblem::Choice {
                value: short(other),
                expected: "base or tool",
            };
            return Err(at(names, line, c.frame.unwrap_or(0), choice));
        }
    };
    Ok(PathPoint {
        line,
        target,
        wrench,
        frame,
        external: ExternalValues::NONE,
    })
}

/// The feed of a row's `feed_mm_s` (field `i`), m/s: `None` for an empty cell.
fn feed(record: &csv::StringRecord, names: &[&str], i: usize, line: u64) -> Result<Option<f64>> {
    if record[i].is_empty() {
        return Ok(None);
    }
    let v = number(record, names, i, line)?;
    match v > 0.0 && FEED_MM_S.contains(v) {
        true => Ok(Some(v * 1e-3)),
        false => {
            let outside = ColumnProblem::Outside {
                name: names[i].into(),
                value: v,
                within: "the feeds (above 0)",
                lower: FEED_MM_S.min,
                upper: FEED_MM_S.max,
            };
            Err(at(names, line, i, outside))
        }
    }
}

/// The feed of the move to each row of a path file (module docs), m/s, in row order: `None`
/// for a row whose `feed_mm_s` is empty; `None` for a file without the column.
///
/// # Errors
/// Those of [`points`] for the rows up to the first one whose feed is not a number within [0, 10
/// 000] mm/s and above 0 ([`Error::Column`] naming its line and column).
pub fn feeds(text: &str) -> Result<Option<Vec<Option<f64>>>> {
    let mut reader = reader(text);
    let header = reader.headers().map_err(|e| unreadable(1, &e))?.clone();
    let names: Vec<&str> = header.iter().collect();
    let Some(i) = names.iter().position(|n| *n == FEED) else {
        return Ok(None);
    };
    let mut lines = stiffid_core::io::LineCount::with_comments(text.as_bytes());
    let mut out = Vec::new();
    for record in reader.records() {
        let (record, line) = located(record, &mut lines)?;
        match record.get(i) {
            Some(_) => out.push(feed(&record, &names, i, line)?),
            None => out.push(None),
        }
    }
    Ok(Some(out))
}
