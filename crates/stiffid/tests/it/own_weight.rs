//! The own weight in compensation and the controller's kinematics: a stiffness file's `gravity`
//! section read and checked, the sag of a robot with link masses compensated (the loaded, sagging
//! TCP on the rigid target, checked against the sag computed here from the potential energy), and
//! `[controller]` read and refused where it means nothing.

use nalgebra::{Point3, Vector3, Vector6};
use stiffid::internal::machining::compensate::{self, Options, PathPoint, Target};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::ik::tool_pose;
use stiffid::{internal::setup, Error};

const SETUP: &str = "zhang2021-comau-nj165";

/// The paper's setup with a TCP, its robot with link masses ([`crate::true_robot::dh_robot_text`]).
fn heavy_setup(extra: &str) -> stiffid::Setup {
    heavy_on(extra, "", &crate::true_robot::dh_robot_text()).unwrap()
}

/// The paper's setup with a TCP and `tool` in its `[tool]`, `extra` before it, its robot
/// `robot_text`.
pub(crate) fn heavy_on(
    extra: &str,
    tool: &str,
    robot_text: &str,
) -> stiffid::Result<stiffid::Setup> {
    let text = setup::builtin_text(SETUP)
        .unwrap()
        .replacen(
            "\n[tool]\n",
            &format!("\n[tool]\ntcp_mm = [0.0, 0.0, 300.0]\n{tool}"),
            1,
        )
        .replacen("\n[tool]", &format!("\n{extra}\n[tool]"), 1);
    setup::parse(&text, "heavy.toml", |name, _| match name {
        "comau-smart5-nj165-3.0" => stiffid::internal::robot::file::parse(robot_text, "robot.toml"),
        other => stiffid::internal::robot::presets::get(other),
    })
}

/// A stiffness file of the setup's nominal stiffness with `gravity`.
pub(crate) fn file_with(gravity: &str) -> String {
    format!(
        r#"{{"stiffness_nm_per_rad": [950000.0, 3000000.0, 900000.0, 250000.0, 200000.0, 150000.0], "gravity": {gravity}}}"#
    )
}

pub(crate) fn masses_section() -> String {
    let k = [950000.0, 3000000.0, 900000.0, 250000.0, 200000.0, 150000.0];
    let terms: Vec<String> = (0..6)
        .map(|j| {
            format!(
                r#"{{"name": "gravity.c{}", "value_si": {:e}}}"#,
                j + 1,
                1.0 / k[j]
            )
        })
        .collect();
    format!(r#"{{"model": "masses", "terms": [{}]}}"#, terms.join(", "))
}

/// The sag of the joints under the link masses, from the potential energy `V(q) = -sum m_l g .
/// p_l(q)` by central differences: `dq = c .* (-dV/dq)`.
pub(crate) fn sag(robot: &stiffid::Robot, c: &Vector6<f64>, q: &Vector6<f64>) -> Vector6<f64> {
    let masses = robot.masses().unwrap();
    let g = Vector3::new(
        0.0,
        0.0,
        -stiffid::internal::metrology::calibration::gravity::G,
    );
    let energy = |q: &Vector6<f64>| {
        let f = robot.frames(q);
        (0..6)
            .map(|l| {
                -masses[l].mass * g.dot(&(f.joints[l] * Point3::from(masses[l].centre)).coords)
            })
            .sum::<f64>()
    };
    let h = 1e-6;
    Vector6::from_fn(|j, _| {
        let e = Vector6::ith(j, h);
        -(energy(&(q + e)) - energy(&(q - e))) / (2.0 * h) * c[j]
    })
}

/// With the gravity terms of known masses the compensated angles put the sagging, loaded TCP on
/// the rigid robot's target: the sag computed here from the potential energy, plus the process
/// deflection, at the compensated angles lands within 0.1 um of it; without the terms the same
/// robot misses by the sag, about a millimetre.
#[test]
fn compensation_adds_the_sag_under_the_robots_weight() {
    let s = heavy_setup("");
    let file = stiffid::internal::io::stiffness::parse(&file_with(&masses_section())).unwrap();
    let compliance = file.compliance(s.model()).unwrap();
    assert!(compliance.own_weight.is_some());
    let q = s.test_postures()[0];
    let wrench = Vector6::new(150.0, -80.0, -200.0, 0.0, 0.0, 0.0);
    let point = PathPoint {
        line: 1,
        target: Target::Posture(q),
        wrench,
        frame: Frame::Base,
        external: stiffid::internal::robot::external::ExternalValues::NONE,
    };
    let options = Options::for_setup(&s);
    let with =
        compensate::path(s.arm(), &compliance, std::slice::from_ref(&point), &options).unwrap();
    let plain = stiffid::internal::model::Compliance {
        own_weight: None,
        ..compliance.clone()
    };
    let without = compensate::path(s.arm(), &plain, &[point], &options).unwrap();
    let robot = s.robot();
    let c = compliance.drives_h();
    let tcp = s.tool().tcp;
    let target = tool_pose(&robot.frames(&q), &tcp);
    // The true robot: sag and the wrench's deflection (J^T W by central differences).
    let lands = |qc: &Vector6<f64>| {
        let h = 1e-7;
        let tau = Vector6::from_fn(|j, _| {
            let e = Vector6::ith(j, h);
            let p = |q: &Vector6<f64>| tool_pose(&robot.frames(q), &tcp);
            let (a, b) = (p(&(qc + e)), p(&(qc - e)));
            let dp = (a.translation.vector - b.translation.vector) / (2.0 * h);
            let dr = (a.rotation * b.rotation.inverse()).scaled_axis() / (2.0 * h);
            dp.dot(&wrench.fixed_rows::<3>(0)) + dr.dot(&wrench.fixed_rows::<3>(3))
        });
        let dq = sag(robot, &c, qc) + tau.component_mul(&c);
        (tool_pose(&robot.frames(&(qc + dq)), &tcp)
            .translation
            .vector
            - target.translation.vector)
            .norm()
    };
    let (hit, miss) = (
        lands(&with[0].q_compensated),
        lands(&without[0].q_compensated),
    );
    assert!(hit < 2e-7, "{hit}");
    assert!(miss > 1e-4, "{miss}");
}

/// A gravity section that is not the setup's model, or not finite, is refused naming the field.
#[test]
fn a_wrong_gravity_section_is_refused() {
    let text =
        file_with(r#"{"model": "masses", "terms": [{"name": "gravity.c1", "value_si": "NaN"}]}"#);
    assert!(stiffid::internal::io::stiffness::parse(&text).is_err());
    let text = file_with(r#"{"model": "masses", "terms": []}"#);
    let e = stiffid::internal::io::stiffness::parse(&text)
        .unwrap_err()
        .to_string();
    assert!(e.contains("gravity.terms"), "{e}");
    let s = heavy_setup("");
    let options = Options::for_setup(&s);
    let point = PathPoint {
        line: 1,
        target: Target::Posture(s.test_postures()[0]),
        wrench: Vector6::zeros(),
        frame: Frame::Base,
        external: stiffid::internal::robot::external::ExternalValues::NONE,
    };
    for (section, field) in [
        (
            masses_section().replace("\"masses\"", "\"heavy\""),
            "gravity.model",
        ),
        (
            masses_section().replace("\"masses\"", "\"lumped\""),
            "gravity.terms",
        ),
    ] {
        let file = stiffid::internal::io::stiffness::parse(&file_with(&section)).unwrap();
        let c = file.compliance(s.model()).unwrap();
        let e = compensate::path(s.arm(), &c, std::slice::from_ref(&point), &options).unwrap_err();
        assert!(
            matches!(&e, Error::InvalidField { field: f, .. } if f == field),
            "{e}"
        );
    }
}

/// `[controller]`: the robot file the controller runs gives the Cartesian targets' kinematics; a
/// calibrated robot without it is refused; a robot with `kinematics = "calibrated"` or an
/// unknown kinematics is refused naming the field.
#[test]
fn the_controller_kinematics_are_read_and_checked() {
    let s =
        heavy_setup("[controller]\nkinematics = \"nominal\"\nrobot = \"comau-smart5-nj165-3.0\"");
    assert_eq!(s.controller_robot().unwrap(), s.robot());
    let plain = heavy_setup("");
    assert_eq!(plain.controller_robot().unwrap(), plain.robot());
    let text: Vec<String> =
        include_str!("../../../stiffid-core/presets/comau-smart5-nj165-3.0.toml")
            .lines()
            .map(|l| match l.starts_with("name = ") {
                true => format!("name = \"COMAU{}\"", stiffid::internal::robot::CALIBRATED),
                false => l.to_string(),
            })
            .collect();
    let text = text.join("\n");
    let calibrated = stiffid::internal::robot::file::parse(&text, "c.toml").unwrap();
    assert!(calibrated.is_calibrated(), "{}", calibrated.name());
    let setup = plain.to_builder().with_robot(calibrated).build().unwrap();
    let e = setup.controller_robot().unwrap_err().to_string();
    assert!(e.contains("controller.robot"), "{e}");
    let setup = setup
        .to_builder()
        .with_controller(setup::Controller {
            kinematics: setup::Kinematics::Calibrated,
            ..Default::default()
        })
        .build()
        .unwrap();
    assert_eq!(setup.controller_robot().unwrap(), setup.robot());
    for (extra, field) in [
        (
            "[controller]\nkinematics = \"exact\"",
            "controller.kinematics",
        ),
        (
            "[controller]\nkinematics = \"calibrated\"\nrobot = \"comau-smart5-nj165-3.0\"",
            "controller.robot",
        ),
    ] {
        let text = setup::builtin_text(SETUP).unwrap().replacen(
            "\n[tool]",
            &format!("\n{extra}\n[tool]"),
            1,
        );
        let e = setup::parse(&text, "s.toml", |r, _| {
            stiffid::internal::robot::presets::get(r)
        })
        .unwrap_err()
        .to_string();
        assert!(e.contains(field), "{e}");
    }
}
