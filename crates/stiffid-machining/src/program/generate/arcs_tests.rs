//! A program's files split between circular moves (`crate::program::generate::arcs::files`).

use crate::program::generate::arcs;
use crate::program::generate::Move;

const FEED: f64 = 0.02;

#[test]
fn a_file_never_ends_inside_a_circular_move() {
    let f = FEED;
    let moves = [
        Move::Rapid,
        Move::Feed(f),
        Move::ArcVia(f),
        Move::ArcEnd(f),
        Move::Feed(f),
    ];
    assert_eq!(arcs::files(&moves, 3), [0..2, 2..5]);
    assert_eq!(arcs::files(&moves, 4), [0..4, 4..5]);
    assert_eq!(arcs::files(&moves, 2), [0..2, 2..4, 4..5]);
    // A taught start (INFORM) goes with its via point and end.
    let taught = [
        Move::Rapid,
        Move::Feed(f),
        Move::ArcStart(f),
        Move::ArcVia(f),
        Move::ArcEnd(f),
        Move::Feed(f),
    ];
    assert_eq!(arcs::files(&taught, 3), [0..2, 2..5, 5..6]);
    assert_eq!(arcs::files(&taught, 4), [0..2, 2..6]);
}
