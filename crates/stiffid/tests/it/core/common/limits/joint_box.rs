use nalgebra::Vector6;
use stiffid_core::common::limits::*;

/// A KRL `A2 -60` outside the limits [-50, 50] deg: the messages show `-60` as the user
/// wrote it, not the degrees of its radians (`-59.99999999999999`).
#[test]
fn messages_show_the_angle_as_given() {
    let limits = JointBox::new(
        Vector6::repeat(-50f64.to_radians()),
        Vector6::repeat(50f64.to_radians()),
    );
    let q = Vector6::new(0.0, -60f64.to_radians(), 0.0, 0.0, 0.0, 0.0);
    let v = limits.first_violation(&q).unwrap();
    let column = v.outside("q2_deg".into(), "the joint limits").to_string();
    assert_eq!(
        column,
        "q2_deg = -60 is outside the joint limits [-50.0, 50.0]"
    );
    let e = limits.check(&q, "the robot's limits", |a| format!("A{}", a + 1));
    let e = e.unwrap_err().to_string();
    assert!(e.starts_with("A2 = -60.00 deg"), "{e}");
}
