//! The direction columns of a readings file: `dir1..dir6`, the sign of each joint's last motion
//! before the reading (-1 or +1), for a backlash term (docs/model.md, "Joint error maps").
//!
//! All six or none; a value other than `-1`, `1` or `+1` is refused naming the line and column.

use super::Row;
use crate::common::error::ColumnProblem;
use crate::Result;
use nalgebra::Vector6;

/// The direction columns' names, joint order.
pub(crate) const DIR: [&str; 6] = ["dir1", "dir2", "dir3", "dir4", "dir5", "dir6"];

/// The direction columns in `names` (0-based), `None` when the header has none.
///
/// # Errors
/// [`crate::Error::Column`] (`Missing`) naming the first direction column absent when another
/// is given.
pub(super) fn columns(names: &[String], line: u64) -> Result<Option<[usize; 6]>> {
    let find = |name: &str| names.iter().position(|n| n == name);
    if DIR.iter().all(|n| find(n).is_none()) {
        return Ok(None);
    }
    let mut out = [0; 6];
    for (c, name) in out.iter_mut().zip(DIR) {
        *c = find(name).ok_or_else(|| super::super::missing(line, name))?;
    }
    Ok(Some(out))
}

/// The directions of `row` in `columns` (each -1.0 or 1.0), `None` without columns.
///
/// # Errors
/// [`crate::Error::Column`] (`Choice`) naming the line and column of a field that is not `-1`,
/// `1` or `+1`.
pub(super) fn values(row: &Row, columns: Option<[usize; 6]>) -> Result<Option<Vector6<f64>>> {
    let Some(columns) = columns else {
        return Ok(None);
    };
    let mut out = Vector6::zeros();
    for (joint, &c) in columns.iter().enumerate() {
        out[joint] = match row.field(c) {
            "1" | "+1" => 1.0,
            "-1" => -1.0,
            other => {
                let value = crate::common::limits::short(other);
                let expected = "-1 or +1 (the sign of the joint's last motion)";
                return Err(row.error(c, ColumnProblem::Choice { value, expected }));
            }
        };
    }
    Ok(Some(out))
}
