//! Rigid bodies ([`LinkMass`]): moved into another frame, combined, and their inertia tensors
//! read from the six numbers files give and checked.

use crate::robot::LinkMass;
use nalgebra::{Isometry3, Matrix3, Point3};

/// The symmetric tensor of `[ixx, iyy, izz, ixy, ixz, iyz]` (kg m^2), the order of robot files
/// and of URDF's `<inertia>`.
pub fn tensor([xx, yy, zz, xy, xz, yz]: [f64; 6]) -> Matrix3<f64> {
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// `[ixx, iyy, izz, ixy, ixz, iyz]` of a tensor (kg m^2), the inverse of [`tensor`].
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
pub fn physical(i: &Matrix3<f64>) -> std::result::Result<(), String> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion, Vector3};

    /// A solid box of sides a, b, c (m) and mass m: I = m/12 diag(b^2+c^2, a^2+c^2, a^2+b^2).
    fn cuboid(m: f64, a: f64, b: f64, c: f64, centre: Vector3<f64>) -> LinkMass {
        let i = Matrix3::from_diagonal(&Vector3::new(b * b + c * c, a * a + c * c, a * a + b * b));
        LinkMass {
            mass: m,
            centre,
            inertia: i * (m / 12.0),
        }
    }

    #[test]
    fn two_halves_make_the_whole_box() {
        // Two 1 x 1 x 0.5 boxes side by side along z make one 1 x 1 x 1 box.
        let low = cuboid(3.0, 1.0, 1.0, 0.5, Vector3::new(0.0, 0.0, -0.25));
        let high = cuboid(3.0, 1.0, 1.0, 0.5, Vector3::new(0.0, 0.0, 0.25));
        let whole = cuboid(6.0, 1.0, 1.0, 1.0, Vector3::zeros());
        let sum = low.plus(&high);
        assert!((sum.inertia - whole.inertia).norm() < 1e-14);
        assert!((sum.centre - whole.centre).norm() < 1e-15);
        assert_eq!(sum.mass, 6.0);
    }

    #[test]
    fn moving_keeps_the_principal_moments_and_carries_the_centre() {
        let b = cuboid(2.0, 0.3, 0.2, 0.1, Vector3::new(0.1, 0.0, 0.0));
        let t = Isometry3::from_parts(
            Translation3::new(1.0, 2.0, 3.0),
            UnitQuaternion::from_euler_angles(0.3, -0.2, 1.1),
        );
        let m = b.moved(&t);
        let sorted = |i: &Matrix3<f64>| {
            let mut e: Vec<f64> = i.symmetric_eigenvalues().iter().copied().collect();
            e.sort_by(f64::total_cmp);
            e
        };
        for (x, y) in sorted(&m.inertia).iter().zip(sorted(&b.inertia)) {
            assert!((x - y).abs() < 1e-15);
        }
        let expected = t.rotation * Vector3::new(0.1, 0.0, 0.0) + Vector3::new(1.0, 2.0, 3.0);
        assert!((m.centre - expected).norm() < 1e-15);
    }

    #[test]
    fn tensors_that_no_body_has_are_refused() {
        assert!(physical(&tensor([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])).is_ok());
        assert!(physical(&tensor([1.0, 1.0, 3.0, 0.0, 0.0, 0.0])).is_err());
        assert!(physical(&tensor([1.0, 1.0, -0.1, 0.0, 0.0, 0.0])).is_err());
        assert!(physical(&Matrix3::zeros()).is_ok());
        let six = [1.0, 2.0, 2.5, 0.1, -0.2, 0.3];
        assert_eq!(components(&tensor(six)), six);
    }
}
