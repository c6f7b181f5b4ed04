//! Non-negative least squares (`crate::nonnegative`): a bound held, a fit cut at its
//! step limit.

use crate::nonnegative::*;
use nalgebra::{DMatrix, DVector};
use stiffid_core::common::stop::Stop;
use stiffid_core::common::warning::WarningKind;

#[test]
fn a_negative_unconstrained_entry_is_held_at_its_bound_and_the_fit_converges() {
    let a = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    let b = DVector::from_column_slice(&[2.0, -1.0, 1.0]);
    let fit = solve_general(&a, &b);
    assert_eq!(fit.active, [false, true]);
    assert!((fit.h[0] - 1.5).abs() < 1e-12, "{}", fit.h);
    assert_eq!(fit.h[1], 0.0);
    assert_eq!(fit.stop, Stop::Converged);
    assert_eq!(warning(fit.stop, 2), None);
}

#[test]
fn a_fit_cut_at_its_step_limit_says_so_and_warns() {
    // Both unknowns must be freed: one step frees one.
    let a = DMatrix::<f64>::identity(2, 2);
    let b = DVector::from_column_slice(&[1.0, 2.0]);
    let cut = solve_within(&a, &b, 1);
    assert_eq!(cut.stop, Stop::IterationLimit);
    assert_eq!(cut.active, [true, false]);
    let w = warning(cut.stop, 2).unwrap();
    assert_eq!(w.kind, WarningKind::NotConverged);
    assert!(
        w.message.contains("limit of 60 active-set steps"),
        "{}",
        w.message
    );
    let done = solve_within(&a, &b, 2);
    assert_eq!(
        (done.stop, done.active),
        (Stop::Converged, vec![false, false])
    );
    assert_eq!(done.h.as_slice(), [1.0, 2.0]);
}
