//! Exact derivatives of point Jacobians and of the dexterity index with respect to the axis angles,
//! in reverse (adjoint) form: the gradient of a scalar that is linear in a point Jacobian.
//!
//! For a revolute chain, joint k turns every body beyond it about its axis (direction `z_k` through
//! `o_k`), so with the kinematic columns `[v_j; w_j] = [z_j x (p - o_j); z_j]` of a point p
//! (Sciavicco & Siciliano; Haschke et al. 2008 for the closed form):
//!
//! - `d[v_j; w_j] / d theta_k = [w_j x v_k; 0]` for `j <= k` (only p moves),
//! - `d[v_j; w_j] / d theta_k = [w_k x v_j; w_k x w_j]` for `j > k` (the whole column turns),
//! - `dp / d theta_k = v_k`.
//!
//! For a weight `W = [H; K]` on the Jacobian's columns and a weight g on the point, the scalar
//! `phi = <W, J_theta> + g . p` (a Frobenius product) then has, by `a . (b x c) = c . (a x b)`,
//!
//! `d phi / d theta_k = v_k . (g + sum_{j <= k} H_j x w_j) + w_k . sum_{j > k} (v_j x H_j + w_j x K_j)`,
//!
//! two running sums over the columns: a few dozen flops per point instead of the 6 x 36 entries of
//! the Jacobian's derivatives. Axis coordinates follow by the chain rule through
//! `theta = M q + c`: `J_q = J_theta M`, so `<W, J_q> = <W M^T, J_theta>`, and
//! `d phi / dq = M^T d phi / d theta`.

use super::{Coordinates, Frames};
use nalgebra::{Matrix6, Vector3, Vector6};

impl Frames {
    /// The gradient with respect to the axis angles q (per rad) of
    /// `phi(q) = <W, J(p)> + g . p`: `W` (6x6, rows `[v; omega]`, units of phi per m/rad and per
    /// rad/rad) weighs the geometric Jacobian `J` of the body point p (given in the flange frame, m)
    /// with columns in `coordinates`, and `g` (units of phi per m) its base-frame position.
    ///
    /// This is a vector-Jacobian product of the derivatives of [`Frames::jacobian`] and
    /// [`Frames::point`]; it costs about as much as one point Jacobian. The gradient of any scalar
    /// built from point Jacobians follows by the chain rule: `W` is the scalar's derivative with
    /// respect to the Jacobian's entries.
    pub fn jacobian_gradient(
        &self,
        in_flange: &Vector3<f64>,
        coordinates: Coordinates,
        weight: &Matrix6<f64>,
        point_weight: &Vector3<f64>,
    ) -> Vector6<f64> {
        let p = self.point(in_flange);
        let w = match coordinates {
            Coordinates::Kinematic => *weight,
            Coordinates::Axis => times_transpose(weight, &self.axis_map),
        };
        let screws = &self.screws[0];
        let z: [Vector3<f64>; 6] = std::array::from_fn(|j| screws.directions.column(j).into());
        let v: [Vector3<f64>; 6] =
            std::array::from_fn(|j| z[j].cross(&p) - screws.moments.column(j));
        let (h, k): ([Vector3<f64>; 6], [Vector3<f64>; 6]) = (
            std::array::from_fn(|j| w.fixed_view::<3, 1>(0, j).into()),
            std::array::from_fn(|j| w.fixed_view::<3, 1>(3, j).into()),
        );
        let mut grad = Vector6::zeros();
        let mut inner = *point_weight;
        for j in 0..6 {
            inner += h[j].cross(&z[j]);
            grad[j] = v[j].dot(&inner);
        }
        let mut outer = Vector3::zeros();
        for j in (0..6).rev() {
            grad[j] += z[j].dot(&outer);
            outer += v[j].cross(&h[j]) + z[j].cross(&k[j]);
        }
        self.axis_map.tr_mul(&grad)
    }
}

impl Frames {
    /// A gradient with respect to the kinematic angles theta turned into one with respect to the
    /// axis angles q: `d / dq = M^T d / d theta` (`theta = M q + c`).
    pub fn kinematic_to_axis(&self, gradient: &Vector6<f64>) -> Vector6<f64> {
        self.axis_map.tr_mul(gradient)
    }
}

/// `W M^T`, skipping the zeros of `M` (most axis maps are a signed permutation plus a coupling).
fn times_transpose(w: &Matrix6<f64>, m: &Matrix6<f64>) -> Matrix6<f64> {
    let mut out = Matrix6::zeros();
    for c in 0..6 {
        for k in 0..6 {
            let f = m[(k, c)];
            if f != 0.0 {
                let mut o = out.column_mut(k);
                o.axpy(f, &w.column(c), 1.0);
            }
        }
    }
    out
}

/// The derivative of `ln k(J_N)` ([`super::dexterity`]) with respect to the entries of the
/// Jacobian J (6x6, rows `[v; omega]`), or `None` where the dexterity is `+infinity`.
///
/// With `J_N = D J`, `D = diag(I/L, I)` and `X = J_N^-1`:
/// `ln k = ln |J_N|_F + ln |X|_F - ln 6`, `d|J_N|_F^2 = 2 <J_N, dJ_N>` and `dX = -X dJ_N X`, so
/// `d ln k = <D (J_N / |J_N|_F^2 - X^T X X^T / |X|_F^2), dJ>`. Feed it to
/// [`Frames::jacobian_gradient`] for the gradient with respect to the axis angles.
pub fn dexterity_log_gradient(
    jacobian: &Matrix6<f64>,
    characteristic_length: f64,
) -> Option<Matrix6<f64>> {
    let (jn, x) = super::normalised(jacobian, characteristic_length)?;
    let mut g = jn / jn.norm_squared() - x.transpose() * x * x.transpose() / x.norm_squared();
    g.fixed_rows_mut::<3>(0)
        .scale_mut(1.0 / characteristic_length);
    Some(g)
}
