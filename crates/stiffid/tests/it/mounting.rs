//! A setup's `[robot_base]` and `[robot_flange]` offsets equal the same transforms written into the
//! robot's own TOML file as `[base]` and `[flange]`.

use approx::assert_relative_eq;
use nalgebra::{Vector3, Vector6};
use stiffid::internal::robot::{file, presets};
use stiffid::internal::setup;

const PRESET: &str = "comau-smart5-nj165-3.0";
const BASE: &str = "xyz_mm = [100.0, -50.0, 500.0]\nrpy_deg = [0.0, 0.0, 30.0]\n";
const FLANGE: &str = "xyz_mm = [0.0, 0.0, 20.0]\nrpy_deg = [0.0, 0.0, 45.0]\n";

/// The paper setup with `extra` appended after its top-level keys, on `robot`.
fn paper_setup(extra: &str, robot: stiffid::Robot) -> stiffid::Setup {
    let text = setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let with = text.replacen("\n[tool]", &format!("\n{extra}\n[tool]"), 1);
    setup::parse(&with, "mounted.toml", |_, _| Ok(robot.clone())).unwrap()
}

#[test]
fn setup_offsets_equal_the_robot_files_base_and_flange() {
    let preset = presets::get(PRESET).unwrap();
    let offsets = format!("[robot_base]\n{BASE}\n[robot_flange]\n{FLANGE}");
    let mounted = paper_setup(&offsets, preset);
    let robot_text = presets::text(PRESET).unwrap();
    let in_file = format!("{robot_text}\n[base]\n{BASE}\n[flange]\n{FLANGE}");
    let in_file = file::parse(&in_file, "comau-with-base.toml").unwrap();
    let plain = paper_setup("", presets::get(PRESET).unwrap());
    let point = Vector3::new(0.08, 0.08, 0.26);
    for q_deg in [
        [0.0, 0.0, -90.0, 0.0, 0.0, 0.0],
        [10.0, 20.0, -90.0, 30.0, 20.0, 10.0],
    ] {
        let q = Vector6::from(q_deg).map(f64::to_radians);
        let (a, b) = (mounted.robot().frames(&q), in_file.frames(&q));
        assert_relative_eq!(a.point(&point), b.point(&point), epsilon = 1e-12);
        let ja = a.jacobian(&point, stiffid::Coordinates::Axis);
        assert_relative_eq!(
            ja,
            b.jacobian(&point, stiffid::Coordinates::Axis),
            epsilon = 1e-12
        );
        // The pedestal lifts the tool by 500 mm plus what the flange plate adds.
        let lifted = a.point(&point) - plain.robot().frames(&q).point(&point);
        assert!(lifted.norm() > 0.4, "{lifted}");
    }
}

#[test]
fn bad_offsets_name_the_table_and_the_value() {
    let text = setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let bad = text.replacen(
        "\n[tool]",
        "\n[robot_base]\nxyz_mm = [0.0, 0.0, 1e300]\n\n[tool]",
        1,
    );
    let e = setup::parse(&bad, "bad.toml", |r, _| presets::get(r)).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("robot_base.xyz_mm") && message.contains("1e300"),
        "{message}"
    );
    let unknown = text.replacen("\n[tool]", "\n[robot_flange]\nz_mm = 1.0\n\n[tool]", 1);
    let e = setup::parse(&unknown, "bad.toml", |r, _| presets::get(r)).unwrap_err();
    assert!(e.to_string().contains("z_mm"), "{e}");
}

/// A robot file's `[controller_world]` (where its controller's programs state positions) sits
/// on the setup's pedestal: the program's world is `[robot_base]` times it. Out of range, it is
/// refused naming the table.
#[test]
fn the_controllers_world_rides_on_the_pedestal() {
    let world = "[controller_world]\nxyz_mm = [0.0, 0.0, 670.0]\nrpy_deg = [0.0, 0.0, 90.0]\n";
    let robot_text = format!("{}\n{world}", presets::text(PRESET).unwrap());
    let robot = file::parse(&robot_text, "comau-world.toml").unwrap();
    let mounted = paper_setup(&format!("[robot_base]\n{BASE}"), robot.clone());
    // [robot_base]: 100, -50, 500 mm turned 30 deg about z; the world 670 mm above, 90 deg more.
    let at = mounted.program_world();
    assert_relative_eq!(
        at.translation.vector,
        Vector3::new(0.1, -0.05, 1.17),
        epsilon = 1e-15
    );
    assert_relative_eq!(at.rotation.angle(), 120f64.to_radians(), epsilon = 1e-14);
    assert_relative_eq!(
        paper_setup("", robot).program_world().translation.vector,
        Vector3::new(0.0, 0.0, 0.67),
        epsilon = 1e-15
    );
    let bad = robot_text.replace("670.0", "1e9");
    let e = file::parse(&bad, "comau-world.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("controller_world.xyz_mm") && e.contains("comau-world.toml"),
        "{e}"
    );
}

/// The FANUC R-2000iC/165F as ROS-Industrial's `fanuc_r2000ic_support` describes it (its
/// `r2000ic165f_macro.xacro`: joint origins and axes), a URDF whose joint 3 turns relative to
/// link 2.
const R2000IC_URDF: &str = r#"<robot name="fanuc_r2000ic165f">
  <link name="base_link"/><link name="link_1"/><link name="link_2"/><link name="link_3"/>
  <link name="link_4"/><link name="link_5"/><link name="link_6"/>
  <joint name="joint_1" type="revolute"><origin xyz="0 0 0.670"/><parent link="base_link"/><child link="link_1"/><axis xyz="0 0 1"/><limit lower="-3.2288" upper="3.2288" effort="0" velocity="2.26"/></joint>
  <joint name="joint_2" type="revolute"><origin xyz="0.312 0 0"/><parent link="link_1"/><child link="link_2"/><axis xyz="0 1 0"/><limit lower="-1.0472" upper="1.3264" effort="0" velocity="2.0"/></joint>
  <joint name="joint_3" type="revolute"><origin xyz="0 0 1.075"/><parent link="link_2"/><child link="link_3"/><axis xyz="0 -1 0"/><limit lower="-2.3038" upper="3.1416" effort="0" velocity="2.18"/></joint>
  <joint name="joint_4" type="revolute"><origin xyz="0 0 0.225"/><parent link="link_3"/><child link="link_4"/><axis xyz="-1 0 0"/><limit lower="-6.2832" upper="6.2832" effort="0" velocity="3.14"/></joint>
  <joint name="joint_5" type="revolute"><origin xyz="1.280 0 0"/><parent link="link_4"/><child link="link_5"/><axis xyz="0 -1 0"/><limit lower="-2.1817" upper="2.1817" effort="0" velocity="3.14"/></joint>
  <joint name="joint_6" type="revolute"><origin xyz="0.215 0 0"/><parent link="link_5"/><child link="link_6"/><axis xyz="-1 0 0"/><limit lower="-6.2832" upper="6.2832" effort="0" velocity="4.54"/></joint>
</robot>"#;

/// A FANUC's J3 is measured from the horizontal (the J2/J3 interaction), a URDF's joint 3 from
/// link 2: with the setup's `[robot_axis_map]` (`joint 3 = J2 + J3`) the ROS-Industrial URDF
/// puts the flange where the built-in robot (the data's DH table and axis map) does at the same
/// axis angles; without it, far from there. A map beside the robot file's own is refused.
#[test]
fn a_urdf_robot_takes_the_controllers_coupled_axes_from_the_setup() {
    let coupled = "robot_axis_map = { matrix = [[1,0,0,0,0,0], [0,1,0,0,0,0], [0,1,1,0,0,0], [0,0,0,1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,1]], offset_deg = [0,0,0,0,0,0] }\n";
    let text = setup::builtin_text("fanuc-r2000ic-165f").unwrap();
    let on_urdf = |extra: &str| {
        let with = text.replacen("\n[tool]", &format!("\n{extra}\n[tool]"), 1);
        setup::parse(&with, "urdf.toml", |_, _| {
            stiffid::internal::robot::urdf::parse(R2000IC_URDF, "r2000ic.urdf", None)
        })
        .unwrap()
    };
    let preset = presets::get("fanuc-r2000ic-165f").unwrap();
    let (mapped, plain) = (on_urdf(coupled), on_urdf(""));
    let mut apart = 0.0f64;
    for q_deg in [
        [0.0, 0.0, 0.0, 0.0, -90.0, 0.0],
        [-60.0, -16.7, -28.9, 3.8, -62.9, 144.9],
        [20.0, 30.0, 10.0, -40.0, 50.0, 60.0],
    ] {
        let q = Vector6::from(q_deg).map(f64::to_radians);
        let at = preset.frames(&q).flange.translation.vector;
        let urdf = mapped.robot().frames(&q).flange.translation.vector;
        assert_relative_eq!(urdf, at, epsilon = 1e-9);
        apart = apart.max((plain.robot().frames(&q).flange.translation.vector - at).norm());
    }
    assert!(apart > 0.3, "{apart} m");
    // A map that cannot be inverted is refused naming the setup's field.
    let singular = coupled.replacen("[[1,0,0", "[[0,0,0", 1);
    let with = setup::builtin_text("fanuc-r2000ic-165f").unwrap().replacen(
        "\n[tool]",
        &format!("\n{singular}\n[tool]"),
        1,
    );
    let e = setup::parse(&with, "urdf.toml", |_, _| {
        stiffid::internal::robot::urdf::parse(R2000IC_URDF, "r2000ic.urdf", None)
    })
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("urdf.toml: robot_axis_map.matrix: expected an invertible"),
        "{e}"
    );
    // The built-in robot has its own map: another one in the setup is refused.
    let other = setup::builtin_text("fanuc-r2000ic-165f").unwrap().replacen(
        "\n[tool]",
        &format!("\n{coupled}\n[tool]"),
        1,
    );
    let e = setup::parse(&other, "twice.toml", |r, _| presets::get(r)).unwrap_err();
    assert!(e.to_string().contains("robot_axis_map"), "{e}");
}

/// The warnings of kind `plausibility` of compensating an LS program of two joint positions on
/// `setup` (the milling example's stiffness and process).
fn ls_plausibility(setup: &stiffid::Setup) -> Vec<String> {
    use stiffid::app::compensate::{self, Input};
    let pos = |i: u32, q: [f64; 6]| {
        format!("P[{i}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {:.3} deg,\tJ2= {:.3} deg,\tJ3= {:.3} deg,\n\tJ4= {:.3} deg,\tJ5= {:.3} deg,\tJ6= {:.3} deg\n}};\n", q[0], q[1], q[2], q[3], q[4], q[5])
    };
    let text = format!(
        "/PROG  TWO\n/MN\n   1:J P[1] 100% FINE ;\n   2:J P[2] 100% FINE ;\n/POS\n{}{}/END\n",
        pos(1, [-60.0, -16.7, -28.9, 3.8, -62.9, 144.9]),
        pos(2, [-62.0, -15.0, -27.0, 3.8, -62.9, 144.9])
    );
    let (compliance, process) = (
        crate::common::milling_compliance(setup),
        crate::common::milling_process(),
    );
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance,
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "two.ls".into(),
            text: &text,
            data: None,
            language: stiffid::internal::machining::Language::Robot(
                stiffid::internal::machining::program::Dialect::FanucLs,
            ),
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output: stiffid::internal::machining::Language::Robot(
                stiffid::internal::machining::program::Dialect::FanucLs,
            ),
            out_name: "two.ls".into(),
            settings: Default::default(),
        },
        options: stiffid::internal::machining::compensate::Options::for_setup(setup),
    };
    let report = compensate::run(request, |_, _: &[_], _: &[_], _: &[_]| {
        Ok::<(), stiffid::Error>(())
    })
    .unwrap();
    (report.report.warnings.iter())
        .filter(|w| w.kind == stiffid::app::WarningKind::Plausibility)
        .map(|w| w.message.clone())
        .collect()
}

/// An LS program's joint positions on a URDF robot whose axes the setup does not couple warn
/// (kind `plausibility`) naming the first joint position's line; coupled, or on the built-in
/// robot (its own axis map), they do not.
#[test]
fn ls_joint_positions_on_an_uncoupled_urdf_robot_warn() {
    let coupled = "robot_axis_map = { matrix = [[1,0,0,0,0,0], [0,1,0,0,0,0], [0,1,1,0,0,0], [0,0,0,1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,1]], offset_deg = [0,0,0,0,0,0] }\n";
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let on = |extra: &str, urdf: bool| {
        let with = text.replacen("\n[tool]", &format!("\n{extra}\n[tool]"), 1);
        setup::parse(&with, "cell.toml", |r, _| match urdf {
            true => stiffid::internal::robot::urdf::parse(R2000IC_URDF, "r2000ic.urdf", None),
            false => presets::get(r),
        })
        .unwrap()
    };
    let warned = ls_plausibility(&on("", true));
    assert_eq!(warned.len(), 1, "{warned:?}");
    assert!(
        warned[0].contains("(line 3 the first)") && warned[0].contains("robot_axis_map"),
        "{}",
        warned[0]
    );
    assert!(ls_plausibility(&on(coupled, true)).is_empty());
    assert!(ls_plausibility(&on("", false)).is_empty());
}

/// A `[controller] robot` whose controller's world is not the setup robot's is refused naming
/// both worlds: one controller has one world, and the program's positions were read and written
/// in the setup robot's (the FANUC's 670 mm left out without a word). With the same world, the
/// setup's program world is it.
#[test]
fn a_controllers_robot_of_another_world_is_refused() {
    let preset = presets::text("fanuc-r2000ic-165f").unwrap();
    let at = preset.find("[controller_world]").unwrap();
    let without = file::parse(&preset[..at], "fanuc.toml").unwrap();
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let text = text.replace("robot = \"fanuc-r2000ic-165f\"", "robot = \"fanuc.toml\"");
    let with = format!("{text}\n[controller]\nrobot = \"fanuc-r2000ic-165f\"\n");
    let on = |robot: stiffid::Robot| {
        setup::parse(&with, "cell.toml", move |r, _| match r {
            "fanuc-r2000ic-165f" => presets::get(r),
            _ => Ok(robot.clone()),
        })
    };
    let e = on(without).unwrap_err().to_string();
    assert!(
        e.contains("cell.toml: controller.robot")
            && e.contains("at xyz_mm = [0, 0, 670], rpy_deg = [0, 0, 0] in its base frame")
            && e.contains("at xyz_mm = [0, 0, 0], rpy_deg = [0, 0, 0]: 670 mm and 0 deg apart"),
        "{e}"
    );
    let same = on(presets::get("fanuc-r2000ic-165f").unwrap()).unwrap();
    assert_eq!(
        same.program_world().translation.vector,
        Vector3::new(0.0, 0.0, 0.670)
    );
}

/// The setup's `[robot_axis_map]` is the URDF robot's: a `[controller] robot` with its own
/// `[axis_map]` (the built-in FANUC, whose axes are the controller's already) keeps it and is
/// accepted beside the coupled URDF (it was refused as a robot file of another map); a
/// `[controller] robot` without one (the URDF again) takes the setup's.
#[test]
fn a_controllers_robot_of_its_own_axis_map_keeps_it() {
    let coupled = "robot_axis_map = { matrix = [[1,0,0,0,0,0], [0,1,0,0,0,0], [0,1,1,0,0,0], [0,0,0,1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,1]], offset_deg = [0,0,0,0,0,0] }";
    // ROS-Industrial's `base` link: FANUC's world, 670 mm above base_link; its `tool0`: FANUC's
    // flange frame (z along the tool).
    let urdf = R2000IC_URDF.replace("</robot>", "<link name=\"base\"/><joint name=\"base_link-base\" type=\"fixed\"><origin xyz=\"0 0 0.670\"/><parent link=\"base_link\"/><child link=\"base\"/></joint><link name=\"tool0\"/><joint name=\"link_6-tool0\" type=\"fixed\"><origin rpy=\"3.141592653589793 -1.5707963267948966 0\"/><parent link=\"link_6\"/><child link=\"tool0\"/></joint></robot>");
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml").replace(
        "robot = \"fanuc-r2000ic-165f\"",
        &format!("robot = \"r2000ic.urdf\"\n{coupled}"),
    );
    let on = |controller: &str| {
        let with = format!("{text}\n[controller]\nrobot = \"{controller}\"\n");
        setup::parse(&with, "cell.toml", |r, _| match r {
            "r2000ic.urdf" => stiffid::internal::robot::urdf::parse(&urdf, r, Some("tool0")),
            _ => presets::get(r),
        })
        .unwrap()
    };
    let preset = presets::get("fanuc-r2000ic-165f").unwrap();
    let j3 = Vector6::new(0.0, 1.0, 1.0, 0.0, 0.0, 0.0);
    for (name, row3) in [
        // The preset's row 3: theta_3 = -q_2 - q_3.
        (
            "fanuc-r2000ic-165f",
            Vector6::new(0.0, -1.0, -1.0, 0.0, 0.0, 0.0),
        ),
        ("r2000ic.urdf", j3),
    ] {
        let setup = on(name);
        let controller = setup.controller_robot().unwrap();
        assert_eq!(controller.axis_map().matrix.row(2).transpose(), row3);
        let q = Vector6::new(-60.0, -16.7, -28.9, 3.8, -62.9, 144.9).map(f64::to_radians);
        let (at, want) = (controller.frames(&q).flange, preset.frames(&q).flange);
        assert_relative_eq!(
            at.translation.vector,
            want.translation.vector,
            epsilon = 1e-9
        );
        assert!(at.rotation.angle_to(&want.rotation) < 1e-9);
        assert_relative_eq!(
            setup.program_world().translation.vector,
            Vector3::new(0.0, 0.0, 0.670),
            epsilon = 1e-15
        );
    }
}

/// A calibrated robot file writes its axis map's offsets in degrees (`calibrate --out`: 3 deg
/// as 3.0000000000000004 after the round trip through radians); the setup that gave the map
/// (`robot_axis_map`, 3 deg) reads it as the same map, not as the file's own other one.
#[test]
fn the_setups_axis_map_is_the_one_a_calibrated_file_writes_back() {
    let written = 3f64.to_radians().to_degrees();
    assert_eq!(written, 3.0000000000000004);
    let offsets = |third: f64| format!("offset_deg = [0, 0, {third:?}, 0, 0, 0]");
    let preset = presets::text("fanuc-r2000ic-165f").unwrap();
    let robot = file::parse(
        &preset.replace("offset_deg = [0, 0, 0, 0, 0, 0]", &offsets(written)),
        "cal.toml",
    )
    .unwrap();
    let map = format!("robot_axis_map = {{ matrix = [[1,0,0,0,0,0], [0,1,0,0,0,0], [0,-1,-1,0,0,0], [0,0,0,-1,0,0], [0,0,0,0,-1,0], [0,0,0,0,0,-1]], {} }}", offsets(3.0));
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml").replace(
        "robot = \"fanuc-r2000ic-165f\"",
        &format!("robot = \"cal.toml\"\n{map}"),
    );
    let setup = setup::parse(&text, "cell.toml", |_, _| Ok(robot.clone())).unwrap();
    assert_eq!(setup.robot().axis_map().offset[2], 3f64.to_radians());
    // Another map is still refused.
    let other = text.replace("offset_deg = [0, 0, 3.0,", "offset_deg = [0, 0, 3.001,");
    let e = setup::parse(&other, "cell.toml", |_, _| Ok(robot.clone())).unwrap_err();
    assert!(e.to_string().contains("cell.toml: robot_axis_map"), "{e}");
}
