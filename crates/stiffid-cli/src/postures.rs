//! Postures files: CSV with the header `posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg`, one
//! posture per row, axis angles in degrees, `posture` numbering the rows from 1.

use crate::output::write_atomic;
use anyhow::{bail, Context, Result};
use nalgebra::Vector6;
use std::path::Path;
use stiffid::Robot;

/// The header of a postures file.
pub const HEADER: [&str; 7] = [
    "posture", "q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg",
];

/// Reads a postures file; angles returned in rad. Every posture must lie within the robot's joint
/// limits.
///
/// # Errors
/// One line naming the file and line: unreadable file, wrong header, a row without 7 fields, a value
/// that is not a finite number, an angle outside the robot's limits, or no posture at all.
pub fn read(path: &Path, robot: &Robot) -> Result<Vec<Vector6<f64>>> {
    let text = crate::load::read(path)?;
    parse(&text, robot).with_context(|| path.display().to_string())
}

/// Parses the text of a postures file (see [`read`]); errors name the line.
pub fn parse(text: &str, robot: &Robot) -> Result<Vec<Vector6<f64>>> {
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
        postures.push(row(&record, line, robot)?);
    }
    if postures.is_empty() {
        bail!("expected at least one posture row after the header");
    }
    Ok(postures)
}

fn row(record: &csv::StringRecord, line: u64, robot: &Robot) -> Result<Vector6<f64>> {
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
                    "line {line}: {} '{field}' is not a finite number",
                    HEADER[i + 1]
                )
            })?;
        q[i] = deg.to_radians();
    }
    if let Some(i) = robot.first_out_of_limits(&q) {
        bail!(
            "line {line}: {} = {} is outside the robot's limits [{:.1}, {:.1}]",
            HEADER[i + 1],
            q[i].to_degrees(),
            robot.lower[i].to_degrees(),
            robot.upper[i].to_degrees()
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

/// Writes postures (axis angles, rad) to a postures file, whole.
pub fn write(path: &Path, postures: &[Vector6<f64>]) -> Result<()> {
    write_atomic(path, to_csv(postures).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn robot() -> Robot {
        stiffid::robot::presets::get("comau-smart5-nj165-3.0").unwrap()
    }

    #[test]
    fn written_postures_read_back() {
        let q = vec![
            Vector6::new(0.1, -0.2, -1.5, 0.4, 0.5, -0.6),
            Vector6::new(-0.3, 0.2, -2.0, -1.0, 0.0, 3.0),
        ];
        let back = parse(&to_csv(&q), &robot()).unwrap();
        assert_eq!(back.len(), 2);
        for (a, b) in q.iter().zip(&back) {
            assert_relative_eq!(a, b, epsilon = 1e-7);
        }
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let head = HEADER.join(",");
        let bad = format!("{head}\n1,0,0,-90,0,0,0\n2,0,x,-90,0,0,0\n");
        let e = parse(&bad, &robot()).unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("q2_deg"), "{e}");
        let e = parse("posture,a\n", &robot()).unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");
        let e = parse(&format!("{head}\n"), &robot())
            .unwrap_err()
            .to_string();
        assert!(e.contains("at least one"), "{e}");
        let e = parse(&format!("{head}\n1,0,0,-90\n"), &robot())
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2: expected 7 fields"), "{e}");
        let e = parse(&format!("{head}\n1,0,0,-90,0,0,9000\n"), &robot())
            .unwrap_err()
            .to_string();
        assert!(e.contains("q6_deg") && e.contains("limits"), "{e}");
    }
}
