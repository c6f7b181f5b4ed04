//! The simulation study in the library: findings against hand-computed values on a made-up study,
//! the paper's Table 4 and when it applies, a small real study, its progress reports and errors.

use nalgebra::Vector6;
use std::sync::Mutex;
use stiffid::internal::design::{Criterion, Evaluation};
use stiffid::internal::study::simulate::GroupSimulation;
use stiffid::internal::study::{self, Group, Options, Origin, StartTrial, Study};
use stiffid::{internal::setup, Error, Progress, Setup};

fn paper() -> Setup {
    setup::builtin("zhang2021-comau-nj165").unwrap()
}

/// A study of made-up groups on `setup`, without postures: no simulation behind the numbers.
fn made_up(setup: Setup, groups: Vec<Group>, trials: Vec<StartTrial>) -> Study {
    Study {
        setup,
        seed: 1,
        runs: 1,
        groups,
        validation_level: 1,
        test_deflection: Vec::new(),
        trials,
        elapsed_s: 0.0,
    }
}

/// A group whose mean deviation rate is `rates` (per joint) at every level, predicted 10% higher;
/// its `classical` value is `classical`, its `relative_a` its average rate, `test_pose` 0.
fn group(origin: Origin, rates: [f64; 6], classical: f64, levels: usize) -> Group {
    let average = rates.iter().sum::<f64>() / 6.0;
    let predicted = vec![rates.map(|r| 1.1 * r); levels];
    Group {
        name: String::new(),
        title: String::new(),
        origin,
        postures: Vec::new(),
        evaluation: Evaluation {
            classical,
            zhang2021: classical,
            scaled_cond: classical,
            d_optimal: classical,
            relative_a: average,
            test_pose: 0.0,
            cond_psi: classical,
            relative_std: Vector6::zeros(),
            spring_relative_std: Vec::new(),
            predicted_deviation_pct: predicted.clone(),
            identifiability: stiffid::internal::identify::svd::Identifiability {
                rank: 6,
                scaled_cond: 1.0,
                unidentifiable: Vec::new(),
                identified: vec![true; 6],
            },
        },
        evaluations: 0,
        simulation: GroupSimulation {
            mean_deviation_pct: vec![rates; levels],
            std_deviation_pct: vec![[0.0; 6]; levels],
            predicted_deviation_pct: predicted,
            mean_stiffness: vec![Vector6::zeros(); levels],
            spring_mean_deviation_pct: Vec::new(),
            spring_std_deviation_pct: Vec::new(),
            spring_predicted_deviation_pct: Vec::new(),
            spring_mean_stiffness: Vec::new(),
        },
        validation_error: Vec::new(),
    }
}

#[test]
fn findings_of_a_made_up_study_match_the_hand_computed_values() {
    let setup = paper();
    let n = setup.noise().levels.len();
    let mut group3 = [1.0; 6];
    group3[0] = 2.5; // average 1.25, worse than Group 1 on joint 1 only
    let groups = vec![
        group(Origin::Start, [2.0; 6], 5.0, n),
        group(Origin::Local(Criterion::Classical), [3.0; 6], 4.0, n),
        group(Origin::Local(Criterion::Zhang2021), group3, 3.0, n),
        group(Origin::Global(Criterion::RelativeA, 2), [0.5; 6], 2.0, n),
        group(Origin::Global(Criterion::DOptimal, 2), [0.8; 6], 1.0, n),
    ];
    let trials = vec![
        StartTrial {
            seed: 1,
            predicted_average_pct: [3.0, 2.0, 1.0],
        },
        StartTrial {
            seed: 2,
            predicted_average_pct: [1.0, 2.0, 1.5],
        },
    ];
    let f = study::findings(&made_up(setup, groups, trials));

    assert_eq!(f.group3.len(), 2);
    assert!((f.group3[0].factor - 2.0 / 1.25).abs() < 1e-12);
    assert_eq!(f.group3[0].joints_better, [2, 3, 4, 5, 6]);
    assert!((f.group3[1].factor - 3.0 / 1.25).abs() < 1e-12);
    assert_eq!(f.group3[1].joints_better, [1, 2, 3, 4, 5, 6]);
    assert!(f.paper_claim_holds);
    let r = f.relative_a.unwrap();
    assert_eq!(r.other, 3);
    assert!((r.factor - 1.25 / 0.5).abs() < 1e-12);
    assert_eq!(r.joints_better, [1, 2, 3, 4, 5, 6]);

    assert_eq!((f.start_check.wins, f.start_check.trials), (1, 2));
    assert_eq!(f.start_check.zhang_range_pct, Some((1.0, 1.5)));
    // simulated / predicted = 1 / 1.1 everywhere.
    assert!((f.prediction_error - (1.0 - 1.0 / 1.1)).abs() < 1e-12);

    // Averages 2, 3, 1.25, 0.5, 0.8 rank 4, 5, 3, 1, 2; classical 5..1 ranks 5..1:
    // d = 1, -1, 0, 1, -1, sum d^2 = 4, rho = 1 - 6 * 4 / (5 * 24) = 0.8.
    assert_eq!(f.rank_correlation.len(), Criterion::ALL.len() + 1);
    assert!((f.rank_correlation[0].unwrap() - 0.8).abs() < 1e-12);
    assert_eq!(f.rank_correlation[4], Some(1.0)); // relative-a is the average itself
    assert_eq!(f.rank_correlation[5], None); // test-pose constant
    assert!((f.rank_correlation[6].unwrap() - 0.8).abs() < 1e-12); // cond(Psi)
}

#[test]
fn the_papers_table4_applies_to_the_paper_setup_at_level_2_only() {
    let paper_study = made_up(paper(), Vec::new(), Vec::new());
    let table = study::paper_table4(&paper_study).unwrap();
    assert_eq!(table[2][2], 0.002); // Group 3, joint 3
                                    // The paper's own claim in its own table: Group 3's average below Groups 1 and 2.
    let avg = |g: usize| table.iter().map(|row| row[g]).sum::<f64>() / 6.0;
    assert!((avg(2) - 3.679 / 6.0).abs() < 1e-12, "{}", avg(2));
    assert!(avg(2) < avg(0) && avg(2) < avg(1));
    let other_level = Study {
        validation_level: 0,
        ..paper_study
    };
    assert_eq!(study::paper_table4(&other_level), None);
    let fanuc = made_up(
        setup::builtin("fanuc-r2000ic-165f").unwrap(),
        Vec::new(),
        Vec::new(),
    );
    assert_eq!(study::paper_table4(&fanuc), None);
}

/// Every progress call, in order (the advance counts only as their maximum per stage).
#[derive(Default)]
struct Recorder(Mutex<Vec<(String, usize, usize)>>);

impl Progress for Recorder {
    fn begin(&self, what: &str, total: usize) {
        self.0.lock().unwrap().push((what.into(), total, 0));
    }
    fn advance(&self, done: usize) {
        let mut stages = self.0.lock().unwrap();
        let last = stages.last_mut().expect("advance inside a stage");
        last.2 = last.2.max(done);
    }
}

#[test]
fn a_small_study_on_the_paper_setup_reports_its_stages_and_repeats_itself() {
    let setup = paper();
    let options = Options {
        runs: 10,
        seed: 3,
        starts: 2,
        trials: 2,
        ..Options::default()
    };
    let progress = Recorder::default();
    let s = study::run(&setup, &options, &progress).unwrap();
    let stages = progress.0.into_inner().unwrap();
    // One stage for every search: 2 trials x 2 local searches, 2 global searches x 2 starts;
    // one unit per Monte Carlo run: 5 groups x 6 noise levels x 10 runs.
    let expected = [("searches", 8, 8), ("Monte Carlo identification", 300, 300)];
    let got: Vec<(&str, usize, usize)> = stages
        .iter()
        .map(|(w, t, d)| (w.as_str(), *t, *d))
        .collect();
    assert_eq!(got, expected);

    let origins: Vec<Origin> = s.groups.iter().map(|g| g.origin.clone()).collect();
    use Criterion::*;
    assert_eq!(
        origins,
        [
            Origin::Start,
            Origin::Local(Classical),
            Origin::Local(Zhang2021),
            Origin::Global(RelativeA, 2),
            Origin::Global(DOptimal, 2),
        ]
    );
    assert_eq!(
        (s.groups[2].name.as_str(), s.groups[4].title.as_str()),
        ("group3-zhang2021", "Group 5 (d-optimal, global)")
    );
    // Multiple 1 is the paper's level 2.
    assert_eq!(setup.noise().levels[s.validation_level], 1.0);
    for g in &s.groups {
        // The prediction is computed once: the simulation holds the evaluation's.
        assert_eq!(
            g.simulation.predicted_deviation_pct,
            g.evaluation.predicted_deviation_pct
        );
        assert!(g.postures.iter().all(|q| setup.bounds().contains(q)));
        assert_eq!(g.validation_error.len(), setup.test_postures().len());
    }
    // The trial from the study's own seed starts from Group 1.
    assert_eq!(s.trials[0].seed, 3);
    assert!(
        (s.trials[0].predicted_average_pct[0] - s.groups[0].predicted_average_pct()).abs() < 1e-12
    );
    // Same options, same study (the progress report is optional).
    let again = study::run(&setup, &options, &()).unwrap();
    for (a, b) in s.groups.iter().zip(&again.groups) {
        assert_eq!(a.postures, b.postures);
        assert_eq!(a.simulation, b.simulation);
    }
    assert_eq!(s.trials, again.trials);
}

#[test]
fn a_study_without_runs_or_starts_is_refused_before_any_search() {
    let setup = paper();
    for (field, options) in [
        (
            "runs",
            Options {
                runs: 0,
                ..Options::default()
            },
        ),
        (
            "starts",
            Options {
                starts: 0,
                ..Options::default()
            },
        ),
    ] {
        let progress = Recorder::default();
        match study::run(&setup, &options, &progress) {
            Err(Error::InvalidField { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
        assert!(progress.0.into_inner().unwrap().is_empty());
    }
}
