//! The external axes against an independent model written here with 4x4 matrices and Rodrigues'
//! formula, and their Jacobian columns against central differences.

use crate::robot::external::ErrorMotions;
use crate::Result;
use nalgebra::{Isometry3, Translation3, Unit, Vector3};

use crate::robot::external::*;
use nalgebra::{Matrix3, Matrix4, Point3, Vector6};

/// A homogeneous 4x4 rotation about the line through `p` along unit `d` by `a` (Rodrigues).
fn rodrigues(p: [f64; 3], d: [f64; 3], a: f64) -> Matrix4<f64> {
    let d = Vector3::from(d).normalize();
    let k = Matrix3::new(0.0, -d.z, d.y, d.z, 0.0, -d.x, -d.y, d.x, 0.0);
    let r = Matrix3::identity() + k * a.sin() + k * k * (1.0 - a.cos());
    let p = Vector3::from(p);
    let mut m = Matrix4::identity();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
    m.fixed_view_mut::<3, 1>(0, 3).copy_from(&(p - r * p));
    m
}

fn tilt_rotate() -> ExternalAxes {
    let tilt = ExternalAxis::rotary(
        "tilt",
        Vector3::new(2.0, 0.5, 0.8),
        Unit::new_normalize(Vector3::new(1.0, 0.1, 0.0)),
        -2.0,
        2.0,
    );
    let turn = ExternalAxis {
        offset: 0.05,
        ..ExternalAxis::rotary(
            "turn",
            Vector3::new(2.1, 0.45, 0.6),
            Unit::new_normalize(Vector3::new(0.0, 0.05, 1.0)),
            -7.0,
            7.0,
        )
    };
    let track = ExternalAxis::linear(
        "track",
        Unit::new_normalize(Vector3::new(1.0, 0.02, 0.0)),
        -0.5,
        6.0,
    );
    ExternalAxes::new(vec![tilt, turn, track]).unwrap()
}

#[test]
fn the_positioner_moves_the_part_as_the_product_of_its_rotations() {
    let axes = tilt_rotate();
    assert_eq!(axes.column_names(), ["e1_mm", "e2_deg", "e3_deg"]);
    let e = [1.2, 0.7, -2.1];
    let p = axes.positioner_pose(&e).to_homogeneous();
    let reference = rodrigues([2.0, 0.5, 0.8], [1.0, 0.1, 0.0], 0.7)
        * rodrigues([2.1, 0.45, 0.6], [0.0, 0.05, 1.0], -2.1 + 0.05);
    assert!((p - reference).abs().max() < 1e-12, "{p} {reference}");
    let track = axes.carrier_pose(&e).to_homogeneous();
    let along = Vector3::new(1.0, 0.02, 0.0).normalize() * 1.2;
    assert!((track.fixed_view::<3, 1>(0, 3) - along).norm() < 1e-15);
}

#[test]
fn the_columns_are_the_derivatives_of_the_positions() {
    let axes = tilt_rotate();
    let e = [2.5, -0.4, 1.3];
    let x = Vector3::new(2.3, 0.2, 1.1);
    let arm = Vector3::new(0.4, -0.3, 1.5);
    let moved = |e: &[f64]| {
        let part = axes.positioner_pose(e) * Point3::from(x);
        let tool = axes.carrier_pose(e) * Point3::from(arm);
        (tool.coords, part.coords)
    };
    let carrier = axes.carrier_columns(&e);
    let positioner =
        axes.positioner_columns(&e, &(axes.positioner_pose(&e) * Point3::from(x)).coords);
    let h = 1e-6;
    for i in 0..3 {
        let (mut plus, mut minus) = (e, e);
        plus[i] += h;
        minus[i] -= h;
        let ((tp, pp), (tm, pm)) = (moved(&plus), moved(&minus));
        let (dt, dp) = ((tp - tm) / (2.0 * h), (pp - pm) / (2.0 * h));
        let (expected_t, expected_p) = match i {
            0 => (carrier[0], Vector3::zeros()),
            _ => (Vector3::zeros(), positioner[i - 1]),
        };
        assert!(
            (dt - expected_t).norm() < 1e-8,
            "axis {i}: {dt} {expected_t}"
        );
        assert!(
            (dp - expected_p).norm() < 1e-8,
            "axis {i}: {dp} {expected_p}"
        );
    }
}

#[test]
fn an_arm_on_a_track_is_the_arm_moved_along_it() {
    let robot = crate::robot::presets::get("kuka-kr210-robond").unwrap();
    let fixed = robot.clone();
    let track = ExternalAxis::linear(
        "track",
        Unit::new_normalize(Vector3::new(0.6, 0.8, 0.0)),
        0.0,
        6.0,
    );
    let robot = robot.with_external(Some(ExternalAxes::new(vec![track]).unwrap()));
    let q = Vector6::new(0.3, -1.2, 1.4, 0.5, 0.8, -0.2);
    let at = robot.frames_at(&q, &[2.5]);
    let here = fixed.frames(&q);
    let shift = Vector3::new(0.6, 0.8, 0.0) * 2.5;
    for i in 0..6 {
        let d = at.joints[i].translation.vector - here.joints[i].translation.vector;
        assert!((d - shift).norm() < 1e-12);
    }
    assert_eq!(robot.frames(&q), here);
    assert_eq!(robot.frames_at(&q, &[0.0]), here);
}

#[test]
fn error_motions_move_the_carriage_in_the_axis_frame() {
    let motions = ErrorMotions::new(vec![
        [1e-4, 2e-4, -3e-4, 1e-5, 2e-4, -1e-4],
        [0.0, 3e-4, 0.0, 0.0, 0.0, 0.0],
    ])
    .unwrap();
    let axis = ExternalAxis {
        errors: motions,
        ..ExternalAxis::linear("track", Unit::new_normalize(Vector3::y()), 0.0, 4.0)
    };
    let frame = axis.frame().to_rotation_matrix();
    assert!((frame * Vector3::x() - Vector3::y()).norm() < 1e-15);
    assert!((frame * Vector3::z() - Vector3::z()).norm() < 1e-15);
    let axes = ExternalAxes::new(vec![axis]).unwrap();
    // At 3 m of 0..4 m, u = 0.5: the straightness y (across the axis: -x in the cell) is
    // 2e-4 u + 3e-4 u^2, the positioning error 1e-4 u along the axis.
    let pose = axes.carrier_pose(&[3.0]);
    let t = pose.translation.vector;
    let expected = Vector3::new(-(2e-4 * 0.5 + 3e-4 * 0.25), 3.0 + 1e-4 * 0.5, -3e-4 * 0.5);
    assert!((t - expected).norm() < 1e-15, "{t} {expected}");
    let r = pose.rotation.scaled_axis();
    let expected = Vector3::new(-2e-4 * 0.5, 1e-5 * 0.5, -1e-4 * 0.5);
    assert!((r - expected).norm() < 1e-15, "{r} {expected}");
    assert_eq!(
        axes.carrier_pose(&[2.0]),
        Isometry3::identity() * Translation3::new(0.0, 2.0, 0.0)
    );
}

#[test]
fn bad_axes_are_refused_naming_the_axis() {
    let track = |name: &str| ExternalAxis::linear(name, Vector3::x_axis(), 0.0, 6.0);
    let message = |r: Result<ExternalAxes>| r.unwrap_err().to_string();
    assert!(message(ExternalAxes::new(vec![])).contains("1 to 5"));
    let four = (0..4).map(|i| track(&format!("x{i}"))).collect();
    assert!(message(ExternalAxes::new(four)).contains("at most 3 carrier"));
    assert!(message(ExternalAxes::new(vec![track("a"), track("a")])).contains("twice"));
    let wrong = ExternalAxis {
        role: Role::Positioner,
        ..track("p")
    };
    assert!(message(ExternalAxes::new(vec![wrong])).contains("rotary positioner"));
    let empty = ExternalAxis {
        upper: 0.0,
        ..track("t")
    };
    let m = message(ExternalAxes::new(vec![empty]));
    assert!(
        m.contains("external_axis[1] (t) limits") && m.contains("0 to 0 mm"),
        "{m}"
    );
    let nan = ExternalAxis {
        offset: f64::NAN,
        ..track("t")
    };
    assert!(message(ExternalAxes::new(vec![nan])).contains("finite"));
    let axes = ExternalAxes::new(vec![track("rail")]).unwrap();
    let m = axes
        .check(&[6.5], "postures.csv line 3")
        .unwrap_err()
        .to_string();
    assert!(
        m.contains("e1_mm (rail)") && m.contains("0 to 6000 mm, got 6500"),
        "{m}"
    );
    assert!(axes
        .check(&[1.0, 2.0], "e")
        .unwrap_err()
        .to_string()
        .contains("expected 1"));
    assert!(axes.check(&[f64::NAN], "e").is_err());
    assert!(axes.check(&[6.0 + 1e-12], "e").is_ok());
    assert_eq!(axes.to_display(&axes.to_si(&[1234.5])), [1234.5]);
}
