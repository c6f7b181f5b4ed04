//! A parallel shift (`SFTON P032`, `SFTON P001 UF#(2)` .. `SFTOF`) computed statically: the
//! controller moves each motion between `SFTON` and `SFTOF` to its position displaced by the
//! shift amount, the position variable's `X,Y,Z` in the shift's coordinates (INFORM manual,
//! `SFTON`: `BF` base, `RF` robot, `UF#(n)` user frame `n`, `TF` tool coordinates). The amount is
//! read from the backup's `VAR.DAT` ([`super::var`]) where it is certain: a Cartesian variable
//! no instruction of the job or the jobs it calls sets, in the coordinates the `SFTON` names
//! (base or robot coordinates, the same on a cell without a base axis, for `BF`, `RF` or no
//! tag; user frame `n` for `UF#(n)`), turning nothing (`Rx`, `Ry`, `Rz` zero). A motion to a
//! Cartesian position in those same coordinates is then read as its position displaced by the
//! amount (written back as the position the controller, displacing it, moves to the compensated
//! pose); a shift of zero changes nothing. Refused naming the line: what the job or the backup
//! does not say (no `VAR.DAT`, a variable set as the job runs, a turning shift, tool
//! coordinates, a frame other than the position's), and a shift of a position in pulses (its
//! pose is the controller's kinematics').

use super::inst::{Instructions, Shift, ShiftFrame};
use super::pos::{Form, Kind, Position};
use super::var::{self, Variable};
use super::variables::Set;
use crate::program::{at, Context, JointTarget};
use nalgebra::{Isometry3, Translation3, Vector3};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// Displaces the targets of the motions of `inst` a shift is in force at (module docs).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the `SFTON` or motion's line (module docs).
pub(super) fn apply(
    inst: &Instructions,
    positions: &HashMap<(Kind, u64), Position>,
    targets: &mut [JointTarget],
    (context, sets): (&Context, &[Set]),
) -> Result<()> {
    if inst.shifts.is_empty() {
        return Ok(());
    }
    let amounts = (inst.shifts.iter())
        .map(|s| amount(s, context, sets))
        .collect::<Result<Vec<_>>>()?;
    for (m, t) in inst.motions.iter().zip(targets.iter_mut()) {
        let Some((s, (d, coordinates))) = m.shift.map(|k| (&inst.shifts[k], amounts[k])) else {
            continue;
        };
        if d == Vector3::zeros() {
            continue;
        }
        let p = positions.get(&(Kind::Robot, m.robot));
        let (Some(c), Some(p)) = (
            t.cartesian.as_deref_mut(),
            p.filter(|p| p.form == Form::Rectan),
        ) else {
            return Err(at(m.line, format!("{}: a position in pulses shifted by {} (line {}): its pose is the controller's kinematics', which stiffid does not displace; teach the shifted position, or the path in Cartesian form", m.word, short(&s.text), s.line)));
        };
        let postype = p.frame.split_whitespace().next().unwrap_or("");
        let same = match (coordinates, postype) {
            (Coordinates::World, "BASE" | "ROBOT") => true,
            (Coordinates::User(n), "USER") => p.user.is_some_and(|(_, u)| u == n),
            _ => false,
        };
        if !same {
            return Err(at(m.line, format!("{}: a position in {postype} coordinates (line {}) shifted in other coordinates by {} (line {}); stiffid displaces a position in the coordinates of its shift", m.word, p.line, short(&s.text), s.line)));
        }
        c.before = Isometry3::from(Translation3::from(d * 1e-3)) * c.before;
    }
    Ok(())
}

/// The coordinates a shift displaces in: base or robot coordinates, or user frame `n`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Coordinates {
    World,
    User(u32),
}

/// The amount of shift `s` (mm) and its coordinates, read from the `context`'s `VAR.DAT`.
fn amount(s: &Shift, context: &Context, sets: &[Set]) -> Result<(Vector3<f64>, Coordinates)> {
    let refuse = |why: String| at(s.line, format!("{}: {why}", short(&s.text)));
    if let Some(set) = sets
        .iter()
        .find(|x| x.index.is_none_or(|i| i == s.variable))
    {
        return Err(refuse(format!("the shift amount is set as the jobs run ({}line {}: {}), so its value is not the one VAR.DAT holds; a run-time shift is not compensated", set.file.as_ref().map_or(String::new(), |f| format!("{f} ")), set.line, short(&set.text))));
    }
    let Some(vars) = var::read(context)? else {
        return Err(refuse(format!("the shift amount P{:03} holds its value on the controller: give the controller's backup holding its VAR.DAT with the job (--backup)", s.variable)));
    };
    let file = vars.file;
    let Some((vline, v)) = vars.list.get(s.variable as usize) else {
        return Err(refuse(format!(
            "{file} holds {} position variables: P{:03} is not in it",
            vars.list.len(),
            s.variable
        )));
    };
    let Variable::Rectan {
        user,
        coordinates,
        values,
        ..
    } = v
    else {
        return Err(refuse(format!(
            "{file} line {vline}: the shift amount is not a Cartesian variable (\"RECTAN\")"
        )));
    };
    let n: Vec<f64> = values.iter().map(|(x, _)| *x).collect();
    if n.len() < 6 || n[3..].iter().any(|x| *x != 0.0) {
        return Err(refuse(format!("{file} line {vline}: a shift that turns the tool (Rx, Ry, Rz or a value after them not zero): how the controller turns a shifted pose is not certain from public sources; stiffid computes a shift that moves the tool parallel")));
    }
    let d = Vector3::new(n[0], n[1], n[2]);
    let stated = match (s.frame, coordinates) {
        (ShiftFrame::Unsaid | ShiftFrame::Base | ShiftFrame::Robot, 16 | 17) => {
            Some(Coordinates::World)
        }
        (ShiftFrame::User(f), 19) if f == *user => Some(Coordinates::User(f)),
        _ => None,
    };
    match stated {
        Some(c) => Ok((d, c)),
        None if d == Vector3::zeros() => Ok((d, Coordinates::World)),
        None => Err(refuse(format!("{file} line {vline}: a shift amount in coordinates {coordinates} (user frame {user}), shifted {}: which coordinates the controller displaces in is not certain; stiffid computes a shift in base, robot or user coordinates that the variable and the SFTON both state", s.frame.words()))),
    }
}
