//! The arm: the robot with its tool, elastostatic model, payload and bodies; what kinematics,
//! deflection, prediction and compensation need of a setup ([`super::Setup::arm`]).

use crate::model::Model;
use crate::robot::collision::CollisionGeometry;
use crate::robot::kinematics::Coordinates;
use crate::robot::parts::polylines;
use crate::robot::Bodies;
use crate::Robot;
use nalgebra::{Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3, Vector6};

/// Points of the tool, in the flange frame, m.
#[derive(Debug, Clone, PartialEq)]
pub struct Tool {
    /// Where the load is applied.
    pub loading_point: Vector3<f64>,
    /// Where the displacements are measured (at least one).
    pub measuring_points: Vec<Vector3<f64>>,
    /// The tool centre point whose Jacobian gives the dexterity index.
    pub tcp: Vector3<f64>,
    /// The tool frame's orientation in the flange frame (`[tool] tcp_rpy_deg`, identity by
    /// default): the axes a robot program's Cartesian targets give the tool's orientation in
    /// (ABB `tooldata` `tframe`, KUKA `$TOOL`, FANUC `UTOOL`). Only those targets use it
    /// (read, written back, generated); the TCP is [`Tool::tcp`] either way.
    pub rotation: UnitQuaternion<f64>,
}

impl Tool {
    /// Every point of the tool, flange frame, m: the loading point, the measuring points, the
    /// tool centre point.
    pub(crate) fn points(&self) -> impl Iterator<Item = &Vector3<f64>> {
        std::iter::once(&self.loading_point)
            .chain(&self.measuring_points)
            .chain(std::iter::once(&self.tcp))
    }

    /// The tool frame in the flange frame, m: its origin the TCP, its axes [`Tool::rotation`].
    pub fn frame(&self) -> Isometry3<f64> {
        Isometry3::from_parts(Translation3::from(self.tcp), self.rotation)
    }
}

/// The tool's mass and centre of mass (a spindle), `[tool] mass_kg` and `centre_of_mass_mm`: its
/// weight, `m g` down the base frame's -z (the base z axis taken as vertical, up), acts on the
/// robot with the process wrench ([`Payload::wrench`]), and a generated robot program states it
/// (KRL `$LOAD`, RAPID `tooldata`); with `inertia_kg_m2` its inertia joins link 6 in the mass
/// matrix ([`Payload::body`], [`crate::robot::dynamics`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Payload {
    /// The mass, kg (within [0.001, 10 000] kg).
    pub mass: f64,
    /// The centre of mass, flange frame, m.
    pub centre: Vector3<f64>,
    /// The inertia tensor about the centre of mass, flange frame's axes, kg m^2 (zero: a point
    /// mass).
    pub inertia: Matrix3<f64>,
}

/// Standard gravity, m/s^2 (CGPM 1901).
pub const GRAVITY: f64 = 9.80665;

impl Payload {
    /// The tool as a rigid body in the flange frame (the mass model's link 6 carries it).
    pub fn body(&self) -> crate::robot::LinkMass {
        crate::robot::LinkMass {
            mass: self.mass,
            centre: self.centre,
            inertia: self.inertia,
        }
    }

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

/// The robot with what it carries and how it gives way: the robot (its base and flange offsets
/// applied), the tool's points, the elastostatic model (drive and virtual springs), the tool's
/// payload and the bodies the cell's checks use. Part of a [`super::Setup`], checked by its
/// builder ([`super::SetupBuilder::build`]); functions that only move, load or compensate the
/// robot take this part, not the experiment around it.
#[derive(Debug, Clone, PartialEq)]
pub struct Arm {
    pub(super) robot: Robot,
    pub(super) tool: Tool,
    pub(super) tcp_given: bool,
    pub(super) model: Model,
    pub(super) payload: Option<Payload>,
    pub(super) mass_sd: f64,
    pub(super) frame_sd: (f64, f64),
    pub(super) geometry: RobotGeometry,
    /// The robot's shapes ([`Bodies::Shapes`]) if the cell uses them, else [`Bodies::Scaled`].
    pub(super) shapes: Bodies,
}

impl Arm {
    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// Tool points, flange frame, m.
    pub fn tool(&self) -> &Tool {
        &self.tool
    }

    /// Whether the tool centre point was given (`[tool] tcp_mm`), not taken from measuring
    /// point 1.
    pub(crate) fn tcp_given(&self) -> bool {
        self.tcp_given
    }

    /// The elastostatic model: the drive springs and the virtual springs ([`crate::model`]);
    /// the drives alone unless the setup has a `[model]`.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Where the springs sit: in the drives (axis coordinates) or on the kinematic joints.
    pub fn springs(&self) -> Coordinates {
        self.model.coordinates()
    }

    /// The tool's mass and centre of mass, if given.
    pub fn payload(&self) -> Option<&Payload> {
        self.payload.as_ref()
    }

    /// The relative standard deviation of every body's mass and inertia (`[masses] sd_pct`
    /// as a fraction; 0: the masses taken as exact), independent between bodies: the mass
    /// model's share of a surge's uncertainty ([`crate::observation::dynamics`]).
    pub fn mass_sd(&self) -> f64 {
        self.mass_sd
    }

    /// How far each frame of the robot model (joints 1-6 and the flange) may be from the true
    /// robot's: the standard deviation of each coordinate of its position (m) and orientation (rad)
    /// (`[robot_accuracy]`, default 0.3 mm and 0.3 mrad): what a registration from the nominal
    /// robot cannot see (`stiffid_metrology::register::robot_covariance`).
    pub fn frame_sd(&self) -> (f64, f64) {
        self.frame_sd
    }

    /// Capsule radii of the robot and tool bodies, m: the setup's `[robot_geometry]`, else the
    /// robot's ([`Bodies::Capsules`]), else scaled to the robot's size. The robot's capsules are
    /// its bodies in the cell unless [`Arm::shapes`] has its own; the tool's always are.
    pub(crate) fn geometry(&self) -> &RobotGeometry {
        &self.geometry
    }

    /// The robot's collision shapes (a URDF's `<collision>` elements, [`Bodies::Shapes`]) that
    /// the cell's checks and drawings use for the base and links 1-6; `None`: capsules, also when
    /// the setup gives `[robot_geometry] link_radius_mm`, the user's override.
    pub fn shapes(&self) -> Option<&CollisionGeometry> {
        match &self.shapes {
            Bodies::Shapes(s) => Some(s),
            _ => None,
        }
    }

    /// Why the robot's collision meshes are missing (a URDF whose meshes were not found,
    /// [`Bodies::Missing`]), if they are.
    pub(super) fn missing_bodies(&self) -> Option<&str> {
        match &self.shapes {
            Bodies::Missing(why) => Some(why),
            _ => None,
        }
    }
}

/// Capsule radii of the robot bodies, m (see [`crate::cell::capsules`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RobotGeometry {
    /// Radii of the base and of links 1-6, m.
    pub link_radii: [f64; 7],
    /// Radius of the tool capsule, m.
    pub tool_radius: f64,
}

/// Default radius of the base and links 1-6 as a fraction of the robot's size (the total length
/// of its capsule segments): 8, 6, 4.5, 4, 3, 2.5 and 2 %.
pub(crate) const DEFAULT_RADIUS_FRACTIONS: [f64; 7] = [0.08, 0.06, 0.045, 0.04, 0.03, 0.025, 0.02];

/// Smallest default tool radius, m (10 mm).
pub(crate) const MIN_TOOL_RADIUS: f64 = 0.01;

/// The default [`RobotGeometry`] of a robot and tool: link radii 8, 6, 4.5, 4, 3, 2.5 and 2 % of
/// the robot's size (the summed length of its base and link segments, the same in every posture;
/// 4.33 m and radii 346, 260, 195, 173, 130, 108, 87 mm for the COMAU NJ 165), and
/// `default_tool_radius`.
pub fn default_geometry(robot: &Robot, tool: &Tool) -> RobotGeometry {
    let frames = robot.frames(&Vector6::zeros());
    let size: f64 = polylines(&frames)
        .iter()
        .flat_map(|(_, p)| p.windows(2).map(|w| (w[1] - w[0]).norm()))
        .sum();
    RobotGeometry {
        link_radii: DEFAULT_RADIUS_FRACTIONS.map(|f| f * size),
        tool_radius: default_tool_radius(tool),
    }
}

/// The default radius of the tool body, m: half the distance of the nearest measuring point from
/// the flange z axis, at least [`MIN_TOOL_RADIUS`]. The measuring points (reflectors) sit on the
/// outside of the tool, so a body that reached them would hide them from the tracker: the tool
/// capsule stands for the spindle or the bar that carries them, not for their envelope.
pub(crate) fn default_tool_radius(tool: &Tool) -> f64 {
    (0.5 * nearest_measuring_point(tool)).max(MIN_TOOL_RADIUS)
}

/// The distance of the measuring point nearest the flange z axis from it, m (infinite without
/// measuring points).
pub(crate) fn nearest_measuring_point(tool: &Tool) -> f64 {
    (tool.measuring_points.iter())
        .map(|p| p.xy().norm())
        .fold(f64::INFINITY, f64::min)
}
