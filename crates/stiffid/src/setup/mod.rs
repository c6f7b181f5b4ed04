//! The experimental cell: robot, tool, spring placement, loading, noise, bounds, nominal stiffness.
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
//! # mass_kg = 12.5                       # optional, with centre_of_mass_mm: the spindle's weight
//! # centre_of_mass_mm = [0, 0, 120]      # joins the process wrench in compensate
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
//! [`crate::machining`]):
//! ```toml
//! [workpiece]
//! base_from_part = { xyz_mm = [1300, -300, 400], rpy_deg = [0, 0, 0] }
//! ```
//!
//! In code, [`Setup::builder`] takes the same fields in SI units and checks them as the file's
//! ([`SetupBuilder::build`]); [`parse`] reads the file through it.

mod cell;
mod file;
pub mod load_steps;
pub mod plausibility;
pub mod prior;
pub mod reference;

pub use cell::{
    default_geometry, Cell, Obstacle, RobotGeometry, Tracker, DEFAULT_RADIUS_FRACTIONS,
    MAX_LENGTH_MM, MAX_OBSTACLES,
};
pub use file::{
    builtin, builtin_names, builtin_text, parse, parse_with, RobotRequest, MAX_PACKAGE_PATHS,
};

use crate::common::limits::joint_box::distinct;
use crate::common::limits::{self, JointBox};
use crate::model::{Compliance, Model, Spring};
use crate::robot::collision::CollisionGeometry;
use crate::robot::kinematics::{Coordinates, Frames};
use crate::robot::Bodies;
use crate::setup::load_steps::StepWeights;
use crate::{Error, Result, Robot};
use nalgebra::{Isometry3, Vector3, Vector6};

/// Points of the tool, in the flange frame, m.
#[derive(Debug, Clone, PartialEq)]
pub struct Tool {
    /// Where the load is applied.
    pub loading_point: Vector3<f64>,
    /// Where the displacements are measured (at least one).
    pub measuring_points: Vec<Vector3<f64>>,
    /// The tool centre point whose Jacobian gives the dexterity index.
    pub tcp: Vector3<f64>,
}

impl Tool {
    /// Every point of the tool, flange frame, m: the loading point, the measuring points, the
    /// tool centre point.
    pub fn points(&self) -> impl Iterator<Item = &Vector3<f64>> {
        std::iter::once(&self.loading_point)
            .chain(&self.measuring_points)
            .chain(std::iter::once(&self.tcp))
    }
}

/// The tool's mass and centre of mass (a spindle), `[tool] mass_kg` and `centre_of_mass_mm`: its
/// weight, `m g` down the base frame's -z (the base z axis taken as vertical, up), acts on the
/// robot with the process wrench ([`Payload::wrench`]), and a generated robot program states it
/// (KRL `$LOAD`, RAPID `tooldata`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Payload {
    /// The mass, kg (within [`limits::TOOL_MASS_KG`]).
    pub mass: f64,
    /// The centre of mass, flange frame, m.
    pub centre: Vector3<f64>,
}

/// Standard gravity, m/s^2 (CGPM 1901).
pub const GRAVITY: f64 = 9.80665;

impl Payload {
    /// The weight's wrench `[f; m]` (N, Nm, base frame) at the tool centre point `tcp` (flange
    /// frame, m) of a flange in orientation `flange` (base frame): `f = (0, 0, -m g)`,
    /// `m = R (c - tcp) x f`.
    pub fn wrench(
        &self,
        flange: &nalgebra::UnitQuaternion<f64>,
        tcp: &Vector3<f64>,
    ) -> Vector6<f64> {
        let f = Vector3::new(0.0, 0.0, -self.mass * GRAVITY);
        let m = (flange * (self.centre - tcp)).cross(&f);
        Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z)
    }
}

/// Rope-and-mass loading: a force of magnitude `load` (N) pulling the loading point toward the rope
/// anchor (pulley), `F = G (P2 - P1) / |P2 - P1|` (Zhang et al. 2021, Section IV-A), no moment.
#[derive(Debug, Clone, PartialEq)]
pub struct RopeLoad {
    /// `G`, N.
    pub load: f64,
    /// `P2`, base frame, m.
    pub anchor: Vector3<f64>,
}

impl RopeLoad {
    /// The wrench `[f; m]` (N, Nm, base frame) at a loading point `p1` (base frame, m). A loading
    /// point at the anchor gets a zero wrench.
    pub fn wrench(&self, p1: &Vector3<f64>) -> Vector6<f64> {
        let d = self.anchor - p1;
        let n = d.norm();
        let f = if n > 0.0 {
            d * (self.load / n)
        } else {
            Vector3::zeros()
        };
        Vector6::new(f.x, f.y, f.z, 0.0, 0.0, 0.0)
    }

    /// The gradient with respect to the loading point `p1` (base frame, m) of `e . f(p1)`, f the
    /// force of [`RopeLoad::wrench`] and `e` a weight on it (per N): with `d = P2 - p1`,
    /// `u = d / |d|`, `df = -(G / |d|) (I - u u^T) dp1`, so the gradient is
    /// `-(G / |d|) (e - (u . e) u)` (per m). Zero at the anchor, where the wrench is zero.
    pub fn force_gradient(&self, p1: &Vector3<f64>, e: &Vector3<f64>) -> Vector3<f64> {
        let d = self.anchor - p1;
        let n = d.norm();
        if n == 0.0 {
            return Vector3::zeros();
        }
        let u = d / n;
        (e - u * u.dot(e)) * (-self.load / n)
    }
}

/// Laser-tracker noise: white Gaussian on every coordinate of every reading (docs/model.md, "The
/// noise convention"). A displacement is a loaded minus an unloaded reading, so its variance per
/// coordinate is twice the reading's ([`Noise::displacement_variance`]); with load steps the
/// displacement at the rope load has [`Setup::displacement_variance`].
#[derive(Debug, Clone, PartialEq)]
pub struct Noise {
    /// Variance `sigma_r^2` of one coordinate of one tracker reading at multiple 1, m^2
    /// (`[noise] reading_sd_mm` squared).
    pub reading_variance: f64,
    /// The noise levels, as multiples of the variance (Table 3: 0.5 .. 3.0).
    pub levels: Vec<f64>,
}

impl Noise {
    /// Standard deviation `sigma_r` of one coordinate of one reading at multiple 1, m.
    pub fn reading_sd(&self) -> f64 {
        self.reading_variance.sqrt()
    }

    /// Variance of one coordinate of one displacement, a loaded minus an unloaded reading, at
    /// multiple 1: `2 sigma_r^2`, m^2 (the paper's noise, Table 3, is this one).
    pub fn displacement_variance(&self) -> f64 {
        2.0 * self.reading_variance
    }

    /// Standard deviation of one coordinate of one displacement at multiple 1, m.
    pub fn displacement_sd(&self) -> f64 {
        self.displacement_variance().sqrt()
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

/// A resolved experimental setup, SI units throughout, its fields checked ([`SetupBuilder::build`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    name: String,
    description: String,
    robot_ref: String,
    robot: Robot,
    tool: Tool,
    model: Model,
    candidate_springs: Vec<Spring>,
    load: RopeLoad,
    load_steps: Vec<f64>,
    noise: Noise,
    bounds: JointBox,
    nominal_stiffness: Option<Vector6<f64>>,
    characteristic_length: Option<f64>,
    test_postures: Vec<Vector6<f64>>,
    constraints: CellConstraints,
    cell: Option<Cell>,
    geometry: RobotGeometry,
    /// The robot's shapes ([`Bodies::Shapes`]) if the cell uses them, else [`Bodies::Scaled`].
    shapes: Bodies,
    tracker: Option<Tracker>,
    workpiece: Option<Isometry3<f64>>,
    tcp_given: bool,
    payload: Option<Payload>,
    notes: Vec<crate::common::warning::Warning>,
}

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
            payload: None,
        }
    }

    /// A builder holding every field of this setup, to change some and build again.
    pub fn to_builder(&self) -> SetupBuilder {
        SetupBuilder {
            name: self.name.clone(),
            description: self.description.clone(),
            robot_ref: self.robot_ref.clone(),
            robot: self.robot.clone(),
            springs: self.model.coordinates(),
            virtual_springs: self.model.springs().to_vec(),
            candidate_springs: self.candidate_springs.clone(),
            loading_point: Some(self.tool.loading_point),
            measuring_points: self.tool.measuring_points.clone(),
            tcp: self.tcp_given.then_some(self.tool.tcp),
            load: Some(self.load.clone()),
            load_steps: self.load_steps.clone(),
            noise: Some(self.noise.clone()),
            bounds: Some(self.bounds),
            nominal_stiffness: self.nominal_stiffness,
            characteristic_length: self.characteristic_length,
            test_postures: self.test_postures.clone(),
            constraints: self.constraints.clone(),
            cell: self.cell.clone(),
            link_radii: self.shapes().is_none().then_some(self.geometry.link_radii),
            tool_radius: Some(self.geometry.tool_radius),
            tracker: self.tracker.clone(),
            workpiece: self.workpiece,
            payload: self.payload,
        }
    }

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

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// Tool points.
    pub fn tool(&self) -> &Tool {
        &self.tool
    }

    /// Where the springs sit: in the drives (axis coordinates) or on the kinematic joints.
    pub fn springs(&self) -> Coordinates {
        self.model.coordinates()
    }

    /// The elastostatic model: the drive springs and the virtual springs ([`crate::model`]);
    /// the drives alone unless the setup has a `[model]`.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The declared candidate springs (`[[model.spring]]` with `candidate = true`): not in the
    /// model, candidates of the model comparison ([`crate::identify::compare`]).
    pub fn candidate_springs(&self) -> &[Spring] {
        &self.candidate_springs
    }

    /// The nominal compliance of every parameter of the model (rad/Nm, m/N), when the setup has a
    /// nominal drive stiffness and every virtual spring one.
    pub fn model_nominal_compliance(&self) -> Option<nalgebra::DVector<f64>> {
        self.model
            .nominal_compliance(self.nominal_stiffness.as_ref()?)
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
        self.model.nominal_compliance(drives).ok_or_else(|| {
            let lacking: Vec<&str> = (self.model.springs().iter())
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

    /// The loading of the simulation and of the posture search.
    pub fn load(&self) -> &RopeLoad {
        &self.load
    }

    /// Measurement noise.
    pub fn noise(&self) -> &Noise {
        &self.noise
    }

    /// The load levels applied in each posture, N, rising (`[loading] steps_n`); empty for one
    /// load per posture, the rope load ([`crate::setup::load_steps`]).
    pub fn load_steps(&self) -> &[f64] {
        &self.load_steps
    }

    /// The variance of one displacement coordinate at the rope load, at noise level multiple 1,
    /// m^2, that gives the compliances' covariance of the design: a loaded minus an unloaded
    /// reading without load steps ([`Noise::displacement_variance`], twice the reading
    /// variance); with them, that of the displacement their readings are worth
    /// ([`crate::setup::load_steps::StepWeights::variance_factor`] times the reading variance,
    /// also 2 for one step at the rope load).
    pub fn displacement_variance(&self) -> f64 {
        match StepWeights::new(self.load.load, &self.load_steps) {
            None => self.noise.displacement_variance(),
            Some(w) => self.noise.reading_variance * w.variance_factor(),
        }
    }

    /// Notes on how the setup file said things (an old field name and what it meant), shown as
    /// warnings with the plausibility ones ([`plausibility::warnings`]).
    pub fn notes(&self) -> &[crate::common::warning::Warning] {
        &self.notes
    }

    /// Experiment bounds, axis coordinates.
    pub fn bounds(&self) -> &JointBox {
        &self.bounds
    }

    /// `n` postures drawn uniformly within the bounds from `seed` (ChaCha8), for the unit tests
    /// of the stages below the design (which draws its groups with [`crate::design::random_group`]).
    #[cfg(test)]
    pub(crate) fn random_postures(&self, n: usize, seed: u64) -> Vec<Vector6<f64>> {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let (lower, upper) = (&self.bounds.lower, &self.bounds.upper);
        (0..n)
            .map(|_| Vector6::from_fn(|j, _| rng.random_range(lower[j]..=upper[j])))
            .collect()
    }

    /// Nominal (or true, in simulation) joint stiffness, Nm/rad, if the setup gives one. The
    /// criteria scaled by it (relative-a, d-optimal, scaled-cond), the predicted deviation rates,
    /// simulation and the study need it; [`Setup::try_nominal_stiffness`] says so when it is
    /// missing.
    pub fn nominal_stiffness(&self) -> Option<&Vector6<f64>> {
        self.nominal_stiffness.as_ref()
    }

    /// The nominal joint stiffness, Nm/rad, for `needed_by` (a criterion or computation, named
    /// in the error).
    ///
    /// # Errors
    /// [`Error::MissingField`] (`nominal_stiffness_nm_per_rad`) naming `needed_by`, with where a
    /// value comes from.
    pub fn try_nominal_stiffness(&self, needed_by: &str) -> Result<&Vector6<f64>> {
        self.nominal_stiffness().ok_or_else(|| Error::MissingField {
            field: "nominal_stiffness_nm_per_rad",
            needed_by: needed_by.to_string(),
        })
    }

    /// Characteristic length `L` of the dexterity index (Eq. 20), m, if the setup gives one (the
    /// classical and zhang2021 criteria need it).
    pub fn characteristic_length(&self) -> Option<f64> {
        self.characteristic_length
    }

    /// The characteristic length, m, for `needed_by` (named in the error).
    ///
    /// # Errors
    /// [`Error::MissingField`] (`characteristic_length_mm`) naming `needed_by`, with where a value
    /// comes from.
    pub fn try_characteristic_length(&self, needed_by: &str) -> Result<f64> {
        self.characteristic_length
            .ok_or_else(|| Error::MissingField {
                field: "characteristic_length_mm",
                needed_by: needed_by.to_string(),
            })
    }

    /// Test (validation) postures, axis angles, rad.
    pub fn test_postures(&self) -> &[Vector6<f64>] {
        &self.test_postures
    }

    /// Optional cell constraints for posture search.
    pub fn constraints(&self) -> &CellConstraints {
        &self.constraints
    }

    /// The floor, clearance and obstacles; `None`: no body checks (the paper's study).
    pub fn cell(&self) -> Option<&Cell> {
        self.cell.as_ref()
    }

    /// Capsule radii of the robot and tool bodies: the setup's `[robot_geometry]`, else the
    /// robot's ([`Bodies::Capsules`]), else scaled to the robot's size. The robot's capsules are
    /// its bodies in the cell unless [`Setup::shapes`] has its own; the tool's always are.
    pub fn geometry(&self) -> &RobotGeometry {
        &self.geometry
    }

    /// The robot's collision shapes (a URDF's `<collision>` elements, [`Bodies::Shapes`]) that
    /// the cell's checks and drawings use for the base and links 1-6; `None`: capsules
    /// ([`Setup::geometry`]), also when the setup gives `[robot_geometry] link_radius_mm`, the
    /// user's override.
    pub fn shapes(&self) -> Option<&CollisionGeometry> {
        match &self.shapes {
            Bodies::Shapes(s) => Some(s),
            _ => None,
        }
    }

    /// Whether the cell's body checks (a `[cell]`, a `[tracker]`'s line of sight) have the robot's
    /// bodies: a URDF whose collision meshes were not found ([`Bodies::Missing`]) serves
    /// everything else, not these checks.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`[cell]` or `[tracker]`) naming the mesh not found and how to give
    /// it (`--package-path`, the setup's `package_paths`) or to do without it
    /// (`[robot_geometry] link_radius_mm`).
    pub fn check_bodies(&self) -> Result<()> {
        let Bodies::Missing(why) = &self.shapes else {
            return Ok(());
        };
        let field = match (&self.cell, &self.tracker) {
            (Some(_), _) => "[cell]",
            (None, Some(_)) => "[tracker]",
            (None, None) => return Ok(()),
        };
        Err(Error::InvalidField {
            field: field.into(),
            message: format!(
                "the cell's body checks need the robot's collision meshes ({why}); give the \
                 directory that holds the ROS packages with --package-path DIR (Python: \
                 package_paths) or the setup's package_paths, or capsule radii as \
                 [robot_geometry] link_radius_mm"
            ),
        })
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
        })
    }

    /// The laser tracker, for the line-of-sight and incidence checks.
    pub fn tracker(&self) -> Option<&Tracker> {
        self.tracker.as_ref()
    }

    /// Whether the tool centre point was given (`[tool] tcp_mm`), not taken from measuring
    /// point 1.
    pub fn tcp_given(&self) -> bool {
        self.tcp_given
    }

    /// The tool's mass and centre of mass, if given.
    pub fn payload(&self) -> Option<&Payload> {
        self.payload.as_ref()
    }

    /// `[workpiece] base_from_part`: a G-code program's part frame in the robot base frame, m.
    pub fn workpiece(&self) -> Option<&Isometry3<f64>> {
        self.workpiece.as_ref()
    }

    /// The nominal compliance `h = 1 / k` (Eq. 8), rad/Nm, if the setup gives a nominal
    /// stiffness.
    pub fn nominal_compliance(&self) -> Option<Vector6<f64>> {
        self.nominal_stiffness.map(|k| k.map(|k| 1.0 / k))
    }

    /// The same setup without the cell's checks (no `[cell]`, `[tracker]` or `[constraints]`):
    /// what the unconstrained optimum is searched on, to show what feasibility costs.
    pub fn without_cell(&self) -> Setup {
        Setup {
            cell: None,
            tracker: None,
            constraints: CellConstraints::default(),
            ..self.clone()
        }
    }

    /// The rope-mass wrench on the loading point of a posture, base frame.
    pub fn rope_wrench(&self, frames: &Frames) -> Vector6<f64> {
        self.load.wrench(&frames.point(&self.tool.loading_point))
    }
}

/// Builds a [`Setup`] from SI values (m, rad, N, Nm/rad, m^2), argmin-style: `with_*` setters,
/// then [`SetupBuilder::build`] checks every field as a setup file's are checked.
///
/// ```
/// use nalgebra::{Vector3, Vector6};
/// use stiffid::setup::{Noise, RopeLoad, Setup};
///
/// let robot = stiffid::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
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
    payload: Option<Payload>,
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

    /// The loading point, flange frame, m (required).
    pub fn with_loading_point(mut self, point: Vector3<f64>) -> Self {
        self.loading_point = Some(point);
        self
    }

    /// The measuring points, flange frame, m (1 to [`limits::MAX_MEASURING_POINTS`]).
    pub fn with_measuring_points(mut self, points: Vec<Vector3<f64>>) -> Self {
        self.measuring_points = points;
        self
    }

    /// The tool centre point, flange frame, m (default the first measuring point).
    pub fn with_tcp(mut self, tcp: Vector3<f64>) -> Self {
        self.tcp = Some(tcp);
        self
    }

    /// The load levels applied in each posture, N (positive, rising, at most
    /// [`crate::setup::load_steps::MAX_STEPS`]; empty: one load, the rope load).
    pub fn with_load_steps(mut self, steps: Vec<f64>) -> Self {
        self.load_steps = steps;
        self
    }

    /// The rope load (required).
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

    /// Capsule radii of the bodies, m (default [`default_geometry`]).
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

    /// A G-code program's part frame in the robot base frame, m (default none; its translation
    /// within [`limits::LENGTH_MM`]).
    pub fn with_workpiece(mut self, base_from_part: Isometry3<f64>) -> Self {
        self.workpiece = Some(base_from_part);
        self
    }

    /// The tool's mass and centre of mass (default none; the mass within [`limits::TOOL_MASS_KG`],
    /// the centre's coordinates within [`limits::LENGTH_MM`]).
    pub fn with_payload(mut self, payload: Payload) -> Self {
        self.payload = Some(payload);
        self
    }

    /// The setup, every field checked against [`crate::common::limits`] and the others.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the field as a setup file names it (unit in the name, the
    /// value given in that unit) for a missing required field, an empty name, a number that is not
    /// finite or outside its documented range, no measuring point or no noise level (or more than
    /// their limits), bounds not below each other, and an inconsistent cell or tracker ([`Cell`],
    /// [`Tracker`]) or virtual springs ([`crate::model::check_springs`]); [`Error::OutsideBox`] with the field, the value and the range for bounds or
    /// test postures outside the robot's limits.
    pub fn build(self) -> Result<Setup> {
        if self.name.trim().is_empty() {
            return Err(invalid("name", "expected a non-empty name"));
        }
        let loading_point = required(self.loading_point, "tool.loading_point_mm")?;
        let load = required(self.load, "loading")?;
        let noise = required(self.noise, "noise")?;
        if let Some(l) = self.characteristic_length {
            check_scaled(
                "characteristic_length_mm",
                &[l],
                1e3,
                &limits::CHARACTERISTIC_LENGTH_MM,
            )?;
        }
        if let Some(k) = &self.nominal_stiffness {
            limits::check(
                "nominal_stiffness_nm_per_rad",
                k.as_slice(),
                &limits::STIFFNESS_NM_PER_RAD,
            )?;
        }
        let tcp = self.tcp.or(self.measuring_points.first().copied());
        check_tool(&loading_point, &self.measuring_points, tcp)?;
        check_load(&load)?;
        check_load_steps(&self.load_steps)?;
        check_noise(&noise)?;
        let bounds = self.bounds.unwrap_or(*self.robot.limits());
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
        }
        let model = Model::new(self.springs, self.virtual_springs)?;
        model.with(&self.candidate_springs)?;
        let tool = Tool {
            loading_point,
            measuring_points: self.measuring_points,
            tcp: tcp.unwrap_or_default(),
        };
        let defaults = cell::default_geometry(&self.robot, &tool);
        let shapes = match (&self.robot.bodies(), self.link_radii) {
            (Bodies::Shapes(s), None) => Bodies::Shapes(s.clone()),
            (Bodies::Missing(m), None) => Bodies::Missing(m.clone()),
            _ => Bodies::Scaled,
        };
        let robot_radii = match &self.robot.bodies() {
            Bodies::Capsules(r) => Some(*r),
            _ => None,
        };
        let geometry = RobotGeometry {
            link_radii: self
                .link_radii
                .or(robot_radii)
                .unwrap_or(defaults.link_radii),
            tool_radius: self.tool_radius.unwrap_or(defaults.tool_radius),
        };
        cell::check_geometry(&geometry)?;
        if let Some(w) = &self.workpiece {
            let xyz = w.translation.vector;
            let field = "workpiece.base_from_part.xyz_mm";
            check_scaled(field, xyz.as_slice(), 1e3, &limits::LENGTH_MM)?;
        }
        if let Some(p) = &self.payload {
            limits::check("tool.mass_kg", &[p.mass], &limits::TOOL_MASS_KG)?;
            check_points("tool.centre_of_mass_mm", std::slice::from_ref(&p.centre))?;
        }
        let tracker = self
            .tracker
            .map(|t| cell::checked_tracker(t, tool.measuring_points.len(), self.cell.as_ref()))
            .transpose()?;
        Ok(Setup {
            name: self.name,
            description: self.description,
            robot_ref: self.robot_ref,
            robot: self.robot,
            tool,
            model,
            candidate_springs: self.candidate_springs,
            load,
            load_steps: self.load_steps,
            noise,
            bounds,
            nominal_stiffness: self.nominal_stiffness,
            characteristic_length: self.characteristic_length,
            test_postures: self.test_postures,
            constraints: self.constraints,
            cell: self.cell,
            geometry,
            shapes,
            tracker,
            workpiece: self.workpiece,
            tcp_given: self.tcp.is_some(),
            payload: self.payload,
            notes: Vec::new(),
        })
    }
}

fn invalid(field: &str, message: impl Into<String>) -> Error {
    Error::InvalidField {
        field: field.to_string(),
        message: message.into(),
    }
}

fn required<T>(value: Option<T>, field: &str) -> Result<T> {
    value.ok_or_else(|| invalid(field, "expected a value: the setup has none"))
}

/// [`limits::check`] of SI `values` against a `range` in the file's unit (`scale` per SI unit),
/// the values shown in that unit.
fn check_scaled(field: &str, values: &[f64], scale: f64, range: &limits::Range) -> Result<()> {
    let scaled: Vec<f64> = values.iter().map(|v| v * scale).collect();
    limits::check(field, &scaled, range)
}

fn check_points(field: &str, points: &[Vector3<f64>]) -> Result<()> {
    let values: Vec<f64> = points.iter().flat_map(|p| p.iter().copied()).collect();
    check_scaled(field, &values, 1e3, &limits::LENGTH_MM)
}

fn check_tool(
    loading_point: &Vector3<f64>,
    measuring_points: &[Vector3<f64>],
    tcp: Option<Vector3<f64>>,
) -> Result<()> {
    check_points("tool.loading_point_mm", std::slice::from_ref(loading_point))?;
    let n = measuring_points.len();
    limits::check_count(
        "tool.measuring_points_mm",
        n,
        1,
        limits::MAX_MEASURING_POINTS,
    )?;
    check_points("tool.measuring_points_mm", measuring_points)?;
    check_points("tool.tcp_mm", tcp.as_slice())
}

fn check_load(load: &RopeLoad) -> Result<()> {
    limits::check("loading.load_n", &[load.load], &limits::LOAD_N)?;
    check_points("loading.anchor_mm", std::slice::from_ref(&load.anchor))
}

fn check_load_steps(steps: &[f64]) -> Result<()> {
    let field = "loading.steps_n";
    limits::check_count(field, steps.len(), 0, crate::setup::load_steps::MAX_STEPS)?;
    limits::check(field, steps, &limits::LOAD_N)?;
    match steps.windows(2).position(|w| w[1] <= w[0]) {
        Some(i) => Err(invalid(
            &format!("{field}[{}]", i + 2),
            format!(
                "{} after {}: expected rising load levels",
                steps[i + 1],
                steps[i]
            ),
        )),
        None => Ok(()),
    }
}

fn check_noise(noise: &Noise) -> Result<()> {
    check_scaled(
        "noise.reading_sd_mm",
        &[noise.reading_variance.sqrt()],
        1e3,
        &limits::READING_SD_MM,
    )?;
    let levels = &noise.levels;
    limits::check_count("noise.level_multiples", levels.len(), 1, limits::MAX_LEVELS)?;
    limits::check("noise.level_multiples", levels, &limits::LEVEL_MULTIPLE)
}

fn degrees(q: &Vector6<f64>) -> Vec<f64> {
    q.iter().map(|v| v.to_degrees()).collect()
}

/// Bounds may leave the robot's limits by this, rad: the rounding of degrees to radians.
const BOUNDS_TOLERANCE: f64 = 1e-12;

fn check_bounds(bounds: &JointBox, robot: &Robot) -> Result<()> {
    let sides = [("lower_deg", &bounds.lower), ("upper_deg", &bounds.upper)];
    for (side, q) in sides {
        limits::check(&format!("bounds.{side}"), &degrees(q), &limits::ANGLE_DEG)?;
    }
    if let Some(i) = (0..6).find(|&i| bounds.lower[i] >= bounds.upper[i]) {
        let (l, u) = (bounds.lower[i].to_degrees(), bounds.upper[i].to_degrees());
        return Err(invalid(
            &format!("bounds.lower_deg[{}]", i + 1),
            format!(
                "{} deg is not below bounds.upper_deg[{}] = {u:.2} deg",
                distinct(l, u, u),
                i + 1
            ),
        ));
    }
    let within = robot.limits().widened(BOUNDS_TOLERANCE);
    for (side, q) in sides {
        within.check(q, "the robot's limits", |a| {
            format!("bounds.{side}[{}]", a + 1)
        })?;
    }
    Ok(())
}

fn check_test_postures(postures: &[Vector6<f64>], robot: &Robot) -> Result<()> {
    let n = postures.len();
    limits::check_count("test.postures_deg", n, 0, limits::MAX_TEST_POSTURES)?;
    for (i, q) in postures.iter().enumerate() {
        let field = format!("test.postures_deg[{}]", i + 1);
        limits::check(&field, &degrees(q), &limits::ANGLE_DEG)?;
        let axis = |a: usize| format!("{field}[{}]", a + 1);
        robot.limits().check(q, "the robot's limits", axis)?;
    }
    Ok(())
}
