//! The setup written with the placement (`stiffid::app::place::written`).

use nalgebra::Isometry3;
use nalgebra::{Translation3, UnitQuaternion};
use stiffid::app::place::written::*;

#[test]
fn the_workpiece_table_is_replaced_and_the_rest_kept() {
    let pose = Isometry3::from_parts(
        Translation3::new(1.5, -0.25, 0.4),
        UnitQuaternion::from_euler_angles(0.0, 0.0, 30f64.to_radians()),
    );
    let text = "name = \"a\"\n[workpiece]\nbase_from_part = { xyz_mm = [1, 2, 3], rpy_deg = [0, 0, 0] }\n\n# the tool\n[tool]\ntcp_mm = [0, 0, 1]\n";
    let out = with_workpiece(text, &pose);
    assert_eq!(out, "name = \"a\"\n[workpiece]\nbase_from_part = { xyz_mm = [1500.000000, -250.000000, 400.000000], rpy_deg = [0.00000000, 0.00000000, 30.00000000] }\n\n# the tool\n[tool]\ntcp_mm = [0, 0, 1]\n");
    let appended = with_workpiece("name = \"a\"", &pose);
    assert!(appended.starts_with("name = \"a\"\n\n[workpiece]\nbase_from_part = "));
    let last = with_workpiece("[workpiece] # here\nbase_from_part = {}\n", &pose);
    assert!(last.starts_with("[workpiece] # here\nbase_from_part = { xyz_mm = [1500.0"));
    assert!(!last.contains("{}"));
}
