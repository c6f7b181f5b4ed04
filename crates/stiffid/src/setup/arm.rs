//! The arm: the robot with its tool, elastostatic model, payload and bodies; what kinematics,
//! deflection, prediction and compensation need of a setup ([`super::Setup::arm`]).

use super::RobotGeometry;
use crate::model::Model;
use crate::robot::collision::CollisionGeometry;
use crate::robot::kinematics::Coordinates;
use crate::robot::Bodies;
use crate::Robot;
use nalgebra::{Matrix3, Vector3, Vector6};

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
/// (KRL `$LOAD`, RAPID `tooldata`); with `inertia_kg_m2` its inertia joins link 6 in the mass
/// matrix ([`Payload::body`], [`crate::robot::dynamics`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Payload {
    /// The mass, kg (within [`crate::common::limits::TOOL_MASS_KG`]).
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
    pub fn tcp_given(&self) -> bool {
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

    /// The relative standard deviation of every body's mass and inertia (`[masses] sd_percent`
    /// as a fraction; 0: the masses taken as exact), independent between bodies: the mass
    /// model's share of a surge's uncertainty ([`crate::observation::dynamics`]).
    pub fn mass_sd(&self) -> f64 {
        self.mass_sd
    }

    /// How far each frame of the robot model (joints 1-6 and the flange) may be from the true
    /// robot's: the standard deviation of each coordinate of its position (m) and orientation
    /// (rad) (`[robot_accuracy]`, default [`super::DEFAULT_FRAME_SD`]): what a registration
    /// from the nominal robot cannot see ([`crate::metrology::register::robot_covariance`]).
    pub fn frame_sd(&self) -> (f64, f64) {
        self.frame_sd
    }

    /// Capsule radii of the robot and tool bodies, m: the setup's `[robot_geometry]`, else the
    /// robot's ([`Bodies::Capsules`]), else scaled to the robot's size. The robot's capsules are
    /// its bodies in the cell unless [`Arm::shapes`] has its own; the tool's always are.
    pub fn geometry(&self) -> &RobotGeometry {
        &self.geometry
    }

    /// The robot's collision shapes (a URDF's `<collision>` elements, [`Bodies::Shapes`]) that
    /// the cell's checks and drawings use for the base and links 1-6; `None`: capsules
    /// ([`Arm::geometry`]), also when the setup gives `[robot_geometry] link_radius_mm`, the
    /// user's override.
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
