//! The names the readings give the measured points.

/// The name the readings give a point (their `point` column): `1`, `2`, ... for the tool's
/// measuring point `point` (0-based), `T1`, `T2`, ... for the reflector fixed in the cell
/// `point` (0-based: on the positioner's table, or on a fixed part) when `table`.
pub fn point_name(point: usize, table: bool) -> String {
    match table {
        true => format!("T{}", point + 1),
        false => (point + 1).to_string(),
    }
}
