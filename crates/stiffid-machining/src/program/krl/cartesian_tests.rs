//! KRL's frames (`crate::program::krl::cartesian`).

use crate::program::cartesian::Frame;
use crate::program::krl::cartesian::*;

#[test]
fn frames_are_set_by_literals_and_refused_when_the_controller_holds_them() {
    let Some((true, Frame::Stated(3, f))) =
        frame_set(3, "$BASE = {X 1000, Y -200, Z 5, A 90, B 0, C 0}")
    else {
        panic!("a literal base")
    };
    assert!((f.translation.vector.x - 1.0).abs() < 1e-15);
    let x = f.rotation * nalgebra::Vector3::x();
    assert!((x - nalgebra::Vector3::y()).norm() < 1e-12, "{x}");
    assert_eq!(
        frame_set(4, "$TOOL=$NULLFRAME"),
        Some((false, Frame::World))
    );
    for held in [
        "$BASE = BASE_DATA[1]",
        "BAS(#BASE, 1)",
        "$TOOL = {X 1, Y 2}",
    ] {
        assert!(
            matches!(frame_set(5, held), Some((_, Frame::Unknown(5, _)))),
            "{held}"
        );
    }
    assert_eq!(frame_set(6, "$VEL.CP = 0.2"), None);
}
