//! Registration of the laser tracker to the robot base: the rigid transform `base_from_tracker`
//! from points known in both frames, how well it fits, and how well it is determined.
//!
//! Each point is a measuring point of the tool at a posture: in the base frame through the robot
//! model (`b_i`), in the tracker frame as the tracker reads it (`t_i`). The least-squares rigid
//! transform `b ~ R t + p` is Umeyama's closed form without scale (Umeyama 1991, IEEE PAMI 13(4),
//! Eq. 40-42; Horn 1987 with an SVD): with the centred clouds and `H = sum (b_i - b) (t_i - t)^T
//! = U S V^T`, `R = U diag(1, 1, det(U V^T)) V^T` (the last factor refuses a reflection) and
//! `p = b - R t`.
//!
//! Uncertainty: with isotropic noise `sigma` on every coordinate, the six parameters
//! `x = [dp; dtheta]` of a perturbation `b = exp([dtheta]x) R t + p + dp` (translation in m and
//! rotation vector in rad, both in the base frame) have the linearised covariance
//! `sigma^2 (J^T J)^-1`, `J` stacking `[I, -[R t_i]x]` per point; `sigma^2` is estimated from the
//! residuals as `sum |r_i|^2 / (3n - 6)`. `(J^T J)^-1` comes from the SVD of `J`, never from the
//! normal equations.
//!
//! The robot's own error: the base-frame points come from the robot model, and a model's frames
//! are off the true robot's (by `s_p` per coordinate of each frame's position and `s_r` of its
//! orientation, the setup's `[robot_accuracy]`; joints 1-6 and the flange, independent). Frame
//! `k`'s error twist `[e_p; e_r]` moves point `i` by `e_p + e_r x (b_i - o_k)` (`G`, 3n x 42); the
//! transform absorbs its least-squares part `J^+ G`, so `robot_covariance` adds
//! `(J^+ G) S (J^+ G)^T`, `S = diag(s_p^2, s_r^2, ...)`. Most of a nominal robot's error is of
//! this kind: joint 1's and the base's errors move every point rigidly and leave no residual.
//!
//! Only the rotation turns a displacement measured in the tracker frame into the base frame, so
//! the rotation's standard deviation is what a registration design minimises
//! ([`rotation_std_per_noise`], `stiffid_design::registration`).
//!
//! Readings that no rigid transform explains are flagged (`suspect`): a mirror image (the best
//! transform with a reflection, `R = U diag(1, 1, -det(U V^T)) V^T`, leaves less than a quarter of
//! the residual RMS of the best rotation, which is beyond ten times the tracker noise: a tracker
//! axis flipped, or two columns swapped), and a residual longer than [`residual_limit`] (wrong
//! axis angles, measuring point or reading).

use nalgebra::{
    DMatrix, Isometry3, Matrix3, Matrix6, Rotation3, Translation3, UnitQuaternion, Vector3, Vector6,
};
use stiffid_core::common::words::number;
use stiffid_core::io::readings::Readings;
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::observation::frames::DisplacementFrame;
use stiffid_core::{Error, Result, Setup};

/// Fewest points of a registration.
pub const MIN_POINTS: usize = 3;

/// Points whose second principal extent is below this share of the first (or below
/// [`COLLINEAR_M`]) are collinear: the rotation about their line is not determined.
pub(crate) const COLLINEAR_RATIO: f64 = 1e-4;

/// Second principal extent (RMS distance from the best line, times `sqrt(n)`) below which points
/// are collinear whatever their length, m (1 um: below a tracker's resolution).
pub(crate) const COLLINEAR_M: f64 = 1e-6;

/// The shortest residual that is refused whatever the tracker noise, m: twice the largest unloaded
/// absolute positioning error of uncalibrated industrial robots (0.5 to 5 mm over the workspace;
/// Nubiola and Bonev 2013, Robotics and Computer-Integrated Manufacturing 29(1): 2.16 mm at most
/// on an ABB IRB 1600), so only readings of another point or posture reach it.
pub(crate) const RESIDUAL_LIMIT: f64 = 10e-3;

/// The residual limit in units of the tracker noise per coordinate: a residual this many times
/// the noise is refused even where the noise is large ([`residual_limit`]).
pub(crate) const RESIDUAL_NOISE_MULTIPLE: f64 = 1000.0;

/// The longest residual a registration accepts without being forced, m: the larger of 10 mm
/// (twice the largest unloaded absolute positioning error of uncalibrated industrial robots) and
/// 1000 times the tracker noise `sigma` (m).
pub fn residual_limit(sigma: f64) -> f64 {
    RESIDUAL_LIMIT.max(RESIDUAL_NOISE_MULTIPLE * sigma)
}

/// Refuses the location of a part from the reflectors on the positioner's table, `r` (the
/// reflectors placed, in the part's frame, registered onto the ones a calibration fitted), that
/// no rigid transform explains at the tracker noise `sigma` (m per coordinate): the
/// registration's check (`suspect`).
///
/// # Errors
/// [`Error::InvalidField`] (`workpiece.reflectors_mm`) for a mirror image or a reflector that
/// lies farther from its place than [`residual_limit`], naming it and how far.
pub fn refuse_unlocated(r: &Registration, sigma: f64) -> Result<()> {
    let why = match suspect(&r.residuals, r.rms, r.mirror_rms, sigma) {
        None => return Ok(()),
        Some(Suspect::Mirrored { rms, mirror_rms }) => format!(
            "the fitted reflectors are a mirror image of the ones placed (a rotation leaves {} mm RMS, a reflection {} mm): check the signs of the coordinates",
            number(rms * 1e3),
            number(mirror_rms * 1e3)
        ),
        Some(Suspect::Residual { index, length, limit }) => format!(
            "no rigid transform puts the reflectors where the calibration fitted them: T{} lies {} mm from its place (at most {} mm; RMS of all {} mm): check its coordinates and that each T row reads the reflector of the same number",
            index + 1,
            number(length * 1e3),
            number(limit * 1e3),
            number(r.rms * 1e3)
        ),
    };
    Err(Error::InvalidField {
        field: "workpiece.reflectors_mm".into(),
        message: format!("{why}; the part is not located from them"),
    })
}

/// What makes readings implausible for a rigid transform (`suspect`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Suspect {
    /// The readings are a mirror image of the robot's points: the best transform with a
    /// reflection fits them far better than any rotation.
    Mirrored {
        /// RMS of the residual lengths of the best rotation, m.
        rms: f64,
        /// RMS of the residual lengths of the best transform with a reflection, m.
        mirror_rms: f64,
    },
    /// A residual longer than [`residual_limit`].
    Residual {
        /// The residual's index (among the points fitted, in order).
        index: usize,
        /// Its length, m.
        length: f64,
        /// The limit, m.
        limit: f64,
    },
}

/// Whether readings fitted with `residuals` (m, per point), their RMS `rms` and the mirror
/// image's RMS `mirror_rms` (m, [`Registration::mirror_rms`]) are implausible at the tracker
/// noise `sigma` (m per coordinate, the setup's): a mirror image (module docs) first, else the
/// longest residual beyond [`residual_limit`]; `None` when neither.
pub(crate) fn suspect(
    residuals: &[Vector3<f64>],
    rms: f64,
    mirror_rms: f64,
    sigma: f64,
) -> Option<Suspect> {
    if rms > 10.0 * sigma && mirror_rms < 0.25 * rms {
        return Some(Suspect::Mirrored { rms, mirror_rms });
    }
    let limit = residual_limit(sigma);
    let (index, length) = residuals
        .iter()
        .map(|r| r.norm())
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    // A NaN length is beyond every limit.
    (length.is_nan() || length > limit).then_some(Suspect::Residual {
        index,
        length,
        limit,
    })
}

/// The largest ratio of the readings' spread to the robot's points' spread ([`spread_ratio`]) in
/// either direction that is a robot's own size: a real robot's lengths are within a few per cent of
/// its model's; millimetres read as centimetres (0.1), metres (0.001) or inches (1/25.4) are
/// far outside.
pub(crate) const SPREAD_RATIO_LIMIT: f64 = 1.25;

/// The robot's points must spread at least this far (RMS distance from their centroid, m) for
/// [`spread_ratio`] to judge the readings' scale: one posture, or postures close together, say
/// nothing of it.
pub(crate) const MIN_SPREAD_M: f64 = 0.05;

/// How far the readings spread against the robot's points (`points`, pairs in any frames: the RMS
/// distance from the centroid is the same in every frame): the RMS distance of the readings from
/// their centroid over that of the robot's points from theirs, with the points' spread (m). 1
/// within the robot's errors for readings in mm as labelled, 0.001 for readings in metres. `None`
/// when the points spread less than 5 cm.
pub(crate) fn spread_ratio(points: &[Correspondence]) -> Option<(f64, f64)> {
    let spread = |v: &[Vector3<f64>]| {
        let n = v.len().max(1) as f64;
        let mean = v.iter().sum::<Vector3<f64>>() / n;
        (v.iter().map(|p| (p - mean).norm_squared()).sum::<f64>() / n).sqrt()
    };
    let base: Vec<_> = points.iter().map(|c| c.base).collect();
    let tracker: Vec<_> = points.iter().map(|c| c.tracker).collect();
    let robot = spread(&base);
    (robot >= MIN_SPREAD_M).then(|| (spread(&tracker) / robot, robot))
}

/// One point known in both frames, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Correspondence {
    /// The point in the robot base frame (through the robot model).
    pub base: Vector3<f64>,
    /// The same point as the tracker reads it, tracker frame.
    pub tracker: Vector3<f64>,
}

/// The fitted transform and its quality.
#[derive(Debug, Clone, PartialEq)]
pub struct Registration {
    /// The tracker frame in the robot base frame (SI): `b = base_from_tracker * t`.
    pub base_from_tracker: Isometry3<f64>,
    /// Per point, `b_i - base_from_tracker * t_i`, base frame, m.
    pub residuals: Vec<Vector3<f64>>,
    /// RMS of the residuals' lengths, m.
    pub rms: f64,
    /// The noise per coordinate estimated from the residuals, `sqrt(sum |r_i|^2 / (3n - 6))`, m.
    pub sigma: f64,
    /// Covariance of `[dp (m); dtheta (rad)]` (module docs), base frame: from the residuals'
    /// noise ([`fit`]), with the robot model's error once [`Registration::with_robot`] adds it.
    pub covariance: Matrix6<f64>,
    /// The robot model's part of the covariance (`robot_covariance`); zero from [`fit`].
    pub robot_covariance: Matrix6<f64>,
    /// RMS of the residual lengths of the best transform with a reflection (`det R = -1`), m:
    /// far below `rms` when the readings are a mirror image (`suspect`).
    pub mirror_rms: f64,
}

impl Registration {
    /// This registration with the robot model's part `covariance` (`robot_covariance`) added.
    pub fn with_robot(mut self, covariance: Matrix6<f64>) -> Self {
        self.covariance += covariance;
        self.robot_covariance = covariance;
        self
    }

    /// Standard deviations of the translation (m) and of the rotation about the base x, y, z axes
    /// (rad): the square roots of the covariance's diagonal.
    pub fn std(&self) -> Vector6<f64> {
        self.covariance.diagonal().map(f64::sqrt)
    }

    /// The transform as a setup file writes it: translation (mm) and fixed-axis roll, pitch, yaw
    /// (deg, `R = Rz(yaw) Ry(pitch) Rx(roll)`).
    pub(crate) fn xyz_mm_rpy_deg(&self) -> ([f64; 3], [f64; 3]) {
        let t = self.base_from_tracker.translation.vector * 1e3;
        let [r, p, y] = stiffid_core::robot::file::rpy(&self.base_from_tracker.rotation);
        ([t.x, t.y, t.z], [r, p, y].map(f64::to_degrees))
    }

    /// The `[tracker]` fragment of a setup file with this transform (the table
    /// `base_from_tracker = { xyz_mm, rpy_deg }` and `registration_uncertainty_mm`, three
    /// standard deviations of the registered position, at most 1000), with the fit in comments.
    pub fn fragment(&self) -> String {
        let (xyz, rpy) = self.xyz_mm_rpy_deg();
        let s = self.std();
        let list = |v: [f64; 3]| format!("[{:.6}, {:.6}, {:.6}]", v[0], v[1], v[2]);
        format!(
            "# registration of {} points: residual RMS {:.4} mm; standard deviation (the tracker \
             noise and the robot model's frames) of the translation [{:.4}, {:.4}, {:.4}] mm, of \
             the rotation [{:.5}, {:.5}, {:.5}] deg\n\
             [tracker]\nbase_from_tracker = {{ xyz_mm = {}, rpy_deg = {} }}\n\
             # three standard deviations of the tracker's position: the margin designs keep\n\
             registration_uncertainty_mm = {:.3}\n",
            self.residuals.len(),
            self.rms * 1e3,
            s[0] * 1e3,
            s[1] * 1e3,
            s[2] * 1e3,
            s[3].to_degrees(),
            s[4].to_degrees(),
            s[5].to_degrees(),
            list(xyz),
            list(rpy),
            (3e3 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()).min(1e3)
        )
    }
}

/// The points of registration readings: every unloaded reading's measuring point through the
/// setup's robot model (base frame) beside the tracker's reading (loaded readings are left out).
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) when the readings are in the base frame (`x_mm`), not
/// the tracker's.
pub(crate) fn correspondences(setup: &Setup, readings: &Readings) -> Result<Vec<Correspondence>> {
    if readings.frame != DisplacementFrame::Tracker {
        return Err(Error::InvalidField {
            field: "readings".into(),
            message: "the readings are in the base frame (x_mm, y_mm, z_mm): a registration needs the tracker's readings (x_tracker_mm, y_tracker_mm, z_tracker_mm)".into(),
        });
    }
    let points = &setup.tool().measuring_points;
    Ok(readings
        .readings
        .iter()
        .filter(|r| r.unloaded() && !r.table)
        .map(|r| Correspondence {
            base: setup
                .robot()
                .frames_at(&r.q, r.e.as_slice())
                .point(&points[r.point]),
            tracker: r.position,
        })
        .collect())
}

/// The least-squares rigid transform of `points` (module docs), its residuals and covariance.
///
/// # Errors
/// [`Error::InvalidField`] (`points`): fewer than [`MIN_POINTS`], a non-finite coordinate, or
/// collinear points (1e-4, 1 micrometre, in either frame); [`Error::NotFinite`] when an SVD does
/// not converge.
///
/// # Examples
/// ```
/// use nalgebra::{Isometry3, Vector3};
/// use stiffid_metrology::register::{fit, Correspondence};
/// let truth = Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.1, -0.2, 3.0));
/// let tracker = [Vector3::zeros(), Vector3::x(), Vector3::y(), Vector3::new(0.3, 0.2, 1.0)];
/// let points: Vec<_> = tracker
///     .iter()
///     .map(|t| Correspondence { base: (truth * nalgebra::Point3::from(*t)).coords, tracker: *t })
///     .collect();
/// let r = fit(&points).unwrap();
/// assert!((r.base_from_tracker.translation.vector - truth.translation.vector).norm() < 1e-12);
/// ```
pub fn fit(points: &[Correspondence]) -> Result<Registration> {
    check(points)?;
    let n = points.len() as f64;
    let b_mean = points.iter().map(|c| c.base).sum::<Vector3<f64>>() / n;
    let t_mean = points.iter().map(|c| c.tracker).sum::<Vector3<f64>>() / n;
    let h: Matrix3<f64> = points
        .iter()
        .map(|c| (c.base - b_mean) * (c.tracker - t_mean).transpose())
        .sum();
    let svd = h.capped_svd(true, true).ok_or(not_converged())?;
    let (u, v_t) = (
        svd.u.ok_or(not_converged())?,
        svd.v_t.ok_or(not_converged())?,
    );
    let sign = (u * v_t).determinant().signum();
    let d = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, sign));
    let rotation =
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(u * d * v_t));
    let translation = b_mean - rotation * t_mean;
    let base_from_tracker = Isometry3::from_parts(Translation3::from(translation), rotation);
    let residuals: Vec<Vector3<f64>> = points
        .iter()
        .map(|c| c.base - base_from_tracker.transform_vector(&c.tracker) - translation)
        .collect();
    let ssr: f64 = residuals.iter().map(|r| r.norm_squared()).sum();
    let mirror = u * Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -sign)) * v_t;
    let mirror_ssr: f64 = points
        .iter()
        .map(|c| ((c.base - b_mean) - mirror * (c.tracker - t_mean)).norm_squared())
        .sum();
    let sigma = (ssr / (3.0 * n - 6.0)).sqrt();
    let rotated: Vec<Vector3<f64>> = points.iter().map(|c| rotation * c.tracker).collect();
    let covariance = unit_covariance(&rotated)? * sigma * sigma;
    Ok(Registration {
        base_from_tracker,
        rms: (ssr / n).sqrt(),
        residuals,
        sigma,
        covariance,
        robot_covariance: Matrix6::zeros(),
        mirror_rms: (mirror_ssr / n).sqrt(),
    })
}

/// `J` (3n x 6, module docs): the rows `[I, -[R t_i]x]` of the rotated tracker points `R t_i`.
fn jacobian(rotated: &[Vector3<f64>]) -> DMatrix<f64> {
    let mut j = DMatrix::zeros(3 * rotated.len(), 6);
    for (i, p) in rotated.iter().enumerate() {
        let mut block = j.fixed_view_mut::<3, 6>(3 * i, 0);
        block.fixed_view_mut::<3, 3>(0, 0).fill_with_identity();
        block
            .fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-p.cross_matrix()));
    }
    j
}

/// The tracker registered to the robot base by `readings` on `setup`: the unloaded readings'
/// points in both frames (`correspondences`), their rigid fit ([`fit`]) and its covariance
/// with the robot model's own error ([`Registration::with_robot`], `robot_covariance`).
///
/// # Errors
/// Those of `correspondences` (readings in the base frame), [`fit`] (fewer than
/// [`MIN_POINTS`] points, collinear points) and `robot_covariance`.
pub fn register(setup: &Setup, readings: &Readings) -> Result<Registration> {
    let fitted = fit(&correspondences(setup, readings)?)?;
    let robot = robot_covariance(setup, readings, &fitted)?;
    Ok(fitted.with_robot(robot))
}

/// The covariance of `[dp (m); dtheta (rad)]` that the robot model's own error gives the
/// registration `fit` of the unloaded `readings` (module docs), with the setup's
/// [`stiffid_core::setup::Arm::frame_sd`].
///
/// # Errors
/// [`Error::NotFinite`] when the SVD does not converge.
pub(crate) fn robot_covariance(
    setup: &Setup,
    readings: &Readings,
    fit: &Registration,
) -> Result<Matrix6<f64>> {
    let (sd_p, sd_r) = setup.arm().frame_sd();
    let points = &setup.tool().measuring_points;
    let unloaded: Vec<_> = (readings.readings.iter())
        .filter(|r| r.unloaded() && !r.table)
        .collect();
    let rotated: Vec<Vector3<f64>> = (unloaded.iter())
        .map(|r| fit.base_from_tracker.rotation * r.position)
        .collect();
    let mut g = DMatrix::zeros(3 * unloaded.len(), 42);
    for (i, r) in unloaded.iter().enumerate() {
        let frames = setup.robot().frames_at(&r.q, r.e.as_slice());
        let b = frames.point(&points[r.point]);
        let origins = frames.joints.iter().chain([&frames.flange]);
        for (k, o) in origins.map(|f| f.translation.vector).enumerate() {
            let mut block = g.fixed_view_mut::<3, 6>(3 * i, 6 * k);
            block
                .fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(Matrix3::identity() * sd_p));
            block
                .fixed_view_mut::<3, 3>(0, 3)
                .copy_from(&(-(b - o).cross_matrix() * sd_r));
        }
    }
    let svd = jacobian(&rotated)
        .capped_svd(true, true)
        .ok_or(not_converged())?;
    let absorbed = svd.solve(&g, 0.0).map_err(|_| not_converged())?;
    let m = absorbed.fixed_rows::<6>(0);
    Ok(m * m.transpose())
}

/// `(J^T J)^-1` for the rotated tracker points `R t_i` (module docs): the covariance per unit noise
/// variance, by the SVD of `J`.
///
/// # Errors
/// [`Error::NotFinite`] when the SVD does not converge; [`Error::InvalidField`] when `J` is
/// rank-deficient (collinear points).
pub fn unit_covariance(rotated: &[Vector3<f64>]) -> Result<Matrix6<f64>> {
    let svd = jacobian(rotated)
        .capped_svd(false, true)
        .ok_or(not_converged())?;
    let v_t = svd.v_t.ok_or(not_converged())?;
    let s = &svd.singular_values;
    let largest = s.max();
    if s.iter().any(|&v| v.is_nan() || v <= largest * 1e-12) {
        return Err(collinear());
    }
    let mut out = Matrix6::zeros();
    for k in 0..6 {
        let row = v_t.row(k).transpose();
        out += row.clone() * row.transpose() / (s[k] * s[k]);
    }
    Ok(out)
}

/// The standard deviation of the rotation (rad, the root of the trace of the rotation block of
/// [`unit_covariance`]) per unit noise (m) for base-frame points: the criterion of a registration
/// design. Infinite for fewer than [`MIN_POINTS`] or collinear points.
pub fn rotation_std_per_noise(points: &[Vector3<f64>]) -> f64 {
    if points.len() < MIN_POINTS || collinear_cloud(points) {
        return f64::INFINITY;
    }
    unit_covariance(points).map_or(f64::INFINITY, |c| c.fixed_view::<3, 3>(3, 3).trace().sqrt())
}

fn check(points: &[Correspondence]) -> Result<()> {
    if points.len() < MIN_POINTS {
        return Err(Error::InvalidField {
            field: "points".into(),
            message: format!(
                "{} given: a registration needs at least {MIN_POINTS} points not on one line",
                points.len()
            ),
        });
    }
    if let Some(i) = points
        .iter()
        .position(|c| !(c.base.iter().chain(&c.tracker).all(|v| v.is_finite())))
    {
        return Err(Error::InvalidField {
            field: format!("points[{}]", i + 1),
            message: "expected finite coordinates".into(),
        });
    }
    let base: Vec<Vector3<f64>> = points.iter().map(|c| c.base).collect();
    let tracker: Vec<Vector3<f64>> = points.iter().map(|c| c.tracker).collect();
    if collinear_cloud(&base) || collinear_cloud(&tracker) {
        return Err(collinear());
    }
    Ok(())
}

/// Whether the points lie on one line (or one point): their second principal extent is below
/// [`COLLINEAR_RATIO`] of the first or below [`COLLINEAR_M`]. Non-finite points count as collinear.
fn collinear_cloud(points: &[Vector3<f64>]) -> bool {
    let n = points.len() as f64;
    let mean = points.iter().sum::<Vector3<f64>>() / n;
    let scatter: Matrix3<f64> = points
        .iter()
        .map(|p| (p - mean) * (p - mean).transpose())
        .sum();
    if !scatter.iter().all(|v| v.is_finite()) {
        return true;
    }
    let Some(svd) = scatter.capped_svd(false, false) else {
        return true;
    };
    let mut s = svd.singular_values.map(f64::sqrt);
    s.as_mut_slice().sort_by(|a, b| b.total_cmp(a));
    s[1] <= COLLINEAR_RATIO * s[0] || s[1] <= COLLINEAR_M
}

fn collinear() -> Error {
    Error::InvalidField {
        field: "points".into(),
        message: "the points lie on one line: the rotation about it is not determined (measure \
                  points that span a plane or a volume)"
            .into(),
    }
}

fn not_converged() -> Error {
    Error::NotFinite {
        what: "the registration's singular value decomposition (did not converge)".into(),
    }
}

/// Refuses readings (any frame, loaded or not) whose spread is not the robot's: the RMS distance
/// of the readings from their centroid against that of the setup's measuring points through the
/// nominal robot at the same axis angles, beyond 1.25 either way. Readings in metres or centimetres under `_mm`
/// names would otherwise calibrate a robot shrunk to their scale with a residual of zero. Nothing
/// forces them: no robot is a tenth of its model's size.
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) with both spreads and the likely unit.
pub fn refuse_other_scale(setup: &Setup, data: &Readings) -> Result<()> {
    let points = &setup.tool().measuring_points;
    let pairs: Vec<Correspondence> = (data.readings.iter())
        .filter(|r| !r.table)
        .map(|r| Correspondence {
            base: setup
                .robot()
                .frames_at(&r.q, r.e.as_slice())
                .point(&points[r.point]),
            tracker: r.position,
        })
        .collect();
    let Some((ratio, spread)) = spread_ratio(&pairs) else {
        return Ok(());
    };
    let limit = SPREAD_RATIO_LIMIT;
    if ratio.is_finite() && ratio <= limit && ratio >= 1.0 / limit {
        return Ok(());
    }
    let units = [
        (1e-3, "metres"),
        (1e-2, "decimetres"),
        (0.1, "centimetres"),
        (1.0 / 25.4, "inches"),
        (1e3, "micrometres"),
    ];
    let (_, unit) = units
        .iter()
        .min_by(|a, b| {
            (a.0 / ratio)
                .ln()
                .abs()
                .total_cmp(&(b.0 / ratio).ln().abs())
        })
        .expect("units");
    Err(Error::InvalidField {
        field: "readings".into(),
        message: format!(
            "the readings spread {:.4} mm about their centroid (RMS) where the robot's measuring points at the same axis angles spread {:.1} mm: {ratio:.4} times the robot's size, readings in {unit}? expected millimetres ({}) of this robot and tool",
            ratio * spread * 1e3,
            spread * 1e3,
            data.columns[1]
        ),
    })
}

/// Refuses readings that no rigid transform explains (`suspect` at the setup's tracker noise):
/// tracker readings that are a mirror image of the nominal robot's points (by `registration`, or
/// the registration of `data` when `None`), or a fitted residual (`residuals`, m, one per unloaded
/// reading of `data` in file order, or per unloaded reading of the arm's points: the table's
/// reflectors left out) beyond [`residual_limit`].
///
/// # Errors
/// [`Error::InvalidField`]: `readings` for a mirror image (both RMS), or the reading's line,
/// posture and point with `residual_norm_mm` (its length and the limit).
pub fn refuse_implausible(
    setup: &Setup,
    data: &Readings,
    registration: Option<&Registration>,
    residuals: &[Vector3<f64>],
) -> Result<()> {
    let sigma = setup.noise().reading_sd();
    let registered = match registration {
        Some(r) => Some(r.clone()),
        // Readings in the base frame, or too few: the job says so itself.
        None => correspondences(setup, data)
            .and_then(|points| fit(&points))
            .ok(),
    };
    let mirrored = registered.and_then(|r| suspect(&[], r.rms, r.mirror_rms, sigma));
    let error = match mirrored.or_else(|| suspect(residuals, 0.0, f64::INFINITY, sigma)) {
        None => return Ok(()),
        Some(Suspect::Mirrored { rms, mirror_rms }) => Error::InvalidField {
            field: "readings".into(),
            message: format!(
                "the tracker's readings are a mirror image of the robot's points: the best rotation leaves a residual RMS of {:.3} mm, a reflection {:.3} mm; expected readings in a right-handed tracker frame (an axis flipped, or two coordinate columns swapped?); --force (Python force=True) fits the best rotation anyway",
                rms * 1e3,
                mirror_rms * 1e3
            ),
        },
        Some(Suspect::Residual {
            index,
            length,
            limit,
        }) => {
            // One residual per unloaded reading, or (the tracker's registration) per unloaded
            // reading of the arm's points, the table's reflectors left out.
            let unloaded = data.readings.iter().filter(|r| r.unloaded()).count();
            let (reading, line) = (data.readings.iter().zip(&data.lines))
                .filter(|(r, _)| r.unloaded() && (residuals.len() == unloaded || !r.table))
                .nth(index)
                .expect("one residual per unloaded reading");
            Error::InvalidField {
                field: format!(
                    "line {line} (posture {}, point {}), residual_norm_mm",
                    stiffid_core::common::limits::short(&data.labels[reading.posture]),
                    stiffid_core::io::readings::point_name(reading.point, reading.table)
                ),
                message: format!(
                    "{:.3}: expected at most {:.3} mm (the larger of {} mm, twice a robot's unloaded absolute error, and {} times the tracker noise {:.4} mm): a reading of another point or posture, or axis angles that are not the robot's; --force (Python force=True) fits the readings anyway",
                    length * 1e3,
                    limit * 1e3,
                    RESIDUAL_LIMIT * 1e3,
                    RESIDUAL_NOISE_MULTIPLE,
                    sigma * 1e3
                ),
            }
        }
    };
    Err(error)
}

#[cfg(test)]
mod tests;
