//! The calibration linearised at a fit, and the held-out errors of any choice of maps on any split
//! of its postures (module docs of [`super`], "Cross-validation on the linearised fit").
//!
//! With `r` the residuals at the fit, `G` the scaled columns of the fitted parameters and `M` the
//! scaled columns of the candidate maps, a split's training rows `T` give the geometry's columns
//! `G_T = U S V^T` (SVD, the part below `1e-10` of the largest singular value dropped) and, for
//! the map columns `M_T` of a choice, `A_M = P M_T = M_T - U U^T M_T`; the ridge `lambda` gives
//! the maps' step `y = -(A_M^T A_M + lambda I)^-1 A_M^T P r_T`, the geometry's
//! `-V S^-1 U^T (r_T + M_T y)`, and the held-out rows `V` the errors
//!
//! ```text
//! e_V = (r_V - A U^T r_T) + (M_V - A U^T M_T) y,        A = G_V V S^-1
//! ```
//!
//! exactly the least squares of the linearised model with the ridge rows on the maps alone (the
//! geometry's columns by SVD, never their normal equations).
//!
//! A split projects every candidate column once (`P M_T` and `M_V - A U^T M_T`, all joints; a
//! choice of fixed maps or none scores on [`Linear::restricted`] to its own columns) and keeps
//! their Gram matrix `(P M_T)^T P M_T` and `(P M_T)^T P r_T`: a choice's are their blocks. The
//! maps' step solves the ridge's normal equations by a Cholesky factor per `lambda`, in the
//! smaller of the two sides: `A_M^T A_M + lambda I` where the training rows are as many as the
//! choice's columns or more, else `y = -A_M^T (A_M A_M^T + lambda I)^-1 P r_T` (the same step).
//! The ridge bounds their condition by `(sigma_max^2 + lambda) / lambda`; a `lambda` below
//! `1e-9` of the largest diagonal entry, or a factor that fails, takes the SVD
//! `A_M = W Sigma Z^T` instead: `y = -Z diag(1 / (sigma^2 + lambda)) Z^T A_M^T P r_T` over the
//! nonzero `sigma`. Both agree with the augmented system solved directly to `1e-9` of the
//! held-out errors (`maps_kernel_tests.rs`).

use super::super::error_model::{JointMaps, Observation, Target};
use super::super::fit::Fit;
use super::super::{ErrorModel, Estimate};
use nalgebra::{DMatrix, DVector};
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::{Error, Result};

/// The singular values below this share of the largest are dropped from the geometry's.
const DROPPED: f64 = 1e-10;

/// The calibration linearised at a fit.
#[derive(Debug, Clone)]
pub struct Linear {
    /// The residuals at the fit (m), 3 per reading.
    pub residuals: DVector<f64>,
    /// The fitted parameters' scaled columns (m per typical error).
    pub geometry: DMatrix<f64>,
    /// Per joint, its map's scaled columns to the largest harmonic count `H`: `cos 1..H`, then
    /// `sin 1..H` (a joint with a candidate map), then its backlash term's (a candidate
    /// backlash); empty for a joint not a candidate.
    pub maps: Vec<DMatrix<f64>>,
    /// The largest harmonic count.
    pub harmonics: usize,
    /// The candidate maps and backlash terms.
    pub candidates: JointMaps,
    /// The rows of each posture, in posture order.
    pub rows: Vec<Vec<usize>>,
}

/// A split's training part, prepared once for every choice of maps.
pub struct Split {
    /// The postures of the test rows (index into the split's test postures), one per row.
    test_posture: Vec<usize>,
    /// `r_V - A U^T r_T`.
    base: DVector<f64>,
    /// Every candidate map column projected, `P M_T` (all of [`Linear::maps`]' columns, joint
    /// after joint).
    projected_maps: DMatrix<f64>,
    /// `P r_T`.
    projected: DVector<f64>,
    /// `(P M_T)^T P M_T`, every candidate column: a choice's ridge matrix is its block.
    gram: DMatrix<f64>,
    /// `(P M_T)^T P r_T`, every candidate column.
    moment: DVector<f64>,
    /// Every candidate map column on the held-out rows, `M_V - A U^T M_T`.
    held_maps: DMatrix<f64>,
}

/// `estimate` with the nominal values of the maps `model` adds after its parameters.
pub fn extended(model: &ErrorModel, estimate: &Estimate) -> Estimate {
    let mut values = model.nominal();
    values
        .rows_mut(0, estimate.values.len())
        .copy_from(&estimate.values);
    Estimate {
        frame: estimate.frame,
        values,
    }
}

impl Linear {
    /// The calibration `model` (without maps) linearised at its fit `fitted` to `observations`
    /// with the candidate maps `harmonics` (each joint's largest count, 0 for none, and the
    /// candidate backlash terms), the columns
    /// scaled with the characteristic length `length` (m) as the fit scales them; the postures
    /// are those of the observations, in ascending order of their index.
    ///
    /// # Errors
    /// Those of [`ErrorModel::with_maps`], [`ErrorModel::residuals`] and
    /// [`ErrorModel::jacobian_of`].
    pub fn at(
        model: &ErrorModel,
        fitted: &Fit,
        observations: &[Observation],
        length: f64,
        harmonics: JointMaps,
    ) -> Result<Linear> {
        let wide = model.clone().with_maps(harmonics)?;
        let estimate = extended(&wide, &fitted.estimate);
        let residuals = wide.residuals(&estimate, observations)?;
        let j = wide.jacobian_of(&estimate.values, observations)?;
        let scales = wide.column_scales_of(length, observations);
        let scaled = |c: usize| j.column(c) * scales[c];
        let columns: Vec<DVector<f64>> = fitted.fitted.iter().map(|&c| scaled(c)).collect();
        let geometry = DMatrix::from_columns(&columns);
        let largest = harmonics.harmonics.iter().copied().max().unwrap_or(0);
        let mut maps: Vec<DMatrix<f64>> = (0..6)
            .map(|joint| {
                let map = if harmonics.harmonics[joint] > 0 {
                    2 * largest
                } else {
                    0
                };
                DMatrix::zeros(j.nrows(), map + usize::from(harmonics.backlash[joint]))
            })
            .collect();
        for (c, p) in wide.parameters().iter().enumerate() {
            match p.target {
                Target::Map {
                    joint,
                    harmonic,
                    sine,
                } => {
                    let at = harmonic - 1 + if sine { largest } else { 0 };
                    maps[joint].set_column(at, &scaled(c));
                }
                Target::Backlash { joint } => {
                    let last = maps[joint].ncols() - 1;
                    maps[joint].set_column(last, &scaled(c));
                }
                _ => {}
            }
        }
        let mut postures: Vec<usize> = observations.iter().map(|o| o.posture).collect();
        postures.sort_unstable();
        postures.dedup();
        let mut rows = vec![Vec::new(); postures.len()];
        for (i, o) in observations.iter().enumerate() {
            if let Ok(p) = postures.binary_search(&o.posture) {
                rows[p].extend(3 * i..3 * i + 3);
            }
        }
        Ok(Linear {
            residuals,
            geometry,
            maps,
            harmonics: largest,
            candidates: harmonics,
            rows,
        })
    }

    /// Prepares the split training on the postures `train` and testing on `test` (posture
    /// indices).
    ///
    /// # Errors
    /// [`Error::NotFinite`] when an SVD does not converge.
    pub fn split(&self, train: &[usize], test: &[usize]) -> Result<Split> {
        let rows = |ps: &[usize]| -> Vec<usize> {
            ps.iter()
                .flat_map(|&p| self.rows[p].iter().copied())
                .collect()
        };
        let (train_rows, test_rows) = (rows(train), rows(test));
        let test_posture = (test.iter().enumerate())
            .flat_map(|(i, &p)| std::iter::repeat_n(i, self.rows[p].len()))
            .collect();
        let g_t = self.geometry.select_rows(train_rows.iter());
        let g_v = self.geometry.select_rows(test_rows.iter());
        let svd = g_t.capped_svd(true, true).ok_or_else(not_converged)?;
        let (u, v_t) = (
            svd.u.ok_or_else(not_converged)?,
            svd.v_t.ok_or_else(not_converged)?,
        );
        let s = &svd.singular_values;
        let largest = s.iter().copied().fold(0.0, f64::max);
        let kept: Vec<usize> = (0..s.len()).filter(|&i| s[i] > DROPPED * largest).collect();
        let u = u.select_columns(kept.iter());
        let v_scaled = DMatrix::from_fn(v_t.ncols(), kept.len(), |r, c| {
            v_t[(kept[c], r)] / s[kept[c]]
        });
        let a = g_v * v_scaled;
        let r_t = DVector::from_iterator(
            train_rows.len(),
            train_rows.iter().map(|&i| self.residuals[i]),
        );
        let r_v = DVector::from_iterator(
            test_rows.len(),
            test_rows.iter().map(|&i| self.residuals[i]),
        );
        let utr = u.tr_mul(&r_t);
        let projected = r_t - &u * &utr;
        let all = self.all_columns();
        let m_t = self.columns_of(&all, &train_rows);
        let utm = u.tr_mul(&m_t);
        let held_maps = self.columns_of(&all, &test_rows) - &a * &utm;
        let projected_maps = m_t - &u * utm;
        // Products through the matrix kernel (`tr_mul` takes a dot product per entry).
        let pm_t = projected_maps.transpose();
        Ok(Split {
            base: r_v - &a * &utr,
            gram: &pm_t * &projected_maps,
            moment: &pm_t * &projected,
            projected,
            projected_maps,
            held_maps,
            test_posture,
        })
    }

    /// This linearisation with the map columns of `keep` alone (each joint's matrix `cos 1..h`,
    /// `sin 1..h`, then its backlash term's, `h` the joint's count in `keep`): the same held-out
    /// errors for any choice within `keep` (to rounding), from splits that project and compress
    /// only these columns. `keep` within [`Linear::candidates`].
    pub fn restricted(&self, keep: &JointMaps) -> Linear {
        let maps = (0..6)
            .map(|j| {
                let h = keep.harmonics[j];
                let sine = self.sine(j);
                let mut cols: Vec<usize> = (0..h).chain(sine..sine + h).collect();
                if keep.backlash[j] {
                    cols.push(self.maps[j].ncols() - 1);
                }
                self.maps[j].select_columns(cols.iter())
            })
            .collect();
        Linear {
            residuals: self.residuals.clone(),
            geometry: self.geometry.clone(),
            maps,
            harmonics: keep.harmonics.iter().copied().max().unwrap_or(0),
            candidates: *keep,
            rows: self.rows.clone(),
        }
    }

    /// The column of joint `j`'s first sine in its matrix of [`Linear::maps`]: its harmonic count.
    fn sine(&self, j: usize) -> usize {
        (self.maps[j].ncols() - usize::from(self.candidates.backlash[j])) / 2
    }

    /// The map columns of `choice` (joint, column of [`Linear::maps`]' matrix of the joint).
    fn columns(&self, choice: &JointMaps) -> Vec<(usize, usize)> {
        let mut cols = Vec::new();
        for (j, &h) in choice.harmonics.iter().enumerate().filter(|&(_, &h)| h > 0) {
            let sine = self.sine(j);
            cols.extend((0..h).chain(sine..sine + h).map(|c| (j, c)));
        }
        for j in (0..6).filter(|&j| choice.backlash[j]) {
            cols.push((j, self.maps[j].ncols() - 1));
        }
        cols
    }

    /// Every map column (joint, column), joint after joint: the layout of a split's
    /// `projected_maps` and `held_maps`.
    fn all_columns(&self) -> Vec<(usize, usize)> {
        (0..6)
            .flat_map(|j| (0..self.maps[j].ncols()).map(move |k| (j, k)))
            .collect()
    }

    /// The indices in [`Self::all_columns`] of the map columns of `choice`.
    fn indices(&self, choice: &JointMaps) -> Vec<usize> {
        let mut offsets = [0; 6];
        for j in 1..6 {
            offsets[j] = offsets[j - 1] + self.maps[j - 1].ncols();
        }
        (self.columns(choice).into_iter())
            .map(|(j, k)| offsets[j] + k)
            .collect()
    }

    /// The map columns `cols` on `rows`.
    fn columns_of(&self, cols: &[(usize, usize)], rows: &[usize]) -> DMatrix<f64> {
        DMatrix::from_fn(rows.len(), cols.len(), |r, c| {
            let (j, k) = cols[c];
            self.maps[j][(rows[r], k)]
        })
    }

    /// The held-out errors of `split` with the maps of `choice` at each ridge `lambdas` (in the
    /// scaled units, module docs): per `lambda`, the sum of the squared errors of each test
    /// posture (m^2).
    ///
    /// # Errors
    /// [`Error::NotFinite`] when an SVD does not converge.
    pub fn errors(
        &self,
        split: &Split,
        choice: &JointMaps,
        lambdas: &[f64],
    ) -> Result<Vec<Vec<f64>>> {
        let postures = split.test_posture.last().map_or(0, |p| p + 1);
        let per_posture = |e: &DVector<f64>| {
            let mut out = vec![0.0; postures];
            for (v, &p) in e.iter().zip(&split.test_posture) {
                out[p] += v * v;
            }
            out
        };
        if choice.is_none() {
            return Ok(vec![per_posture(&split.base); lambdas.len()]);
        }
        let chosen = self.indices(choice);
        let steps = match ridge_steps(split, &chosen, lambdas) {
            Some(steps) => steps,
            None => svd_steps(split, &chosen, lambdas)?,
        };
        let moved = split.held_maps.select_columns(chosen.iter()) * steps;
        Ok((0..lambdas.len())
            .map(|k| per_posture(&(&split.base + moved.column(k))))
            .collect())
    }
}

/// The least share of the ridge matrix's largest diagonal entry a ridge `lambda` must reach for
/// [`ridge_steps`]: it bounds the condition of `C + lambda I` (`C` the Gram matrix of the
/// smaller side) by about its order times its inverse.
const LEAST_RIDGE: f64 = 1e-9;

/// The maps' steps `y = -(A^T A + lambda I)^-1 A^T P r_T` of the columns `chosen` (`A` their
/// `P M_T`) at each `lambda` (one column each), from a Cholesky factor per `lambda` of the
/// smaller of the two Gram matrices: `A^T A` (a block of the split's) where the training rows
/// are as many as the columns or more, else `A A^T` (`y = -A^T (A A^T + lambda I)^-1 P r_T`).
/// The ridge bounds their condition (module docs); `None` where a `lambda` is below
/// [`LEAST_RIDGE`] of the largest diagonal entry or a factor fails (the SVD then).
fn ridge_steps(split: &Split, chosen: &[usize], lambdas: &[f64]) -> Option<DMatrix<f64>> {
    let (m, p) = (split.projected_maps.nrows(), chosen.len());
    let wide = m < p;
    let (c, rhs, a) = match wide {
        false => (
            DMatrix::from_fn(p, p, |i, j| split.gram[(chosen[i], chosen[j])]),
            DVector::from_fn(p, |i, _| split.moment[chosen[i]]),
            None,
        ),
        true => {
            let a = split.projected_maps.select_columns(chosen.iter());
            (&a * a.transpose(), split.projected.clone(), Some(a))
        }
    };
    let largest = c.diagonal().max();
    let mut solved = DMatrix::zeros(c.nrows(), lambdas.len());
    for (k, &lambda) in lambdas.iter().enumerate() {
        if !lambda.is_finite() || lambda <= LEAST_RIDGE * largest {
            return None;
        }
        let mut shifted = c.clone();
        for i in 0..shifted.nrows() {
            shifted[(i, i)] += lambda;
        }
        let x = nalgebra::Cholesky::new(shifted)?.solve(&rhs);
        solved.set_column(k, &(-x));
    }
    Some(match a {
        Some(a) => a.transpose() * solved,
        None => solved,
    })
}

/// [`ridge_steps`] from the SVD of the chosen columns' `P M_T = W Sigma Z^T`:
/// `y = -Z diag(1 / (sigma^2 + lambda)) Z^T A^T P r_T` over the nonzero `sigma`.
///
/// # Errors
/// [`Error::NotFinite`] when the SVD does not converge.
fn svd_steps(split: &Split, chosen: &[usize], lambdas: &[f64]) -> Result<DMatrix<f64>> {
    let pm = split.projected_maps.select_columns(chosen.iter());
    // `Z^T (P M_T)^T P r_T`: its entry i is `s_i g_i` (`g = W^T P r_T`), without `W`.
    let b = DVector::from_fn(chosen.len(), |i, _| split.moment[chosen[i]]);
    let svd = pm.capped_svd(false, true).ok_or_else(not_converged)?;
    let z_t = svd.v_t.ok_or_else(not_converged)?;
    let sg = &z_t * b;
    let s = &svd.singular_values;
    let weights = DMatrix::from_fn(sg.len(), lambdas.len(), |i, k| {
        let d = s[i] * s[i] + lambdas[k];
        match d > 0.0 && s[i] > 0.0 {
            true => -sg[i] / d,
            false => 0.0,
        }
    });
    Ok(z_t.transpose() * weights)
}

fn not_converged() -> Error {
    Error::NotFinite {
        what: "the error maps' SVD did not converge".into(),
    }
}
