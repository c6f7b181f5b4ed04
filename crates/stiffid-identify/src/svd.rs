//! Identification of a model with any number of parameters ([`stiffid_core::model`]: the six drives and
//! virtual springs), with its identifiability, uncertainty and leave-one-posture-out error.
//!
//! `Psi` (`m x n`, one column per parameter, [`Observations::from_measurements`]) is scaled by its
//! column norms, `S = diag(1 / |psi_j|)`, so that `Psi S` is free of the parameters' units, and
//! factored by the SVD `Psi S = U diag(s) V^T` (nalgebra, after a check for non-finite entries).
//!
//! ## Identifiability
//! The scaled rank `r` counts the singular values above `RANK_TOLERANCE` times the largest; the
//! scaled condition number is `s_1 / s_n`. Each right singular vector `v` of a singular value at
//! or below the tolerance is a combination `sum_j (S v)_j h_j` of compliances that the data cannot
//! see: the data cannot separate the parameters with a visible share in it (more than
//! `SHARE` of the unit vector `v`). Such parameters get no interval; every other compliance is
//! an estimable function (orthogonal to the null space) with the usual interval.
//!
//! ## Fit and uncertainty
//! `h = S V diag(1/s) U^T delta` over the `r` identifiable directions (the minimum-norm solution
//! in scaled units when `r < n`). With `dof = m - r` and `s^2 = |delta - Psi h|^2 / dof`,
//! `Cov(h) = s^2 S V diag(1/s^2) V^T S`; the 95% interval of a compliance is `h_j +- t se_j`
//! (Student's t, `dof`), that of its stiffness `[1/h_upper, 1/h_lower]` (as
//! [`crate::Uncertainty::stiffness_ci95_from_compliance`]).
//!
//! ## Held out
//! Leaving posture i out and refitting predicts its rows with the residual
//! `e_i = (I - H_ii)^-1 r_i`, `r_i` its full-fit residuals and `H_ii = U_i U_i^T` its diagonal
//! block of the hat matrix (`U_i` its rows of the first `r` columns of U): exact, one factorisation
//! for all folds (the block form of the PRESS residual; Belsley, Kuh, Welsch, "Regression
//! Diagnostics", 1980, ch. 2). `delta_b` is the norm of each measurement's three residuals
//! (Eq. 22); the explained share is `1 - RMS(delta_b) / RMS(|delta|)`.

use super::robust::{self, Loss, RobustFit};
use super::{explained_share, Method};
use nalgebra::{DMatrix, DVector};
use statrs::distribution::{ChiSquared, ContinuousCDF, StudentsT};
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::model::Parameter;
use stiffid_core::observation::Observations;
use stiffid_core::{Error, Result};

/// Relative singular value of the column-scaled `Psi` at or below which a direction is not
/// identified.
pub(crate) const RANK_TOLERANCE: f64 = 1e-8;

/// The share of a null vector from which a parameter is named in an unidentifiable combination.
pub(crate) const SHARE: f64 = 0.05;

/// A combination of compliances the data cannot see (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Combination {
    /// `(parameter index, coefficient)` of the parameters with a visible share, coefficients of
    /// the unit null vector `v` of the scaled problem, largest first.
    pub terms: Vec<(usize, f64)>,
}

impl Combination {
    /// The combination written with the parameters' names, e.g. `0.71 k6 - 0.71 tool_rz`.
    pub fn describe(&self, parameters: &[Parameter]) -> String {
        let mut s = String::new();
        for (i, (j, c)) in self.terms.iter().enumerate() {
            let sign = match (i, *c < 0.0) {
                (0, true) => "-",
                (0, false) => "",
                (_, true) => " - ",
                (_, false) => " + ",
            };
            s += &format!("{sign}{:.2} {}", c.abs(), parameters[*j].name);
        }
        s
    }
}

/// What the data identify (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Identifiability {
    /// The rank of the column-scaled `Psi`.
    pub rank: usize,
    /// Its condition number `s_1 / s_n` (`+inf` when rank deficient).
    pub scaled_cond: f64,
    /// The combinations the data cannot see, one per missing rank.
    pub unidentifiable: Vec<Combination>,
    /// Per parameter: whether it appears in no unidentifiable combination.
    pub identified: Vec<bool>,
}

/// The 95% interval of one identified parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// `se(h_j)`, rad/Nm or m/N.
    pub compliance_std_error: f64,
    /// `h_j +- t se(h_j)`.
    pub compliance_ci95: [f64; 2],
    /// `[1/h_upper, 1/h_lower]`, SI (`+inf` above when the compliance interval reaches 0).
    pub stiffness_ci95: [f64; 2],
}

/// An identification of a model's parameters (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// The parameters, drives first.
    pub parameters: Vec<Parameter>,
    /// `h`, rad/Nm or m/N per parameter.
    pub compliance: DVector<f64>,
    /// `1/h`, Nm/rad or N/m (SI).
    pub stiffness: DVector<f64>,
    /// The 95% interval of each identified parameter; `None` for an unidentifiable one or
    /// without degrees of freedom.
    pub intervals: Vec<Option<Interval>>,
    /// What the data identify.
    pub identifiability: Identifiability,
    /// `Cov(h) = s^2 S V diag(1/s^2) V^T S` over the identifiable directions (n x n, SI; for a
    /// bounded fit, that of the free compliances with the others' rows and columns zero); `None`
    /// without degrees of freedom.
    pub covariance: Option<DMatrix<f64>>,
    /// `delta - Psi h`, m, rows in the order of [`stiffid_core::observation`].
    pub residuals: DVector<f64>,
    /// `Psi h`, the displacement the fit predicts, m, rows in the order of `residuals`.
    pub predicted: DVector<f64>,
    /// `|delta - Psi h|^2`, m^2.
    pub rss: f64,
    /// Rows of `Psi`.
    pub rows: usize,
    /// Distinct postures.
    pub postures: usize,
    /// `m - r`, r the scaled rank.
    pub dof: usize,
    /// Which compliances are held at 0, for a bounded fit (`fit_nonnegative`).
    pub active_bounds: Option<Vec<bool>>,
    /// Why the bounded fit's active-set steps stopped (`fit_nonnegative`; converged when the
    /// least-squares fit is already non-negative); `None` for another fit.
    pub nonnegative_stop: Option<stiffid_core::common::stop::Stop>,
    /// The iteratively reweighted fit, for a robust fit (`fit_robust`).
    pub robust: Option<RobustFit>,
}

impl Fit {
    /// `sqrt(|r|^2 / m)`, m.
    pub(crate) fn residual_rms(&self) -> f64 {
        (self.rss / self.rows as f64).sqrt()
    }

    /// `s / sigma`: the residual standard deviation in units of the tracker noise
    /// (`noise_variance`, m^2); `None` without degrees of freedom.
    pub fn noise_ratio(&self, noise_variance: f64) -> Option<f64> {
        (self.dof > 0).then(|| (self.rss / self.dof as f64 / noise_variance).sqrt())
    }

    /// The upper-tail p-value of `rss / sigma^2` under chi-square with `dof` degrees of freedom
    /// (the model check of [`crate::adequacy`]).
    pub fn adequacy_p_value(&self, noise_variance: f64) -> Option<f64> {
        let chi = ChiSquared::new(self.dof as f64).ok()?;
        Some(chi.sf(self.rss / noise_variance))
    }

    /// The model check's verdict against the tracker noise (`noise_variance`, m^2, one row's
    /// coordinate); `None` without degrees of freedom.
    pub fn verdict(&self, noise_variance: f64) -> Option<crate::adequacy::Verdict> {
        crate::adequacy::Verdict::of(self.rss / noise_variance, self.dof)
    }

    /// Akaike's information criterion of the Gaussian fit, `m ln(rss / m) + 2 r`.
    pub(crate) fn aic(&self) -> f64 {
        let m = self.rows as f64;
        m * (self.rss / m).ln() + 2.0 * self.identifiability.rank as f64
    }

    /// The Bayesian information criterion, `m ln(rss / m) + r ln m`.
    pub(crate) fn bic(&self) -> f64 {
        let m = self.rows as f64;
        m * (self.rss / m).ln() + self.identifiability.rank as f64 * m.ln()
    }

    /// Whether every compliance is finite and positive (every stiffness physical).
    pub fn physical(&self) -> bool {
        self.compliance.iter().all(|h| h.is_finite() && *h > 0.0)
    }
}

/// The column-scaled SVD of `Psi` and what follows from it.
struct Scaled {
    scale: DVector<f64>,
    u: DMatrix<f64>,
    s: DVector<f64>,
    v: DMatrix<f64>,
    rank: usize,
}

impl Scaled {
    fn new(psi: &DMatrix<f64>) -> Result<Self> {
        if psi.iter().any(|v| !v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the observation matrix".into(),
            });
        }
        let n = psi.ncols();
        if psi.nrows() < n {
            return Err(Error::TooFewRows { rows: psi.nrows() });
        }
        let norms = DVector::from_iterator(n, psi.column_iter().map(|c| c.norm()));
        let largest = norms.max();
        let scale = norms.map(|c| {
            if c > largest * 1e-300 && c > 0.0 {
                1.0 / c
            } else {
                1.0
            }
        });
        let mut a = psi.clone();
        for (mut col, s) in a.column_iter_mut().zip(scale.iter()) {
            col *= *s;
        }
        let svd = a.capped_svd(true, true).ok_or_else(|| Error::NotFinite {
            what: "the singular value decomposition of the observation matrix".into(),
        })?;
        // Sort descending (nalgebra does not promise an order).
        let mut order: Vec<usize> = (0..svd.singular_values.len()).collect();
        let sv = &svd.singular_values;
        order.sort_by(|&i, &j| sv[j].total_cmp(&sv[i]));
        let (u0, vt) = (svd.u.expect("asked for U"), svd.v_t.expect("asked for V"));
        let u = DMatrix::from_fn(u0.nrows(), order.len(), |i, k| u0[(i, order[k])]);
        let v = DMatrix::from_fn(n, order.len(), |i, k| vt[(order[k], i)]);
        let s = DVector::from_iterator(order.len(), order.iter().map(|&k| sv[k]));
        let top = s.max();
        let rank = s.iter().filter(|x| **x > top * RANK_TOLERANCE).count();
        Ok(Self {
            scale,
            u,
            s,
            v,
            rank,
        })
    }

    fn identifiability(&self) -> Identifiability {
        let n = self.v.nrows();
        let unidentifiable: Vec<Combination> = (self.rank..n)
            .map(|k| {
                let v = self.v.column(k);
                let mut terms: Vec<(usize, f64)> = (0..n)
                    .filter(|&j| v[j].abs() > SHARE)
                    .map(|j| (j, v[j]))
                    .collect();
                terms.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
                if terms.first().is_some_and(|t| t.1 < 0.0) {
                    terms.iter_mut().for_each(|t| t.1 = -t.1);
                }
                Combination { terms }
            })
            .collect();
        let identified = (0..n)
            .map(|j| {
                unidentifiable
                    .iter()
                    .all(|c| c.terms.iter().all(|t| t.0 != j))
            })
            .collect();
        let s_min = if self.rank < n { 0.0 } else { self.s.min() };
        Identifiability {
            rank: self.rank,
            scaled_cond: self.s.max() / s_min,
            unidentifiable,
            identified,
        }
    }

    /// `h` over the identifiable directions.
    fn solve(&self, delta: &DVector<f64>) -> DVector<f64> {
        let r = self.rank;
        let ur = self.u.columns(0, r);
        let c = ur.tr_mul(delta).component_div(&self.s.rows(0, r));
        (self.v.columns(0, r) * c).component_mul(&self.scale)
    }

    /// `(Psi^T Psi)^+` over the identifiable directions: `S V diag(1/s^2) V^T S`.
    fn unit_covariance(&self) -> DMatrix<f64> {
        let r = self.rank;
        let mut a = self.v.columns(0, r).into_owned();
        for (k, mut col) in a.column_iter_mut().enumerate() {
            col /= self.s[k];
        }
        for (j, mut row) in a.row_iter_mut().enumerate() {
            row *= self.scale[j];
        }
        &a * a.transpose()
    }
}

/// What an observation matrix `psi` (`m x n`, one column per parameter; or any matrix with its
/// column norms and Gram matrix `psi^T psi`, such as a planned group's compact blocks) identifies,
/// by the rule of the module docs; the design side's answer to which springs a group of postures
/// identifies (`stiffid_design::Evaluation::identifiability`).
///
/// # Errors
/// [`Error::NotFinite`] for non-finite entries, [`Error::TooFewRows`] for fewer rows than columns.
pub fn identifiability(psi: &DMatrix<f64>) -> Result<Identifiability> {
    Ok(Scaled::new(psi)?.identifiability())
}

/// The least-squares fit of `obs` (one column per entry of `parameters`) with its identifiability
/// and intervals (module docs).
///
/// # Errors
/// [`Error::NotFinite`] for non-finite entries, [`Error::TooFewRows`] for fewer rows than
/// parameters, [`Error::InvalidField`] when `parameters` does not match the columns or every
/// displacement is zero.
pub fn fit(obs: &Observations, parameters: &[Parameter]) -> Result<Fit> {
    check_shape(obs, parameters)?;
    let scaled = Scaled::new(&obs.psi)?;
    let h = scaled.solve(&obs.delta);
    Ok(finish(obs, parameters, &scaled, h, None, None))
}

/// The robust fit of `obs`: iteratively reweighted least squares with `loss`
/// ([`super::robust`]) from the least-squares fit, each step solved over the identifiable
/// directions of the weighted, column-scaled `Psi` (module docs). The intervals treat the final
/// weights `w` as known: `Cov(h) = s^2 (Psi^T W Psi)^+` with `s^2 = sum w_i r_i^2 / (m_w - r)`,
/// `m_w` the rows of non-zero weight ([`Fit::dof`] is `m_w - r`); the residuals and
/// [`Fit::rss`] are unweighted.
///
/// # Errors
/// As [`fit`].
pub(crate) fn fit_robust(obs: &Observations, parameters: &[Parameter], loss: Loss) -> Result<Fit> {
    check_shape(obs, parameters)?;
    let start = Scaled::new(&obs.psi)?.solve(&obs.delta);
    let solve = |a: DMatrix<f64>, b: &DVector<f64>| {
        let scaled = Scaled::new(&a)?;
        Ok((scaled.solve(b), scaled))
    };
    let (h, scaled, fit) = robust::fit(&obs.psi, &obs.delta, start, loss, &solve)?;
    Ok(finish(obs, parameters, &scaled, h, None, Some(fit)))
}

/// The fit of `obs` by `method`: [`fit`], `fit_nonnegative` or `fit_robust`.
///
/// # Errors
/// Those of the fit.
pub fn fit_by(obs: &Observations, parameters: &[Parameter], method: Method) -> Result<Fit> {
    match method {
        Method::LeastSquares => fit(obs, parameters),
        Method::Nonnegative => fit_nonnegative(obs, parameters),
        Method::Robust(loss) => fit_robust(obs, parameters, loss),
    }
}

/// `S V_r diag(1 / s_r)` of the column-scaled SVD of `psi` over its `r` identifiable directions
/// (n x r): `psi` times it is `U_r`, with orthonormal columns. It plays the part of `R^-1` in the
/// fold identities of [`super::cross_validation::without_rows`] (the least-squares solution is
/// this times `U_r^T delta`).
///
/// # Errors
/// Those of [`fit`] for a non-finite or short `psi`.
pub(crate) fn inverse_factor(psi: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let scaled = Scaled::new(psi)?;
    let r = scaled.rank;
    let mut a = scaled.v.columns(0, r).into_owned();
    for (k, mut col) in a.column_iter_mut().enumerate() {
        col /= scaled.s[k];
    }
    for (j, mut row) in a.row_iter_mut().enumerate() {
        row *= scaled.scale[j];
    }
    Ok(a)
}

/// The least-squares fit with every compliance `>= 0` (Lawson-Hanson, [`super::nonnegative`])
/// on the identifiable problem; compliances at the bound are listed in
/// [`Fit::active_bounds`], the intervals are those of the free ones with the others fixed.
///
/// # Errors
/// As [`fit`].
pub(crate) fn fit_nonnegative(obs: &Observations, parameters: &[Parameter]) -> Result<Fit> {
    check_shape(obs, parameters)?;
    let scaled = Scaled::new(&obs.psi)?;
    let h = scaled.solve(&obs.delta);
    if h.iter().all(|v| *v >= 0.0) {
        let mut out = finish(obs, parameters, &scaled, h, None, None);
        out.nonnegative_stop = Some(stiffid_core::common::stop::Stop::Converged);
        return Ok(out);
    }
    let bounded = super::nonnegative::solve_general(&obs.psi, &obs.delta);
    let free: Vec<usize> = (0..h.len()).filter(|&j| !bounded.active[j]).collect();
    let sub = Observations {
        psi: obs.psi.select_columns(&free),
        ..obs.clone()
    };
    let sub_params: Vec<Parameter> = free.iter().map(|&j| parameters[j].clone()).collect();
    let sub_fit = fit(&sub, &sub_params)?;
    let mut out = finish(
        obs,
        parameters,
        &scaled,
        bounded.h,
        Some(bounded.active.clone()),
        None,
    );
    out.intervals = vec![None; parameters.len()];
    for (k, &j) in free.iter().enumerate() {
        out.intervals[j] = sub_fit.intervals[k];
    }
    out.covariance = sub_fit.covariance.map(|sub| {
        let mut c = DMatrix::zeros(h.len(), h.len());
        for (a, &i) in free.iter().enumerate() {
            for (b, &j) in free.iter().enumerate() {
                c[(i, j)] = sub[(a, b)];
            }
        }
        c
    });
    out.dof = sub_fit.dof;
    out.nonnegative_stop = Some(bounded.stop);
    Ok(out)
}

fn check_shape(obs: &Observations, parameters: &[Parameter]) -> Result<()> {
    if parameters.len() != obs.psi.ncols() {
        return Err(Error::InvalidField {
            field: "model".into(),
            message: format!(
                "{} parameters for {} columns of the observation matrix",
                parameters.len(),
                obs.psi.ncols()
            ),
        });
    }
    if obs.delta.iter().all(|d| *d == 0.0) {
        return Err(Error::InvalidField {
            field: "displacement".into(),
            message: "every measured displacement is zero: nothing to identify (check the displacement columns)".into(),
        });
    }
    Ok(())
}

fn finish(
    obs: &Observations,
    parameters: &[Parameter],
    scaled: &Scaled,
    h: DVector<f64>,
    active_bounds: Option<Vec<bool>>,
    robust: Option<RobustFit>,
) -> Fit {
    let identifiability = scaled.identifiability();
    let predicted = &obs.psi * &h;
    let residuals = &obs.delta - &predicted;
    let rss = residuals.norm_squared();
    let rows = obs.psi.nrows();
    // A robust fit's variance: the weighted residuals over the rows of non-zero weight.
    let (weighted_rss, weighted_rows) = match &robust {
        None => (rss, rows),
        Some(fit) => (
            residuals.component_mul(&residuals).dot(&fit.weights),
            fit.weights.iter().filter(|w| **w > 0.0).count(),
        ),
    };
    let dof = weighted_rows.saturating_sub(scaled.rank);
    let t = (dof > 0)
        .then(|| StudentsT::new(0.0, 1.0, dof as f64).ok())
        .flatten()
        .map(|d| d.inverse_cdf(0.975));
    let covariance = scaled.unit_covariance() * (weighted_rss / dof.max(1) as f64);
    let variances = covariance.diagonal();
    let intervals = (0..h.len())
        .map(|j| {
            let t = t.filter(|_| identifiability.identified[j])?;
            let se = variances[j].sqrt();
            let ci = [h[j] - t * se, h[j] + t * se];
            Some(Interval {
                compliance_std_error: se,
                compliance_ci95: ci,
                stiffness_ci95: invert(ci),
            })
        })
        .collect();
    Fit {
        parameters: parameters.to_vec(),
        stiffness: h.map(|v| 1.0 / v),
        compliance: h,
        intervals,
        identifiability,
        covariance: (dof > 0).then_some(covariance),
        residuals,
        predicted,
        rss,
        rows,
        postures: obs.postures,
        dof,
        active_bounds,
        nonnegative_stop: None,
        robust,
    }
}

fn invert([lower, upper]: [f64; 2]) -> [f64; 2] {
    match (lower > 0.0, upper > 0.0) {
        (true, _) => [1.0 / upper, 1.0 / lower],
        (false, true) => [1.0 / upper, f64::INFINITY],
        (false, false) => [f64::INFINITY, f64::INFINITY],
    }
}

/// The leave-one-posture-out error of a least-squares fit (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOut {
    /// `delta_b` of every measurement predicted with its posture left out, m.
    pub delta_b: Vec<f64>,
    /// Per posture, the mean of `delta_b^2` over its measurements, m^2.
    pub posture_mse: Vec<f64>,
    /// Per posture, the sums of `delta_b^2` and of `|delta|^2` over its measurements, m^2 (what
    /// `explained_share` takes).
    pub posture_sums: Vec<[f64; 2]>,
    /// `RMS(delta_b)`, m.
    pub rms_delta_b: f64,
    /// `RMS(|delta|)` of the measured displacements, m.
    pub rms_measured: f64,
}

impl HeldOut {
    /// `1 - RMS(delta_b) / RMS(|delta|)`.
    pub fn explained(&self) -> f64 {
        1.0 - self.rms_delta_b / self.rms_measured
    }

    /// The standard error of [`HeldOut::explained`] over the postures (the delta method on the
    /// ratio of the postures' sums, `explained_share`).
    pub(crate) fn explained_std_error(&self) -> f64 {
        explained_share(&self.posture_sums)[1]
    }

    /// The mean over postures of their mean `delta_b^2` (m^2), and its standard error
    /// (the postures' sample standard deviation over `sqrt(postures)`).
    pub(crate) fn mse_and_se(&self) -> (f64, f64) {
        let n = self.posture_mse.len() as f64;
        let mean = self.posture_mse.iter().sum::<f64>() / n;
        let var = self
            .posture_mse
            .iter()
            .map(|x| (x - mean).powi(2))
            .sum::<f64>()
            / (n - 1.0).max(1.0);
        (mean, (var / n).sqrt())
    }
}

/// The leave-one-posture-out error of the least-squares fit of `obs` (module docs); `None` when
/// some posture is needed to identify the parameters (`I - H_ii` singular) or the data are
/// unusable ([`fit`]'s errors).
pub fn held_out(obs: &Observations) -> Option<HeldOut> {
    let scaled = Scaled::new(&obs.psi).ok()?;
    let h = scaled.solve(&obs.delta);
    let r = &obs.delta - &obs.psi * h;
    let ur = scaled.u.columns(0, scaled.rank);
    let mut rows_of: Vec<Vec<usize>> = vec![Vec::new(); obs.postures];
    for (i, &p) in obs.posture_index.iter().enumerate() {
        rows_of[p].extend(3 * i..3 * i + 3);
    }
    let mut delta_b = vec![0.0; obs.posture_index.len()];
    let mut posture_mse = Vec::with_capacity(obs.postures);
    let mut posture_sums = Vec::with_capacity(obs.postures);
    for rows in &rows_of {
        let ui = ur.select_rows(rows);
        let mut a = -(&ui * ui.transpose());
        for d in 0..rows.len() {
            a[(d, d)] += 1.0;
        }
        let ri = DVector::from_iterator(rows.len(), rows.iter().map(|&k| r[k]));
        let lu = a.clone().lu();
        let e = lu.solve(&ri)?;
        // I - H_ii must be well away from singular: its smallest eigenvalue is 1 - leverage.
        let leverage_ok = a.symmetric_eigenvalues().min() > 1e-9;
        if !leverage_ok || e.iter().any(|x| !x.is_finite()) {
            return None;
        }
        let mut sum = 0.0;
        for (k, chunk) in rows.chunks(3).enumerate() {
            let d = e.rows(3 * k, 3).norm();
            delta_b[chunk[0] / 3] = d;
            sum += d * d;
        }
        posture_mse.push(sum / (rows.len() / 3) as f64);
        posture_sums.push([sum, rows.iter().map(|&k| obs.delta[k].powi(2)).sum()]);
    }
    let n = delta_b.len() as f64;
    Some(HeldOut {
        rms_delta_b: (delta_b.iter().map(|d| d * d).sum::<f64>() / n).sqrt(),
        rms_measured: (obs.delta.norm_squared() / n).sqrt(),
        delta_b,
        posture_mse,
        posture_sums,
    })
}
