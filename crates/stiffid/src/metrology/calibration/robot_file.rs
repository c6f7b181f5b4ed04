//! The calibrated robot, and the files that carry it: a robot TOML file (the DH table with
//! Hayati's `beta_deg`, the axis map, base and flange) and a URDF with corrected joint origins.
//!
//! The calibrated chain is [`ErrorModel::robot_at`] of the fitted values; for readings in the
//! base frame its base becomes `T^-1 base` (the base frame's error, [`Estimate::frame`]), for
//! tracker readings the registration stays with the tracker (its fragment). A DH table holds the
//! errors exactly: in a modified-DH row `i`, `a`, `alpha` and Hayati's `beta` of joint `i` join
//! `a_{i-1}`, `alpha_{i-1}`, `beta_{i-1}`, `theta` and `d` join `theta_offset` and `d_i`; in a
//! standard-DH table `a`, `alpha` and `beta` of joint `i` join row `i - 1` (joint 1's the base
//! transform) and `theta`, `d` row `i` (module docs of [`super::error_model`]). A lateral error
//! `b` has no place in a DH table: a calibration that fitted one writes a URDF only. In a URDF,
//! joint `i`'s origin becomes `post_{i-1} pre_i E_i Rot(w_i, offset_i + theta_i)`, the base folded
//! into the first and the flange into a fixed joint to the `flange` link.

use super::error_model::{Component, ErrorModel, Estimate, MeasuredIn};
use crate::robot::dh::Convention;
use crate::robot::urdf::UrdfSource;
use crate::robot::{urdf_write, Bodies};
use crate::{Error, Result, Robot};
use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use std::fmt::Write;

use crate::robot::CALIBRATED;

/// Lengths below this (m) count as zero when a chain is read as a DH table.
const DH_TOLERANCE: f64 = 1e-12;

/// The calibrated robot: the chain with the fitted errors, the base corrected for base-frame
/// readings.
///
/// # Errors
/// Those of [`ErrorModel::robot_at`] and [`Robot::with_base`].
pub fn calibrated(model: &ErrorModel, estimate: &Estimate) -> Result<Robot> {
    let robot = model.robot_at(&estimate.values)?;
    match model.measured_in() {
        MeasuredIn::Tracker => Ok(robot),
        MeasuredIn::Base => {
            let base = estimate.frame.inverse() * robot.base();
            robot.with_base(base)
        }
    }
}

/// A row of a DH table, SI.
#[derive(Debug, Clone, Copy, Default)]
struct Row {
    a: f64,
    alpha: f64,
    beta: f64,
    d: f64,
    theta: f64,
}

/// The nominal robot's DH convention and rows, or `None` when its chain is not a DH table.
fn dh_rows(robot: &Robot) -> Option<(Convention, [Row; 6])> {
    let x_rotation = |q: &UnitQuaternion<f64>| {
        let v = q.as_ref().imag();
        (v.y.abs() < DH_TOLERANCE && v.z.abs() < DH_TOLERANCE).then(|| 2.0 * v.x.atan2(q.w))
    };
    let joints = robot.joints();
    if joints.iter().any(|j| j.axis != Vector3::z_axis()) {
        return None;
    }
    let modified = joints.iter().all(|j| {
        let (t, p) = (j.post.translation.vector, j.pre.translation.vector);
        j.post.rotation == UnitQuaternion::identity()
            && t.x.abs() < DH_TOLERANCE
            && t.y.abs() < DH_TOLERANCE
            && p.y.abs() < DH_TOLERANCE
            && p.z.abs() < DH_TOLERANCE
            && x_rotation(&j.pre.rotation).is_some()
    });
    let standard = joints.iter().all(|j| {
        let t = j.post.translation.vector;
        j.pre == Isometry3::identity()
            && t.y.abs() < DH_TOLERANCE
            && x_rotation(&j.post.rotation).is_some()
    });
    let row = |i: usize| {
        let j = &joints[i];
        let (t, alpha) = match modified {
            true => (j.pre.translation.vector, x_rotation(&j.pre.rotation)),
            false => (j.post.translation.vector, x_rotation(&j.post.rotation)),
        };
        let d = match modified {
            true => j.post.translation.vector.z,
            false => t.z,
        };
        Row {
            a: t.x,
            alpha: alpha.unwrap_or(0.0),
            beta: 0.0,
            d,
            theta: j.offset,
        }
    };
    let convention = match (modified, standard) {
        (true, _) => Convention::ModifiedDh,
        (false, true) => Convention::StandardDh,
        _ => return None,
    };
    Some((convention, std::array::from_fn(row)))
}

/// The errors `[theta, d, a, alpha, beta, b]` of joint `i` at `values`.
fn errors(model: &ErrorModel, estimate: &Estimate, i: usize) -> [f64; 6] {
    let mut e = [0.0; 6];
    for (p, v) in model.parameters().iter().zip(estimate.values.iter()) {
        if let super::Target::Joint { joint, component } = p.target {
            if joint == i {
                let c = Component::ALL.iter().position(|&c| c == component);
                e[c.unwrap_or(0)] = *v;
            }
        }
    }
    e
}

/// The calibrated robot as a robot TOML file (module docs): the DH table with the errors
/// applied, Hayati's `beta_deg` where fitted, the axis map, joint limits, base, flange, capsule
/// radii and masses of the nominal robot. Numbers are written in full (shortest round-trip), so
/// the file reproduces the calibrated positions to rounding.
///
/// # Errors
/// [`Error::InvalidField`] (`robot`) when the nominal robot is not a DH table (a URDF: write a
/// URDF) or a lateral error `b` was fitted.
pub fn robot_toml(model: &ErrorModel, estimate: &Estimate) -> Result<String> {
    let nominal = model.robot();
    let Some((convention, mut rows)) = dh_rows(nominal) else {
        return Err(not_dh(
            "its chain is not a DH table (a URDF): write a URDF instead",
        ));
    };
    let mut base = *nominal.base();
    for i in 0..6 {
        let [theta, d, a, alpha, beta, b] = errors(model, estimate, i);
        if b != 0.0 {
            return Err(not_dh(&format!(
                "joint{}.b was fitted, which a DH table cannot hold: write a URDF instead",
                i + 1
            )));
        }
        rows[i].theta += theta;
        rows[i].d += d;
        let target = match (convention, i) {
            (Convention::ModifiedDh, _) => Some(i),
            (Convention::StandardDh, 0) => None,
            (Convention::StandardDh, _) => Some(i - 1),
        };
        match target {
            Some(r) => {
                rows[r].a += a;
                rows[r].alpha += alpha;
                rows[r].beta += beta;
            }
            None => {
                let e = model.basis(0).error(&[0.0, 0.0, a, alpha, beta, 0.0]);
                base *= e;
            }
        }
    }
    if model.measured_in() == MeasuredIn::Base {
        base = estimate.frame.inverse() * base;
    }
    let mut t = String::new();
    let name = format!("{}{CALIBRATED}", nominal.name());
    let _ = writeln!(t, "name = {}", quoted(&name));
    let _ = writeln!(t, "source = {}", quoted(nominal.source()));
    let _ = writeln!(
        t,
        "convention = \"{}\"",
        match convention {
            Convention::ModifiedDh => "modified-dh",
            Convention::StandardDh => "standard-dh",
        }
    );
    let limits = nominal.limits();
    for (i, r) in rows.iter().enumerate() {
        let _ = writeln!(t, "\n[[joint]]");
        let _ = writeln!(t, "a_mm = {:?}", r.a * 1e3);
        let _ = writeln!(t, "alpha_deg = {:?}", r.alpha.to_degrees());
        if r.beta != 0.0 {
            let _ = writeln!(t, "beta_deg = {:?}", r.beta.to_degrees());
        }
        let _ = writeln!(t, "d_mm = {:?}", r.d * 1e3);
        let _ = writeln!(t, "theta_offset_deg = {:?}", r.theta.to_degrees());
        let _ = writeln!(t, "lower_deg = {:?}", limit(limits.lower[i]));
        let _ = writeln!(t, "upper_deg = {:?}", limit(limits.upper[i]));
        if let Some(m) = nominal.masses() {
            let _ = writeln!(t, "mass_kg = {:?}", m[i].mass);
            let _ = writeln!(t, "com_mm = {}", list(&(m[i].centre * 1e3)));
        }
    }
    let map = nominal.axis_map();
    let _ = writeln!(t, "\n[axis_map]\nmatrix = [");
    for r in 0..6 {
        let row: Vec<String> = (0..6)
            .map(|c| format!("{:?}", map.matrix[(r, c)]))
            .collect();
        let _ = writeln!(t, "  [{}],", row.join(", "));
    }
    let offsets: Vec<String> = map
        .offset
        .iter()
        .map(|v| format!("{:?}", v.to_degrees()))
        .collect();
    let _ = writeln!(t, "]\noffset_deg = [{}]", offsets.join(", "));
    let _ = write!(t, "\n[base]\n{}", transform(&base));
    let _ = write!(t, "\n[flange]\n{}", transform(nominal.flange()));
    if let Bodies::Capsules(r) = nominal.bodies() {
        let radii: Vec<String> = r.iter().map(|v| format!("{:?}", v * 1e3)).collect();
        let _ = writeln!(
            t,
            "\n[robot_geometry]\nlink_radius_mm = [{}]",
            radii.join(", ")
        );
    }
    Ok(t)
}

/// The calibrated robot as a URDF (module docs). A robot read from a URDF gets its own document
/// back with the origins of its six chain joints corrected (`origin_i N_i^-1 C_i`, `N_i` and
/// `C_i` the nominal and calibrated transforms from the previous joint's frame to joint `i`'s, a
/// base correction folded into the first): links, meshes, inertials, mimic joints, fixed joints
/// and comments kept; it is read back and its kinematics checked against the calibrated robot's.
/// Any other robot is written as links `base_link`, `link1`..`link6`, `flange`, revolute joints
/// `joint1`..`joint6` with the corrected origins (the axis map's constant `c` folded in: the
/// URDF's joint positions are `M q`, the axis angles themselves for the identity `M`), as limits
/// the range of each joint position `(M q)_i` over the nominal axis limits (an unbounded one as a
/// continuous joint) and the links' masses when the nominal robot has them (zero inertia tensors: stiffid uses masses and centres only).
///
/// # Errors
/// Those of [`calibrated`]; [`Error::InvalidField`] (`robot`) when the nominal URDF's text cannot
/// carry the correction (a chain joint not found in it, a document that no longer reproduces the
/// calibrated robot).
pub fn urdf(model: &ErrorModel, estimate: &Estimate) -> Result<String> {
    let robot = calibrated(model, estimate)?;
    if let Some(source) = model.robot().urdf_source() {
        return edited_urdf(model.robot(), &robot, source);
    }
    let mut t = String::new();
    let _ = writeln!(
        t,
        "<?xml version=\"1.0\"?>\n<robot name={}>",
        xml_quoted(&format!("{}{CALIBRATED}", robot.name()))
    );
    let mut links = vec!["base_link".to_string()];
    links.extend((1..=6).map(|i| format!("link{i}")));
    links.push("flange".into());
    for (i, l) in links.iter().enumerate() {
        match (i, robot.masses()) {
            (1..=6, Some(m)) => {
                let m = &m[i - 1];
                // The link frame of the URDF is the joint frame before `post`.
                let c = robot.joints()[i - 1].post * nalgebra::Point3::from(m.centre);
                let _ = writeln!(
                    t,
                    "  <link name=\"{l}\"><inertial><origin xyz=\"{:?} {:?} {:?}\"/><mass value=\"{:?}\"/><inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial></link>",
                    c.x, c.y, c.z, m.mass
                );
            }
            _ => {
                let _ = writeln!(t, "  <link name=\"{l}\"/>");
            }
        }
    }
    let mut before = *robot.base();
    for (i, j) in robot.joints().iter().enumerate() {
        let origin = before
            * j.pre
            * UnitQuaternion::from_axis_angle(&j.axis, j.offset + robot.axis_map().offset[i]);
        before = j.post;
        let (lo, hi) = position_range(&robot, i);
        let bounded = lo.is_finite() && hi.is_finite();
        let _ = writeln!(
            t,
            "  <joint name=\"joint{}\" type=\"{}\">\n    <parent link=\"{}\"/><child link=\"{}\"/>\n    {}\n    <axis xyz=\"{:?} {:?} {:?}\"/>",
            i + 1,
            if bounded { "revolute" } else { "continuous" },
            links[i],
            links[i + 1],
            urdf_write::origin_xml(&origin),
            j.axis.x,
            j.axis.y,
            j.axis.z
        );
        if bounded {
            let _ = writeln!(
                t,
                "    <limit lower=\"{lo:?}\" upper=\"{hi:?}\" effort=\"0\" velocity=\"0\"/>"
            );
        }
        let _ = writeln!(t, "  </joint>");
    }
    let _ = writeln!(
        t,
        "  <joint name=\"flange\" type=\"fixed\">\n    <parent link=\"link6\"/><child link=\"flange\"/>\n    {}\n  </joint>\n</robot>",
        urdf_write::origin_xml(&(before * robot.flange()))
    );
    Ok(t)
}

/// The nominal URDF `source` of `nominal` with the origins of `calibrated` (the function docs of
/// [`urdf`]), checked by reading it back.
fn edited_urdf(nominal: &Robot, calibrated: &Robot, source: &UrdfSource) -> Result<String> {
    let invalid = |message: String| Error::InvalidField {
        field: "robot".into(),
        message: format!("the calibrated robot cannot be written as a URDF: {message}"),
    };
    // From the previous joint's frame to joint `i`'s at `theta = 0` (the axis map applies to
    // both robots alike and stays out).
    let step = |r: &Robot, i: usize| {
        let before = match i {
            0 => *r.base(),
            _ => r.joints()[i - 1].post,
        };
        let j = &r.joints()[i];
        before * j.pre * UnitQuaternion::from_axis_angle(&j.axis, j.offset)
    };
    let origins: [Isometry3<f64>; 6] = std::array::from_fn(|i| {
        source.origins[i] * step(nominal, i).inverse() * step(calibrated, i)
    });
    let name = match calibrated.name().ends_with(CALIBRATED) {
        true => calibrated.name().to_string(),
        false => format!("{}{CALIBRATED}", calibrated.name()),
    };
    let text = urdf_write::with_origins(source, &name, &origins).map_err(invalid)?;
    let back = crate::robot::urdf::parse(&text, "the calibrated URDF", Some(&source.tip))?
        .with_base(*nominal.base())?
        .with_axis_map(nominal.axis_map().clone())?;
    let q = [
        Vector6::zeros(),
        Vector6::new(0.3, -0.4, 0.5, -0.6, 0.7, -0.8),
        Vector6::new(-1.1, 0.9, -0.7, 1.3, -0.5, 2.1),
    ];
    let worst = (q.iter())
        .map(|q| {
            let (a, b) = (calibrated.frames(q).flange, back.frames(q).flange);
            (a.inverse() * b).translation.vector.norm() + (a.rotation.angle_to(&b.rotation))
        })
        .fold(0.0, f64::max);
    match worst <= 1e-12 {
        true => Ok(text),
        false => Err(invalid(format!(
            "read back, its flange misses the calibrated robot's by {worst:.3e} (m + rad)"
        ))),
    }
}

fn transform(t: &Isometry3<f64>) -> String {
    let (r, p, y) = t.rotation.euler_angles();
    format!(
        "xyz_mm = {}\nrpy_deg = [{:?}, {:?}, {:?}]\n",
        list(&(t.translation.vector * 1e3)),
        r.to_degrees(),
        p.to_degrees(),
        y.to_degrees()
    )
}

fn list(v: &Vector3<f64>) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

/// The range (rad) of the joint position `(M q)_i` of `robot` over its axis limits (interval
/// arithmetic: for a row of `M` with one entry, that axis's limits, mirrored for a negative one;
/// for a coupled row, the sum of its terms' ranges); infinite where an axis it reads is
/// unbounded.
fn position_range(robot: &Robot, i: usize) -> (f64, f64) {
    let (m, limits) = (robot.axis_map().matrix, robot.limits());
    (0..6)
        .filter(|&j| m[(i, j)] != 0.0)
        .fold((0.0, 0.0), |(lo, hi), j| {
            let w = m[(i, j)];
            let (a, b) = (w * limits.lower[j], w * limits.upper[j]);
            (lo + a.min(b), hi + a.max(b))
        })
}

/// A joint limit (rad) in degrees; an unbounded end as the file's largest angle.
fn limit(v: f64) -> f64 {
    match v.is_finite() {
        true => v.to_degrees(),
        false => v.signum() * crate::common::limits::ANGLE_DEG.max,
    }
}

fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

fn xml_quoted(s: &str) -> String {
    let escaped = s
        .replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    format!("\"{escaped}\"")
}

fn not_dh(message: &str) -> Error {
    Error::InvalidField {
        field: "robot".into(),
        message: format!("the calibrated robot cannot be written as a robot TOML file: {message}"),
    }
}
