//! Why the ladder fitted the rung it fitted, in words: where a rung predicted the held-out groups
//! better than the one fitted, the one-standard-error rule ([`super::ladder::choose`]) and its
//! figures.

use super::ladder::{Ladder, Rung};
use stiffid_core::common::choice::Choice;

/// The scored rung (not skipped) with the least held-out error; `None` when none was scored.
pub fn best(rungs: &[Rung]) -> Option<usize> {
    let total = |r: &Rung| r.errors.iter().sum::<f64>();
    (0..rungs.len())
        .filter(|&i| rungs[i].skipped.is_none() && !rungs[i].errors.is_empty())
        .min_by(|&a, &b| total(&rungs[a]).total_cmp(&total(&rungs[b])))
}

/// The mean of the paired per-posture differences of the held-out squared errors of `a` over
/// `b` and its standard error, m^2.
fn paired(a: &Rung, b: &Rung) -> (f64, f64) {
    let d: Vec<f64> = (a.errors.iter().zip(&b.errors))
        .map(|(x, y)| x - y)
        .collect();
    let n = d.len().max(1) as f64;
    let mean = d.iter().sum::<f64>() / n;
    let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, (var / n).sqrt())
}

/// The rung's name: `arm + maps`.
pub fn name(r: &Rung) -> String {
    format!(
        "{}{}",
        r.gravity.name(),
        if r.maps { " + maps" } else { "" }
    )
}

/// Why `ladder` fitted its chosen rung, one sentence (module docs).
pub fn why(ladder: &Ladder) -> String {
    if ladder.folds == 0 {
        return "too few distinct postures to hold out groups: the first rung fitted".into();
    }
    let rungs = &ladder.rungs;
    let chosen = &rungs[ladder.chosen];
    let Some(b) = best(rungs) else {
        return "no rung was scored: the first fitted".into();
    };
    if b == ladder.chosen {
        return "the least held-out error of the rungs scored".into();
    }
    let best = &rungs[b];
    let (mean, se) = paired(chosen, best);
    format!(
        "{} predicts the held-out groups best ({:.4} mm RMS against {:.4} mm), but by less than one standard error of the paired per-posture differences (the squared error per posture {:.3e} mm^2 lower on average, one standard error {:.3e} mm^2): the one-standard-error rule fits the simplest rung within one standard error of the best, never one that a simpler rung beats",
        name(best),
        best.rms.unwrap_or(f64::NAN) * 1e3,
        chosen.rms.unwrap_or(f64::NAN) * 1e3,
        mean * 1e6,
        se * 1e6,
    )
}
