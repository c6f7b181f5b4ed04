//! A robot program's programmed speeds: the milling example's KRL, RAPID and LS programs, written
//! from `pocket.nc`, read back on their cells and state the G-code's feed of every move (the
//! readers give it back, move by move); an LS program's speeds time its moves in the compensate
//! job, whose free tool rotation then keeps every joint within its largest speed (checked from
//! the postures the job returns, against the distances and speeds of the program's own
//! targets); a KRL speed stiffid does not read is counted and named in a warning; a speed out of
//! range is refused naming the line.

use nalgebra::Vector6;
use stiffid::app::compensate::{self, Input, Report};
use stiffid::internal::machining::compensate::{
    Compensated, Free, FreeVariables, Objective, Options, PathPoint,
};
use stiffid::internal::machining::dynamics::Dynamics;
use stiffid::internal::machining::gcode::{self, Motion};
use stiffid::internal::machining::program::speed::Speed;
use stiffid::internal::machining::program::{self, Dialect};
use stiffid::internal::machining::{Language, Program};
use stiffid::internal::robot::ik::tool_pose;
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Error, Setup};

const POCKET: &str = include_str!("../../../../examples/milling/pocket.nc");
const LS: &str = include_str!("../../../../examples/milling/pocket.ls");
const KUKA: &str = include_str!("../../../../examples/milling/kuka-milling.toml");
const PROCESS: &str = include_str!("../../../../examples/milling/aluminium.toml");

#[test]
fn the_written_programs_state_the_feed_of_every_move() {
    let g = gcode::parse(POCKET, 1e-5).unwrap();
    let programs = [
        (crate::common::pocket_krl(), Dialect::Krl),
        (
            include_str!("../../../../examples/milling/pocket.mod"),
            Dialect::Rapid,
        ),
        (LS, Dialect::FanucLs),
    ];
    for (text, dialect) in programs {
        let p = program::parse(text, dialect).unwrap();
        // One target per point but for the chord points of the arcs written as circular moves.
        assert!(p.targets.len() < g.points.len(), "{dialect:?}");
        // Read back on its cell: the RAPID wrist sits on a quadrant boundary (axis 4 at 0).
        let case = match dialect {
            Dialect::FanucLs => ls(),
            _ => krl(String::new()),
        };
        let (s, read) = (cell(&case, None), Program::Robot(p.clone()));
        let resolved =
            stiffid::internal::machining::resolve(&read, &s, None, &Options::for_setup(&s));
        assert!(resolved.is_ok(), "{dialect:?}: {:?}", resolved.err());
        // The speeds in path order, each run of one speed once: the G-code's rapids and feeds.
        let runs = |speeds: Vec<Option<f64>>| {
            let mut out: Vec<Option<f64>> = Vec::new();
            for v in speeds {
                if out.last() != Some(&v) {
                    out.push(v);
                }
            }
            out
        };
        let want = runs(
            (g.points.iter())
                .map(|point| match point.motion {
                    Motion::Rapid => None,
                    Motion::Feed => point.feed,
                })
                .collect(),
        );
        let got = runs(
            (p.targets.iter())
                .map(|t| match &t.speed {
                    Speed::Joint => None,
                    Speed::Path(v) => Some(*v),
                    other => panic!("{dialect:?} line {}: {other:?}", t.line),
                })
                .collect(),
        );
        assert_eq!(got.len(), want.len(), "{dialect:?}");
        for (a, b) in got.iter().zip(&want) {
            assert_eq!(a.is_some(), b.is_some(), "{dialect:?}");
            assert!(
                (a.unwrap_or(0.0) - b.unwrap_or(0.0)).abs() < 1e-12,
                "{dialect:?}"
            );
        }
    }
}

/// A milling example's program on its cell: the setup file's text and name, its stiffness, the
/// program's text, dialect and file name.
struct Case {
    setup: (&'static str, &'static str),
    stiffness: &'static str,
    program: (String, Dialect, &'static str),
}

/// The KRL pocket on the KUKA KR 210 cell.
fn krl(text: String) -> Case {
    Case {
        setup: (KUKA, "kuka-milling.toml"),
        stiffness: include_str!("../../../../examples/milling/kuka-stiffness.json"),
        program: (text, Dialect::Krl, "pocket.src"),
    }
}

/// The LS pocket on the FANUC R-2000iC/165F cell.
fn ls() -> Case {
    Case {
        setup: (
            include_str!("../../../../examples/milling/fanuc-milling.toml"),
            "fanuc-milling.toml",
        ),
        stiffness: include_str!("../../../../examples/milling/stiffness.json"),
        program: (LS.to_string(), Dialect::FanucLs, "pocket.ls"),
    }
}

/// The case's cell with every joint's largest speed `deg_s` (none: no limit).
fn cell(case: &Case, deg_s: Option<f64>) -> Setup {
    let (text, name) = case.setup;
    let limits = deg_s.map_or(String::new(), |v| {
        format!("max_speed_deg_s = [{v}, {v}, {v}, {v}, {v}, {v}]\n")
    });
    let text = text.replacen("\nrobot = ", &format!("\n{limits}robot = "), 1);
    setup::parse(&text, name, |r, _| presets::get(r)).unwrap()
}

/// The nominal postures of a path (rad): the program's own, and those the job chose.
type Postures = [Vec<Vector6<f64>>; 2];

/// The case's program compensated on `s` with the tool rotation free (+-30 deg, at most 2 deg
/// between points): the report and the nominal postures of every point.
fn rotated(case: &Case, s: &Setup) -> Result<(Report, Postures), Error> {
    let options = Options {
        free: FreeVariables {
            free: vec![Free::ToolRotation(crate::compensate::rotation(30.0, 2.0))],
            minimise: Objective::Deflection,
            ..FreeVariables::default()
        },
        ..Options::for_setup(s)
    };
    let (text, dialect, name) = &case.program;
    let stiffness = stiffid::internal::io::stiffness::parse(case.stiffness).unwrap();
    let request = compensate::Request {
        names: Default::default(),
        setup: s,
        compliance: stiffness.compliance(s.model()).unwrap(),
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: name.to_string(),
            text,
            data: None,
            language: Language::Robot(*dialect),
            process_name: "aluminium.toml".into(),
            process: stiffid::internal::machining::process::file::parse(PROCESS, "aluminium.toml")
                .unwrap(),
            chord_tolerance: 1e-5,
            output: Language::Robot(*dialect),
            out_name: name.to_string(),
            settings: Default::default(),
        },
        options,
    };
    let (mut own, mut chosen) = (Vec::new(), Vec::new());
    let report = compensate::run(
        request,
        |_, _: &[PathPoint], r: &[Compensated], _: &[Dynamics]| {
            own.extend(r.iter().map(|r| r.q_before.unwrap_or(r.q)));
            chosen.extend(r.iter().map(|r| r.q));
            Ok::<(), Error>(())
        },
    )?;
    Ok((report.report, [own, chosen]))
}

/// Each move's highest share of a joint's largest speed of 1 deg/s along the postures `q` (rad)
/// of the case's program's targets, timed by the program's own TCP distance and speed (`None`
/// for a move without a path speed).
fn shares(case: &Case, s: &Setup, q: &[Vector6<f64>]) -> Vec<Option<f64>> {
    let (text, dialect, _) = &case.program;
    let p = Program::Robot(program::parse(text, *dialect).unwrap());
    let options = Options::for_setup(s);
    let resolved = stiffid::internal::machining::resolve(&p, s, None, &options).unwrap();
    let Program::Robot(p) = resolved.into_owned() else {
        unreachable!()
    };
    let tcp = |t: &program::JointTarget| {
        let q = Vector6::from(t.q_deg).map(f64::to_radians);
        tool_pose(&s.robot().frames(&q), &s.tool().tcp)
            .translation
            .vector
    };
    (1..p.targets.len())
        .map(|i| {
            let Speed::Path(v) = p.targets[i].speed else {
                return None;
            };
            let dt = (tcp(&p.targets[i]) - tcp(&p.targets[i - 1])).norm() / v;
            Some((q[i] - q[i - 1]).abs().max() / (1f64.to_radians() * dt))
        })
        .collect()
}

/// The highest share (at 1 deg/s) of the moves the free rotation chose away from the
/// program's own (either end rotated: the dynamic programming could refuse them).
fn highest_chosen(case: &Case, s: &Setup, [own, chosen]: &Postures) -> f64 {
    let moved = |i: usize| own[i] != chosen[i] || own[i + 1] != chosen[i + 1];
    let shares = shares(case, s, chosen).into_iter().enumerate();
    shares
        .filter(|(i, _)| moved(*i))
        .filter_map(|(_, v)| v)
        .fold(0.0, f64::max)
}

#[test]
fn a_joint_speed_binds_the_free_rotation_of_a_robot_program() {
    let case = ls();
    let (free, q) = rotated(&case, &cell(&case, None)).unwrap();
    assert!(!free.speed_limits.checked);
    // A limit below the free optimum's fastest chosen move: the limit must move the choice.
    let deg_s = 0.8 * highest_chosen(&case, &cell(&case, None), &q);
    let s = cell(&case, Some(deg_s));
    let (limited, q) = rotated(&case, &s).unwrap();
    assert!(limited.speed_limits.checked);
    assert_eq!(limited.speed_limits.moves_not_read, 0);
    let share = highest_chosen(&case, &s, &q) / deg_s;
    assert!(share <= 1.0 + 1e-9, "{share}");
    assert!(limited.feasibility.unwrap().moves_refused_speed > 0);
    // The document's own shares are the program's own postures' (at the limit).
    let own = shares(&case, &s, &q[0]).into_iter().flatten();
    let own = own.fold(0.0, f64::max) / deg_s;
    let doc = limited.speed_limits.axes.iter();
    let documented = doc.filter_map(|a| a.own_highest_share).fold(0.0, f64::max);
    assert!(
        (documented - own).abs() < 1e-9 * own,
        "{documented} vs {own}"
    );
}

#[test]
fn unread_speeds_are_counted_and_bad_ones_refused_naming_the_line() {
    let unread =
        krl(crate::common::pocket_krl().replacen("$VEL.CP = 0.03\n", "$VEL.CP = vcut\n", 1));
    let s = cell(&unread, Some(30.0));
    let (r, _) = rotated(&unread, &s).unwrap();
    assert!(r.speed_limits.checked);
    let line = 1 + crate::common::pocket_krl()
        .lines()
        .position(|l| l == "$VEL.CP = 0.03")
        .unwrap() as u64;
    // Its moves: each LIN a target, each CIRC two (its via point and end).
    let after = crate::common::pocket_krl()
        .lines()
        .skip(line as usize)
        .take_while(|l| l.starts_with("LIN") || l.starts_with("CIRC"))
        .map(|l| 1 + usize::from(l.starts_with("CIRC")));
    assert_eq!(r.speed_limits.moves_not_read, after.sum::<usize>());
    let w = r
        .warnings
        .iter()
        .find(|w| w.kind.code() == "speed")
        .unwrap();
    assert!(
        w.message
            .contains(&format!("line {line} sets $VEL.CP to 'vcut'")),
        "{w}"
    );
    for bad in ["-1", "0", "11", "nan"] {
        let text = crate::common::pocket_krl().replacen(
            "$VEL.CP = 0.03\n",
            &format!("$VEL.CP = {bad}\n"),
            1,
        );
        match rotated(&krl(text), &s) {
            Err(e) => {
                let e = e.to_string();
                assert!(
                    e.contains("pocket.src") && e.contains(&format!("line {line}")),
                    "{bad}: {e}"
                );
            }
            Ok((r, _)) => {
                assert_eq!(bad, "nan", "{bad} accepted");
                assert!(r.speed_limits.moves_not_read > 0);
            }
        }
    }
    // 1e308 m/s is no number of mm/s: the message said "a path speed of inf mm/s".
    let text = crate::common::pocket_krl().replacen("$VEL.CP = 0.03\n", "$VEL.CP = 1e308\n", 1);
    let e = rotated(&krl(text), &s).unwrap_err().to_string();
    assert!(
        e.contains(&format!("line {line}"))
            && e.contains("$VEL.CP = 1e308 m/s: a path speed of more than any number of mm/s; expected one in (0, 10000] mm/s"),
        "{e}"
    );
}
