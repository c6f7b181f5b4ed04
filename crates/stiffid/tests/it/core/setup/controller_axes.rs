//! `[controller] robot` on a cell with external axes: the controller moves the arm on its
//! carriage by its own model of the track, so that model is the controller's robot file's own
//! (never the setup's tables put in its place), compared with the setup's as the robots are.

use stiffid::internal::setup;

/// The guide's track cell (`examples/track/track-cell.toml`) with `[controller]` lines
/// `controller`; `ctl.toml` resolves to `robot_file` (a robot TOML), `ctl.urdf` to `urdf`.
fn read(controller: &str, robot_file: &str, urdf: &str) -> stiffid::Result<stiffid::Setup> {
    let cell = include_str!("../../../../../../examples/track/track-cell.toml");
    let text = format!("{cell}\n[controller]\n{controller}");
    setup::parse(&text, "cell.toml", |r, tip| match r {
        "ctl.toml" => stiffid::internal::robot::file::parse(robot_file, "ctl.toml"),
        "ctl.urdf" => stiffid::internal::robot::urdf::parse(urdf, "ctl.urdf", tip),
        preset => stiffid::internal::robot::presets::get(preset),
    })
}

/// The preset the cell's robot is, with its track turned `deg` about z (or along y) as its own
/// `[[external_axis]]`.
fn with_track(direction: [f64; 3]) -> String {
    let text = stiffid::internal::robot::presets::text("kuka-kr210-robond").unwrap();
    format!(
        "{text}\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = {direction:?}\nlimits_mm = [0.0, 6000.0]\n\n[[external_axis]]\nname = \"tilt\"\nrole = \"positioner\"\ndirection = [1.0, 0.0, 0.0]\npoint_mm = [3000.0, 1800.0, 700.0]\nlimits_deg = [-95.0, 95.0]\n\n[[external_axis]]\nname = \"rotate\"\nrole = \"positioner\"\ndirection = [0.0, 0.0, 1.0]\npoint_mm = [3000.0, 1800.0, 900.0]\nlimits_deg = [-360.0, 360.0]\n"
    )
}

#[test]
fn a_controller_track_another_way_than_the_cells_is_refused() {
    let turned = |deg: f64| {
        let r = deg.to_radians();
        with_track([r.cos(), r.sin(), 0.0])
    };
    let m = read("robot = \"ctl.toml\"\n", &turned(0.81), "")
        .unwrap_err()
        .to_string();
    assert!(
        m.contains("controller.robot") && m.contains("track_mm = 3000"),
        "{m}"
    );
    assert!(m.contains("42.4 mm and 0.0 deg apart"), "{m}");
    assert!(
        m.contains("another model of the cell's external axes"),
        "{m}"
    );
    let m = read("robot = \"ctl.toml\"\n", &with_track([0.0, 1.0, 0.0]), "")
        .unwrap_err()
        .to_string();
    assert!(
        m.contains("track_mm = 3000") && m.contains("4242.6 mm"),
        "{m}"
    );
    // 0.1 deg (10 mm at 6 m: what a calibration corrects) is the same track, the controller's own.
    let s = read("robot = \"ctl.toml\"\n", &turned(0.1), "").unwrap();
    let own = s.controller_robot().unwrap().external().unwrap().axes()[0].direction;
    assert!((own.y - 0.1f64.to_radians().sin()).abs() < 1e-12, "{own:?}");
}

#[test]
fn a_controller_preset_without_the_cells_axes_keeps_none() {
    let s = read("robot = \"kuka-kr210-robond\"\n", "", "").unwrap();
    assert!(s.controller_robot().unwrap().external().is_none());
    assert_eq!(s.robot().external().unwrap().len(), 3);
}

/// RoboND's KR 210 URDF on a 6 m track (a prismatic joint from `world` above `base_footprint`)
/// with ROS-Industrial's `base` link `world_z` m above `base_link`.
fn track_urdf(world_z: f64) -> String {
    let path = format!(
        "{}/tests/data/kuka-kr210-robond.urdf",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap();
    let root = "  <link name=\"base_footprint\"/>";
    assert!(text.contains(root));
    let added = format!(
        r#"  <link name="world"/>
  <link name="base"/>
  <joint name="track" type="prismatic">
    <parent link="world"/>
    <child link="base_footprint"/>
    <axis xyz="1 0 0"/>
    <limit lower="0" upper="6" effort="1" velocity="1"/>
  </joint>
  <joint name="base_link-base" type="fixed">
    <parent link="base_link"/>
    <child link="base"/>
    <origin xyz="0 0 {world_z}" rpy="0 0 0"/>
  </joint>
{root}"#
    );
    // tool0: link_6 turned to the preset's flange frame (z out of the flange).
    let plain = stiffid::internal::robot::urdf::parse(&text, "kr210.urdf", None).unwrap();
    let preset = stiffid::internal::robot::presets::get("kuka-kr210-robond").unwrap();
    let q = nalgebra::Vector6::new(0.1, 0.2, -0.3, 0.4, 0.5, 0.6);
    let turn = plain.frames(&q).flange.rotation.inverse() * preset.frames(&q).flange.rotation;
    let (r, p, y) = turn.euler_angles();
    let tool0 = format!(
        r#"  <link name="tool0"/>
  <joint name="link_6-tool0" type="fixed">
    <parent link="link_6"/>
    <child link="tool0"/>
    <origin xyz="0 0 0" rpy="{r} {p} {y}"/>
  </joint>
</robot>"#
    );
    text.replacen(root, &added, 1)
        .replacen("</robot>", &tool0, 1)
}

/// The guide's track cell whose controller is a URDF with the track as a prismatic joint above
/// `base_link` (the reference's way): its `base` link, found through the track at zero, is the
/// controller's world, the setup robot's `[controller_world]` (0.5 m up here, as a FANUC's);
/// read as the root, it was refused as another world.
#[test]
fn a_urdf_controller_on_a_track_finds_its_world_through_the_track() {
    let urdf = track_urdf(0.5);
    let robot = stiffid::internal::robot::urdf::parse(&urdf, "ctl.urdf", Some("tool0")).unwrap();
    let world = robot.controller_world().translation.vector;
    assert!(
        (world - nalgebra::Vector3::new(0.0, 0.0, 0.5)).norm() < 1e-12,
        "{world}"
    );
    let toml = stiffid::internal::robot::presets::text("kuka-kr210-robond")
        .unwrap()
        .to_string()
        + "\n[controller_world]\nxyz_mm = [0.0, 0.0, 500.0]\nrpy_deg = [0.0, 0.0, 0.0]\n";
    let cell = include_str!("../../../../../../examples/track/track-cell.toml").replacen(
        "robot = \"kuka-kr210-robond\"",
        "robot = \"ctl.toml\"",
        1,
    );
    // Without the cell's positioner in the URDF, the setup's tables keep only the track.
    let cell = cell.split("# The positioner").next().unwrap().to_string()
        + "[tool]\nloading_point_mm = [100, 0, 250]\nmeasuring_points_mm = [[100, 0, 250], [-100, 0, 250], [0, 100, 250]]\ntcp_mm = [0, 0, 250]\n[loading]\nload_n = 500.0\nanchor_mm = [2500, -1500, 0]\n[noise]\nreading_sd_mm = 0.0068\nlevel_multiples = [1.0]\n";
    let text = format!("{cell}\n[controller]\nrobot = \"ctl.urdf\"\nrobot_tip = \"tool0\"\n");
    let s = setup::parse(&text, "cell.toml", |r, tip| match r {
        "ctl.toml" => stiffid::internal::robot::file::parse(&toml, "ctl.toml"),
        _ => stiffid::internal::robot::urdf::parse(&urdf, "ctl.urdf", tip),
    });
    let s = s.unwrap();
    let track = s.controller_robot().unwrap().external().unwrap();
    assert_eq!(track.axes()[0].name, "track");
}

/// ROS-Industrial's KR 210 URDF (joint 2 from the vertical, joint 3 from link 2: the limits of
/// its joints -45..85 and -210..65 deg) with the map to KUKA's A2 = joint 2 - 90 deg, A3 = joint
/// 3 + 90 deg: the joints' limits bound the axes through the map, A2 -135..-5 and A3 -120..155
/// deg, so the cell's home A2 -115 is within them and A2 = +80 (joint 2 at 170 deg) is not.
#[test]
fn a_urdfs_limits_bound_the_axes_through_the_setups_axis_map() {
    let urdf_path = format!(
        "{}/tests/data/kuka-kr210-robond.urdf",
        env!("CARGO_MANIFEST_DIR")
    );
    let urdf = std::fs::read_to_string(urdf_path).unwrap();
    let map = "robot_axis_map = { matrix = [[1,0,0,0,0,0], [0,1,0,0,0,0], [0,0,1,0,0,0], [0,0,0,1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,1]], offset_deg = [0, 90, -90, 0, 0, 0] }\n";
    let read = |home: &str| {
        let text = crate::true_robot::setup_text("r.urdf", "").replacen(
            "springs = ",
            &format!("{map}springs = "),
            1,
        ) + &format!("\n[controller]\nhome_deg = {home}\n");
        setup::parse(&text, "cell.toml", |_, tip| {
            stiffid::internal::robot::urdf::parse(&urdf, "r.urdf", tip)
        })
    };
    let s = read("[0, -115, 90, 0, 30, 0]").unwrap();
    let deg = |v: f64| (v.to_degrees() * 1e9).round() / 1e9;
    let limits = s.robot().limits();
    assert_eq!((deg(limits.lower[1]), deg(limits.upper[1])), (-135.0, -5.0));
    assert_eq!(
        (deg(limits.lower[2]), deg(limits.upper[2])),
        (-120.0, 155.0)
    );
    let e = read("[0, 80, 90, 0, 30, 0]").unwrap_err().to_string();
    assert!(e.contains("home_deg[2]"), "{e}");
}
