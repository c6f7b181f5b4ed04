//! A G-code program on a track with the station free: written back with every point carrying
//! its mapped external axes, the track at the station chosen (within the range and the travel,
//! one step at most between points), the table as read; the loaded tool at the compensated
//! angles, on the carriage at the chosen station, lands on the programmed point of the part to
//! 0.1 micrometre; no point's bound above its bound at the program's own station.

use nalgebra::{Isometry3, Vector3};
use stiffid::internal::machining::compensate::{Free, FreeVariables, Model, Options};
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::{self, gcode, Language};
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis};
use stiffid::internal::setup;

const GCODE: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n(stiffid: external = U C)\nG0 X0 Y0 Z5 U1500 C0\nG1 Z0 F600\nG1 X40\nG1 X80\nG91 G1 X20 C5\nG90 G1 Y30\n";

const PROCESS: &str = "[tool]\ndiameter_mm = 20\nflutes = 3\nhelix_deg = 30\n[cut]\nfeed_per_tooth_mm = 0.1\n\
    axial_depth_mm = 4\nradial_depth_mm = 10\nmode = \"down\"\n[coefficients]\npreset = \"al7075-t6\"\n";

/// A track along x (0 to 6 m) and a turntable about z through (2.83, -0.68) m, next to the
/// part's origin.
fn cell() -> ExternalAxes {
    let turn = 360f64.to_radians();
    ExternalAxes::new(vec![
        ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0),
        ExternalAxis::rotary(
            "table",
            Vector3::new(2.83, -0.68, 0.0),
            Vector3::z_axis(),
            -turn,
            turn,
        ),
    ])
    .unwrap()
}

#[test]
fn a_gcode_program_is_written_back_at_the_stations_chosen() {
    let part = Isometry3::translation(2.8, -0.7, 0.4);
    let base = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let robot = base.robot().clone().with_external(Some(cell()));
    let s = (base.to_builder().with_robot(robot))
        .with_workpiece(part)
        .build()
        .unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let program = machining::read(GCODE, Language::GCode, 1e-5).unwrap();
    let own_options = Options::for_setup(&s);
    let compensate = |options: &Options| {
        machining::compensate(
            s.arm(),
            s.workpiece(),
            &compliance,
            &program,
            &process,
            options,
        )
        .unwrap()
    };
    let own = compensate(&own_options);
    let options = Options {
        free: FreeVariables {
            free: vec![Free::Station(crate::compensate::station(200.0, 50.0))],
            ..FreeVariables::default()
        },
        ..own_options.clone()
    };
    let free = compensate(&options);
    let read = gcode::parse(GCODE, 1e-5).unwrap();
    let again = gcode::parse(&free.program, 1e-5).unwrap();
    assert_eq!(again.points.len(), read.points.len());
    let model = Model::new(s.arm(), &compliance).unwrap();
    let cell = cell();
    let mut moved = false;
    let mut offsets = Vec::new();
    for (i, ((r, given), written)) in (free.results.iter().zip(&read.points))
        .zip(&again.points)
        .enumerate()
    {
        let e = r.external.as_slice();
        // The track written in mm with 6 decimals, the table as read.
        assert!((written.external[0] - e[0] * 1e3).abs() < 1e-6, "{i}");
        assert!(
            (written.external[1] - given.external[1]).abs() < 1e-9,
            "{i}"
        );
        let offset = written.external[0] - given.external[0];
        assert!(offset.abs() <= 200.0 + 1e-6, "{i}: {offset}");
        assert!((0.0..=6000.0).contains(&written.external[0]));
        moved |= offset.abs() > 1.0;
        offsets.push(offset);
        // The loaded tool on the carriage at the chosen station lands on the programmed point.
        let part_from_arm =
            part.inverse() * cell.positioner_pose(e).inverse() * cell.carrier_pose(e);
        let loaded = model.loaded_pose(&r.q_compensated, &arm_wrench(r, &cell));
        let landed = part_from_arm.transform_point(&loaded.translation.vector.into());
        assert!(
            (landed.coords - given.position).norm() < 1e-7,
            "{i}: {} m",
            (landed.coords - given.position).norm()
        );
        // No point above its bound at the program's own station.
        let before = own.results[i].budget.bound;
        assert!(r.budget.bound <= before * (1.0 + 1e-9) + 1e-12, "{i}");
    }
    assert!(moved, "the station moves somewhere: {offsets:?}");
    for w in offsets.windows(2) {
        assert!((w[1] - w[0]).abs() <= 50.0 + 1e-6, "{offsets:?}");
    }
    // The program's own values written back as read without a free station.
    let kept = gcode::parse(&own.program, 1e-5).unwrap();
    for (a, b) in kept.points.iter().zip(&read.points) {
        assert_eq!(a.external, b.external);
    }
}

/// A result's wrench in the arm's frame on the carriage at its station: the result's (cell
/// frame) turned back by the carriage.
fn arm_wrench(
    r: &stiffid::internal::machining::compensate::Compensated,
    cell: &ExternalAxes,
) -> nalgebra::Vector6<f64> {
    let turn = cell.carrier_pose(r.external.as_slice()).rotation.inverse();
    let f = turn * r.wrench.fixed_rows::<3>(0).into_owned();
    let m = turn * r.wrench.fixed_rows::<3>(3).into_owned();
    nalgebra::Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z)
}
