//! Yaskawa INFORM (`.jbi`): `/JOB`, `//NAME`, `//POS` (the teaching positions in pulses),
//! `//INST` (`NOP`, the moves, `END`) (module docs of [`crate::program::generate`]).
//!
//! Every target is written as its axis angles in whole encoder pulses (`///POSTYPE PULSE`,
//! `C00000=S,L,U,R,B,T`), whatever [`Targets`](crate::program::generate::Targets) asks: stiffid reads no rectangular position back
//! ([`super`]), so a job it writes states none. The pulses per degree are the setup's
//! (`[controller] pulses_per_deg`, [`Pulses`]), which read it back ([`crate::program::Context`]):
//! the job states them in no comment (a comment line is at most 32 characters on the pendant,
//! and six numbers do not fit); a base axis group (the carrier's axes, `BC00000`) and a station
//! group (the positioner's, `EC00000`) are written in pulses with `external_pulses`, else in
//! `///ANGLE` form (mm, deg).

use crate::program::generate::arcs::Form;
use crate::program::generate::date::Stamp;
use crate::program::generate::{
    missing_pulses, number, stated_feed, v, zyx_deg, Move, Part, Plan, Settings, Target,
};
use crate::program::{whole_pulses, Arcs, ExternalGroup, Generator, Writing};
use std::fmt::Write;
use stiffid_core::robot::external::Role;
use stiffid_core::setup::Pulses;
use stiffid_core::Result;

/// The job's comment (`///COMM`): what the pendant shows beside its name (32 characters at most).
pub(crate) const COMM: &str = "stiffid";

/// The tool file a job of `plan` moves with: the one the controller holds its tool in, else the
/// lowest the setup's `[controller] tools` leaves free, whose values the job's comments state
/// ([`crate::program::generate::numbered`]; the body refuses a table with none free).
fn tool_file(plan: &Plan) -> u32 {
    plan.numbers.tool_number().unwrap_or(1)
}

/// The most teaching positions of one kind in a job: a position's number has five digits
/// (`C00000` to `C99999`).
pub(crate) const MAX_POSITIONS: usize = 100_000;

/// A path speed's resolution, mm/s: `V=` states tenths of a mm/s.
const SPEED_STEP_MM_S: f64 = 0.1;

/// The pulses of `plan`, which a job needs.
///
/// # Errors
/// [`Error::InvalidField`] (`controller.pulses_per_deg`) without them.
pub(crate) fn pulses<'a>(plan: &Plan<'a>) -> Result<&'a Pulses> {
    plan.pulses.ok_or_else(missing_pulses)
}

/// A feed (m/s) as `V=` in tenths of a mm/s, whether exact; `None` below 0.1 mm/s (the
/// slowest `V=`: a slower feed written as it would run up to twice as fast, `F5` mm/min 20 %).
pub fn speed(feed: f64) -> Option<(String, bool)> {
    let steps = feed * 1e3 / SPEED_STEP_MM_S;
    let exact = (steps - steps.round()).abs() <= 1e-9 * steps.max(1.0);
    (steps >= 1.0 - 1e-9).then(|| (format!("V={:.1}", steps.round() * SPEED_STEP_MM_S), exact))
}

/// Whether the cell of `plan` has a base axis group (carrier axes) and a station group
/// (positioner axes).
fn groups(plan: &Plan) -> (bool, bool) {
    let has = |role| (plan.external).is_some_and(|a| a.axes().iter().any(|x| x.role == role));
    (has(Role::Carrier), has(Role::Positioner))
}

/// The `//POS` section of one job: `///NPOS`, `///TOOL`, then the robot's, base and station
/// positions, each group after its form.
fn positions(plan: &Plan, part: &Part, pulses: &Pulses) -> String {
    let n = part.targets.len();
    let (base, station) = groups(plan);
    let carriers = plan.external.map_or(0, |a| a.carrier_len());
    let mut s = format!(
        "///NPOS {n},{},{},0,0,0\n///TOOL {}\n///POSTYPE PULSE\n///PULSE\n",
        if base { n } else { 0 },
        if station { n } else { 0 },
        tool_file(plan)
    );
    for (k, t) in part.targets.iter().enumerate() {
        let values: Vec<String> = (t.q_deg.iter().zip(&pulses.per_deg))
            .map(|(q, per)| whole_pulses(*q, *per).to_string())
            .collect();
        let _ = writeln!(s, "C{k:05}={}", values.join(","));
    }
    if base {
        s += &external(part.targets, "BC", 0..carriers, pulses);
    }
    if station {
        let all = plan.external.map_or(0, |a| a.len());
        s += &external(part.targets, "EC", carriers..all, pulses);
    }
    s
}

/// The positions of one external group (`prefix` `BC` or `EC`): the values `range` of each
/// target's external ones, in pulses with `external_pulses`, else in `///ANGLE` form.
fn external(
    targets: &[Target],
    prefix: &str,
    range: std::ops::Range<usize>,
    pulses: &Pulses,
) -> String {
    let in_pulses = !pulses.external.is_empty();
    let mut s = match in_pulses {
        true => String::from("///POSTYPE PULSE\n///PULSE\n"),
        false => String::from("///POSTYPE ANGLE\n///ANGLE\n"),
    };
    for (k, t) in targets.iter().enumerate() {
        let values: Vec<String> = (range.clone())
            .map(|i| match in_pulses {
                true => whole_pulses(t.external[i], pulses.external[i]).to_string(),
                false => v(t.external[i]),
            })
            .collect();
        let _ = writeln!(s, "{prefix}{k:05}={}", values.join(","));
    }
    s
}

/// What an INFORM job holds and how it writes it: at most [`MAX_POSITIONS`] teaching positions,
/// every target in encoder pulses (`C` positions, never a pose), three `MOVC` positions (start,
/// via, end) whatever the targets (a `MOVC` between pulse positions moves the tool on the circle
/// through their poses in the controller's kinematics, as a `MOVL` moves it on a line), a base
/// axis group `BC` of up to 3 axes and a station group `EC` of up to 6 (YASKAWA INFORM language
/// manual).
static WRITING: Writing = Writing {
    lines_per_file: Some(MAX_POSITIONS),
    routine_prefix: "",
    states_mass: false,
    cartesian: false,
    pulses: true,
    arcs: Some(Arcs {
        form: Form::StartViaEnd,
        joint_targets: true,
    }),
    carrier: ExternalGroup {
        most: 3,
        form: "a base axis group BC of 3 axes",
    },
    positioner: ExternalGroup {
        most: 6,
        form: "a station group EC of 6 axes",
    },
    process: Some(&crate::program::inform::process::FORM),
};

impl Generator for super::Inform {
    /// The main job's comments of the tool file it moves with (`tool_file`): the tool frame from the
    /// controller's flange (X, Y, Z mm; Rx, Ry, Rz deg with `R = Rz Ry Rx`) and, when the setup
    /// gives them, the mass (W, kg) and centre of gravity (Xg, Yg, Zg, mm); a comment line is at
    /// most 32 characters on the pendant.
    fn header(&self, plan: &Plan, _main: &str, _subs: &[String]) -> String {
        let t = &plan.tool.frame;
        let p = t.translation.vector * 1e3;
        let [rz, ry, rx] = zyx_deg(&t.rotation);
        let mut s = format!("'set tool file {} to the tool:\n", tool_file(plan));
        let mut values = vec![
            ("X", p.x, "mm"),
            ("Y", p.y, "mm"),
            ("Z", p.z, "mm"),
            ("Rx", rx, "deg"),
            ("Ry", ry, "deg"),
            ("Rz", rz, "deg"),
        ];
        if let Some((mass, c)) = plan.tool.payload {
            let c = c * 1e3;
            values.extend([("W", mass, "kg"), ("Xg", c.x, "mm"), ("Yg", c.y, "mm")]);
            values.push(("Zg", c.z, "mm"));
        }
        for (name, value, unit) in values {
            let _ = writeln!(s, "'{name} = {} {unit}", number(value));
        }
        s
    }
    /// The moves (`//INST` lines after `NOP`) and the positions (`//POS` lines) of one job,
    /// `//POS` between them.
    fn body(&self, plan: &Plan, part: &Part, warnings: &mut Vec<String>) -> Result<String> {
        plan.numbers.tool_number()?;
        let pulses = pulses(plan)?;
        let mut inst = String::new();
        let n = part.targets.len();
        let (base, station) = groups(plan);
        for (k, m) in part.moves.iter().enumerate() {
            let exact = part.last && k + 1 == n;
            inst += part.before(k);
            let external = |prefix: &str, has: bool| match has {
                true => format!(" {prefix}{k:05}"),
                false => String::new(),
            };
            let names = format!("C{k:05}{}{}", external("BC", base), external("EC", station));
            let _ = match m {
                Move::Rapid => writeln!(
                    inst,
                    "MOVJ {names} VJ={:.2} PL=0",
                    plan.settings.rapid_joint_pct
                ),
                m => {
                    let slowest = (
                        "0.1 mm/s, the slowest an INFORM job states",
                        "whole tenth of a mm/s",
                    );
                    let f = m.feed().unwrap_or_default();
                    let v = stated_feed(f, part.first + k + 1, speed, slowest, warnings)?;
                    let motion = match m {
                        Move::Feed(_) => "MOVL",
                        _ => "MOVC",
                    };
                    writeln!(inst, "{motion} {names} {v} PL={}", u8::from(!exact))
                }
            };
        }
        inst += part.after();
        Ok(format!("{inst}//POS\n{}", positions(plan, part, pulses)))
    }
    /// The main job's calls of its sub-jobs (no position of its own).
    fn calls(&self, subs: &[String]) -> String {
        let calls: String = subs.iter().map(|n| format!("CALL JOB:{n}\n")).collect();
        calls + "//POS\n///NPOS 0,0,0,0,0,0\n"
    }
    /// A whole `.jbi` file (CR LF line ends, as the controllers write them): `//POS` from the body,
    /// `//INST` with its date ([`crate::program::generate::date`]), comment ([`COMM`]), the motion group (the robot `RB1`, a base `BS1`, a station `ST1`), `NOP`, the
    /// header's and the body's lines, `END`.
    fn wrap(&self, name: &str, header: &str, body: &str, _main: bool, d: Stamp) -> String {
        let (inst, pos) = body.split_once("//POS\n").unwrap_or((body, ""));
        let mut group = String::from("RB1");
        if pos.contains("\nBC00000=") {
            group += ",BS1";
        }
        if pos.contains("\nEC00000=") {
            group += ",ST1";
        }
        let text = format!(
            "/JOB\n//NAME {name}\n//POS\n{pos}//INST\n///DATE {:04}/{:02}/{:02} {:02}:{:02}\n///COMM {COMM}\n///ATTR SC,RW\n///GROUP1 {group}\nNOP\n{header}{inst}END\n",
            d.year, d.month, d.day, d.time.0, d.time.1
        );
        text.replace('\n', "\r\n")
    }
    /// A joint speed `VJ=` in hundredths of a percent.
    fn check_settings(&self, settings: &Settings) -> Result<()> {
        let steps = settings.rapid_joint_pct * 100.0;
        match (steps - steps.round()).abs() <= 1e-9 * steps {
            true => Ok(()),
            false => Err(stiffid_core::Error::InvalidField {
                field: "controller.rapid_joint_pct".into(),
                message: format!("{}: an INFORM joint move states the joint speed in hundredths of a percent (VJ=20.00)", settings.rapid_joint_pct),
            }),
        }
    }
    fn writing(&self) -> &'static Writing {
        &WRITING
    }
}
