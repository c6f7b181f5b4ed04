//! The names the readings give the measured points.

/// The name the readings give a point (their `point` column): `1`, `2`, ... for the tool's
/// measuring point `point` (0-based), `T1`, `T2`, ... for the positioner table's reflector
/// `point` (0-based) when `table`.
pub fn point_name(point: usize, table: bool) -> String {
    match table {
        true => format!("T{}", point + 1),
        false => (point + 1).to_string(),
    }
}
