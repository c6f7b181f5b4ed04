//! Cell calibration from unloaded readings: the tracker's transform and the measuring points in
//! the flange frame, fitted together.
//!
//! Reading `i` is measuring point `k(i)` at axis angles `q_i`, read by the tracker at `t_i`. With
//! the flange pose `F_i = (R_f,i, p_f,i)` from the robot model, the base-frame point is
//! `b_i = R_f,i c_k + p_f,i` (`c_k` the point in the flange frame) and the residual
//! `r_i = b_i - (R t_i + p)`, `(R, p)` the tracker frame in the base frame. Gauss-Newton over the
//! `6 + 3P` unknowns `x = [dp; dtheta; dc_1; ...; dc_P]` (the transform perturbed as
//! `exp([dtheta]x) R t + p + dp`, base frame; `P` the measuring points read) with the analytic
//! Jacobian `dr_i/d(dp) = -I`, `dr_i/d(dtheta) = [R t_i]x`, `dr_i/d(dc_k) = R_f,i`; each step
//! solves `J dx = -r` by SVD (never the normal equations), starting from the setup's measuring
//! points and the rigid transform of [`crate::metrology::register::fit`].
//!
//! The covariance of all unknowns is `sigma^2 (J^T J)^-1` at the solution, `sigma^2 = |r|^2 /
//! (3n - 6 - 3P)`. The residual RMS left is the robot's unloaded absolute positioning error at
//! those postures (plus the tracker noise): the kinematic model's error, which no transform or
//! tool point can absorb. The points must be read in postures that turn the flange: with one
//! flange orientation, a point's offset and the transform's translation are the same unknown
//! (an error names the combination's rank).

use crate::io::readings::Readings;
use crate::metrology::register::{self, Correspondence};
use crate::{Error, Result, Setup};
use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3};

/// Most Gauss-Newton iterations.
pub const MAX_ITERATIONS: usize = 50;

/// The step length (m or rad) below which Gauss-Newton has converged.
pub const STEP_TOLERANCE: f64 = 1e-12;

/// One unloaded reading as calibration needs it: the flange pose and the tracker's reading.
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// The measuring point, 0-based.
    pub point: usize,
    /// The flange frame in the base frame at the reading's axis angles.
    pub flange: Isometry3<f64>,
    /// The tracker's reading, tracker frame, m.
    pub tracker: Vector3<f64>,
}

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
    /// Gauss-Newton iterations taken.
    pub iterations: usize,
}

/// The observations of a readings file: its unloaded readings with their flange poses.
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) when the readings are in the base frame.
pub fn observations(setup: &Setup, readings: &Readings) -> Result<Vec<Observation>> {
    register::correspondences(setup, readings)?;
    Ok(readings
        .readings
        .iter()
        .filter(|r| r.unloaded())
        .map(|r| Observation {
            point: r.point,
            flange: setup.robot().frames(&r.q).flange,
            tracker: r.position,
        })
        .collect())
}

/// Fits the tracker transform and the measuring points together (module docs), starting from
/// `points` (flange frame, m: the setup's).
///
/// # Errors
/// [`Error::InvalidField`] (`points`) with too few readings for the unknowns, or readings that
/// cannot separate them (one flange orientation, collinear points); those of
/// [`register::fit`]; [`Error::NotFinite`] when an SVD does not converge.
pub fn fit(observations: &[Observation], points: &[Vector3<f64>]) -> Result<Calibration> {
    let read = read_points(observations, points.len());
    let unknowns = 6 + 3 * read.iter().filter(|c| c.is_some()).count();
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
    let start: Vec<Correspondence> = observations
        .iter()
        .map(|o| Correspondence {
            base: (o.flange * nalgebra::Point3::from(points[o.point])).coords,
            tracker: o.tracker,
        })
        .collect();
    let mut transform = register::fit(&start)?.base_from_tracker;
    let mut estimate = points.to_vec();
    let mut iterations = 0;
    let mut svd = solve(observations, &transform, &estimate, &read)?;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let step = svd.step;
        transform = Isometry3::from_parts(
            Translation3::from(transform.translation.vector + step.fixed_rows::<3>(0)),
            UnitQuaternion::from_scaled_axis(step.fixed_rows::<3>(3).into_owned())
                * transform.rotation,
        );
        for (k, column) in read.iter().enumerate() {
            if let Some(c) = column {
                estimate[k] += step.fixed_rows::<3>(*c);
            }
        }
        svd = solve(observations, &transform, &estimate, &read)?;
        if step.amax() < STEP_TOLERANCE {
            break;
        }
    }
    Ok(finish(
        observations,
        transform,
        estimate,
        points,
        &read,
        svd,
        iterations,
    ))
}

/// The first column of each measuring point's unknowns, `None` for a point never read.
fn read_points(observations: &[Observation], count: usize) -> Vec<Option<usize>> {
    let mut read = vec![None; count];
    let mut next = 6;
    for o in observations {
        if read[o.point].is_none() {
            read[o.point] = Some(next);
            next += 3;
        }
    }
    read
}

/// The residuals at an estimate.
pub fn residuals(
    observations: &[Observation],
    transform: &Isometry3<f64>,
    points: &[Vector3<f64>],
) -> DVector<f64> {
    let mut r = DVector::zeros(3 * observations.len());
    for (i, o) in observations.iter().enumerate() {
        let base = o.flange * nalgebra::Point3::from(points[o.point]);
        let tracked = transform * nalgebra::Point3::from(o.tracker);
        r.fixed_rows_mut::<3>(3 * i).copy_from(&(base - tracked));
    }
    r
}

/// The Jacobian of [`residuals`] in the unknowns (module docs); `read` the first column of each
/// point's unknowns.
pub fn jacobian(
    observations: &[Observation],
    transform: &Isometry3<f64>,
    read: &[Option<usize>],
) -> DMatrix<f64> {
    let columns = 6 + 3 * read.iter().filter(|c| c.is_some()).count();
    let mut j = DMatrix::zeros(3 * observations.len(), columns);
    for (i, o) in observations.iter().enumerate() {
        let rotated = transform.rotation * o.tracker;
        j.fixed_view_mut::<3, 3>(3 * i, 0)
            .copy_from(&(-Matrix3::identity()));
        j.fixed_view_mut::<3, 3>(3 * i, 3)
            .copy_from(&rotated.cross_matrix());
        if let Some(c) = read[o.point] {
            j.fixed_view_mut::<3, 3>(3 * i, c)
                .copy_from(o.flange.rotation.to_rotation_matrix().matrix());
        }
    }
    j
}

/// The Gauss-Newton step at an estimate and what the covariance needs.
struct Solved {
    step: DVector<f64>,
    residuals: DVector<f64>,
    /// `(J^T J)^-1`.
    unit_covariance: DMatrix<f64>,
}

fn solve(
    observations: &[Observation],
    transform: &Isometry3<f64>,
    points: &[Vector3<f64>],
    read: &[Option<usize>],
) -> Result<Solved> {
    let r = residuals(observations, transform, points);
    let j = jacobian(observations, transform, read);
    if !(j.iter().chain(r.iter()).all(|v| v.is_finite())) {
        return Err(Error::NotFinite {
            what: "the calibration's Jacobian".into(),
        });
    }
    let svd = j
        .try_svd(
            true,
            true,
            f64::EPSILON,
            crate::math::linalg::SVD_MAX_ITERATIONS,
        )
        .ok_or(not_converged())?;
    let (u, v_t) = (
        svd.u.ok_or(not_converged())?,
        svd.v_t.ok_or(not_converged())?,
    );
    let s = &svd.singular_values;
    let rank = s.iter().filter(|&&v| v > s.max() * 1e-10).count();
    if rank < s.len() {
        return Err(Error::InvalidField {
            field: "points".into(),
            message: format!(
                "the readings determine {rank} of the {} unknowns (the transform and 3 per measuring point read): read the points in postures that turn the flange about different axes",
                s.len()
            ),
        });
    }
    let inverse = DMatrix::from_diagonal(&s.map(|v| 1.0 / v));
    let step = -(v_t.transpose() * &inverse * (u.transpose() * &r));
    let unit_covariance = v_t.transpose() * &inverse * &inverse * &v_t;
    Ok(Solved {
        step,
        residuals: r,
        unit_covariance,
    })
}

fn finish(
    observations: &[Observation],
    transform: Isometry3<f64>,
    estimate: Vec<Vector3<f64>>,
    setup_points: &[Vector3<f64>],
    read: &[Option<usize>],
    solved: Solved,
    iterations: usize,
) -> Calibration {
    let n = observations.len();
    let dof = (3 * n).saturating_sub(solved.step.len()).max(1) as f64;
    let ssr = solved.residuals.norm_squared();
    let sigma2 = ssr / dof;
    let std = |c: usize| (solved.unit_covariance[(c, c)] * sigma2).sqrt();
    Calibration {
        base_from_tracker: transform,
        shifts: estimate
            .iter()
            .zip(setup_points)
            .map(|(e, s)| e - s)
            .collect(),
        point_std: read
            .iter()
            .map(|c| c.map(|c| Vector3::new(std(c), std(c + 1), std(c + 2))))
            .collect(),
        transform_std: std::array::from_fn(std),
        residuals: (0..n)
            .map(|i| solved.residuals.fixed_rows::<3>(3 * i).into_owned())
            .collect(),
        rms: (ssr / n as f64).sqrt(),
        sigma: sigma2.sqrt(),
        points: estimate,
        iterations,
    }
}

fn not_converged() -> Error {
    Error::NotFinite {
        what: "the calibration's SVD did not converge".into(),
    }
}

/// Calibrates the cell of `setup` from the unloaded readings of a readings file ([`fit`] from
/// the setup's measuring points).
///
/// # Errors
/// Those of [`observations`] and [`fit`].
pub fn calibrate(setup: &Setup, readings: &Readings) -> Result<Calibration> {
    fit(
        &observations(setup, readings)?,
        &setup.tool().measuring_points,
    )
}
