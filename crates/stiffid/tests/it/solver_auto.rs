//! The default solver ([`Solver::Auto`]) resolved per criterion: our SQP on the smooth criteria,
//! SLSQP on the maximum-type ones and `scaled-cond`, in local and global searches and in the
//! study, bit for bit.

use stiffid::internal::design::{self, Criterion, SearchOptions, Solver};
use stiffid::internal::setup;
use stiffid::internal::study::{self, Options};

fn with(solver: Solver) -> SearchOptions {
    SearchOptions {
        solver,
        ..SearchOptions::default()
    }
}

/// The solver `auto` should run on `criterion`, and the other one.
fn expected(criterion: Criterion) -> (Solver, Solver) {
    match criterion {
        Criterion::RelativeA | Criterion::DOptimal | Criterion::TestPose => {
            (Solver::ActiveSet, Solver::Slsqp)
        }
        Criterion::Classical | Criterion::Zhang2021 | Criterion::ScaledCond => {
            (Solver::Slsqp, Solver::ActiveSet)
        }
    }
}

#[test]
fn auto_is_the_default_and_resolves_every_criterion_to_a_concrete_solver() {
    assert_eq!(SearchOptions::default().solver, Solver::Auto);
    assert_eq!(Options::default().solver, Solver::Auto);
    for criterion in Criterion::ALL {
        assert_eq!(Solver::Auto.resolve(criterion), expected(criterion).0);
        for solver in Solver::CONCRETE {
            assert_eq!(solver.resolve(criterion), solver, "{criterion}");
        }
    }
    assert_eq!("auto".parse::<Solver>().unwrap(), Solver::Auto);
    let error = "newton".parse::<Solver>().unwrap_err().to_string();
    assert!(
        error.contains("(known: auto, slsqp, active-set)"),
        "{error}"
    );
}

/// From the study's start group, `auto` gives the very outcome of the solver it resolves to, and
/// not the other's (the two end at different points on every criterion).
#[test]
fn auto_local_searches_are_bit_identical_to_the_resolved_solver() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let start = design::random_group(&setup, 6, 1);
    for criterion in Criterion::ALL {
        let (chosen, other) = expected(criterion);
        let run = |solver| design::local(&setup, criterion, &start, &with(solver)).unwrap();
        let auto = run(Solver::Auto);
        assert_eq!(auto, run(chosen), "{criterion}");
        assert_ne!(auto.postures, run(other).postures, "{criterion}");
    }
}

#[test]
fn auto_global_searches_go_through_the_same_rule() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    for criterion in [Criterion::RelativeA, Criterion::Zhang2021] {
        let options = |solver| SearchOptions {
            starts: 2,
            polished: 1,
            max_evals: 600,
            ..with(solver)
        };
        let run = |solver| design::global(&setup, criterion, 6, &options(solver), &()).unwrap();
        assert_eq!(run(Solver::Auto), run(expected(criterion).0), "{criterion}");
    }
}

/// The study's paper searches (Groups 2 and 3: `classical`, `zhang2021`) stay SLSQP's and its
/// global searches (Groups 4 and 5: `relative-a`, `d-optimal`) are ours.
#[test]
fn the_auto_study_takes_the_paper_searches_from_slsqp_and_the_global_ones_from_ours() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let run = |solver| {
        let options = Options {
            runs: 1,
            starts: 1,
            trials: 0,
            solver,
            ..Options::default()
        };
        study::run(&setup, &options, &()).unwrap().groups
    };
    let (auto, slsqp, ours) = (
        run(Solver::Auto),
        run(Solver::Slsqp),
        run(Solver::ActiveSet),
    );
    for k in [1, 2] {
        assert_eq!(auto[k].postures, slsqp[k].postures, "group {}", k + 1);
        assert_ne!(auto[k].postures, ours[k].postures, "group {}", k + 1);
    }
    for k in [3, 4] {
        assert_eq!(auto[k].postures, ours[k].postures, "group {}", k + 1);
        assert_ne!(auto[k].postures, slsqp[k].postures, "group {}", k + 1);
    }
}
