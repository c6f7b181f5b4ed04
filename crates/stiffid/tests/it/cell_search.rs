//! Posture search in a cell: every returned posture passes the exact checks, impossible
//! constraints are an error naming the check, and the same seed gives the same postures whatever
//! the thread count.

use stiffid::cell::Checker;
use stiffid::design::{self, Criterion, SearchOptions};
use stiffid::{Error, Setup};

use crate::common;
use common::{paper_with, PAPER_CELL};

/// The guide's cell with a table beside the robot and a 60 deg acceptance half-angle.
fn cell_with_table() -> Setup {
    paper_with(&format!(
        "{PAPER_CELL}max_incidence_deg = 60.0
[[cell.obstacle]]
name = \"table\"
min_mm = [-1500.0, 1000.0, 0.0]
max_mm = [-700.0, 1800.0, 800.0]
"
    ))
    .unwrap()
}

fn small(max_evals: usize, starts: usize) -> SearchOptions {
    SearchOptions {
        max_evals,
        starts,
        seed: 3,
        ..SearchOptions::default()
    }
}

fn assert_all_feasible(setup: &Setup, postures: &[nalgebra::Vector6<f64>]) {
    let checker = Checker::new(setup);
    for (i, q) in postures.iter().enumerate() {
        let f = checker.feasibility(q);
        assert!(
            f.feasible(),
            "posture {}: {:?}",
            i + 1,
            f.violations().collect::<Vec<_>>()
        );
    }
}

#[test]
fn random_groups_pass_the_cell_checks() {
    let setup = cell_with_table();
    let group = design::random_group(&setup, 6, 5);
    assert_all_feasible(&setup, &group);
}

#[test]
fn local_search_in_a_cell_returns_feasible_postures() {
    let setup = cell_with_table();
    let start = design::random_group(&setup, 6, 2);
    let out = design::local(&setup, Criterion::RelativeA, &start, &small(1500, 1)).unwrap();
    assert!(
        out.value < out.start_value,
        "{} vs {}",
        out.value,
        out.start_value
    );
    assert_all_feasible(&setup, &out.postures);
}

#[test]
fn global_search_in_a_cell_is_feasible_and_thread_independent() {
    let setup = cell_with_table();
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| design::global(&setup, Criterion::RelativeA, 6, &small(300, 2), &|_| {}))
            .unwrap()
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.postures, two.postures);
    assert_all_feasible(&setup, &one.postures);
}

#[test]
fn impossible_constraints_are_an_error_naming_the_check() {
    // 100 m: the highest the limits accept (stiffid::common::limits::LENGTH_MM), far out of reach.
    let setup = paper_with("\n[constraints]\nloading_point_min_z_mm = 1e5\n").unwrap();
    let start = design::random_group(&setup, 6, 1);
    for result in [
        design::global(&setup, Criterion::RelativeA, 6, &small(200, 2), &|_| {}),
        design::local(&setup, Criterion::RelativeA, &start, &small(200, 1)),
    ] {
        match result {
            Err(Error::Infeasible {
                check,
                failed,
                postures,
            }) => {
                assert_eq!(check, "loading-point-min-z");
                assert_eq!(failed, postures);
                assert!(postures >= 6);
            }
            other => panic!("{other:?}"),
        }
    }
}
