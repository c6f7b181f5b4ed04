//! The process wrench where the tool cuts, in every program language: the milling example's
//! pocket as G-code (`pocket.nc`) and as the robot programs written from it (`pocket.ls` on the
//! FANUC cell, `pocket.src` and `pocket.mod` on the KUKA cell, and an INFORM job of the G-code's
//! own postures) gets the same wrench and the same error bound at every point they share (a
//! circular move's via point and end, fed along the circle's tangent, to the G-code chord's lag
//! behind it: 7.4 N, 4 um) (written by
//! stiffid: to 1e-6 N of 244 N and 1e-12 m; INFORM's whole pulses: 0.1 N and 1e-7 m; the shipped
//! files, whose targets carry a deflection of up to 0.2 um: 0.01 N and 2e-9 m): the joint moves,
//! the plunges and the retracts none, the cutting moves the operation's; so do two slots joined
//! by a rapid across (a joint move in a robot program). `place` evaluates the KRL and RAPID
//! programs as their G-code. A drilling program's cycles (`G81`, `G83`) written as LS, KRL,
//! RAPID and INFORM get the thrust where the G-code's drill cuts (the feed below where it meets
//! the part), never at the `R` level, on the feed down to the surface or a peck's re-entry.

use nalgebra::Isometry3;
use stiffid::app::place::{self, Region, Request, Work};
use stiffid::internal::machining::compensate::{Aggregate, Compliance, Options};
use stiffid::internal::machining::process::{file, Process};
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::{self, Language, Program, Report};
use stiffid::internal::robot::presets;
use stiffid::Setup;

const POCKET: &str = include_str!("../../../../examples/milling/pocket.nc");
const FANUC: &str = include_str!("../../../../examples/milling/fanuc-milling.toml");
const KUKA: &str = include_str!("../../../../examples/milling/kuka-milling.toml");

/// A cell: its setup (and the setup file's text) and the example's stiffness identified for it.
struct Cell {
    setup: Setup,
    text: &'static str,
    compliance: Compliance,
    process: Process,
}

/// How far a circular move's via point and end (fed along the circle's tangent) may be from the
/// G-code's chord point there, whose feed is its chord from the point before: half a chord's
/// angle off the tangent, `acos(1 - 0.01 mm / 20 mm)` = 1.8 deg at the tests' chord tolerance on
/// the pocket's 20 mm corners, 7.7 N of the 244 N cut. Measured: 7.35 N; fed along the chord
/// from the point before (the program's start and via point), 81.8 N.
const ARC_N: f64 = 7.8;
/// The same for the error bound, m. Measured: 3.7 um; fed along the chord, 41 um.
const ARC_M: f64 = 5e-6;

/// The milling example's process.
const ALUMINIUM: &str = include_str!("../../../../examples/milling/aluminium.toml");
/// The drilling example's process: an 8 mm drill, 600 N of thrust (`k_f f D / 2`).
const DRILL: &str = include_str!("../../../../examples/milling/drilling.toml");

fn cell(text: &'static str, name: &str, stiffness: &str) -> Cell {
    let setup = stiffid::internal::setup::parse(text, name, |r, _| presets::get(r)).unwrap();
    let compliance = stiffid::internal::io::stiffness::parse(stiffness)
        .unwrap()
        .compliance(setup.model())
        .unwrap();
    let process = file::parse(ALUMINIUM, "aluminium.toml").unwrap();
    Cell {
        setup,
        text,
        compliance,
        process,
    }
}

fn fanuc() -> Cell {
    let stiffness = include_str!("../../../../examples/milling/stiffness.json");
    cell(FANUC, "fanuc-milling.toml", stiffness)
}

fn kuka() -> Cell {
    let stiffness = include_str!("../../../../examples/milling/kuka-stiffness.json");
    cell(KUKA, "kuka-milling.toml", stiffness)
}

/// `c` under the drilling process [`DRILL`].
fn drilling(c: Cell) -> Cell {
    Cell {
        process: file::parse(DRILL, "drilling.toml").unwrap(),
        ..c
    }
}

/// `text` in `language` compensated on `c` (its Cartesian targets resolved first).
fn compensated(c: &Cell, text: &str, language: Language) -> Report {
    let options = Options::for_setup(&c.setup);
    let program = machining::read(text, language, 1e-5).unwrap();
    let program = machining::resolve(&program, &c.setup, None, &options).unwrap();
    machining::compensate(
        c.setup.arm(),
        c.setup.workpiece(),
        &c.compliance,
        &program,
        &c.process,
        &options,
    )
    .unwrap()
}

/// [`differences`] over the points of `robot` (a program of `text`) that are points of
/// `reference` (the same nominal posture, in path order), a circular move's via point and end
/// apart (the third and fourth numbers): the program reaches them on a circle, fed along its
/// tangent, the G-code's chord points along the chord from the one before (which turns by half a
/// chord's angle less).
fn matched(reference: &Report, robot: &Report, text: &str) -> (f64, f64, f64, f64) {
    let lines: Vec<&str> = text.lines().collect();
    let circular = |line: u64| {
        let l = lines[line as usize - 1].trim();
        let body = l
            .split_once(':')
            .map_or(l, |(n, b)| match n.trim().parse::<u64>() {
                Ok(_) => b,
                Err(_) => l,
            });
        ["CIRC ", "MoveC ", "C P[", ":"]
            .iter()
            .any(|m| body.trim_start().starts_with(m))
    };
    let mut j = 0;
    let (mut wrench, mut bound) = (0.0f64, 0.0f64);
    let (mut arc_wrench, mut arc_bound) = (0.0f64, 0.0f64);
    let mut shared = 0;
    for (p, r) in robot.points.iter().zip(&robot.results) {
        let found = (j..reference.results.len())
            .find(|&k| (reference.results[k].q - r.q).amax() < 1e-6)
            .unwrap_or_else(|| panic!("a target of line {} off the G-code's path", p.line));
        j = found + 1;
        if circular(p.line) {
            arc_wrench = arc_wrench.max((reference.points[found].wrench - p.wrench).amax());
            let b = (reference.results[found].budget.bound - r.budget.bound).abs();
            arc_bound = arc_bound.max(b);
            continue;
        }
        shared += 1;
        wrench = wrench.max((reference.points[found].wrench - p.wrench).amax());
        bound = bound.max((reference.results[found].budget.bound - r.budget.bound).abs());
    }
    assert!(
        shared > robot.points.len() / 2,
        "{shared} of {}",
        robot.points.len()
    );
    (wrench, bound, arc_wrench, arc_bound)
}

/// The milling example's pocket with each arc a straight move to its end.
fn straight_pocket() -> String {
    (POCKET.lines())
        .map(|l| match l.strip_prefix("G3 ").or(l.strip_prefix("G2 ")) {
            Some(words) => {
                let kept: Vec<&str> = (words.split_whitespace())
                    .filter(|w| !w.starts_with(['I', 'J', 'K', 'R']))
                    .collect();
                format!("G1 {}\n", kept.join(" "))
            }
            None => format!("{l}\n"),
        })
        .collect()
}

/// The largest differences of the points' wrenches (N, Nm together) and bounds (m) between two
/// compensations of the same points.
fn differences(a: &Report, b: &Report) -> (f64, f64) {
    assert_eq!(a.points.len(), b.points.len());
    let wrench = (a.points.iter().zip(&b.points))
        .map(|(p, q)| (p.wrench - q.wrench).amax())
        .fold(0.0, f64::max);
    let bound = (a.results.iter().zip(&b.results))
        .map(|(r, s)| (r.budget.bound - s.budget.bound).abs())
        .fold(0.0, f64::max);
    (wrench, bound)
}

/// An INFORM job of `q` (rad, one posture per point), a joint move where `joint` says so, else
/// a linear one, its positions in pulses (100000 per degree).
fn inform(q: &[nalgebra::Vector6<f64>], joint: &[bool]) -> String {
    let mut text = format!(
        "/JOB\r\n//NAME POCKET\r\n//POS\r\n///NPOS {},0,0,0,0,0\r\n///TOOL 0\r\n///POSTYPE PULSE\r\n///PULSE\r\n",
        q.len()
    );
    for (i, q) in q.iter().enumerate() {
        let pulses: Vec<String> = (q.iter())
            .map(|v| format!("{:.0}", v.to_degrees() * 1e5))
            .collect();
        text += &format!("C{i:05}={}\r\n", pulses.join(","));
    }
    text += "//INST\r\n///DATE 2026/11/25 12:00\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\n'stiffid: pulses_per_deg = 100000 100000 100000 100000 100000 100000\r\nNOP\r\n";
    for (i, joint) in joint.iter().enumerate() {
        text += &match joint {
            true => format!("MOVJ C{i:05} VJ=20.00\r\n"),
            false => format!("MOVL C{i:05} V=30.0 CR=0.1\r\n"),
        };
    }
    text + "END\r\n"
}

/// The G-code `gcode` written as a `dialect` program by stiffid's writer, uncompensated (a
/// compensation under zero compliance: every target the G-code's nominal pose, Cartesian, with
/// its configuration).
fn written(c: &Cell, gcode: &'static str, dialect: Dialect) -> String {
    use stiffid::app::compensate::{self, Input};
    let zero = Compliance {
        h: c.compliance.h.map(|_| 0.0),
        covariance: None,
        prediction: None,
        ..c.compliance.clone()
    };
    let request = compensate::Request {
        names: Default::default(),
        setup: &c.setup,
        compliance: zero,
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "pocket.nc".into(),
            text: gcode,
            data: None,
            language: Language::GCode,
            process_name: "process.toml".into(),
            process: c.process.clone(),
            chord_tolerance: 1e-5,
            output: Language::Robot(dialect),
            out_name: format!("part.{}", Language::Robot(dialect).extension()),
            settings: Default::default(),
        },
        options: Options::for_setup(&c.setup),
    };
    let report = compensate::run(request, |_, _: &[_], _: &[_], _: &[_]| {
        Ok::<(), stiffid::Error>(())
    })
    .unwrap();
    crate::common::program_text(report.report.program.unwrap())
}

#[test]
fn the_pocket_gets_the_same_wrench_and_bound_in_every_language() {
    let (fanuc, kuka) = (fanuc(), kuka());
    let gcode = compensated(&fanuc, POCKET, Language::GCode);
    let g = machining::gcode::parse(POCKET, 1e-5).unwrap();
    let rapid: Vec<bool> = (g.points.iter())
        .map(|p| p.motion == machining::gcode::Motion::Rapid)
        .collect();
    // The joint moves (the approach and the retract) and the plunges carry no force; every
    // point of the walls carries the operation's.
    let force = |r: &Report, i: usize| r.points[i].wrench.fixed_rows::<3>(0).norm();
    assert!(rapid[0] && rapid[rapid.len() - 1]);
    let cuts = |r: &Report| {
        (0..r.points.len())
            .map(|i| force(r, i) > 1.0)
            .collect::<Vec<_>>()
    };
    let cut = cuts(&gcode);
    assert_eq!(
        cut.iter().filter(|c| **c).count(),
        rapid.len() - 4,
        "two rapids and two plunges cut nothing"
    );
    for i in [0, 1, rapid.len() - 1] {
        assert!(!cut[i], "point {i}");
    }
    let postures: Vec<_> = gcode.results.iter().map(|r| r.q).collect();
    let on_kuka = compensated(&kuka, POCKET, Language::GCode);
    let programs = [
        (
            &fanuc,
            written(&fanuc, POCKET, Dialect::FanucLs),
            Dialect::FanucLs,
        ),
        (&fanuc, inform(&postures, &rapid), Dialect::Inform),
        (&kuka, written(&kuka, POCKET, Dialect::Krl), Dialect::Krl),
        (
            &kuka,
            written(&kuka, POCKET, Dialect::Rapid),
            Dialect::Rapid,
        ),
    ];
    for (c, text, dialect) in &programs {
        let robot = compensated(c, text, Language::Robot(*dialect));
        let reference = match std::ptr::eq(*c, &kuka) {
            true => &on_kuka,
            false => &gcode,
        };
        let (wrench, bound, arc_wrench, arc_bound) = matched(reference, &robot, text);
        eprintln!(
            "{dialect:?} vs G-code: wrench {wrench:.3e} N, bound {:.3e} mm; on arcs {arc_wrench:.3e} N, {:.3e} mm",
            bound * 1e3,
            arc_bound * 1e3
        );
        assert!(
            arc_wrench < ARC_N && arc_bound < ARC_M,
            "{dialect:?} on arcs: {arc_wrench} N, {arc_bound} m"
        );
        // INFORM states whole pulses (1e-5 deg); the others 9 decimals of mm and deg.
        let (n, m) = match dialect {
            Dialect::Inform => (0.1, 1e-7),
            _ => (1e-6, 1e-12),
        };
        assert!(wrench < n, "{dialect:?}: {wrench} N");
        assert!(bound < m, "{dialect:?}: {bound} m");
    }
    // The shipped programs are the G-code written for a robot of stiffness 1e10 Nm/rad (each
    // target within 0.2 um of the nominal pose): the same wrench to 0.01 N and bound to 2e-9 m.
    let shipped = [
        (
            &fanuc,
            &gcode,
            include_str!("../../../../examples/milling/pocket.ls"),
            Dialect::FanucLs,
        ),
        (&kuka, &on_kuka, crate::common::pocket_krl(), Dialect::Krl),
        (
            &kuka,
            &on_kuka,
            include_str!("../../../../examples/milling/pocket.mod"),
            Dialect::Rapid,
        ),
    ];
    for (c, reference, text, dialect) in shipped {
        let robot = compensated(c, text, Language::Robot(dialect));
        let (wrench, bound, arc_wrench, arc_bound) = matched(reference, &robot, text);
        eprintln!(
            "shipped {dialect:?} vs G-code: wrench {wrench:.3e} N, bound {:.3e} mm; on arcs {arc_wrench:.3e} N, {:.3e} mm",
            bound * 1e3,
            arc_bound * 1e3
        );
        assert!(
            arc_wrench < ARC_N && arc_bound < ARC_M,
            "shipped {dialect:?} on arcs: {arc_wrench} N, {arc_bound} m"
        );
        assert!(wrench < 1e-2, "shipped {dialect:?}: {wrench} N");
        assert!(bound < 2e-9, "shipped {dialect:?}: {bound} m");
    }
}

/// Two slots 4 mm deep joined by rapids in the air: a plunge, a cut along X, a rapid up, a
/// rapid across to the second slot, a plunge and a cut back.
const SLOTS: &str = "(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90 G17\nG0 X0 Y-50 Z5\n\
    G1 Z-4 F300\nG1 X25 F1800\nG1 X50\nG0 Z5\nG0 X50 Y50\nG1 Z-4 F300\nG1 X25 F1800\nG1 X0\n\
    G0 Z50\n";

/// A milling program written as LS (FANUC cell), KRL and RAPID (KUKA cell) by stiffid, read back
/// and compensated, gets the G-code's wrench (to 1e-9 N) and bound (to 1e-12 m) at every point:
/// the operation's force along the slots, none at the plunges and the rapids (the joint moves
/// `J`, `PTP`, `MoveJ`), the one across between the slots included.
#[test]
fn rapids_between_cuts_cut_nothing_in_every_language() {
    let (fanuc, kuka) = (fanuc(), kuka());
    let g = machining::gcode::parse(SLOTS, 1e-5).unwrap();
    // Where the tool cuts: the feeds across the tool axis (not the plunges).
    let cuts: Vec<bool> = (0..g.points.len())
        .map(|i| {
            let p = &g.points[i];
            let lateral = i > 0 && (p.position.z - g.points[i - 1].position.z).abs() < 1e-12;
            p.motion == machining::gcode::Motion::Feed && lateral
        })
        .collect();
    assert_eq!(cuts.iter().filter(|c| **c).count(), 4);
    for (c, dialect) in [
        (&fanuc, Dialect::FanucLs),
        (&kuka, Dialect::Krl),
        (&kuka, Dialect::Rapid),
    ] {
        let gcode = compensated(c, SLOTS, Language::GCode);
        let text = written(c, SLOTS, dialect);
        let robot = compensated(c, &text, Language::Robot(dialect));
        for r in [&gcode, &robot] {
            // The spindle's weight (the KUKA's; the same force at every point).
            let weight = r.points[0].wrench.fixed_rows::<3>(0).into_owned();
            for (i, p) in r.points.iter().enumerate() {
                let force = (p.wrench.fixed_rows::<3>(0) - weight).norm();
                match cuts[i] {
                    true => assert!(force > 100.0, "{dialect:?} {i}: {force} N"),
                    false => assert!(force < 1e-9, "{dialect:?} {i}: {force} N"),
                }
            }
        }
        let (wrench, bound) = differences(&gcode, &robot);
        eprintln!(
            "slots {dialect:?} vs G-code: wrench {wrench:.3e} N, bound {:.3e} mm",
            bound * 1e3
        );
        assert!(wrench < 1e-9, "{dialect:?}: {wrench} N");
        assert!(bound < 1e-12, "{dialect:?}: {bound} m");
    }
}

/// A drilling program: a `G81` hole 8 mm deep and a `G83` hole 30 mm deep in pecks of 12 mm,
/// both from `R` 2 mm above the part's surface (`Z = 0`), returning to the level they started from.
const DRILLING: &str = "(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90 G17\nG0 X0 Y0 Z20\n\
    G81 X20 Y10 Z-8 R2 F120\nG80\nG0 X-20 Y10 Z20\nG83 X-20 Y10 Z-30 R2 Q12 F120\nG80\nG0 Z50\n";

/// The drilling example's panel: 20 holes drilled by `G1` from 5 mm above a curved panel, the
/// tool tilted by `A` to each hole's normal.
const PANEL: &str = include_str!("../../../../examples/milling/panel.nc");

/// Drilling programs written as LS (FANUC cell), KRL and RAPID (KUKA cell) by stiffid, and as an
/// INFORM job of the G-code's postures (FANUC cell), read back and compensated, get the G-code's
/// wrench (to 1e-9 N), bound (to 1e-12 m) and compensated posture (to 1e-10 rad) at every point
/// (INFORM's whole pulses: 1e-3 N, 1e-10 m, 1e-6 rad): the thrust (600 N up the spindle) from
/// where the drill meets the part (its surface, or the depth a peck reached: stated twice,
/// reached unloaded then under the thrust) to each feed's end, none at a cycle's `R` level, on
/// the feed from there to the surface, a peck's re-approach or re-entry, an approach or a
/// retract. The cycles:
/// [`DRILLING`]; the panel ([`PANEL`], LS only).
#[test]
fn a_drilling_program_gets_the_thrust_where_the_drill_cuts_in_every_language() {
    let (fanuc, kuka) = (drilling(fanuc()), drilling(kuka()));
    let g = machining::gcode::parse(DRILLING, 1e-5).unwrap();
    let at = |z: f64| {
        let level = |p: &&machining::gcode::Point| (p.position.z - z).abs() < 1e-12;
        g.points.iter().filter(level).count()
    };
    assert_eq!(at(2e-3), 4, "R: once per hole, once per peck's retract");
    assert_eq!(at(-10e-3 + 0.254e-3), 1, "a peck's re-approach");
    let programs = [
        (&fanuc, DRILLING, Dialect::FanucLs),
        (&kuka, DRILLING, Dialect::Krl),
        (&kuka, DRILLING, Dialect::Rapid),
        (&fanuc, DRILLING, Dialect::Inform),
        (&fanuc, PANEL, Dialect::FanucLs),
    ];
    for (c, program, dialect) in programs {
        let g = machining::gcode::parse(program, 1e-5).unwrap();
        // Where the drill cuts: where it meets the part, stated again by a feed of no length
        // (the cycle's point under thrust), and the feeds below the part's surface to a point no
        // feed reached before (the R level, the re-approaches, 0.254 mm above the depth reached,
        // and the retracts are rapids; the feed from R to the surface and a peck's re-entry to
        // the depth reached move in the air or the hole drilled).
        let feed = |p: &machining::gcode::Point| p.motion == machining::gcode::Motion::Feed;
        let cuts: Vec<bool> = (g.points.iter().enumerate())
            .map(|(i, p)| {
                let again = g.points[..i]
                    .iter()
                    .any(|q| feed(q) && (q.position - p.position).norm() < 1e-12);
                let repeated =
                    i > 0 && feed(&g.points[i - 1]) && g.points[i - 1].position == p.position;
                let below = p.position.z <= 1e-12 && !again;
                let surface = program == DRILLING && p.position.z.abs() < 1e-12;
                feed(p) && (repeated || (below && !surface))
            })
            .collect();
        if program == DRILLING {
            let depths: Vec<f64> = (g.points.iter().zip(&cuts))
                .filter(|(_, c)| **c)
                .map(|(p, _)| (p.position.z * 1e3).round())
                .collect();
            assert_eq!(depths, [0.0, -8.0, 0.0, -10.0, -10.0, -22.0, -22.0, -30.0]);
        } else {
            assert_eq!(cuts.iter().filter(|c| **c).count(), 20);
        }
        let gcode = compensated(c, program, Language::GCode);
        let text = match dialect {
            // An INFORM job of the G-code's postures: `MOVJ` for its rapids, else `MOVL`.
            Dialect::Inform => {
                let rapid: Vec<bool> = (g.points.iter())
                    .map(|p| p.motion == machining::gcode::Motion::Rapid)
                    .collect();
                let postures: Vec<_> = gcode.results.iter().map(|r| r.q).collect();
                inform(&postures, &rapid)
            }
            _ => written(c, program, dialect),
        };
        let robot = compensated(c, &text, Language::Robot(dialect));
        for r in [&gcode, &robot] {
            // The spindle's weight (the KUKA's; the same force at every point).
            let weight = r.points[0].wrench.fixed_rows::<3>(0).into_owned();
            for (i, p) in r.points.iter().enumerate() {
                let thrust = p.wrench.fixed_rows::<3>(0) - weight;
                let tool_z = r.results[i].pose.rotation * nalgebra::Vector3::z();
                let up = -thrust.dot(&tool_z);
                let expected = if cuts[i] { 600.0 } else { 0.0 };
                assert!((up - expected).abs() < 1e-9, "{dialect:?} {i}: {up} N");
                assert!(
                    thrust.norm() - up.abs() < 1e-9,
                    "{dialect:?} {i}: along the axis"
                );
                assert_eq!(r.operations[i].is_some(), cuts[i], "{dialect:?} {i}");
            }
        }
        let (wrench, bound) = differences(&gcode, &robot);
        let posture = (gcode.results.iter().zip(&robot.results))
            .map(|(a, b)| (a.q_compensated - b.q_compensated).amax())
            .fold(0.0, f64::max);
        eprintln!(
            "drilling {dialect:?} vs G-code ({} points): wrench {wrench:.3e} N, bound {:.3e} mm, compensated posture {posture:.3e} rad",
            g.points.len(),
            bound * 1e3
        );
        // INFORM states whole pulses (1e-5 deg); the others 9 decimals of mm and deg.
        let (n, m, rad) = match dialect {
            Dialect::Inform => (1e-3, 1e-10, 1e-6),
            _ => (1e-9, 1e-12, 1e-10),
        };
        assert!(wrench < n, "{dialect:?}: {wrench} N");
        assert!(bound < m, "{dialect:?}: {bound} m");
        assert!(posture < rad, "{dialect:?}: {posture} rad");
    }
}

/// The place request of `program` on `c`.
fn request<'a>(c: &'a Cell, options: &'a Options, program: &'a Program) -> Request<'a> {
    Request {
        setup: &c.setup,
        setup_text: c.text,
        compliance: &c.compliance,
        work: Work::Program {
            program,
            process: &c.process,
        },
        options,
        region: Region {
            x: [1.8, 2.2],
            y: [-0.2, 0.2],
            rotation: [0.0, 0.0],
            free: None,
        },
        objective: Aggregate::Max,
        margin: 1f64.to_radians(),
        max_condition: 1000.0,
        effort: Request::EFFORT,
    }
}

/// `place` evaluates the KRL and RAPID pockets (Cartesian targets in the part frame, `$BASE` and
/// the work object) as the G-code they were written from: the same peak and mean of the bounds at
/// the own placement and at two others.
#[test]
fn place_evaluates_a_robot_program_as_its_gcode() {
    let c = kuka();
    let options = Options::for_setup(&c.setup);
    // The pocket with straight corners: every point of the G-code a target of the programs
    // (an arc's chord points would be left out of a circular move).
    let straight: &'static str = Box::leak(straight_pocket().into_boxed_str());
    let gcode = machining::read(straight, Language::GCode, 1e-5).unwrap();
    let programs = [
        (written(&c, straight, Dialect::Krl), Dialect::Krl),
        (written(&c, straight, Dialect::Rapid), Dialect::Rapid),
    ];
    let own = *c.setup.workpiece().unwrap();
    for (text, dialect) in programs {
        let robot = machining::read(&text, Language::Robot(dialect), 1e-5).unwrap();
        for dx in [0.0, 0.05, -0.1] {
            let pose = Isometry3::translation(dx, 0.5 * dx, 0.0) * own;
            let a = place::evaluate(&request(&c, &options, &gcode), &pose);
            let b = place::evaluate(&request(&c, &options, &robot), &pose);
            let (a, b) = (a.unwrap().unwrap(), b.unwrap().unwrap());
            let mean = |e: &place::Evaluation| e.sum / e.points as f64;
            eprintln!(
                "place {dialect:?} at dx {dx}: peak {:.9} vs {:.9} mm, mean {:.9} vs {:.9} mm",
                a.peak * 1e3,
                b.peak * 1e3,
                mean(&a) * 1e3,
                mean(&b) * 1e3
            );
            assert!((a.peak - b.peak).abs() < 1e-10, "{} vs {}", a.peak, b.peak);
            assert!((mean(&a) - mean(&b)).abs() < 1e-10);
        }
    }
}
