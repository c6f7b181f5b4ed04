//! Cell calibration from unloaded readings: the tracker's transform and the measuring points in
//! the flange frame, fitted together: the robot calibration
//! ([`crate::calibration`]) without joint errors or gravity terms (`stiffid calibrate
//! --geometry none --gravity none`), one Levenberg-Marquardt fit behind both commands.
//!
//! Reading `i` is measuring point `k(i)` at axis angles `q_i`, read by the tracker at `t_i`. With
//! the nominal flange pose `F_i`, the base-frame point is `b_i = F_i c_k` (`c_k` the point in the
//! flange frame) and the residual `r_i = b_i - T t_i`, `T = (R, p)` the tracker frame in the base
//! frame: `6 + 3P` unknowns (`P` the measuring points read), starting from the setup's measuring
//! points and the rigid transform of [`crate::register::fit`]
//! ([`crate::calibration::fit`]: the analytic Jacobian, the scaled problem by QR and
//! SVD, never the normal equations).
//!
//! The covariance of all unknowns is `sigma^2 (J^T J)^-1` at the solution, `sigma^2 = |r|^2 /
//! (3n - 6 - 3P)`; the transform's is given for its translation `p` and its rotation (a rotation
//! vector applied to `R`, base frame). The residual RMS left is the robot's unloaded absolute
//! positioning error at those postures (plus the tracker noise): the kinematic model's error,
//! which no transform or tool point can absorb. The points must be read in postures that turn the
//! flange: with one flange orientation, a point's offset and the transform's translation are the
//! same unknown (an error names the combination's rank).

use crate::calibration::error_model::{MeasuredIn, Observation, Target};
use crate::calibration::fit::{self, Options};
use crate::calibration::{gravity, ErrorModel, Geometry};
use crate::register;
use nalgebra::{Isometry3, Matrix6, Vector3, Vector6};
use stiffid_core::io::readings::Readings;
use stiffid_core::{Error, Result, Setup};

/// The calibrated cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The tracker frame in the robot base frame.
    pub base_from_tracker: Isometry3<f64>,
    /// Every measuring point of the setup in the flange frame, m (the setup's value for a point
    /// never read).
    pub points: Vec<Vector3<f64>>,
    /// Each point's shift from the setup's value, flange frame, m (zero for a point never read).
    pub shifts: Vec<Vector3<f64>>,
    /// The standard deviation of each point's coordinates, m; `None` for a point never read.
    pub point_std: Vec<Option<Vector3<f64>>>,
    /// Standard deviations of the transform's translation (m) and rotation (rad), base frame.
    pub transform_std: [f64; 6],
    /// Per reading, `b_i - (R t_i + p)`, base frame, m.
    pub residuals: Vec<Vector3<f64>>,
    /// RMS of the residuals' lengths, m: the robot's unloaded absolute error at these postures
    /// (with the tracker noise).
    pub rms: f64,
    /// The noise per coordinate estimated from the residuals, m.
    pub sigma: f64,
    /// Levenberg-Marquardt iterations taken.
    pub iterations: usize,
    /// Why they stopped.
    pub stop: stiffid_core::common::stop::Stop,
}

/// The observations of a readings file: its unloaded readings.
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) when the readings are in the base frame.
pub fn observations(setup: &Setup, readings: &Readings) -> Result<Vec<Observation>> {
    register::correspondences(setup, readings)?;
    Ok((readings.readings.iter())
        .filter(|r| r.unloaded() && !r.table)
        .map(|r| Observation {
            posture: r.posture,
            point: r.point,
            q: r.q,
            measured: r.position,
            wrench: Vector6::zeros(),
            e: r.e,
            table: false,
            direction: r.direction.unwrap_or_default(),
        })
        .collect())
}

/// Fits the tracker transform and the measuring points of `setup` together (module docs),
/// starting from the setup's measuring points.
///
/// # Errors
/// [`Error::InvalidField`] (`points`) with too few readings for the unknowns, or readings that
/// cannot separate them (one flange orientation, collinear points); those of
/// [`fit::start`] and [`fit::fit`].
pub fn fit(setup: &Setup, observations: &[Observation]) -> Result<Calibration> {
    let setup_points = &setup.tool().measuring_points;
    let mut read = vec![false; setup_points.len()];
    for o in observations {
        read[o.point] = true;
    }
    let unknowns = 6 + 3 * read.iter().filter(|r| **r).count();
    if 3 * observations.len() <= unknowns {
        return Err(Error::InvalidField {
            field: "points".into(),
            message: format!(
                "{} unloaded readings give {} coordinates for {unknowns} unknowns (the transform and 3 per measuring point read): read more postures",
                observations.len(),
                3 * observations.len()
            ),
        });
    }
    let robot = setup.robot();
    let model = ErrorModel::new(
        robot,
        setup_points,
        MeasuredIn::Tracker,
        Geometry::None,
        gravity::Terms::none(robot),
    )?;
    // The arm on its carrier as the robot gives it.
    let model = match robot.external() {
        Some(_) => model.with_external_nominal(0)?,
        None => model,
    };
    let start = fit::start(&model, observations)?;
    let options = Options {
        length: setup.characteristic_length().unwrap_or(1.0),
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let result = fit::fit(&model, observations, &start, &options)?;
    let rank = result.identifiability.rank;
    if rank < unknowns {
        return Err(Error::InvalidField {
            field: "points".into(),
            message: format!(
                "the readings determine {rank} of the {unknowns} unknowns (the transform and 3 per measuring point read): read the points in postures that turn the flange about different axes"
            ),
        });
    }
    let values = &result.estimate.values;
    let points: Vec<Vector3<f64>> = (0..setup_points.len())
        .map(|k| model.point(values, k))
        .collect();
    let sd = |c: usize| result.sd[c].unwrap_or(0.0);
    let point_std = (0..setup_points.len())
        .map(|k| read[k].then(|| Vector3::from_fn(|a, _| sd(6 + 3 * k + a))))
        .collect();
    Ok(Calibration {
        transform_std: transform_std(&model, &result, &result.estimate.frame),
        shifts: points
            .iter()
            .zip(setup_points)
            .map(|(p, s)| p - s)
            .collect(),
        points,
        point_std,
        residuals: (result.residuals.as_slice().chunks_exact(3))
            .map(Vector3::from_column_slice)
            .collect(),
        rms: result.rms,
        sigma: result.sigma,
        base_from_tracker: result.estimate.frame,
        iterations: result.iterations,
        stop: result.stop,
    })
}

/// The standard deviations of the transform's translation `p` and rotation from the fit's
/// frame parameters: the fit perturbs the prediction in the base frame, `(dp, dphi)`, so that
/// `T <- exp(-[dphi]x) (T - dp)`: `p` moves by `-dp - dphi x p` and the rotation by `-dphi`.
fn transform_std(model: &ErrorModel, result: &fit::Fit, frame: &Isometry3<f64>) -> [f64; 6] {
    let index: Vec<Option<usize>> = (0..6)
        .map(|a| {
            debug_assert!(matches!(model.parameters()[a].target, Target::Frame(_)));
            result.fitted.iter().position(|&c| c == a)
        })
        .collect();
    let mut cov = Matrix6::zeros();
    for a in 0..6 {
        for b in 0..6 {
            if let (Some(i), Some(j)) = (index[a], index[b]) {
                cov[(a, b)] = result.covariance[(i, j)];
            }
        }
    }
    let p = frame.translation.vector;
    let mut to = -Matrix6::identity();
    to.fixed_view_mut::<3, 3>(0, 3).copy_from(&p.cross_matrix());
    let moved = to * cov * to.transpose();
    std::array::from_fn(|a| moved[(a, a)].max(0.0).sqrt())
}
