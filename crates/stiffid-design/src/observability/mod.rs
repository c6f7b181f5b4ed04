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

use jacobian::Layout;
use nalgebra::{DMatrix, Vector6};
use serde::Serialize;
use std::sync::Arc;
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::{Error, Result};
use stiffid_metrology::calibration::error_model::Observation;
use stiffid_metrology::calibration::identifiability;
use stiffid_metrology::calibration::ErrorModel;

mod jacobian;
mod score;
mod station;
mod table;

pub use score::CalibrationCriterion;
pub use table::TableDesign;

/// A singular value below this share of the largest counts as zero: the group does not
/// separate the kept parameters.
pub(crate) const RANK_TOLERANCE: f64 = 1e-10;

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

/// A posture where it is read: axis angles (rad) and the external axes' values (SI, the cell's
/// order; [`ExternalValues::NONE`] without external axes).
pub type Placed = (Vector6<f64>, ExternalValues);

/// A design problem for calibration: the error model, its kept parameters and scaling, and the
/// test postures' Jacobian; on a cell with a carrier (a track), where the group is read and the
/// campaign's postures already chosen ([`CalibrationDesign::on_station`]).
#[derive(Debug, Clone)]
pub struct CalibrationDesign {
    layout: Layout,
    kept: Vec<usize>,
    test: DMatrix<f64>,
    /// Where the group scored stands (the external axes' values, SI).
    station: ExternalValues,
    /// The scaled rows of the table reflectors' readings at the positioner's angles (`table`; 0
    /// rows without), the first of `fixed`.
    table: DMatrix<f64>,
    /// The scaled Jacobian of the table's readings and of the campaign's postures chosen already
    /// (0 rows without), stacked above the group's, and the postures' count.
    fixed: DMatrix<f64>,
    fixed_postures: usize,
    /// `F^T F` of the fixed rows `F` (`p x p`; zero without): added to every group's
    /// information, so a search's step forms the group's alone.
    fixed_information: DMatrix<f64>,
    /// `H = A_0^T A_0 = R_A^T R_A` (`p x p`) from the QR `A_0 = Q_A R_A` of `test`.
    test_information: DMatrix<f64>,
    noise: f64,
    /// What the carrier columns eliminated add, on a reduced design (`station`).
    schur: station::Schur,
    /// A step at one station with a carrier, reduced to the arm's columns (`station`): what
    /// [`CalibrationDesign::value`] and its gradient score O1, D-optimality and the predicted
    /// error on.
    reduced: Option<Arc<CalibrationDesign>>,
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
        let placed = |qs: &[Vector6<f64>]| -> Vec<Placed> {
            qs.iter().map(|q| (*q, ExternalValues::NONE)).collect()
        };
        Self::new_placed(model, length, &placed(reference), &placed(test), noise)
    }

    /// [`CalibrationDesign::new`] with each reference and test posture read where the cell's
    /// external axes stand ([`Placed`]): for a model with a carrier's parameters
    /// ([`ErrorModel::with_external`]), the reference postures spread over its travel decide
    /// which of the track's parameters a campaign can separate. The group scored stands at the
    /// first reference posture's station until [`CalibrationDesign::on_station`] moves it.
    ///
    /// # Errors
    /// As [`CalibrationDesign::new`].
    pub fn new_placed(
        model: ErrorModel,
        length: f64,
        reference: &[Placed],
        test: &[Placed],
        noise: f64,
    ) -> Result<Self> {
        Self::build(model, length, reference, test, noise, None)
    }

    /// [`CalibrationDesign::new_placed`] for a model with reflectors on the positioner's table
    /// ([`ErrorModel::with_external`]): the Jacobian taken with the reflectors where `table`
    /// puts them, the table read at `table.reference` too (in the reference campaign, and as
    /// the fixed rows of every group until [`CalibrationDesign::with_table_angles`] replaces
    /// them), and the test rows with every reflector as a point of the part at each reference
    /// angle (module `table`).
    ///
    /// # Errors
    /// As [`CalibrationDesign::new`]; [`Error::InvalidField`] (`table`) for another count of
    /// reflectors than the model's, or no reference angle.
    pub fn new_with_table(
        model: ErrorModel,
        length: f64,
        reference: &[Placed],
        test: &[Placed],
        noise: f64,
        table: &TableDesign,
    ) -> Result<Self> {
        Self::build(model, length, reference, test, noise, Some(table))
    }

    /// [`CalibrationDesign::new_placed`], with `table` when the model has table reflectors
    /// ([`TableDesign`]).
    fn build(
        model: ErrorModel,
        length: f64,
        reference: &[Placed],
        test: &[Placed],
        noise: f64,
        table: Option<&TableDesign>,
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
        let qs: Vec<Vector6<f64>> = reference.iter().map(|p| p.0).collect();
        let scales = model.column_scales(length, &qs);
        let priorities: Vec<u8> = model.parameters().iter().map(|p| p.priority).collect();
        let mut values = rigid(&model);
        let mut observations = readings(&model, reference);
        if let Some(t) = table {
            t.place(&model, &mut values)?;
            observations.extend(table::readings(model.tables(), &t.reference));
        }
        let j = model.jacobian_of(&values, &observations)?;
        let kept = identifiability::analyse(&j, &scales, &priorities)?.identified;
        let scales: Vec<f64> = kept.iter().map(|&c| scales[c]).collect();
        let layout = Layout::new(model, &kept, scales, values);
        let mut design = CalibrationDesign {
            layout,
            kept,
            test: DMatrix::zeros(0, 0),
            station: reference[0].1,
            table: DMatrix::zeros(0, 0),
            fixed: DMatrix::zeros(0, 0),
            fixed_postures: 0,
            fixed_information: DMatrix::zeros(0, 0),
            test_information: DMatrix::zeros(0, 0),
            noise,
            schur: station::Schur::default(),
            reduced: None,
        };
        let p = design.kept.len();
        (design.fixed, design.fixed_information) = (DMatrix::zeros(0, p), DMatrix::zeros(p, p));
        design.table = DMatrix::zeros(0, p);
        design.test = design.jacobian_placed(test)?;
        if let Some(t) = table {
            design.test = stack(&design.test, &design.table_rows(&t.reference, true)?);
            design = design.with_table_angles(&t.reference)?;
        }
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

    /// This design scored on the whole Jacobian, every column, not reduced: what the reduced
    /// scoring equals.
    #[cfg(test)]
    pub(crate) fn whole(&self) -> CalibrationDesign {
        CalibrationDesign {
            reduced: None,
            ..self.clone()
        }
    }

    /// The design of a campaign's next group: read at `station` (the external axes' values, SI,
    /// the cell's order), after the postures `chosen` (read where each stands), whose rows join
    /// every group's in the criteria (their count too).
    ///
    /// # Errors
    /// Those of `CalibrationDesign::jacobian`.
    pub fn on_station(&self, station: ExternalValues, chosen: &[Placed]) -> Result<Self> {
        let fixed = stack(&self.table, &self.jacobian_placed(chosen)?);
        let mut design = CalibrationDesign {
            station,
            fixed_information: fixed.tr_mul(&fixed),
            fixed,
            fixed_postures: chosen.len(),
            reduced: None,
            ..self.clone()
        };
        design.reduced = station::reduce(&design).map(Arc::new);
        Ok(design)
    }

    /// The scaled Jacobian of the kept parameters at `postures`, each read where it stands
    /// ([`CalibrationDesign::jacobian`]).
    ///
    /// # Errors
    /// [`Error::NotFinite`] for a non-finite posture.
    pub(crate) fn jacobian_placed(&self, postures: &[Placed]) -> Result<DMatrix<f64>> {
        if !(postures.iter()).all(|(q, e)| q.iter().chain(e.as_slice()).all(|v| v.is_finite())) {
            return Err(Error::NotFinite {
                what: "a posture of the calibration design".into(),
            });
        }
        let l = &self.layout;
        let mut j = DMatrix::zeros(l.rows(postures.len()), self.kept.len());
        let rows = l.rows(1);
        for (i, (q, e)) in postures.iter().enumerate() {
            l.write_rows(&l.posture(q, e.as_slice()), &mut j, rows * i);
        }
        Ok(j)
    }

    /// The fixed rows stacked above `j` (for the criteria that factor the whole Jacobian).
    fn with_fixed(&self, j: DMatrix<f64>) -> DMatrix<f64> {
        match self.fixed.nrows() {
            0 => j,
            _ => stack(&self.fixed, &j),
        }
    }

    /// The scaled identification Jacobian of the kept parameters at `postures` (rad), every
    /// measuring point at each: 3 rows per (posture, point), posture-major, m per scaled unit;
    /// on the nominal chain at the commanded postures (no deflection under gravity: the
    /// gravity terms' values do not enter).
    ///
    /// # Errors
    /// [`Error::NotFinite`] for a non-finite posture.
    pub(crate) fn jacobian(&self, postures: &[Vector6<f64>]) -> Result<DMatrix<f64>> {
        let placed: Vec<Placed> = postures.iter().map(|q| (*q, self.station)).collect();
        self.jacobian_placed(&placed)
    }

    /// The criteria of the group `postures` (rad; module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`postures`) with no posture; those of
    /// `CalibrationDesign::jacobian` and `criteria`.
    pub fn evaluate(&self, postures: &[Vector6<f64>]) -> Result<CalibrationCriteria> {
        if postures.is_empty() {
            return Err(Error::InvalidField {
                field: "postures".into(),
                message: "expected at least one posture".into(),
            });
        }
        criteria(
            &self.with_fixed(self.jacobian(postures)?),
            self.fixed_postures + postures.len(),
            &self.test,
            self.noise,
        )
    }

    /// The criteria of a campaign's `postures`, each read where it stands (module docs), after
    /// the fixed postures of [`CalibrationDesign::on_station`] (none on a new design).
    ///
    /// # Errors
    /// As [`CalibrationDesign::evaluate`].
    pub fn evaluate_placed(&self, postures: &[Placed]) -> Result<CalibrationCriteria> {
        if postures.is_empty() {
            return Err(Error::InvalidField {
                field: "postures".into(),
                message: "expected at least one posture".into(),
            });
        }
        let j = self.with_fixed(self.jacobian_placed(postures)?);
        criteria(
            &j,
            self.fixed_postures + postures.len(),
            &self.test,
            self.noise,
        )
    }

    /// `CalibrationDesign::value` of a campaign's `postures`, each read where it stands, after
    /// the fixed postures of [`CalibrationDesign::on_station`] (none on a new design).
    pub fn value_placed(&self, criterion: CalibrationCriterion, postures: &[Placed]) -> f64 {
        match self.jacobian_placed(postures) {
            Ok(j) => score::Scored::new(j, criterion, self).map_or(f64::INFINITY, |s| s.value),
            Err(_) => f64::INFINITY,
        }
    }

    /// The value of `criterion` for `postures` (rad) as a search minimises it
    /// ([`CalibrationCriterion::loss`]): `+infinity` for a group that does not separate the
    /// kept parameters or a non-finite posture.
    pub(crate) fn value(&self, criterion: CalibrationCriterion, postures: &[Vector6<f64>]) -> f64 {
        let d = self.scorer(criterion);
        match d.jacobian(postures) {
            Ok(j) => score::Scored::new(j, criterion, d).map_or(f64::INFINITY, |s| s.value),
            Err(_) => f64::INFINITY,
        }
    }

    /// `CalibrationDesign::value` and the exact gradient of its logarithm with respect to
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
        let d = self.scorer(criterion);
        let l = &d.layout;
        let e = d.station.as_slice();
        let terms: Vec<_> = postures.iter().map(|q| l.posture(q, e)).collect();
        let rows = l.rows(1);
        let mut j = DMatrix::zeros(l.rows(postures.len()), d.kept.len());
        for (i, t) in terms.iter().enumerate() {
            l.write_rows(t, &mut j, rows * i);
        }
        let Some(scored) = score::Scored::new(j, criterion, d) else {
            return (f64::INFINITY, zero);
        };
        let g = scored.log_gradient(d);
        let gradient = (terms.iter().enumerate())
            .map(|(i, t)| l.gradient(t, &scored.j, &g, rows * i))
            .collect();
        (scored.value, gradient)
    }
}

impl CalibrationDesign {
    /// The design a group at this design's station is scored on for `criterion`: the reduced
    /// one (`station`) for the criteria read from the information matrix, this one otherwise.
    fn scorer(&self, criterion: CalibrationCriterion) -> &CalibrationDesign {
        match (&self.reduced, criterion.spectral()) {
            (Some(reduced), false) => reduced,
            _ => self,
        }
    }
}

/// `a` above `b` (the same columns).
fn stack(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut all = DMatrix::zeros(a.nrows() + b.nrows(), b.ncols());
    all.rows_mut(0, a.nrows()).copy_from(a);
    all.rows_mut(a.nrows(), b.nrows()).copy_from(b);
    all
}

/// The model's nominal values with the gravity terms at zero: the rigid nominal chain, where the
/// design Jacobian is taken.
pub(crate) fn rigid(model: &ErrorModel) -> nalgebra::DVector<f64> {
    let mut x = model.nominal();
    x.rows_mut(model.gravity_start(), model.gravity().len())
        .fill(0.0);
    x
}

/// Unloaded readings of every measuring point of `model` at every posture, posture-major.
pub(crate) fn readings(model: &ErrorModel, postures: &[Placed]) -> Vec<Observation> {
    (postures.iter().enumerate())
        .flat_map(|(i, (q, e))| {
            (0..model.points()).map(move |k| Observation {
                posture: i,
                point: k,
                q: *q,
                measured: nalgebra::Vector3::zeros(),
                wrench: Vector6::zeros(),
                e: *e,
                table: false,
                direction: Vector6::zeros(),
            })
        })
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
pub(crate) fn criteria(
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

#[cfg(test)]
mod tests;
