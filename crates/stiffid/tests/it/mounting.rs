//! A setup's `[robot_base]` and `[robot_flange]` offsets equal the same transforms written into the
//! robot's own TOML file as `[base]` and `[flange]`.

use approx::assert_relative_eq;
use nalgebra::{Vector3, Vector6};
use stiffid::robot::{file, presets};
use stiffid::setup;

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
