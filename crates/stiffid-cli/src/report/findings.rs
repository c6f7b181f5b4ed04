//! What the study found, in numbers and sentences: does Group 3 beat Groups 1 and 2 (the paper's
//! claim), by how much does the globally searched `relative-a` group beat Group 3, does the
//! first-order prediction hold, which criterion predicts accuracy.

use super::{criteria_values, CRITERIA};
use crate::study::{Group, Origin, Study};
use stiffid::design::Criterion;

/// Group 3 against another group.
#[derive(Debug, Clone, PartialEq)]
pub struct Versus {
    /// Index of the other group.
    pub other: usize,
    /// Other's average deviation rate / Group 3's (> 1: Group 3 better).
    pub factor: f64,
    /// Joints (1-based) on which the group's mean deviation rate is lower, at the validation level.
    pub joints_better: Vec<usize>,
}

/// The study's findings.
#[derive(Debug, Clone, PartialEq)]
pub struct Findings {
    /// Group 3 against Groups 1 and 2 (empty if the study has fewer than 3 groups).
    pub group3: Vec<Versus>,
    /// Whether Group 3 has a lower average deviation rate than Groups 1 and 2.
    pub paper_claim_holds: bool,
    /// The globally searched `relative-a` group against Group 3: (its index, Group 3's average
    /// deviation rate / its own, joints on which it is better at the validation level).
    pub relative_a: Option<Versus>,
    /// Start groups of the start-group check in which the `zhang2021` local search beats both the
    /// start group and the `classical` local search (predicted), and how many there were.
    pub start_check: (usize, usize),
    /// Mean of |simulated / predicted - 1| over groups, levels and joints.
    pub prediction_error: f64,
    /// Spearman's rank correlation between each criterion and the average deviation rate over
    /// the groups, in [`CRITERIA`] order (`None` if undefined).
    pub rank_correlation: Vec<Option<f64>>,
}

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

/// The findings of a study whose groups 1-3 are start, classical, zhang2021.
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
    let averages: Vec<f64> = study
        .groups
        .iter()
        .map(Group::average_deviation_pct)
        .collect();
    Findings {
        paper_claim_holds: !group3.is_empty() && group3.iter().all(|v| v.factor > 1.0),
        group3,
        relative_a,
        start_check: (
            study.trials.iter().filter(|t| t.zhang_beats_both()).count(),
            study.trials.len(),
        ),
        prediction_error: prediction_error(study),
        rank_correlation: (0..CRITERIA.len())
            .map(|c| {
                let xs: Vec<f64> = study
                    .groups
                    .iter()
                    .map(|g| criteria_values(&g.evaluation)[c].1)
                    .collect();
                spearman(&xs, &averages)
            })
            .collect(),
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

fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut k = i;
        while k + 1 < order.len() && v[order[k + 1]] == v[order[i]] {
            k += 1;
        }
        for &o in &order[i..=k] {
            r[o] = 0.5 * (i + k) as f64 + 1.0;
        }
        i = k + 1;
    }
    r
}

/// Spearman's rank correlation of two equally long samples (ties get mean ranks); `None` for fewer
/// than 3 values or a constant sample.
pub fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    if x.len() < 3 || x.len() != y.len() {
        return None;
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let mean = (x.len() as f64 + 1.0) / 2.0;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        sxy += (a - mean) * (b - mean);
        sxx += (a - mean).powi(2);
        syy += (b - mean).powi(2);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

impl Findings {
    /// The findings as sentences for the terminal and the reports.
    pub fn sentences(&self, study: &Study) -> Vec<String> {
        let avg = |g: usize| study.groups[g].average_deviation_pct();
        let title = |g: usize| study.groups[g].title.clone();
        let level = study.validation_level + 1;
        let mut out = Vec::new();
        if let [a, b] = self.group3.as_slice() {
            out.push(format!(
                "{} {} Groups 1 and 2, {} the paper claims: average deviation rate {:.3}% against {:.3}% ({}) and {:.3}% ({}); at level {level} it is lower than Group 1 on {} and lower than Group 2 on {}.",
                title(2),
                if self.paper_claim_holds { "beats" } else { "does not beat" },
                if self.paper_claim_holds { "as" } else { "unlike what" },
                avg(2),
                avg(0),
                ratio_words(a.factor),
                avg(1),
                ratio_words(b.factor),
                joints(&a.joints_better),
                joints(&b.joints_better),
            ));
        }
        if let Some(r) = &self.relative_a {
            out.push(format!(
                "{} {} Group 3 by a factor {:.2} (average deviation rate {:.3}% against {:.3}%); at level {level} it is lower on {}.",
                title(r.other),
                if r.factor > 1.0 { "beats" } else { "does not beat" },
                r.factor,
                avg(r.other),
                avg(2),
                joints(&r.joints_better)
            ));
        }
        if let (wins, n @ 1..) = self.start_check {
            let zhang = study.trials.iter().map(|t| t.predicted_average_pct[2]);
            let (lo, hi) = zhang.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
            let seeds = study
                .trials
                .first()
                .zip(study.trials.last())
                .map(|(a, b)| format!("{}-{}", a.seed, b.seed))
                .unwrap_or_default();
            let global = self.relative_a.as_ref().map_or(String::new(), |r| {
                let p = &study.groups[r.other].simulation.predicted_deviation_pct;
                format!(
                    "; the globally searched relative-a group's is {:.3}%",
                    p.iter().flatten().sum::<f64>() / (6 * p.len()) as f64
                )
            });
            out.push(format!(
                "Does that depend on the start group? From {n} seeded start groups (seeds {seeds}), the zhang2021 local search beats both its start group and the classical local search in {wins} of {n} (first-order predicted average deviation rate); its predicted average ranges from {lo:.3}% to {hi:.3}%{global}."
            ));
        }
        out.push(format!(
            "The first-order prediction 100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj) {} the simulation: mean |simulated/predicted - 1| = {:.1}% over all groups, levels and joints ({} runs each){}.",
            if self.prediction_error < 0.1 { "matches" } else { "departs from" },
            100.0 * self.prediction_error,
            study.runs,
            if self.prediction_error < 0.1 { "" } else { "; it holds for small errors only, and some groups here identify a joint with errors of tens of percent" }
        ));
        let best = (0..CRITERIA.len()).max_by(|&a, &b| {
            self.rank_correlation[a]
                .unwrap_or(-2.0)
                .total_cmp(&self.rank_correlation[b].unwrap_or(-2.0))
        });
        if let Some(b) = best {
            let rho =
                |c: usize| self.rank_correlation[c].map_or("n/a".into(), |r| format!("{r:+.2}"));
            out.push(format!(
                "Which criterion predicts accuracy (Spearman's rho between criterion and average deviation rate over the {} groups): best {} (rho {}); the paper's zhang2021 {}, classical {}.",
                study.groups.len(),
                CRITERIA[b].0,
                rho(b),
                rho(1),
                rho(0)
            ));
        }
        out
    }
}

/// "joints 1, 4 (2 of 6)", "every joint", "no joint".
fn joints(list: &[usize]) -> String {
    match list.len() {
        0 => "no joint".into(),
        6 => "every joint".into(),
        1 => format!("joint {} only", list[0]),
        n => {
            let names: Vec<String> = list.iter().map(|j| j.to_string()).collect();
            format!("joints {} ({n} of 6)", names.join(", "))
        }
    }
}

fn ratio_words(factor: f64) -> String {
    match factor >= 1.0 {
        true => format!("{factor:.2}x lower"),
        false => format!("{:.2}x higher", 1.0 / factor),
    }
}

#[cfg(test)]
mod tests {
    use super::spearman;

    #[test]
    fn spearman_of_monotone_reversed_and_tied_samples() {
        let x = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(spearman(&x, &[10.0, 20.0, 25.0, 100.0]), Some(1.0));
        assert_eq!(spearman(&x, &[4.0, 3.0, 2.0, 1.0]), Some(-1.0));
        assert_eq!(spearman(&x, &[1.0, 1.0, 1.0, 1.0]), None);
        // x ranks 1..5, y ranks 2,1,4,3,5: d^2 = 4, rho = 1 - 6*4/(5*24) = 0.8.
        let rho = spearman(&[1.0, 2.0, 3.0, 4.0, 5.0], &[2.0, 1.0, 4.0, 3.0, 5.0]).unwrap();
        assert!((rho - 0.8).abs() < 1e-12);
    }
}
