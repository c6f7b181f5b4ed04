//! Which parameters the readings determine: QR with column pivoting on the column-scaled
//! identification Jacobian.
//!
//! The Jacobian `J` ([`crate::calibration::ErrorModel::jacobian`], 3 rows per reading) is scaled by
//! the parameters' typical sizes ([`crate::calibration::ErrorModel::column_scales`]) and reduced to
//! its triangular factor (Householder QR: the columns' inner products, all the analysis needs).
//! Each column is then normalised to unit length and the columns are taken in the order of their
//! priority ([`crate::calibration::Parameter::priority`]: the frame and the measuring points, the
//! four (M)DH errors, Hayati's beta, the lateral `b`, the gravity terms), within a priority the one
//! with the largest part not yet explained first (QR with column pivoting, Businger and Golub
//! 1965). A column whose unexplained part is below [`RANK_TOLERANCE`] of its length is merged: it
//! is, within the tolerance, a combination of the columns kept, and the fit leaves it at its
//! nominal value; the combination (the kept parameters with their coefficients, in scaled units)
//! says into which it merges (joint 1's errors into the tracker's registration, joint 6's `theta`
//! and `d` into the measuring points, `d` of the second of two parallel joints into the first's). A
//! column with no effect at all (gravity about a vertical axis) merges into nothing. The kept
//! columns' count is the rank, the condition number is that of their scaled columns, and the
//! correlations of the kept parameters (from `(J^T J)^-1`) above 0.9 in absolute value are listed:
//! the weakly separated pairs (Sun and Hollerbach 2008 on observability).

use nalgebra::{DMatrix, DVector};
use stiffid_core::math::householder;
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::{Error, Result};

/// The relative length of a column's unexplained part below which it merges.
pub const RANK_TOLERANCE: f64 = 1e-7;

/// Correlations above this, in absolute value, are listed.
pub(crate) const CORRELATION_REPORTED: f64 = 0.9;

/// Correlations above this, in absolute value, leave the two parameters not separately
/// identifiable: the readings determine one combination of them, and each one's standard
/// deviation alone means nothing (a change of one is taken up by the other).
pub const CORRELATION_INSEPARABLE: f64 = 0.999;

/// Coefficients below this share of a merged column's largest are not listed.
const COEFFICIENT_LISTED: f64 = 1e-3;

/// A correlation of two kept parameters: `(i, j, rho)`, `i < j` their indices.
pub(crate) type Correlation = (usize, usize, f64);

/// A parameter the readings do not separate from the kept ones.
#[derive(Debug, Clone, PartialEq)]
pub struct Merged {
    /// The parameter's index.
    pub parameter: usize,
    /// The kept parameters whose combination its column is, with the coefficients (scaled
    /// units: unit-length columns), largest first; empty when it has no effect at all.
    pub into: Vec<(usize, f64)>,
}

/// What the readings determine.
#[derive(Debug, Clone, PartialEq)]
pub struct Identifiability {
    /// The kept parameters' indices, ascending.
    pub identified: Vec<usize>,
    /// The merged parameters, in parameter order.
    pub merged: Vec<Merged>,
    /// How many kept: the rank of the Jacobian.
    pub rank: usize,
    /// The condition number of the kept columns of the scaled Jacobian (largest over smallest
    /// singular value).
    pub condition: f64,
    /// The kept parameters' correlations above 0.9 in absolute value: `(i, j, rho)`, `i < j`
    /// parameter indices.
    pub correlations: Vec<Correlation>,
}

/// The triangular factor `R` (`n x n`, `n` the columns) of `a` (`m x n`): `a^T a = R^T R`.
/// `a` itself when it has fewer rows than columns.
pub(crate) fn triangular(a: &DMatrix<f64>) -> DMatrix<f64> {
    let (m, n) = a.shape();
    if m <= n {
        return a.clone();
    }
    let mut work = a.clone();
    householder::qr(work.as_mut_slice(), m, n);
    DMatrix::from_fn(n, n, |i, j| if i <= j { work[(i, j)] } else { 0.0 })
}

/// Analyses the Jacobian `j` (rows the readings' coordinates, columns the parameters) with the
/// column scales `scales` and the parameters' `priorities` (module docs).
///
/// # Errors
/// [`Error::NotFinite`] when the Jacobian or a scale is not finite or an SVD does not converge;
/// [`Error::InvalidField`] (`parameters`) when the lengths disagree.
pub fn analyse(
    j: &DMatrix<f64>,
    scales: &DVector<f64>,
    priorities: &[u8],
) -> Result<Identifiability> {
    let n = j.ncols();
    if scales.len() != n || priorities.len() != n {
        return Err(Error::InvalidField {
            field: "parameters".into(),
            message: format!(
                "expected {n} scales and priorities, got {} and {}",
                scales.len(),
                priorities.len()
            ),
        });
    }
    let mut scaled = j.clone();
    for (c, s) in scales.iter().enumerate() {
        scaled.column_mut(c).scale_mut(*s);
    }
    if !scaled.iter().all(|v| v.is_finite()) {
        return Err(Error::NotFinite {
            what: "the scaled identification Jacobian".into(),
        });
    }
    let r = triangular(&scaled);
    let (identified, merged) = pivot(&r, priorities)?;
    let kept = r.select_columns(identified.iter());
    let (condition, correlations) = conditioning(&kept, &identified)?;
    Ok(Identifiability {
        rank: identified.len(),
        identified,
        merged,
        condition,
        correlations,
    })
}

/// The kept and merged columns of `r` (module docs).
fn pivot(r: &DMatrix<f64>, priorities: &[u8]) -> Result<(Vec<usize>, Vec<Merged>)> {
    let n = r.ncols();
    let norms: Vec<f64> = (0..n).map(|c| r.column(c).norm()).collect();
    let largest = norms.iter().copied().fold(0.0, f64::max);
    // Unit columns (a column negligible beside the largest counts as no effect).
    let mut residual: Vec<DVector<f64>> = (0..n)
        .map(|c| match norms[c] > largest * f64::EPSILON {
            true => r.column(c) / norms[c],
            false => DVector::zeros(r.nrows()),
        })
        .collect();
    let unit = residual.clone();
    let mut kept = Vec::new();
    let mut order: Vec<u8> = priorities.to_vec();
    order.sort_unstable();
    order.dedup();
    for p in order {
        let mut open: Vec<usize> = (0..n).filter(|&c| priorities[c] == p).collect();
        while let Some((at, &c)) = open
            .iter()
            .enumerate()
            .max_by(|a, b| residual[*a.1].norm().total_cmp(&residual[*b.1].norm()))
        {
            if residual[c].norm() < RANK_TOLERANCE {
                break;
            }
            open.remove(at);
            let q = residual[c].normalize();
            for other in residual.iter_mut() {
                for _ in 0..2 {
                    let d = q.dot(other);
                    other.axpy(-d, &q, 1.0);
                }
            }
            kept.push(c);
        }
    }
    kept.sort_unstable();
    let kept_columns =
        DMatrix::from_columns(&kept.iter().map(|&c| unit[c].clone()).collect::<Vec<_>>());
    let svd = match kept.is_empty() {
        true => None,
        false => kept_columns.clone().capped_svd(true, true),
    };
    let merged = (0..n)
        .filter(|c| !kept.contains(c))
        .map(|c| {
            let into = match (&svd, unit[c].norm() > 0.0) {
                (Some(svd), true) => {
                    let x = svd
                        .solve(&unit[c], f64::EPSILON)
                        .map_err(|_| not_converged())?;
                    let top = x.amax();
                    let mut into: Vec<(usize, f64)> = (kept.iter().zip(x.iter()))
                        .filter(|(_, v)| v.abs() > COEFFICIENT_LISTED * top)
                        .map(|(&k, &v)| (k, v))
                        .collect();
                    into.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
                    into
                }
                _ => Vec::new(),
            };
            Ok(Merged { parameter: c, into })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok((kept, merged))
}

/// The condition number of `kept` and the correlations above [`CORRELATION_REPORTED`] of its
/// columns (parameter indices `identified`).
fn conditioning(kept: &DMatrix<f64>, identified: &[usize]) -> Result<(f64, Vec<Correlation>)> {
    if identified.is_empty() {
        return Ok((f64::NAN, Vec::new()));
    }
    let svd = kept
        .clone()
        .capped_svd(false, true)
        .ok_or_else(not_converged)?;
    let s = &svd.singular_values;
    let condition = s.max() / s.min();
    let v_t = svd.v_t.ok_or_else(not_converged)?;
    let inverse = DMatrix::from_diagonal(&s.map(|v| 1.0 / (v * v)));
    let covariance = v_t.transpose() * inverse * &v_t;
    let mut correlations = Vec::new();
    for a in 0..identified.len() {
        for b in a + 1..identified.len() {
            let rho = covariance[(a, b)] / (covariance[(a, a)] * covariance[(b, b)]).sqrt();
            if rho.abs() > CORRELATION_REPORTED {
                correlations.push((identified[a], identified[b], rho));
            }
        }
    }
    Ok((condition, correlations))
}

fn not_converged() -> Error {
    Error::NotFinite {
        what: "the identifiability analysis's SVD did not converge".into(),
    }
}
