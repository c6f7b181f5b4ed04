//! The deflection of any tool point under a wrench at any tool point, in the base or the tool
//! frame, and its uncertainty (Zhang et al. 2021, Eq. 4-6).
//!
//! The wrench `W = [f; m]` (N, Nm) acts at the tool point a; the joint torques are
//! `tau = J_a^T W_base` (Eq. 4), the joint deflections `dq = h .* tau` (Eq. 5) and the displacement
//! of the tool point b `[dp; dphi] = J_b dq` (Eq. 6): translation of b (m) and rotation of the tool
//! (rad), base frame. With a = b this is [`crate::cartesian::compliance`] times `W`.
//!
//! **Uncertainty**: the displacement is linear in the compliance, `J_b diag(tau) h`, so with the
//! covariance `Cov(h)` of an identification ([`crate::identify::Uncertainty`]) its covariance is
//! exactly `J_b diag(tau) Cov(h) diag(tau) J_b^T` (first-order propagation, exact here because the
//! map is linear in h).

use crate::kinematics::{Coordinates, Frames};
use nalgebra::{Matrix6, Vector3, Vector6};
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
    pub const ALL: [Frame; 2] = [Frame::Base, Frame::Tool];

    /// The name in files, options and documents: `base` or `tool`.
    pub fn name(self) -> &'static str {
        match self {
            Frame::Base => "base",
            Frame::Tool => "tool",
        }
    }
}

impl crate::choice::Choice for Frame {
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

crate::choice::by_name!(Frame);

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

/// Where a wrench acts and where the deflection is wanted, in one posture.
#[derive(Debug, Clone, Copy)]
pub struct Points<'a> {
    /// The posture's kinematics.
    pub frames: &'a Frames,
    /// The coordinates of the joint springs.
    pub springs: Coordinates,
    /// Where the wrench acts, flange frame, m.
    pub loaded: &'a Vector3<f64>,
    /// Whose deflection is wanted, flange frame, m.
    pub observed: &'a Vector3<f64>,
}

/// A tool point's deflection under a wrench.
#[derive(Debug, Clone, PartialEq)]
pub struct PointDeflection {
    /// `tau = J_a^T W` (Eq. 4), Nm, springs' coordinates.
    pub torques: Vector6<f64>,
    /// `dq = h .* tau` (Eq. 5), rad, springs' coordinates.
    pub joint_deflections: Vector6<f64>,
    /// `J_b dq` (Eq. 6): translation of the point (m) then rotation of the tool (rad), base frame.
    pub displacement: Vector6<f64>,
    /// The Jacobian `J_b` of the observed point, for [`PointDeflection::covariance`].
    jacobian: Matrix6<f64>,
}

impl Points<'_> {
    /// The deflection under `wrench` (`[f; m]`, N and Nm, base frame, at the loaded point) with
    /// joint compliance `h` (rad/Nm).
    pub fn deflection(&self, wrench: &Vector6<f64>, h: &Vector6<f64>) -> PointDeflection {
        let jb = self.frames.jacobian(self.observed, self.springs);
        let torques = match self.loaded == self.observed {
            true => jb.tr_mul(wrench),
            false => self
                .frames
                .jacobian(self.loaded, self.springs)
                .tr_mul(wrench),
        };
        let joint_deflections = torques.component_mul(h);
        PointDeflection {
            torques,
            joint_deflections,
            displacement: jb * joint_deflections,
            jacobian: jb,
        }
    }
}

impl PointDeflection {
    /// The covariance (6x6, m^2, m rad, rad^2, base frame) of the displacement given the
    /// covariance of the compliance `Cov(h)` ((rad/Nm)^2): `J_b diag(tau) Cov(h) diag(tau) J_b^T`.
    pub fn covariance(&self, compliance_covariance: &Matrix6<f64>) -> Matrix6<f64> {
        let mut a = self.jacobian;
        for (c, mut col) in a.column_iter_mut().enumerate() {
            col *= self.torques[c];
        }
        a * compliance_covariance * a.transpose()
    }

    /// The standard deviation of each coordinate of the displacement (m, m, m, rad, rad, rad).
    pub fn std(&self, compliance_covariance: &Matrix6<f64>) -> Vector6<f64> {
        self.covariance(compliance_covariance)
            .diagonal()
            .map(|v| v.max(0.0).sqrt())
    }
}
