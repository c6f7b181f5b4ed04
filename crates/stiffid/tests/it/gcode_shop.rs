//! What hand-written shop programs and CAM posts write that the corpus of real programs found
//! refused or misread: canned cycles in another work offset and under a tool length offset, a
//! dwell beside a move (LinuxCNC), a `G53` retract under `G91` on Haas, and a `T` that names the
//! tool the spindle held from the start, LinuxCNC's polar coordinates. Each read at known values or refused naming the line.

use approx::assert_relative_eq;
use nalgebra::{Isometry3, Vector3};
use stiffid::internal::machining::gcode::{self, GcodeDialect, Machine, ProgramFrames};
use stiffid::Error;

const DOWN: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n";

fn mm(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z) * 1e-3
}

fn parse(text: &str, m: &Machine) -> stiffid::Result<gcode::GCode> {
    gcode::parse_on(&format!("{DOWN}{text}"), 1e-5, m)
}

fn refused(text: &str, m: &Machine, line: u64, construct: &str) {
    match parse(text, m) {
        Err(Error::Program { line: l, message }) => {
            assert_eq!(l, line, "{message}");
            assert!(message.contains(construct), "{construct}: {message}");
        }
        other => panic!("{construct}: {other:?}"),
    }
}

/// A Haas cell: `G55` 100 mm along X and 20 mm up from `G54`, T1 50 mm and T2 80 mm long.
fn haas() -> Machine {
    Machine {
        frames: ProgramFrames {
            offsets: vec![("G55".into(), Isometry3::translation(0.1, 0.0, 0.02))],
            g28: Some(mm(0.0, 0.0, 150.0)),
            ..Default::default()
        },
        tool_lengths: vec![(Some(1), 0.05), (Some(2), 0.08)],
        dialect: Some(GcodeDialect::Haas),
        ..Default::default()
    }
}

#[test]
fn a_canned_cycle_drills_in_the_work_offset_and_tool_length_offset_in_force() {
    // As a Haas shop program writes it (the safe start block selects G55, "G43 H08" alone):
    // each hole's bottom is its X Y Z in G55, the tip where H of the tool in use puts it.
    let m = haas();
    let text = "G0 G17 G40 G49 G55 G80 G90 G98\nT1 M6\nG43 H1\nG0 X10 Y5\nZ10\nG81 Z-30 R2 F100\nX20\nG80\nT2 M6\nG43 H1 G0 Z10\nG81 X30 Y5 Z-30 R2 F100\nG80\n";
    let g = parse(text, &m).unwrap();
    let bottoms: Vec<Vector3<f64>> = g.cycles.iter().map(|c| c.bottom).collect();
    // Under H1 with T2 in the spindle the tip is 30 mm below where H2 would put it.
    let want = [
        mm(110.0, 5.0, -10.0),
        mm(120.0, 5.0, -10.0),
        mm(130.0, 5.0, -10.0 - 30.0),
    ];
    assert_eq!(bottoms.len(), 3);
    for (b, w) in bottoms.iter().zip(want) {
        assert_relative_eq!(*b, w, epsilon = 1e-12);
    }
    // The levels are the part frame's: the hole cuts from the part's surface (Z0 of G54, 20
    // mm below G55's Z0), the feed from R down to it in the air.
    assert_relative_eq!(g.cycles[0].retract, 0.022, epsilon = 1e-12);
    assert_relative_eq!(g.cycles[0].clearance, 0.03, epsilon = 1e-12);
    assert_relative_eq!(g.cycles[0].entry, 0.0, epsilon = 1e-12);
    // Written back in G55 with the offsets in force, it reads back to the same points.
    let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
    let out = g.write(&positions).unwrap();
    assert!(out.contains("G1 X10.000000 Y5.000000 Z-30.000000"), "{out}");
    let again = parse(&out, &m).unwrap();
    assert_eq!(again.points.len(), g.points.len());
    for (a, b) in again.points.iter().zip(&g.points) {
        assert_relative_eq!(a.position, b.position, epsilon = 1e-12);
    }
    // On FANUC and Haas a changed offset is taken up at the next Z move, and a cycle positions
    // over the hole first: a cycle right after G43 alone is refused naming both lines.
    refused(
        "T1 M6 G43 H1 G0 X0 Y0 Z10\nT2 M6\nG43 H2\nG81 X1 Y1 Z-30 R2 F100\n",
        &haas(),
        5,
        "a canned cycle after the tool length offset changed on line 4 without a Z move",
    );
    // A work offset that turns the part's Z axis: refused naming the line.
    let mut m = haas();
    m.frames.offsets = vec![(
        "G55".into(),
        Isometry3::rotation(Vector3::new(0.3, 0.0, 0.0)),
    )];
    refused(
        "G55 T1 M6 G43 H1\nG0 X0 Y0 Z10\nG81 Z-3 R2 F100\n",
        &m,
        4,
        "whose Z axis is not the part's",
    );
}

#[test]
fn a_dwell_beside_a_move_is_read_as_linuxcnc_runs_it() {
    // LinuxCNC's skeleton.ngc: "G04 P.001 G0 X1.0 Y1.0": the dwell, then the move.
    let mut m = Machine {
        dialect: Some(GcodeDialect::LinuxCnc),
        ..Default::default()
    };
    let g = parse("G21 G0 X0 Y0 Z5\nG04 P.001 G0 X10 Y20\n", &m).unwrap();
    assert_eq!(g.points.len(), 2);
    assert_relative_eq!(g.points[1].position, mm(10.0, 20.0, 5.0), epsilon = 1e-12);
    assert_eq!(g.points[1].line, 3);
    // Without P LinuxCNC refuses the G4; FANUC and Haas read an X beside it as its time.
    for bad in [
        "G4 G0 X10",
        "G4 P-1 G0 X10",
        "G4 P1 G28 X0",
        "G4 P1 G53 G0 Z0",
    ] {
        refused(
            &format!("G21 G0 X0 Y0 Z5\n{bad}\n"),
            &m,
            3,
            "refuse a G4 without its time P of 0 or more, or beside G28, G30 or G53",
        );
    }
    m.dialect = Some(GcodeDialect::Fanuc);
    refused(
        "G21 G0 X0 Y0 Z5\nG04 P1 G0 Y20\n",
        &m,
        3,
        "G4 with an axis word",
    );
    m.dialect = None;
    refused(
        "G21 G0 X0 Y0 Z5\nG04 P1 G0 X10\n",
        &m,
        3,
        "the setup names no controller",
    );
}

#[test]
fn a_g53_retract_under_g91_without_the_setups_frame_leaves_its_axes_unknown() {
    // A Haas shop program faces in G91 and ends with "G53 G49 Z0." / "G53 Y0.": whether Haas
    // reads G53's words under G91 as machine coordinates or increments, the setup gives no
    // machine frame, so Z is unknown after it in both readings; the next point is where the
    // program gives it again.
    let m = haas();
    let g = parse(
        "G21 G90 T1 M6 G43 H1 G0 X0 Y0 Z5\nG91 G1 X10 F100\nG0 Z1.\nG53 G49 Z0.\nG90 G0 X0 Y0\nG43 H1 Z5\n",
        &m,
    )
    .unwrap();
    let lines: Vec<u64> = g.points.iter().map(|p| p.line).collect();
    assert_eq!(lines, [2, 3, 4, 7]);
    assert_relative_eq!(g.points[2].position, mm(10.0, 0.0, 6.0), epsilon = 1e-12);
    assert_relative_eq!(g.points[3].position, mm(0.0, 0.0, 5.0), epsilon = 1e-12);
    assert_eq!(g.unplaced_g53, [5]);
    // A feed from there is refused naming the line; with the setup's machine frame the two
    // readings differ and the block is refused naming the dialect.
    refused(
        "G21 G90 T1 M6 G43 H1 G0 X0 Y0 Z5\nG91 G53 Z0.\nG1 X5 F100\n",
        &m,
        4,
        "Z has no value since line 3",
    );
    let mut framed = haas();
    framed
        .frames
        .offsets
        .push(("G53".into(), Isometry3::translation(0.0, 0.0, 0.3)));
    refused(
        "G21 G90 T1 M6 G43 H1 G0 X0 Y0 Z5\nG91 G53 Z0.\n",
        &framed,
        3,
        "G53 in G91 on the dialect \"haas\"",
    );
}

#[test]
fn a_t_before_the_first_tool_change_names_the_tool_held_since_the_start() {
    // CAMotics' cutout.ngc: "T2" (no M6), then X Y, then a feed down; the setup states where
    // the tip starts. The spindle held T2 from the start: Z is known once T2 is named.
    let mut m = haas();
    m.dialect = Some(GcodeDialect::LinuxCnc);
    m.frames.start = Some(mm(0.0, 0.0, 100.0));
    let g = parse("G21\nT2\nG0 X0 Y16\nG1 Z-13 F50\n", &m).unwrap();
    let path: Vec<(u64, Vector3<f64>)> = g.points.iter().map(|p| (p.line, p.position)).collect();
    assert_eq!(path.len(), 2);
    assert_relative_eq!(path[0].1, mm(0.0, 16.0, 100.0), epsilon = 1e-12);
    assert_relative_eq!(path[1].1, mm(0.0, 16.0, -13.0 - 80.0), epsilon = 1e-12);
    // After a Z move before the T, or in another work offset, the start no longer says.
    refused("G21\nG55\nT2\nG1 Z-13 F50\n", &m, 5, "Z has no value yet");
}

#[test]
fn linuxcncs_polar_coordinates_give_x_and_y() {
    let m = Machine {
        dialect: Some(GcodeDialect::LinuxCnc),
        ..Default::default()
    };
    // G90: the point at @ ^ from the origin, @ alone keeps the angle, ^ alone the distance;
    // G91: @ adds to the distance and ^ to the angle (LinuxCNC's find_ends).
    let text = "G21 G90 G0 X0 Y0 Z5\nG0 @10 ^90\nG91 G1 @5 F100\nG1 ^90\nG90 G0 ^0\nG0 @2\n";
    let g = parse(text, &m).unwrap();
    let want = [
        mm(0.0, 0.0, 5.0),
        mm(0.0, 10.0, 5.0),
        mm(0.0, 15.0, 5.0),
        mm(-15.0, 0.0, 5.0),
        mm(15.0, 0.0, 5.0),
        mm(2.0, 0.0, 5.0),
    ];
    assert_eq!(g.points.len(), want.len());
    for (p, w) in g.points.iter().zip(want) {
        assert_relative_eq!(p.position, w, epsilon = 1e-15);
    }
    // Written back as X Y (in G91 as increments), read back to the same points.
    let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
    let out = g.write(&positions).unwrap();
    assert!(!out.contains('@') && !out.contains('^'), "{out}");
    let again = parse(&out, &m).unwrap();
    for (a, b) in again.points.iter().zip(&g.points) {
        assert_relative_eq!(a.position, b.position, epsilon = 1e-12);
    }
    // A bolt circle by a computed angle, as LinuxCNC's examples write it.
    let g = parse("G21 G0 X0 Y0 Z5\n#1 = 3\nG0 @20 ^[360 / #1]\n", &m).unwrap();
    let t = 120f64.to_radians();
    assert_relative_eq!(
        g.points[1].position,
        mm(20.0 * t.cos(), 20.0 * t.sin(), 5.0),
        epsilon = 1e-15
    );
    for (text, line, construct) in [
        ("G0 X0 Y0 Z5\nG0 X1 @2\n", 3, "X or Y beside them"),
        ("G0 X0 Y0 Z5\nG91 G0 @1\n", 3, "G91 at the XY origin"),
        ("G0 X0 Y0 Z5\nG0 @1\n", 3, "@ alone at the XY origin"),
        (
            "G0 Z5\nG0 ^30\n",
            3,
            "from a place not known: X Y has no value yet",
        ),
        ("G0 X1 Y0 Z5\nG53 G0 @1 ^2\n", 3, "with G53"),
    ] {
        refused(text, &m, line, construct);
    }
    let fanuc = Machine {
        dialect: Some(GcodeDialect::Fanuc),
        ..Default::default()
    };
    refused("G0 @1 ^2 Z5\n", &fanuc, 2, "LinuxCNC's words");
    // LinuxCNC's hole-circle.ngc drills by ^ under G91, L repeats: each hole 60 deg on, R from
    // the starting level, Z from R (interp_cycles.cc, CYCLE_MACRO).
    let g = parse(&corpus("linuxcnc-hole-circle.ngc"), &m).unwrap();
    assert_eq!(g.cycles.len(), 6);
    for (k, c) in (1..=6).zip(&g.cycles) {
        let t = (60.0 * f64::from(k)).to_radians();
        let want = Vector3::new(1.5 * t.cos(), 1.5 * t.sin(), -0.4) * 0.0254;
        assert_relative_eq!(c.bottom, want, epsilon = 1e-12);
    }
}

fn corpus(name: &str) -> String {
    let path = format!(
        "{}/tests/data/programs/gcode/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).unwrap()
}

#[test]
fn linuxcncs_spiral_and_camotics_cutout_read_as_found() {
    let mut m = Machine {
        dialect: Some(GcodeDialect::LinuxCnc),
        ..Default::default()
    };
    // spiral.ngc: from X2 Y0 (inch), 800 repeats of "g91 g1 @-.0025 ^4.5": step k at radius
    // 2 - 0.0025 k and angle 4.5 k deg (the header line before it shifts the lines by one).
    let g = parse(&corpus("linuxcnc-spiral.ngc"), &m).unwrap();
    let steps: Vec<Vector3<f64>> = (g.points.iter())
        .filter(|p| p.line == 10)
        .map(|p| p.position)
        .collect();
    assert_eq!(steps.len(), 800);
    for (k, p) in (1..=800).zip(&steps) {
        let (r, t) = (
            2.0 - 0.0025 * f64::from(k),
            (4.5 * f64::from(k)).to_radians(),
        );
        let want = Vector3::new(r * t.cos(), r * t.sin(), -0.1) * 0.0254;
        assert_relative_eq!(*p, want, epsilon = 1e-12);
    }
    // cutout.ngc: "T2" without M6, then X Y and a feed down; the spindle held T2 (50 mm)
    // from the start the setup states (the tip 100 mm up).
    m.tool_lengths = vec![(Some(2), 0.05)];
    m.frames.start = Some(mm(0.0, 0.0, 100.0));
    let g = parse(&corpus("camotics-cutout.ngc"), &m).unwrap();
    assert_eq!((g.points[0].line, g.points[1].line), (11, 12));
    assert_relative_eq!(
        g.points[0].position,
        mm(0.0, 16.082887, 100.0),
        epsilon = 1e-12
    );
    assert_relative_eq!(
        g.points[1].position,
        mm(0.0, 16.082887, -63.0),
        epsilon = 1e-12
    );
}

#[test]
fn linuxcncs_quadratic_spline_runs_as_its_biarcs() {
    let m = Machine {
        dialect: Some(GcodeDialect::LinuxCnc),
        ..Default::default()
    };
    // The manual's parabola y = x^2 from X-2 Y4 to X2 Y4: LinuxCNC joins its points at 12 equal
    // steps of the parameter (x = -2 + k/3) by biarcs, each split into chords here.
    let text = "G21 G90 G17\nG0 X-2 Y4 Z0\nG5.1 X2 I2 J-8 F100\nG1 X3\n";
    let g = parse(text, &m).unwrap();
    let curve: Vec<Vector3<f64>> = (g.points.iter())
        .filter(|p| p.line == 4)
        .map(|p| p.position * 1e3)
        .collect();
    assert!(curve.len() >= 24, "{}", curve.len());
    for k in 1..=12 {
        let x = -2.0 + f64::from(k) / 3.0;
        let on = |p: &&Vector3<f64>| (p.x - x).abs() < 1e-9 && (p.y - x * x).abs() < 1e-9;
        assert!(curve.iter().any(|p| on(&p)), "x = {x}");
    }
    // Between them the arcs stay within a micrometre of the parabola.
    let off = curve
        .iter()
        .map(|p| (p.y - p.x * p.x).abs())
        .fold(0.0, f64::max);
    assert!(off < 1e-3 && curve.iter().all(|p| p.z == 0.0), "{off}");
    let back = g.write(&g.points.iter().map(|p| p.position).collect::<Vec<_>>());
    let again = gcode::parse_on(&back.unwrap(), 1e-5, &m).unwrap();
    assert_eq!(again.points.len(), g.points.len());
    for (a, b) in again.points.iter().zip(&g.points) {
        assert!((a.position - b.position).norm() < 1e-9);
    }
    refused(
        text,
        &Machine::default(),
        4,
        "G5.1: LinuxCNC's quadratic spline",
    );
    refused(
        "G0 X0 Y0 Z0\nG5.1 X2 Z1 I2 J-8 F9\n",
        &m,
        3,
        "Z beside a spline",
    );
    refused("G0 X0 Y0 Z0\nG5.1 X2 I2 F9\n", &m, 3, "both I and J");
}

#[test]
fn linuxcncs_g92_shifts_every_offset_from_where_the_tool_is() {
    let m = Machine {
        dialect: Some(GcodeDialect::LinuxCnc),
        frames: ProgramFrames {
            offsets: vec![("G55".into(), Isometry3::translation(0.1, 0.0, 0.0))],
            ..Default::default()
        },
        ..Default::default()
    };
    // G92 X0 at X1: X reads 1 less in G54 and in G55 alike, until G92.1.
    let text = "G21\nG0 X1 Y0 Z5\nG92 X0\nG0 X2\nG55 G0 X0\nG92.1\nG0 X0\n";
    let x: Vec<f64> = parse(text, &m)
        .unwrap()
        .points
        .iter()
        .map(|p| p.position.x * 1e3)
        .collect();
    assert_eq!(x.len(), 4);
    for (a, b) in x.iter().zip([1.0, 3.0, 101.0, 100.0]) {
        assert!((a - b).abs() < 1e-9, "{x:?}");
    }
    refused(
        text,
        &Machine::default(),
        4,
        "G92: read with [controller] dialect",
    );
    refused(
        "G0 X1 Y0\nG92 Z0\n",
        &m,
        3,
        "G92: the tool's position is not known",
    );
}

#[test]
fn fanuc_and_haas_coordinate_rotation_turns_the_coordinates_not_the_tool() {
    let fanuc = Machine {
        dialect: Some(GcodeDialect::Fanuc),
        ..Default::default()
    };
    // G68 R90 about the origin: X10 Y0 lands at X0 Y10; G69 back; the tool does not turn.
    let text = "G21 G90\nG0 X10 Y0 Z5\nG68 X0 Y0 R90\nG1 X10 Y0 F100\nG69\nG0 X10 Y0\n";
    let g = parse(text, &fanuc).unwrap();
    let want = [mm(10.0, 0.0, 5.0), mm(0.0, 10.0, 5.0), mm(10.0, 0.0, 5.0)];
    assert_eq!(g.points.len(), 3);
    for (p, w) in g.points.iter().zip(want) {
        assert!((p.position - w).norm() < 1e-15 && p.orientation == g.points[0].orientation);
    }
    // Haas: the centre by A B (the A axis word is no rotary word there).
    let haas = Machine {
        dialect: Some(GcodeDialect::Haas),
        ..Default::default()
    };
    let g = parse("G21\nG0 X0 Y0 Z5\nG68 A10 B0 R180\nG1 X0 Y0 F9\n", &haas).unwrap();
    assert!((g.points[1].position - mm(20.0, 0.0, 5.0)).norm() < 1e-15);
    let rotated = "G0 X0 Y0 Z5\nG68 X0 Y0 R90\n";
    refused(
        rotated,
        &Machine::default(),
        3,
        "G68: a coordinate rotation, read with",
    );
    refused(
        &format!("{rotated}G1 X5 F9\n"),
        &fanuc,
        4,
        "the first motion after the G68/G69 of line 3",
    );
    refused(
        &format!("{rotated}G1 X5 Y0 F9\nG55\n"),
        &fanuc,
        5,
        "a work offset while the coordinate rotation G68 of line 3",
    );
    refused("G0 X0 Y0 Z5\nG91\nG68 R90\n", &fanuc, 4, "under G91");
}
