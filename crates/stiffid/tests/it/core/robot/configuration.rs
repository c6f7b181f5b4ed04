use nalgebra::Vector6;
use stiffid_core::robot::configuration::*;
use stiffid_core::robot::presets;

fn arm(robot: &str, q_deg: [f64; 6]) -> Configuration {
    let robot = presets::get(robot).unwrap();
    Configuration::of(&robot, &Vector6::from(q_deg).map(f64::to_radians))
}

#[test]
fn the_usual_posture_is_front_elbow_up() {
    // FANUC's usual posture, tool down: J5 negative, no flip, elbow up, front.
    let a = arm("fanuc-r2000ic-165f", [-23.2, 3.9, -48.1, 0.0, -41.9, 23.2]);
    assert!(!a.behind() && !a.elbow_down(), "{a:?}");
    // Axis 1 turned half a revolution and the arm swung back over: the wrist centre is behind
    // axis 1's forward direction.
    let back = arm(
        "fanuc-r2000ic-165f",
        [10.0, -80.0, 60.0, 200.0, 30.0, -400.0],
    );
    assert!(back.behind(), "{back:?}");
    assert!(!back.wrist_negative() && a.wrist_negative(), "{back:?}");
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
