//! The cell's feasibility checks ([`crate::cell`]) as smooth inequality constraints `c(q) <= 0` on
//! one posture, for the SQP.

use crate::cell::{CheckKind, Checker, Margin};
use nalgebra::Vector6;

/// What a search keeps on top of every check's margin (m, or rad for angles; the bounds excepted,
/// which the SQP keeps exactly): 0.1 mm, so that postures written with 6 decimals of a degree
/// still pass the exact checks.
const SLACK: f64 = 1e-4;

/// Weight below which a pair's gradient is left out of a smooth minimum's: `2^-60`, under the
/// rounding of a weighted sum of terms of weight up to 1.
const NEGLIGIBLE: f64 = 8.673617379884035e-19;

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
    let margins = checker.margins(q);
    kinds
        .iter()
        .map(|&k| SLACK - smooth_min(&margins, k))
        .collect()
}

/// How much posture `q` misses the checks by, the search's [`SLACK`] included (m and rad
/// summed over the failing pairs): 0 when it passes them all with the slack.
pub(super) fn violation(checker: &Checker, q: &Vector6<f64>) -> f64 {
    if !checker.constrains() {
        return 0.0;
    }
    let slack = |k: CheckKind| if k == CheckKind::Bounds { 0.0 } else { SLACK };
    checker
        .margins(q)
        .iter()
        .map(|m| (slack(m.kind) - m.margin).max(0.0))
        .sum()
}

/// [`inequalities`] and their exact gradients in the six angles of `q`: the gradient of the
/// smooth minimum is the average of the pairs' margin gradients
/// ([`Checker::margins_and_gradients`]) weighted by `exp(-(m_i - m_min) / tau) / sum`. A pair
/// whose weight is below [`NEGLIGIBLE`] (its margin more than about 42 tau, 8 cm or 0.2 rad, above the
/// check's smallest) is skipped: its term is below the rounding of the sum.
pub(super) fn inequalities_and_gradients(
    checker: &Checker,
    kinds: &[CheckKind],
    q: &Vector6<f64>,
) -> (Vec<f64>, Vec<Vector6<f64>>) {
    if kinds.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let (margins, gradients) = checker.margins_and_gradients(q);
    kinds
        .iter()
        .map(|&k| {
            let mut g = Vector6::zeros();
            let v = smooth_min_with(&margins, k, |i, w| {
                if w >= NEGLIGIBLE {
                    g += gradients.gradient(i) * w;
                }
            });
            (SLACK - v, -g)
        })
        .unzip()
}

fn smooth_min(margins: &[Margin], kind: CheckKind) -> f64 {
    smooth_min_with(margins, kind, |_, _| ())
}

/// The smooth minimum of the margins of check `kind`; `weight(i, w)` receives the weight of
/// margin i in its gradient (weights summing to 1), where the minimum is finite.
fn smooth_min_with(margins: &[Margin], kind: CheckKind, mut weight: impl FnMut(usize, f64)) -> f64 {
    let tau = match kind.is_angle() {
        true => SMOOTHING_RAD,
        false => SMOOTHING_M,
    };
    let values = || {
        margins
            .iter()
            .enumerate()
            .filter(|(_, m)| m.kind == kind)
            .map(|(i, m)| (i, m.margin))
    };
    let min = values().map(|(_, m)| m).fold(f64::INFINITY, f64::min);
    if !min.is_finite() {
        return min;
    }
    let sum: f64 = values().map(|(_, m)| (-(m - min) / tau).exp()).sum();
    for (i, m) in values() {
        weight(i, (-(m - min) / tau).exp() / sum);
    }
    min - tau * sum.ln()
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
