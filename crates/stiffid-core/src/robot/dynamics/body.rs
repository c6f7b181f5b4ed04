//! Rigid bodies ([`LinkMass`]): moved into another frame, combined, and their inertia tensors
//! read from the six numbers files give and checked.

use crate::robot::LinkMass;
use nalgebra::{Isometry3, Matrix3, Point3};

/// The symmetric tensor of `[ixx, iyy, izz, ixy, ixz, iyz]` (kg m^2), the order of robot files
/// and of URDF's `<inertia>`.
pub(crate) fn tensor([xx, yy, zz, xy, xz, yz]: [f64; 6]) -> Matrix3<f64> {
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// `[ixx, iyy, izz, ixy, ixz, iyz]` of a tensor (kg m^2), the inverse of `tensor`.
pub fn components(i: &Matrix3<f64>) -> [f64; 6] {
    [
        i[(0, 0)],
        i[(1, 1)],
        i[(2, 2)],
        i[(0, 1)],
        i[(0, 2)],
        i[(1, 2)],
    ]
}

/// Why `i` (kg m^2, about the centre of mass) is no rigid body's inertia tensor, if it is not: a
/// principal moment below zero or one above the sum of the other two (the triangle inequality
/// every mass distribution keeps), beyond rounding (1e-9 of the largest moment).
pub(crate) fn physical(i: &Matrix3<f64>) -> std::result::Result<(), String> {
    let moments = i.symmetric_eigenvalues();
    let scale = moments.amax();
    let tolerance = 1e-9 * scale;
    if moments.iter().any(|m| *m < -tolerance) {
        return Err(
            "expected a positive semi-definite inertia tensor (a principal moment is negative)"
                .into(),
        );
    }
    let sum = moments.sum();
    if moments.iter().any(|m| *m > sum - m + tolerance) {
        return Err("expected principal moments that keep the triangle inequality (each at most the sum of the other two)".into());
    }
    Ok(())
}

impl LinkMass {
    /// The body with its centre and inertia expressed in the frame in which `t` places the
    /// body's frame (`t` maps the body's coordinates to the new ones): centre `t c`, tensor
    /// `R I R^T`.
    pub fn moved(&self, t: &Isometry3<f64>) -> LinkMass {
        let r = t.rotation.to_rotation_matrix().into_inner();
        LinkMass {
            mass: self.mass,
            centre: (t * Point3::from(self.centre)).coords,
            inertia: r * self.inertia * r.transpose(),
        }
    }

    /// The rigid union of two bodies given in one frame: mass `m_a + m_b`, centre the weighted
    /// mean, tensor about it by the parallel-axis theorem
    /// `sum_k I_k + m_k (|d_k|^2 E - d_k d_k^T)`, `d_k` from the new centre to body k's.
    pub fn plus(&self, other: &LinkMass) -> LinkMass {
        let mass = self.mass + other.mass;
        if mass <= 0.0 {
            return LinkMass {
                inertia: self.inertia + other.inertia,
                ..*self
            };
        }
        let centre = (self.centre * self.mass + other.centre * other.mass) / mass;
        let shifted = |b: &LinkMass| {
            let d = b.centre - centre;
            b.inertia + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * b.mass
        };
        LinkMass {
            mass,
            centre,
            inertia: shifted(self) + shifted(other),
        }
    }
}
