//! Machining path files: CSV, one row per path point, units in the header.
//!
//! ```text
//! q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm][,frame]
//! x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm][,frame]
//! ```
//! - Either the axis angles `q1_deg..q6_deg` (deg) of each point, or its TCP pose: position
//!   `x_mm,y_mm,z_mm` (base frame, mm) and orientation `rx_deg,ry_deg,rz_deg`, fixed-axis
//!   roll-pitch-yaw as in URDF (`R = Rz(rz) Ry(ry) Rx(rx)`), reached by inverse kinematics.
//! - The wrench at the TCP: `fx_n,fy_n,fz_n` (N) and optionally `mx_nm,my_nm,mz_nm` (Nm; all
//!   three or none, none means zero).
//! - `frame` (optional): `base` or `tool`, the frame of the wrench; an empty cell or no column
//!   takes the default the caller gives.
//!
//! Columns may come in any order; lines starting with `#` are comments. At most [`MAX_POINTS`]
//! rows. Errors name the line and column ([`Error::Row`]).

use crate::compensate::{PathPoint, Target};
use crate::deflection::Frame;
use crate::{Error, Result};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector6};

/// The most path points a file may hold.
pub const MAX_POINTS: usize = 1_000_000;

const Q: [&str; 6] = ["q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg"];
const POSE: [&str; 6] = ["x_mm", "y_mm", "z_mm", "rx_deg", "ry_deg", "rz_deg"];
const FORCE: [&str; 3] = ["fx_n", "fy_n", "fz_n"];
const MOMENT: [&str; 3] = ["mx_nm", "my_nm", "mz_nm"];
const FRAME: &str = "frame";

fn row(line: u64, column: &str, message: impl Into<String>) -> Error {
    Error::Row {
        line,
        column: column.into(),
        message: message.into(),
    }
}

/// Where each quantity sits in a row (0-based field indices).
struct Columns {
    target: [usize; 6],
    pose: bool,
    force: [usize; 3],
    moment: Option<[usize; 3]>,
    frame: Option<usize>,
}

/// Parses a path file (module docs); `default_frame` is the wrench frame of rows without one.
///
/// # Errors
/// [`Error::Row`] naming the line and column: an unknown, repeated or missing column, both or
/// neither of the axis-angle and pose columns, a row with another number of fields than the
/// header, a value that is not a finite number (the value shown, shortened), a frame other than
/// `base` or `tool`, no rows, or more than [`MAX_POINTS`].
pub fn parse(text: &str, default_frame: Frame) -> Result<Vec<PathPoint>> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| row(1, "header", e.to_string()))?
        .clone();
    let header_line = header.position().map_or(1, |p| p.line());
    let names: Vec<&str> = header.iter().collect();
    let columns = columns(&names, header_line)?;
    let mut points = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            row(line, "-", e.to_string())
        })?;
        let line = record.position().map_or(0, |p| p.line());
        if record.len() != names.len() {
            return Err(row(
                line,
                "-",
                format!(
                    "expected {} fields as in the header, got {}",
                    names.len(),
                    record.len()
                ),
            ));
        }
        if points.len() == MAX_POINTS {
            return Err(row(
                line,
                "-",
                format!("more than {MAX_POINTS} path points"),
            ));
        }
        points.push(point(&columns, &names, &record, line, default_frame)?);
    }
    if points.is_empty() {
        return Err(row(
            header_line,
            "-",
            "expected at least one path point after the header",
        ));
    }
    Ok(points)
}

fn columns(names: &[&str], line: u64) -> Result<Columns> {
    let known = |n: &str| {
        Q.contains(&n)
            || POSE.contains(&n)
            || FORCE.contains(&n)
            || MOMENT.contains(&n)
            || n == FRAME
    };
    for (i, n) in names.iter().enumerate() {
        if !known(n) {
            return Err(row(
                line,
                n,
                format!(
                    "unknown column (expected {}, {}, {}, optional {} and {FRAME})",
                    Q.join(","),
                    POSE.join(","),
                    FORCE.join(","),
                    MOMENT.join(",")
                ),
            ));
        }
        if names[..i].contains(n) {
            return Err(row(line, n, "the column appears twice"));
        }
    }
    let find = |n: &str| names.iter().position(|h| *h == n);
    let all = |set: &[&str]| -> Result<Option<Vec<usize>>> {
        let found: Vec<Option<usize>> = set.iter().map(|n| find(n)).collect();
        match (
            found.iter().all(Option::is_some),
            found.iter().any(Option::is_some),
        ) {
            (true, _) => Ok(Some(found.into_iter().flatten().collect())),
            (false, false) => Ok(None),
            (false, true) => {
                let missing = set
                    .iter()
                    .zip(&found)
                    .find(|(_, f)| f.is_none())
                    .map_or("", |(n, _)| n);
                Err(row(
                    line,
                    missing,
                    format!("missing column: {} go together", set.join(",")),
                ))
            }
        }
    };
    let q = all(&Q)?;
    let pose = all(&POSE)?;
    let (target, is_pose) = match (q, pose) {
        (Some(q), None) => (q, false),
        (None, Some(p)) => (p, true),
        (Some(_), Some(_)) => {
            return Err(row(
                line,
                "q1_deg",
                "give either the axis angles q1_deg..q6_deg or the pose x_mm..rz_deg, not both",
            ))
        }
        (None, None) => {
            return Err(row(
                line,
                "q1_deg",
                format!(
                    "missing columns: expected the axis angles {} or the TCP pose {}",
                    Q.join(","),
                    POSE.join(",")
                ),
            ))
        }
    };
    let force = all(&FORCE)?.ok_or_else(|| {
        row(
            line,
            "fx_n",
            format!("missing columns: expected the force {}", FORCE.join(",")),
        )
    })?;
    let as3 = |v: Vec<usize>| [v[0], v[1], v[2]];
    Ok(Columns {
        target: [
            target[0], target[1], target[2], target[3], target[4], target[5],
        ],
        pose: is_pose,
        force: as3(force),
        moment: all(&MOMENT)?.map(as3),
        frame: find(FRAME),
    })
}

fn number(record: &csv::StringRecord, names: &[&str], i: usize, line: u64) -> Result<f64> {
    let text = &record[i];
    let shown: String = text.chars().take(24).collect();
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(row(
            line,
            names[i],
            format!("'{shown}' is not a finite number"),
        )),
        Err(_) => Err(row(line, names[i], format!("'{shown}' is not a number"))),
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
    let t: Vec<f64> = c.target.iter().map(|&i| get(i)).collect::<Result<_>>()?;
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
        wrench[k] = get(i)?;
    }
    if let Some(m) = &c.moment {
        for (k, &i) in m.iter().enumerate() {
            wrench[3 + k] = get(i)?;
        }
    }
    let frame = match c.frame.map(|i| &record[i]) {
        None | Some("") => default_frame,
        Some("base") => Frame::Base,
        Some("tool") => Frame::Tool,
        Some(other) => {
            let shown: String = other.chars().take(24).collect();
            return Err(row(
                line,
                FRAME,
                format!("'{shown}': expected base or tool"),
            ));
        }
    };
    Ok(PathPoint {
        line,
        target,
        wrench,
        frame,
    })
}
