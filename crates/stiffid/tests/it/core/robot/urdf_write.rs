use nalgebra::Isometry3;
use nalgebra::{Translation3, UnitQuaternion};
use stiffid_core::robot::urdf;
use stiffid_core::robot::urdf_write::*;

/// Six joints in a row, one without `<origin>`, one in single quotes with an `<origin>`
/// closed by `</origin>`, a commented-out copy of a chain joint, a fixed joint between two
/// revolute ones, a mimic joint off the chain, a mesh and an inertial.
const TEXT: &str = r#"<?xml version="1.0"?>
<robot name="six &amp; more">
  <link name="l0"><visual><geometry><mesh filename="package://p/meshes/l0.stl"/></geometry></visual></link>
  <link name="l1"><inertial><origin xyz="0 0 0.1"/><mass value="12"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="l1b"/><link name="l2"/><link name="l3"/><link name="l4"/><link name="l5"/><link name="l6"/><link name="cb"/>
  <!-- <joint name="j2" type="revolute"><origin xyz="9 9 9"/></joint> -->
  <joint name="j1" type="revolute"><parent link="l0"/><child link="l1"/>
<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="fix" type="fixed"><parent link="l1"/><child link="l1b"/><origin xyz="0 0 0.4" rpy="0 0 0"/></joint>
  <joint name='j2' type='revolute'><parent link='l1b'/><child link='l2'/>
<origin xyz='0.1 0 0' rpy='0 0 0'></origin><axis xyz='0 1 0'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/><origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j4" type="revolute"><parent link="l3"/><child link="l4"/><origin xyz="0.8 0 0.1" rpy="0 0 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j5" type="revolute"><parent link="l4"/><child link="l5"/><origin xyz="0.2 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j6" type="revolute"><parent link="l5"/><child link="l6"/><origin xyz="0.1 0 0" rpy="0 0 0"/><axis xyz="1 0 0"/><limit lower="-6" upper="6" effort="1" velocity="1"/></joint>
  <joint name="cbj" type="revolute"><parent link="l1"/><child link="cb"/><origin xyz="-0.3 0 0.1"/><axis xyz="0 1 0"/><mimic joint="j2" multiplier="-0.25"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"#;

#[test]
fn only_the_chain_origins_and_the_name_change() {
    let robot = urdf::parse(TEXT, "six.urdf", Some("l6")).unwrap();
    let source = robot.urdf_source().unwrap();
    assert_eq!(
        source.joints,
        ["j1", "j2", "j3", "j4", "j5", "j6"].map(String::from)
    );
    let origins: [Isometry3<f64>; 6] = std::array::from_fn(|i| {
        let k = i as f64 + 1.0;
        Isometry3::from_parts(
            Translation3::new(0.1 * k, -0.01 * k, 0.001 * k),
            UnitQuaternion::from_euler_angles(0.01 * k, -0.02 * k, 0.03 * k),
        )
    });
    let text = with_origins(source, "six <calibrated>", &origins).unwrap();
    let back = urdf::parse(&text, "back.urdf", Some("l6")).unwrap();
    assert_eq!(back.name(), "six <calibrated>");
    for (got, want) in back.urdf_source().unwrap().origins.iter().zip(&origins) {
        let d = got.inverse() * want;
        assert!(d.translation.vector.norm() < 1e-15 && d.rotation.angle() < 1e-15);
    }
    for kept in [
        r#"<!-- <joint name="j2" type="revolute"><origin xyz="9 9 9"/></joint> -->"#,
        r#"<origin xyz="0 0 0.4" rpy="0 0 0"/>"#,
        r#"<origin xyz="-0.3 0 0.1"/><axis xyz="0 1 0"/><mimic joint="j2""#,
        r#"<mesh filename="package://p/meshes/l0.stl"/>"#,
        r#"<inertial><origin xyz="0 0 0.1"/><mass value="12"/>"#,
    ] {
        assert!(text.contains(kept), "{kept} lost:\n{text}");
    }
    assert!(!text.contains("</origin>") && !text.contains("0.1 0 0' rpy"));
    assert_eq!(back.masses(), robot.masses());
}
