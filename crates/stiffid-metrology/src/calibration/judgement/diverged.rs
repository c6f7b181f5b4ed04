//! Folds of leave-one-posture-out that diverged, left out of the prediction intervals.
//!
//! A fold without posture `p` is linearised at the full fit: its change is
//! `V S^-1 U_p^T (I - U_p U_p^T)^-1 r_p`, and where posture `p` nearly alone determines a
//! direction of the parameters (its leverage near 1) that change, and the fold's held-out error,
//! grow without bound: metres or more where the robot's error is a fraction of a millimetre.
//! Such a fold says that one posture holds up the fit, not how far a new posture's error lies;
//! left in, it inflates every bound built from the folds: the jackknife+'s quantiles (one fold
//! is `1 / n` of its values) and the variance of the fit's Gaussian bound (a mean square, which
//! one fold can make as large as it likes). A fold whose held-out RMS exceeds `DIVERGED` (30) times
//! the median fold's is left out of both, and the calibration says which and why (a `left-out` warning);
//! the bounds rest on the other folds. A heavy-tailed but finite spread of the postures' errors
//! stays in: on the real UR10 (series C, ten draws of 100 random poses, the default model) the
//! largest leave-one-posture-out error is 3.2 to 9.9 times the median one (docs/model.md).

use crate::calibration::validation::Fold;
use stiffid_core::common::warning::{Warning, WarningKind};

/// The held-out RMS of a fold, as a multiple of the median fold's, beyond which it diverged.
pub(crate) const DIVERGED: f64 = 30.0;

/// The folds of `folds` that did not diverge (module docs), and the warning naming those that
/// did (postures numbered from 1, or by `labels` where given), `None` when none did.
pub fn kept(folds: Vec<Fold>, labels: &[String]) -> (Vec<Fold>, Option<Warning>) {
    let Some(median) = median_rms(&folds) else {
        return (folds, None);
    };
    let (kept, out): (Vec<Fold>, Vec<Fold>) = (folds.into_iter())
        .partition(|f| f.held.errors.is_empty() || !diverges(f.held.rms, median));
    let warning = (!out.is_empty()).then(|| warning(&out, kept.len(), median, labels));
    (kept, warning)
}

/// Whether a fold of held-out RMS `rms` diverged from the median fold's `median` (m): beyond
/// `DIVERGED` (30) times it, or not finite.
fn diverges(rms: f64, median: f64) -> bool {
    matches!(
        rms.partial_cmp(&(DIVERGED * median)),
        Some(std::cmp::Ordering::Greater) | None
    )
}

/// The median of the folds' held-out RMS (those with errors), m; `None` when it is not positive.
fn median_rms(folds: &[Fold]) -> Option<f64> {
    let mut rms: Vec<f64> = (folds.iter())
        .filter(|f| !f.held.errors.is_empty() && f.held.rms.is_finite())
        .map(|f| f.held.rms)
        .collect();
    if rms.is_empty() {
        return None;
    }
    rms.sort_by(f64::total_cmp);
    let n = rms.len();
    let median = match n % 2 {
        1 => rms[n / 2],
        _ => 0.5 * (rms[n / 2 - 1] + rms[n / 2]),
    };
    (median > 0.0).then_some(median)
}

/// The warning ([`WarningKind::LeftOut`]) of the diverged folds `out`, `kept` folds left.
fn warning(out: &[Fold], kept: usize, median: f64, labels: &[String]) -> Warning {
    let name = |p: usize| labels.get(p).cloned().unwrap_or(format!("{}", p + 1));
    let named: Vec<String> = (out.iter())
        .map(|f| format!("{} ({:.4} mm held out)", name(f.posture), f.held.rms * 1e3))
        .collect();
    Warning::new(
        WarningKind::LeftOut,
        format!(
            "the prediction intervals leave out the leave-one-posture-out fold{} of posture{} {}: {} predicted {} held-out posture{} more than {DIVERGED:.0} times worse than the median fold ({:.4} mm), because without {} the fit is nearly undetermined along some direction; the intervals rest on the other {kept} folds (read more postures like {} to keep {} in)",
            plural(out.len()),
            plural(out.len()),
            named.join(", "),
            if out.len() == 1 { "it" } else { "they" },
            if out.len() == 1 { "its" } else { "their" },
            plural(out.len()),
            median * 1e3,
            if out.len() == 1 { "it" } else { "each" },
            if out.len() == 1 { "it" } else { "them" },
            if out.len() == 1 { "it" } else { "them" },
        ),
    )
}

/// `s` for more than one.
fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
