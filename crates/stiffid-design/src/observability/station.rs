//! A campaign's step at one station of a carrier, scored on the arm's columns alone.
//!
//! At one station `e` every carrier column of the group (a track's direction and error
//! motions) is a rigid motion of the point, `a x b + c` with `a`, `c` fixed by `e`
//! ([`super::jacobian::Column::Carrier`]): a combination of the registration's six columns
//! (`e_a x b`, `e_a`). With the kept columns split into the arm's `a` (the registration among
//! them) and the carrier's `t`, the group's Jacobian is `J = [J_a, J_a E B]` and the unit upper
//! triangular `U = [[I, -E B], [0, I]]` gives `J U = [J_a, 0]`. With the fixed postures'
//! information `F` and the test information `H` congruent by `U` (`F' = U^T F U`,
//! `H' = U^T H U`), the information of the whole campaign becomes
//! `U^T (F + J^T J) U = F' + diag(J_a^T J_a, 0)`, and the Schur complement of its constant
//! carrier block `F'_tt` (`K = F'_tt^-1`, `M = F'_at K`) leaves
//!
//! ```text
//! A        = J_a^T J_a + G,   G = F'_aa - M F'_ta
//! tr(H C)  = tr(H~ A^-1) + tr(H'_tt K),   H~ = H'_aa - M H'_ta - H'_at M^T + M H'_tt M^T
//! ln det   = ln det A + ln det F'_tt
//! ```
//!
//! so a step's criterion (O1, D-optimality, the predicted error) and its gradient are those of
//! the arm's `p_a` columns with the fixed information `G` and the test information `H~`, the
//! constants added: the step costs what it costs on a fixed base. The spectral indices (O3,
//! O4, O5) and groups spread over stations take the whole Jacobian.

use super::jacobian::Column;
use super::CalibrationDesign;
use nalgebra::{DMatrix, Vector3};

/// The smallest ratio of `F'_tt`'s Cholesky pivots (smallest over largest) a step is reduced
/// at: `K = F'_tt^-1` then loses at most about `1e12 eps` relative; a carrier block the fixed
/// postures determine worse is scored on the whole Jacobian, as without the reduction.
const PIVOT_RATIO: f64 = 1e-6;

/// The constants of a reduced design ([`reduce`]): what the eliminated carrier block adds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Schur {
    /// The carrier columns eliminated (0 on a design that is not reduced).
    pub(super) eliminated: usize,
    /// `tr(H'_tt K)`, added to `tr(H~ A^-1)`.
    pub(super) trace: f64,
    /// `ln det F'_tt` over two: the sum of the logarithms of its Cholesky pivots.
    pub(super) log_pivots: f64,
    /// The smallest and the largest Cholesky pivot of `F'_tt` (in the rank rule with `A`'s,
    /// [`super::RANK_TOLERANCE`]).
    pub(super) pivots: (f64, f64),
}

/// The step's design reduced to the arm's columns (module docs), or `None` when it does not
/// apply: no carrier column kept, a registration column not kept, or a carrier block `F'_tt`
/// that the fixed postures do not determine well (pivots within [`PIVOT_RATIO`]).
pub(super) fn reduce(d: &CalibrationDesign) -> Option<CalibrationDesign> {
    let l = &d.layout;
    let carrier: Vec<usize> = (0..l.columns.len())
        .filter(|&c| matches!(l.columns[c], Column::Carrier(_)))
        .collect();
    let arm: Vec<usize> = (0..l.columns.len())
        .filter(|&c| !matches!(l.columns[c], Column::Carrier(_)))
        .collect();
    let find = |want: Column| l.columns.iter().position(|c| *c == want);
    let rotation: Vec<usize> = (0..3)
        .map(|a| find(Column::FrameRotation(a)))
        .collect::<Option<_>>()?;
    let translation: Vec<usize> = (0..3)
        .map(|a| find(Column::FrameTranslation(a)))
        .collect::<Option<_>>()?;
    if carrier.is_empty() {
        return None;
    }
    let u = congruence(d, &carrier, &rotation, &translation);
    let f = u.tr_mul(&(&d.fixed_information * &u));
    let h = u.tr_mul(&(&d.test_information * &u));
    let block = |m: &DMatrix<f64>, rows: &[usize], cols: &[usize]| {
        DMatrix::from_fn(rows.len(), cols.len(), |i, j| m[(rows[i], cols[j])])
    };
    let cholesky = block(&f, &carrier, &carrier).cholesky()?;
    let pivots = cholesky.l_dirty().diagonal();
    let (low, high) = (pivots.min(), pivots.max());
    if low <= PIVOT_RATIO * high {
        return None;
    }
    let k = cholesky.inverse();
    let m = block(&f, &arm, &carrier) * &k;
    let h_at = block(&h, &arm, &carrier);
    let g = block(&f, &arm, &arm) - &m * block(&f, &carrier, &arm);
    let cross = &m * h_at.transpose();
    let test = block(&h, &arm, &arm) - &cross - cross.transpose()
        + &m * block(&h, &carrier, &carrier) * m.transpose();
    let schur = Schur {
        eliminated: carrier.len(),
        trace: block(&h, &carrier, &carrier).component_mul(&k).sum(),
        log_pivots: pivots.iter().map(|v| v.ln()).sum(),
        pivots: (low, high),
    };
    let kept: Vec<usize> = arm.iter().map(|&c| d.kept[c]).collect();
    let scales = arm.iter().map(|&c| l.scales[c]).collect();
    Some(CalibrationDesign {
        layout: l.subset(&kept, scales),
        kept,
        table: DMatrix::zeros(0, arm.len()),
        fixed: DMatrix::zeros(d.fixed.nrows(), 0),
        fixed_information: g,
        test_information: test,
        schur,
        reduced: None,
        ..d.clone()
    })
}

/// `U` of the module docs (`p x p`): the identity, with each carrier column's combination of the
/// registration's rotation and translation columns (scaled) subtracted in its column.
fn congruence(
    d: &CalibrationDesign,
    carrier: &[usize],
    rotation: &[usize],
    translation: &[usize],
) -> DMatrix<f64> {
    let l = &d.layout;
    let (at_origin, axes) = l.carrier_terms(&[Vector3::zeros()], d.station.as_slice());
    let mut u = DMatrix::identity(l.columns.len(), l.columns.len());
    for &c in carrier {
        let Column::Carrier(slot) = l.columns[c] else {
            continue;
        };
        for a in 0..3 {
            u[(rotation[a], c)] = -l.scales[c] * axes[slot][a] / l.scales[rotation[a]];
            u[(translation[a], c)] =
                -l.scales[c] * at_origin[0][slot][a] / l.scales[translation[a]];
        }
    }
    u
}
