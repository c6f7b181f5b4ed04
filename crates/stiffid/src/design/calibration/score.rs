//! A calibration criterion as a search minimises it, and its gradient with respect to the
//! design Jacobian.
//!
//! The search minimises the logarithm of a smaller-is-better value ([`CalibrationCriterion::loss`]):
//! the reciprocal of an observability index, the predicted RMS error itself. With the Householder
//! QR `J_s = Q R` (never the normal equations), `ln det` terms read `R`'s diagonal and the
//! predicted error `sigma |R_A R^-1|_F / sqrt(m_0)` (`A_0 = Q_A R_A`, factored once); the indices
//! that need singular values take them from the SVD of the `p x p` `R` (the same as `J_s`'s). The
//! gradient of `ln loss` with respect to `J_s` is `J_s W` with `W` symmetric (`p x p`):
//!
//! ```text
//! O1:         W = -(1/p) R^-1 R^-T                 (d ln det = <J (J^T J)^-1, dJ>)
//! D:          W = -(2/p) R^-1 R^-T
//! test-pose:  W = -(Y^T Y) / |Z|_F^2,  Z = R_A R^-1, Y = Z R^-T
//! O3:         W = -v_p v_p^T / s_p^2               (d s_i = u_i^T dJ v_i, u_i = J v_i / s_i)
//! O4:         W = -2 v_p v_p^T / s_p^2 + v_1 v_1^T / s_1^2
//! O5:         W = -(sum_i v_i v_i^T / s_i^3) / (sum_i 1 / s_i)
//! ```

use super::{CalibrationDesign, RANK_TOLERANCE};
use nalgebra::DMatrix;

/// A calibration design criterion, as `select` and `evaluate` name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum CalibrationCriterion {
    /// `O1`, the geometric mean of the singular values over `sqrt(n)` (larger is better).
    O1,
    /// `O3`, the smallest singular value (larger is better).
    O3,
    /// `O4`, the noise amplification index (larger is better).
    O4,
    /// `O5`, the inverse sum of the singular values' inverses (larger is better).
    O5,
    /// D-optimality, `det(J_s^T J_s)^(1/p)` (larger is better).
    DOptimality,
    /// The predicted RMS position error after calibration at the test postures (smaller is
    /// better): the default, the criterion that ranks groups by their held-out error best
    /// (docs/model.md, "Design for calibration").
    #[default]
    TestPose,
}

impl CalibrationCriterion {
    /// Every criterion, in report order.
    pub const ALL: [CalibrationCriterion; 6] = [
        CalibrationCriterion::O1,
        CalibrationCriterion::O3,
        CalibrationCriterion::O4,
        CalibrationCriterion::O5,
        CalibrationCriterion::DOptimality,
        CalibrationCriterion::TestPose,
    ];

    /// The value a search minimises for the criteria `c`: the reciprocal of an index (1/m, or
    /// 1/m^2 for D-optimality), the predicted RMS error (m).
    pub fn loss(self, c: &super::CalibrationCriteria) -> f64 {
        let inverse = |v: f64| if v > 0.0 { 1.0 / v } else { f64::INFINITY };
        match self {
            CalibrationCriterion::O1 => inverse(c.o1),
            CalibrationCriterion::O3 => inverse(c.o3),
            CalibrationCriterion::O4 => inverse(c.o4),
            CalibrationCriterion::O5 => inverse(c.o5),
            CalibrationCriterion::DOptimality => inverse(c.d_optimality),
            CalibrationCriterion::TestPose => c.predicted_rms,
        }
    }
}

impl crate::common::choice::Choice for CalibrationCriterion {
    const FIELD: &'static str = "calibration_criterion";
    const ALL: &'static [Self] = &CalibrationCriterion::ALL;
    fn name(self) -> &'static str {
        match self {
            CalibrationCriterion::O1 => "o1",
            CalibrationCriterion::O3 => "o3",
            CalibrationCriterion::O4 => "o4",
            CalibrationCriterion::O5 => "o5",
            CalibrationCriterion::DOptimality => "d-optimality",
            CalibrationCriterion::TestPose => "test-pose",
        }
    }
    fn help(self) -> &'static str {
        match self {
            CalibrationCriterion::O1 => "Geometric mean of the singular values (maximised)",
            CalibrationCriterion::O3 => "Smallest singular value (maximised)",
            CalibrationCriterion::O4 => "Noise amplification index (maximised)",
            CalibrationCriterion::O5 => "Inverse sum of inverse singular values (maximised)",
            CalibrationCriterion::DOptimality => "det(J^T J)^(1/p) (maximised)",
            CalibrationCriterion::TestPose => {
                "Predicted RMS position error at the test postures (the default)"
            }
        }
    }
}

crate::common::choice::by_name!(CalibrationCriterion);

/// `R` (`p x p`, upper triangular) of the Householder QR of `a` (`m x p`), zero rows added
/// when `m < p`.
pub(super) fn triangular_factor(a: &DMatrix<f64>) -> DMatrix<f64> {
    let p = a.ncols();
    let rows = a.nrows().max(p);
    a.clone().resize_vertically(rows, 0.0).qr().r()
}

/// A full-rank group's Jacobian scored: the value and what its gradient needs.
pub(super) struct Scored {
    /// The loss ([`CalibrationCriterion::loss`]).
    pub(super) value: f64,
    /// The scaled Jacobian.
    pub(super) j: DMatrix<f64>,
    /// What `W` (module docs) is made of.
    weight: Weight,
}

/// `W` of the module docs, formed only for a gradient.
enum Weight {
    /// `c R^-1 R^-T`.
    GramInverse(DMatrix<f64>, f64),
    /// `-(Y^T Y) / t`.
    Test(DMatrix<f64>, f64),
    /// Formed already (the spectral indices).
    Formed(DMatrix<f64>),
}

impl Scored {
    /// The score of the scaled Jacobian `j` of `n` postures; `None` for a group that does not
    /// separate the kept parameters (fewer rows than columns, a zero pivot of `R`, a singular
    /// value below [`RANK_TOLERANCE`] of the largest) or a non-finite value.
    pub(super) fn new(
        j: DMatrix<f64>,
        criterion: CalibrationCriterion,
        design: &CalibrationDesign,
    ) -> Option<Self> {
        let p = j.ncols();
        if j.nrows() < p || p == 0 || !j.iter().all(|v| v.is_finite()) {
            return None;
        }
        let n = j.nrows() / design.layout.rows(1);
        let r = j.clone().qr().r();
        let diagonal = r.diagonal().map(f64::abs);
        if diagonal.min() <= RANK_TOLERANCE * diagonal.max() {
            return None;
        }
        let r_inv = r.solve_upper_triangular(&DMatrix::identity(p, p))?;
        let mean_log = diagonal.iter().map(|d| d.ln()).sum::<f64>() / p as f64;
        let (value, weight) = match criterion {
            CalibrationCriterion::O1 => (
                (n as f64).sqrt() * (-mean_log).exp(),
                Weight::GramInverse(r_inv, -1.0 / p as f64),
            ),
            CalibrationCriterion::DOptimality => (
                (-2.0 * mean_log).exp(),
                Weight::GramInverse(r_inv, -2.0 / p as f64),
            ),
            CalibrationCriterion::TestPose => {
                let z = &design.test_factor * &r_inv;
                let trace = z.norm_squared();
                let m0 = (design.test.nrows() / 3).max(1) as f64;
                let value = design.noise * (trace / m0).sqrt();
                (value, Weight::Test(z * r_inv.transpose(), trace))
            }
            _ => {
                let (value, w) = spectral(&r, criterion)?;
                (value, Weight::Formed(w))
            }
        };
        (value.is_finite() && value > 0.0).then_some(Scored { value, j, weight })
    }

    /// The gradient of `ln value` with respect to the scaled Jacobian: `J_s W`.
    pub(super) fn log_gradient(&self) -> DMatrix<f64> {
        match &self.weight {
            Weight::GramInverse(r_inv, c) => (&self.j * r_inv) * r_inv.transpose() * *c,
            Weight::Test(y, trace) => (&self.j * y.transpose()) * y * (-1.0 / trace),
            Weight::Formed(w) => &self.j * w,
        }
    }
}

/// The value and `W` of an index that needs the singular values, from the SVD of `r`.
fn spectral(r: &DMatrix<f64>, criterion: CalibrationCriterion) -> Option<(f64, DMatrix<f64>)> {
    let p = r.ncols();
    let svd = r.clone().try_svd(
        false,
        true,
        f64::EPSILON,
        crate::math::linalg::SVD_MAX_ITERATIONS,
    )?;
    let v_t = svd.v_t?;
    let s = svd.singular_values;
    let mut order: Vec<usize> = (0..p).collect();
    order.sort_by(|&a, &b| s[b].total_cmp(&s[a]));
    let (first, last) = (order[0], order[p - 1]);
    if s[last] <= RANK_TOLERANCE * s[first] {
        return None;
    }
    // v_i v_i^T as a p x p matrix.
    let outer = |i: usize| {
        let v = v_t.row(i).transpose();
        &v * v.transpose()
    };
    Some(match criterion {
        CalibrationCriterion::O3 => (1.0 / s[last], outer(last) * (-1.0 / s[last].powi(2))),
        CalibrationCriterion::O4 => (
            s[first] / s[last].powi(2),
            outer(last) * (-2.0 / s[last].powi(2)) + outer(first) * (1.0 / s[first].powi(2)),
        ),
        _ => {
            let sum: f64 = s.iter().map(|v| 1.0 / v).sum();
            let mut w = DMatrix::zeros(p, p);
            for i in 0..p {
                w += outer(i) * (1.0 / s[i].powi(3));
            }
            (sum, w * (-1.0 / sum))
        }
    })
}
