//! Measurement files: CSV, one row per posture and measuring point, units in the header.
//!
//! ```text
//! posture,point,q1_deg,...,q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm],dx_mm,dy_mm,dz_mm
//! ```
//! - `posture`: a label; rows of one posture share it (and their axis angles).
//! - `point`: the measuring point, numbered from 1 as in the setup's `measuring_points_mm`.
//! - `q1_deg..q6_deg`: axis angles, deg. `fx_n..mz_nm`: the wrench at the loading point, base
//!   frame, N and Nm; the moment columns are optional (all three or none; none means zero).
//! - `dx_mm..dz_mm`: translation of the measuring point, loaded minus unloaded, base frame, mm; or
//!   instead the six columns `x_loaded_mm,y_loaded_mm,z_loaded_mm,x_unloaded_mm,y_unloaded_mm,
//!   z_unloaded_mm` (positions, which are subtracted).
//!
//! Columns may come in any order; lines starting with `#` are comments. Errors name the line and
//! column.

use anyhow::{anyhow, bail, Context, Result};
use nalgebra::{Vector3, Vector6};
use std::path::Path;
use stiffid::identify::Measurement;

const POSTURE: &str = "posture";
const POINT: &str = "point";
const Q: [&str; 6] = ["q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg"];
const FORCE: [&str; 3] = ["fx_n", "fy_n", "fz_n"];
const MOMENT: [&str; 3] = ["mx_nm", "my_nm", "mz_nm"];
const DISPLACEMENT: [&str; 3] = ["dx_mm", "dy_mm", "dz_mm"];
const LOADED: [&str; 3] = ["x_loaded_mm", "y_loaded_mm", "z_loaded_mm"];
const UNLOADED: [&str; 3] = ["x_unloaded_mm", "y_unloaded_mm", "z_unloaded_mm"];

/// The measurements of a file and where each came from.
pub struct Data {
    /// One per row, SI units, point 0-based.
    pub measurements: Vec<Measurement>,
    /// The line of each measurement in the file.
    lines: Vec<u64>,
    /// The header, to name columns in errors.
    header: Vec<String>,
    /// Where each quantity is in a row.
    columns: Columns,
}

/// Reads a measurement file. Errors start with the file name, then the line and column.
pub fn read(path: &Path) -> Result<Data> {
    let text = crate::load::read(path)?;
    parse(&text).with_context(|| path.display().to_string())
}

/// Parses the text of a measurement file (see the module docs).
pub fn parse(text: &str) -> Result<Data> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header_record = reader.headers().context("line 1: cannot read the header")?;
    let line_of_header = header_record.position().map_or(1, |p| p.line());
    let header: Vec<String> = header_record.iter().map(str::to_string).collect();
    if header.iter().all(|h| h.is_empty()) {
        bail!(
            "the file is empty: expected the header '{}' and one row per measurement",
            expected_header()
        );
    }
    let columns = Columns::new(&header, line_of_header)?;
    let (mut measurements, mut lines) = (Vec::new(), Vec::new());
    for record in reader.records() {
        let record = record.context("cannot read a row")?;
        let line = record.position().map_or(0, |p| p.line());
        if record.len() != header.len() {
            bail!(
                "line {line}: expected {} fields as in the header, got {}",
                header.len(),
                record.len()
            );
        }
        measurements.push(columns.measurement(&record, line, &header)?);
        lines.push(line);
    }
    if measurements.is_empty() {
        bail!("expected at least one measurement row after the header");
    }
    Ok(Data {
        measurements,
        lines,
        header,
        columns,
    })
}

fn expected_header() -> String {
    let mut names = vec![POSTURE, POINT];
    names.extend(Q);
    names.extend(FORCE);
    names.extend(DISPLACEMENT);
    names.join(",")
}

/// Where each quantity sits in a row (0-based field indices).
struct Columns {
    posture: usize,
    point: usize,
    q: [usize; 6],
    force: [usize; 3],
    moment: Option<[usize; 3]>,
    displacement: Displacement,
}

enum Displacement {
    Relative([usize; 3]),
    Positions([usize; 3], [usize; 3]),
}

impl Columns {
    fn new(header: &[String], line: u64) -> Result<Self> {
        for (i, name) in header.iter().enumerate() {
            if !known().any(|k| k == name) {
                let hint =
                    suggestion(name).map_or(String::new(), |s| format!(" (did you mean '{s}'?)"));
                bail!(
                    "line {line}, column {}: unknown column '{name}'{hint}; expected {} (moments {} optional; or {} and {} instead of the d columns)",
                    i + 1,
                    expected_header(),
                    MOMENT.join(","),
                    LOADED.join(","),
                    UNLOADED.join(",")
                );
            }
            if header[..i].contains(name) {
                bail!(
                    "line {line}, column {}: column '{name}' appears twice",
                    i + 1
                );
            }
        }
        let find = |name: &str| header.iter().position(|h| h == name);
        let need =
            |name: &str| find(name).ok_or_else(|| anyhow!("line {line}: missing column '{name}'"));
        let need3 = |names: [&str; 3]| -> Result<[usize; 3]> {
            Ok([need(names[0])?, need(names[1])?, need(names[2])?])
        };
        let any = |names: &[&str]| names.iter().any(|n| find(n).is_some());
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
        let force = need3(FORCE)?;
        let moment = match any(&MOMENT) {
            true => Some(need3(MOMENT)?),
            false => None,
        };
        let displacement = match (any(&DISPLACEMENT), any(&LOADED) || any(&UNLOADED)) {
            (true, true) => bail!(
                "line {line}: give either {} or the loaded and unloaded positions, not both",
                DISPLACEMENT.join(",")
            ),
            (false, true) => Displacement::Positions(need3(LOADED)?, need3(UNLOADED)?),
            _ => Displacement::Relative(need3(DISPLACEMENT)?),
        };
        Ok(Self {
            posture,
            point,
            q,
            force,
            moment,
            displacement,
        })
    }

    fn measurement(
        &self,
        record: &csv::StringRecord,
        line: u64,
        header: &[String],
    ) -> Result<Measurement> {
        let number = |i: usize| -> Result<f64> {
            let field = &record[i];
            field
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    anyhow!(
                        "line {line}, column {} ({}): '{field}' is not a finite number",
                        i + 1,
                        header[i]
                    )
                })
        };
        let vector3 = |c: [usize; 3]| -> Result<Vector3<f64>> {
            Ok(Vector3::new(number(c[0])?, number(c[1])?, number(c[2])?))
        };
        let posture = record[self.posture].to_string();
        if posture.is_empty() {
            bail!(
                "line {line}, column {} (posture): empty posture label",
                self.posture + 1
            );
        }
        let point = record[self.point]
            .parse::<usize>()
            .ok()
            .filter(|p| *p >= 1)
            .ok_or_else(|| {
                anyhow!(
                    "line {line}, column {} (point): '{}' is not a measuring point number (1, 2, ...)",
                    self.point + 1,
                    &record[self.point]
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

fn known() -> impl Iterator<Item = &'static str> {
    [POSTURE, POINT]
        .into_iter()
        .chain(Q)
        .chain(FORCE)
        .chain(MOMENT)
        .chain(DISPLACEMENT)
        .chain(LOADED)
        .chain(UNLOADED)
}

/// The known column a misspelled one probably meant: the same but for case or a missing unit
/// suffix (`q4` for `q4_deg`), or at most two edits away.
fn suggestion(name: &str) -> Option<&'static str> {
    let lower = name.to_lowercase();
    let unit_missing = |k: &str| {
        k.strip_prefix(lower.as_str())
            .is_some_and(|r| r.starts_with('_'))
    };
    known().find(|k| unit_missing(k)).or_else(|| {
        known()
            .map(|k| (edit_distance(&lower, k), k))
            .filter(|(d, _)| *d <= 2)
            .min()
            .map(|(_, k)| k)
    })
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (diagonal + usize::from(ca != *cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

impl Data {
    /// The line in the file of measurement `i` (0-based).
    pub fn line(&self, i: usize) -> u64 {
        self.lines[i]
    }

    /// Turns a library error about one of these measurements ([`stiffid::Error::Measurement`])
    /// into one naming its line and column; other errors pass through.
    pub fn explain(&self, error: stiffid::Error) -> anyhow::Error {
        let stiffid::Error::Measurement {
            number,
            field,
            message,
        } = error
        else {
            return error.into();
        };
        let c = &self.columns;
        let column = match field.as_str() {
            "point" => c.point,
            "wrench" => c.force[0],
            "displacement" => match c.displacement {
                Displacement::Relative(d) => d[0],
                Displacement::Positions(l, _) => l[0],
            },
            axis => axis
                .strip_prefix('q')
                .and_then(|a| a.parse::<usize>().ok())
                .and_then(|a| c.q.get(a.wrapping_sub(1)).copied())
                .unwrap_or(c.posture),
        };
        let line = self.lines.get(number.wrapping_sub(1)).copied().unwrap_or(0);
        anyhow!(
            "line {line}, column {} ({}): {message}",
            column + 1,
            self.header[column]
        )
    }
}
