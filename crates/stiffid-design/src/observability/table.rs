//! The positioner's table in a calibration design: reflectors fixed on the table, read at the
//! positioner's angles.
//!
//! A reflector on the table read where the external axes stand, `e`, is predicted at `P(e) x_k`
//! ([`ErrorModel::with_external`]): its rows hold the frame's columns `[I, -[b]x]`, the
//! positioner's lines and offsets and its own coordinates, and none of the arm's, so they do not
//! depend on the arm's posture. The information of a campaign is the arm's plus the table's,
//! `J_a^T J_a + sum_e T(e)^T T(e)`: the table's readings are fixed rows of every group scored
//! ([`CalibrationDesign::with_table_angles`]), and for a group of postures the angles are chosen
//! from candidates (a grid over the positioner's travel) by
//! [`CalibrationDesign::choose_table_angles`]: one reading at a time, each the candidate that
//! lowers the loss most (with a ridge of [`RIDGE`] times the information's mean diagonal while
//! the positioner's columns are not yet determined), then each angle exchanged for the best
//! candidate while the loss falls (Fedorov's exchange, Fedorov 1972). The test rows add every
//! reflector as a point of the part at each reference angle, its own coordinates known (their
//! columns zero): the error of a point of the part where the positioner puts it.

use super::{score, stack, station, CalibrationCriterion, CalibrationDesign, Placed};
use nalgebra::{DMatrix, DVector, Vector3, Vector6};
use rayon::prelude::*;
use std::sync::Arc;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::{Error, Result};
use stiffid_metrology::calibration::error_model::{Observation, Target};
use stiffid_metrology::calibration::ErrorModel;

/// The ridge of the greedy choice, relative to the information's mean diagonal.
const RIDGE: f64 = 1e-9;

/// The most exchange passes over the chosen angles.
const EXCHANGE_PASSES: usize = 4;

/// The positioner's table of a calibration design: its reflectors and where they are read for
/// reference.
#[derive(Debug, Clone, PartialEq)]
pub struct TableDesign {
    /// The reflectors (the model's table reflectors, in order), cell frame with every axis at
    /// 0, m: where the design's Jacobian is taken.
    pub reflectors: Vec<Vector3<f64>>,
    /// The external axes' values (SI, the cell's order) of the reference readings, every
    /// reflector read at each: they fix the kept parameters with the arm's reference postures,
    /// are the angles of the part's test points, and are the table readings a group is scored
    /// with until [`CalibrationDesign::with_table_angles`] replaces them. At least one.
    pub reference: Vec<ExternalValues>,
}

impl TableDesign {
    /// Writes the reflectors into the model's table coordinates of `values`.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`table`) for another count of reflectors than the model's or
    /// no reference angle.
    pub(super) fn place(&self, model: &ErrorModel, values: &mut DVector<f64>) -> Result<()> {
        if self.reflectors.len() != model.tables() || self.reference.is_empty() {
            return Err(Error::InvalidField {
                field: "table".into(),
                message: format!(
                    "expected {} reflectors and at least one reference angle, got {} and {}",
                    model.tables(),
                    self.reflectors.len(),
                    self.reference.len()
                ),
            });
        }
        for (c, p) in model.parameters().iter().enumerate() {
            if let Target::Table { point, axis } = p.target {
                values[c] = self.reflectors[point][axis];
            }
        }
        Ok(())
    }
}

/// The positioner's angles chosen for a group.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TableChoice {
    /// The candidates chosen (indices), one per reading of the table, in the order chosen.
    pub chosen: Vec<usize>,
    /// The loss of the group with the table read there (`CalibrationCriterion::loss`).
    pub value: f64,
}

/// Readings of each of `tables` reflectors at each of `angles`, angle-major.
pub(super) fn readings(tables: usize, angles: &[ExternalValues]) -> Vec<Observation> {
    (angles.iter().enumerate())
        .flat_map(|(i, e)| {
            (0..tables).map(move |k| Observation {
                posture: i,
                point: k,
                q: Vector6::zeros(),
                measured: Vector3::zeros(),
                wrench: Vector6::zeros(),
                e: *e,
                table: true,
                direction: Vector6::zeros(),
            })
        })
        .collect()
}

impl CalibrationDesign {
    /// The scaled rows of the kept parameters of every table reflector read at each of `angles`
    /// (the external axes' values, SI, the cell's order): 3 per reflector and angle,
    /// angle-major; with `part`, the reflectors' own coordinates' columns zero (a point of the
    /// part known in its frame). No rows without table reflectors.
    ///
    /// # Errors
    /// Those of [`ErrorModel::jacobian_of`].
    pub(crate) fn table_rows(&self, angles: &[ExternalValues], part: bool) -> Result<DMatrix<f64>> {
        let l = &self.layout;
        let observations = readings(l.model.tables(), angles);
        let mut out = DMatrix::zeros(3 * observations.len(), self.kept.len());
        if observations.is_empty() {
            return Ok(out);
        }
        let j = l.model.jacobian_of(&l.values, &observations)?;
        for (c, &k) in self.kept.iter().enumerate() {
            let own = matches!(l.model.parameters()[k].target, Target::Table { .. });
            if !(part && own) {
                out.column_mut(c).copy_from(&(j.column(k) * l.scales[c]));
            }
        }
        Ok(out)
    }

    /// This design with the table's reflectors read at `angles` (replacing the readings it has:
    /// the reference angles of a new design), fixed rows of every group scored.
    ///
    /// # Errors
    /// Those of `CalibrationDesign::table_rows`.
    pub fn with_table_angles(&self, angles: &[ExternalValues]) -> Result<Self> {
        let rows = self.table_rows(angles, false)?;
        let t = self.table.nrows();
        let rest = self.fixed.rows(t, self.fixed.nrows() - t).into_owned();
        let fixed = stack(&rows, &rest);
        let mut design = CalibrationDesign {
            fixed_information: fixed.tr_mul(&fixed),
            fixed,
            table: rows,
            reduced: None,
            ..self.clone()
        };
        if self.reduced.is_some() {
            design.reduced = station::reduce(&design).map(Arc::new);
        }
        Ok(design)
    }

    /// The angles of `count` readings of the table (each reading every reflector) that minimise
    /// `criterion` with the group `postures` (each read where it stands), chosen among
    /// `candidates` (the external axes' values, SI; the positioner's are what matter) by the
    /// greedy choice and exchange of the module docs. With `allowed`, reading `i` takes only a
    /// candidate `c` with `allowed[i][c]` (one row of `candidates.len()` per reading: where the
    /// arm's posture of reading `i` clears what the positioner carries); `None` allows every
    /// candidate to every reading. The value is `+infinity` when no choice separates the kept
    /// parameters.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`table`) with no candidate or a count of 0, or `allowed` with
    /// another shape or a reading with no candidate allowed; those of
    /// `CalibrationDesign::table_rows` and `CalibrationDesign::jacobian_placed`.
    pub(crate) fn choose_table_angles(
        &self,
        criterion: CalibrationCriterion,
        postures: &[Placed],
        candidates: &[ExternalValues],
        count: usize,
        allowed: Option<&[Vec<bool>]>,
    ) -> Result<TableChoice> {
        if candidates.is_empty() || count == 0 {
            return Err(Error::InvalidField {
                field: "table".into(),
                message: format!(
                    "expected candidate angles and readings, got {} and {count}",
                    candidates.len()
                ),
            });
        }
        check_allowed(allowed, count, candidates.len())?;
        let may = |i: usize, c: usize| allowed.is_none_or(|a| a[i][c]);
        let d = self.with_table_angles(&[])?;
        let arm = d.jacobian_placed(postures)?;
        let mut base = d.fixed_information.clone();
        base.gemm_tr(1.0, &arm, &arm, 1.0);
        let blocks: Vec<DMatrix<f64>> = (candidates.iter())
            .map(|e| {
                let t = d.table_rows(std::slice::from_ref(e), false)?;
                Ok(t.tr_mul(&t))
            })
            .collect::<Result<_>>()?;
        let rows = d.fixed.nrows() + arm.nrows() + 3 * count * d.model().tables();
        let n = rows / d.layout.rows(1).max(1);
        let loss = |m: DMatrix<f64>| score::information_loss(m, n, criterion, &d);
        // The candidate of reading `i` that gives `info` the smallest loss, the first of equals.
        let best = |info: &DMatrix<f64>, ridge: f64, i: usize| {
            (0..blocks.len())
                .into_par_iter()
                .filter(|&c| may(i, c))
                .map(|c| {
                    let mut m = info + &blocks[c];
                    m.set_diagonal(&(m.diagonal().add_scalar(ridge)));
                    (loss(m), c)
                })
                .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
                .expect("an allowed candidate")
        };
        let p = base.nrows().max(1) as f64;
        let ridge = RIDGE * base.trace() / p;
        let (mut info, mut chosen) = (base, Vec::with_capacity(count));
        for i in 0..count {
            let (_, c) = best(&info, ridge, i);
            info += &blocks[c];
            chosen.push(c);
        }
        let mut value = loss(info.clone());
        for _ in 0..EXCHANGE_PASSES {
            let mut improved = false;
            for i in 0..count {
                let without = &info - &blocks[chosen[i]];
                let (v, c) = best(&without, 0.0, i);
                if v < value * (1.0 - 1e-9) {
                    (info, chosen[i], value, improved) = (without + &blocks[c], c, v, true);
                }
            }
            if !improved {
                break;
            }
        }
        let angles: Vec<ExternalValues> = chosen.iter().map(|&c| candidates[c]).collect();
        let value = self
            .with_table_angles(&angles)?
            .value_placed(criterion, postures);
        Ok(TableChoice { chosen, value })
    }
}

/// Refuses an `allowed` of [`CalibrationDesign::choose_table_angles`] that is not `count` rows
/// of `candidates` flags, or leaves a reading no candidate.
fn check_allowed(allowed: Option<&[Vec<bool>]>, count: usize, candidates: usize) -> Result<()> {
    let Some(allowed) = allowed else {
        return Ok(());
    };
    let shaped = allowed.len() == count && allowed.iter().all(|a| a.len() == candidates);
    let empty = allowed.iter().position(|a| !a.contains(&true));
    let message = match (shaped, empty) {
        (true, None) => return Ok(()),
        (false, _) => format!(
            "expected {count} rows of {candidates} allowed candidates, got {} rows",
            allowed.len()
        ),
        (true, Some(i)) => format!("reading {} has no allowed candidate angle", i + 1),
    };
    Err(Error::InvalidField {
        field: "table".into(),
        message,
    })
}
