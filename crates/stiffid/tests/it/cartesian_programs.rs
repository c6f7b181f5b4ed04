//! Cartesian robot programs (KRL `E6POS`, RAPID `robtarget`, LS Cartesian positions): the
//! configuration data choose the inverse-kinematics solution, a compensated program equals the
//! path file of the same poses, placement moves the targets as it moves a G-code program's, and
//! what cannot be read is refused naming the line.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::app::place::{self, Effort, Region, Request, Work};
use stiffid::internal::machining::compensate::{self, Aggregate, Options};
use stiffid::internal::machining::program::generate::{
    generate, Move, Plan, Settings, Target, Tool,
};
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::{ik, presets};
use stiffid::{Error, Setup};

const SETUP: &str = include_str!("../../../../examples/milling/fanuc-milling.toml");
const PROCESS: &str = include_str!("../../../../examples/milling/aluminium.toml");

fn setup() -> Setup {
    stiffid::internal::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap()
}

fn compliance(s: &Setup) -> compensate::Compliance {
    stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(s.model())
    .unwrap()
}

fn process() -> stiffid::internal::machining::process::Process {
    stiffid::internal::machining::process::file::parse(PROCESS, "aluminium.toml").unwrap()
}

/// A straight cut along the part's x at depth 4 mm, the tool down the part's -z: `n` poses
/// 10 mm apart, part frame.
fn cut(n: usize) -> Vec<Isometry3<f64>> {
    let down = UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    (0..n)
        .map(|i| Isometry3::from_parts(Translation3::new(0.01 * i as f64, 0.0, -0.004), down))
        .collect()
}

/// The program stiffid writes for the part-frame poses `poses` on `s` (the postures by inverse
/// kinematics from the setup's start), every move a cutting one (KRL `LIN`), or the first a
/// joint one (`rapid_first`): its targets and its text.
fn written(
    s: &Setup,
    dialect: Dialect,
    poses: &[Isometry3<f64>],
    rapid_first: bool,
) -> (Vec<Target>, String) {
    let (robot, tcp, part) = (s.robot(), s.tool().tcp, *s.workpiece().unwrap());
    let mut q = Options::for_setup(s).q0;
    let targets: Vec<Target> = poses
        .iter()
        .map(|p| {
            q = ik::solve(robot, &tcp, &(part * p), &q, &ik::Options::default())
                .unwrap()
                .q;
            Target::new(robot, &tcp, &q)
        })
        .collect();
    let mut moves = vec![Move::Feed(0.03); targets.len()];
    if rapid_first {
        moves[0] = Move::Rapid;
    }
    let plan = Plan {
        dialect,
        name: "CUT",
        targets: &targets,
        moves: &moves,
        tool: Tool {
            frame: Isometry3::from(Translation3::from(tcp)),
            payload: Some((10.0, Vector3::new(0.0, 0.0, 0.1))),
        },
        work: part,
        world: s.program_world(),
        external: None,
        approximation: 1e-5,
        numbers: Default::default(),
        pulses: None,
        settings: Settings::default(),
    };
    let text = one_text(generate(&plan).unwrap().files.remove(0));
    (targets, text)
}

/// An LS program's positions put in user frame 1 instead of the world, the remark naming it
/// the part frame.
fn in_user_frame(s: &Setup, text: &str) -> String {
    named_part_frame(&positions_in_user_frame(s, text))
}

/// The remark naming user frame 1 the part frame, first in `/MN`.
fn named_part_frame(text: &str) -> String {
    text.replacen("/MN\n", "/MN\n   1:  ! stiffid: user_frame = 1 ;\n", 1)
}

/// An LS program's positions put in user frame 1 (the part's place) instead of the world, and
/// user frame 1 selected (`UFRAME_NUM=1`).
fn positions_in_user_frame(s: &Setup, text: &str) -> String {
    // The part frame in the controller's world (FANUC's, 670 mm above the setup's base frame).
    let part = s.program_world().inv_mul(s.workpiece().unwrap());
    // The world positions of the writer moved into the part frame: X, Y and Z less the part's
    // origin (the example's part frame is not turned).
    assert!(part.rotation.angle() < 1e-12);
    let o = part.translation.vector * 1e3;
    let mut out = String::new();
    for line in text.split_inclusive('\n') {
        let mut l = line
            .replace("UF : 0", "UF : 1")
            .replace("UFRAME_NUM=0", "UFRAME_NUM=1");
        if let Some(rest) = l.trim_start().strip_prefix("X = ") {
            let v: Vec<f64> = rest
                .split(['=', ','])
                .filter_map(|w| w.trim().trim_end_matches("mm").trim().parse().ok())
                .collect();
            l = format!(
                "\tX = {:.9} mm,\tY = {:.9} mm,\tZ = {:.9} mm,\n",
                v[0] - o.x,
                v[1] - o.y,
                v[2] - o.z
            );
        }
        out += &l;
    }
    out
}

/// A generated file as one text (a KRL program's points put back from its `.dat`): these tests
/// read and edit single files.
fn one_text(f: stiffid::internal::machining::program::generate::File) -> String {
    crate::common::inlined(&f.text, f.data.as_deref())
}

fn read(s: &Setup, dialect: Dialect, text: &str) -> Program {
    let p = machining::read(text, Language::Robot(dialect), 1e-4).unwrap();
    machining::resolve(&p, s, None, &Options::for_setup(s))
        .unwrap()
        .into_owned()
}

#[test]
fn a_program_with_a_byte_order_mark_reads_as_without_it() {
    let s = setup();
    for dialect in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
        let (targets, text) = written(&s, dialect, &cut(3), true);
        let Program::Robot(p) = read(&s, dialect, &format!("\u{feff}{text}")) else {
            panic!()
        };
        assert_eq!(p.targets.len(), targets.len(), "{dialect:?}");
        for (got, want) in p.targets.iter().zip(&targets) {
            let got = Vector6::from(got.q_deg);
            let want = Vector6::from(want.q_deg);
            assert!(
                (got - want).amax() <= read_back(dialect),
                "{dialect:?}: {got} {want}"
            );
        }
    }
}

#[test]
fn the_configuration_data_choose_the_solution_of_a_pose() {
    let s = setup();
    let poses = cut(2);
    for dialect in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
        let (targets, text) = written(&s, dialect, &poses, true);
        // The second target's wrist flipped: the same pose, the other solution, as the writer
        // states it for the posture (q4 + 180, -q5, q6 + 180) (PTP: KUKA reads S and T).
        let q = targets[1].q_deg;
        let twin = [q[0], q[1], q[2], q[3] - 180.0, -q[4], q[5] - 180.0];
        let robot = s.robot();
        let flipped = Target::new(
            robot,
            &s.tool().tcp,
            &Vector6::from(twin).map(f64::to_radians),
        );
        let (_, twin_text) = {
            let t = [targets[0].clone(), flipped];
            let moves = [Move::Rapid, Move::Rapid];
            let plan = Plan {
                dialect,
                name: "CUT",
                targets: &t,
                moves: &moves,
                tool: Tool {
                    frame: Isometry3::from(Translation3::from(s.tool().tcp)),
                    payload: Some((10.0, Vector3::new(0.0, 0.0, 0.1))),
                },
                work: *s.workpiece().unwrap(),
                world: s.program_world(),
                external: None,
                approximation: 1e-5,
                numbers: Default::default(),
                pulses: None,
                settings: Settings::default(),
            };
            ((), one_text(generate(&plan).unwrap().files.remove(0)))
        };
        for (text, want) in [(&text, q), (&twin_text, twin)] {
            let Program::Robot(p) = read(&s, dialect, text) else {
                panic!()
            };
            let got = Vector6::from(p.targets[1].q_deg);
            assert!(
                (got - Vector6::from(want)).amax() <= 1e-9,
                "{dialect:?}: {got} against {want:?}"
            );
        }
    }
}

#[test]
fn a_compensated_cartesian_program_equals_the_path_file_of_its_poses() {
    let s = setup();
    let (compliance, process) = (compliance(&s), process());
    let options = Options::for_setup(&s);
    let part = *s.workpiece().unwrap();
    let poses = cut(7);
    for dialect in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
        let (_, text) = written(&s, dialect, &poses, true);
        let program = read(&s, dialect, &text);
        let report =
            machining::compensate(s.arm(), None, &compliance, &program, &process, &options)
                .unwrap();
        // The path file: the same poses in the base frame with the wrenches the program's
        // points got from the process.
        let mut csv =
            String::from("x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm\n");
        for (pose, p) in poses.iter().zip(&report.points) {
            let pose = part * pose;
            let t = pose.translation.vector * 1e3;
            let (rx, ry, rz) = pose.rotation.euler_angles();
            let cells: Vec<String> = [
                t.x,
                t.y,
                t.z,
                rx.to_degrees(),
                ry.to_degrees(),
                rz.to_degrees(),
            ]
            .iter()
            .chain(p.wrench.iter())
            .map(|v| format!("{v:e}"))
            .collect();
            csv += &(cells.join(",") + "\n");
        }
        let points = machining::path::parse(&csv, Frame::Base).unwrap();
        let by_csv = compensate::path(s.arm(), &compliance, &points, &options).unwrap();
        // The compensated program read back: the controller moves to the compensated postures.
        let Program::Robot(back) = read(&s, dialect, &report.program) else {
            panic!()
        };
        for ((a, b), t) in report.results.iter().zip(&by_csv).zip(&back.targets) {
            let (qa, qb) = (
                a.q_compensated.map(f64::to_degrees),
                b.q_compensated.map(f64::to_degrees),
            );
            assert!((qa - qb).amax() <= 1e-9, "{dialect:?}: {qa} {qb}");
            // The written pose's decimals (RAPID's quaternion to 1e-9, about 1e-7 deg) bound
            // the axis angles read back.
            let back = (qa - Vector6::from(t.q_deg)).amax();
            assert!(back <= read_back(dialect), "{dialect:?}: {back} deg");
            // A cutting point moves; the first target, a joint move, cuts nothing.
            let moved = (qa - a.q.map(f64::to_degrees)).amax() > 1e-3;
            assert_eq!(moved, a.wrench.norm() > 0.0, "{dialect:?}");
        }
        assert_ne!(report.program, text);
        assert_eq!(report.program.lines().count(), text.lines().count());
    }
}

/// How close a written program's targets read back to the axis angles written, deg: the
/// written decimals of the pose (1e-9 mm and deg, RAPID's quaternion 1e-9) through the inverse
/// kinematics.
pub fn read_back(dialect: Dialect) -> f64 {
    match dialect {
        Dialect::Rapid => 1e-6,
        _ => 1e-8,
    }
}

/// `text` with `from` replaced by `to` once (which must be there).
fn replaced(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from} in {text}");
    text.replacen(from, to, 1)
}

/// Cartesian programs that cannot be read, each with its language, the line its refusal names
/// and what the refusal says: `krl`, `rapid` and `ls` as written, their targets changed;
/// `status` the first KRL target's (at line `first_krl`).
fn unreadable(
    (krl, rapid, ls): (&str, &str, &str),
    status: &str,
    first_krl: u64,
) -> Vec<(Dialect, String, u64, &'static str)> {
    let rapid_conf = rapid.lines().find(|l| l.contains("MoveJ")).unwrap();
    let conf = rapid_conf.split("],[").nth(2).unwrap();
    vec![
        // An unknown configuration.
        (
            Dialect::FanucLs,
            replaced(ls, "CONFIG : 'N", "CONFIG : 'X"),
            line_of(ls, "CONFIG"),
            "CONFIG 'X",
        ),
        // A pose out of reach in the configuration it names: axis 1 in its fourth quadrant.
        (
            Dialect::Rapid,
            replaced(
                rapid,
                &format!("],[{conf}],["),
                &format!("],[3{}],[", &conf[conf.find(',').unwrap()..]),
            ),
            line_of(rapid, "MoveJ"),
            "out of reach in the configuration [3,",
        ),
        // The shoulder behind axis 1 and the elbow down, out of reach in the joint limits.
        (
            Dialect::Krl,
            replaced(krl, status, "S 'B001'"),
            first_krl,
            "out of reach in the configuration S 'B001'",
        ),
        // A tool that is not the setup's.
        (
            Dialect::Krl,
            replaced(krl, "$TOOL = {X 6.9", "$TOOL = {X 16.9"),
            line_of(krl, "$TOOL ="),
            "is not the setup's",
        ),
        (
            Dialect::Rapid,
            replaced(
                rapid,
                "tooldata tspindle := [TRUE,[[6.9",
                "tooldata tspindle := [TRUE,[[7.9",
            ),
            line_of(rapid, "tooldata"),
            "is not the setup's",
        ),
        // A work object the robot holds, a base the controller holds.
        (
            Dialect::Rapid,
            replaced(rapid, "wobjdata wpart := [FALSE", "wobjdata wpart := [TRUE"),
            line_of(rapid, "wobjdata"),
            "wobjdata wpart: robhold TRUE: a work object the robot holds",
        ),
        (
            Dialect::Krl,
            krl.lines()
                .map(|l| match l.starts_with("$BASE") {
                    true => "$BASE = BASE_DATA[1]\n".to_string(),
                    false => format!("{l}\n"),
                })
                .collect(),
            line_of(krl, "$BASE ="),
            "frame number 1 of the controller's bases",
        ),
        // An LS user frame without a part frame is fine here (the setup has one); a RAPID tool
        // not declared is not.
        (
            Dialect::Rapid,
            rapid.replace("tspindle\\WObj", "tmill\\WObj"),
            line_of(rapid, "MoveJ"),
            "tooldata tmill: not declared",
        ),
        // A position or angle beyond the limits: 1e300 mm reached inverse kinematics as an
        // infinite distance ("inf mm away"), 1e300 deg was read as some orientation.
        (
            Dialect::FanucLs,
            replaced(
                ls,
                &format!("X = {} mm", first_value(ls, "X = ", " mm")),
                "X = 1e300 mm",
            ),
            position_line(ls, 0),
            "X 1e300: outside -100000 to 100000 mm",
        ),
        (
            Dialect::FanucLs,
            replaced(
                ls,
                &format!("R = {} deg", first_value(ls, "R = ", " deg")),
                "R = -1e300 deg",
            ),
            position_line(ls, 0),
            "R -1e300: outside -10000 to 10000 deg",
        ),
        (
            Dialect::Rapid,
            replaced(
                rapid,
                &format!("MoveJ [[{},", first_value(rapid, "MoveJ [[", ",")),
                "MoveJ [[1e300,",
            ),
            line_of(rapid, "MoveJ"),
            "MoveJ: x 1e300: outside -100000 to 100000 mm",
        ),
    ]
}

/// The text of `text` between the first `before` of a target (after an LS program's `/POS`)
/// and the `after` that follows it.
fn first_value<'a>(text: &'a str, before: &str, after: &str) -> &'a str {
    let targets = text.find("/POS").unwrap_or(0);
    let from = targets + text[targets..].find(before).unwrap() + before.len();
    &text[from..from + text[from..].find(after).unwrap()]
}

/// The compensate job refuses the KRL program `text` naming its file and the line `line`.
fn refused_by_the_job(s: &Setup, options: Options, text: &str, line: u64) {
    let request = stiffid::app::compensate::Request {
        names: Default::default(),
        setup: s,
        compliance: compliance(s),
        input: stiffid::app::compensate::Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "cut.src".into(),
            text,
            data: None,
            language: Language::Robot(Dialect::Krl),
            process_name: "aluminium.toml".into(),
            process: process(),
            chord_tolerance: 1e-4,
            output: Language::Robot(Dialect::Krl),
            out_name: "out.src".into(),
            settings: Settings::default(),
        },
        options,
    };
    let e = stiffid::app::compensate::run::<Error, _>(request, |_, _, _, _| Ok(())).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("cut.src") && message.contains(&format!("line {line}")),
        "{message}"
    );
}

#[test]
fn cartesian_targets_that_cannot_be_read_are_refused_naming_the_line() {
    let s = setup();
    let options = Options::for_setup(&s);
    let poses = cut(2);
    let (_, krl) = written(&s, Dialect::Krl, &poses, true);
    let (_, rapid) = written(&s, Dialect::Rapid, &poses, true);
    let (_, ls) = written(&s, Dialect::FanucLs, &poses, true);
    let first_krl = line_of(&krl, "PTP {E6POS");
    let krl_s = krl.lines().nth(first_krl as usize - 1).unwrap();
    let status = &krl_s[krl_s.find("S 'B").unwrap()..][..8];
    let cases = unreadable((&krl, &rapid, &ls), status, first_krl);
    for (dialect, text, line, needle) in cases {
        let e = machining::read(&text, Language::Robot(dialect), 1e-4)
            .and_then(|p| machining::resolve(&p, &s, None, &options).map(|_| ()));
        match e {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{dialect:?} {needle}: {message}");
                assert!(message.contains(needle), "{dialect:?}: {message}");
            }
            other => panic!("{dialect:?} {needle}: {other:?}"),
        }
    }
    // Through the compensate job: the file and the line named.
    let text = replaced(&krl, status, "S 'B001'");
    refused_by_the_job(&s, options, &text, first_krl);
}

/// A cut of seven points as G-code, every move a cutting one.
const GCODE: &str = "(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90 G17\nG1 X0 Y0 Z-4 F1800\nG1 X10\nG1 X20\nG1 X30\nG1 X40\nG1 X50\nG1 X60\n";

/// The cut of seven points written as KRL, RAPID and LS (in a user frame) Cartesian targets in
/// the part frame, read back.
fn in_part_frame(s: &Setup) -> Vec<(Dialect, Program)> {
    let (_, krl) = written(s, Dialect::Krl, &cut(7), false);
    let (_, rapid) = written(s, Dialect::Rapid, &cut(7), false);
    let (_, ls) = written(s, Dialect::FanucLs, &cut(7), false);
    let ls = in_user_frame(s, &ls);
    [
        (Dialect::Krl, krl),
        (Dialect::Rapid, rapid),
        (Dialect::FanucLs, ls),
    ]
    .into_iter()
    .map(|(d, text)| (d, machining::read(&text, Language::Robot(d), 1e-4).unwrap()))
    .collect()
}

/// Programs whose targets do not move with the part (joint targets, targets in the world
/// frame), each with what its refusal says.
fn not_in_part_frame(s: &Setup) -> Vec<(Dialect, Program, &'static str)> {
    let (_, world) = written(s, Dialect::FanucLs, &cut(7), false);
    let joint = "DEF a( )\nPTP {A1 -20, A2 -10, A3 -20, A4 0, A5 -60, A6 180}\nEND\n";
    [
        (
            Dialect::FanucLs,
            world.as_str(),
            "the world frame: the targets are not in the part frame (the setup's [workpiece]), so they do not move with the part; give them as Cartesian positions in a user frame UF : n, n >= 1, that a remark `! stiffid: user_frame = n ;` names",
        ),
        (
            Dialect::Krl,
            joint,
            "joint targets (E6AXIS, AXIS, line 2 the first)",
        ),
    ]
    .into_iter()
    .map(|(d, text, needle)| {
        (
            d,
            machining::read(text, Language::Robot(d), 1e-4).unwrap(),
            needle,
        )
    })
    .collect()
}

/// The program of `r` evaluates as the G-code of `g` at three placements (feasible at two at
/// least) and is placed where the G-code is (`by_gcode`).
fn assert_placed_as(g: &Request, r: &Request, by_gcode: &place::Report, dialect: Dialect) {
    let mut feasible = 0;
    for (x, y) in [(1.3, -0.7), (1.1, -0.5), (1.4, -0.8)] {
        let pose = Isometry3::translation(x, y, 0.4);
        let (eg, er) = (
            place::evaluate(g, &pose).unwrap(),
            place::evaluate(r, &pose).unwrap(),
        );
        assert_eq!(eg.is_ok(), er.is_ok(), "{dialect:?}: {eg:?} vs {er:?}");
        if let (Ok(eg), Ok(er)) = (eg, er) {
            feasible += 1;
            assert!(
                (eg.peak - er.peak).abs() <= 1e-9 * eg.peak,
                "{dialect:?}: {eg:?} vs {er:?}"
            );
            assert!((eg.sum - er.sum).abs() <= 1e-9 * eg.sum, "{dialect:?}");
        }
    }
    assert!(feasible >= 2, "{dialect:?}: {feasible}");
    let placed = place::run(r).unwrap();
    let (a, b) = (
        &by_gcode.placed.base_from_part,
        &placed.placed.base_from_part,
    );
    assert!(
        (a.translation.vector - b.translation.vector).norm() < 1e-6,
        "{dialect:?}"
    );
    assert!((by_gcode.placed.peak - placed.placed.peak).abs() <= 1e-9 * placed.placed.peak);
    assert_eq!(by_gcode.setup_text, placed.setup_text);
}

#[test]
fn a_cartesian_program_in_the_part_frame_is_placed_as_the_gcode_of_its_points() {
    let s = setup();
    let (compliance, process) = (compliance(&s), process());
    let options = Options::for_setup(&s);
    // The cut starts where the tool is (the setup's start): its first feed is no plunge from
    // a place the program does not say.
    let start = machining::gcode::Machine {
        frames: machining::gcode::ProgramFrames {
            start: Some(nalgebra::Vector3::new(0.0, 0.0, -4e-3)),
            ..Default::default()
        },
        ..Default::default()
    };
    let gcode = Program::GCode(machining::gcode::parse_on(GCODE, 1e-4, &start).unwrap());
    let programs = in_part_frame(&s);
    let refused = not_in_part_frame(&s);
    let region = Region {
        x: [0.9, 1.5],
        y: [-0.9, -0.3],
        rotation: [0.0, 0.0],
        free: None,
    };
    let effort = Effort {
        grid: 3,
        samples: 6,
        starts: 1,
        seed: 2,
    };
    let request = |work| Request {
        setup: &s,
        setup_text: SETUP,
        compliance: &compliance,
        work,
        options: &options,
        region,
        objective: Aggregate::Max,
        margin: 5f64.to_radians(),
        max_condition: 1000.0,
        effort,
    };
    let g = request(Work::Program {
        program: &gcode,
        process: &process,
    });
    let by_gcode = place::run(&g).unwrap();
    for (dialect, program) in &programs {
        let r = request(Work::Program {
            program,
            process: &process,
        });
        assert_placed_as(&g, &r, &by_gcode, *dialect);
    }
    for (dialect, program, needle) in &refused {
        let r = request(Work::Program {
            program,
            process: &process,
        });
        let e = match place::run(&r) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("{dialect:?} placed"),
        };
        assert!(e.contains(needle), "{dialect:?}: {e}");
    }
}

/// The line of `needle`'s first occurrence in `text`, 1-based.
fn line_of(text: &str, needle: &str) -> u64 {
    text.lines().position(|l| l.contains(needle)).unwrap() as u64 + 1
}

/// The line of the position (`P[i]{`) whose frames are the `n`-th `UF : ..` of `text`.
fn position_line(text: &str, n: usize) -> u64 {
    let at = text.match_indices("UF : ").nth(n).unwrap().0;
    let before: Vec<&str> = text[..at].lines().collect();
    before.iter().rposition(|l| l.starts_with("P[")).unwrap() as u64 + 1
}

/// The FANUC milling setup with the controller's frames by number: `[controller] bases` and
/// `tools` as `table` gives them.
fn with_table(table: &str) -> Setup {
    let text = format!("{SETUP}\n[controller]\n{table}\n");
    stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap()
}

/// The axis angles of the LS program `text` resolved on `s`.
fn ls_resolved(s: &Setup, text: &str) -> stiffid::Result<Vec<[f64; 6]>> {
    let p = machining::read(text, Language::Robot(Dialect::FanucLs), 1e-4)?;
    let p = machining::resolve(&p, s, None, &Options::for_setup(s))?;
    match p.into_owned() {
        Program::Robot(p) => Ok(p.targets.iter().map(|t| t.q_deg).collect()),
        _ => panic!("not a robot program"),
    }
}

/// The milling setup, an LS program of three poses in the world (user frame 0) and the same in
/// user frame 1 at the part frame's place.
fn ls_frames_case() -> (Setup, String, String) {
    let s = setup();
    let (_, world) = written(&s, Dialect::FanucLs, &cut(3), false);
    let part = positions_in_user_frame(&s, &world);
    (s, world, part)
}

#[test]
fn ls_user_and_tool_frames_are_read_by_number_or_as_the_program_declares_them() {
    let (s, world, part) = ls_frames_case();
    let named = named_part_frame(&part);
    let resolve_on = ls_resolved;
    let resolve = |text: &str| resolve_on(&s, text);
    // The world, and the user frame the remark names the part frame: read alike.
    let q_world = resolve(&world).unwrap();
    let q_named = resolve(&named).unwrap();
    // User frame 1 by number from the setup's table, the part frame's value there: the same
    // axis angles; another value there moves every target by it.
    let tcp = "tools = [{ number = 1, xyz_mm = [6.9, 245.3, 319.3], rpy_deg = [0, 0, 0] }]";
    let table = |base: &str| {
        with_table(&format!(
            "bases = [{{ number = 1, xyz_mm = {base}, rpy_deg = [0, 0, 0] }}]\n{tcp}"
        ))
    };
    // The part frame in the controller's world: 670 mm above the base frame, z 400 is -270.
    let q_table = resolve_on(&table("[1300, -700, -270]"), &part).unwrap();
    let q_off = resolve_on(&table("[1300, -690, -270]"), &part).unwrap();
    // `UF : F, UT : F`: the frames in force where the motions run (UFRAME_NUM=0, UTOOL_NUM=1).
    let floating = world.replace("UF : 0, UT : 1", "UF : F, UT : F");
    assert_ne!(floating, world);
    let q_floating = resolve(&floating).unwrap();
    for q in [&q_named, &q_table, &q_floating] {
        for (a, b) in q.iter().flatten().zip(q_world.iter().flatten()) {
            assert!((a - b).abs() < 1e-9, "{a} {b}");
        }
    }
    assert!(q_off[0]
        .iter()
        .zip(&q_table[0])
        .any(|(a, b)| (a - b).abs() > 0.1));
}

/// Where the setup's tables lack a frame, the frames in force differ from the position's, a
/// number is in a register, or the remarks contradict themselves: refused naming the line.
#[test]
fn ls_frames_not_stated_or_not_in_force_are_refused_naming_the_line() {
    let (s, _, part) = ls_frames_case();
    let named = named_part_frame(&part);
    // The second position's frames as `with`.
    let second = |text: &str, with: &str| {
        let at = text.match_indices("UF : 1, UT : 1").nth(1).unwrap().0;
        format!("{}{with}{}", &text[..at], &text[at + 14..])
    };
    let tool_remark = named.replacen("/MN\n", "/MN\n   1:  ! stiffid: tool_frame = 3 ;\n", 1);
    let no_number = part.replacen("/MN\n", "/MN\n   1:  ! stiffid: user_frame ;\n", 1);
    let twice = named_part_frame(&named.replacen("user_frame = 1", "user_frame = 2", 1));
    let from_register = named.replacen("UTOOL_NUM=1", "UTOOL_NUM=R[5]", 1);
    let (other_user, other_tool) = (
        second(&named, "UF : 2, UT : 1"),
        second(&named, "UF : 1, UT : 2"),
    );
    let motion = |text: &str, n: usize| {
        text.lines()
            .enumerate()
            .filter(|(_, l)| l.contains(":L P[") || l.contains(":J P["))
            .nth(n)
            .unwrap()
            .0 as u64
            + 1
    };
    let wrong_tool =
        with_table("tools = [{ number = 1, xyz_mm = [6.9, 245.3, 300], rpy_deg = [0, 0, 0] }]");
    let cases: Vec<(&Setup, &str, u64, String)> = vec![
        // A user frame no remark names, and no table gives.
        (
            &s,
            &part,
            position_line(&part, 0),
            "frame number 1 of the controller's bases".into(),
        ),
        // Another user frame than the one selected: the controller's mismatch alarm.
        (
            &s,
            &other_user,
            motion(&other_user, 1),
            format!(
                "UF : 2: the position is in frame 2, and UFRAME_NUM=1 on line {} is in force",
                line_of(&other_user, "UFRAME_NUM=1")
            ),
        ),
        (
            &s,
            &other_tool,
            motion(&other_tool, 1),
            format!(
                "UT : 2: the position is in frame 2, and UTOOL_NUM=1 on line {} is in force",
                line_of(&other_tool, "UTOOL_NUM=1")
            ),
        ),
        // A tool frame number from a register.
        (
            &s,
            &from_register,
            line_of(&from_register, "UTOOL_NUM=R[5]"),
            "UTOOL_NUM=R[5]: the frame number is held in a register".into(),
        ),
        // Another tool frame than the one a remark names: read from the table, which lacks it.
        (
            &s,
            &tool_remark,
            position_line(&tool_remark, 0),
            "frame number 1 of the controller's tools".into(),
        ),
        // A table whose tool 1 is not the setup's tool.
        (
            &wrong_tool,
            &tool_remark,
            position_line(&tool_remark, 0),
            "is not the setup's".into(),
        ),
        // A remark without a number, and two remarks naming two frames.
        (
            &s,
            &no_number,
            line_of(&no_number, "stiffid: user_frame ;"),
            "stiffid: user_frame: expected = and a frame number".into(),
        ),
        (
            &s,
            &twice,
            line_of(&twice, "user_frame = 2"),
            format!(
                "stiffid: user_frame = 2: the remark on line {} names 1",
                line_of(&twice, "user_frame = 1")
            ),
        ),
    ];
    assert_refused(&cases);
}

/// Each case's text resolved on its setup is refused naming its line with its message.
fn assert_refused(cases: &[(&Setup, &str, u64, String)]) {
    for (setup, text, line, needle) in cases {
        match ls_resolved(setup, text) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, *line, "{needle}: {message}");
                assert!(message.contains(needle.as_str()), "{needle}: {message}");
            }
            other => panic!("{needle}: {other:?}\n{text}"),
        }
    }
}

/// A position in the frame in force where the program selects none, a position never taught
/// and a frame number beyond the controllers' are refused naming the line.
#[test]
fn ls_positions_in_no_frame_in_force_or_never_taught_are_refused_naming_the_line() {
    let (s, _, part) = ls_frames_case();
    let motion = |text: &str| {
        let first = text
            .lines()
            .position(|l| l.contains(":L P[") || l.contains(":J P["));
        first.unwrap() as u64 + 1
    };
    // The frame in force where none is selected; a position never taught; a number too large.
    let floating =
        (part.replacen("UF : 1, UT : 1", "UF : F, UT : 1", 1)).replace("  UFRAME_NUM=1 ;\n", "");
    let untaught = {
        let at = part.find("\tX = ").unwrap() + "\tX = ".len();
        let end = at + part[at..].find(" mm").unwrap();
        format!("{}********{}", &part[..at], &part[end..])
    };
    let large = part.replacen("UF : 1, UT : 1", "UF : 1000, UT : 1", 1);
    // A selection that is neither a frame number nor a register's (the controller loads
    // neither): refused as such, not as "held in a register".
    let selections = [
        "UFRAME_NUM=-1",
        "UFRAME_NUM=1000",
        "UFRAME_NUM=1.5",
        "UFRAME_NUM=",
    ]
    .map(|sel| (sel, part.replacen("UFRAME_NUM=1 ;", &format!("{sel} ;"), 1)));
    let mut cases: Vec<(&Setup, &str, u64, String)> = vec![
        (
            &s,
            &floating,
            motion(&floating),
            "UF : F: the position is in the frame in force where it runs, and no UFRAME_NUM=n before this motion selects one".into(),
        ),
        (
            &s,
            &untaught,
            line_of(&untaught, "********"),
            "X = ********: the position was never taught".into(),
        ),
        (
            &s,
            &large,
            line_of(&large, "UF : 1000"),
            "UF : 1000: expected a frame number, 0 to 999, or F (the frame in force)".into(),
        ),
    ];
    for (sel, text) in &selections {
        let message = format!("{sel}: expected = and a frame number, 0 to 999 (as a position's UF : n), or a register (R[i])");
        cases.push((&s, text, line_of(text, sel), message));
    }
    assert_refused(&cases);
}

/// The frame selections naming the motion group (`UTOOL_NUM[GP1]=n`, as ROBOGUIDE and SimPRO
/// write them) are read as group 1's plain ones; a register stays refused, and another group's
/// selection is refused naming its line.
#[test]
fn ls_frame_selections_naming_group_1_are_read_as_the_plain_ones() {
    let (s, _, part) = ls_frames_case();
    let named = named_part_frame(&part);
    let group_one = named
        .replacen("UFRAME_NUM=1", "UFRAME_NUM[GP1]=1", 1)
        .replacen("UTOOL_NUM=1", "UTOOL_NUM[GP1]=1", 1);
    let q_named = ls_resolved(&s, &named).unwrap();
    assert_eq!(ls_resolved(&s, &group_one).unwrap(), q_named);
    let other_tool = named.replacen("UTOOL_NUM=1", "UTOOL_NUM[GP1]=2", 1);
    let register = named.replacen("UTOOL_NUM=1", "UTOOL_NUM[GP1]=R[5]", 1);
    let other_group = named.replacen("UFRAME_NUM=1", "UFRAME_NUM[GP2]=1", 1);
    let first_motion = |text: &str| {
        text.lines()
            .position(|l| l.contains(":L P[") || l.contains(":J P["))
            .unwrap() as u64
            + 1
    };
    let cases = [
        (
            &register,
            line_of(&register, "UTOOL_NUM[GP1]=R[5]"),
            "UTOOL_NUM[GP1]=R[5]: the frame number is held in a register".to_string(),
        ),
        // Group 1's tool frame 2 selected: the positions' tool frame 1 is not the one in force.
        (
            &other_tool,
            first_motion(&other_tool),
            format!(
                "UT : 1: the position is in frame 1, and UTOOL_NUM=2 on line {} is in force",
                line_of(&other_tool, "UTOOL_NUM[GP1]=2")
            ),
        ),
        (
            &other_group,
            line_of(&other_group, "UFRAME_NUM[GP2]=1"),
            "UFRAME_NUM[GP2]=1: selects the frame of motion group GP2".to_string(),
        ),
    ];
    for (text, line, needle) in &cases {
        match ls_resolved(&s, text) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, *line, "{needle}: {message}");
                assert!(message.contains(needle.as_str()), "{needle}: {message}");
            }
            other => panic!("{needle}: {other:?}\n{text}"),
        }
    }
}

/// A German program's frame selections, `BENUTZER_NUM=n` and `WKZ_NUM=n`, are read as
/// `UFRAME_NUM=n` and `UTOOL_NUM=n`: the same axis angles, and a tool frame other than the
/// positions' refused naming the motion's line.
#[test]
fn ls_german_frame_selections_are_read_as_the_english_ones() {
    let (s, _, part) = ls_frames_case();
    let named = named_part_frame(&part);
    let german = |tool: &str| {
        named
            .replacen("UFRAME_NUM=1", "BENUTZER_NUM=1", 1)
            .replacen("UTOOL_NUM=1", &format!("WKZ_NUM={tool}"), 1)
    };
    let q_named = ls_resolved(&s, &named).unwrap();
    assert_eq!(ls_resolved(&s, &german("1")).unwrap(), q_named);
    let other = german("2");
    let motion = other
        .lines()
        .position(|l| l.contains(":L P[") || l.contains(":J P["))
        .unwrap() as u64
        + 1;
    match ls_resolved(&s, &other) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, motion, "{message}");
            let needle = format!(
                "UT : 1: the position is in frame 1, and UTOOL_NUM=2 on line {} is in force",
                line_of(&other, "WKZ_NUM=2")
            );
            assert!(message.contains(&needle), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// A program's own frame statement and the setup's table combine by one rule: an LS remark
/// `! stiffid: user_frame = 1 ;` declares user frame 1 the part frame, and where the setup's
/// `[controller] bases` also gives number 1, it must be that frame (the part frame in the
/// controller's world, within 1 µm); another one (10 mm off) is refused naming the remark's
/// line, both frames and how far apart they are, never the remark's silently.
#[test]
fn ls_a_remark_and_the_setups_table_giving_one_number_two_frames_is_refused() {
    let (_, _, part) = ls_frames_case();
    let named = named_part_frame(&part);
    let tcp = "tools = [{ number = 1, xyz_mm = [6.9, 245.3, 319.3], rpy_deg = [0, 0, 0] }]";
    let table = |base: &str| {
        with_table(&format!(
            "bases = [{{ number = 1, xyz_mm = {base}, rpy_deg = [0, 0, 0] }}]\n{tcp}"
        ))
    };
    let agreed = ls_resolved(&table("[1300, -700, -270]"), &named).unwrap();
    assert_eq!(agreed.len(), 3);
    match ls_resolved(&table("[1300, -690, -270]"), &named) {
        Err(stiffid::Error::Program { line, message }) => {
            assert_eq!(line, line_of(&named, "stiffid: user_frame"), "{message}");
            assert!(
                message.contains("frame number 1 the part frame")
                    && message.contains("[controller] bases gives number 1 another frame")
                    && message.contains("10.000 mm"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}
