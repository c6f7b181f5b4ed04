//! The drilling cell's programs (`tests/data/programs/ls/wilder-backup/` and the `wilder_` files,
//! SOURCES.md: a FANUC R-2000iC/210L on a rail, its `E1`) run on the robot they were written
//! for: ROS-Industrial's R-2000iC/210L URDF (`robots/r2000ic210l.urdf`) on the rail as the
//! backup states it (along the world's y, the arm at the world's origin at `E1 = 0`, its travel
//! -2884 to 91 mm), with the controller's tool of each program as the setup's tool and the rest
//! of its backup (its `SYSFRAME.VA`, `POSREG.VA` and the programs they call) given with it. Each
//! one read as the files state it and compensated, or refused naming its line.

use crate::ls_corpus::{compensated_in, independent, pose, refusal};
use nalgebra::Isometry3;
use stiffid::internal::machining::compensate::Compensated;
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::program::cartesian::Frame;
use stiffid::internal::machining::program::{
    parse_in, read_backup, Context, Dialect, JointProgram,
};
use stiffid::internal::robot::ik;
use stiffid::internal::setup;
use stiffid::Setup;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/programs/ls/");

/// The tool frames of the backup's `SYSFRAME.VA` (`$MNUTOOL[1,n]`), `X, Y, Z` mm and `W, P, R`
/// deg: tool 0 the faceplate.
fn tool(n: u32) -> [f64; 6] {
    match n {
        0 | 1 => [0.0; 6],
        2 => [0.0, -250.8, 152.8, -90.0, -90.0, 0.0],
        3 => [74.5, -301.7, 27.4, -90.0, -90.0, 0.0],
        4 => [19.5, -275.054, 25.5, -90.0, -90.0, 0.0],
        5 => [20.5, -306.6, 50.5, -90.0, -90.0, 0.0],
        other => panic!("tool {other}"),
    }
}

/// The drilling cell with the controller's tool `n` as the setup's tool: the rail as the
/// backup's `SYMOTN.VA` states it (`$SCR_GRP[1].$EXT_XYZ_MAP[1] = 2`: along the world's y;
/// `$PARAM_GROUP[1].$LOWERLIMS[7]`, `$UPPERLIMS[7]`: -2884 to 91 mm), the arm at the world's
/// origin at `E1 = 0` (its `CURPOS.DG`: the world position of the joint position it gives, to
/// 0.06 mm).
fn cell(n: u32) -> Setup {
    let t = tool(n);
    let text = setup::builtin_text("fanuc-r2000ic-165f").unwrap().replacen(
        "robot = \"fanuc-r2000ic-165f\"\n",
        "robot = \"r2000ic210l.urdf\"\nrobot_tip = \"tool0\"\nrobot_axis_map = { matrix = [[1,0,0,0,0,0], [0,1,0,0,0,0], [0,1,1,0,0,0], [0,0,0,1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,1]], offset_deg = [0,0,0,0,0,0] }\n",
        1,
    );
    let text = text.replacen(
        "[tool]\n",
        &format!(
            "[tool]\ntcp_mm = [{}, {}, {}]\ntcp_rpy_deg = [{}, {}, {}]\n",
            t[0], t[1], t[2], t[3], t[4], t[5]
        ),
        1,
    ) + "\n[[external_axis]]\nname = \"rail\"\nrole = \"carrier\"\ndirection = [0.0, 1.0, 0.0]\nlimits_mm = [-2884.0, 91.0]\noffset_mm = 0.0\n";
    let urdf = std::fs::read_to_string(format!("{DIR}robots/r2000ic210l.urdf")).unwrap();
    setup::parse(&text, "drilling.toml", |_, tip| {
        stiffid::internal::robot::urdf::parse(&urdf, "r2000ic210l.urdf", tip)
    })
    .unwrap()
}

/// The backup's files kept beside the corpus, read as `--backup wilder-backup/` reads the
/// folder (its programs and `.VA` files, not its `CURPOS.DG`), each named as in the backup.
fn backup() -> Vec<(String, String)> {
    let read = |p: &std::path::Path| std::fs::read(p).map_err(|e| e.to_string());
    let folder = std::path::PathBuf::from(format!("{DIR}wilder-backup"));
    let files = read_backup(&[folder], Dialect::FanucLs, read, |e| e.to_string()).unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(files.len(), 16, "{names:?}");
    assert!(
        names.iter().any(|n| n.ends_with("sysframe.va")),
        "{names:?}"
    );
    (files.into_iter())
        .map(|(name, text)| (name.replacen(DIR, "", 1), text))
        .collect()
}

/// What stiffid does with a program of the drilling cell, run with the controller's tool `n`:
/// compensated, or refused naming this line and, in its message, this.
enum Outcome {
    Compensated,
    Refused(u64, &'static str),
}
use Outcome::{Compensated as Runs, Refused};

/// The programs of the drilling cell kept beside the corpus (the backup's, then the `wilder_`
/// files), the controller's tool each one's Cartesian positions name, and what stiffid does.
const PROGRAMS: [(&str, u32, Outcome); 21] = [
    ("wilder-backup/ahome.ls", 1, Runs),
    ("wilder-backup/azero.ls", 1, Runs),
    ("wilder-backup/alex_uf.ls", 5, Runs),
    ("wilder-backup/transport_pos.ls", 4, Runs),
    ("wilder-backup/safe_position.ls", 4, Runs),
    // Cartesian registers whose poses, in the frames the backup holds, the arm does not reach.
    ("wilder-backup/raik_conf_check.ls", 4, Refused(28, "the pose is out of reach")),
    ("wilder-backup/test.ls", 4, Refused(29, "the pose is out of reach")),
    ("wilder-backup/config_change.ls", 1, Refused(28, "the pose is out of reach")),
    ("wilder-backup/asdf.ls", 0, Refused(25, "the pose is out of reach")),
    (
        "wilder-backup/tool_change.ls",
        1,
        Refused(26, "L PR[14]: wilder-backup/posreg.va line 63 gives PR[14] no value (Uninitialized)"),
    ),
    (
        "wilder-backup/clamp.ls",
        1,
        Refused(30, "L PR[6]: the position register is set on line 29 as the program runs (PR[6:CLAMP CURRT POS]=LPOS)"),
    ),
    (
        "wilder-backup/tool_offset.ls",
        1,
        Refused(27, "L PR[9]: the position register is set on line 26 as the program runs (PR[9]=LPOS)"),
    ),
    (
        "wilder-backup/norm_to_vis.ls",
        1,
        Refused(29, "L PR[4]: the position register is set on line 27 as the program runs (PR[4:VIS CURRT POS]=LPOS)"),
    ),
    // Its user frame set from a register at its start (read), its rail beyond today's travel.
    (
        "wilder_a10defaste.ls",
        1,
        Refused(42, "E1 1545 mm: outside the travel of the cell's external axis 1 (rail), -2884 to 91 mm"),
    ),
    (
        "wilder_robot_repeatability.ls",
        2,
        Refused(27, "E1 1582.463 mm: outside the travel of the cell's external axis 1 (rail)"),
    ),
    // Tool 3 on its joint position, tool 4 (the setup's) on its Cartesian one.
    ("wilder_job_dbl_safe_1.ls", 4, Runs),
    ("wilder_tool_1_dropoff_aproach.ls", 2, Runs),
    ("wilder_tool_3_dropoff_aproach.ls", 2, Runs),
    // In the world (user frame 0); a joint motion in tool 5, a Cartesian one in tool 4.
    ("wilder_job_dbl_safe_505.ls", 4, Runs),
    ("wilder_job_dbl_safe_601.ls", 4, Runs),
    // No user frame selected: the register's `UF : F` is the controller's.
    (
        "wilder_vis_normality.ls",
        4,
        Refused(29, "UF : F: the position is in the frame in force where it runs, and no UFRAME_NUM=n before this motion selects one"),
    ),
];

/// The independent reading of register `n` in the backup's `POSREG.VA` (string searches, not
/// stiffid's reader): its six values (`J1`..`J6` or `X`..`R`) and its `EXT1`.
fn register(posreg: &str, n: u32) -> ([f64; 6], f64) {
    let at = posreg.find(&format!("[1,{n}] =")).unwrap();
    let block: String = posreg[at..]
        .lines()
        .skip(1)
        .take(4)
        .collect::<Vec<_>>()
        .join(" ");
    let value = |key: &str| -> f64 {
        let rest = &block[block.find(key).unwrap() + key.len()..];
        let word = rest
            .trim_start()
            .trim_start_matches('=')
            .split_whitespace()
            .next()
            .unwrap();
        word.parse().unwrap()
    };
    let keys = match block.contains("J1 =") {
        true => ["J1 ", "J2 ", "J3 ", "J4 ", "J5 ", "J6 "],
        false => ["X:", "Y:", "Z:", "W:", "P:", "R:"],
    };
    (keys.map(value), value("EXT1:"))
}

/// The registers the motions of `text` move to, in order.
fn registers(text: &str) -> Vec<u32> {
    (text
        .lines()
        .filter_map(|l| l.split_once(":J PR[").or_else(|| l.split_once(":L PR["))))
    .map(|(_, r)| r.split([':', ']']).next().unwrap().parse().unwrap())
    .collect()
}

/// `text` read as the files state it (`runs`: each Cartesian position in a frame the backup or
/// the program gives): each motion to a register its `POSREG.VA` values and
/// `EXT1`, each other motion its `/POS` position (the independent readings).
fn check_read(name: &str, text: &str, read: &JointProgram, runs: bool) {
    let posreg = std::fs::read_to_string(format!("{DIR}wilder-backup/posreg.va")).unwrap();
    let from_registers = registers(text);
    let expected: Vec<([f64; 6], bool)> = match from_registers.is_empty() {
        true => (independent(text).into_iter())
            .map(|p| (p.values, p.cartesian))
            .collect(),
        false => (from_registers.into_iter())
            .map(|n| (register(&posreg, n).0, posreg_cartesian(&posreg, n)))
            .collect(),
    };
    assert_eq!(read.targets.len(), expected.len(), "{name}");
    for (t, (values, cartesian)) in read.targets.iter().zip(&expected) {
        match (&t.cartesian, cartesian) {
            (Some(c), true) => {
                let p = c.position_mm;
                assert_eq!([p.x, p.y, p.z], [values[0], values[1], values[2]], "{name}");
                // Where it runs, in a frame the backup or the program gives.
                let given = matches!(c.frame, Frame::Held(..) | Frame::World | Frame::Stated(..));
                assert!(given || !runs, "{name}");
            }
            (None, false) => assert_eq!(t.q_deg, *values, "{name}"),
            _ => panic!("{name}: line {}: another representation", t.line),
        }
    }
}

/// Whether register `n` of `posreg` is in Cartesian representation.
fn posreg_cartesian(posreg: &str, n: u32) -> bool {
    let at = posreg.find(&format!("[1,{n}] =")).unwrap();
    !posreg[at..].lines().take(3).any(|l| l.contains("J1 ="))
}

/// `out`, `text` compensated (`results`): `/MN` as read, each position written the compensated
/// posture in the frames it names (the pose it names where the nominal posture is, moved as
/// the tool moves from the nominal to the compensated posture), joint positions the
/// compensated angles; unloaded motions (joint) written as read.
fn check_written(s: &Setup, name: &str, (text, out): (&str, &str), results: &[Compensated]) {
    // `/PROG` names the file written.
    let mn = |t: &str| {
        let after = t.split_once("/ATTR").unwrap().1;
        after.split_once("/POS").unwrap().0.to_string()
    };
    assert_eq!(mn(out), mn(text), "{name}");
    let (read, written) = (independent(text), independent(out));
    if read.is_empty() {
        // Joint motions to registers, unloaded: the registers hold, the program as read.
        return assert_eq!(
            out.split_once("/ATTR").unwrap().1,
            text.split_once("/ATTR").unwrap().1,
            "{name}"
        );
    }
    let robot = s.controller_robot().unwrap();
    // The tool frame: the TCP on the flange, turned by the tool's orientation.
    let tcp = |q| {
        let flange = ik::tool_pose(&robot.frames(q), &s.tool().tcp);
        Isometry3::from_parts(flange.translation, flange.rotation * s.tool().rotation)
    };
    let mut moved: f64 = 0.0;
    for ((r, w), c) in read.iter().zip(&written).zip(results) {
        assert_eq!((w.frames, w.cartesian), (r.frames, r.cartesian), "{name}");
        if !w.cartesian {
            let q = c.q_compensated.map(f64::to_degrees);
            let moved = c.q_compensated != c.q;
            let same = (w.values.iter().zip(q.iter())).all(|(a, b)| (a - b).abs() < 1e-8);
            assert!(same || (!moved && w.values == r.values), "{name}");
            continue;
        }
        let chain = pose(&r.values) * tcp(&c.q).inverse();
        let at = chain * tcp(&c.q_compensated);
        let p = pose(&w.values);
        let d = (p.translation.vector - at.translation.vector).norm();
        assert!(d < 1e-8, "{name}");
        assert!(p.rotation.angle_to(&at.rotation) < 1e-8, "{name}");
        moved = moved.max((p.translation.vector - pose(&r.values).translation.vector).norm());
    }
    // Linear motions, loaded: compensated, the positions written are not the ones read.
    assert!(moved > 1e-5, "{name}: moved {moved} m");
}

#[test]
fn the_drilling_cells_programs_run_on_its_robot_with_their_registers() {
    let backup = backup();
    let mut cells: std::collections::HashMap<u32, Setup> = Default::default();
    for (name, n, outcome) in &PROGRAMS {
        let s = cells.entry(*n).or_insert_with(|| cell(*n));
        let text = std::fs::read_to_string(format!("{DIR}{name}")).unwrap();
        let context = Context::of(s).with_backup(&backup);
        if let Ok(read) = parse_in(&text, Dialect::FanucLs, &context) {
            check_read(name, &text, &read, matches!(outcome, Runs));
        }
        let compliance = s.model_compliance("test").unwrap();
        let run = compensated_in(
            s,
            &compliance,
            Options::for_setup(s),
            (name, &text),
            &backup,
        );
        match outcome {
            Runs => {
                let (out, results, _) = run.unwrap();
                check_written(s, name, (&text, &out), &results);
            }
            Refused(line, what) => {
                let (l, m) = refusal(&run.map(|_| ()).unwrap_err());
                assert_eq!(l, *line, "{name}: {m}");
                assert!(m.starts_with(what), "{name}: {m}");
            }
        }
    }
}
