//! The conformal ranks of the jackknife+ intervals (`ranks`, crate-private).

use crate::model::prediction::{held_out_needed, ranks};

#[test]
fn the_ranks_follow_barber_et_al() {
    // N = 19 at 90%: ceil(0.9 * 20) = 18, floor(0.1 * 20) = 2.
    assert_eq!(ranks(19, 0.9), [Some(2), Some(18)]);
    // N = 9 at 90%: ceil(9.000000000000002) must be 9.
    assert_eq!(ranks(9, 0.9), [Some(1), Some(9)]);
    // Too few scores for 95%: both ends infinite.
    assert_eq!(ranks(10, 0.95), [None, None]);
}

/// The count of held-out values a finite bound needs at a level is the smallest at which the
/// conformal rank fits among them: 19 at 95%, 333 at 99.7%; one fewer gives an infinite end.
#[test]
fn a_finite_bound_needs_the_held_out_values_the_level_asks() {
    for (level, needed) in [(0.95, 19), (0.997, 333), (0.9, 9), (0.5, 1)] {
        assert_eq!(held_out_needed(level), needed, "{level}");
        assert!(ranks(needed, level)[1].is_some(), "{level}");
        if needed > 1 {
            assert!(ranks(needed - 1, level)[1].is_none(), "{level}");
        }
    }
}
