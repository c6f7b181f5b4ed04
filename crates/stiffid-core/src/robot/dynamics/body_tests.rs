//! The link bodies' tests: sums, moves and the tensors no body has.

use super::body::*;
use crate::robot::LinkMass;
use nalgebra::{Isometry3, Matrix3};
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
