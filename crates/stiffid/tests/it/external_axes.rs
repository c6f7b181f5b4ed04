//! A robot on a track and a part on a positioner, read from robot and setup files: positions,
//! Jacobians and the part's frame against a reference written here with plain 4 x 4 matrices
//! (Rodrigues' formula, the chain's joints as data), and the files' refusals.

use nalgebra::{Isometry3, Matrix3, Matrix4, Vector3, Vector6};
use stiffid::app::kinematics;
use stiffid::internal::robot::{presets, Robot};

const ARM: &str = "comau-smart5-nj165-3.0";

/// A 6 m track along a slanted direction, 250 mm offset.
const TRACK: &str = r#"
[[external_axis]]
name = "track"
role = "carrier"
direction = [1.0, 0.2, 0.0]
limits_mm = [0.0, 6000.0]
offset_mm = 250.0
"#;

/// A tilt-rotate table: tilt about x through (3000, 1500, 800) mm, then rotate about z through
/// (3000, 1500, 1000) mm (carried by the tilt), listed before the track in the file.
const POSITIONER: &str = r#"
[[external_axis]]
name = "tilt"
role = "positioner"
direction = [1.0, 0.0, 0.0]
point_mm = [3000.0, 1500.0, 800.0]
limits_deg = [-90.0, 90.0]
offset_deg = 5.0

[[external_axis]]
name = "rotate"
role = "positioner"
direction = [0.0, 0.0, 1.0]
point_mm = [3000.0, 1500.0, 1000.0]
limits_deg = [-360.0, 360.0]
"#;

fn robot(tables: &str) -> Robot {
    let text = format!("{}\n{tables}", presets::text(ARM).unwrap());
    stiffid::internal::robot::file::parse(&text, "cell.toml").unwrap()
}

fn refusal(tables: &str) -> String {
    let text = format!("{}\n{tables}", presets::text(ARM).unwrap());
    stiffid::internal::robot::file::parse(&text, "cell.toml")
        .unwrap_err()
        .to_string()
}

// ---- the reference: plain homogeneous matrices ----

fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Rodrigues: the rotation by `angle` about the unit vector `d`.
fn rodrigues(d: &Vector3<f64>, angle: f64) -> Matrix3<f64> {
    let k = skew(d);
    Matrix3::identity() + k * angle.sin() + k * k * (1.0 - angle.cos())
}

fn homogeneous(r: &Matrix3<f64>, t: &Vector3<f64>) -> Matrix4<f64> {
    let mut m = Matrix4::identity();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(r);
    m.fixed_view_mut::<3, 1>(0, 3).copy_from(t);
    m
}

fn matrix(t: &Isometry3<f64>) -> Matrix4<f64> {
    t.to_homogeneous()
}

fn translation(m: &Matrix4<f64>) -> Vector3<f64> {
    m.fixed_view::<3, 1>(0, 3).into_owned()
}

fn apply(m: &Matrix4<f64>, x: &Vector3<f64>) -> Vector3<f64> {
    (m * x.push(1.0)).xyz()
}

/// The arm on the mount `mount` (cell frame): the flange and the axis-coordinate Jacobian of
/// `point` (flange frame), rows `[v; omega]`.
fn arm(
    robot: &Robot,
    mount: &Matrix4<f64>,
    q: &Vector6<f64>,
    point: &Vector3<f64>,
) -> (Matrix4<f64>, Vector3<f64>, nalgebra::Matrix6<f64>) {
    let map = robot.axis_map();
    let theta = map.matrix * q + map.offset;
    let mut t = mount * matrix(robot.base());
    let mut axes = Vec::new();
    for (j, joint) in robot.joints().iter().enumerate() {
        t *= matrix(&joint.pre);
        let r = t.fixed_view::<3, 3>(0, 0).into_owned();
        axes.push((r * joint.axis.into_inner(), translation(&t)));
        let turn = rodrigues(&joint.axis.into_inner(), theta[j] + joint.offset);
        t *= homogeneous(&turn, &Vector3::zeros());
        t *= matrix(&joint.post);
    }
    let flange = t * matrix(robot.flange());
    let x = apply(&flange, point);
    let mut jt = nalgebra::Matrix6::zeros();
    for (j, (z, o)) in axes.iter().enumerate() {
        let v = z.cross(&(x - o));
        jt.column_mut(j)
            .copy_from(&Vector6::new(v.x, v.y, v.z, z.x, z.y, z.z));
    }
    (flange, x, jt * map.matrix)
}

/// One positioner axis's transform `Trans(p) Rot(d, angle) Trans(-p)` and its derivative.
fn turn(p: &Vector3<f64>, d: &Vector3<f64>, angle: f64) -> (Matrix4<f64>, Matrix4<f64>) {
    let (to, from) = (
        homogeneous(&Matrix3::identity(), p),
        homogeneous(&Matrix3::identity(), &-p),
    );
    let r = rodrigues(d, angle);
    let mut dr = Matrix4::zeros();
    dr.fixed_view_mut::<3, 3>(0, 0).copy_from(&(skew(d) * r));
    (
        to * homogeneous(&r, &Vector3::zeros()) * from,
        to * dr * from,
    )
}

fn close(a: &[f64], b: &[f64], tolerance: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tolerance,
            "{what}[{i}]: {x} against the reference {y}"
        );
    }
}

fn run(robot: &Robot, q: Vector6<f64>, e: Vec<f64>, point: Vector3<f64>) -> kinematics::Report {
    kinematics::run(&kinematics::Request {
        robot,
        q,
        point,
        characteristic_length: Some(1.5),
        coordinates: stiffid::Coordinates::Axis,
        stiffness: None,
        external: e,
        workpiece: None,
    })
    .unwrap()
    .report
}

#[test]
fn a_robot_on_a_track_moves_along_it_to_1e9() {
    let robot = robot(TRACK);
    let axes = robot.external().unwrap();
    assert_eq!(axes.column_names(), ["e1_mm"]);
    let d = Vector3::new(1.0, 0.2, 0.0).normalize();
    let point = Vector3::new(0.15, -0.05, 0.3);
    for (q, s_mm) in [
        ([10.0, -40.0, -95.0, 30.0, -40.0, 50.0], 0.0),
        ([-35.0, 20.0, -110.0, -70.0, 60.0, -120.0], 2750.0),
        ([120.0, 60.0, -170.0, 10.0, 20.0, 30.0], 6000.0),
    ] {
        let q = Vector6::from(q).map(f64::to_radians);
        let e = axes.to_si(&[s_mm]);
        let report = run(&robot, q, e.clone(), point);
        let mount = homogeneous(&Matrix3::identity(), &(d * (s_mm + 250.0) * 1e-3));
        let (flange, x, jacobian) = arm(&robot, &mount, &q, &point);
        let f = &report.frames;
        close(
            f.flange.to_homogeneous().as_slice(),
            flange.as_slice(),
            1e-9,
            "flange",
        );
        close(f.point(&point).as_slice(), x.as_slice(), 1e-9, "point");
        close(
            report.jacobian.as_slice(),
            jacobian.as_slice(),
            1e-9,
            "arm's columns",
        );
        assert_eq!(report.external_jacobian.len(), 1);
        let track = Vector6::new(d.x, d.y, d.z, 0.0, 0.0, 0.0);
        close(
            report.external_jacobian[0].as_slice(),
            track.as_slice(),
            1e-12,
            "track's column",
        );
        assert!(report.part.is_none());
    }
}

#[test]
fn a_part_on_a_tilt_rotate_positioner_turns_under_the_tool_to_1e9() {
    // The positioner listed first in the file: the cell's order is carrier, then positioner.
    let robot = robot(&format!("{POSITIONER}{TRACK}"));
    let axes = robot.external().unwrap();
    assert_eq!(axes.column_names(), ["e1_mm", "e2_deg", "e3_deg"]);
    let names: Vec<&str> = axes.axes().iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["track", "tilt", "rotate"]);
    let workpiece = Isometry3::new(Vector3::new(2.9, 1.4, 1.1), Vector3::new(0.0, 0.0, 0.3));
    let point = Vector3::new(0.2, 0.0, 0.25);
    let q = Vector6::new(15.0, 10.0, -100.0, 20.0, 35.0, -60.0).map(f64::to_radians);
    let (p1, d1) = (Vector3::new(3.0, 1.5, 0.8), Vector3::x());
    let (p2, d2) = (Vector3::new(3.0, 1.5, 1.0), Vector3::z());
    for display in [
        [1200.0, 0.0, 0.0],
        [3400.0, 35.0, -120.0],
        [500.0, -80.0, 300.0],
    ] {
        let e = axes.to_si(&display);
        let report = kinematics::run(&kinematics::Request {
            robot: &robot,
            q,
            point,
            characteristic_length: Some(1.5),
            coordinates: stiffid::Coordinates::Axis,
            stiffness: None,
            external: e.clone(),
            workpiece: Some(workpiece),
        })
        .unwrap();
        let d = Vector3::new(1.0, 0.2, 0.0).normalize();
        let mount = homogeneous(&Matrix3::identity(), &(d * (display[0] + 250.0) * 1e-3));
        let (_, x, jacobian) = arm(&robot, &mount, &q, &point);
        close(
            report.frames.point(&point).as_slice(),
            x.as_slice(),
            1e-9,
            "point",
        );
        close(report.jacobian.as_slice(), jacobian.as_slice(), 1e-9, "arm");
        let (a1, da1) = turn(&p1, &d1, e[1] + 5f64.to_radians());
        let (a2, da2) = turn(&p2, &d2, e[2]);
        let positioner = a1 * a2;
        let part = positioner * matrix(&workpiece);
        close(
            report.part.unwrap().to_homogeneous().as_slice(),
            part.as_slice(),
            1e-9,
            "part's frame",
        );
        // The tool point's velocity relative to the part per radian: minus the part's twist at
        // the tool point, the twist dP/de P^-1.
        let inverse = positioner.try_inverse().unwrap();
        for (k, derivative) in [(1, da1 * a2), (2, a1 * da2)] {
            let twist = derivative * inverse;
            let w = twist.fixed_view::<3, 3>(0, 0).into_owned();
            let omega = -Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]);
            let velocity = -apply(&twist, &x);
            let want = Vector6::new(
                velocity.x, velocity.y, velocity.z, omega.x, omega.y, omega.z,
            );
            close(
                report.external_jacobian[k].as_slice(),
                want.as_slice(),
                1e-9,
                &format!("column of e{}", k + 1),
            );
        }
        let point_in_part = part.try_inverse().unwrap() * x.push(1.0);
        let document = report.document();
        close(
            &document.point_in_part_mm.unwrap(),
            (point_in_part.xyz() * 1e3).as_slice(),
            1e-6,
            "point in the part's frame",
        );
        let values: Vec<f64> = document.external.iter().map(|v| v.value).collect();
        close(&values, &display, 1e-9, "values");
        assert_eq!(document.external_jacobian.as_ref().unwrap().len(), 6);
        assert_eq!(document.external_jacobian.as_ref().unwrap()[0].len(), 3);
    }
}

#[test]
fn the_kinematics_of_a_cell_need_its_axes_values() {
    let robot = robot(TRACK);
    let q = Vector6::new(0.0, 0.3, -1.5, 0.0, 0.5, 0.0);
    let request = |e: Vec<f64>| kinematics::Request {
        robot: &robot,
        q,
        point: Vector3::zeros(),
        characteristic_length: Some(1.5),
        coordinates: stiffid::Coordinates::Axis,
        stiffness: None,
        external: e,
        workpiece: None,
    };
    let missing = kinematics::run(&request(vec![])).unwrap_err().to_string();
    assert!(missing.contains("e1_mm track"), "{missing}");
    let outside = kinematics::run(&request(vec![6.5]))
        .unwrap_err()
        .to_string();
    assert!(
        outside.contains("e1_mm (track)") && outside.contains("0 to 6000 mm"),
        "{outside}"
    );
    let plain = presets::get(ARM).unwrap();
    let extra = kinematics::run(&kinematics::Request {
        robot: &plain,
        ..request(vec![1.0])
    })
    .unwrap_err()
    .to_string();
    assert!(extra.contains("no external axes"), "{extra}");
    // A robot without external axes: exactly as before.
    let before = plain.frames(&q);
    let report = kinematics::run(&kinematics::Request {
        robot: &plain,
        ..request(vec![])
    })
    .unwrap();
    assert_eq!(report.frames, before);
    assert!(report.external_jacobian.is_empty());
}

#[test]
fn external_axis_tables_are_refused_naming_the_file_table_and_field() {
    let cases = [
        (
            "[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\n",
            "cell.toml: external_axis[1] (track).limits_mm",
            "missing",
        ),
        (
            "[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_deg = [0, 10]\n",
            "external_axis[1] (track).limits_deg",
            "limits_mm",
        ),
        (
            "[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [0, 0, 0]\nlimits_mm = [0, 10]\n",
            "external_axis[1] (track).direction",
            "non-zero",
        ),
        (
            "[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_mm = [0, 10]\npoint_mm = [0, 0, 0]\n",
            "external_axis[1] (track).point_mm",
            "rotary",
        ),
        (
            "[[external_axis]]\nname = \"turn\"\nrole = \"positioner\"\ndirection = [0, 0, 1]\nlimits_mm = [0, 10]\n",
            "external_axis[1] (turn).limits_mm",
            "limits_deg",
        ),
        (
            "[[external_axis]]\nname = \"turn\"\nrole = \"positioner\"\ndirection = [0, 0, 1]\n",
            "external_axis[1] (turn).limits_deg",
            "missing",
        ),
        (
            "[[external_axis]]\nname = \"turn\"\nrole = \"positioner\"\ndirection = [0, 0, 1]\nlimits_deg = [0, 10]\nerror_motions = [[0, 0, 0, 0, 0, 0]]\n",
            "external_axis[1] (turn).error_motions",
            "linear",
        ),
        (
            "[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_mm = [10, 0]\n",
            "external_axis[1] (track).limits_mm",
            "lower below upper",
        ),
        (
            "[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_mm = [0, 10]\nerror_motions = [[0, 0, 0, 0, 500, 0]]\n",
            "external_axis[1] (track).error_motions",
            "100 mrad",
        ),
        (
            "[[external_axis]]\nname = \"a\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_mm = [0, 10]\n[[external_axis]]\nname = \"a\"\nrole = \"carrier\"\ndirection = [0, 1, 0]\nlimits_mm = [0, 10]\n",
            "cell.toml: external_axis[2].name",
            "twice",
        ),
        (
            "[[external_axis]]\nname = \"track\"\nrole = \"rail\"\ndirection = [1, 0, 0]\nlimits_mm = [0, 10]\n",
            "cell.toml",
            "carrier",
        ),
    ];
    for (tables, field, message) in cases {
        let error = refusal(tables);
        assert!(
            error.contains(field) && error.contains(message),
            "{tables}\n-> {error}"
        );
    }
}

/// Tables built in code (Python's `Robot.with_external_axes`) are refused naming the argument
/// and the table, and no position in the JSON text the caller never wrote.
#[test]
fn external_axis_tables_from_json_are_refused_naming_the_table_not_a_column() {
    use stiffid::internal::robot::external::file::from_json;
    let track =
        r#"{"name": "track", "role": "carrier", "direction": [0, 1, 0], "limits_mm": [0, 4000]}"#;
    let cases = [
        (
            format!(
                r#"[{track}, {{"name": "t2", "role": "carrier", "direction": "x", "limits_mm": [0, 1]}}]"#
            ),
            "axes: external_axis[2]: invalid type: string \"x\"",
        ),
        (
            r#"[{"name": "track", "direction": [0, 1, 0], "limits_mm": [0, 4000]}]"#.to_string(),
            "axes: external_axis[1]: missing field `role`",
        ),
        (
            track.to_string(),
            "axes: expected a list of tables, one per external axis",
        ),
    ];
    for (text, expected) in cases {
        let error = from_json(&text, "axes").unwrap_err().to_string();
        assert!(error.starts_with(expected), "{text}\n-> {error}");
        assert!(!error.contains("column"), "{error}");
    }
    let axes = from_json(&format!("[{track}]"), "axes").unwrap().unwrap();
    assert_eq!(axes.len(), 1);
}

/// The arm's bodies ride on the track of `setup`: every capsule moved by the carriage's travel.
fn assert_bodies_ride_on_the_track(setup: &stiffid::Setup) {
    let q = Vector6::new(0.2, 0.3, -1.6, 0.1, 0.4, -0.3);
    let axes = setup.robot().external().unwrap();
    let at = |s_mm: f64| {
        let frames = setup.robot().frames_at(&q, &axes.to_si(&[s_mm]));
        stiffid::internal::cell::capsules(setup.arm(), &frames)
    };
    let (home, far) = (at(0.0), at(4000.0));
    assert_eq!(home.len(), far.len());
    let shift = Vector3::new(1.0, 0.2, 0.0).normalize() * 4.0;
    for (a, b) in home.iter().zip(&far) {
        close(
            (b.a - a.a).as_slice(),
            shift.as_slice(),
            1e-9,
            "capsule start",
        );
        close(
            (b.b - a.b).as_slice(),
            shift.as_slice(),
            1e-9,
            "capsule end",
        );
    }
}

/// The track (with error motions) and the positioner written back and read again: the same
/// axes.
fn assert_axes_written_back() {
    let with_errors = robot(&format!(
        "{}\nerror_motions = [[0.1, 0.3, -0.05, 0.02, 0.2, -0.01], [0.0, 0.01, 0.0, 0.0, 0.0, 0.03]]\n{POSITIONER}",
        TRACK.trim_end()
    ));
    let axes = with_errors.external().unwrap();
    let written = stiffid::internal::robot::external::file::toml(axes);
    let back = robot(&written);
    assert_eq!(back.external().unwrap().len(), 3);
    for (a, b) in axes.axes().iter().zip(back.external().unwrap().axes()) {
        assert_eq!(a.name, b.name);
        close(
            a.direction.as_slice(),
            b.direction.as_slice(),
            1e-15,
            "direction",
        );
        close(a.point.as_slice(), b.point.as_slice(), 1e-15, "point");
        close(
            &[a.offset, a.lower, a.upper],
            &[b.offset, b.lower, b.upper],
            1e-12,
            "travel",
        );
        let (ca, cb) = (a.errors.coefficients(), b.errors.coefficients());
        assert_eq!(ca.len(), cb.len());
        for (x, y) in ca.iter().zip(cb) {
            close(x, y, 1e-18, "error motions");
        }
    }
}

#[test]
fn a_setups_tables_replace_the_robot_files_and_the_files_write_them_back() {
    let dir = std::env::temp_dir().join(format!("stiffid-external-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let robot_text = format!("{}\n{TRACK}", presets::text(ARM).unwrap());
    std::fs::write(dir.join("cell-robot.toml"), &robot_text).unwrap();
    let builtin = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let setup_text = builtin.replacen(
        "robot = \"comau-smart5-nj165-3.0\"",
        "robot = \"cell-robot.toml\"",
        1,
    );
    assert_ne!(setup_text, builtin);
    let read = |text: &str| {
        stiffid::internal::setup::parse(text, "cell-setup.toml", |r, _| {
            let text = std::fs::read_to_string(dir.join(r)).unwrap();
            stiffid::internal::robot::file::parse(&text, r)
        })
    };
    let setup = read(&setup_text).unwrap();
    let names = |s: &stiffid::Setup| -> Vec<String> {
        (s.robot().external().into_iter())
            .flat_map(|a| a.axes().iter().map(|a| a.name.clone()))
            .collect()
    };
    assert_eq!(names(&setup), ["track"]);
    // The resolved setup's JSON (reproduce's summary) shows them.
    let resolved =
        serde_json::to_value(stiffid::app::reproduce::document::SetupJson::new(&setup)).unwrap();
    let axis = &resolved["robot"]["external_axes"][0];
    assert_eq!(axis["column"], "e1_mm");
    assert_eq!(axis["limits"], serde_json::json!([0.0, 6000.0]));
    assert_eq!(axis["offset"], 250.0);
    assert_eq!(names(&setup), {
        let arm = setup.arm();
        (arm.robot().external().into_iter())
            .flat_map(|a| a.axes().iter().map(|a| a.name.clone()))
            .collect::<Vec<_>>()
    });
    let replaced = read(&format!("{setup_text}\n{POSITIONER}")).unwrap();
    assert_eq!(names(&replaced), ["tilt", "rotate"]);
    let removed = read(&setup_text.replacen(
        "robot = \"cell-robot.toml\"",
        "robot = \"cell-robot.toml\"\nexternal_axis = []",
        1,
    ))
    .unwrap();
    assert!(removed.robot().external().is_none());
    assert_bodies_ride_on_the_track(&setup);
    let bad = read(&format!(
        "{setup_text}\n[[external_axis]]\nname = \"t\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\n"
    ))
    .unwrap_err()
    .to_string();
    assert!(
        bad.contains("cell-setup.toml: external_axis[1] (t).limits_mm"),
        "{bad}"
    );
    assert_axes_written_back();
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn inverse_kinematics_reaches_a_point_of_the_part_with_the_carrier_where_it_is() {
    use stiffid::internal::robot::ik;
    let robot = robot(&format!("{TRACK}{POSITIONER}"));
    let axes = robot.external().unwrap();
    let point = Vector3::new(0.1, 0.0, 0.2);
    let workpiece = Isometry3::translation(3.0, 1.5, 1.0);
    // The pose the arm has at a known posture, carriage at 2000 mm, table tilted and turned:
    // written in the part's frame, then solved for from another start.
    let e = axes.to_si(&[2000.0, 30.0, -50.0]);
    let q = Vector6::new(0.3, 0.2, -1.7, 0.4, 0.6, -0.2);
    let reached = ik::tool_pose(&robot.frames_at(&q, &e), &point);
    let part = axes.positioner_pose(&e) * workpiece;
    let in_part = part.inverse() * reached;
    let start = Vector6::new(0.25, 0.25, -1.6, 0.3, 0.5, -0.1);
    let options = ik::Options::default();
    let frame = ik::TargetFrame::Part(workpiece);
    let s = ik::solve_at(&robot, &point, &in_part, frame, &e, &start, &options).unwrap();
    let got = ik::tool_pose(&robot.frames_at(&s.q, &e), &point);
    close(
        got.translation.vector.as_slice(),
        reached.translation.vector.as_slice(),
        1e-9,
        "tool point",
    );
    assert!(got.rotation.angle_to(&reached.rotation) < 1e-9);
    // The same target at another carriage position is another posture; outside the travel,
    // refused naming the axis.
    let moved = axes.to_si(&[2500.0, 30.0, -50.0]);
    let other = ik::solve_at(&robot, &point, &in_part, frame, &moved, &start, &options).unwrap();
    assert!((other.q - s.q).norm() > 1e-3);
    let far = axes.to_si(&[7000.0, 30.0, -50.0]);
    let e = ik::solve_at(&robot, &point, &in_part, frame, &far, &start, &options).unwrap_err();
    assert!(e.to_string().contains("e1_mm (track)"), "{e}");
}

/// The COMAU URDF on a track (a prismatic joint between the root and the arm's mount, its frame
/// turned 0.3 rad about z) with a tilt-rotate positioner as a second chain from the root.
fn cell_urdf(track_limit: &str) -> String {
    let path = format!("{}/tests/data/comau-nj165.urdf", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    let mount = r#"  <joint name="mount" type="fixed">
    <parent link="world"/>"#;
    assert!(text.contains(mount));
    let added = format!(
        r#"  <link name="carriage"/>
  <link name="table_base"/>
  <link name="table"/>
  <joint name="track" type="prismatic">
    <parent link="world"/>
    <child link="carriage"/>
    <origin xyz="0 0 0" rpy="0 0 0.3"/>
    <axis xyz="1 0 0"/>
    {track_limit}
  </joint>
  <joint name="tilt" type="revolute">
    <parent link="world"/>
    <child link="table_base"/>
    <origin xyz="3 1.5 0.8" rpy="0 0 0"/>
    <axis xyz="1 0 0"/>
    <limit lower="-1.5" upper="1.5" effort="1" velocity="1"/>
  </joint>
  <joint name="rotate" type="continuous">
    <parent link="table_base"/>
    <child link="table"/>
    <origin xyz="0 0 0.2" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
  </joint>
  <joint name="mount" type="fixed">
    <parent link="carriage"/>"#
    );
    text.replacen(mount, &added, 1)
}

#[test]
fn a_urdf_holds_the_track_before_the_arm_and_the_positioner_as_a_second_chain() {
    use stiffid::internal::robot::urdf;
    let limit = r#"<limit lower="0" upper="6" effort="1" velocity="1"/>"#;
    let cell = urdf::parse(&cell_urdf(limit), "cell.urdf", None).unwrap();
    let plain_text = std::fs::read_to_string(format!(
        "{}/tests/data/comau-nj165.urdf",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let plain = urdf::parse(&plain_text, "comau-nj165.urdf", None).unwrap();
    let axes = cell.external().unwrap();
    let names: Vec<&str> = axes.axes().iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["track", "tilt", "rotate"]);
    assert_eq!(axes.column_names(), ["e1_mm", "e2_deg", "e3_deg"]);
    let track = &axes.axes()[0];
    assert_eq!((track.lower, track.upper), (0.0, 6.0));
    let d = Vector3::new(0.3f64.cos(), 0.3f64.sin(), 0.0);
    close(
        track.direction.as_slice(),
        d.as_slice(),
        1e-15,
        "track direction",
    );
    let (tilt, rotate) = (&axes.axes()[1], &axes.axes()[2]);
    close(tilt.point.as_slice(), &[3.0, 1.5, 0.8], 1e-15, "tilt point");
    close(
        rotate.point.as_slice(),
        &[3.0, 1.5, 1.0],
        1e-15,
        "rotate point",
    );
    close(
        rotate.direction.as_slice(),
        &[0.0, 0.0, 1.0],
        1e-15,
        "rotate direction",
    );
    assert_eq!((tilt.lower, tilt.upper), (-1.5, 1.5));
    assert_eq!(cell.urdf_source().unwrap().joints[0], "joint_1");
    // The arm at e: the carriage's frame turned 0.3 rad about z, moved along its x axis.
    let q = Vector6::new(0.3, -0.2, 0.4, 0.5, -0.6, 0.7);
    let e = [2.5, 0.4, -1.0];
    let turned = homogeneous(&rodrigues(&Vector3::z(), 0.3), &(d * 2.5));
    let want = turned * matrix(&plain.frames(&q).flange);
    close(
        cell.frames_at(&q, &e).flange.to_homogeneous().as_slice(),
        want.as_slice(),
        1e-12,
        "flange on the track",
    );
    // A prismatic joint inside the arm is still refused; a track without its travel too.
    let missing = urdf::parse(&cell_urdf(""), "cell.urdf", None)
        .unwrap_err()
        .to_string();
    assert!(
        missing.contains("'track'") && missing.contains("no <limit"),
        "{missing}"
    );
    let inside = std::fs::read_to_string(format!(
        "{}/tests/data/comau-nj165-prismatic.urdf",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let e = urdf::parse(&inside, "p.urdf", None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("joint_3") && e.contains("where the arm's six revolute joints are expected"),
        "{e}"
    );
}

#[test]
fn a_urdf_positioner_hanging_from_the_arm_is_refused_naming_the_joint_and_link() {
    use stiffid::internal::robot::urdf;
    let limit = r#"<limit lower="0" upper="6" effort="1" velocity="1"/>"#;
    let tilt_on = |link: &str| {
        let from = "<joint name=\"tilt\" type=\"revolute\">\n    <parent link=\"world\"/>";
        let text = cell_urdf(limit);
        assert!(text.contains(from));
        text.replacen(
            from,
            &format!("<joint name=\"tilt\" type=\"revolute\">\n    <parent link=\"{link}\"/>"),
            1,
        )
    };
    // On the upper arm: moved by joint_3; through the tool: moved by joint_6.
    for (link, tip, mover) in [
        ("link_3", None, "joint_3"),
        ("tool0", Some("tool0"), "joint_6"),
    ] {
        let e = urdf::parse(&tilt_on(link), "cell.urdf", tip)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("joint 'tilt'")
                && e.contains(&format!("link '{link}'"))
                && e.contains(&format!("joint '{mover}'"))
                && e.contains("cell.urdf"),
            "{e}"
        );
    }
    // Hanging from the root (through fixed joints only) it is the positioner.
    assert!(urdf::parse(&cell_urdf(limit), "cell.urdf", None).is_ok());
}

/// A setup whose positioner axis passes through the tool's TCP (with the arm at zero and the
/// track at mid-travel) is refused naming the axis, as a URDF positioner hanging from the arm
/// is; 5 mm away from it the setup stands.
#[test]
fn a_setups_positioner_axis_through_the_tool_is_refused() {
    let text = include_str!("../../../../examples/track/track-cell.toml");
    let parse = |text: &str| {
        stiffid::internal::setup::parse(text, "track-cell.toml", |r, _| {
            stiffid::internal::robot::presets::get(r)
        })
    };
    let setup = parse(text).unwrap();
    let axes = setup.robot().external().unwrap();
    let e = axes.stations(1)[0];
    let frames = setup
        .robot()
        .frames_at(&nalgebra::Vector6::zeros(), e.as_slice());
    let tcp = frames.point(&setup.tool().tcp) * 1e3;
    let at = |dy: f64| {
        text.replacen(
            "point_mm = [3000.0, 1800.0, 900.0]",
            &format!("point_mm = [{:?}, {:?}, {:?}]", tcp.x, tcp.y + dy, tcp.z),
            1,
        )
    };
    let e = parse(&at(0.0)).unwrap_err().to_string();
    assert!(
        e.contains("track-cell.toml")
            && e.contains("external_axis (rotate)")
            && e.contains("passes through the tool's TCP"),
        "{e}"
    );
    assert!(parse(&at(5.0)).is_ok());
}
