//! ABB RAPID's Cartesian targets (module docs of [`super`]): `MoveL`/`MoveJ` to a `robtarget`
//! with its `tooldata` and `\WObj:=` `wobjdata`, each a literal or declared in the module.

use crate::program::cartesian::flags::Part;
use crate::program::cartesian::literal::{self, Node};
use crate::program::cartesian::{within_limits, Cartesian, Flags, Frame};
use crate::program::rapid::ConfData;
use crate::program::{at, Dialect, JointTarget};
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use std::collections::HashMap;
use stiffid_core::Result;

/// A declared target by name (`named` of [`motion`]).
type Named<'a> = &'a dyn Fn(&str) -> Result<JointTarget>;

/// How far from 1 the norm of a quaternion the program gives may be.
const UNIT: f64 = 1e-4;

/// The target of the `robtarget` literal `[[x,y,z],[q1,q2,q3,q4],[cf1,cf4,cf6,cfx],[eax_a,
/// ..,eax_f]]` at or after byte `from` of `code` (`9E9`: an external axis not used).
pub(crate) fn robtarget(line: u64, code: &str, from: usize) -> Result<JointTarget> {
    let bad = |what: &str| {
        at(line, format!("robtarget: expected [[x,y,z],[q1,q2,q3,q4],[cf1,cf4,cf6,cfx],[eax_a,..,eax_f]], {what}"))
    };
    let (node, _) = literal::parse(code, from).ok_or_else(|| {
        bad(&format!(
            "not a literal (balanced brackets, nested at most {} deep)",
            literal::MAX_DEPTH
        ))
    })?;
    let parts = node
        .list()
        .filter(|p| p.len() == 4)
        .ok_or_else(|| bad("not four brackets"))?;
    let mut pose = parts[0]
        .numbers(3)
        .ok_or_else(|| bad("the position is not 3 numbers"))?;
    pose.extend(
        parts[1]
            .numbers(4)
            .ok_or_else(|| bad("the orientation is not 4 numbers"))?,
    );
    let conf = parts[2]
        .numbers(4)
        .ok_or_else(|| bad("the confdata are not 4 numbers"))?;
    let external = parts[3]
        .numbers(6)
        .ok_or_else(|| bad("the external axes are not 6 numbers"))?;
    within_limits(line, &["x", "y", "z"], &pose[..3])?;
    check_unit(line, &pose[3..])?;
    if conf.iter().any(|(v, _)| v.fract() != 0.0) {
        return Err(bad("the confdata are not whole numbers"));
    }
    let mut c = Cartesian::new(Dialect::Rapid, &pose);
    c.flags = Some(Flags::new(ConfData([0, 1, 2, 3].map(|k| conf[k].0 as i64))));
    c.flag_spans = (conf.into_iter().enumerate())
        .map(|(k, (_, span))| (span, Part::new(k)))
        .collect();
    let external = external
        .into_iter()
        .map(|(v, s)| (v < 8.9e9).then_some((v, s)))
        .collect();
    Ok(JointTarget::cartesian(line, c).with_external(external))
}

/// Refuses an orientation that is not a unit quaternion (a component beyond 1 first: the
/// norm of `[1e308, 0, 0, 0]` is no number).
fn check_unit(line: u64, q: &[(f64, std::ops::Range<usize>)]) -> Result<()> {
    if let Some((v, _)) = q.iter().find(|(v, _)| v.abs() > 1.0 + UNIT) {
        return Err(at(line, format!("the orientation's quaternion has a component {}: expected a unit quaternion, each component within -1 to 1", stiffid_core::common::words::number(*v))));
    }
    let norm = q.iter().map(|(v, _)| v * v).sum::<f64>().sqrt();
    match (norm - 1.0).abs() <= UNIT {
        true => Ok(()),
        false => Err(at(
            line,
            format!(
                "the orientation's quaternion has norm {}: expected 1 (within {UNIT})",
                stiffid_core::common::words::number(norm)
            ),
        )),
    }
}

/// A RAPID `pose` `[[x,y,z],[q1,q2,q3,q4]]` (mm) as a frame, m.
fn pose(line: u64, node: &Node) -> Result<Isometry3<f64>> {
    let bad = || at(line, "expected a pose [[x,y,z],[q1,q2,q3,q4]]".into());
    let parts = node.list().filter(|p| p.len() == 2).ok_or_else(bad)?;
    let p = parts[0].numbers(3).ok_or_else(bad)?;
    let q = parts[1].numbers(4).ok_or_else(bad)?;
    within_limits(line, &["x", "y", "z"], &p)?;
    check_unit(line, &q)?;
    let r = UnitQuaternion::from_quaternion(Quaternion::new(q[0].0, q[1].0, q[2].0, q[3].0));
    Ok(Isometry3::from_parts(
        Translation3::new(p[0].0 * 1e-3, p[1].0 * 1e-3, p[2].0 * 1e-3),
        r,
    ))
}

/// The frame a `tooldata` (its `tframe`, the robot holding the tool) or `wobjdata` (`uframe`
/// then `oframe`, a fixed user frame the robot does not hold) literal at or after byte `from`
/// states, or why it is none.
pub(crate) fn frame(kind: &str, name: &str, line: u64, code: &str, from: usize) -> Frame {
    let read = || -> Result<Frame> {
        let bad = |what: &str| at(line, format!("{kind} {name}: {what}"));
        let (node, _) = literal::parse(code, from).ok_or_else(|| bad("expected a literal"))?;
        let items = node.list().ok_or_else(|| bad("expected a literal"))?;
        let frame = match (kind, items) {
            ("tooldata", [hold, tframe, ..]) => match hold.boolean() {
                Some(true) => pose(line, tframe)?,
                _ => return Err(bad(
                    "a stationary tool (robhold FALSE): stiffid compensates a tool the robot holds",
                )),
            },
            ("wobjdata", [hold, programmed, unit, uframe, oframe, ..]) => {
                match (hold.boolean(), programmed.boolean()) {
                    (Some(false), Some(true)) => pose(line, uframe)? * pose(line, oframe)?,
                    (Some(true), _) => return Err(bad("robhold TRUE: a work object the robot holds (its tool stationary); stiffid reads a work object fixed in the world, the robot holding the tool")),
                    (_, Some(false)) => {
                        let unit = match unit { Node::Text(t) => t.as_str(), _ => "" };
                        return Err(bad(&format!("ufprog FALSE: a user frame the mechanical unit \"{unit}\" (ufmec) moves, whose pose at the motion is the controller's; stiffid reads a fixed user frame (ufprog TRUE)")));
                    }
                    _ => return Err(bad("expected robhold and ufprog to be TRUE or FALSE")),
                }
            }
            _ => return Err(bad("expected the members of its type")),
        };
        Ok(Frame::Stated(line, frame))
    };
    read().unwrap_or_else(|e| match e {
        stiffid_core::Error::Program { line, message } => Frame::Unknown(line, message),
        other => Frame::Unknown(line, other.to_string()),
    })
}

/// The targets of a `MoveL`/`MoveJ` (`points` 1) or `MoveC` (`points` 2: the circle point, then
/// the end point) statement, with its tool and work object, from its arguments `args` (the text
/// after the instruction's name and switches, without `;`, at byte `from` of `code`), `process`
/// arguments between its speed and zone (an arc welding motion's seam and weld data); `named`
/// gives a declared `robtarget` by name.
pub(crate) fn motion(
    line: u64,
    (code, from, args): (&str, usize, &str),
    (points, process): (usize, usize),
    named: &dyn Fn(&str) -> Result<JointTarget>,
    (frames, nums): (&HashMap<String, Frame>, &super::num::Nums),
) -> Result<Vec<JointTarget>> {
    let joined = super::arguments::switches_joined(args);
    let args = joined.as_str();
    let parts = super::arguments::top_level(args);
    let at_tool = points + 2 + process;
    let Some(tool) = parts.get(at_tool).filter(|_| parts.len() > at_tool) else {
        let what = match points {
            1 => "a target",
            _ => "a circle point, an end point",
        };
        let data = if process > 0 {
            ", its seam and weld data"
        } else {
            ""
        };
        return Err(at(
            line,
            format!("expected {what}, a speed{data}, a zone and a tool"),
        ));
    };
    // *RAPID Instructions*, MoveL: `.. Zone [\Z] [\Inpos] Tool [\WObj] [\Corr] [\TLoad]`.
    let early = |r: &std::ops::Range<usize>| {
        let t = args[r.clone()].to_ascii_lowercase();
        ["\\wobj", "\\corr", "\\tload"]
            .into_iter()
            .find(|w| t.contains(w))
    };
    if let Some(w) = parts[..at_tool].iter().find_map(early) {
        return Err(at(line, format!("{w} before the tool: the controller refuses the statement (the tool, then {w}); write it after the tool")));
    }
    let tool_text = &args[tool.clone()];
    let (tool_name, switches) = tool_text.split_once('\\').unwrap_or((tool_text, ""));
    let names: Vec<String> = (switches.split('\\'))
        .map(|s| {
            s.split(":=")
                .next()
                .unwrap_or("")
                .trim()
                .to_ascii_lowercase()
        })
        .collect();
    if let Some(twice) =
        (names.iter().enumerate()).find_map(|(k, n)| names[..k].contains(n).then_some(n))
    {
        // *RAPID kernel*, routine calls: an optional argument is given once.
        return Err(at(line, format!("\\{twice} given twice after the tool: the controller refuses the statement; give it once")));
    }
    let wobj = switches.split('\\').find_map(|s| {
        let (k, v) = s.split_once(":=")?;
        k.trim()
            .eq_ignore_ascii_case("wobj")
            .then(|| v.trim().to_string())
    });
    if switches
        .split('\\')
        .any(|s| s.trim().eq_ignore_ascii_case("corr"))
    {
        // *RAPID Instructions*, MoveL: `\Corr` adds the correction a sensor writes
        // (`CorrWrite`) to the path at run time.
        return Err(at(line, format!("\\Corr (tool {}): the path is corrected at run time by the offsets a correction generator receives (CorrWrite), which the program does not hold; not compensated", tool_name.trim())));
    }
    let mut out = Vec::with_capacity(points);
    for part in &parts[..points] {
        let mut t = point(
            line,
            code,
            from + part.start,
            &args[part.clone()],
            (named, nums),
        )?;
        let c = t
            .cartesian
            .as_deref_mut()
            .ok_or_else(|| at(line, "expected a robtarget".into()))?;
        c.tool = lookup(line, "tooldata", "tool0", tool_name.trim(), frames);
        c.frame = match &wobj {
            None => Frame::World,
            Some(w) => lookup(line, "wobjdata", "wobj0", w, frames),
        };
        out.push(t);
    }
    out[0].via = points == 2;
    Ok(out)
}

/// One point argument `text` (at byte `from` of `code`): a `robtarget` literal, a declared one,
/// or `Offs`/`RelTool` of one with constant displacements ([`super::offset`]).
pub(super) fn point(
    line: u64,
    code: &str,
    from: usize,
    text: &str,
    (named, nums): (Named, &super::num::Nums),
) -> Result<JointTarget> {
    let lead = text.len() - text.trim_start().len();
    let text = text.trim_start();
    if text.starts_with('[') {
        return robtarget(line, code, from + lead);
    }
    let ident: String = text
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    let next = text[ident.len()..].trim_start();
    if !ident.is_empty() && (next.is_empty() || next.starts_with('\\')) {
        let at = from + lead;
        return named(&ident).map(|t| super::at_reference(t, at..at + ident.len()));
    }
    // An array's element (`pts{2}`), as the whole point.
    let element = (next.starts_with('{').then(|| next.find('}')).flatten()).filter(|&c| {
        next[c + 1..].trim().is_empty() || next[c + 1..].trim_start().starts_with('\\')
    });
    if let (Some(close), false) = (element, ident.is_empty()) {
        return named(&text[..text.len() - next.len() + close + 1]);
    }
    if let Some(f) = super::offset::Function::of(&ident).filter(|_| next.starts_with('(')) {
        let open = from + lead + text.len() - next.len();
        let end = from + lead + text.len();
        let (base, args) = super::offset::arguments(line, f, code, (open, end), nums)?;
        let mut t = point(line, code, base.start, &code[base], (named, nums))?;
        if let Some(c) = t.cartesian.as_deref_mut() {
            f.apply(c, &args);
        }
        return Ok(t);
    }
    Err(at(line, "the target is computed on the controller (a function other than Offs and RelTool, a variable argument, an expression or an array element); stiffid compensates robtarget literals, robtargets declared in the module and Offs or RelTool of them by constants".into()))
}

/// The frame of a tool or work object named in a motion.
fn lookup(
    line: u64,
    kind: &str,
    flange: &str,
    name: &str,
    frames: &HashMap<String, Frame>,
) -> Frame {
    let key = name.to_ascii_lowercase();
    if key == flange {
        return Frame::World;
    }
    let mut frame = frames.get(&key).cloned().unwrap_or_else(|| {
        Frame::Unknown(line, format!("{kind} {name}: not declared with a value in this module or the backup's modules given; give the task's modules (--backup, Python backup=), or declare it in the module"))
    });
    // A frame of another module of the task (line 0, `backup::foreign`): the motion's line.
    if let Frame::Stated(l @ 0, _) | Frame::Unknown(l @ 0, _) = &mut frame {
        *l = line;
    }
    frame
}

/// Whether a declared type is one of the Cartesian data (`robtarget`, `tooldata`, `wobjdata`).
pub(crate) fn is_data(kind: &str) -> bool {
    matches!(kind, "robtarget" | "tooldata" | "wobjdata")
}
