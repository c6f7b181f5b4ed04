//! The drilling cell's programs (`tests/data/programs/ls/wilder-backup/`, SOURCES.md: a FANUC
//! R-2000iC/210L on a rail, its `E1`) run on the robot they were written for: ROS-Industrial's
//! R-2000iC/210L URDF (`robots/r2000ic210l.urdf`) on a rail along the world's y, with the
//! controller's tool of each program as the setup's tool and the rest of its backup (its
//! `SYSFRAME.VA`, `POSREG.VA` and the programs they call) given with it. Each one compensated,
//! its registers read from `POSREG.VA` as the file states them, or refused naming its line.

use crate::ls_corpus::{compensated_in, refusal};
use nalgebra::Vector6;
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::program::cartesian::Frame;
use stiffid::internal::machining::program::{parse_in, Context, Dialect};
use stiffid::internal::setup;
use stiffid::Setup;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/programs/ls/");

/// The backup's files kept beside the corpus.
const BACKUP: [&str; 16] = [
    "safe_position.ls",
    "sysframe.va",
    "posreg.va",
    "plchandshake.ls",
    "ahome.ls",
    "azero.ls",
    "alex_uf.ls",
    "asdf.ls",
    "transport_pos.ls",
    "raik_conf_check.ls",
    "config_change.ls",
    "test.ls",
    "tool_change.ls",
    "clamp.ls",
    "tool_offset.ls",
    "norm_to_vis.ls",
];

/// The tool frames of the backup's `SYSFRAME.VA` (`$MNUTOOL[1,n]`), `X, Y, Z` mm and `W, P, R`
/// deg: tool 0 the faceplate.
fn tool(n: u32) -> [f64; 6] {
    match n {
        0 | 1 => [0.0; 6],
        4 => [19.5, -275.054, 25.5, -90.0, -90.0, 0.0],
        5 => [20.5, -306.6, 50.5, -90.0, -90.0, 0.0],
        other => panic!("tool {other}"),
    }
}

/// The drilling cell with the controller's tool `n` as the setup's tool.
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
    ) + "\n[[external_axis]]\nname = \"rail\"\nrole = \"carrier\"\ndirection = [0.0, 1.0, 0.0]\nlimits_mm = [-9000.0, 1000.0]\noffset_mm = 0.0\n";
    let urdf = std::fs::read_to_string(format!("{DIR}robots/r2000ic210l.urdf")).unwrap();
    setup::parse(&text, "drilling.toml", |_, tip| {
        stiffid::internal::robot::urdf::parse(&urdf, "r2000ic210l.urdf", tip)
    })
    .unwrap()
}

/// The backup's files, each named as in the backup.
fn backup() -> Vec<(String, String)> {
    (BACKUP.iter())
        .map(|f| {
            let name = format!("wilder-backup/{f}");
            (
                name.clone(),
                std::fs::read_to_string(format!("{DIR}{name}")).unwrap(),
            )
        })
        .collect()
}

/// What stiffid does with a program of the backup: compensated (its tool), read with its
/// registers and frames (its tool; its poses in the world depend on where the rail lies, which
/// the backup does not hold), or refused naming this line and, in its message, this.
enum Outcome {
    Compensated(u32),
    Read(u32),
    Refused(u64, &'static str),
}
use Outcome::{Compensated, Read, Refused};

/// The programs of the backup kept beside the corpus and what stiffid does with each.
const PROGRAMS: [(&str, Outcome); 13] = [
    ("ahome.ls", Compensated(1)),
    ("azero.ls", Compensated(1)),
    ("alex_uf.ls", Compensated(5)),
    ("transport_pos.ls", Compensated(4)),
    ("safe_position.ls", Compensated(4)),
    ("raik_conf_check.ls", Read(4)),
    ("test.ls", Read(4)),
    ("config_change.ls", Read(1)),
    ("asdf.ls", Read(0)),
    (
        "tool_change.ls",
        Refused(26, "L PR[14]: wilder-backup/posreg.va line 63 gives PR[14] no value (Uninitialized)"),
    ),
    (
        "clamp.ls",
        Refused(30, "L PR[6]: the position register is set on line 29 as the program runs (PR[6:CLAMP CURRT POS]=LPOS)"),
    ),
    (
        "tool_offset.ls",
        Refused(27, "L PR[9]: the position register is set on line 26 as the program runs (PR[9]=LPOS)"),
    ),
    (
        "norm_to_vis.ls",
        Refused(29, "L PR[4]: the position register is set on line 27 as the program runs (PR[4:VIS CURRT POS]=LPOS)"),
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

#[test]
fn the_drilling_cells_programs_run_on_its_robot_with_their_registers() {
    let backup = backup();
    let posreg = std::fs::read_to_string(format!("{DIR}wilder-backup/posreg.va")).unwrap();
    for (name, outcome) in &PROGRAMS {
        let s = cell(match outcome {
            Compensated(n) | Read(n) => *n,
            Refused(..) => 1,
        });
        let text = backup
            .iter()
            .find(|(f, _)| f.ends_with(name))
            .unwrap()
            .1
            .clone();
        let context = Context::of(&s).with_backup(&backup);
        let read = parse_in(&text, Dialect::FanucLs, &context);
        let compliance = s.model_compliance("test").unwrap();
        let run = compensated_in(
            &s,
            &compliance,
            Options::for_setup(&s),
            (name, &text),
            &backup,
        );
        match outcome {
            Compensated(_) => {
                let expected: Vec<([f64; 6], f64)> = registers(&text)
                    .into_iter()
                    .map(|n| register(&posreg, n))
                    .collect();
                let (out, results, _) = run.unwrap();
                let read = read.unwrap();
                assert_eq!(read.targets.len(), expected.len(), "{name}");
                for ((t, (values, e1)), r) in read.targets.iter().zip(&expected).zip(&results) {
                    assert_eq!(
                        (t.q_deg, t.external.clone()),
                        (*values, vec![Some(*e1)]),
                        "{name}"
                    );
                    assert!((r.q - Vector6::from(*values).map(f64::to_radians)).amax() < 1e-12);
                }
                // Joint motions, unloaded: the registers hold, the program is written as read.
                assert_eq!(out, text, "{name}");
                assert_eq!(read.copied.len(), expected.len(), "{name}");
            }
            Read(_) => {
                let expected: Vec<([f64; 6], f64)> = registers(&text)
                    .into_iter()
                    .map(|n| register(&posreg, n))
                    .collect();
                let read = read.unwrap();
                assert_eq!(read.targets.len(), expected.len(), "{name}");
                for (t, (values, e1)) in read.targets.iter().zip(&expected) {
                    let c = t.cartesian.as_deref().unwrap();
                    assert!(
                        matches!(c.frame, Frame::Held(..) | Frame::World),
                        "{name}: {:?}",
                        c.frame
                    );
                    let p = c.position_mm;
                    assert_eq!([p.x, p.y, p.z], [values[0], values[1], values[2]], "{name}");
                    assert_eq!(t.external, vec![Some(*e1)], "{name}");
                }
            }
            Refused(line, what) => {
                let (l, m) = refusal(&run.map(|_| ()).unwrap_err());
                assert_eq!(l, *line, "{name}: {m}");
                assert!(m.starts_with(what), "{name}: {m}");
            }
        }
    }
}
