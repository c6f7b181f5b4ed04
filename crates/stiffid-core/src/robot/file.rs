//! Robot files in TOML: a DH table with units in the field names.
//!
//! ```toml
//! name = "COMAU SMART5 NJ 165-3.0"
//! source = "where the numbers come from"
//! convention = "modified-dh"            # or "standard-dh"
//! max_speed_deg_s = [110, 110, 110, 180, 180, 260]
//!                                       # optional: each axis's largest speed, deg/s, each in
//!                                       #   (0, 10 000] or inf (that axis unlimited); none: no
//!                                       #   limit (the compensate job keeps every axis within
//!                                       #   it at the program's feed)
//! [[joint]]                             # six, base to flange
//! a_mm = 0.0
//! alpha_deg = 0.0
//! d_mm = 830.0
//! theta_offset_deg = 0.0                # optional, default 0
//! beta_deg = 0.0                        # optional, default 0: Hayati's rotation about y
//! mass_kg = 250.0                       # optional (all six or none): the link's mass
//! com_mm = [0, 0, 0]                    #   and its centre in the joint's frame (with mass_kg)
//! inertia_kg_m2 = [12, 10, 8, 0, 0, 0]  # optional: [ixx, iyy, izz, ixy, ixz, iyz] about the
//!                                       #   centre, joint frame's axes (default zero)
//! lower_deg = -175.0                    # axis (controller) coordinates
//! upper_deg = 175.0
//! error_map = { cos_deg = [0.001, 0.0002], sin_deg = [-0.0005, 0.0] }
//!                                       # optional: the axis's angle error (deg) at axis angle q,
//!                                       #   sum_h cos_deg[h-1] cos(h q) + sin_deg[h-1] sin(h q)
//!                                       #   (each list optional, default empty), plus
//!                                       #   half_backlash_deg (optional, default 0) times the
//!                                       #   sign of the last motion where a reading has one
//! # ... five more [[joint]] tables
//! [axis_map]                            # optional: theta = matrix * q + offset
//! matrix = [[-1,0,0,0,0,0], [0,1,0,0,0,0], [0,-1,-1,0,0,0], [0,0,0,-1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,-1]]
//! offset_deg = [0, -90, -90, 0, 0, 180]
//! [base]                                # optional: world to the first DH frame
//! xyz_mm = [0, 0, 0]
//! rpy_deg = [0, 0, 0]                   # fixed-axis roll, pitch, yaw as in URDF
//! [flange]                              # optional: last DH frame to the flange frame
//! xyz_mm = [0, 0, 0]
//! rpy_deg = [0, 0, 0]
//! [controller_world]                    # optional: the controller's world frame (where a
//! xyz_mm = [0, 0, 670]                  #   program's positions are: FANUC's world, user frame
//! rpy_deg = [0, 0, 0]                   #   0, at the height of axis 2) in the base frame;
//!                                       #   default the base frame (KUKA, ABB: at the foot)
//! [robot_geometry]                      # optional: capsule radii of the base and links 1-6
//! link_radius_mm = [350, 260, 195, 175, 130, 110, 90]   # default scaled to the robot's size
//! [held_out]                            # optional (stiffid calibrate --out writes it): the
//! source = "validate"                   #   calibration's held-out position errors, "validate"
//! errors_mm = [0.012, 0.019, 0.031]     #   or "cross-validate", each |error| in mm (1 to 1e6)
//! [mount]                               # optional (stiffid calibrate --out writes it): the
//! xyz_mm = [0, 0, 300]                  #   pedestal the robot was calibrated on (the setup's
//! rpy_deg = [0, 0, 0]                   #   [robot_base]), which [base] holds; a setup pointing
//!                                       #   at the file takes the controller's world from it
//! [part]                                # optional (stiffid calibrate --out writes it): the
//! xyz_mm = [1500, 0, 400]               #   part's frame the calibration located from the
//! rpy_deg = [0, 0, 0.11]                #   reflectors on the table or a fixed part (the setup's
//!                                       #   [workpiece] reflectors_mm are in it), cell frame,
//!                                       #   external axes at 0: a setup pointing at the file
//!                                       #   takes it as [workpiece] base_from_part
//! [gravity]                             # optional (stiffid calibrate --out writes it): the
//! model = "masses"                      #   sag under the robot's own weight and its tool's
//! terms = [{ name = "gravity.c2", value_si = 1.1e-7 }]   # ([`super::weight_file`])
//! [[external_axis]]                     # optional, one per axis: a carrier under the arm (a
//! name = "track"                        #   track) or a positioner under the workpiece
//! role = "carrier"                      #   ([`super::external::file`] has the format)
//! direction = [1, 0, 0]
//! limits_mm = [0, 6000]
//! ```
//! Unknown keys are rejected.

use super::dh::{self, Convention, Row};
use super::{AxisMap, LinkMass, Robot};
use crate::common::limits::{self, check_in, JointBox};
use crate::{Error, Result};
use nalgebra::{Isometry3, Matrix6, Translation3, UnitQuaternion, Vector6};
use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotFile {
    name: String,
    #[serde(default)]
    source: String,
    convention: Convention,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    max_speed_deg_s: Option<[f64; 6]>,
    joint: Vec<JointRow>,
    axis_map: Option<AxisMapFile>,
    base: Option<TransformFile>,
    flange: Option<TransformFile>,
    controller_world: Option<TransformFile>,
    robot_geometry: Option<GeometryFile>,
    #[serde(default)]
    external_axis: Vec<super::external::file::AxisFile>,
    held_out: Option<HeldOutFile>,
    mount: Option<TransformFile>,
    part: Option<TransformFile>,
    gravity: Option<super::weight_file::GravityFile>,
}

/// A calibrated robot's `[held_out]`: its calibration's held-out position errors.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct HeldOutFile {
    source: String,
    errors_mm: Vec<f64>,
}

/// The most held-out errors a robot file carries.
pub(crate) const MAX_HELD_OUT: usize = 1_000_000;

/// The `[held_out]` table checked: `source` `validate` or `cross-validate`, 1 to
/// [`MAX_HELD_OUT`] errors, each finite, within [0, 1000] mm; sorted.
fn held_out(file: Option<HeldOutFile>, source_name: &str) -> Result<Option<super::HeldOut>> {
    let Some(h) = file else { return Ok(None) };
    if !matches!(h.source.as_str(), "validate" | "cross-validate") {
        return Err(invalid(
            source_name,
            "held_out.source".into(),
            &format!(
                "'{}': expected \"validate\" or \"cross-validate\"",
                limits::short(&h.source)
            ),
        ));
    }
    let bad = h.errors_mm.iter().any(|e| !(0.0..=1000.0).contains(e));
    if h.errors_mm.is_empty() || h.errors_mm.len() > MAX_HELD_OUT || bad {
        return Err(invalid(
            source_name,
            "held_out.errors_mm".into(),
            &format!("expected 1 to {MAX_HELD_OUT} lengths, each finite, within [0, 1000] mm"),
        ));
    }
    let mut errors: Vec<f64> = h.errors_mm.iter().map(|e| e * 1e-3).collect();
    errors.sort_by(f64::total_cmp);
    Ok(Some(super::HeldOut {
        source: h.source,
        errors,
    }))
}

/// A robot's `[robot_geometry]`: the capsule radii of its bodies (the tool's is the setup's).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct GeometryFile {
    #[serde(deserialize_with = "crate::common::exact::array")]
    link_radius_mm: [f64; 7],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JointRow {
    a_mm: f64,
    alpha_deg: f64,
    d_mm: f64,
    #[serde(default)]
    theta_offset_deg: f64,
    #[serde(default)]
    beta_deg: f64,
    mass_kg: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    com_mm: Option<[f64; 3]>,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    inertia_kg_m2: Option<[f64; 6]>,
    lower_deg: f64,
    upper_deg: f64,
    error_map: Option<ErrorMapFile>,
}

/// A joint's `error_map`: the Fourier coefficients of its axis's angle error and half its
/// backlash, deg ([`super::ErrorMap`]), and the axis angles it was fitted over, deg (a file
/// without them: the series at every angle).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ErrorMapFile {
    #[serde(default)]
    cos_deg: Vec<f64>,
    #[serde(default)]
    sin_deg: Vec<f64>,
    #[serde(default)]
    half_backlash_deg: f64,
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    range_deg: Option<[f64; 2]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct AxisMapFile {
    #[serde(deserialize_with = "crate::common::exact::matrix")]
    matrix: [[f64; 6]; 6],
    #[serde(deserialize_with = "crate::common::exact::array")]
    offset_deg: [f64; 6],
}

/// A rigid transform as written in files: translation in mm, URDF roll-pitch-yaw in degrees.
#[derive(Debug, Deserialize, Default, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub(crate) struct TransformFile {
    /// Translation, mm.
    #[serde(default, deserialize_with = "crate::common::exact::array")]
    pub xyz_mm: [f64; 3],
    /// Fixed-axis roll, pitch, yaw (`R = Rz(yaw) Ry(pitch) Rx(roll)`), degrees.
    #[serde(default, deserialize_with = "crate::common::exact::array")]
    pub rpy_deg: [f64; 3],
}

impl TransformFile {
    /// The transform in SI units.
    pub(crate) fn isometry(&self) -> Isometry3<f64> {
        let [x, y, z] = self.xyz_mm.map(|v| v * 1e-3);
        let [r, p, w] = self.rpy_deg.map(f64::to_radians);
        Isometry3::from_parts(
            Translation3::new(x, y, z),
            UnitQuaternion::from_euler_angles(r, p, w),
        )
    }
}

/// The fixed-axis roll, pitch and yaw of `rotation` (rad, `R = Rz(yaw) Ry(pitch) Rx(roll)`) that
/// give it back to rounding, for the files stiffid writes, at any pitch. The pitch is the
/// arctangent of the first column (the arcsine of a number near 1 loses half the digits near
/// pitch +-90 degrees, a ROS-Industrial `tool0`). Roll and yaw are carried by elements that
/// shrink with the cosine of the pitch, except one combination of them: `roll - yaw` (pitch >= 0)
/// is `atan2(m01 - m12, m11 + m02)`, `roll + yaw` (pitch < 0) `atan2(-(m01 + m12), m11 - m02)`,
/// exactly and from elements of size 1 to 2; that one is taken from them, the other from the
/// small elements, whose error the rotation feels only through that cosine.
pub fn rpy(rotation: &UnitQuaternion<f64>) -> [f64; 3] {
    use std::f64::consts::TAU;
    let m = rotation.to_rotation_matrix().into_inner();
    let pitch = (-m[(2, 0)]).atan2(m[(0, 0)].hypot(m[(1, 0)]));
    let (roll, yaw) = (m[(2, 1)].atan2(m[(2, 2)]), m[(1, 0)].atan2(m[(0, 0)]));
    let sign = if pitch >= 0.0 { 1.0 } else { -1.0 };
    let exact = match sign > 0.0 {
        true => (m[(0, 1)] - m[(1, 2)]).atan2(m[(1, 1)] + m[(0, 2)]),
        false => (-(m[(0, 1)] + m[(1, 2)])).atan2(m[(1, 1)] - m[(0, 2)]),
    };
    // The same combination from the small elements picks the turn (roll and yaw stay in
    // -pi..pi of the closed form's branch).
    let exact = exact + ((roll - sign * yaw - exact) / TAU).round() * TAU;
    let r = 0.5 * (roll + sign * yaw + exact);
    [r, pitch, sign * (r - exact)]
}

/// The angle of the rotation from `a` to `b`, rad, to rounding even when tiny (`2 atan2(|v|, |w|)`
/// of the quaternion between them; the arccosine of `w` loses half the digits there).
pub fn angle_between(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> f64 {
    let d = a.inverse() * b;
    2.0 * d.imag().norm().atan2(d.w.abs())
}

/// Parses a robot TOML file; `source_name` (the file name) is used in error messages.
///
/// # Errors
/// [`Error::Parse`] for malformed TOML, unknown or missing keys and wrong types (the message names
/// the key, line and column), [`Error::InvalidField`] for a joint count other than six, a number
/// that is not finite or outside its range ([`crate::common::limits`]: lengths
/// [`limits::LENGTH_MM`], angles [`limits::ANGLE_DEG`], speeds [0, 10 000] deg/s or mm/s),
/// `lower_deg >= upper_deg` or an axis map whose condition number exceeds 1e8, and those of the
/// `[[external_axis]]` tables ([`super::external::file`]: the file, the table and the field named).
pub fn parse(text: &str, source_name: &str) -> Result<Robot> {
    let file: RobotFile = toml::from_str(text).map_err(|e| Error::Parse {
        source_name: source_name.to_string(),
        message: limits::one_line(&e.to_string()),
    })?;
    build(file, source_name)
}

fn invalid(source_name: &str, field: String, message: &str) -> Error {
    Error::InvalidField {
        field: format!("{source_name}: {field}"),
        message: message.to_string(),
    }
}

fn build(file: RobotFile, source_name: &str) -> Result<Robot> {
    if file.joint.len() != 6 {
        return Err(invalid(
            source_name,
            "joint".into(),
            &format!("expected 6 [[joint]] tables, found {}", file.joint.len()),
        ));
    }
    let mut lower = Vector6::zeros();
    let mut upper = Vector6::zeros();
    let mut rows = Vec::with_capacity(6);
    for (i, j) in file.joint.iter().enumerate() {
        let field = |name: &str| format!("joint[{}].{name}", i + 1);
        let (length, angle) = (&limits::LENGTH_MM, &limits::ANGLE_DEG);
        check_in(source_name, &field("a_mm"), &[j.a_mm], length)?;
        check_in(source_name, &field("d_mm"), &[j.d_mm], length)?;
        for (name, v) in [
            ("alpha_deg", j.alpha_deg),
            ("theta_offset_deg", j.theta_offset_deg),
            ("beta_deg", j.beta_deg),
            ("lower_deg", j.lower_deg),
            ("upper_deg", j.upper_deg),
        ] {
            check_in(source_name, &field(name), &[v], angle)?;
        }
        if j.lower_deg >= j.upper_deg {
            return Err(invalid(
                source_name,
                format!("joint[{}].lower_deg", i + 1),
                "expected lower_deg < upper_deg",
            ));
        }
        lower[i] = j.lower_deg.to_radians();
        upper[i] = j.upper_deg.to_radians();
        rows.push(dh::hayati_joint(
            file.convention,
            &Row {
                a: j.a_mm * 1e-3,
                alpha: j.alpha_deg.to_radians(),
                d: j.d_mm * 1e-3,
                theta_offset: j.theta_offset_deg.to_radians(),
            },
            j.beta_deg.to_radians(),
        ));
    }
    let joints = rows.try_into().expect("six joints checked above");
    let masses = masses(&file.joint, source_name)?;
    let maps = error_maps(&file.joint, source_name)?;
    let base = transform(file.base, "base", source_name)?;
    let flange = transform(file.flange, "flange", source_name)?;
    let world = transform(file.controller_world, "controller_world", source_name)?;
    let bodies = bodies(file.robot_geometry, source_name)?;
    let held = held_out(file.held_out, source_name)?;
    let mount = match file.mount {
        Some(m) => Some(transform(Some(m), "mount", source_name)?),
        None => None,
    };
    let part = match file.part {
        Some(p) => Some(transform(Some(p), "part", source_name)?),
        None => None,
    };
    let own_weight = super::weight_file::build(file.gravity, source_name)?;
    let speeds = max_speeds(file.max_speed_deg_s.as_ref(), source_name)?;
    let external = super::external::file::build(&file.external_axis, source_name)?;
    let axis_map = match file.axis_map {
        None => AxisMap::default(),
        Some(m) => axis_map(&m, "axis_map", source_name)?,
    };
    Robot::new(file.name, file.source, joints, JointBox::new(lower, upper))
        .and_then(|r| r.with_axis_map(axis_map))
        .and_then(|r| r.with_base(base))
        .and_then(|r| r.with_flange(flange))
        .and_then(|r| r.with_controller_world(world))
        .and_then(|r| r.with_max_speeds(speeds))
        .map(|r| {
            r.with_bodies(bodies)
                .with_masses(masses)
                .with_error_maps(maps)
                .with_held_out(held)
                .with_mount(mount)
                .with_part(part)
                .with_own_weight(own_weight)
                .with_external(external)
        })
        .map_err(|e| match e {
            Error::InvalidField { field, message } => invalid(source_name, field, &message),
            other => other,
        })
}

/// Each axis's largest speed of `max_speed_deg_s` (a robot file's or a setup's, in the file
/// `source_name`), rad/s: TOML's `inf` for an axis without a limit, every other value checked
/// by [`limits::check_speeds`] (NaN, 0, negatives and values above the range refused naming
/// the axis); infinite (no limit) without the field.
pub(crate) fn max_speeds(deg_s: Option<&[f64; 6]>, source_name: &str) -> Result<Vector6<f64>> {
    let Some(v) = deg_s else {
        return Ok(Vector6::repeat(f64::INFINITY));
    };
    let limited = v.map(|d| match d == f64::INFINITY {
        true => limits::AXIS_SPEED.max,
        false => d,
    });
    limits::check_speeds(&format!("{source_name}: max_speed_deg_s"), &limited)?;
    Ok(Vector6::from_iterator(v.iter().map(|d| d.to_radians())))
}

/// The links' masses, centres and inertia tensors of `mass_kg`, `com_mm` (every joint or none)
/// and `inertia_kg_m2` (optional, zero without it), each mass within [`limits::MASS_KG`], centre
/// within [`limits::LENGTH_MM`], tensor component within [`limits::INERTIA_KG_M2`] and tensor
/// physical ([`super::dynamics::body::physical`]; zero for a massless link).
fn masses(joints: &[JointRow], source_name: &str) -> Result<Option<[LinkMass; 6]>> {
    let given = joints.iter().filter(|j| j.mass_kg.is_some()).count();
    let centres = joints.iter().filter(|j| j.com_mm.is_some()).count();
    let tensors = joints.iter().filter(|j| j.inertia_kg_m2.is_some()).count();
    if given == 0 && centres == 0 && tensors == 0 {
        return Ok(None);
    }
    let mut out = [LinkMass::default(); 6];
    for (i, j) in joints.iter().enumerate() {
        let (Some(mass), Some(com)) = (j.mass_kg, j.com_mm) else {
            return Err(invalid(
                source_name,
                format!("joint[{}].mass_kg", i + 1),
                "expected mass_kg and com_mm on every joint or on none (inertia_kg_m2 needs them)",
            ));
        };
        let field = |name: &str| format!("joint[{}].{name}", i + 1);
        check_in(source_name, &field("mass_kg"), &[mass], &limits::MASS_KG)?;
        check_in(source_name, &field("com_mm"), &com, &limits::LENGTH_MM)?;
        let six = j.inertia_kg_m2.unwrap_or_default();
        check_in(
            source_name,
            &field("inertia_kg_m2"),
            &six,
            &limits::INERTIA_KG_M2,
        )?;
        let inertia = super::dynamics::body::tensor(six);
        super::dynamics::body::physical(&inertia)
            .map_err(|m| invalid(source_name, field("inertia_kg_m2"), &m))?;
        if mass == 0.0 && six.iter().any(|v| *v != 0.0) {
            return Err(invalid(
                source_name,
                field("inertia_kg_m2"),
                "expected zeros for a link of mass_kg = 0 (a body without mass has no inertia)",
            ));
        }
        out[i] = LinkMass {
            mass,
            centre: nalgebra::Vector3::from(com.map(|v| v * 1e-3)),
            inertia,
        };
    }
    Ok(Some(out))
}

/// The joints' error maps (`error_map`, deg, each as [`super::ErrorMap::new`] checks it), empty
/// where a joint has none.
fn error_maps(joints: &[JointRow], source_name: &str) -> Result<[super::ErrorMap; 6]> {
    let mut maps: [super::ErrorMap; 6] = Default::default();
    for (i, j) in joints.iter().enumerate() {
        if let Some(m) = &j.error_map {
            // Each list is optional: one left out holds zeros, as many as the other.
            let n = m.cos_deg.len().max(m.sin_deg.len());
            let rad = |v: &[f64]| match v.is_empty() {
                true => vec![0.0; n],
                false => v.iter().map(|d| d.to_radians()).collect(),
            };
            let map = super::ErrorMap::new(rad(&m.cos_deg), rad(&m.sin_deg))
                .and_then(|map| map.with_backlash(m.half_backlash_deg.to_radians()))
                .and_then(|map| match m.range_deg {
                    Some([lo, hi]) => map.with_range(lo.to_radians(), hi.to_radians()),
                    None => Ok(map),
                });
            maps[i] = map.map_err(|e| {
                let message = match e {
                    Error::InvalidField { message, .. } => message,
                    other => other.to_string(),
                };
                invalid(source_name, format!("joint[{}].error_map", i + 1), &message)
            })?;
        }
    }
    Ok(maps)
}

/// The bodies of `[robot_geometry]`: capsules of the radii given, each within
/// [`limits::BODY_RADIUS_MM`]; scaled capsules without it.
fn bodies(g: Option<GeometryFile>, source_name: &str) -> Result<super::Bodies> {
    let Some(g) = g else {
        return Ok(super::Bodies::Scaled);
    };
    let field = "robot_geometry.link_radius_mm";
    check_in(
        source_name,
        field,
        &g.link_radius_mm,
        &limits::BODY_RADIUS_MM,
    )?;
    Ok(super::Bodies::Capsules(g.link_radius_mm.map(|r| r * 1e-3)))
}

/// The optional `[base]` or `[flange]` transform (or a setup's `[robot_base]` / `[robot_flange]`),
/// its numbers checked against the limits; `name` is the table's name in errors.
pub(crate) fn transform(
    t: Option<TransformFile>,
    name: &str,
    source_name: &str,
) -> Result<Isometry3<f64>> {
    let t = t.unwrap_or_default();
    check_in(
        source_name,
        &format!("{name}.xyz_mm"),
        &t.xyz_mm,
        &limits::LENGTH_MM,
    )?;
    check_in(
        source_name,
        &format!("{name}.rpy_deg"),
        &t.rpy_deg,
        &limits::ANGLE_DEG,
    )?;
    Ok(t.isometry())
}

/// The axis map of the table `name` (a robot file's `[axis_map]`, a setup's
/// `[robot_axis_map]`), its entries checked against the limits.
pub(crate) fn axis_map(m: &AxisMapFile, name: &str, source_name: &str) -> Result<AxisMap> {
    for (r, row) in m.matrix.iter().enumerate() {
        let field = format!("{name}.matrix[{}]", r + 1);
        check_in(source_name, &field, row, &limits::AXIS_MAP_ENTRY)?;
    }
    check_in(
        source_name,
        &format!("{name}.offset_deg"),
        &m.offset_deg,
        &limits::ANGLE_DEG,
    )?;
    let matrix = Matrix6::from_fn(|r, c| m.matrix[r][c]);
    let offset = Vector6::from_iterator(m.offset_deg.iter().map(|d| d.to_radians()));
    Ok(AxisMap { matrix, offset })
}
