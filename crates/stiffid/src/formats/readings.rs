//! Registration readings: CSV, one row per posture and measuring point, the robot's axis angles and
//! the laser tracker's reading of that measuring point, units in the header.
//!
//! ```text
//! posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm
//! ```
//! - `posture`: a label; rows of one posture share it and their axis angles.
//! - `point`: the measuring point, numbered from 1 as in the setup's `measuring_points_mm`; each
//!   point at most once per posture.
//! - `q1_deg..q6_deg`: axis angles, deg, within the robot's joint limits.
//! - `x_tracker_mm..z_tracker_mm`: the tracker's reading of the measuring point, tracker frame,
//!   mm, within [`crate::limits::LENGTH_MM`].
//!
//! Columns may come in any order; lines starting with `#` are comments. At most
//! [`MAX_READINGS`] rows. [`crate::register`] turns them into the tracker's transform.

use crate::error::ColumnProblem;
use crate::limits::{self, short};
use crate::{Error, Result, Robot};
use nalgebra::{Vector3, Vector6};

/// Most rows a readings file may hold.
pub const MAX_READINGS: usize = 10_000;

const POSTURE: &str = "posture";
const POINT: &str = "point";
const Q: [&str; 6] = ["q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg"];
const TRACKER: [&str; 3] = ["x_tracker_mm", "y_tracker_mm", "z_tracker_mm"];

/// One row: a measuring point at a posture, read by the tracker (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// The posture, 0-based in order of first appearance ([`Readings::labels`]).
    pub posture: usize,
    /// The measuring point, 0-based.
    pub point: usize,
    /// Axis angles, rad.
    pub q: Vector6<f64>,
    /// The tracker's reading, tracker frame, m.
    pub tracker: Vector3<f64>,
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
}

/// The header's column names, in the documented order.
pub fn header() -> String {
    let mut names = vec![POSTURE, POINT];
    names.extend(Q);
    names.extend(TRACKER);
    names.join(",")
}

/// Parses a readings file (module docs) for `robot`, whose tool has `points` measuring points.
///
/// # Errors
/// [`Error::Column`] naming the line, the column and the [`ColumnProblem`]: unknown (with a
/// suggestion), repeated or missing columns, a row with another field count, a value that is not
/// a finite number, an empty label, a point that is not 1..=`points`, an angle outside the joint
/// limits, a tracker coordinate outside [`limits::LENGTH_MM`], a posture label at two sets of
/// axis angles or a point read twice in one posture, no rows or more than [`MAX_READINGS`].
///
/// # Examples
/// ```
/// use stiffid::formats::readings;
/// let robot = stiffid::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
/// let text = format!("{}\nA,1,0,0,-90,0,0,0,1000,2000,300\n", readings::header());
/// let r = readings::parse(&text, &robot, 4).unwrap();
/// assert_eq!((r.readings[0].point, r.readings[0].tracker.x), (0, 1.0));
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
    let columns = Columns::new(&names, header_line)?;
    let mut out = Readings {
        readings: Vec::new(),
        labels: Vec::new(),
        lines: Vec::new(),
    };
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
        let reading = columns.reading(&row, robot, points, &mut out)?;
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
    tracker: [usize; 3],
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
}

impl Columns {
    fn new(names: &[String], line: u64) -> Result<Self> {
        let known = || [POSTURE, POINT].into_iter().chain(Q).chain(TRACKER);
        super::known_names(names, line, known(), header)?;
        let need = |name: &str| {
            names
                .iter()
                .position(|n| n == name)
                .ok_or_else(|| super::missing(line, name))
        };
        Ok(Self {
            posture: need(POSTURE)?,
            point: need(POINT)?,
            q: [
                need(Q[0])?,
                need(Q[1])?,
                need(Q[2])?,
                need(Q[3])?,
                need(Q[4])?,
                need(Q[5])?,
            ],
            tracker: [need(TRACKER[0])?, need(TRACKER[1])?, need(TRACKER[2])?],
        })
    }

    /// The reading of one row; `so_far` holds the rows before it (labels numbered there).
    fn reading(
        &self,
        row: &Row,
        robot: &Robot,
        points: usize,
        so_far: &mut Readings,
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
        let point = self.point(row, points)?;
        let mut q = Vector6::zeros();
        for (a, &c) in self.q.iter().enumerate() {
            q[a] = row.number(c)?.to_radians();
        }
        if let Some(v) = robot.limits.first_violation(&q) {
            let outside = v.outside(Q[v.axis].into(), "the robot's limits");
            return Err(row.error(self.q[v.axis], outside));
        }
        let mut tracker = Vector3::zeros();
        for (k, &c) in self.tracker.iter().enumerate() {
            let v = row.number(c)?;
            if !limits::LENGTH_MM.contains(v) {
                return Err(row.error(c, limits::LENGTH_MM.outside(TRACKER[k], v)));
            }
            tracker[k] = v * 1e-3;
        }
        let posture = self.posture_index(row, label, &q, point, so_far)?;
        Ok(Reading {
            posture,
            point,
            q,
            tracker,
        })
    }

    fn point(&self, row: &Row, points: usize) -> Result<usize> {
        let field = row.field(self.point);
        match field.parse::<usize>() {
            Ok(p) if (1..=points).contains(&p) => Ok(p - 1),
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
    /// and another point.
    fn posture_index(
        &self,
        row: &Row,
        label: &str,
        q: &Vector6<f64>,
        point: usize,
        so_far: &mut Readings,
    ) -> Result<usize> {
        let Some(index) = so_far.labels.iter().position(|l| l == label) else {
            so_far.labels.push(label.to_string());
            return Ok(so_far.labels.len() - 1);
        };
        let earlier = so_far.readings.iter().zip(&so_far.lines);
        for (r, line) in earlier.filter(|(r, _)| r.posture == index) {
            let message = if r.q != *q {
                format!(
                    "posture '{}' has other axis angles on line {line}",
                    short(label)
                )
            } else if r.point == point {
                format!(
                    "point {} of posture '{}' is read on line {line} already",
                    point + 1,
                    short(label)
                )
            } else {
                continue;
            };
            return Err(row.error(self.posture, ColumnProblem::Measurement { message }));
        }
        Ok(index)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn robot() -> Robot {
        crate::robot::presets::get("comau-smart5-nj165-3.0").unwrap()
    }

    fn error(body: &str) -> String {
        let text = format!("{}\n{body}", header());
        parse(&text, &robot(), 4).unwrap_err().to_string()
    }

    #[test]
    fn rows_read_in_any_column_order() {
        let text = "# registration\nx_tracker_mm,posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,y_tracker_mm,z_tracker_mm\n\
                    1500,a,2,10,0,-90,0,0,0,-20,300\n1600,a,1,10,0,-90,0,0,0,-20,300\n1700,b,1,0,0,-90,0,0,0,-20,300\n";
        let r = parse(text, &robot(), 4).unwrap();
        assert_eq!(r.labels, ["a", "b"]);
        assert_eq!(r.lines, [3, 4, 5]);
        let first = &r.readings[0];
        assert_eq!((first.posture, first.point), (0, 1));
        assert!((first.q[0] - 10f64.to_radians()).abs() < 1e-15);
        assert_eq!(first.tracker, Vector3::new(1.5, -0.02, 0.3));
        assert_eq!(r.readings[2].posture, 1);
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let e = error("a,1,0,0,-90,0,0,0,1,2,x\n");
        assert_eq!(
            e,
            "line 2, column 11 (z_tracker_mm): 'x' is not a finite number"
        );
        let e = error("a,5,0,0,-90,0,0,0,1,2,3\n");
        assert!(
            e.contains(
                "column 2 (point): point = 5 is outside the setup's measuring points [1.0, 4.0]"
            ),
            "{e}"
        );
        let e = error("a,1,0,0,-90,0,0,0,1,2,3\na,1,0,0,-90,0,0,0,1,2,3\n");
        assert!(
            e.contains(
                "line 3, column 1 (posture): point 1 of posture 'a' is read on line 2 already"
            ),
            "{e}"
        );
        let e = error("a,1,0,0,-90,0,0,0,1,2,3\na,2,1,0,-90,0,0,0,1,2,3\n");
        assert!(
            e.contains("posture 'a' has other axis angles on line 2"),
            "{e}"
        );
        let e = error("a,1,0,0,-90,0,0,0,1,2,1e9\n");
        assert!(
            e.contains(
                "column 11 (z_tracker_mm): z_tracker_mm = 1e9 is outside the accepted range"
            ),
            "{e}"
        );
        let e = error("a,1,0,999,-90,0,0,0,1,2,3\n");
        assert!(e.contains("column 4 (q2_deg): q2_deg = 999"), "{e}");
        let e = error("");
        assert!(e.contains("at least one reading row"), "{e}");
        let e = parse("posture,point,q1,q2_deg\n", &robot(), 4)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("unknown column 'q1' (did you mean 'q1_deg'?)"),
            "{e}"
        );
        let e = parse("posture,point\n", &robot(), 4)
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing column 'q1_deg'"), "{e}");
    }
}
