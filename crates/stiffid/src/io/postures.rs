//! Postures files: CSV with the header `posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg`, one
//! posture per row (at most [`MAX_GROUP_POSTURES`]), axis angles in degrees within the robot's
//! joint limits (and, where a caller needs it, a setup's bounds), `posture` numbering the rows
//! from 1. [`to_csv`] writes them.

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
/// use stiffid::io::postures;
/// let robot = stiffid::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
/// let text = "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n1,0,0,-90,0,30,0\n";
/// let group = postures::parse(text, &robot, None).unwrap();
/// assert!((group[0][2] - (-90f64).to_radians()).abs() < 1e-12);
/// assert!(postures::to_csv(&group).starts_with(&postures::HEADER.join(",")));
/// ```
pub fn parse(text: &str, robot: &Robot, bounds: Option<&JointBox>) -> Result<Vec<Vector6<f64>>> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = reader.headers().map_err(|e| unreadable(1, &e))?;
    if header.iter().ne(HEADER) {
        return Err(problem(
            1,
            None,
            ColumnProblem::Header {
                expected: HEADER.join(","),
                hint: super::separator_hint(&header.iter().collect::<Vec<_>>()).into(),
            },
        ));
    }
    let mut postures = Vec::new();
    // Lines counted from the text: csv's own count is one too low after a `\r\n` line end.
    let mut lines = super::LineCount::new(text.as_bytes());
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| lines.at(p.byte()));
            unreadable(line, &e)
        })?;
        let line = record.position().map_or(0, |p| lines.at(p.byte()));
        if postures.len() == MAX_GROUP_POSTURES {
            let too_many = ColumnProblem::TooMany {
                limit: MAX_GROUP_POSTURES,
                what: "postures",
            };
            return Err(problem(line, None, too_many));
        }
        postures.push(row(&record, line, robot, bounds)?);
    }
    if postures.is_empty() {
        let what = "posture row";
        return Err(problem(1, None, ColumnProblem::NoRows { what }));
    }
    Ok(postures)
}

fn row(
    record: &csv::StringRecord,
    line: u64,
    robot: &Robot,
    bounds: Option<&JointBox>,
) -> Result<Vector6<f64>> {
    if record.len() != HEADER.len() {
        let count = ColumnProblem::FieldCount {
            expected: HEADER.len(),
            got: record.len(),
        };
        return Err(problem(line, None, count));
    }
    let mut q = Vector6::zeros();
    for (i, field) in record.iter().skip(1).enumerate() {
        let deg = field
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                let value = short(field);
                problem(line, Some(i + 1), ColumnProblem::NotANumber { value })
            })?;
        q[i] = deg.to_radians();
    }
    let (limits, within) = match bounds {
        Some(b) => (b, "the setup's bounds"),
        None => (robot.limits(), "the robot's limits"),
    };
    match limits.first_violation(&q) {
        None => Ok(q),
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
        name: column.map_or(String::new(), |c| HEADER[c].into()),
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

/// The CSV text of postures (axis angles, rad) measured with the external axes `axes` at `e`
/// (SI, the cell's order): [`to_csv`] with one more column per axis, `e1_mm`, `e2_deg`, ...
/// (mm and deg with 6 decimals), the same values on every row.
pub fn to_csv_at(
    postures: &[Vector6<f64>],
    axes: &crate::robot::ExternalAxes,
    e: &crate::robot::external::ExternalValues,
) -> String {
    let values: Vec<String> = (axes.to_display(e.as_slice()).iter())
        .map(|v| format!("{v:.6}"))
        .collect();
    let mut lines = to_csv(postures)
        .lines()
        .map(str::to_string)
        .collect::<Vec<_>>();
    lines[0] += &format!(",{}", axes.column_names().join(","));
    for line in &mut lines[1..] {
        *line += &format!(",{}", values.join(","));
    }
    lines.join("\n") + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn parse_in_bounds(text: &str) -> Result<Vec<Vector6<f64>>> {
        let s = crate::setup::builtin("zhang2021-comau-nj165").unwrap();
        parse(text, s.robot(), Some(s.bounds()))
    }

    #[test]
    fn written_postures_read_back() {
        let q = vec![
            Vector6::new(0.1, -0.2, -1.5, 0.4, 0.5, -0.6),
            Vector6::new(-0.3, 0.2, -2.0, -1.0, 0.0, 3.0),
        ];
        let back = parse_in_bounds(&to_csv(&q)).unwrap();
        assert_eq!(back.len(), 2);
        for (a, b) in q.iter().zip(&back) {
            assert_relative_eq!(a, b, epsilon = 1e-7);
        }
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let head = HEADER.join(",");
        let bad = format!("{head}\n1,0,0,-90,0,0,0\n2,0,x,-90,0,0,0\n");
        let e = parse_in_bounds(&bad).unwrap_err();
        assert!(
            matches!(&e, Error::Column { line: 3, column: Some(3), name, problem: ColumnProblem::NotANumber { value } } if name == "q2_deg" && value == "x"),
            "{e:?}"
        );
        let e = parse_in_bounds("posture,a\n").unwrap_err().to_string();
        assert!(
            e.starts_with("line 1: expected the header 'posture,q1_deg"),
            "{e}"
        );
        let e = parse_in_bounds(&format!("{head}\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("at least one posture row"), "{e}");
        let e = parse_in_bounds(&format!("{head}\n1,0,0,-90\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2: expected 7 fields"), "{e}");
        let e = parse_in_bounds(&format!("{head}\n1,0,0,-90,0,0,9000\n"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("column 7 (q6_deg): q6_deg = 9000 is outside the setup's bounds"),
            "{e}"
        );
    }

    #[test]
    fn a_semicolon_separated_file_gets_the_separator_hint() {
        let text = HEADER.join(";") + "\n1;0;0;-90;0;0;0\n";
        let e = parse_in_bounds(&text).unwrap_err().to_string();
        assert!(
            e.contains("' (this header separates its columns with ';'"),
            "{e}"
        );
        // A header merely wrong gets none.
        let e = parse_in_bounds("posture,a\n").unwrap_err().to_string();
        assert!(!e.contains("';'"), "{e}");
        // A measurement file (whose columns are named, in any order) gets it too.
        let measurements = "posture;point;q1_deg;q2_deg;q3_deg;q4_deg;q5_deg;q6_deg;fx_n;fy_n;fz_n;dx_mm;dy_mm;dz_mm\n";
        let e = crate::io::measurements::parse(measurements)
            .unwrap_err()
            .to_string();
        assert!(e.contains("columns with ';'"), "{e}");
    }

    #[test]
    fn more_postures_than_the_limit_are_refused() {
        let mut text = HEADER.join(",") + "\n";
        for i in 0..=MAX_GROUP_POSTURES {
            text += &format!("{},0,0,-90,0,30,0\n", i + 1);
        }
        let e = parse_in_bounds(&text).unwrap_err().to_string();
        let last = MAX_GROUP_POSTURES + 2;
        assert!(
            e.starts_with(&format!(
                "line {last}: more than {MAX_GROUP_POSTURES} postures"
            )),
            "{e}"
        );
    }
}
