//! Cross-validation over postures: refit without some postures, predict them (Eq. 22).
//!
//! With `K` folds, posture `p` (numbered `0..n` in order of first appearance,
//! [`Observations::posture_index`]) is held out in fold `p mod K`; `K = n` is leave-one-posture-out.
//! Each fold identifies the compliance from the other postures' rows with the full fit's
//! [`Method`] (least squares, bounded or robust) and predicts the held-out measurements:
//! `delta_b = |delta_m - Psi_i h|` per measurement. The spread of a joint's stiffness across folds
//! says how much it depends on which postures were measured; a fold whose removal moves a
//! stiffness by more than its standard error in the full fit is influential for that joint (with
//! a standard error of zero, a noise-free fit, nothing is: influence is not computed). Nor is it
//! for data exact to their rounding: a full fit whose residuals are at most `EXACT_SHARE` of
//! the measured displacements (both as root sum of squares), where the standard errors and the
//! folds' moves are both the rounding's.
//!
//! ## Least squares: every fold from the full fit, linear in the postures
//! With `Psi = Q R` (QR of the full `Psi`, `p` columns), `e = delta - Psi h` the full residuals and
//! `o` the held-out rows, the block hat matrix is `H_oo = A A^T` with `A = Psi_o R^-1`. Removing
//! the rows `o` (the block form of the leave-one-out identities, Belsley, Kuh & Welsch,
//! *Regression Diagnostics*, 1980, ch. 2; Cook & Weisberg, *Residuals and Influence in
//! Regression*, 1982, sec. 3.6) gives exactly
//! - the held-out residual `delta_o - Psi_o h_(-o) = (I - H_oo)^-1 e_o`,
//! - the fold's compliance `h_(-o) = h - R^-1 A^T (I - H_oo)^-1 e_o`,
//!
//! so a fold costs `O(m_o p^2 + m_o^3)` for its `m_o` held-out rows and the whole
//! cross-validation one QR of `Psi` plus time linear in the rows. A fold is refused as
//! unidentifiable when `I - H_oo` is singular to working precision (its Cholesky factor has a
//! pivot below `MIN_PIVOT`): the other postures cannot identify every joint.
//!
//! ## Bounded and robust fits: refitted
//! The non-negative and robust fits are not linear in `delta`; each fold is refitted from its rows.
//! That costs `O(K m p^2)`: `folds x measurements` is at most 4 000 000.

pub use super::Method;

use crate::{explained_share, svd, Identification};
use nalgebra::{DMatrix, DVector, Vector6};
use rayon::prelude::*;
use stiffid_core::math::lsq::Factor;
use stiffid_core::observation::Observations;
use stiffid_core::{Error, Result};

/// The smallest Cholesky pivot of `I - H_oo` (module docs) for a fold to count as identifiable.
pub(crate) const MIN_PIVOT: f64 = 1e-7;

/// The most `folds x measurements` of a refitted (bounded or robust) cross-validation: each
/// fold's fit costs about 13 us of CPU per measurement, so the bound is about a minute of CPU (2
/// folds of the 1.48 million rows of a 256 MiB file: 38 s).
pub(crate) const MAX_REFIT_WORK: usize = 4_000_000;

/// One fold: the fit without some postures and its predictions of them.
#[derive(Debug, Clone, PartialEq)]
pub struct Fold {
    /// The held-out postures (dense numbers, [`Observations::posture_index`]).
    pub postures: Vec<usize>,
    /// The held-out measurements (indices into the measurements).
    pub measurements: Vec<usize>,
    /// The compliance of every parameter fitted without them, SI (rad/Nm, m/N), in the order of
    /// the columns of `Psi`.
    pub compliance: DVector<f64>,
    /// The stiffness of every parameter fitted without them, SI (Nm/rad, N/m), in the order of
    /// the columns of `Psi`.
    pub stiffness: DVector<f64>,
    /// The held-out residuals `delta_m - Psi_i h` of each held-out measurement (three per
    /// measurement, in the order of `measurements`), base frame, m.
    pub residuals: DVector<f64>,
    /// `delta_b` (Eq. 22) of each held-out measurement, m.
    pub delta_b: Vec<f64>,
    /// Root mean square of `delta_b`, m.
    pub rms_delta_b: f64,
    /// Per parameter: whether its stiffness moved by more than its full-fit standard error.
    pub influential: Vec<bool>,
}

/// The result of a cross-validation. Stiffness vectors have one entry per parameter (column of
/// `Psi`), SI.
#[derive(Debug, Clone, PartialEq)]
pub struct CrossValidation {
    /// One per fold, in fold order.
    pub folds: Vec<Fold>,
    /// Mean stiffness across folds.
    pub stiffness_mean: DVector<f64>,
    /// Sample standard deviation of the stiffness across folds.
    pub stiffness_std: DVector<f64>,
    /// Smallest and largest stiffness across folds.
    pub stiffness_range: [DVector<f64>; 2],
    /// Root mean square of `delta_b` over every held-out measurement, m.
    pub rms_delta_b: f64,
    /// Root mean square of the measured displacement magnitudes, m.
    pub rms_measured: f64,
    /// The standard error of [`CrossValidation::explained`] over the postures
    /// (`explained_share`).
    pub explained_std_error: f64,
}

impl CrossValidation {
    /// The held-out explained share `1 - rms_delta_b / rms_measured`.
    pub fn explained(&self) -> f64 {
        1.0 - self.rms_delta_b / self.rms_measured
    }
}

/// The share of the measured displacements (root sum of squares) at or below which a full fit's
/// residuals are the data's rounding: no tracker measures a displacement to a part in a million
/// (0.01 mm of noise on a 1 mm deflection is 1e-2), while data computed by a model and written
/// with six or more significant digits fit it this well.
pub(crate) const EXACT_SHARE: f64 = 1e-6;

/// Whether a fit with `residuals` explains `delta` (m) to the data's rounding ([`EXACT_SHARE`]).
fn exact(residuals: &DVector<f64>, delta: &DVector<f64>) -> bool {
    residuals.norm() <= EXACT_SHARE * delta.norm()
}

/// The full fit that every fold repeats: its compliance and its stiffness standard errors.
struct Full {
    /// `h`, SI, one per column of `Psi`.
    h: DVector<f64>,
    /// The stiffness standard errors (all positive and finite), or `None`: nothing influential.
    se: Option<DVector<f64>>,
}

/// Cross-validates the six drives with `folds` folds (module docs), each fitted with `method`;
/// `full` is the identification of all of `obs` by `method` (its standard errors decide
/// influence; without them, or with a zero standard error, nothing is influential).
///
/// # Errors
/// [`Error::InvalidField`] (`folds`) unless `2 <= folds <= postures`, or for a bounded or robust
/// `method` when `folds x measurements` exceeds 4 000 000; (`cross-validation fold N`) when the
/// postures left in a fold cannot identify every joint (the message says why).
pub fn cross_validate(
    obs: &Observations,
    full: &Identification,
    folds: usize,
    method: Method,
) -> Result<CrossValidation> {
    let dvec = |v: &Vector6<f64>| DVector::from_column_slice(v.as_slice());
    let full_fit = Full {
        h: dvec(&full.compliance),
        se: (full.uncertainty.as_ref())
            .filter(|_| !exact(&full.residuals, &obs.delta))
            .map(|u| dvec(&u.stiffness_std_error)),
    };
    let inverse = || {
        let factor = Factor::try_new(obs.psi.clone())?;
        Ok(DMatrix::from_column_slice(6, 6, factor.r_inv().as_slice()))
    };
    let refit = |rest: &Observations| Ok(dvec(&method.fit(rest)?.compliance));
    run(obs, &full_fit, folds, method, inverse, refit)
}

/// Cross-validates a model of any number of parameters ([`super::svd`]) as
/// [`cross_validate`]: `full` is the fit of all of `obs` by `method` ([`svd::fit_by`]);
/// least-squares folds come from its column-scaled SVD (`svd::inverse_factor`), bounded and
/// robust folds are refitted. A fold whose other postures do not identify every parameter is
/// refused.
///
/// # Errors
/// As [`cross_validate`].
pub fn cross_validate_model(
    obs: &Observations,
    full: &svd::Fit,
    folds: usize,
    method: Method,
) -> Result<CrossValidation> {
    let se = full
        .intervals
        .iter()
        .zip(full.compliance.iter())
        .map(|(i, h)| i.map(|i| i.compliance_std_error / (h * h)))
        .collect::<Option<Vec<f64>>>();
    let full_fit = Full {
        h: full.compliance.clone(),
        se: (se.map(DVector::from_vec)).filter(|_| !exact(&full.residuals, &obs.delta)),
    };
    let n = full.parameters.len();
    let inverse = || svd::inverse_factor(&obs.psi);
    let refit = |rest: &Observations| {
        let f = svd::fit_by(rest, &full.parameters, method)?;
        match f.identifiability.rank == n {
            true => Ok(f.compliance),
            false => Err(Error::InvalidField {
                field: "model".into(),
                message: format!(
                    "the data cannot separate {}",
                    f.identifiability.unidentifiable[0].describe(&full.parameters)
                ),
            }),
        }
    };
    run(obs, &full_fit, folds, method, inverse, refit)
}

/// The cross-validation of `obs` against `full`: least-squares folds from `inverse()` (the
/// full fit's `R^-1` or its equivalent), other folds by `refit` of the rest's rows.
fn run(
    obs: &Observations,
    full: &Full,
    folds: usize,
    method: Method,
    inverse: impl FnOnce() -> Result<DMatrix<f64>>,
    refit: impl Fn(&Observations) -> Result<DVector<f64>> + Sync,
) -> Result<CrossValidation> {
    check_folds(obs, folds, method)?;
    let se = full
        .se
        .as_ref()
        .filter(|se| se.iter().all(|s| *s > 0.0 && s.is_finite()));
    let held: Vec<Vec<usize>> = {
        let mut held = vec![Vec::new(); folds];
        for (i, p) in obs.posture_index.iter().enumerate() {
            held[p % folds].push(i);
        }
        held
    };
    let fitted: Vec<(DVector<f64>, DVector<f64>)> = match method {
        Method::LeastSquares => linear_folds(obs, &full.h, &inverse()?, &held)?,
        _ => held
            .par_iter()
            .enumerate()
            .map(|(f, out)| refit_fold(obs, f, out, &refit))
            .collect::<Result<_>>()?,
    };
    let full_k = full.h.map(|v| 1.0 / v);
    let folds: Vec<Fold> = held
        .into_iter()
        .zip(fitted)
        .map(|(out, (h, residuals))| fold(obs, out, h, residuals, &full_k, se))
        .collect();
    Ok(summarise(obs, folds))
}

/// Refuses fewer than two folds, more than the postures, and too much refitting work.
fn check_folds(obs: &Observations, folds: usize, method: Method) -> Result<()> {
    if folds < 2 || folds > obs.postures {
        return Err(Error::InvalidField {
            field: "folds".into(),
            message: format!(
                "expected 2 to {} (the number of postures), got {folds}",
                obs.postures
            ),
        });
    }
    let measurements = obs.posture_index.len();
    if method != Method::LeastSquares && folds.saturating_mul(measurements) > MAX_REFIT_WORK {
        return Err(Error::InvalidField {
            field: "folds".into(),
            message: format!(
                "{folds} folds of {measurements} measurements: a bounded or robust fit refits every fold, and folds x measurements is at most {MAX_REFIT_WORK} (at most {} folds here)",
                (MAX_REFIT_WORK / measurements.max(1)).max(2)
            ),
        });
    }
    Ok(())
}

/// The spread of the stiffness across `folds` and the held-out error.
fn summarise(obs: &Observations, folds: Vec<Fold>) -> CrossValidation {
    let n = folds.len() as f64;
    let p = obs.psi.ncols();
    let mean = folds
        .iter()
        .fold(DVector::zeros(p), |a, f| a + &f.stiffness)
        / n;
    let var = folds.iter().fold(DVector::zeros(p), |a, f| {
        a + (&f.stiffness - &mean).map(|d| d * d)
    }) / (n - 1.0);
    let range = [
        folds
            .iter()
            .fold(DVector::repeat(p, f64::INFINITY), |a, f| {
                a.inf(&f.stiffness)
            }),
        folds
            .iter()
            .fold(DVector::repeat(p, f64::NEG_INFINITY), |a, f| {
                a.sup(&f.stiffness)
            }),
    ];
    let held_out: Vec<f64> = folds
        .iter()
        .flat_map(|f| f.delta_b.iter().copied())
        .collect();
    let measured = obs.delta.norm_squared() / (obs.delta.len() / 3) as f64;
    let mut per_posture = vec![[0.0; 2]; obs.postures];
    for f in &folds {
        for (&i, d) in f.measurements.iter().zip(&f.delta_b) {
            let p = &mut per_posture[obs.posture_index[i]];
            p[0] += d * d;
            p[1] += obs.delta.fixed_rows::<3>(3 * i).norm_squared();
        }
    }
    CrossValidation {
        explained_std_error: explained_share(&per_posture)[1],
        stiffness_mean: mean,
        stiffness_std: var.map(f64::sqrt),
        stiffness_range: range,
        rms_delta_b: rms(&held_out),
        rms_measured: measured.sqrt(),
        folds,
    }
}

fn rms(values: &[f64]) -> f64 {
    (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt()
}

/// The error of fold `f` (0-based) whose other postures cannot identify the stiffness.
fn unidentifiable(f: usize, why: &str) -> Error {
    Error::InvalidField {
        field: format!("cross-validation fold {}", f + 1),
        message: format!("the other postures cannot identify the stiffness: {why}"),
    }
}

/// The three rows of each measurement of `ids`: `Psi` and `delta`.
fn rows(obs: &Observations, ids: &[usize]) -> (DMatrix<f64>, DVector<f64>) {
    let p = obs.psi.ncols();
    let mut psi = DMatrix::zeros(3 * ids.len(), p);
    let mut delta = DVector::zeros(3 * ids.len());
    for (k, &i) in ids.iter().enumerate() {
        psi.rows_mut(3 * k, 3).copy_from(&obs.psi.rows(3 * i, 3));
        delta
            .rows_mut(3 * k, 3)
            .copy_from(&obs.delta.rows(3 * i, 3));
    }
    (psi, delta)
}

/// `delta_b` of each held-out measurement from the held-out residual rows.
fn delta_b(residual: &DVector<f64>) -> Vec<f64> {
    (0..residual.len() / 3)
        .map(|k| residual.rows(3 * k, 3).norm())
        .collect()
}

/// Every least-squares fold from the full fit `h` and `r_inv` (module docs): the compliance
/// without the fold's rows and the held-out residuals of its measurements.
fn linear_folds(
    obs: &Observations,
    h: &DVector<f64>,
    r_inv: &DMatrix<f64>,
    held: &[Vec<usize>],
) -> Result<Vec<(DVector<f64>, DVector<f64>)>> {
    let residual = &obs.delta - &obs.psi * h;
    held.par_iter()
        .enumerate()
        .map(|(f, out)| {
            let ids: Vec<usize> = out.iter().flat_map(|&i| 3 * i..3 * i + 3).collect();
            let psi_o = obs.psi.select_rows(&ids);
            let e_o = residual.select_rows(&ids);
            let (dh, e_loo) = without_rows(&psi_o, r_inv, &e_o)
                .ok_or_else(|| unidentifiable(f, "removing them leaves Psi rank deficient"))?;
            Ok((h - dh, e_loo))
        })
        .collect()
}

/// Removing the rows `Psi_o` (residuals `e_o` of the full least-squares fit, `R^-1` of the full
/// QR factor, any number of columns `p`) from a least-squares problem: the change of the solution
/// `h - h_(-o) = R^-1 A^T x` and the held-out residuals `x = (I - A A^T)^-1 e_o`, `A = Psi_o
/// R^-1` (module docs); `None` when `I - A A^T` is singular to working precision.
pub(crate) fn without_rows(
    psi_o: &DMatrix<f64>,
    r_inv: &DMatrix<f64>,
    e_o: &DVector<f64>,
) -> Option<(DVector<f64>, DVector<f64>)> {
    let a = psi_o * r_inv;
    let m = a.nrows();
    let i_minus_h = DMatrix::identity(m, m) - &a * a.transpose();
    let chol = i_minus_h.cholesky()?;
    if chol
        .l_dirty()
        .diagonal()
        .iter()
        .any(|d| d.is_nan() || *d < MIN_PIVOT)
    {
        return None;
    }
    let x = chol.solve(e_o);
    Some((r_inv * (a.transpose() * &x), x))
}

/// Fold `f` (held-out measurements `out`) refitted by `refit` from the other postures' rows.
fn refit_fold(
    obs: &Observations,
    f: usize,
    out: &[usize],
    refit: &impl Fn(&Observations) -> Result<DVector<f64>>,
) -> Result<(DVector<f64>, DVector<f64>)> {
    let mut is_out = vec![false; obs.posture_index.len()];
    out.iter().for_each(|&i| is_out[i] = true);
    let train: Vec<usize> = (0..is_out.len()).filter(|&i| !is_out[i]).collect();
    let (psi, delta) = rows(obs, &train);
    let mut index: Vec<usize> = train.iter().map(|&i| obs.posture_index[i]).collect();
    let postures = renumber(&mut index);
    let rest = Observations {
        psi,
        delta,
        postures,
        posture_index: index,
    };
    let h = refit(&rest).map_err(|e| unidentifiable(f, &e.to_string()))?;
    let (psi, delta) = rows(obs, out);
    let residual = delta - psi * &h;
    Ok((h, residual))
}

/// Renumbers posture numbers densely in order of first appearance; returns how many there are.
fn renumber(index: &mut [usize]) -> usize {
    let mut map = std::collections::HashMap::new();
    for p in index.iter_mut() {
        let next = map.len();
        *p = *map.entry(*p).or_insert(next);
    }
    map.len()
}

fn fold(
    obs: &Observations,
    out: Vec<usize>,
    h: DVector<f64>,
    residuals: DVector<f64>,
    full: &DVector<f64>,
    se: Option<&DVector<f64>>,
) -> Fold {
    let stiffness = h.map(|v| 1.0 / v);
    let delta_b = delta_b(&residuals);
    let mut postures: Vec<usize> = out.iter().map(|&i| obs.posture_index[i]).collect();
    postures.sort_unstable();
    postures.dedup();
    Fold {
        postures,
        rms_delta_b: rms(&delta_b),
        influential: (0..stiffness.len())
            .map(|j| se.is_some_and(|se| (stiffness[j] - full[j]).abs() > se[j]))
            .collect(),
        stiffness,
        compliance: h,
        residuals,
        measurements: out,
        delta_b,
    }
}
