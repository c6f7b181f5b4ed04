//! `[controller] robot` is the setup's robot as the controller knows it: another robot model, or a
//! calibrated file run as the nominal one, is refused naming both, calibrated setup or not.

use stiffid::internal::setup;

/// The paper setup (a COMAU NJ 165 preset) with `[controller]` lines `controller`; `robot.toml`
/// resolves to `robot_file`.
fn read(controller: &str, robot_file: &str) -> stiffid::Result<stiffid::Setup> {
    let text = setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .to_string()
        + "\n[controller]\n"
        + controller;
    setup::parse(&text, "cell.toml", |r, _| match r {
        "robot.toml" => stiffid::internal::robot::file::parse(robot_file, "robot.toml"),
        preset => stiffid::internal::robot::presets::get(preset),
    })
}

fn refused(controller: &str, robot_file: &str) -> String {
    match read(controller, robot_file) {
        Err(stiffid::Error::InvalidField { field, message }) => {
            assert_eq!(field, "cell.toml: controller.robot", "{message}");
            message
        }
        other => panic!("{controller}: {other:?}"),
    }
}

/// The COMAU preset's robot file with `suffix` after its name and `from` replaced by `to`.
fn comau(suffix: &str, from: &str, to: &str) -> String {
    let text = stiffid::internal::robot::presets::text("comau-smart5-nj165-3.0").unwrap();
    let name = text.lines().find(|l| l.starts_with("name = ")).unwrap();
    let renamed = format!("{}{suffix}\"", name.trim_end_matches('"'));
    assert!(text.contains(from), "{from}");
    text.replacen(name, &renamed, 1).replacen(from, to, 1)
}

#[test]
fn a_controller_of_another_robot_is_refused_naming_both() {
    // A FANUC preset as the controller of the COMAU setup: every target about 2 m away.
    let m = refused("robot = \"fanuc-r2000ic-165f\"\n", "");
    assert!(m.contains("FANUC") && m.contains("COMAU"), "{m}");
    assert!(m.contains("mm apart (more than 20 mm"), "{m}");
    // The setup's own preset, and the same robot with a link 3 mm longer (what a calibration
    // corrects), are accepted.
    read("robot = \"comau-smart5-nj165-3.0\"\n", "").unwrap();
    let longer = comau(
        " as the controller holds it",
        "a_mm = 1175.0",
        "a_mm = 1178.0",
    );
    read("robot = \"robot.toml\"\n", &longer).unwrap();
    // 30 mm longer is another robot.
    let other = comau(" long arm", "a_mm = 1175.0", "a_mm = 1205.0");
    let m = refused("robot = \"robot.toml\"\n", &other);
    assert!(m.contains("long arm") && m.contains("mm apart"), "{m}");
}

#[test]
fn a_calibrated_file_as_the_nominal_controller_is_refused() {
    let calibrated = comau(
        stiffid::internal::robot::CALIBRATED,
        "a_mm = 1175.0",
        "a_mm = 1175.0",
    );
    let m = refused("robot = \"robot.toml\"\n", &calibrated);
    assert!(m.contains("is a calibrated robot file"), "{m}");
    assert!(m.contains("kinematics = \"calibrated\""), "{m}");
}

/// The setup's robot with its flange's axes turned another way (ROS's x along the tool where a
/// controller has z: a URDF's tip beside the built-in robot) puts every flange in the same place
/// but the setup's `[tool]` in another frame than the controller's tool: refused naming the
/// angle and what to give. A flange turned 0.5 deg (what a calibration could correct) passes.
#[test]
fn a_controller_of_another_flange_frame_is_refused() {
    let turned = |deg: f64| {
        comau(" as ROS sees it", "[axis_map]", "[axis_map]")
            + &format!("\n[flange]\nxyz_mm = [0.0, 0.0, 0.0]\nrpy_deg = [0.0, {deg:?}, 0.0]\n")
    };
    let m = refused("robot = \"robot.toml\"\n", &turned(90.0));
    assert!(
        m.contains("with another flange frame")
            && m.contains("their flanges are turned 90 deg apart (more than 1 deg")
            && m.contains("robot_tip"),
        "{m}"
    );
    read("robot = \"robot.toml\"\n", &turned(0.5)).unwrap();
}
