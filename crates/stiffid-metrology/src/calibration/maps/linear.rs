//! The calibration linearised at a fit, and the held-out errors of any choice of maps on any split
//! of its postures (module docs of [`super`], "Cross-validation on the linearised fit").
//!
//! With `r` the residuals at the fit, `G` the scaled columns of the fitted parameters and `M` the
//! scaled columns of the candidate maps, a split's training rows `T` give the geometry's columns
//! `G_T = U S V^T` (SVD, the part below `1e-10` of the largest singular value dropped) and, for
//! the map columns `M_T` of a choice, `P M_T = M_T - U U^T M_T = W Sigma Z^T` (SVD); the ridge
//! `lambda` gives the maps' step `y = -Z diag(sigma / (sigma^2 + lambda)) W^T P r_T`, the
//! geometry's `-V S^-1 U^T (r_T + M_T y)`, and the held-out rows `V` the errors
//!
//! ```text
//! e_V = (r_V - A U^T r_T) + (M_V - A U^T M_T) y,        A = G_V V S^-1
//! ```
//!
//! exactly the least squares of the linearised model with the ridge rows on the maps alone, for
//! every `lambda` from one SVD (never the normal equations).

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
    train: Vec<usize>,
    test: Vec<usize>,
    /// The postures of the test rows (index into the split's test postures), one per row.
    test_posture: Vec<usize>,
    u: DMatrix<f64>,
    a: DMatrix<f64>,
    /// `r_V - A U^T r_T`.
    base: DVector<f64>,
    /// `P r_T`.
    projected: DVector<f64>,
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
        Ok(Split {
            base: r_v - &a * &utr,
            projected: r_t - &u * utr,
            train: train_rows,
            test: test_rows,
            test_posture,
            u,
            a,
        })
    }

    /// The map columns of `choice` on `rows`.
    fn columns(&self, choice: &JointMaps, rows: &[usize]) -> DMatrix<f64> {
        let mut cols = Vec::new();
        for (j, &h) in choice.harmonics.iter().enumerate().filter(|&(_, &h)| h > 0) {
            cols.extend(
                (0..h)
                    .chain(self.harmonics..self.harmonics + h)
                    .map(|c| (j, c)),
            );
        }
        for j in (0..6).filter(|&j| choice.backlash[j]) {
            cols.push((j, self.maps[j].ncols() - 1));
        }
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
        let m_t = self.columns(choice, &split.train);
        let m_v = self.columns(choice, &split.test);
        let utm = split.u.tr_mul(&m_t);
        let pm = m_t - &split.u * &utm;
        let mv = m_v - &split.a * utm;
        let svd = pm.capped_svd(true, true).ok_or_else(not_converged)?;
        let (w, z_t) = (
            svd.u.ok_or_else(not_converged)?,
            svd.v_t.ok_or_else(not_converged)?,
        );
        let g = w.tr_mul(&split.projected);
        let mvz = mv * z_t.transpose();
        Ok(lambdas
            .iter()
            .map(|&lambda| {
                let weights = DVector::from_iterator(
                    g.len(),
                    (svd.singular_values.iter().zip(g.iter())).map(|(s, g)| {
                        let d = s * s + lambda;
                        match d > 0.0 {
                            true => -s * g / d,
                            false => 0.0,
                        }
                    }),
                );
                per_posture(&(&split.base + &mvz * weights))
            })
            .collect())
    }
}

fn not_converged() -> Error {
    Error::NotFinite {
        what: "the error maps' SVD did not converge".into(),
    }
}
