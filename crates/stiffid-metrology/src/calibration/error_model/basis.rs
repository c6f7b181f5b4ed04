//! The basis `(u, v, w)` of a joint's rotation frame in which its six errors are expressed.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

/// The basis `(u, v, w)` of a joint's rotation frame: `w` its axis, `u` the coordinate axis (x,
/// then y, then z) least aligned with it, made perpendicular, `v = w x u`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Basis {
    /// `u`.
    pub u: Vector3<f64>,
    /// `v = w x u`.
    pub v: Vector3<f64>,
    /// `w`, the joint axis.
    pub w: Vector3<f64>,
}

impl Basis {
    /// The basis of the joint axis `w` (unit).
    pub(crate) fn of(w: &Unit<Vector3<f64>>) -> Self {
        let w = w.into_inner();
        let pick = (0..3)
            .min_by(|&a, &b| w[a].abs().total_cmp(&w[b].abs()))
            .unwrap_or(0);
        let e = Vector3::ith(pick, 1.0);
        let u = (e - w * w.dot(&e)).normalize();
        Basis {
            u,
            v: w.cross(&u),
            w,
        }
    }

    /// `E = Trans(a u + b v) Rot(u, alpha) Rot(v, beta) Trans(d w)` of the errors
    /// `[theta, d, a, alpha, beta, b]` (theta is not part of it: it adds to the joint angle).
    pub(crate) fn error(&self, e: &[f64; 6]) -> Isometry3<f64> {
        let [_, d, a, alpha, beta, b] = *e;
        let shift = Isometry3::from_parts(
            Translation3::from(self.u * a + self.v * b),
            UnitQuaternion::from_axis_angle(&Unit::new_unchecked(self.u), alpha),
        );
        shift
            * UnitQuaternion::from_axis_angle(&Unit::new_unchecked(self.v), beta)
            * Isometry3::translation(self.w.x * d, self.w.y * d, self.w.z * d)
    }
}
