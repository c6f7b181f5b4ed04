//! The real G-code programs of `tests/data/programs/gcode` (SOURCES.md: Fusion 360's personal,
//! generic and MPCNC posts, LinuxCNC's examples, pcb2gcode's outputs), each read as found on a
//! setup a user would write beside it, or refused naming its line and construct. The path of
//! each one read is checked point by point against an independent reading by gcodeparser in
//! `crates/stiffid-py/tests/test_gcode_corpus.py`; here, its first point against the file as
//! read by eye, and its compensation written back reads back to the same path.

use approx::assert_relative_eq;
use nalgebra::Vector3;
use stiffid::internal::machining::gcode::{self, Machine};
use stiffid::internal::machining::process::file as process_file;
use stiffid::Error;

const SETUP: &str = include_str!("../../../../examples/milling/fanuc-milling.toml");

fn corpus(name: &str) -> String {
    let path = format!(
        "{}/tests/data/programs/gcode/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).unwrap()
}

/// The milling setup with its `[workpiece]` replaced by the corpus's `workpiece`, and the
/// process file `process` (a corpus file, or the milling example's aluminium.toml).
pub(crate) fn machine(workpiece: &str, process: &str) -> Machine {
    let start = SETUP.find("[workpiece]").unwrap();
    let text = format!("{}{}", &SETUP[..start], corpus(workpiece));
    let setup = stiffid::internal::setup::parse(&text, "setup.toml", |n, _| {
        stiffid::internal::robot::presets::get(n)
    })
    .unwrap();
    let process_text = match process {
        "aluminium.toml" => include_str!("../../../../examples/milling/aluminium.toml").to_string(),
        other => corpus(other),
    };
    let process = process_file::parse(&process_text, process).unwrap();
    Machine::of(&setup, Some(&process))
}

/// Each compensated file: its setup's workpiece, its process, the line of its first point and
/// that point as the file gives it (mm, or inch for a G20 file), read by eye.
/// A compensated file: name, workpiece, process, first point's line, position, unit (mm).
pub(crate) type Read = (&'static str, &'static str, &'static str, u64, [f64; 3], f64);

pub(crate) const READ: [Read; 10] = [
    (
        "fusion360-personal-contour.nc",
        "workpiece-fusion360.toml",
        "aluminium.toml",
        16,
        [-0.7, -0.7, 10.0],
        1.0,
    ),
    (
        "fusion360-personal-arcs.nc",
        "workpiece-fusion360.toml",
        "aluminium.toml",
        16,
        [0.0, -1.587, 10.0],
        1.0,
    ),
    (
        "fusion360-generic-router.nc",
        "workpiece-fusion360.toml",
        "process-fusion360.toml",
        19,
        [1013.311, -462.124, 15.24],
        25.4,
    ),
    (
        "fusion360-mpcnc-mill.gcode",
        "workpiece-fusion360.toml",
        "aluminium.toml",
        60,
        [3.412, 49.305, 3.0],
        1.0,
    ),
    (
        "fusion360-mpcnc-drill.gcode",
        "workpiece-fusion360.toml",
        "aluminium.toml",
        54,
        [77.688, 49.688, 3.0],
        1.0,
    ),
    (
        "linuxcnc-two-tools.ngc",
        "workpiece-linuxcnc.toml",
        "process-two-tools.toml",
        17,
        [-25.0, 100.0, 10.0],
        1.0,
    ),
    (
        "pcb2gcode-drill.ngc",
        "workpiece-linuxcnc.toml",
        "aluminium.toml",
        24,
        [0.9, -0.45, 0.08],
        25.4,
    ),
    // LinuxCNC's interpreter tests (subs, loops): expanded as LinuxCNC runs them.
    (
        "linuxcnc-interp-test-sub.ngc",
        "workpiece-linuxcnc.toml",
        "aluminium.toml",
        8,
        [2.1, 3.2, 4.3],
        1.0,
    ),
    (
        "linuxcnc-interp-test-loop.ngc",
        "workpiece-linuxcnc.toml",
        "aluminium.toml",
        3,
        [0.0, 0.0, 0.0],
        1.0,
    ),
    (
        "pcb2gcode-outline.ngc",
        "workpiece-linuxcnc.toml",
        "aluminium.toml",
        25,
        [-0.07953, -1.1, 0.08],
        25.4,
    ),
];

/// Each refused file: the line and the construct its error names.
const REFUSED: [(&str, u64, &str); 2] = [
    // Its ^60 is LinuxCNC's, and the setup names no dialect (read on LinuxCNC: gcode_shop.rs).
    ("linuxcnc-hole-circle.ngc", 10, "LinuxCNC's words"),
    // Its sub is never called: the program runs no motion.
    ("linuxcnc-g20sub.ngc", 1, "no motion block"),
];

#[test]
fn every_corpus_program_is_read_from_its_first_known_point_and_written_back_as_read() {
    for (name, workpiece, process, line, first, unit) in READ {
        let m = machine(workpiece, process);
        let g = gcode::parse_on(&corpus(name), 1e-5, &m).unwrap_or_else(|e| panic!("{name}: {e}"));
        let p = &g.points[0];
        assert_eq!(p.line, line, "{name}");
        assert_relative_eq!(
            p.position,
            Vector3::from(first) * unit * 1e-3,
            epsilon = 1e-12
        );
        assert_relative_eq!(p.orientation * Vector3::z(), -Vector3::z(), epsilon = 1e-12);
        // Written back at the positions read, the program reads back to them (to the 6
        // decimals of its units the written words carry).
        let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
        let again = gcode::parse_on(&g.write(&positions).unwrap(), 1e-5, &m).unwrap();
        assert_eq!(again.points.len(), g.points.len(), "{name}");
        for (a, b) in again.points.iter().zip(&g.points) {
            let tolerance = unit * 1e-9 * 3f64.sqrt();
            assert!(
                (a.position - b.position).norm() <= tolerance,
                "{name}: line {}",
                b.line
            );
        }
    }
}

#[test]
fn corpus_programs_outside_the_subset_are_refused_naming_line_and_construct() {
    let m = machine("workpiece-linuxcnc.toml", "aluminium.toml");
    for (name, line, construct) in REFUSED {
        match gcode::parse_on(&corpus(name), 1e-5, &m) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{name}: {message}");
                assert!(message.contains(construct), "{name}: {message}");
            }
            other => panic!("{name}: {other:?}"),
        }
    }
}

/// The Fusion 360 files as found on a setup that does not state what they need: each refused
/// naming the line and what the setup lacks, never read with an axis taken as 0.
#[test]
fn fusion_files_need_what_their_controller_knows() {
    let text = corpus("fusion360-personal-contour.nc");
    match gcode::parse(&text, 1e-5) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 15, "{message}");
            assert!(message.contains("no tool orientation"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    let no_home = machine("workpiece-linuxcnc.toml", "process-fusion360.toml");
    let router = corpus("fusion360-generic-router.nc");
    match gcode::parse_on(&router, 1e-5, &no_home) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 9, "{message}");
            assert!(
                message.contains("G28: the setup does not state the G28 position"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    let no_lengths = machine("workpiece-fusion360.toml", "aluminium.toml");
    match gcode::parse_on(&router, 1e-5, &no_lengths) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 19, "{message}");
            assert!(
                message.contains("G43: a tool length offset needs the tools' lengths"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// LinuxCNC's comp-g1.ngc on the LinuxCNC dialect with its tool 4 (1 inch): its part outline
/// cut again under `G41`, every point of the compensated arcs 0.5 inch outside the programmed
/// ones (concentric), the sides 0.5 inch outside theirs.
#[test]
fn linuxcnc_comp_g1_offsets_its_arcs_and_sides_by_the_tool_radius() {
    let mut m = machine("workpiece-linuxcnc.toml", "process-comp-g1.toml");
    m.dialect = Some(gcode::GcodeDialect::LinuxCnc);
    let g = gcode::parse_on(&corpus("linuxcnc-comp-g1.ngc"), 1e-5, &m).unwrap();
    let inch = 25.4e-3;
    let on = |line: u64| {
        g.points
            .iter()
            .filter(move |p| p.line == line)
            .map(|p| p.position / inch)
    };
    // The arcs (lines 29, 31, 34) about (2, 2), (2, -1), (2, 2) of radius 1: 1.5 with the tool,
    // after the outside corner's arc of 0.5 about their start (none at the tangent one, 31).
    let arcs = [
        (29, [2.0, 2.0], [2.0, 3.0]),
        (31, [2.0, -1.0], [3.0, -1.0]),
        (34, [2.0, 2.0], [1.4, 2.8]),
    ];
    for (line, c, start) in arcs {
        let from = |p: &Vector3<f64>, c: [f64; 2]| (p.x - c[0]).hypot(p.y - c[1]);
        let on_arc = on(line)
            .filter(|p| (from(p, c) - 1.5).abs() < 1e-9 / 25.4)
            .count();
        let on_corner = on(line)
            .filter(|p| (from(p, start) - 0.5).abs() < 1e-12)
            .count();
        assert!(on_arc > 3, "{line}");
        // The entry along Y3.5 ends tangent to arc 29 at (2, 3.5), the arc 29 meets the side 30
        // and the side 30 the arc 31 tangentially: no corner; the slanted side 33 meets arc 34
        // at an outside corner (its last point, the arc's start, on both circles).
        let corner = usize::from(line == 34);
        assert_eq!(on_arc + on_corner, on(line).count() + corner, "{line}");
        assert!(
            on_corner >= 2 * corner && (corner == 1 || on_corner == 0),
            "{line}"
        );
    }
    assert_relative_eq!(
        on(28).next_back().unwrap(),
        Vector3::new(2.0, 3.5, 0.0),
        epsilon = 1e-12
    );
    // The sides X3 (line 30) and Y-2 (line 32), the tool on their left.
    assert!(on(30).all(|p| (p.x - 3.5).abs() < 1e-12));
    assert!(on(32).all(|p| (p.y + 2.5).abs() < 1e-12));
    // The slanted side (line 33) from (-3, -2) to (1.4, 2.8): its end 0.5 to its left, after
    // the outside corner's arc about (-3, -2).
    let d = Vector3::new(4.4, 4.8, 0.0).normalize();
    let end = on(33).next_back().unwrap();
    assert_relative_eq!(end.x, 1.4 - 0.5 * d.y, epsilon = 1e-12);
    assert_relative_eq!(end.y, 2.8 + 0.5 * d.x, epsilon = 1e-12);
    let corner: Vec<_> = on(33).collect();
    for p in &corner[..corner.len() - 1] {
        assert_relative_eq!((p.x + 3.0).hypot(p.y + 2.0), 0.5, epsilon = 1e-12);
    }
    // G40: the exit goes to its programmed end (3, 3.5).
    let exit = on(36).next_back().unwrap();
    assert_relative_eq!(exit, Vector3::new(3.0, 3.5, 0.0), epsilon = 1e-12);
}
