//! What the study found, in sentences: the [`Findings`] put into words for the summary, the
//! terminal and the reports; how each group was obtained, in words.

use stiffid_design::study::{Findings, Origin, Study};

/// The keys of the design criteria in documents, in the order of
/// [`stiffid_design::study::criterion_values`] and [`Findings::rank_correlation`].
pub(crate) const CRITERION_KEYS: [&str; 7] = [
    "classical",
    "zhang2021",
    "scaled_cond",
    "d_optimal",
    "relative_a",
    "test_pose_mm",
    "cond_psi",
];

/// The findings as sentences for the terminal and the reports.
pub fn sentences(f: &Findings, study: &Study) -> Vec<String> {
    let avg = |g: usize| study.groups[g].average_deviation_pct();
    let title = |g: usize| study.groups[g].title.clone();
    let level = study.validation_level + 1;
    let mut out = Vec::new();
    if let [a, b] = f.group3.as_slice() {
        out.push(format!(
            "{} {} Groups 1 and 2, {} the paper claims: average deviation rate {:.3}% against {:.3}% ({}) and {:.3}% ({}); at level {level} it is lower than Group 1 on {} and lower than Group 2 on {}.",
            title(2),
            if f.paper_claim_holds { "beats" } else { "does not beat" },
            if f.paper_claim_holds { "as" } else { "unlike what" },
            avg(2),
            avg(0),
            ratio_words(a.factor),
            avg(1),
            ratio_words(b.factor),
            joints(&a.joints_better),
            joints(&b.joints_better),
        ));
    }
    if let Some(r) = &f.relative_a {
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
    let check = &f.start_check;
    if let (wins, n @ 1.., Some((lo, hi))) = (check.wins, check.trials, check.zhang_range_pct) {
        let seeds = study
            .trials
            .first()
            .zip(study.trials.last())
            .map(|(a, b)| format!("{}-{}", a.seed, b.seed))
            .unwrap_or_default();
        let global = f.relative_a.as_ref().map_or(String::new(), |r| {
            format!(
                "; the globally searched relative-a group's is {:.3}%",
                study.groups[r.other].predicted_average_pct()
            )
        });
        out.push(format!(
            "Does that depend on the start group? From {n} seeded start groups (seeds {seeds}), the zhang2021 local search beats both its start group and the classical local search in {wins} of {n} (first-order predicted average deviation rate); its predicted average ranges from {lo:.3}% to {hi:.3}%{global}."
        ));
    }
    out.push(format!(
        "The first-order prediction 100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj) {} the simulation: mean |simulated/predicted - 1| = {:.1}% over all groups, levels and joints ({} runs each){}.",
        if f.prediction_error < 0.1 { "matches" } else { "departs from" },
        100.0 * f.prediction_error,
        study.runs,
        if f.prediction_error < 0.1 { "" } else { "; it holds for small errors only, and some groups here identify a joint with errors of tens of percent" }
    ));
    let best = (0..CRITERION_KEYS.len()).max_by(|&a, &b| {
        f.rank_correlation[a]
            .unwrap_or(-2.0)
            .total_cmp(&f.rank_correlation[b].unwrap_or(-2.0))
    });
    if let Some(b) = best {
        let rho = |c: usize| f.rank_correlation[c].map_or("n/a".into(), |r| format!("{r:+.2}"));
        out.push(format!(
            "Which criterion predicts accuracy (Spearman's rho between criterion and average deviation rate over the {} groups): best {} (rho {}); the paper's zhang2021 {}, classical {}.",
            study.groups.len(),
            CRITERION_KEYS[b],
            rho(b),
            rho(1),
            rho(0)
        ));
    }
    out
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

/// How a group was obtained, in words.
pub fn search_words(origin: &Origin, seed: u64) -> String {
    match origin {
        Origin::Start => format!(
            "seeded random start group: a Latin hypercube in the bounds (seed {seed}; each axis range cut into 6 equal strata, one posture per stratum of every axis, uniform within it)"
        ),
        Origin::Local(c) => format!("`{c}` minimised by SQP from Group 1 (as the paper)"),
        Origin::Global(c, n) => format!(
            "`{c}` minimised globally: best of {n} SQP searches from seeded Latin-hypercube starts (beyond the paper)"
        ),
    }
}
