//! The `[[external_axis]]` tables of robot and setup TOML files: one table per axis, in any
//! order (the cell's order is carrier first, then positioner, each as listed).
//!
//! ```toml
//! [[external_axis]]
//! name = "track"
//! role = "carrier"               # carrier (a linear axis under the arm) | positioner (a rotary
//!                                #   axis under the workpiece)
//! direction = [1.0, 0.0, 0.0]    # cell frame at e = 0 (normalised when read)
//! limits_mm = [0.0, 6000.0]      # linear: limits_mm (required), offset_mm (default 0)
//! offset_mm = 0.0
//! max_speed_mm_s = 1000.0        # optional, linear: the largest speed, mm/s in (0, 10 000]
//! error_motions = [[0.0, 0.05, 0.0, 0.0, 0.1, 0.0]]
//!                                # optional, linear only: one row per order 1..K of
//!                                #   [positioning_mm, straightness_y_mm, straightness_z_mm,
//!                                #    roll_mrad, pitch_mrad, yaw_mrad]
//!
//! [[external_axis]]
//! name = "tilt"
//! role = "positioner"
//! direction = [1.0, 0.0, 0.0]
//! point_mm = [3000.0, 1500.0, 800.0] # a point on the axis's line, cell frame at e = 0
//! limits_deg = [-90.0, 90.0]     # rotary: limits_deg (required), offset_deg (default 0)
//! max_speed_deg_s = 90.0         # optional, rotary: the largest speed, deg/s in (0, 10 000]
//! ```
//!
//! Without a `max_speed_*` the axis has no speed limit.
//!
//! Unknown keys are rejected; a field of the other kind of axis (`limits_deg` on a carrier,
//! `point_mm` on one, `limits_mm` or `error_motions` on a positioner) is an error naming the
//! file, the table (`external_axis[2] (tilt)`, 1-based in the file's order) and the field.

use super::{AxisKind, ErrorMotions, ExternalAxes, ExternalAxis, Role};
use crate::common::limits::{self, check_in};
use crate::{Error, Result};
use nalgebra::{Unit, Vector3};
use serde::Deserialize;
use std::fmt::Write;

/// One `[[external_axis]]` table as written.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct AxisFile {
    name: String,
    role: RoleFile,
    #[serde(deserialize_with = "crate::common::exact::array")]
    direction: [f64; 3],
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    limits_mm: Option<[f64; 2]>,
    offset_mm: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    limits_deg: Option<[f64; 2]>,
    offset_deg: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    point_mm: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option_arrays")]
    error_motions: Option<Vec<[f64; 6]>>,
    max_speed_mm_s: Option<f64>,
    max_speed_deg_s: Option<f64>,
}

#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RoleFile {
    Carrier,
    Positioner,
}

/// The cell's external axes of the tables `tables` (file order) of the file `source_name`;
/// `None` for no tables.
///
/// # Errors
/// [`Error::InvalidField`] naming the file, the table (`external_axis[i] (name)`) and the field for
/// a missing travel (`limits_mm` on a carrier, `limits_deg` on a positioner), a field of the other
/// kind of axis, a zero or non-finite direction, a number outside its range ([`limits::LENGTH_MM`],
/// [`limits::ANGLE_DEG`], [0, 10 000] deg/s or mm/s), error motions beyond 50 mm or 0.1 rad or
/// [`super::MAX_ORDER`], and everything [`ExternalAxes::new`] checks (counts, names, travel).
pub fn build(tables: &[AxisFile], source_name: &str) -> Result<Option<ExternalAxes>> {
    if tables.is_empty() {
        return Ok(None);
    }
    let axes = (tables.iter().enumerate())
        .map(|(i, t)| axis(t, &format!("external_axis[{}]", i + 1), source_name))
        .collect::<Result<Vec<_>>>()?;
    ExternalAxes::new(axes)
        .map(Some)
        .map_err(|e| in_file(e, source_name))
}

/// The cell's external axes of a JSON array of tables with the keys of `[[external_axis]]`
/// (module docs): what a program builds in code (Python's `Robot.with_external_axes`);
/// `source_name` names it in errors. An empty array: none.
///
/// # Errors
/// [`Error::Parse`] for malformed JSON, anything but an array, and unknown or missing keys and
/// wrong types naming the table (`external_axis[i]`, 1-based in the array's order); those of
/// the tables as a file's ([`crate::robot::file::parse`]).
pub fn from_json(text: &str, source_name: &str) -> Result<Option<ExternalAxes>> {
    let parse = |message: String| Error::Parse {
        source_name: source_name.to_string(),
        message,
    };
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| parse(limits::one_line(&e.to_string())))?;
    let serde_json::Value::Array(items) = value else {
        return Err(parse(format!(
            "expected a list of tables, one per external axis, got {}",
            limits::short(&value.to_string())
        )));
    };
    // Each table read from its value: serde's message then names no position in the text.
    let tables = (items.into_iter().enumerate())
        .map(|(i, item)| {
            AxisFile::deserialize(item).map_err(|e| {
                parse(format!(
                    "external_axis[{}]: {}",
                    i + 1,
                    limits::one_line(&e.to_string())
                ))
            })
        })
        .collect::<Result<Vec<_>>>()?;
    build(&tables, source_name)
}

fn axis(t: &AxisFile, table: &str, source_name: &str) -> Result<ExternalAxis> {
    if t.name.trim().is_empty() {
        return Err(invalid(
            source_name,
            &format!("{table}.name"),
            "expected a name",
        ));
    }
    let table = format!("{table} ({})", limits::short(&t.name));
    let field = |f: &str| format!("{table}.{f}");
    let field_in = |f: &str| format!("{source_name}: {table}.{f}");
    check_in(
        source_name,
        &field("direction"),
        &t.direction,
        &limits::DIRECTION,
    )?;
    let direction = Unit::try_new(Vector3::from(t.direction), 1e-9).ok_or_else(|| {
        invalid(
            source_name,
            &field("direction"),
            "expected a non-zero vector (the axis's direction, cell frame)",
        )
    })?;
    let (kind, role) = match t.role {
        RoleFile::Carrier => (AxisKind::Linear, Role::Carrier),
        RoleFile::Positioner => (AxisKind::Rotary, Role::Positioner),
    };
    let Travel {
        lower,
        upper,
        offset,
        point,
        errors,
    } = match kind {
        AxisKind::Linear => linear(t, source_name, &field)?,
        AxisKind::Rotary => rotary(t, source_name, &field)?,
    };
    if lower >= upper {
        let unit = match kind {
            AxisKind::Linear => "limits_mm",
            AxisKind::Rotary => "limits_deg",
        };
        return Err(invalid(
            source_name,
            &field(unit),
            "expected [lower, upper] with lower below upper",
        ));
    }
    let max_speed = match (t.max_speed_mm_s, t.max_speed_deg_s) {
        (Some(v), _) => limits::check_speeds(&field_in("max_speed_mm_s"), &[v]).map(|_| v * 1e-3),
        (_, Some(v)) => {
            limits::check_speeds(&field_in("max_speed_deg_s"), &[v]).map(|_| v.to_radians())
        }
        (None, None) => Ok(f64::INFINITY),
    }?;
    Ok(ExternalAxis {
        name: t.name.clone(),
        kind,
        role,
        direction,
        point,
        offset,
        lower,
        upper,
        errors,
        max_speed,
    })
}

/// An axis's travel `[lower, upper]` and offset (m or rad), the point its line passes (m) and
/// its error motions.
struct Travel {
    lower: f64,
    upper: f64,
    offset: f64,
    point: Vector3<f64>,
    errors: ErrorMotions,
}

/// A linear carrier axis's travel, offset and error motions (mm in the table); the keys of a
/// rotary axis refused.
fn linear(t: &AxisFile, source_name: &str, field: &dyn Fn(&str) -> String) -> Result<Travel> {
    let refuse = |present: bool, f: &str, why: &str| match present {
        true => Err(invalid(source_name, &field(f), why)),
        false => Ok(()),
    };
    let linear =
        "given on a linear carrier axis: a carrier axis takes limits_mm and offset_mm (mm)";
    refuse(t.limits_deg.is_some(), "limits_deg", linear)?;
    refuse(t.offset_deg.is_some(), "offset_deg", linear)?;
    refuse(t.max_speed_deg_s.is_some(), "max_speed_deg_s", linear)?;
    refuse(
        t.point_mm.is_some(),
        "point_mm",
        "given on a linear carrier axis: only a rotary positioner axis has a line through a point",
    )?;
    let Some([lower, upper]) = t.limits_mm else {
        return Err(invalid(
            source_name,
            &field("limits_mm"),
            "missing: expected the axis's travel [lower, upper], mm",
        ));
    };
    let offset = t.offset_mm.unwrap_or(0.0);
    check_in(
        source_name,
        &field("limits_mm"),
        &[lower, upper],
        &limits::LENGTH_MM,
    )?;
    check_in(
        source_name,
        &field("offset_mm"),
        &[offset],
        &limits::LENGTH_MM,
    )?;
    let rows = (t.error_motions.iter().flatten())
        .map(|r| [r[0], r[1], r[2], r[3], r[4], r[5]].map(|v| v * 1e-3))
        .collect();
    let errors = ErrorMotions::new(rows).map_err(|e| {
        let message = match e {
            Error::InvalidField { message, .. } => {
                message.replace("50 mm and 0.1 rad", "50 mm and 100 mrad")
            }
            other => other.to_string(),
        };
        invalid(source_name, &field("error_motions"), &message)
    })?;
    Ok(Travel {
        lower: lower * 1e-3,
        upper: upper * 1e-3,
        offset: offset * 1e-3,
        point: Vector3::zeros(),
        errors,
    })
}

/// A rotary positioner axis's travel, offset and point (deg and mm in the table); the keys of a
/// linear axis refused.
fn rotary(t: &AxisFile, source_name: &str, field: &dyn Fn(&str) -> String) -> Result<Travel> {
    let refuse = |present: bool, f: &str, why: &str| match present {
        true => Err(invalid(source_name, &field(f), why)),
        false => Ok(()),
    };
    let rotary = "given on a rotary positioner axis: a positioner axis takes limits_deg, offset_deg and point_mm";
    refuse(t.limits_mm.is_some(), "limits_mm", rotary)?;
    refuse(t.offset_mm.is_some(), "offset_mm", rotary)?;
    refuse(t.max_speed_mm_s.is_some(), "max_speed_mm_s", rotary)?;
    refuse(
        t.error_motions.is_some(),
        "error_motions",
        "given on a rotary positioner axis: only a linear axis has error motions (a rotary axis's line and offset are its errors)",
    )?;
    let Some([lower, upper]) = t.limits_deg else {
        return Err(invalid(
            source_name,
            &field("limits_deg"),
            "missing: expected the axis's travel [lower, upper], deg",
        ));
    };
    let offset = t.offset_deg.unwrap_or(0.0);
    let point = t.point_mm.unwrap_or_default();
    check_in(
        source_name,
        &field("limits_deg"),
        &[lower, upper],
        &limits::ANGLE_DEG,
    )?;
    check_in(
        source_name,
        &field("offset_deg"),
        &[offset],
        &limits::ANGLE_DEG,
    )?;
    check_in(source_name, &field("point_mm"), &point, &limits::LENGTH_MM)?;
    let rad = f64::to_radians;
    let point = Vector3::from(point) * 1e-3;
    Ok(Travel {
        lower: rad(lower),
        upper: rad(upper),
        offset: rad(offset),
        point,
        errors: ErrorMotions::default(),
    })
}

/// The `[[external_axis]]` tables of `axes`, in the cell's order, numbers in full (shortest
/// round trip): what [`build`] reads back to the same axes.
pub fn toml(axes: &ExternalAxes) -> String {
    let mut t = String::new();
    let list = |v: &[f64]| {
        let items: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
        format!("[{}]", items.join(", "))
    };
    for a in axes.axes() {
        let _ = writeln!(t, "\n[[external_axis]]");
        let _ = writeln!(t, "name = {}", quoted(&a.name));
        let d = a.direction.into_inner();
        match a.kind {
            AxisKind::Linear => {
                let _ = writeln!(t, "role = \"carrier\"");
                let _ = writeln!(t, "direction = {}", list(d.as_slice()));
                let _ = writeln!(t, "limits_mm = {}", list(&[a.lower * 1e3, a.upper * 1e3]));
                let _ = writeln!(t, "offset_mm = {:?}", a.offset * 1e3);
                if a.max_speed.is_finite() {
                    let _ = writeln!(t, "max_speed_mm_s = {:?}", a.max_speed * 1e3);
                }
                if !a.errors.is_empty() {
                    let rows: Vec<String> = (a.errors.coefficients().iter())
                        .map(|r| list(&r.map(|v| v * 1e3)))
                        .collect();
                    let _ = writeln!(t, "error_motions = [{}]", rows.join(", "));
                }
            }
            AxisKind::Rotary => {
                let _ = writeln!(t, "role = \"positioner\"");
                let _ = writeln!(t, "direction = {}", list(d.as_slice()));
                let _ = writeln!(t, "point_mm = {}", list((a.point * 1e3).as_slice()));
                let deg = [a.lower.to_degrees(), a.upper.to_degrees()];
                let _ = writeln!(t, "limits_deg = {}", list(&deg));
                let _ = writeln!(t, "offset_deg = {:?}", a.offset.to_degrees());
                if a.max_speed.is_finite() {
                    let _ = writeln!(t, "max_speed_deg_s = {:?}", a.max_speed.to_degrees());
                }
            }
        }
    }
    t
}

/// `s` as a TOML basic string.
fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

fn invalid(source_name: &str, field: &str, message: &str) -> Error {
    Error::InvalidField {
        field: format!("{source_name}: {field}"),
        message: message.to_string(),
    }
}

fn in_file(e: Error, source_name: &str) -> Error {
    match e {
        Error::InvalidField { field, message } => Error::InvalidField {
            field: format!("{source_name}: {field}"),
            message,
        },
        other => other,
    }
}
