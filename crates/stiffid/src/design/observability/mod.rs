//! Design for calibration: how well a group of postures determines the calibration's parameters
//! (geometry, gravity, compliance) and how accurate the calibrated robot will be.
//!
//! # The Jacobian the criteria read
//! A calibration campaign reads every measuring point at every posture of the group. Its
//! identification Jacobian `J` ([`ErrorModel::jacobian`], 3 rows per reading) is column-scaled
//! as the calibration scales it ([`ErrorModel::column_scales`], with the characteristic length
//! and the gravity regressors' RMS over the reference postures), and reduced to the parameters
//! the calibration identifies: those [`identifiability::analyse`] keeps on the Jacobian of the
//! reference postures (a generic campaign over the joint ranges), the merged ones left out as the
//! calibration leaves them at their nominal values. The kept set is fixed once, so that every
//! group is scored on the same parameters: a group that does not separate them has a zero
//! smallest singular value, not a smaller model. `J_s` is that scaled, reduced Jacobian
//! (`3 n_p n_k x p`, `n` postures, `n_k` points, `p` kept parameters) with singular values
//! `sigma_1 >= ... >= sigma_p`.
//!
//! # The criteria (docs/model.md, "Design for calibration")
//! The observability indices of Sun and Hollerbach 2008 (their numbering), larger is better:
//!
//! ```text
//! O1 = (sigma_1 ... sigma_p)^(1/p) / sqrt(n)      (Borm and Menq 1991; a root to stay finite)
//! O3 = sigma_p                                     (Nahvi and Hollerbach 1996, MinSV)
//! O4 = sigma_p^2 / sigma_1                         (noise amplification, Nahvi and Hollerbach 1996)
//! O5 = 1 / (1/sigma_1 + ... + 1/sigma_p)           (Sun and Hollerbach 2008, inverse sum)
//! D  = det(J_s^T J_s)^(1/p) = (sigma_1 ... sigma_p)^(2/p)   (D-optimality)
//! ```
//!
//! and the one a user cares about, smaller is better: the predicted RMS position error after the
//! calibration at the test postures (the machining region), every measuring point at each,
//!
//! ```text
//! e_rms^2 = sigma^2 tr(A_0 (J_s^T J_s)^-1 A_0^T) / m_0 = sigma^2 |A_0 V S^-1|_F^2 / m_0
//! ```
//!
//! with `A_0` the scaled, reduced identification Jacobian at the test postures (`m_0` readings),
//! `J_s = U S V^T` (the SVD: never the normal equations) and `sigma` the tracker's noise per
//! coordinate: the expected squared position error of a reading predicted by a least-squares
//! calibration under independent noise (the test-pose criterion of Klimchik, Pashkevich et al.
//! applied to calibration). It does not depend on the column scaling.

use crate::math::linalg::CappedSvd;
use crate::metrology::calibration::identifiability;
use crate::metrology::calibration::ErrorModel;
use crate::{Error, Result};
use jacobian::Layout;
use nalgebra::{DMatrix, Vector6};
use serde::Serialize;

mod jacobian;
mod score;
#[cfg(test)]
mod tests;

pub use score::CalibrationCriterion;

/// A singular value below this share of the largest counts as zero: the group does not
/// separate the kept parameters.
pub const RANK_TOLERANCE: f64 = 1e-10;

/// The calibration criteria of a group of postures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CalibrationCriteria {
    /// The kept parameters' count `p`.
    pub parameters: usize,
    /// `O1`, the geometric mean of the singular values over `sqrt(n)` (m: a scaled column is a
    /// position change).
    pub o1: f64,
    /// `O3`, the smallest singular value (m).
    pub o3: f64,
    /// `O4`, the smallest singular value squared over the largest (m).
    pub o4: f64,
    /// `O5`, the inverse of the sum of the singular values' inverses (m).
    pub o5: f64,
    /// D-optimality, `det(J_s^T J_s)^(1/p)` (m^2).
    pub d_optimality: f64,
    /// The predicted RMS position error after calibration at the test postures (m); infinite
    /// when the group does not separate the parameters.
    pub predicted_rms: f64,
}

/// A design problem for calibration: the error model, its kept parameters and scaling, and the
/// test postures' Jacobian.
#[derive(Debug, Clone)]
pub struct CalibrationDesign {
    layout: Layout,
    kept: Vec<usize>,
    test: DMatrix<f64>,
    /// `H = A_0^T A_0 = R_A^T R_A` (`p x p`) from the QR `A_0 = Q_A R_A` of `test`.
    test_information: DMatrix<f64>,
    noise: f64,
}

impl CalibrationDesign {
    /// The design problem of `model` with the characteristic length `length` (m), the reference
    /// postures `reference` (axis angles, rad: a generic campaign that fixes the kept parameters
    /// and the gravity terms' scaling), the test postures `test` (rad: the machining region) and
    /// the tracker's noise `noise` per coordinate (m). Every measuring point is read at every
    /// posture.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`length`, `noise`) for a value not positive and finite,
    /// (`postures`) with no reference or test posture; those of [`ErrorModel::jacobian`] and
    /// [`identifiability::analyse`].
    pub fn new(
        model: ErrorModel,
        length: f64,
        reference: &[Vector6<f64>],
        test: &[Vector6<f64>],
        noise: f64,
    ) -> Result<Self> {
        for (field, v) in [("length", length), ("noise", noise)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::InvalidField {
                    field: field.into(),
                    message: format!("expected a positive number, got {v}"),
                });
            }
        }
        if reference.is_empty() || test.is_empty() {
            return Err(Error::InvalidField {
                field: "postures".into(),
                message: "expected at least one reference and one test posture".into(),
            });
        }
        let scales = model.column_scales(length, reference);
        let priorities: Vec<u8> = model.parameters().iter().map(|p| p.priority).collect();
        let j = model.jacobian(&rigid(&model), &pairs(&model, reference))?;
        let kept = identifiability::analyse(&j, &scales, &priorities)?.identified;
        let scales: Vec<f64> = kept.iter().map(|&c| scales[c]).collect();
        let layout = Layout::new(model, &kept, scales);
        let mut design = CalibrationDesign {
            layout,
            kept,
            test: DMatrix::zeros(0, 0),
            test_information: DMatrix::zeros(0, 0),
            noise,
        };
        design.test = design.jacobian(test)?;
        let r_a = score::triangular_factor(&design.test);
        design.test_information = r_a.tr_mul(&r_a);
        Ok(design)
    }

    /// The error model.
    pub fn model(&self) -> &ErrorModel {
        &self.layout.model
    }

    /// The kept parameters' indices (in [`ErrorModel::parameters`]), ascending.
    pub fn kept(&self) -> &[usize] {
        &self.kept
    }

    /// The tracker's noise per coordinate, m.
    pub fn noise(&self) -> f64 {
        self.noise
    }

    /// The scaled identification Jacobian of the kept parameters at `postures` (rad), every
    /// measuring point at each: 3 rows per (posture, point), posture-major, m per scaled unit;
    /// on the nominal chain at the commanded postures (no deflection under gravity: the
    /// gravity terms' values do not enter).
    ///
    /// # Errors
    /// [`Error::NotFinite`] for a non-finite posture.
    pub fn jacobian(&self, postures: &[Vector6<f64>]) -> Result<DMatrix<f64>> {
        if !postures.iter().all(|q| q.iter().all(|v| v.is_finite())) {
            return Err(Error::NotFinite {
                what: "a posture of the calibration design".into(),
            });
        }
        let l = &self.layout;
        let mut j = DMatrix::zeros(l.rows(postures.len()), self.kept.len());
        let rows = l.rows(1);
        for (i, q) in postures.iter().enumerate() {
            l.write_rows(&l.posture(q), &mut j, rows * i);
        }
        Ok(j)
    }

    /// The criteria of the group `postures` (rad; module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`postures`) with no posture; those of
    /// [`CalibrationDesign::jacobian`] and [`criteria`].
    pub fn evaluate(&self, postures: &[Vector6<f64>]) -> Result<CalibrationCriteria> {
        if postures.is_empty() {
            return Err(Error::InvalidField {
                field: "postures".into(),
                message: "expected at least one posture".into(),
            });
        }
        criteria(
            &self.jacobian(postures)?,
            postures.len(),
            &self.test,
            self.noise,
        )
    }

    /// The value of `criterion` for `postures` (rad) as a search minimises it
    /// ([`CalibrationCriterion::loss`]): `+infinity` for a group that does not separate the
    /// kept parameters or a non-finite posture.
    pub fn value(&self, criterion: CalibrationCriterion, postures: &[Vector6<f64>]) -> f64 {
        match self.jacobian(postures) {
            Ok(j) => score::Scored::new(j, criterion, self).map_or(f64::INFINITY, |s| s.value),
            Err(_) => f64::INFINITY,
        }
    }

    /// [`CalibrationDesign::value`] and the exact gradient of its logarithm with respect to
    /// every posture's axis angles (1/rad, one per posture; zero for an infinite value), from
    /// the derivative of the criterion with respect to the Jacobian (`score`) and of the
    /// Jacobian with respect to the postures (`jacobian`).
    pub fn value_and_log_gradient(
        &self,
        criterion: CalibrationCriterion,
        postures: &[Vector6<f64>],
    ) -> (f64, Vec<Vector6<f64>>) {
        let zero = vec![Vector6::zeros(); postures.len()];
        if !postures.iter().all(|q| q.iter().all(|v| v.is_finite())) {
            return (f64::INFINITY, zero);
        }
        let l = &self.layout;
        let terms: Vec<_> = postures.iter().map(|q| l.posture(q)).collect();
        let rows = l.rows(1);
        let mut j = DMatrix::zeros(l.rows(postures.len()), self.kept.len());
        for (i, t) in terms.iter().enumerate() {
            l.write_rows(t, &mut j, rows * i);
        }
        let Some(scored) = score::Scored::new(j, criterion, self) else {
            return (f64::INFINITY, zero);
        };
        let g = scored.log_gradient(self);
        let gradient = (terms.iter().enumerate())
            .map(|(i, t)| l.gradient(t, &scored.j, &g, rows * i))
            .collect();
        (scored.value, gradient)
    }
}

/// The model's nominal values with the gravity terms at zero: the rigid nominal chain, where the
/// design Jacobian is taken.
fn rigid(model: &ErrorModel) -> nalgebra::DVector<f64> {
    let mut x = model.nominal();
    x.rows_mut(model.gravity_start(), model.gravity().len())
        .fill(0.0);
    x
}

/// Every measuring point of `model` at every posture, posture-major.
fn pairs(model: &ErrorModel, postures: &[Vector6<f64>]) -> Vec<(Vector6<f64>, usize)> {
    (postures.iter())
        .flat_map(|q| (0..model.points()).map(move |k| (*q, k)))
        .collect()
}

/// The criteria of the scaled, reduced Jacobian `j` of a group of `postures` postures, with the
/// test postures' Jacobian `test` (same columns) and the noise `noise` per coordinate (m; module
/// docs). A group with fewer rows than columns or a singular value below [`RANK_TOLERANCE`] of
/// the largest scores `O3 = O4 = 0` and an infinite predicted error.
///
/// # Errors
/// [`Error::InvalidField`] (`parameters`) when `test` has other columns than `j`;
/// [`Error::NotFinite`] when `j` is not finite or its SVD does not converge.
pub fn criteria(
    j: &DMatrix<f64>,
    postures: usize,
    test: &DMatrix<f64>,
    noise: f64,
) -> Result<CalibrationCriteria> {
    let p = j.ncols();
    if test.ncols() != p {
        return Err(Error::InvalidField {
            field: "parameters".into(),
            message: format!("expected {p} test columns, got {}", test.ncols()),
        });
    }
    let not_finite = || Error::NotFinite {
        what: "the calibration design's Jacobian".into(),
    };
    if !j.iter().all(|v| v.is_finite()) {
        return Err(not_finite());
    }
    let svd = j.clone().capped_svd(false, true).ok_or_else(not_finite)?;
    let mut s: Vec<f64> = svd.singular_values.iter().copied().collect();
    s.resize(p, 0.0);
    s.sort_by(|a, b| b.total_cmp(a));
    let largest = s.first().copied().unwrap_or(0.0);
    let singular = p == 0 || s[p - 1] <= RANK_TOLERANCE * largest;
    let mean_log = s.iter().map(|v| v.ln()).sum::<f64>() / p.max(1) as f64;
    let predicted_rms = match singular {
        true => f64::INFINITY,
        false => {
            let v_t = svd.v_t.ok_or_else(not_finite)?;
            let inverse = DMatrix::from_diagonal(&svd.singular_values.map(|v| 1.0 / v));
            let spread = test * v_t.transpose() * inverse;
            noise * (spread.norm_squared() / (test.nrows() / 3).max(1) as f64).sqrt()
        }
    };
    Ok(CalibrationCriteria {
        parameters: p,
        o1: mean_log.exp() / (postures.max(1) as f64).sqrt(),
        o3: if singular { 0.0 } else { s[p - 1] },
        o4: if singular {
            0.0
        } else {
            s[p - 1].powi(2) / largest
        },
        o5: if singular {
            0.0
        } else {
            1.0 / s.iter().map(|v| 1.0 / v).sum::<f64>()
        },
        d_optimality: (2.0 * mean_log).exp(),
        predicted_rms,
    })
}
