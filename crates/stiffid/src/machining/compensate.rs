//! Deflection compensation of a machining path: the axis angles that put the loaded tool where
//! the unloaded robot would.
//!
//! ## The loaded robot
//! At commanded axis angles q a wrench `W` (base frame) at the tool centre point (TCP) deflects the
//! joint springs by `dq = h .* (J^T W)` (Zhang et al. 2021, Eq. 4-5, the torques of the unloaded
//! posture: the complementary stiffness is neglected, see [`crate::observation::cartesian`]), and the rigid links
//! then put the tool at the forward kinematics of the deflected joints, [`Model::loaded_pose`]. (Eq. 6's
//! `J dq` is its first-order approximation; the two differ by about `|dq|^2` times the reach,
//! a micrometre, which matters at the 0.1 micrometre this module solves to.)
//!
//! ## Compensation
//! The compensated axis angles `q_c` solve `loaded_pose(q_c) = T_nominal`, the TCP pose of the
//! unloaded (rigid) robot at the nominal posture, the loaded pose sagging under the robot's own
//! weight too when the compliance carries a calibration's gravity terms
//! ([`crate::machining::weight`]), by Newton steps `q += J^-1 e` from the nominal posture
//! (the first step is the classical `q - J^-1 J dq`), until the residual is below
//! [`TOLERANCE_M`] and [`TOLERANCE_RAD`] (success needs 0.1 micrometre and 1 microradian). The
//! Jacobian neglects `d(dq)/dq`, so the convergence is linear with a rate of about `|dq|`:
//! three or four steps.
//!
//! ## The free tool axis
//! In 5-axis milling and drilling the rotation about the spindle (tool z) is free. With
//! [`FreeToolAxis`], every path point's pose is turned about its tool z by the angle that minimises
//! the TCP translation deflection, within the joint limits and with at most
//! [`FreeToolAxis::max_step`] between consecutive points: dynamic programming over a grid of
//! angles, each angle's postures continued along the path by inverse kinematics; a point only takes
//! an angle whose deflection is no larger than at the nominal angle (so the nominal path is always
//! feasible and no point's deflection rises); the sum of the deflections is minimised, plus a
//! tie-breaking cost of [`TIE_BREAK`] times each point's nominal deflection per full range away
//! from the path's own angle and per full step between points: where the angles tie (a TCP on
//! the spindle axis turns nothing) the path keeps its own angle, and a rotation is smooth along
//! the path, never a zig-zag between equal angles; a gain below about 1e-6 of the deflection is
//! not worth a turn. The wrench
//! stays fixed in the base frame (the process force does not turn with the spindle). This is the
//! redundancy resolution of stiffness-oriented posture optimisation for robotic machining: Caro,
//! Dumas, Garnier and Furet, "Workpiece placement optimization for machining operations with a
//! KUKA KR270-2 robot", IEEE ICRA 2013; Xiong, Ding and Zhu, "Stiffness-based pose optimization of
//! an industrial robot for five-axis milling", Robotics and Computer-Integrated Manufacturing 55,
//! 2019.

use crate::common::error::ColumnProblem;
use crate::common::error::JobOption;
use crate::common::limits::number;
use crate::machining::weight::Weight;
use crate::observation::deflection::PointDeflection;
use crate::observation::deflection::{base_wrench, Frame, Points};
use crate::robot::configuration::Configuration;
use crate::robot::ik::{self, pose_error, tool_pose};
use crate::robot::kinematics::{Coordinates, Frames};
use crate::setup::Arm;
use crate::{common::limits, Error, Result, Setup};
use nalgebra::{Isometry3, Matrix6, UnitQuaternion, Vector3, Vector6};
use rayon::prelude::*;

/// The residual the Newton steps aim at, m.
pub const TOLERANCE_M: f64 = 1e-10;
/// The residual rotation the Newton steps aim at, rad.
pub const TOLERANCE_RAD: f64 = 1e-10;
/// The residual a compensated point must reach: 0.1 micrometre.
pub const REQUIRED_M: f64 = 1e-7;
/// The residual rotation a compensated point must reach: 1 microradian.
pub const REQUIRED_RAD: f64 = 1e-6;
/// Newton steps at most.
pub const MAX_ITERATIONS: usize = 30;
/// The relative weight of the free tool axis' tie-breaking cost (module docs).
pub const TIE_BREAK: f64 = 1e-6;

/// Where a path point is: axis angles, or a TCP pose reached by inverse kinematics.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// Axis angles, rad.
    Posture(Vector6<f64>),
    /// TCP position (m) and tool orientation, base frame.
    Pose(Isometry3<f64>),
}

/// One point of a machining path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    /// Its line in the path file (for errors), 1-based.
    pub line: u64,
    /// Where the TCP is.
    pub target: Target,
    /// The wrench `[f; m]` at the TCP, N and Nm, in `frame`.
    pub wrench: Vector6<f64>,
    /// The frame of the wrench.
    pub frame: Frame,
}

/// The compliance of every parameter of the setup's model and, from an identification, its
/// covariance ([`crate::model::Compliance`]).
pub use crate::model::Compliance;

/// The stiffness-optimal rotation about the tool z axis (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeToolAxis {
    /// Largest change of the rotation between consecutive points, rad, > 0.
    pub max_step: f64,
    /// The rotation stays within `+-range` of the path's, rad.
    pub range: f64,
}

impl FreeToolAxis {
    /// Largest accepted `max_step`, deg.
    pub const MAX_STEP_DEG: f64 = 90.0;
    /// Largest accepted `range`, deg.
    pub const MAX_RANGE_DEG: f64 = 180.0;

    /// The free tool axis from its step and range in degrees (the units of the command line and
    /// the Python package): `max_step_deg` in (0, 90], `tool_axis_range_deg` in (0, 180].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the one argument that is wrong ([`JobOption::MaxStepDeg`] or
    /// [`JobOption::ToolAxisRangeDeg`]) with the value given.
    pub fn try_from_degrees(max_step_deg: f64, tool_axis_range_deg: f64) -> Result<Self> {
        // A subnormal angle in rad (5e-324 deg) is zero in every computation: refused as <= 0.
        let check = |v: f64, max: f64, option| match v.to_radians().is_normal() && v <= max {
            true => Ok(v.to_radians()),
            false => Err(Error::InvalidOption {
                option,
                message: format!("{}: expected a number > 0 and <= {max}", number(v)),
            }),
        };
        Ok(Self {
            max_step: check(max_step_deg, Self::MAX_STEP_DEG, JobOption::MaxStepDeg)?,
            range: check(
                tool_axis_range_deg,
                Self::MAX_RANGE_DEG,
                JobOption::ToolAxisRangeDeg,
            )?,
        })
    }

    /// The most grid cells (angles x path points) the optimisation may visit: each is one
    /// inverse kinematics solution kept in memory (about 70 bytes), so at most about 0.4 GB.
    pub const MAX_GRID_CELLS: f64 = 5e6;

    /// The grid spacing: `max_step` divided into whole cells of at most 5 deg, and the number of
    /// cells one step may move.
    fn grid(&self) -> (f64, usize) {
        let cells = (self.max_step / 5f64.to_radians()).ceil().max(1.0);
        (self.max_step / cells, cells as usize)
    }

    /// The number of angles of the grid: `2 floor(range / spacing) + 1`, as a float (it may be
    /// astronomically large for a tiny `max_step`).
    fn angle_count(&self) -> f64 {
        2.0 * (self.range / self.grid().0 + 1e-9).floor() + 1.0
    }

    /// Checks that the grid of a path of `points` points stays within [`Self::MAX_GRID_CELLS`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::MaxStepDeg`]) with the grid's size and what to
    /// change.
    pub fn check_grid(&self, points: usize) -> Result<()> {
        let angles = self.angle_count();
        let cells = angles * points as f64;
        if cells <= Self::MAX_GRID_CELLS {
            return Ok(());
        }
        Err(Error::InvalidOption {
            option: JobOption::MaxStepDeg,
            message: format!(
                "{} deg with a range of +-{} deg makes a grid of {angles:.3e} angles x {points} path points = {cells:.3e} cells; at most {:.0e} (a larger step, a smaller range or a shorter path)",
                number(self.max_step.to_degrees()),
                number(self.range.to_degrees()),
                Self::MAX_GRID_CELLS
            ),
        })
    }
}

/// How to compensate a path.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Where inverse kinematics starts for the first pose, axis angles, rad.
    pub q0: Vector6<f64>,
    /// Inverse kinematics tolerances and effort.
    pub ik: ik::Options,
    /// Optimise the rotation about the tool z axis.
    pub free_tool_axis: Option<FreeToolAxis>,
    /// The level of the prediction intervals of the deflection (with a compliance that carries
    /// a prediction calibration, [`crate::model::prediction`]), within
    /// [`crate::model::prediction::LEVEL`].
    pub level: f64,
}

impl Options {
    /// Checks every field: `q0` within [`limits::ANGLE_RAD`] (finite), `ik`
    /// ([`ik::Options::validate`]), and a free tool axis' `max_step` in (0, 90] deg and `range` in
    /// (0, 180] deg as [`FreeToolAxis::try_from_degrees`] gives them. [`path`] calls it.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the field, the value and the range.
    pub fn validate(&self) -> Result<()> {
        limits::check(
            "compensate::Options.q0",
            self.q0.as_slice(),
            &limits::ANGLE_RAD,
        )?;
        self.ik.validate()?;
        crate::model::prediction::check_level("compensate::Options.level", self.level)?;
        let Some(free) = &self.free_tool_axis else {
            return Ok(());
        };
        let fields = [
            ("max_step", free.max_step, FreeToolAxis::MAX_STEP_DEG),
            ("range", free.range, FreeToolAxis::MAX_RANGE_DEG),
        ];
        for (field, value, most) in fields {
            if !(value > 0.0 && value <= most.to_radians()) {
                return Err(Error::InvalidField {
                    field: format!("FreeToolAxis.{field}"),
                    message: format!(
                        "{} rad: expected a number > 0 and <= {most} deg",
                        number(value)
                    ),
                });
            }
        }
        Ok(())
    }

    /// The defaults for `setup`: inverse kinematics starts at the setup's first test posture (else
    /// the middle of its bounds), with [`ik::Options::default`]; no free tool axis.
    pub fn for_setup(setup: &Setup) -> Self {
        let bounds = setup.bounds();
        Self {
            q0: setup
                .test_postures()
                .first()
                .copied()
                .unwrap_or((bounds.lower + bounds.upper) / 2.0),
            ik: ik::Options::default(),
            free_tool_axis: None,
            level: crate::model::prediction::DEFAULT_LEVEL,
        }
    }
}

/// One compensated path point, SI units, base frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Compensated {
    /// The nominal axis angles (after the tool-axis rotation, if optimised), rad.
    pub q: Vector6<f64>,
    /// The nominal TCP pose (m).
    pub pose: Isometry3<f64>,
    /// The wrench at the TCP, base frame, N and Nm.
    pub wrench: Vector6<f64>,
    /// TCP translation (m) and tool rotation (rad) under the wrench at the nominal posture (Eq. 6).
    pub deflection: Vector6<f64>,
    /// Its standard deviation per coordinate, given the compliance covariance.
    pub deflection_std: Option<Vector6<f64>>,
    /// The standard deviation of the translation's length `|dp|` (first order:
    /// `sqrt(u^T Cov(dp) u)`, `u = dp / |dp|`), m.
    pub translation_norm_std: Option<f64>,
    /// The prediction interval of the translation (m, base frame) at [`Options::level`], given
    /// the compliance's prediction calibration ([`crate::model::prediction`]).
    pub deflection_interval: Option<crate::model::prediction::Interval>,
    /// The compensated axis angles `q_c`, rad.
    pub q_compensated: Vector6<f64>,
    /// `|p_nominal - p_loaded(q_c)|`, m.
    pub residual_position: f64,
    /// The rotation between the nominal and the loaded tool at `q_c`, rad.
    pub residual_rotation: f64,
    /// Newton steps taken.
    pub iterations: usize,
    /// The rotation about tool z chosen by [`FreeToolAxis`] (0 without), rad.
    pub tool_rotation: f64,
    /// With [`FreeToolAxis`]: the deflection at the path's own rotation, before optimisation.
    pub deflection_before: Option<Vector6<f64>>,
}

/// The compensation model of one arm: its robot, TCP, springs and compliance.
#[derive(Debug, Clone)]
pub struct Model<'a> {
    arm: &'a Arm,
    compliance: &'a Compliance,
    /// Spring deflections to axis angles: `M^-1` for kinematic springs, else the identity.
    to_axis: Matrix6<f64>,
    /// The level of the prediction intervals.
    level: f64,
    /// The sag under the robot's own weight, from a calibration with gravity.
    weight: Option<Weight>,
}

impl<'a> Model<'a> {
    /// The model of `arm` (its TCP, drive springs and virtual springs) with the compliance
    /// `compliance` of every parameter of the arm's model; with the compliance's
    /// [`crate::model::OwnWeight`], the sag under the robot's own weight ([`Weight`]).
    ///
    /// # Errors
    /// Those of [`Compliance::check`] and [`Weight::new`]; [`Error::InvalidField`] when the
    /// springs are kinematic and the robot's axis map is singular.
    pub fn new(arm: &'a Arm, compliance: &'a Compliance) -> Result<Self> {
        compliance.check(arm.model())?;
        let to_axis =
            match arm.springs() {
                Coordinates::Axis => Matrix6::identity(),
                Coordinates::Kinematic => {
                    arm.robot().axis_map().matrix.try_inverse().ok_or_else(|| {
                        Error::InvalidField {
                            field: "axis_map".into(),
                            message: "singular: kinematic spring deflections have no axis angles"
                                .into(),
                        }
                    })?
                }
            };
        let weight = (compliance.own_weight.as_ref())
            .map(|w| Weight::new(arm.robot(), arm.springs(), w))
            .transpose()?;
        Ok(Self {
            arm,
            compliance,
            to_axis,
            level: crate::model::prediction::DEFAULT_LEVEL,
            weight,
        })
    }

    /// The model with prediction intervals at `level` (default
    /// [`crate::model::prediction::DEFAULT_LEVEL`]).
    pub fn at_level(self, level: f64) -> Self {
        Self { level, ..self }
    }

    /// The TCP pose of the robot commanded to `q` (rad) and loaded by `wrench` (base frame) at the
    /// TCP, sagging under its own weight with a [`Weight`] (module docs).
    pub fn loaded_pose(&self, q: &Vector6<f64>, wrench: &Vector6<f64>) -> Isometry3<f64> {
        self.loaded(&self.arm.robot().frames(q), q, wrench)
    }

    /// [`Model::loaded_pose`] with the frames of `q` given. The virtual springs' deflection (a
    /// twist of the tool, `sum_s c_s (J_s^T W) J_s`) is applied to first order after the drives'
    /// (their second-order terms are about `|dq|^2` times the reach, far below the tolerance).
    fn loaded(&self, frames: &Frames, q: &Vector6<f64>, wrench: &Vector6<f64>) -> Isometry3<f64> {
        let tcp = &self.arm.tool().tcp;
        let h = &self.compliance.h;
        let j = frames.jacobian(tcp, self.arm.springs());
        let drives = Vector6::from_fn(|r, _| h[r]);
        let mut dq = self.to_axis * j.tr_mul(wrench).component_mul(&drives);
        if let Some(w) = &self.weight {
            dq += w.deflection(q);
        }
        let pose = tool_pose(&self.arm.robot().frames(&(q + dq)), tcp);
        let model = self.arm.model();
        if model.is_drives_only() {
            return pose;
        }
        let p = frames.point(tcp);
        let twist: Vector6<f64> = model
            .placed(self.arm.robot(), frames)
            .iter()
            .enumerate()
            .map(|(s, spring)| spring.column(&p) * (h[6 + s] * spring.load(&p, wrench)))
            .sum();
        let rotation = UnitQuaternion::from_scaled_axis(twist.fixed_rows::<3>(3).into_owned());
        Isometry3::from_parts(
            (pose.translation.vector + twist.fixed_rows::<3>(0)).into(),
            rotation * pose.rotation,
        )
    }

    /// The TCP deflection (Eq. 6) in the posture `frames` under `wrench` (base frame) and its
    /// standard deviation.
    fn deflection(
        &self,
        frames: &Frames,
        wrench: &Vector6<f64>,
    ) -> (Vector6<f64>, Option<(Vector6<f64>, f64)>) {
        let d = self.tcp_deflection(frames, wrench);
        (d.displacement, self.std(&d))
    }

    /// The TCP's deflection in the posture `frames` under `wrench` (base frame).
    fn tcp_deflection(&self, frames: &Frames, wrench: &Vector6<f64>) -> PointDeflection {
        let tcp = &self.arm.tool().tcp;
        let points = Points {
            arm: self.arm,
            frames,
            loaded: tcp,
            observed: tcp,
        };
        points.deflection(wrench, &self.compliance.h)
    }

    /// The standard deviation of the deflection `d` per coordinate and of its translation's
    /// length, given the compliance covariance.
    fn std(&self, d: &PointDeflection) -> Option<(Vector6<f64>, f64)> {
        self.compliance.covariance.as_ref().map(|c| {
            let cov = d.covariance(c);
            let u = d.displacement.fixed_rows::<3>(0).normalize();
            let along = (u.transpose() * cov.fixed_view::<3, 3>(0, 0) * u)[0];
            (
                cov.diagonal().map(|v| v.max(0.0).sqrt()),
                along.max(0.0).sqrt(),
            )
        })
    }

    /// Compensates one point: the nominal posture `q` (rad) under `wrench` (base frame) at the
    /// TCP. Returns `q_c`, the residual (m, rad) and the steps taken (module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (field `posture`) when the Jacobian is singular on the way.
    pub fn compensate(
        &self,
        q: &Vector6<f64>,
        wrench: &Vector6<f64>,
    ) -> Result<(Vector6<f64>, f64, f64, usize)> {
        self.compensate_from(q, self.arm.robot().frames(q), wrench)
    }

    /// [`Model::compensate`] with the frames of `q` given.
    fn compensate_from(
        &self,
        q: &Vector6<f64>,
        mut frames: Frames,
        wrench: &Vector6<f64>,
    ) -> Result<(Vector6<f64>, f64, f64, usize)> {
        let tcp = &self.arm.tool().tcp;
        let target = tool_pose(&frames, tcp);
        let mut qc = *q;
        let mut iterations = 0;
        loop {
            let e = pose_error(&target, &self.loaded(&frames, &qc, wrench));
            let (ep, eo) = (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
            if (ep <= TOLERANCE_M && eo <= TOLERANCE_RAD) || iterations == MAX_ITERATIONS {
                return Ok((qc, ep, eo, iterations));
            }
            let j = frames.jacobian(tcp, Coordinates::Axis);
            let step = j.lu().solve(&e).ok_or_else(|| Error::InvalidField {
                field: "posture".into(),
                message: "singular: the TCP Jacobian is not invertible, no compensation exists"
                    .into(),
            })?;
            qc += step;
            frames = self.arm.robot().frames(&qc);
            iterations += 1;
        }
    }
}

/// Compensates every point of a path (module docs), the points in parallel; the result does not
/// depend on the number of threads.
///
/// # Errors
/// [`Error::InvalidField`] for `options` outside their limits ([`Options::validate`]) or a free
/// tool axis grid beyond [`FreeToolAxis::MAX_GRID_CELLS`] ([`FreeToolAxis::check_grid`]);
/// [`Error::Column`] naming the line of the first point (in path order) that fails: axis angles
/// outside the joint limits ([`ColumnProblem::Outside`], `q1_deg..q6_deg`), a pose inverse
/// kinematics cannot reach ([`ColumnProblem::Uncompensated`] with [`Error::Unreachable`]'s
/// message, `x_mm..rz_deg`), or compensated axis angles outside the joint limits or a residual
/// above 0.1 micrometre / 1 microradian (`Uncompensated` with the lines of the other points that
/// fail, `q_compensated`).
pub fn path(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    options: &Options,
) -> Result<Vec<Compensated>> {
    options.validate()?;
    if let Some(free) = &options.free_tool_axis {
        free.check_grid(points.len())?;
    }
    let model = Model::new(arm, compliance)?.at_level(options.level);
    let nominal = nominal_postures(arm, points, options.q0, options)?;
    let wrenches: Vec<Vector6<f64>> = points
        .par_iter()
        .zip(&nominal)
        .map(|(p, q)| base_wrench(&arm.robot().frames(q), &p.wrench, p.frame))
        .collect();
    let (postures, rotations) = match &options.free_tool_axis {
        None => (nominal.clone(), vec![0.0; points.len()]),
        Some(free) => optimise_tool_axis(&model, &nominal, &wrenches, free, &options.ik),
    };
    let chosen = Chosen {
        nominal: &nominal,
        postures: &postures,
        rotations: &rotations,
        wrenches: &wrenches,
    };
    compensate_chosen(&model, points, &chosen, options.free_tool_axis.is_some())
}

/// Path points per chunk of [`stream`].
pub const CHUNK: usize = 4096;

/// [`path`] for a path of any length in bounded memory: the points come from `points` (an
/// iterator, e.g. a file's rows as they are parsed) and are compensated [`CHUNK`] at a time (in
/// parallel within a chunk, inverse kinematics continued from the previous chunk's last
/// posture); `sink` gets each chunk's points and results, in path order, before the next chunk is
/// read. With [`FreeToolAxis`] the whole path is one problem (dynamic programming over the
/// path): its points are collected (at most [`FreeToolAxis::MAX_GRID_CELLS`] grid cells) and
/// compensated by [`path`], then given to `sink` chunk by chunk. The results equal [`path`]'s.
/// Returns the number of points.
///
/// # Errors
/// Those of [`path`] (an uncompensated point names the other failing lines of its chunk, not of
/// the whole path), the first error `points` yields, [`Error::InvalidField`] (`path`) for a path
/// without points (all as `E`), and those of `sink`.
pub fn stream<I, F, E>(
    arm: &Arm,
    compliance: &Compliance,
    points: I,
    options: &Options,
    mut sink: F,
) -> std::result::Result<usize, E>
where
    I: IntoIterator<Item = Result<PathPoint>>,
    F: FnMut(&[PathPoint], &[Compensated]) -> std::result::Result<(), E>,
    E: From<Error>,
{
    options.validate()?;
    let mut points = points.into_iter();
    if let Some(free) = &options.free_tool_axis {
        let mut all = Vec::new();
        for p in points {
            all.push(p?);
            free.check_grid(all.len())?;
        }
        let results = path(arm, compliance, &all, options)?;
        for (p, r) in all.chunks(CHUNK).zip(results.chunks(CHUNK)) {
            sink(p, r)?;
        }
        return Ok(all.len());
    }
    let model = Model::new(arm, compliance)?.at_level(options.level);
    let (mut previous, mut count) = (options.q0, 0);
    loop {
        let chunk: Vec<PathPoint> = points.by_ref().take(CHUNK).collect::<Result<_>>()?;
        if chunk.is_empty() {
            break;
        }
        let nominal = nominal_postures(arm, &chunk, previous, options)?;
        previous = nominal[nominal.len() - 1];
        let wrenches: Vec<Vector6<f64>> = chunk
            .par_iter()
            .zip(&nominal)
            .map(|(p, q)| base_wrench(&arm.robot().frames(q), &p.wrench, p.frame))
            .collect();
        let rotations = vec![0.0; chunk.len()];
        let chosen = Chosen {
            nominal: &nominal,
            postures: &nominal,
            rotations: &rotations,
            wrenches: &wrenches,
        };
        sink(&chunk, &compensate_chosen(&model, &chunk, &chosen, false)?)?;
        count += chunk.len();
    }
    match count {
        0 => Err(Error::InvalidField {
            field: "path".into(),
            message: "no path points".into(),
        }
        .into()),
        n => Ok(n),
    }
}

/// The postures chosen for a run of path points: nominal, after the tool-axis rotation (equal
/// without one), the rotations and the base-frame wrenches.
struct Chosen<'a> {
    nominal: &'a [Vector6<f64>],
    postures: &'a [Vector6<f64>],
    rotations: &'a [f64],
    wrenches: &'a [Vector6<f64>],
}

/// Compensates every point at its chosen posture, in parallel; the first error in path order.
fn compensate_chosen(
    model: &Model,
    points: &[PathPoint],
    c: &Chosen,
    free: bool,
) -> Result<Vec<Compensated>> {
    let arm = model.arm;
    let results: Vec<Result<Compensated>> = (0..points.len())
        .into_par_iter()
        .map(|i| {
            let q = &c.postures[i];
            let frames = arm.robot().frames(q);
            let (qc, ep, eo, iterations) = model
                .compensate_from(q, frames.clone(), &c.wrenches[i])
                .map_err(|e| uncompensated(points[i].line, "q_compensated", e.to_string()))?;
            check_compensated(arm, points[i].line, &qc, ep, eo)?;
            let d = model.tcp_deflection(&frames, &c.wrenches[i]);
            let deflection_std = model.std(&d);
            let deflection_interval = model
                .compliance
                .prediction
                .as_ref()
                .map(|p| d.interval(p, model.level));
            let deflection_before = free.then(|| {
                let frames = arm.robot().frames(&c.nominal[i]);
                model.deflection(&frames, &c.wrenches[i]).0
            });
            Ok(Compensated {
                q: *q,
                pose: tool_pose(&frames, &arm.tool().tcp),
                wrench: c.wrenches[i],
                deflection: d.displacement,
                deflection_std: deflection_std.map(|s| s.0),
                translation_norm_std: deflection_std.map(|s| s.1),
                deflection_interval,
                q_compensated: qc,
                residual_position: ep,
                residual_rotation: eo,
                iterations,
                tool_rotation: c.rotations[i],
                deflection_before,
            })
        })
        .collect();
    first_error(results)
}

/// The error of the path point at `line` that cannot be compensated; `columns` names where.
fn uncompensated(line: u64, columns: &str, reason: String) -> Error {
    Error::Column {
        line,
        column: None,
        name: columns.into(),
        problem: ColumnProblem::Uncompensated {
            reason,
            others: Vec::new(),
            failed: 1,
        },
    }
}

/// The results, or the first error (in path order) naming the lines of the other failing points
/// (the first ten).
fn first_error<T>(results: Vec<Result<T>>) -> Result<Vec<T>> {
    let failed: Vec<u64> = results
        .iter()
        .filter_map(|r| match r {
            Err(Error::Column { line, .. }) => Some(*line),
            _ => None,
        })
        .collect();
    let mut out = Vec::with_capacity(results.len());
    for r in results {
        match r {
            Ok(v) => out.push(v),
            Err(Error::Column {
                line,
                column,
                name,
                problem: ColumnProblem::Uncompensated { reason, .. },
            }) => {
                let problem = ColumnProblem::Uncompensated {
                    reason,
                    others: failed[1..].iter().take(10).copied().collect(),
                    failed: failed.len(),
                };
                return Err(Error::Column {
                    line,
                    column,
                    name,
                    problem,
                });
            }
            Err(e) => return Err(e),
        }
    }
    Ok(out)
}

fn check_compensated(arm: &Arm, line: u64, qc: &Vector6<f64>, ep: f64, eo: f64) -> Result<()> {
    let robot = &arm.robot();
    if let Some(v) = robot.limits().first_violation(qc) {
        return Err(uncompensated(
            line,
            "q_compensated",
            format!(
                "cannot be compensated within the joint limits: axis {} would need {:.4} deg, limits [{:.2}, {:.2}] deg",
                v.axis + 1,
                v.value.to_degrees(),
                v.lower.to_degrees(),
                v.upper.to_degrees()
            ),
        ));
    }
    if !(ep <= REQUIRED_M && eo <= REQUIRED_RAD) {
        return Err(uncompensated(
            line,
            "q_compensated",
            format!(
                "the compensation did not converge: residual {:.3} um and {:.3} urad after {MAX_ITERATIONS} steps (near a singularity?)",
                ep * 1e6,
                eo * 1e6
            ),
        ));
    }
    Ok(())
}

/// The nominal axis angles of every point: given, or by inverse kinematics continued from the
/// previous point (the first from `start`).
fn nominal_postures(
    arm: &Arm,
    points: &[PathPoint],
    start: Vector6<f64>,
    options: &Options,
) -> Result<Vec<Vector6<f64>>> {
    let robot = &arm.robot();
    let mut previous = start;
    let mut out = Vec::with_capacity(points.len());
    for p in points {
        let q = match &p.target {
            Target::Posture(q) => {
                if let Some(v) = robot.limits().first_violation(q) {
                    let name = format!("q{}_deg", v.axis + 1);
                    return Err(Error::Column {
                        line: p.line,
                        column: None,
                        problem: v.outside(name.clone(), "the joint limits"),
                        name,
                    });
                }
                *q
            }
            Target::Pose(t) => {
                let q = ik::solve(robot, &arm.tool().tcp, t, &previous, &options.ik)
                    .map_err(|e| uncompensated(p.line, "x_mm..rz_deg", e.to_string()))?
                    .q;
                let from = if out.is_empty() {
                    "the start posture"
                } else {
                    "the previous point"
                };
                if let Some(change) =
                    Configuration::of(robot, &q).change_from(&Configuration::of(robot, &previous))
                {
                    return Err(uncompensated(p.line, "x_mm..rz_deg", format!("inverse kinematics reaches this pose only in another configuration than {from}'s ({change}); refused rather than switched silently: start in the configuration wanted (--q0-deg, q0_deg)")));
                }
                q
            }
        };
        previous = q;
        out.push(q);
    }
    Ok(out)
}

/// The postures and tool rotations of the free tool axis (module docs).
fn optimise_tool_axis(
    model: &Model,
    nominal: &[Vector6<f64>],
    wrenches: &[Vector6<f64>],
    free: &FreeToolAxis,
    ik_options: &ik::Options,
) -> (Vec<Vector6<f64>>, Vec<f64>) {
    let (spacing, reach) = free.grid();
    let half = (free.range / spacing + 1e-9).floor() as isize;
    let angles: Vec<f64> = (-half..=half).map(|g| g as f64 * spacing).collect();
    let columns: Vec<Column> = angles
        .par_iter()
        .map(|&phi| column(model, nominal, wrenches, phi, ik_options))
        .collect();
    let zero = half as usize;
    let n = nominal.len();
    let g_count = angles.len();
    // cost[i][g]: the smallest sum of deflections up to point i ending at angle g.
    let feasible = |i: usize, g: usize| {
        columns[g][i]
            .as_ref()
            .filter(|(_, d)| *d <= columns[zero][i].as_ref().map_or(0.0, |z| z.1))
            .map(|(_, d)| *d)
    };
    // The tie-breaking cost (module docs): TIE_BREAK of the nominal deflection per full range
    // away from the path's angle and per full step between points.
    let weight = |i: usize| TIE_BREAK * columns[zero][i].as_ref().map_or(0.0, |z| z.1);
    let mut cost = vec![vec![f64::INFINITY; g_count]; n];
    let mut from = vec![vec![0usize; g_count]; n];
    for i in 0..n {
        let w = weight(i);
        for g in 0..g_count {
            let Some(d) = feasible(i, g) else { continue };
            let own = d + w * angles[g].abs() / free.range;
            if i == 0 {
                cost[0][g] = own;
                continue;
            }
            let lo = g.saturating_sub(reach);
            let hi = (g + reach).min(g_count - 1);
            let turn =
                |a: usize| cost[i - 1][a] + w * (angles[g] - angles[a]).abs() / free.max_step;
            if let Some(best) = (lo..=hi).min_by(|&a, &b| turn(a).total_cmp(&turn(b))) {
                cost[i][g] = turn(best) + own;
                from[i][g] = best;
            }
        }
    }
    let mut g = (0..g_count)
        .min_by(|&a, &b| cost[n - 1][a].total_cmp(&cost[n - 1][b]))
        .unwrap_or(zero);
    let mut chosen = vec![zero; n];
    for i in (0..n).rev() {
        chosen[i] = g;
        g = from[i][g];
    }
    chosen
        .iter()
        .enumerate()
        .map(|(i, &g)| {
            let q = columns[g][i].as_ref().map_or(nominal[i], |c| c.0);
            (q, angles[g])
        })
        .unzip()
}

/// One angle's posture and TCP translation deflection (m) at every path point; `None` where
/// inverse kinematics fails.
type Column = Vec<Option<(Vector6<f64>, f64)>>;

/// The postures of the path turned by `phi` about tool z, continued along the path, and their TCP
/// translation deflection (m); `None` where inverse kinematics fails.
fn column(
    model: &Model,
    nominal: &[Vector6<f64>],
    wrenches: &[Vector6<f64>],
    phi: f64,
    ik_options: &ik::Options,
) -> Column {
    let arm = model.arm;
    let tcp = &arm.tool().tcp;
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi);
    let options = ik::Options {
        restarts: 0,
        ..*ik_options
    };
    let mut previous: Option<Vector6<f64>> = None;
    nominal
        .iter()
        .zip(wrenches)
        .map(|(q, w)| {
            let q = match phi == 0.0 {
                true => Some(*q),
                false => {
                    let mut target = tool_pose(&arm.robot().frames(q), tcp);
                    target.rotation *= turn;
                    let start = previous.unwrap_or(*q);
                    ik::solve(arm.robot(), tcp, &target, &start, &options)
                        .or_else(|_| ik::solve(arm.robot(), tcp, &target, q, &options))
                        .ok()
                        .map(|s| s.q)
                }
            };
            previous = q;
            q.map(|q| {
                let d = model.deflection(&arm.robot().frames(&q), w).0;
                (q, d.fixed_rows::<3>(0).norm())
            })
        })
        .collect()
}
