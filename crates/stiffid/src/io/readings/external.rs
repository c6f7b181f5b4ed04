//! The external axis columns of a readings file: which columns hold the cell's axes, and a column
//! of an axis the cell lacks refused naming the cell's axes.

use super::problem;
use crate::common::error::ColumnProblem;
use crate::common::limits::short;
use crate::{Result, Robot};

/// Whether a column's name has the form of an external axis's: `e<digits>_mm` or
/// `e<digits>_deg`.
pub(super) fn external_like(name: &str) -> bool {
    let Some(rest) = name.strip_prefix('e') else {
        return false;
    };
    let Some((digits, unit)) = rest.split_once('_') else {
        return false;
    };
    !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) && matches!(unit, "mm" | "deg")
}

/// The columns of the cell's external axes (`robot`'s, [`crate::robot::ExternalAxes`]), in the
/// cell's order.
///
/// # Errors
/// [`ColumnProblem::Measurement`] naming a column of an axis the cell lacks (or of an axis in
/// the other unit); [`ColumnProblem::Missing`] for an axis without its column.
pub(super) fn external_columns(names: &[String], line: u64, robot: &Robot) -> Result<Vec<usize>> {
    let wanted = robot
        .external()
        .map(|x| x.column_names())
        .unwrap_or_default();
    let described = || match robot.external() {
        None => "the cell has no external axes".to_string(),
        Some(x) => {
            let list: Vec<String> = (x.column_names().iter().zip(x.axes()))
                .map(|(c, a)| format!("{c} ({})", short(&a.name)))
                .collect();
            format!("the cell's external axes are {}", list.join(", "))
        }
    };
    for (i, name) in names.iter().enumerate() {
        if external_like(name) && !wanted.contains(name) {
            let message = format!("no external axis has this column: {}", described());
            return Err(problem(
                line,
                Some(i + 1),
                name,
                ColumnProblem::Measurement { message },
            ));
        }
    }
    wanted
        .iter()
        .map(|w| (names.iter().position(|n| n == w)).ok_or_else(|| crate::io::missing(line, w)))
        .collect()
}
