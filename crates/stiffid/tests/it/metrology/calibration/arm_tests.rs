//! The arm's three gravity terms ([`gravity::Gravity::Arm`]): recovered from noise-free readings
//! of a true robot whose only weights are two point masses on the upper arm's and the forearm's
//! axes (the true deflection from [`gravity::Terms::masses`], the torques of the known masses),
//! and refused on a robot that is not an anthropomorphic arm.

use super::error_model::MeasuredIn;
use super::fit::{self, Options};
use super::gravity::{self, LinkMass};
use super::tests::{points, postures, readings, tracker};
use super::*;
use nalgebra::{Matrix3x2, Point3, Vector3, Vector6};
use stiffid_core::robot::presets;
use stiffid_core::{Coordinates, Robot};

/// The component of `d` across the unit axis `z`.
fn across(d: Vector3<f64>, z: Vector3<f64>) -> Vector3<f64> {
    d - z * z.dot(&d)
}

/// The point of joint 4's axis nearest joint 5's, by least squares on the two lines.
fn wrist(robot: &Robot) -> Vector3<f64> {
    let f = robot.frames(&Vector6::zeros());
    let (p, z) = (f.axis_points, f.axis_directions);
    let a = Matrix3x2::from_columns(&[z[3], -z[4]]);
    let st = a.svd(true, true).solve(&(p[4] - p[3]), 1e-12).unwrap();
    p[3] + z[3] * st[0]
}

#[test]
fn the_three_terms_are_recovered_from_noise_free_readings() {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let f = robot.frames(&Vector6::zeros());
    let (p, z) = (f.axis_points, f.axis_directions);
    // The upper arm's axis from joint 2's axis to joint 3's, the forearm's from joint 3's to
    // the wrist; 210 kg at 45 % of the upper arm, 330 kg at 40 % of the forearm.
    let (upper, fore) = (
        across(p[2] - p[1], z[1]),
        across(wrist(&robot) - p[2], z[2]),
    );
    let (m1, m2) = (210.0, 330.0);
    let centres = [p[1] + 0.45 * upper, p[2] + 0.4 * fore];
    let masses: [LinkMass; 6] = std::array::from_fn(|l| match l {
        1 | 2 => LinkMass {
            mass: [m1, m2][l - 1],
            centre: (f.joints[l].inverse() * Point3::from(centres[l - 1])).coords,
            ..LinkMass::default()
        },
        _ => LinkMass::default(),
    });
    let compliance = Vector6::new(1.2e-6, 3.5e-7, 5.4e-7, 3.6e-6, 2.4e-6, 3.6e-6);
    let truth_gravity =
        gravity::Terms::masses(&robot, masses, Coordinates::Kinematic, compliance).unwrap();
    let truth_model = ErrorModel::new(
        &robot,
        &points(),
        MeasuredIn::Tracker,
        Geometry::Full,
        truth_gravity,
    )
    .unwrap();
    // a = c_2 (m_1 r_1 + m_2 L_2), b = c_2 m_2 r_2, c = c_3 m_2 r_2.
    let (l2, r1, r2) = (upper.norm(), 0.45 * upper.norm(), 0.4 * fore.norm());
    let want = [
        compliance[1] * (m1 * r1 + m2 * l2),
        compliance[1] * m2 * r2,
        compliance[2] * m2 * r2,
    ];
    let mut values = truth_model.nominal();
    for (c, prm) in truth_model.parameters().iter().enumerate() {
        if let Target::Joint { component, .. } = prm.target {
            values[c] += if component.is_angle() { 2e-4 } else { 1e-4 } * (1.0 + c as f64 % 3.0);
        }
    }
    let truth = Estimate {
        frame: tracker(),
        values,
    };
    let obs = readings(&truth_model, &truth, &postures(&robot, 40, 7));
    let model = ErrorModel::new(
        &robot,
        &points(),
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::arm(&robot, Coordinates::Kinematic).unwrap(),
    )
    .unwrap();
    let options = Options {
        length: 1.2,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let start = fit::start(&model, &obs).unwrap();
    let fitted = fit::fit(&model, &obs, &start, &options).unwrap();
    let got = fitted.estimate.values.rows(model.gravity_start(), 3);
    let names: Vec<String> = model.gravity().terms().iter().map(|t| t.name()).collect();
    assert_eq!(
        names,
        [
            "gravity.c2.upper-arm",
            "gravity.c2.forearm",
            "gravity.c3.forearm"
        ]
    );
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() <= 1e-9 * w.abs(), "{got} against {want:?}");
    }
}

#[test]
fn a_robot_that_is_not_an_anthropomorphic_arm_is_refused() {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    // The robot laid on its side: joint 1 horizontal.
    let side = nalgebra::Isometry3::rotation(Vector3::new(std::f64::consts::FRAC_PI_2, 0.0, 0.0));
    let tilted = robot.clone().with_base(side * robot.base()).unwrap();
    let e = gravity::Terms::arm(&tilted, Coordinates::Kinematic)
        .unwrap_err()
        .to_string();
    assert!(e.contains("joint 1 is not vertical"), "{e}");
    assert!(gravity::Terms::arm(&robot, Coordinates::Axis).is_ok());
}
