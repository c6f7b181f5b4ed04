//! G-code where controllers differ, read as the setup's `[controller] dialect` says or refused
//! naming the line and the option: a tool length offset made without a move and `G91` after it
//! (Haas and FANUC take the offset up in the next `Z` move, LinuxCNC re-expresses where the tool
//! is), `G28` with an offset in force, `G53` under `G91`; and what every controller reads alike
//! but a program may still mean otherwise (a tool of known length without `G43`).

use approx::assert_relative_eq;
use nalgebra::Vector3;
use stiffid::internal::machining::gcode::{self, GcodeDialect, Machine, ProgramFrames};
use stiffid::Error;

const DOWN: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n";

fn mm(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z) * 1e-3
}

/// T1 of 76.2 mm (3 inch), as the Haas case's, on `dialect`.
fn haas_tool(dialect: Option<GcodeDialect>) -> Machine {
    Machine {
        frames: ProgramFrames {
            g28: Some(mm(0.0, 0.0, 300.0)),
            ..Default::default()
        },
        tool_lengths: vec![(Some(1), 0.0762)],
        dialect,
        ..Default::default()
    }
}

fn read(text: &str, m: &Machine) -> gcode::GCode {
    gcode::parse_on(&format!("{DOWN}{text}"), 1e-5, m).unwrap_or_else(|e| panic!("{e}"))
}

fn refused(text: &str, m: &Machine, line: u64, words: &[&str]) {
    match gcode::parse_on(&format!("{DOWN}{text}"), 1e-5, m) {
        Err(Error::Program { line: l, message }) => {
            assert_eq!(l, line, "{message}");
            for w in words {
                assert!(message.contains(w), "{w}: {message}");
            }
        }
        other => panic!("{words:?}: {other:?}"),
    }
}

fn assert_path(g: &gcode::GCode, want: &[(u64, Vector3<f64>)]) {
    assert_eq!(g.points.len(), want.len(), "{:?}", g.points);
    for (p, (line, q)) in g.points.iter().zip(want) {
        assert_eq!(p.line, *line);
        assert_relative_eq!(p.position, *q, epsilon = 1e-12);
    }
}

/// `G43 H1` without a move, then cuts in `G91` (inch): the gauge line at Z7 under `G49` puts
/// the tip at 7 - 3 = 4 inch.
const G43_THEN_G91: &str =
    "G20 G90 G17\nT1 M6\nG0 X0 Y0 Z7.\nG43 H1\nG91 G1 Z-1. F10.\nX1.\nY1.\nG90 G0 Z1.\n";

#[test]
fn a_g43_without_a_move_then_g91_is_read_as_each_dialect_runs_it() {
    let inch = |x: f64, y: f64, z: f64| mm(x, y, z) * 25.4;
    // Haas and FANUC: the first Z move takes the offset up; the increment counts from the
    // programmed Z7, the tip 6 inch up after it (3 inch of offset less 1 inch of increment
    // from where the tip was: 4 inch).
    let haas = [
        (4, inch(0.0, 0.0, 4.0)),
        (6, inch(0.0, 0.0, 6.0)),
        (7, inch(1.0, 0.0, 6.0)),
        (8, inch(1.0, 1.0, 6.0)),
        (9, inch(1.0, 1.0, 1.0)),
    ];
    for d in [GcodeDialect::Haas, GcodeDialect::Fanuc] {
        let m = haas_tool(Some(d));
        let g = read(G43_THEN_G91, &m);
        assert_path(&g, &haas);
        // Written back, the increment is the controller's: the tip's 2 inch less the 3 inch of
        // the offset it moves by; read back on the same dialect, the same path.
        let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
        let written = g.write(&positions).unwrap();
        assert!(
            written.contains("G91 G1 X0.000000 Y0.000000 Z-1.000000 F10."),
            "{written}"
        );
        let again = gcode::parse_on(&written, 1e-5, &m).unwrap();
        assert_path(&again, &haas);
        // Moved 0.1 mm, the points read back moved.
        let moved: Vec<_> = positions.iter().map(|p| p + mm(0.0, 0.0, 0.1)).collect();
        let again = gcode::parse_on(&g.write(&moved).unwrap(), 1e-5, &m).unwrap();
        for (a, b) in again.points.iter().zip(&moved) {
            assert_relative_eq!(a.position, *b, epsilon = 1e-9);
        }
    }
    // LinuxCNC: G43 moves nothing and re-expresses where the tool is; the increment counts
    // from the tip, 3 inch lower than on a Haas (76.2 mm).
    let linuxcnc = [
        (4, inch(0.0, 0.0, 4.0)),
        (6, inch(0.0, 0.0, 3.0)),
        (7, inch(1.0, 0.0, 3.0)),
        (8, inch(1.0, 1.0, 3.0)),
        (9, inch(1.0, 1.0, 1.0)),
    ];
    assert_path(
        &read(G43_THEN_G91, &haas_tool(Some(GcodeDialect::LinuxCnc))),
        &linuxcnc,
    );
    // Unstated: refused naming the line, the G43's line, the distance and the option.
    refused(
        G43_THEN_G91,
        &haas_tool(None),
        6,
        &["line 5", "76.2000 mm apart", "[controller] dialect"],
    );
    // A Z given absolutely after the G43 reads alike everywhere: no dialect needed, and moves
    // without Z in between stay where the tool is.
    let g = read(
        "G20 G90\nT1 M6\nG0 X0 Y0 Z7.\nG43 H1\nX1.\nZ1.\nG91 G1 Z-1. F10.\n",
        &haas_tool(None),
    );
    assert_path(
        &g,
        &[
            (4, inch(0.0, 0.0, 4.0)),
            (6, inch(1.0, 0.0, 4.0)),
            (7, inch(1.0, 0.0, 1.0)),
            (8, inch(1.0, 0.0, 0.0)),
        ],
    );
    // grbl has no tool table.
    refused(
        "T1 M6\nG43 H1 Z5\n",
        &haas_tool(Some(GcodeDialect::Grbl)),
        3,
        &["grbl has no tool table"],
    );
}

#[test]
fn g28_with_a_tool_length_offset_and_g53_in_g91_are_read_as_each_dialect_says() {
    // Haas cancels the offset at G28: Z10 after it is the gauge line's, the tip 76.2 mm lower.
    let text = "G21 G90\nT1 M6\nG43 H1 G0 X0 Y0 Z10\nG28 G91 Z0\nG90 G0 Z10\n";
    let g = read(text, &haas_tool(Some(GcodeDialect::Haas)));
    assert_path(
        &g,
        &[
            (4, mm(0.0, 0.0, 10.0)),
            (5, mm(0.0, 0.0, 300.0)),
            (6, mm(0.0, 0.0, 10.0 - 76.2)),
        ],
    );
    let g = read(text, &haas_tool(Some(GcodeDialect::LinuxCnc)));
    assert_eq!(g.points[2].position, mm(0.0, 0.0, 10.0));
    for d in [None, Some(GcodeDialect::Fanuc)] {
        refused(
            text,
            &haas_tool(d),
            6,
            &["G28 of line 5", "state G43 H.. or G49 again"],
        );
    }
    // Stated again after the G28: read alike everywhere.
    let again = "G21 G90\nT1 M6\nG43 H1 G0 X0 Y0 Z10\nG28 G91 Z0\nG90 G43 H1 G0 Z10\n";
    assert_eq!(
        read(again, &haas_tool(None)).points[2].position,
        mm(0.0, 0.0, 10.0)
    );
    // G53 in G91: LinuxCNC and grbl read absolute machine coordinates.
    let mut m = haas_tool(Some(GcodeDialect::LinuxCnc));
    m.frames.offsets = vec![(
        "G53".into(),
        nalgebra::Isometry3::translation(-0.5, -0.4, 0.2),
    )];
    let g = read("T1 M6\nG43 H1 G0 X0 Y0 Z10\nG91\nG53 G0 Z0\n", &m);
    assert_relative_eq!(
        g.points[1].position,
        mm(0.0, 0.0, 200.0 - 76.2),
        epsilon = 1e-12
    );
    m.dialect = Some(GcodeDialect::Haas);
    refused(
        "T1 M6\nG43 H1 G0 X0 Y0 Z10\nG91\nG53 G0 Z0\n",
        &m,
        5,
        &["G53 in G91", "\"haas\""],
    );
    m.dialect = None;
    refused(
        "T1 M6\nG43 H1 G0 X0 Y0 Z10\nG91\nG53 G0 Z0\n",
        &m,
        5,
        &["[controller] dialect"],
    );
}

#[test]
fn a_tool_of_known_length_without_g43_is_named_and_an_arc_word_off_its_plane_refused() {
    // One length for every tool (an operation without tool_number), no T, no G43: the tip is
    // read 50 mm below the programmed point, and the first such motion is named.
    let m = Machine {
        tool_lengths: vec![(None, 0.05)],
        ..Default::default()
    };
    let g = read("G21 G90\nG0 X0 Y0 Z10\nG1 Z-1 F100\n", &m);
    assert_eq!(g.points[0].position, mm(0.0, 0.0, -40.0));
    assert_eq!(g.no_length_offset, Some((3, 0.05)));
    // Under G43 nothing is named.
    let g = read("G21 G90\nT1 M6\nG43 H1 G0 X0 Y0 Z10\n", &m);
    assert_eq!(g.no_length_offset, None);
    // K in G17: LinuxCNC refuses the block (it was read in XY, the K ignored).
    let m = Machine::default();
    refused(
        "G21 G90 G17\nG0 X0 Y0 Z0\nG3 X10 Z-10 I5 K0 F100\n",
        &m,
        4,
        &["K: a centre word off the arc's plane G17"],
    );
    refused(
        "G18\nG0 X0 Y0 Z0\nG2 X10 I5 J1 F100\n",
        &m,
        4,
        &["J: a centre word off"],
    );
}

#[test]
fn hostile_sequences_of_offsets_homes_and_g53_never_panic_and_name_a_line() {
    // Every pair of these blocks, then a G91 Z move, after a known start, on every dialect and
    // none: read with finite points, or refused naming a line of the program.
    let blocks = [
        "G43 H1",
        "G44 H1",
        "G49",
        "G43 H2",
        "G91 G1 Z-1 F100",
        "G90 G0 Z5",
        "G91 X1",
        "G28 G91 Z0",
        "G28",
        "G28 X0",
        "G53 G0 Z0",
        "G91 G53 G1 X1 F10",
        "G81 X1 Y1 Z-1 R2 F50",
        "G80",
        "G43 H1 G91 Z-1e9",
        "G43 H99999999",
        "G3 X1 Y1 I1 K1 F10",
        "G18 G2 X1 Z1 I1 J0 F10",
        "G41 D1",
        "G42",
        "G40",
        "G1 X5 Y5 F10",
        "G1 X5.001 Y5 F10",
        "G54",
    ];
    let mut m = haas_tool(None);
    m.tool_lengths.push((Some(2), 0.3));
    m.tool_radii = vec![(Some(1), 0.003)];
    m.frames.offsets = vec![(
        "G53".into(),
        nalgebra::Isometry3::translation(0.0, 0.0, 0.5),
    )];
    let dialects = [
        None,
        Some(GcodeDialect::LinuxCnc),
        Some(GcodeDialect::Fanuc),
        Some(GcodeDialect::Haas),
        Some(GcodeDialect::Grbl),
    ];
    let (mut read, mut refused) = (0, 0);
    for d in dialects {
        m.dialect = d;
        for a in blocks {
            for b in blocks {
                let c = "G91 G1 Z-1 F10";
                let text = format!("{DOWN}G21 G90\nT1 M6\nG0 X0 Y0 Z10\n{a}\n{b}\n{c}\n");
                match gcode::parse_on(&text, 1e-4, &m) {
                    Ok(g) => {
                        assert!(g
                            .points
                            .iter()
                            .all(|p| p.position.iter().all(|v| v.is_finite())));
                        read += 1;
                    }
                    Err(Error::Program { line, .. }) => {
                        assert!((1..=7).contains(&line), "{text}");
                        refused += 1;
                    }
                    Err(e) => panic!("{text}: {e}"),
                }
            }
        }
    }
    assert_eq!(read + refused, 5 * blocks.len().pow(2));
    assert!(read > 0 && refused > 0);
}

/// A 10 mm square cut clockwise from (0, 0), entered from (10, -10), left by G40 back there.
fn square(code: &str) -> String {
    format!("G21 G90 G17\nT1 M6\nG0 X10 Y-10 Z5\nG1 Z-1 F100\n{code} D1\nX0 Y0\nY10\nX10\nY0\nX0\nG40\nX10 Y-10\n")
}

/// The distance from `p` (mm) to the boundary of the square [0, 10]^2.
fn to_square(p: &Vector3<f64>) -> f64 {
    let (x, y) = (p.x * 1e3, p.y * 1e3);
    let dx = (-x).max(x - 10.0).max(0.0);
    let dy = (-y).max(y - 10.0).max(0.0);
    if dx > 0.0 || dy > 0.0 {
        dx.hypot(dy)
    } else {
        x.min(10.0 - x).min(y).min(10.0 - y)
    }
}

#[test]
fn cutter_radius_compensation_offsets_a_square_by_the_tool_radius_as_linuxcnc() {
    let m = radius;
    // G41 (left) on a clockwise square: outside, every corner turned on an arc of 5 mm around
    // the square's corner: every point of the sides and corners is 5 mm from the square.
    let g = read(&square("G41"), &m(5.0, Some(GcodeDialect::LinuxCnc)));
    let lines: Vec<u64> = g.points.iter().map(|p| p.line).collect();
    let side = |l: u64| g.points.iter().filter(|p| p.line == l).collect::<Vec<_>>();
    for l in 8..=11 {
        for p in side(l) {
            assert_relative_eq!(to_square(&p.position), 5.0, epsilon = 1e-9);
        }
    }
    let ends: Vec<Vector3<f64>> = (8..=11).map(|l| side(l).last().unwrap().position).collect();
    let want = [
        mm(-5.0, 10.0, -1.0),
        mm(10.0, 15.0, -1.0),
        mm(15.0, 0.0, -1.0),
        mm(0.0, -5.0, -1.0),
    ];
    for (a, b) in ends.iter().zip(want) {
        assert_relative_eq!(*a, b, epsilon = 1e-12);
    }
    // The corner of each side starts where the last one ended, on the corner's circle: the
    // side's first arc point turns around the programmed corner.
    assert!(
        side(9).len() > 1 && side(9)[0].position.y * 1e3 > 10.0,
        "{lines:?}"
    );
    // The entry ends tangent to the circle of 5 mm around (0, 0), seen from (10, -10).
    let entry = side(7)[0].position * 1e3;
    assert_relative_eq!(entry.x.hypot(entry.y), 5.0, epsilon = 1e-9);
    let from = Vector3::new(10.0, -10.0, -1.0);
    assert_relative_eq!(
        (entry - from).dot(&entry.xy().push(0.0)),
        0.0,
        epsilon = 1e-9
    );
    // G40: the next move goes to its programmed end.
    assert_relative_eq!(
        g.points.last().unwrap().position,
        mm(10.0, -10.0, -1.0),
        epsilon = 1e-12
    );
    // G42 (right) of 2 mm: inside, each side ends where the offset sides meet.
    let g = read(&square("G42"), &m(2.0, Some(GcodeDialect::LinuxCnc)));
    let ends: Vec<Vector3<f64>> = (8..=11)
        .map(|l| g.points.iter().rfind(|p| p.line == l).unwrap().position)
        .collect();
    let want = [
        mm(2.0, 8.0, -1.0),
        mm(8.0, 8.0, -1.0),
        mm(8.0, 2.0, -1.0),
        mm(0.0, 2.0, -1.0),
    ];
    for (a, b) in ends.iter().zip(want) {
        assert_relative_eq!(*a, b, epsilon = 1e-12);
    }
    // Written back: the tool centre's path, G41/G42 and D dropped; read back, the same.
    let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
    let written = g.write(&positions).unwrap();
    assert!(
        !written.contains("G42") && !written.contains("D1"),
        "{written}"
    );
    let again = gcode::parse_on(&written, 1e-5, &m(2.0, Some(GcodeDialect::LinuxCnc))).unwrap();
    assert_eq!(again.points.len(), g.points.len());
    for (a, b) in again.points.iter().zip(&g.points) {
        assert_relative_eq!(a.position, b.position, epsilon = 1e-9);
    }
}

/// A circle of radius 20 about the origin cut counter-clockwise from (20, 0) under `code`,
/// entered from (50, 0), left by `G40` back there.
fn circle(code: &str) -> String {
    format!("G21 G90 G17\nT1 M6\nG0 X50 Y0 Z5\nG1 Z-1 F100\n{code} D1\nG1 X20 Y0\nG3 X20 Y0 I-20 J0\nG40\nG1 X50 Y0\n")
}

#[test]
fn cutter_radius_compensation_offsets_arcs_concentrically_with_the_wear() {
    // The tool's radius 5 mm (less its wear of 0.1 mm): inside the circle under G41 (15 and
    // 15.1 mm), outside under G42 (25); the corner from the entry an arc of the radius about
    // (20, 0).
    let mut worn = radius(5.0, Some(GcodeDialect::LinuxCnc));
    worn.radius_wear = vec![(1, -0.1e-3)];
    for (code, m, r, want) in [
        ("G41", radius(5.0, Some(GcodeDialect::LinuxCnc)), 5.0, 15.0),
        ("G42", radius(5.0, Some(GcodeDialect::LinuxCnc)), 5.0, 25.0),
        ("G41", worn, 4.9, 15.1),
    ] {
        let g = read(&circle(code), &m);
        let arc: Vec<_> = g
            .points
            .iter()
            .filter(|p| p.line == 8)
            .map(|p| p.position * 1e3)
            .collect();
        let on_circle = arc
            .iter()
            .filter(|p| (p.x.hypot(p.y) - want).abs() < 1e-9)
            .count();
        let on_corner = arc
            .iter()
            .filter(|p| ((p.x - 20.0).hypot(p.y) - r).abs() < 1e-9)
            .count();
        assert!(on_circle > 50, "{code}: {on_circle}");
        // G41: an outside corner from the entry, its last point the circle's first (and last,
        // (15, 0), 5 from (20, 0) too); G42: an inside one, the circle from where the entry meets
        // it, its last point (25, 0) 5 from (20, 0) too.
        let (both, corner_only) = if code == "G42" { (1, 0) } else { (2, 1) };
        assert_eq!(on_circle + on_corner, arc.len() + both, "{code}");
        assert!(on_corner - both >= corner_only, "{code}: {on_corner}");
        assert_relative_eq!(
            arc[arc.len() - 1],
            Vector3::new(want, 0.0, -1.0),
            epsilon = 1e-12
        );
    }
}

#[test]
fn cutter_radius_compensation_meets_an_arc_at_an_inside_corner_as_linuxcnc() {
    // G42 of 2 mm along Y = 0 to (0, 0), then counter-clockwise about (10, 0) to (10, -10): the
    // tool on the arc's outside (radius 12), the corner inside: the side ends where Y = -2 meets
    // that circle, X = 10 - sqrt(12^2 - 2^2).
    let text = "G21 G90 G17\nT1 M6\nG0 X-30 Y20 Z5\nG1 Z-1 F100\nG42 D1\nG1 X-30 Y0\nG1 X0 Y0\nG3 X10 Y-10 I10 J0\nG40\nG1 X30 Y-30\n";
    let g = read(text, &radius(2.0, Some(GcodeDialect::LinuxCnc)));
    // (The program's lines 7 and 8 are 8 and 9 after the header `read` puts first.)
    let side = g.points.iter().rfind(|p| p.line == 8).unwrap().position * 1e3;
    assert_relative_eq!(
        side,
        Vector3::new(10.0 - 140f64.sqrt(), -2.0, -1.0),
        epsilon = 1e-12
    );
    let arc: Vec<_> = g
        .points
        .iter()
        .filter(|p| p.line == 9)
        .map(|p| p.position * 1e3)
        .collect();
    assert!(arc.len() > 10);
    for p in &arc {
        assert_relative_eq!((p.x - 10.0).hypot(p.y), 12.0, epsilon = 1e-9);
    }
    assert_relative_eq!(
        arc[arc.len() - 1],
        Vector3::new(10.0, -12.0, -1.0),
        epsilon = 1e-12
    );
    // From the corner on: the arc's first point is past it, counter-clockwise.
    assert!(arc[0].y < side.y && arc[0].x > side.x);
    // An arc as the entry (LinuxCNC's convert_arc_comp1): from (30, 0) to its end (0, 30) moved
    // 5 mm along its radius (G41 with G3: inside, to (0, 25); G42: to (0, 35)), on the circle
    // through both about a centre on that radius: (0, -5.5) and (0, 325/70). In G18 the same
    // in Z X (LinuxCNC's comp_get_current), Y the normal.
    let g17 =
        "G17\nT1 M6\nG0 X30 Y0 Z5\nG1 Z-1 F100\nGCOMP D1\nG3 X0 Y30 I-30 J0\nG40\nG1 X0 Y40\n";
    let g18 =
        "G18\nT1 M6\nG0 X0 Y5 Z30\nG1 Y-1 F100\nGCOMP D1\nG3 Z0 X30 K-30 I0\nG40\nG1 Z0 X40\n";
    for (code, end, centre) in [("41", 25.0, -5.5), ("42", 35.0, 325.0 / 70.0)] {
        for (plane, uvn) in [(g17, [0, 1, 2]), (g18, [2, 0, 1])] {
            let text = format!("G21 G90 {}", plane.replace("COMP", code));
            let g = read(&text, &radius(5.0, Some(GcodeDialect::LinuxCnc)));
            let arc: Vec<_> = (g.points.iter().filter(|p| p.line == 7))
                .map(|p| p.position * 1e3)
                .map(|p| [p[uvn[0]], p[uvn[1]], p[uvn[2]]])
                .collect();
            assert!(arc.len() > 10, "G{code}: {text}");
            for p in &arc {
                assert_relative_eq!(p[0].hypot(p[1] - centre), end - centre, epsilon = 1e-9);
            }
            assert_eq!(
                arc[arc.len() - 1].map(|v| (v * 1e9).round() / 1e9),
                [0.0, end, -1.0]
            );
        }
    }
}

/// A machine whose tool 1 has radius `r` mm, on `dialect`.
fn radius(r: f64, dialect: Option<GcodeDialect>) -> Machine {
    Machine {
        tool_radii: vec![(Some(1), r * 1e-3)],
        dialect,
        ..Default::default()
    }
}

#[test]
fn cutter_radius_compensation_outside_what_is_read_is_refused_naming_the_line() {
    let m = radius;
    // Refused naming the line: without the dialect, on Haas, an arc, a tool that does not fit,
    // an entry shorter than the radius (straight or an arc).
    let t = square("G41");
    refused(
        &t,
        &m(5.0, None),
        6,
        &["[controller] dialect = \"linuxcnc\""],
    );
    refused(&t, &m(5.0, Some(GcodeDialect::Haas)), 6, &["\"haas\""]);
    refused(
        &t.replace("Y10\n", "G3 Y10 I0 J5\n"),
        &m(5.0, Some(GcodeDialect::LinuxCnc)),
        8,
        &["is not less than the arc's"],
    );
    refused(
        &square("G42"),
        &m(6.0, Some(GcodeDialect::LinuxCnc)),
        10,
        &["does not fit"],
    );
    refused(
        &t,
        &m(20.0, Some(GcodeDialect::LinuxCnc)),
        7,
        &["not longer than the tool radius"],
    );
    refused(
        "G0 X0 Y0 Z0\nG41 D1\nG2 X3 Y0 I1.5 J0 F100\n",
        &m(5.0, Some(GcodeDialect::LinuxCnc)),
        4,
        &["arc entering cutter radius compensation"],
    );
    refused(
        "G19\nG41 D1\n",
        &m(5.0, Some(GcodeDialect::LinuxCnc)),
        3,
        &["in G19"],
    );
    refused(
        "G41 D1\nG41 D1\n",
        &m(5.0, Some(GcodeDialect::LinuxCnc)),
        3,
        &["on already"],
    );
    refused(
        "G41 D7\n",
        &m(5.0, Some(GcodeDialect::LinuxCnc)),
        2,
        &["radius of tool 7"],
    );
}
