//! [`SetupBuilder`]: a [`Setup`] from SI values, every field checked as a setup file's are.

use super::cell;
use super::checks::{
    check_accuracy, check_bounds, check_load, check_load_steps, check_noise, check_points,
    check_positioner, check_scaled, check_scales, check_table_reflectors, check_test_postures,
    check_tool, required,
};
use super::{invalid, RobotGeometry};
use super::{Arm, Cell, CellConstraints, Experiment, Noise, Payload, RopeLoad, Setup, Tool};
use super::{Controller, Tracker, Workcell};
use crate::common::limits::{self, JointBox};
use crate::model::{Model, Spring};
use crate::robot::kinematics::Coordinates;
use crate::robot::Bodies;
use crate::{Result, Robot};
use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};

impl Setup {
    /// A builder of a setup named `name` on `robot`, SI units; see [`SetupBuilder`].
    pub fn builder(name: impl Into<String>, robot: Robot) -> SetupBuilder {
        SetupBuilder {
            name: name.into(),
            description: String::new(),
            robot_ref: robot.name().to_string(),
            robot,
            springs: Coordinates::default(),
            virtual_springs: Vec::new(),
            candidate_springs: Vec::new(),
            loading_point: None,
            measuring_points: Vec::new(),
            tcp: None,
            tcp_rotation: UnitQuaternion::identity(),
            load: None,
            load_steps: Vec::new(),
            noise: None,
            bounds: None,
            nominal_stiffness: None,
            characteristic_length: None,
            test_postures: Vec::new(),
            constraints: CellConstraints::default(),
            cell: None,
            link_radii: None,
            tool_radius: None,
            tracker: None,
            workpiece: None,
            table_reflectors: Vec::new(),
            program_frames: Default::default(),
            controller: Controller::default(),
            payload: None,
            mass_sd: 0.0,
            frame_sd: DEFAULT_FRAME_SD,
        }
    }

    /// A builder holding every field of this setup, to change some and build again.
    pub fn to_builder(&self) -> SetupBuilder {
        let (arm, experiment, workcell) = (&self.arm, &self.experiment, &self.workcell);
        SetupBuilder {
            name: self.name.clone(),
            description: self.description.clone(),
            robot_ref: self.robot_ref.clone(),
            robot: arm.robot.clone(),
            springs: arm.model.coordinates(),
            virtual_springs: arm.model.springs().to_vec(),
            candidate_springs: experiment.candidate_springs.clone(),
            loading_point: (!experiment.missing.contains(&"tool.loading_point_mm"))
                .then_some(arm.tool.loading_point),
            measuring_points: arm.tool.measuring_points.clone(),
            tcp: arm.tcp_given.then_some(arm.tool.tcp),
            tcp_rotation: arm.tool.rotation,
            load: (!experiment.missing.contains(&"loading")).then(|| experiment.load.clone()),
            load_steps: experiment.load_steps.clone(),
            noise: Some(experiment.noise.clone()),
            bounds: Some(experiment.bounds),
            nominal_stiffness: experiment.nominal_stiffness,
            characteristic_length: experiment.characteristic_length,
            test_postures: experiment.test_postures.clone(),
            constraints: workcell.constraints.clone(),
            cell: workcell.cell.clone(),
            link_radii: arm.shapes().is_none().then_some(arm.geometry.link_radii),
            tool_radius: Some(arm.geometry.tool_radius),
            tracker: workcell.tracker.clone(),
            workpiece: workcell.workpiece,
            table_reflectors: workcell.table_reflectors.clone(),
            program_frames: workcell.program_frames.clone(),
            controller: workcell.controller.clone(),
            payload: arm.payload,
            mass_sd: arm.mass_sd,
            frame_sd: arm.frame_sd,
        }
    }
}

/// The default standard deviations of a robot model's frames, m and rad (0.3 mm and 0.3 mrad
/// per coordinate): a nominal industrial robot, whose joint frames are typically off by 0.1 to 0.5
/// mm and mrad, 1 to 3 mm at the tool over the workspace (Nubiola and Bonev 2013, Robotics and
/// Computer-Integrated Manufacturing 29(1)).
pub(crate) const DEFAULT_FRAME_SD: (f64, f64) = (3e-4, 3e-4);

/// Builds a [`Setup`] from SI values (m, rad, N, Nm/rad, m^2), argmin-style: `with_*` setters,
/// then [`SetupBuilder::build`] checks every field as a setup file's are checked.
///
/// ```
/// use nalgebra::{Vector3, Vector6};
/// use stiffid_core::setup::{Noise, RopeLoad, Setup};
///
/// let robot = stiffid_core::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
/// let setup = Setup::builder("my-cell", robot)
///     .with_loading_point(Vector3::new(0.15, 0.0, 0.2))
///     .with_measuring_points(vec![Vector3::new(0.08, 0.08, 0.26)])
///     .with_load(RopeLoad { load: 500.0, anchor: Vector3::new(1.5, 1.5, 0.0) })
///     .with_noise(Noise { reading_variance: 4.615e-11, levels: vec![1.0] })
///     .with_nominal_stiffness(Vector6::repeat(1e6))
///     .with_characteristic_length(1.2)
///     .build()
///     .unwrap();
/// assert_eq!(setup.tool().tcp, setup.tool().measuring_points[0]);
/// ```
#[derive(Debug, Clone)]
pub struct SetupBuilder {
    name: String,
    description: String,
    robot_ref: String,
    robot: Robot,
    springs: Coordinates,
    virtual_springs: Vec<Spring>,
    candidate_springs: Vec<Spring>,
    loading_point: Option<Vector3<f64>>,
    measuring_points: Vec<Vector3<f64>>,
    tcp: Option<Vector3<f64>>,
    tcp_rotation: UnitQuaternion<f64>,
    load: Option<RopeLoad>,
    load_steps: Vec<f64>,
    noise: Option<Noise>,
    bounds: Option<JointBox>,
    nominal_stiffness: Option<Vector6<f64>>,
    characteristic_length: Option<f64>,
    test_postures: Vec<Vector6<f64>>,
    constraints: CellConstraints,
    cell: Option<Cell>,
    link_radii: Option<[f64; 7]>,
    tool_radius: Option<f64>,
    tracker: Option<Tracker>,
    workpiece: Option<Isometry3<f64>>,
    table_reflectors: Vec<Vector3<f64>>,
    program_frames: super::ProgramFrames,
    controller: Controller,
    payload: Option<Payload>,
    mass_sd: f64,
    frame_sd: (f64, f64),
}

impl SetupBuilder {
    /// Free-text description (default empty).
    pub fn with_description(mut self, description: impl Into<String>) -> Self {
        self.description = description.into();
        self
    }

    /// The robot reference as written (default the robot's name).
    pub fn with_robot_ref(mut self, robot_ref: impl Into<String>) -> Self {
        self.robot_ref = robot_ref.into();
        self
    }

    /// The robot (the setup's other fields are kept).
    pub fn with_robot(mut self, robot: Robot) -> Self {
        self.robot = robot;
        self
    }

    /// Where the springs sit (default [`Coordinates::Axis`]).
    pub fn with_springs(mut self, springs: Coordinates) -> Self {
        self.springs = springs;
        self
    }

    /// The virtual springs of the model after the drives (default none: [`Setup::model`]).
    pub fn with_virtual_springs(mut self, springs: Vec<Spring>) -> Self {
        self.virtual_springs = springs;
        self
    }

    /// The declared candidate springs of the model comparison (default none:
    /// [`Setup::candidate_springs`]); their names must differ from the model's springs'.
    pub fn with_candidate_springs(mut self, springs: Vec<Spring>) -> Self {
        self.candidate_springs = springs;
        self
    }

    /// The loading point, flange frame, m (default the tool centre point, the setup then having
    /// no loading point: [`Setup::require_loading`]).
    pub fn with_loading_point(mut self, point: Vector3<f64>) -> Self {
        self.loading_point = Some(point);
        self
    }

    /// The measuring points, flange frame, m (1 to 100).
    pub fn with_measuring_points(mut self, points: Vec<Vector3<f64>>) -> Self {
        self.measuring_points = points;
        self
    }

    /// The tool centre point, flange frame, m (default the first measuring point).
    pub fn with_tcp(mut self, tcp: Vector3<f64>) -> Self {
        self.tcp = Some(tcp);
        self
    }

    /// The tool frame's orientation in the flange frame ([`Tool::rotation`], default identity).
    pub fn with_tcp_rotation(mut self, rotation: UnitQuaternion<f64>) -> Self {
        self.tcp_rotation = rotation;
        self
    }

    /// The load levels applied in each posture, N (positive, rising, at most 100; empty: one load,
    /// the rope load).
    pub fn with_load_steps(mut self, steps: Vec<f64>) -> Self {
        self.load_steps = steps;
        self
    }

    /// The rope load (default none: a calibration-only setup, [`Setup::require_loading`]).
    pub fn with_load(mut self, load: RopeLoad) -> Self {
        self.load = Some(load);
        self
    }

    /// The measurement noise (required).
    pub fn with_noise(mut self, noise: Noise) -> Self {
        self.noise = Some(noise);
        self
    }

    /// The experiment bounds, rad (default the robot's joint limits).
    pub fn with_bounds(mut self, bounds: JointBox) -> Self {
        self.bounds = Some(bounds);
        self
    }

    /// The nominal joint stiffness, Nm/rad (default none: [`Setup::nominal_stiffness`]).
    pub fn with_nominal_stiffness(mut self, stiffness: Vector6<f64>) -> Self {
        self.nominal_stiffness = Some(stiffness);
        self
    }

    /// The characteristic length `L` of the dexterity index (Eq. 20), m (default none:
    /// [`Setup::characteristic_length`]).
    pub fn with_characteristic_length(mut self, length: f64) -> Self {
        self.characteristic_length = Some(length);
        self
    }

    /// Test postures, axis angles, rad (default none).
    pub fn with_test_postures(mut self, postures: Vec<Vector6<f64>>) -> Self {
        self.test_postures = postures;
        self
    }

    /// Cell constraints for posture search (default none).
    pub fn with_constraints(mut self, constraints: CellConstraints) -> Self {
        self.constraints = constraints;
        self
    }

    /// The cell's floor, clearance and obstacles (default none).
    pub fn with_cell(mut self, cell: Cell) -> Self {
        self.cell = Some(cell);
        self
    }

    /// Capsule radii of the bodies, m (default [`default_geometry`](super::default_geometry)).
    pub fn with_geometry(self, geometry: RobotGeometry) -> Self {
        self.with_link_radii(geometry.link_radii)
            .with_tool_radius(geometry.tool_radius)
    }

    /// Capsule radii of the base and links 1-6, m (default the robot's: its capsule radii, or
    /// its collision shapes, else scaled to its size); given, they replace the robot's shapes.
    pub fn with_link_radii(mut self, radii: [f64; 7]) -> Self {
        self.link_radii = Some(radii);
        self
    }

    /// Capsule radius of the tool, m (default: holding every tool point).
    pub fn with_tool_radius(mut self, radius: f64) -> Self {
        self.tool_radius = Some(radius);
        self
    }

    /// The laser tracker (default none).
    pub fn with_tracker(mut self, tracker: Tracker) -> Self {
        self.tracker = Some(tracker);
        self
    }

    /// The kinematics of the controller that runs a program (default: nominal, the setup's
    /// robot) and its axes' pulses (checked by [`Self::build`] against the robot's external
    /// axes: `super::Pulses::check`).
    pub fn with_controller(mut self, controller: Controller) -> Self {
        self.controller = controller;
        self
    }

    /// A G-code program's part frame in the robot base frame, m (default none; its translation
    /// within [`limits::LENGTH_MM`]).
    pub fn with_workpiece(mut self, base_from_part: Isometry3<f64>) -> Self {
        self.workpiece = Some(base_from_part);
        self
    }

    /// A G-code program's work offsets, start and home positions ([`super::ProgramFrames`],
    /// checked when read from `[workpiece]`; default none).
    pub fn with_program_frames(mut self, frames: super::ProgramFrames) -> Self {
        self.program_frames = frames;
        self
    }

    /// Reflectors fixed on the positioner's table or, in a cell without a positioner, on the
    /// part or its fixture, the part's frame ([`Self::with_workpiece`]), m (default none; at
    /// most `limits::MAX_TABLE_REFLECTORS`, each coordinate within [`limits::LENGTH_MM`]; they
    /// need a workpiece), read as `T1`, `T2`, ... in that order: the points `select --for
    /// calibration` designs the positioner's angles for, and those the calibration locates the
    /// part from.
    pub fn with_table_reflectors(mut self, reflectors: Vec<Vector3<f64>>) -> Self {
        self.table_reflectors = reflectors;
        self
    }

    /// The tool's mass and centre of mass (default none; the mass within [0.001, 10 000] kg, the
    /// centre's coordinates within [`limits::LENGTH_MM`]).
    pub fn with_payload(mut self, payload: Payload) -> Self {
        self.payload = Some(payload);
        self
    }

    /// The relative standard deviation of every body's mass and inertia, the robot's links' and
    /// the tool's, independent between bodies (default 0: the masses taken as exact; a fraction,
    /// within `limits::MASS_SD_PERCENT` as a percentage).
    pub fn with_mass_sd(mut self, relative: f64) -> Self {
        self.mass_sd = relative;
        self
    }

    /// How far each frame of the robot model (joints 1-6 and the flange) may be from the true
    /// robot's: the standard deviation of each coordinate of its position (m) and of its
    /// orientation (rad), independent (default [`DEFAULT_FRAME_SD`]; 0 and 0 for a calibrated
    /// robot; each within [`limits::FRAME_SD`] in mm and mrad).
    pub(crate) fn with_frame_sd(mut self, position: f64, orientation: f64) -> Self {
        self.frame_sd = (position, orientation);
        self
    }

    /// The setup, every field checked against [`crate::common::limits`] and the others.
    ///
    /// # Errors
    /// [`Error::InvalidField`](crate::Error::InvalidField) naming the field as a setup file names it (unit in the name, the
    /// value given in that unit) for a missing required field, an empty name, a number that is not
    /// finite or outside its documented range, no measuring point or no noise level (or more than
    /// their limits), bounds not below each other, and an inconsistent cell (a box `carried_by` no
    /// positioner axis of the robot's) or tracker ([`Cell`],
    /// [`Tracker`]) or virtual springs (`crate::model::check_springs`); [`Error::OutsideBox`](crate::Error::OutsideBox) with the field, the value and the range for bounds or
    /// test postures outside the robot's limits.
    pub fn build(self) -> Result<Setup> {
        if self.name.trim().is_empty() {
            return Err(invalid("name", "expected a non-empty name"));
        }
        let missing: Vec<&'static str> = [
            ("loading", self.load.is_none()),
            ("tool.loading_point_mm", self.loading_point.is_none()),
        ]
        .into_iter()
        .filter_map(|(field, absent)| absent.then_some(field))
        .collect();
        let noise = required(self.noise, "noise")?;
        check_scales(self.characteristic_length, self.nominal_stiffness.as_ref())?;
        let tcp = self.tcp.or(self.measuring_points.first().copied());
        let loading_point = (self.loading_point.or(tcp)).unwrap_or_default();
        check_tool(&loading_point, &self.measuring_points, tcp)?;
        check_positioner(&self.robot, &tcp.unwrap_or_default())?;
        // No load: a calibration-only setup, whose rope load is zero ([`Setup::require_loading`]).
        let load = self.load.unwrap_or(RopeLoad {
            load: 0.0,
            anchor: Vector3::zeros(),
        });
        if !missing.contains(&"loading") {
            check_load(&load)?;
        }
        check_load_steps(&self.load_steps)?;
        check_noise(&noise)?;
        let bounds = self.bounds.map_or_else(|| robot_bounds(&self.robot), Ok)?;
        check_bounds(&bounds, &self.robot)?;
        check_test_postures(&self.test_postures, &self.robot)?;
        if let Some(z) = self.constraints.loading_point_min_z {
            check_scaled(
                "constraints.loading_point_min_z_mm",
                &[z],
                1e3,
                &limits::LENGTH_MM,
            )?;
        }
        if let Some(c) = &self.cell {
            cell::check_cell(c)?;
            super::carried::check_carried(c, &self.robot)?;
        }
        let model = Model::new(self.springs, self.virtual_springs)?;
        model.with(&self.candidate_springs)?;
        crate::model::check_declared_names(&self.candidate_springs)?;
        let tool = Tool {
            loading_point,
            measuring_points: self.measuring_points,
            tcp: tcp.unwrap_or_default(),
            rotation: self.tcp_rotation,
        };
        let (shapes, geometry) =
            robot_geometry(&self.robot, (self.link_radii, self.tool_radius), &tool)?;
        let reflectors = (self.workpiece.as_ref(), self.table_reflectors.as_slice());
        check_part_and_tool(reflectors, self.payload.as_ref())?;
        check_accuracy(self.frame_sd, self.mass_sd)?;
        if let Some(pulses) = &self.controller.pulses {
            pulses.check(self.robot.external().map_or(0, |a| a.len()))?;
        }
        self.controller.program.check(&self.robot)?;
        let tracker = self
            .tracker
            .map(|t| cell::checked_tracker(t, tool.measuring_points.len(), self.cell.as_ref()))
            .transpose()?;
        Ok(Setup {
            name: self.name,
            description: self.description,
            robot_ref: self.robot_ref,
            arm: Arm {
                robot: self.robot,
                tool,
                tcp_given: self.tcp.is_some(),
                model,
                payload: self.payload,
                mass_sd: self.mass_sd,
                frame_sd: self.frame_sd,
                geometry,
                shapes,
            },
            experiment: Experiment {
                load,
                missing,
                load_steps: self.load_steps,
                noise,
                bounds,
                test_postures: self.test_postures,
                nominal_stiffness: self.nominal_stiffness,
                characteristic_length: self.characteristic_length,
                candidate_springs: self.candidate_springs,
            },
            workcell: Workcell {
                constraints: self.constraints,
                cell: self.cell,
                tracker,
                workpiece: self.workpiece,
                table_reflectors: self.table_reflectors,
                program_frames: self.program_frames,
                controller: self.controller,
            },
            notes: Vec::new(),
        })
    }
}

/// The robot's bodies and geometry for the collision checks: the setup's `(link_radii,
/// tool_radius)`, else the robot's capsules, else the defaults for the robot and the tool.
fn robot_geometry(
    robot: &Robot,
    (link_radii, tool_radius): (Option<[f64; 7]>, Option<f64>),
    tool: &Tool,
) -> Result<(Bodies, RobotGeometry)> {
    let defaults = super::default_geometry(robot, tool);
    let shapes = match (robot.bodies(), link_radii) {
        (Bodies::Shapes(s), None) => Bodies::Shapes(s.clone()),
        (Bodies::Missing(m), None) => Bodies::Missing(m.clone()),
        _ => Bodies::Scaled,
    };
    let robot_radii = match robot.bodies() {
        Bodies::Capsules(r) => Some(*r),
        _ => None,
    };
    let geometry = RobotGeometry {
        link_radii: link_radii.or(robot_radii).unwrap_or(defaults.link_radii),
        tool_radius: tool_radius.unwrap_or(defaults.tool_radius),
    };
    cell::check_geometry(&geometry)?;
    Ok((shapes, geometry))
}

/// The workpiece frame's position, the table reflectors and the tool's mass within their
/// limits.
fn check_part_and_tool(
    (workpiece, reflectors): (Option<&Isometry3<f64>>, &[Vector3<f64>]),
    payload: Option<&Payload>,
) -> Result<()> {
    if let Some(w) = workpiece {
        let xyz = w.translation.vector;
        let field = "workpiece.base_from_part.xyz_mm";
        check_scaled(field, xyz.as_slice(), 1e3, &limits::LENGTH_MM)?;
    }
    check_table_reflectors(reflectors, workpiece.is_some())?;
    if let Some(p) = payload {
        limits::check("tool.mass_kg", &[p.mass], &limits::TOOL_MASS_KG)?;
        check_points("tool.centre_of_mass_mm", std::slice::from_ref(&p.centre))?;
        let six = crate::robot::dynamics::body::components(&p.inertia);
        limits::check("tool.inertia_kg_m2", &six, &limits::INERTIA_KG_M2)?;
        crate::robot::dynamics::body::physical(&p.inertia).map_err(|message| {
            crate::Error::InvalidField {
                field: "tool.inertia_kg_m2".into(),
                message,
            }
        })?;
    }
    Ok(())
}

/// The experiment's bounds a setup without `[bounds]` takes: the robot's joint limits, each
/// finite.
///
/// # Errors
/// [`crate::Error::InvalidField`] (`bounds`) naming the first unlimited joint.
fn robot_bounds(robot: &Robot) -> Result<JointBox> {
    let b = *robot.limits();
    match (0..6).find(|&i| !(b.lower[i].is_finite() && b.upper[i].is_finite())) {
        None => Ok(b),
        Some(i) => Err(invalid(
            "bounds",
            format!(
                "missing: the robot's joint {} has no limits (a continuous joint, or a revolute \
                 joint without <limit> in its URDF), and the postures need a range: give the \
                 experiment's [bounds] lower_deg and upper_deg",
                i + 1
            ),
        )),
    }
}
