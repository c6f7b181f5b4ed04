//! The regressors remembered ([`super::memo`]) are those computed, and each model's peaks are
//! its own terms' (the arm's with its links' axes).

use super::{spanning, Terms};
use nalgebra::Vector6;
use stiffid_core::common::limits::JointBox;
use stiffid_core::robot::dh::{self, Convention, Row};
use stiffid_core::Robot;

/// The UR10 (Universal Robots' standard DH table), an anthropomorphic arm.
fn ur10() -> Robot {
    let half = std::f64::consts::FRAC_PI_2;
    let rows = [
        (0.0, half, 0.1273),
        (-0.612, 0.0, 0.0),
        (-0.5723, 0.0, 0.0),
        (0.0, half, 0.163941),
        (0.0, -half, 0.1157),
        (0.0, 0.0, 0.0922),
    ];
    let joints = rows.map(|(a, alpha, d)| {
        let row = Row {
            a,
            alpha,
            d,
            theta_offset: 0.0,
        };
        dh::joint(Convention::StandardDh, &row)
    });
    let limits = JointBox::new(Vector6::repeat(-3.0), Vector6::repeat(3.0));
    Robot::new("UR10", "test", joints, limits).unwrap()
}

#[test]
fn remembered_regressors_are_the_computed_ones_and_peaks_the_models_own() {
    let robot = ur10();
    for terms in [
        Terms::arm(&robot, Default::default()).unwrap(),
        Terms::lumped_bodies(&robot, Default::default()),
    ] {
        let q = Vector6::new(0.1, -1.2, 0.7, 0.3, -0.4, 0.5);
        let first = terms.regressors(&q);
        assert_eq!(first, terms.computed(&q));
        assert_eq!(terms.regressors(&q), first);
        assert!(first.iter().any(|&y| y.abs() > 1.0), "{first:?}");
        // The peaks, from the memo filled at construction, are the largest computed magnitudes.
        let peaks: Vec<f64> = (0..terms.len())
            .map(|t| {
                (spanning(robot.limits()).iter())
                    .map(|q| terms.computed(q)[t].abs())
                    .fold(0.0, f64::max)
            })
            .collect();
        assert_eq!(terms.peaks(), peaks.as_slice());
        assert!(peaks.iter().any(|&p| p > 1.0), "{peaks:?}");
    }
}
