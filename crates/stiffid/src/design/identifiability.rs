//! Which parameters of the model a group of postures identifies, from the column-scaled rank of
//! its observation matrix.
//!
//! `Psi` (`3pn x n`, one column per parameter: the six drives, then the model's virtual springs)
//! is scaled to unit column norms, `Psi_e = Psi diag(1 / |psi_j|)`, so that units and sizes of
//! the compliances do not count; its singular values `s_k` and right singular vectors `v_k` (by
//! one-sided Jacobi of its triangular factor) then give its numerical null space, the `v_k` with
//! `s_k <= RANK_TOLERANCE s_max` ([`crate::lsq::RANK_TOLERANCE`], the rule of
//! [`crate::lsq::Factor::try_new`]). A change of the compliances along a null vector changes no
//! measured displacement: the parameters it involves cannot be separated by the group.
//! Parameter j is **identified** when the null space has no share in it (`|P_null e_j| <= 0.01`,
//! `P_null` the projector on the null space), and a zero column (no posture loads the spring or
//! no measuring point moves with it) is a null space of its own.

use crate::linalg::householder_qr_columns;
use crate::lsq::RANK_TOLERANCE;
use nalgebra::DMatrix;

/// Share of the null space in a parameter above which it counts as not identified.
const SHARE: f64 = 0.01;

/// Entry of a null vector above which its parameter is named in the combination.
const COMBINATION_ENTRY: f64 = 0.1;

/// Which parameters a group of postures identifies (module docs). Parameters are numbered in the
/// model's order: the drives `0..6` (`k1` .. `k6`), then the virtual springs.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Identifiability {
    /// The numerical rank of the column-scaled `Psi` (the number of parameters when the group
    /// identifies them all).
    pub rank: usize,
    /// The parameters the group does not identify, ascending.
    pub unidentified: Vec<usize>,
    /// The combinations of parameters the group cannot separate: for each null vector, the
    /// parameters with an entry above 0.1 in it (a basis of the null space, so one parameter may
    /// appear in several).
    pub combinations: Vec<Vec<usize>>,
}

impl Identifiability {
    /// The identifiability of the parameters of an observation matrix `psi` (`m x n`, or any
    /// matrix with its column norms and Gram matrix, such as a group's stacked compact blocks).
    /// Non-finite entries identify nothing.
    pub fn of(psi: &DMatrix<f64>) -> Self {
        let n = psi.ncols();
        let none = || Self {
            rank: 0,
            unidentified: (0..n).collect(),
            combinations: vec![(0..n).collect()],
        };
        if psi.iter().any(|v| !v.is_finite()) {
            return none();
        }
        let norms: Vec<f64> = psi.column_iter().map(|c| c.norm()).collect();
        let largest = norms.iter().copied().fold(0.0, f64::max);
        let zero: Vec<usize> = (0..n)
            .filter(|&j| norms[j] <= largest * RANK_TOLERANCE)
            .collect();
        if zero.len() == n {
            return none();
        }
        // The scaled columns that are not zero, factored (rows padded to at least their count).
        let kept: Vec<usize> = (0..n).filter(|j| !zero.contains(j)).collect();
        let k = kept.len();
        let m = psi.nrows().max(k);
        let mut a = DMatrix::zeros(m, k);
        for (c, &j) in kept.iter().enumerate() {
            a.view_mut((0, c), (psi.nrows(), 1))
                .copy_from(&(psi.column(j) / norms[j]));
        }
        let mut taus = vec![0.0; k];
        householder_qr_columns(a.as_mut_slice(), m, &mut taus);
        let r = DMatrix::from_fn(k, k, |i, j| if i <= j { a[(i, j)] } else { 0.0 });
        let (s, v) = super::evaluator::singular_values_and_vectors(&r);
        let null: Vec<usize> = (0..k)
            .filter(|&i| s[i] <= s.max() * RANK_TOLERANCE)
            .collect();
        let mut combinations: Vec<Vec<usize>> = zero.iter().map(|&j| vec![j]).collect();
        for &i in &null {
            combinations.push(
                (0..k)
                    .filter(|&c| v[(c, i)].abs() > COMBINATION_ENTRY)
                    .map(|c| kept[c])
                    .collect(),
            );
        }
        let mut unidentified = zero.clone();
        for (c, &j) in kept.iter().enumerate() {
            let share: f64 = null.iter().map(|&i| v[(c, i)] * v[(c, i)]).sum();
            if share.sqrt() > SHARE {
                unidentified.push(j);
            }
        }
        unidentified.sort_unstable();
        Self {
            rank: k - null.len(),
            unidentified,
            combinations,
        }
    }

    /// Whether the group identifies parameter `j` (model order).
    pub fn identifies(&self, j: usize) -> bool {
        !self.unidentified.contains(&j)
    }

    /// Whether the group identifies every parameter.
    pub fn is_complete(&self) -> bool {
        self.unidentified.is_empty()
    }
}
