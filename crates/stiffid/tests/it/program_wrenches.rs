//! The process wrench where the tool cuts, in every program language: the milling example's
//! pocket as G-code (`pocket.nc`) and as the robot programs written from it (`pocket.ls` on the
//! FANUC cell, `pocket.src` and `pocket.mod` on the KUKA cell, and an INFORM job of the G-code's
//! own postures) gets the same wrench (to 1 N) and the same error bound (to 1 um) at every point:
//! the joint moves, the plunges and the retracts none, the cutting moves the operation's. `place`
//! evaluates the KRL program as its G-code. A drill's retract and a move across its axis cut
//! nothing, in G-code and robot programs alike.

use nalgebra::Isometry3;
use stiffid::app::place::{self, Region, Request, Work};
use stiffid::machining::compensate::{Aggregate, Compliance, Options};
use stiffid::machining::process::{file, Process};
use stiffid::machining::program::Dialect;
use stiffid::machining::{self, Language, Program, Report};
use stiffid::robot::presets;
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

fn cell(text: &'static str, name: &str, stiffness: &str) -> Cell {
    let setup = stiffid::setup::parse(text, name, |r, _| presets::get(r)).unwrap();
    let compliance = stiffid::io::stiffness::parse(stiffness)
        .unwrap()
        .compliance(setup.model())
        .unwrap();
    let process = file::parse(
        include_str!("../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
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

/// `POCKET` written as a `dialect` program by stiffid's writer, uncompensated (a compensation
/// under zero compliance: every target the G-code's nominal pose, Cartesian, with its
/// configuration).
fn written(c: &Cell, dialect: Dialect) -> String {
    use stiffid::app::compensate::{self, Input};
    let zero = Compliance {
        h: c.compliance.h.map(|_| 0.0),
        covariance: None,
        prediction: None,
        ..c.compliance.clone()
    };
    let request = compensate::Request {
        setup: &c.setup,
        compliance: zero,
        input: Input::Program {
            name: "pocket.nc".into(),
            text: POCKET,
            language: Language::GCode,
            process_name: "aluminium.toml".into(),
            process: c.process.clone(),
            chord_tolerance: 1e-5,
            output: Language::Robot(dialect),
            out_name: format!("pocket.{}", Language::Robot(dialect).extension()),
            settings: Default::default(),
        },
        options: Options::for_setup(&c.setup),
    };
    let report = compensate::run(request, |_, _: &[_], _: &[_], _: &[_]| {
        Ok::<(), stiffid::Error>(())
    })
    .unwrap();
    report.program.unwrap().text
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
        (&fanuc, written(&fanuc, Dialect::FanucLs), Dialect::FanucLs),
        (&fanuc, inform(&postures, &rapid), Dialect::Inform),
        (&kuka, written(&kuka, Dialect::Krl), Dialect::Krl),
        (&kuka, written(&kuka, Dialect::Rapid), Dialect::Rapid),
    ];
    for (c, text, dialect) in &programs {
        let robot = compensated(c, text, Language::Robot(*dialect));
        let reference = match std::ptr::eq(*c, &kuka) {
            true => &on_kuka,
            false => &gcode,
        };
        let (wrench, bound) = differences(reference, &robot);
        eprintln!(
            "{dialect:?} vs G-code: wrench {wrench:.3e} N, bound {:.3e} mm",
            bound * 1e3
        );
        assert!(wrench < 1.0, "{dialect:?}: {wrench} N");
        assert!(bound < 1e-6, "{dialect:?}: {bound} m");
    }
    // The shipped programs are the G-code written uncompensated (the targets to 9 decimals):
    // the same wrench to 1 N and bound to 2 um at every point.
    let shipped = [
        (
            &fanuc,
            &gcode,
            include_str!("../../../../examples/milling/pocket.ls"),
            Dialect::FanucLs,
        ),
        (
            &kuka,
            &on_kuka,
            include_str!("../../../../examples/milling/pocket.src"),
            Dialect::Krl,
        ),
        (
            &kuka,
            &on_kuka,
            include_str!("../../../../examples/milling/pocket.mod"),
            Dialect::Rapid,
        ),
    ];
    for (c, reference, text, dialect) in shipped {
        let robot = compensated(c, text, Language::Robot(dialect));
        let (wrench, bound) = differences(reference, &robot);
        eprintln!(
            "shipped {dialect:?} vs G-code: wrench {wrench:.3e} N, bound {:.3e} mm",
            bound * 1e3
        );
        assert!(wrench < 1.0, "shipped {dialect:?}: {wrench} N");
        assert!(bound < 2e-6, "shipped {dialect:?}: {bound} m");
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

/// `place` evaluates the KRL pocket (Cartesian targets in the part frame `$BASE`) as the G-code
/// it was written from: the same peak and sum of the bounds at the own placement and at two
/// others.
#[test]
fn place_evaluates_a_robot_program_as_its_gcode() {
    let c = kuka();
    let options = Options::for_setup(&c.setup);
    let gcode = machining::read(POCKET, Language::GCode, 1e-5).unwrap();
    let krl = include_str!("../../../../examples/milling/pocket.src");
    let krl = machining::read(krl, Language::Robot(Dialect::Krl), 1e-5).unwrap();
    let own = *c.setup.workpiece().unwrap();
    for dx in [0.0, 0.05, -0.1] {
        let pose = Isometry3::translation(dx, 0.5 * dx, 0.0) * own;
        let a = place::evaluate(&request(&c, &options, &gcode), &pose);
        let b = place::evaluate(&request(&c, &options, &krl), &pose);
        let (a, b) = (a.unwrap().unwrap(), b.unwrap().unwrap());
        eprintln!(
            "place at dx {dx}: peak {:.6} vs {:.6} mm",
            a.peak * 1e3,
            b.peak * 1e3
        );
        assert!((a.peak - b.peak).abs() < 1e-6, "{} vs {}", a.peak, b.peak);
        let mean = |e: &place::Evaluation| e.sum / e.points as f64;
        assert!((mean(&a) - mean(&b)).abs() < 1e-6);
    }
}
