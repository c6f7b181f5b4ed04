//! The cell's feasibility checks ([`stiffid_core::cell`]) as smooth inequality constraints `c(q) <= 0` on
//! one posture, for the SQP.

use nalgebra::Vector6;
use stiffid_core::cell::{CheckKind, Checker, Margin};
use stiffid_core::setup::Setup;

/// The margin a design keeps to every constraint of the cell, m: `margin` when stated
/// ([`super::SearchOptions::margin`]), else the tracker's registration uncertainty
/// ([`stiffid_core::setup::Tracker::registration_uncertainty`]), else 0.
pub(crate) fn design_margin(setup: &Setup, margin: Option<f64>) -> f64 {
    margin
        .or_else(|| setup.tracker().and_then(|t| t.registration_uncertainty))
        .unwrap_or(0.0)
}

/// The checker of a design on `setup`: every check but the bounds keeps [`design_margin`]
/// ([`Checker::keeping`]). The searches, the start groups and a pool's filter use it.
pub(crate) fn design_checker(setup: &Setup, margin: Option<f64>) -> Checker<'_> {
    Checker::new(setup).keeping(design_margin(setup, margin))
}

/// What a search keeps on top of every check's margin (m, or rad for angles; the bounds excepted,
/// which the SQP keeps exactly): 0.1 mm, so that postures written with 6 decimals of a degree
/// still pass the exact checks.
const SLACK: f64 = 1e-4;

/// How far below [`SLACK`] a pair's margin may fall and still count as kept (m, or rad): 1 nm.
/// A search ends on its active constraints, met to the SQP's feasibility tolerance and rounding
/// (a margin of `SLACK - 2e-15` m); counted as a violation, it made the start, exactly outside
/// every constraint, beat a better group on them (a 36-posture design kept its start, 29% worse).
const ROUNDING: f64 = 1e-9;

/// Weight below which a pair's gradient is left out of a smooth minimum's: `2^-60`, under the
/// rounding of a weighted sum of terms of weight up to 1.
const NEGLIGIBLE: f64 = 8.673617379884035e-19;

/// `(m_i - m_min) / tau` beyond which a margin's term `exp(-(m_i - m_min) / tau)` of the smooth
/// minimum is left out (below `exp(-40) ~ 4e-18`).
const FAR_EXPONENT: f64 = 40.0;

/// Scale of the smooth minimum of a check's margins over its pairs, for lengths (m).
const SMOOTHING_M: f64 = 2e-3;
/// The same for angles (rad).
const SMOOTHING_RAD: f64 = 5e-3;

/// The checks a search constrains: every check of the checker but the bounds (which the SQP keeps
/// by itself).
pub(super) fn kinds(checker: &Checker) -> Vec<CheckKind> {
    checker
        .kinds()
        .iter()
        .copied()
        .filter(|&k| k != CheckKind::Bounds)
        .collect()
}

/// One inequality `c_k(q) <= 0` per check k of `kinds`: `c_k = SLACK - softmin_k`, with the
/// smooth minimum of the check's pair margins `softmin = m_min - tau ln sum_i exp(-(m_i - m_min) /
/// tau)` (tau 2 mm, or 0.005 rad for angles). `softmin <= m_min`, so `c_k <= 0` implies that the
/// exact check passes (at most `tau ln(pairs)` conservative), and unlike the minimum it has a
/// continuous gradient.
pub(super) fn inequalities(checker: &Checker, kinds: &[CheckKind], q: &Vector6<f64>) -> Vec<f64> {
    if kinds.is_empty() {
        return Vec::new();
    }
    let (minima, _) = smooth_minima(&checker.margins(q));
    kinds.iter().map(|&k| SLACK - minima[k as usize]).collect()
}

/// How much posture `q` misses the checks by, the search's [`SLACK`] included (m and rad
/// summed over the failing pairs; the bounds excepted, which the searches keep exactly): 0 when
/// it passes them all with the slack.
pub(super) fn violation(checker: &Checker, q: &Vector6<f64>) -> f64 {
    if !checker.constrains() {
        return 0.0;
    }
    margins_violation(&checker.margins(q))
}

/// [`violation`] from the margins of [`Checker::margins`] (or those of
/// [`Checker::margins_and_gradients`], the same): the bounds excepted, which the searches keep
/// exactly.
fn margins_violation(margins: &[Margin]) -> f64 {
    margins
        .iter()
        .filter(|m| m.kind != CheckKind::Bounds)
        .map(|m| (SLACK - ROUNDING - m.margin).max(0.0))
        .sum()
}

/// The cell's checks of one posture as the searches constrain them ([`cell_constraints`]).
#[derive(Debug, Clone, PartialEq)]
pub struct CellConstraints {
    /// One smooth inequality `c_k(q) <= 0` per check `k` of [`Checker::kinds`] but the bounds, in
    /// that order: `c_k = 1e-4 - softmin_k` (m: 0.1 mm kept on top; rad for the incidence angle:
    /// 0.1 mrad), the smooth
    /// minimum of the check's pair margins `softmin = m_min - tau ln sum_i exp(-(m_i - m_min) /
    /// tau)`, tau 2 mm (0.005 rad), never above the exact minimum: `c_k <= 0` implies that the
    /// exact check passes.
    pub values: Vec<f64>,
    /// The exact gradient of each value in the six axis angles (m/rad, or rad/rad).
    pub gradients: Vec<Vector6<f64>>,
    /// How much the posture misses the checks of the values by, the `1e-4` kept on top included
    /// (m and rad summed over the failing pairs, from the exact margins; the bounds excepted): 0
    /// when it passes them all.
    pub violation: f64,
}

/// The cell's checks of `checker` (floor, obstacles, self-collision, rope, line of sight,
/// incidence, `[constraints]`; the bounds excepted, which an optimiser keeps as bounds) as the
/// posture searches constrain posture `q` (axis angles, rad): smooth inequalities with their exact
/// gradients and the posture's exact violation ([`CellConstraints`]), for an optimiser of one's
/// own. Without a cell or a tracker there are no values and the violation is 0. A posture with
/// an angle that is not finite violates every constraint: each value and the violation are
/// `+infinity`, the gradients zero.
///
/// # Examples
/// A posture whose constraints all hold passes the exact checks.
/// ```
/// use stiffid_core::cell::Checker;
/// use stiffid_design::search::cell_constraints;
/// let text = stiffid_core::setup::builtin_text("zhang2021-comau-nj165")?.to_string()
///     + "[cell]\nfloor_z_mm = 0.0\n[tracker]\nposition_mm = [3000.0, -2000.0, 1500.0]\n";
/// let setup = stiffid_core::setup::parse(&text, "cell.toml", |r, _| stiffid_core::robot::presets::get(r))?;
/// let checker = Checker::new(&setup);
/// let mut held = 0;
/// for q in stiffid_design::random_group(&setup, 20, 1) {
///     let c = cell_constraints(&checker, &q);
///     assert_eq!(c.values.len(), checker.kinds().len() - 1);
///     if c.values.iter().all(|v| *v <= 0.0) {
///         assert!(checker.feasibility(&q).feasible());
///         assert_eq!(c.violation, 0.0);
///         held += 1;
///     }
/// }
/// assert!(held > 0);
/// let lost = cell_constraints(&checker, &nalgebra::Vector6::repeat(f64::NAN));
/// assert!(lost.values.iter().all(|v| *v == f64::INFINITY));
/// # Ok::<(), stiffid_core::Error>(())
/// ```
pub fn cell_constraints(checker: &Checker, q: &Vector6<f64>) -> CellConstraints {
    let kinds = kinds(checker);
    if !q.iter().all(|a| a.is_finite()) {
        return CellConstraints {
            values: vec![f64::INFINITY; kinds.len()],
            gradients: vec![Vector6::zeros(); kinds.len()],
            violation: f64::INFINITY,
        };
    }
    inequalities_and_gradients(checker, &kinds, q)
}

/// [`inequalities`] and their exact gradients in the six angles of `q`, and the posture's
/// [`violation`] (the margins worked out once): the gradient of the smooth minimum is the
/// average of the pairs' margin gradients ([`Checker::margins_and_gradients`]) weighted by
/// `exp(-(m_i - m_min) / tau) / sum`. A pair whose weight is below [`NEGLIGIBLE`] (its margin
/// more than [`FAR_EXPONENT`] tau, 8 cm or 0.2 rad, above the check's smallest) is left out: its
/// term is below the rounding of the sum.
pub(super) fn inequalities_and_gradients(
    checker: &Checker,
    kinds: &[CheckKind],
    q: &Vector6<f64>,
) -> CellConstraints {
    if kinds.is_empty() {
        let violation = violation(checker, q);
        return CellConstraints {
            values: Vec::new(),
            gradients: Vec::new(),
            violation,
        };
    }
    let (margins, gradients) = checker.margins_and_gradients(q);
    let (minima, weights) = smooth_minima(&margins);
    let mut sums = [Vector6::zeros(); CheckKind::ALL.len()];
    for (i, (m, &w)) in margins.iter().zip(&weights).enumerate() {
        if w >= NEGLIGIBLE {
            sums[m.kind as usize] += gradients.gradient(i) * w;
        }
    }
    CellConstraints {
        values: kinds.iter().map(|&k| SLACK - minima[k as usize]).collect(),
        gradients: kinds.iter().map(|&k| -sums[k as usize]).collect(),
        violation: margins_violation(&margins),
    }
}

/// The smooth minimum of each check's margins, indexed by `CheckKind as usize` (`+infinity` for
/// a check without margins, the exact minimum where it is not finite), and each margin's weight
/// in its check's gradient (a check's weights sum to 1; 0 where its minimum is not finite): every
/// check in the same passes over the margins, one `exp` per margin, none for a margin more than
/// [`FAR_EXPONENT`] `tau` above its check's minimum (its term, below `4e-18`, is under the
/// rounding of the sum, which is at least 1).
fn smooth_minima(margins: &[Margin]) -> ([f64; CheckKind::ALL.len()], Vec<f64>) {
    let mut min = [f64::INFINITY; CheckKind::ALL.len()];
    for m in margins {
        let k = m.kind as usize;
        min[k] = min[k].min(m.margin);
    }
    let mut sum = [0.0; CheckKind::ALL.len()];
    let mut weights: Vec<f64> = margins
        .iter()
        .map(|m| {
            let k = m.kind as usize;
            let x = (m.margin - min[k]) / smoothing(m.kind);
            if !min[k].is_finite() || x > FAR_EXPONENT {
                return 0.0;
            }
            let e = (-x).exp();
            sum[k] += e;
            e
        })
        .collect();
    for (w, m) in weights.iter_mut().zip(margins) {
        // A check with a NaN margin has a NaN sum: its weights are 0 (no gradient).
        let s = sum[m.kind as usize];
        *w = if s > 0.0 { *w / s } else { 0.0 };
    }
    let mut soft = min;
    for (k, kind) in CheckKind::ALL.iter().enumerate() {
        if min[k].is_finite() {
            soft[k] = min[k] - smoothing(*kind) * sum[k].ln();
        }
    }
    (soft, weights)
}

/// The smooth minimum's scale of a check: [`SMOOTHING_RAD`] for angles, else [`SMOOTHING_M`].
fn smoothing(kind: CheckKind) -> f64 {
    match kind.is_angle() {
        true => SMOOTHING_RAD,
        false => SMOOTHING_M,
    }
}

/// The check that fails in the most postures of `groups`, with that count and the number of
/// postures; `None` if every posture passes.
pub(super) fn most_failed<'g>(
    checker: &Checker,
    groups: impl Iterator<Item = &'g [Vector6<f64>]>,
) -> Option<(CheckKind, usize, usize)> {
    let mut counts = [0usize; CheckKind::ALL.len()];
    let mut total = 0;
    for q in groups.flatten() {
        total += 1;
        for c in checker.feasibility(q).violations() {
            counts[c.kind as usize] += 1;
        }
    }
    let (i, &n) = counts
        .iter()
        .enumerate()
        .max_by_key(|&(i, n)| (*n, std::cmp::Reverse(i)))?;
    (n > 0).then_some((CheckKind::ALL[i], n, total))
}
