//! A calibration criterion as a search minimises it, and its gradient with respect to the
//! design Jacobian.
//!
//! The search minimises the logarithm of a smaller-is-better value ([`CalibrationCriterion::loss`]):
//! the reciprocal of an observability index, the predicted RMS error itself. O1, D-optimality
//! and the predicted error (the default) are scored from the information matrix
//! `J_s^T J_s = R^T R` (one matrix product; the Cholesky factor `R` equals the QR's up to the
//! signs of its rows, which no criterion sees) and its inverse `C = (J_s^T J_s)^-1`: `ln det`
//! terms read `R`'s diagonal, the predicted error is `sigma sqrt(tr(H C) / m_0)` with
//! `H = A_0^T A_0 = R_A^T R_A` (`A_0 = Q_A R_A` factored once). The Cholesky factor loses about
//! `cond(J_s)^2 eps` relative where a QR of `J_s` loses `cond(J_s) eps`: a search ranks groups as
//! well (a group with `cond(J_s)` beyond about `1e8` scores as not separating the parameters),
//! reports re-evaluate the criteria by the SVD of `J_s` ([`super::criteria`]), and it costs a
//! third of a Householder QR with its products in the matrix-product kernel. The indices that
//! need singular values (O3, O4, O5) take them from the SVD of the `p x p` `R` of the
//! Householder QR of `J_s` (the same as `J_s`'s: the smallest one is what they read, so it is
//! kept as accurate as `J_s` allows). The gradient of `ln loss` with respect to `J_s` is `J_s W`
//! with `W` symmetric (`p x p`):
//!
//! ```text
//! O1:         W = -(1/p) C                         (d ln det = <J (J^T J)^-1, dJ>)
//! D:          W = -(2/p) C
//! test-pose:  W = -C H C / tr(H C)
//! O3:         W = -v_p v_p^T / s_p^2               (d s_i = u_i^T dJ v_i, u_i = J v_i / s_i)
//! O4:         W = -2 v_p v_p^T / s_p^2 + v_1 v_1^T / s_1^2
//! O5:         W = -(sum_i v_i v_i^T / s_i^3) / (sum_i 1 / s_i)
//! ```

use super::{CalibrationDesign, RANK_TOLERANCE};
use nalgebra::{DMatrix, DMatrixView};
use stiffid_core::math::linalg::CappedSvd;

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
    pub(crate) const ALL: [CalibrationCriterion; 6] = [
        CalibrationCriterion::O1,
        CalibrationCriterion::O3,
        CalibrationCriterion::O4,
        CalibrationCriterion::O5,
        CalibrationCriterion::DOptimality,
        CalibrationCriterion::TestPose,
    ];

    /// The value a search minimises for the criteria `c`: the reciprocal of an index (1/m, or
    /// 1/m^2 for D-optimality), the predicted RMS error (m).
    #[cfg(test)]
    pub(crate) fn loss(self, c: &super::CalibrationCriteria) -> f64 {
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

impl stiffid_core::common::choice::Choice for CalibrationCriterion {
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

stiffid_core::common::choice::by_name!(CalibrationCriterion);

impl CalibrationCriterion {
    /// Whether the criterion reads singular values (O3, O4, O5), not the information matrix.
    pub(super) fn spectral(self) -> bool {
        matches!(
            self,
            CalibrationCriterion::O3 | CalibrationCriterion::O4 | CalibrationCriterion::O5
        )
    }
}

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
    /// The scaled Jacobian of the group (without a campaign's fixed rows).
    pub(super) j: DMatrix<f64>,
    /// What `W` (module docs) is made of.
    weight: Weight,
}

/// `W` of the module docs, formed only for a gradient.
enum Weight {
    /// `c C`.
    Covariance(DMatrix<f64>, f64),
    /// `-C H C / t`.
    Test(DMatrix<f64>, f64),
    /// Formed already (the spectral indices).
    Formed(DMatrix<f64>),
}

impl Scored {
    /// The score of the scaled Jacobian `j` of a group, after the design's fixed postures (their
    /// information added, [`CalibrationDesign::on_station`]); `None` for a group that does not
    /// separate the kept parameters (fewer rows than columns, an information matrix that is
    /// not positive definite, a pivot of `R` below [`RANK_TOLERANCE`] of the largest, a
    /// singular value below it for the spectral indices) or a non-finite value. On a reduced
    /// design (`station`), `j` holds the arm's columns and the counts are the whole design's.
    pub(super) fn new(
        j: DMatrix<f64>,
        criterion: CalibrationCriterion,
        design: &CalibrationDesign,
    ) -> Option<Self> {
        let p = j.ncols() + design.schur.eliminated;
        let rows = j.nrows() + design.fixed.nrows();
        if rows < p || p == 0 || !j.iter().all(|v| v.is_finite()) {
            return None;
        }
        let n = rows / design.layout.rows(1);
        let (value, weight) = match criterion.spectral() {
            false => from_information(&j, n, criterion, design)?,
            true => {
                // The spectral indices need the SVD anyway: of the QR's `R`, as accurate as
                // `J_s` allows.
                let r = triangular_factor(&design.with_fixed(j.clone()));
                let diagonal = r.diagonal().map(f64::abs);
                if diagonal.min() <= RANK_TOLERANCE * diagonal.max() {
                    return None;
                }
                let (value, w) = spectral(&r, criterion)?;
                (value, Weight::Formed(w))
            }
        };
        (value.is_finite() && value > 0.0).then_some(Scored { value, j, weight })
    }

    /// The gradient of `ln value` with respect to the scaled Jacobian: `J_s W`, with the
    /// `p x p` `W` formed first (one product with the tall `J_s`).
    pub(super) fn log_gradient(&self, design: &CalibrationDesign) -> DMatrix<f64> {
        let w = match &self.weight {
            Weight::Covariance(c, factor) => c * *factor,
            Weight::Test(c, trace) => c * (&design.test_information * c) * (-1.0 / trace),
            Weight::Formed(w) => return &self.j * w,
        };
        &self.j * w
    }
}

/// The value and `W` of O1, D-optimality or the test-pose criterion of the scaled Jacobian `j`
/// of `n` postures, from the information matrix (module docs); `None` when it is not positive
/// definite or a pivot is below [`RANK_TOLERANCE`] of the largest. On a reduced design
/// (`station`), the eliminated block's pivots, log-determinant and trace join `A`'s.
fn from_information(
    j: &DMatrix<f64>,
    n: usize,
    criterion: CalibrationCriterion,
    design: &CalibrationDesign,
) -> Option<(f64, Weight)> {
    // J^T J by the matrix-product kernel, J^T as a view of J's columns (no copy).
    let (m, arm) = j.shape();
    let transposed = DMatrixView::from_slice_with_strides(j.as_slice(), arm, m, m, 1);
    let mut information = design.fixed_information.clone();
    information.gemm(1.0, &transposed, j, 1.0);
    from_factor(information.cholesky()?.unpack(), n, criterion, design)
}

/// The loss of `criterion` ([`CalibrationCriterion::loss`]) for the whole information matrix
/// `information` (`p x p`, scaled, the kept parameters; the fixed rows' included) of `n`
/// postures' worth of rows, on a design that is not reduced; `+infinity` when it is not
/// positive definite or a pivot (a singular value, for the spectral indices) is below
/// [`RANK_TOLERANCE`] of the largest.
pub(super) fn information_loss(
    information: DMatrix<f64>,
    n: usize,
    criterion: CalibrationCriterion,
    design: &CalibrationDesign,
) -> f64 {
    let value = information.cholesky().and_then(|c| {
        let l = c.unpack();
        match criterion.spectral() {
            true => spectral(&l.transpose(), criterion).map(|(v, _)| v),
            false => from_factor(l, n, criterion, design).map(|(v, _)| v),
        }
    });
    value
        .filter(|v| v.is_finite() && *v > 0.0)
        .unwrap_or(f64::INFINITY)
}

/// [`from_information`] from the Cholesky factor `l` of the information matrix.
fn from_factor(
    l: DMatrix<f64>,
    n: usize,
    criterion: CalibrationCriterion,
    design: &CalibrationDesign,
) -> Option<(f64, Weight)> {
    let schur = &design.schur;
    let p = l.ncols() + schur.eliminated;
    let diagonal = l.diagonal();
    let (low, high) = match schur.eliminated {
        0 => (diagonal.min(), diagonal.max()),
        _ => (
            diagonal.min().min(schur.pivots.0),
            diagonal.max().max(schur.pivots.1),
        ),
    };
    if low <= RANK_TOLERANCE * high {
        return None;
    }
    let inverse = lower_inverse(&l);
    let c = inverse.transpose() * inverse;
    let mean_log = (diagonal.iter().map(|d| d.ln()).sum::<f64>() + schur.log_pivots) / p as f64;
    Some(match criterion {
        CalibrationCriterion::O1 => (
            (n as f64).sqrt() * (-mean_log).exp(),
            Weight::Covariance(c, -1.0 / p as f64),
        ),
        CalibrationCriterion::DOptimality => (
            (-2.0 * mean_log).exp(),
            Weight::Covariance(c, -2.0 / p as f64),
        ),
        _ => {
            let trace = c.component_mul(&design.test_information).sum() + schur.trace;
            let m0 = (design.test.nrows() / 3).max(1) as f64;
            let value = design.noise * (trace.max(0.0) / m0).sqrt();
            (value, Weight::Test(c, trace))
        }
    })
}

/// The inverse of the lower triangular `l` (`p x p`, nonzero diagonal) by forward substitution,
/// column by column in column sweeps (contiguous updates).
fn lower_inverse(l: &DMatrix<f64>) -> DMatrix<f64> {
    let p = l.ncols();
    let mut x = DMatrix::zeros(p, p);
    let l = l.as_slice();
    for (j, col) in x.as_mut_slice().chunks_exact_mut(p).enumerate() {
        col[j] = 1.0;
        for i in j..p {
            col[i] /= l[i * p + i];
            let xi = col[i];
            let (below, source) = (&mut col[i + 1..], &l[i * p + i + 1..(i + 1) * p]);
            below.iter_mut().zip(source).for_each(|(y, v)| *y -= xi * v);
        }
    }
    x
}

/// The value and `W` of an index that needs the singular values, from the SVD of `r`.
fn spectral(r: &DMatrix<f64>, criterion: CalibrationCriterion) -> Option<(f64, DMatrix<f64>)> {
    let p = r.ncols();
    let svd = r.clone().capped_svd(false, true)?;
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
