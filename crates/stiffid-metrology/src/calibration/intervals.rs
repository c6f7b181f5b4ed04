//! Prediction intervals of a calibration's position error, built from held-out errors: the
//! jackknife+ over postures ([`stiffid_core::model::prediction`], Barber, Candes, Ramdas and Tibshirani
//! 2021), as the stiffness's intervals are, not from the residual noise alone (which understates
//! what the model misses: the residuals of the fitted readings are smaller than the errors of
//! readings the fit has not seen).
//!
//! Fold `p` of leave-one-posture-out ([`super::validation::leave_one_out`]) fits the calibration
//! `x_(-p)` without posture `p` and predicts its readings: each coordinate `c` of their errors
//! gives the score `R = |e_(-p),c|` (m; predicted minus read, base frame), absolute: a robot's
//! position error does not grow with anything the prediction knows. For a new reading (any
//! posture and measuring point; its tracker reading mapped by each fit's own registration, the
//! tracker being the fixed reference), fold `p` predicts the error `e_(-p)` and the reading lies
//! in its jackknife+ interval when
//!
//! ```text
//! q-_alpha{ e_(-p),c - R } <= 0 <= q+_alpha{ e_(-p),c + R }                                (C1)
//! ```
//!
//! the quantiles over every fold and every score of it ([`stiffid_core::model::prediction::interval_of`]).
//! The interval of the error of the full calibration `e_c` (the document's `error_mm`) is then
//! `[e_c - q+{e_(-p),c + R}, e_c - q-{e_(-p),c - R}]`, which does not depend on the reading: it
//! is `mu_c - [q+{mu_(-p),c + R}, q-{mu_(-p),c - R}]` in the predicted positions `mu`. The
//! coverage is the share of held-out coordinates inside their intervals; the guarantee is the
//! jackknife+'s (at least `1 - 2 alpha` for a posture drawn like the fitted ones, about
//! `1 - alpha` in practice), not for postures unlike them.
//!
//! The folds are refitted ([`super::validation::leave_one_out`]) or linearised at the full fit
//! ([`super::validation::leave_one_out_linearised`], what `calibrate` uses, with or without
//! maps): a linearised fold predicts `e_(-p) = e + J dx_p`, the full fit's error plus the
//! Jacobian at the full fit times the fold's change of the values, so that a change along a
//! weakly determined direction moves its predictions as little as it moves the fit's.

use super::error_model::{ErrorModel, Estimate, Observation};
use super::validation::Fold;
use nalgebra::{DVector, Vector3};
use rayon::prelude::*;
use stiffid_core::model::prediction::{interval_of, Interval};
use stiffid_core::Result;

/// The held-out readings whose errors are computed together (bounds the memory: one error per
/// fold and reading).
const CHUNK: usize = 1024;

/// What the intervals are built from: each fold's calibration and the scores of its held-out
/// coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Intervals {
    /// Per fold: the fit without its posture (re-centred), and the scores `R` of its held-out
    /// coordinates (three per reading), m.
    folds: Vec<(Estimate, Vec<f64>)>,
    /// Per fold of linearised folds ([`super::validation::leave_one_out_linearised`]), the
    /// change of the values from the full fit's (SI): a fold predicts the full fit's errors plus
    /// the Jacobian times it. Empty for refitted folds.
    changes: Vec<DVector<f64>>,
    /// Per fold, the reflectors fixed in the cell (0-based) that only its held-out posture
    /// reads: the fold has no reading of them, so it predicts none of their readings.
    lacks: Vec<Vec<usize>>,
}

/// Per fold, the reflectors fixed in the cell that no other fold's held-out posture reads.
fn lone_reflectors(folds: &[Fold]) -> Vec<Vec<usize>> {
    let reads = |f: &Fold, k: usize| (f.held.errors.iter()).any(|e| e.table && e.point == k);
    (folds.iter().enumerate())
        .map(|(i, f)| {
            let mut ks: Vec<usize> = (f.held.errors.iter())
                .filter(|e| e.table)
                .map(|e| e.point)
                .collect();
            ks.dedup();
            ks.retain(|&k| !(folds.iter().enumerate()).any(|(j, g)| j != i && reads(g, k)));
            ks
        })
        .collect()
}

/// How well the intervals covered held-out readings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coverage {
    /// The folds (fitted postures) the intervals are built from.
    pub folds: usize,
    /// The intervals' level.
    pub level: f64,
    /// Held-out coordinates inside their intervals.
    pub covered: usize,
    /// Held-out coordinates (three per reading).
    pub coordinates: usize,
}

impl Coverage {
    /// `covered / coordinates`.
    pub fn coverage(&self) -> f64 {
        self.covered as f64 / self.coordinates.max(1) as f64
    }
}

impl Intervals {
    /// The intervals of the leave-one-posture-out `folds`: refitted ones predict by their
    /// estimates, linearised ones (all of them with a change) by the full fit's errors plus the
    /// Jacobian at it times their change.
    pub fn new(folds: &[Fold]) -> Self {
        let changes: Option<Vec<DVector<f64>>> = folds.iter().map(|f| f.change.clone()).collect();
        let lacks = lone_reflectors(folds);
        Intervals {
            changes: changes.unwrap_or_default(),
            folds: (folds.iter().zip(&lacks))
                .map(|(f, lacks)| {
                    let scores = (f.held.errors.iter())
                        .filter(|e| !(e.table && lacks.contains(&e.point)))
                        .flat_map(|e| [e.error.x.abs(), e.error.y.abs(), e.error.z.abs()])
                        .collect();
                    (f.estimate.recentre(), scores)
                })
                .collect(),
            lacks,
        }
    }

    /// The number of folds.
    pub fn folds(&self) -> usize {
        self.folds.len()
    }

    /// The interval at `level` of the error of each of `observations` at `estimate` (predicted
    /// minus read, base frame, m; the readings mapped by `estimate`'s frame), in their order
    /// (module docs, C1); a reading of a reflector fixed in the cell leaves out the folds whose
    /// held-out posture alone reads it (they have no reading of it to predict from). Each refitted fold maps the readings by its own frame, or with
    /// `reregister` by the frame registered anew on `observations` at its values
    /// ([`super::fit::start_at`]: another series, the tracker moved). Linearised folds predict
    /// `estimate`'s errors plus the Jacobian at `estimate` times their change, which with
    /// `reregister` leaves out the change of the frame (the held-out series' own registration
    /// takes it; the part of a geometric change it would absorb too is kept, erring wide).
    ///
    /// # Errors
    /// Those of `ErrorModel::residuals`, [`ErrorModel::jacobian_of`] and
    /// [`super::fit::start_at`].
    pub fn of(
        &self,
        model: &ErrorModel,
        estimate: &Estimate,
        observations: &[Observation],
        level: f64,
        reregister: bool,
    ) -> Result<Vec<Interval>> {
        let folds = match self.changes.is_empty() {
            false => Vec::new(),
            true => (self.folds.par_iter())
                .map(|(e, _)| match reregister {
                    false => Ok(e.clone()),
                    true => Ok(Estimate {
                        frame: super::fit::start_at(model, observations, &e.values)?,
                        values: e.values.clone(),
                    }),
                })
                .collect::<Result<Vec<Estimate>>>()?,
        };
        let changes: Vec<DVector<f64>> = (self.changes.iter())
            .map(|c| {
                let mut c = c.clone();
                for (i, p) in model.parameters().iter().enumerate() {
                    if reregister && matches!(p.target, super::Target::Frame(_)) {
                        c[i] = 0.0;
                    }
                }
                c
            })
            .collect();
        let mut all = Vec::with_capacity(observations.len());
        for chunk in observations.chunks(CHUNK) {
            let full = model.residuals(estimate, chunk)?;
            let each = match changes.is_empty() {
                true => (folds.par_iter())
                    .map(|fold| model.residuals(fold, chunk))
                    .collect::<Result<Vec<DVector<f64>>>>()?,
                false => {
                    let j = model.jacobian_of(&estimate.values, chunk)?;
                    (changes.par_iter()).map(|c| &full + &j * c).collect()
                }
            };
            let intervals: Vec<Interval> = (0..chunk.len())
                .into_par_iter()
                .map(|i| {
                    let o = &chunk[i];
                    let folds: Vec<(Vector3<f64>, f64, &[f64])> = (each.iter())
                        .zip(&self.folds)
                        .zip(&self.lacks)
                        .filter(|(_, lacks)| !(o.table && lacks.contains(&o.point)))
                        .map(|((r, (_, scores)), _)| {
                            (
                                r.fixed_rows::<3>(3 * i).into_owned(),
                                1.0,
                                scores.as_slice(),
                            )
                        })
                        .collect();
                    let e = full.fixed_rows::<3>(3 * i);
                    let j = interval_of(&folds, level);
                    std::array::from_fn(|c| [e[c] - j[c][1], e[c] - j[c][0]])
                })
                .collect();
            all.extend(intervals);
        }
        Ok(all)
    }
}

/// The coverage at `level` of `intervals` of the `errors` (m) they bound, the intervals built
/// from `folds` folds.
pub fn coverage(
    intervals: &[Interval],
    errors: &[Vector3<f64>],
    level: f64,
    folds: usize,
) -> Coverage {
    let covered = (intervals.iter().zip(errors))
        .map(|(i, e)| stiffid_core::model::prediction::inside(i, &[e.x, e.y, e.z]))
        .map(|b| b.iter().filter(|b| **b).count())
        .sum();
    Coverage {
        folds,
        level,
        covered,
        coordinates: 3 * intervals.len(),
    }
}
