//! The program's own copy of each position register a motion moves to ([`super::registers`]):
//! a new position `P[n]` of `/POS` (after the positions the program holds, numbered on from
//! its largest), its values the register's as the backup holds them (with the 9 decimals a
//! compensated value is written with: a value that does not move is the same text), in the
//! frame numbers in
//! force at the motion (`UFRAME_NUM`, `UTOOL_NUM`: a Cartesian register is in the frames in
//! force where it is used, FANUC's `UF : F, UT : F`; where the program selects none, the
//! position keeps `F` and is refused as such). Compensated, the motion names the copy (`J PR[3]`
//! becomes `J P[n]`) and the copy is written before `/END`; a motion whose target does not move
//! keeps the register.

use super::registers::Register;
use super::statements::{Number, Selected};
use super::va::Value;
use crate::program::generate::v as v_text;
use crate::program::points::Foreign;
use crate::program::{at, lines, JointTarget, Units};
use std::collections::HashMap;
use std::ops::Range;
use stiffid_core::{Error, Result};

/// One motion's copy: its position's number, the copy's text and where it goes, the bytes of the
/// register's name at the motion, and the note that says so.
pub(super) struct Copy {
    pub index: u64,
    foreign: Foreign,
    insert: usize,
    reference: Range<usize>,
    pub note: String,
}

/// The copies of a program: their positions by number (spans in the copies' own text), their
/// external axes and units, and per motion instruction its copy.
#[derive(Default)]
pub(super) struct Copies {
    pub positions: HashMap<u64, JointTarget>,
    pub axes: Vec<String>,
    pub units: Units,
    pub by_motion: HashMap<usize, Copy>,
}

impl Copy {
    /// `t`, the target read from the copy, as the position the program declares anew and the
    /// motion names ([`JointTarget::declared_elsewhere`]).
    pub(super) fn attach(&self, t: JointTarget) -> JointTarget {
        let name = 0..format!("P[{}]", self.index).len();
        t.declared_elsewhere(self.foreign.clone(), name, self.insert)
            .named_at(self.reference.clone())
    }
}

/// The copies of the `registers` the motions of `instructions` move to in the program `text`,
/// numbered after the largest of its `positions`, each in the frame numbers `selected` in force
/// at its motion (module docs).
///
/// # Errors
/// Naming the motion's line: a program without `/POS`, a register whose values do not read as a
/// position (an axis never set, `********`).
pub(super) fn build(
    text: &str,
    instructions: &[(u64, String)],
    registers: &HashMap<usize, Register>,
    selected: impl Fn(usize) -> Option<Selected>,
    largest: u64,
) -> Result<Copies> {
    let mut motions: Vec<usize> = registers.keys().copied().collect();
    motions.sort_unstable();
    let Some(&first) = motions.first() else {
        return Ok(Copies::default());
    };
    let starts: HashMap<u64, (usize, &str)> = lines(text).map(|(l, s, t)| (l, (s, t))).collect();
    let find = |word: &str| lines(text).find(|(_, _, l)| l.trim_start().starts_with(word));
    let (Some(_), Some((_, insert, _))) = (find("/POS"), find("/END")) else {
        let line = instructions[first].0;
        return Err(at(line, "a motion to a position register of a program without /POS and /END: stiffid writes the register's copy as a position of /POS".into()));
    };
    let eol = if text.contains("\r\n") { "\r\n" } else { "\n" };
    let mut all = format!("/POS{eol}");
    let mut placed = Vec::with_capacity(motions.len());
    for (j, k) in motions.iter().enumerate() {
        let index = largest + 1 + j as u64;
        let s = selected(*k).unwrap_or_default();
        let block = block(index, &registers[k], &s, eol);
        placed.push((*k, index, all.len(), block.clone(), lines_in(&all)));
        all.push_str(&block);
    }
    let (positions, axes, units) = super::positions(&all).map_err(|e| {
        let line = match &e {
            Error::Program { line, .. } => *line,
            _ => 0,
        };
        let k = placed
            .iter()
            .rev()
            .find(|p| p.4 < line)
            .map_or(first, |p| p.0);
        let r = &registers[&k];
        at(
            instructions[k].0,
            format!("PR[{}] as {} holds it: {}", r.number, r.source, message(e)),
        )
    })?;
    let mut by_motion = HashMap::with_capacity(placed.len());
    for (k, index, offset, block, _) in placed {
        let (line, instruction) = &instructions[k];
        let (start, l) = starts[line];
        let reference = reference(l).map_or(start..start, |r| start + r.start..start + r.end);
        let r = &registers[&k];
        let letter = &instruction.trim()[..1];
        let note = format!("line {line}: {letter} PR[{}] read as {} holds it; the register is the controller's, shared by every program on it, and is left as it is: where compensating moves the target, the motion goes to the program's new position P[{index}] instead", r.number, r.source);
        let foreign = Foreign {
            text: block,
            at: offset,
            computed: false,
        };
        by_motion.insert(
            k,
            Copy {
                index,
                foreign,
                insert,
                reference,
                note,
            },
        );
    }
    Ok(Copies {
        positions,
        axes,
        units,
        by_motion,
    })
}

/// The message of a refusal, without its line.
fn message(e: Error) -> String {
    match e {
        Error::Program { message, .. } => message,
        other => other.to_string(),
    }
}

/// How many lines `s` holds.
fn lines_in(s: &str) -> u64 {
    s.matches('\n').count() as u64
}

/// The bytes of `PR[..]` in the motion's line `l`.
fn reference(l: &str) -> Option<Range<usize>> {
    let body = l.find(':')? + 1;
    let open = body + l[body..].find("PR[")?;
    let close = open + l[open..].find(']')?;
    Some(open..close + 1)
}

/// The frame number `n` selects, as a position names it: the number, or `F` (the frame in force,
/// which the program does not select) for a Cartesian position, 0 for a joint one.
fn number(n: &Option<Number>, cartesian: bool) -> String {
    match (n, cartesian) {
        (Some(Number::Literal(_, m)), _) => m.to_string(),
        (_, true) => "F".into(),
        (_, false) => "0".into(),
    }
}

/// The `/POS` text of position `index` holding register `r` in the frames `s` in force, its
/// lines ended by `eol`.
fn block(index: u64, r: &Register, s: &Selected, eol: &str) -> String {
    let cartesian = matches!(r.entry.value, Ok(Some(Value::Cartesian(..))));
    let (uf, ut) = (number(&s.user, cartesian), number(&s.tool, cartesian));
    let mut lines = vec![format!("P[{index}]{{"), "   GP1:".to_string()];
    let values: Vec<String> = match &r.entry.value {
        Ok(Some(Value::Cartesian(p, config))) => {
            lines.push(format!("\tUF : {uf}, UT : {ut},\t\tCONFIG : '{config}',"));
            let names = ["X", "Y", "Z", "W", "P", "R"];
            (names.iter().zip(p).enumerate())
                .map(|(k, (n, v))| {
                    format!("{n} = {} {}", v_text(*v), if k < 3 { "mm" } else { "deg" })
                })
                .collect()
        }
        Ok(Some(Value::Joint(q))) => {
            lines.push(format!("\tUF : {uf}, UT : {ut},"));
            (q.iter().enumerate())
                .map(|(k, v)| format!("J{}= {v:.9} deg", k + 1))
                .collect()
        }
        _ => Vec::new(),
    };
    let extended =
        (r.entry.extended.iter().enumerate()).map(|(k, (v, u))| format!("E{}= {v:.9} {u}", k + 1));
    let values: Vec<String> = values.into_iter().chain(extended).collect();
    for (k, chunk) in values.chunks(3).enumerate() {
        let last = (k + 1) * 3 >= values.len();
        lines.push(format!(
            "\t{}{}",
            chunk.join(",\t"),
            if last { "" } else { "," }
        ));
    }
    lines.push("};".into());
    lines.iter().map(|l| format!("{l}{eol}")).collect()
}

/// The program's external axes and their units (`own`: whether its `/POS` holds positions,
/// then its axes and units) with those of its `copies`: the program's, which each copy must
/// give alike (a program without positions of its own takes the copies').
///
/// # Errors
/// Naming the first motion to a register: a program that moves motion group 2 (a register's
/// group 1 alone is read), a register whose extended axes or units differ from the program's.
pub(super) fn axes(
    instructions: &[(u64, String)],
    copies: &Copies,
    (own, axes, units): (bool, Vec<String>, Units),
) -> Result<(Vec<String>, Units)> {
    let Some(k) = copies.by_motion.keys().min().copied() else {
        return Ok((axes, units));
    };
    let line = instructions[k].0;
    let theirs = (copies.units.iter()).map(|u| u.map(|(unit, _)| (unit, line)));
    if axes.iter().any(|a| a.starts_with("GP2")) {
        return Err(at(line, "a motion to a position register in a program that moves motion group 2 (GP2): stiffid reads a register's group 1 alone; copy its value into a P[] position".into()));
    }
    if !own {
        return Ok((copies.axes.clone(), theirs.collect()));
    }
    let same_units =
        (units.iter().zip(theirs)).all(|(a, b)| a.zip(b).is_none_or(|(a, b)| a.0 == b.0));
    match axes == copies.axes && same_units {
        true => Ok((axes, units)),
        false => Err(at(line, format!("a motion to a position register whose extended axes [{}] are not the program's positions' [{}] (or in another unit): give the register the program's axes, or copy its value into a P[] position", copies.axes.join(", "), axes.join(", ")))),
    }
}
