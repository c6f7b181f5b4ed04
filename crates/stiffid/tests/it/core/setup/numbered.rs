//! `[controller] tools` and `bases`: the frames a controller holds by number, read as given
//! (tools in the flange frame, bases in the world frame, mm and deg to m and rad) and checked.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use stiffid_core::setup;

fn read(controller: &str) -> stiffid_core::Result<stiffid_core::Setup> {
    let text = setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .to_string()
        + "\n[controller]\n"
        + controller;
    setup::parse(&text, "cell.toml", |r, _| {
        stiffid_core::robot::presets::get(r)
    })
}

#[test]
fn the_controllers_numbered_frames_are_read_in_si() {
    let setup = read(
        "tools = [{ number = 1, xyz_mm = [10, -20, 250], rpy_deg = [0, 90, 0] }, { number = 7 }]\n\
         bases = [{ number = 2, xyz_mm = [1200, -300, 400], rpy_deg = [180, 0, 90] }]\n",
    )
    .unwrap();
    let c = setup.workcell().controller();
    let tool = c.tools.get(1).unwrap();
    assert!((tool.translation.vector - Vector3::new(0.010, -0.020, 0.250)).norm() < 1e-15);
    let pitch = UnitQuaternion::from_euler_angles(0.0, 90f64.to_radians(), 0.0);
    assert!(tool.rotation.angle_to(&pitch) < 1e-12);
    // A tool the table gives without a transform is the flange itself.
    assert_eq!(c.tools.get(7), Some(&Isometry3::identity()));
    assert_eq!(c.tools.numbers().collect::<Vec<_>>(), [1, 7]);
    let base = c.bases.get(2).unwrap();
    let expected = Isometry3::from_parts(
        Translation3::new(1.2, -0.3, 0.4),
        UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, std::f64::consts::FRAC_PI_2),
    );
    // The base's z axis points down (roll 180 deg) and its x axis along the world's y (yaw 90 deg).
    let z = base.rotation * Vector3::z();
    assert!((z - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-12, "{z}");
    assert!((base.translation.vector - expected.translation.vector).norm() < 1e-15);
    assert!(base.rotation.angle_to(&expected.rotation) < 1e-12);
    assert_eq!((c.tools.get(2), c.bases.get(1)), (None, None));
    // Without the tables both are empty.
    let plain = read("kinematics = \"nominal\"\n").unwrap();
    assert_eq!(plain.workcell().controller().tools.numbers().count(), 0);
    assert_eq!(plain.workcell().controller().bases.numbers().count(), 0);
}

#[test]
fn a_bad_numbered_frame_is_refused_naming_its_entry() {
    for (controller, field, words) in [
        (
            "tools = [{ number = -1 }]",
            "cell.toml: controller.tools[1].number",
            "-1: expected a frame number from 0 to 999",
        ),
        (
            "bases = [{ number = 1000 }]",
            "cell.toml: controller.bases[1].number",
            "1000: expected",
        ),
        (
            "tools = [{ number = 3 }, { number = 3 }]",
            "cell.toml: controller.tools[2].number",
            "3 is given twice (entries 1 and 2)",
        ),
        (
            "bases = [{ number = 1, xyz_mm = [0, nan, 0] }]",
            "cell.toml: controller.bases[1].xyz_mm[2]",
            "NaN is outside",
        ),
        (
            "tools = [{ number = 1, rpy_deg = [0, 0, 1e9] }]",
            "cell.toml: controller.tools[1].rpy_deg[3]",
            "is outside",
        ),
    ] {
        match read(&format!("{controller}\n")) {
            Err(stiffid_core::Error::InvalidField { field: f, message }) => {
                assert_eq!(f, field, "{controller}: {message}");
                assert!(message.contains(words), "{controller}: {message}");
            }
            other => panic!("{controller}: {other:?}"),
        }
    }
    // An unknown key of an entry is refused by the file's reader, never ignored.
    let err = read("tools = [{ number = 1, xyz = [0, 0, 1] }]\n")
        .unwrap_err()
        .to_string();
    assert!(err.contains("xyz"), "{err}");
}
