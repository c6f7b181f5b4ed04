//! A G-code dwell (`G4 P..`) written to a robot program as the language's wait, at its place
//! between the motions, in seconds as the setup's `[controller] dialect` reads `P`; refused
//! naming the line where the dialect is not stated (controllers read `P` in seconds or
//! milliseconds).

use super::process::{motion_lines, plan, targets, PULSES};
use stiffid::internal::machining::gcode::{self, GcodeDialect, Machine};
use stiffid_core::setup::Pulses;
use stiffid_core::Error;
use stiffid_machining::program::generate::*;
use stiffid_machining::program::Dialect;

/// A cut with a dwell `p` (as written) after its plunge and a dwell of no time after the cut.
fn cut(p: &str) -> String {
    format!("(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90\nG0 X0 Y0 Z10\nG1 Z0 F600\nG4 P{p}\nG1 X10\nG4 P0\nG0 Z10\nM30\n")
}

/// The programs written from `text` read on `dialect`'s controller, in each language.
fn written(text: &str, dialect: Option<GcodeDialect>) -> Vec<(Dialect, Result<String, Error>)> {
    let machine = Machine {
        dialect,
        ..Default::default()
    };
    let g = gcode::parse_on(text, 1e-5, &machine).unwrap();
    let lines: Vec<Option<u64>> = g.points.iter().map(|p| Some(p.line)).collect();
    let mut before = place(&g.process, &lines);
    let points: Vec<Option<usize>> = (0..g.points.len()).map(Some).collect();
    after_points(&g.process, &points, &mut before);
    let moves = moves(&g.points, 2.0).unwrap();
    let t = targets(g.points.len());
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let process = Process {
        words: &g.process,
        before: &before,
        ..Default::default()
    };
    (Dialect::ALL.into_iter())
        .map(|d| {
            let p = plan(d, &t, &moves, &pulses, Targets::Joint);
            let out = generate_with(&p, &process).map(|w| w.files[0].text.clone());
            (d, out)
        })
        .collect()
}

#[test]
fn a_dwell_is_written_as_the_languages_wait_in_seconds_as_the_dialect_reads_p() {
    let waits = |d: Dialect, x: f64| match d {
        Dialect::Krl => format!("WAIT SEC {x}"),
        Dialect::Rapid => format!("WaitTime \\InPos, {x};"),
        Dialect::FanucLs => format!("WAIT {x:.2}(sec) ;"),
        Dialect::Inform => format!("TIMER T={x:.2}"),
    };
    for (p, dialect) in [
        ("2.5", GcodeDialect::LinuxCnc),
        ("2.5", GcodeDialect::Grbl),
        ("2500", GcodeDialect::Fanuc),
        ("2500", GcodeDialect::Haas),
        ("2.5", GcodeDialect::Haas),
    ] {
        for (d, text) in written(&cut(p), Some(dialect)) {
            let text = text.unwrap();
            let lines: Vec<&str> = text.lines().collect();
            let find = |what: &str| lines.iter().position(|l| l.ends_with(what));
            let (long, none) = (waits(d, 2.5), waits(d, 0.0));
            let at = find(&long)
                .unwrap_or_else(|| panic!("{d:?} G4 P{p} on {dialect:?}: {long} not in\n{text}"));
            let zero = find(&none).unwrap_or_else(|| panic!("{d:?}: {none} not in\n{text}"));
            // Each wait after the motion of the block before it and before the next one.
            let m = motion_lines(d, &text);
            let after = |k: usize| m.iter().filter(|&&i| i < k).count();
            assert_eq!(
                (after(at), after(zero)),
                (m.len() - 2, m.len() - 1),
                "{d:?}\n{text}"
            );
        }
    }
    // Unstated: LinuxCNC's 2 s are FANUC's 2 ms; the G-code reads, a robot program is refused.
    for (d, out) in written(&cut("2"), None) {
        match out {
            Err(Error::Program { line: 5, message }) => {
                assert!(
                    message.contains("[controller] dialect") && message.contains("G4 P2"),
                    "{message}"
                );
            }
            other => panic!("{d:?}: {other:?}"),
        }
    }
}

/// The waits of `d` in `text`, each with the count of motions before it.
fn waits_in(d: Dialect, text: &str) -> Vec<(String, usize)> {
    let m = motion_lines(d, text);
    let wait = ["WAIT SEC", "WaitTime", "WAIT ", "TIMER"];
    (text.lines().enumerate())
        .filter(|(_, l)| {
            wait.iter().any(|w| {
                l.trim_start()
                    .trim_start_matches(|c: char| c.is_ascii_digit() || c == ':')
                    .trim_start()
                    .starts_with(w)
            })
        })
        .map(|(k, l)| (l.trim().to_string(), m.iter().filter(|&&i| i < k).count()))
        .collect()
}

/// `G4 X` is the dwell's time on FANUC and Haas (seconds with a decimal point, thousandths
/// without), written where `G4 P` is and moving no axis; refused naming the line where `X` is a
/// move (LinuxCNC, grbl) or the dialect is not stated.
#[test]
fn g4_x_is_the_dwells_time_on_fanuc_and_haas_and_refused_elsewhere() {
    let by_p = gcode::parse_on(&cut("2500"), 1e-5, &fanuc()).unwrap();
    for (x, dialect) in [
        ("X2.5", GcodeDialect::Fanuc),
        ("X2500", GcodeDialect::Fanuc),
        ("X2.5", GcodeDialect::Haas),
    ] {
        let text = cut("0").replacen("G4 P0\nG1", &format!("G4 {x}\nG1"), 1);
        let machine = Machine {
            dialect: Some(dialect),
            ..Default::default()
        };
        let g = gcode::parse_on(&text, 1e-5, &machine).unwrap();
        assert_eq!(g.points, by_p.points, "{x} on {dialect:?} moved an axis");
        for (d, out) in written(&text, Some(dialect)) {
            let waits = waits_in(d, &out.unwrap());
            assert_eq!(waits.len(), 2, "{d:?} {x}: {waits:?}");
            assert!(waits[0].0.contains("2.5"), "{d:?} {x}: {waits:?}");
            assert_eq!(waits[0].1, 2, "{d:?} {x}: after the plunge");
        }
    }
    for dialect in [Some(GcodeDialect::LinuxCnc), None] {
        let text = cut("0").replacen("G4 P0\nG1", "G4 X2.5\nG1", 1);
        let machine = Machine {
            dialect,
            ..Default::default()
        };
        match gcode::parse_on(&text, 1e-5, &machine) {
            Err(Error::Program { line: 5, message }) => {
                assert!(message.contains("G4 with an axis word"), "{message}")
            }
            other => panic!("{dialect:?}: {other:?}"),
        }
    }
}

fn fanuc() -> Machine {
    Machine {
        dialect: Some(GcodeDialect::Fanuc),
        ..Default::default()
    }
}

/// A `G82`'s dwell is written as the language's wait at each hole's bottom (after the motion
/// there, before the rapid out), in seconds as the dialect reads `P`; refused naming the line
/// without a dialect.
#[test]
fn a_g82_dwell_is_written_as_the_wait_at_each_holes_bottom() {
    let drill = |p: &str| {
        format!("(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90\nG0 X0 Y0 Z10\nG99 G82 X0 Y0 Z-5 R2 {p} F120\nX30\nG80\nM30\n")
    };
    for (p, dialect) in [
        ("P500", GcodeDialect::Fanuc),
        ("P0.5", GcodeDialect::LinuxCnc),
    ] {
        let machine = Machine {
            dialect: Some(dialect),
            ..Default::default()
        };
        let g = gcode::parse_on(&drill(p), 1e-5, &machine).unwrap();
        let rapid_out: Vec<usize> = (1..g.points.len())
            .filter(|&i| g.points[i].position.z > g.points[i - 1].position.z + 1e-9)
            .collect();
        assert_eq!(rapid_out.len(), 2, "{:?}", g.points);
        for (d, out) in written(&drill(p), Some(dialect)) {
            let waits = waits_in(d, &out.unwrap());
            let at: Vec<usize> = waits.iter().map(|w| w.1).collect();
            assert_eq!(at, rapid_out, "{d:?} {p}: {waits:?}");
            assert!(
                waits.iter().all(|w| w.0.contains("0.5")),
                "{d:?}: {waits:?}"
            );
        }
    }
    for (d, out) in written(&drill("P500"), None) {
        match out {
            Err(Error::Program { line: 4, message }) => {
                assert!(
                    message.contains("[controller] dialect") && message.contains("G82 P500"),
                    "{message}"
                )
            }
            other => panic!("{d:?}: {other:?}"),
        }
    }
}
