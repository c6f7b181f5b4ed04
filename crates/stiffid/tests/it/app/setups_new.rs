use std::path::Path;
use stiffid::app::setups_new::*;
use stiffid_core::robot::presets;

#[test]
fn every_placeholder_of_the_template_is_filled() {
    let robot = presets::get("comau-smart5-nj165-3.0").unwrap();
    let request = Request {
        robot: &robot,
        robot_ref: "comau-smart5-nj165-3.0",
        tip: None,
        package_paths: &[],
        payload_kg: None,
    };
    let text = run(&request).unwrap();
    assert!(!text.contains('@'), "{text}");
}

#[test]
fn relative_paths_climb_out_of_the_output_directory() {
    let rel = relative(Path::new("/a/robots/r.urdf"), Path::new("/a/cells/x"));
    assert_eq!(rel, Path::new("../../robots/r.urdf"));
}
