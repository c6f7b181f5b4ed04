//! The workcell: what surrounds the arm in a real cell (the floor, clearance and obstacles, the
//! laser tracker, the search's constraints, the workpiece's frame) ([`super::Setup::workcell`]).

use super::{Cell, Tracker};
use nalgebra::Isometry3;

/// Constraints of a real cell on the postures a search may choose.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CellConstraints {
    /// The loading point stays at or above this height (base z), m.
    pub loading_point_min_z: Option<f64>,
    /// The rope anchor stays below the loading point (a hanging mass pulls down).
    pub anchor_below_loading_point: bool,
}

/// What surrounds the arm: the cell's floor, clearance and obstacles, the laser tracker, the
/// constraints of a posture search, and a G-code program's part frame. All optional: the paper's
/// study has none. Part of a [`super::Setup`], checked by its builder
/// ([`super::SetupBuilder::build`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Workcell {
    pub(super) constraints: CellConstraints,
    pub(super) cell: Option<Cell>,
    pub(super) tracker: Option<Tracker>,
    pub(super) workpiece: Option<Isometry3<f64>>,
}

impl Workcell {
    /// Optional cell constraints for posture search.
    pub fn constraints(&self) -> &CellConstraints {
        &self.constraints
    }

    /// The floor, clearance and obstacles; `None`: no body checks (the paper's study).
    pub fn cell(&self) -> Option<&Cell> {
        self.cell.as_ref()
    }

    /// The laser tracker, for the line-of-sight and incidence checks.
    pub fn tracker(&self) -> Option<&Tracker> {
        self.tracker.as_ref()
    }

    /// `[workpiece] base_from_part`: a G-code program's part frame in the robot base frame, m.
    pub fn workpiece(&self) -> Option<&Isometry3<f64>> {
        self.workpiece.as_ref()
    }
}
