//! The boxes a positioner carries (`[[cell.obstacle]] carried_by`): where they stand at the
//! external axes' values, and the check of the axis they name.

use super::{invalid, Cell, Obstacle};
use crate::robot::external::{ExternalAxes, Role, MAX_AXES};
use crate::{Result, Robot};
use std::borrow::Cow;

impl Obstacle {
    /// The box where it stands with the cell's external axes `axes` at `e` (SI, the cell's
    /// order; values left out count as 0, so an empty `e` puts every carried box at `e = 0`):
    /// carried by positioner axis `j`, turned by the positioner's pose through that axis,
    /// `P_j(e) * pose` ([`ExternalAxes::positioner_pose`] of the values up to axis `j`, the
    /// function that carries the part), and fixed there (`carried_by` `None`); a fixed box
    /// (or one whose axis `axes` lacks) as it is.
    pub fn at(&self, axes: Option<&ExternalAxes>, e: &[f64]) -> Obstacle {
        let axis = self
            .carried_by
            .as_ref()
            .and_then(|name| axes.and_then(|a| a.axes().iter().position(|x| &x.name == name)));
        let (Some(axes), Some(j)) = (axes, axis) else {
            return self.clone();
        };
        let mut values = [0.0; MAX_AXES];
        for (v, x) in values.iter_mut().zip(e.iter().take(j + 1)) {
            *v = *x;
        }
        Obstacle {
            carried_by: None,
            pose: axes.positioner_pose(&values[..=j]) * self.pose,
            ..self.clone()
        }
    }
}

impl Cell {
    /// The obstacles where they stand with the robot's external axes at `e` ([`Obstacle::at`]):
    /// borrowed as they are when none is carried.
    pub fn obstacles_at(&self, robot: &Robot, e: &[f64]) -> Cow<'_, [Obstacle]> {
        match self.obstacles.iter().any(|o| o.carried_by.is_some()) {
            false => Cow::Borrowed(&self.obstacles),
            true => Cow::Owned(
                (self.obstacles.iter())
                    .map(|o| o.at(robot.external(), e))
                    .collect(),
            ),
        }
    }
}

/// Refuses a `carried_by` that names no external axis of `robot`, or a carrier axis.
pub(super) fn check_carried(cell: &Cell, robot: &Robot) -> Result<()> {
    let axes = robot.external().map_or(&[][..], |a| a.axes());
    let positioners: Vec<&str> = (axes.iter())
        .filter(|a| a.role == Role::Positioner)
        .map(|a| a.name.as_str())
        .collect();
    let expected = match positioners.is_empty() {
        true => "the cell has no positioner axis: give its [[external_axis]] (role = \"positioner\") or no carried_by".to_string(),
        false => format!("expected a positioner axis of the cell: {}", positioners.join(", ")),
    };
    for (i, o) in cell.obstacles.iter().enumerate() {
        let Some(name) = &o.carried_by else {
            continue;
        };
        let field = format!("cell.obstacle[{}].carried_by", i + 1);
        match axes.iter().find(|a| &a.name == name) {
            Some(a) if a.role == Role::Positioner => {}
            Some(_) => {
                return Err(invalid(
                    &field,
                    format!("{name:?} is a carrier axis: a track carries the arm, not obstacles; {expected}"),
                ))
            }
            None => return Err(invalid(&field, format!("{name:?} given: {expected}"))),
        }
    }
    Ok(())
}
