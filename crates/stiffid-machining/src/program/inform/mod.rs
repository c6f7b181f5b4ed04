//! Yaskawa INFORM (`.jbi` job files of the DX, YRC and FS controllers), as the controller
//! stores a job: `MOVJ C00000 VJ=50.00`, `MOVL C00001 V=100.0 PL=0` and `MOVC C00002 V=20.0`
//! (the tags `VJ=`, `V=`, `VR=`, `VE=`, `PL=`, `CR=`, `ACC=`, `DEC=`, each a number or a B, I, D
//! or R variable, `NWAIT` and `TOOL#(n)`) to the job's teaching positions in `//POS`: the
//! robot's `C00000=p1,..,p6` and, in the same motion, a base axis group `BC00000=..` (a track:
//! `MOVJ C00000 BC00000 ..`) and a station axis group `EC00000=..` (a positioner). A line that
//! starts with `'` is a comment. The rules follow Yaskawa's INFORM language manuals (YRC1000
//! and DX200 "INFORM Explanations", the instructions and tags by name) and the job file format
//! the controllers save and load (`/JOB`, `//NAME`, `//POS`, `///NPOS`, `///TOOL`,
//! `///POSTYPE`, `//INST`, `END`).
//!
//! ## Forms of a position
//! Each block of positions follows its `///POSTYPE` and form line:
//! - `///POSTYPE PULSE` then `///PULSE`, or no form line at all (the form a controller stores a
//!   job in by default): whole encoder pulses. How many make a degree (or a mm) is the
//!   controller's (its axis parameters), not the job's: the setup's `[controller]
//!   pulses_per_deg = [S, L, U, R, B, T]` and, for base or station axes in pulses,
//!   `external_pulses` (base axes first, then station axes; per mm of a linear axis, per degree
//!   of a rotary one) ([`Context`]). A job may state them too, in comments of `//INST` the
//!   controller skips, `'stiffid: pulses_per_deg = S L U R B T` and `'stiffid: external_pulses
//!   = ..`: a comment that contradicts the setup, or one stated twice with other values, is
//!   refused naming both. A value is the pulses divided by its number, and a compensated value
//!   is written as the nearest whole pulse (the round trip is exact to half a pulse).
//! - `///POSTYPE ANGLE` then `///ANGLE` (base and station axes): deg for a rotary axis, mm for a
//!   linear one, written with 9 decimals.
//! - `///POSTYPE BASE`, `ROBOT` or `USER` then `///RECTAN` (robot positions): Cartesian targets
//!   (`rectan`) in base coordinates, robot coordinates (the same without a base axis) or the
//!   user frame of `///USER n` (the backup's `UFRAME.CND` or the setup's `[controller] bases`),
//!   of the tool file's point, in the manipulator type of `///RCONF` (`rconf`); written back
//!   as the pose the controller must be told, mm with 3 decimals and deg with 4, the
//!   `///RCONF` line as read.
//!
//! ## Motions
//! `MOVJ` (joint), `MOVL` (linear) and `MOVC` (circular: the controller moves on the circle
//! through each three consecutive `MOVC` points) are targets in the job's order; a compensated
//! `MOVC` point is written back as a `MOVC` point, so the controller draws its circle through
//! the compensated points (each point compensated; between them the circle of the compensated
//! points, not the compensation of the arc); a `MOVC` point between two others is a circle's
//! via point, fed along the circle's tangent.
//!
//! ## The tool file
//! A position's tool file is the `///TOOL n` before it in `//POS`, or a motion's `TOOL#(n)`
//! tag. A tool file the setup's `[controller] tools` gives is checked against the setup's tool
//! (`[tool]` after `[robot_flange]`) as a stated tool is, refused when it differs; one it does
//! not give is taken as the setup's tool only in a job that never changes its tool file,
//! refused naming the line where it changes.
//!
//! ## Accepted around the motions
//! What cannot move the robot or change a frame: input and output (`DOUT`, `DIN`, `WAIT`,
//! `PULSE`, `AOUT`), `TIMER`, arithmetic on B, I, D, R and S variables (`SET`, `ADD`, ..),
//! arc welding (`ARCON`, `ARCOF`, `ARCSET`), weaving switched on and off with no motion between
//! (`WVON`, `WVOF`), `SPEED`, `MSG`, user alarms and dialogs (`SETUALM`, `DIALOG`), `TSYNC`,
//! labels (`*LABEL`), comments (`'..`), an instruction's comment
//! (`MOVJ C00000 VJ=65.00  //FROM LEFT`: the text after `//`) and lines commented out on the
//! pendant (`COMM CALL JOB:..`, `COMM MOVL C00003 ..`: the controller skips them, and so does
//! stiffid; a position only such a line names is written back as found).
//!
//! ## Refused, naming the line
//! - a Cartesian position in tool coordinates (`///POSTYPE TOOL`, `MTOOL`), in robot
//!   coordinates on a base axis, in a user frame or with a tool file neither the backup nor the
//!   setup gives; a base or station position in Cartesian form;
//! - a motion to a position variable (`P000`) but one the backup's `VAR.DAT` gives in pulses or
//!   in Cartesian form, which is copied into the job (`variables`), a local one (`LP000`), base and station
//!   variables (`BP`, `EX`): they hold their values on the controller, not in the job;
//! - `MOVS` (spline), `IMOV` (incremental from where the robot is), `SMOVL` and `SMOVC`
//!   without the station's position (with it, read as `MOVL` and `MOVC` with the station's
//!   values: the robot's target where the part stands), `SYMOV` (a motion on a conveyor), a
//!   motion with `UNTIL` (a search) or with another group's own motion
//!   (`+MOVL`; a station's `+MOVJ EC00000 VJ=..` is read as the target's station values), a
//!   shift but a constant parallel one of Cartesian positions (`shift`), any tag outside the
//!   list above, and any instruction stiffid does not know;
//! - `WVON` with a motion after it before `WVOF`: weaving moves the tool across the path;
//! - a `CALL` or `MACRO` in a job with motions (the motions of the job it calls would not be the
//!   file's), but a call of a job of the backup, passed over when it moves nothing and read where
//!   it is called (compensated in its own file) when it moves; a `JUMP` to a label the job
//!   does not hold, to another job or to a variable's label; weaving in a job with jumps
//!   (`calls`: labels, jumps, branches and loops are followed);
//! - a job of another robot than the controller's first (`RB2` in a `///GROUP` line), a job
//!   of a station or base axes alone (`///GROUP1 ST1`);
//! - a job that does not end with `END` (cut off), a control character (a NUL) anywhere;
//! - a position named in a motion that `//POS` does not hold, one defined twice, a count that
//!   differs from `///NPOS`, pulses that are not whole numbers, pulses whose conversion neither
//!   the setup nor the job gives, and a base or station group's positions in two forms.
//!
//! ## Written
//! A G-code path is written as a new job in pulses ([`generate`]) with the setup's pulses.

mod backupfile;
mod called;
mod calls;
pub mod generate;
mod inst;
mod pos;
mod process;
mod pulses;
mod rconf;
mod rectan;
mod shift;
pub(crate) mod speed;
mod tool;
mod toolcnd;
mod uframe;
mod var;
mod variables;
mod varvalue;
mod written;

use super::controller::{BoundComment, Controller, Generator};
use super::descriptor::{AxisNames, Descriptor, FileName, NameRules};
use super::{at, six, Context, Read};
use nalgebra::{UnitQuaternion, Vector3};
use pos::{Form, Kind, Position};
use std::collections::HashMap;
use std::ops::Range;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// Every joint target of `text`, in the order of its motions (module docs), the program's
/// external axes (`BC1`.., then `EC1`..) and the pulses per unit of each value, with what the
/// setup gives in `context` (its pulses and tools).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line (module docs).
pub(crate) fn targets(text: &str, context: &Context) -> Result<Read> {
    let sets = variables::sets(text, context);
    read_job(text, (context, &sets), &mut Vec::new())
}

/// [`targets`] of the job `text`, called through the jobs of `chain` (their names), with what
/// sets position variables in the job first read and the jobs it calls (`sets`).
fn read_job(
    text: &str,
    (context, sets): (&Context, &[variables::Set]),
    chain: &mut Vec<String>,
) -> Result<Read> {
    control_characters(text)?;
    let mut section = pos::section(text)?;
    check_counts(&section)?;
    let mut inst = inst::instructions(text)?;
    robots(&inst.robots, context)?;
    let copies = variables::build(text, &mut inst, &mut section, (context, sets))?;
    let positions = &section.positions;
    let width = |kind: Kind| {
        (positions.iter().filter(|(k, _)| k.0 == kind))
            .map(|(_, p)| p.values.len())
            .max()
            .unwrap_or(0)
    };
    let (nb, ne) = (width(Kind::Base), width(Kind::Station));
    let forms = [
        form(positions, Kind::Robot)?,
        form(positions, Kind::Base)?,
        form(positions, Kind::Station)?,
    ];
    let moving = calls::check(&inst, context)?;
    let first = inst.motions.first().map_or(1, |m| m.line);
    let mut pulses: Vec<Option<f64>> = vec![None; 6 + nb + ne];
    let used = |kind: Kind| inst.motions.iter().any(|m| m.uses(kind));
    let pulsed = |m: &inst::Motion| {
        (positions.get(&(Kind::Robot, m.robot))).is_some_and(|p| p.form == Form::Pulse)
    };
    if forms[0].is_some() && inst.motions.iter().any(pulsed) {
        let per = pulses::robot(&inst.directives, context, first)?;
        for (p, r) in pulses.iter_mut().zip(per) {
            *p = Some(r);
        }
    }
    let external_pulse = [
        (forms[1], Kind::Base, 0..nb),
        (forms[2], Kind::Station, nb..nb + ne),
    ]
    .into_iter()
    .filter(|(f, kind, _)| *f == Some(Form::Pulse) && used(*kind))
    .flat_map(|(_, _, r)| r);
    for k in external_pulse {
        let per = pulses::external(&inst.directives, context, (k, nb + ne), first)?;
        pulses[6 + k] = Some(per);
    }
    tool::check(&inst.motions, positions, context)?;
    let held = rectan::Held::of(context)?;
    let mut out = (inst.motions.iter())
        .map(|m| target(m, positions, (&pulses, &held), (nb, ne)))
        .collect::<Result<Vec<_>>>()?;
    for (k, copy) in &copies.by_motion {
        out[*k] = copy.attach(out[*k].clone());
    }
    shift::apply(&inst, positions, &mut out, (context, sets))?;
    circles(&inst.motions, &mut out);
    let axes = (1..=nb).map(|k| format!("BC{k}"));
    let axes = axes.chain((1..=ne).map(|k| format!("EC{k}"))).collect();
    let read = Read {
        targets: out,
        axes,
        pulses,
        units: Vec::new(),
        left: Vec::new(),
        called: Vec::new(),
        notes: copies.notes,
    };
    called::read(read, (text, &moving), (context, sets), chain)
}

/// Marks the via points of the job's circles: the controller moves on the circle through each
/// three consecutive `MOVC` points (INFORM manual, `MOVC`), so each `MOVC` target between two
/// others is a circle's via point, fed along its tangent ([`crate::program::JointTarget`]'s
/// `via`, as KRL's `CIRC`, RAPID's `MoveC` and LS's `C`).
fn circles(motions: &[inst::Motion], targets: &mut [super::JointTarget]) {
    let circular = |k: usize| motions.get(k).is_some_and(inst::Motion::circular);
    for (k, t) in targets.iter_mut().enumerate().skip(1) {
        t.via = circular(k - 1) && circular(k) && circular(k + 1);
    }
}

/// Refuses a control character (a NUL, ..) anywhere in the job, naming its line: no
/// controller writes one, and a job that holds one is damaged.
fn control_characters(text: &str) -> Result<()> {
    for (line, _, l) in super::lines(text) {
        if let Some(c) = l.chars().find(|c| c.is_control() && *c != '\t') {
            return Err(at(line, format!("a control character (U+{:04X}) in the job: a damaged file; the controller writes none", c as u32)));
        }
    }
    Ok(())
}

/// Refuses a job of another robot than the setup's, the controller's `RB1` or the one
/// `[controller] robot_number` names (`///GROUP1 RB2`), and a job of two robots, naming the line.
fn robots(robots: &[inst::Robot], context: &Context) -> Result<()> {
    let number = context.robot_number.unwrap_or(1);
    let own = format!("RB{number}");
    match robots.iter().find(|r| r.name != own) {
        Some(r) => Err(at(r.line, format!("{}: a job of robot {}; stiffid compensates the setup's robot, the controller's {own} ([controller] robot_number = {number}{}): compensate a job of that robot, or give the number of the robot the setup is", short(&r.text), short(&r.name), if context.robot_number.is_none() { ", unsaid: the first" } else { "" }))),
        None => Ok(()),
    }
}

/// Refuses counts of positions other than `///NPOS` declares.
fn check_counts(section: &pos::Section) -> Result<()> {
    let Some((line, declared)) = &section.npos else {
        return Ok(());
    };
    for (k, kind) in [Kind::Robot, Kind::Base, Kind::Station].iter().enumerate() {
        let have = (section.positions.keys())
            .filter(|(c, _)| c == kind)
            .count();
        if declared.get(k).is_some_and(|n| *n != have) {
            return Err(at(*line, format!("///NPOS declares {} {} positions, //POS holds {have}: the controller refuses the job (is the file cut off?)", declared[k], kind.prefix())));
        }
    }
    Ok(())
}

/// The one form of the positions of `kind`, if it has any (a robot's may mix pulses and
/// Cartesian form: the first's).
fn form(positions: &HashMap<(Kind, u64), Position>, kind: Kind) -> Result<Option<Form>> {
    let mut of: Vec<&Position> = (positions.iter().filter(|(k, _)| k.0 == kind))
        .map(|(_, p)| p)
        .collect();
    of.sort_by_key(|p| p.line);
    // A robot's positions may be in pulses and in Cartesian form, each read in its own.
    let mixed = |a: Form, b: Form| kind == Kind::Robot && a != Form::Angle && b != Form::Angle;
    match of
        .iter()
        .find(|p| p.form != of[0].form && !mixed(p.form, of[0].form))
    {
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
}

impl inst::Motion {
    /// Whether the motion is a circle's point (`MOVC`, or the coordinated `SMOVC`).
    fn circular(&self) -> bool {
        self.word == "MOVC" || self.word == "SMOVC"
    }

    /// Whether the motion moves to a position of `kind`.
    fn uses(&self, kind: Kind) -> bool {
        match kind {
            Kind::Robot => true,
            Kind::Base => self.base.is_some(),
            Kind::Station => self.station.is_some(),
        }
    }
}

/// The target of motion `m`: its robot position in pulses converted by `pulses` (per value, the
/// six axes then the `nb` base and `ne` station axes), or in Cartesian form (`rectan`, the
/// frames the backup gives in `held`), its base and station positions.
fn target(
    m: &inst::Motion,
    positions: &HashMap<(Kind, u64), Position>,
    (pulses, held): (&[Option<f64>], &rectan::Held),
    (nb, ne): (usize, usize),
) -> Result<super::JointTarget> {
    let get = |kind: Kind, index: u64| {
        positions.get(&(kind, index)).ok_or_else(|| {
            let (word, prefix) = (&m.word, kind.prefix());
            at(
                m.line,
                format!("{word} {prefix}{index:05}: no such position in //POS"),
            )
        })
    };
    let robot = get(Kind::Robot, m.robot)?;
    let external = external(m, &get, pulses, (nb, ne))?;
    let mut target = match robot.form {
        Form::Rectan => {
            let c = rectan::target(m, robot, held)?;
            super::JointTarget::cartesian(m.line, c).with_external(external)
        }
        _ => six(m.line, robot_values(m, robot, pulses)?, "C")?.with_external(external),
    };
    target.origin = robot.line;
    target.speed = m.speed.clone();
    Ok(target)
}

/// The six axis values of the robot position `robot` of motion `m` in pulses (or degrees),
/// converted by `pulses`.
fn robot_values(
    m: &inst::Motion,
    robot: &Position,
    pulses: &[Option<f64>],
) -> Result<super::Found> {
    if robot.values.len() != 6 {
        let n = robot.values.len();
        return Err(at(
            robot.line,
            format!("C{:05}: expected 6 axis values, found {n}", m.robot),
        ));
    }
    let mut found: super::Found = Default::default();
    for (k, (v, span)) in robot.values.iter().enumerate() {
        found[k] = Some((v / pulses[k].unwrap_or(1.0), span.clone()));
    }
    Ok(found)
}

/// A value read and its span, if the position gives it.
type Value = Option<(f64, Range<usize>)>;

/// A motion's external values: its base and station positions' (`nb` and `ne` axes, in pulses
/// converted by `pulses` or `///ANGLE`), each with its span.
fn external<'p>(
    m: &inst::Motion,
    get: &dyn Fn(Kind, u64) -> Result<&'p Position>,
    pulses: &[Option<f64>],
    (nb, ne): (usize, usize),
) -> Result<Vec<Value>> {
    let mut external: Vec<Value> = vec![None; nb + ne];
    for (kind, index, offset) in [(Kind::Base, m.base, 0), (Kind::Station, m.station, nb)] {
        let Some(index) = index else { continue };
        let p = get(kind, index)?;
        if p.form == Form::Rectan {
            return Err(at(m.line, format!("{} {}{index:05}: a position in Cartesian form (line {}); stiffid reads base and station axes in pulses or ANGLE", m.word, kind.prefix(), p.line)));
        }
        for (k, (v, span)) in p.values.iter().enumerate() {
            let v = v / pulses[6 + offset + k].unwrap_or(1.0);
            if !v.is_finite() {
                let (prefix, axis) = (kind.prefix(), k + 1);
                return Err(at(
                    p.line,
                    format!("{prefix}{index:05}: axis {axis}: {v} is not a finite value"),
                ));
            }
            external[offset + k] = Some((v, span.clone()));
        }
    }
    Ok(external)
}

/// Yaskawa INFORM (module docs).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Inform;

impl Controller for Inform {
    /// `///RCONF` (`rconf`).
    type Flags = rconf::Rconf;
    const LANGUAGE: &'static Descriptor = &Descriptor {
        key: "inform",
        title: "Yaskawa INFORM",
        extensions: &["jbi"],
        data_files: &[],
        motions: "MOVJ, MOVL or MOVC to a C position of //POS",
        joint_forms: "pulse positions",
        part_forms: Some("positions in user coordinates (///POSTYPE USER) of the user frame that is the part frame"),
        external_axes: AxisNames::Numbered("external axis "),
        unused_axis: "",
        zero_is_no_axis: false,
        names: NameRules {
            declared_by: Some("//NAME"),
            file: FileName::Upper,
            max_length: 32,
            default_length: 32,
            reserved: &[],
        },
        bound_comment: BoundComment::LineBefore { marker: '\'' },
        motion_words: &["MOVJ ", "MOVL ", "MOVC "],
        frame_numbers: (63, 63),
        axis_3_from_horizontal: false,
    };

    fn read(&self, text: &str) -> Result<Read> {
        targets(text, &Context::default())
    }
    fn read_in(&self, text: &str, context: &Context) -> Result<Read> {
        targets(text, context)
    }
    /// `X,Y,Z,Rx,Ry,Rz`: `Rz Ry Rx` (`rectan`).
    fn rotation(&self, n: &[f64]) -> UnitQuaternion<f64> {
        UnitQuaternion::from_euler_angles(n[3].to_radians(), n[4].to_radians(), n[5].to_radians())
    }
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        let [a, b, c] = super::generate::zyx_deg(r);
        vec![p.x, p.y, p.z, c, b, a]
    }
    /// As the controller writes a position: mm with 3 decimals, deg with 4 (its resolution).
    fn pose_text(&self, k: usize, value: f64) -> String {
        let s = match k < 3 {
            true => format!("{value:.3}"),
            false => format!("{value:.4}"),
        };
        match s.strip_prefix('-') {
            Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
            _ => s,
        }
    }
    /// `-`: a job's name may hold it (real YRC1000 backups hold `R1_HAND-OFF.JBI`, `SHIP-R1.JBI`,
    /// named so on the pendant).
    fn name_symbols(&self) -> &'static str {
        "-"
    }
    /// The condition and data files read by name: `TOOL.CND`, `UFRAME.CND`, `VAR.DAT`.
    fn backup_names(&self) -> &'static [&'static str] {
        &[toolcnd::FILE, uframe::FILE, var::FILE]
    }
    /// Jobs in pulses ([`generate`]).
    fn generator(&self) -> Option<&'static dyn Generator> {
        Some(&Inform)
    }
    /// The jobs a job calls (`jbi`) and the backup's condition and data files (`TOOL.CND`,
    /// `UFRAME.CND`, `VAR.DAT`).
    fn backup_extensions(&self) -> &'static [&'static str] {
        &["jbi", "cnd", "dat"]
    }
    /// A base axis (`BC1`..) carries the arm, a station axis (`EC1`..) the part.
    fn axis_role(&self, name: &str) -> Option<stiffid_core::robot::external::Role> {
        use stiffid_core::robot::external::Role;
        match name.get(..2) {
            Some("BC") => Some(Role::Carrier),
            Some("EC") => Some(Role::Positioner),
            _ => None,
        }
    }
    /// `///NPOS` counting the positions copied from position variables (`written`).
    fn written(&self, read: &str, written: String) -> String {
        written::finish(read, written)
    }
}

#[cfg(test)]
mod circles_tests;

#[cfg(test)]
mod rconf_tests;
