//! The extrapolation screen of the ladder ([`super::ladder::extrapolating`]) on rungs scored by hand:
//! each rung judged by its own held-out error against the geometry with the same maps variant.

use super::ladder::*;
use crate::calibration::gravity::Gravity;

/// A scored rung of `gravity` with (`maps`) or without maps: 20 postures of one reading whose
/// squared errors scatter about `rms` (m), and the spread `spread` (m).
fn scored(gravity: Gravity, maps: bool, rms: f64, spread: f64) -> Rung {
    let errors: Vec<f64> = (0..20)
        .map(|i| rms * rms * (1.0 + 0.5 * (i as f64).sin()))
        .collect();
    let total: f64 = errors.iter().sum();
    Rung {
        gravity,
        maps,
        rms: Some((total / 20.0).sqrt()),
        skipped: None,
        spread: Some(spread),
        errors,
    }
}

/// A gravity model that misses without maps (its held-out error and spread beyond the
/// geometry's) but predicts best of all with them is skipped without maps and chosen with them;
/// with a spread far beyond the geometry's, it is skipped with maps too.
#[test]
fn each_rung_is_screened_by_its_own_held_out_error() {
    let order = [(0, false), (1, false), (0, true), (1, true)];
    let ladder = |arm_spread: f64| {
        vec![
            scored(Gravity::None, false, 5.0e-4, 1.7e-4),
            scored(Gravity::Arm, false, 6.0e-4, arm_spread),
            scored(Gravity::None, true, 1.8e-4, 1.7e-4),
            scored(Gravity::Arm, true, 1.5e-4, arm_spread),
        ]
    };
    let mut rungs = ladder(1.8e-4);
    extrapolating(&mut rungs, &order);
    let why = rungs[1].skipped.as_deref().unwrap_or_default();
    assert!(why.starts_with("it extrapolates"), "{rungs:#?}");
    assert!(why.contains("0.627 mm off there against 0.529 mm for the geometry,"));
    assert!(rungs[3].skipped.is_none(), "{rungs:#?}");
    assert!(rungs[0].skipped.is_none() && rungs[2].skipped.is_none());
    assert_eq!(choose(&rungs), 3);
    // Spread by 0.4 mm where the geometry's predictions spread by 0.17 mm: skipped with its
    // maps too, and the geometry with maps chosen.
    let mut rungs = ladder(4.0e-4);
    extrapolating(&mut rungs, &order);
    let why = rungs[3].skipped.as_deref().unwrap_or_default();
    assert!(why.contains("for the geometry with maps,"), "{rungs:#?}");
    assert_eq!(choose(&rungs), 2);
}

/// A rung that predicts the groups a little better than the geometry, within one standard error
/// of the paired differences, loses to the simpler geometry, and the ladder's `why` names the
/// rule with the figures; a rung whose held-out error diverged is skipped without its figure.
#[test]
fn the_ladder_says_why_a_better_rung_lost() {
    use super::why::{best, why};
    let order = [(0, false), (1, false), (2, false)];
    let noisy = |gravity: Gravity, shift: f64, turn: f64| {
        let mut r = scored(gravity, false, 5.0e-4, 1.7e-4);
        for (i, e) in r.errors.iter_mut().enumerate() {
            *e *= 1.0 + shift + 0.3 * (turn * i as f64).cos();
        }
        let total: f64 = r.errors.iter().sum();
        r.rms = Some((total / 20.0).sqrt());
        r
    };
    let mut rungs = vec![
        noisy(Gravity::None, 0.0, 1.7),
        noisy(Gravity::Arm, -0.03, 2.3),
        scored(Gravity::Lumped, false, 3.0, 1.7e-4),
    ];
    diverged(&mut rungs, &order);
    let lumped = &rungs[2];
    assert!(lumped.rms.is_none() && lumped.errors.is_empty());
    let skipped = lumped.skipped.as_deref().unwrap_or_default();
    assert!(skipped.starts_with("its held-out error diverged: more than 30 times the geometry's"));
    assert!(!skipped.contains("3000"), "{skipped}");
    let ladder = Ladder {
        folds: 5,
        chosen: choose(&rungs),
        rungs,
        region: stiffid_core::common::limits::JointBox::new(
            nalgebra::Vector6::repeat(-1.0),
            nalgebra::Vector6::repeat(1.0),
        ),
    };
    assert_eq!(ladder.chosen, 0);
    assert_eq!(best(&ladder.rungs), Some(1));
    let text = why(&ladder);
    println!("{text}");
    assert!(
        text.starts_with("arm predicts the held-out groups best ("),
        "{text}"
    );
    assert!(
        text.contains("the one-standard-error rule fits the simplest rung"),
        "{text}"
    );
    assert!(
        text.contains("lower on average, one standard error"),
        "{text}"
    );
}
