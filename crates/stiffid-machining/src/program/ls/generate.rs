//! FANUC LS (`.ls`): `/PROG NAME`, `/ATTR`, `/MN`, `/POS`, `/END` (module docs of [`crate::program::generate`]).

use crate::program::cartesian::flags::ConfigurationData;
use crate::program::generate::arcs::Form;
use crate::program::generate::date::Stamp;
use crate::program::generate::LS_MAX_LINES;
use crate::program::generate::{
    in_world, number, stated_feed, v, zyx_deg, Move, Part, Plan, Settings, Target, Targets,
};
use crate::program::{Arcs, ExternalGroup, Generator, Writing};
use nalgebra::Isometry3;
use std::fmt::Write;
use stiffid_core::robot::external::Role;
use stiffid_core::Result;

/// How the continuation line of a circular move (its end) starts, unnumbered as FANUC writes it.
const CONTINUATION: &str = "    :  ";

/// The `COMMENT` of every program: at most 16 characters, what the pendant shows.
pub(crate) const COMMENT: &str = "stiffid";

/// The frames set up at the top of the main program: user frame 0 (the world), tool frame 1,
/// whose values (the tool frame from the controller's flange) the remarks state, one per line
/// (a remark is at most 32 characters on the pendant); or the frames the controller holds the
/// part frame and the tool in ([`crate::program::generate::numbered`]).
pub fn header(plan: &Plan) -> String {
    let t = &plan.tool.frame;
    let p = t.translation.vector * 1e3;
    let [r, pitch, w] = zyx_deg(&t.rotation);
    let (uf, ut) = frame_numbers(plan);
    let mut s = match plan.numbers.tool {
        Some(_) => format!("! UTOOL[{ut}] holds the tool: ;\n"),
        None => format!("! set UTOOL[{ut}] to the tool: ;\n"),
    };
    for (name, value, unit) in [
        ("X", p.x, "mm"),
        ("Y", p.y, "mm"),
        ("Z", p.z, "mm"),
        ("W", w, "deg"),
        ("P", pitch, "deg"),
        ("R", r, "deg"),
    ] {
        let _ = writeln!(s, "! UT{ut} {name} = {} {unit} ;", number(value));
    }
    s + &format!("UFRAME_NUM={uf} ;\nUTOOL_NUM={ut} ;\n")
}

/// The user frame and the tool frame a program of `plan` runs in: those the controller holds
/// its part frame and tool in ([`crate::program::generate::numbered`]), else user frame 0 (the
/// world) and the lowest tool frame the setup's table leaves free (the body refuses a table
/// with none free).
fn frame_numbers(plan: &Plan) -> (u32, u32) {
    let uf = plan.numbers.base.map_or(0, |(n, _)| n);
    (uf, plan.numbers.tool_number().unwrap_or(1))
}

/// A feed (m/s) as an LS speed: whole mm/sec, else whole cm/min, else the nearest cm/min (with a
/// warning); `None` below 1 cm/min.
pub fn speed(feed: f64) -> Option<(String, bool)> {
    let whole = |x: f64| (x - x.round()).abs() <= 1e-9 * x.max(1.0) && x.round() >= 1.0;
    let (mm_s, cm_min) = (feed * 1e3, feed * 6e3);
    if whole(mm_s) {
        Some((format!("{}mm/sec", mm_s.round()), true))
    } else if whole(cm_min) {
        Some((format!("{}cm/min", cm_min.round()), true))
    } else if cm_min >= 1.0 {
        Some((format!("{}cm/min", cm_min.round()), false))
    } else {
        None
    }
}

/// The moves (`/MN` lines, unnumbered) and positions of one file, `/POS` between them.
pub(crate) fn body(plan: &Plan, part: &Part, warnings: &mut Vec<String>) -> Result<String> {
    plan.numbers.tool_number()?;
    let mut mn = String::with_capacity(part.targets.len() * 30);
    let mut pos = String::with_capacity(part.targets.len() * 200);
    let n = part.targets.len();
    for (k, (t, m)) in part.targets.iter().zip(part.moves).enumerate() {
        let i = k + 1;
        let exact = part.last && k + 1 == n;
        mn += part.before(k);
        let _ = match m {
            Move::Rapid => writeln!(mn, "J P[{i}] {}% FINE ;", plan.settings.rapid_joint_pct),
            // A circular move: the via point on its line, the end on the continuation line.
            Move::ArcVia(_) => writeln!(mn, "C P[{i}]"),
            m => {
                let slowest = (
                    "1 cm/min, the slowest an LS program states",
                    "whole mm/sec or cm/min",
                );
                let f = m.feed().unwrap_or_default();
                let text = stated_feed(f, part.first + i, speed, slowest, warnings)?;
                let motion = match m {
                    Move::ArcEnd(_) => CONTINUATION,
                    _ => "L ",
                };
                writeln!(
                    mn,
                    "{motion}P[{i}] {text} {} ;",
                    if exact { "FINE" } else { "CNT100" }
                )
            }
        };
        let (uf, ut) = frame_numbers(plan);
        let _ = write!(pos, "P[{i}]{{\n   GP1:\n\tUF : {uf}, UT : {ut},");
        let _ = match plan.settings.targets {
            Targets::Joint => write!(
                pos,
                "\n\tJ1= {} deg,\tJ2= {} deg,\tJ3= {} deg,\n\tJ4= {} deg,\tJ5= {} deg,\tJ6= {} deg",
                v(t.q_deg[0]),
                v(t.q_deg[1]),
                v(t.q_deg[2]),
                v(t.q_deg[3]),
                v(t.q_deg[4]),
                v(t.q_deg[5])
            ),
            Targets::Cartesian => {
                // In the user frame the controller holds the part frame in, else the world.
                let user = plan.numbers.base.map_or(Isometry3::identity(), |(_, f)| f);
                let (p, rotation) = in_world(
                    plan,
                    &(plan.world * user.inverse() * plan.world.inverse() * t.pose),
                );
                let [r, pitch, w] = zyx_deg(&rotation);
                write!(
                    pos,
                    "\t\tCONFIG : '{}',\n\tX = {} mm,\tY = {} mm,\tZ = {} mm,\n\tW = {} deg,\tP = {} deg,\tR = {} deg",
                    super::Config::of(&t.arm), v(p.x), v(p.y), v(p.z), v(w), v(pitch), v(r)
                )
            }
        };
        pos += &groups(plan, t);
    }
    mn += part.after();
    Ok(format!("{mn}/POS\n{pos}"))
}

/// The end of a position after group 1's six values: the carrier's axes as group 1's extended
/// axes `E1`.. (mm), the positioner's as group 2's `J1`.. (deg), then `};`.
fn groups(plan: &Plan, t: &Target) -> String {
    let Some(axes) = plan.external else {
        return "\n};\n".into();
    };
    let mut s = String::new();
    let (mut extended, mut second) = (0, 0);
    for (axis, x) in axes.axes().iter().zip(&t.external) {
        let unit = axis.unit();
        if axis.role == Role::Carrier {
            extended += 1;
            let _ = write!(s, ",\n\tE{extended}= {} {unit}", v(*x));
        } else {
            second += 1;
            let start = if second == 1 {
                "\n   GP2:\n\tUF : 0, UT : 1,\n\t"
            } else {
                ",\t"
            };
            let _ = write!(s, "{start}J{second}= {} {unit}", v(*x));
        }
    }
    s + "\n};\n"
}

/// The main program's calls of its sub-programs.
pub(crate) fn calls(subs: &[String]) -> String {
    subs.iter()
        .map(|n| format!("CALL {n} ;\n"))
        .collect::<String>()
        + "/POS\n"
}

/// A whole `.ls` file: the `/MN` lines numbered.
pub(crate) fn wrap(name: &str, header: &str, body: &str, date: Stamp) -> String {
    let (mn, pos) = body.split_once("/POS\n").unwrap_or((body, ""));
    // A positioner's group 2 joins the default motion group mask.
    let groups = match pos.contains("\n   GP2:") {
        true => "1,1,*,*,*",
        false => "1,*,*,*,*",
    };
    let mut lines = String::new();
    let mut number = 0;
    for line in header.lines().chain(mn.lines()) {
        if line.starts_with(CONTINUATION) {
            let _ = writeln!(lines, "{line}");
            continue;
        }
        number += 1;
        let pad = if ["J P", "L P", "C P"].iter().any(|m| line.starts_with(m)) {
            ""
        } else {
            "  "
        };
        let _ = writeln!(lines, "{number:>4}:{pad}{line}");
    }
    format!(
        "/PROG  {name}\n{}/MN\n{lines}/POS\n{pos}/END\n",
        attributes(groups, number, date)
    )
}

/// The `/ATTR` section as the controller writes it (the corpus's programs; FANUC R-30iB
/// Operator's Manual, "program header"): `OWNER = MNEDITOR`, the [`COMMENT`], sizes 0 (the
/// controller computes them when it loads the program), the creation and modification dates
/// ([`crate::program::generate::date`]), `LINE_COUNT` the numbered lines, `PROTECT =
/// READ_WRITE`, the task attributes (`TCD`) at their defaults, the motion group mask `groups`,
/// `CONTROL_CODE` zero.
fn attributes(groups: &str, lines: usize, d: Stamp) -> String {
    let date = format!(
        "DATE {:02}-{:02}-{:02}  TIME {:02}:{:02}:{:02}",
        d.year.rem_euclid(100),
        d.month,
        d.day,
        d.time.0,
        d.time.1,
        d.time.2
    );
    format!(
        "/ATTR\nOWNER\t\t= MNEDITOR;\nCOMMENT\t\t= \"{COMMENT}\";\nPROG_SIZE\t= 0;\nCREATE\t\t= {date};\nMODIFIED\t= {date};\nFILE_NAME\t= ;\nVERSION\t\t= 0;\nLINE_COUNT\t= {lines};\nMEMORY_SIZE\t= 0;\nPROTECT\t\t= READ_WRITE;\nTCD:  STACK_SIZE\t= 0,\n      TASK_PRIORITY\t= 50,\n      TIME_SLICE\t= 0,\n      BUSY_LAMP_OFF\t= 0,\n      ABORT_REQUEST\t= 0,\n      PAUSE_REQUEST\t= 0;\nDEFAULT_GROUP\t= {groups};\nCONTROL_CODE\t= 00000000 00000000;\n"
    )
}

/// What an LS program holds and how it writes it: at most [`LS_MAX_LINES`] lines with its
/// header, `C` moves with Cartesian targets, group 1's extended axes `E1` to `E3` under the arm
/// and group 2's `J1` to `J6` for a positioner (FANUC Operator's Manual, TP programs).
static WRITING: Writing = Writing {
    lines_per_file: Some(LS_MAX_LINES - LS_HEADER_LINES),
    routine_prefix: "",
    states_mass: false,
    cartesian: true,
    pulses: false,
    arcs: Some(Arcs {
        form: Form::ViaEnd,
        joint_targets: false,
    }),
    carrier: ExternalGroup {
        most: 3,
        form: "group 1's extended axes E1 to E3",
    },
    positioner: ExternalGroup {
        most: 6,
        form: "group 2's J1 to J6",
    },
    process: Some(&super::process::FORM),
};

impl Generator for super::FanucLs {
    fn header(&self, plan: &Plan, _main: &str, _subs: &[String]) -> String {
        header(plan)
    }
    fn body(&self, plan: &Plan, part: &Part, warnings: &mut Vec<String>) -> Result<String> {
        body(plan, part, warnings)
    }
    fn calls(&self, subs: &[String]) -> String {
        calls(subs)
    }
    fn wrap(&self, name: &str, header: &str, body: &str, _main: bool, date: Stamp) -> String {
        wrap(name, header, body, date)
    }
    /// [`LS_MAX_LINES`] numbered lines, the main program's header included.
    /// A carrier in group 1's extended axes `E1` to `E3`, a positioner in group 2's `J1`..
    /// A joint move's speed is a whole percent (`J P[1] 20% FINE`).
    fn check_settings(&self, settings: &Settings) -> Result<()> {
        let pct = settings.rapid_joint_pct;
        match pct.fract() == 0.0 && pct >= 1.0 {
            true => Ok(()),
            false => Err(stiffid_core::Error::InvalidField {
                field: "controller.rapid_joint_pct".into(),
                message: format!("{pct}: an LS joint move states a whole percent of the joint speed, 1 to 100 (J P[1] 20% FINE)"),
            }),
        }
    }
    fn writing(&self) -> &'static Writing {
        &WRITING
    }
}

/// The lines an LS main program's header adds before its moves or calls (`! set UTOOL`, six
/// remarks of the tool frame's values, `UFRAME_NUM`, `UTOOL_NUM`).
pub(crate) const LS_HEADER_LINES: usize = 9;
