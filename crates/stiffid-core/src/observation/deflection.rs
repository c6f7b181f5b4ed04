//! The deflection of any tool point under a wrench at any tool point, in the base or the tool
//! frame, and its uncertainty (Zhang et al. 2021, Eq. 4-6).
//!
//! The wrench `W = [f; m]` (N, Nm) acts at the tool point a; the joint torques are
//! `tau = J_a^T W_base` (Eq. 4), the joint deflections `dq = h .* tau` (Eq. 5) and the displacement
//! of the tool point b `[dp; dphi] = J_b dq` (Eq. 6): translation of b (m) and rotation of the tool
//! (rad), base frame. With a = b this is [`crate::observation::cartesian::compliance`] times `W`.
//!
//! **Over the model** ([`crate::model`]): the Jacobians are augmented by one column per virtual
//! spring (`[J_q | J_s]`, `crate::model::Model::jacobian`), `tau` holds every parameter's load
//! (Nm or N) and `h` every parameter's compliance, so the same three lines give the deflection
//! `J_b diag(h) J_a^T W = (J_q,b K^-1 J_q,a^T + sum_s c_s J_s,b J_s,a^T) W`.
//!
//! **Uncertainty**: the displacement is linear in the compliance, `J_b diag(tau) h`, so with the
//! covariance `Cov(h)` of an identification ([`crate::model::Compliance`]) its covariance is
//! exactly `J_b diag(tau) Cov(h) diag(tau) J_b^T` (first-order propagation, exact here because the
//! map is linear in h).

use crate::robot::kinematics::Frames;
use crate::setup::Arm;
use nalgebra::{DMatrix, DVector, Matrix6, Matrix6xX, Vector3, Vector6};
use serde::{Deserialize, Serialize};

/// The frame a wrench is given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Frame {
    /// The robot base frame.
    #[default]
    Base,
    /// The tool frame: the flange frame's orientation, moving with the tool.
    Tool,
}

impl Frame {
    /// Both, base first.
    pub(crate) const ALL: [Frame; 2] = [Frame::Base, Frame::Tool];

    /// The name in files, options and documents: `base` or `tool`.
    pub fn name(self) -> &'static str {
        match self {
            Frame::Base => "base",
            Frame::Tool => "tool",
        }
    }
}

impl crate::common::choice::Choice for Frame {
    const FIELD: &'static str = "frame";
    const ALL: &'static [Self] = &Frame::ALL;
    fn name(self) -> &'static str {
        Frame::name(self)
    }
    fn help(self) -> &'static str {
        match self {
            Frame::Base => "The robot base frame",
            Frame::Tool => "The tool (flange) frame, moving with the tool",
        }
    }
}

crate::common::choice::by_name!(Frame);

/// A wrench `[f; m]` (N, Nm) in `frame` rotated into the base frame of the posture `frames`:
/// `[R f; R m]`, `R` the flange orientation (the identity for [`Frame::Base`]).
pub fn base_wrench(frames: &Frames, wrench: &Vector6<f64>, frame: Frame) -> Vector6<f64> {
    match frame {
        Frame::Base => *wrench,
        Frame::Tool => {
            let r = frames.flange.rotation;
            let f = r * wrench.fixed_rows::<3>(0);
            let m = r * wrench.fixed_rows::<3>(3);
            Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z)
        }
    }
}

/// Where a wrench acts and where the deflection is wanted, in one posture of an arm's robot,
/// over the arm's model ([`crate::model`]: the drives and the virtual springs).
#[derive(Debug, Clone, Copy)]
pub struct Points<'a> {
    /// The arm: robot, model (drive coordinates, virtual springs).
    pub arm: &'a Arm,
    /// The posture's kinematics.
    pub frames: &'a Frames,
    /// Where the wrench acts, flange frame, m.
    pub loaded: &'a Vector3<f64>,
    /// Whose deflection is wanted, flange frame, m.
    pub observed: &'a Vector3<f64>,
}

/// A tool point's deflection under a wrench.
#[derive(Debug, Clone, PartialEq)]
pub struct PointDeflection {
    /// `tau = J_a^T W` (Eq. 4) of every parameter, drives first: Nm (drives in the springs'
    /// coordinates, rotational springs) or N (translational springs).
    pub torques: DVector<f64>,
    /// `dq = h .* tau` (Eq. 5) of every parameter: rad or m.
    pub joint_deflections: DVector<f64>,
    /// `J_b dq` (Eq. 6): translation of the point (m) then rotation of the tool (rad), base frame.
    pub displacement: Vector6<f64>,
    /// The augmented Jacobian `J_b` of the observed point, for [`PointDeflection::covariance`].
    jacobian: Matrix6xX<f64>,
}

impl Points<'_> {
    /// The deflection under `wrench` (`[f; m]`, N and Nm, base frame, at the loaded point) with
    /// the compliance `h` of every parameter of the arm's model (rad/Nm, m/N; drives first),
    /// by the augmented Jacobians.
    ///
    /// # Panics
    /// If `h` does not have one value per parameter ([`crate::model::Compliance::check`]).
    pub fn deflection(&self, wrench: &Vector6<f64>, h: &DVector<f64>) -> PointDeflection {
        let model = self.arm.model();
        assert_eq!(h.len(), model.len(), "one compliance per parameter");
        let jb = model.jacobian(self.frames, self.observed);
        let torques = match self.loaded == self.observed {
            true => jb.tr_mul(wrench),
            false => model.jacobian(self.frames, self.loaded).tr_mul(wrench),
        };
        let joint_deflections = torques.component_mul(h);
        PointDeflection {
            displacement: &jb * &joint_deflections,
            torques,
            joint_deflections,
            jacobian: jb,
        }
    }
}

impl PointDeflection {
    /// The covariance (6x6, m^2, m rad, rad^2, base frame) of the displacement given the
    /// covariance `Cov(h)` of the compliance (n x n, SI): `J_b diag(tau) Cov(h) diag(tau) J_b^T`.
    ///
    /// # Panics
    /// If `compliance_covariance` is not n x n.
    pub fn covariance(&self, compliance_covariance: &DMatrix<f64>) -> Matrix6<f64> {
        let mut a = self.jacobian.clone();
        for (c, mut col) in a.column_iter_mut().enumerate() {
            col *= self.torques[c];
        }
        let full = &a * compliance_covariance * a.transpose();
        Matrix6::from_fn(|r, c| full[(r, c)])
    }

    /// The translation rows of the observation matrix here: `J_b[0..3] diag(tau)` (3 x n, SI), so
    /// that the translation is these rows times the compliance (Eq. 10-11).
    pub fn translation_rows(&self) -> DMatrix<f64> {
        let mut a = self.jacobian.rows(0, 3).into_owned();
        for (c, mut col) in a.column_iter_mut().enumerate() {
            col *= self.torques[c];
        }
        DMatrix::from_column_slice(3, a.ncols(), a.as_slice())
    }

    /// The interval at `level` of the true translation (m, base frame) predicted with the
    /// compliance `h` (SI), when the compliance carries a prediction calibration: what a
    /// compensation by the prediction leaves ([`crate::model::prediction`], P3).
    pub fn interval(
        &self,
        calibration: &crate::model::prediction::Calibration,
        h: &nalgebra::DVector<f64>,
        level: f64,
    ) -> crate::model::prediction::Interval {
        calibration.deflection_interval(&self.translation_rows(), h, level)
    }

    /// The standard deviation of each coordinate of the displacement (m, m, m, rad, rad, rad).
    pub fn std(&self, compliance_covariance: &DMatrix<f64>) -> Vector6<f64> {
        self.covariance(compliance_covariance)
            .diagonal()
            .map(|v| v.max(0.0).sqrt())
    }
}
