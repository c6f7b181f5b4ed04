//! G-code as a controller runs it: axes known only once given (or from the setup's start),
//! work offsets, `G53`, `G28`, tool length offsets from the process's tool table, arc centre
//! modes, the arc end tolerance of LinuxCNC and grbl, and what real posts write besides, each
//! read at known values or refused naming the line and the construct.

use approx::assert_relative_eq;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use stiffid::internal::machining::gcode::{self, Machine, ProgramFrames};
use stiffid::Error;

const DOWN: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n";

fn mm(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z) * 1e-3
}

fn read(text: &str, m: &Machine) -> gcode::GCode {
    gcode::parse_on(&format!("{DOWN}{text}"), 1e-5, m).unwrap_or_else(|e| panic!("{e}"))
}

fn refused(text: &str, m: &Machine, line: u64, construct: &str) {
    match gcode::parse_on(&format!("{DOWN}{text}"), 1e-5, m) {
        Err(Error::Program { line: l, message }) => {
            assert_eq!(l, line, "{message}");
            assert!(message.contains(construct), "{construct}: {message}");
        }
        other => panic!("{construct}: {other:?}"),
    }
}

/// The lines and positions of the points.
fn path(g: &gcode::GCode) -> Vec<(u64, Vector3<f64>)> {
    g.points.iter().map(|p| (p.line, p.position)).collect()
}

#[test]
fn an_axis_is_known_only_once_given_or_from_the_setups_start() {
    let m = Machine::default();
    // Fusion 360: X Y before any Z: no point until Z is given, never a move to Z = 0.
    let g = read("G0 X-0.7 Y-0.7\nZ10\nG1 Z-1 F100\n", &m);
    assert_eq!(
        path(&g),
        vec![(3, mm(-0.7, -0.7, 10.0)), (4, mm(-0.7, -0.7, -1.0))]
    );
    refused(
        "G0 X1 Y2\nG1 Z-1 F100\n",
        &m,
        3,
        "G1: a feed move from or to a place not known: Z has no value yet",
    );
    refused(
        "G0 Z5\nG2 X1 Y0 I1 J0 F100\n",
        &m,
        3,
        "X Y has no value yet",
    );
    refused(
        "G0 X1 Y2\nG91 G0 Z5\n",
        &m,
        2,
        "no motion reaches a point whose X, Y and Z are all known",
    );
    // The setup's start: the first rapid moves X and Y from there (LinuxCNC).
    let started = Machine {
        frames: ProgramFrames {
            start: Some(mm(0.0, 0.0, 100.0)),
            ..Default::default()
        },
        ..Default::default()
    };
    let g = read("G0 X1 Y2\nG91 G1 Z-5 F100\n", &started);
    assert_eq!(
        path(&g),
        vec![(2, mm(1.0, 2.0, 100.0)), (3, mm(1.0, 2.0, 95.0))]
    );
    // Written back incrementally from the start: the increment is the compensated one.
    let text = g.write(&[mm(1.0, 2.0, 100.0), mm(1.0, 2.0, 94.0)]).unwrap();
    assert!(
        text.contains("G91 G1 X0.000000 Y0.000000 Z-6.000000 F100"),
        "{text}"
    );
}

fn offsets() -> Machine {
    let g55 = Isometry3::from_parts(
        Translation3::new(0.3, 0.0, 0.0),
        UnitQuaternion::from_euler_angles(0.0, 0.0, std::f64::consts::FRAC_PI_2),
    );
    let g53 = Isometry3::translation(-0.5, -0.4, -0.3);
    let extended = Isometry3::translation(0.0, 0.25, 0.0);
    Machine {
        frames: ProgramFrames {
            offsets: vec![
                ("G55".into(), g55),
                ("G53".into(), g53),
                ("G54.1 P2".into(), extended),
            ],
            ..Default::default()
        },
        ..Default::default()
    }
}

#[test]
fn work_offsets_place_the_path_in_the_setups_frames_and_write_it_back_in_them() {
    let m = offsets();
    let text =
        "G54 G0 X10 Y0 Z5\nG55 G0 X10 Y0 Z5\nG1 X20 F100\nG53 G0 Z0\nG54.1 P2 G0 X1\nG54 X0\n";
    let g = read(text, &m);
    // G55 turned 90 deg about Z at (300, 0, 0) mm: its X is G54's Y.
    let expected = [
        (2, mm(10.0, 0.0, 5.0)),
        (3, mm(300.0, 10.0, 5.0)),
        (4, mm(300.0, 20.0, 5.0)),
        (5, mm(300.0, 20.0, -300.0)),
        (6, mm(1.0, 20.0, -300.0)),
        (7, mm(0.0, 20.0, -300.0)),
    ];
    for ((line, p), (l, q)) in path(&g).iter().zip(expected) {
        assert_eq!(*line, l);
        assert_relative_eq!(*p, q, epsilon = 1e-12);
    }
    // Written back, each block's words are in its own frame (G53's in machine coordinates).
    let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
    let written = g.write(&positions).unwrap();
    assert!(
        written.contains("G53 G0 X800.000000 Y420.000000 Z0.000000"),
        "{written}"
    );
    assert!(
        written.contains("G1 X20.000000 Y-0.000000 Z5.000000")
            || written.contains("G1 X20.000000 Y0.000000 Z5.000000"),
        "{written}"
    );
    let again = gcode::parse_on(&written, 1e-5, &m).unwrap();
    for (a, b) in again.points.iter().zip(&g.points) {
        assert_relative_eq!(a.position, b.position, epsilon = 1e-9);
    }
    refused(
        "G56 G0 X1 Y2 Z3\n",
        &m,
        2,
        "G56: the setup gives no frame for this work offset",
    );
    refused("G59.2\n", &m, 2, "G59.2: the setup gives no frame");
    refused("G54.1 P7\n", &m, 2, "G54.1 P7: the setup gives no frame");
    refused(
        "G54.1 X1\n",
        &m,
        2,
        "G54.1: expected the additional work offset's number P",
    );
    refused(
        "G0 X1 Y2 Z3\nG91 G53 G0 Z0\n",
        &m,
        3,
        "G53 in G91: controllers differ",
    );
    refused(
        "G0 X1 Y2 Z3\nG53 G2 X1 Y2 R5\n",
        &m,
        3,
        "G53: machine coordinates move with G0 or G1 only",
    );
    refused(
        "G0 X1 Y2 Z3\nG1 Z1 F100\nG53 Z0\n",
        &Machine::default(),
        4,
        "G53: the setup gives no frame for machine coordinates, which a feed (G1) to them needs",
    );
}

fn tools() -> Machine {
    Machine {
        frames: ProgramFrames {
            g28: Some(mm(0.0, 0.0, 150.0)),
            ..Default::default()
        },
        tool_lengths: vec![(Some(1), 0.05), (Some(2), 0.08)],
        ..Default::default()
    }
}

#[test]
fn tool_length_offsets_place_the_tip_with_the_process_tool_table() {
    let m = tools();
    // G43 H of the tool in use programs the tip; without an offset (G49) the gauge line.
    let g = read(
        "T1 M6\nG43 H1 G0 X0 Y0 Z10\nG49\nG0 Z10\nT2 M6\nG43 G0 Z10\nG43 H1 G0 Z10\n",
        &m,
    );
    let z: Vec<f64> = g.points.iter().map(|p| p.position.z * 1e3).collect();
    let want = [10.0, 10.0 - 50.0, 10.0, 10.0 + 50.0 - 80.0];
    for (a, b) in z.iter().zip(want) {
        assert_relative_eq!(*a, b, epsilon = 1e-9);
    }
    refused(
        "T1 M6\nG43 H3\n",
        &m,
        3,
        "G43 H3: the process's tool table has no length for tool 3",
    );
    refused("G43 Z10\n", &m, 2, "G43 without H before any T");
    // One length for every tool: G43 alone puts it in force, whichever tool the spindle holds.
    let one = Machine {
        tool_lengths: vec![(None, 0.05)],
        ..Default::default()
    };
    let g = read("G43 G0 X0 Y0 Z10\nG1 Z-1 F100\n", &one);
    assert_eq!(
        (g.points[1].position, g.no_length_offset),
        (mm(0.0, 0.0, -1.0), None)
    );
    refused(
        "T1 G43 H1\n",
        &Machine::default(),
        2,
        "G43: a tool length offset needs the tools' lengths",
    );
    refused(
        "T5 M6\nG0 X0 Y0 Z10\n",
        &m,
        3,
        "the tool in use (T5) has no length in the process's tool table",
    );
    // G28 G91 Z0 (Fusion 360): Z to the setup's G28 position, the tip's; X Y stay.
    let g = read(
        "T1 M6 G43 H1\nG0 X1 Y2 Z3\nG28 G91 Z0.\nG90\nG28 G91 X0. Y0.\n",
        &m,
    );
    assert_eq!(
        path(&g),
        vec![
            (3, mm(1.0, 2.0, 3.0)),
            (4, mm(1.0, 2.0, 150.0)),
            (6, mm(0.0, 0.0, 150.0))
        ]
    );
    refused(
        "G0 X1 Y2 Z3\nG28\n",
        &Machine::default(),
        3,
        "G28: the setup does not state the G28 position",
    );
}

#[test]
fn g53_places_the_spindle_without_the_tool_length_offset_under_g43_and_g49() {
    // Machine Z0 is 200 mm above the part's origin; T1 is 50 mm long. G53 Z0 puts the gauge
    // line at Z200 of the part, the tip at Z150, whatever offset is in force.
    let mut m = tools();
    m.frames.offsets = vec![("G53".into(), Isometry3::translation(-0.5, -0.4, 0.2))];
    for offset in ["G43 H1", "G49"] {
        let text = format!("T1 M6\n{offset} G0 X0 Y0 Z20\nG53 G0 Z0\nG53 G1 X510 F300\nG0 Z20\n");
        let g = read(&text, &m);
        // Z20 under G43 H1 is the tip; under G49 the gauge line, the tip 50 mm below it.
        let z = if offset == "G49" { -30.0 } else { 20.0 };
        let want = [
            (3, mm(0.0, 0.0, z)),
            (4, mm(0.0, 0.0, 150.0)),
            (5, mm(10.0, 0.0, 150.0)),
            (6, mm(10.0, 0.0, z)),
        ];
        assert_eq!(g.points.len(), want.len(), "{offset}");
        for (p, (line, q)) in g.points.iter().zip(want) {
            assert_eq!(p.line, line, "{offset}");
            assert_relative_eq!(p.position, q, epsilon = 1e-9);
        }
        // Written back, the G53 blocks are the spindle's machine coordinates again.
        let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
        let written = g.write(&positions).unwrap();
        assert!(
            written.contains("G53 G0 X500.000000 Y400.000000 Z0.000000"),
            "{written}"
        );
        let again = gcode::parse_on(&written, 1e-5, &m).unwrap();
        for (a, b) in again.points.iter().zip(&g.points) {
            assert_relative_eq!(a.position, b.position, epsilon = 1e-9);
        }
    }
}

#[test]
fn a_g53_rapid_without_the_setups_frame_leaves_the_axes_it_names_unknown() {
    // Fusion 360's Haas post: "G53 G0 Z0." before the first tool, between tools and at the
    // end; the setup gives no G53 frame. Each retract makes no point and leaves Z unknown: the
    // next point is where X, Y and Z are stated again (G43 H of the tool in use: the tip).
    let m = tools();
    let text = "G21 G90\nG53 G0 Z0.\nT1 M6\nG54\nG0 X10. Y10.\nG43 Z15. H1\nG1 Z-1. F300.\nX20.\nG0 Z15.\nG53 G0 Z0.\nT2 M6\nG0 X30. Y0.\nG43 Z15. H2\nG1 Z-2.\nG0 Z15.\nG53 G0 Z0.\nM30\n";
    let g = read(text, &m);
    let want = [
        (7, Some(1), mm(10.0, 10.0, 15.0)),
        (8, Some(1), mm(10.0, 10.0, -1.0)),
        (9, Some(1), mm(20.0, 10.0, -1.0)),
        (10, Some(1), mm(20.0, 10.0, 15.0)),
        (14, Some(2), mm(30.0, 0.0, 15.0)),
        (15, Some(2), mm(30.0, 0.0, -2.0)),
        (16, Some(2), mm(30.0, 0.0, 15.0)),
    ];
    assert_eq!(g.points.len(), want.len());
    for (p, (line, tool, q)) in g.points.iter().zip(want) {
        assert_eq!((p.line, p.tool_number), (line, tool));
        assert_relative_eq!(p.position, q, epsilon = 1e-12);
    }
    assert_eq!(g.unplaced_g53, vec![3, 11, 17]);
    // Written back, the G53 blocks are as found: the controller goes where its machine is.
    let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
    let written = g.write(&positions).unwrap();
    assert_eq!(written.matches("\nG53 G0 Z0.\n").count(), 3, "{written}");
    // What moves from the place the G53 rapid left unknown is refused naming the line, and
    // the G53 rapid's (Z was given on line 3: not "no value yet", which blames the start).
    let since = "Z has no value since line 4 (a G53 rapid there went to machine coordinates, which the setup does not place";
    refused(
        "T1 M6 G43 H1\nG0 X1 Y2 Z3\nG53 G0 Z0\nG1 X5 F100\n",
        &m,
        5,
        &format!("G1: a feed move from or to a place not known: {since}"),
    );
    refused(
        "T1 M6 G43 H1\nG0 X1 Y2 Z3\nG53 G0 Z0\nG0 X7 Y7\nG1 Z-1 F100\n",
        &m,
        6,
        since,
    );
    refused(
        "T1 M6 G43 H1\nG0 X1 Y2 Z3\nG53 G0 Z0\nG81 X5 Y5 Z-2 R2 F100\n",
        &m,
        5,
        &format!("G81: a canned cycle from a place not known: {since}"),
    );
    // A home return while the tool in use has no length: the axes it moves, from its line.
    refused(
        "G0 X1 Y2 Z3\nG28 Z10\nT1 M6 G43 H1\nG1 X5 F100\n",
        &m,
        5,
        "Z has no value since line 3 (a home return (G28/G30) there",
    );
    refused(
        "G53 G0 Z0\nM30\n",
        &m,
        2,
        "no motion reaches a point whose X, Y and Z are all known",
    );
}

#[test]
fn g53_before_the_first_tool_places_the_spindle_and_the_tip_once_a_tool_is_named() {
    // Machine Z0 is 200 mm above the part's origin, the start is stated, T1 is 50 mm long.
    // Before any T the spindle holds whatever tool the machine holds: the retract makes no
    // point (its tip is not known), and after T1 M6 the tip is T1's length below the gauge
    // line, which stayed at machine Z0 (part Z 200).
    let mut m = tools();
    m.frames.offsets = vec![("G53".into(), Isometry3::translation(-0.5, -0.4, 0.2))];
    m.frames.start = Some(mm(0.0, 0.0, 100.0));
    let g = read(
        "G21 G90\nG53 G0 Z0.\nT1 M6\nG54 G0 X10. Y10.\nG43 Z15. H1\nG1 Z-1. F300.\n",
        &m,
    );
    let want = [
        (5, mm(10.0, 10.0, 200.0 - 50.0)),
        (6, mm(10.0, 10.0, 15.0)),
        (7, mm(10.0, 10.0, -1.0)),
    ];
    assert_eq!(path(&g).len(), want.len());
    for ((line, p), (l, q)) in path(&g).into_iter().zip(want) {
        assert_eq!(line, l);
        assert_relative_eq!(p, q, epsilon = 1e-12);
    }
    assert!(g.unplaced_g53.is_empty());
    // A feed, or no point at all, before any tool is named: refused naming the line.
    refused(
        "G53 G0 Z0.\nG1 X5 F100\n",
        &m,
        3,
        "no tool named yet (no T word before this line)",
    );
    refused("G53 G0 Z0.\nM30\n", &m, 2, "no tool named yet");
    // G43 H1 in force before the first tool: G53 Z0 places the gauge line whatever the tool
    // in use, so after T1 M6 the tip is 50 mm below machine Z0 (part Z 150), not at it.
    let mut m = tools();
    m.frames.offsets = vec![("G53".into(), Isometry3::translation(-0.5, -0.4, 0.2))];
    let g = read("G43 H1\nG53 G0 Z0.\nT1 M6\nG0 X0 Y0\n", &m);
    assert_eq!(path(&g).len(), 1);
    assert_eq!(path(&g)[0].0, 5);
    assert_relative_eq!(path(&g)[0].1, mm(0.0, 0.0, 150.0), epsilon = 1e-12);
}

#[test]
fn g53_outside_a_g0_or_g1_block_is_refused_naming_the_line() {
    // LinuxCNC refuses G53 unless G0 or G1 is in force; read in a canned cycle, the hole would
    // be drilled at the G54 coordinates of the words, 500 mm off.
    let mut m = Machine::default();
    m.frames.offsets = vec![("G53".into(), Isometry3::translation(-0.5, -0.4, 0.2))];
    refused(
        "G0 X0 Y0 Z20\nG98 G81 X10 Y10 Z-3 R2 F100\nG53 X20 Y10\n",
        &m,
        4,
        "G53 while the canned cycle G81 is in force",
    );
    m.frames.g28 = Some(mm(0.0, 0.0, 150.0));
    refused(
        "G0 X0 Y0 Z20\nG53 G28 Z0\n",
        &m,
        3,
        "G53 with G28 in its block",
    );
}

#[test]
fn a_t_word_after_a_tool_change_preselects_and_the_tool_in_use_is_the_one_m6_loaded() {
    let m = tools();
    // Fusion 360's Haas and Fanuc posts: the next tool selected right after the change. T1
    // (50 mm) is in the spindle, G43 H1 programs its tip: the cut is at Z-1, not 30 mm lower
    // with T2's 80 mm.
    let g = read(
        "T1 M6\nT2\nG54 G0 X0 Y0\nG43 Z15 H1\nG1 Z-1 F300\nX20\nG0 Z15\n",
        &m,
    );
    let want = [
        (5, mm(0.0, 0.0, 15.0)),
        (6, mm(0.0, 0.0, -1.0)),
        (7, mm(20.0, 0.0, -1.0)),
        (8, mm(20.0, 0.0, 15.0)),
    ];
    assert_eq!(g.points.len(), want.len());
    for (p, (line, q)) in g.points.iter().zip(want) {
        assert_eq!((p.line, p.tool_number), (line, Some(1)));
        assert_relative_eq!(p.position, q, epsilon = 1e-9);
    }
    // The tool select event names the tool selected.
    let select = g.process.iter().find(|w| w.line == 3).unwrap();
    assert_eq!((select.words.as_str(), select.tool), ("T2", Some(2)));
    // M6 alone loads the last T selected before it; G43 without H in its block takes the tool
    // it loaded (T2, 80 mm): the tip programmed.
    let g = read(
        "T1 M6\nG43 H1 G0 X0 Y0 Z10\nT2\nG0 X5\nM6 G43 Z12\nG0 X6\n",
        &m,
    );
    let tools: Vec<(u64, Option<u32>)> = g.points.iter().map(|p| (p.line, p.tool_number)).collect();
    let want = [(3, Some(1)), (5, Some(1)), (6, Some(2)), (7, Some(2))];
    assert_eq!(tools, want);
    assert_relative_eq!(g.points[1].position, mm(5.0, 0.0, 10.0), epsilon = 1e-9);
    assert_relative_eq!(g.points[2].position, mm(5.0, 0.0, 12.0), epsilon = 1e-9);
    assert_relative_eq!(g.points[3].position, mm(6.0, 0.0, 12.0), epsilon = 1e-9);
    // Without any M6 (a machine without a tool changer), the T is the tool in use.
    let g = read("T2\nG43 G0 X0 Y0 Z10\n", &m);
    assert_eq!(g.points[0].tool_number, Some(2));
    assert_relative_eq!(g.points[0].position, mm(0.0, 0.0, 10.0), epsilon = 1e-9);
}

#[test]
fn arcs_end_within_grbls_and_linuxcncs_tolerance_and_centres_in_either_mode() {
    let m = Machine::default();
    // Fusion's 3-decimal rounding: 1.587 and 1.588 mm radii, 1 um off; the end is reached.
    let g = read(
        "G0 X0 Y-1.587 Z0\nG2 X-1.587 Y0 I0 J1.587 F500\nG2 X0 Y1.588 I1.587 J0\n",
        &m,
    );
    assert_relative_eq!(
        g.points.last().unwrap().position,
        mm(0.0, 1.588, 0.0),
        epsilon = 1e-15
    );
    // 9 um off a 10 mm radius (0.09 %) is accepted; its points spiral from one radius to the other.
    let g = read("G0 X10 Y0 Z0\nG3 X-10.009 Y0 I-10 J0\n", &m);
    for p in &g.points {
        let r = ((p.position.x * 1e3).powi(2) + (p.position.y * 1e3).powi(2)).sqrt();
        assert!((10.0 - 1e-9..=10.009 + 1e-9).contains(&r), "{r}");
    }
    refused(
        "G0 X1 Y0 Z0\nG3 X-1.006 Y0 I-1 J0\n",
        &m,
        3,
        "the arc's end is 0.0060 mm off its circle",
    );
    refused(
        "G0 X400 Y0 Z0\nG3 X-400.6 Y0 I-400 J0\n",
        &m,
        3,
        "0.6000 mm off",
    );
    // An R short of half the chord (5 mm) by more than LinuxCNC's 0.00127 mm, both in mm.
    refused(
        "G0 X0 Y0 Z5\nG1 Z0 F100\nG2 X10 Y0 R4\n",
        &m,
        4,
        "R4.0000 mm is shorter than half the chord (5.0000 mm)",
    );
    // G90.1: I J K are the centre itself.
    let absolute = read("G90.1\nG0 X10 Y5 Z0\nG3 X0 Y15 I0 J5\n", &m);
    let incremental = read("G91.1\nG0 X10 Y5 Z0\nG3 X0 Y15 I-10 J0\n", &m);
    assert_eq!(absolute.points.len(), incremental.points.len());
    for (a, b) in absolute.points.iter().zip(&incremental.points) {
        assert_relative_eq!(a.position, b.position, epsilon = 1e-15);
    }
    refused(
        "G90.1\nG0 X10 Y5 Z0\nG3 X0 Y15 I0\n",
        &m,
        4,
        "G90.1 (absolute arc centres): give both",
    );
}

#[test]
fn what_real_posts_write_is_read_or_refused_naming_the_line() {
    let m = Machine::default();
    let g = read(
        "%\n%MPF1 text after the tape mark\nO1001 (PROGRAM)\nN10 G61 G64 P0.01 Q0.01 G94\nN20 G0 X1 Y2 Z3 ; comment\nM6 T1\nS1000 M3 M8\nG4 P1\nM9 M5\nG61.1 G40 G49\nG1 X2 F100\nM30\n%\n",
        &m,
    );
    assert_eq!(
        path(&g),
        vec![(6, mm(1.0, 2.0, 3.0)), (12, mm(2.0, 2.0, 3.0))]
    );
    for (text, construct) in [
        ("/G0 X1 Y2 Z3\n", "/: a block delete line"),
        ("G0 X1 Y2 Z3 /M8\n", "/ within the block: a block delete of the words after it"),
        ("G0 X#5061 Y0 Z0\n", "#5061: a parameter the controller sets at run time"),
        ("G0 X#100 Y0 Z0\n", "#100 is read before the program sets it"),
        ("G0 X[1 +] Y0 Z0\n", "X: expected a value at '] Y0 Z0'"),
        ("o100 sub\n", "O100: no endsub of the same label after it"),
        ("O<probe> call [1]\n", "O<probe> call: no O<probe> sub in this file"),
        ("M98 P100\n", "P100: the program O100 is not in this file"),
        ("G92 X0 Y0\n", "G92: read with [controller] dialect"),
        ("G93\n", "G93: not in the supported subset"),
        ("G41 D1\n", "G41: controllers enter cutter radius compensation"),
        ("G0 @10 ^45\n", "polar coordinates (@ ^): LinuxCNC's words"),
        ("G28.1\n", "G28.1: not in the supported subset"),
        ("G1 X1e3 Y0 Z0 F100\n", "X1e3: a number with an exponent is no G-code number (a controller reads X1 and then a word E)"),
        ("G1 X10E-1 Y0 Z0 F100\n", "X10E-1: a number with an exponent"),
        ("(stiffid: rotary = abd)\n", "rotary = abd: expected abc"),
    ] {
        refused(text, &m, 2, construct);
    }
}
