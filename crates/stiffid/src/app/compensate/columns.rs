//! The columns of the compensate CSV and of every JSON point ([`header`], [`values`]), and the
//! CSV's lines ([`csv_line`]).

use nalgebra::Vector6;
use stiffid_core::robot::ExternalAxes;
use stiffid_machining::compensate::Compensated;
use stiffid_machining::dynamics::Dynamics;

fn names(prefix: &str, items: &[&str], unit: &str) -> Vec<String> {
    items.iter().map(|i| format!("{prefix}{i}{unit}")).collect()
}

/// The column names of the CSV (and the keys of a [`Row`](super::document::Row)).
pub fn header() -> Vec<String> {
    let axes = ["1", "2", "3", "4", "5", "6"];
    let xyz = ["x", "y", "z"];
    let mut header = vec!["point".to_string(), "line".to_string()];
    header.extend(names("q", &axes, "_deg"));
    header.extend(names("", &xyz, "_mm"));
    header.extend(names("r", &xyz, "_deg"));
    header.extend(names("f", &xyz, "_base_n"));
    header.extend(names("m", &xyz, "_base_nm"));
    header.extend(names("d", &xyz, "_mm"));
    header.push("d_norm_mm".into());
    header.extend(names("dr", &xyz, "_mrad"));
    header.extend(names("d", &xyz, "_std_mm"));
    header.extend(names("dr", &xyz, "_std_mrad"));
    header.extend(names("qc", &axes, "_deg"));
    for name in [
        "residual_um",
        "residual_urad",
        "iterations",
        "tool_rotation_deg",
        "lead_deg",
        "tilt_deg",
        "d_norm_before_mm",
    ] {
        header.push(name.into());
    }
    for c in xyz {
        header.push(format!("d{c}_lower_mm"));
        header.push(format!("d{c}_upper_mm"));
    }
    header.push("extrapolates".into());
    header.extend(DYNAMICS.map(String::from));
    header.extend(super::budget::COLUMNS.map(String::from));
    header
}

/// The columns of a point's dynamics ([`stiffid_machining::dynamics`]): at a drilling exit the
/// breakthrough surge, its standard deviation, the held effective mass along the drill and, with
/// the free tool axis, the surge at the path's own rotation; at a milling point the first natural
/// frequency and the tooth-passing frequency.
pub const DYNAMICS: [&str; 6] = [
    "surge_mm_s",
    "surge_std_mm_s",
    "effective_mass_kg",
    "surge_before_mm_s",
    "first_frequency_hz",
    "tooth_passing_hz",
];

/// The values of point `i` (0-based) from `line` of its file with its dynamics `dynamics`, one
/// per column of [`header`] (mm, deg, N, Nm, mrad, um, urad, mm/s, kg, Hz); `None` for an empty
/// cell.
pub fn values(i: usize, line: u64, r: &Compensated, dynamics: &Dynamics) -> Vec<Option<f64>> {
    let deg = |q: &Vector6<f64>| q.iter().map(|v| Some(v.to_degrees())).collect::<Vec<_>>();
    let [rx, ry, rz] = stiffid_core::robot::file::rpy(&r.pose.rotation);
    let p = r.pose.translation.vector * 1e3;
    let d = &r.deflection;
    let mut v = vec![Some(i as f64 + 1.0), Some(line as f64)];
    v.extend(deg(&r.q));
    v.extend([p.x, p.y, p.z].map(Some));
    v.extend([rx, ry, rz].map(|a| Some(a.to_degrees())));
    v.extend(r.wrench.iter().map(|w| Some(*w)));
    v.extend((0..3).map(|k| Some(d[k] * 1e3)));
    v.push(Some(d.fixed_rows::<3>(0).norm() * 1e3));
    v.extend((3..6).map(|k| Some(d[k] * 1e3)));
    v.extend((0..6).map(|k| r.deflection_std.map(|s| s[k] * 1e3)));
    v.extend(deg(&r.q_compensated));
    v.extend([
        Some(r.residual_position * 1e6),
        Some(r.residual_rotation * 1e6),
        Some(r.iterations as f64),
        Some(r.tool_rotation.to_degrees()),
        Some(r.lead.to_degrees()),
        Some(r.tilt.to_degrees()),
        r.deflection_before
            .map(|b| b.fixed_rows::<3>(0).norm() * 1e3),
    ]);
    let ends = |k: usize| r.deflection_interval.map(|i| i[k / 2][k % 2] * 1e3);
    v.extend((0..6).map(|k| ends(k).filter(|e| e.is_finite())));
    v.push(
        r.outside_region
            .as_ref()
            .map(|o| f64::from(u8::from(!o.is_empty()))),
    );
    let surge = dynamics.surge.as_ref();
    v.extend([
        surge.map(|s| s.speed * 1e3),
        surge.and_then(|s| s.speed_std).map(|s| s * 1e3),
        surge.map(|s| s.mass),
        dynamics.surge_before.map(|s| s.speed * 1e3),
        dynamics.first_frequency,
        dynamics.tooth_passing,
    ]);
    v.extend(super::budget::values(r));
    v
}

/// The CSV's columns of the cell's external axes after [`header`]: one per axis in the cell's
/// order, named as path files name them (`e1_mm` for a linear axis, `e2_deg` for a rotary one);
/// none for a robot without external axes.
pub fn external_header(cell: Option<&ExternalAxes>) -> Vec<String> {
    cell.map_or(Vec::new(), ExternalAxes::column_names)
}

/// A point's values of the cell's external axes ([`external_header`]; mm, deg): the station
/// chosen or the values given ([`Compensated::external`]); empty cells where the result holds
/// none.
pub fn external_values(cell: Option<&ExternalAxes>, r: &Compensated) -> Vec<Option<f64>> {
    let Some(cell) = cell else {
        return Vec::new();
    };
    match r.external.as_slice().len() == cell.len() {
        true => (cell.to_display(r.external.as_slice()).into_iter())
            .map(Some)
            .collect(),
        false => vec![None; cell.len()],
    }
}

/// One CSV line of a point's values: 9 decimals (1 nm in mm, 2e-11 rad in deg), trailing zeros
/// dropped, empty cells for missing values.
pub fn csv_line(values: &[Option<f64>]) -> String {
    let cells: Vec<String> = values
        .iter()
        .map(|v| v.map_or(String::new(), cell))
        .collect();
    cells.join(",")
}

/// A number with 9 decimals, trailing zeros dropped.
fn cell(x: f64) -> String {
    let s = format!("{x:.9}");
    match s.trim_end_matches('0').trim_end_matches('.') {
        "-0" => "0".into(),
        t => t.into(),
    }
}
