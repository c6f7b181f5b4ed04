//! The compensation model of one arm: the loaded TCP pose and the Newton steps that compensate
//! one point (module docs of [`super`], "The loaded robot", "Compensation").

use super::{Compliance, MAX_ITERATIONS, TOLERANCE_M, TOLERANCE_RAD};
use crate::weight::Weight;
use nalgebra::{Isometry3, Matrix6, UnitQuaternion, Vector6};
use stiffid_core::common::stop::Stop;
use stiffid_core::observation::deflection::PointDeflection;
use stiffid_core::observation::deflection::Points;
use stiffid_core::robot::ik::{pose_error, tool_pose};
use stiffid_core::robot::kinematics::{Coordinates, Frames};
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result};

/// The compensation model of one arm: its robot, TCP, springs and compliance.
#[derive(Debug, Clone)]
pub struct Model<'a> {
    pub(super) arm: &'a Arm,
    pub(super) compliance: &'a Compliance,
    /// Spring deflections to axis angles: `M^-1` for kinematic springs, else the identity.
    to_axis: Matrix6<f64>,
    /// The level of the prediction intervals.
    pub(super) level: f64,
    /// The sag under the robot's own weight, from a calibration with gravity.
    weight: Option<Weight>,
    /// Newton steps at most per point.
    max_iterations: usize,
    /// The process force model's relative error (the budget's force part).
    force_tolerance: f64,
}

/// One point compensated by the Newton steps ([`Model::compensate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Newton {
    /// The compensated axis angles `q_c`, rad.
    pub q: Vector6<f64>,
    /// `|p_nominal - p_loaded(q_c)|`, m.
    pub residual_position: f64,
    /// The rotation between the nominal and the loaded tool at `q_c`, rad.
    pub residual_rotation: f64,
    /// Newton steps taken.
    pub iterations: usize,
    /// Why they stopped: [`Stop::Converged`], the residual below 1e-10 m and
    /// 1e-10 rad; or [`Stop::IterationLimit`], the most steps taken with the residual
    /// above them (the point is accepted when it is within 0.1 micrometre and
    /// 1 microradian, with a warning).
    pub stop: Stop,
}

impl<'a> Model<'a> {
    /// The model of `arm` (its TCP, drive springs and virtual springs) with the compliance
    /// `compliance` of every parameter of the arm's model; with the calibrated robot's
    /// [`stiffid_core::model::OwnWeight`] (or the compliance's), the sag under the robot's own weight.
    ///
    /// # Errors
    /// Those of [`Compliance::check`] and `Weight::of`; [`Error::InvalidField`] when the
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
        let weight = Weight::of(arm, compliance)?;
        Ok(Self {
            arm,
            compliance,
            to_axis,
            level: stiffid_core::model::prediction::DEFAULT_LEVEL,
            weight,
            max_iterations: MAX_ITERATIONS,
            force_tolerance: super::budget::DEFAULT_FORCE_TOLERANCE,
        })
    }

    /// The model with prediction intervals at `level` (default
    /// [`stiffid_core::model::prediction::DEFAULT_LEVEL`]).
    pub(crate) fn at_level(self, level: f64) -> Self {
        Self { level, ..self }
    }

    /// The model taking at most `max_iterations` Newton steps per point (at least 1; default
    /// [`MAX_ITERATIONS`]).
    pub(crate) fn with_max_iterations(self, max_iterations: usize) -> Self {
        Self {
            max_iterations: max_iterations.max(1),
            ..self
        }
    }

    /// The model whose error budget takes the process force model's relative error
    /// `force_tolerance` (default [`super::budget::DEFAULT_FORCE_TOLERANCE`]).
    pub(crate) fn with_force_tolerance(self, force_tolerance: f64) -> Self {
        Self {
            force_tolerance,
            ..self
        }
    }

    /// The error budget ([`super::Budget`]) of a point whose deflection under its wrench is `d`,
    /// compensated to the residual `left` (m).
    pub(crate) fn budget(&self, d: &super::budget::Deflected, left: f64) -> super::Budget {
        let held = self.arm.robot().held_out();
        super::Budget::new(
            left,
            super::budget::compensation(d, self.compliance, self.level),
            held.map(|h| h.quantile(self.level)),
            self.force_tolerance * d.displacement.fixed_rows::<3>(0).norm(),
            d.model_form,
        )
    }

    /// The TCP pose of the robot commanded to `q` (rad) and loaded by `wrench` (base frame) at the
    /// TCP, sagging under its own weight with a `Weight` (module docs).
    pub fn loaded_pose(&self, q: &Vector6<f64>, wrench: &Vector6<f64>) -> Isometry3<f64> {
        self.loaded(&self.arm.robot().frames(q), q, wrench)
    }

    /// [`Model::loaded_pose`] with the frames of `q` given. The virtual springs' deflection (a
    /// twist of the tool, `sum_s c_s (J_s^T W) J_s`) is applied to first order after the drives'
    /// (their second-order terms are about `|dq|^2` times the reach, far below the tolerance).
    pub(super) fn loaded(
        &self,
        frames: &Frames,
        q: &Vector6<f64>,
        wrench: &Vector6<f64>,
    ) -> Isometry3<f64> {
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
            .placed(frames)
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
    pub(super) fn deflection(
        &self,
        frames: &Frames,
        wrench: &Vector6<f64>,
    ) -> (Vector6<f64>, Option<(Vector6<f64>, f64)>) {
        let d = self.point_deflection(frames, wrench);
        (d.displacement, self.std(&d))
    }

    /// The TCP's deflection in the posture `frames` under `wrench` (base frame), with the
    /// model-form part of its budget when the compliance carries a `model_form`.
    pub(super) fn tcp_deflection(
        &self,
        frames: &Frames,
        wrench: &Vector6<f64>,
    ) -> super::budget::Deflected {
        let point = self.point_deflection(frames, wrench);
        let model_form = self.compliance.model_form.as_ref().and_then(|form| {
            let t = point.displacement.fixed_rows::<3>(0).into_owned();
            let tcp = &self.arm.tool().tcp;
            super::budget::model_form(form, frames, tcp, wrench, &t, self.level)
        });
        super::budget::Deflected { point, model_form }
    }

    /// The TCP's deflection in the posture `frames` under `wrench` (base frame).
    fn point_deflection(&self, frames: &Frames, wrench: &Vector6<f64>) -> PointDeflection {
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
    pub(super) fn std(&self, d: &PointDeflection) -> Option<(Vector6<f64>, f64)> {
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
    /// TCP. Returns `q_c`, the residual (m, rad), the steps taken and why they stopped (module
    /// docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (field `posture`) when the Jacobian is singular on the way.
    pub fn compensate(&self, q: &Vector6<f64>, wrench: &Vector6<f64>) -> Result<Newton> {
        self.compensate_from(q, self.arm.robot().frames(q), wrench)
    }

    /// [`Model::compensate`] with the frames of `q` given.
    pub(super) fn compensate_from(
        &self,
        q: &Vector6<f64>,
        mut frames: Frames,
        wrench: &Vector6<f64>,
    ) -> Result<Newton> {
        let tcp = &self.arm.tool().tcp;
        let target = tool_pose(&frames, tcp);
        let mut qc = *q;
        let mut iterations = 0;
        loop {
            let e = pose_error(&target, &self.loaded(&frames, &qc, wrench));
            let (ep, eo) = (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
            let stop = match ep <= TOLERANCE_M && eo <= TOLERANCE_RAD {
                true => Some(Stop::Converged),
                false => (iterations >= self.max_iterations).then_some(Stop::IterationLimit),
            };
            if let Some(stop) = stop {
                return Ok(Newton {
                    q: qc,
                    residual_position: ep,
                    residual_rotation: eo,
                    iterations,
                    stop,
                });
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
