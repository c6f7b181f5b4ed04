//! `map.csv` of `stiffid compensate --map --report`: the error bound, deflection, condition
//! number and distance to the joint limits of every path point at every rotation about the
//! spindle (its figure: [`stiffid_figures::compensate::map`]).

use stiffid::machining::compensate::Map;

/// The CSV of `map` (`map.csv`): one row per path point and rotation, units in the header.
pub fn csv(map: &Map) -> String {
    let mut out = String::from(
        "point,line,tool_rotation_deg,bound_mm,deflection_mm,condition,limit_distance_deg,chosen\n",
    );
    let cell = |v: f64, scale: f64| match v.is_finite() {
        true => format!("{:.9}", v * scale),
        false => String::new(),
    };
    for i in 0..map.bound.nrows() {
        for (k, a) in map.angles.iter().enumerate() {
            let chosen = map.chosen.get(i).is_some_and(|c| (c - a).abs() < 1e-9);
            out += &format!(
                "{},{},{:.6},{},{},{},{},{}\n",
                i + 1,
                map.lines.get(i).copied().unwrap_or(0),
                a.to_degrees(),
                cell(map.bound[(i, k)], 1e3),
                cell(map.deflection[(i, k)], 1e3),
                cell(map.condition[(i, k)], 1.0),
                cell(map.limit_distance[(i, k)], 180.0 / std::f64::consts::PI),
                u8::from(chosen)
            );
        }
    }
    out
}
