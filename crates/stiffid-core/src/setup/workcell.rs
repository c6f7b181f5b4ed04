//! The workcell: what surrounds the arm in a real cell (the floor, clearance and obstacles, the
//! laser tracker, the search's constraints, the workpiece's frame) ([`super::Setup::workcell`]).

use super::{Cell, NumberedFrames, Tracker};
use crate::Robot;
use nalgebra::{Isometry3, Vector3};

/// Which kinematics the robot controller runs a program with (`[controller] kinematics`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Kinematics {
    /// The nominal robot: the robot file the controller runs (`[controller] robot`, else the
    /// setup's `robot` when it is not a calibrated one).
    #[default]
    Nominal,
    /// The setup's (calibrated) robot: a controller loaded with an absolute-accuracy model.
    Calibrated,
}

impl crate::common::choice::Choice for Kinematics {
    const FIELD: &'static str = "controller.kinematics";
    const ALL: &'static [Self] = &[Kinematics::Nominal, Kinematics::Calibrated];
    fn name(self) -> &'static str {
        match self {
            Kinematics::Nominal => "nominal",
            Kinematics::Calibrated => "calibrated",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Kinematics::Nominal => "The robot file the controller runs (the nominal robot)",
            Kinematics::Calibrated => {
                "The setup's calibrated robot (an absolute-accuracy controller)"
            }
        }
    }
}

crate::common::choice::by_name!(Kinematics);

/// What a program's joint targets are (`[controller] joint_targets`): where they came from
/// decides what compensating them corrects on a robot whose geometry is not the controller's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointTargets {
    /// Taught on this robot (jogged to and recorded): the pose is wherever the real robot went,
    /// so only the deflection is corrected.
    Taught,
    /// Computed by the controller's inverse kinematics (an offline program, a CAM post, a
    /// conversion from Cartesian targets) with its own, nominal geometry: the pose meant is the
    /// controller's forward kinematics of the angles, which the setup's robot is solved for
    /// (geometry and deflection corrected, as for a Cartesian target).
    Computed,
}

impl crate::common::choice::Choice for JointTargets {
    const FIELD: &'static str = "controller.joint_targets";
    const ALL: &'static [Self] = &[JointTargets::Taught, JointTargets::Computed];
    fn name(self) -> &'static str {
        match self {
            JointTargets::Taught => "taught",
            JointTargets::Computed => "computed",
        }
    }
    fn help(self) -> &'static str {
        match self {
            JointTargets::Taught => "Taught on this robot: the deflection only is corrected",
            JointTargets::Computed => {
                "Computed by the controller's inverse kinematics: geometry and deflection corrected"
            }
        }
    }
}

crate::common::choice::by_name!(JointTargets);

/// `[controller]`: the kinematics of the controller that runs a generated program. Its
/// Cartesian targets are the controller's own forward kinematics of the compensated axis angles
/// (the calibration "filters" them), so that its inverse kinematics returns those angles.
///
/// The frames the controller speaks in are its own: its world frame (FANUC's user frame 0,
/// KUKA's `$WORLD`, ABB's world) is the robot's [`Robot::controller_world`] on the setup's
/// `[robot_base]` (a pedestal) ([`super::Setup::program_world`]), and its flange is the robot
/// file's, before the setup's `[robot_flange]` (an adapter plate). A program read or written
/// states its positions, base and work object in that world and its tool from that flange.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Controller {
    /// Which kinematics.
    pub kinematics: Kinematics,
    /// `[controller] robot`: the robot file the controller runs (with the setup's
    /// `[robot_base]` and `[robot_flange]`), if given.
    pub robot: Option<Robot>,
    /// The robot's mount in the setup's base (cell) frame: the setup's `[robot_base]` (or the
    /// one a calibrated robot file records), the identity without one. Lengths in m. The
    /// controller's world is the robot's [`Robot::controller_world`] on it
    /// ([`super::Setup::program_world`]).
    pub mount: Isometry3<f64>,
    /// The mounted flange (the tool's frame of reference, where `[tool]` points are given) in
    /// the controller's flange frame: the setup's `[robot_flange]` adapter, the identity without
    /// one. Lengths in m.
    pub adapter: Isometry3<f64>,
    /// `[controller] pulses_per_deg` and `external_pulses`: the encoder pulses of the
    /// controller's axes, for a program written in pulses (a Yaskawa INFORM job); `None` when
    /// the setup does not give them.
    pub pulses: Option<Pulses>,
    /// `[controller] tools`: the tool frames the controller holds by number (KUKA
    /// `TOOL_DATA[n]`, FANUC `UTOOL[n]`, a Yaskawa tool file), each in the controller's flange
    /// frame, m (`super::numbered`); empty without.
    pub tools: NumberedFrames,
    /// `[controller] bases`: the base and user frames the controller holds by number (KUKA
    /// `BASE_DATA[n]`, FANUC `UFRAME[n]`, a Yaskawa user frame), each in the controller's world
    /// frame, m; empty without.
    pub bases: NumberedFrames,
    /// `[controller] rapid_speed_mm_s`, `rapid_joint_pct`, `home_deg` and `[controller.io]`:
    /// how a generated program moves to and from its path and what it does at the G-code's
    /// process words ([`super::program_io`]).
    pub program: super::ProgramSettings,
    /// `[controller] dialect`: the controller a G-code program is written for, where
    /// controllers read the same words differently; `None` when the setup does not say.
    pub dialect: Option<super::GcodeDialect>,
    /// `[controller] radius_wear_mm`: the controller's wear offsets of the tools' radii by the
    /// number a G-code's `D` names, m, in number order; empty without.
    pub radius_wear: Vec<(u32, f64)>,
    /// `[controller] joint_targets`: whether a program's joint targets were taught on this
    /// robot or computed by the controller's inverse kinematics; `None` when the setup does not
    /// say (refused where it matters: a robot whose geometry is not the controller's).
    pub joint_targets: Option<JointTargets>,
    /// `[controller] robot_number`: which of the controller's robots the setup's robot is (a
    /// Yaskawa controller's `RB2`: 2), from 1 to 8; `None`: the first.
    pub robot_number: Option<u32>,
}

/// The most robots one controller moves (a Yaskawa controller's `R1` to `R8`).
pub(crate) const MAX_ROBOT_NUMBER: u32 = 8;

/// `[controller] robot_number` checked.
///
/// # Errors
/// [`crate::Error::InvalidField`] (`controller.robot_number`) outside 1 to [`MAX_ROBOT_NUMBER`].
pub(super) fn robot_number(n: Option<u32>) -> crate::Result<Option<u32>> {
    match n {
        Some(k) if !(1..=MAX_ROBOT_NUMBER).contains(&k) => Err(crate::Error::InvalidField {
            field: "controller.robot_number".into(),
            message: format!("{k}: expected which of the controller's robots the setup's robot is, 1 to {MAX_ROBOT_NUMBER} (a Yaskawa job's RB1 to RB{MAX_ROBOT_NUMBER})"),
        }),
        other => Ok(other),
    }
}

/// How many encoder pulses make a unit of each axis on the controller (its axis parameters): a
/// program in pulses (a Yaskawa INFORM job's `///PULSE` positions) writes an axis value as the
/// nearest whole number of its pulses. Each number within `PULSES`.
#[derive(Debug, Clone, PartialEq)]
pub struct Pulses {
    /// Pulses per degree of the robot's six axes (S, L, U, R, B, T), in the order of its
    /// axis angles.
    pub per_deg: [f64; 6],
    /// Pulses per mm of a linear external axis and per degree of a rotary one, one per external
    /// axis in the cell's order (the carrier's axes, then the positioner's); empty: the
    /// external axes are written as decimals (mm, deg).
    pub external: Vec<f64>,
}

impl Pulses {
    /// The setup file's `[controller] pulses_per_deg` and `external_pulses` (their ranges and
    /// counts are checked with the robot's external axes: [`Pulses::check`]).
    ///
    /// # Errors
    /// [`crate::Error::InvalidField`] (`controller.external_pulses`) given without
    /// `pulses_per_deg`.
    pub(super) fn read(
        per_deg: Option<[f64; 6]>,
        external: Option<Vec<f64>>,
    ) -> crate::Result<Option<Self>> {
        match (per_deg, external) {
            (None, None) => Ok(None),
            (None, Some(_)) => Err(crate::Error::InvalidField {
                field: "controller.external_pulses".into(),
                message: "given without pulses_per_deg: a program in pulses needs the robot's six axes' pulses per degree too (pulses_per_deg = [S, L, U, R, B, T])".into(),
            }),
            (Some(per_deg), external) => Ok(Some(Self {
                per_deg,
                external: external.unwrap_or_default(),
            })),
        }
    }

    /// Checks every number against [`crate::common::limits::PULSES`] and the external count
    /// against the cell's `external` axes (none, or one per axis).
    ///
    /// # Errors
    /// [`crate::Error::InvalidField`] naming `controller.pulses_per_deg[i]` or
    /// `controller.external_pulses[i]` (a value outside the range or not finite), or
    /// `controller.external_pulses` (another count than the cell's axes).
    pub(crate) fn check(&self, external: usize) -> crate::Result<()> {
        use crate::common::limits::{check, PULSES};
        check("controller.pulses_per_deg", &self.per_deg, &PULSES)?;
        check("controller.external_pulses", &self.external, &PULSES)?;
        match self.external.len() {
            0 => Ok(()),
            n if n == external => Ok(()),
            n => Err(crate::Error::InvalidField {
                field: "controller.external_pulses".into(),
                message: format!("{n} numbers for {external} external axes: expected one per external axis ([[external_axis]]), in the cell's order (the carrier's axes, then the positioner's), or none (the external axes written in mm and deg)"),
            }),
        }
    }
}

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
    /// `[workpiece]`'s work offsets, start and home positions for G-code.
    pub(super) program_frames: super::ProgramFrames,
    /// Reflectors on the positioner's table or on a fixed part, the part's frame, m.
    pub(super) table_reflectors: Vec<Vector3<f64>>,
    pub(super) controller: Controller,
}

impl Workcell {
    /// Optional cell constraints for posture search.
    pub(crate) fn constraints(&self) -> &CellConstraints {
        &self.constraints
    }

    /// The floor, clearance and obstacles; `None`: no body checks (the paper's study).
    pub(crate) fn cell(&self) -> Option<&Cell> {
        self.cell.as_ref()
    }

    /// The laser tracker, for the line-of-sight and incidence checks.
    pub(crate) fn tracker(&self) -> Option<&Tracker> {
        self.tracker.as_ref()
    }

    /// `[workpiece] base_from_part`: a G-code program's part frame in the robot base frame, m.
    pub(crate) fn workpiece(&self) -> Option<&Isometry3<f64>> {
        self.workpiece.as_ref()
    }

    /// `[workpiece]`'s work offsets (`[workpiece.offsets]`), `start_mm`, `g28_mm` and
    /// `g30_mm`: what a G-code program's `G53`-`G59.3`, `G28` and `G30` and its first moves
    /// need ([`super::ProgramFrames`]).
    pub fn program_frames(&self) -> &super::ProgramFrames {
        &self.program_frames
    }

    /// `[workpiece] reflectors_mm`: the reflectors fixed on the positioner's table or, in a
    /// cell without a positioner, on the part or its fixture (`T1`, `T2`, ... of a readings
    /// file), in the cell frame with every axis at 0 (the part's frame `base_from_part`
    /// applied), m; empty without.
    pub(crate) fn table_reflectors(&self) -> Vec<Vector3<f64>> {
        let part = self.workpiece.unwrap_or_default();
        (self.table_reflectors.iter())
            .map(|p| (part * nalgebra::Point3::from(*p)).coords)
            .collect()
    }

    /// `[controller]`: the kinematics of the controller that runs a program.
    pub fn controller(&self) -> &Controller {
        &self.controller
    }
}
