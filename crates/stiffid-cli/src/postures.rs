//! Postures files: CSV with the header `posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg`, one
//! posture per row (at most [`limits::MAX_GROUP_POSTURES`]), axis angles in degrees within the
//! robot's joint limits (and, where a command needs it, the setup's bounds), `posture` numbering
//! the rows from 1.

use anyhow::{bail, Context, Result};
use nalgebra::Vector6;
use std::path::Path;
use stiffid::limits::{self, short};
use stiffid::setup::Bounds;
use stiffid::Robot;

/// The header of a postures file.
pub const HEADER: [&str; 7] = [
    "posture", "q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg",
];

/// Reads a postures file; angles returned in rad. Every posture must lie within the robot's joint
/// limits and, if given, the `bounds` (a setup's).
///
/// # Errors
/// One line naming the file and line: unreadable file, wrong header, a row without 7 fields, a value
/// that is not a finite number, an angle outside the limits or bounds, no posture at all or more
/// than [`limits::MAX_GROUP_POSTURES`].
pub fn read(path: &Path, robot: &Robot, bounds: Option<&Bounds>) -> Result<Vec<Vector6<f64>>> {
    let text = crate::load::read(path)?;
    parse(&text, robot, bounds).with_context(|| path.display().to_string())
}

/// Parses the text of a postures file (see [`read`]); errors name the line.
pub fn parse(text: &str, robot: &Robot, bounds: Option<&Bounds>) -> Result<Vec<Vector6<f64>>> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = reader.headers().context("line 1: cannot read the header")?;
    if header.iter().ne(HEADER) {
        bail!("line 1: expected the header '{}'", HEADER.join(","));
    }
    let mut postures = Vec::new();
    for record in reader.records() {
        let record = record.context("cannot read a row")?;
        let line = record.position().map_or(0, |p| p.line());
        if postures.len() == limits::MAX_GROUP_POSTURES {
            bail!(
                "line {line}: more than {} postures",
                limits::MAX_GROUP_POSTURES
            );
        }
        postures.push(row(&record, line, robot, bounds)?);
    }
    if postures.is_empty() {
        bail!("expected at least one posture row after the header");
    }
    Ok(postures)
}

fn row(
    record: &csv::StringRecord,
    line: u64,
    robot: &Robot,
    bounds: Option<&Bounds>,
) -> Result<Vector6<f64>> {
    if record.len() != HEADER.len() {
        bail!("line {line}: expected 7 fields, got {}", record.len());
    }
    let mut q = Vector6::zeros();
    for (i, field) in record.iter().skip(1).enumerate() {
        let deg: f64 = field
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .with_context(|| {
                format!(
                    "line {line}: {} '{}' is not a finite number",
                    HEADER[i + 1],
                    short(field)
                )
            })?;
        q[i] = deg.to_radians();
    }
    let (lower, upper, what) = match bounds {
        Some(b) => (&b.lower, &b.upper, "the setup's bounds"),
        None => (&robot.lower, &robot.upper, "the robot's limits"),
    };
    if let Some(i) = (0..6).find(|&i| !(q[i] >= lower[i] && q[i] <= upper[i])) {
        bail!(
            "line {line}: {} = {} is outside {what} [{:.1}, {:.1}]",
            HEADER[i + 1],
            limits::number(q[i].to_degrees()),
            lower[i].to_degrees(),
            upper[i].to_degrees()
        );
    }
    Ok(q)
}

/// The CSV text of postures (axis angles, rad), degrees with 6 decimals.
pub fn to_csv(postures: &[Vector6<f64>]) -> String {
    let mut text = HEADER.join(",") + "\n";
    for (i, q) in postures.iter().enumerate() {
        let angles: Vec<String> = q.iter().map(|v| format!("{:.6}", v.to_degrees())).collect();
        text += &format!("{},{}\n", i + 1, angles.join(","));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn setup() -> stiffid::Setup {
        stiffid::setup::builtin("zhang2021-comau-nj165").unwrap()
    }

    fn parse_in_bounds(text: &str) -> Result<Vec<Vector6<f64>>> {
        let s = setup();
        parse(text, &s.robot(), Some(&s.bounds()))
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
        let e = parse_in_bounds(&bad).unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("q2_deg"), "{e}");
        let e = parse_in_bounds("posture,a\n").unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");
        let e = parse_in_bounds(&format!("{head}\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("at least one"), "{e}");
        let e = parse_in_bounds(&format!("{head}\n1,0,0,-90\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2: expected 7 fields"), "{e}");
        let e = parse_in_bounds(&format!("{head}\n1,0,0,-90,0,0,9000\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("q6_deg") && e.contains("bounds"), "{e}");
    }
}
