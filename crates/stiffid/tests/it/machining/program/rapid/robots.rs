//! The stored real RAPID modules (`tests/data/programs/rapid/`, SOURCES.md) run as found, with
//! the other modules of their task (`--backup`), on the robots they were written for: the
//! ROS-Industrial models of `tests/data/robots/` (SOURCES.md there), each with the module's own
//! tool. Each is compensated, every target checked against the file read here apart from the
//! reader (the target's pose the file's to 1e-6 mm through the model's forward kinematics of the
//! solved posture; a joint target the file's angles), or refused naming the line and a
//! construct that neither the module nor its task's other modules state.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector6};
use stiffid::app::compensate::{self, Input};
use stiffid::internal::machining::compensate::{Compensated, Options, PathPoint, Target};
use stiffid::internal::machining::program::{Dialect, Reading};
use stiffid::internal::machining::Language;
use stiffid::internal::model::Compliance;
use stiffid::internal::robot::ik::tool_pose;
use stiffid::{Error, Setup};

/// The test data folder.
fn data(path: &str) -> String {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");
    std::fs::read_to_string(format!("{dir}/{path}")).unwrap()
}

/// A cell of the ROS-Industrial robot `urdf` (its flange the link `tip`, `more` added to the
/// setup: an axis map) holding the tool `tcp_mm` of `mass_kg`.
pub(crate) fn cell(urdf: &str, tip: &str, more: &str, tcp_mm: [f64; 3], mass_kg: f64) -> Setup {
    let [x, y, z] = tcp_mm;
    let text = format!("name = \"cell\"\ndescription = \"a ROS-Industrial robot\"\nrobot = \"{urdf}\"\nrobot_tip = \"{tip}\"\nsprings = \"axis\"\n{more}\n[tool]\nmeasuring_points_mm = [[{x}, {y}, {z}]]\ntcp_mm = [{x}, {y}, {z}]\nmass_kg = {mass_kg}\ncentre_of_mass_mm = [{x}, {y}, {}]\n\n[noise]\nreading_sd_mm = 0.01\n", z / 2.0);
    stiffid::internal::setup::parse(&text, "cell.toml", |name, tip| {
        stiffid::internal::robot::urdf::parse(&data(&format!("robots/{name}")), name, tip)
    })
    .unwrap()
}

/// No cut: every motion carries the tool's weight alone.
pub(crate) const HANDLING: &str = "[[operation]]\nname = \"none\"\nlines = [1, 1]\n[operation.tool]\ndiameter_mm = 10\nflutes = 2\nhelix_deg = 30\n[operation.cut]\nfeed_per_tooth_mm = 0.05\naxial_depth_mm = 1\nradial_depth_mm = 1\nmode = \"down\"\n[operation.coefficients]\npreset = \"al7075-t6\"\n";

/// The program `name` (its `text`, its backup `files`) compensated on `setup` as the command
/// does (`--backup`, `--leave-refused` as `leave`): every point's target and result.
pub(crate) fn run(
    setup: &Setup,
    (name, text, dialect): (&str, &str, Dialect),
    files: &[(String, String)],
    leave: bool,
) -> stiffid::Result<Vec<(PathPoint, Compensated)>> {
    let process = stiffid::internal::machining::process::file::parse(HANDLING, "handling.toml")?;
    let h = Vector6::new(2e-6, 2e-6, 3e-6, 1e-5, 1e-5, 2e-5);
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance: Compliance::drives(h, None),
        input: Input::Program {
            encoding: Default::default(),
            reading: Reading {
                backup: files,
                leave_refused: leave,
            },
            name: name.into(),
            text,
            data: None,
            language: Language::Robot(dialect),
            process_name: "handling.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output: Language::Robot(dialect),
            out_name: format!("compensated_{name}"),
            settings: Default::default(),
        },
        options: Options::for_setup(setup),
    };
    let mut points = Vec::new();
    compensate::run::<Error, _>(request, |_, p, r, _| {
        points.extend(p.iter().cloned().zip(r.iter().cloned()));
        Ok(())
    })?;
    Ok(points)
}

/// The error a file's refusal holds (the command names the file around it).
pub(crate) fn inner(e: Error) -> Error {
    match e {
        Error::Input { error, .. } => inner(*error),
        other => other,
    }
}

/// The numbers of a RAPID literal `[[..],[..],..]`, read here apart from the reader.
fn numbers(literal: &str) -> Vec<f64> {
    literal
        .split(['[', ']', ','])
        .map(str::trim)
        .filter(|w| !w.is_empty())
        .map(|w| w.parse::<f64>().unwrap())
        .collect()
}

/// A target of the file, read here: a `robtarget`'s pose in the work object (m) or a
/// `jointtarget`'s angles (deg).
#[derive(Debug)]
enum Read {
    Pose(Isometry3<f64>),
    Joints([f64; 6]),
}

/// The motions of `text` with their targets, read here (the `CONST robtarget` declarations of
/// the module, joint targets written as literals): `(line, target)`.
fn motions(text: &str) -> Vec<(u64, Read)> {
    let mut declared = std::collections::HashMap::new();
    for l in text.lines().map(str::trim) {
        if let Some(rest) = l.strip_prefix("CONST robtarget ") {
            let (name, value) = rest.split_once(":=").unwrap();
            let n = numbers(value.trim_end_matches(';'));
            let q = UnitQuaternion::from_quaternion(Quaternion::new(n[3], n[4], n[5], n[6]));
            let p = Translation3::new(n[0] * 1e-3, n[1] * 1e-3, n[2] * 1e-3);
            declared.insert(name.to_string(), Isometry3::from_parts(p, q));
        }
    }
    let mut out = Vec::new();
    for (k, l) in text.lines().enumerate() {
        let l = l.trim();
        let line = k as u64 + 1;
        if let Some(rest) = l.strip_prefix("MoveAbsJ ") {
            let n = numbers(&rest[..rest.find("]]").unwrap() + 2]);
            out.push((line, Read::Joints([n[0], n[1], n[2], n[3], n[4], n[5]])));
        } else if let Some(rest) = l.strip_prefix("MoveL ").or(l.strip_prefix("MoveJ ")) {
            let name = rest.split(',').next().unwrap();
            out.push((line, Read::Pose(declared[name])));
        }
    }
    out
}

/// Every point of `points` against the file's own motions `file` (in the world frame: the
/// modules move in `wobj0`): the same lines, the pose the file's and the forward kinematics of
/// the solved posture on it, a joint target's angles the file's.
fn check(setup: &Setup, points: &[(PathPoint, Compensated)], file: &[(u64, Read)]) {
    assert_eq!(points.len(), file.len());
    for ((p, c), (line, read)) in points.iter().zip(file) {
        assert_eq!(p.line, *line);
        match (&p.target, read) {
            // A Cartesian target reaches the compensation as the posture the controller solves
            // it to: its forward kinematics is the file's pose.
            (Target::Posture(q), Read::Pose(stated)) => {
                assert!((q - c.q).norm() < 1e-12, "line {line}");
                let fk = tool_pose(&setup.robot().frames(&c.q), &setup.tool().tcp);
                let d = (fk.translation.vector - stated.translation.vector).norm();
                assert!(d < 1e-9, "line {line}: {d} m");
                assert!(fk.rotation.angle_to(&stated.rotation) < 1e-9, "line {line}");
            }
            (Target::Posture(q), Read::Joints(deg)) => {
                let stated = Vector6::from(*deg).map(f64::to_radians);
                assert!((q - stated).norm() < 1e-12, "line {line}");
                assert!((c.q - stated).norm() < 1e-12, "line {line}");
            }
            other => panic!("line {line}: {other:?}"),
        }
        assert!((c.q_compensated - c.q).norm() > 0.0, "line {line}");
    }
}

/// A stored module's run: the file, its task's other modules, the robot (URDF) and the tool
/// (the module's `tooldata`, mm, kg), whether refused motions are left as found, and the outcome:
/// the targets compensated, or the line refused and the words its message holds.
struct Case {
    file: &'static str,
    backup: &'static [&'static str],
    robot: &'static str,
    tool: ([f64; 3], f64),
    leave: bool,
    refused: Option<(u64, &'static [&'static str])>,
}

const SMC: ([f64; 3], f64) = ([0.0, 0.004, 197.001], 1.0);
const SERVO: ([f64; 3], f64) = ([0.0, 0.0, 114.2], 0.24);

/// The stored modules with motions whose robot has a ROS-Industrial model (SOURCES.md).
const CASES: [Case; 8] = [
    Case {
        file: "Tutorial-Simple_Module1.mod",
        backup: &["Tutorial-Simple_CalibData.mod"],
        robot: "abb_irb120_3_58.urdf",
        tool: SMC,
        leave: false,
        refused: None,
    },
    Case {
        file: "VInRoS_DP.mod",
        backup: &[],
        robot: "abb_irb120_3_58.urdf",
        tool: ([0.0, 0.0, 0.0], 2.0),
        leave: false,
        refused: Some((10, &["out of reach in the configuration [0,0,0,0]"])),
    },
    Case {
        file: "SortingLine_IRB_1200_T_ROB1_Module1.mod",
        backup: &["SortingLine_IRB_1200_T_ROB1_CalibData.mod"],
        robot: "abb_irb1200_5_90.urdf",
        tool: SMC,
        leave: false,
        refused: Some((164, &["Offs: x = '0 + offset_T_x'"])),
    },
    Case {
        file: "SortingLine_IRB_1200_T_ROB1_Module1.mod",
        backup: &["SortingLine_IRB_1200_T_ROB1_CalibData.mod"],
        robot: "abb_irb1200_5_90.urdf",
        tool: SMC,
        leave: true,
        refused: Some((136, &["out of reach"])),
    },
    Case {
        file: "SortingLine_IRB_1200_T_ROB2_Module1.mod",
        backup: &["SortingLine_IRB_1200_T_ROB2_CalibData.mod"],
        robot: "abb_irb1200_5_90.urdf",
        tool: SERVO,
        leave: false,
        refused: Some((93, &["out of reach"])),
    },
    Case {
        file: "SortingLine_GoFa_Controller1_Module1.mod",
        backup: &["SortingLine_GoFa_Controller1_CalibData.mod"],
        robot: "abb_crb15000_5_95.urdf",
        tool: SMC,
        leave: true,
        refused: Some((68, &["eax_a 0", "no external axes"])),
    },
    Case {
        file: "SortingLine_GoFa_Controller2_Module1.mod",
        backup: &["SortingLine_GoFa_Controller2_CalibData.mod"],
        robot: "abb_crb15000_5_95.urdf",
        tool: SERVO,
        leave: false,
        refused: Some((120, &["the program's tool (X 63.5 mm"])),
    },
    Case {
        file: "EGM_IRB_120_Module1.mod",
        backup: &[],
        robot: "abb_irb120_3_58.urdf",
        tool: ([0.0, 0.0, 0.0], 0.5),
        leave: true,
        refused: Some((39, &["singular"])),
    },
];

#[test]
fn the_stored_modules_run_on_the_robots_they_were_written_for() {
    for case in &CASES {
        let setup = cell(case.robot, "tool0", "", case.tool.0, case.tool.1);
        let text = data(&format!("programs/rapid/{}", case.file));
        let files: Vec<(String, String)> = (case.backup.iter())
            .map(|b| (b.to_string(), data(&format!("programs/rapid/{b}"))))
            .collect();
        let run = run(
            &setup,
            (case.file, &text, Dialect::Rapid),
            &files,
            case.leave,
        );
        match (run.map_err(inner), case.refused) {
            (Ok(points), None) => check(&setup, &points, &motions(&text)),
            (Err(e @ (Error::Program { .. } | Error::Column { .. })), Some((at, says))) => {
                let (Error::Program { line, .. } | Error::Column { line, .. }) = e else {
                    unreachable!()
                };
                let message = e.to_string();
                assert_eq!(line, at, "{}: {message}", case.file);
                for words in says {
                    assert!(message.contains(words), "{}: {message}", case.file);
                }
            }
            (other, _) => panic!("{}: {:?}", case.file, other.map(|p| p.len())),
        }
    }
}

/// ROS-Industrial's KR 210 L150 turns its joints 1, 4 and 6 the other way from KUKA's A1, A4 and
/// A6 (its later models turn them about -z and -x, as the controller), its joint 2 from the
/// upright arm (KUKA's A2 -90 deg) and its joint 3 from the forearm square to the upper arm (A3
/// +90 deg): the setup's `robot_axis_map` makes the axes KUKA's, its joint limits bound them
/// mapped back (A2 -135 to -5 deg, A3 -120 to 155 deg), and KUKA's home posture is the URDF's
/// zero.
#[test]
fn the_kr210l150_takes_kukas_axes_through_the_setups_axis_map() {
    let map = "robot_axis_map = { matrix = [[-1,0,0,0,0,0], [0,1,0,0,0,0], [0,0,1,0,0,0], [0,0,0,-1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,-1]], offset_deg = [0, 90, -90, 0, 0, 0] }";
    let kuka = cell(
        "kuka_kr210l150.urdf",
        "flange",
        map,
        [0.0, 0.0, 250.0],
        25.0,
    );
    let urdf = cell("kuka_kr210l150.urdf", "flange", "", [0.0, 0.0, 250.0], 25.0);
    let limits = kuka.robot().limits();
    let deg = |v: Vector6<f64>| v.map(|x| (x.to_degrees() * 1e6).round() / 1e6);
    assert_eq!(
        deg(limits.lower),
        Vector6::new(-185.0, -135.0, -120.0, -350.0, -125.0, -350.0)
    );
    assert_eq!(
        deg(limits.upper),
        Vector6::new(185.0, -5.0, 155.0, 350.0, 125.0, 350.0)
    );
    let at = |s: &Setup, q: [f64; 6]| {
        let q = Vector6::from(q).map(f64::to_radians);
        s.robot().frames(&q).flange
    };
    let home = at(&kuka, [0.0, -90.0, 90.0, 0.0, 0.0, 0.0]);
    let zero = at(&urdf, [0.0; 6]);
    assert!((home.translation.vector - zero.translation.vector).norm() < 1e-12);
    assert!(home.rotation.angle_to(&zero.rotation) < 1e-12);
    // A1 positive turns the arm clockwise seen from above (to -y), A4 and A6 as the URDF's
    // joints turned back.
    assert!(at(&kuka, [30.0, -90.0, 90.0, 0.0, 0.0, 0.0]).translation.y < -0.5);
    let wrist = at(&kuka, [0.0, -90.0, 90.0, 20.0, 30.0, 40.0]);
    let joints = at(&urdf, [0.0, 0.0, 0.0, -20.0, 30.0, -40.0]);
    assert!((wrist.translation.vector - joints.translation.vector).norm() < 1e-12);
    assert!(wrist.rotation.angle_to(&joints.rotation) < 1e-12);
}
