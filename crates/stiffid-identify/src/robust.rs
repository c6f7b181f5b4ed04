//! Robust identification: iteratively reweighted least squares (IRLS) with Huber or Tukey weights.
//!
//! A laser tracker that loses its target, or a rope that slips, gives a few coordinates far off the
//! model. Least squares spreads such an outlier over all compliances; IRLS down-weights it.
//!
//! Each iteration, from the current compliance `h`:
//! 1. residuals `r = delta - Psi h`;
//! 2. scale `s = 1.4826 * median(|r_i|)` ([`MAD_TO_SIGMA`]: the median absolute residual, about
//!    zero, as an estimate of the noise standard deviation that is consistent for Gaussian errors
//!    and insensitive to up to half the rows being outliers);
//! 3. weights `w_i = w(r_i / s)` of the [`Loss`];
//! 4. `h` = the least-squares solution of the rows scaled by `sqrt(w_i)` (`sqrt(w) Psi h = sqrt(w)
//!    delta`), by QR as always.
//!
//! It stops when no compliance changes by more than [`TOLERANCE`] relative to the largest, or after
//! [`MAX_ITERATIONS`]. Huber starts from the least-squares fit; Tukey, whose weights can reach zero
//! and whose objective is not convex, starts from the converged Huber fit (the usual practice, e.g.
//! Holland & Welsch 1977; statsmodels RLM).
//!
//! Tuning constants (Huber 1.345, Tukey 4.685) give 95% of the efficiency of least squares when
//! the errors are Gaussian (Holland & Welsch 1977).

use nalgebra::{DMatrix, DVector};
use stiffid_core::common::stop::Stop;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::Result;

/// `1 / Phi^-1(3/4)`: turns the median absolute deviation of Gaussian errors into their standard
/// deviation.
pub const MAD_TO_SIGMA: f64 = 1.482_602_218_505_602;

/// Rows with a final weight below this count as down-weighted: a residual beyond about 2.6 scale
/// units for both losses (Huber `2c = 2.69`, Tukey `0.541c = 2.53`). Tukey gives every non-zero
/// residual some weight below 1, so "below 1" would list every row.
pub const DOWN_WEIGHTED: f64 = 0.5;

/// Iteration limit.
pub const MAX_ITERATIONS: usize = 100;

/// Convergence: largest change of a compliance, relative to the largest compliance.
pub const TOLERANCE: f64 = 1e-10;

/// The weight function of IRLS.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Loss {
    /// Huber: `w(u) = 1` for `|u| <= c`, `c / |u|` beyond; `c = 1.345`. Never zero: an outlier keeps
    /// a small say.
    Huber,
    /// Tukey's biweight: `w(u) = (1 - (u/c)^2)^2` for `|u| < c`, 0 beyond; `c = 4.685`. Rejects far
    /// outliers entirely.
    Tukey,
}

impl Loss {
    /// The tuning constant `c`, in units of the scale `s`.
    pub const fn tuning_constant(self) -> f64 {
        match self {
            Loss::Huber => 1.345,
            Loss::Tukey => 4.685,
        }
    }

    /// The weight `w(u)` of a residual `u` in units of the scale, in `[0, 1]`.
    pub fn weight(self, u: f64) -> f64 {
        let c = self.tuning_constant();
        match self {
            Loss::Huber if u.abs() <= c => 1.0,
            Loss::Huber => c / u.abs(),
            Loss::Tukey if u.abs() < c => (1.0 - (u / c).powi(2)).powi(2),
            Loss::Tukey => 0.0,
        }
    }

    /// Lower-case name: `huber` or `tukey`.
    pub const fn name(self) -> &'static str {
        match self {
            Loss::Huber => "huber",
            Loss::Tukey => "tukey",
        }
    }
}

impl stiffid_core::common::choice::Choice for Loss {
    const FIELD: &'static str = "robust";
    const ALL: &'static [Self] = &[Loss::Huber, Loss::Tukey];
    fn name(self) -> &'static str {
        Loss::name(self)
    }
    fn help(self) -> &'static str {
        match self {
            Loss::Huber => "Huber weights (c = 1.345 MAD scales): outliers keep a small weight",
            Loss::Tukey => "Tukey's biweight (c = 4.685 MAD scales): far outliers get weight 0",
        }
    }
}

stiffid_core::common::choice::by_name!(Loss);

/// What the robust fit did.
#[derive(Debug, Clone, PartialEq)]
pub struct RobustFit {
    /// The weight function.
    pub loss: Loss,
    /// The final scale `s`, m.
    pub scale: f64,
    /// IRLS iterations taken with `loss` (after the Huber start, for Tukey).
    pub iterations: usize,
    /// Why the iterations stopped: [`Stop::Converged`], no compliance changed by more than
    /// [`TOLERANCE`] relative to the largest; or [`Stop::IterationLimit`], [`MAX_ITERATIONS`]
    /// reached with a compliance still changing (the weights and the compliances may still
    /// move).
    pub stop: Stop,
    /// The final weight of every row of `Psi`, in `[0, 1]`.
    pub weights: DVector<f64>,
}

impl RobustFit {
    /// Whether the iterations met [`TOLERANCE`] before [`MAX_ITERATIONS`].
    pub fn converged(&self) -> bool {
        self.stop == Stop::Converged
    }

    /// A warning ([`WarningKind::NotConverged`]) when the reweighting stopped at its iteration
    /// limit: the stiffness comes from weights that were still changing.
    pub fn warning(&self) -> Option<Warning> {
        (!self.converged()).then(|| {
            Warning::new(
                WarningKind::NotConverged,
                format!(
                    "the {} reweighting stopped at its limit of {} iterations with the compliances still changing: the weights and the stiffness may still move; look at the down-weighted rows, or fit without a robust loss",
                    self.loss.name(),
                    self.iterations
                ),
            )
        })
    }

    /// The rows (indices into `Psi`) with weight below [`DOWN_WEIGHTED`], lowest weight first.
    pub fn down_weighted(&self) -> Vec<usize> {
        let mut rows: Vec<usize> = (0..self.weights.len())
            .filter(|&i| self.weights[i] < DOWN_WEIGHTED)
            .collect();
        rows.sort_by(|&a, &b| self.weights[a].total_cmp(&self.weights[b]));
        rows
    }
}

/// Runs IRLS with `loss` from the least-squares solution `start` (any number of parameters),
/// each step solved by `solve(sqrt(w) Psi, sqrt(w) delta)`, which returns the solution and its
/// factor (a QR [`stiffid_core::math::lsq::Factor`] for the six drives, the column-scaled SVD for a model).
/// Returns the compliance, the factor of the last weighted observation matrix (for its
/// covariance) and the fit.
///
/// # Errors
/// Those of `solve`, e.g. [`stiffid_core::Error::Unidentifiable`] if the rows left with weight make
/// `Psi` rank deficient.
pub(crate) fn fit<S>(
    psi: &DMatrix<f64>,
    delta: &DVector<f64>,
    start: DVector<f64>,
    loss: Loss,
    solve: &impl Fn(DMatrix<f64>, &DVector<f64>) -> Result<(DVector<f64>, S)>,
) -> Result<(DVector<f64>, S, RobustFit)> {
    let start = match loss {
        Loss::Huber => start,
        Loss::Tukey => iterate(psi, delta, start, Loss::Huber, solve, MAX_ITERATIONS)?.0,
    };
    iterate(psi, delta, start, loss, solve, MAX_ITERATIONS)
}

/// IRLS with `loss` from `h`, at most `limit` iterations.
fn iterate<S>(
    psi: &DMatrix<f64>,
    delta: &DVector<f64>,
    mut h: DVector<f64>,
    loss: Loss,
    solve: &impl Fn(DMatrix<f64>, &DVector<f64>) -> Result<(DVector<f64>, S)>,
    limit: usize,
) -> Result<(DVector<f64>, S, RobustFit)> {
    let mut iterations = 0;
    loop {
        iterations += 1;
        let residuals = delta - psi * &h;
        let scale = mad_scale(&residuals, delta.amax());
        let weights = residuals.map(|r| loss.weight(r / scale));
        let roots = weights.map(f64::sqrt);
        let mut weighted = psi.clone();
        for (mut row, w) in weighted.row_iter_mut().zip(roots.iter()) {
            row *= *w;
        }
        let (next, factor) = solve(weighted, &delta.component_mul(&roots))?;
        let change = (&next - &h).amax();
        h = next;
        let stop = match change <= TOLERANCE * h.amax() {
            true => Some(Stop::Converged),
            false => (iterations >= limit).then_some(Stop::IterationLimit),
        };
        if let Some(stop) = stop {
            let fit = RobustFit {
                loss,
                scale,
                iterations,
                stop,
                weights,
            };
            return Ok((h, factor, fit));
        }
    }
}

/// `MAD_TO_SIGMA * median(|r|)`, floored at a tiny fraction of the data's size so that an exact
/// fit of most rows (noise-free data) does not divide by zero.
fn mad_scale(residuals: &DVector<f64>, size: f64) -> f64 {
    let mut abs: Vec<f64> = residuals.iter().map(|r| r.abs()).collect();
    abs.sort_by(f64::total_cmp);
    let n = abs.len();
    let median = match n % 2 {
        1 => abs[n / 2],
        _ => 0.5 * (abs[n / 2 - 1] + abs[n / 2]),
    };
    (MAD_TO_SIGMA * median)
        .max(f64::EPSILON * size)
        .max(f64::MIN_POSITIVE)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mad_scale_is_the_median_absolute_residual_times_the_gaussian_factor() {
        // |r| sorted: 0.5 1 2 3 100 -> median 2 (odd count, the outlier does not move it).
        let odd = DVector::from_vec(vec![-1.0, 3.0, 0.5, -100.0, 2.0]);
        assert_eq!(mad_scale(&odd, 100.0), MAD_TO_SIGMA * 2.0);
        // Even count: the mean of the middle two, 1 and 2.
        let even = DVector::from_vec(vec![2.0, -1.0, 0.5, 4.0]);
        assert_eq!(mad_scale(&even, 4.0), MAD_TO_SIGMA * 1.5);
        // 1.4826 is 1 / Phi^-1(3/4): the MAD of N(0, 1) is 0.6744897501960817.
        assert!((MAD_TO_SIGMA * 0.674_489_750_196_081_7 - 1.0).abs() < 1e-15);
    }

    /// A line `y = a x` through 20 points with two outliers: by plain least squares per step.
    fn line_with_outliers() -> (DMatrix<f64>, DVector<f64>) {
        let x = DMatrix::from_fn(20, 1, |i, _| 1.0 + i as f64);
        let noise = |i: usize| 1e-3 * ((i * 7919) % 13) as f64 - 6e-3;
        let mut y = DVector::from_fn(20, |i, _| 2.0 * x[(i, 0)] + noise(i));
        y[3] += 5.0;
        y[11] -= 8.0;
        (x, y)
    }

    fn solve(a: DMatrix<f64>, b: &DVector<f64>) -> Result<(DVector<f64>, ())> {
        let qr = a.clone().qr();
        let h = qr
            .r()
            .solve_upper_triangular(&(qr.q().transpose() * b))
            .unwrap();
        Ok((h, ()))
    }

    #[test]
    fn the_reweighting_says_why_it_stopped_and_warns_at_its_iteration_limit() {
        let (x, y) = line_with_outliers();
        let start = solve(x.clone(), &y).unwrap().0;
        for loss in [Loss::Huber, Loss::Tukey] {
            // Forced to stop after one step, the compliance is still moving.
            let (h1, _, cut) = iterate(&x, &y, start.clone(), loss, &solve, 1).unwrap();
            assert_eq!((cut.stop, cut.iterations), (Stop::IterationLimit, 1));
            assert!(!cut.converged());
            let warning = cut.warning().unwrap();
            assert_eq!(warning.kind, WarningKind::NotConverged);
            assert!(
                warning
                    .message
                    .contains("stopped at its limit of 1 iterations"),
                "{}",
                warning.message
            );
            // Left to converge, it meets the tolerance, near the slope 2, and does not warn.
            let (h, _, done) = fit(&x, &y, start.clone(), loss, &solve).unwrap();
            assert_eq!(done.stop, Stop::Converged);
            assert!(done.iterations > 1 && done.iterations < MAX_ITERATIONS);
            assert_eq!(done.warning(), None);
            assert!((h[0] - 2.0).abs() < 1e-3, "{}", h[0]);
            assert!((h1[0] - h[0]).abs() > TOLERANCE * h[0].abs());
        }
    }

    #[test]
    fn mad_scale_of_an_exact_fit_is_floored_above_zero() {
        let exact = DVector::from_vec(vec![0.0, 0.0, 0.0, 1e-3]);
        assert_eq!(mad_scale(&exact, 2.0), f64::EPSILON * 2.0);
        assert_eq!(mad_scale(&DVector::zeros(3), 0.0), f64::MIN_POSITIVE);
    }
}
