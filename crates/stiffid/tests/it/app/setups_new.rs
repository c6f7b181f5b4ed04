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

/// An axis's limits and the bounds written, deg.
type Row = ((f64, f64), (f64, f64));

#[test]
fn the_bounds_are_the_robots_own_limits_less_the_margin() {
    // Per axis: the robot's limits (deg) and the bounds a new setup writes: a UR10's +-360 deg
    // axes keep their whole travel (not cut at +-180), an unlimited joint a turn, one limited on
    // one side a turn from that side, a joint narrower than twice the margin its full range.
    let inf = f64::INFINITY;
    let rows = [
        ((-360.0, 360.0), (-355.0, 355.0)),
        ((-inf, inf), (-180.0, 180.0)),
        ((-4.0, 4.0), (-4.0, 4.0)),
        ((-200.0, inf), (-195.0, 155.0)),
        ((-120.0, 120.0), (-115.0, 115.0)),
        ((-inf, 300.0), (-55.0, 295.0)),
    ];
    let deg = |f: fn(&Row) -> f64| nalgebra::Vector6::from_fn(|a, _| f(&rows[a]).to_radians());
    let limits = stiffid::internal::common::limits::JointBox::new(deg(|r| r.0 .0), deg(|r| r.0 .1));
    let robot = presets::get("comau-smart5-nj165-3.0")
        .unwrap()
        .with_limits(limits)
        .unwrap();
    let request = Request {
        robot: &robot,
        robot_ref: "comau-smart5-nj165-3.0",
        tip: None,
        package_paths: &[],
        payload_kg: None,
    };
    let text = run(&request).unwrap();
    let list = |key: &str| -> Vec<f64> {
        let line = text.lines().find(|l| l.starts_with(key)).unwrap();
        let inner = line.split_once('[').unwrap().1.split_once(']').unwrap().0;
        inner
            .split(',')
            .map(|v| v.trim().parse().unwrap())
            .collect()
    };
    let lower: Vec<f64> = rows.iter().map(|r| r.1 .0).collect();
    let upper: Vec<f64> = rows.iter().map(|r| r.1 .1).collect();
    assert_eq!((list("lower_deg"), list("upper_deg")), (lower, upper));
}
