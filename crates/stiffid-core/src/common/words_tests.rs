//! The words' tests: counts, short numbers, distinct and apart values.

use super::words::*;

#[test]
fn one_is_singular_and_every_other_count_plural() {
    assert_eq!(count(1, "posture"), "1 posture");
    for n in [0, 2, 11, usize::MAX] {
        assert_eq!(count(n, "posture"), format!("{n} postures"));
        assert_eq!(is_are(n), "are");
    }
    assert_eq!(is_are(1), "is");
}

#[test]
fn numbers_are_short() {
    assert_eq!(number(1e308), "1e308");
    assert_eq!(number(1e-320), "1e-320");
    assert_eq!(number(950000.0), "950000");
    assert_eq!(number(f64::NAN), "NaN");
    // Degrees the user gave, converted to radians and back, read as given.
    for deg in [-60.0f64, -120.0, 15.0, 130.2] {
        assert_eq!(number(deg.to_radians().to_degrees()), format!("{deg}"));
    }
    assert_eq!(number(1.0 / 3.0), "0.333333333333");
}

#[test]
fn distinct_shows_enough_digits() {
    assert_eq!(distinct(40.0, -155.0, 35.0), "40.00");
    assert_eq!(distinct(35.001, -155.0, 35.0), "35.001");
    assert_eq!(distinct(35.0, -155.0, 35.0), "35.00");
    assert_eq!(distinct(f64::NAN, -1.0, 1.0), "NaN");
    assert_eq!(distinct(f64::INFINITY, -1.0, 1.0), "inf");
}

/// Values that differ read differently, with the fewest digits (at least the least asked) that
/// show it; equal values read the same; magnitudes outside 1e-4 to 1e9 in scientific notation.
#[test]
fn values_apart_read_apart_with_no_digit_more() {
    assert_eq!(apart(&[4009.1, 4009.4], 4), ["4009.1", "4009.4"]);
    assert_eq!(apart(&[4009.12, 4009.13], 4), ["4009.12", "4009.13"]);
    assert_eq!(apart(&[4009.0, 4010.0], 4), ["4009", "4010"]);
    assert_eq!(apart(&[0.5, 0.5], 4), ["0.5000", "0.5000"]);
    assert_eq!(apart(&[2.5e9, 2.6e9], 2), ["2.5e9", "2.6e9"]);
    assert_eq!(apart(&[-1.0, 1.0], 1), ["-1", "1"]);
    // Two parts in 1e11 apart: 12 digits show it; within the 12 digits a value is given to
    // (as_given), the same.
    assert_eq!(
        apart(&[1.0, 1.0 + 2e-11], 4),
        ["1.00000000000", "1.00000000002"]
    );
    assert_eq!(apart(&[1.0, 1.0 + 2e-15], 4), ["1.000", "1.000"]);
}
