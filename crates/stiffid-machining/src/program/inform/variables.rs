//! Motions to robot position variables (`MOVJ P016`, `MOVL P005 V=100.0`), read from the
//! controller's backup's `VAR.DAT` ([`super::var`]) and copied into the job: each motion's own
//! new position `C0nnnn` (numbered after the job's positions) at the end of `//POS`, after its
//! tool file and form lines (`///TOOL n` as the variable holds it, `///POSTYPE PULSE` and
//! `///PULSE`, or a Cartesian variable's frame, `///RECTAN` and `///RCONF`: [`super::varvalue`]),
//! its values the variable's. Compensated, the motion names the copy (`MOVJ P016`
//! becomes `MOVJ C00002`), the copy is written, `///NPOS` counts it
//! ([`super::written`]), and the variable, which every job on the controller shares, is left as
//! it is; a motion whose target does not move keeps the variable. The copy mechanism is the
//! language-neutral one of [`crate::program::points`] (an LS position register's `P[n]` too).
//!
//! Refused naming the motion's line: no `VAR.DAT` given; a variable the file does not hold
//! (beyond its last line), `"UNUSED"`, or one [`super::varvalue`] does not read; one the job or
//! a job it calls sets as it runs (`SET P016 ..`, `ADD`, `SETE`, `GETS`, `CNVRT`, .., [`sets`]);
//! one the job lists with other values than the file's; a variable beside base or station
//! positions.

use super::inst::{without_comment, Instructions};
use super::pos::{Kind, Position, Section};
use super::var::{self, Variables};
use super::varvalue;
use crate::program::points::Foreign;
use crate::program::{at, lines, Context, JointTarget};
use std::collections::HashMap;
use std::ops::Range;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// How deep calls are followed for what sets a variable.
const DEPTH: usize = 16;

/// One motion's copy: its text and where it goes, the copy's name in it, the bytes of the
/// variable's name at the motion.
pub(super) struct Copy {
    foreign: Foreign,
    name: Range<usize>,
    insert: usize,
    reference: Range<usize>,
}

impl Copy {
    /// `t`, read from the copy, as the position the job declares anew and the motion names.
    pub(super) fn attach(&self, t: JointTarget) -> JointTarget {
        t.declared_elsewhere(self.foreign.clone(), self.name.clone(), self.insert)
            .named_at(self.reference.clone())
    }
}

/// The copies of a job: per motion (its index among the motions) its copy, and a sentence per
/// copy naming the motion's line.
#[derive(Default)]
pub(super) struct Copies {
    pub by_motion: HashMap<usize, Copy>,
    pub notes: Vec<String>,
}

/// An instruction that sets a robot position variable as the job runs: the variable (`None`:
/// one chosen by an index), the job's file (`None`: the job read), the line and its text.
pub(super) struct Set {
    pub index: Option<u64>,
    pub file: Option<String>,
    pub line: u64,
    pub text: String,
}

/// The copies of the variables the motions of `inst` move to (module docs), each added to
/// `section`'s positions under its new number and the motion renumbered to it.
///
/// # Errors
/// Naming the motion's line (module docs); those of reading `VAR.DAT`.
pub(super) fn build(
    text: &str,
    inst: &mut Instructions,
    section: &mut Section,
    (context, sets): (&Context, &[Set]),
) -> Result<Copies> {
    let wanted: Vec<usize> = (inst.motions.iter().enumerate())
        .filter(|(_, m)| m.variable.is_some())
        .map(|(k, _)| k)
        .collect();
    let Some(&first) = wanted.first() else {
        return Ok(Copies::default());
    };
    let m = &inst.motions[first];
    let name = format!("{} P{:03}", m.word, m.variable.unwrap_or(0));
    let Some(vars) = var::read(context)? else {
        return Err(at(m.line, format!("{name}: a position variable holds its value on the controller, not in this job: give the controller's backup holding its VAR.DAT with the job (--backup), or teach the position in the job (C)")));
    };
    let robot = (section.positions.iter()).filter(|(k, _)| k.0 == Kind::Robot);
    let insert = (lines(text).find(|(_, _, l)| l.trim_start().starts_with("//INST")))
        .map_or(text.len(), |(_, s, _)| s);
    let eol = if text.contains("\r\n") { "\r\n" } else { "\n" };
    let starts: HashMap<u64, (usize, &str)> = lines(text).map(|(l, s, t)| (l, (s, t))).collect();
    let first_new = robot.map(|(k, _)| k.1 + 1).max().unwrap_or(0);
    let (mut out, mut offset) = (Copies::default(), 0);
    for (next, k) in (first_new..).zip(wanted) {
        let m = &mut inst.motions[k];
        let (line, word, index) = (m.line, m.word.clone(), m.variable.unwrap_or(0));
        if m.base.is_some() || m.station.is_some() {
            return Err(at(line, format!("{word} P{index:03}: a position variable beside base or station positions; stiffid copies a robot's variable alone into the job: teach the position in the job (C)")));
        }
        let (vline, value) = value(&vars, (section, sets), (line, &word, index), eol)?;
        let copy_name = format!("C{next:05}");
        let head = value.head.clone();
        let texts: Vec<&str> = value.values.iter().map(|(_, t)| t.as_str()).collect();
        let block = format!("{head}{copy_name}={}{eol}", texts.join(","));
        let mut from = offset + head.len() + copy_name.len() + 1;
        let mut read = Vec::with_capacity(6);
        for (v, t) in &value.values {
            read.push((*v, from..from + t.len()));
            from += t.len() + 1;
        }
        section.positions.insert(
            (Kind::Robot, next),
            Position {
                line,
                form: value.form,
                values: read,
                tool: Some((line, value.tool)),
                frame: value.frame.into(),
                user: value.user.map(|u| (line, u)),
                rconf: value.rconf.map(|r| (line, r)),
            },
        );
        m.robot = next;
        let (start, l) = starts.get(&line).copied().unwrap_or((0, ""));
        let (token, reference) = reference(l, &word, start);
        out.notes.push(format!("line {line}: {word} {token} read as {} line {vline} holds it; the variable is the controller's, shared by every job on it, and is left as it is: where compensating moves the target, the motion goes to the job's new position {copy_name} instead", vars.file));
        let name = head.len()..head.len() + copy_name.len();
        let foreign = Foreign {
            text: block,
            at: offset,
            computed: false,
        };
        offset += foreign.text.len();
        let copy = Copy {
            foreign,
            name,
            insert,
            reference,
        };
        out.by_motion.insert(k, copy);
    }
    Ok(out)
}

/// The variable's line in `vars` and its value as its copy declares it (line ends `eol`), for
/// the motion `word` to variable `index` on `line`, checked against what sets it (`sets`) and
/// the job's own listing of it (`section`).
fn value(
    vars: &Variables,
    (section, sets): (&Section, &[Set]),
    (line, word, index): (u64, &str, u64),
    eol: &str,
) -> Result<(u64, varvalue::Value)> {
    let refuse = |why: String| at(line, format!("{word} P{index:03}: {why}"));
    if let Some(s) = sets.iter().find(|s| s.index.is_none_or(|i| i == index)) {
        let file = s.file.as_ref().map_or(String::new(), |f| format!("{f} "));
        return Err(refuse(format!("the variable is set as the jobs run ({file}line {}: {}), so its value at the motion is not the one VAR.DAT holds; teach the position in the job (C)", s.line, short(&s.text))));
    }
    let file = vars.file;
    let Some((vline, v)) = vars.list.get(index as usize) else {
        let n = vars.list.len();
        return Err(refuse(format!("{file} holds {n} position variables (P000 to P{:03}): the variable is not in it (is the file cut off, or of another controller?)", n.saturating_sub(1))));
    };
    let listed = section.variables.get(&index);
    let value = varvalue::of(v, (file, *vline), listed, eol).map_err(refuse)?;
    Ok((*vline, value))
}

/// The variable's name as the motion `word`'s line `l` (starting at byte `start` of the job)
/// writes it, and its bytes in the job.
fn reference(l: &str, word: &str, start: usize) -> (String, Range<usize>) {
    let upper = l.to_ascii_uppercase();
    let after = upper.find(word).map_or(0, |w| w + word.len());
    let rest = &l[after..];
    let skip = rest.len() - rest.trim_start().len();
    let token = rest.split_whitespace().next().unwrap_or("");
    let from = start + after + skip;
    (token.to_string(), from..from + token.len())
}

/// What sets a robot position variable in the job `text` and every job of the backup it calls
/// (`CALL JOB:NAME`, followed [`DEPTH`] deep): an instruction other than a motion, `SFTON` or
/// `MFRAME` whose first operand is a robot position variable (`SET P016 ..`, `ADD P021 P019`,
/// `SETE P001 (3) D000`, `GETS PX000 ..`, `CNVRT PX001 ..`), or one chosen by an index
/// (`SET P[I000] ..`: any variable).
pub(super) fn sets(text: &str, context: &Context) -> Vec<Set> {
    let mut out = Vec::new();
    let mut chain = Vec::new();
    scan(text, None, context, &mut chain, &mut out);
    out
}

/// [`sets`] of the job `text` (its file `file`, `None`: the job read), through the jobs of
/// `chain`, into `out`.
fn scan(
    text: &str,
    file: Option<&str>,
    context: &Context,
    chain: &mut Vec<String>,
    out: &mut Vec<Set>,
) {
    let mut in_inst = false;
    for (line, _, l) in lines(text) {
        let t = l.trim();
        if let Some(section) = t.strip_prefix("//").filter(|s| !s.starts_with('/')) {
            in_inst = section.starts_with("INST");
            continue;
        }
        if !in_inst || t.starts_with(['/', '\'', '*']) || t.is_empty() {
            continue;
        }
        let t = without_comment(t);
        let words: Vec<String> = t.split_whitespace().map(str::to_ascii_uppercase).collect();
        let (Some(first), second) = (words.first(), words.get(1)) else {
            continue;
        };
        if first == "CALL" {
            let job = second.and_then(|w| w.strip_prefix("JOB:"));
            let held = job.and_then(|j| context.backup_file(&format!("{j}.JBI")));
            let fresh = |job: &str| chain.len() < DEPTH && !chain.iter().any(|c| c == job);
            if let (Some(job), Some((name, called))) = (job, held)
                && fresh(job)
            {
                chain.push(job.to_string());
                scan(called, Some(name), context, chain, out);
                chain.pop();
            }
            continue;
        }
        let reads = first.contains("MOV") || ["SFTON", "MFRAME", "COMM"].contains(&first.as_str());
        let Some(operand) = second.filter(|_| !reads) else {
            continue;
        };
        let name = operand.strip_prefix("PX").or(operand.strip_prefix('P'));
        let Some(name) = name else { continue };
        let index = name.split('(').next().unwrap_or("");
        let index = match index.parse::<u64>() {
            Ok(i) => Some(i),
            Err(_) if index.starts_with('[') => None,
            Err(_) => continue,
        };
        out.push(Set {
            index,
            file: file.map(str::to_string),
            line,
            text: t.to_string(),
        });
    }
}
