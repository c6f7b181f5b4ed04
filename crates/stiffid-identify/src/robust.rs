//! Robust identification: iteratively reweighted least squares (IRLS) with Huber or Tukey weights.
//!
//! A laser tracker that loses its target, or a rope that slips, gives a few coordinates far off the
//! model. Least squares spreads such an outlier over all compliances; IRLS down-weights it.
//!
//! Each iteration, from the current compliance `h`:
//! 1. residuals `r = delta - Psi h`;
//! 2. scale `s = 1.4826 * median(|r_i|)` (`MAD_TO_SIGMA`: the median absolute residual, about
//!    zero, as an estimate of the noise standard deviation that is consistent for Gaussian errors
//!    and insensitive to up to half the rows being outliers);
//! 3. weights `w_i = w(r_i / s)` of the [`Loss`];
//! 4. `h` = the least-squares solution of the rows scaled by `sqrt(w_i)` (`sqrt(w) Psi h = sqrt(w)
//!    delta`), by QR as always.
//!
//! It stops when no compliance changes by more than `TOLERANCE` relative to the largest, or after
//! `MAX_ITERATIONS`. Huber starts from the least-squares fit; Tukey, whose weights can reach zero
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
pub(crate) const MAD_TO_SIGMA: f64 = 1.482_602_218_505_602;

/// Rows with a final weight below this count as down-weighted: a residual beyond about 2.6 scale
/// units for both losses (Huber `2c = 2.69`, Tukey `0.541c = 2.53`). Tukey gives every non-zero
/// residual some weight below 1, so "below 1" would list every row.
pub const DOWN_WEIGHTED: f64 = 0.5;

/// Iteration limit.
pub(crate) const MAX_ITERATIONS: usize = 100;

/// Convergence: largest change of a compliance, relative to the largest compliance.
pub(crate) const TOLERANCE: f64 = 1e-10;

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
    pub(crate) fn weight(self, u: f64) -> f64 {
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
    /// `TOLERANCE` relative to the largest; or [`Stop::IterationLimit`], `MAX_ITERATIONS`
    /// reached with a compliance still changing (the weights and the compliances may still
    /// move).
    pub stop: Stop,
    /// The final weight of every row of `Psi`, in `[0, 1]`.
    pub weights: DVector<f64>,
}

impl RobustFit {
    /// Whether the iterations met `TOLERANCE` before `MAX_ITERATIONS`.
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

/// IRLS with `loss` from the compliance `h` (one entry per column of `psi`), at most `limit`
/// iterations: [`fit`]'s loop, one weighted solve by `solve` per iteration. Returns as [`fit`];
/// a fit cut at `limit` has [`Stop::IterationLimit`] and [`RobustFit::warning`] says so.
///
/// # Errors
/// Those of `solve`.
pub(crate) fn iterate<S>(
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

/// The robust scale of `residuals` (their unit, e.g. m): `MAD_TO_SIGMA * median(|r|)` (the mean
/// of the middle two for an even count), floored at `f64::EPSILON * size` (`size` the data's
/// largest magnitude, same unit) and at `f64::MIN_POSITIVE`, so that an exact fit of most rows
/// (noise-free data) does not divide by zero. `residuals` is not empty.
pub(crate) fn mad_scale(residuals: &DVector<f64>, size: f64) -> f64 {
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
