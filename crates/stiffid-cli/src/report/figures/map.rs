//! `map.csv` of `stiffid compensate --map --report`: the error bound, deflection, condition
//! number and distances to the joint limits and the cell's bodies of every path point at every
//! rotation about the spindle or track station (its figure: [`stiffid_figures::compensate::map`]).

use stiffid::internal::machining::compensate::{Map, MapVariable};
use stiffid_figures::compensate::map::axis;

/// The CSV of `map` (`map.csv`): one row per path point and value of the variable (the
/// rotation, `tool_rotation_deg`, or the station's offset, `station_offset_mm`), units in the
/// header; `collision_distance_mm` empty without a cell floor or obstacles.
pub fn csv(map: &Map) -> String {
    let column = match map.variable {
        MapVariable::Rotation => "tool_rotation_deg",
        MapVariable::Track => "station_offset_mm",
    };
    let mut out = format!(
        "point,line,{column},bound_mm,deflection_mm,condition,limit_distance_deg,collision_distance_mm,chosen\n",
    );
    let cell = |v: f64, scale: f64| match v.is_finite() {
        true => format!("{:.9}", v * scale),
        false => String::new(),
    };
    let (values, ..) = axis(map);
    let si: &[f64] = match map.variable {
        MapVariable::Rotation => &map.angles,
        MapVariable::Track => &map.stations,
    };
    for i in 0..map.bound.nrows() {
        for (k, (a, shown)) in si.iter().zip(&values).enumerate() {
            let chosen = map.chosen.get(i).is_some_and(|c| (c - a).abs() < 1e-9);
            let collision = map
                .collision_distance
                .as_ref()
                .map_or(f64::NAN, |c| c[(i, k)]);
            out += &format!(
                "{},{},{:.6},{},{},{},{},{},{}\n",
                i + 1,
                map.lines.get(i).copied().unwrap_or(0),
                shown,
                cell(map.bound[(i, k)], 1e3),
                cell(map.deflection[(i, k)], 1e3),
                cell(map.condition[(i, k)], 1.0),
                cell(map.limit_distance[(i, k)], 180.0 / std::f64::consts::PI),
                cell(collision, 1e3),
                u8::from(chosen)
            );
        }
    }
    out
}
