//! G-code drilling canned cycles (G81, G82, G83) written back as the moves they make and
//! compensated under a drilling operation; cutter compensation, unit changes under a feed and the
//! cycles' malformed forms refused naming the line (the moves read from each cycle:
//! `crates/stiffid-machining/src/gcode/cycles_tests.rs`).

use nalgebra::{Isometry3, Vector3};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::gcode::{self, GcodeDialect, Machine};
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::{self, Language};
use stiffid::{internal::setup, Error};

const HEADER: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n";

#[test]
fn canned_cycles_are_written_back_as_their_moves() {
    let text = format!(
        "{HEADER}G21 G90 G17\nG0 X0 Y0 Z10\nN10 G99 G82 X10 Y20 Z-5 R2 P500 F120 M8\nX30\nG80\nG0 Z20\n"
    );
    let g = gcode::parse(&text, 1e-5).unwrap();
    let positions: Vec<Vector3<f64>> = g.points.iter().map(|p| p.position).collect();
    let out = g.write(&positions).unwrap();
    assert!(
        !out.contains("G82") && !out.contains("R2") && !out.contains('Q'),
        "{out}"
    );
    assert!(
        out.contains("N10 F120 M8\nG0 X10.000000 Y20.000000 Z10.000000\n"),
        "{out}"
    );
    assert!(
        out.contains(
            "G1 X10.000000 Y20.000000 Z-5.000000\nG0 X10.000000 Y20.000000 Z-5.000000\nG4 P500\nG0 X10.000000 Y20.000000 Z2.000000\n"
        ),
        "{out}"
    );
    // The bottom stated again without the thrust, where the dwell and the exit start.
    assert_eq!(out.matches("G4 P500").count(), 2, "{out}");
    // Read back: the same moves, now plain G0/G1 blocks; a moved point goes where it is sent.
    let again = gcode::parse(&out, 1e-5).unwrap();
    assert!(again.cycles.is_empty());
    assert_eq!(again.points.len(), g.points.len());
    for (a, b) in again.points.iter().zip(&g.points) {
        assert!((a.position - b.position).norm() < 1e-12);
        assert_eq!(a.motion, b.motion);
    }
    let mut moved = positions.clone();
    moved[3].x += 0.1234e-3;
    let again = gcode::parse(&g.write(&moved).unwrap(), 1e-5).unwrap();
    assert!((again.points[3].position - moved[3]).norm() < 1e-9);
    // Written back again, the program is the same text: no blank gained where words were.
    let positions: Vec<Vector3<f64>> = again.points.iter().map(|p| p.position).collect();
    let twice = again.write(&positions).unwrap();
    assert_eq!(twice, g.write(&moved).unwrap());
    assert!(!twice.contains("  "), "{twice}");
}

#[test]
fn cutter_compensation_unit_changes_under_a_feed_and_malformed_cycles_are_refused() {
    let start = format!("{HEADER}G21 G90 G17\nG0 X0 Y0 Z10\n");
    let cases = [
        (
            "G41 G1 X10 D1 F100",
            4,
            "G41: controllers enter cutter radius compensation and turn its corners differently",
        ),
        (
            "G42 G1 X10 D1 F100",
            4,
            "G42: controllers enter cutter radius compensation and turn its corners differently",
        ),
        ("G1 X5 F600\nG20 G1 X1", 5, "F of line 4 is in force"),
        ("G91 G81 X10 Y0 Z-15 R-8 L0 F100", 4, "L0"),
        ("G18 G81 X10 Y0 Z-5 R2 F100", 4, "G17"),
        ("G81 X10 Y0 Z-5 F100", 4, "R"),
        // Another cycle code without G80: LinuxCNC needs Z and R again, FANUC keeps them.
        (
            "G81 X10 Y0 Z-5 R2 F100\nG83 X20 Q1",
            5,
            "since the cycle started (line 5)",
        ),
        ("G81 X10 Y0 Z5 R2 F100", 4, "below the retract level"),
        (
            "(stiffid: surface_mm = -6)\nG81 X10 Y0 Z-5 R2 F100",
            5,
            "below the part's surface (Z = -6 mm",
        ),
        ("(stiffid: surface_mm = x)", 4, "surface_mm: expected"),
        ("G83 X10 Y0 Z-5 R2 F100", 4, "peck depth Q"),
        ("G81 X10 Y0 Z-5 R2 Q1 F100", 4, "belongs to G83"),
        ("G81 X10 Y0 Z-5 R2 P100 F100", 4, "belongs to G82"),
        ("G82 X10 Y0 Z-5 R2 F100", 4, "dwell P"),
        // A negative dwell was written back as read (G4 P-1).
        (
            "G82 X10 Y0 Z-5 R2 P-1 F100",
            4,
            "G82: a dwell P of 0 or more is needed",
        ),
        ("G81 X10 Y0 Z-5 R2 F100\nR3", 5, "controllers differ"),
        ("G81 X10 Y0 Z-5 R2 F100\nG80\nX20", 6, "after G80"),
        ("G1 X1 Q2 F100", 4, "Q: a peck depth outside"),
        ("G81 X10 Y0 Z-5 R2 F100 L2.5", 4, "whole number"),
        // A dwell's X is its time on FANUC and Haas, a move on LinuxCNC.
        ("G1 X10 F100\nG04 X2.", 5, "G4 with an axis word"),
        ("G1 X10 F100\nG4 P2 Y20", 5, "G4 with an axis word"),
        (
            "G1 X10 I5 F100",
            4,
            "I, J, K or R (an arc's centre or radius) in a G1 block",
        ),
        (
            "G1 X10 F100 ; a note\rG1 Y50",
            4,
            "a carriage return inside the line",
        ),
    ];
    for (body, line, word) in cases {
        let text = format!("{start}{body}\n");
        match gcode::parse(&text, 1e-5) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{body}: {message}");
                assert!(message.contains(word), "{word}: {message}");
            }
            other => panic!("{body}: {other:?}"),
        }
    }
    let fanuc = Machine {
        dialect: Some(GcodeDialect::Fanuc),
        ..Default::default()
    };
    let text = format!("{start}G81 X10 Y0 Z-5 R2 F100\nG83 X20 Q1\n");
    let g = gcode::parse_on(&text, 1e-5, &fanuc).unwrap();
    let c = &g.cycles[1];
    assert_eq!(c.code, 83);
    assert!((c.bottom.z + 5e-3).abs() < 1e-15 && (c.retract - 2e-3).abs() < 1e-15);
    // A tool not pointing down.
    let text = "(stiffid: tool_rpy_deg = 90 0 0)\nG0 X0 Y0 Z10\nG81 X1 Z-1 R1 F100\n";
    match gcode::parse(text, 1e-5) {
        Err(Error::Program { line: 3, message }) => assert!(message.contains("-Z"), "{message}"),
        other => panic!("{other:?}"),
    }
    // A dwell alone moves nothing.
    let g = gcode::parse(&format!("{start}G1 X10 F100\nG4 P2\nG1 Y10\n"), 1e-5).unwrap();
    let last = g.points.last().unwrap().position;
    assert!(
        (last - Vector3::new(10e-3, 10e-3, 10e-3)).norm() < 1e-12,
        "{last}"
    );
    // Feeds: per minute in the block's units, F given again with the change is accepted.
    let g = gcode::parse(&format!("{start}G1 X5 F600\nG20 G1 X1 F12\n"), 1e-5).unwrap();
    assert!((g.points[2].feed.unwrap() - 12.0 * 25.4e-3 / 60.0).abs() < 1e-15);
}

const DRILL: &str = "[[operation]]\nname = \"drill\"\nkind = \"drilling\"\ntool_number = 2\n\
    [operation.tool]\ndiameter_mm = 10\n[operation.cut]\nfeed_per_rev_mm = 0.2\n\
    [operation.coefficients]\nspecific_energy_n_per_mm2 = 800\nspecific_thrust_n_per_mm2 = 1000\n\
    [[operation]]\nname = \"wall\"\ntool_number = 1\n[operation.tool]\ndiameter_mm = 20\nflutes = 3\n\
    [operation.cut]\nfeed_per_tooth_mm = 0.1\naxial_depth_mm = 4\nradial_depth_mm = 10\nmode = \"down\"\n\
    [operation.coefficients]\npreset = \"al7075-t6\"\n";

/// The FANUC setup with the part of the drilling tests at (1300, -700, 400) mm.
fn drilling_setup() -> setup::Setup {
    setup::builtin("fanuc-r2000ic-165f")
        .unwrap()
        .to_builder()
        .with_workpiece(Isometry3::translation(1.3, -0.7, 0.4))
        .build()
        .unwrap()
}

/// The G-code `text` compensated on `s` (its test compliance) under the process [`DRILL`].
fn compensated(s: &setup::Setup, text: &str) -> stiffid::Result<machining::Report> {
    let program = machining::read(text, Language::GCode, 1e-5).unwrap();
    machining::compensate(
        s.arm(),
        s.workpiece(),
        &s.model_compliance("test").unwrap(),
        &program,
        &file::parse(DRILL, "p.toml").unwrap(),
        &Options::for_setup(s),
    )
}

/// A drilling cycle's feed moves carry the drilling operation's thrust along the tool axis (1000 N
/// up the spindle, the model's `k_f f D / 2`) and are compensated; under a milling operation the
/// cycle is refused naming its line.
#[test]
fn a_drilling_cycle_is_compensated_under_its_drilling_operation() {
    let s = drilling_setup();
    let text = format!("{HEADER}T2\nG0 X0 Y0 Z10\nG81 X20 Y10 Z-8 R2 F120\nX40\nG80\n");
    let report = compensated(&s, &text).unwrap();
    let drilled: Vec<_> = report
        .points
        .iter()
        .zip(&report.operations)
        .filter(|(_, o)| o.is_some())
        .collect();
    assert_eq!(
        drilled.len(),
        4,
        "where the drill meets the part and the bottom, per hole"
    );
    for (p, _) in &drilled {
        // The tool points down (base -Z): the thrust pushes the tool up, +Z.
        assert!((p.wrench[2] - 1000.0).abs() < 1e-9, "{}", p.wrench);
        assert!(p.wrench.fixed_rows::<2>(0).norm() < 1e-9);
    }
    let moved = report
        .results
        .iter()
        .map(|r| (r.q_compensated - r.q).amax())
        .fold(0.0, f64::max);
    assert!(moved > 1e-6);
    let milled = text.replace("T2", "T1");
    match compensated(&s, &milled) {
        Err(Error::Program { line: 4, message }) => {
            assert!(
                message.contains("G81") && message.contains("'wall'"),
                "{message}"
            )
        }
        other => panic!("{other:?}"),
    }
}

/// A drilling feed cuts from where the drill meets material (the part's surface, `Z = 0`, or the
/// depth a peck reached) to its end, both ends compensated under the thrust: on the simulated
/// robot (the compensation's forward model, the controller moving the tool in a straight line
/// between the commanded points, each posture by inverse kinematics) the loaded drill stays on
/// the hole axis to 1 um over the cut. Every other point of the cycle (the `R` level, a peck's
/// re-approach, the retracts) is unloaded and commanded at its nominal posture.
#[test]
fn a_drilling_feed_runs_along_the_compensated_hole_axis() {
    use stiffid::internal::machining::compensate::Model;
    use stiffid::internal::robot::ik;
    let s = drilling_setup();
    let compliance = s.model_compliance("test").unwrap();
    let model = Model::new(s.arm(), &compliance).unwrap();
    let tcp = s.tool().tcp;
    for cycle in ["G81 X20 Y10 Z-30 R2 F120", "G83 X20 Y10 Z-30 R2 Q12 F120"] {
        let text = format!("{HEADER}T2\nG0 X0 Y0 Z10\n{cycle}\nG80\n");
        let report = compensated(&s, &text).unwrap();
        let commanded = |q: &nalgebra::Vector6<f64>| ik::tool_pose(&s.robot().frames(q), &tcp);
        let (mut cuts, mut worst) = (0, 0f64);
        for i in 0..report.points.len() {
            let r = &report.results[i];
            if report.operations[i].is_none() {
                assert!(
                    report.points[i].wrench.norm() < 1e-12,
                    "point {i} is unloaded"
                );
                assert!((r.q_compensated - r.q).amax() < 1e-12, "point {i}");
                continue;
            }
            if report.operations[i - 1].is_none() {
                continue; // where the drill meets material: the cut starts here
            }
            cuts += 1;
            let start = &report.results[i - 1];
            let axis = start.pose.rotation * Vector3::z();
            let off_axis = |p: Vector3<f64>| {
                let v = p - start.pose.translation.vector;
                (v - axis * axis.dot(&v)).norm()
            };
            assert!(
                off_axis(r.pose.translation.vector) < 1e-12,
                "nominal feed on the axis"
            );
            assert!(r.deflection.fixed_rows::<3>(0).norm() > 1e-4, "{cycle}");
            let (a, b) = (commanded(&start.q_compensated), commanded(&r.q_compensated));
            let mut q = start.q_compensated;
            for k in 0..=8 {
                let t = k as f64 / 8.0;
                let pose = Isometry3::from_parts(
                    (a.translation.vector.lerp(&b.translation.vector, t)).into(),
                    a.rotation.slerp(&b.rotation, t),
                );
                q = ik::solve(s.robot(), &tcp, &pose, &q, &ik::Options::default())
                    .unwrap()
                    .q;
                let loaded = model.loaded_pose(&q, &report.points[i].wrench);
                worst = worst.max(off_axis(loaded.translation.vector));
            }
        }
        eprintln!(
            "{cycle}: the loaded drill at most {:.3e} mm off the hole axis",
            worst * 1e3
        );
        assert!(worst < 1e-6, "{cycle}: {worst} m off the hole axis");
        assert_eq!(cuts, if cycle.starts_with("G83") { 3 } else { 1 });
    }
}

/// Operations without a selector are each chosen by name: a process of a drilling and a milling
/// operation chosen by `(operation: NAME)` only is read, each point takes the one named in force
/// (the drill's thrust on the hole, the milling force on the wall), and a point that names none
/// is refused naming its line.
#[test]
fn operations_chosen_by_name_alone_cover_the_points_that_name_them() {
    let by_name = DRILL
        .replace("tool_number = 2\n", "")
        .replace("tool_number = 1\n", "");
    let process = file::parse(&by_name, "p.toml").unwrap();
    assert_eq!(process.operations.len(), 2);
    let s = drilling_setup();
    let program = |text: &str| machining::read(text, Language::GCode, 1e-5).unwrap();
    let run = |text: &str| {
        machining::compensate(
            s.arm(),
            s.workpiece(),
            &s.model_compliance("test").unwrap(),
            &program(text),
            &process,
            &Options::for_setup(&s),
        )
    };
    let text = format!(
        "{HEADER}(operation: drill)\nG0 X0 Y0 Z10\nG81 X20 Y10 Z-8 R2 F120\nG80\n\
         (operation: wall)\nG0 X0 Y0 Z5\nG1 Z-4 F300\nG1 X50 F1800\n"
    );
    let report = run(&text).unwrap();
    let named: Vec<&str> = (report.operations.iter().flatten())
        .map(|&i| process.operations[i].name.as_str())
        .collect();
    assert!(
        named.contains(&"drill") && named.contains(&"wall"),
        "{named:?}"
    );
    let drilled = (report.points.iter().zip(&report.operations))
        .find(|(_, o)| o.map(|i| process.operations[i].name.as_str()) == Some("drill"))
        .unwrap();
    assert!(
        (drilled.0.wrench[2] - 1000.0).abs() < 1e-9,
        "{}",
        drilled.0.wrench
    );
    match run(&format!("{HEADER}G0 X0 Y0 Z10\nG1 Z-4 F300\n")) {
        Err(Error::Program { line: 2, message }) => {
            assert!(
                message.contains("'drill', 'wall'") && message.contains("(operation: NAME)"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}
