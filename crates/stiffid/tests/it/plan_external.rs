//! The measurement plan of postures read at external values (a station on the track, the
//! table's angles): each posture's rope is the arm's on its carriage there (its length the
//! distance from the anchor to the loading point of the kinematics at those values), its values
//! are the plan's, and its obstacle check sees the box on the table turned there (the
//! clearance the arm's distance to the turned box).

use crate::carried_obstacles::{arm_to_box, track_cell, PLATE};
use stiffid::app::plan::{self, Request};
use stiffid::internal::cell::CheckKind;
use stiffid::internal::robot::external::ExternalValues;

#[test]
fn a_plans_postures_stand_where_they_are_read() {
    let setup = track_cell(&PLATE.replace("AXIS", "rotate")).unwrap();
    let q = stiffid::internal::design::random_group(&setup.without_cell(), 3, 5);
    let e: Vec<Vec<f64>> = (0..3)
        .map(|k| {
            vec![
                3.0 + 0.5 * k as f64,
                (20.0 - 15.0 * k as f64).to_radians(),
                1.0 + k as f64,
            ]
        })
        .collect();
    let run = |external: &[Vec<f64>]| {
        plan::run(&Request {
            scene: false,
            setup: &setup,
            criterion: stiffid::internal::design::Criterion::RelativeA,
            postures: &q,
            target_pct: None,
            external,
        })
        .unwrap()
    };
    let (there, at_zero) = (run(&e), run(&vec![vec![0.0; 3]; 3]));
    // Without the values the plan is refused: it would stand every posture at every axis 0.
    let none = plan::run(&Request {
        scene: false,
        setup: &setup,
        criterion: stiffid::internal::design::Criterion::RelativeA,
        postures: &q,
        target_pct: None,
        external: &[],
    });
    let Err(e0) = none else { panic!("not refused") };
    let e0 = e0.to_string();
    assert!(
        e0.contains("external: none given: the robot has external axes (e1_mm, "),
        "{e0}"
    );
    let plate = &setup.cell().unwrap().obstacles[0];
    for (i, (p, e)) in there.postures.iter().zip(&e).enumerate() {
        assert_eq!(&p.external, e);
        let frames = setup.robot().frames_at(&q[i], e);
        let loading = frames.point(&setup.tool().loading_point);
        let rope = (setup.load().anchor - loading).norm();
        assert!(
            (p.rope_length - rope).abs() < 1e-12,
            "{i}: {} {rope}",
            p.rope_length
        );
        let moved = (p.rope_length - at_zero.postures[i].rope_length).abs();
        assert!(moved > 1e-3, "{i}: the station moves the rope by {moved} m");
        let at = ExternalValues::new(e).unwrap();
        let turned = plate.at(setup.robot().external(), e);
        let check = (p.feasibility.checks.iter())
            .find(|c| c.kind == CheckKind::Obstacles)
            .unwrap();
        let d = arm_to_box(&setup, &q[i], &at, &turned);
        assert!(
            (check.clearance.unwrap() - d).abs() < 1e-9,
            "{i}: {check:?} {d}"
        );
    }
}
