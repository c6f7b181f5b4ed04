//! The misfit warning's hint ([`super::judge::judge`]): it names only the gravity models the
//! robot takes that the ladder did not just try.

use super::judge::judge;
use super::ladder::{Ladder, Rung};
use crate::calibration::error_model::{ErrorModel, MeasuredIn, Observation};
use crate::calibration::fit::{self, Options};
use crate::calibration::gravity::{Gravity, Terms};
use crate::calibration::Geometry;
use nalgebra::{Vector3, Vector6};
use stiffid_core::common::limits::JointBox;
use stiffid_core::robot::dh::{self, Convention, Row};
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::Robot;

/// The UR10 (Universal Robots' standard DH table): an anthropomorphic arm without link masses.
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
        dh::joint(
            Convention::StandardDh,
            &Row {
                a,
                alpha,
                d,
                theta_offset: 0.0,
            },
        )
    });
    let limits = JointBox::new(Vector6::repeat(-6.0), Vector6::repeat(6.0));
    Robot::new("UR10", "test", joints, limits).unwrap()
}

/// A rung of the ladder tried and lost (scored, not chosen).
fn tried(gravity: Gravity) -> Rung {
    Rung {
        gravity,
        maps: false,
        rms: Some(5e-4),
        skipped: None,
        spread: None,
        errors: vec![2.5e-7; 10],
    }
}

/// The rigid model's misfit on readings 1 mm off the nominal robot: without a ladder the hint
/// names `arm` and `lumped` (no `masses`: the robot has none); after a ladder that tried the
/// geometry and `lumped`, `arm` alone; after one that tried both, none, saying so.
#[test]
fn the_misfit_hint_names_only_untried_models() {
    let robot = ur10();
    let points = [Vector3::new(0.0, 0.0, 0.1)];
    let model = ErrorModel::new(
        &robot,
        &points,
        MeasuredIn::Base,
        Geometry::Offsets,
        Terms::none(&robot),
    )
    .unwrap();
    let obs: Vec<Observation> = (0..12)
        .map(|i| {
            let q = Vector6::from_fn(|j, _| 0.3 * ((i * 6 + j) as f64).sin());
            let mut o = Observation {
                posture: i,
                point: 0,
                q,
                measured: Vector3::zeros(),
                wrench: Vector6::zeros(),
                e: ExternalValues::NONE,
                table: false,
                direction: Vector6::zeros(),
            };
            let b = model.predict(&model.nominal(), &[o.clone()]).unwrap()[0];
            o.measured = b + Vector3::new(1e-3 * (i as f64).cos(), 0.0, 0.0);
            o
        })
        .collect();
    let options = Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let start = fit::start(&model, &obs).unwrap();
    let f = fit::fit(&model, &obs, &start, &options).unwrap();
    let ladder = |rungs: Vec<Rung>| Ladder {
        folds: 5,
        rungs,
        chosen: 0,
        region: JointBox::new(Vector6::repeat(-1.0), Vector6::repeat(1.0)),
    };
    let hint = |ladder: Option<&Ladder>| {
        let w = judge((&model, &f, ladder), 30.0, "fit.csv");
        let misfit = w
            .iter()
            .find(|w| w.message.contains("times the tracker noise"));
        misfit.unwrap().message.clone()
    };
    assert!(
        hint(None).ends_with("(try --gravity arm or lumped)"),
        "{}",
        hint(None)
    );
    let some = ladder(vec![tried(Gravity::None), tried(Gravity::Lumped)]);
    assert!(hint(Some(&some)).ends_with("(try --gravity arm)"));
    let all = ladder(vec![
        tried(Gravity::None),
        tried(Gravity::Arm),
        tried(Gravity::Lumped),
    ]);
    let text = hint(Some(&all));
    assert!(!text.contains("try --gravity"), "{text}");
    assert!(
        text.contains("predict the held-out groups no better"),
        "{text}"
    );
}
