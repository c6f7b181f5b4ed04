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

#[test]
fn frames_linked_by_the_geometric_operator_are_their_product_or_refused() {
    // `{Z 540} : {Z 10, A 90}` is Z 550 turned 90 deg about z; a rotation first moves the
    // second frame's translation: `{A 90} : {X 10}` is at Y 10.
    let frame = |code: &str| match frame_set(7, code) {
        Some((_, Frame::Stated(7, f))) => f,
        other => panic!("{code}: {other:?}"),
    };
    let f = frame("$BASE = {X 2000, Y 0, Z 540, A 0, B 0, C 0} : {X 0, Y 0, Z 10, A 90, B 0, C 0}");
    assert!((f.translation.vector - nalgebra::Vector3::new(2.0, 0.0, 0.55)).norm() < 1e-12);
    assert!((f.rotation * nalgebra::Vector3::x() - nalgebra::Vector3::y()).norm() < 1e-12);
    let f = frame("$TOOL = {X 0, Y 0, Z 0, A 90, B 0, C 0}:{X 10, Y 0, Z 0, A 0, B 0, C 0} : {FRAME: X 0, Y 0, Z 5, A 0, B 0, C 0}");
    assert!((f.translation.vector - nalgebra::Vector3::new(0.0, 0.01, 0.005)).norm() < 1e-12);
    for refused in [
        "$BASE = {X 2000, Y 0, Z 540, A 0, B 0, C 0} : BASE_DATA[1]",
        "$TOOL = {X 0, Y 0, Z 240, A 0, B 0, C 0} :",
        "$TOOL = {X 0, Y 0, Z 240, A 0, B 0, C 0} + OFFSET",
    ] {
        assert!(
            matches!(frame_set(8, refused), Some((_, Frame::Unknown(8, _)))),
            "{refused}"
        );
    }
}
