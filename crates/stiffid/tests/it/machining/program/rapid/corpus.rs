//! The stored corpus of real RAPID modules (`tests/data/programs/rapid/`, each one's
//! repository, commit and licence in its `SOURCES.md`), run as stored: every refusal names its
//! line and construct, and the file itself, read line by line here, holds that construct on
//! that line (and each enclosing construct on the line the message gives it).

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::program::{self, Dialect};
use stiffid::internal::machining::{self, Language};
use stiffid::internal::robot::presets;
use stiffid::{Error, Setup};
use stiffid_machining::program::cartesian::{flags::Flags, Frame};
use stiffid_machining::program::rapid::ConfData;

/// A stored module's refusal: the line it names, the words of its message, and the words each
/// named line of the file holds (the file's own text, read here line by line).
struct Refusal {
    file: &'static str,
    line: u64,
    says: &'static [&'static str],
    holds: &'static [(usize, &'static str)],
}

/// The modules read without a refusal: checked point by point in
/// [`a_generated_path_is_read_point_by_point_as_the_file_states_it`].
const READ: [&str; 4] = [
    "VInRoS_DP.mod",
    "Tutorial-Simple_Module1.mod",
    "SortingLine_IRB_1200_T_ROB2_Module1.mod",
    "SortingLine_GoFa_Controller2_Module1.mod",
];

/// The modules refused as read (`program::parse`), without a setup.
const REFUSED: [Refusal; 22] = [
    Refusal {
        file: "ROS_motion.mod",
        line: 66,
        says: &["MoveAbsJ target: target is assigned on line 56"],
        holds: &[
            (66, "MoveAbsJ target"),
            (56, "target.robax := trajectory{current_index}"),
        ],
    },
    Refusal {
        file: "motion.mod",
        line: 43,
        says: &["MOVEABSJ target: target is assigned on line 41"],
        holds: &[
            (43, "MOVEABSJ target"),
            (41, "target.robax := motion_trajectory"),
        ],
    },
    Refusal {
        file: "motion_program_exec.mod",
        line: 299,
        says: &["MoveAbsJ j: j is declared on line 288 without a value"],
        holds: &[(299, "MoveAbsJ j,"), (288, "VAR jointtarget j;")],
    },
    Refusal {
        file: "Axxx_Motion_Procs_21.mod",
        line: 20,
        says: &["MoveL current_pos: not a robtarget declared in this module"],
        holds: &[(20, "MoveL RelTool(current_pos, 0, 0, -100)")],
    },
    Refusal {
        file: "ROS_motionServer.mod",
        line: 1,
        says: &[
            "no motion instruction",
            "main (line 38)",
            "trajectory_pt_callback (line 64)",
            "add_traj_pt (line 100)",
            "activate_trajectory (line 110)",
        ],
        holds: &[
            (38, "PROC main()"),
            (64, "PROC trajectory_pt_callback("),
            (100, "PROC add_traj_pt("),
            (110, "PROC activate_trajectory()"),
        ],
    },
    Refusal {
        file: "ROS_stateServer.mod",
        line: 1,
        says: &[
            "no motion instruction",
            "main (line 37)",
            "send_joints (line 60)",
            "send_status (line 87)",
        ],
        holds: &[
            (37, "PROC main()"),
            (60, "PROC send_joints()"),
            (87, "PROC send_status()"),
        ],
    },
    Refusal {
        file: "ROS_socket.sys",
        line: 1,
        says: &[
            "no motion instruction",
            "ros_init_socket (line 30)",
            "ros_wait_for_client (line 39)",
            "ros_receive_msg (line 55)",
            "ros_send_msg (line 89)",
        ],
        holds: &[
            (30, "PROC ROS_init_socket("),
            (39, "PROC ROS_wait_for_client("),
            (55, "PROC ROS_receive_msg("),
            (89, "PROC ROS_send_msg("),
        ],
    },
    Refusal {
        file: "ROS_messages.sys",
        line: 1,
        says: &[
            "no motion instruction",
            "ros_receive_msg_joint_traj_pt (line 100)",
            "ros_send_msg_joint_data (line 153)",
            "ros_send_msg_robot_status (line 187)",
        ],
        holds: &[
            (100, "PROC ROS_receive_msg_joint_traj_pt("),
            (153, "PROC ROS_send_msg_joint_data("),
            (187, "PROC ROS_send_msg_robot_status("),
        ],
    },
    Refusal {
        file: "ROS_common.sys",
        line: 1,
        says: &["no motion instruction", "holds no routine"],
        holds: &[(1, "MODULE ROS_common")],
    },
    Refusal {
        file: "EGM_IRB_120_Module1.mod",
        line: 74,
        says: &["EGMRunJoint: an Externally Guided Motion"],
        holds: &[
            (74, "EGMRunJoint egm_id, EGM_STOP_HOLD"),
            (58, "WHILE TRUE DO"),
        ],
    },
    Refusal {
        file: "SortingLine_GoFa_Controller1_Module1.mod",
        line: 166,
        says: &[
            "Offs: x = '0 + offset_T_x' is not a number written in the call",
            "offset_t_x is the argument '(r_str.objec_type - 1)*r_str.env_param.tAB_offset_x' of the call on line 86",
            "(in PP_TP_AB, called on line 86)",
        ],
        holds: &[(166, "MoveJ Offs(Target_INIT_AP1,0 + offset_T_x")],
    },
    Refusal {
        file: "SortingLine_IRB_1200_T_ROB1_CalibData.mod",
        line: 1,
        says: &["no motion instruction", "holds no routine"],
        holds: &[(2, "PERS tooldata smc_gripper")],
    },
    Refusal {
        file: "SortingLine_IRB_1200_T_ROB2_CalibData.mod",
        line: 1,
        says: &["no motion instruction", "holds no routine"],
        holds: &[(2, "PERS tooldata Servo"), (3, "PERS tooldata VaccumOne")],
    },
    Refusal {
        file: "SortingLine_GoFa_Controller1_CalibData.mod",
        line: 1,
        says: &["no motion instruction", "holds no routine"],
        holds: &[(2, "PERS tooldata smc_gripper")],
    },
    Refusal {
        file: "SortingLine_GoFa_Controller2_CalibData.mod",
        line: 1,
        says: &["no motion instruction", "holds no routine"],
        holds: &[(2, "PERS tooldata Servo")],
    },
    Refusal {
        file: "Tutorial-Simple_CalibData.mod",
        line: 1,
        says: &["no motion instruction", "holds no routine"],
        holds: &[(2, "PERS tooldata smc_gripper")],
    },
    Refusal {
        file: "data_processing_Module1.mod",
        line: 14,
        says: &["MoveAbsJ J_Orientation_Target{i}: j_orientation_target is an array of jointtargets (line 2) declared without a value"],
        holds: &[
            (14, "MoveAbsJ J_Orientation_Target{i}"),
            (13, "FOR i FROM 1 TO 5 DO"),
            (7, "TEST main_state"),
        ],
    },
    Refusal {
        file: "SortingLine_IRB_1200_T_ROB1_Module1.mod",
        line: 164,
        says: &[
            "Offs: x = '0 + offset_T_x' is not a number written in the call",
            "offset_t_x is the argument 'r_str.tAB_actual_counter*r_str.env_param.tAB_offset_x' of the call on line 84",
            "(in PP_TP_AB, called on line 84)",
        ],
        holds: &[
            (164, "MoveL Offs(Target_INIT_AP1,0 + offset_T_x"),
            (57, "TEST r_str.actual_state"),
        ],
    },
    Refusal {
        file: "mfc_test_path1.mod",
        line: 39,
        says: &["FCPress1LStart: a force-controlled motion"],
        holds: &[
            (39, "FCPress1LStart T1Process1, v50"),
            (8, "generated by RobotWare Machining FC V3.000"),
        ],
    },
    Refusal {
        file: "mfc_rMach_path1.mod",
        line: 49,
        says: &["FCPress1LStart: a force-controlled motion"],
        holds: &[(49, "FCPress1LStart ")],
    },
    Refusal {
        file: "MFCUserData.sys",
        line: 1,
        says: &[
            "no motion instruction",
            "spindleon (line 21)",
            "spindleoff (line 25)",
        ],
        holds: &[
            (21, "PROC SpindleOn()"),
            (25, "PROC SpindleOff()"),
            (8, "TASK PERS tooldata mfcTool1"),
        ],
    },
    Refusal {
        file: "error_reporter.mod",
        line: 1,
        says: &[
            "no motion instruction",
            "main (line 5)",
            "motion_program_trap_err (line 14)",
        ],
        holds: &[(5, "PROC main()"), (14, "TRAP motion_program_trap_err")],
    },
];

/// The module refused on a setup: `ABB_Example_21.sys`, its motions read, refused where its
/// work object's frame is the controller's (`ufprog FALSE`, moved by `ROB_1`).
const ON_SETUP: Refusal = Refusal {
    file: "ABB_Example_21.sys",
    line: 14,
    says: &["wobjdata obrob11_tool0", "ufprog FALSE"],
    holds: &[
        (
            14,
            "TASK PERS wobjdata obRob11_Tool0:=[FALSE,FALSE,\"ROB_1\"",
        ),
        (31, "MoveJ pEx_Coord_10\\ID:=10"),
    ],
};

fn dir() -> String {
    format!("{}/tests/data/programs/rapid", env!("CARGO_MANIFEST_DIR"))
}

/// The stored module `name`, as stored.
fn text(name: &str) -> String {
    std::fs::read_to_string(format!("{}/{name}", dir())).unwrap()
}

/// `r`'s message checked against `r`, and the file's lines against `r.holds`.
fn check(r: &Refusal, refusal: Result<(), Error>) {
    let (line, message) = match refusal {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!(
            "{}: expected a refusal naming a line, got {other:?}",
            r.file
        ),
    };
    assert_eq!(line, r.line, "{}: {message}", r.file);
    for words in r.says {
        assert!(
            message.contains(words),
            "{}: {message}\nexpected: {words}",
            r.file
        );
    }
    let text = text(r.file);
    let lines: Vec<&str> = text.split('\n').collect();
    for (n, words) in r.holds {
        assert!(
            lines[n - 1].contains(words),
            "{} line {n}: {:?}",
            r.file,
            lines[n - 1]
        );
    }
}

#[test]
fn every_stored_module_is_in_the_table() {
    let mut stored: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| {
            [".mod", ".modx", ".prg", ".sys"]
                .iter()
                .any(|x| n.to_lowercase().ends_with(x))
        })
        .collect();
    stored.sort();
    let mut listed: Vec<String> = REFUSED
        .iter()
        .chain([&ON_SETUP])
        .map(|r| r.file.to_string())
        .chain(READ.map(String::from))
        .collect();
    listed.sort();
    assert_eq!(stored, listed);
    let sources = text("SOURCES.md");
    for name in &listed {
        assert!(
            sources.contains(&format!("`{name}`")),
            "{name} is not in SOURCES.md"
        );
    }
}

#[test]
fn the_stored_modules_are_refused_naming_their_line_and_construct() {
    for r in &REFUSED {
        check(r, program::parse(&text(r.file), Dialect::Rapid).map(drop));
    }
    // Motions in several routines, each read where it is: main's, then Path_10's.
    // The sorting line's second robot and second GoFa: every motion read (their tools are
    // the task's other module's: `robots.rs` runs them with it).
    for file in &READ[2..] {
        assert!(
            program::parse(&text(file), Dialect::Rapid).is_ok(),
            "{file}"
        );
    }
    let p = program::parse(&text(READ[1]), Dialect::Rapid).unwrap();
    assert_eq!(p.targets.len(), 29);
    assert_eq!((p.targets[0].line, p.targets[1].line), (39, 48));
}

/// The milling example's setup with the module's own tool, `tExample`: 300 mm along the
/// flange's z axis.
fn setup_with_t_example() -> Setup {
    const SETUP: &str = include_str!("../../../../../../../examples/milling/fanuc-milling.toml");
    let text = SETUP.replacen("tcp_mm = [6.9, 245.3, 319.3]", "tcp_mm = [0, 0, 300]", 1);
    assert_ne!(text, SETUP);
    stiffid::internal::setup::parse(&text, "fanuc-milling.toml", |n, _| presets::get(n)).unwrap()
}

#[test]
fn a_multimove_example_is_refused_at_its_work_object_moved_by_another_robot() {
    let setup = setup_with_t_example();
    let read =
        machining::read(&text(ON_SETUP.file), Language::Robot(Dialect::Rapid), 1e-4).unwrap();
    let resolved = machining::resolve(&read, &setup, None, &Options::for_setup(&setup)).map(drop);
    check(&ON_SETUP, resolved);
}

/// A motion line of a generated path, read here apart from the reader: the numbers of its
/// `robtarget` literal `[[x,y,z],[q1,q2,q3,q4],[cf1,cf4,cf6,cfx],[eax_a..eax_f]]`.
fn literal(line: &str) -> Option<Vec<f64>> {
    let rest = line
        .strip_prefix("MoveJ ")
        .or_else(|| line.strip_prefix("MoveL "))?;
    let end = rest.find("]],")? + 2;
    let numbers = rest[..end]
        .split(['[', ']', ','])
        .filter(|w| !w.trim().is_empty())
        .map(|w| w.trim().parse::<f64>().unwrap())
        .collect::<Vec<_>>();
    assert_eq!(numbers.len(), 17, "{line}");
    Some(numbers)
}

#[test]
fn a_generated_path_is_read_point_by_point_as_the_file_states_it() {
    let text = text(READ[0]);
    // The file's own motion lines: (line number, numbers of the literal).
    let file: Vec<(u64, Vec<f64>)> = text
        .split('\n')
        .enumerate()
        .filter_map(|(k, l)| literal(l.trim_end_matches('\r')).map(|n| (k as u64 + 1, n)))
        .collect();
    assert_eq!(file.len(), 121);
    let p = program::parse(&text, Dialect::Rapid).unwrap();
    assert_eq!(p.targets.len(), file.len());
    for (t, (line, n)) in p.targets.iter().zip(&file) {
        assert_eq!(t.line, *line);
        let c = t.cartesian.as_deref().unwrap();
        assert!(
            (c.position_mm - Vector3::new(n[0], n[1], n[2])).norm() < 1e-9,
            "line {line}"
        );
        let q = UnitQuaternion::from_quaternion(Quaternion::new(n[3], n[4], n[5], n[6]));
        let d = (c.rotation.coords - q.coords)
            .norm()
            .min((c.rotation.coords + q.coords).norm());
        assert!(d < 1e-12, "line {line}: {d}");
        let conf = [n[7], n[8], n[9], n[10]].map(|v| v as i64);
        assert_eq!(c.flags, Some(Flags::new(ConfData(conf))), "line {line}");
        // The tool `gripper` (line 6) at the flange, as the module declares it; the work object
        // `wobj1` (line 7), whose user and object frames are both the identity: the world frame.
        assert!(
            matches!(&c.tool, Frame::Stated(6, f) if f.translation.vector.norm() < 1e-12 && f.rotation.angle() < 1e-12),
            "{:?}",
            c.tool
        );
        assert!(
            matches!(&c.frame, Frame::Stated(7, f) if f.translation.vector.norm() < 1e-12 && f.rotation.angle() < 1e-12),
            "{:?}",
            c.frame
        );
        assert!(t.external.iter().all(Option::is_none));
    }
}
