//! The calibration linearised at a fit, and the held-out errors of any choice of maps on any split
//! of its postures (module docs of [`super`], "Cross-validation on the linearised fit").
//!
//! With `r` the residuals at the fit, `G` the scaled columns of the fitted parameters and `M` the
//! scaled columns of the candidate maps, a split's training rows `T` give the geometry's columns
//! `G_T = U S V^T` (SVD, the part below `1e-10` of the largest singular value dropped) and, for
//! the map columns `M_T` of a choice, `A_M = P M_T = M_T - U U^T M_T`; the ridge `lambda` gives
//! the maps' step `y = -argmin |A_M y - P r_T|^2 + lambda |y|^2`, the geometry's
//! `-V S^-1 U^T (r_T + M_T y)`, and the held-out rows `V` the errors
//!
//! ```text
//! e_V = (r_V - A U^T r_T) + (M_V - A U^T M_T) y,        A = G_V V S^-1
//! ```
//!
//! exactly the least squares of the linearised model with the ridge rows on the maps alone (the
//! geometry's columns by SVD, never their normal equations). The held-out rows' map columns `M_V`
//! are tapered beyond the training postures' range of their axis's angle
//! ([`stiffid_core::robot::error_map::taper`], the backlash term's kept), as the calibrated
//! robot's maps taper beyond the fitted postures' range: a split predicts its held-out postures as
//! the calibrated robot predicts a new one.
//!
//! A split projects every candidate column once (`P M_T` and `M_V - A U^T M_T`, all joints; a
//! choice of fixed maps or none scores on [`Linear::restricted`] to its own columns) and keeps the
//! Householder QR `C^T M_T = Q R` as `R` and `Q^T C^T r_T` (`C^T r_T` taken through the
//! reflections as one more column, `Q` never formed), `P = C C^T`: where the `m` training rows
//! are fewer than the geometry's `p` kept columns and the candidates' together, `C` is the
//! orthonormal complement of `U` and `C^T M_T` is `P M_T` in its `m - p` coordinates (the rows
//! `P` does not zero; the reflections that reduce `U` give them), elsewhere `P M_T` itself
//! (`C = P`, `m` rows). A choice's projected columns are `C Q S`, `S` its columns of `R` (their
//! rows down to the last chosen column), so its ridge least squares is that of `S` with
//! `Q^T C^T r_T`, exactly. The maps' step follows Eldén's method (L. Eldén, "Algorithms
//! for the regularization of ill-conditioned least squares problems", BIT 17, 1977): one
//! bidiagonalisation `S = W B Z^T` per choice (of `S^T` where `S` has fewer rows than columns;
//! `W` and `Z` kept as their reflections and applied to the right-hand side and the steps),
//! then per `lambda` the ridge `min |B z - W^T Q^T C^T r_T|^2 + lambda |z|^2` by Givens rotations
//! of `[B; sqrt(lambda) I]` in `O(k)` (two per column, `k` the order of `B`), `y = -Z z`:
//! orthogonal transformations throughout, never the ridge's normal equations, at any `lambda > 0`.
//! It agrees with the augmented system solved directly to `1e-9` of the held-out errors from the
//! least ridge a calibration takes, and to the system's own condition at a ridge of `1e-12`
//! (`maps_kernel_tests.rs`).

use super::super::error_model::{JointMaps, Observation, Target};
use super::super::fit::Fit;
use super::super::reflections::{bidiagonal_ridge, Bidiagonal};
use super::super::{ErrorModel, Estimate};
use nalgebra::{DMatrix, DVector, Vector6};
use stiffid_core::math::householder;
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::robot::error_map;
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
    /// The axis angles of each posture, in posture order (rad): a split tapers its held-out rows'
    /// map columns beyond its training postures' range as the calibrated robot's maps taper
    /// beyond the fitted postures' ([`Linear::split`]).
    pub angles: Vec<Vector6<f64>>,
}

/// A split's training part, prepared once for every choice of maps.
pub struct Split {
    /// The postures of the test rows (index into the split's test postures), one per row.
    test_posture: Vec<usize>,
    /// `r_V - A U^T r_T`.
    base: DVector<f64>,
    /// `R` of the Householder QR `C^T M_T = Q R` of every candidate map column (all of
    /// [`Linear::maps`]' columns, joint after joint; at most `m - p` or `m` rows, upper
    /// trapezoidal; module docs): a choice's projected columns are `C Q` times its columns of `R`.
    factor: DMatrix<f64>,
    /// `Q^T C^T r_T` (the rows of [`Split::factor`]).
    rotated: DVector<f64>,
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
    /// Those of [`ErrorModel::with_maps`], `ErrorModel::residuals` and
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
        let mut angles = vec![Vector6::zeros(); postures.len()];
        for (i, o) in observations.iter().enumerate() {
            if let Ok(p) = postures.binary_search(&o.posture) {
                rows[p].extend(3 * i..3 * i + 3);
                angles[p] = o.q;
            }
        }
        Ok(Linear {
            residuals,
            geometry,
            maps,
            harmonics: largest,
            candidates: harmonics,
            rows,
            angles,
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
        let all = self.all_columns();
        let m_t = self.columns_of(&all, &train_rows);
        let utm = u.tr_mul(&m_t);
        let held_maps = self.tapered(&all, test, train) - &a * &utm;
        let (factor, rotated) = compressed(&u, (m_t, &utm), (&r_t, &utr));
        Ok(Split {
            base: r_v - &a * &utr,
            rotated,
            factor,
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
            angles: self.angles.clone(),
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

    /// The map columns `cols` on the rows of the postures `test`, each joint's series columns
    /// tapered beyond the `train` postures' range of its axis angle as the calibrated robot's map
    /// tapers beyond the fitted postures' ([`error_map::taper`]; its backlash term kept): a
    /// held-out posture beyond the training range is predicted as the calibrated robot predicts a
    /// posture beyond the fitted range.
    fn tapered(&self, cols: &[(usize, usize)], test: &[usize], train: &[usize]) -> DMatrix<f64> {
        let range = |j: usize| {
            (train.iter().map(|&p| self.angles[p][j]))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                })
        };
        let ranges: [(f64, f64); 6] = std::array::from_fn(range);
        let mut rows = Vec::new();
        let mut weights: Vec<[f64; 6]> = Vec::new();
        for &p in test {
            let w: [f64; 6] =
                std::array::from_fn(|j| error_map::taper(self.angles[p][j], ranges[j]));
            rows.extend(self.rows[p].iter().copied());
            weights.extend(std::iter::repeat_n(w, self.rows[p].len()));
        }
        let mut m = self.columns_of(cols, &rows);
        for (c, &(j, k)) in cols.iter().enumerate() {
            if k < 2 * self.sine(j) {
                for r in 0..rows.len() {
                    m[(r, c)] *= weights[r][j];
                }
            }
        }
        m
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
    /// [`Error::NotFinite`] when a step is not finite (a residual, a column or a ridge not
    /// finite).
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
        let steps = ridge_steps(split, &chosen, lambdas);
        if steps.iter().any(|v| !v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the error maps' ridge steps".into(),
            });
        }
        let moved = split.held_maps.select_columns(chosen.iter()) * steps;
        Ok((0..lambdas.len())
            .map(|k| per_posture(&(&split.base + moved.column(k))))
            .collect())
    }
}

/// The maps' steps `y = -argmin |A y - P r_T|^2 + lambda |y|^2` of the columns `chosen` (`A`
/// their `P M_T`, `C Q S` with `S` their columns of the split's `R`) at each `lambda > 0` (one
/// column each), by Eldén's method: one bidiagonalisation `S = W B Z^T` (`B` upper bidiagonal,
/// `k = min(rows, columns)`), then per `lambda` the ridge of `B` in `O(k)` ([`bidiagonal_ridge`]),
/// `y = -Z z`. Where `S` has fewer rows than columns, `S^T` is bidiagonalised and `B^T` (lower)
/// solved with its rows and columns in reverse order (upper).
fn ridge_steps(split: &Split, chosen: &[usize], lambdas: &[f64]) -> DMatrix<f64> {
    // `R`'s rows below the last chosen column are zero in the chosen columns.
    let rows = chosen.iter().max().map_or(0, |&c| c + 1);
    let rows = rows.min(split.factor.nrows());
    let mut steps = DMatrix::zeros(chosen.len(), lambdas.len());
    if rows == 0 {
        return steps;
    }
    let s = split.factor.rows(0, rows).select_columns(chosen.iter());
    let mut c: Vec<f64> = split.rotated.rows(0, rows).iter().copied().collect();
    let tall = rows >= chosen.len();
    let bi = match tall {
        true => Bidiagonal::new(s.as_slice().to_vec(), rows),
        false => Bidiagonal::new(s.transpose().as_slice().to_vec(), chosen.len()),
    };
    // The ridge of `B z = c'`: tall, `c' = W^T c` (its first `k`), `y = Z z`; wide
    // (`S^T = W B Z^T`), `B^T z = Z^T c`, `y = W z`, reversed.
    match tall {
        true => bi.left_tr(&mut c),
        false => bi.right_tr(&mut c),
    }
    let k = bi.diagonal.len();
    c.truncate(k);
    let order = |x: &[f64]| -> Vec<f64> {
        match tall {
            true => x.to_vec(),
            false => x.iter().rev().copied().collect(),
        }
    };
    let (d, e, c) = (order(&bi.diagonal), order(&bi.upper), order(&c));
    for (i, &lambda) in lambdas.iter().enumerate() {
        let mut z = bidiagonal_ridge(&d, &e, &c, lambda);
        let y = match tall {
            true => {
                bi.right(&mut z);
                z
            }
            false => {
                z.reverse();
                z.resize(chosen.len(), 0.0);
                bi.left(&mut z);
                z
            }
        };
        steps.set_column(i, &(-DVector::from_vec(y)));
    }
    steps
}

/// The QR of a split's projected map columns `P M_T` (`P = I - U U^T`, `u` the geometry's
/// orthonormal `m x p` columns `U`; `utm = U^T M_T`, `utr = U^T r_T`) with `P r_T`: `R`
/// (`min(rows, n) x n`, upper trapezoidal) and the first `min(rows, n)` entries of the
/// right-hand side taken through the same reflections as one more column (module docs).
///
/// Where `m - p < n`, in the coordinates of the complement of `U`: the `p` reflections that
/// reduce `U` take `[M_T | r_T]` to `[U^T; C^T] [M_T | r_T]` (up to the signs of `U^T`'s rows),
/// `C` (`m x (m - p)`) orthonormal with `P = C C^T`, so `|P (M_T y - r_T)| = |C^T M_T y - C^T
/// r_T|`: the least squares in `m - p` rows (`rows`), without the `p` rows `P` leaves zero, and
/// every choice's bidiagonalisation that much smaller. Elsewhere `R` has `n` rows either way and
/// `P M_T` is formed by matrix products (`rows = m`), faster than `p` reflections through
/// columns of `m` rows.
fn compressed(
    u: &DMatrix<f64>,
    (m_t, utm): (DMatrix<f64>, &DMatrix<f64>),
    (r_t, utr): (&DVector<f64>, &DVector<f64>),
) -> (DMatrix<f64>, DVector<f64>) {
    let (m, p) = u.shape();
    let n = m_t.ncols();
    let (mut c, rows) = match m - p >= n {
        true => {
            let mut a = (m_t - u * utm).insert_column(n, 0.0);
            a.set_column(n, &(r_t - u * utr));
            (a.as_slice().to_vec(), m)
        }
        false => (complement(u, &m_t, r_t), m - p),
    };
    let k = rows.min(n);
    if k > 0 {
        householder::qr(&mut c, rows, k);
    }
    let factor = DMatrix::from_fn(k, n, |r, j| if r <= j { c[j * rows + r] } else { 0.0 });
    (factor, DVector::from_fn(k, |r, _| c[n * rows + r]))
}

/// `C^T [M_T | r_T]` (column-major, `m - p` rows) of [`compressed`]: `[U | M_T | r_T]` through
/// the `p` reflections that reduce `U`, the rows below `p` of the columns after `U`.
fn complement(u: &DMatrix<f64>, m_t: &DMatrix<f64>, r_t: &DVector<f64>) -> Vec<f64> {
    let (m, p) = u.shape();
    let mut a = Vec::with_capacity(m * (p + m_t.ncols() + 1));
    a.extend_from_slice(u.as_slice());
    a.extend_from_slice(m_t.as_slice());
    a.extend_from_slice(r_t.as_slice());
    householder::qr(&mut a, m, p);
    (a[p * m..].chunks_exact(m))
        .flat_map(|column| column[p..].iter().copied())
        .collect()
}

fn not_converged() -> Error {
    Error::NotFinite {
        what: "the error maps' SVD did not converge".into(),
    }
}
