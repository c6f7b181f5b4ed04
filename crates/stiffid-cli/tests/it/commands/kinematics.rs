//! The kinematics command's numbers (`stiffid_cli::commands::kinematics`).

use stiffid_cli::commands::kinematics::fixed;

#[test]
fn fixed_drops_the_sign_of_zero() {
    assert_eq!(fixed(-1e-14, 3), "0.000");
    assert_eq!(fixed(-0.0006, 3), "-0.001");
    assert_eq!(fixed(2074.0000000000005, 3), "2074.000");
}
