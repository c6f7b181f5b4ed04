//! Subprograms, parameters and control flow read as the controller runs them: LinuxCNC's own
//! interpreter tests from the corpus (their comments state where the machine ends), a FANUC
//! program with `M98 .. L3` and a `G65` macro, each point naming the program's line and the
//! expanded program written back reading back to the same path.

use crate::gcode_corpus::machine;
use approx::assert_relative_eq;
use nalgebra::Vector3;
use stiffid::internal::machining::gcode::{self, GcodeDialect, Machine};

fn corpus(name: &str) -> String {
    let path = format!(
        "{}/tests/data/programs/gcode/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).unwrap()
}

fn on(dialect: GcodeDialect) -> Machine {
    let mut m = machine("workpiece-linuxcnc.toml", "aluminium.toml");
    m.dialect = Some(dialect);
    m
}

fn mm(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z) * 1e-3
}

/// The path read, and read again from the program written back at its own positions.
fn read_and_written(text: &str, m: &Machine) -> gcode::GCode {
    let g = gcode::parse_on(text, 1e-5, m).unwrap();
    assert!(g.expanded);
    let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
    let again = gcode::parse_on(&g.write(&positions).unwrap(), 1e-5, m).unwrap();
    assert!(!again.expanded);
    assert_eq!(again.points.len(), g.points.len());
    for (a, b) in again.points.iter().zip(&g.points) {
        assert!((a.position - b.position).norm() < 1e-9);
    }
    g
}

#[test]
fn linuxcnc_interpreter_tests_end_where_their_comments_say() {
    let m = on(GcodeDialect::LinuxCnc);
    // "on exit X=2.4 Y=3.5 Z=4.6": two calls of o100, each calling o[150+50] with [2+#1]..
    let g = read_and_written(&corpus("linuxcnc-interp-test-sub.ngc"), &m);
    let lines: Vec<u64> = g.points.iter().map(|p| p.line).collect();
    assert_eq!(lines, vec![8, 8]);
    assert_relative_eq!(g.points[0].position, mm(2.1, 3.2, 4.3), epsilon = 1e-15);
    assert_relative_eq!(g.points[1].position, mm(2.4, 3.5, 4.6), epsilon = 1e-15);
    // "on exit X = 5.323 Y = 3.0 Z = 3.0": do-while, while, break and continue.
    let g = read_and_written(&corpus("linuxcnc-interp-test-loop.ngc"), &m);
    let last = g.points.last().unwrap();
    assert_eq!(last.line, 36);
    assert_relative_eq!(last.position, mm(5.323, 3.0, 3.0), epsilon = 1e-15);
    // 1 + 5 + 3 + 2 (break at #102 = 2) + 1 + 3 (continue skips z5) + 1 moves.
    assert_eq!(g.points.len(), 16);
    // "exits with X=.4 Z=4" (Y from the setup's start: the file never gives it).
    let mut m = m;
    m.frames.start = Some(mm(0.0, 7.0, 0.0));
    let g = read_and_written(&corpus("linuxcnc-interp-test-if.ngc"), &m);
    assert_eq!(g.points.len(), 1);
    assert_eq!(g.points[0].line, 38);
    assert_relative_eq!(g.points[0].position, mm(0.4, 7.0, 4.0), epsilon = 1e-15);
}

const FANUC: &str = "%
O1000 (MAIN)
G21 G17 G90 G40 G80
T1 M6
G0 X0 Y0 Z5
#100 = 0
M98 P2000 L3
G65 P9100 A4 R10 Z-1
G0 Z50
M30
O2000 (ONE GROOVE)
#100 = #100 + 10
G1 Z-1 F100
G1 X#100
G0 Z5
M99
O9100 (A HOLES ON A CIRCLE OF RADIUS R AT DEPTH Z)
#10 = 0
WHILE [#10 LT #1] DO 1
G0 X[#18 * COS[#10 * 360 / #1]] Y[#18 * SIN[#10 * 360 / #1]]
G1 Z#26
G0 Z5
#10 = #10 + 1
END 1
M99
%
";

#[test]
fn a_fanuc_program_runs_its_subprogram_three_times_and_its_macro_with_arguments() {
    let m = on(GcodeDialect::Fanuc);
    let g = read_and_written(FANUC, &m);
    // The three grooves: each plunges, feeds to X = 10, 20, 30 (the common #100), retracts.
    let grooves: Vec<(u64, Vector3<f64>)> = g.points[1..10]
        .iter()
        .map(|p| (p.line, p.position))
        .collect();
    let mut expected = Vec::new();
    let mut x = 0.0;
    for k in 1..=3 {
        expected.push((13, mm(x, 0.0, -1.0)));
        x = 10.0 * k as f64;
        expected.push((14, mm(x, 0.0, -1.0)));
        expected.push((15, mm(x, 0.0, 5.0)));
    }
    assert_eq!(grooves.len(), expected.len());
    for ((line, p), (l, e)) in grooves.iter().zip(&expected) {
        assert_eq!(line, l);
        assert_relative_eq!(p, e, epsilon = 1e-15);
    }
    // The macro: 4 holes on a circle of radius 10 (A = #1, R = #18, Z = #26).
    let holes: Vec<&Vector3<f64>> = g
        .points
        .iter()
        .filter(|p| p.line == 21)
        .map(|p| &p.position)
        .collect();
    assert_eq!(holes.len(), 4);
    for (k, p) in holes.iter().enumerate() {
        let a = (90.0 * k as f64).to_radians();
        assert_relative_eq!(
            **p,
            mm(10.0 * a.cos(), 10.0 * a.sin(), -1.0),
            epsilon = 1e-15
        );
    }
    assert_eq!(g.points.last().unwrap().line, 9);
}
