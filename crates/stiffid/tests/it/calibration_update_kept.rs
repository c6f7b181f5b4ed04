//! `calibrate --update` keeps what the calibration found and refits what its list names: a
//! calibrated robot that sags under its own weight (the calibration's gravity terms, from its
//! robot file or an older stiffness file) drifts in its joint offsets; the update predicts the sag and recovers the
//! offsets, or refits the gravity terms too with `gravity` in its list, and refuses a list the
//! check readings cannot identify.

use super::calibration_update::{
    check_postures, drifted, readings_by, request, robot, setup, DRIFT, OFFSETS,
};
use nalgebra::{DVector, Vector6};
use stiffid::app::calibrate::{self, Refit, Refits, Report};
use stiffid::internal::metrology::calibration::gravity::{Gravity, Terms};
use stiffid::internal::model::OwnWeight;
use stiffid::{Coordinates, Setup};

/// The lumped gravity terms of three bodies on the calibrated robot (the torques on its
/// nominal chain, as the calibration evaluates them), with values that sag the arm by about
/// 0.1 to 1 mm, times `scale`.
fn weight(scale: f64) -> (Terms, OwnWeight) {
    let terms = Terms::of(
        &robot(&OFFSETS),
        Gravity::Lumped,
        Coordinates::Axis,
        Vector6::zeros(),
    )
    .unwrap();
    let values: Vec<f64> = (0..terms.len())
        .map(|i| scale * [6e-5, 2e-5, -1e-5, 1.5e-5][i % 4] * (1.0 + 0.1 * (i / 4) as f64))
        .collect();
    let own = OwnWeight {
        gravity: "lumped".into(),
        terms: (terms.terms().iter().map(|t| t.name()))
            .zip(values)
            .collect(),
        tool_mass: None,
        tool_centre: None,
    };
    (terms, own)
}

/// Readings of the drifted robot sagging under the terms of `weight(scale)`.
fn sagging(
    setup: &Setup,
    postures: &[Vector6<f64>],
    scale: f64,
    (prefix, seed): (&str, u64),
) -> String {
    let (terms, own) = weight(scale);
    let values = DVector::from_iterator(own.terms.len(), own.terms.iter().map(|t| t.1));
    let truth = drifted();
    let frames =
        |q: &Vector6<f64>| truth.frames(&(q + terms.deflection(&values.rows(0, values.len()), q)));
    readings_by(&frames, setup, postures, (prefix, 0.0, seed))
}

fn update_with(
    setup: &Setup,
    data: &str,
    held: &str,
    refit: &str,
    weight: Option<OwnWeight>,
) -> stiffid::Result<Report> {
    calibrate::run(&calibrate::Request {
        refit: Refits::parse(refit)?,
        weight,
        ..request(setup, data, Some(held), true)
    })
    .map(|o| o.report)
}

/// The fitted joint offsets' drift of joints 2 to 5, deg, against the true drift: the largest
/// miss.
fn offset_miss(report: &Report) -> f64 {
    let params = report.model.parameters();
    (1..5)
        .map(|j| {
            let c = (params.iter())
                .position(|p| p.name == format!("joint{}.theta", j + 1))
                .unwrap();
            (report.fit.estimate.values[c].to_degrees() - DRIFT[j]).abs()
        })
        .fold(0.0, f64::max)
}

/// Noise-free, the update with the calibration's stiffness file keeps the sag in its forward
/// model: the offsets are recovered to 1e-9 deg, the held-out readings predicted to 1e-12 m, the
/// gravity terms held at the file's values (listed in `held`, written back unchanged in the
/// compliance); without the file the offsets absorb part of the sag and miss.
#[test]
fn the_update_keeps_the_calibrations_sag() {
    let setup = setup();
    let check = check_postures(&setup);
    let data = sagging(&setup, &check, 1.0, ("C", 1));
    let held = sagging(
        &setup,
        &stiffid::internal::design::random_group(&setup, 20, 7),
        1.0,
        ("H", 2),
    );
    let (_, own) = weight(1.0);
    let report = update_with(&setup, &data, &held, "offsets,base,tool", Some(own.clone())).unwrap();
    let rms = report.validation.as_ref().unwrap().calibrated.rms;
    assert!(rms < 1e-12, "{rms:e}");
    assert!(offset_miss(&report) < 1e-9, "{:e}", offset_miss(&report));
    let document = report.document();
    assert_eq!(document.held.len(), own.terms.len());
    assert!(document.held.iter().all(|n| n.starts_with("gravity.")));
    assert!(document
        .merged
        .iter()
        .all(|m| !m.name.starts_with("gravity.")));
    // The updated robot file carries the terms, unchanged.
    let written = report.robot_toml.as_ref().unwrap();
    let written = stiffid::internal::robot::file::parse(written, "updated.toml").unwrap();
    let carried = written.own_weight().unwrap();
    assert_eq!(carried.gravity, own.gravity);
    for ((n, v), (m, w)) in carried.terms.iter().zip(&own.terms) {
        assert!(
            n == m && (v - w).abs() <= 1e-9 * w.abs().max(1e-9),
            "{n} {v:e} {w:e}"
        );
    }
    let start = report.model.gravity_start();
    for (i, (_, v)) in own.terms.iter().enumerate() {
        assert_eq!(report.fit.estimate.values[start + i], *v);
    }
    // The calibrated robot file carrying the terms gives the same update without the stiffness
    // file; a stiffness file with other terms is refused naming both.
    let carried = setup
        .to_builder()
        .with_robot(setup.robot().clone().with_own_weight(Some(own.clone())))
        .build()
        .unwrap();
    let from_robot = update_with(&carried, &data, &held, "offsets,base,tool", None).unwrap();
    assert!(
        offset_miss(&from_robot) < 1e-9,
        "{:e}",
        offset_miss(&from_robot)
    );
    let (_, other) = weight(1.1);
    let e = update_with(&carried, &data, &held, "offsets,base,tool", Some(other))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("[gravity]") && e.contains("stiffness file"),
        "{e}"
    );
    // Today's update, the sag dropped: the offsets take part of it.
    let dropped = update_with(&setup, &data, &held, "offsets,base,tool", None).unwrap();
    assert!(offset_miss(&dropped) > 1e-3, "{:e}", offset_miss(&dropped));
    let rms = dropped.validation.as_ref().unwrap().calibrated.rms;
    assert!(rms > 1e-5, "{rms:e}");
}

/// With `gravity` in the list the update refits the gravity terms from the file's values: on a
/// robot whose sag grew by 30 % the separable terms move, and the held-out readings are
/// predicted to 1e-8 m noise-free from 60 random postures; the offsets to 1e-6 deg (the bound on
/// the gravity terms, a prior, leaves a noise-free fit nanometres off).
#[test]
fn an_update_with_gravity_refits_the_sag() {
    let setup = setup();
    let postures = stiffid::internal::design::random_group(&setup, 60, 5);
    let data = sagging(&setup, &postures, 1.3, ("C", 1));
    let held = sagging(
        &setup,
        &stiffid::internal::design::random_group(&setup, 20, 7),
        1.3,
        ("H", 2),
    );
    let (_, own) = weight(1.0);
    let kept = update_with(&setup, &data, &held, "offsets,base,tool", Some(own.clone())).unwrap();
    let refit = update_with(&setup, &data, &held, "offsets,base,tool,gravity", Some(own)).unwrap();
    let (k, r) = (
        kept.validation.as_ref().unwrap().calibrated.rms,
        refit.validation.as_ref().unwrap().calibrated.rms,
    );
    assert!(r < 1e-8 && k > 1e-5, "refit {r:e}, kept {k:e}");
    assert!(offset_miss(&refit) < 1e-6, "{:e}", offset_miss(&refit));
    assert!(refit.document().held.is_empty());
}

/// A list without base, with an unknown name or a name twice is refused naming `update`;
/// `gravity` without the stiffness file is refused; a list the check readings cannot identify
/// (the gravity terms from 10 postures designed for the offsets) is refused naming what merges;
/// without `tool` the measuring points are held at the setup's.
#[test]
fn update_lists_are_checked() {
    for (list, says) in [
        ("offsets,tool", "needs base"),
        ("offsets,base,wrist", "unknown value 'wrist'"),
        ("base,base", "listed twice"),
    ] {
        let e = Refits::parse(list).unwrap_err().to_string();
        assert!(e.starts_with("update") && e.contains(says), "{e}");
    }
    assert!(Refits::default().contains(Refit::Tool));
    let setup = setup();
    let check = check_postures(&setup);
    let data = sagging(&setup, &check, 1.0, ("C", 1));
    let held = sagging(&setup, &check, 1.0, ("H", 2));
    let e = update_with(&setup, &data, &held, "offsets,base,gravity", None)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("update") && e.contains("stiffness file"),
        "{e}"
    );
    let (_, own) = weight(1.0);
    let few = &check[..6];
    let data_few = sagging(&setup, few, 1.0, ("C", 1));
    let e = update_with(
        &setup,
        &data_few,
        &held,
        "offsets,base,tool,gravity",
        Some(own.clone()),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("update") && e.contains("cannot identify") && e.contains("merges with"),
        "{e}"
    );
    let report = update_with(&setup, &data, &held, "offsets,base", Some(own)).unwrap();
    let document = report.document();
    assert!(
        document.held.iter().any(|n| n == "point1.x"),
        "{:?}",
        document.held
    );
    assert!(offset_miss(&report) < 1e-9, "{:e}", offset_miss(&report));
}
