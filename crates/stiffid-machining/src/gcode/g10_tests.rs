//! Work offsets the program sets (`G10 L2`, `G10 L20`, module `g10`).

use crate::gcode::{self, GcodeDialect, Machine, ProgramFrames};
use nalgebra::{Isometry3, Translation3};

const HEADER: &str = "(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90 G17\n";

fn machine(dialect: Option<GcodeDialect>, offsets: &[(&str, [f64; 3])]) -> Machine {
    let offsets = (offsets.iter())
        .map(|(n, t)| {
            let t = Translation3::new(t[0] * 1e-3, t[1] * 1e-3, t[2] * 1e-3);
            (n.to_string(), Isometry3::from_parts(t, Default::default()))
        })
        .collect();
    Machine {
        frames: ProgramFrames {
            offsets,
            ..Default::default()
        },
        dialect,
        ..Default::default()
    }
}

#[test]
fn g10_sets_work_offsets_in_machine_coordinates_and_refuses_what_it_cannot_place() {
    let linuxcnc = Some(GcodeDialect::LinuxCnc);
    let last = |text: &str, m: &Machine| {
        let g = gcode::parse_on(&format!("{HEADER}{text}"), 1e-5, m).unwrap();
        let p = g.points.last().unwrap().position * 1e3;
        [p.x, p.y, p.z].map(|v| (v * 1e9).round() / 1e9)
    };
    // G54 at machine X10 Y20 places the machine's origin; G55 at X15 Y20 Z-1 is 5 mm along X.
    let text = "G10 L2 P1 X10 Y20 Z0\nG10 L2 P2 X15 Y20 Z-1\nG55\nG0 X0 Y0 Z5\n";
    assert_eq!(last(text, &machine(None, &[])), [5.0, 0.0, 4.0]);
    // With the setup's G53, the axes not given keep their values (machine 100 0 0 -> 100 0 7).
    let m = machine(None, &[("G53", [-100.0, 0.0, 0.0])]);
    let text = "G10 L2 P3 X100 Y0 Z0\nG10 L2 P3 Z7\nG56 G0 X1 Y0 Z0\n";
    assert_eq!(last(text, &m), [1.0, 0.0, 7.0]);
    // LinuxCNC's L20: G55 moved so that the tool (X1 Y2) reads X0 Y0 there.
    let text =
        "G10 L2 P1 X0 Y0 Z0\nG10 L2 P2 X0 Y0 Z0\nG0 X1 Y2 Z3\nG10 L20 P2 X0 Y0\nG55 G0 X0 Y0 Z3\n";
    assert_eq!(last(text, &machine(linuxcnc, &[])), [1.0, 2.0, 3.0]);
    // FANUC's L20 sets G54.1 Pn; under G91 the values add to the offset.
    let fanuc = machine(Some(GcodeDialect::Fanuc), &[("G53", [0.0; 3])]);
    let text = "G10 L20 P3 X5 Y0 Z0\nG91 G10 L20 P3 X1\nG90 G54.1 P3\nG0 X0 Y0 Z1\n";
    assert_eq!(last(text, &fanuc), [6.0, 0.0, 1.0]);
    for (text, m, why) in [
        ("G10 L2 P2 X1 Y1 Z1\n", machine(None, &[]), "does not place"),
        (
            "G10 L2 P1 X1 Y1 Z1\n",
            machine(None, &[("G53", [0.0; 3])]),
            "part frame",
        ),
        (
            "G10 L2 P2 X1 Y0 Z0\n",
            machine(None, &[("G53", [0.0; 3]), ("G55", [0.0; 3])]),
            "another frame",
        ),
        ("G10 L20 P2 X0\n", machine(None, &[]), "names no controller"),
        ("G10 L1 P1 Z50\n", machine(None, &[]), "tool table"),
        ("G91 G10 L2 P1 X0 Y0 Z0\n", machine(None, &[]), "under G91"),
        (
            "G10 L2 P0 X0 Y0 Z0\n",
            machine(Some(GcodeDialect::Haas), &[]),
            "P0",
        ),
        ("G10 L2 P1 X0 Y0 Z0 R30\n", machine(None, &[]), "rotation"),
        (
            "G10 L2 P1 G0 X0 Y0 Z0\n",
            machine(None, &[]),
            "a block of its own",
        ),
    ] {
        let e = gcode::parse_on(&format!("{HEADER}{text}G0 X0 Y0 Z1\n"), 1e-5, &m).unwrap_err();
        let e = e.to_string();
        assert!(e.contains("line 3") && e.contains(why), "{text}: {e}");
    }
}
