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
    let before = place(&g.process, &lines);
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
