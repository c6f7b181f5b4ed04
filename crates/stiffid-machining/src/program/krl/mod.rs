//! KUKA KRL: `PTP {A1 0, A2 -90, ...}`, `LIN {...}` (also `SPTP`, `SLIN`, an optional type
//! `{E6AXIS: ...}` and an approximation `C_PTP`, `C_DIS`, `C_VEL`, `C_ORI`, `C_SPL`), or the same
//! to a point declared in the file: `DECL E6AXIS XP1={A1 0,...}` (or `AXIS`, with or without
//! `DECL`, `GLOBAL`, `CONST`); `;` starts a comment. KRL is line based and case-insensitive.
//!
//! The members `E1` to `E6` of an aggregate are the external axes as `$EX_AX_NUM` numbers them
//! (mm for a linear axis, deg for a rotary one): read, and written back where they change.
//!
//! An aggregate or declared point with `X`, `Y`, `Z`, `A`, `B`, `C` (`E6POS`, `POS`, `FRAME`,
//! with `S` and `T`) is a Cartesian target in the `$BASE` and for the `$TOOL` the program sets
//! before the motion ([`super::cartesian`]).

pub mod cartesian;
mod generate;
mod names;
pub mod speed;

use super::cartesian::Flags;
use super::cartesian::Frame;
use super::controller::{lines_starting, BoundComment, Controller, Generator, Read};
use super::generate::zyx_deg;
use super::{at, number_at, six, JointTarget};
use nalgebra::{UnitQuaternion, Vector3};
use std::collections::HashMap;
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::{Error, Result};

/// A point declared in the file: its line and its joint target, or why it is none.
type Declared = HashMap<String, (u64, std::result::Result<JointTarget, String>)>;

/// Every joint target of `text`, in the order of its motions (module docs), and the program's
/// external axes: `E1` to the highest `E`n any target gives.
pub(crate) fn targets(text: &str) -> Result<(Vec<JointTarget>, Vec<String>)> {
    let (declared, assigned) = declarations(text)?;
    let mut out = Vec::new();
    // The routine of the first motion, and the first jump, loop or branch.
    let mut routine: Option<(String, u64)> = None;
    let mut current: Option<(String, u64)> = None;
    let mut control: Option<(u64, String)> = None;
    let unset = |name: &str| {
        Frame::Unknown(0, format!("no {name} set before this Cartesian motion: its frame is the controller's, which the program does not state; set {name} = {{X .., Y .., Z .., A .., B .., C ..}} in the program"))
    };
    let (mut base, mut tool) = (unset("$BASE"), unset("$TOOL"));
    let mut speed = speed::Krl::new();
    for (line, start, l) in super::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        if let Some((is_base, frame)) = cartesian::frame_set(line, code) {
            *(if is_base { &mut base } else { &mut tool }) = frame;
            continue;
        }
        if speed.set(line, code)? {
            continue;
        }
        let words = words(code);
        let first = words.first().map(String::as_str).unwrap_or("");
        if let Some(name) = routine_name(&words) {
            current = Some((name, line));
            continue;
        }
        if matches!(
            first,
            "FOR" | "WHILE" | "LOOP" | "REPEAT" | "GOTO" | "IF" | "SWITCH"
        ) && control.is_none()
        {
            control = Some((line, first.to_string()));
        }
        let Some(mut target) = motion(line, start, code, first, &declared, &assigned)? else {
            continue;
        };
        target.speed = speed.motion(line, first, code)?;
        if let Some(c) = target.cartesian.as_deref_mut() {
            let at_motion = |f: &Frame| match f {
                Frame::Unknown(0, why) => Frame::Unknown(line, why.clone()),
                other => other.clone(),
            };
            (c.frame, c.tool) = (at_motion(&base), at_motion(&tool));
            c.follows = matches!(first, "LIN" | "SLIN");
        }
        match (&routine, &current) {
            (Some((a, a_line)), Some((b, b_line))) if a != b => {
                return Err(at(line, format!("motions in DEF {a} (line {a_line}) and DEF {b} (line {b_line}): the order the controller runs them depends on the calls; put the path in one DEF")));
            }
            (None, _) => routine = current.clone(),
            _ => {}
        }
        out.push(target);
    }
    if let (Some((line, word)), false) = (control, out.is_empty()) {
        return Err(at(line, format!("{word}: a jump, loop or branch in a program with motions; the order the controller runs them would not be the file's: write the path as straight-line code")));
    }
    let n = out.iter().map(|t| t.external.len()).max().unwrap_or(0);
    Ok((out, (1..=n).map(|k| format!("E{k}")).collect()))
}

/// The upper-case words of a line's code.
fn words(code: &str) -> Vec<String> {
    code.split(|c: char| c.is_whitespace() || c == '=' || c == '{' || c == '(')
        .filter(|w| !w.is_empty())
        .map(str::to_ascii_uppercase)
        .collect()
}

/// The name of the routine a `DEF`/`DEFFCT` line opens (`GLOBAL DEF name( )`).
fn routine_name(words: &[String]) -> Option<String> {
    let w: Vec<&str> = words
        .iter()
        .map(String::as_str)
        .skip_while(|w| *w == "GLOBAL")
        .collect();
    match w.as_slice() {
        ["DEF", name, ..] => Some(name.to_string()),
        ["DEFFCT", _, name, ..] => Some(name.to_string()),
        _ => None,
    }
}

/// The points declared in the file (`E6AXIS`, `AXIS` with their targets; `E6POS`, `POS`,
/// `FRAME` as Cartesian) and the lines that assign a declared point at run time.
fn declarations(text: &str) -> Result<(Declared, HashMap<String, u64>)> {
    let mut declared = Declared::new();
    let mut assignments = Vec::new();
    for (line, start, l) in super::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        let words = words(code);
        let w: Vec<&str> = words
            .iter()
            .map(String::as_str)
            .skip_while(|w| matches!(*w, "DECL" | "GLOBAL" | "CONST"))
            .collect();
        let declares = words.first().is_some_and(|f| f == "DECL") || w.len() < words.len();
        match w.as_slice() {
            ["E6AXIS" | "AXIS" | "E6POS" | "POS" | "FRAME", name, ..] => {
                let name = name.split(['[', ',']).next().unwrap_or(name).to_string();
                let value = match code.find('{') {
                    None => Err(format!(
                        "{name} is declared on line {line} without a value (set at run time)"
                    )),
                    Some(open) => Ok(aggregate_at(line, start, code, open)?),
                };
                declared.insert(name, (line, value));
            }
            [name, ..] if !declares && code.contains('=') => {
                let name = name.split(['.', '[']).next().unwrap_or(name).to_string();
                assignments.push((name, line));
            }
            _ => {}
        }
    }
    let assigned = assignments
        .into_iter()
        .filter(|(name, _)| declared.contains_key(name))
        .rev()
        .collect();
    Ok((declared, assigned))
}

/// The target of a motion line, `None` for a line that is no motion; every motion outside the
/// subset refused naming the line.
fn motion(
    line: u64,
    start: usize,
    code: &str,
    first: &str,
    declared: &Declared,
    assigned: &HashMap<String, u64>,
) -> Result<Option<JointTarget>> {
    let refuse = |what: &str| Err(at(line, format!("{first}: {what}")));
    match first {
        "PTP" | "LIN" | "SPTP" | "SLIN" => {}
        "PTP_REL" | "LIN_REL" | "SPTP_REL" | "SLIN_REL" | "CIRC_REL" | "SCIRC_REL" => {
            return refuse("a relative motion; stiffid compensates absolute joint targets: write the absolute target")
        }
        "CIRC" | "SCIRC" => {
            return refuse("a circular motion; the arc between compensated points is not the compensated arc: split it into LIN motions")
        }
        "SPL" | "SPLINE" | "PTP_SPLINE" | "ENDSPLINE" => {
            return refuse("a spline; its path bends through all its points, not along the compensated ones: write it as LIN or PTP motions")
        }
        "ASYPTP" | "ASYCONT" => {
            return refuse("an asynchronous motion of external axes; not compensated: remove it")
        }
        _ => return Ok(None),
    }
    let rest = code.trim_start()[first.len()..].trim_start();
    let (target, after) = if rest.starts_with('{') {
        let open = code.len() - rest.len();
        let close = code[open..]
            .find('}')
            .map(|c| open + c)
            .ok_or_else(|| at(line, "aggregate without its closing '}' on the line".into()))?;
        (aggregate_at(line, start, code, open)?, &code[close + 1..])
    } else {
        let name: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '$' | '[' | ']'))
            .collect();
        let upper = name.to_ascii_uppercase();
        if let Some(assigned_on) = assigned.get(&upper) {
            return Err(at(line, format!("{first} {name}: {name} is assigned on line {assigned_on}, so its value at the motion is the controller's, not the file's: give the motion its own declared point")));
        }
        let target = match declared.get(&upper) {
            Some((_, Ok(t))) => t.moved_to(line, false),
            Some((_, Err(why))) => return Err(at(line, format!("{first} {name}: {why}"))),
            None => return Err(at(line, format!("{first} {name}: not a point declared in this file (a .dat, $config.dat or system variable holds it); stiffid compensates one file: declare the point in it as E6AXIS or write the target as {{A1 .., A6 ..}}"))),
        };
        (target, &rest[name.len()..])
    };
    let extra = after
        .split(|c: char| c.is_whitespace() || c == ',')
        .find(|w| !w.is_empty())
        .filter(|w| {
            let w = w.to_ascii_uppercase();
            !matches!(
                w.as_str(),
                "C_PTP" | "C_DIS" | "C_VEL" | "C_ORI" | "C_SPL" | "WITH"
            )
        });
    if let Some(word) = extra {
        return Err(at(line, format!("{first}: '{}' after the target is not followed (a geometric operator, an offset or an option): write the motion to its absolute target", stiffid_core::common::limits::short(word))));
    }
    Ok(Some(target))
}

/// The joint target of the aggregate opening at byte `open` of `code` (which starts at byte
/// `start` of the text).
fn aggregate_at(line: u64, start: usize, code: &str, open: usize) -> Result<JointTarget> {
    let close = code[open..]
        .find('}')
        .map(|c| open + c)
        .ok_or_else(|| at(line, "aggregate without its closing '}' on the line".into()))?;
    aggregate(line, start, code, open + 1, close)
}

/// The target of the aggregate between `from` and `to` of `code` (which starts at byte `start`).
fn aggregate(line: u64, start: usize, code: &str, from: usize, to: usize) -> Result<JointTarget> {
    let inner = &code[from..to];
    // An optional type: `{E6AXIS: A1 0, ...}`.
    let skip = inner.find(':').map_or(0, |c| c + 1);
    let mut found: [Option<(f64, std::ops::Range<usize>)>; 6] = Default::default();
    let mut external: Vec<Option<(f64, std::ops::Range<usize>)>> = Vec::new();
    let mut pose: Vec<(String, usize)> = Vec::new();
    let mut at_byte = from + skip;
    for item in code[from + skip..to].split(',') {
        let name_start = at_byte + item.len() - item.trim_start().len();
        let trimmed = item.trim();
        let name: String = trimmed
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        let upper = name.to_ascii_uppercase();
        if cartesian::is_member(&upper) {
            pose.push((upper, name_start + name.len()));
            at_byte += item.len() + 1;
            continue;
        }
        let slot = |prefix: char| {
            upper
                .strip_prefix(prefix)
                .and_then(|d| d.parse::<usize>().ok())
                .filter(|k| (1..=6).contains(k))
        };
        let value = || {
            number_at(code, name_start + name.len())
                .map(|(v, span)| (v, start + span.start..start + span.end))
                .ok_or_else(|| at(line, format!("{name}: expected a number")))
        };
        if let Some(k) = slot('A') {
            if found[k - 1].is_some() {
                return Err(at(line, format!("{name} given twice")));
            }
            found[k - 1] = Some(value()?);
        } else if let Some(k) = slot('E') {
            if external.len() < k {
                external.resize(k, None);
            }
            if external[k - 1].is_some() {
                return Err(at(line, format!("{name} given twice")));
            }
            external[k - 1] = Some(value()?);
        }
        at_byte += item.len() + 1;
    }
    if !pose.is_empty() {
        if found.iter().any(Option::is_some) {
            return Err(at(
                line,
                "an aggregate with both axis angles (A1..) and a Cartesian pose (X..): give one"
                    .into(),
            ));
        }
        let c = cartesian::target(line, start, code, &pose)?;
        return Ok(JointTarget::cartesian(line, c).with_external(external));
    }
    six(line, found, "A").map(|t| t.with_external(external)).map_err(|e| match e {
        Error::Program { line, message } => Error::Program {
            line,
            message: format!("{message}: KRL keeps the axes a partial aggregate leaves out where the robot is, which the file does not say; give all six"),
        },
        other => other,
    })
}

/// KUKA KRL (module docs).
#[derive(Debug, Clone, Copy)]
pub struct Krl;

impl Controller for Krl {
    fn key(&self) -> &'static str {
        "krl"
    }
    fn title(&self) -> &'static str {
        "KUKA KRL"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["src", "dat"]
    }
    fn refuses_output(&self, extension: &str) -> Option<&'static str> {
        (extension == "dat").then_some(
            "a KRL program (DEF) is written to a .src file; its .dat holds only data (DEFDAT)",
        )
    }
    fn read(&self, text: &str) -> Result<Read> {
        let (targets, axes) = targets(text)?;
        Ok(Read {
            targets,
            axes,
            ..Read::default()
        })
    }
    fn motions(&self) -> &'static str {
        "PTP or LIN to {A1 .., A6 ..} or {X .., .., C .., S .., T ..}, or to an E6AXIS or E6POS declared in the file; a .dat holds declarations only: give the .src"
    }
    fn joint_forms(&self) -> &'static str {
        "E6AXIS, AXIS"
    }
    fn part_forms(&self) -> Option<&'static str> {
        Some("E6POS with $BASE equal to [workpiece]")
    }
    fn external_axis(&self, k: usize) -> String {
        format!("E{}", k + 1)
    }
    fn unused_axis(&self) -> &'static str {
        ""
    }
    fn zero_is_no_axis(&self) -> bool {
        true
    }
    fn rotation(&self, n: &[f64]) -> UnitQuaternion<f64> {
        abc(n[3], n[4], n[5])
    }
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        let [a, b, c] = zyx_deg(r);
        vec![p.x, p.y, p.z, a, b, c]
    }
    fn flags(&self, arm: &Configuration) -> Flags {
        let (s, t) = arm.kuka();
        Flags::Kuka(s, t)
    }
    fn flags_name(&self) -> &'static str {
        "S and T"
    }
    fn declares_name(&self, line: &str) -> Option<usize> {
        let upper = line.to_ascii_uppercase();
        let rest = upper
            .strip_prefix("GLOBAL")
            .map_or(upper.as_str(), str::trim_start);
        rest.strip_prefix("DEF")
            .filter(|r| r.starts_with(char::is_whitespace))
            .map(|r| line.len() - r.len())
    }
    fn program_name(&self, stem: &str) -> Option<String> {
        Some(stem.to_string())
    }
    fn max_name_length(&self) -> usize {
        24
    }
    fn default_name_length(&self) -> usize {
        24
    }
    fn reserved_words(&self) -> &'static [&'static str] {
        names::RESERVED
    }
    fn bound_comment(&self) -> BoundComment {
        BoundComment::EndOfLine {
            marker: ';',
            statement: None,
        }
    }
    fn motion_lines(&self, text: &str) -> Vec<u64> {
        lines_starting(text, &["PTP ", "LIN "])
    }
    fn generator(&self) -> Option<&'static dyn Generator> {
        Some(&Krl)
    }
}

/// A rotation from KUKA's A, B, C (deg): `R = Rz(A) Ry(B) Rx(C)`.
fn abc(a: f64, b: f64, c: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_euler_angles(c.to_radians(), b.to_radians(), a.to_radians())
}
