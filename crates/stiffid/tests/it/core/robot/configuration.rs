use nalgebra::Vector6;
use stiffid_core::robot::configuration::*;
use stiffid_core::robot::presets;

fn arm(robot: &str, q_deg: [f64; 6]) -> Configuration {
    let robot = presets::get(robot).unwrap();
    Configuration::of(&robot, &Vector6::from(q_deg).map(f64::to_radians))
}

#[test]
fn the_usual_posture_is_front_elbow_up_and_the_flags_follow_the_axes() {
    // FANUC's usual posture, tool down: J5 negative, no flip, elbow up, front.
    let a = arm("fanuc-r2000ic-165f", [-23.2, 3.9, -48.1, 0.0, -41.9, 23.2]);
    assert!(!a.behind() && !a.elbow_down(), "{a:?}");
    assert_eq!(a.fanuc(), "N U T, 0, 0, 0");
    assert_eq!(a.abb(), [-1, 0, 0, 1]);
    // Status: front (bit 0 clear), A3 >= phi (bit 1), A5 <= 0 (bit 2); turn: A1, A3, A5 < 0.
    assert_eq!(a.kuka(), (0b110, 0b010101));
    // Axis 1 turned half a revolution and the arm swung back over: the wrist centre is behind
    // axis 1's forward direction.
    let back = arm(
        "fanuc-r2000ic-165f",
        [10.0, -80.0, 60.0, 200.0, 30.0, -400.0],
    );
    assert!(back.behind(), "{back:?}");
    assert!(back.fanuc().starts_with("F "), "{}", back.fanuc());
    assert!(back.fanuc().ends_with(", 0, 1, -1"), "{}", back.fanuc());
    assert_eq!(back.abb()[1..3], [2, -5]);
}

#[test]
fn the_elbow_and_wrist_changes_are_named() {
    let robot = presets::get("kuka-kr210-robond").unwrap();
    // The model's zero: upper arm up, forearm forward (the URDF's axis angles).
    let q = Vector6::new(0.0, 0.0, 0.0, 0.0, 45.0, 0.0).map(f64::to_radians);
    let a = Configuration::of(&robot, &q);
    assert!(!a.elbow_down() && !a.behind(), "{a:?}");
    let mut flipped = q;
    flipped[4] = -flipped[4];
    let change = Configuration::of(&robot, &flipped).change_from(&a).unwrap();
    assert!(change.contains("wrist flips"), "{change}");
    assert_eq!(Configuration::of(&robot, &q).change_from(&a), None);
}
