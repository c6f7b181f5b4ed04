//! Standard errors and 95% confidence intervals of an identification (the statistics of the
//! [`crate`] module docs), and the Student's t quantile they use, memoised per thread.

use nalgebra::{Matrix6, Vector6};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::cell::Cell;

/// Standard errors and 95% confidence intervals of an identification (see the [`crate`] module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Uncertainty {
    /// Degrees of freedom `m - 6` (robust mode: rows of non-zero weight minus 6).
    pub dof: usize,
    /// The variance the intervals use, m^2: `s^2`, the residual variance of one coordinate (or,
    /// in [`super::Adequacy::from_noise`], the setup's tracker noise variance).
    pub residual_variance: f64,
    /// The quantile of the 95% intervals: of Student's t with `dof` degrees of freedom, or of the
    /// normal distribution for a known variance.
    pub t_quantile: f64,
    /// `s^2 (Psi^T Psi)^-1`, (rad/Nm)^2.
    pub compliance_covariance: Matrix6<f64>,
    /// `se(h_j)`, rad/Nm.
    pub compliance_std_error: Vector6<f64>,
    /// `[h_j - t se(h_j), h_j + t se(h_j)]`, rad/Nm.
    pub compliance_ci95: [[f64; 2]; 6],
    /// `se(k_j) = se(h_j) / h_j^2` (delta method), Nm/rad.
    pub stiffness_std_error: Vector6<f64>,
    /// `[k_j - t se(k_j), k_j + t se(k_j)]` (delta method), Nm/rad.
    pub stiffness_ci95: [[f64; 2]; 6],
    /// The positive stiffness values whose compliance lies in the compliance interval:
    /// `[1/h_upper, 1/h_lower]`, the upper end `+inf` when `h_lower <= 0` (both `+inf`, an empty
    /// interval, when even `h_upper <= 0`), Nm/rad.
    pub stiffness_ci95_from_compliance: [[f64; 2]; 6],
}

impl Uncertainty {
    /// The uncertainty of compliance `h` given `Cov(h) / s^2` (`unit_covariance`), `s^2` and the
    /// degrees of freedom; `None` for zero degrees of freedom.
    pub(crate) fn new(
        h: &Vector6<f64>,
        unit_covariance: &Matrix6<f64>,
        residual_variance: f64,
        dof: usize,
    ) -> Option<Self> {
        Some(Self::with_quantile(
            h,
            unit_covariance,
            residual_variance,
            dof,
            t975(dof)?,
        ))
    }

    /// As [`Uncertainty::new`] with a given quantile of the 95% intervals (e.g. 1.96 for a known
    /// variance).
    pub(crate) fn with_quantile(
        h: &Vector6<f64>,
        unit_covariance: &Matrix6<f64>,
        residual_variance: f64,
        dof: usize,
        t_quantile: f64,
    ) -> Self {
        let compliance_covariance = unit_covariance * residual_variance;
        let se = compliance_covariance.diagonal().map(f64::sqrt);
        let k = h.map(|v| 1.0 / v);
        let se_k = se.component_div(&h.component_mul(h));
        let interval = |c: f64, s: f64| [c - t_quantile * s, c + t_quantile * s];
        let compliance_ci95: [[f64; 2]; 6] = std::array::from_fn(|j| interval(h[j], se[j]));
        Self {
            dof,
            residual_variance,
            t_quantile,
            compliance_covariance,
            compliance_std_error: se,
            compliance_ci95,
            stiffness_std_error: se_k,
            stiffness_ci95: std::array::from_fn(|j| interval(k[j], se_k[j])),
            stiffness_ci95_from_compliance: compliance_ci95.map(invert),
        }
    }
}

thread_local! {
    /// The last `(dof, t_{0.975, dof})` of this thread: the quantile costs microseconds, and
    /// repeated identifications (Monte Carlo runs, robust iterations) share their degrees of freedom.
    static LAST_T975: Cell<(usize, f64)> = const { Cell::new((0, f64::NAN)) };
}

/// The 0.975 quantile of Student's t with `dof` degrees of freedom (statrs), memoised per thread.
fn t975(dof: usize) -> Option<f64> {
    let (last, t) = LAST_T975.get();
    if last == dof && dof > 0 {
        return Some(t);
    }
    let t = StudentsT::new(0.0, 1.0, dof as f64)
        .ok()?
        .inverse_cdf(0.975);
    LAST_T975.set((dof, t));
    Some(t)
}

fn invert([lower, upper]: [f64; 2]) -> [f64; 2] {
    match (lower > 0.0, upper > 0.0) {
        (true, _) => [1.0 / upper, 1.0 / lower],
        (false, true) => [1.0 / upper, f64::INFINITY],
        (false, false) => [f64::INFINITY, f64::INFINITY],
    }
}
