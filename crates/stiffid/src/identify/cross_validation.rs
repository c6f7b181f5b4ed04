//! Cross-validation over postures: refit without some postures, predict them (Eq. 22).
//!
//! With `K` folds, posture `p` (numbered `0..n` in order of first appearance,
//! [`Observations::posture_index`]) is held out in fold `p mod K`; `K = n` is leave-one-posture-out.
//! Each fold identifies the compliance by least squares (QR) from the other postures' rows and
//! predicts the held-out measurements: `delta_b = |delta_m - Psi_i h|` per measurement. The spread
//! of a joint's stiffness across folds says how much it depends on which postures were measured; a
//! fold whose removal moves a stiffness by more than its standard error in the full fit is
//! influential for that joint.

use crate::identify::Identification;
use crate::lsq::Factor;
use crate::observation::Observations;
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Vector6};

/// One fold: the fit without some postures and its predictions of them.
#[derive(Debug, Clone, PartialEq)]
pub struct Fold {
    /// The held-out postures (dense numbers, [`Observations::posture_index`]).
    pub postures: Vec<usize>,
    /// The held-out measurements (indices into the measurements).
    pub measurements: Vec<usize>,
    /// The stiffness fitted without them, Nm/rad.
    pub stiffness: Vector6<f64>,
    /// `delta_b` (Eq. 22) of each held-out measurement, m.
    pub delta_b: Vec<f64>,
    /// Root mean square of `delta_b`, m.
    pub rms_delta_b: f64,
    /// Joints whose stiffness moved by more than its full-fit standard error.
    pub influential: [bool; 6],
}

/// The result of a cross-validation.
#[derive(Debug, Clone, PartialEq)]
pub struct CrossValidation {
    /// One per fold, in fold order.
    pub folds: Vec<Fold>,
    /// Mean stiffness across folds, Nm/rad.
    pub stiffness_mean: Vector6<f64>,
    /// Sample standard deviation of the stiffness across folds, Nm/rad.
    pub stiffness_std: Vector6<f64>,
    /// Smallest and largest stiffness across folds, Nm/rad.
    pub stiffness_range: [Vector6<f64>; 2],
    /// Root mean square of `delta_b` over every held-out measurement, m.
    pub rms_delta_b: f64,
    /// Root mean square of the measured displacement magnitudes, m.
    pub rms_measured: f64,
}

/// Cross-validates with `folds` folds (module docs); `full` is the identification of all of
/// `obs` (its standard errors decide influence; without them nothing is influential).
///
/// # Errors
/// [`Error::InvalidField`] (`folds`) unless `2 <= folds <= postures`; (`cross-validation fold
/// N`) when the postures left in a fold cannot identify every joint (the message says why).
pub fn cross_validate(
    obs: &Observations,
    full: &Identification,
    folds: usize,
) -> Result<CrossValidation> {
    if folds < 2 || folds > obs.postures {
        return Err(Error::InvalidField {
            field: "folds".into(),
            message: format!(
                "expected 2 to {} (the number of postures), got {folds}",
                obs.postures
            ),
        });
    }
    let se = full.uncertainty.as_ref().map(|u| u.stiffness_std_error);
    let folds: Vec<Fold> = (0..folds)
        .map(|f| fold(obs, f, folds, &full.stiffness, se.as_ref()))
        .collect::<Result<_>>()?;
    let n = folds.len() as f64;
    let mean = folds.iter().map(|f| f.stiffness).sum::<Vector6<f64>>() / n;
    let var = folds
        .iter()
        .map(|f| (f.stiffness - mean).map(|d| d * d))
        .sum::<Vector6<f64>>()
        / (n - 1.0);
    let range = [
        folds
            .iter()
            .fold(Vector6::repeat(f64::INFINITY), |a, f| a.inf(&f.stiffness)),
        folds
            .iter()
            .fold(Vector6::repeat(f64::NEG_INFINITY), |a, f| {
                a.sup(&f.stiffness)
            }),
    ];
    let held_out: Vec<f64> = folds
        .iter()
        .flat_map(|f| f.delta_b.iter().copied())
        .collect();
    let measured = obs.delta.norm_squared() / (obs.delta.len() / 3) as f64;
    Ok(CrossValidation {
        stiffness_mean: mean,
        stiffness_std: var.map(f64::sqrt),
        stiffness_range: range,
        rms_delta_b: rms(&held_out),
        rms_measured: measured.sqrt(),
        folds,
    })
}

fn rms(values: &[f64]) -> f64 {
    (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt()
}

fn fold(
    obs: &Observations,
    f: usize,
    folds: usize,
    full: &Vector6<f64>,
    se: Option<&Vector6<f64>>,
) -> Result<Fold> {
    let held = |i: &usize| obs.posture_index[*i] % folds == f;
    let n = obs.posture_index.len();
    let (out, train): (Vec<usize>, Vec<usize>) = (0..n).partition(held);
    let rows = |ids: &[usize]| -> (DMatrix<f64>, DVector<f64>) {
        let mut psi = DMatrix::zeros(3 * ids.len(), 6);
        let mut delta = DVector::zeros(3 * ids.len());
        for (k, &i) in ids.iter().enumerate() {
            psi.fixed_view_mut::<3, 6>(3 * k, 0)
                .copy_from(&obs.psi.fixed_view::<3, 6>(3 * i, 0));
            delta
                .fixed_rows_mut::<3>(3 * k)
                .copy_from(&obs.delta.fixed_rows::<3>(3 * i));
        }
        (psi, delta)
    };
    let (psi, delta) = rows(&train);
    let h = Factor::try_new(psi)
        .map_err(|e| Error::InvalidField {
            field: format!("cross-validation fold {}", f + 1),
            message: format!("the other postures cannot identify the stiffness: {e}"),
        })?
        .solve(&delta);
    let stiffness = h.map(|v| 1.0 / v);
    let (psi, delta) = rows(&out);
    let residual = delta - psi * h;
    let delta_b: Vec<f64> = (0..out.len())
        .map(|k| residual.fixed_rows::<3>(3 * k).norm())
        .collect();
    let mut postures: Vec<usize> = out.iter().map(|&i| obs.posture_index[i]).collect();
    postures.sort_unstable();
    postures.dedup();
    Ok(Fold {
        postures,
        rms_delta_b: rms(&delta_b),
        influential: std::array::from_fn(|j| {
            se.is_some_and(|se| (stiffness[j] - full[j]).abs() > se[j])
        }),
        stiffness,
        measurements: out,
        delta_b,
    })
}
