//! Posture search in a cell: every returned posture passes the exact checks, impossible
//! constraints are an error naming the check, and the same seed gives the same postures whatever
//! the thread count.

use stiffid::app::select::{self, PoolInput, Request};
use stiffid::internal::cell::{CheckKind, Checker, Thing};
use stiffid::internal::design::{self, Criterion, SearchOptions};
use stiffid::{Error, Setup};

use crate::common;
use common::{paper_with, PAPER_CELL};

/// The guide's cell with a table beside the robot and a 60 deg acceptance half-angle.
/// The paper setup in a cell with a floor, a tracker, a table and a 150 mm tool body.
fn cell_with_table() -> Setup {
    cell_with_table_and("")
}

/// [`cell_with_table`] with `tracker` appended to its `[tracker]` table.
fn cell_with_table_and(tracker: &str) -> Setup {
    paper_with(&format!(
        "{PAPER_CELL}max_incidence_deg = 60.0
{tracker}[[cell.obstacle]]
name = \"table\"
min_mm = [-1500.0, 1000.0, 0.0]
max_mm = [-700.0, 1800.0, 800.0]
[robot_geometry]
tool_radius_mm = 150.0
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
    // 100 m: the highest the limits accept (stiffid::internal::common::limits::LENGTH_MM), far out of reach.
    let setup = paper_with("\n[constraints]\nloading_point_min_z_mm = 1e5\n").unwrap();
    let start = design::random_group(&setup, 6, 1);
    let global = design::global(&setup, Criterion::RelativeA, 6, &small(200, 2), &|_| {});
    let local = design::local(&setup, Criterion::RelativeA, &start, &small(200, 1));
    // The global search stops after its probe draws, before any start is searched.
    for (result, searched) in [(global, Some(2000)), (local, None)] {
        match result {
            Err(Error::Infeasible {
                check,
                failed,
                postures,
                remedy,
            }) => {
                assert_eq!(check, "loading-point-min-z");
                assert_eq!(failed, postures);
                assert!(postures >= 6);
                assert!(searched.is_none_or(|n| n == postures), "{postures}");
                assert_eq!(remedy, "[constraints] loading_point_min_z_mm = 100000");
            }
            other => panic!("{other:?}"),
        }
    }
}

/// A search (and a pool choice) with a stated margin keeps it to every constraint of the cell:
/// every length check's margin, as the plain checker (`evaluate`) measures it, is at least 20 mm
/// (a line against the tool it starts from too, beyond the tool's radius) and each incidence angle 20 mm / (line of sight) below its limit;
/// the same search without it hugs a line of sight by the 0.1 mm the searches keep. The tracker's registration
/// uncertainty is the default margin.
#[test]
fn a_design_keeps_its_margin_where_one_without_hugs_a_line_of_sight() {
    let setup = cell_with_table();
    let start = design::random_group(&setup, 6, 1);
    let plain = design::local(&setup, Criterion::RelativeA, &start, &small(1500, 1)).unwrap();
    let sight = |q| {
        let f = Checker::new(&setup).feasibility(q);
        let c = f.checks.iter().find(|c| c.kind == CheckKind::LineOfSight);
        c.unwrap().margin
    };
    let hug = plain
        .postures
        .iter()
        .map(sight)
        .fold(f64::INFINITY, f64::min);
    assert!((0.0..1e-3).contains(&hug), "{hug}");
    let kept_options = SearchOptions {
        margin: Some(0.02),
        ..small(1500, 1)
    };
    let kept = design::local(&setup, Criterion::RelativeA, &start, &kept_options).unwrap();
    let tracker = setup.tracker().unwrap().position;
    let mut seen = std::collections::BTreeSet::new();
    for q in &kept.postures {
        let frames = setup.robot().frames(q);
        for m in Checker::new(&setup).margins(q) {
            let kept_by = match (m.kind, m.between.0) {
                (CheckKind::Bounds, _) => continue,
                (CheckKind::Incidence, Thing::MeasuringPoint(i)) => {
                    let p = frames.point(&setup.tool().measuring_points[i]);
                    0.02 / (tracker - p).norm()
                }
                _ => 0.02,
            };
            assert!(m.margin >= kept_by, "{m:?}");
            seen.insert(m.kind);
        }
    }
    assert_eq!(seen.len(), 6, "{seen:?}");
    let keeping = Checker::new(&setup).keeping(0.02);
    assert!(kept
        .postures
        .iter()
        .all(|q| keeping.feasibility(q).feasible()));
    assert!(
        kept.value > plain.value,
        "{} vs {}",
        kept.value,
        plain.value
    );
    // The registration's uncertainty in the setup gives the same design.
    let registered = cell_with_table_and("registration_uncertainty_mm = 20.0\n");
    let by_default = design::local(&registered, Criterion::RelativeA, &start, &small(1500, 1));
    assert_eq!(by_default.unwrap().postures, kept.postures);
    // A pool of both groups: with the margin, the postures hugging a line of sight are skipped.
    let pool: Vec<_> = plain
        .postures
        .iter()
        .chain(&kept.postures)
        .copied()
        .collect();
    let pool_input = || PoolInput {
        name: "pool".into(),
        postures: pool.clone(),
    };
    let choose = |margin| {
        select::run(&Request {
            setup: &setup,
            criterion: Criterion::RelativeA,
            purpose: Default::default(),
            calibration: Default::default(),
            method: select::Method::Pool,
            start: None,
            pool: Some(pool_input()),
            postures: 6,
            target_pct: None,
            options: SearchOptions {
                margin,
                ..small(1500, 1)
            },
            restarts: Some(8),
            distinct: None,
            for_candidates: false,
            candidates: None,
            stations: Vec::new(),
            progress: &(),
            out: None,
            report_dir: None,
        })
        .unwrap()
    };
    let (free, held) = (choose(None), choose(Some(0.02)));
    let skipped = held.pool.as_ref().unwrap().skipped.len();
    assert!(
        skipped >= 1 && free.report.pool.unwrap().skipped.is_empty(),
        "{skipped}"
    );
    assert!(
        held.min_margins.iter().all(|m| m.unwrap() >= 0.02),
        "{:?}",
        held.min_margins
    );
    assert_eq!(held.margin, 0.02);
}
