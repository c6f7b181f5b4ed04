//! The inner folds the nested figure's outer folds share ([`Pairs`]) score every candidate as an
//! inner cross-validation of the outer fold's own splits would: the same best ridge and the same
//! held-out errors.

use super::inner::{folds, Inner, Pairs};
use super::{JointMaps, Linear};
use nalgebra::{DMatrix, DVector, Vector6};

/// Mixed sizes and signs, reproducible.
fn value(i: usize, salt: f64) -> f64 {
    (salt + 0.71 * i as f64).sin() * (1.0 + (i % 3) as f64)
}

/// A linearisation of 23 postures read at one point: 4 geometric columns, joint 1's map of 2
/// harmonics (4 columns) as the candidate, residuals with part of that map in them.
fn linear() -> Linear {
    let (postures, rows) = (23, 69);
    let geometry = DMatrix::from_fn(rows, 4, |r, c| value(4 * r + c, 0.3));
    let angles: Vec<Vector6<f64>> = (0..postures)
        .map(|p| Vector6::from_fn(|j, _| if j == 0 { 0.27 * p as f64 - 3.0 } else { 0.0 }))
        .collect();
    let map = DMatrix::from_fn(rows, 4, |r, c| {
        let (h, sine) = (1 + c % 2, c >= 2);
        let q = angles[r / 3][0] * h as f64;
        value(r, 1.1) * if sine { q.sin() } else { q.cos() }
    });
    let residuals = DVector::from_fn(rows, |r, _| 1e-2 * value(r, 2.0) + 0.3 * map[(r, 1)]);
    let mut maps = vec![DMatrix::zeros(rows, 0); 6];
    maps[0] = map;
    Linear {
        residuals,
        geometry,
        maps,
        harmonics: 2,
        candidates: JointMaps::from([2, 0, 0, 0, 0, 0]),
        rows: (0..postures)
            .map(|p| (3 * p..3 * p + 3).collect())
            .collect(),
        angles,
    }
}

#[test]
fn an_outer_folds_shared_inner_folds_score_as_its_own_splits() {
    let linear = linear();
    let all: Vec<usize> = (0..23).collect();
    let outer = folds(&all);
    let pairs = Pairs::new(&linear, &all).unwrap().unwrap();
    let choices = [
        JointMaps::NONE,
        JointMaps::from([1, 0, 0, 0, 0, 0]),
        JointMaps::from([2, 0, 0, 0, 0, 0]),
    ];
    for k in 0..outer.len() {
        // Outer fold `k`'s inner folds: the other outer folds, each trained on neither.
        let parts: Vec<(Vec<usize>, Vec<usize>)> = (0..outer.len())
            .filter(|&f| f != k)
            .map(|f| {
                let train = (outer[k].0.iter().copied())
                    .filter(|p| !outer[f].1.contains(p))
                    .collect();
                (train, outer[f].1.clone())
            })
            .collect();
        let own = Inner::of(&linear, &parts).unwrap();
        let shared = pairs.inner(k);
        for c in &choices {
            let (a, b) = (shared.score(c).unwrap(), own.score(c).unwrap());
            assert_eq!(a.ridge, b.ridge, "fold {k}, {c:?}");
            assert_eq!(a.errors.len(), b.errors.len());
            for (x, y) in a.errors.iter().zip(&b.errors) {
                assert!((x - y).abs() <= 1e-12 * y.abs().max(1e-30), "{x:e} {y:e}");
            }
            assert!((shared.rms(&a) - own.rms(&b)).abs() <= 1e-12 * own.rms(&b));
        }
    }
    // Fewer than three outer folds leave an outer fold no inner fold to train on: no pairs.
    assert!(Pairs::new(&linear, &[0, 1]).unwrap().is_none());
}

/// A candidate scored against a bound: where its held-out total at its best ridge reaches the
/// bound it is dropped (`None`), below it the score is [`Inner::score`]'s to the last bit (the
/// choice it serves keeps what it kept: the real UR10's ten draws give the same documents).
#[test]
fn a_candidate_that_cannot_be_kept_is_dropped_and_one_that_can_is_scored_in_full() {
    let linear = linear();
    let all: Vec<usize> = (0..23).collect();
    let pairs = Pairs::new(&linear, &all).unwrap().unwrap();
    for k in 0..5 {
        let (pruned, full) = (pairs.inner(k), pairs.inner(k));
        for c in [
            JointMaps::from([1, 0, 0, 0, 0, 0]),
            JointMaps::from([2, 0, 0, 0, 0, 0]),
        ] {
            let s = full.score(&c).unwrap();
            assert!(pruned.score_below(&c, s.total).unwrap().is_none());
            let below = pruned.score_below(&c, s.total * (1.0 + 1e-9)).unwrap();
            let below = below.expect("below its bound");
            assert_eq!(below.ridge, s.ridge);
            assert_eq!(below.errors, s.errors);
            assert_eq!(below.total.to_bits(), s.total.to_bits());
        }
    }
}
