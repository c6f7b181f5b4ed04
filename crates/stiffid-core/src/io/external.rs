//! The external axis columns of the data files (postures, readings, measurements, paths): one
//! column per external axis of the cell after the joint columns, named `e1_mm`, `e2_deg`, ...
//! in the cell's order ([`crate::robot::external::ExternalAxes::column_names`]): mm for a
//! linear axis, deg for a rotary one. Read here without the cell (any of [`NAMES`]); the values
//! are checked against the cell's axes where the file meets the robot
//! ([`crate::robot::external::ExternalAxes::check`]).

use crate::common::error::ColumnProblem;
use crate::common::limits;
use crate::robot::external::{ExternalAxes, ExternalValues, MAX_AXES};
use crate::{Error, Result};

/// Every external axis column a file may hold: `e1_mm`, `e1_deg`, ... `e5_mm`, `e5_deg`.
pub const NAMES: [&str; 2 * MAX_AXES] = [
    "e1_mm", "e1_deg", "e2_mm", "e2_deg", "e3_mm", "e3_deg", "e4_mm", "e4_deg", "e5_mm", "e5_deg",
];

/// Where a file's external axis values sit: per axis in the cell's order, its column (0-based)
/// and whether it is in deg (else mm).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Columns {
    columns: Vec<(usize, bool)>,
}

impl Columns {
    /// The external axis columns of a header (`names`, at `line`): `e1_*` to `ek_*` with no
    /// gap, each once, in mm or deg; none when the file has none.
    ///
    /// # Errors
    /// [`Error::Column`] at `line`: an axis given in both units (`e2_mm` and `e2_deg`), or a gap
    /// (`e2_mm` without `e1_*`: missing column `e1_mm or e1_deg`).
    pub fn find<S: AsRef<str>>(names: &[S], line: u64) -> Result<Self> {
        let position = |name: &str| names.iter().position(|n| n.as_ref() == name);
        let mut columns = Vec::new();
        for axis in 0..MAX_AXES {
            let (mm, deg) = (NAMES[2 * axis], NAMES[2 * axis + 1]);
            match (position(mm), position(deg)) {
                (Some(_), Some(_)) => {
                    return Err(column_error(
                        line,
                        ColumnProblem::Conflict {
                            first: mm.into(),
                            second: deg.into(),
                        },
                    ))
                }
                (Some(c), None) => columns.push((c, false)),
                (None, Some(c)) => columns.push((c, true)),
                (None, None) => {
                    if NAMES[2 * axis + 2..].iter().any(|n| position(n).is_some()) {
                        return Err(crate::io::missing(line, &format!("{mm} or {deg}")));
                    }
                    break;
                }
            }
        }
        Ok(Self { columns })
    }

    /// The columns of the cell's external axes (`cell`'s, none without), in the cell's order:
    /// `Columns::find` with each column named as the cell names it
    /// ([`ExternalAxes::column_names`]: the unit its axis's kind takes).
    ///
    /// # Errors
    /// [`Error::Column`] at `line`: [`ColumnProblem::Measurement`] naming a column of the form of
    /// an external axis's (`e<digits>_mm` or `e<digits>_deg`, `external_like`) that the cell
    /// lacks or gives in the other unit, the message listing the cell's axes;
    /// [`ColumnProblem::Missing`] for an axis of the cell without its column.
    pub fn against(names: &[String], line: u64, cell: Option<&ExternalAxes>) -> Result<Self> {
        let wanted = cell.map(ExternalAxes::column_names).unwrap_or_default();
        let described = || match cell {
            None => "the cell has no external axes".to_string(),
            Some(x) => {
                let list: Vec<String> = (x.column_names().iter().zip(x.axes()))
                    .map(|(c, a)| format!("{c} ({})", limits::short(&a.name)))
                    .collect();
                format!("the cell's external axes are {}", list.join(", "))
            }
        };
        for (i, name) in names.iter().enumerate() {
            if external_like(name) && !wanted.contains(name) {
                let message = format!("no external axis has this column: {}", described());
                return Err(Error::Column {
                    line,
                    column: Some(i + 1),
                    name: name.clone(),
                    problem: ColumnProblem::Measurement { message },
                });
            }
        }
        if let Some(w) = wanted.iter().find(|w| !names.contains(w)) {
            return Err(crate::io::missing(line, w));
        }
        Self::find(names, line)
    }

    /// The column of the first axis, when the file gives any.
    pub(crate) fn first(&self) -> Option<usize> {
        self.columns.first().map(|c| c.0)
    }

    /// The column (0-based) of axis `k` (0-based, the cell's order).
    pub(crate) fn column(&self, k: usize) -> usize {
        self.columns[k].0
    }

    /// The values of one row (SI: mm to m, deg to rad), whose field `i` is `field(i)`;
    /// `error(column, problem)` places a problem in the row.
    ///
    /// # Errors
    /// What `error` makes of a field that is not a finite number or lies outside
    /// [`limits::LENGTH_MM`] or [`limits::ANGLE_DEG`].
    pub fn values<'a>(
        &self,
        field: impl Fn(usize) -> &'a str,
        error: impl Fn(usize, ColumnProblem) -> Error,
    ) -> Result<ExternalValues> {
        let mut values = [0.0; MAX_AXES];
        for (k, &(c, degrees)) in self.columns.iter().enumerate() {
            let text = field(c).trim();
            let v: f64 = (text.parse().ok())
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| {
                    error(
                        c,
                        ColumnProblem::NotANumber {
                            value: limits::short(text),
                        },
                    )
                })?;
            let (range, name) = match degrees {
                true => (&limits::ANGLE_DEG, NAMES[2 * k + 1]),
                false => (&limits::LENGTH_MM, NAMES[2 * k]),
            };
            if !range.contains(v) {
                return Err(error(c, range.outside(name, v)));
            }
            values[k] = match degrees {
                true => v.to_radians(),
                false => v * 1e-3,
            };
        }
        ExternalValues::new(&values[..self.columns.len()])
    }
}

/// Whether a column's name has the form of an external axis's: `e<digits>_mm` or
/// `e<digits>_deg`.
pub(crate) fn external_like(name: &str) -> bool {
    let Some(rest) = name.strip_prefix('e') else {
        return false;
    };
    let Some((digits, unit)) = rest.split_once('_') else {
        return false;
    };
    !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) && matches!(unit, "mm" | "deg")
}

fn column_error(line: u64, problem: ColumnProblem) -> Error {
    Error::Column {
        line,
        column: None,
        name: String::new(),
        problem,
    }
}
