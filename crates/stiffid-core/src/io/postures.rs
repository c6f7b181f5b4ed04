//! Postures files: CSV with the header `posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg`, one
//! posture per row (at most [`MAX_GROUP_POSTURES`]), axis angles in degrees within the robot's
//! joint limits (and, where a caller needs it, a setup's bounds), `posture` numbering the rows
//! from 1. [`to_csv`] writes them.
//!
//! A cell with external axes ([`crate::robot::external`]: a track, a positioner) has one more
//! column per axis after the angles, in the cell's order, named with its unit
//! ([`crate::robot::external::ExternalAxes::column_names`]: `e1_mm`, `e2_deg`, ...), each value
//! within its axis's travel; `parse_cell` returns them, [`to_csv_cell`] writes them. A file of
//! a robot without external axes has none, and a column of an axis the cell lacks is refused.

use crate::common::error::ColumnProblem;
use crate::common::limits::{short, JointBox, MAX_GROUP_POSTURES};
use crate::{Error, Result, Robot};
use nalgebra::Vector6;

/// The header of a postures file.
pub const HEADER: [&str; 7] = [
    "posture", "q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg",
];

/// Parses the text of a postures file; angles returned in rad. Every posture must lie within the
/// robot's joint limits and, if given, the `bounds` (a setup's).
///
/// # Errors
/// [`Error::Column`] naming the line (and column) and the [`ColumnProblem`]: an unreadable row, a
/// header other than [`HEADER`], a row without 7 fields, a value that is not a finite number
/// (shown, shortened), an angle outside the limits or bounds, no posture at all or more than
/// [`MAX_GROUP_POSTURES`].
///
/// # Examples
/// ```
/// use stiffid_core::io::postures;
/// let robot = stiffid_core::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
/// let text = "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n1,0,0,-90,0,30,0\n";
/// let group = postures::parse(text, &robot, None).unwrap();
/// assert!((group[0][2] - (-90f64).to_radians()).abs() < 1e-12);
/// assert!(postures::to_csv(&group).starts_with(&postures::HEADER.join(",")));
/// ```
///
/// A cell with external axes: the file has their columns, checked as `parse_cell` checks
/// them, each value 0 (the arm's postures at the cell's zero; `parse_cell` returns other
/// values).
///
/// # Errors
/// As `parse_cell`; [`Error::InvalidField`] naming the first posture and column whose external
/// axis is not at 0: its postures would be read at a station they were not designed at.
pub fn parse(text: &str, robot: &Robot, bounds: Option<&JointBox>) -> Result<Vec<Vector6<f64>>> {
    let postures = parse_cell(text, robot, bounds)?;
    let moved = (postures.e.iter().enumerate())
        .find_map(|(i, e)| Some(i).zip(e.iter().position(|v| *v != 0.0)));
    match (moved, robot.external()) {
        (Some((i, a)), Some(axes)) => Err(Error::InvalidField {
            field: format!("posture {}: {}", i + 1, axes.column_names()[a]),
            message: "not 0: the arm's postures are read here at the cell's external axes at \
                      0, and this one at another station would be read at 0; give the postures \
                      of one station at 0, or design across stations (select --station)"
                .into(),
        }),
        _ => Ok(postures.q),
    }
}

/// The postures of a cell: axis angles and external axes' values.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Postures {
    /// Axis angles, rad, one per row.
    pub q: Vec<Vector6<f64>>,
    /// The external axes' values, SI (m, rad) in the cell's order, one per row (each empty for a
    /// robot without external axes).
    pub e: Vec<Vec<f64>>,
}

/// The header of a postures file of `robot`: [`HEADER`], then its external axes' columns.
pub(crate) fn header(robot: &Robot) -> Vec<String> {
    let mut names: Vec<String> = HEADER.iter().map(|h| h.to_string()).collect();
    names.extend(robot.external().map_or(Vec::new(), |a| a.column_names()));
    names
}

/// [`parse`] with the external axes' values of a cell (module docs): one column per axis after
/// the angles, mm or deg, each within its travel; returned in SI.
///
/// # Errors
/// Those of [`parse`], the header expected being `header` (a column of an axis the robot
/// lacks is a header error saying so), and a value of an external axis that is not a finite
/// number or outside its travel (naming the line, the column and the axis).
pub fn parse_cell(text: &str, robot: &Robot, bounds: Option<&JointBox>) -> Result<Postures> {
    let expected = header(robot);
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = reader.headers().map_err(|e| unreadable(1, &e))?;
    if header.iter().ne(expected.iter()) {
        let extra = header.iter().find(|h| {
            h.starts_with('e')
                && (h.ends_with("_mm") || h.ends_with("_deg"))
                && !expected.iter().any(|x| x == h)
        });
        let hint = match (extra, robot.external()) {
            (Some(column), None) => format!(" (the robot has no external axes: {column} is the column of a cell's external axis)"),
            (Some(column), Some(a)) => format!(" (the cell's external axes are {}: {column} names none of them)", a.column_names().join(", ")),
            (None, _) => super::separator_hint(&header.iter().collect::<Vec<_>>()).into(),
        };
        return Err(problem(
            1,
            None,
            ColumnProblem::Header {
                expected: expected.join(","),
                hint,
            },
        ));
    }
    let columns = super::external::Columns::against(&expected, 1, robot.external())?;
    let mut postures = Postures::default();
    // Lines counted from the text: csv's own count is one too low after a `\r\n` line end.
    let mut lines = super::LineCount::new(text.as_bytes());
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| lines.at(p.byte()));
            unreadable(line, &e)
        })?;
        let line = record.position().map_or(0, |p| lines.at(p.byte()));
        if postures.q.len() == MAX_GROUP_POSTURES {
            let too_many = ColumnProblem::TooMany {
                limit: MAX_GROUP_POSTURES,
                what: "postures",
            };
            return Err(problem(line, None, too_many));
        }
        let (q, e) = row(&record, line, robot, bounds, (&expected, &columns))?;
        postures.q.push(q);
        postures.e.push(e);
    }
    if postures.q.is_empty() {
        let what = "posture row";
        return Err(problem(1, None, ColumnProblem::NoRows { what }));
    }
    Ok(postures)
}

/// One row: the axis angles (rad) and the external axes' values (SI) of the header's
/// `expected` columns, the external ones at `columns` ([`super::external::Columns`], the one
/// reader of the data files' external columns).
fn row(
    record: &csv::StringRecord,
    line: u64,
    robot: &Robot,
    bounds: Option<&JointBox>,
    (expected, columns): (&[String], &super::external::Columns),
) -> Result<(Vector6<f64>, Vec<f64>)> {
    if record.len() != expected.len() {
        let count = ColumnProblem::FieldCount {
            expected: expected.len(),
            got: record.len(),
        };
        return Err(problem(line, None, count));
    }
    let named = |c: usize, p: ColumnProblem| {
        let mut p = problem(line, Some(c), p);
        if let Error::Column { name, .. } = &mut p {
            *name = expected[c].clone();
        }
        p
    };
    let mut q = Vector6::zeros();
    for (i, field) in record.iter().skip(1).take(6).enumerate() {
        let deg = (field.parse::<f64>().ok())
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                let value = short(field);
                named(i + 1, ColumnProblem::NotANumber { value })
            })?;
        q[i] = deg.to_radians();
    }
    let e = columns.values(|c| record.get(c).unwrap_or(""), named)?;
    if let Some(axes) = robot.external() {
        axes.check(e.as_slice(), &format!("line {line}"))?;
    }
    let e = e.as_slice().to_vec();
    let (limits, within) = match bounds {
        Some(b) => (b, "the setup's bounds"),
        None => (robot.limits(), "the robot's limits"),
    };
    match limits.first_violation(&q) {
        None => Ok((q, e)),
        Some(v) => {
            let outside = v.outside(HEADER[v.axis + 1].into(), within);
            Err(problem(line, Some(v.axis + 1), outside))
        }
    }
}

/// The error at `line`, 0-based field `column` of [`HEADER`].
fn problem(line: u64, column: Option<usize>, problem: ColumnProblem) -> Error {
    Error::Column {
        line,
        column: column.map(|c| c + 1),
        name: column
            .and_then(|c| HEADER.get(c))
            .map_or(String::new(), |h| h.to_string()),
        problem,
    }
}

fn unreadable(line: u64, e: &csv::Error) -> Error {
    let message = super::csv_message(e);
    problem(line, None, ColumnProblem::Unreadable { message })
}

/// The CSV text of postures (axis angles, rad): [`HEADER`], then degrees with 6 decimals.
pub fn to_csv(postures: &[Vector6<f64>]) -> String {
    let mut text = HEADER.join(",") + "\n";
    for (i, q) in postures.iter().enumerate() {
        let angles: Vec<String> = q.iter().map(|v| format!("{:.6}", v.to_degrees())).collect();
        text += &format!("{},{}\n", i + 1, angles.join(","));
    }
    text
}

/// The CSV text of a cell's postures: [`to_csv`] with the external axes' values (SI, the cell's
/// order, one per posture) in mm or deg after the angles, 6 decimals; `axes` `None` (a robot
/// without external axes): [`to_csv`].
pub fn to_csv_cell(
    postures: &[Vector6<f64>],
    e: &[Vec<f64>],
    axes: Option<&crate::robot::external::ExternalAxes>,
) -> String {
    let Some(axes) = axes else {
        return to_csv(postures);
    };
    let mut text = HEADER.join(",") + "," + &axes.column_names().join(",") + "\n";
    for (i, (q, e)) in postures.iter().zip(e).enumerate() {
        let angles = q.iter().map(|v| v.to_degrees());
        let values: Vec<String> = (angles.chain(axes.to_display(e)))
            .map(|v| format!("{v:.6}"))
            .collect();
        text += &format!("{},{}\n", i + 1, values.join(","));
    }
    text
}

/// The CSV text of postures (axis angles, rad) measured with the external axes `axes` at `e`
/// (SI, the cell's order): [`to_csv_cell`] with the same values on every row.
pub fn to_csv_at(
    postures: &[Vector6<f64>],
    axes: &crate::robot::ExternalAxes,
    e: &crate::robot::external::ExternalValues,
) -> String {
    let e = vec![e.as_slice().to_vec(); postures.len()];
    to_csv_cell(postures, &e, Some(axes))
}
