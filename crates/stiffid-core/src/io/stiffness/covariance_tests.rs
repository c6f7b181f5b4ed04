use crate::io::stiffness::check_covariance;
use nalgebra::Matrix6;

#[test]
fn a_positive_diagonal_covariance_passes_and_a_negative_one_is_refused() {
    assert!(check_covariance(&Matrix6::from_diagonal_element(1e-14)).is_ok());
    assert!(check_covariance(&Matrix6::from_diagonal_element(-1e-14)).is_err());
}
