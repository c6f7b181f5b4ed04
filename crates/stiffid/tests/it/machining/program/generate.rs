//! Programs generated for each controller (`stiffid_machining::program::generate`).

use nalgebra::{Isometry3, Vector3, Vector6};
use nalgebra::{Translation3, UnitQuaternion};
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::presets;
use stiffid_core::{Error, Robot};
use stiffid_machining::program::cartesian::flags::ConfigurationData;
use stiffid_machining::program::generate::*;
use stiffid_machining::program::ls::generate as ls;
use stiffid_machining::program::Dialect;
use stiffid_machining::program::{krl::StatusTurn, ls::Config, rapid::ConfData};

fn robot() -> Robot {
    presets::get("fanuc-r2000ic-165f").unwrap()
}

fn tool() -> Tool {
    Tool {
        frame: Isometry3::translation(0.01, -0.02, 0.3),
        payload: Some((12.5, Vector3::new(0.0, 0.0, 0.12))),
    }
}

fn work() -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(1.3, -0.7, 0.4),
        UnitQuaternion::from_euler_angles(0.1, -0.2, 0.3),
    )
}

/// Targets of `robot` at these axis angles (deg).
fn targets(q_deg: &[[f64; 6]]) -> Vec<Target> {
    let r = robot();
    q_deg
        .iter()
        .map(|q| {
            Target::new(
                &r,
                &tool().frame.translation.vector,
                &Vector6::from(*q).map(f64::to_radians),
            )
        })
        .collect()
}

fn plan<'a>(dialect: Dialect, name: &'a str, t: &'a [Target], m: &'a [Move]) -> Plan<'a> {
    Plan {
        dialect,
        name,
        targets: t,
        moves: m,
        tool: tool(),
        work: work(),
        world: Isometry3::identity(),
        external: None,
        approximation: 1e-5,
        numbers: Default::default(),
        pulses: None,
        settings: Settings::default(),
    }
}

const Q: [[f64; 6]; 3] = [
    [-23.2, 3.9, -48.1, 10.0, -41.9, 23.2],
    [-20.0, 5.0, -45.0, 100.0, -40.0, 200.0],
    [-18.0, 6.0, -44.0, -95.0, 35.0, -190.0],
];
const MOVES: [Move; 3] = [Move::Rapid, Move::Feed(0.03), Move::Feed(100.0 / 6e4)];

/// The number after `key` in `line`.
fn after(line: &str, key: &str) -> f64 {
    let at = line.find(key).unwrap_or_else(|| panic!("{key} in {line}")) + key.len();
    let text = line[at..].trim_start();
    let end = text
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
        .unwrap_or(text.len());
    text[..end].parse().unwrap_or_else(|_| panic!("{line}"))
}

/// The most numbered lines of an LS file (the pendant's four digits, the reference's).
const LS_MAX_LINES: usize = 9999;

/// The lines of an LS main program's header before its moves: `! set UTOOL`, six remarks of
/// the tool's frame, `UFRAME_NUM`, `UTOOL_NUM`.
const LS_HEADER_LINES: usize = 9;

fn rotation_zyx(a: f64, b: f64, c: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_euler_angles(c.to_radians(), b.to_radians(), a.to_radians())
}

/// The pose stated by a written target line (KRL, RAPID) or position (LS), base frame.
fn stated(dialect: Dialect, text: &str) -> Isometry3<f64> {
    match dialect {
        Dialect::Krl => {
            let p = Translation3::new(after(text, "X "), after(text, "Y "), after(text, "Z "));
            let r = rotation_zyx(after(text, "A "), after(text, "B "), after(text, "C "));
            work() * Isometry3::from_parts(Translation3::from(p.vector * 1e-3), r)
        }
        Dialect::Rapid => {
            let n: Vec<f64> = text
                .split(['[', ']', ','])
                .filter_map(|w| w.trim().parse::<f64>().ok())
                .collect();
            let p = Translation3::new(n[0], n[1], n[2]);
            let q = nalgebra::Quaternion::new(n[3], n[4], n[5], n[6]);
            let r = UnitQuaternion::from_quaternion(q);
            work() * Isometry3::from_parts(Translation3::from(p.vector * 1e-3), r)
        }
        Dialect::FanucLs => {
            let p = Translation3::new(after(text, "X ="), after(text, "Y ="), after(text, "Z ="));
            let r = rotation_zyx(after(text, "R ="), after(text, "P ="), after(text, "W ="));
            Isometry3::from_parts(Translation3::from(p.vector * 1e-3), r)
        }
        Dialect::Inform => unreachable!("INFORM jobs state no Cartesian target"),
    }
}

/// The written targets: each motion line's (KRL, RAPID) or position's (LS) text.
fn written_targets(dialect: Dialect, text: &str) -> Vec<String> {
    match dialect {
        Dialect::Krl => text
            .lines()
            .filter(|l| l.starts_with("LIN") || l.starts_with("PTP {E6POS"))
            .map(String::from)
            .collect(),
        Dialect::Rapid => text
            .lines()
            .filter(|l| l.trim_start().starts_with("Move"))
            .map(String::from)
            .collect(),
        Dialect::FanucLs => text
            .split("P[")
            .skip(1)
            .filter(|p| p.contains("GP1"))
            .map(String::from)
            .collect(),
        Dialect::Inform => unreachable!("INFORM jobs state no Cartesian target"),
    }
}

#[test]
fn cartesian_targets_state_the_forward_kinematics_and_the_configuration_of_the_postures() {
    let t = targets(&Q);
    for d in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
        let w = generate(&plan(d, "POCKET", &t, &MOVES)).unwrap();
        assert_eq!(w.files.len(), 1);
        let text = crate::common::inlined(&w.files[0].text, w.files[0].data.as_deref());
        let lines = written_targets(d, &text);
        assert_eq!(lines.len(), 3, "{d:?}: {text}");
        for (line, target) in lines.iter().zip(&t) {
            let pose = stated(d, line);
            let dp = (pose.translation.vector - target.pose.translation.vector).norm();
            assert!(dp < 1e-12, "{d:?}: {dp} m: {line}");
            let angle = pose.rotation.angle_to(&target.pose.rotation);
            assert!(angle < 1e-8, "{d:?}: {angle} rad: {line}");
            // The configuration data against the axis angles, computed here from the manuals'
            // definitions of the axis-angle parts.
            let q = target.q_deg;
            match d {
                Dialect::Krl => {
                    let turn: String = (0..6)
                        .rev()
                        .map(|k| if q[k] < 0.0 { '1' } else { '0' })
                        .collect();
                    assert!(line.contains(&format!("T 'B{turn}'")), "{line}");
                    let wrist = if q[4] <= 0.0 { '1' } else { '0' };
                    assert!(line.contains(&format!("S 'B{wrist}10'")), "{line}");
                }
                Dialect::Rapid => {
                    let quadrant = |x: f64| (x / 90.0).floor() as i64;
                    let cfx = i64::from(q[4] < 0.0);
                    let conf = format!(
                        "[{},{},{},{cfx}]",
                        quadrant(q[0]),
                        quadrant(q[3]),
                        quadrant(q[5])
                    );
                    assert!(line.contains(&conf), "{conf}: {line}");
                }
                Dialect::FanucLs => {
                    let turn = |x: f64| ((x + 180.0) / 360.0).floor() as i64;
                    let flip = if q[4] > 0.0 { 'F' } else { 'N' };
                    let config = format!(
                        "'{flip} U T, {}, {}, {}'",
                        turn(q[0]),
                        turn(q[3]),
                        turn(q[5])
                    );
                    assert!(line.contains(&config), "{config}: {line}");
                }
                Dialect::Inform => unreachable!("INFORM jobs state no Cartesian target"),
            }
        }
    }
}

#[test]
fn the_configuration_tells_the_two_wrist_solutions_of_one_pose_apart() {
    // (q4 + 180, -q5, q6 + 180) puts the flange in the same pose with the wrist flipped.
    let q = Q[0];
    let twin = [q[0], q[1], q[2], q[3] + 180.0, -q[4], q[5] + 180.0];
    let t = targets(&[q, twin]);
    let dp = (t[0].pose.translation.vector - t[1].pose.translation.vector).norm();
    assert!(dp < 1e-12 && t[0].pose.rotation.angle_to(&t[1].pose.rotation) < 1e-12);
    let (a, b) = (t[0].arm, t[1].arm);
    assert_eq!(StatusTurn::of(&a).status ^ StatusTurn::of(&b).status, 0b100);
    assert_eq!((ConfData::of(&a).0[3] - ConfData::of(&b).0[3]).abs(), 1);
    assert_ne!(Config::of(&a).as_str()[..1], Config::of(&b).as_str()[..1]);
    assert!(b.change_from(&a).unwrap().contains("wrist"));
}

#[test]
fn the_programs_initialise_motion_end_exact_and_name_their_tool_and_work_object() {
    let t = targets(&Q);
    let krl = generate(&plan(Dialect::Krl, "POCKET", &t, &MOVES))
        .unwrap()
        .files
        .remove(0);
    // Its points put back from its .dat: the motions' lines as one text.
    let krl = &crate::common::inlined(&krl.text, krl.data.as_deref());
    // The lines KSS writes before DEF, then the program.
    let (header, krl) = krl.split_at(krl.find("DEF ").unwrap());
    assert!(header.starts_with("&ACCESS RVP\n&REL 1\n"), "{header}");
    assert!(header.lines().all(|l| l.starts_with('&')), "{header}");
    assert!(krl.starts_with("DEF POCKET( )\n"), "{krl}");
    for needed in [
        "BAS(#INITMOV, 0)",
        "$VEL.CP = 0.03\n",
        "$ACC.CP =",
        "$APO.CDIS = 0.01\n",
        "$TOOL = {X 10, Y -20, Z 300, A 0, B 0, C 0}",
        "$LOAD = {M 12.5, CM {X 0, Y 0, Z 120,",
        "$BASE = {X 1300, Y -700, Z 400,",
    ] {
        assert!(krl.contains(needed), "{needed}: {krl}");
    }
    let motions: Vec<&str> = krl
        .lines()
        .filter(|l| l.starts_with("LIN") || l.starts_with("PTP"))
        .collect();
    assert!(
        motions[0].starts_with("PTP {E6POS") && !motions[0].contains("C_"),
        "{}",
        motions[0]
    );
    assert!(motions[1].ends_with("} C_DIS"), "{}", motions[1]);
    assert!(
        motions[2].ends_with('}'),
        "the last point is exact: {}",
        motions[2]
    );
    // F100 mm/min exactly: 0.001666666667 m/s.
    assert!(krl.contains("$VEL.CP = 0.001666667\n"), "{krl}");
    let rapid = &generate(&plan(Dialect::Rapid, "POCKET", &t, &MOVES))
        .unwrap()
        .files[0]
        .text;
    for needed in [
        "MODULE POCKET\n",
        "PERS tooldata tspindle := [TRUE,[[10,-20,300],[1.000000000,0.000000000,0.000000000,0.000000000]],[12.5,[0,0,120],",
        "PERS wobjdata wpart := [FALSE,TRUE,\"\",[[1300,-700,400],",
        "ConfL \\On;",
        ", [30,500,5000,1000], zpath, tspindle\\WObj:=wpart;",
        "[1.666666667,500,5000,1000], fine, tspindle\\WObj:=wpart;\n  ENDPROC",
    ] {
        assert!(rapid.contains(needed), "{needed}: {rapid}");
    }
    assert!(
        rapid.contains("    MoveJ ") && rapid.contains("    MoveL "),
        "{rapid}"
    );
    let ls = &generate(&plan(Dialect::FanucLs, "POCKET", &t, &MOVES))
        .unwrap()
        .files[0]
        .text;
    let comment = ls.lines().find(|l| l.starts_with("COMMENT")).unwrap();
    let quoted = comment.split('"').nth(1).unwrap();
    assert!(quoted.len() <= 16, "{comment}");
    for needed in [
        "UFRAME_NUM=0 ;",
        "UTOOL_NUM=1 ;",
        ":J P[1] 20% FINE ;",
        ":L P[2] 30mm/sec CNT100 ;",
        ":L P[3] 10cm/min FINE ;",
    ] {
        assert!(ls.contains(needed), "{needed}: {ls}");
    }
    // Without a mass, RAPID has no tooldata to write.
    let mut p = plan(Dialect::Rapid, "POCKET", &t, &MOVES);
    p.tool.payload = None;
    assert!(
        matches!(generate(&p), Err(Error::InvalidField { field, .. }) if field == "tool.mass_kg")
    );
}

#[test]
fn joint_targets_read_back_to_their_axis_angles() {
    let t = targets(&Q);
    for d in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
        let mut p = plan(d, "POCKET", &t, &MOVES);
        p.settings.targets = Targets::Joint;
        let w = generate(&p).unwrap();
        // A KRL program is read with its .dat, which declares its points.
        let (text, data) = (&w.files[0].text, w.files[0].data.as_deref());
        assert_eq!(data.is_some(), d == Dialect::Krl, "{d:?}");
        let read = stiffid_machining::program::parse_with_data(text, data, d).unwrap();
        assert_eq!(read.targets.len(), 3, "{d:?}");
        for (r, e) in read.targets.iter().zip(&Q) {
            for (a, b) in r.q_deg.iter().zip(e) {
                assert!((a - b).abs() <= 1e-9, "{d:?}: {:?}", r.q_deg);
            }
        }
        if let Some(dat) = data {
            // The `.src` names the points, the `.dat` declares them (independently read here:
            // each declaration's values against the axis angles).
            assert!(
                text.contains("PTP XP1\n") && text.contains("PTP XP3\n"),
                "{text}"
            );
            assert!(
                dat.starts_with("&ACCESS RVP\n&REL 1\nDEFDAT POCKET\n"),
                "{dat}"
            );
            let decls: Vec<&str> = dat
                .lines()
                .filter(|l| l.starts_with("DECL E6AXIS XP"))
                .collect();
            assert_eq!(decls.len(), 3, "{dat}");
            for (k, (decl, e)) in decls.iter().zip(&Q).enumerate() {
                let (name, value) = decl["DECL E6AXIS ".len()..].split_once('=').unwrap();
                assert_eq!(name, format!("XP{}", k + 1));
                let values: Vec<f64> = (value.trim_matches(['{', '}']).split(','))
                    .map(|m| m.split_whitespace().nth(1).unwrap().parse().unwrap())
                    .collect();
                for (a, b) in values.iter().zip(e) {
                    assert!((a - b).abs() <= 1e-9, "{decl}");
                }
            }
        }
    }
}

#[test]
fn feeds_are_exact_or_refused() {
    // LS: whole mm/sec, else whole cm/min, else the nearest cm/min with a warning.
    assert_eq!(ls::speed(0.03), Some(("30mm/sec".into(), true)));
    assert_eq!(ls::speed(100.0 / 6e4), Some(("10cm/min".into(), true)));
    assert_eq!(ls::speed(1234.0 / 6e4), Some(("123cm/min".into(), false)));
    assert_eq!(ls::speed(5.0 / 6e4), None);
    let t = targets(&Q[..2]);
    let slow = [Move::Rapid, Move::Feed(5.0 / 6e4)];
    assert!(matches!(
        generate(&plan(Dialect::FanucLs, "P", &t, &slow)),
        Err(Error::Program { line: 2, .. })
    ));
    let odd = [Move::Rapid, Move::Feed(1234.0 / 6e4)];
    let w = generate(&plan(Dialect::FanucLs, "P", &t, &odd)).unwrap();
    assert!(
        w.warnings[0].contains("1234 mm/min") && w.warnings[0].contains("123cm/min"),
        "{:?}",
        w.warnings
    );
    // Below 0.001 mm/s (RAPID once wrote 0 for 0.03 mm/min): refused, never written as 0.
    for d in [Dialect::Krl, Dialect::Rapid] {
        let tiny = [Move::Rapid, Move::Feed(0.03 / 6e4)];
        assert!(
            matches!(generate(&plan(d, "P", &t, &tiny)), Err(Error::InvalidField { field, .. }) if field == "moves")
        );
    }
}

#[test]
fn names_are_identifiers_within_the_controllers_length_and_never_reserved() {
    let t = targets(&Q);
    let name_error = |d, name: &str| match generate(&plan(d, name, &t, &MOVES)) {
        Err(Error::InvalidOption {
            option: JobOption::ProgramName,
            message,
        }) => message,
        other => panic!("{name}: {other:?}"),
    };
    assert!(name_error(Dialect::Krl, "END").contains("reserved word of KUKA KRL"));
    assert!(name_error(Dialect::Krl, "end").contains("reserved"));
    assert!(name_error(Dialect::Rapid, "PROC").contains("reserved word of ABB RAPID"));
    assert!(name_error(Dialect::FanucLs, "CALL").contains("reserved"));
    assert!(name_error(Dialect::Krl, "1X").contains("starting with a letter"));
    assert!(name_error(Dialect::Krl, "A-B").contains("letters, digits"));
    // LS: 8 characters by default (R-30iA), a setting for later controllers.
    assert!(name_error(Dialect::FanucLs, "POCKET_WALL").contains("at most 8"));
    let mut p = plan(Dialect::FanucLs, "POCKET_WALL", &t, &MOVES);
    p.settings.name_length = Some(36);
    assert!(generate(&p).unwrap().files[0]
        .text
        .starts_with("/PROG  POCKET_WALL\n"));
    assert!(name_error(Dialect::Krl, &"A".repeat(25)).contains("at most 24"));
    generate(&plan(Dialect::Rapid, &"A".repeat(32), &t, &MOVES)).unwrap();
}

#[test]
fn settings_and_moves_outside_their_limits_are_refused() {
    let t = targets(&Q);
    let mut p = plan(Dialect::Krl, "P", &t, &MOVES);
    for (settings, field) in [
        (
            Settings {
                max_tcp_speed: 0.0,
                ..Settings::default()
            },
            JobOption::MaxTcpSpeedMmS,
        ),
        (
            Settings {
                name_length: Some(4),
                ..Settings::default()
            },
            JobOption::NameLength,
        ),
        (
            Settings {
                moves_per_file: 10,
                ..Settings::default()
            },
            JobOption::MovesPerFile,
        ),
    ] {
        p.settings = settings;
        assert!(
            matches!(generate(&p), Err(Error::InvalidOption { option, .. }) if option == field)
        );
    }
    let p = plan(Dialect::Krl, "P", &t, &MOVES[..2]);
    assert!(matches!(generate(&p), Err(Error::InvalidField { field, .. }) if field == "moves"));
    assert!(
        matches!(generate(&plan(Dialect::Krl, "P", &[], &[])), Err(Error::InvalidField { field, .. }) if field == "targets")
    );
}

#[test]
fn moves_beyond_one_files_lines_are_split_into_called_sub_programs() {
    const N: usize = 120_000;
    let one = targets(&Q[..1]).pop().unwrap();
    let t = vec![one; N];
    let mut m = vec![Move::Feed(0.03); t.len()];
    m[0] = Move::Rapid;
    let mut p = plan(Dialect::FanucLs, "PK", &t, &m);
    p.settings.targets = Targets::Joint;
    let w = generate(&p).unwrap();
    // 10 000 moves per file, but an LS file numbers at most 9999 lines, nine of them the
    // header's: 9990 moves each.
    let per_file = LS_MAX_LINES - LS_HEADER_LINES;
    let subs = N.div_ceil(per_file);
    assert_eq!((per_file, subs), (9990, 13));
    assert_eq!(w.files.len(), subs + 1);
    let main = &w.files[0];
    assert_eq!(main.name, "PK");
    let calls: Vec<&str> = main.text.lines().filter(|l| l.contains("CALL ")).collect();
    assert_eq!(calls.len(), subs);
    assert!(calls[0].ends_with("CALL PK_01 ;") && calls[12].ends_with("CALL PK_13 ;"));
    for (k, f) in w.files[1..].iter().enumerate() {
        assert_eq!(f.name, format!("PK_{:02}", k + 1));
        assert!(f.text.starts_with(&format!("/PROG  {}\n", f.name)));
        let moves = if k + 1 < subs {
            per_file
        } else {
            N - 12 * per_file
        };
        assert_eq!(f.text.matches("GP1:").count(), moves);
    }
    // Only the very last point is exact.
    let fine = w
        .files
        .iter()
        .map(|f| f.text.matches("CNT100 ;").count())
        .sum::<usize>();
    assert_eq!(fine, N - 2);
    // More than 99 sub-programs are numbered with three digits (100 moves to a file here), and a
    // name with no room for their numbers on an 8-character controller is refused.
    let (t, m) = (&t[..10_050], &m[..10_050]);
    p = plan(Dialect::FanucLs, "PK", t, m);
    p.settings.moves_per_file = 100;
    let names: Vec<String> = (generate(&p).unwrap().files.into_iter())
        .map(|f| f.name)
        .collect();
    assert_eq!(names.len(), 102);
    assert_eq!(
        (names[1].as_str(), names[101].as_str()),
        ("PK_001", "PK_101")
    );
    let mut long = plan(Dialect::FanucLs, "POCKET", t, m);
    long.settings.moves_per_file = 100;
    assert!(
        matches!(generate(&long), Err(Error::InvalidOption { option: JobOption::ProgramName, message }) if message.contains("POCKET_001"))
    );
}

#[test]
fn split_krl_and_rapid_programs_call_their_sub_programs() {
    let one = targets(&Q[..1]).pop().unwrap();
    let t = vec![one; 250];
    let m = vec![Move::Feed(0.03); 250];
    for (d, call) in [
        (Dialect::Krl, "P_01( )\nP_02( )\nP_03( )\nEND\n"),
        (
            Dialect::Rapid,
            "    rP_01;\n    rP_02;\n    rP_03;\n  ENDPROC",
        ),
    ] {
        let mut p = plan(d, "P", &t, &m);
        p.settings.moves_per_file = 100;
        let w = generate(&p).unwrap();
        assert_eq!(w.files.len(), 4, "{d:?}");
        assert!(w.files[0].text.contains(call), "{d:?}: {}", w.files[0].text);
        assert!(w.files[3].text.starts_with(match d {
            Dialect::Krl => "&ACCESS RVP\n&REL 1\n&PARAM TEMPLATE = C:\\KRC\\Roboter\\Template\\vorgabe\n&PARAM EDITMASK = *\nDEF P_03( )\n",
            _ => "MODULE P_03\n  PROC rP_03()\n",
        }));
    }
}

#[test]
fn the_controllers_limits_hold_whatever_the_settings() {
    let t = targets(&Q);
    // KRL's spline motion is a reserved word too.
    let e = generate(&plan(Dialect::Krl, "SPL", &t, &MOVES)).unwrap_err();
    assert!(e.to_string().contains("reserved word of KUKA KRL"), "{e}");
    // name_length lowers the controller's longest name, never raises it.
    for (dialect, most) in [
        (Dialect::Krl, 24),
        (Dialect::Rapid, 32),
        (Dialect::FanucLs, 36),
    ] {
        let mut p = plan(dialect, "P", &t, &MOVES);
        p.settings.name_length = Some(most + 1);
        match generate(&p) {
            Err(Error::InvalidOption {
                option: JobOption::NameLength,
                message,
            }) => assert!(
                message.contains(&format!("at most {most} characters")),
                "{message}"
            ),
            other => panic!("{dialect:?}: {other:?}"),
        }
        p.settings.name_length = Some(most);
        generate(&p).unwrap();
    }
    // RAPID's rapids move no faster than the robot's largest TCP speed.
    let mut p = plan(Dialect::Rapid, "P", &t, &MOVES);
    p.settings.max_tcp_speed = 0.05;
    let text = &generate(&p).unwrap().files[0].text;
    assert!(text.contains("CONST speeddata vrapid := [50,"), "{text}");
    p.settings.max_tcp_speed = 2.0;
    let text = &generate(&p).unwrap().files[0].text;
    assert!(text.contains("CONST speeddata vrapid := [200,"), "{text}");
}

#[test]
fn an_ls_file_never_numbers_more_lines_than_the_pendant() {
    let q: Vec<[f64; 6]> = (0..10_000)
        .map(|i| [-20.0 + 1e-3 * i as f64, 5.0, -45.0, 10.0, -40.0, 20.0])
        .collect();
    let t = targets(&q);
    let m = vec![Move::Feed(0.01); t.len()];
    // One file of 10 000 moves would number 10 003 lines; the main program's header counts.
    let written = generate(&plan(Dialect::FanucLs, "P", &t, &m)).unwrap();
    assert_eq!(
        written.files.len(),
        3,
        "the main program and two sub-programs"
    );
    for file in &written.files {
        let number = |l: &str| {
            let p = l.get(..5).filter(|p| p.ends_with(':'))?;
            p[..4].trim().parse::<u32>().ok()
        };
        let last = file.text.lines().filter_map(number).max().unwrap();
        assert!(last <= LS_MAX_LINES as u32, "{}: {last} lines", file.name);
    }
    assert_eq!(
        LS_HEADER_LINES,
        ls::header(&plan(Dialect::FanucLs, "P", &t, &m))
            .lines()
            .count()
    );
}

/// Every name a KRL program written in files states, read from the files here: each file's
/// `DEF` and its `.dat`'s `DEFDAT` (the file's name, KSS pairs them by it), the main program's
/// calls, the points `XPn` its motions name and its `.dat` declares.
fn krl_names(w: &Written) -> Vec<String> {
    let mut names = Vec::new();
    for f in &w.files {
        let dat = f.data.as_deref().unwrap();
        let def = f.text.lines().find_map(|l| l.strip_prefix("DEF ")).unwrap();
        let defdat = dat.lines().find_map(|l| l.strip_prefix("DEFDAT ")).unwrap();
        assert_eq!((def, defdat), (&*format!("{}( )", f.name), f.name.as_str()));
        names.push(defdat.to_string());
        let calls = (f.text.lines())
            .filter_map(|l| l.strip_suffix("( )"))
            .filter(|l| !l.contains(' '));
        names.extend(calls.map(String::from));
        let points =
            (dat.lines()).filter_map(|l| l.split_once(' ')?.1.split_once(' ')?.1.split_once('='));
        names.extend(points.map(|(n, _)| n.to_string()));
    }
    names
}

#[test]
fn every_name_a_krl_program_writes_is_within_the_controllers_length() {
    // 250 moves in files of 100: a main program calling three sub-programs, each with its .dat.
    let q: Vec<[f64; 6]> = (0..250)
        .map(|i| {
            [
                Q[0][0] + i as f64 * 1e-3,
                Q[0][1],
                Q[0][2],
                Q[0][3],
                Q[0][4],
                Q[0][5],
            ]
        })
        .collect();
    let t = targets(&q);
    let mut m = vec![Move::Feed(0.03); t.len()];
    m[0] = Move::Rapid;
    let most = Dialect::Krl.controller().max_name_length();
    assert_eq!(most, 24);
    // A name of 21 characters: its sub-programs' `_01` make 24, the longest KSS takes.
    let name = "A".repeat(most - 3);
    let mut p = plan(Dialect::Krl, &name, &t, &m);
    p.settings.moves_per_file = 100;
    let w = generate(&p).unwrap();
    assert_eq!(w.files.len(), 4);
    let names = krl_names(&w);
    assert!(names.contains(&format!("{name}_03")) && names.contains(&"XP100".to_string()));
    for n in &names {
        assert!(n.len() <= most, "{n}");
        check_name(Dialect::Krl, n, most).unwrap();
    }
    // One character more: the sub-programs' names would be 25, refused before anything is
    // written, naming the option.
    let longer = "A".repeat(most - 2);
    let e = generate(&Plan { name: &longer, ..p }).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidOption { option: JobOption::ProgramName, message } if message.contains("longer than 24")),
        "{e}"
    );
    // A program of one file may take the whole 24; 25 is refused.
    let one = "B".repeat(most);
    let few = plan(Dialect::Krl, &one, &t[..3], &m[..3]);
    assert!(krl_names(&generate(&few).unwrap())
        .iter()
        .all(|n| n.len() <= most));
    let too_long = "B".repeat(most + 1);
    let e = generate(&plan(Dialect::Krl, &too_long, &t[..3], &m[..3])).unwrap_err();
    assert!(
        matches!(
            &e,
            Error::InvalidOption {
                option: JobOption::ProgramName,
                ..
            }
        ),
        "{e}"
    );
}
