//! A program or a path file that moves the cell's external axes: each target compensated with
//! its external axes as the program or the path gives them.
//!
//! The carrier and the positioner hold still at a target's values while the arm's springs give
//! way, so the compensation is the arm's, in the arm's frame on its carriage (the robot's base
//! frame at `e = 0`, [`stiffid_core::Robot::frames`]): the compensated axis angles put the loaded tool
//! where the unloaded one is on the carriage, which is where it is in the cell. What the external
//! axes change is the load: the process force follows the cut, which is the tool's motion over
//! the part (the path in the part's frame, which the positioner turns and the carriage
//! leaves behind: the feed direction between two targets is taken there), and the tool's weight
//! pulls along the cell's `-z`, which a carriage's error motions (pitch, roll) tilt in the arm's
//! frame. Both are turned into the arm's frame at each target. A G-code program's points are
//! the part's (its `[workpiece]` frame, carried by the positioner): the arm is sent to them on
//! its carriage, and written back as the part's. The results (the nominal pose,
//! the wrench, the deflections) are given in the cell frame; the standard deviations and the
//! prediction intervals stay in the arm's frame on the carriage, whose orientation differs
//! from the cell's by the carriage's error rotations only (of the order of 0.1 mrad).

use super::compensate::{Compensated, PathPoint, Target};
use super::gcode::GCode;
use super::program::external::cell_values;
use super::Program;
use nalgebra::{Isometry3, Rotation3, Vector6};
use stiffid_core::common::error::ColumnProblem;
use stiffid_core::common::words::number;
use stiffid_core::observation::deflection::Frame;
use stiffid_core::robot::external::AxisKind;
use stiffid_core::robot::ExternalAxes;
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result, Robot};

/// Where one target's arm is in the cell.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Placement {
    /// The carrier's pose: the cell frame from the arm's frame on the carriage.
    pub carrier: Isometry3<f64>,
    /// The part's frame from the arm's frame on the carriage.
    pub part: Isometry3<f64>,
    /// The external axes' values (SI, the cell's order).
    pub external: stiffid_core::robot::external::ExternalValues,
}

/// Each target's placement, `None` for a cell without external axes and a program that moves
/// none: every program of such a cell is compensated as on a fixed base. A G-code program's part
/// frame is `workpiece` (the part in the cell at `e = 0`) carried by the positioner.
///
/// # Errors
/// Those of [`cell_values`] for a robot program, [`gcode_values`] for G-code: a program that
/// names an axis the cell lacks, a value outside its travel, no value for an axis of the cell,
/// naming the line and the axis; [`Error::InvalidField`] for G-code that moves external axes
/// without a `workpiece`.
pub(super) fn placements(
    arm: &Arm,
    workpiece: Option<&Isometry3<f64>>,
    program: &Program,
) -> Result<Option<Vec<Placement>>> {
    let cell = arm.robot().external();
    let (e, part) = match program {
        Program::Robot(p) => (cell_values(p, cell)?, Isometry3::identity()),
        Program::GCode(g) => match gcode_values(g, cell)? {
            Some(e) => (e, super::part_frame(workpiece)?),
            None => return Ok(None),
        },
    };
    let Some(cell) = cell.filter(|c| !c.is_empty()) else {
        return Ok(None);
    };
    Ok(Some(e.iter().map(|e| placement(cell, e, &part)).collect()))
}

/// The placements of a program's targets at the external values the compensation chose
/// ([`Compensated::external`]: a free station's, [`crate::compensate::on_track`]), for
/// a program [`placements`] placed (a cell with external axes).
///
/// # Errors
/// Those of [`super::part_frame`] for G-code without a `workpiece`.
pub(super) fn at_chosen(
    arm: &Arm,
    workpiece: Option<&Isometry3<f64>>,
    program: &Program,
    results: &[Compensated],
) -> Result<Vec<Placement>> {
    let Some(cell) = arm.robot().external() else {
        return Ok(Vec::new());
    };
    let part = match program {
        Program::Robot(_) => Isometry3::identity(),
        Program::GCode(_) => super::part_frame(workpiece)?,
    };
    Ok((results.iter())
        .map(|r| placement(cell, r.external.as_slice(), &part))
        .collect())
}

/// The placement at the external values `e` (SI, the cell's order) of a program whose part frame
/// is `part` at `e = 0` (the identity for a robot program: its targets are the arm's).
fn placement(cell: &ExternalAxes, e: &[f64], part: &Isometry3<f64>) -> Placement {
    let carrier = cell.carrier_pose(e);
    Placement {
        carrier,
        part: part.inverse() * cell.positioner_pose(e).inverse() * carrier,
        external: stiffid_core::robot::external::ExternalValues::new(e).unwrap_or_default(),
    }
}

/// A G-code program's external axis values at each point in the cell's order, SI, checked:
/// `None` when neither the cell nor the program has external axes.
///
/// # Errors
/// [`Error::Program`] naming the header's line for a mapping the cell does not match (another
/// count, a linear letter `U V W` for a rotary axis or a rotary `A B C` for a linear one, no
/// mapping in a cell with external axes), and a point's line for a value outside the travel.
pub fn gcode_values(g: &GCode, cell: Option<&ExternalAxes>) -> Result<Option<Vec<Vec<f64>>>> {
    let (letters, header) = (&g.external.0, g.external.1);
    let cell = cell.filter(|c| !c.is_empty());
    let axes = match (cell, letters.is_empty()) {
        (None, true) => return Ok(None),
        (None, false) => return Err(Error::Program { line: header, message: format!("external = {}: the program drives external axes and the robot has none", letters.iter().collect::<String>()) }),
        (Some(c), true) => return Err(Error::Program { line: g.points.first().map_or(1, |p| p.line), message: format!("the cell has external axes ({}) and the program gives none of their values: map them to letters in a header comment, e.g. (stiffid: external = {})", names(c), example_letters(c)) }),
        (Some(c), false) => c,
    };
    if letters.len() != axes.len() {
        return Err(Error::Program { line: header, message: format!("external = {}: {} letters for the cell's {} external axes ({}), one per axis in the cell's order", letters.iter().collect::<String>(), letters.len(), axes.len(), names(axes)) });
    }
    for (l, a) in letters.iter().zip(axes.axes()) {
        let linear = matches!(l, 'U' | 'V' | 'W');
        if linear != (a.kind == AxisKind::Linear) {
            return Err(Error::Program { line: header, message: format!("external: {l} is a {} letter and drives the cell's {} axis {}: U V W drive linear axes (mm), A B C rotary ones (deg)", if linear { "linear" } else { "rotary" }, if linear { "rotary" } else { "linear" }, a.name) });
        }
    }
    g.points
        .iter()
        .map(|p| {
            let si = axes.to_si(&p.external);
            for ((l, a), (v, d)) in letters.iter().zip(axes.axes()).zip(si.iter().zip(&p.external)) {
                let slack = 1e-9 * (a.upper - a.lower);
                if !(*v >= a.lower - slack && *v <= a.upper + slack) {
                    let unit = a.unit();
                    return Err(Error::Program { line: p.line, message: format!("{l} {} {unit}: outside the travel of the cell's external axis {}, {} to {} {unit}", number(*d), a.name, number(a.to_display(a.lower)), number(a.to_display(a.upper))) });
                }
            }
            Ok(si)
        })
        .collect::<Result<Vec<_>>>()
        .map(Some)
}

/// Letters for the cell's axes in order: `U V W` for the linear ones, `C B A` for the rotary.
fn example_letters(c: &ExternalAxes) -> String {
    let (mut linear, mut rotary) = (["U", "V", "W"].iter(), ["C", "B", "A"].iter());
    let letters: Vec<&str> = c
        .axes()
        .iter()
        .filter_map(|a| match a.kind {
            AxisKind::Linear => linear.next().copied(),
            AxisKind::Rotary => rotary.next().copied(),
        })
        .collect();
    letters.join(" ")
}

/// The cell's axes as messages name them.
fn names(c: &ExternalAxes) -> String {
    c.axes()
        .iter()
        .map(|a| format!("{} ({})", a.name, a.unit()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A path file's point ([`crate::path`]) in the arm's frame on its carriage, where
/// the compensation works (module docs): its pose, a point of the part `x`, taken to
/// `C(e)^-1 P(e) x`; a `base` wrench (cell frame) turned by `C(e)^-1`; axis angles and a `tool`
/// wrench as given. A point of a robot without external axes is returned as it is; the results
/// go back to the cell by [`path_to_cell`].
///
/// # Errors
/// [`Error::Column`] at the point's line naming the axis ([`ColumnProblem::Measurement`]):
/// external values for a robot without external axes, none (or another count) for a cell with
/// them, a value outside its axis's travel ([`stiffid_core::Robot::check_external`]).
pub fn on_carriage(robot: &Robot, mut p: PathPoint) -> Result<PathPoint> {
    let e = p.external;
    robot
        .check_external(e.as_slice(), "external axes")
        .map_err(|error| match error {
            Error::InvalidField { field, message } => Error::Column {
                line: p.line,
                column: None,
                name: field,
                problem: ColumnProblem::Measurement { message },
            },
            other => other,
        })?;
    let Some(cell) = robot.external() else {
        return Ok(p);
    };
    let carrier = cell.carrier_pose(e.as_slice());
    if let Target::Pose(pose) = &p.target {
        p.target = Target::Pose(carrier.inverse() * cell.positioner_pose(e.as_slice()) * pose);
    }
    if p.frame == Frame::Base {
        p.wrench = turned(&carrier.rotation.inverse().to_rotation_matrix(), &p.wrench);
    }
    Ok(p)
}

/// The results of path points placed by [`on_carriage`] in the cell frame, as a program's
/// ([`crate::compensate()`]: the nominal pose, the wrench and the deflections; the
/// standard deviations and intervals stay in the arm's frame on the carriage), each on the
/// carriage at its result's external values ([`Compensated::external`]: the station chosen by
/// [`crate::compensate::path_on_track`]), else at its point's.
pub fn path_to_cell(
    robot: &Robot,
    points: &[PathPoint],
    mut results: Vec<Compensated>,
) -> Vec<Compensated> {
    let Some(cell) = robot.external() else {
        return results;
    };
    let placements: Vec<Placement> = (points.iter().zip(&results))
        .map(|(p, r)| {
            let e = match r.external.is_empty() {
                true => p.external,
                false => r.external,
            };
            Placement {
                carrier: cell.carrier_pose(e.as_slice()),
                part: Isometry3::identity(),
                external: e,
            }
        })
        .collect();
    to_cell(&mut results, &placements);
    results
}

/// `w` (`[f; m]`) turned by `r`.
pub(super) fn turned(r: &Rotation3<f64>, w: &Vector6<f64>) -> Vector6<f64> {
    let f = r * w.fixed_rows::<3>(0);
    let m = r * w.fixed_rows::<3>(3);
    Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z)
}

/// The results of a compensated program in the cell frame (module docs).
pub(super) fn to_cell(results: &mut [Compensated], placements: &[Placement]) {
    for (r, p) in results.iter_mut().zip(placements) {
        let rot = p.carrier.rotation.to_rotation_matrix();
        r.pose = p.carrier * r.pose;
        r.external = p.external;
        r.wrench = turned(&rot, &r.wrench);
        r.deflection = turned(&rot, &r.deflection);
        if let Some(d) = r.deflection_before.as_mut() {
            *d = turned(&rot, d);
        }
    }
}
