//! The experimental cell: robot, tool, spring placement, loading, noise, bounds, nominal stiffness.
//!
//! A setup is written in TOML with units in the field names; unknown keys are rejected:
//! ```toml
//! name = "zhang2021-comau-nj165"
//! description = "what this cell is"
//! robot = "comau-smart5-nj165-3.0"       # a preset name, or a robot .toml / .urdf file
//! # robot_tip = "tool0"                  # URDF only: the tip link
//! # [robot_base]                         # optional: the robot on a pedestal, in the cell frame
//! # xyz_mm = [0, 0, 500]                 # (before the robot's own base transform)
//! # rpy_deg = [0, 0, 0]                  # fixed-axis roll, pitch, yaw as URDF
//! # [robot_flange]                       # optional: an adapter plate after the flange
//! # xyz_mm = [0, 0, 20]
//! springs = "axis"                       # or "kinematic": where the joint springs sit
//! characteristic_length_mm = 1200.0      # L of the dexterity index (Eq. 20)
//! nominal_stiffness_nm_per_rad = [950000, 3000000, 900000, 250000, 200000, 150000]
//! [tool]                                 # points in the flange frame
//! loading_point_mm = [150, 0, 200]
//! measuring_points_mm = [[80, 80, 260], [-80, 80, 260]]
//! # tcp_mm = [80, 80, 260]               # for the dexterity index; default measuring point 1
//! [loading]                              # rope and mass over a pulley
//! load_n = 500.0
//! anchor_mm = [1500, 1500, 0]            # base frame
//! [noise]
//! variance_mm2 = 9.23e-5                 # per measured coordinate
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
//! and optionally the physical cell, `[cell]`, `[robot_geometry]` and `[tracker]` (see [`Cell`]).

mod cell;

pub use cell::{Cell, Obstacle, RobotGeometry, Tracker, MAX_LENGTH_MM, MAX_OBSTACLES};

use crate::kinematics::{Coordinates, Frames};
use crate::limits::{self, check_in};
use crate::robot::file::{transform, TransformFile};
use crate::{Error, Result, Robot};
use nalgebra::{Vector3, Vector6};
use serde::Deserialize;

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

/// Laser-tracker noise: white Gaussian on every measured coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Noise {
    /// Variance `sigma^2` of one coordinate at multiple 1, m^2.
    pub variance: f64,
    /// The noise levels, as multiples of the variance (Table 3: 0.5 .. 3.0).
    pub levels: Vec<f64>,
}

impl Noise {
    /// Standard deviation `sigma` at multiple 1, m.
    pub fn sigma(&self) -> f64 {
        self.variance.sqrt()
    }
}

/// Box bounds on the axis angles of the experiment postures, rad (Table 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Bounds {
    /// Lower bounds, rad.
    pub lower: Vector6<f64>,
    /// Upper bounds, rad.
    pub upper: Vector6<f64>,
}

impl Bounds {
    /// Whether every angle of `q` (rad) lies within the bounds (inclusive).
    pub fn contains(&self, q: &Vector6<f64>) -> bool {
        (0..6).all(|i| q[i] >= self.lower[i] && q[i] <= self.upper[i])
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

/// A resolved experimental setup, SI units throughout.
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    /// Short name, e.g. `zhang2021-comau-nj165`.
    pub name: String,
    /// What this cell is, free text.
    pub description: String,
    /// The robot reference as written (preset name or file).
    pub robot_ref: String,
    /// The robot.
    pub robot: Robot,
    /// Tool points.
    pub tool: Tool,
    /// Where the springs sit: in the drives (axis coordinates) or on the kinematic joints.
    pub springs: Coordinates,
    /// The loading of the simulation and of the posture search.
    pub load: RopeLoad,
    /// Measurement noise.
    pub noise: Noise,
    /// Experiment bounds, axis coordinates.
    pub bounds: Bounds,
    /// Nominal (or true, in simulation) joint stiffness, Nm/rad.
    pub nominal_stiffness: Vector6<f64>,
    /// Characteristic length `L` of the dexterity index, m.
    pub characteristic_length: f64,
    /// Test (validation) postures, axis angles, rad.
    pub test_postures: Vec<Vector6<f64>>,
    /// Optional cell constraints for posture search.
    pub constraints: CellConstraints,
    /// The floor, clearance and obstacles; `None`: no body checks (the paper's study).
    pub cell: Option<Cell>,
    /// Capsule radii of the robot and tool bodies (defaults scaled to the robot's size).
    pub geometry: RobotGeometry,
    /// The laser tracker, for the line-of-sight and incidence checks.
    pub tracker: Option<Tracker>,
}

impl Setup {
    /// The nominal compliance `h = 1 / k` (Eq. 8), rad/Nm.
    pub fn nominal_compliance(&self) -> Vector6<f64> {
        self.nominal_stiffness.map(|k| 1.0 / k)
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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SetupFile {
    name: String,
    #[serde(default)]
    description: String,
    robot: String,
    robot_tip: Option<String>,
    robot_base: Option<TransformFile>,
    robot_flange: Option<TransformFile>,
    #[serde(default)]
    springs: Coordinates,
    characteristic_length_mm: f64,
    nominal_stiffness_nm_per_rad: [f64; 6],
    tool: ToolFile,
    loading: LoadingFile,
    noise: NoiseFile,
    bounds: BoundsFile,
    test: Option<TestFile>,
    constraints: Option<ConstraintsFile>,
    cell: Option<cell::CellFile>,
    robot_geometry: Option<cell::GeometryFile>,
    tracker: Option<cell::TrackerFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ToolFile {
    loading_point_mm: [f64; 3],
    measuring_points_mm: Vec<[f64; 3]>,
    tcp_mm: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoadingFile {
    load_n: f64,
    anchor_mm: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct NoiseFile {
    variance_mm2: f64,
    level_multiples: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BoundsFile {
    lower_deg: [f64; 6],
    upper_deg: [f64; 6],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TestFile {
    postures_deg: Vec<[f64; 6]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ConstraintsFile {
    loading_point_min_z_mm: Option<f64>,
    #[serde(default)]
    anchor_below_loading_point: bool,
}

/// The built-in setups: `(name, TOML)`.
const BUILTIN: &crate::builtin::Table = &[
    (
        "zhang2021-comau-nj165",
        include_str!("../setups/zhang2021-comau-nj165.toml"),
    ),
    (
        "fanuc-r2000ic-165f",
        include_str!("../setups/fanuc-r2000ic-165f.toml"),
    ),
];

/// Names of the built-in setups.
pub fn builtin_names() -> impl Iterator<Item = &'static str> {
    crate::builtin::names(BUILTIN)
}

/// The TOML text of a built-in setup.
///
/// # Errors
/// [`Error::Unknown`] if no built-in setup has this name.
pub fn builtin_text(name: &str) -> Result<&'static str> {
    crate::builtin::text(BUILTIN, "setup", name)
}

/// A built-in setup, its robot taken from the presets.
///
/// # Errors
/// [`Error::Unknown`] if no built-in setup has this name.
pub fn builtin(name: &str) -> Result<Setup> {
    parse(builtin_text(name)?, &format!("setup {name}"), |r, _| {
        crate::robot::presets::get(r)
    })
}

/// Parses a setup TOML. `source_name` (the file name) is used in errors; `resolve_robot` turns the
/// `robot` field (and the optional `robot_tip`) into a [`Robot`] (a preset, or a file the caller
/// reads).
///
/// # Errors
/// [`Error::Parse`] for malformed TOML, unknown or missing keys and wrong types;
/// [`Error::InvalidField`] naming the field and the value for an empty name, a number that is not
/// finite or outside its documented range ([`crate::limits`]: for example a stiffness outside
/// [`limits::STIFFNESS_NM_PER_RAD`]), no measuring point or no noise level (or more than their
/// limits), bounds outside the robot's limits or test postures outside them; whatever
/// `resolve_robot` returns.
pub fn parse<F>(text: &str, source_name: &str, resolve_robot: F) -> Result<Setup>
where
    F: FnOnce(&str, Option<&str>) -> Result<Robot>,
{
    let file: SetupFile = toml::from_str(text).map_err(|e| Error::Parse {
        source_name: source_name.to_string(),
        message: limits::one_line(&e.to_string()),
    })?;
    let robot = resolve_robot(&file.robot, file.robot_tip.as_deref())?;
    let robot = mounted(robot, &file, source_name)?;
    build(file, robot, source_name)
}

/// The robot with the setup's offsets: `[robot_base]` places the robot's base frame in the cell
/// (a pedestal: results are then in the cell frame), before the robot's own base transform;
/// `[robot_flange]` adds an adapter plate after its flange. Either is `xyz_mm` and `rpy_deg`
/// (fixed-axis roll, pitch, yaw as URDF), the same as a robot TOML's `[base]` and `[flange]`.
fn mounted(mut robot: Robot, f: &SetupFile, src: &str) -> Result<Robot> {
    if f.robot_base.is_some() {
        robot.base = transform(f.robot_base, "robot_base", src)? * robot.base;
    }
    if f.robot_flange.is_some() {
        robot.flange *= transform(f.robot_flange, "robot_flange", src)?;
    }
    Ok(robot)
}

fn field_error(source_name: &str, field: &str, message: impl Into<String>) -> Error {
    Error::InvalidField {
        field: format!("{source_name}: {field}"),
        message: message.into(),
    }
}

fn mm(v: &[f64; 3]) -> Vector3<f64> {
    Vector3::new(v[0], v[1], v[2]) * 1e-3
}

fn deg6(v: &[f64; 6]) -> Vector6<f64> {
    Vector6::from_iterator(v.iter().map(|d| d.to_radians()))
}

fn check_count(src: &str, field: &str, count: usize, min: usize, max: usize) -> Result<()> {
    limits::check_count(&format!("{src}: {field}"), count, min, max)
}

/// Checks every field of a setup file against the documented limits ([`crate::limits`]).
fn check_fields(f: &SetupFile, src: &str) -> Result<()> {
    if f.name.trim().is_empty() {
        return Err(field_error(src, "name", "expected a non-empty name"));
    }
    check_in(
        src,
        "characteristic_length_mm",
        &[f.characteristic_length_mm],
        &limits::CHARACTERISTIC_LENGTH_MM,
    )?;
    check_in(
        src,
        "nominal_stiffness_nm_per_rad",
        &f.nominal_stiffness_nm_per_rad,
        &limits::STIFFNESS_NM_PER_RAD,
    )?;
    let length = &limits::LENGTH_MM;
    check_in(
        src,
        "tool.loading_point_mm",
        &f.tool.loading_point_mm,
        length,
    )?;
    let points = &f.tool.measuring_points_mm;
    check_count(
        src,
        "tool.measuring_points_mm",
        points.len(),
        1,
        limits::MAX_MEASURING_POINTS,
    )?;
    check_in(
        src,
        "tool.measuring_points_mm",
        points.as_flattened(),
        length,
    )?;
    check_in(
        src,
        "tool.tcp_mm",
        &f.tool.tcp_mm.unwrap_or_default(),
        length,
    )?;
    check_in(src, "loading.load_n", &[f.loading.load_n], &limits::LOAD_N)?;
    check_in(src, "loading.anchor_mm", &f.loading.anchor_mm, length)?;
    check_in(
        src,
        "noise.variance_mm2",
        &[f.noise.variance_mm2],
        &limits::VARIANCE_MM2,
    )?;
    let levels = &f.noise.level_multiples;
    check_count(
        src,
        "noise.level_multiples",
        levels.len(),
        1,
        limits::MAX_LEVELS,
    )?;
    check_in(
        src,
        "noise.level_multiples",
        levels,
        &limits::LEVEL_MULTIPLE,
    )?;
    if let Some(t) = &f.test {
        let n = t.postures_deg.len();
        check_count(src, "test.postures_deg", n, 0, limits::MAX_TEST_POSTURES)?;
    }
    if let Some(z) = f
        .constraints
        .as_ref()
        .and_then(|c| c.loading_point_min_z_mm)
    {
        check_in(src, "constraints.loading_point_min_z_mm", &[z], length)?;
    }
    Ok(())
}

fn build(f: SetupFile, robot: Robot, src: &str) -> Result<Setup> {
    check_fields(&f, src)?;
    let bounds = bounds(&f.bounds, &robot, src)?;
    let test_postures = match &f.test {
        None => Vec::new(),
        Some(t) => test_postures(&t.postures_deg, &robot, src)?,
    };
    let measuring_points: Vec<_> = f.tool.measuring_points_mm.iter().map(mm).collect();
    let constraints = f
        .constraints
        .map_or(CellConstraints::default(), |c| CellConstraints {
            loading_point_min_z: c.loading_point_min_z_mm.map(|z| z * 1e-3),
            anchor_below_loading_point: c.anchor_below_loading_point,
        });
    let tool = Tool {
        loading_point: mm(&f.tool.loading_point_mm),
        tcp: f.tool.tcp_mm.as_ref().map_or(measuring_points[0], mm),
        measuring_points,
    };
    let cell = f.cell.map(|c| cell::cell(c, src)).transpose()?;
    let defaults = crate::cell::default_geometry(&robot, &tool);
    let geometry = cell::geometry(f.robot_geometry, defaults, src)?;
    let tracker = f
        .tracker
        .map(|t| cell::tracker(t, tool.measuring_points.len(), cell.as_ref(), src))
        .transpose()?;
    Ok(Setup {
        name: f.name,
        description: f.description,
        robot_ref: f.robot,
        robot,
        tool,
        springs: f.springs,
        load: RopeLoad {
            load: f.loading.load_n,
            anchor: mm(&f.loading.anchor_mm),
        },
        noise: Noise {
            variance: f.noise.variance_mm2 * 1e-6,
            levels: f.noise.level_multiples,
        },
        bounds,
        nominal_stiffness: Vector6::from_column_slice(&f.nominal_stiffness_nm_per_rad),
        characteristic_length: f.characteristic_length_mm * 1e-3,
        test_postures,
        constraints,
        cell,
        geometry,
        tracker,
    })
}

fn bounds(b: &BoundsFile, robot: &Robot, src: &str) -> Result<Bounds> {
    check_in(src, "bounds.lower_deg", &b.lower_deg, &limits::ANGLE_DEG)?;
    check_in(src, "bounds.upper_deg", &b.upper_deg, &limits::ANGLE_DEG)?;
    let bounds = Bounds {
        lower: deg6(&b.lower_deg),
        upper: deg6(&b.upper_deg),
    };
    for i in 0..6 {
        if bounds.lower[i] >= bounds.upper[i] {
            return Err(field_error(
                src,
                &format!("bounds.lower_deg[{}]", i + 1),
                "expected lower_deg < upper_deg",
            ));
        }
        if bounds.lower[i] < robot.lower[i] - 1e-12 || bounds.upper[i] > robot.upper[i] + 1e-12 {
            return Err(field_error(
                src,
                &format!("bounds, axis {}", i + 1),
                format!(
                    "expected within the robot's limits [{:.2}, {:.2}] deg",
                    robot.lower[i].to_degrees(),
                    robot.upper[i].to_degrees()
                ),
            ));
        }
    }
    Ok(bounds)
}

fn test_postures(postures: &[[f64; 6]], robot: &Robot, src: &str) -> Result<Vec<Vector6<f64>>> {
    postures
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let field = format!("test.postures_deg[{}]", i + 1);
            check_in(src, &field, p, &limits::ANGLE_DEG)?;
            let q = deg6(p);
            match robot.first_out_of_limits(&q) {
                None => Ok(q),
                Some(axis) => Err(field_error(
                    src,
                    &field,
                    format!("axis {} is outside the robot's limits", axis + 1),
                )),
            }
        })
        .collect()
}
