//! The pool's criteria from information matrices (`crate::pool`).

use crate::evaluator::Information;
use crate::pool::*;
use crate::random_group;
use crate::{Criterion, Evaluator};
use nalgebra::Matrix6;

#[test]
fn criteria_from_the_information_matrix_equal_those_from_qr() {
    let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    let postures = random_group(&setup, 7, 3);
    let pool = Pool::new(&setup, &postures, &[]).unwrap();
    let evaluator = Evaluator::new(&setup);
    for criterion in Criterion::ALL {
        let qr = evaluator.value(criterion, &postures);
        let cholesky = pool.value(criterion, &(0..7).collect::<Vec<_>>());
        assert!(
            (cholesky - qr).abs() <= 1e-9 * qr,
            "{criterion}: {cholesky} vs {qr}"
        );
    }
    let none = evaluator.value_from_information(
        Criterion::RelativeA,
        &Information::Six(Matrix6::zeros()),
        1.0,
    );
    assert_eq!(none, f64::INFINITY, "no information");
}
