//! A path's runs (`crate::compensate::runs`).

use crate::compensate::runs::*;

#[test]
fn a_run_is_a_cut_and_the_joint_moves_before_it() {
    // approach, drill, retract, approach, drill, retract: two runs, the last retract in the
    // second.
    let joint = [true, false, true, true, false, true];
    assert_eq!(starts(&joint), vec![0, 2]);
    assert_eq!(ranges(&starts(&joint), 6), vec![0..2, 2..6]);
    // A program of cuts only, or of joint moves only: one run.
    assert_eq!(starts(&[false, false, false]), vec![0]);
    assert_eq!(starts(&[true, true]), vec![0]);
    assert_eq!(starts(&[]), Vec::<usize>::new());
    // Starts out of order, repeated or beyond the path.
    assert_eq!(ranges(&[4, 2, 2, 9], 5), vec![0..2, 2..4, 4..5]);
    // A cut that starts with a linear move after a cut is the same run.
    assert_eq!(starts(&[true, false, false, true, false]), vec![0, 3]);
}
