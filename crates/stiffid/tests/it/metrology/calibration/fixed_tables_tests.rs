//! Reflectors fixed in a cell without a positioner (`ErrorModel::with_tables`): each a free
//! point of the cell, read through the tracker's registration. Their Jacobian against central
//! differences on a fixed base and on a track, their noise-free recovery, and the refusals.

use super::error_model::{MeasuredIn, Observation};
use super::fit::{self, Options};
use super::tests::{matches_central_differences, points, postures, tracker};
use super::*;
use nalgebra::{DVector, Isometry3, Point3, Vector3, Vector6};
use stiffid_core::robot::external::{ExternalAxes, ExternalAxis, ExternalValues};
use stiffid_core::robot::presets;
use stiffid_core::Robot;

fn model(robot: &Robot) -> ErrorModel {
    ErrorModel::new(
        robot,
        &points(),
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(robot),
    )
    .unwrap()
}

/// A reflector on the part, cell frame, m.
fn on_part(k: usize) -> Vector3<f64> {
    Vector3::new(
        1.6 + 0.25 * k as f64,
        -0.4 + 0.3 * k as f64,
        0.5 + 0.05 * k as f64,
    )
}

/// The readings (tracker frame at `truth`, noise-free) of every measuring point at 12 postures
/// (on a track at stations 0 to 4 m) and of each reflector twice, beside two postures.
fn campaign(model: &ErrorModel, truth: &Estimate) -> Vec<Observation> {
    let track = model.robot().external().is_some();
    let qs = postures(model.robot(), 12, 5);
    let station = |i: usize| match track {
        true => ExternalValues::new(&[i as f64 / 3.0]).unwrap(),
        false => ExternalValues::NONE,
    };
    let reading = |posture: usize, point: usize, table: bool| Observation {
        posture,
        point,
        q: qs[posture],
        measured: Vector3::zeros(),
        wrench: Vector6::zeros(),
        e: station(posture),
        table,
        direction: Vector6::zeros(),
    };
    let mut obs: Vec<Observation> = (0..qs.len())
        .flat_map(|i| (0..model.points()).map(move |k| (i, k)))
        .map(|(i, k)| reading(i, k, false))
        .collect();
    for posture in [0, 7] {
        obs.extend((0..model.tables()).map(|k| reading(posture, k, true)));
    }
    let b = model.predict(&truth.values, &obs).unwrap();
    for (o, b) in obs.iter_mut().zip(b) {
        o.measured = (truth.frame.inverse() * Point3::from(b)).coords;
    }
    obs
}

/// The nominal values with the joints' errors of a real arm and the reflectors on the part.
fn truth(model: &ErrorModel) -> DVector<f64> {
    let mut x = model.nominal();
    for (c, p) in model.parameters().iter().enumerate() {
        x[c] += match p.target {
            Target::Joint { joint, .. } => 3e-4 * ((c + joint) as f64).sin(),
            Target::Table { point, axis } => on_part(point)[axis],
            _ => 0.0,
        };
    }
    x
}

fn track() -> Robot {
    let rail = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 4.0);
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    robot.with_external(Some(ExternalAxes::new(vec![rail]).unwrap()))
}

#[test]
fn fixed_reflectors_jacobian_matches_central_differences() {
    let fixed = model(&presets::get("fanuc-r2000ic-165f").unwrap())
        .with_tables(3)
        .unwrap();
    let on_track = model(&track()).with_external(&[0], 3).unwrap();
    for model in [fixed, on_track] {
        assert_eq!(model.tables(), 3);
        let x = truth(&model);
        let obs = campaign(
            &model,
            &Estimate {
                frame: Isometry3::identity(),
                values: x.clone(),
            },
        );
        let j = model.jacobian_of(&x, &obs).unwrap();
        // A fixed reflector's rows: the frame's columns and its own coordinates' (the identity).
        let row = obs.iter().position(|o| o.table && o.point == 1).unwrap();
        let own = (model.parameters().iter())
            .position(|p| p.name == "table2.x")
            .unwrap();
        let block = j.fixed_view::<3, 3>(3 * row, own);
        assert_eq!(block.into_owned(), nalgebra::Matrix3::identity());
        matches_central_differences(&model, &x, &j, |v| model.predict(v, &obs).unwrap());
    }
}

/// Noise-free readings of the arm and of three reflectors fixed in the cell: the fit returns
/// each reflector where it is (cell frame) to 1e-9 m, on a fixed base and on a track.
#[test]
fn noise_free_fixed_reflectors_are_recovered() {
    let fixed = model(&presets::get("fanuc-r2000ic-165f").unwrap())
        .with_tables(3)
        .unwrap();
    let on_track = model(&track()).with_external(&[0], 3).unwrap();
    for model in [fixed, on_track] {
        let truth = Estimate {
            frame: tracker(),
            values: truth(&model),
        };
        let obs = campaign(&model, &truth);
        let options = Options {
            length: 1.0,
            priors: None,
            ridge: 0.0,
            gravity: None,
        };
        let start = fit::start(&model, &obs).unwrap();
        let found = fit::fit(&model, &obs, &start, &options).unwrap();
        assert!(found.rms < 1e-9, "{}", found.rms);
        // The registration takes the base's errors: the reflectors are read in its cell frame.
        let moved = found.estimate.frame * truth.frame.inverse();
        for k in 0..3 {
            let got = model.table(&found.estimate.values, k);
            let want = moved * Point3::from(on_part(k));
            assert!((got - want.coords).norm() < 1e-9, "{got} vs {want}");
        }
    }
}

#[test]
fn fixed_reflectors_beyond_the_limit_or_twice_are_refused() {
    let arm = model(&presets::get("fanuc-r2000ic-165f").unwrap());
    let e = arm.clone().with_tables(101).unwrap_err().to_string();
    assert!(
        e.contains("workpiece.reflectors_mm") && e.contains("0 to 100"),
        "{e}"
    );
    let e = arm.clone().with_tables(2).unwrap().with_tables(1);
    assert!(e.unwrap_err().to_string().contains("once"));
    let e = model(&track())
        .with_tables(2)
        .unwrap()
        .with_external(&[0], 0);
    assert!(e.unwrap_err().to_string().contains("external_axis"));
    assert_eq!(arm.clone().with_tables(0).unwrap().tables(), 0);
    // Readings of the reflectors alone, or of the tool at two postures: the tracker is
    // registered on the tool's measuring points, named in the readings' words.
    let cell = arm.with_tables(2).unwrap();
    let truth = Estimate {
        frame: tracker(),
        values: truth(&cell),
    };
    let obs = campaign(&cell, &truth);
    let two = [&obs[..2], &obs[obs.len() - 2..]].concat();
    for (some, n) in [
        (obs.iter().filter(|o| o.table).cloned().collect(), 0),
        (two, 2),
    ] {
        let e = fit::start(&cell, &some).unwrap_err().to_string();
        assert!(
            e.starts_with("readings: ") && e.contains(&format!("measuring points (point 1, 2, ..; the reflectors' T rows are placed after it), {n} here: {n} given")),
            "{e}"
        );
    }
}
