//! FANUC LS: the `/MN` section's motions `J P[i] 100% FINE ;`, `L P[i] 50mm/sec CNT100 ;` and
//! `C P[i] .. P[j] ..` (the via point and the end: two targets; `motion`), their terminations
//! and options (`options`), to the `/POS` section's positions in joint representation,
//! `P[1]{ GP1: UF : 0, UT : 1, J1= 0.000 deg, J2= ... J6= ... deg };` over one or more lines.
//! Group 1 (`GP1`: the robot's `J1`..`J6` and its extended axes `E1`..`E3`, such as a track)
//! and group 2 (`GP2`: `J1`.., a positioner) are read, mm for a linear axis and deg for a rotary
//! one; a position without group 1, group 2 in Cartesian representation (a second robot) and a
//! third group are refused. An `INC` motion after one that ends `FINE` goes to the previous
//! target plus the position's increments (every axis of both groups). A position in Cartesian
//! representation (`CONFIG : '..'`, `X = .. mm` to `R = .. deg`, in its `UF` and `UT`) is a
//! Cartesian target ([`super::cartesian`]) in the frames the controller holds by number
//! (`numbered`); an `INC` motion to one is refused. The instructions around the motions are
//! passed over, followed (`UFRAME_NUM`, `UTOOL_NUM`) or refused naming the line
//! (`statements`). The rules come from the FANUC R-30iA/R-30iB HandlingTool Operator's Manual;
//! docs/programs/ls.md gives each with its source.

mod calls;
mod cartesian;
pub(crate) mod config;
mod copies;
mod flow;
pub mod generate;
mod mask;
mod motion;
mod names;
mod numbered;
mod offsets;
mod options;
mod process;
mod read;
mod registers;
mod set_frames;
pub(crate) mod speed;
mod statements;
mod sysframe;
mod va;
mod values;

pub use config::Config;

use super::cartesian::Flags;
use super::controller::{BoundComment, Controller, Generator, Read};
use super::descriptor::{AxisNames, Descriptor, FileName, NameRules};
use super::generate::zyx_deg;
use super::{at, number_at, six, Found, JointTarget, Units};
use cartesian::Value;
use nalgebra::{UnitQuaternion, Vector3};
use std::collections::{HashMap, HashSet};
use stiffid_core::Result;

/// The `/MN` instructions: the line of each and its text (continuation lines `   :` joined),
/// without the line number and the closing `;`; comments (`!`, `//`) dropped. A line without a
/// number (`   :`) continues the instruction before it while that one is open (its line did not
/// end with `;`: a circular move's end, a motion's options on the next line); after a closed one
/// it is an instruction of its own, as generators that leave the numbering to the controller
/// write them. A line of `/MN` that is neither blank, numbered (`  4:`) nor unnumbered (`   :`)
/// is refused: the controller loads no such line, and passed over it would drop what it holds
/// (a motion).
fn instructions(text: &str) -> Result<Vec<(u64, String)>> {
    let mut out: Vec<(u64, String)> = Vec::new();
    let mut in_mn = false;
    let mut open = false;
    for (line, _, l) in super::lines(text) {
        let t = l.trim();
        if t.starts_with('/') {
            in_mn = t.starts_with("/MN");
            continue;
        }
        if !in_mn {
            continue;
        }
        if t.is_empty() {
            continue;
        }
        let unnumbered = || {
            at(line, format!("'{}': expected a numbered instruction ('4: L P[4] ..') or a continuation (': ..') in /MN", stiffid_core::common::limits::short(t)))
        };
        let (number, body) = t.split_once(':').ok_or_else(unnumbered)?;
        let closed = body.trim_end().ends_with(';');
        let body = body.trim_end().trim_end_matches(';');
        let number = number.trim();
        match out.last_mut() {
            Some(last) if number.is_empty() && open => {
                last.1.push(' ');
                last.1.push_str(body);
            }
            _ if number.chars().all(|c| c.is_ascii_digit()) => {
                let b = body.trim_start();
                if !(b.starts_with('!') || b.starts_with("//")) {
                    out.push((line, body.to_string()));
                }
            }
            _ => return Err(unnumbered()),
        }
        open = !closed;
    }
    Ok(out)
}

/// A position being read: its index, first line, the six axes, group 1's extended axes and
/// group 2's axes, and the group of the values read now.
struct Open {
    index: u64,
    first: u64,
    found: Found,
    extended: Vec<Value>,
    second: Vec<Value>,
    group: u8,
    /// Whether the position gives group 1 (`GP1:`).
    first_group: bool,
    /// A Cartesian position's `X`..`R`, `CONFIG` and user and tool frame numbers.
    pose: [Value; 6],
    config: Option<(Flags, std::ops::Range<usize>)>,
    frames: (Option<u32>, Option<u32>),
}

/// The `/POS` section's positions by index (module docs), the program's external axes: group 1's
/// `E1`.. then group 2's `J1`.. (`GP2 J1`), and their units.
fn positions(text: &str) -> Result<(HashMap<u64, JointTarget>, Vec<String>, Units)> {
    let mut read: Vec<Open> = Vec::new();
    let mut numbers = HashSet::new();
    let mut units: AxisUnits = HashMap::new();
    let mut in_pos = false;
    let mut open: Option<Open> = None;
    for (line, start, l) in super::lines(text) {
        let t = l.trim();
        if t.starts_with('/') {
            in_pos = t.starts_with("/POS");
            continue;
        }
        if !in_pos {
            continue;
        }
        if let Some(inner) = t.strip_prefix("P[") {
            if let Some(o) = &open {
                return Err(at(o.first, "position without its closing '};'".into()));
            }
            open = Some(Open::new(line, inner, &mut numbers)?);
        }
        let Some(o) = open.as_mut() else {
            continue;
        };
        let masked = cartesian::masked(l);
        for (offset, item) in split_keeping_offsets(&masked) {
            o.item((line, start, l), offset, item, &mut units)?;
        }
        if o.group == 1
            && let Some(c) = cartesian::config(line, start, l)?
        {
            o.config = Some(c);
        }
        if t.ends_with("};")
            && let Some(o) = open.take()
        {
            read.push(o);
        }
    }
    if let Some(o) = open {
        return Err(at(o.first, "position without its closing '};'".into()));
    }
    assemble(read, &units)
}

/// Per group and axis number, the unit of an axis's values and the line of the first.
type AxisUnits = HashMap<(u8, usize), (&'static str, u64)>;

impl Open {
    /// The position opened on `line` by `P[` and `inner`, its number not among `numbers` (the
    /// numbers opened before, a set: a scan of the positions read made reading quadratic).
    fn new(line: u64, inner: &str, numbers: &mut HashSet<u64>) -> Result<Self> {
        let index = inner
            .split([':', ']'])
            .next()
            .and_then(|i| i.trim().parse::<u64>().ok())
            .ok_or_else(|| at(line, "P[: expected a position number".into()))?;
        if !numbers.insert(index) {
            return Err(at(line, format!("P[{index}] defined twice in /POS")));
        }
        Ok(Open {
            index,
            first: line,
            found: Default::default(),
            extended: Vec::new(),
            second: Vec::new(),
            group: 0,
            first_group: false,
            pose: Default::default(),
            config: None,
            frames: (None, None),
        })
    }

    /// One item of line `l` (its number `line`, its first byte `start` in the text) at byte
    /// `offset`: a group's start, a frame number, a pose's value, an axis's value.
    fn item(
        &mut self,
        (line, start, l): (u64, usize, &str),
        offset: usize,
        item: &str,
        units: &mut AxisUnits,
    ) -> Result<()> {
        let mut item_t = item.trim();
        if let Some(g) = item_t.strip_prefix("GP") {
            self.group = group(line, item_t, g)?;
            self.first_group |= self.group == 1;
            item_t = item_t.split_once(':').map_or("", |(_, r)| r.trim());
        }
        if self.group == 0 {
            return Ok(());
        }
        if let Some((user, n)) = cartesian::frame_number(line, item_t)? {
            if self.group == 1 {
                *(if user {
                    &mut self.frames.0
                } else {
                    &mut self.frames.1
                }) = Some(n);
            }
            return Ok(());
        }
        let Some(eq) = item.find('=') else {
            return Ok(());
        };
        let name = item[..eq].trim();
        let name = name.rsplit(':').next().unwrap_or(name).trim();
        let number = |prefix: char| {
            name.strip_prefix(prefix)
                .and_then(|d| d.parse::<usize>().ok())
        };
        let span = |s: std::ops::Range<usize>| start + s.start..start + s.end;
        if self.group == 2 && cartesian::POSE.iter().any(|(n, _)| *n == name) {
            return Err(at(line, format!("GP2 {name}: group 2 in Cartesian representation (a second robot); stiffid reads group 2 as a positioner's axes J1.. in joint representation")));
        }
        if let (1, Some(k)) = (
            self.group,
            cartesian::POSE.iter().position(|(n, _)| *n == name),
        ) {
            let (v, s, _) = value(l, offset + eq + 1, line, name, &[cartesian::POSE[k].1])?;
            once(line, self.index, name, self.pose[k].is_some())?;
            self.pose[k] = Some((v, span(s)));
            return Ok(());
        }
        let (values, k) = match (self.group, number('J'), number('E')) {
            (1, Some(k @ 1..=6), _) => {
                let (v, s, _) = value(l, offset + eq + 1, line, name, &["deg"])?;
                once(line, self.index, name, self.found[k - 1].is_some())?;
                self.found[k - 1] = Some((v, span(s)));
                return Ok(());
            }
            (1, _, Some(k @ 1..=3)) => (&mut self.extended, k),
            (2, Some(k @ 1..=6), _) => (&mut self.second, k),
            _ => return Ok(()),
        };
        let (v, s, unit) = value(l, offset + eq + 1, line, name, &["mm", "deg"])?;
        let (first_unit, first_line) = *units.entry((self.group, k)).or_insert((unit, line));
        if first_unit != unit {
            return Err(at(line, format!("{name} in {unit}: the same axis is in {first_unit} on line {first_line}; one unit per axis (mm for a linear axis, deg for a rotary one)")));
        }
        if values.len() < k {
            values.resize(k, None);
        }
        once(line, self.index, name, values[k - 1].is_some())?;
        values[k - 1] = Some((v, span(s)));
        Ok(())
    }
}

/// The positions read, each a joint or a Cartesian target with its external values (group 1's
/// extended axes, then group 2's), the program's external axes and their units.
fn assemble(
    read: Vec<Open>,
    units: &AxisUnits,
) -> Result<(HashMap<u64, JointTarget>, Vec<String>, Units)> {
    let n1 = read.iter().map(|o| o.extended.len()).max().unwrap_or(0);
    let n2 = read.iter().map(|o| o.second.len()).max().unwrap_or(0);
    let mut out = HashMap::with_capacity(read.len());
    for mut o in read {
        o.extended.resize(n1, None);
        o.extended.append(&mut o.second);
        if !o.first_group {
            return Err(at(o.first, format!("P[{}]: no group 1 (GP1): the program moves another motion group (its DEFAULT_GROUP); stiffid reads motion group 1 as the robot", o.index)));
        }
        let target = match o.pose.iter().any(Option::is_some) || o.config.is_some() {
            true if o.found.iter().any(Option::is_some) => {
                return Err(at(o.first, "a position with both joint (J1=) and Cartesian (X =, CONFIG) values: give one representation".into()));
            }
            true => {
                let c = cartesian::target(o.first, &o.pose, o.config.take(), o.frames)?;
                JointTarget::cartesian(o.first, c)
            }
            false => six(o.first, o.found, "J")?,
        };
        out.insert(o.index, target.with_external(o.extended));
    }
    let axes = (1..=n1).map(|k| format!("E{k}"));
    let axes = axes.chain((1..=n2).map(|k| format!("GP2 J{k}")));
    let keys = (1..=n1).map(|k| (1, k)).chain((1..=n2).map(|k| (2, k)));
    let units = keys.map(|key| units.get(&key).copied()).collect();
    Ok((out, axes.collect(), units))
}

/// The motion group `GPn:` opens (`g`: the item `item` after `GP`), 1 or 2; a third group or
/// no number is refused naming the line.
fn group(line: u64, item: &str, g: &str) -> Result<u8> {
    let shown = stiffid_core::common::limits::short(item.trim_end_matches(':'));
    match g.split(':').next().unwrap_or("").trim().parse::<u32>() {
        Ok(n @ 1..=2) => Ok(n as u8),
        Ok(_) => Err(at(line, format!("{shown}: a third motion group; stiffid reads group 1 (the robot and its extended axes) and group 2 (a positioner)"))),
        Err(_) => Err(at(line, format!("{shown}: expected a motion group number, GP1 or GP2"))),
    }
}

/// Refuses a value of a position given a second time (`given`): which one the controller takes
/// is not the file's to say.
fn once(line: u64, index: u64, name: &str, given: bool) -> Result<()> {
    match given {
        true => Err(at(line, format!("{name}: given twice in P[{index}]"))),
        false => Ok(()),
    }
}

/// The number after the `=` at byte `from` of `l` and its unit, one of `units`.
fn value(
    l: &str,
    from: usize,
    line: u64,
    name: &str,
    units: &[&'static str],
) -> Result<(f64, std::ops::Range<usize>, &'static str)> {
    let (v, span) = number_at(l, from).ok_or_else(|| match l[from..].trim_start() {
        t if t.starts_with('*') => at(line, format!("{name} = ********: the position was never taught (the pendant shows its values as asterisks); teach it, or remove the motion to it")),
        _ => at(line, format!("{name}: expected a number")),
    })?;
    let unit = l[span.end..].trim_start();
    match units.iter().find(|u| unit.starts_with(*u)) {
        Some(u) => Ok((v, span, u)),
        None => Err(at(
            line,
            format!("{name}: expected a value in {}", units.join(" or ")),
        )),
    }
}

/// The comma-separated pieces of a line (also split at `{`) with their byte offsets.
fn split_keeping_offsets(l: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut from = 0;
    for (i, c) in l.char_indices() {
        if c == ',' || c == '{' {
            out.push((from, &l[from..i]));
            from = i + 1;
        }
    }
    out.push((from, &l[from..]));
    out
}

/// FANUC LS (module docs).
#[derive(Debug, Clone, Copy)]
pub(crate) struct FanucLs;

impl Controller for FanucLs {
    type Flags = Config;
    const LANGUAGE: &'static Descriptor = &Descriptor {
        key: "ls",
        title: "FANUC LS",
        extensions: &["ls"],
        data_files: &[],
        motions: "J, L or C to a P[i] of /POS",
        joint_forms: "positions in joint representation",
        part_forms: Some("Cartesian positions in a user frame UF : n, n >= 1, that a remark `! stiffid: user_frame = n ;` names"),
        external_axes: AxisNames::Numbered("E"),
        unused_axis: "",
        zero_is_no_axis: false,
        // R-30iA's default length; later controllers take longer names.
        names: NameRules {
            declared_by: Some("/PROG"),
            file: FileName::Upper,
            max_length: 36,
            default_length: 8,
            reserved: names::RESERVED,
        },
        bound_comment: BoundComment::PositionComment,
        // The motion lines are those of `/MN` only (`motion_lines`).
        motion_words: &[],
        frame_numbers: (10, 9),
        axis_3_from_horizontal: true,
    };

    fn read(&self, text: &str) -> Result<Read> {
        self.read_in(text, &super::Context::default())
    }
    fn read_in(&self, text: &str, context: &super::Context) -> Result<Read> {
        let read::Program {
            targets,
            axes,
            units,
            left,
            called,
            notes,
        } = read::targets(text, context)?;
        Ok(Read {
            targets,
            axes,
            pulses: Vec::new(),
            units,
            left,
            called,
            notes,
        })
    }
    /// `R = Rz(R) Ry(P) Rx(W)`.
    fn rotation(&self, n: &[f64]) -> UnitQuaternion<f64> {
        UnitQuaternion::from_euler_angles(n[3].to_radians(), n[4].to_radians(), n[5].to_radians())
    }
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        let [a, b, c] = zyx_deg(r);
        vec![p.x, p.y, p.z, c, b, a]
    }
    /// The `J P[..]`, `L P[..]` and `C P[..]` lines of `/MN`.
    fn motion_lines(&self, text: &str) -> Vec<u64> {
        let mut in_mn = false;
        (text.lines().enumerate())
            .filter(|(_, l)| {
                let t = l.trim_start();
                if t.starts_with('/') {
                    in_mn = t.starts_with("/MN");
                }
                let body = t.split_once(':').map_or("", |(_, b)| b);
                in_mn && ["J P[", "L P[", "C P["].iter().any(|m| body.starts_with(m))
            })
            .map(|(i, _)| i as u64 + 1)
            .collect()
    }
    /// A backup folder's programs and its ASCII variable files (`SYSFRAME.VA`, `POSREG.VA`).
    fn backup_extensions(&self) -> &'static [&'static str] {
        &["ls", "va"]
    }
    /// The variable files read by name: one of a folder that is not text is refused.
    fn backup_names(&self) -> &'static [&'static str] {
        &["SYSFRAME.VA", "POSREG.VA", "SYMOTN.VA"]
    }
    fn generator(&self) -> Option<&'static dyn Generator> {
        Some(&FanucLs)
    }
}
