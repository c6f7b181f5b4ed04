//! The acceptance rule of every choice by cross-validation in the calibration: a candidate
//! model is kept when it lowers the held-out error by more than a number of standard errors of
//! the paired per-posture differences and by a least share of the total (the joint maps,
//! [`super::maps`]; the error motions' orders, [`super::motions`]; the gravity prior's strength,
//! [`super::fit`]).

/// The least share of the held-out squared error a candidate must remove to be kept.
pub(crate) const LEAST_GAIN: f64 = 0.02;

/// Whether the candidate's held-out errors (per held-out posture, and their total) lower the
/// current ones by more than `accept` standard errors of the paired per-posture differences and by
/// 2 % of the total: the acceptance rule of every choice by cross-validation in the calibration
/// (the maps at `MAP_ACCEPT`, the error motions' orders at `ACCEPT`).
pub(crate) fn lowers(current: (&[f64], f64), candidate: (&[f64], f64), accept: f64) -> bool {
    let n = current.0.len();
    if n < 2 {
        return false;
    }
    let d: Vec<f64> = (current.0.iter().zip(candidate.0))
        .map(|(a, b)| a - b)
        .collect();
    let mean = d.iter().sum::<f64>() / n as f64;
    let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    mean > accept * (var / n as f64).sqrt() && candidate.1 < (1.0 - LEAST_GAIN) * current.1
}
