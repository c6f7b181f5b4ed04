//! Least squares with an offset per posture and measuring point beside the compliances: backlash
//! and friction show as a displacement that does not grow with the load ([`crate::steps`]).
//!
//! The model of a reading of point `p` in posture `i` under a load step is
//! `delta = Psi h + o_ip`, `o_ip` a constant translation (base frame, m) of that point in that
//! posture: 3 more unknowns per posture and point, so `Psi` gains one indicator column per
//! posture, point and coordinate. They are eliminated exactly (Frisch-Waugh-Lovell): the rows of
//! `Psi` and `delta` of each posture, point and coordinate are centred on their mean, `h` is the
//! least-squares solution of the centred system (by QR), its covariance `s^2 (Psi_c^T Psi_c)^-1`
//! with `s^2 = |r|^2 / (m - 6 - 3 G)` for `G` offsets, and `o_ip` the mean of `delta - Psi h` over
//! its rows. The residuals equal those of the full system. An offset needs at least two different
//! loads of its point in its posture: with one, the offset and the compliances cannot be told
//! apart.

use super::{check_deflection, finish, six_parameters_only, Identification};
use nalgebra::{DVector, RowVector6, Vector3};
use std::collections::HashMap;
use stiffid_core::math::lsq::Factor;
use stiffid_core::observation::{Measurement, Observations};
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result};

/// The fitted offset of one measuring point in one posture.
#[derive(Debug, Clone, PartialEq)]
pub struct Offset {
    /// The posture (as in the measurements).
    pub posture: usize,
    /// The measuring point, 0-based.
    pub point: usize,
    /// The offset `o_ip`, base frame, m.
    pub offset: Vector3<f64>,
}

/// The compliances and an offset per posture and measuring point (module docs), offsets in order
/// of first appearance.
///
/// # Errors
/// [`Error::InvalidField`] (`offsets`) when a posture's point has a single load (one wrench);
/// those of [`Observations::from_measurements`] and of [`least_squares`](crate::Identify::least_squares).
pub fn least_squares(
    arm: &Arm,
    measurements: &[Measurement],
) -> Result<(Identification, Vec<Offset>)> {
    let obs = Observations::from_measurements(arm, measurements)?;
    if obs.psi.ncols() != 6 {
        return Err(six_parameters_only());
    }
    check_deflection(obs.delta.iter())?;
    let groups = groups(measurements)?;
    let (mut psi, mut delta) = (obs.psi.clone(), obs.delta.clone());
    let mut means = Vec::with_capacity(groups.len());
    for (_, rows) in &groups {
        for a in 0..3 {
            let idx: Vec<usize> = rows.iter().map(|&i| 3 * i + a).collect();
            let n = idx.len() as f64;
            let row_mean = idx
                .iter()
                .map(|&r| psi.fixed_view::<1, 6>(r, 0).into_owned())
                .sum::<RowVector6<f64>>()
                / n;
            let delta_mean = idx.iter().map(|&r| delta[r]).sum::<f64>() / n;
            for &r in &idx {
                let centred = psi.fixed_view::<1, 6>(r, 0) - row_mean;
                psi.fixed_view_mut::<1, 6>(r, 0).copy_from(&centred);
                delta[r] -= delta_mean;
            }
            means.push((row_mean, delta_mean));
        }
    }
    let factor = Factor::try_new(psi.clone())?;
    let h = factor.solve(&delta);
    let residuals: DVector<f64> = &delta - &psi * h;
    let offsets = groups
        .iter()
        .enumerate()
        .map(|(g, ((posture, point), _))| Offset {
            posture: *posture,
            point: *point,
            offset: Vector3::from_fn(|a, _| {
                let (row, d) = &means[3 * g + a];
                d - row.dot(&h.transpose())
            }),
        })
        .collect::<Vec<_>>();
    let free = 6 + 3 * offsets.len();
    // With the offsets, what the fit predicts is the measured displacement less its residual.
    let predicted = &obs.delta - &residuals;
    let id = finish(
        obs.postures,
        h,
        (residuals, predicted),
        factor.unit_covariance(),
        free,
        factor.cond(),
        None,
    );
    Ok((id, offsets))
}

/// The measurements of each posture and point, in order of first appearance.
///
/// # Errors
/// [`Error::InvalidField`] (`offsets`) for a posture and point with a single wrench.
#[allow(clippy::type_complexity)]
fn groups(measurements: &[Measurement]) -> Result<Vec<((usize, usize), Vec<usize>)>> {
    let mut index = HashMap::new();
    let mut groups: Vec<((usize, usize), Vec<usize>)> = Vec::new();
    for (i, m) in measurements.iter().enumerate() {
        let key = (m.posture, m.point);
        let g = *index.entry(key).or_insert_with(|| {
            groups.push((key, Vec::new()));
            groups.len() - 1
        });
        groups[g].1.push(i);
    }
    for ((posture, point), rows) in &groups {
        let first = &measurements[rows[0]].wrench;
        if rows.iter().all(|&i| measurements[i].wrench == *first) {
            return Err(Error::InvalidField {
                field: "offsets".into(),
                message: format!(
                    "measurement {} (posture {}, point {}) has one load only: an offset beside the compliances needs at least two different loads of each point in each posture",
                    rows[0] + 1,
                    posture + 1,
                    point + 1
                ),
            });
        }
    }
    Ok(groups)
}
