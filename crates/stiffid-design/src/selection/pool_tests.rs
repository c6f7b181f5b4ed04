//! A pool screened for a selection (`crate::selection::pool`).

use crate::distinct::Distinctness;
use crate::selection::pool::Screened;
use crate::{random_group, Criterion, Evaluator, Goal, PoolOptions};
use nalgebra::Vector6;
use stiffid_core::Error;

#[test]
fn a_near_posture_is_left_out_and_the_best_group_is_the_one_its_criterion_says() {
    let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut postures = random_group(&setup, 8, 5);
    // Posture 9 is posture 3 moved by 0.1 deg on axis 1: near it by any default distance.
    postures.push(postures[2] + Vector6::new(0.1_f64.to_radians(), 0.0, 0.0, 0.0, 0.0, 0.0));
    let distinct = Distinctness::default();
    let pool = Screened::new(&setup, "pool.csv", &postures, None, Some(&distinct)).unwrap();
    assert_eq!((pool.total, pool.usable()), (9, 8));
    assert_eq!(pool.not_distinct, [(9, 3)]);
    assert!(pool.skipped.is_empty(), "no cell: every posture passes");
    let goal = Goal::stiffness(Criterion::RelativeA);
    let chosen = pool.best(&goal, 6, &PoolOptions::default(), &()).unwrap();
    assert!(!chosen.numbers.contains(&9));
    let again: Vec<Vector6<f64>> = chosen.numbers.iter().map(|&k| postures[k - 1]).collect();
    assert_eq!(chosen.postures, again);
    // The value is the group's criterion by QR, an independent evaluation.
    let qr = Evaluator::new(&setup).value(Criterion::RelativeA, &again);
    assert!(
        (chosen.value - qr).abs() <= 1e-9 * qr,
        "{} vs {qr}",
        chosen.value
    );
    // The 28 groups of 6 of the 8 usable postures (the pool enumerates them): none is better.
    let usable: Vec<usize> = (1..=8).collect();
    for leave in 0..8 {
        for other in leave + 1..8 {
            let group: Vec<Vector6<f64>> = (usable.iter())
                .filter(|&&k| k != usable[leave] && k != usable[other])
                .map(|&k| postures[k - 1])
                .collect();
            let v = Evaluator::new(&setup).value(Criterion::RelativeA, &group);
            assert!(v >= chosen.value * (1.0 - 1e-9), "{v} < {}", chosen.value);
        }
    }
    // Asking for more than pass: the pool's error names the distinctness.
    match pool
        .best(&goal, 9, &PoolOptions::default(), &())
        .unwrap_err()
    {
        Error::Input { source_name, error } => {
            assert_eq!(source_name, "pool.csv");
            let m = error.to_string();
            assert!(
                m.contains("9 asked for, but only 8 of the 9 pass the cell's checks and are distinct (1 near an earlier one)"),
                "{m}"
            );
        }
        other => panic!("{other:?}"),
    }
}
