//! The calibration criteria's study (`crate::study::observability`).

use super::observability::postures;
use crate::observability::{CalibrationCriteria, CalibrationDesign};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid_core::{Error, Result};
use stiffid_metrology::calibration::error_model::{MeasuredIn, Observation};
use stiffid_metrology::calibration::{fit, gravity, validation, ErrorModel, Estimate, Geometry};

/// Most groups of the study.
const MAX_GROUPS: usize = 10_000;

/// Most postures a group.
const MAX_SIZE: usize = 200;

/// The test (held-out) postures of the study.
const TEST_POSTURES: usize = 30;

/// The reference postures that fix the kept parameters.
const REFERENCE_POSTURES: usize = 60;

/// The criteria's names in [`CalibrationStudy::rho`] order.
const CRITERIA: [&str; 6] = ["o1", "o3", "o4", "o5", "d-optimality", "test-pose"];

/// The study's outcome.
#[derive(Debug, Clone, PartialEq)]
struct CalibrationStudy {
    /// Each group's criteria.
    criteria: Vec<CalibrationCriteria>,
    /// Each group's held-out RMS position error, m.
    held_out: Vec<f64>,
    /// Spearman's rho of each criterion ([`CRITERIA`] order) with the held-out error; `None`
    /// when it is undefined (a constant sample). A larger-is-better index predicts well with a
    /// rho near -1, the test-pose error with a rho near +1.
    rho: [Option<f64>; 6],
}

/// The study over `groups` random groups of `size` postures, tracker noise `noise` per
/// coordinate (m), `draws` noise draws a group, from `seed` (module docs).
///
/// # Errors
/// [`Error::InvalidField`] (`groups`, `size`, `draws`) for a count out of its range (3 to
/// [`MAX_GROUPS`] groups, 1 to 200 postures, 1 to 100 draws), (`noise`) for a noise not positive
/// and finite; those of the fit.
fn calibration_study(
    groups: usize,
    size: usize,
    noise: f64,
    draws: usize,
    seed: u64,
) -> Result<CalibrationStudy> {
    for (field, v, hi, lo) in [
        ("groups", groups, MAX_GROUPS, 3),
        ("size", size, MAX_SIZE, 1),
        ("draws", draws, 100, 1),
    ] {
        if !(lo..=hi).contains(&v) {
            return Err(Error::InvalidField {
                field: field.into(),
                message: format!("expected {lo} to {hi}, got {v}"),
            });
        }
    }
    let robot = stiffid_core::robot::presets::get("fanuc-r2000ic-165f")?;
    let points = [
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let model = ErrorModel::new(
        &robot,
        &points,
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(&robot),
    )?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let reference = postures(&robot, REFERENCE_POSTURES, &mut rng);
    let test = postures(&robot, TEST_POSTURES, &mut rng);
    let design = CalibrationDesign::new(model.clone(), 1.0, &reference, &test, noise)?;
    let mut values = model.nominal();
    for v in values.iter_mut().skip(6) {
        *v += 1e-3 * (2.0 * rng.random::<f64>() - 1.0);
    }
    let truth = Estimate {
        frame: Isometry3::new(Vector3::new(3.2, -1.1, 0.4), Vector3::new(0.1, -0.05, 2.4)),
        values,
    };
    let held_out = read(&model, &truth, &test, 0.0, &mut rng)?;
    let options = fit::Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let mut outcome = CalibrationStudy {
        criteria: Vec::with_capacity(groups),
        held_out: Vec::with_capacity(groups),
        rho: [None; 6],
    };
    for _ in 0..groups {
        let group = postures(&robot, size, &mut rng);
        outcome.criteria.push(design.evaluate(&group)?);
        let mut squares = 0.0;
        for _ in 0..draws {
            let readings = read(&model, &truth, &group, noise, &mut rng)?;
            let start = fit::start(&model, &readings)?;
            let f = fit::fit(&model, &readings, &start, &options)?;
            squares += validation::validate(&model, &f.estimate, &held_out)?
                .rms
                .powi(2);
        }
        outcome.held_out.push((squares / draws as f64).sqrt());
    }
    let columns: [fn(&CalibrationCriteria) -> f64; 6] = [
        |c| c.o1,
        |c| c.o3,
        |c| c.o4,
        |c| c.o5,
        |c| c.d_optimality,
        |c| c.predicted_rms,
    ];
    for (rho, column) in outcome.rho.iter_mut().zip(columns) {
        let x: Vec<f64> = outcome.criteria.iter().map(column).collect();
        *rho = crate::study::spearman(&x, &outcome.held_out);
    }
    Ok(outcome)
}

/// Every measuring point of `model` read at every posture of `qs` from `truth`, with Gaussian
/// noise `sd` per coordinate (tracker frame, m).
pub(crate) fn read(
    model: &ErrorModel,
    truth: &Estimate,
    qs: &[Vector6<f64>],
    sd: f64,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<Observation>> {
    let normal = Normal::new(0.0, sd).map_err(|e| Error::InvalidField {
        field: "noise".into(),
        message: e.to_string(),
    })?;
    let at: Vec<(usize, Vector6<f64>, usize)> = (qs.iter().enumerate())
        .flat_map(|(i, q)| (0..model.points()).map(move |k| (i, *q, k)))
        .collect();
    let pairs: Vec<_> = at.iter().map(|(_, q, k)| (*q, *k)).collect();
    let b = model.positions(&truth.values, &pairs)?;
    Ok((at.iter().zip(b))
        .map(|((i, q, k), b)| {
            let t = (truth.frame.inverse() * Point3::from(b)).coords;
            Observation {
                posture: *i,
                point: *k,
                q: *q,
                measured: t + Vector3::from_fn(|_, _| normal.sample(rng)),
                wrench: Vector6::zeros(),
                e: stiffid_core::robot::external::ExternalValues::NONE,
                table: false,
                direction: Vector6::zeros(),
            }
        })
        .collect())
}

/// At a small size every criterion ranks the groups the right way round: the indices
/// against the held-out error, the predicted error with it.
#[test]
fn criteria_predict_held_out_error_at_small_size() {
    let s = calibration_study(16, 12, 5e-5, 1, 1).unwrap();
    let rho = |name: &str| s.rho[CRITERIA.iter().position(|c| *c == name).unwrap()].unwrap();
    assert!(rho("test-pose") > 0.0);
    for index in &CRITERIA[..5] {
        assert!(rho(index) < -0.3, "{index}: {}", rho(index));
    }
    assert!(calibration_study(2, 12, 5e-5, 1, 1).is_err());
    assert!(calibration_study(3, 12, 0.0, 1, 1).is_err());
}

/// With several noise draws a group (the held-out error's expectation, not one draw's
/// luck), the predicted error ranks the groups best of all criteria: the default of
/// `select --for calibration`.
#[test]
fn the_predicted_error_ranks_groups_best() {
    let s = calibration_study(64, 12, 5e-5, 8, 7).unwrap();
    let rho = |name: &str| s.rho[CRITERIA.iter().position(|c| *c == name).unwrap()].unwrap();
    assert!(rho("test-pose") > 0.6, "{}", rho("test-pose"));
    for index in &CRITERIA[..5] {
        assert!(
            rho("test-pose") > -rho(index) + 0.1,
            "{index}: {}",
            rho(index)
        );
    }
}
