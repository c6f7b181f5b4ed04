//! The G-code's process words in generated programs (`generate::Process`,
//! `[controller.io]`), the rapid speeds, the real tool of joint-target programs and the names
//! every writer emits.

use nalgebra::{Isometry3, Vector3, Vector6};
use stiffid::internal::machining::gcode::{self, ProcessWord};
use stiffid::internal::setup::program_io::{Io, ProcessEvent};
use stiffid_core::setup::Pulses;
use stiffid_core::Error;
use stiffid_machining::program::generate::*;
use stiffid_machining::program::Dialect;

/// The most numbered lines of an LS file (the pendant's four digits, the reference's).
const LS_MAX_LINES: usize = 9999;

pub(super) fn corpus(name: &str) -> String {
    let path = format!(
        "{}/tests/data/programs/gcode/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(path).unwrap()
}

/// One target per point, at postures a little apart (the process words' places, not the
/// targets' values, are what these tests read).
pub(super) fn targets(n: usize) -> Vec<Target> {
    let robot = stiffid_core::robot::presets::get("fanuc-r2000ic-165f").unwrap();
    (0..n)
        .map(|i| {
            let q = [-20.0 + i as f64 * 1e-3, 5.0, -45.0, 10.0, -40.0, 20.0];
            let q = Vector6::from(q).map(f64::to_radians);
            Target::new(&robot, &Vector3::new(0.0, 0.0, 0.3), &q)
        })
        .collect()
}

pub(super) const PULSES: [f64; 6] = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];

pub(super) fn plan<'a>(
    dialect: Dialect,
    t: &'a [Target],
    m: &'a [Move],
    pulses: &'a Pulses,
    targets: Targets,
) -> Plan<'a> {
    Plan {
        dialect,
        name: "ROUTER",
        targets: t,
        moves: m,
        tool: Tool {
            frame: Isometry3::translation(0.01, -0.02, 0.3),
            payload: Some((12.5, Vector3::new(0.0, 0.0, 0.12))),
        },
        work: Isometry3::translation(1.3, -0.7, 0.4),
        world: Isometry3::identity(),
        external: None,
        approximation: 1e-5,
        numbers: Default::default(),
        pulses: Some(pulses),
        settings: Settings {
            targets,
            ..Settings::default()
        },
    }
}

/// The lines of a program that move the robot, each with its index among all lines.
pub(super) fn motion_lines(dialect: Dialect, text: &str) -> Vec<usize> {
    let starts: &[&str] = match dialect {
        Dialect::Krl => &["PTP ", "LIN "],
        Dialect::Rapid => &["MoveL ", "MoveJ ", "MoveAbsJ "],
        Dialect::FanucLs => &["J P[", "L P["],
        _ => &["MOVJ ", "MOVL "],
    };
    (text.lines().enumerate())
        .filter(|(_, l)| {
            let body = l.split_once(':').filter(|_| dialect == Dialect::FanucLs);
            let l = body.map_or(l.trim_start(), |(_, b)| b.trim_start());
            starts.iter().any(|s| l.starts_with(s))
        })
        .map(|(i, _)| i)
        .collect()
}

/// The index of the first line of `text` containing `what`.
fn line_of(text: &str, what: &str) -> usize {
    (text.lines().position(|l| l.contains(what))).unwrap_or_else(|| panic!("{what} not in\n{text}"))
}

/// The Fusion 360 generic router post's file as found (its setup's workpiece and process).
pub(super) fn router() -> gcode::GCode {
    let m = crate::gcode_corpus::machine("workpiece-fusion360.toml", "process-fusion360.toml");
    gcode::parse_on(&corpus("fusion360-generic-router.nc"), 1e-5, &m).unwrap()
}

/// A process word as read: its line, event, words, speed and tool in force.
type Read<'a> = (u64, Option<ProcessEvent>, &'a str, Option<f64>, Option<u32>);

#[test]
fn the_fusion_router_files_process_words_are_read_in_path_order_with_their_values() {
    let g = router();
    let read: Vec<Read> = (g.process.iter())
        .map(|w: &ProcessWord| (w.line, w.event, w.words.as_str(), w.rpm, w.tool))
        .collect();
    // By eye: "T1 M6" on line 13, "S5000 M3" on 14, "M5" on 53, "M30" on 58.
    use ProcessEvent::*;
    assert_eq!(
        read,
        vec![
            (13, Some(ToolChange), "T1 M6", None, Some(1)),
            (14, Some(SpindleCw), "S5000 M3", Some(5000.0), Some(1)),
            (53, Some(SpindleOff), "M5", Some(5000.0), Some(1)),
            (58, Some(ProgramEnd), "M30", Some(5000.0), Some(1)),
        ]
    );
    // Tool change and spindle before the first point (line 19), the spindle stop after the
    // cut's retract (line 50) and before the G28 moves home (lines 54 and 56), the end after
    // everything.
    let lines: Vec<Option<u64>> = g.points.iter().map(|p| Some(p.line)).collect();
    assert_eq!(g.points[0].line, 19);
    let k = stop_index(&g);
    assert_eq!((g.points[k - 1].line, g.points[k].line), (50, 54));
    assert_eq!(g.points.last().unwrap().line, 56);
    let n = lines.len();
    assert_eq!(place(&g.process, &lines), vec![0, 0, k, n]);
    // With a home posture at both ends: the words before the path after the first home move,
    // the end after the last.
    let homed: Vec<Option<u64>> = [None].into_iter().chain(lines).chain([None]).collect();
    assert_eq!(place(&g.process, &homed), vec![1, 1, k + 1, n + 2]);
    // A word after the path's last point goes before the home move that follows it.
    let after = ProcessWord {
        line: 57,
        ..g.process[2].clone()
    };
    assert_eq!(place(&[after], &homed), vec![n + 1]);
}

/// The index of the router's first point after its spindle stop (`M5`, line 53).
fn stop_index(g: &gcode::GCode) -> usize {
    g.points.iter().position(|p| p.line > 53).unwrap()
}

/// The router's io as a user of a post maps it: tool change and spindle on by calls (by outputs
/// where the language calls without arguments), the spindle stop and the end left unmapped.
fn router_io(dialect: Dialect) -> Io {
    let io = Io::default();
    match dialect {
        Dialect::Inform => io
            .with(ProcessEvent::ToolChange, &["TOOLCHG"])
            .and_then(|io| io.with(ProcessEvent::SpindleCw, &["out[3] = on"])),
        _ => io
            .with(ProcessEvent::ToolChange, &["TOOL_CHANGE({tool})"])
            .and_then(|io| io.with(ProcessEvent::SpindleCw, &["SPINDLE_ON({rpm}, 1)"])),
    }
    .unwrap()
}

#[test]
fn the_fusion_routers_process_words_are_kept_in_every_language_as_mapped_or_named() {
    let g = router();
    let moves = moves(&g.points, 2.0).unwrap();
    let t = targets(g.points.len());
    let lines: Vec<Option<u64>> = g.points.iter().map(|p| Some(p.line)).collect();
    let before = place(&g.process, &lines);
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    // Each language's forms of the two mapped words, in order.
    let mapped = [
        (Dialect::Krl, ["TOOL_CHANGE(1)", "SPINDLE_ON(5000, 1)"]),
        (Dialect::Rapid, ["TOOL_CHANGE 1;", "SPINDLE_ON 5000, 1;"]),
        (
            Dialect::FanucLs,
            ["CALL TOOL_CHANGE(1) ;", "CALL SPINDLE_ON(5000,1) ;"],
        ),
        (Dialect::Inform, ["CALL JOB:TOOLCHG", "DOUT OT#(3) ON"]),
    ];
    let comment = |d: Dialect, words: &str| match d {
        Dialect::Krl => format!("; {words}"),
        Dialect::Rapid => format!("    ! {words}"),
        Dialect::FanucLs => format!("! {words} ;"),
        _ => format!("'{words}"),
    };
    for (dialect, [tool, spindle]) in mapped {
        let io = router_io(dialect);
        let process = Process {
            words: &g.process,
            before: &before,
            io: Some(&io),
            ..Default::default()
        };
        for targets in Targets::ALL {
            let p = plan(dialect, &t, &moves, &pulses, targets);
            let written = generate_with(&p, &process).unwrap();
            let text = &written.files[0].text;
            let motions = motion_lines(dialect, text);
            assert_eq!(motions.len(), g.points.len(), "{dialect:?}");
            let (first, last) = (motions[0], *motions.last().unwrap());
            let (tool_at, spindle_at) = (line_of(text, tool), line_of(text, spindle));
            assert!(
                tool_at < spindle_at && spindle_at < first,
                "{dialect:?}\n{text}"
            );
            let stop = line_of(text, &comment(dialect, "M5 (line 53)"));
            let end = line_of(text, &comment(dialect, "M30 (line 58)"));
            let k = stop_index(&g);
            assert!(
                motions[k - 1] < stop && stop < motions[k],
                "{dialect:?}\n{text}"
            );
            assert!(last < end, "{dialect:?}\n{text}");
            // One warning naming every word left unmapped, and nothing else.
            assert_eq!(written.left_out.len(), 1, "{:?}", written.left_out);
            let w = &written.left_out[0];
            assert!(w.starts_with("2 process word(s)"), "{w}");
            assert!(
                w.ends_with("spindle_off: M5 (line 53); program_end: M30 (line 58)"),
                "{w}"
            );
            assert!(!w.contains("line 13") && !w.contains("line 14"), "{w}");
            if dialect == Dialect::FanucLs {
                ls_numbered(text);
            }
        }
    }
}

/// An LS program's `/MN` lines numbered 1, 2, .. without a gap, each at most the pendant's
/// four digits.
fn ls_numbered(text: &str) {
    let mn = text
        .split("/MN\n")
        .nth(1)
        .unwrap()
        .split("/POS\n")
        .next()
        .unwrap();
    for (i, line) in mn.lines().enumerate() {
        let (number, _) = line.split_once(':').unwrap_or_else(|| panic!("{line}"));
        assert_eq!(number.trim().parse::<usize>().unwrap(), i + 1, "{line}");
        assert!(i < LS_MAX_LINES);
    }
}

/// A path whose process words sit between its motions.
const BETWEEN: &str = "(stiffid: tool_rpy_deg = 180 0 0)
G21 G90
G0 X0 Y0 Z10
M8
G1 Z0 F600
S8000
G1 X10
M9 M5
G0 Z10
M30
";

#[test]
fn process_words_are_written_between_the_motions_the_gcode_puts_them_between() {
    let g = gcode::parse(BETWEEN, 1e-5).unwrap();
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
        io: None,
        ..Default::default()
    };
    let p = plan(Dialect::Krl, &t, &moves, &pulses, Targets::Joint);
    let written = generate_with(&p, &process).unwrap();
    let text = &written.files[0].text;
    // Motions and process words in the order of the G-code; a block's spindle word before its
    // coolant word (the order a controller runs one block's words).
    let order: Vec<&str> = (text.lines())
        .filter(|l| l.starts_with("PTP ") || l.starts_with("; M") || l.starts_with("; S"))
        .map(|l| match l.starts_with("PTP") {
            true => "move",
            false => l,
        })
        .collect();
    assert_eq!(
        order,
        [
            "move",
            "; M8 (line 4)",
            "move",
            "; S8000 (line 6)",
            "move",
            "; M5 (line 8)",
            "; M9 (line 8)",
            "move",
            "; M30 (line 10)"
        ],
        "{text}"
    );
    let w = &written.left_out[0];
    assert!(w.contains("coolant_flood: M8 (line 4); spindle_speed: S8000 (line 6); spindle_off: M5 (line 8); coolant_off: M9 (line 8); program_end: M30 (line 10)"), "{w}");
}

#[test]
fn an_action_the_language_cannot_write_or_a_value_not_given_is_refused_naming_the_key() {
    let g = gcode::parse(BETWEEN, 1e-5).unwrap();
    let lines: Vec<Option<u64>> = g.points.iter().map(|p| Some(p.line)).collect();
    let before = place(&g.process, &lines);
    let moves = moves(&g.points, 2.0).unwrap();
    let t = targets(g.points.len());
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let cases: [(Dialect, ProcessEvent, &str, &str); 6] = [
        (
            Dialect::Rapid,
            ProcessEvent::CoolantFlood,
            "out[3] = on",
            "a RAPID digital output is a named signal",
        ),
        (
            Dialect::FanucLs,
            ProcessEvent::CoolantFlood,
            "out[doCool] = on",
            "by its number, DO[n]",
        ),
        (
            Dialect::Inform,
            ProcessEvent::CoolantFlood,
            "COOL(1)",
            "without arguments",
        ),
        (
            Dialect::Inform,
            ProcessEvent::CoolantFlood,
            "out[doCool] = off",
            "by its number",
        ),
        // KRL names are at most 24 characters; RAPID's 32 take it.
        (
            Dialect::Krl,
            ProcessEvent::CoolantFlood,
            "COOLANT_FLOOD_ON_AT_LINE_4",
            "at most 24 characters",
        ),
        (
            Dialect::Rapid,
            ProcessEvent::CoolantFlood,
            "wpart",
            "a reserved word",
        ),
    ];
    for (dialect, event, action, expected) in cases {
        let io = Io::default().with(event, &[action]).unwrap();
        let process = Process {
            words: &g.process,
            before: &before,
            io: Some(&io),
            ..Default::default()
        };
        let p = plan(dialect, &t, &moves, &pulses, Targets::Joint);
        match generate_with(&p, &process) {
            Err(Error::InvalidField { field, message }) => {
                assert_eq!(field, "controller.io.coolant_flood", "{message}");
                assert!(message.contains(expected), "{dialect:?}: {message}");
                assert!(message.contains("M8 on line 4"), "{message}");
            }
            other => panic!("{dialect:?} {action}: {other:?}"),
        }
    }
    let rapid = Io::default().with(ProcessEvent::CoolantFlood, &["COOLANT_FLOOD_ON_AT_LINE_4"]);
    let process = Process {
        words: &g.process,
        before: &before,
        io: Some(rapid.as_ref().unwrap()),
        ..Default::default()
    };
    let p = plan(Dialect::Rapid, &t, &moves, &pulses, Targets::Joint);
    let text = &generate_with(&p, &process).unwrap().files[0].text;
    assert!(
        text.contains("\n    COOLANT_FLOOD_ON_AT_LINE_4;\n"),
        "{text}"
    );
    // A spindle call passing {rpm} where no S word has been given.
    let io = Io::default()
        .with(ProcessEvent::SpindleCw, &["ON({rpm})"])
        .unwrap();
    let g = gcode::parse("(stiffid: tool_rpy_deg = 180 0 0)\nM3\nG0 X0 Y0 Z0\n", 1e-5).unwrap();
    let before = place(&g.process, &[Some(3)]);
    let process = Process {
        words: &g.process,
        before: &before,
        io: Some(&io),
        ..Default::default()
    };
    let t = targets(1);
    let p = plan(Dialect::Krl, &t, &[Move::Rapid], &pulses, Targets::Joint);
    match generate_with(&p, &process) {
        Err(Error::Program { line: 2, message }) => {
            assert!(message.contains("{rpm}, the spindle speed S"), "{message}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_io_table_is_checked_on_load_naming_the_key() {
    use ProcessEvent::*;
    let cases: [(ProcessEvent, &str, &str); 6] = [
        (SpindleOff, "STOP({rpm})", "this event gives no value"),
        (SpindleCw, "ON({tool})", "this event gives {rpm} only"),
        (ToolChange, "TC(x)", "argument 'x': expected a number"),
        (CoolantMist, "out[0] = on", "output numbers start at 1"),
        (CoolantMist, "out[3] = maybe", "expected on or off"),
        (CoolantMist, "1CALL", "is no name"),
    ];
    for (event, action, expected) in cases {
        match Io::default().with(event, &[action]) {
            Err(Error::InvalidField { field, message }) => {
                assert_eq!(field, format!("controller.io.{}", event.key()));
                assert!(message.contains(expected), "{action}: {message}");
            }
            other => panic!("{action}: {other:?}"),
        }
    }
}

const SETUP: &str = include_str!("../../../../../../examples/milling/fanuc-milling.toml");

fn setup_with(controller: &str) -> stiffid::Result<stiffid::Setup> {
    let text = format!("{SETUP}\n[controller]\n{controller}\n");
    stiffid::internal::setup::parse(&text, "setup.toml", |n, _| {
        stiffid::internal::robot::presets::get(n)
    })
}

#[test]
fn the_controllers_program_settings_are_read_and_refused_outside_their_ranges() {
    let setup = setup_with(
        "rapid_speed_mm_s = 150\nrapid_joint_pct = 12.5\nhome_deg = [0, 0, 0, 0, -90, 0]\n\
         [controller.io]\nspindle_cw = \"SPINDLE_ON({rpm})\"\nspindle_off = [\"SPINDLE_OFF\", \"out[4] = off\"]\n",
    )
    .unwrap();
    let program = &setup.workcell().controller().program;
    assert_eq!(program.rapid_speed, Some(0.15));
    assert_eq!(program.rapid_joint_pct, Some(12.5));
    assert_eq!(program.home_deg, Some([0.0, 0.0, 0.0, 0.0, -90.0, 0.0]));
    assert_eq!(program.io.get(ProcessEvent::SpindleOff).unwrap().len(), 2);
    assert!(program.io.get(ProcessEvent::CoolantOff).is_none());
    for (controller, field, expected) in [
        (
            "rapid_speed_mm_s = 0",
            "controller.rapid_speed_mm_s",
            "outside",
        ),
        (
            "rapid_joint_pct = 101",
            "controller.rapid_joint_pct",
            "outside",
        ),
        (
            "home_deg = [0, 0, 0, 0, 300, 0]",
            "controller.home_deg[5]",
            "the robot's limits",
        ),
        (
            "[controller.io]\nspindle = \"ON\"",
            "controller.io.spindle",
            "unknown event",
        ),
        (
            "[controller.io]\ntool_change = []",
            "controller.io.tool_change",
            "expected 1 to 8 actions",
        ),
    ] {
        let e = setup_with(controller).unwrap_err().to_string();
        assert!(
            e.contains(field) && e.contains(expected),
            "{controller}: {e}"
        );
    }
}

#[test]
fn rapid_speeds_are_the_settings_and_stated_in_each_languages_form_or_refused() {
    let t = targets(2);
    let moves = [Move::Rapid, Move::Feed(0.01)];
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let settings = |pct: f64| Settings {
        rapid_speed: 0.15,
        rapid_joint_pct: pct,
        ..Settings::default()
    };
    for (dialect, pct, expected) in [
        (Dialect::Krl, 12.5, "BAS(#VEL_PTP, 12.5)"),
        (Dialect::Rapid, 12.5, "CONST speeddata vrapid := [150,"),
        (Dialect::FanucLs, 12.0, "J P[1] 12% FINE ;"),
        (Dialect::Inform, 12.25, "VJ=12.25 PL=0"),
    ] {
        let mut p = plan(dialect, &t, &moves, &pulses, Targets::Joint);
        p.settings = settings(pct);
        let text = &generate(&p).unwrap().files[0].text;
        assert!(text.contains(expected), "{dialect:?}\n{text}");
    }
    for (dialect, pct) in [(Dialect::FanucLs, 12.5), (Dialect::Inform, 12.125)] {
        let mut p = plan(dialect, &t, &moves, &pulses, Targets::Joint);
        p.settings = settings(pct);
        match generate(&p) {
            Err(Error::InvalidField { field, .. }) => {
                assert_eq!(field, "controller.rapid_joint_pct")
            }
            other => panic!("{dialect:?}: {other:?}"),
        }
    }
    let mut p = plan(Dialect::Rapid, &t, &moves, &pulses, Targets::Joint);
    p.settings.rapid_speed = 0.0;
    match generate(&p) {
        Err(Error::InvalidField { field, .. }) => assert_eq!(field, "controller.rapid_speed_mm_s"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn joint_target_programs_move_with_the_real_tool() {
    let t = targets(2);
    let moves = [Move::Rapid, Move::Feed(0.01)];
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let rapid = generate(&plan(Dialect::Rapid, &t, &moves, &pulses, Targets::Joint)).unwrap();
    let text = &rapid.files[0].text;
    assert!(
        text.contains("PERS tooldata tspindle := [TRUE,[[10,-20,300],"),
        "{text}"
    );
    assert!(text.contains("PERS wobjdata wpart"), "{text}");
    let moves_with: Vec<&str> = text.lines().filter(|l| l.contains("MoveAbsJ")).collect();
    assert_eq!(moves_with.len(), 2);
    assert!(
        moves_with
            .iter()
            .all(|l| l.ends_with(", tspindle\\WObj:=wpart;")),
        "{text}"
    );
    assert!(!text.contains("tool0"), "{text}");
    let krl = generate(&plan(Dialect::Krl, &t, &moves, &pulses, Targets::Joint)).unwrap();
    let text = &krl.files[0].text;
    assert!(
        text.contains("$TOOL = {X 10, Y -20, Z 300, A 0, B 0, C 0}"),
        "{text}"
    );
    assert!(
        text.contains("$LOAD = {M 12.5, CM {X 0, Y 0, Z 120"),
        "{text}"
    );
    // A RAPID tooldata states a mass: without one, a joint-target program is refused too.
    let mut p = plan(Dialect::Rapid, &t, &moves, &pulses, Targets::Joint);
    p.tool.payload = None;
    match generate(&p) {
        Err(Error::InvalidField { field, .. }) => assert_eq!(field, "tool.mass_kg"),
        other => panic!("{other:?}"),
    }
}

/// The names a program declares or calls: after `DEF`, `MODULE`, `PROC`, `/PROG`, `//NAME`,
/// `CALL` (`JOB:`), the data a RAPID module declares.
fn emitted_names(text: &str) -> Vec<String> {
    let mut names = Vec::new();
    for line in text.lines() {
        let l = line
            .split_once(':')
            .filter(|(n, _)| n.trim().parse::<u32>().is_ok());
        let l = l.map_or(line, |(_, b)| b).trim();
        for key in [
            "DEF ",
            "MODULE ",
            "PROC ",
            "/PROG  ",
            "//NAME ",
            "CALL JOB:",
            "CALL ",
            "tooldata ",
            "wobjdata ",
            "speeddata ",
            "zonedata ",
        ] {
            if let Some(rest) = l.split_once(key).map(|(_, r)| r) {
                let name: String = (rest.trim_start().chars())
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() && name != "JOB" {
                    names.push(name);
                }
            }
        }
        // A KRL sub-program's call: `NAME_01( )`.
        if let Some(name) = l.strip_suffix("( )").filter(|n| !n.contains(' ')) {
            names.push(name.to_string());
        }
        // A RAPID sub-program's call: `rNAME_01;`.
        if l.starts_with('r') && l.ends_with(';') && !l.contains(' ') {
            names.push(l.trim_end_matches(';').to_string());
        }
    }
    names
}

#[test]
fn every_name_written_in_every_language_is_within_the_controllers_length() {
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let t = targets(250);
    let mut moves = vec![Move::Feed(0.01); 250];
    moves[0] = Move::Rapid;
    for dialect in [
        Dialect::Krl,
        Dialect::Rapid,
        Dialect::FanucLs,
        Dialect::Inform,
    ] {
        let most = dialect.controller().max_name_length();
        // The longest main name that leaves room for the sub-programs' (`_01`.. and RAPID's `r`).
        let room = most - 3 - usize::from(dialect == Dialect::Rapid);
        let name: String = "P".repeat(room);
        let io = Io::default()
            .with(
                ProcessEvent::SpindleOff,
                &[&format!("CALL{}", "X".repeat(most - 4))],
            )
            .unwrap();
        let g = gcode::parse("(stiffid: tool_rpy_deg = 180 0 0)\nG0 X0 Y0 Z0\nM5\n", 1e-5).unwrap();
        let before = vec![250];
        let process = Process {
            words: &g.process,
            before: &before,
            io: Some(&io),
            ..Default::default()
        };
        let mut p = plan(dialect, &t, &moves, &pulses, Targets::Joint);
        p.name = &name;
        p.settings.name_length = Some(most);
        p.settings.moves_per_file = 100;
        let written = generate_with(&p, &process).unwrap();
        assert_eq!(written.files.len(), 4, "{dialect:?}");
        let mut seen = 0;
        for file in &written.files {
            for n in emitted_names(&file.text) {
                assert!(n.len() <= most, "{dialect:?}: {n} longer than {most}");
                seen += 1;
            }
        }
        assert!(seen >= 7, "{dialect:?}: {seen} names");
        // One character more is refused, naming the option or the key.
        let longer = format!("{name}P");
        p.name = &longer;
        assert!(matches!(
            generate_with(&p, &process),
            Err(Error::InvalidOption { .. })
        ));
        p.name = &name;
        let io = Io::default()
            .with(
                ProcessEvent::SpindleOff,
                &[&format!("CALL{}", "X".repeat(most - 3))],
            )
            .unwrap();
        let process = Process {
            io: Some(&io),
            ..process
        };
        match generate_with(&p, &process) {
            Err(Error::InvalidField { field, .. }) => {
                assert_eq!(field, "controller.io.spindle_off")
            }
            other => panic!("{dialect:?}: {other:?}"),
        }
    }
}

#[test]
fn an_ls_files_process_lines_count_toward_the_pendants_line_numbers() {
    let n = 9_900;
    let t = targets(n);
    let mut moves = vec![Move::Feed(0.01); n];
    moves[0] = Move::Rapid;
    // 300 spindle speed changes spread along the path.
    let words: Vec<ProcessWord> = (0..300)
        .map(|i| ProcessWord {
            line: i + 1,
            event: Some(ProcessEvent::SpindleSpeed),
            words: format!("S{}", 1000 + i),
            rpm: Some(1000.0 + i as f64),
            tool: None,
            dwell: None,
            point: None,
        })
        .collect();
    let before: Vec<usize> = (0..300).map(|i| i * 33).collect();
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let process = Process {
        words: &words,
        before: &before,
        io: None,
        ..Default::default()
    };
    let mut p = plan(Dialect::FanucLs, &t, &moves, &pulses, Targets::Joint);
    p.settings.moves_per_file = 1_000_000;
    p.settings.name_length = Some(12);
    let written = generate_with(&p, &process).unwrap();
    // Without the process lines one file of 9 900 moves would do; with them, two.
    assert_eq!(written.files.len(), 3);
    let mut moved = 0;
    let mut remarks = 0;
    for file in &written.files[1..] {
        ls_numbered(&file.text);
        let mn = file
            .text
            .split("/MN\n")
            .nth(1)
            .unwrap()
            .split("/POS\n")
            .next()
            .unwrap();
        assert!(mn.lines().count() <= LS_MAX_LINES);
        moved += mn
            .lines()
            .filter(|l| l.contains(":L P[") || l.contains(":J P["))
            .count();
        remarks += mn.lines().filter(|l| l.contains("! S")).count();
    }
    assert_eq!((moved, remarks), (n, 300));
}

#[test]
fn an_m_word_of_no_event_is_a_comment_named_in_the_warning() {
    let g = gcode::parse(
        "(stiffid: tool_rpy_deg = 180 0 0)\nM62 P0\nG0 X0 Y0 Z0\nM0\n",
        1e-5,
    )
    .unwrap();
    let words: Vec<(u64, Option<ProcessEvent>, &str)> = (g.process.iter())
        .map(|w| (w.line, w.event, w.words.as_str()))
        .collect();
    assert_eq!(words, [(2, None, "M62"), (4, None, "M0")]);
    let before = place(&g.process, &[Some(3)]);
    assert_eq!(before, [0, 1]);
    let io = Io::default()
        .with(ProcessEvent::ProgramEnd, &["END_CELL"])
        .unwrap();
    let process = Process {
        words: &g.process,
        before: &before,
        io: Some(&io),
        ..Default::default()
    };
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let t = targets(1);
    let p = plan(Dialect::Rapid, &t, &[Move::Rapid], &pulses, Targets::Joint);
    let written = generate_with(&p, &process).unwrap();
    let text = &written.files[0].text;
    assert!(text.contains("    ! M62 (line 2)\n    MoveAbsJ"), "{text}");
    assert!(text.contains("    ! M0 (line 4)\n  ENDPROC"), "{text}");
    assert_eq!(
        written.left_out,
        ["2 process word(s) of the G-code not mapped in the setup's [controller.io], written as comments where the G-code has them (map an event to a call or an output to run it): other M words (no event): M62 (line 2), M0 (line 4)"]
    );
}
