//! Robots from URDF: the same kinematics as their DH tables, and clear errors for chains stiffid
//! cannot use.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::robot::{presets, urdf};
use stiffid::{AxisMap, Coordinates, Error, Robot};

fn data(name: &str) -> String {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn random_posture(robot: &Robot, rng: &mut ChaCha8Rng) -> Vector6<f64> {
    let limit = 2.0 * std::f64::consts::PI;
    Vector6::from_fn(|i, _| {
        rng.random_range(robot.limits().lower[i].max(-limit)..robot.limits().upper[i].min(limit))
    })
}

fn assert_close(a: &[f64], b: &[f64], tolerance: f64, what: &str) {
    let worst = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        worst <= tolerance,
        "{what}: differ by {worst:e}\n{a:?}\n{b:?}"
    );
}

#[test]
fn comau_as_urdf_has_the_kinematics_of_its_dh_table() {
    // The URDF mounts the robot on a base transform, turns joint 3 about a non-z axis, flips
    // joint 4's axis and carries a tool frame; give the DH robot the same base and flange, and
    // the identity axis map (URDF joint positions are the kinematic angles).
    let from_urdf = urdf::parse(&data("comau-nj165.urdf"), "comau-nj165.urdf", None).unwrap();
    let preset = presets::get("comau-smart5-nj165-3.0").unwrap();
    let from_dh = preset
        .clone()
        .with_axis_map(AxisMap::default())
        .and_then(|r| {
            r.with_base(Isometry3::from_parts(
                Translation3::new(0.1, -0.2, 0.5),
                UnitQuaternion::from_euler_angles(0.0, 0.0, 0.7),
            ))
        })
        .and_then(|r| {
            r.with_flange(Isometry3::from_parts(
                Translation3::new(0.01, 0.02, 0.03),
                UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3),
            ))
        })
        .unwrap();
    assert_ne!(from_urdf.joints()[2].axis, Vector3::z_axis());
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..50 {
        let theta = preset
            .axis_map()
            .kinematic(&random_posture(&preset, &mut rng));
        let (a, b) = (from_dh.frames(&theta), from_urdf.frames(&theta));
        let (ra, rb) = (
            a.flange.rotation.to_rotation_matrix(),
            b.flange.rotation.to_rotation_matrix(),
        );
        assert_close(
            ra.matrix().as_slice(),
            rb.matrix().as_slice(),
            1e-9,
            "flange rotation",
        );
        for p in [
            Vector3::zeros(),
            Vector3::new(0.15, 0.0, 0.2),
            Vector3::new(-0.08, 0.08, 0.26),
        ] {
            assert_close(
                a.point(&p).as_slice(),
                b.point(&p).as_slice(),
                1e-9,
                "point",
            );
            let (ja, jb) = (
                a.jacobian(&p, Coordinates::Kinematic),
                b.jacobian(&p, Coordinates::Kinematic),
            );
            assert_close(ja.as_slice(), jb.as_slice(), 1e-9, "Jacobian");
        }
    }
}

#[test]
fn kuka_preset_matches_its_source_urdf() {
    // The kuka-kr210-robond preset's DH table against the joint origins of kr210.urdf.xacro. Its
    // flange frame is DH frame 6 (z out of the flange); the URDF's link_6 is the same frame turned
    // by a constant rotation.
    let from_urdf = urdf::parse(&data("kuka-kr210-robond.urdf"), "kr210", None).unwrap();
    let preset = presets::get("kuka-kr210-robond").unwrap();
    assert_close(
        preset.limits().lower.as_slice(),
        from_urdf.limits().lower.as_slice(),
        1e-12,
        "lower limits",
    );
    assert_close(
        preset.limits().upper.as_slice(),
        from_urdf.limits().upper.as_slice(),
        1e-12,
        "upper limits",
    );
    let mut rng = ChaCha8Rng::seed_from_u64(210);
    let mut turn = None;
    for _ in 0..50 {
        let q = random_posture(&preset, &mut rng);
        let (a, b) = (preset.frames(&q), from_urdf.frames(&q));
        let relative = (a.flange.rotation.inverse() * b.flange.rotation).to_rotation_matrix();
        let turn = *turn.get_or_insert(relative);
        assert_close(
            relative.matrix().as_slice(),
            turn.matrix().as_slice(),
            1e-9,
            "flange turn",
        );
        let p_urdf = Vector3::new(0.1, -0.05, 0.02);
        let p_dh = turn * p_urdf;
        assert_close(
            a.point(&p_dh).as_slice(),
            b.point(&p_urdf).as_slice(),
            1e-9,
            "point",
        );
        for coordinates in [Coordinates::Axis, Coordinates::Kinematic] {
            let (ja, jb) = (
                a.jacobian(&p_dh, coordinates),
                b.jacobian(&p_urdf, coordinates),
            );
            assert_close(ja.as_slice(), jb.as_slice(), 1e-9, "Jacobian");
        }
    }
    // At zero the flange (link_6) sits at (0.35 + 0.96 + 0.54 + 0.193, 0, 0.33 + 0.42 + 1.25 - 0.054).
    let zero = preset.frames(&Vector6::zeros()).flange.translation.vector;
    assert_close(
        zero.as_slice(),
        &[2.043, 0.0, 1.946],
        1e-12,
        "flange at zero",
    );
}

fn chain_error(file: &str, tip: Option<&str>) -> String {
    match urdf::parse(&data(file), file, tip) {
        Err(e @ Error::Chain { .. }) => e.to_string(),
        other => panic!("{file}: expected a chain error, got {other:?}"),
    }
}

#[test]
fn a_prismatic_joint_in_the_chain_is_an_error_naming_it() {
    let message = chain_error("comau-nj165-prismatic.urdf", None);
    assert!(
        message.starts_with("comau-nj165-prismatic.urdf: "),
        "{message}"
    );
    assert!(
        message.contains("joint_3") && message.contains("Prismatic"),
        "{message}"
    );
}

#[test]
fn a_missing_or_ambiguous_tip_link_is_an_error() {
    let message = chain_error("comau-nj165.urdf", Some("gripper"));
    assert!(message.contains("no link named 'gripper'"), "{message}");
    // Naming the tip resolves the ambiguity; a tip short of six revolute joints does not.
    assert!(urdf::parse(&data("comau-nj165-two-leaves.urdf"), "x", Some("tool0")).is_ok());
    let message = chain_error("comau-nj165-two-leaves.urdf", Some("camera"));
    assert!(
        message.contains("3 revolute joints; expected 6"),
        "{message}"
    );
}

#[test]
fn malformed_urdf_is_a_parse_error_naming_the_file() {
    match urdf::parse("<robot name='x'><link", "broken.urdf", None) {
        Err(e @ Error::Parse { .. }) => assert!(e.to_string().starts_with("broken.urdf: ")),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn revolute_joint_without_limit_is_unlimited_and_the_others_keep_theirs() {
    let text = data("comau-nj165.urdf").replacen(
        r#"<limit lower="-3.2" upper="3.2" effort="1000" velocity="2"/>"#,
        "",
        1,
    );
    let robot = urdf::parse(&text, "no-limit.urdf", None).unwrap();
    assert_eq!(robot.limits().lower[0], f64::NEG_INFINITY);
    assert_eq!(robot.limits().upper[0], f64::INFINITY);
    assert_eq!(
        (robot.limits().lower[1], robot.limits().upper[1]),
        (-3.2, 3.2)
    );
    assert!(robot
        .limits()
        .contains(&Vector6::new(10.0, 0.0, 0.0, 0.0, 0.0, 0.0)));
}

/// The two-leaves test URDF with a third leaf `sensor` fixed to link_6 (so two leaves end the chain
/// of six revolute joints), and `tool0` renamed to `rename` (None: kept).
fn three_leaves(rename: Option<&str>) -> String {
    let sensor = r#"<link name="sensor"/>
  <joint name="sensor_mount" type="fixed">
    <parent link="link_6"/>
    <child link="sensor"/>
    <origin xyz="0.1 0 0" rpy="0 0 0"/>
  </joint>
</robot>"#;
    let text = data("comau-nj165-two-leaves.urdf").replace("</robot>", sensor);
    match rename {
        Some(name) => text.replace("\"tool0\"", &format!("\"{name}\"")),
        None => text,
    }
}

#[test]
fn the_tip_defaults_to_the_leaf_ending_six_revolute_joints_else_tool0() {
    let two = data("comau-nj165-two-leaves.urdf");
    let named = urdf::parse(&two, "two.urdf", Some("tool0")).unwrap();
    let chosen = urdf::parse(&two, "two.urdf", None).unwrap();
    assert_eq!(chosen.joints(), named.joints());
    assert_eq!(chosen.flange(), named.flange());
    assert_eq!(chosen.source(), "two.urdf, tip link 'tool0'");
    // Two leaves after six revolute joints (tool0 and sensor) and a short one: tool0 wins.
    let chosen = urdf::parse(&three_leaves(None), "three.urdf", None).unwrap();
    assert_eq!(chosen.flange(), named.flange());
    assert!(chosen.source().ends_with("tip link 'tool0'"));
    // Without a tool0 the choice is left to the user, with both names.
    let e = urdf::parse(&three_leaves(Some("tcp")), "three.urdf", None).unwrap_err();
    let message = e.to_string();
    for part in [
        "several leaf links end a chain of six",
        "tcp",
        "sensor",
        "name the tip link",
    ] {
        assert!(message.contains(part), "{part}: {message}");
    }
    assert!(!message.contains("camera"), "{message}");
}

#[test]
fn a_tip_link_is_refused_for_a_robot_without_a_choice_of_tip() {
    use stiffid::internal::setup::reference;
    let urdf_text = data("comau-nj165-two-leaves.urdf");
    let presets = format!(
        "{}/../stiffid-core/presets/comau-smart5-nj165-3.0.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let robot_toml = std::fs::read_to_string(presets).unwrap();
    let read = |p: &std::path::Path| match p.to_str() {
        Some("cell/robot.urdf") => Some(Ok::<_, Error>(urdf_text.clone())),
        Some("cell/robot.toml") => Some(Ok(robot_toml.clone())),
        _ => None,
    };
    // A URDF takes it; a preset or a robot TOML has no tip to choose, and the error says which
    // field the user wrote.
    let robot = reference::robot("cell/robot.urdf", Some("tool0"), read).unwrap();
    assert!(
        robot.source().ends_with("tip link 'tool0'"),
        "{}",
        robot.source()
    );
    for reference in ["comau-smart5-nj165-3.0", "cell/robot.toml"] {
        let e = reference::robot(reference, Some("tool0"), read).unwrap_err();
        let message = e.to_string();
        assert!(message.starts_with("tip link: 'tool0' given"), "{message}");
        assert!(message.contains(reference), "{message}");
    }
    // A URDF that is not there is not found, tip or not.
    let e = reference::robot("cell/none.urdf", Some("tool0"), read).unwrap_err();
    assert!(matches!(e, Error::NotFound { .. }), "{e}");
    let paper = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let setup = paper.replacen("\n[tool]", "\nrobot_tip = \"tool0\"\n[tool]", 1);
    let e = reference::setup_text(&setup, "s.toml", std::path::Path::new(""), read).unwrap_err();
    assert!(e.to_string().contains("robot_tip: 'tool0' given"), "{e}");
}

/// Each mutation of the test URDF gives an error naming the cause (and, for a parse error, the
/// file): an empty file, a DTD, a loop of joints beside the chain, a mimic joint in the chain.
#[test]
fn broken_urdfs_name_their_cause() {
    let text = data("comau-nj165.urdf");
    let loop_links = "<link name=\"a\"/><link name=\"b\"/>\
        <joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\
        <joint name=\"ba\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint></robot>";
    let looped = text.replacen("</robot>", loop_links, 1);
    let doctype = format!(
        "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY l \"1\">]>\n{}",
        text.replacen("<?xml version=\"1.0\"?>", "", 1)
    );
    let mimic = text.replacen(
        "<joint name=\"joint_3\" type=\"revolute\">",
        "<joint name=\"joint_3\" type=\"revolute\"><mimic joint=\"joint_2\" multiplier=\"-1\"/>",
        1,
    );
    assert_ne!(mimic, text, "the mutation must apply");
    let cases: [(&str, &str, &[&str]); 5] = [
        ("", "empty.urdf", &["empty.urdf", "the file is empty"]),
        ("  \n", "blank.urdf", &["blank.urdf", "the file is empty"]),
        (
            &doctype,
            "dtd.urdf",
            &["dtd.urdf", "DTDs are not supported"],
        ),
        (&looped, "loop.urdf", &["loop.urdf", "loop", "a -> b -> a"]),
        (
            &mimic,
            "mimic.urdf",
            &["mimic.urdf", "joint_3", "mimics joint 'joint_2'"],
        ),
    ];
    for (text, name, parts) in cases {
        let message = urdf::parse(text, name, None).unwrap_err().to_string();
        for part in parts {
            assert!(
                message.contains(part),
                "{name}: '{part}' missing from {message}"
            );
        }
    }
    let message = chain_error("comau-nj165-two-leaves.urdf", Some("nothing"));
    assert!(message.contains("no link named"), "{message}");
}

/// The KUKA test URDF with ROS-Industrial's `base` link ("base_link to KUKA World
/// Coordinates") hanging from `parent` by a fixed joint: 675 mm up, turned half a turn.
fn with_base_link(parent: &str) -> String {
    let base = format!(
        r#"<link name="base"/>
  <joint name="base_link-base" type="fixed">
    <parent link="{parent}"/>
    <child link="base"/>
    <origin xyz="0 0 0.675" rpy="0 0 3.141592653589793"/>
  </joint>
</robot>"#
    );
    data("kuka-kr210-robond.urdf").replace("</robot>", &base)
}

#[test]
fn the_ros_industrial_base_link_is_the_controllers_world() {
    let plain = urdf::parse(&data("kuka-kr210-robond.urdf"), "kr210.urdf", None).unwrap();
    assert_eq!(*plain.controller_world(), Isometry3::identity());
    // From the root through fixed joints only (base_footprint, base_link, base): the world.
    let robot = urdf::parse(&with_base_link("base_link"), "kr210.urdf", None).unwrap();
    assert_eq!(robot.joints(), plain.joints());
    assert_eq!(robot.flange(), plain.flange());
    let world = robot.controller_world();
    assert!((world.translation.vector - Vector3::new(0.0, 0.0, 0.675)).norm() < 1e-15);
    let half = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI);
    assert!(world.rotation.angle_to(&half) < 1e-12);
    // A `base` the arm moves (on link_1) is no controller's world.
    let moved = urdf::parse(&with_base_link("link_1"), "kr210.urdf", Some("link_6")).unwrap();
    assert_eq!(*moved.controller_world(), Isometry3::identity());
}
