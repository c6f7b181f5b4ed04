//! The experimental cell: robot, tool, spring placement, loading, noise, bounds, nominal stiffness.
//!
//! A [`Setup`] is composed of three parts, and a function takes the smallest part it needs:
//! - the [`Arm`] ([`Setup::arm`]): the robot, its tool points, the elastostatic model, the tool's
//!   payload and the robot's bodies; kinematics, deflection, prediction and compensation need
//!   this alone;
//! - the [`Experiment`] (`Setup::experiment`): the rope load and its steps, the noise, the
//!   bounds, the test postures, the nominal stiffness and the characteristic length, with the
//!   arm what design, simulation and identification need;
//! - the [`Workcell`] ([`Setup::workcell`]): the cell's floor and obstacles, the tracker, the
//!   search's constraints and the workpiece's frame, for the feasibility checks and compensation.
//!
//! [`Setup`]'s own accessors (`robot()`, `load()`, `cell()`, ...) read the same fields through
//! the parts.
//!
//! A setup is written in TOML with units in the field names; unknown keys are rejected:
//! ```toml
//! name = "zhang2021-comau-nj165"
//! description = "what this cell is"
//! robot = "comau-smart5-nj165-3.0"       # a preset name, or a robot .toml / .urdf file
//! # robot_tip = "tool0"                  # URDF only: the tip link
//! # package_paths = ["../ros"]          # URDF only: where package:// meshes are (ROS convention)
//! # [robot_base]                         # optional: the robot on a pedestal, in the cell frame
//! # xyz_mm = [0, 0, 500]                 # (before the robot's own base transform)
//! # rpy_deg = [0, 0, 0]                  # fixed-axis roll, pitch, yaw as URDF
//! # [robot_flange]                       # optional: an adapter plate after the flange
//! # xyz_mm = [0, 0, 20]
//! springs = "axis"                       # or "kinematic": where the joint springs sit
//! characteristic_length_mm = 1200.0      # L of the dexterity index (Eq. 20); optional
//! nominal_stiffness_nm_per_rad = [950000, 3000000, 900000, 250000, 200000, 150000]   # optional
//! [tool]                                 # points in the flange frame
//! loading_point_mm = [150, 0, 200]
//! measuring_points_mm = [[80, 80, 260], [-80, 80, 260]]
//! # tcp_mm = [80, 80, 260]               # the dexterity index's (default measuring point 1);
//! #                                      # compensate requires it: the cutting tool's centre point
//! # tcp_rpy_deg = [0, -90, 0]            # optional: the tool frame's axes on the flange, as a
//! #                                      # robot program's tooldata / $TOOL states them
//! # mass_kg = 12.5                       # optional, with centre_of_mass_mm: the spindle's weight
//! # centre_of_mass_mm = [0, 0, 120]      # joins the process wrench in compensate
//! # inertia_kg_m2 = [0.3, 0.3, 0.1, 0, 0, 0]  # optional: [ixx, iyy, izz, ixy, ixz, iyz] about the
//! #                                     # centre, flange axes: joins link 6 in the mass matrix
//! [loading]                              # rope and mass over a pulley
//! load_n = 500.0
//! anchor_mm = [1500, 1500, 0]            # base frame
//! [noise]
//! reading_sd_mm = 0.0068                 # one coordinate of one tracker reading
//! level_multiples = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0]
//! [bounds]                               # experiment bounds, axis coordinates
//! lower_deg = [-90, -60, -180, -180, -90, -180]
//! upper_deg = [90, 40, -40, 180, 90, 180]
//! [test]                                 # optional: postures to validate and design for
//! postures_deg = [[12.81, 33.07, -126.36, 72.81, -67.88, 24.27]]
//! [constraints]                          # optional, for posture search
//! loading_point_min_z_mm = 300.0
//! anchor_below_loading_point = true
//! ```
//! and optionally the physical cell, `[cell]`, `[robot_geometry]` and `[tracker]` (see [`Cell`]),
//! and where a G-code program's part frame sits in the robot base frame (for
//! `stiffid_machining`):
//! ```toml
//! [workpiece]
//! base_from_part = { xyz_mm = [1300, -300, 400], rpy_deg = [0, 0, 0] }
//! ```
//! A robot on a track and a part on a positioner: `[[external_axis]]` tables
//! ([`crate::robot::external::file`]), which replace the robot file's (`external_axis = []`
//! takes them away); the setup's robot carries them ([`crate::Robot::external`]). With a
//! positioner, `[workpiece]` is the part's frame at `e = 0`, cell frame; a calibrated robot file
//! that records the part's frame its calibration located from the table reflectors (`[part]`,
//! [`crate::Robot::part`]) gives it instead (a setup's other `base_from_part` is refused). A
//! cell without a positioner locates a fixed part the same way from reflectors on the part or
//! its fixture (`[workpiece] reflectors_mm`, read as fixed points of the cell).
//!
//! In code, [`Setup::builder`] takes the same fields in SI units and checks them as the file's
//! ([`SetupBuilder::build`]); [`parse`] reads the file through it.

mod arm;
mod builder;
mod calibrated;
mod carried;
mod cell;
mod cell_file;
mod checks;
mod controller_axes;
mod controller_robot;
mod experiment;
mod file;
mod gcode_dialect;
pub mod load_steps;
mod noise_file;
pub(crate) mod numbered;
pub mod plausibility;
pub mod prior;
mod program_frames;
pub mod program_io;
mod radius_wear;
pub mod reference;
mod workcell;

pub(crate) use arm::nearest_measuring_point;
pub use arm::Arm;
pub use arm::{default_geometry, RobotGeometry, Tool};
pub use arm::{Payload, GRAVITY};
pub use builder::SetupBuilder;
pub use cell::{Cell, Obstacle, Tracker};
pub use experiment::{Experiment, Noise, RopeLoad};
pub(crate) use file::parse_with;
pub use file::{builtin, builtin_names, builtin_text, parse, MAX_PACKAGE_PATHS};
pub use gcode_dialect::GcodeDialect;
pub use numbered::NumberedFrames;
pub use program_frames::ProgramFrames;
pub(crate) use program_io::ProgramSettings;
pub use workcell::{CellConstraints, Controller, JointTargets, Kinematics, Pulses, Workcell};

use crate::common::limits::JointBox;
use crate::model::{Compliance, Model, Spring};
use crate::robot::collision::CollisionGeometry;
use crate::robot::kinematics::{Coordinates, Frames};
use crate::{Error, Result, Robot};
use nalgebra::{Isometry3, Vector3, Vector6};

/// The error of the setup field `field`.
fn invalid(field: &str, message: impl Into<String>) -> Error {
    Error::InvalidField {
        field: field.to_string(),
        message: message.into(),
    }
}

/// A point in mm as a vector in m.
fn mm(v: &[f64; 3]) -> nalgebra::Vector3<f64> {
    nalgebra::Vector3::new(v[0], v[1], v[2]) * 1e-3
}

/// A resolved experimental setup, SI units throughout, its fields checked ([`SetupBuilder::build`]):
/// a name, the [`Arm`], the [`Experiment`] and the [`Workcell`].
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    name: String,
    description: String,
    robot_ref: String,
    arm: Arm,
    experiment: Experiment,
    workcell: Workcell,
    notes: Vec<crate::common::warning::Warning>,
}

impl Setup {
    /// Short name, e.g. `zhang2021-comau-nj165`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// What this cell is, free text.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The robot reference as written (preset name or file).
    pub fn robot_ref(&self) -> &str {
        &self.robot_ref
    }

    /// The arm: robot, tool, model, payload, bodies.
    pub fn arm(&self) -> &Arm {
        &self.arm
    }

    /// The workcell: cell, tracker, constraints, workpiece.
    pub fn workcell(&self) -> &Workcell {
        &self.workcell
    }

    /// The robot ([`Arm::robot`]).
    pub fn robot(&self) -> &Robot {
        self.arm.robot()
    }

    /// Tool points ([`Arm::tool`]).
    pub fn tool(&self) -> &Tool {
        self.arm.tool()
    }

    /// Where the springs sit ([`Arm::springs`]).
    pub fn springs(&self) -> Coordinates {
        self.arm.springs()
    }

    /// The elastostatic model ([`Arm::model`]).
    pub fn model(&self) -> &Model {
        self.arm.model()
    }

    /// The declared candidate springs (`Experiment::candidate_springs`).
    pub fn candidate_springs(&self) -> &[Spring] {
        self.experiment.candidate_springs()
    }

    /// The nominal compliance of every parameter of the model (rad/Nm, m/N), when the setup has a
    /// nominal drive stiffness and every virtual spring one.
    pub fn model_nominal_compliance(&self) -> Option<nalgebra::DVector<f64>> {
        self.model().nominal_compliance(self.nominal_stiffness()?)
    }

    /// [`Setup::model_nominal_compliance`] for `needed_by` (a criterion or computation, named in
    /// the error).
    ///
    /// # Errors
    /// [`Error::MissingField`] without the drives' `nominal_stiffness_nm_per_rad`;
    /// [`Error::InvalidField`] (`[[model.spring]] NAME, ...`) naming every virtual spring without
    /// a nominal stiffness.
    pub fn try_model_nominal_compliance(&self, needed_by: &str) -> Result<nalgebra::DVector<f64>> {
        let drives = self.try_nominal_stiffness(needed_by)?;
        self.model().nominal_compliance(drives).ok_or_else(|| {
            let lacking: Vec<&str> = (self.model().springs().iter())
                .filter(|s| s.nominal_stiffness.is_none())
                .map(|s| s.name.as_str())
                .collect();
            Error::InvalidField {
                field: format!("[[model.spring]] {}", lacking.join(", ")),
                message: format!(
                    "no nominal stiffness (nominal_stiffness_nm_per_rad of a rotation, \
                     nominal_stiffness_n_per_mm of a translation): {needed_by} needs one for \
                     every virtual spring"
                ),
            }
        })
    }

    /// The loading.
    pub fn load(&self) -> &RopeLoad {
        self.experiment.load()
    }

    /// Nothing when the setup gives the loading, for `needed_by` (`Experiment::require_loading`).
    ///
    /// # Errors
    /// As `Experiment::require_loading`.
    pub fn require_loading(&self, needed_by: &str) -> Result<()> {
        self.experiment.require_loading(needed_by)
    }

    /// Measurement noise.
    pub fn noise(&self) -> &Noise {
        self.experiment.noise()
    }

    /// The load levels applied in each posture, N.
    pub fn load_steps(&self) -> &[f64] {
        self.experiment.load_steps()
    }

    /// The variance of one displacement coordinate at the rope load, at noise level multiple 1,
    /// m^2.
    pub fn displacement_variance(&self) -> f64 {
        self.experiment.displacement_variance()
    }

    /// Notes on how the setup file said things (an old field name and what it meant), shown as
    /// warnings with the plausibility ones ([`plausibility::warnings`]).
    pub fn notes(&self) -> &[crate::common::warning::Warning] {
        &self.notes
    }

    /// Experiment bounds, axis coordinates.
    pub fn bounds(&self) -> &JointBox {
        self.experiment.bounds()
    }

    /// Nominal joint stiffness, Nm/rad, if the setup gives one.
    pub fn nominal_stiffness(&self) -> Option<&Vector6<f64>> {
        self.experiment.nominal_stiffness()
    }

    /// The nominal joint stiffness, Nm/rad, for `needed_by` (named in the error).
    ///
    /// # Errors
    /// As `Experiment::try_nominal_stiffness`.
    pub fn try_nominal_stiffness(&self, needed_by: &str) -> Result<&Vector6<f64>> {
        self.experiment.try_nominal_stiffness(needed_by)
    }

    /// Characteristic length `L` of the dexterity index (Eq. 20), m, if the setup gives one.
    pub fn characteristic_length(&self) -> Option<f64> {
        self.experiment.characteristic_length()
    }

    /// The characteristic length, m, for `needed_by` (named in the error).
    ///
    /// # Errors
    /// As `Experiment::try_characteristic_length`.
    pub fn try_characteristic_length(&self, needed_by: &str) -> Result<f64> {
        self.experiment.try_characteristic_length(needed_by)
    }

    /// Test (validation) postures, axis angles, rad (`Experiment::test_postures`).
    pub fn test_postures(&self) -> &[Vector6<f64>] {
        self.experiment.test_postures()
    }

    /// Cell constraints for posture search ([`Workcell::constraints`]).
    pub(crate) fn constraints(&self) -> &CellConstraints {
        self.workcell.constraints()
    }

    /// The floor, clearance and obstacles.
    pub fn cell(&self) -> Option<&Cell> {
        self.workcell.cell()
    }

    /// Capsule radii of the robot and tool bodies.
    pub fn geometry(&self) -> &RobotGeometry {
        self.arm.geometry()
    }

    /// The robot's collision shapes, if the cell uses them ([`Arm::shapes`]).
    pub fn shapes(&self) -> Option<&CollisionGeometry> {
        self.arm.shapes()
    }

    /// Whether the cell's body checks (a `[cell]`, a `[tracker]`'s line of sight) have the robot's
    /// bodies: a URDF whose collision meshes were not found ([`crate::robot::Bodies::Missing`])
    /// serves everything else, not these checks.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`[cell]` or `[tracker]`) naming the mesh not found and how to give
    /// it (`--package-path`, the setup's `package_paths`) or to do without it
    /// (`[robot_geometry] link_radius_mm`).
    pub fn check_bodies(&self) -> Result<()> {
        let Some(why) = self.arm.missing_bodies() else {
            return Ok(());
        };
        let field = match (self.cell(), self.tracker()) {
            (Some(_), _) => "[cell]",
            (None, Some(_)) => "[tracker]",
            (None, None) => return Ok(()),
        };
        Err(invalid(
            field,
            format!(
                "the cell's body checks need the robot's collision meshes ({why}); give the \
                 directory that holds the ROS packages with --package-path DIR (Python: \
                 package_paths) or the setup's package_paths, or capsule radii as \
                 [robot_geometry] link_radius_mm"
            ),
        ))
    }

    /// The nominal compliance of every parameter of its model, for `needed_by` (named in
    /// the error).
    ///
    /// # Errors
    /// [`Error::MissingField`] (`nominal_stiffness_nm_per_rad`) without a nominal drive
    /// stiffness; [`Error::InvalidField`] naming the first virtual spring without a nominal
    /// stiffness.
    pub fn model_compliance(&self, needed_by: &str) -> Result<Compliance> {
        let k = self.try_nominal_stiffness(needed_by)?;
        let model = self.model();
        if let Some(i) = model
            .springs()
            .iter()
            .position(|s| s.nominal_stiffness.is_none())
        {
            let key = match model.springs()[i].kind {
                crate::model::Kind::Rotation => "nominal_stiffness_nm_per_rad",
                crate::model::Kind::Translation => "nominal_stiffness_n_per_mm",
            };
            return Err(Error::InvalidField {
                field: format!("model.spring[{}].{key}", i + 1),
                message: format!(
                    "missing: {needed_by} needs a nominal stiffness of every spring ('{}' has none)",
                    model.springs()[i].name
                ),
            });
        }
        let h = model.nominal_compliance(k).expect("every spring has one");
        Ok(Compliance {
            h,
            covariance: None,
            prediction: None,
            own_weight: None,
            region: crate::model::Region::NotIdentified,
            model_form: None,
        })
    }

    /// The laser tracker.
    pub fn tracker(&self) -> Option<&Tracker> {
        self.workcell.tracker()
    }

    /// Whether the tool centre point was given (`Arm::tcp_given`).
    pub fn tcp_given(&self) -> bool {
        self.arm.tcp_given()
    }

    /// The tool's mass and centre of mass, if given ([`Arm::payload`]).
    pub fn payload(&self) -> Option<&Payload> {
        self.arm.payload()
    }

    /// The reflectors fixed on the positioner's table or on a fixed part, cell frame at `e = 0`,
    /// m (`Workcell::table_reflectors`).
    pub fn table_reflectors(&self) -> Vec<Vector3<f64>> {
        self.workcell.table_reflectors()
    }

    /// A G-code program's part frame in the robot base frame, m.
    pub fn workpiece(&self) -> Option<&Isometry3<f64>> {
        self.workcell.workpiece()
    }

    /// The robot whose forward kinematics the controller runs ([`Workcell::controller`]): the
    /// setup's robot with `kinematics = "calibrated"`, else `[controller] robot`, else the setup's
    /// robot unless that is a calibrated one.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`controller.robot`) when the setup's robot is a calibrated one
    /// (`stiffid calibrate --out`) and neither `[controller] robot` nor
    /// `kinematics = "calibrated"` says which kinematics the controller runs.
    pub fn controller_robot(&self) -> Result<&Robot> {
        let c = self.workcell.controller();
        match (c.kinematics, &c.robot) {
            (Kinematics::Calibrated, _) => Ok(self.robot()),
            (Kinematics::Nominal, Some(r)) => Ok(r),
            (Kinematics::Nominal, None) if self.robot().is_calibrated() => Err(Error::InvalidField {
                field: "controller.robot".into(),
                message: format!(
                    "missing: the setup's robot '{}' is a calibrated one, and a controller with its own nominal kinematics would take Cartesian targets of the calibrated model elsewhere; name the robot file the controller runs ([controller] robot), or say kinematics = \"calibrated\" for a controller loaded with the calibrated model",
                    self.robot().name()
                ),
            }),
            (Kinematics::Nominal, None) => Ok(self.robot()),
        }
    }

    /// The controller's world frame in the setup's base (cell) frame, m: the frame a program's
    /// positions, base and user frames are stated in, for every language read and written. The
    /// mount ([`Controller::mount`], the setup's `[robot_base]`) times the robot's own
    /// [`Robot::controller_world`] (FANUC's world at the height of axis 2).
    pub fn program_world(&self) -> Isometry3<f64> {
        self.workcell.controller().mount * self.robot().controller_world()
    }

    /// The nominal compliance `h = 1 / k` (Eq. 8), rad/Nm (`Experiment::nominal_compliance`).
    pub fn nominal_compliance(&self) -> Option<Vector6<f64>> {
        self.experiment.nominal_compliance()
    }

    /// The same setup without the cell's checks (no `[cell]`, `[tracker]` or `[constraints]`):
    /// what the unconstrained optimum is searched on, to show what feasibility costs. The
    /// workpiece stays.
    pub fn without_cell(&self) -> Setup {
        Setup {
            workcell: Workcell {
                workpiece: self.workcell.workpiece,
                program_frames: self.workcell.program_frames.clone(),
                table_reflectors: self.workcell.table_reflectors.clone(),
                controller: self.workcell.controller.clone(),
                ..Workcell::default()
            },
            ..self.clone()
        }
    }

    /// The setup with the arm standing at the external axis values `e` (SI, the cell's order,
    /// [`crate::robot::external`]): the robot's base moved by the carrier's pose, `C(e) * base`,
    /// and its external axes dropped (with them the reflectors on the positioner's table; the
    /// boxes a positioner carries fixed where `e` puts them, [`Obstacle::at`]), everything else (the cell, the tracker, the rope's anchor, the model) where it was. A design or a simulation of this setup is one of the arm at that
    /// station in the fixed cell; its postures are measured with the external axes at `e`.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`station`) when the robot has no external axes, or as
    /// [`crate::robot::external::ExternalAxes::check`] for values of another count or outside
    /// their travel.
    pub fn at_station(&self, e: &[f64]) -> crate::Result<Setup> {
        let Some(axes) = self.robot().external() else {
            return Err(crate::Error::InvalidField {
                field: "station".into(),
                message: "the robot has no external axes".into(),
            });
        };
        axes.check(e, "station")?;
        let base = axes.carrier_pose(e) * self.robot().base();
        let robot = (self.robot().clone().with_external(None)).with_base(base)?;
        let mut builder = (self.to_builder().with_robot(robot))
            .with_controller(self.controller_keeping(axes.len()..axes.len()));
        if let Some(cell) = self.cell() {
            let obstacles = cell.obstacles_at(self.robot(), e).into_owned();
            builder = builder.with_cell(Cell {
                obstacles,
                ..cell.clone()
            });
        }
        builder.with_table_reflectors(Vec::new()).build()
    }

    /// The setup with the carrier's axes at their values in `e` (SI, the cell's order): the
    /// robot's base moved by the carrier's pose, `C(e) * base`, and only the positioner's axes
    /// left (with the reflectors on its table); [`Setup::at_station`] without a positioner.
    ///
    /// # Errors
    /// As [`Setup::at_station`].
    pub fn at_carrier(&self, e: &[f64]) -> crate::Result<Setup> {
        let Some(axes) = self.robot().external() else {
            return self.at_station(e);
        };
        axes.check(e, "station")?;
        let rest = axes.axes()[axes.carrier_len()..].to_vec();
        if rest.is_empty() {
            return self.at_station(e);
        }
        let base = axes.carrier_pose(e) * self.robot().base();
        let positioner = crate::robot::ExternalAxes::new(rest)?;
        let robot = (self.robot().clone().with_external(Some(positioner))).with_base(base)?;
        (self.to_builder().with_robot(robot))
            .with_controller(self.controller_keeping(axes.carrier_len()..axes.len()))
            .build()
    }

    /// The controller with the external pulses of the axes `kept` only (the cell's order): the
    /// setup of [`Setup::at_station`] or [`Setup::at_carrier`], whose robot keeps those axes.
    fn controller_keeping(&self, kept: std::ops::Range<usize>) -> Controller {
        let mut c = self.workcell.controller().clone();
        if let Some(p) = c.pulses.as_mut().filter(|p| !p.external.is_empty()) {
            p.external = p
                .external
                .get(kept)
                .map(<[f64]>::to_vec)
                .unwrap_or_default();
        }
        c
    }

    /// The rope-mass wrench on the loading point of a posture, base frame.
    pub fn rope_wrench(&self, frames: &Frames) -> Vector6<f64> {
        self.load()
            .wrench(&frames.point(&self.tool().loading_point))
    }
}

#[cfg(test)]
mod load_steps_tests;
#[cfg(test)]
mod prior_tests;
