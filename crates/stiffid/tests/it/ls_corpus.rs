//! The real FANUC LS programs of `tests/data/programs/ls` (SOURCES.md), as found: each one
//! compensated, every target equal to an independent reading of the file and every position of
//! the program written back equal to the compensated posture, or refused naming its line and
//! the construct.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use stiffid::app::compensate::{self, Input};
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::program::speed::Speed;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::robot::{ik, presets};
use stiffid::{Error, Setup};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/programs/ls/");

/// The frames the corpus's controllers hold by number, as a user of the cell gives them: tool 1
/// the setup's spindle, user frame 1 a fixture 1.2 m in front of the robot.
const CONTROLLER: &str = "
[controller]
tools = [{ number = 1, xyz_mm = [6.9, 245.3, 319.3], rpy_deg = [0, 0, 0] }]
bases = [{ number = 1, xyz_mm = [200, 0, -1200], rpy_deg = [0, 0, 0] }]
";

/// The FANUC R-2000iC/165F milling cell with [`CONTROLLER`].
pub(crate) fn setup() -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml").to_string();
    stiffid::internal::setup::parse(&(text + CONTROLLER), "cell.toml", |n, _| presets::get(n))
        .unwrap()
}

/// The same cell with a straight spindle 200 mm long, tool 1 on the controller.
fn straight_spindle() -> Setup {
    let (from, to) = ("[6.9, 245.3, 319.3]", "[0, 0, 200]");
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml");
    let text = text.replacen(&format!("tcp_mm = {from}"), &format!("tcp_mm = {to}"), 1);
    let text = text + &CONTROLLER.replace(from, to);
    stiffid::internal::setup::parse(&text, "cell.toml", |n, _| presets::get(n)).unwrap()
}

/// What stiffid does with a corpus file.
enum Outcome {
    /// Compensated.
    Compensated,
    /// Refused naming this line and, in its message, this construct.
    Refused(u64, &'static str),
}
use Outcome::{Compensated as Read, Refused};

/// Every file of the corpus and what stiffid does with it.
const CORPUS: [(&str, Outcome); 13] = [
    ("rpi_test.ls", Read),
    ("crs_ws_surface.ls", Read),
    ("rpi_example.ls", Read),
    ("rpi_tmpa.ls", Read),
    ("rpi_test_record.ls", Read),
    // Written for a smaller arm: its fourth pose is out of this one's reach.
    (
        "crs_surface_cartesian.ls",
        Refused(27, "the pose is out of reach"),
    ),
    // A second robot as group 2, in Cartesian representation.
    (
        "rpi_example_coor.ls",
        Refused(34, "GP2 X: group 2 in Cartesian representation"),
    ),
    (
        "rpi_tmpb.ls",
        Refused(21, "GP2 X: group 2 in Cartesian representation"),
    ),
    (
        "crs_surface_tool_offset.ls",
        Refused(
            24,
            "Tool_Offset,PR[15]: a position register holds its value on the controller",
        ),
    ),
    (
        "rosi_ros_movesm.ls",
        Refused(
            43,
            "J PR[2]: the position register is set on line 36 as the program runs",
        ),
    ),
    (
        "wilder_a10defaste.ls",
        Refused(
            37,
            "UFRAME[9:STRIP_DRILL]=PR[9]: the program sets a frame's value",
        ),
    ),
    // Its loop is followed; its tool frame 2 is not in the setup's table.
    (
        "wilder_robot_repeatability.ls",
        Refused(31, "frame number 2 of the controller's tools"),
    ),
    // A tool frame the setup's table does not give.
    (
        "wilder_job_dbl_safe_1.ls",
        Refused(50, "frame number 4 of the controller's tools"),
    ),
];

/// `text` (the corpus file `name`) compensated on `s` with the milling example's stiffness, LS
/// in and out: the program written and each target's compensation.
pub(crate) fn compensated(
    s: &Setup,
    name: &str,
    text: &str,
) -> stiffid::Result<(String, Vec<Compensated>)> {
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(s.model())
    .unwrap();
    compensated_with(s, &compliance, Options::for_setup(s), (name, text))
}

/// The LS program `text` (file `name`) compensated on `s` with `compliance` and `options`, LS
/// in and out: the program written and each target's compensation.
pub(crate) fn compensated_with(
    s: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    options: Options,
    (name, text): (&str, &str),
) -> stiffid::Result<(String, Vec<Compensated>)> {
    let (out, results, _) = compensated_in(s, compliance, options, (name, text), &[])?;
    Ok((out, results))
}

/// [`compensated_with`] with the controller backup's files `backup`: the program written, each
/// target's compensation, and the programs it calls written beside it (name and text).
#[allow(clippy::type_complexity)]
pub(crate) fn compensated_in(
    s: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    options: Options,
    (name, text): (&str, &str),
    backup: &[(String, String)],
) -> stiffid::Result<(String, Vec<Compensated>, Vec<(String, String)>)> {
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
    let request = compensate::Request {
        names: Default::default(),
        setup: s,
        compliance: compliance.clone(),
        input: Input::Program {
            encoding: Default::default(),
            reading: stiffid::internal::machining::program::Reading {
                backup,
                leave_refused: false,
            },
            name: name.into(),
            text,
            data: None,
            language: Language::Robot(Dialect::FanucLs),
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-4,
            output: Language::Robot(Dialect::FanucLs),
            out_name: name.into(),
            settings: Settings::default(),
        },
        options,
    };
    let mut results = Vec::new();
    let report = compensate::run::<Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })?;
    let program = report.report.program.unwrap();
    let called = (program.subprograms.iter())
        .map(|f| (f.name.clone(), f.text.clone()))
        .collect();
    Ok((crate::common::program_text(program), results, called))
}

/// A position of `/POS` as the file gives it: its frame numbers and its six numbers (`X`..`R`
/// mm and deg, or `J1`..`J6` deg).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Position {
    pub(crate) frames: (u32, u32),
    pub(crate) cartesian: bool,
    pub(crate) values: [f64; 6],
}

/// The independent reading: the positions of the motions of `text` in the order of `/MN`
/// (a `C` motion's via point, then its end), each as `/POS` gives it. Read line by line with
/// string searches, not with stiffid's reader.
pub(crate) fn independent(text: &str) -> Vec<Position> {
    let (mn, pos) = text.split_once("/POS").unwrap();
    let mut order = Vec::new();
    let mut lines = mn
        .lines()
        .skip_while(|l| !l.starts_with("/MN"))
        .skip(1)
        .peekable();
    while let Some(l) = lines.next() {
        let body = l.split_once(':').map_or("", |(_, b)| b);
        let letter = body.chars().next().unwrap_or(' ');
        if !matches!(letter, 'J' | 'L' | 'C') || !body[1..].trim_start().starts_with("P[") {
            continue;
        }
        let mut motion = body.to_string();
        while lines
            .peek()
            .is_some_and(|n| n.trim_start().starts_with(':'))
        {
            motion += lines.next().unwrap();
        }
        for (at, _) in motion
            .match_indices("P[")
            .filter(|(i, _)| !motion[..*i].ends_with('R'))
        {
            let digits: String = motion[at + 2..]
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            order.push(digits.parse::<u64>().unwrap());
        }
    }
    // Where each position's block starts (its first `P[i`), found in one pass.
    let mut starts = std::collections::HashMap::new();
    for (start, _) in pos.match_indices("\nP[") {
        let digits: String = (pos[start + 3..].chars())
            .take_while(char::is_ascii_digit)
            .collect();
        if let Ok(i) = digits.parse::<u64>() {
            starts.entry(i).or_insert(start);
        }
    }
    let block = |i: u64| {
        let start = starts[&i];
        let group1 = &pos[start..start + pos[start..].find("};").unwrap()];
        group1.split("GP2").next().unwrap().to_string()
    };
    let after = |b: &str, key: &str| -> f64 {
        let rest = &b[b.find(key).unwrap() + key.len()..];
        let rest = rest.trim_start().trim_start_matches('=').trim_start();
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || "+-.".contains(c)))
            .unwrap();
        // The controller writes `-.384` and `.094`.
        rest[..end]
            .replacen(
                '.',
                "0.",
                usize::from(rest[..end].trim_start_matches('-').starts_with('.')),
            )
            .parse()
            .unwrap()
    };
    order
        .into_iter()
        .map(|i| {
            let b = block(i);
            let cartesian = b.contains("X =");
            let keys = match cartesian {
                true => ["X =", "Y =", "Z =", "W =", "P =", "R ="],
                false => ["J1", "J2", "J3", "J4", "J5", "J6"],
            };
            Position {
                frames: (after(&b, "UF :") as u32, after(&b, "UT :") as u32),
                cartesian,
                values: keys.map(|k| after(&b, k)),
            }
        })
        .collect()
}

/// The line and message of a program's refusal.
pub(crate) fn refusal(e: &Error) -> (u64, String) {
    match e {
        Error::Program { line, message } => (*line, message.clone()),
        Error::Input { error, .. } => refusal(error),
        other => panic!("not a refusal naming a line: {other}"),
    }
}

/// The pose `X, Y, Z` (mm), `W, P, R` (deg) of an LS position: `R = Rz(R) Ry(P) Rx(W)`.
pub(crate) fn pose(v: &[f64; 6]) -> Isometry3<f64> {
    let [w, p, r] = [v[3], v[4], v[5]].map(f64::to_radians);
    Isometry3::from_parts(
        Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), r)
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), p)
            * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), w),
    )
}

/// The file `text` compensated into `out` (`results`, one per target): stiffid read every
/// target as the independent reading does, wrote back only `/POS`, and every position it wrote
/// is the compensated posture (joint values, or the controller's forward kinematics in the
/// position's user frame).
pub(crate) fn check(s: &Setup, name: &str, (text, out): (&str, &str), results: &[Compensated]) {
    let found = independent(text);
    let read = stiffid::internal::machining::program::parse(text, Dialect::FanucLs).unwrap();
    assert_eq!(read.targets.len(), found.len(), "{name}");
    assert_eq!(results.len(), found.len(), "{name}");
    for (t, f) in read.targets.iter().zip(&found) {
        match &t.cartesian {
            Some(c) => {
                assert!(f.cartesian, "{name}: line {}", t.line);
                let expected = pose(&f.values);
                let d = (c.pose().translation.vector - expected.translation.vector).norm();
                assert!(d < 1e-12, "{name}: line {}: {d} m", t.line);
                assert!(
                    c.rotation.angle_to(&expected.rotation) < 1e-12,
                    "{name}: line {}",
                    t.line
                );
            }
            None => {
                assert!(!f.cartesian, "{name}: line {}", t.line);
                assert_eq!(t.q_deg, f.values, "{name}: line {}", t.line);
            }
        }
    }
    // Only the positions' numbers change (and `/PROG`, named after the file written).
    let mn = |t: &str| {
        t.split_once("/ATTR")
            .unwrap()
            .1
            .split_once("/POS")
            .unwrap()
            .0
            .to_string()
    };
    assert_eq!(mn(out), mn(text), "{name}");
    let controller = s.workcell().controller();
    let robot = s.controller_robot().unwrap();
    let written = independent(out);
    let mut moved: f64 = 0.0;
    for ((w, f), r) in written.iter().zip(&found).zip(results) {
        assert_eq!((w.frames, w.cartesian), (f.frames, f.cartesian), "{name}");
        let q_deg = r.q_compensated.map(f64::to_degrees);
        if !w.cartesian {
            for (a, b) in w.values.iter().zip(q_deg.iter()) {
                assert!((a - b).abs() < 1e-8, "{name}: {a} {b}");
            }
            let most = w.values.iter().zip(&f.values).map(|(a, b)| (a - b).abs());
            moved = moved.max(most.fold(0.0, f64::max) * 1e-3);
            continue;
        }
        let frame = match w.frames.0 {
            0 => Isometry3::identity(),
            n => *controller.bases.get(n).unwrap(),
        };
        let at = s.program_world() * frame * pose(&w.values);
        let fk = ik::tool_pose(&robot.frames(&r.q_compensated), &s.tool().tcp);
        let d = (at.translation.vector - fk.translation.vector).norm();
        assert!(d < 1e-8, "{name}: {d} m");
        assert!(at.rotation.angle_to(&fk.rotation) < 1e-8, "{name}");
        moved = moved
            .max((pose(&w.values).translation.vector - pose(&f.values).translation.vector).norm());
    }
    // Compensated: where the process loads the tool (a linear or circular motion, at its feed),
    // the positions written are not the ones read; joint motions are rapids, unloaded.
    let loaded = read.targets.iter().any(|t| t.speed != Speed::Joint);
    assert_eq!(moved > 1e-6, loaded, "{name}: moved {moved} m");
}

#[test]
fn every_real_ls_program_is_compensated_point_by_point_or_refused_naming_its_line() {
    let s = setup();
    let texts = CORPUS.map(|(name, _)| std::fs::read_to_string(format!("{DIR}{name}")).unwrap());
    let runs: Vec<_> = (CORPUS.iter().zip(&texts))
        .map(|((name, _), text)| compensated(&s, name, text))
        .collect();
    for ((name, _), run) in CORPUS.iter().zip(&runs) {
        eprintln!("{name}: {:?}", run.as_ref().map(|_| ()).map_err(refusal));
    }
    for (((name, outcome), text), run) in CORPUS.iter().zip(&texts).zip(runs) {
        match (outcome, run) {
            (Read, Ok((out, results))) => check(&s, name, (text, &out), &results),
            (Refused(line, construct), Err(e)) => {
                let (l, message) = refusal(&e);
                assert_eq!(l, *line, "{name}: {message}");
                assert!(
                    message.contains(construct),
                    "{name}: {construct}: {message}"
                );
            }
            (_, other) => panic!("{name}: {:?}", other.map(|_| ())),
        }
    }
    assert!(CORPUS.len() >= 8);
}

/// `rpi_example.ls` with its `C` motion's via point in the configuration of the positions
/// around it (`N U T`), on a straight spindle that reaches its poses: compensated, the via point
/// and the end both targets of the `C` line, equal to the independent reading, written back as
/// `C` with both positions compensated.
#[test]
fn a_circular_motion_is_compensated_at_its_via_point_and_its_end() {
    let s = straight_spindle();
    assert_eq!(s.tool().tcp, Vector3::new(0.0, 0.0, 0.2));
    let found = std::fs::read_to_string(format!("{DIR}rpi_example.ls")).unwrap();
    let text = found.replacen("'N D B, 0, 0, 0'", "'N U T, 0, 0, 0'", 1);
    let (out, results) = compensated(&s, "rpi_example.ls", &text).unwrap();
    check(&s, "rpi_example.ls", (&text, &out), &results);
    let read = stiffid::internal::machining::program::parse(&text, Dialect::FanucLs).unwrap();
    let line = |i: usize| read.targets[i].line;
    // J P[1], J P[2], L P[3], C P[4] P[5], L P[6]: the via point and the end on the C's line.
    assert_eq!((line(3), line(4)), (30, 30));
    assert!(
        out.contains("   9:C P[4]    \n    :  P[5] 100mm/sec CNT100    ;\n"),
        "{out}"
    );
}

/// `rpi_tmpa.ls` with its motions inside a loop and a branch (`LBL`, `IF ..,JMP`, `IF .. THEN`,
/// `ELSE`, `ENDIF`): each motion compensated where it is, to the very posture the same motion
/// takes in the straight program; every line but the numbers of its positions written as read.
#[test]
fn a_motion_inside_a_branch_or_loop_is_compensated_as_the_same_motion_outside_it() {
    let s = setup();
    let straight = std::fs::read_to_string(format!("{DIR}rpi_tmpa.ls")).unwrap();
    let branched = straight
        .replace(
            "   3:J P[1] 100% FINE ;",
            "   3:  LBL[1] ;\n   4:  IF R[1]=1,JMP LBL[2] ;\n   5:J P[1] 100% FINE ;\n   6:  IF (DI[1]=ON) THEN ;",
        )
        .replace(
            "   5:L P[3] 50mm/sec FINE ;",
            "   7:L P[3] 50mm/sec FINE ;\n   8:  ELSE ;\n   9:  WAIT 1.00(sec) ;\n  10:  ENDIF ;\n  11:  JMP LBL[1] ;\n  12:  LBL[2] ;",
        );
    assert_ne!(straight, branched);
    let (out_a, a) = compensated(&s, "TMPA.ls", &straight).unwrap();
    let (out_b, b) = compensated(&s, "TMPA.ls", &branched).unwrap();
    assert_eq!(a.len(), 3);
    let q = |r: &[Compensated]| -> Vec<_> { r.iter().map(|c| c.q_compensated).collect() };
    assert_eq!(q(&a), q(&b));
    assert!(
        a.iter().any(|c| c.q_compensated != c.q),
        "a loaded path moves"
    );
    let pos = |t: &str| t[t.find("/POS").unwrap()..].to_string();
    assert_eq!(pos(&out_a), pos(&out_b));
    assert!(out_b.contains("  11:  JMP LBL[1] ;"));
}

/// A user frame selected on one path only: the Cartesian position after the paths meet is
/// refused naming both selections; `--leave-refused` leaves those as found, named, and reads
/// the others.
#[test]
fn a_frame_selected_on_one_path_only_is_refused_naming_both_lines() {
    let s = setup();
    let straight = std::fs::read_to_string(format!("{DIR}rpi_tmpa.ls")).unwrap();
    let text = straight.replace(
        "   4:L P[2] 50mm/sec CNT100 ;",
        "   4:  IF R[1]=1,JMP LBL[1] ;\n   4:  UFRAME_NUM=0 ;\n   4:  LBL[1] ;\n   4:L P[2] 50mm/sec CNT100 ;",
    );
    let e = compensated(&s, "TMPA.ls", &text).unwrap_err();
    let (line, why) = refusal(&e);
    assert_eq!(line, 11, "{why}");
    assert!(
        why.contains("UFRAME_NUM=1 (line 5)") && why.contains("UFRAME_NUM=0 (line 9)"),
        "{why}"
    );
    let backup = [];
    let context = stiffid::internal::machining::program::Context::of(&s)
        .with_backup(&backup)
        .with_leave_refused(true);
    let p =
        stiffid::internal::machining::program::parse_in(&text, Dialect::FanucLs, &context).unwrap();
    // Both Cartesian positions after the paths meet are in the frame the path decides.
    assert_eq!(p.left.iter().map(|l| l.line).collect::<Vec<_>>(), [11, 12]);
    assert_eq!(p.targets.iter().map(|t| t.line).collect::<Vec<_>>(), [7]);
}

/// The files of the drilling cell's controller backup kept beside the corpus: `SYSFRAME.VA` and
/// the program `PLCHANDSHAKE.LS` its programs call.
fn wilder_backup() -> Vec<(String, String)> {
    ["plchandshake.ls", "sysframe.va"]
        .iter()
        .map(|f| {
            let name = format!("wilder-backup/{f}");
            (
                name.clone(),
                std::fs::read_to_string(format!("{DIR}{name}")).unwrap(),
            )
        })
        .collect()
}

/// A program of the drilling cell read with its controller's backup: its user frame 4 and tool
/// frame 2 taken from `SYSFRAME.VA` as the controller holds them, the program it calls after its
/// last motion (`PLCHANDSHAKE.LS`, I/O) passed over; compensation refused naming the position's
/// line, since the cell's tool 2 is not the setup's.
#[test]
fn the_drilling_cells_backup_gives_its_frames_and_its_called_program() {
    use stiffid::internal::machining::program::{cartesian::Frame, parse_in, Context};
    let s = setup();
    let backup = wilder_backup();
    let name = "wilder_tool_1_dropoff_aproach.ls";
    let text = std::fs::read_to_string(format!("{DIR}{name}")).unwrap();
    let p = parse_in(
        &text,
        Dialect::FanucLs,
        &Context::of(&s).with_backup(&backup),
    )
    .unwrap();
    assert_eq!(p.targets.len(), 4);
    for t in &p.targets {
        let c = t.cartesian.as_deref().unwrap();
        let (Frame::Held(_, 4, user, _), Frame::Held(_, 2, tool, _)) = (&c.frame, &c.tool) else {
            panic!("{:?} {:?}", c.frame, c.tool);
        };
        // SYSFRAME.VA's $MNUFRAME[1,4] and $MNUTOOL[1,2], m.
        let (u, k) = (user.translation.vector * 1e3, tool.translation.vector * 1e3);
        assert!(
            (u - Vector3::new(-819.252, -3360.795, -643.547)).norm() < 1e-9,
            "{u}"
        );
        assert!((k - Vector3::new(0.0, -250.8, 152.8)).norm() < 1e-9, "{k}");
        assert_eq!(p.called_in(0), None);
    }
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(s.model())
    .unwrap();
    let options = Options::for_setup(&s);
    let e = compensated_in(&s, &compliance, options, (name, &text), &backup).unwrap_err();
    let (line, why) = refusal(&e);
    assert_eq!(line, 40, "{why}");
    assert!(
        why.contains("the program's tool (X 0 mm, Y -250.8 mm, Z 152.8 mm"),
        "{why}"
    );
}

/// The milling cell with ROS-Industrial's R-2000iC/165F URDF (`robots/r2000ic165f.urdf`) as its
/// robot: its `base` link the controller's world, `tool0` its faceplate, J3 coupled to J2 as the
/// controller counts it (the axis map), [`CONTROLLER`]'s frames.
fn ros_industrial_165f() -> Setup {
    let text = include_str!("../../../../examples/milling/fanuc-milling.toml").replacen(
        "robot = \"fanuc-r2000ic-165f\"",
        "robot = \"r2000ic165f.urdf\"\nrobot_tip = \"tool0\"\nrobot_axis_map = { matrix = [[1,0,0,0,0,0], [0,1,0,0,0,0], [0,1,1,0,0,0], [0,0,0,1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,1]], offset_deg = [0,0,0,0,0,0] }",
        1,
    );
    let urdf = std::fs::read_to_string(format!("{DIR}robots/r2000ic165f.urdf")).unwrap();
    stiffid::internal::setup::parse(&(text + CONTROLLER), "cell.toml", |_, tip| {
        stiffid::internal::robot::urdf::parse(&urdf, "r2000ic165f.urdf", tip)
    })
    .unwrap()
}

/// The sanding path of ROS-Industrial's collaborative robotic sanding (`crs_ws_surface.ls`) on
/// the robot its repository models, ROS-Industrial's R-2000iC/165F: compensated, every target
/// equal to the independent reading and every position written the compensated posture; the
/// same postures as on the milling cell's preset of that robot (its DH model) to 1e-6 rad.
#[test]
fn the_sanding_path_runs_on_ros_industrials_r2000ic_165f() {
    let s = ros_industrial_165f();
    let name = "crs_ws_surface.ls";
    let text = std::fs::read_to_string(format!("{DIR}{name}")).unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let (out, results) =
        compensated_with(&s, &compliance, Options::for_setup(&s), (name, &text)).unwrap();
    assert_eq!(results.len(), 22);
    check(&s, name, (&text, &out), &results);
    let preset = setup();
    let compliance = preset.model_compliance("test").unwrap();
    let (_, on_preset) = compensated_with(
        &preset,
        &compliance,
        Options::for_setup(&preset),
        (name, &text),
    )
    .unwrap();
    for (a, b) in results.iter().zip(&on_preset) {
        assert!((a.q - b.q).amax() < 1e-6, "{}", (a.q - b.q).amax());
    }
    // The other fork's path: out of this arm's reach as on the preset.
    let name = "crs_surface_cartesian.ls";
    let text = std::fs::read_to_string(format!("{DIR}{name}")).unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let e = compensated_with(&s, &compliance, Options::for_setup(&s), (name, &text)).unwrap_err();
    let (line, why) = refusal(&e);
    assert_eq!(line, 27, "{why}");
    assert!(why.contains("the pose is out of reach"), "{why}");
}
