//! The spread of a calibration's predictions at another noise ([`super::spread`], *At another
//! noise*): what the readings determine scales with the noise, the priors' part does not.

use super::error_model::{ErrorModel, MeasuredIn, Observation};
use super::fit::{self, Fit, GravityPrior, Options};
use super::gravity::Terms;
use super::spread::{at_noise, postures_sds};
use super::Geometry;
use nalgebra::{DMatrix, Vector3, Vector6};
use stiffid_core::common::limits::JointBox;
use stiffid_core::robot::dh::{self, Convention, Row};
use stiffid_core::robot::external::ExternalValues;
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

/// The model of `terms` fitted, its terms bounded by 3 mrad, to 12 postures whose joints 2 and 3
/// sweep 0.1 rad (the sag's terms left mostly to their bound) read 0.2 mm off the nominal robot.
fn fitted(arm: bool) -> (ErrorModel, Fit, Vec<Observation>) {
    let robot = ur10();
    let terms = match arm {
        true => Terms::arm(&robot, Default::default()).unwrap(),
        false => Terms::none(&robot),
    };
    let points = [Vector3::new(0.0, 0.0, 0.1)];
    let model = ErrorModel::new(&robot, &points, MeasuredIn::Base, Geometry::Offsets, terms);
    let model = model.unwrap();
    let obs: Vec<Observation> = (0..12)
        .map(|i| {
            let wide = |j: usize| 1.2 * ((i * 6 + j) as f64).sin();
            let q = Vector6::from_fn(|j, _| {
                if j == 1 || j == 2 {
                    -0.8 + 0.05 * wide(j)
                } else {
                    wide(j)
                }
            });
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
            o.measured =
                b + Vector3::new(2e-4 * (3.0 * i as f64).cos(), 1e-4 * (i as f64).sin(), 0.0);
            o
        })
        .collect();
    let options = Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: Some(GravityPrior {
            deflection: 3e-3,
            noise: 3e-5,
        }),
    };
    let start = fit::start(&model, &obs).unwrap();
    let f = fit::fit(&model, &obs, &start, &options).unwrap();
    (model, f, obs)
}

/// The inverse of a symmetric positive definite matrix.
fn inverse(m: &DMatrix<f64>) -> DMatrix<f64> {
    m.clone().cholesky().unwrap().inverse()
}

#[test]
fn without_priors_the_spread_scales_with_the_noise() {
    let (model, f, obs) = fitted(false);
    assert!(f.prior_precision.iter().all(|&p| p == 0.0));
    let qs: Vec<Vector6<f64>> = obs.iter().map(|o| o.q * 0.9).collect();
    let sds = postures_sds(&model, &f, &obs[0], &qs, &[1.0, 0.3]).unwrap();
    assert!(sds[0] > 0.0);
    assert!((sds[1] / sds[0] - 0.3).abs() < 1e-12, "{sds:?}");
}

#[test]
fn the_priors_part_of_the_spread_stays_at_a_lower_noise() {
    let (model, f, obs) = fitted(true);
    let gravity: Vec<usize> = (0..f.fitted.len())
        .filter(|&i| f.prior_precision[i] > 0.0)
        .collect();
    assert_eq!(gravity.len(), 3, "{:?}", f.prior_precision);
    let s = 0.25;
    let c = &f.covariance;
    let cs = at_noise(&f, s);
    // What the readings determine, `C^-1 - P`, is 1/s^2 times larger; the prior's part the same.
    let p = DMatrix::from_diagonal(&f.prior_precision);
    let (d, ds) = (inverse(c) - &p, inverse(&cs) - &p);
    let scale = d.amax();
    assert!((&ds - &d / (s * s)).amax() < 1e-6 * scale / (s * s));
    // Every standard deviation shrinks, the gravity terms' by less than `s`: their prior holds them.
    for i in 0..c.nrows() {
        assert!(cs[(i, i)] <= c[(i, i)] * (1.0 + 1e-9), "{i}");
    }
    for &i in &gravity {
        assert!(cs[(i, i)].sqrt() > 1.5 * s * c[(i, i)].sqrt(), "{i}");
    }
    let qs: Vec<Vector6<f64>> = obs.iter().map(|o| o.q).collect();
    let sds = postures_sds(&model, &f, &obs[0], &qs, &[1.0, s]).unwrap();
    assert!(sds[1] < sds[0] && sds[1] > s * sds[0], "{sds:?}");
}
