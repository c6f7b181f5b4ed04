//! The calibrated robot file is the one model of the robot: its `[gravity]` table carries the sag
//! under its own weight and its tool's, so any stiffness file combines with it; the tool's weight
//! enters the compensation once; and a setup that repeats or contradicts the calibrated robot
//! (its mount, its external axes, a controller of another robot, a tool mass the lumped terms do
//! not hold) is refused naming both places, or taken from the calibration with a note.

use crate::own_weight::{file_with, heavy_on, masses_section, sag};
use nalgebra::{Vector3, Vector6};
use stiffid::internal::machining::compensate::{self, Options, PathPoint, Target};
use stiffid::internal::machining::weight::tool_load;
use stiffid::internal::metrology::calibration::gravity::{self, Terms};
use stiffid::internal::model::{Compliance, OwnWeight};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::ik::tool_pose;
use stiffid::{internal::setup, Coordinates, Error};

const STIFFNESS: [f64; 6] = [950000.0, 3000000.0, 900000.0, 250000.0, 200000.0, 150000.0];
const TOOL: &str = "mass_kg = 40.0\ncentre_of_mass_mm = [0.0, 0.0, 150.0]\n";

/// The COMAU robot with link masses as a calibrated robot file, `more` appended.
fn calibrated_text(more: &str) -> String {
    let text: Vec<String> = (crate::true_robot::dh_robot_text().lines())
        .map(|l| match l.starts_with("name = ") {
            true => format!("name = \"COMAU{}\"", stiffid::internal::robot::CALIBRATED),
            false => l.to_string(),
        })
        .collect();
    text.join("\n") + "\n" + more
}

/// The gravity terms of known masses: the joint compliances of [`STIFFNESS`] times `scale`.
fn masses(scale: f64, tool_mass: Option<f64>) -> OwnWeight {
    OwnWeight {
        gravity: "masses".into(),
        terms: (0..6)
            .map(|j| (format!("gravity.c{}", j + 1), scale / STIFFNESS[j]))
            .collect(),
        tool_mass,
        tool_centre: None,
    }
}

/// The setup's nominal stiffness, without gravity terms.
fn plain(setup: &stiffid::Setup) -> Compliance {
    let text = format!(r#"{{"stiffness_nm_per_rad": {STIFFNESS:?}}}"#);
    let file = stiffid::internal::io::stiffness::parse(&text).unwrap();
    file.compliance(setup.model()).unwrap()
}

fn point(q: Vector6<f64>, wrench: Vector6<f64>) -> PathPoint {
    PathPoint {
        line: 1,
        target: Target::Posture(q),
        wrench,
        frame: Frame::Base,
        external: stiffid::internal::robot::external::ExternalValues::NONE,
    }
}

/// The calibrated robot file's `[gravity]` (known masses) with a 40 kg spindle: the compensated
/// angles put the TCP, sagging under the links' and the spindle's weight (the oracle: the
/// potential energy with the spindle joined to link 6) and deflected by the process wrench alone,
/// on the rigid target within 0.2 um; the spindle's weight is not added again through the
/// compliance; an older stiffness file with the same terms gives the same angles, one with other
/// terms is refused naming both.
#[test]
fn the_calibrated_robot_carries_the_sag_and_the_tool_once() {
    let own = masses(1.0, Some(40.0));
    let robot_text = calibrated_text(&stiffid::internal::robot::weight_file::toml(&own));
    let s = heavy_on("", TOOL, &robot_text).unwrap();
    assert_eq!(s.robot().own_weight(), Some(&own));
    let compliance = plain(&s);
    assert!(tool_load(s.arm(), &compliance).is_none());
    let q = s.test_postures()[0];
    let wrench = Vector6::new(150.0, -80.0, -200.0, 0.0, 0.0, 0.0);
    let options = Options::for_setup(&s);
    let at = [point(q, wrench)];
    let with = compensate::path(s.arm(), &compliance, &at, &options).unwrap();
    let robot = s.robot();
    let heavy = gravity::with_tool(robot, s.payload().map(|p| p.body()));
    let c = compliance.drives_h();
    let tcp = s.tool().tcp;
    let target = tool_pose(&robot.frames(&q), &tcp);
    let qc = with[0].q_compensated;
    let h = 1e-7;
    let tau = Vector6::from_fn(|j, _| {
        let e = Vector6::ith(j, h);
        let p = |q: &Vector6<f64>| tool_pose(&robot.frames(q), &tcp);
        let (a, b) = (p(&(qc + e)), p(&(qc - e)));
        let dp = (a.translation.vector - b.translation.vector) / (2.0 * h);
        let dr = (a.rotation * b.rotation.inverse()).scaled_axis() / (2.0 * h);
        dp.dot(&wrench.fixed_rows::<3>(0)) + dr.dot(&wrench.fixed_rows::<3>(3))
    });
    let dq = sag(&heavy, &c, &qc) + tau.component_mul(&c);
    let lands = tool_pose(&robot.frames(&(qc + dq)), &tcp)
        .translation
        .vector;
    let miss = (lands - target.translation.vector).norm();
    assert!(miss < 2e-7, "{miss:e}");
    // The same terms from an older stiffness file on the robot without them.
    let bare = s.robot().clone().with_own_weight(None);
    let old = s.to_builder().with_robot(bare).build().unwrap();
    let file = stiffid::internal::io::stiffness::parse(&file_with(&masses_section())).unwrap();
    let legacy = file.compliance(old.model()).unwrap();
    let again = compensate::path(old.arm(), &legacy, &at, &options).unwrap();
    assert!((again[0].q_compensated - qc).amax() < 1e-12);
    // Both, differing: refused naming both.
    let other = Compliance {
        own_weight: Some(masses(1.1, None)),
        ..compliance.clone()
    };
    let e = compensate::path(s.arm(), &other, &at, &options).unwrap_err();
    let text = e.to_string();
    assert!(
        matches!(&e, Error::InvalidField { field, .. } if field == "gravity")
            && text.contains("[gravity]")
            && text.contains("stiffness file"),
        "{text}"
    );
}

/// Lumped terms hold the tool the robot carried in its calibration: a setup with that tool
/// compensates without adding its weight again; one with a tool of another mass is refused
/// naming both places.
#[test]
fn lumped_terms_hold_the_tool_of_the_calibration() {
    let bare = heavy_on("", "", &calibrated_text("")).unwrap();
    let terms = Terms::of(
        bare.robot(),
        gravity::Gravity::Lumped,
        Coordinates::Axis,
        Vector6::zeros(),
    )
    .unwrap();
    let own = OwnWeight {
        gravity: "lumped".into(),
        terms: (terms.terms().iter().enumerate())
            .map(|(i, t)| (t.name(), [6e-5, 2e-5, -1e-5, 1.5e-5][i % 4]))
            .collect(),
        tool_mass: Some(40.0),
        tool_centre: None,
    };
    let robot_text = calibrated_text(&stiffid::internal::robot::weight_file::toml(&own));
    let s = heavy_on("", TOOL, &robot_text).unwrap();
    let compliance = plain(&s);
    assert!(tool_load(s.arm(), &compliance).is_none());
    let at = [point(s.test_postures()[0], Vector6::zeros())];
    let options = Options::for_setup(&s);
    compensate::path(s.arm(), &compliance, &at, &options).unwrap();
    let other = TOOL.replace("40.0", "25.0");
    let s = heavy_on("", &other, &robot_text).unwrap();
    let e = compensate::path(s.arm(), &compliance, &at, &options).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("tool.mass_kg") && text.contains("25 kg") && text.contains("40 kg"),
        "{text}"
    );
}

/// Lumped terms calibrated with the tool's centre of mass at 150 mm on the flange's axis hold
/// its moment there: the same 40 kg at 262 mm (44 N m more at the wrist) is refused naming both
/// centres and the moment's difference; 2 mm away (0.78 N m) is taken.
#[test]
fn lumped_terms_hold_the_tools_centre_of_the_calibration() {
    let bare = heavy_on("", "", &calibrated_text("")).unwrap();
    let terms = Terms::of(
        bare.robot(),
        gravity::Gravity::Lumped,
        Coordinates::Axis,
        Vector6::zeros(),
    )
    .unwrap();
    let own = OwnWeight {
        gravity: "lumped".into(),
        terms: (terms.terms().iter().enumerate())
            .map(|(i, t)| (t.name(), [6e-5, 2e-5, -1e-5, 1.5e-5][i % 4]))
            .collect(),
        tool_mass: Some(40.0),
        tool_centre: Some(Vector3::new(0.0, 0.0, 0.15)),
    };
    let robot_text = calibrated_text(&stiffid::internal::robot::weight_file::toml(&own));
    let s = heavy_on("", TOOL, &robot_text).unwrap();
    let compliance = plain(&s);
    let at = [point(s.test_postures()[0], Vector6::zeros())];
    let options = Options::for_setup(&s);
    compensate::path(s.arm(), &compliance, &at, &options).unwrap();
    let near = TOOL.replace("150.0", "152.0");
    let s = heavy_on("", &near, &robot_text).unwrap();
    compensate::path(s.arm(), &compliance, &at, &options).unwrap();
    let far = TOOL.replace("150.0", "262.0");
    let s = heavy_on("", &far, &robot_text).unwrap();
    let e = compensate::path(s.arm(), &compliance, &at, &options).unwrap_err();
    let text = e.to_string();
    // 40 kg * 9.80665 m/s^2 * 0.112 m.
    let moment: f64 = 40.0 * 9.80665 * 0.112;
    assert!((moment - 43.93).abs() < 0.01);
    assert!(
        text.contains("tool.centre_of_mass_mm")
            && text.contains("[0, 0, 262] mm")
            && text.contains("[0, 0, 150] mm")
            && text.contains(&format!(
                "{} N m",
                stiffid::internal::common::words::number(moment)
            )),
        "{text}"
    );
}

/// A setup pointing at a calibrated robot: its `[robot_base]` is not applied again (a note says
/// so; the nominal robot is still mounted on it), its `[[external_axis]]` tables beside the
/// file's calibrated ones and a controller of another robot are refused naming both places.
#[test]
fn a_setup_does_not_repeat_the_calibrated_robot() {
    let riser = "[robot_base]\nxyz_mm = [0.0, 0.0, 300.0]";
    let file = stiffid::internal::robot::file::parse(&calibrated_text(""), "robot.toml").unwrap();
    let at = file.base().translation.vector;
    let nominal = heavy_on(riser, "", &crate::true_robot::dh_robot_text()).unwrap();
    let lift = nominal.robot().base().translation.vector - at;
    assert!(
        (lift - Vector3::new(0.0, 0.0, 0.3)).norm() < 1e-12,
        "{lift}"
    );
    let s = heavy_on(riser, "", &calibrated_text("")).unwrap();
    assert_eq!(s.robot().base(), file.base());
    assert!(
        (s.notes().iter())
            .any(|n| n.kind == stiffid::internal::common::warning::WarningKind::Calibrated),
        "{:?}",
        s.notes()
    );
    let track = "\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1, 0, 0]\nlimits_mm = [0, 6000]\n";
    let e = heavy_on(track, "", &calibrated_text(track))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("heavy.toml: external_axis")
            && e.contains("track")
            && e.contains("comau-smart5-nj165-3.0"),
        "{e}"
    );
    let other = "[controller]\nkinematics = \"nominal\"\nrobot = \"fanuc-r2000ic-165f\"";
    let e = heavy_on(other, "", &calibrated_text(""))
        .unwrap_err()
        .to_string();
    assert!(e.contains("controller.robot") && e.contains("FANUC"), "{e}");
    // The calibrated file itself as the nominal controller's robot: every Cartesian target
    // would move by the calibration's correction.
    let itself = "[controller]\nkinematics = \"nominal\"\nrobot = \"comau-smart5-nj165-3.0\"";
    let e = heavy_on(itself, "", &calibrated_text(""))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("controller.robot") && e.contains("is a calibrated robot file"),
        "{e}"
    );
}

/// A calibrated robot file records the mount it was calibrated on (`[mount]`, which its `[base]`
/// holds): a setup pointing at it that gives `[robot_base]` again is refused naming both
/// places; without it the controller's world is the recorded mount and a nominal controller's
/// robot stands on it, as it did on the setup's `[robot_base]` before the calibration.
#[test]
fn the_calibrated_mount_is_recorded_and_not_given_twice() {
    // The file's [base] holds the mount, as a calibration writes it.
    let mount = "[mount]\nxyz_mm = [0.0, 0.0, 300.0]\nrpy_deg = [0.0, 0.0, 0.0]\n[base]\nxyz_mm = [0.0, 0.0, 300.0]\n";
    let riser = "[robot_base]\nxyz_mm = [0.0, 0.0, 300.0]";
    let recorded = calibrated_text(mount);
    let file = stiffid::internal::robot::file::parse(&recorded, "robot.toml").unwrap();
    let lift = Vector3::new(0.0, 0.0, 0.3);
    assert!((file.mount().unwrap().translation.vector - lift).norm() < 1e-15);
    let e = heavy_on(riser, "", &recorded).unwrap_err().to_string();
    assert!(
        e.contains("heavy.toml: robot_base")
            && e.contains("[mount] xyz_mm = [0, 0, 300]")
            && e.contains("comau-smart5-nj165-3.0"),
        "{e}"
    );
    // Without [robot_base]: the recorded mount is the controller's world, the nominal
    // controller's robot mounted on it; the calibrated robot's base as its file gives it.
    let text = setup::builtin_text("zhang2021-comau-nj165").unwrap().replacen(
        "\n[tool]\n",
        "\n[controller]\nkinematics = \"nominal\"\nrobot = \"nominal\"\n\n[tool]\ntcp_mm = [0.0, 0.0, 300.0]\n",
        1,
    );
    // The nominal robot the calibrated one was calibrated from (its name without the mark).
    let nominal_text: Vec<String> = (crate::true_robot::dh_robot_text().lines())
        .map(|l| match l.starts_with("name = ") {
            true => "name = \"COMAU\"".to_string(),
            false => l.to_string(),
        })
        .collect();
    let nominal_text = nominal_text.join("\n");
    let s = setup::parse(&text, "mounted.toml", |name, _| match name {
        "nominal" => stiffid::internal::robot::file::parse(&nominal_text, "nominal.toml"),
        _ => stiffid::internal::robot::file::parse(&recorded, "robot.toml"),
    })
    .unwrap();
    let c = s.workcell().controller();
    assert!((c.mount.translation.vector - lift).norm() < 1e-15);
    assert_eq!(s.robot().base(), file.base());
    let nominal = stiffid::internal::robot::file::parse(&nominal_text, "nominal.toml").unwrap();
    let controller = c.robot.as_ref().unwrap();
    let raised = controller.base().translation.vector - nominal.base().translation.vector;
    assert!((raised - lift).norm() < 1e-12, "{raised}");
    // The same nominal robot under another name (a controller's file renamed) is the same
    // robot: compared by its kinematics, not its name.
    let renamed = nominal_text.replacen("name = \"COMAU\"", "name = \"cell 4 controller\"", 1);
    let s = setup::parse(&text, "mounted.toml", |name, _| match name {
        "nominal" => stiffid::internal::robot::file::parse(&renamed, "nominal.toml"),
        _ => stiffid::internal::robot::file::parse(&recorded, "robot.toml"),
    })
    .unwrap();
    assert_eq!(s.controller_robot().unwrap().name(), "cell 4 controller");
}

/// A calibrated robot file records the part's frame its calibration located (`[part]`): a setup
/// pointing at it without `[workpiece] base_from_part` takes it with a note, one that repeats it
/// to the file's precision keeps it, one 0.11 deg off is refused naming both places and the
/// difference; a `[workpiece]` without the part's frame and no `[part]` to take it from is refused.
#[test]
fn the_located_part_is_taken_not_contradicted() {
    let part = "[part]\nxyz_mm = [1500.0, -200.0, 400.0]\nrpy_deg = [0.0, 0.0, 30.0]\n";
    let recorded = calibrated_text(part);
    let file = stiffid::internal::robot::file::parse(&recorded, "robot.toml").unwrap();
    let located = *file.part().unwrap();
    assert!((located.translation.vector - Vector3::new(1.5, -0.2, 0.4)).norm() < 1e-15);
    let taken = heavy_on("", "", &recorded).unwrap();
    assert_eq!(taken.workpiece(), Some(&located));
    let note = (taken.notes().iter())
        .find(|n| n.message.contains("[part]"))
        .unwrap();
    assert_eq!(
        note.kind,
        stiffid::internal::common::warning::WarningKind::Calibrated
    );
    let given = |yaw: f64| {
        format!("[workpiece]\nbase_from_part = {{ xyz_mm = [1500.0, -200.0, 400.0], rpy_deg = [0.0, 0.0, {yaw:?}] }}")
    };
    let same = heavy_on(&given(30.0), "", &recorded).unwrap();
    assert!(
        same.workpiece()
            .unwrap()
            .rotation
            .angle_to(&located.rotation)
            < 1e-12
    );
    let e = heavy_on(&given(30.11), "", &recorded)
        .unwrap_err()
        .to_string();
    for words in [
        "heavy.toml: workpiece.base_from_part",
        "comau-smart5-nj165-3.0",
        "[part] xyz_mm = [1500, -200, 400], rpy_deg = [0, 0, 30]",
        "its origin 0 mm away and turned 0.11 deg",
    ] {
        assert!(e.contains(words), "{words}: {e}");
    }
    // No [part] to take: a [workpiece] must give the part's frame.
    let e = heavy_on("[workpiece]", "", &calibrated_text(""))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("workpiece.base_from_part") && e.contains("missing"),
        "{e}"
    );
}
