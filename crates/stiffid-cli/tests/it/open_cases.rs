//! Steps that would land a program or a model off without a word, refused or stated: G-code
//! written back on a cell with external axes for a controller that runs its own nominal model.

use crate::common;

use common::{example, refused, stiffid, temp_dir, write_file};

/// The milling example's FANUC cell with a track along x and a turntable about z through
/// (1330, -680) mm beside the part, and `controller` appended.
fn cell_setup(controller: &str) -> String {
    let base = std::fs::read_to_string(example("milling/fanuc-milling.toml")).unwrap();
    let axes = "\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1.0, 0.0, 0.0]\nlimits_mm = [0.0, 6000.0]\n\n[[external_axis]]\nname = \"table\"\nrole = \"positioner\"\ndirection = [0.0, 0.0, 1.0]\npoint_mm = [1330.0, -680.0, 0.0]\nlimits_deg = [-360.0, 360.0]\n";
    let base = base.replace("[tool]", &format!("{}\n[tool]", axes.trim_start()));
    format!("{base}\n{controller}")
}

/// A short contour with the track's `U` and the table's `C` in every block.
const GCODE: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n(stiffid: external = U C)\nG0 X0 Y0 Z5 U0 C0\nG1 Z0 F600\nG1 X40 U20 C5\nG1 Y30 C10\n";

fn compensate_gcode(dir: &std::path::Path, setup: &str) -> Vec<String> {
    let setup = write_file(dir, "cell.toml", setup);
    let program = write_file(dir, "part.nc", GCODE);
    [
        "compensate",
        "--setup",
        setup.to_str().unwrap(),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        program.to_str().unwrap(),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        dir.join("out.nc").to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec()
}

/// A nominal controller whose robot file declares no external axes: the G-code written back
/// would place the part by the setup's own model of the track and table, which the controller
/// does not run. Refused naming `controller.robot` and what it needs, nothing written.
#[test]
fn gcode_on_a_cell_for_a_nominal_controller_without_its_axes_is_refused() {
    let dir = temp_dir("open-gcode-cell");
    let nominal = "[controller]\nkinematics = \"nominal\"\nrobot = \"fanuc-r2000ic-165f\"\n";
    let args = compensate_gcode(&dir, &cell_setup(nominal));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let line = refused(&dir, &args, &["controller.robot", "track, table", "G-code"]);
    assert!(line.contains("kinematics = \"calibrated\""), "{line}");
    // The setup's own kinematics (no [controller]): written, no such warning.
    let args = compensate_gcode(&dir, &cell_setup(""));
    let out = stiffid(&args.iter().map(String::as_str).collect::<Vec<_>>());
    common::assert_success(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("controller.robot"), "{stderr}");
    assert!(dir.join("out.nc").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
