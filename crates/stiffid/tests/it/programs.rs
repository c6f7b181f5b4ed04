//! Programs in and out: G-code arcs against their circle, KRL/RAPID/LS joint targets read and
//! written back byte for byte, malformed programs refused naming the line, and a compensated
//! program whose targets equal the CSV route's.

use approx::assert_relative_eq;
use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::{self, Compliance, Options};
use stiffid::internal::machining::gcode;
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program::{self, Dialect};
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::ik::{self, tool_pose};
use stiffid::{internal::setup, Error};

const KRL: &str = "&ACCESS RVP\nDEF pocket( )\n; a comment {A1 99}\nPTP {A1 10.5, A2 -80, A3 95.25, A4 0, A5 30, A6 -5.0, E1 0}\r\nLIN {E6AXIS: A1 11, A2 -79.5, A3 95, A4 0.0, A5 31, A6 -5}  ; cut\nDECL E6AXIS XP3={A1 12,A2 -79,A3 94.5,A4 1E-1,A5 32,A6 -5}\nPTP XP3\nEND\n";

const RAPID: &str = "MODULE Pocket\n  ! joint targets\n  CONST jointtarget j1:=[[10.5,-20,30,0,45.125,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n  PROC main()\n    MoveAbsJ j1, v100, fine, tool0;\n    MoveAbsJ [[11, -19.5, 30, 0, 44, 0.5],[9E9,9E9,9E9,9E9,9E9,9E9]]\\NoEOffs, v100, z10, tool0;\n  ENDPROC\nENDMODULE\n";

const LS: &str = "/PROG  POCKET\n/ATTR\nOWNER\t\t= MNEDITOR;\n/MN\n   1:J P[1] 100% FINE    ;\n   2:L P[2] 50mm/sec CNT100    ;\n/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1=    10.000 deg,\tJ2=   -20.500 deg,\tJ3=    30.000 deg,\n\tJ4=     0.000 deg,\tJ5=   -45.000 deg,\tJ6=     5.000 deg\n};\nP[2:\"cut\"]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1=    11.000 deg,\tJ2=   -20.000 deg,\tJ3=    30.250 deg,\n\tJ4=     0.000 deg,\tJ5=   -44.000 deg,\tJ6=     5.000 deg\n};\n/END\n";

#[test]
fn robot_programs_round_trip_byte_for_byte_and_read_their_joint_targets() {
    for (text, dialect, first, count, line) in [
        (
            KRL,
            Dialect::Krl,
            [10.5, -80.0, 95.25, 0.0, 30.0, -5.0],
            3,
            4,
        ),
        (
            RAPID,
            Dialect::Rapid,
            [10.5, -20.0, 30.0, 0.0, 45.125, 0.0],
            2,
            5,
        ),
        (
            LS,
            Dialect::FanucLs,
            [10.0, -20.5, 30.0, 0.0, -45.0, 5.0],
            2,
            5,
        ),
    ] {
        let p = program::parse(text, dialect).unwrap();
        assert_eq!(p.targets.len(), count, "{dialect:?}");
        assert_eq!(p.targets[0].q_deg, first, "{dialect:?}");
        assert_eq!(p.targets[0].line, line, "{dialect:?}");
        let same: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
        assert_eq!(p.write(&same).unwrap(), text, "{dialect:?}");
        // A changed value replaces that number only.
        let mut changed = same.clone();
        changed[1][2] += 0.0123456789;
        let out = p.write(&changed).unwrap();
        let again = program::parse(&out, dialect).unwrap();
        assert_relative_eq!(again.targets[1].q_deg[2], changed[1][2], epsilon = 1e-9);
        assert_eq!(again.targets[0].q_deg, first);
        assert_eq!(out.lines().count(), text.lines().count());
    }
    assert_eq!(
        program::parse(KRL, Dialect::Krl).unwrap().targets[2].q_deg[3],
        0.1
    );
}

#[test]
fn malformed_programs_are_refused_naming_the_line() {
    let cases = [
        (KRL.replace("A3 95.25", "A3 abc"), Dialect::Krl, 4, "A3"),
        (
            KRL.replace("LIN {E6AXIS: A1 11,", "LIN {X 11,"),
            Dialect::Krl,
            5,
            "Cartesian",
        ),
        (
            KRL.replace(", A6 -5}  ; cut", "}  ; cut"),
            Dialect::Krl,
            5,
            "axis 6",
        ),
        (
            KRL.replace("PTP XP3", "LIN_REL {A1 1}"),
            Dialect::Krl,
            7,
            "relative",
        ),
        (
            RAPID.replace("MoveAbsJ j1", "MoveL p1"),
            Dialect::Rapid,
            5,
            "not a robtarget declared",
        ),
        (
            RAPID.replace("[[10.5,-20,30,0,45.125,0]", "[[10.5,-20,30,0,45.125]"),
            Dialect::Rapid,
            3,
            "expected ','",
        ),
        (
            LS.replace(
                "\tUF : 0, UT : 1,\n\tJ1=    11.000",
                "\tUF : 0, UT : 1, CONFIG : 'N U T, 0, 0, 0',\n\tJ1=    11.000",
            ),
            Dialect::FanucLs,
            14,
            "Cartesian",
        ),
        (
            LS.replace(
                "J4=     0.000 deg,\tJ5=   -44.000",
                "J4=     0.000 mm,\tJ5=   -44.000",
            ),
            Dialect::FanucLs,
            18,
            "deg",
        ),
        (
            "MODULE M\nENDMODULE\n".to_string(),
            Dialect::Rapid,
            1,
            "no motion instruction in the module",
        ),
        (
            LS.replace(
                "J6=     5.000 deg\n};\nP[2",
                "J6=     5.000 deg,\tJ1= 12 deg\n};\nP[2",
            ),
            Dialect::FanucLs,
            12,
            "J1: given twice in P[1]",
        ),
        (
            LS.replace(
                "\tUF : 0, UT : 1,\n\tJ1=    11.000",
                "\tUF : 0, UT : 1,\n\tJ1=    11.000 deg,\tJ1=    11.000",
            ),
            Dialect::FanucLs,
            17,
            "J1: given twice in P[2]",
        ),
    ];
    for (text, dialect, line, word) in cases {
        match program::parse(&text, dialect) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}");
                assert!(message.contains(word), "{message}");
            }
            other => panic!("{dialect:?} {word}: {other:?}"),
        }
    }
}

const HEADER: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n";

#[test]
fn gcode_arcs_lie_on_their_analytic_circle_within_the_chord_tolerance() {
    let tolerance = 0.01e-3;
    // A counter-clockwise half circle of radius 20 mm about (50, 0) by IJK, a clockwise quarter
    // by R in the ZX plane, a full helical circle by IJK, inches for the last block.
    let text = format!(
        "{HEADER}G21 G90 G17\nG0 X30 Y0 Z5\nG1 Z0 F500\nG3 X70 Y0 I20 J0\nG18 G2 X90 Z-20 R20\n\
         G17 G91 G2 I-20 J0 Z-2\nG20 G90 G1 X1 F20\n"
    );
    let g = gcode::parse(&text, tolerance).unwrap();
    let on_circle = |line: u64, centre: Vector3<f64>, normal: usize| {
        let pts: Vec<_> = g.points.iter().filter(|p| p.line == line).collect();
        assert!(pts.len() > 10, "line {line}: {}", pts.len());
        for p in &pts {
            let mut d = p.position - centre;
            d[normal] = 0.0;
            assert_relative_eq!(d.norm(), 20e-3, epsilon = 1e-12);
        }
        pts.len()
    };
    let n = on_circle(5, Vector3::new(50e-3, 0.0, 0.0), 2);
    // Chords: the sagitta of the largest step within the tolerance, and no more chords than
    // needed plus one.
    let step = 2.0 * (1.0 - tolerance / 20e-3).acos();
    assert_eq!(n, (std::f64::consts::PI / step).ceil() as usize);
    let low = g
        .points
        .iter()
        .filter(|p| p.line == 5)
        .map(|p| p.position.y)
        .fold(f64::MAX, f64::min);
    assert!(
        low < -19.99e-3,
        "the CCW half circle from (30,0) to (70,0) goes through -y: {low}"
    );
    // G18 G2 R20 from (70, 0, 0) to (90, 0, -20): centre (70, 0, -20) or (90, 0, 0); clockwise
    // seen from +Y in the ZX plane (Z to X is counter-clockwise) over 90 deg: centre (90, 0, 0)
    // (about (70, 0, -20) the clockwise way is 270 deg).
    on_circle(6, Vector3::new(90e-3, 0.0, 0.0), 1);
    // The full circle: back at its start, 2 mm lower, about (70, 0).
    let full: Vec<_> = g.points.iter().filter(|p| p.line == 7).collect();
    on_circle(7, Vector3::new(70e-3, 0.0, -20e-3), 2);
    assert_relative_eq!(
        full.last().unwrap().position,
        Vector3::new(90e-3, 0.0, -22e-3),
        epsilon = 1e-15
    );
    let last = g.points.last().unwrap();
    assert_relative_eq!(last.position.x, 25.4e-3, epsilon = 1e-15);
    assert_relative_eq!(
        g.points[0].orientation * Vector3::z(),
        -Vector3::z(),
        epsilon = 1e-15
    );
}

#[test]
fn malformed_gcode_is_refused_naming_the_line() {
    let cases = [
        (format!("{HEADER}G0 X10 Y0 Z0\nG41 X20\n"), 3, "G41"),
        (
            format!("{HEADER}G0 X10 Y0 Z0\nG2 X20 Y0 I3 J0\n"),
            3,
            "off its circle",
        ),
        (
            "G1 X10\n".to_string(),
            1,
            "no tool orientation: state it in the setup, [workpiece] tool_rpy_deg",
        ),
        (format!("{HEADER}G1 X10 A30\n"), 2, "rotary"),
        (
            format!("{HEADER}G0 X0 Y0 Z0 A0\nG1 X10 A-0.5 F100\n"),
            3,
            "A-0.5: a rotary axis off its zero, and the cell has none",
        ),
        (format!("{HEADER}G1 X1Q\n"), 2, "Q: expected a number"),
        (format!("{HEADER}G1 X10 (open\n"), 2, "')'"),
        (
            format!("{HEADER}G0 X0 Y0 Z0\nG2 X10 Y0 R2\n"),
            3,
            "shorter than half",
        ),
        (format!("{HEADER}M3 S1000\n"), 1, "no motion"),
        (format!("{HEADER}G1 X10 X20\n"), 2, "X given twice"),
        (
            format!("{HEADER}G0 X0 Y0 Z5\nG81 X10 Y0 Z-5 R2\n"),
            3,
            "G81: a canned cycle feeds to Z at the feed rate F in force, and none is",
        ),
        (
            format!("(stiffid: rotary = abc)\n{HEADER}G1 X10 C100000\n"),
            3,
            "C100000: expected a tool angle from -360 to 360 deg",
        ),
        (
            format!("(stiffid: rotary = abc)\n{HEADER}G1 X10 A-360.5\n"),
            3,
            "A-360.5: expected a tool angle",
        ),
        (
            format!("{HEADER}G1 X10 F0\n"),
            2,
            "F0: expected a feed rate",
        ),
        (format!("{HEADER}G1 X10 F10000000\n"), 2, "feed rate"),
        (
            format!("{HEADER}G0 X10 Y0 Z0\nM98 P100\n"),
            3,
            "P100: the program O100 is not in this file",
        ),
        (
            format!("{HEADER}G0 X10 Y0 Z0\nM30\nG1 X20\n"),
            4,
            "end of the program (M2/M30 on line 3)",
        ),
    ];
    refused_naming_the_line(&cases);
    // Rotary words that never leave the axis's zero: read as no motion, the first named.
    let zero = gcode::parse(
        &format!("{HEADER}G0 X0 Y0 Z0\nG1 X10 A0 F9\nB-0. C0\n"),
        1e-5,
    );
    let zero = zero.unwrap();
    assert_eq!((zero.zero_rotary, zero.points.len()), (Some(3), 2));
    assert!(matches!(
        gcode::parse(&format!("{HEADER}G1 X1\n"), 0.0),
        Err(Error::InvalidOption {
            option: stiffid::JobOption::ChordToleranceMm,
            ..
        })
    ));
}

/// Each G-code `text` refused by [`gcode::parse`] naming its `line` and saying `word`.
fn refused_naming_the_line(cases: &[(String, u64, &str)]) {
    for (text, line, word) in cases {
        match gcode::parse(text, 1e-5) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, *line, "{message}");
                assert!(message.contains(word), "{word}: {message}");
            }
            other => panic!("{word}: {other:?}"),
        }
    }
}

/// Blocks the subset used to read wrongly, now refused naming the line (found by mutation
/// fuzzing): a motion, an arc's turns or a spindle speed read other than as written, an arc
/// computed from a radius beyond the numbers.
#[test]
fn gcode_blocks_read_wrongly_before_are_refused_naming_the_line() {
    let cases = [
        // Two motions in one block: the last one was run, silently.
        (
            format!("{HEADER}G0 X0 Y0 Z5\nG0 G1 X10 F100\n"),
            3,
            "G1: a second code of the motion (G0-G3, G81-G83) group in one block (G0 before it)",
        ),
        (
            format!("{HEADER}G0 X0 Y0 Z5\nG1 X10 F100 G81 Z-5 R2\n"),
            3,
            "G81: a second code of the motion (G0-G3, G81-G83) group in one block (G1 before it)",
        ),
        // Two codes of another modal group: the last one was in force, silently; mist and
        // flood together are one coolant state.
        (
            format!("{HEADER}G0 X0 Y0 Z5\nG91 G90 G1 X10 F100\n"),
            3,
            "G90: a second code of the distance mode (G90, G91) group in one block (G91 before it)",
        ),
        (
            format!("{HEADER}G0 X0 Y0 Z5\nG17 G18 G1 X10 F100\n"),
            3,
            "G18: a second code of the plane (G17-G19) group in one block",
        ),
        (
            format!("{HEADER}G0 X0 Y0 Z5 G54 G55\n"),
            2,
            "G55: a second code of the work offset (G54-G59.3) group in one block",
        ),
        (
            format!("{HEADER}G0 X0 Y0 Z5 M3 M4\n"),
            2,
            "M4: a second code of the spindle (M3-M5) group in one block (M3 before it)",
        ),
        (
            format!("{HEADER}G0 X0 Y0 Z5 M7 M8 M9\n"),
            2,
            "M9: a second code of the coolant off (M9) group in one block (M7 before it)",
        ),
        // An arc's number of turns (LinuxCNC) was ignored: five turns read as one.
        (
            format!("{HEADER}G0 X0 Y0 Z0\nG1 X10 F100\nG2 X10 Y0 I-10 J0 P5\n"),
            4,
            "P5: an arc's number of turns (LinuxCNC's G2/G3 P) is not read",
        ),
        // An arc's radius or centre beyond the limits: a radius of 1e308 mm made the centre NaN
        // ("the arc's end is NaN mm off its circle").
        (
            format!("{HEADER}G0 X0 Y0 Z0\nG1 X10 F100\nG2 X11 Y0 R1000000000\n"),
            4,
            "R1e9: an arc's centre or radius beyond 100 m",
        ),
        (
            format!("G20\n{HEADER}G0 X0 Y0 Z0\nG1 X1 F100\nG2 X1 Y0 I-4000 J0\n"),
            5,
            "I-4000: an arc's centre or radius beyond 100 m",
        ),
        // An M code that is none was written into the robot program as an unknown one.
        (
            format!("{HEADER}G0 X10 Y0 Z0\nM-30\n"),
            3,
            "M-30: expected an M code, a whole number from 0 to 999",
        ),
        (
            format!("{HEADER}G0 X10 Y0 Z0 M3.5\n"),
            2,
            "M3.5: expected an M code",
        ),
        // A spindle speed out of range was written into the robot program's spindle call.
        (
            format!("{HEADER}S-1 M3\nG0 X10 Y0 Z0\n"),
            2,
            "S-1: expected a spindle speed from 0 to 100000 rev/min",
        ),
        (
            format!("{HEADER}G0 X10 Y0 Z0 S1000000000\n"),
            2,
            "S1e9: expected a spindle speed",
        ),
    ];
    refused_naming_the_line(&cases);
}

/// A G-code program saved with a byte-order mark (as editors on Windows do) reads as without
/// it; elsewhere, and for any other character that is no word, the line names the character as
/// written (it used to name the first byte of its UTF-8 encoding: 'ï' for the mark).
#[test]
fn gcode_with_a_byte_order_mark_reads_as_without_it() {
    let text = format!("{HEADER}G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 Y10\n");
    let plain = gcode::parse(&text, 1e-5).unwrap();
    let marked = gcode::parse(&format!("\u{feff}{text}"), 1e-5).unwrap();
    assert_eq!(marked.points.len(), plain.points.len());
    for (a, b) in marked.points.iter().zip(&plain.points) {
        assert_eq!(a.position, b.position);
    }
    for (text, line, expected) in [
        (
            format!("{HEADER}\u{feff}G1 X1\n"),
            2,
            "'\u{feff}': expected a word",
        ),
        (format!("{HEADER}G1 X1 é2\n"), 2, "'é': expected a word"),
    ] {
        match gcode::parse(&text, 1e-5) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}");
                assert!(message.contains(expected), "{expected}: {message}");
            }
            other => panic!("{expected}: {other:?}"),
        }
    }
}

const PROCESS: &str = "[tool]\ndiameter_mm = 20\nflutes = 3\nhelix_deg = 30\n[cut]\nfeed_per_tooth_mm = 0.1\n\
    axial_depth_mm = 4\nradial_depth_mm = 10\nmode = \"down\"\n[coefficients]\npreset = \"al7075-t6\"\n";

/// The FANUC example setup with the part frame at (1300, -700, 400) mm in the base frame.
fn fanuc() -> (stiffid::Setup, Compliance) {
    let part = Isometry3::translation(1.3, -0.7, 0.4);
    let s = setup::builtin("fanuc-r2000ic-165f")
        .unwrap()
        .to_builder()
        .with_workpiece(part)
        .build()
        .unwrap();
    let c = s.model_compliance("test").unwrap();
    (s, c)
}

/// An LS program whose targets reach a square in the plane z = 400 mm.
fn ls_program(s: &stiffid::Setup) -> String {
    ls_square(s, false)
}

/// The square's LS program, its `/POS` table in the motions' order or reversed.
fn ls_square(s: &stiffid::Setup, reversed: bool) -> String {
    let tcp = s.tool().tcp;
    let mut q = Options::for_setup(s).q0;
    let mut text = String::from("/PROG  SQUARE\n/MN\n");
    for i in 1..=5 {
        text += &format!("{i:>4}:L P[{i}] 10mm/sec FINE ;\n");
    }
    text += "/POS\n";
    let corners = [
        (0.0, 0.0),
        (60.0, 0.0),
        (60.0, 40.0),
        (0.0, 40.0),
        (0.0, 0.0),
    ];
    let mut positions = Vec::new();
    for (i, (x, y)) in corners.iter().enumerate() {
        let pose = Isometry3::from_parts(
            Vector3::new(1.3 + x * 1e-3, -0.7 + y * 1e-3, 0.4).into(),
            UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0),
        );
        q = ik::solve(s.robot(), &tcp, &pose, &q, &ik::Options::default())
            .unwrap()
            .q;
        let d = q.map(f64::to_degrees);
        positions.push(format!(
            "P[{}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {:.6} deg,\tJ2= {:.6} deg,\tJ3= {:.6} deg,\n\tJ4= {:.6} deg,\tJ5= {:.6} deg,\tJ6= {:.6} deg\n}};\n",
            i + 1, d[0], d[1], d[2], d[3], d[4], d[5]
        ));
    }
    if reversed {
        positions.reverse();
    }
    text + &positions.concat() + "/END\n"
}

/// The path follows the motions, not the `/POS` table: the square with its table reversed is
/// compensated exactly as with the table in order (the process force along the same feed).
#[test]
fn the_path_order_is_the_motions_not_the_position_table() {
    let (s, compliance) = fanuc();
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let options = Options::for_setup(&s);
    let run = |reversed: bool| {
        let text = ls_square(&s, reversed);
        let program = machining::read(&text, Language::Robot(Dialect::FanucLs), 1e-5).unwrap();
        machining::compensate(
            s.arm(),
            s.workpiece(),
            &compliance,
            &program,
            &process,
            &options,
        )
        .unwrap()
    };
    let (forward, backward) = (run(false), run(true));
    for (a, b) in forward.results.iter().zip(&backward.results) {
        assert_eq!(a.q, b.q);
        assert!((a.q_compensated - b.q_compensated).amax() <= 1e-12);
    }
    for (a, b) in forward.points.iter().zip(&backward.points) {
        assert_eq!(a.line, b.line);
        assert!(
            (a.wrench - b.wrench).amax() <= 1e-9,
            "{} {}",
            a.wrench,
            b.wrench
        );
    }
    // The feed along +x first: the down-milling feed force (x of the feed frame) on the tool
    // points along the feed, so the base-frame force of the second point has +x.
    assert!(
        forward.points[1].wrench[0] > 0.0,
        "{}",
        forward.points[1].wrench
    );
}

#[test]
fn a_compensated_program_has_the_csv_routes_targets() {
    let (s, compliance) = fanuc();
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let text = ls_program(&s);
    let program = machining::read(&text, Language::Robot(Dialect::FanucLs), 1e-5).unwrap();
    let options = Options::for_setup(&s);
    let report = machining::compensate(
        s.arm(),
        s.workpiece(),
        &compliance,
        &program,
        &process,
        &options,
    )
    .unwrap();
    // Every point cuts: the down-milling force, about 300 N, against the feed.
    for p in &report.points {
        let f = p.wrench.fixed_rows::<3>(0).norm();
        assert!(f > 100.0 && f < 1000.0, "{f}");
    }
    // The CSV route: the same postures and base-frame wrenches through the path file.
    let mut csv = String::from(
        "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm\n",
    );
    let Program::Robot(r) = &program else {
        panic!()
    };
    for (t, p) in r.targets.iter().zip(&report.points) {
        let cells: Vec<String> = t
            .q_deg
            .iter()
            .chain(p.wrench.iter())
            .map(|v| format!("{v:e}"))
            .collect();
        csv += &(cells.join(",") + "\n");
    }
    let points = machining::path::parse(&csv, Frame::Base).unwrap();
    let by_csv = compensate::path(s.arm(), &compliance, &points, &options).unwrap();
    let written = program::parse(&report.program, Dialect::FanucLs).unwrap();
    for ((a, b), t) in report.results.iter().zip(&by_csv).zip(&written.targets) {
        let qa = a.q_compensated.map(f64::to_degrees);
        let qb = b.q_compensated.map(f64::to_degrees);
        assert!((qa - qb).amax() <= 1e-9, "{qa} {qb}");
        assert!((qa - Vector6::from(t.q_deg)).amax() <= 1e-9);
        assert!(
            (qa - a.q.map(f64::to_degrees)).amax() > 1e-3,
            "the compensation moved the target"
        );
    }
    // Untouched lines stay.
    assert!(report
        .program
        .starts_with("/PROG  SQUARE\n/MN\n   1:L P[1] 10mm/sec FINE ;\n"));
}

#[test]
fn a_compensated_gcode_program_is_sent_where_the_loaded_tool_lands_on_the_programmed_path() {
    let (s, compliance) = fanuc();
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let text = format!("{HEADER}G0 X0 Y0 Z5\nG1 Z0 F600\nG1 X40\nG3 X60 Y20 I0 J20\nG1 Y40\n");
    let program = machining::read(&text, Language::GCode, 0.05e-3).unwrap();
    let report = machining::compensate(
        s.arm(),
        s.workpiece(),
        &compliance,
        &program,
        &process,
        &Options::for_setup(&s),
    )
    .unwrap();
    assert!(
        report.warnings.iter().any(|w| w.contains("plunge")),
        "{:?}",
        report.warnings
    );
    let again = gcode::parse(&report.program, 0.05e-3).unwrap();
    let Program::GCode(g) = &program else {
        panic!()
    };
    assert_eq!(again.points.len(), g.points.len());
    let part = *s.workpiece().unwrap();
    for (r, p) in report.results.iter().zip(&again.points) {
        let sent = tool_pose(&s.robot().frames(&r.q_compensated), &s.tool().tcp);
        let expected = part.inverse() * Point3::from(sent.translation.vector);
        assert!(
            (expected.coords - p.position).amax() < 1e-9,
            "{} {}",
            expected,
            p.position
        );
    }
    let moved = report
        .results
        .iter()
        .map(|r| (r.q_compensated - r.q).amax())
        .fold(0.0, f64::max);
    assert!(moved > 1e-5);
}

/// A G-code path written as a robot program moves at its own feed: `F` read per minute in the
/// block's units, rapid moves and the first point as joint motions; a cutting move without a feed
/// in force is refused naming its line, as is a feed that is not positive or faster than the
/// robot.
#[test]
fn a_gcode_path_written_as_a_robot_program_moves_at_its_feed() {
    use stiffid::internal::machining::program::generate::{
        generate, moves, Move, Plan, Settings, Target, Tool,
    };
    let text = format!("{HEADER}G21 G0 X0 Y0 Z5\nG1 Z0 F600\nG1 X40\nG20 G1 X2 F12\nG0 Z1\n");
    let g = gcode::parse(&text, 1e-5).unwrap();
    let m = moves(&g.points, 2.0).unwrap();
    assert_eq!(m.len(), 5);
    assert_eq!(m[0], Move::Rapid);
    assert_relative_eq!(g.points[1].feed.unwrap(), 0.01, max_relative = 1e-15);
    assert_eq!(m[1..3], [Move::Feed(0.01), Move::Feed(0.01)]);
    let Move::Feed(inch) = m[3] else {
        panic!("{m:?}")
    };
    assert_relative_eq!(inch, 12.0 * 25.4e-3 / 60.0, max_relative = 1e-15);
    assert_eq!(m[4], Move::Rapid);
    let (s, _) = fanuc();
    let q = Vector6::new(0.0, -10.0, 10.0, 0.0, -30.0, 0.0).map(f64::to_radians);
    let targets = vec![Target::new(s.robot(), &s.tool().tcp, &q); 5];
    let plan = Plan {
        dialect: Dialect::FanucLs,
        name: "P",
        targets: &targets,
        moves: &m,
        tool: Tool {
            frame: nalgebra::Translation3::from(s.tool().tcp).into(),
            payload: None,
        },
        work: *s.workpiece().unwrap(),
        world: nalgebra::Isometry3::identity(),
        external: None,
        approximation: 1e-5,
        numbers: Default::default(),
        pulses: None,
        settings: Settings::default(),
    };
    let written = generate(&plan).unwrap();
    let ls = &written.files[0].text;
    assert!(ls.contains("  11:L P[2] 10mm/sec CNT100 ;\n"), "{ls}");
    // 12 inch/min = 5.08 mm/s = 30.48 cm/min: the nearest whole cm/min, with a warning.
    assert!(
        ls.contains("  13:L P[4] 30cm/min CNT100 ;\n  14:J P[5] 20% FINE ;\n"),
        "{ls}"
    );
    assert!(
        written.warnings[0].contains("304.8 mm/min"),
        "{:?}",
        written.warnings
    );
    // F1000000 mm/min (16.7 m/s), or a feed in inch/min after G20 beyond the robot: refused.
    for fast in ["G21 G1 X1 F1000000", "G20 G1 X1 F5000"] {
        match moves(
            &gcode::parse(&format!("{HEADER}G0 X0 Y0 Z5\n{fast}\n"), 1e-5)
                .unwrap()
                .points,
            2.0,
        ) {
            Err(Error::Program { line: 3, message }) => {
                assert!(
                    message.contains("largest TCP speed, 2000 mm/s"),
                    "{message}"
                )
            }
            other => panic!("{fast}: {other:?}"),
        }
    }
    let without = format!("{HEADER}G0 X0 Y0 Z5\nG1 Z0\n");
    match moves(&gcode::parse(&without, 1e-5).unwrap().points, 2.0) {
        Err(Error::Program { line: 3, message }) => assert!(message.contains("feed"), "{message}"),
        other => panic!("{other:?}"),
    }
    match gcode::parse(&format!("{HEADER}G1 X1 F-5\n"), 1e-5) {
        Err(Error::Program { line: 2, message }) => assert!(message.contains("F-5"), "{message}"),
        other => panic!("{other:?}"),
    }
}

/// The controller's straight line between two compensated Cartesian targets stays on the
/// compensated path: the midpoint of the line between the targets of a path cut every 10 mm is
/// within the chord tolerance of the compensated midpoint (the target of the same path cut every
/// 5 mm).
#[test]
fn a_linear_move_between_compensated_targets_stays_within_the_chord_tolerance() {
    use stiffid::internal::machining::program::generate::Target;
    let (s, compliance) = fanuc();
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let path = |step: usize| {
        let blocks: String = (1..=80 / step)
            .map(|i| format!("G1 X{}\n", i * step))
            .collect();
        let text = format!("{HEADER}G0 X0 Y0 Z0\nG1 X0 F600\n{blocks}");
        let program = machining::read(&text, Language::GCode, 1e-5).unwrap();
        let r = machining::compensate(
            s.arm(),
            s.workpiece(),
            &compliance,
            &program,
            &process,
            &Options::for_setup(&s),
        )
        .unwrap();
        r.results
            .iter()
            .map(|c| Target::new(s.robot(), &s.tool().tcp, &c.q_compensated))
            .collect::<Vec<_>>()
    };
    let (coarse, fine) = (path(10), path(5));
    let tolerance = 0.01e-3;
    let mut largest = 0.0f64;
    for i in 2..coarse.len() - 1 {
        let (a, b) = (&coarse[i], &coarse[i + 1]);
        let middle = (a.pose.translation.vector + b.pose.translation.vector) / 2.0;
        let compensated = fine[2 * i].pose.translation.vector;
        largest = largest.max((middle - compensated).norm());
        // The targets are the compensated axis angles' forward kinematics, not the path's.
        let nominal_x = (i - 1) as f64 * 10e-3 + 1.3;
        assert!((a.pose.translation.x - nominal_x).abs() > 1e-6);
    }
    assert!(largest < tolerance, "{largest} m");
    assert!(largest > 0.0);
}

/// A program name no file can take (a Windows device name: `CON`, `NUL`, `COM1`, ..) is
/// refused in every dialect, and so is KRL's `BAS` (the standard `BAS.SRC` every generated KRL
/// program calls); names that only begin like them are taken.
#[test]
fn device_names_and_krl_bas_are_refused_as_program_names() {
    use stiffid::internal::machining::program::generate::check_name;
    for dialect in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
        for name in ["CON", "con", "Nul", "AUX", "PRN", "COM1", "lpt9"] {
            let e = check_name(dialect, name, 24).unwrap_err().to_string();
            assert!(
                e.contains("a device name of Windows"),
                "{dialect:?} {name}: {e}"
            );
        }
        for name in ["COM", "COM10", "CONE", "NULL1", "LPTX"] {
            assert!(check_name(dialect, name, 24).is_ok(), "{dialect:?} {name}");
        }
    }
    let e = check_name(Dialect::Krl, "bas", 24).unwrap_err().to_string();
    assert!(e.contains("reserved word of KUKA KRL"), "{e}");
    assert!(check_name(Dialect::Rapid, "BAS", 24).is_ok());
    // An INFORM job's name may hold `-` (a real YRC1000 backup's `R1_HAND-OFF.JBI`); KRL's not.
    assert!(check_name(Dialect::Inform, "R1_HAND-OFF", 32).is_ok());
    let renamed = stiffid::internal::machining::program::rename::renamed(
        "/JOB\r\n//NAME R1_HAND-OFF\r\n",
        Dialect::Inform,
        "R1_HAND-OFF_C",
    );
    assert_eq!(renamed, "/JOB\r\n//NAME R1_HAND-OFF_C\r\n");
    let e = check_name(Dialect::Krl, "R1_HAND-OFF", 24)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("expected letters, digits and _, starting"),
        "{e}"
    );
}
