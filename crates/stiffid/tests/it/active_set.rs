//! Our SQP ([`Solver::ActiveSet`]) against SLSQP from the same starts: no worse on the smooth
//! `relative-a` (paper setup and tracker cell) and on the maximum-type `classical` and `zhang2021`
//! from the study's start groups, the exact-gradient search no worse than finite
//! differences in the cell, and the same bits whatever the thread count.

use crate::common::converged;
use stiffid::internal::design::{self, Criterion, Gradient, SearchOptions, Solver};
use stiffid::internal::setup::{self, Setup};

fn tracker_cell() -> Setup {
    let text = include_str!("../../../../examples/cell/zhang2021-tracker.toml");
    setup::parse(text, "zhang2021-tracker.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
}

fn active_set() -> SearchOptions {
    SearchOptions {
        solver: Solver::ActiveSet,
        ..SearchOptions::default()
    }
}

fn slsqp() -> SearchOptions {
    SearchOptions {
        solver: Solver::Slsqp,
        ..SearchOptions::default()
    }
}

/// Same local minimum as SLSQP or a better one, within 1e-4 relative, from the same starts, in
/// at most as many evaluations.
#[test]
fn no_worse_than_slsqp_on_relative_a_from_the_same_starts() {
    for (name, setup) in [
        ("paper", setup::builtin("zhang2021-comau-nj165").unwrap()),
        ("cell", tracker_cell()),
    ] {
        for seed in 1..=2 {
            let start = design::random_group(&setup, 6, seed);
            let ours = design::local(&setup, Criterion::RelativeA, &start, &active_set()).unwrap();
            let slsqp = design::local(&setup, Criterion::RelativeA, &start, &slsqp()).unwrap();
            println!(
                "{name}, start {seed}: active-set {:.8} ({} evaluations, {}), slsqp {:.8} ({} evaluations, {})",
                ours.value, ours.evaluations, ours.termination, slsqp.value, slsqp.evaluations, slsqp.termination
            );
            assert!(
                ours.value <= slsqp.value * (1.0 + 1e-4),
                "{name}, start {seed}"
            );
            assert!(
                ours.evaluations <= slsqp.evaluations,
                "{name}, start {seed}"
            );
            assert!(converged(ours.termination), "{name}, start {seed}");
            let feasible = |q| stiffid::internal::cell::feasibility(&setup, q).feasible();
            assert!(ours.postures.iter().all(feasible), "{name}, start {seed}");
        }
    }
}

/// The maximum-type criteria (searched in epigraph form by ours) from the paper setup's first
/// seeded start groups: no worse than SLSQP (to 1e-6), and strictly better on `zhang2021` from the
/// study's start group (seed 1: SLSQP stops at a kink near 131.5), converged (the stops take the
/// epigraph rows, met to second order by a step, as met within `ftol`). Not from every start:
/// over seeds 1-20 ours ends lower on `zhang2021` from 14 and higher from 6 (docs/performance.md).
#[test]
fn maximum_criteria_no_worse_than_slsqp_from_the_studys_starts() {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    for criterion in [Criterion::Classical, Criterion::Zhang2021] {
        for seed in 1..=3 {
            let start = design::random_group(&setup, 6, seed);
            let ours = design::local(&setup, criterion, &start, &active_set()).unwrap();
            let slsqp = design::local(&setup, criterion, &start, &slsqp()).unwrap();
            println!(
                "{criterion}, start {seed}: active-set {:.8} ({} evaluations, {}), slsqp {:.8} ({} evaluations, {})",
                ours.value, ours.evaluations, ours.termination, slsqp.value, slsqp.evaluations, slsqp.termination
            );
            assert!(
                ours.value <= slsqp.value * (1.0 + 1e-6),
                "{criterion}, start {seed}"
            );
            assert!(ours.value < ours.start_value, "{criterion}, start {seed}");
            assert!(converged(ours.termination), "{criterion}, start {seed}");
            if criterion == Criterion::Zhang2021 && seed == 1 {
                assert!(ours.value < 0.9 * slsqp.value, "{}", ours.value);
            }
        }
    }
}

#[test]
fn exact_gradients_end_no_worse_than_finite_differences_in_a_cell() {
    let setup = tracker_cell();
    let fd = SearchOptions {
        gradient: Gradient::FiniteDifference,
        ..active_set()
    };
    for seed in 1..=2 {
        let start = design::random_group(&setup, 6, seed);
        let exact = design::local(&setup, Criterion::RelativeA, &start, &active_set()).unwrap();
        let finite = design::local(&setup, Criterion::RelativeA, &start, &fd).unwrap();
        println!(
            "start {seed}: exact {:.8} ({} evaluations), fd {:.8} ({} evaluations, {})",
            exact.value, exact.evaluations, finite.value, finite.evaluations, finite.termination
        );
        assert!(exact.value <= finite.value * (1.0 + 1e-4), "start {seed}");
        assert!(exact.evaluations < finite.evaluations, "start {seed}");
    }
}

/// The same bits with one thread or two: in the cell, and for the epigraph form of `zhang2021`.
#[test]
fn global_search_is_thread_independent() {
    let options = SearchOptions {
        starts: 4,
        polished: 2,
        ..active_set()
    };
    let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
    for (setup, criterion) in [
        (tracker_cell(), Criterion::RelativeA),
        (paper, Criterion::Zhang2021),
    ] {
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| design::global(&setup, criterion, 6, &options, &()).unwrap())
        };
        let (one, two) = (run(1), run(2));
        assert_eq!(one, two, "{criterion}");
        assert!(one.value < one.start_value, "{criterion}");
    }
}
