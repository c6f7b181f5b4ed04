//! `[controller] radius_wear_mm`: the wear offsets of the tools' radii the controller holds,
//! by the number a G-code's `D` word names (`{ 1 = -0.02, 4 = 0.01 }`, mm): cutter radius
//! compensation offsets by the process's tool radius plus this wear, as a CNC adds its wear
//! offset to the geometry offset of the same number.

use crate::{Error, Result};
use std::collections::BTreeMap;

/// The largest wear accepted, mm (either sign).
const MAX_WEAR_MM: f64 = 10.0;

/// The table read: each number's wear, m, in number order.
///
/// # Errors
/// [`Error::InvalidField`] naming `controller.radius_wear_mm.N` for a key that is not a whole
/// number from 0 to 1000000, or a wear that is not finite or beyond 10 mm.
pub(super) fn read(table: &BTreeMap<String, f64>) -> Result<Vec<(u32, f64)>> {
    let mut out = Vec::with_capacity(table.len());
    for (key, wear) in table {
        let field = format!("controller.radius_wear_mm.{key}");
        let number = key.trim().parse::<u32>().ok().filter(|n| *n <= 1_000_000);
        let Some(number) = number else {
            return Err(Error::InvalidField {
                field,
                message: "expected the number D names, a whole number from 0 to 1000000".into(),
            });
        };
        if !(wear.is_finite() && wear.abs() <= MAX_WEAR_MM) {
            return Err(Error::InvalidField {
                field,
                message: format!(
                    "expected a wear of the radius within +-{MAX_WEAR_MM} mm, got {}",
                    crate::common::words::number(*wear)
                ),
            });
        }
        out.push((number, wear * 1e-3));
    }
    out.sort_by_key(|(n, _)| *n);
    Ok(out)
}
