//! A robot program's external axes as the cell's: the values each target gives, in the cell's
//! order and checked against the cell ([`stiffid_core::robot::external`]).
//!
//! The program's external axes ([`JointProgram::axes`]) are the cell's in order: KRL `E1`..`En`
//! (the `$EX_AX_NUM` numbering), RAPID `eax_a`.. (the mechanical units' logical axes), LS group
//! 1's `E1`.. then group 2's `J1`.., INFORM's base axes `BC` then station axes `EC`: the first is
//! the cell's first external axis (the carrier's first), and so on. Values are mm for a linear
//! axis and deg for a rotary one, as the controllers write them.
//!
//! Refused, naming the line and the axis:
//! - a value for an axis the cell lacks (a program for a cell with fewer external axes, or
//!   none); KRL's `E`n `0` aside: KUKA's tools write `E1` to `E6` in every `E6AXIS`, `0` for an
//!   axis that does not exist;
//! - an axis of the cell for which the target gives no value (RAPID `9E9`, a KRL aggregate
//!   without its `E`n, an LS position without it): the controller would keep the axis where it
//!   is, which the program does not say;
//! - a value outside the axis's travel;
//! - an axis written in the unit of the other kind (LS `E1= 1500 deg` for a linear axis, `mm`
//!   for a rotary one: the controller takes the unit of the axis it drives).

use super::{JointProgram, JointTarget};
use stiffid_core::robot::external::Role;
use stiffid_core::robot::ExternalAxes;
use stiffid_core::{Error, Result};

/// Each target's external axis values in the cell's order, SI (m or rad), checked (module docs);
/// one empty row per target for a cell without external axes (`cell` `None`) and a program
/// that moves none.
///
/// # Errors
/// [`Error::Program`] naming the target's line and the axis (module docs).
pub fn cell_values(program: &JointProgram, cell: Option<&ExternalAxes>) -> Result<Vec<Vec<f64>>> {
    check_units(program, cell)?;
    check_roles(program, cell)?;
    program
        .targets
        .iter()
        .map(|t| target_values(program, t, cell))
        .collect()
}

/// One target's values (module docs).
fn target_values(
    program: &JointProgram,
    t: &JointTarget,
    cell: Option<&ExternalAxes>,
) -> Result<Vec<f64>> {
    let n = cell.map_or(0, ExternalAxes::len);
    let names = || match cell {
        Some(c) if !c.is_empty() => format!(
            "the cell's external axes are {}",
            c.axes()
                .iter()
                .map(|a| format!("{} ({})", a.name, a.unit()))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        _ => "the robot has no external axes".into(),
    };
    for (k, value) in t.external.iter().enumerate().skip(n) {
        let Some(v) = value else { continue };
        if program.dialect.controller().zero_is_no_axis() && *v == 0.0 {
            continue;
        }
        return Err(Error::Program {
            line: t.line,
            message: format!(
                "{} {}: the program moves external axis {} and {}: give the robot its external axes or remove the axis from the program",
                program.axes[k],
                stiffid_core::common::words::number(*v),
                k + 1,
                names()
            ),
        });
    }
    let Some(cell) = cell.filter(|c| !c.is_empty()) else {
        return Ok(Vec::new());
    };
    let mut out = Vec::with_capacity(n);
    for (k, axis) in cell.axes().iter().enumerate() {
        let named = program
            .axes
            .get(k)
            .cloned()
            .unwrap_or_else(|| program.dialect.controller().external_axis(k));
        let display = t.external.get(k).copied().flatten().ok_or_else(|| Error::Program {
            line: t.line,
            message: match t.is_held() {
                true => format!("{named}: no value for the cell's external axis {} ({}) at the home position: the setup's [controller] home_deg gives the six axis angles only; declare the home position with its external axes in the program's .dat (DECL E6AXIS XHOME={{A1 .., A6 .., {named} ..}}, as the controller's $config.dat holds it)", k + 1, axis.name),
                false => format!(
                    "{named}: no value for the cell's external axis {} ({}){}: the controller would keep the axis where it is, which the program does not say; give its value in every target",
                    k + 1,
                    axis.name,
                    program.dialect.controller().unused_axis()
                ),
            },
        })?;
        let si = axis.to_si(display);
        let slack = 1e-9 * (axis.upper - axis.lower);
        if !(si >= axis.lower - slack && si <= axis.upper + slack) {
            let unit = axis.unit();
            return Err(Error::Program {
                line: t.line,
                message: format!(
                    "{named} {} {unit}: outside the travel of the cell's external axis {} ({}), {} to {} {unit}",
                    stiffid_core::common::words::number(display),
                    k + 1,
                    axis.name,
                    stiffid_core::common::words::number(axis.to_display(axis.lower)),
                    stiffid_core::common::words::number(axis.to_display(axis.upper)),
                ),
            });
        }
        out.push(si);
    }
    Ok(out)
}

/// Each program axis whose language says what it carries (INFORM: base axes `BC` the arm,
/// station axes `EC` the part) against the cell's axis in its place: a job of a cell without a
/// track (no `BC`) on a setup with one would read its station's degrees as the track's mm.
fn check_roles(program: &JointProgram, cell: Option<&ExternalAxes>) -> Result<()> {
    let Some(cell) = cell else { return Ok(()) };
    let controller = program.dialect.controller();
    for (k, (axis, name)) in cell.axes().iter().zip(&program.axes).enumerate() {
        let Some(role) = controller.axis_role(name).filter(|r| *r != axis.role) else {
            continue;
        };
        let given =
            (program.targets.iter()).find(|t| t.external.get(k).is_some_and(Option::is_some));
        let carries = |r: Role| match r {
            Role::Carrier => "the arm (a carrier's axis)",
            Role::Positioner => "the part (a positioner's axis)",
        };
        return Err(Error::Program {
            line: given.or(program.targets.first()).map_or(1, |t| t.line),
            message: format!(
                "{name}: the program's axis carrying {} stands where the cell's external axis {} ({}) carries {}: the cell's order is the carrier's axes, then the positioner's, and the program's the same ({}); give the setup the cell's axes the program was written for",
                carries(role),
                k + 1,
                axis.name,
                carries(axis.role),
                program.axes.join(", ")
            ),
        });
    }
    Ok(())
}

/// Each unit the program writes an axis of the cell in (LS) against the axis's kind.
fn check_units(program: &JointProgram, cell: Option<&ExternalAxes>) -> Result<()> {
    let Some(cell) = cell else { return Ok(()) };
    for (k, (axis, unit)) in cell.axes().iter().zip(&program.units).enumerate() {
        let Some((unit, line)) = unit.filter(|(u, _)| *u != axis.unit()) else {
            continue;
        };
        return Err(Error::Program {
            line,
            message: format!(
                "{} in {unit}: the cell's external axis {} ({}) is {}, its values in {}",
                program.axes[k],
                k + 1,
                axis.name,
                match axis.kind {
                    stiffid_core::robot::external::AxisKind::Linear => "linear",
                    stiffid_core::robot::external::AxisKind::Rotary => "rotary",
                },
                axis.unit()
            ),
        });
    }
    Ok(())
}

/// Each target's external values in the program's order (mm or deg) from the cell's SI values
/// `e` (as [`cell_values`] returned them, or changed), for [`JointProgram::write_with_external`]:
/// the axes past the cell's as read.
pub(crate) fn program_values(
    program: &JointProgram,
    e: &[Vec<f64>],
    cell: Option<&ExternalAxes>,
) -> Vec<Vec<Option<f64>>> {
    program
        .targets
        .iter()
        .zip(e)
        .map(|(t, e)| {
            let mut row = t.external.clone();
            if let Some(cell) = cell {
                for ((slot, v), axis) in row.iter_mut().zip(e).zip(cell.axes()) {
                    if let Some(read) = slot.as_mut().filter(|r| axis.to_si(**r) != *v) {
                        *read = axis.to_display(*v);
                    }
                }
            }
            row
        })
        .collect()
}
