//! INFORM positions in Cartesian form (`///POSTYPE USER` / `BASE`, `///RECTAN`, `///RCONF`,
//! `///USER n`, `///TOOL n`) read through the shared Cartesian targets: each resolves to the
//! posture of the same job in pulses, with the user frame and tool file of the setup's
//! `[controller]` tables or of the backup's `UFRAME.CND` and `TOOL.CND`, and is written back in
//! its own form.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::robot::presets;
use stiffid::Setup;
use stiffid_core::robot::ik::tool_pose;
use stiffid_core::Error;
use stiffid_machining::program::{parse_in, Context, Dialect, JointProgram};

const SETUP: &str = include_str!("../../../../../../examples/milling/fanuc-milling.toml");
const PER_DEG: [f64; 6] = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7];
/// Three postures of the milling cell's test postures' neighbourhood (deg).
const Q: [[f64; 6]; 3] = [
    [-59.991, -16.693, -28.93, 3.788, -62.93, 144.919],
    [-61.5, -14.2, -27.1, 4.4, -61.0, 141.0],
    [-63.0, -12.8, -26.0, 5.1, -60.2, 139.5],
];
/// User frame 2 in the controller's world, mm and deg.
const USER: ([f64; 3], [f64; 3]) = ([1300.0, -700.0, -270.0], [0.0, 0.0, 30.0]);

fn setup(tables: bool) -> Setup {
    let mut text = format!(
        "{SETUP}\n[controller]\npulses_per_deg = {PER_DEG:?}\njoint_targets = \"taught\"\n"
    );
    if tables {
        text.push_str("tools = [{ number = 3, xyz_mm = [6.9, 245.3, 319.3] }]\nbases = [{ number = 2, xyz_mm = [1300, -700, -270], rpy_deg = [0, 0, 30] }]\n");
    }
    stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap()
}

/// The pulses of each posture of [`Q`].
fn pulses() -> Vec<[i64; 6]> {
    (Q.iter())
        .map(|q| std::array::from_fn(|k| (q[k] * PER_DEG[k]).round() as i64))
        .collect()
}

/// A job of three motions (`MOVJ`, `MOVL`, `MOVL`) to `positions`, after the `//POS` lines
/// `head`.
fn job(head: &str, positions: &[String]) -> String {
    let mut pos = String::new();
    for (k, p) in positions.iter().enumerate() {
        pos.push_str(&format!("C{k:05}={p}\r\n"));
    }
    format!("/JOB\r\n//NAME RECT\r\n//POS\r\n///NPOS 3,0,0,0,0,0\r\n{head}{pos}//INST\r\n///DATE 2024/01/01 00:00\r\n///ATTR SC,RW,RJ\r\n///GROUP1 RB1\r\nNOP\r\nMOVJ C00000 VJ=10.00\r\nMOVL C00001 V=20.0\r\nMOVL C00002 V=20.0\r\nEND\r\n")
}

/// User frame 2 in the setup's base frame.
fn user_frame(s: &Setup) -> Isometry3<f64> {
    let (p, r) = USER;
    let r = r.map(f64::to_radians);
    s.program_world()
        * Isometry3::from_parts(
            Translation3::new(p[0] * 1e-3, p[1] * 1e-3, p[2] * 1e-3),
            UnitQuaternion::from_euler_angles(r[0], r[1], r[2]),
        )
}

/// The tool's pose at axis angles `q_deg` in user frame 2.
fn pose(s: &Setup, q_deg: &[f64; 6]) -> Isometry3<f64> {
    let q = Vector6::from(*q_deg).map(f64::to_radians);
    let robot = s.controller_robot().unwrap();
    user_frame(s).inverse() * tool_pose(&robot.frames(&q), &s.tool().tcp)
}

/// `X,Y,Z,Rx,Ry,Rz` of `pose` (mm, deg; `Rz Ry Rx`) with `decimals`.
fn numbers(pose: &Isometry3<f64>, decimals: [usize; 2]) -> String {
    let p = pose.translation.vector * 1e3;
    let (rx, ry, rz) = pose.rotation.euler_angles();
    let [a, b] = decimals;
    let r = [rx, ry, rz].map(|v| format!("{:.b$}", v.to_degrees()));
    format!("{:.a$},{:.a$},{:.a$},{}", p.x, p.y, p.z, r.join(","))
}

/// The job in Cartesian form in user frame 2 with tool file 3: each posture's pose with 9
/// decimals, no flip (the B axis is negative), upper arm, front.
fn rectan(s: &Setup, rconf: &str) -> String {
    let q: Vec<[f64; 6]> = (pulses().iter())
        .map(|p| std::array::from_fn(|k| p[k] as f64 / PER_DEG[k]))
        .collect();
    let positions: Vec<String> = q.iter().map(|q| numbers(&pose(s, q), [9, 9])).collect();
    let head =
        format!("///USER 2\r\n///TOOL 3\r\n///POSTYPE USER\r\n///RECTAN\r\n///RCONF {rconf}\r\n");
    job(&head, &positions)
}

fn resolved(
    s: &Setup,
    text: &str,
    backup: &[(String, String)],
) -> stiffid_core::Result<JointProgram> {
    let context = Context::of(s).with_backup(backup);
    let read = machining::read_in(text, Language::Robot(Dialect::Inform), 1e-4, &context)?;
    let read = machining::resolve(&read, s, None, &Options::for_setup(s))?;
    let Program::Robot(r) = read.into_owned() else {
        panic!()
    };
    Ok(r)
}

fn refused(result: stiffid_core::Result<JointProgram>) -> (u64, String) {
    match result {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("{other:?}"),
    }
}

/// Each Cartesian position resolves to the posture of the same job in pulses, its pose equal to
/// the forward kinematics of the pulse position; written back after a change, the position's
/// numbers are the changed posture's pose in the user frame, mm with 3 decimals and deg with 4,
/// and every other byte (the `///RCONF` line too) is as read.
#[test]
fn a_rectan_position_is_the_pose_of_its_pulse_position() {
    let s = setup(true);
    let text = rectan(&s, "1,0,0,0,0,0,0,0");
    let in_pulses: Vec<String> = (pulses().iter())
        .map(|p| p.map(|v| v.to_string()).join(","))
        .collect();
    let plain = job("///TOOL 3\r\n", &in_pulses);
    let joint = parse_in(&plain, Dialect::Inform, &Context::of(&s)).unwrap();
    let read = resolved(&s, &text, &[]).unwrap();
    assert_eq!(read.targets.len(), 3);
    for (a, b) in read.targets.iter().zip(&joint.targets) {
        let (pa, pb) = (pose(&s, &a.q_deg), pose(&s, &b.q_deg));
        // Within inverse kinematics' tolerance, 1e-10 m and 1e-10 rad.
        let apart = (pa.translation.vector - pb.translation.vector).norm();
        assert!(apart < 1e-10, "{apart} m");
        assert!(pa.rotation.angle_to(&pb.rotation) < 1e-10);
        assert!((Vector6::from(a.q_deg) - Vector6::from(b.q_deg)).amax() < 1e-6);
    }
    let mut q: Vec<[f64; 6]> = read.targets.iter().map(|t| t.q_deg).collect();
    q[1][1] += 0.01;
    let written = read.write(&q).unwrap();
    let changed: Vec<(&str, &str)> = (written.lines().zip(text.lines()))
        .filter(|(a, b)| a != b)
        .collect();
    assert_eq!(changed.len(), 1, "{changed:?}");
    assert_eq!(
        changed[0].0,
        format!("C00001={}", numbers(&pose(&s, &q[1]), [3, 4]))
    );
    assert!(written.contains("///RCONF 1,0,0,0,0,0,0,0\r\n"));
    // A posture whose wrist flips cannot be written under the job's one `///RCONF` line.
    q[2][4] = 12.0;
    let (line, message) = refused(read.write(&q).map(|_| read.clone()));
    assert_eq!(line, 20);
    assert!(
        message.contains("RCONF 0,0,0,0,0,0, the position's RCONF 1,0,0,0,0,0"),
        "{message}"
    );
}

/// The user frame and tool file the backup's `UFRAME.CND` and `TOOL.CND` give are the setup's
/// tables': the same postures without the tables; a `///RCONF` the poses are not reached in,
/// a user frame neither gives, tool coordinates: refused naming the line.
#[test]
fn the_backups_user_frame_and_tool_file_are_read_and_refusals_name_the_line() {
    let (with_tables, bare) = (setup(true), setup(false));
    let text = rectan(&with_tables, "1,0,0,0,0,0,0,0");
    let tables = resolved(&with_tables, &text, &[]).unwrap();
    let backup = [
        ("CMOS/UFRAME.CND".to_string(), "//UFRAME 2\r\n///NAME TABLE\r\n///TOOL 0\r\n///GROUP 1,0,0,0\r\n///PULSE\r\n////RORG C000=0,0,0,0,0,0\r\n////RXX C001=0,0,0,0,0,0\r\n////RXY C002=0,0,0,0,0,0\r\n////BUSER 1300.000,-700.000,-270.000,0.0000,0.0000,30.0000\r\n".to_string()),
        ("CMOS/TOOL.CND".to_string(), "//TOOL 3\r\n///NAME SPINDLE\r\n6.900,245.300,319.300,0.0000,0.0000,0.0000\r\n0.000,0.000,0.000\r\n1.000\r\n0.000,0.000,0.000\r\n0.000,0,1\r\n".to_string()),
    ];
    let held = resolved(&bare, &text, &backup).unwrap();
    for (a, b) in held.targets.iter().zip(&tables.targets) {
        assert!((Vector6::from(a.q_deg) - Vector6::from(b.q_deg)).amax() < 1e-6);
    }
    // A UFRAME.CND with no user frame block (empty, or headers only) names the file.
    for empty in ["", "///NAME TABLE\r\n"] {
        let given = [("CMOS/UFRAME.CND".to_string(), empty.to_string())];
        match resolved(&bare, &text, &given) {
            Err(Error::Parse {
                source_name,
                message,
            }) => {
                assert_eq!(source_name, "CMOS/UFRAME.CND");
                assert!(
                    message.starts_with("no user frame: the file is empty"),
                    "{message}"
                );
            }
            other => panic!("{other:?}"),
        }
    }
    // One that holds other user frames names itself and the frames it gives.
    let other = [
        (
            backup[0].0.clone(),
            backup[0].1.replace("//UFRAME 2", "//UFRAME 7"),
        ),
        backup[1].clone(),
    ];
    let (line, message) = refused(resolved(&bare, &text, &other));
    assert_eq!(line, 5, "{message}");
    assert!(
        message.contains("user frame 2: the backup's CMOS/UFRAME.CND gives user frames 7 only"),
        "{message}"
    );
    let (line, message) = refused(resolved(&bare, &text, &backup[1..]));
    assert_eq!(line, 5, "{message}");
    assert!(
        message.contains("frame number 2 of the controller's bases"),
        "{message}"
    );
    let rear = rectan(&with_tables, "1,0,1,0,0,0,0,0");
    let (line, message) = refused(resolved(&with_tables, &rear, &[]));
    assert_eq!(line, 18, "{message}");
    assert!(
        message.contains("out of reach in the configuration RCONF 1,0,1,0,0,0"),
        "{message}"
    );
    let tool = text.replace("///POSTYPE USER", "///POSTYPE TOOL");
    let (line, message) = refused(resolved(&with_tables, &tool, &[]));
    assert_eq!(line, 18, "{message}");
    assert!(
        message.contains("///POSTYPE TOOL (line 10): tool coordinates"),
        "{message}"
    );
    // In base coordinates: each pose stated in the controller's world, the same postures.
    let world = with_tables.program_world();
    let positions: Vec<String> = (tables.targets.iter())
        .map(|t| {
            numbers(
                &(world.inverse() * user_frame(&with_tables) * pose(&with_tables, &t.q_deg)),
                [9, 9],
            )
        })
        .collect();
    let head = "///TOOL 3\r\n///POSTYPE BASE\r\n///RECTAN\r\n///RCONF 1,0,0,0,0,0,0,0\r\n";
    let base = resolved(&with_tables, &job(head, &positions), &[]).unwrap();
    for (a, b) in base.targets.iter().zip(&tables.targets) {
        assert!((Vector6::from(a.q_deg) - Vector6::from(b.q_deg)).amax() < 1e-6);
    }
}

/// A job of the controller's second robot (`///GROUP1 RB2`) is refused naming its line unless
/// the setup says its robot is that one (`[controller] robot_number = 2`), then read as the
/// same job of `RB1` is; a job of `RB1` is then refused; a number beyond 8 is refused naming the
/// field.
#[test]
fn a_job_of_the_second_robot_is_read_when_the_setup_names_it() {
    let in_pulses: Vec<String> = (pulses().iter())
        .map(|p| p.map(|v| v.to_string()).join(","))
        .collect();
    let first = job("///TOOL 3\r\n", &in_pulses);
    let second = first.replace("///GROUP1 RB1", "///GROUP1 RB2");
    let with = |more: &str| {
        let text = format!("{SETUP}\n[controller]\npulses_per_deg = {PER_DEG:?}\n{more}");
        stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n))
    };
    let (one, two) = (with("").unwrap(), with("robot_number = 2\n").unwrap());
    let (line, message) = refused(parse_in(&second, Dialect::Inform, &Context::of(&one)));
    assert_eq!(line, 12);
    assert!(message.contains("a job of robot RB2"), "{message}");
    let read = parse_in(&second, Dialect::Inform, &Context::of(&two)).unwrap();
    let same = parse_in(&first, Dialect::Inform, &Context::of(&one)).unwrap();
    assert_eq!(read.targets.len(), 3);
    for (a, b) in read.targets.iter().zip(&same.targets) {
        assert_eq!(a.q_deg, b.q_deg);
    }
    let (line, message) = refused(parse_in(&first, Dialect::Inform, &Context::of(&two)));
    assert_eq!(line, 12);
    assert!(message.contains("a job of robot RB1"), "{message}");
    match with("robot_number = 9\n") {
        Err(e) => assert!(e.to_string().contains("controller.robot_number"), "{e}"),
        Ok(_) => panic!("robot_number = 9 read"),
    }
}

/// A motion to a Cartesian position variable of the backup's `VAR.DAT` (`"RECTAN"` in user
/// frame 2 with tool file 3, as a YRC1000 writes it) resolves to the posture of the same pose
/// taught in the job; compensated, its copy is written as a Cartesian position of the job in
/// the variable's frame, tool file and `///RCONF` (the job's listing of the variable), the
/// variable left as it is. Refused naming the motion's line: a manipulator type neither all
/// zero nor listed by the job, tool coordinates (a shift amount), a value of a seventh axis.
#[test]
fn a_cartesian_variable_is_read_in_its_frame_and_copied_into_the_job() {
    let s = setup(true);
    let taught = rectan(&s, "1,0,0,0,0,0,0,0");
    let inline = resolved(&s, &taught, &[]).unwrap();
    let pose_text = taught.lines().find(|l| l.starts_with("C00001=")).unwrap()[7..].to_string();
    let listing = format!("///USER 2\r\n///TOOL 3\r\n///POSTYPE USER\r\n///RECTAN\r\n///RCONF 1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\r\nP00001={pose_text}\r\n");
    let job = taught
        .replace("MOVL C00001", "MOVL P001")
        .replace(&format!("C00001={pose_text}\r\n"), "")
        .replace("///NPOS 3,0,0,0,0,0", "///NPOS 2,0,0,1,0,0")
        .replace("//INST", &format!("{listing}//INST"))
        .replace("C00002=", "C00001=")
        .replace("MOVL C00002", "MOVL C00001");
    let var = |config: &str, coordinates: u32, more: &str| {
        let line = format!("\"RECTAN\"0,2,3,{config},0,{coordinates},{pose_text},{more}");
        let text = format!(
            "//VAR\r\n///PFNUM 6,0,0,0\r\n///P\r\n\"UNUSED\"\r\n{line}\r\n///BP\r\n///EX\r\n"
        );
        vec![("backup/VAR.DAT".to_string(), text)]
    };
    let flags = "100000000000000000000000";
    let read = resolved(&s, &job, &var(flags, 19, "0.0000,0.0000")).unwrap();
    for (a, b) in read.targets.iter().zip(&inline.targets) {
        assert!((Vector6::from(a.q_deg) - Vector6::from(b.q_deg)).amax() < 1e-6);
    }
    let mut q: Vec<[f64; 6]> = read.targets.iter().map(|t| t.q_deg).collect();
    q[1][1] += 0.01;
    let written = read.write(&q).unwrap();
    let copy = format!("///TOOL 3\r\n///USER 2\r\n///POSTYPE USER\r\n///RECTAN\r\n///RCONF 1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\r\nC00002={}\r\n//INST", numbers(&pose(&s, &q[1]), [3, 4]));
    assert!(written.contains(&copy), "{written}");
    assert!(
        written.contains("MOVL C00002 V=20.0\r\nMOVL C00001 V=20.0"),
        "{written}"
    );
    assert!(
        written.contains(&format!("P00001={pose_text}\r\n")),
        "{written}"
    );
    let unlisted = job
        .replace(&listing, "")
        .replace("///NPOS 2,0,0,1", "///NPOS 2,0,0,0");
    let cases = [
        (
            unlisted.as_str(),
            var(flags, 19, "0,0"),
            "in an order that is not public",
        ),
        (&job, var(flags, 18, "0,0"), "in tool coordinates (18)"),
        (
            &job,
            var(flags, 19, "12.5000,0"),
            "a value after X,Y,Z,Rx,Ry,Rz (12.5000)",
        ),
        (
            &job,
            var("000000000000000000000000", 19, "0,0"),
            "the job lists the variable (line 17",
        ),
    ];
    for (text, files, words) in cases {
        let (line, message) = refused(resolved(&s, text, &files));
        assert_eq!(line, if text == unlisted { 18 } else { 24 }, "{message}");
        assert!(message.contains(words), "{words}: {message}");
    }
}

/// A parallel shift of a constant amount (`SFTON P001 UF#(2)` .. `SFTOF`, the amount a
/// Cartesian variable of `VAR.DAT` in user frame 2) moves the motions between to their
/// positions displaced by it: the posture of the same job taught at the displaced position;
/// written back, the position the controller displaces to the compensated pose. Refused naming
/// the line: a shift that turns, one in other coordinates than the position's, a shift of a
/// pulse position, one set as the job runs, a label under it, no `SFTOF`.
#[test]
fn a_constant_shift_is_computed_and_a_run_time_one_refused() {
    let s = setup(true);
    let taught = rectan(&s, "1,0,0,0,0,0,0,0");
    let c1 = taught.lines().find(|l| l.starts_with("C00001=")).unwrap()[7..].to_string();
    let mut n: Vec<f64> = c1.split(',').map(|v| v.parse().unwrap()).collect();
    let job = taught.replace(
        "MOVL C00001 V=20.0\r\n",
        "SFTON P001 UF#(2)\r\nMOVL C00001 V=20.0\r\nSFTOF\r\n",
    );
    let var = |amount: &str| {
        let text = format!("//VAR\r\n///PFNUM 6,0,0,0\r\n///P\r\n\"UNUSED\"\r\n\"RECTAN\"0,2,0,000000000000000000000000,0,19,{amount},0.0000,0.0000\r\n///BP\r\n///EX\r\n");
        vec![("backup/VAR.DAT".to_string(), text)]
    };
    let d = [5.0, -3.0, 2.0];
    let read = resolved(&s, &job, &var("5.000,-3.000,2.000,0.0000,0.0000,0.0000")).unwrap();
    for k in 0..3 {
        n[k] += d[k];
    }
    let moved: Vec<String> = n.iter().map(|v| format!("{v:.9}")).collect();
    let displaced = resolved(&s, &taught.replace(&c1, &moved.join(",")), &[]).unwrap();
    for (a, b) in read.targets.iter().zip(&displaced.targets) {
        assert!((Vector6::from(a.q_deg) - Vector6::from(b.q_deg)).amax() < 1e-6);
    }
    let mut q: Vec<[f64; 6]> = read.targets.iter().map(|t| t.q_deg).collect();
    q[1][1] += 0.01;
    let written = read.write(&q).unwrap();
    let mut back = pose(&s, &q[1]);
    back.translation.vector -= Vector3::from(d) * 1e-3;
    assert!(
        written.contains(&format!("C00001={}\r\n", numbers(&back, [3, 4]))),
        "{written}"
    );
    let pulses_job = job.replace(
        "///POSTYPE USER\r\n///RECTAN\r\n///RCONF 1,0,0,0,0,0,0,0\r\n",
        "",
    );
    let in_pulses: Vec<String> = (pulses().iter())
        .map(|p| p.map(|v| v.to_string()).join(","))
        .collect();
    let mut pulses_job = pulses_job;
    for (k, p) in in_pulses.iter().enumerate() {
        let old = taught
            .lines()
            .find(|l| l.starts_with(&format!("C{k:05}=")))
            .unwrap()
            .to_string();
        pulses_job = pulses_job.replace(&old, &format!("C{k:05}={p}"));
    }
    let amount = "5.000,-3.000,2.000,0.0000,0.0000,0.0000";
    let cases = [
        (
            job.clone(),
            var("5.000,-3.000,2.000,0.0000,0.0000,1.0000"),
            19,
            "a shift that turns the tool",
        ),
        (
            job.replace("UF#(2)", "BF"),
            var(amount),
            19,
            "a shift amount in coordinates 19 (user frame 2), shifted in base coordinates (BF)",
        ),
        (
            pulses_job,
            var(amount),
            17,
            "a position in pulses shifted by SFTON P001 UF#(2) (line 16)",
        ),
        (
            job.replace("SFTOF", "ADD P001 P000\r\nSFTOF"),
            var(amount),
            19,
            "set as the jobs run (line 21: ADD P001 P000)",
        ),
        (
            job.replace("SFTOF", "*HERE\r\nSFTOF"),
            var(amount),
            21,
            "a jump, call, branch or label while the shift of line 19",
        ),
        (
            job.replace("SFTOF\r\n", ""),
            var(amount),
            19,
            "a shift with no SFTOF after it",
        ),
    ];
    for (text, files, line, words) in cases {
        let (l, message) = refused(resolved(&s, &text, &files));
        assert_eq!(l, line, "{words}: {message}");
        assert!(message.contains(words), "{words}: {message}");
    }
}
