//! KUKA KRL's Cartesian targets and frames (module docs of [`super`]): the members `X`, `Y`,
//! `Z`, `A`, `B`, `C`, `S`, `T` of an aggregate, and the `$BASE` and `$TOOL` a program sets.

use crate::program::cartesian::flags::Part;
use crate::program::cartesian::{outside_limits, within_limits, Cartesian, Flags, Frame};
use crate::program::krl::{StatusPart, StatusTurn};
use crate::program::{at, number_at, Dialect};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use std::ops::Range;
use stiffid_core::Result;

/// The Cartesian members of an aggregate, in the order a target's pose takes them.
const POSE: [&str; 6] = ["X", "Y", "Z", "A", "B", "C"];

/// Whether an aggregate member (upper case) is a Cartesian one.
pub(crate) fn is_member(name: &str) -> bool {
    POSE.contains(&name) || name == "S" || name == "T"
}

/// The Cartesian target of an aggregate's members `(name, byte after the name)` of `code`
/// (which starts at byte `start` of the text): all six of `X`..`C`, `S` and `T` both or
/// neither.
pub(crate) fn target(
    line: u64,
    start: usize,
    code: &str,
    members: &[(String, usize)],
) -> Result<Cartesian> {
    let mut pose: Vec<(f64, Range<usize>)> = Vec::with_capacity(6);
    for name in POSE {
        let found: Vec<&(String, usize)> = members.iter().filter(|(n, _)| n == name).collect();
        let [(_, after)] = found.as_slice() else {
            return Err(at(line, format!("a Cartesian target with {} {name}: expected each of X, Y, Z, A, B, C once (KRL keeps the members a partial aggregate leaves out where the robot is, which the file does not say)", if found.is_empty() { "no" } else { "more than one" })));
        };
        let (v, span) = number_at(code, *after)
            .filter(|(_, s)| ends_member(code, s.end))
            .ok_or_else(|| at(line, format!("{name}: expected a number, then ',' or '}}'")))?;
        pose.push((v, start + span.start..start + span.end));
    }
    within_limits(line, &POSE, &pose)?;
    let mut c = Cartesian::new(Dialect::Krl, &pose);
    let status = members.iter().find(|(n, _)| n == "S");
    let turn = members.iter().find(|(n, _)| n == "T");
    match (status, turn) {
        (None, None) => {}
        (Some((_, s)), Some((_, t))) => {
            let (s, s_span, s_binary) = bits(line, code, *s, "S")?;
            let (t, t_span, t_binary) = bits(line, code, *t, "T")?;
            c.flags = Some(Flags::new(StatusTurn {
                status: (s & 0b111) as u8,
                turn: (t & 0b11_1111) as u8,
            }));
            c.flag_spans = vec![
                (start + s_span.start..start + s_span.end, Part::new(StatusPart::Status { binary: s_binary })),
                (start + t_span.start..start + t_span.end, Part::new(StatusPart::Turn { binary: t_binary })),
            ];
        }
        _ => {
            return Err(at(line, "a Cartesian target with only one of S and T: give both (status and turn name the solution together) or neither".into()))
        }
    }
    Ok(c)
}

/// Whether an aggregate's member ends at byte `end` of `code`: blanks, then `,` or `}` (a
/// number run into letters, `0S`, is no number to KRL).
fn ends_member(code: &str, end: usize) -> bool {
    let rest = code[end..].trim_start();
    rest.is_empty() || rest.starts_with([',', '}'])
}

/// The value of `S` or `T` after byte `after`: a binary string `'B0110'` or a whole number;
/// its value, span and whether it is binary.
fn bits(line: u64, code: &str, after: usize, name: &str) -> Result<(u64, Range<usize>, bool)> {
    let rest = code[after..].trim_start();
    let from = code.len() - rest.len();
    let bad = || {
        at(
            line,
            format!("{name}: expected a binary string 'B..' or a whole number"),
        )
    };
    if let Some(inner) = rest.strip_prefix('\'') {
        let close = inner.find('\'').ok_or_else(bad)?;
        let digits = inner[..close]
            .strip_prefix(['B', 'b'])
            .filter(|d| !d.is_empty() && d.len() <= 8)
            .ok_or_else(bad)?;
        let value = u64::from_str_radix(digits, 2).map_err(|_| bad())?;
        return Ok((value, from..from + close + 2, true));
    }
    let (v, span) = number_at(code, from)
        .filter(|(_, s)| ends_member(code, s.end))
        .ok_or_else(bad)?;
    match v >= 0.0 && v.fract() == 0.0 && v < 256.0 {
        true => Ok((v as u64, span, false)),
        false => Err(bad()),
    }
}

/// What a line sets: the base (`true`) or the tool (`false`) and the frame, `None` for a line
/// that sets neither. `$BASE`/`$TOOL` = a literal frame (all six members), `$NULLFRAME`,
/// `$WORLD` (a base); anything else (`BASE_DATA[n]`, `BAS(#BASE, n)`, a variable) is held on
/// the controller.
pub(crate) fn frame_set(line: u64, code: &str) -> Option<(bool, Frame)> {
    let t = code.trim();
    let upper = t.to_ascii_uppercase();
    let compact: String = upper.chars().filter(|c| !c.is_whitespace()).collect();
    let base = if compact.starts_with("$BASE=") || compact.starts_with("BAS(#BASE") {
        true
    } else if compact.starts_with("$TOOL=") || compact.starts_with("BAS(#TOOL") {
        false
    } else {
        return None;
    };
    let name = if base { "$BASE" } else { "$TOOL" };
    let held = |what: &str| {
        Frame::Unknown(line, format!("{name} is {what} on line {line}: a frame held on the controller, which the program does not state; set {name} = {{X .., Y .., Z .., A .., B .., C ..}} in the program"))
    };
    let Some(value) = t.split_once('=').map(|(_, v)| v.trim()) else {
        return Some((base, held(&stiffid_core::common::limits::short(t))));
    };
    let value_upper = value.to_ascii_uppercase();
    let frame = match value_upper.as_str() {
        "$NULLFRAME" => Frame::World,
        "$WORLD" if base => Frame::World,
        _ if value.starts_with('{') => match linked(value) {
            Ok(f) => Frame::Stated(line, f),
            Err(why) => Frame::Unknown(line, format!("{name} on line {line}: {why}")),
        },
        other => held(&stiffid_core::common::limits::short(other)),
    };
    Some((base, frame))
}

/// The frame of literal frames linked by KRL's geometric operator, `{..} : {..} : ..` (each
/// operand in the frame of the one before it: their product, left to right), m; `Err` why not
/// (an operand that is not a whole literal frame: the controller's frame or a variable).
fn linked(value: &str) -> std::result::Result<Isometry3<f64>, String> {
    let mut frame = Isometry3::identity();
    let mut rest = value.trim();
    while !rest.is_empty() {
        let Some(close) = rest.find('}').filter(|_| rest.starts_with('{')) else {
            return Err(format!("expected a frame {{X .., Y .., Z .., A .., B .., C ..}} with all six members, or literal frames linked by ':', at '{}'", stiffid_core::common::limits::short(rest)));
        };
        frame *= literal(&rest[..=close])?;
        rest = rest[close + 1..].trim_start();
        if let Some(next) = rest.strip_prefix(':') {
            rest = next.trim_start();
            if rest.is_empty() {
                return Err("':' without a frame after it".into());
            }
        } else if !rest.is_empty() {
            return Err(format!(
                "'{}' after the frame: expected ':' and a frame, or nothing",
                stiffid_core::common::limits::short(rest)
            ));
        }
    }
    Ok(frame)
}

/// A literal frame `{X .., Y .., Z .., A .., B .., C ..}` (optionally `{FRAME: ..}`), m, or
/// why it is none: not all six members once, or one beyond the limits ([`outside_limits`]).
fn literal(value: &str) -> std::result::Result<Isometry3<f64>, String> {
    let members =
        || "expected a frame {X .., Y .., Z .., A .., B .., C ..} with all six members".to_string();
    let v = members_of(value).ok_or_else(members)?;
    if let Some(why) = outside_limits(&POSE, v.iter().copied()) {
        return Err(why);
    }
    let r =
        UnitQuaternion::from_euler_angles(v[5].to_radians(), v[4].to_radians(), v[3].to_radians());
    Ok(Isometry3::from_parts(
        Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3),
        r,
    ))
}

/// The six members of a literal frame, each given once, in [`POSE`]'s order.
fn members_of(value: &str) -> Option<Vec<f64>> {
    let inner = value.strip_prefix('{')?.split('}').next()?;
    let inner = inner.split_once(':').map_or(inner, |(_, r)| r);
    let mut v = [None; 6];
    for item in inner.split(',') {
        let item = item.trim();
        let name: String = item
            .chars()
            .take_while(|c| c.is_ascii_alphabetic())
            .collect();
        let k = POSE.iter().position(|p| p.eq_ignore_ascii_case(&name))?;
        let (x, _) = number_at(item, name.len())?;
        v[k] = Some(v[k].map_or(x, |_| f64::NAN));
    }
    let v: Vec<f64> = v.into_iter().collect::<Option<Vec<f64>>>()?;
    v.iter().all(|x| x.is_finite()).then_some(v)
}
