//! What the study found, in numbers: does Group 3 beat Groups 1 and 2 (the paper's claim), by how
//! much does the globally searched `relative-a` group beat Group 3, does the first-order
//! prediction hold, which criterion predicts accuracy.

use super::{spearman, Group, Origin, Study};
use crate::{Criterion, Evaluation};

/// How many values [`criterion_values`] gives.
pub(crate) const CRITERION_VALUES: usize = Criterion::ALL.len() + 1;

/// The values a group's accuracy is ranked against: every criterion of [`Criterion::ALL`] in that
/// order ([`Criterion::TestPose`] in m), then `cond_2(Psi)` (SI units).
pub fn criterion_values(e: &Evaluation) -> [f64; CRITERION_VALUES] {
    std::array::from_fn(|i| match Criterion::ALL.get(i) {
        Some(&c) => e.value(c),
        None => e.cond_psi,
    })
}

/// One group against another.
#[derive(Debug, Clone, PartialEq)]
pub struct Versus {
    /// Index of the other group.
    pub other: usize,
    /// The other group's average deviation rate / this group's (> 1: this group better).
    pub factor: f64,
    /// Joints (1-based) on which this group's mean deviation rate is lower, at the validation
    /// level.
    pub joints_better: Vec<usize>,
}

/// The start-group check in numbers ([`super::StartTrial`]).
#[derive(Debug, Clone, PartialEq)]
pub struct StartCheck {
    /// Start groups in which the `zhang2021` local search beats both the start group and the
    /// `classical` local search (predicted).
    pub wins: usize,
    /// Start groups checked.
    pub trials: usize,
    /// Lowest and highest predicted average deviation rate of the `zhang2021` local searches, %
    /// (`None` without start groups).
    pub zhang_range_pct: Option<(f64, f64)>,
}

/// The study's findings.
#[derive(Debug, Clone, PartialEq)]
pub struct Findings {
    /// Group 3 against Groups 1 and 2 (empty if the study has fewer than 3 groups).
    pub group3: Vec<Versus>,
    /// Whether Group 3 has a lower average deviation rate than Groups 1 and 2.
    pub paper_claim_holds: bool,
    /// The globally searched `relative-a` group against Group 3 (`other` is the `relative-a`
    /// group's index, `factor` Group 3's average deviation rate / its own, `joints_better` the
    /// joints on which it is better at the validation level).
    pub relative_a: Option<Versus>,
    /// The start-group check.
    pub start_check: StartCheck,
    /// Mean of |simulated / predicted - 1| over groups, levels and joints (finite ratios only).
    pub prediction_error: f64,
    /// Spearman's rank correlation ([`spearman`]) between each of the [`criterion_values`] and
    /// the average deviation rate over the groups, in that order (`None` if undefined).
    pub rank_correlation: Vec<Option<f64>>,
}

/// Group `a` against group `b`.
fn versus(study: &Study, a: usize, b: usize) -> Versus {
    let (ga, gb) = (&study.groups[a], &study.groups[b]);
    let l = study.validation_level;
    Versus {
        other: b,
        factor: gb.average_deviation_pct() / ga.average_deviation_pct(),
        joints_better: (1..=6)
            .filter(|&j| {
                ga.simulation.mean_deviation_pct[l][j - 1]
                    < gb.simulation.mean_deviation_pct[l][j - 1]
            })
            .collect(),
    }
}

/// The findings of a study whose groups 1-3 are start, classical, zhang2021 (as [`super::run`]
/// makes them).
pub fn findings(study: &Study) -> Findings {
    let group3: Vec<Versus> = match study.groups.len() >= 3 {
        true => vec![versus(study, 2, 0), versus(study, 2, 1)],
        false => Vec::new(),
    };
    let relative_a = study
        .groups
        .iter()
        .position(|g| matches!(g.origin, Origin::Global(Criterion::RelativeA, _)))
        .filter(|_| study.groups.len() >= 3)
        .map(|r| Versus {
            other: r,
            ..versus(study, r, 2)
        });
    Findings {
        paper_claim_holds: !group3.is_empty() && group3.iter().all(|v| v.factor > 1.0),
        group3,
        relative_a,
        start_check: start_check(study),
        prediction_error: prediction_error(study),
        rank_correlation: rank_correlation(study),
    }
}

fn start_check(study: &Study) -> StartCheck {
    let zhang = study.trials.iter().map(|t| t.predicted_average_pct[2]);
    StartCheck {
        wins: study.trials.iter().filter(|t| t.zhang_beats_both()).count(),
        trials: study.trials.len(),
        zhang_range_pct: (!study.trials.is_empty()).then(|| {
            zhang.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
        }),
    }
}

fn prediction_error(study: &Study) -> f64 {
    let pairs: Vec<f64> = study
        .groups
        .iter()
        .flat_map(|g| {
            let s = &g.simulation;
            s.mean_deviation_pct
                .iter()
                .zip(&s.predicted_deviation_pct)
                .flat_map(|(m, p)| (0..6).map(move |j| (m[j] / p[j] - 1.0).abs()))
        })
        .filter(|v| v.is_finite())
        .collect();
    pairs.iter().sum::<f64>() / pairs.len().max(1) as f64
}

fn rank_correlation(study: &Study) -> Vec<Option<f64>> {
    let averages: Vec<f64> = study
        .groups
        .iter()
        .map(Group::average_deviation_pct)
        .collect();
    (0..CRITERION_VALUES)
        .map(|c| {
            let xs: Vec<f64> = study
                .groups
                .iter()
                .map(|g| criterion_values(&g.evaluation)[c])
                .collect();
            spearman(&xs, &averages)
        })
        .collect()
}
