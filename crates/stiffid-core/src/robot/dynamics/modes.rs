//! Natural frequencies and mode shapes of the undamped elastic robot: `K v = w^2 M v`, `K` the
//! joint-space stiffness and `M` the mass matrix of one posture (the rigid-body modes of the
//! springs held by the links' inertia, as in Bottin et al., Appl. Sci. 10, 2020).
//!
//! The generalised symmetric eigenproblem is solved by the Cholesky factor `M = L L^T` on the
//! compliance `C = K^-1` (which virtual springs give without inverting anything):
//! `K v = w^2 M v` is `(L^T C L) y = w^-2 y` with `v = L^-T y`, one symmetric 6x6 eigenproblem.

use nalgebra::{Matrix6, SymmetricEigen, Vector3, Vector6};

/// The six modes of one posture, lowest frequency first.
#[derive(Debug, Clone, PartialEq)]
pub struct Modes {
    /// Natural frequencies `w / (2 pi)`, Hz, ascending.
    pub frequencies: [f64; 6],
    /// The mode shape of each frequency (columns of joint motion, rad per rad in the coordinates
    /// of `M` and `C`), scaled to a largest component of +1.
    pub shapes: [Vector6<f64>; 6],
}

/// The modes of the joint-space compliance `c` (rad/Nm, symmetric positive definite) and the
/// mass matrix `m` (kg m^2), both in the same joint coordinates; `None` where `m` is not positive
/// definite, `c` not positive definite, or either not finite.
pub fn modes(m: &Matrix6<f64>, c: &Matrix6<f64>) -> Option<Modes> {
    c.iter().all(|v| v.is_finite()).then_some(())?;
    let l = super::factor(m)?.l();
    let b = l.transpose() * c * l;
    let eigen = SymmetricEigen::new((b + b.transpose()) * 0.5);
    let mut order: [usize; 6] = std::array::from_fn(|i| i);
    order.sort_by(|&i, &j| eigen.eigenvalues[j].total_cmp(&eigen.eigenvalues[i]));
    let lt = l.transpose();
    let mut out = Modes {
        frequencies: [0.0; 6],
        shapes: [Vector6::zeros(); 6],
    };
    for (slot, &i) in order.iter().enumerate() {
        let mu = eigen.eigenvalues[i];
        if mu.is_nan() || mu <= 0.0 {
            return None;
        }
        out.frequencies[slot] = 1.0 / (mu.sqrt() * std::f64::consts::TAU);
        let v = lt.solve_upper_triangular(&eigen.eigenvectors.column(i).into_owned())?;
        out.shapes[slot] = scaled(v);
    }
    Some(out)
}

/// The direction (unit, base frame) in which each mode moves the point of `jacobian` (6x6, rows
/// `[v; omega]`, columns in the coordinates of the modes), lowest frequency first; zeros where a
/// mode does not move it, and without modes.
pub fn point_directions(jacobian: &Matrix6<f64>, modes: Option<&Modes>) -> [Vector3<f64>; 6] {
    let mut out = [Vector3::zeros(); 6];
    for (d, shape) in out.iter_mut().zip(modes.iter().flat_map(|m| &m.shapes)) {
        let v = jacobian.fixed_rows::<3>(0) * shape;
        *d = v.try_normalize(0.0).unwrap_or_default();
    }
    out
}

/// `v` over its largest component (by magnitude, sign included), so that it is +1.
fn scaled(v: Vector6<f64>) -> Vector6<f64> {
    let k = v.iamax();
    v / v[k]
}
