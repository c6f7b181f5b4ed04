//! Yaskawa INFORM (`.jbi` job files of the DX, YRC and FS controllers): `MOVJ C00000 VJ=50.00`
//! and `MOVL C00001 V=100.0 PL=0` (the tags `VJ=`, `V=`, `VR=`, `VE=`, `PL=`, `CR=`, `ACC=`,
//! `DEC=` and `NWAIT`) to the job's teaching positions in `//POS`: the robot's `C00000=p1,..,p6`
//! and, in the same motion, a base axis group `BC00000=..` (a track: `MOVJ C00000 BC00000 ..`)
//! and a station axis group `EC00000=..` (a positioner). A line that starts with `'` is a
//! comment.
//!
//! ## Forms of a position
//! Each block of positions follows its `///POSTYPE` and form line:
//! - `///POSTYPE PULSE` then `///PULSE`: whole encoder pulses. How many make a degree (or a mm)
//!   is the controller's, not the job's: the job states it in a comment of `//INST`, which the
//!   controller skips, `'stiffid: pulses_per_deg = S L U R B T` (six numbers, the robot's axes)
//!   and, with base or station axes in pulses, `'stiffid: external_pulses = ..` (one number per
//!   axis, base axes first then station axes; per mm for a linear axis, per deg for a rotary
//!   one). A value is the pulses divided by its number, and a compensated value is written as
//!   the nearest whole pulse (the round trip is exact to half a pulse).
//! - `///POSTYPE ANGLE` then `///ANGLE` (base and station axes): deg for a rotary axis, mm for a
//!   linear one, written with [`super::DECIMALS`] decimals.
//!
//! ## Refused, naming the line
//! - a motion to a Cartesian position (`///RECTAN` under `///POSTYPE BASE`, `ROBOT`, `USER`,
//!   `TOOL`, `MTOOL`): its axis angles depend on the controller's configuration (`///RCONF`) and
//!   kinematics, as for the other languages; a base or station position in Cartesian form too;
//! - a motion to a position variable (`P000`, `LP000`, `BP`, `EX`): it holds its value on the
//!   controller, not in the job;
//! - `MOVC` (circular), `MOVS` (spline), `IMOV` (incremental from where the robot is), `SMOVL`
//!   and `SMOVC` (a motion on a conveyor), a motion with `UNTIL` (a search) or another group's
//!   own motion (`+MOVJ`..), and any tag outside the list above;
//! - `JUMP`, `CALL`, `IF`, `IFTHEN`, `FOR`, `WHILE`, `SWITCH` and labels in a job with motions
//!   (the order the controller runs would not be the file's);
//! - a position named in a motion that `//POS` does not hold, one defined twice, a count that
//!   differs from `///NPOS`, pulses that are not whole numbers, a pulse position without the
//!   `stiffid:` comment that converts it, and a group's positions in two forms.
//!
//! ## Written
//! A G-code path is written as a new job in pulses ([`generate`]), with the `'stiffid:` comments
//! of the setup's `[controller] pulses_per_deg` and `external_pulses`, so it reads back here.

pub mod generate;
pub mod speed;

use super::cartesian::Flags;
use super::controller::{lines_starting, BoundComment, Controller, Generator};
use super::{at, number_at, six, Read};
use nalgebra::{UnitQuaternion, Vector3};
use std::collections::HashMap;
use std::ops::Range;
use stiffid_core::common::limits::short;
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::Result;

/// How a block of positions is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Form {
    Pulse,
    Angle,
    Rectan,
}

/// The three kinds of teaching positions a motion names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Kind {
    Robot,
    Base,
    Station,
}

impl Kind {
    fn prefix(self) -> &'static str {
        match self {
            Kind::Robot => "C",
            Kind::Base => "BC",
            Kind::Station => "EC",
        }
    }
}

/// A teaching position: its line, form and values with their spans.
struct Position {
    line: u64,
    form: Form,
    values: Vec<(f64, Range<usize>)>,
}

/// Every joint target of `text`, in the order of its motions (module docs), the program's
/// external axes (`BC1`.., then `EC1`..) and the pulses per unit of each value.
pub(crate) fn targets(text: &str) -> Result<Read> {
    let (positions, npos) = positions(text)?;
    let mut counts: HashMap<Kind, usize> = HashMap::new();
    for (kind, _) in positions.keys() {
        *counts.entry(*kind).or_default() += 1;
    }
    if let Some((line, declared)) = npos {
        for (k, kind) in [Kind::Robot, Kind::Base, Kind::Station].iter().enumerate() {
            let have = counts.get(kind).copied().unwrap_or(0);
            if declared.get(k).is_some_and(|n| *n != have) {
                return Err(at(line, format!("///NPOS declares {} {} positions, //POS holds {have}: the controller refuses the job", declared[k], kind.prefix())));
            }
        }
    }
    let width = |kind: Kind| {
        positions
            .iter()
            .filter(|(k, _)| k.0 == kind)
            .map(|(_, p)| p.values.len())
            .max()
            .unwrap_or(0)
    };
    let (nb, ne) = (width(Kind::Base), width(Kind::Station));
    let form = |kind: Kind| -> Result<Option<Form>> {
        let mut of: Vec<&Position> = positions
            .iter()
            .filter(|(k, _)| k.0 == kind)
            .map(|(_, p)| p)
            .collect();
        of.sort_by_key(|p| p.line);
        match of.iter().find(|p| p.form != of[0].form) {
            Some(p) => Err(at(
                p.line,
                format!(
                    "{} positions in two forms (lines {} and {}); stiffid reads one form per group",
                    kind.prefix(),
                    of[0].line,
                    p.line
                ),
            )),
            None => Ok(of.first().map(|p| p.form)),
        }
    };
    let forms = [form(Kind::Robot)?, form(Kind::Base)?, form(Kind::Station)?];
    let (directives, motions) = instructions(text)?;
    let mut pulses: Vec<Option<f64>> = vec![None; 6 + nb + ne];
    if forms[0] == Some(Form::Pulse) || forms[1..].contains(&Some(Form::Pulse)) {
        let first = motions.first().map_or(1, |m| m.line);
        if forms[0] == Some(Form::Pulse) {
            let (_, r) = directives.robot.as_ref().ok_or_else(|| at(first, "the robot's positions are in pulses and the job does not say how many make a degree: add the comment line 'stiffid: pulses_per_deg = S L U R B T to //INST (the controller's pulses per degree of each axis)".into()))?;
            for (p, r) in pulses.iter_mut().zip(r) {
                *p = Some(*r);
            }
        }
        let external_pulse = [(forms[1], 0..nb), (forms[2], nb..nb + ne)]
            .into_iter()
            .filter(|(f, _)| *f == Some(Form::Pulse))
            .flat_map(|(_, r)| r);
        for k in external_pulse {
            let (line, r) = directives.external.as_ref().ok_or_else(|| at(first, format!("the base or station positions are in pulses and the job does not say how many make a mm or a degree: add the comment line 'stiffid: external_pulses = .. to //INST ({} numbers: base axes, then station axes)", nb + ne)))?;
            let r = r.get(k).ok_or_else(|| {
                at(
                    *line,
                    format!(
                        "'stiffid: external_pulses gives {} numbers for {} base and station axes",
                        r.len(),
                        nb + ne
                    ),
                )
            })?;
            pulses[6 + k] = Some(*r);
        }
    }
    let out = (motions.iter())
        .map(|m| target(m, &positions, &pulses, (nb, ne)))
        .collect::<Result<Vec<_>>>()?;
    let axes = (1..=nb).map(|k| format!("BC{k}"));
    let axes = axes.chain((1..=ne).map(|k| format!("EC{k}"))).collect();
    Ok(Read {
        targets: out,
        axes,
        pulses,
        units: Vec::new(),
    })
}

/// The target of motion `m`: its robot position in pulses converted by `pulses` (per value, the
/// six axes then the `nb` base and `ne` station axes), its base and station positions.
fn target(
    m: &Motion,
    positions: &HashMap<(Kind, u64), Position>,
    pulses: &[Option<f64>],
    (nb, ne): (usize, usize),
) -> Result<super::JointTarget> {
    let get = |kind: Kind, index: u64| {
        positions.get(&(kind, index)).ok_or_else(|| {
            at(
                m.line,
                format!(
                    "{} {}{index:05}: no such position in //POS",
                    m.word,
                    kind.prefix()
                ),
            )
        })
    };
    let robot = get(Kind::Robot, m.robot)?;
    if robot.form == Form::Rectan {
        return Err(at(m.line, format!("{} C{:05}: a Cartesian position (line {}); stiffid compensates positions in pulses: teach or post the job in pulses (///POSTYPE PULSE)", m.word, m.robot, robot.line)));
    }
    if robot.values.len() != 6 {
        return Err(at(
            robot.line,
            format!(
                "C{:05}: expected 6 axis values, found {}",
                m.robot,
                robot.values.len()
            ),
        ));
    }
    let mut found: super::Found = Default::default();
    for (k, (v, span)) in robot.values.iter().enumerate() {
        found[k] = Some((v / pulses[k].unwrap_or(1.0), span.clone()));
    }
    let mut external: Vec<Option<(f64, Range<usize>)>> = vec![None; nb + ne];
    for (kind, index, offset) in [(Kind::Base, m.base, 0), (Kind::Station, m.station, nb)] {
        let Some(index) = index else { continue };
        let p = get(kind, index)?;
        if p.form == Form::Rectan {
            return Err(at(m.line, format!("{} {}{index:05}: a position in Cartesian form (line {}); stiffid reads base and station axes in pulses or ANGLE", m.word, kind.prefix(), p.line)));
        }
        for (k, (v, span)) in p.values.iter().enumerate() {
            let v = v / pulses[6 + offset + k].unwrap_or(1.0);
            if !v.is_finite() {
                return Err(at(
                    p.line,
                    format!(
                        "{}{index:05}: axis {}: {v} is not a finite value",
                        kind.prefix(),
                        k + 1
                    ),
                ));
            }
            external[offset + k] = Some((v, span.clone()));
        }
    }
    let mut target = six(m.line, found, "C")?.with_external(external);
    target.origin = robot.line;
    target.speed = m.speed.clone();
    Ok(target)
}

/// The `//POS` section's teaching positions by kind and number, and `///NPOS`'s line and counts.
#[allow(clippy::type_complexity)]
fn positions(text: &str) -> Result<(HashMap<(Kind, u64), Position>, Option<(u64, Vec<usize>)>)> {
    let mut out = HashMap::new();
    let mut npos = None;
    let mut in_pos = false;
    let mut form = None;
    for (line, start, l) in super::lines(text) {
        let t = l.trim();
        if let Some(section) = t.strip_prefix("//").filter(|s| !s.starts_with('/')) {
            in_pos = section.starts_with("POS");
            continue;
        }
        if !in_pos {
            continue;
        }
        if let Some(pseudo) = t.strip_prefix("///") {
            let word = pseudo.split_whitespace().next().unwrap_or("");
            match word {
                "PULSE" => form = Some(Form::Pulse),
                "ANGLE" => form = Some(Form::Angle),
                "RECTAN" => form = Some(Form::Rectan),
                "NPOS" => {
                    let counts = pseudo[4..]
                        .split(',')
                        .map(|n| n.trim().parse::<usize>())
                        .collect::<std::result::Result<Vec<_>, _>>()
                        .map_err(|_| {
                            at(line, "///NPOS: expected six counts C,BC,EC,P,BP,EX".into())
                        })?;
                    npos = Some((line, counts));
                }
                _ => {}
            }
            continue;
        }
        let Some((name, _)) = t.split_once('=') else {
            continue;
        };
        let name = name.trim();
        let (kind, digits) = match name {
            n if n.starts_with("BC") => (Kind::Base, &n[2..]),
            n if n.starts_with("EC") => (Kind::Station, &n[2..]),
            n if n.starts_with('C') => (Kind::Robot, &n[1..]),
            // Position variables' initial values: held on the controller.
            _ => continue,
        };
        let index: u64 = digits
            .parse()
            .map_err(|_| at(line, format!("{}: expected a position number", short(name))))?;
        let form = form.ok_or_else(|| {
            at(
                line,
                format!("{name}: a position before its form (///PULSE, ///ANGLE or ///RECTAN)"),
            )
        })?;
        let mut values = Vec::new();
        let mut from = l.find('=').map_or(l.len(), |e| e + 1);
        loop {
            let (v, span) = number_at(l, from)
                .ok_or_else(|| at(line, format!("{name}: expected numbers separated by ','")))?;
            if form == Form::Pulse && l[span.clone()].contains(['.', 'e', 'E']) {
                return Err(at(
                    line,
                    format!(
                        "{name}: {} is not a whole number of pulses",
                        &l[span.clone()]
                    ),
                ));
            }
            values.push((v, start + span.start..start + span.end));
            let rest = l[span.end..].trim_start();
            match rest.strip_prefix(',') {
                Some(_) => from = l.len() - rest.len() + 1,
                None if rest.is_empty() => break,
                None => {
                    return Err(at(
                        line,
                        format!("{name}: '{}' after its values", short(rest)),
                    ))
                }
            }
        }
        if out
            .insert((kind, index), Position { line, form, values })
            .is_some()
        {
            return Err(at(line, format!("{name} defined twice in //POS")));
        }
    }
    Ok((out, npos))
}

/// A motion to a teaching position: its line, instruction and the positions it names.
struct Motion {
    line: u64,
    word: String,
    robot: u64,
    base: Option<u64>,
    station: Option<u64>,
    speed: super::speed::Speed,
}

/// The `stiffid:` comments of `//INST`: the robot's and the external axes' pulses per unit, with
/// their lines.
#[derive(Default)]
struct Directives {
    robot: Option<(u64, Vec<f64>)>,
    external: Option<(u64, Vec<f64>)>,
}

/// The `//INST` section's directives and motions (module docs).
fn instructions(text: &str) -> Result<(Directives, Vec<Motion>)> {
    let mut directives = Directives::default();
    let mut motions = Vec::new();
    let mut in_inst = false;
    let mut control: Option<(u64, String)> = None;
    for (line, _, l) in super::lines(text) {
        let t = l.trim();
        if let Some(section) = t.strip_prefix("//").filter(|s| !s.starts_with('/')) {
            in_inst = section.starts_with("INST");
            continue;
        }
        if !in_inst || t.starts_with("///") || t.is_empty() {
            continue;
        }
        if let Some(comment) = t.strip_prefix('\'') {
            directive(line, comment, &mut directives)?;
            continue;
        }
        let words: Vec<&str> = t.split_whitespace().collect();
        let first = words[0].to_ascii_uppercase();
        if (first.starts_with('*')
            || matches!(
                first.as_str(),
                "JUMP"
                    | "CALL"
                    | "IF"
                    | "IFTHEN"
                    | "IFTHENEXP"
                    | "FOR"
                    | "WHILE"
                    | "WHILEEXP"
                    | "SWITCH"
            ))
            && control.is_none()
        {
            control = Some((line, first.clone()));
        }
        match first.as_str() {
            "MOVJ" | "MOVL" => motions.push(motion(line, &first, &words[1..])?),
            "MOVC" => return Err(at(line, "MOVC: a circular motion; the arc between compensated points is not the compensated arc: split it into MOVL motions".into())),
            "MOVS" => return Err(at(line, "MOVS: a spline; its path bends through all its points, not along the compensated ones: write it as MOVL or MOVJ motions".into())),
            "IMOV" => return Err(at(line, "IMOV: an increment from where the robot is, which the job does not say: write the absolute position".into())),
            w if w.starts_with("SMOV") || w.starts_with("+MOV") || w.starts_with("SYMOV") => {
                return Err(at(line, format!("{}: a motion stiffid does not follow (on a conveyor, or of another group alone); write the path as MOVJ and MOVL to C positions", short(words[0]))));
            }
            _ => {}
        }
    }
    if let (Some((line, word)), false) = (control, motions.is_empty()) {
        return Err(at(line, format!("{}: a jump, call, label, loop or branch in a job with motions; the order the controller runs them would not be the file's: write the path as straight-line motions", short(&word))));
    }
    Ok((directives, motions))
}

/// The positions and tags of a `MOVJ`/`MOVL` line after its word.
fn motion(line: u64, word: &str, words: &[&str]) -> Result<Motion> {
    let index = |w: &str, prefix: &str| -> Option<u64> {
        w.strip_prefix(prefix)
            .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|d| d.parse().ok())
    };
    let target = words.first().copied().unwrap_or("");
    let robot = index(target, "C").ok_or_else(|| {
        let why = match target.chars().next() {
            Some('P' | 'L') => "a position variable holds its value on the controller, not in this job; teach the position in the job (C)",
            _ => "expected a teaching position C00000",
        };
        at(line, format!("{word} {}: {why}", short(target)))
    })?;
    let mut m = Motion {
        line,
        word: word.to_string(),
        robot,
        base: None,
        station: None,
        speed: speed::speed(line, word, &words[1..])?,
    };
    for w in &words[1..] {
        let upper = w.to_ascii_uppercase();
        if let Some(i) = index(&upper, "BC") {
            m.base = Some(i);
        } else if let Some(i) = index(&upper, "EC") {
            m.station = Some(i);
        } else if upper.starts_with("BP") || upper.starts_with("EX") {
            return Err(at(line, format!("{word} .. {}: a position variable holds its value on the controller, not in this job; teach the position in the job (BC, EC)", short(w))));
        } else if upper == "UNTIL" {
            return Err(at(line, format!("{word} .. UNTIL: a search stops where a signal comes, which the job does not say; not compensated")));
        } else if !(["VJ=", "V=", "VR=", "VE=", "PL=", "CR=", "ACC=", "DEC="]
            .iter()
            .any(|t| upper.starts_with(t))
            || upper == "NWAIT")
        {
            return Err(at(line, format!("{word} .. {}: a tag stiffid does not follow (the path or its end would not be the job's); remove it or compensate the job without it", short(w))));
        }
    }
    Ok(m)
}

/// Reads a `'stiffid: key = numbers` comment into `directives` (other comments are kept as they
/// are and mean nothing here).
fn directive(line: u64, comment: &str, directives: &mut Directives) -> Result<()> {
    let Some(rest) = comment.trim().strip_prefix("stiffid:") else {
        return Ok(());
    };
    let (key, value) = rest
        .split_once('=')
        .ok_or_else(|| at(line, "'stiffid: expected 'key = numbers'".into()))?;
    let numbers: Vec<f64> = value
        .split([' ', ',', '\t'])
        .filter(|w| !w.is_empty())
        .map(str::parse)
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| at(line, format!("'stiffid: {}: expected numbers", key.trim())))?;
    if numbers
        .iter()
        .any(|n: &f64| !(n.is_finite() && (1e-6..=1e9).contains(&n.abs())))
    {
        return Err(at(
            line,
            format!(
                "'stiffid: {}: expected pulses per unit, from 1e-6 to 1e9 in size",
                key.trim()
            ),
        ));
    }
    match key.trim() {
        "pulses_per_deg" if numbers.len() == 6 => directives.robot = Some((line, numbers)),
        "pulses_per_deg" => {
            return Err(at(
                line,
                format!(
                    "'stiffid: pulses_per_deg: expected 6 numbers (S L U R B T), found {}",
                    numbers.len()
                ),
            ))
        }
        "external_pulses" => directives.external = Some((line, numbers)),
        other => {
            return Err(at(
                line,
                format!(
                    "'stiffid: unknown '{}' (expected pulses_per_deg or external_pulses)",
                    short(other)
                ),
            ))
        }
    }
    Ok(())
}

/// Yaskawa INFORM (module docs).
#[derive(Debug, Clone, Copy)]
pub struct Inform;

impl Controller for Inform {
    fn key(&self) -> &'static str {
        "inform"
    }
    fn title(&self) -> &'static str {
        "Yaskawa INFORM"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["jbi"]
    }
    fn refuses_output(&self, _extension: &str) -> Option<&'static str> {
        None
    }
    fn read(&self, text: &str) -> Result<Read> {
        targets(text)
    }
    fn motions(&self) -> &'static str {
        "MOVJ or MOVL to a C-variable of //POS in pulses"
    }
    fn joint_forms(&self) -> &'static str {
        "pulse positions"
    }
    /// None: its rectangular positions are not read.
    fn part_forms(&self) -> Option<&'static str> {
        None
    }
    fn external_axis(&self, k: usize) -> String {
        format!("external axis {}", k + 1)
    }
    fn unused_axis(&self) -> &'static str {
        ""
    }
    fn zero_is_no_axis(&self) -> bool {
        false
    }
    /// No Cartesian target is read from a job: KUKA's A, B, C order, never used.
    fn rotation(&self, n: &[f64]) -> UnitQuaternion<f64> {
        UnitQuaternion::from_euler_angles(n[5].to_radians(), n[4].to_radians(), n[3].to_radians())
    }
    /// No Cartesian target is written to a job: KUKA's order, never used.
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        let [a, b, c] = super::generate::zyx_deg(r);
        vec![p.x, p.y, p.z, a, b, c]
    }
    /// No Cartesian target is read from a job: KUKA's data, never used.
    fn flags(&self, arm: &Configuration) -> Flags {
        let (s, t) = arm.kuka();
        Flags::Kuka(s, t)
    }
    fn flags_name(&self) -> &'static str {
        "S and T"
    }
    fn declares_name(&self, line: &str) -> Option<usize> {
        line.strip_prefix("//NAME").map(|r| line.len() - r.len())
    }
    fn program_name(&self, stem: &str) -> Option<String> {
        Some(stem.to_ascii_uppercase())
    }
    fn max_name_length(&self) -> usize {
        32
    }
    fn default_name_length(&self) -> usize {
        32
    }
    fn reserved_words(&self) -> &'static [&'static str] {
        &[]
    }
    fn bound_comment(&self) -> BoundComment {
        BoundComment::LineBefore { marker: '\'' }
    }
    fn motion_lines(&self, text: &str) -> Vec<u64> {
        lines_starting(text, &["MOVJ ", "MOVL "])
    }
    /// Jobs in pulses ([`generate`]).
    fn generator(&self) -> Option<&'static dyn Generator> {
        Some(&Inform)
    }
}
