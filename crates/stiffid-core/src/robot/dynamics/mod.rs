//! The robot's mass: the joint-space mass matrix `M(q)` (composite rigid body algorithm), the
//! operational-space inertia `Lambda = (J M^-1 J^T)^-1` of a tool point and its effective masses
//! (O. Khatib, "A unified approach for motion and force control of robot manipulators: the
//! operational space formulation", IEEE J. Robotics and Automation 3(1), 1987), and the natural
//! frequencies and mode shapes of the undamped elastic robot ([`modes`]).
//!
//! A [`MassModel`] is the six links' rigid bodies ([`LinkMass`], from a robot file's `mass_kg`,
//! `com_mm`, `inertia_kg_m2` or a URDF's `<inertial>`) and the tool's (a setup's `[tool]`),
//! checked for the placeholders robot descriptions often carry. All results are SI, base frame,
//! columns in axis coordinates `q` (`theta = A q + c`: `M_q = A^T M_theta A`).
//!
//! **How well the masses are known.** A model may carry a relative standard deviation `s` of every
//! body's mass and inertia (`MassModel::with_relative_sd`), independent between bodies. `M` is
//! linear in the bodies, `M = sum_k M_k` ([`MassModel::parts`]), and so is the held mass along `u`:
//! `m = w^T M w = sum_k w^T M_k w` with `w = J^-1 [u; 0]`, so its standard deviation is
//! `s sqrt(sum_k (w^T M_k w)^2)` (`MassModel::held_mass_sd`), exactly (no linearisation).

pub mod body;
mod crba;
pub mod modes;

use crate::common::warning::{Warning, WarningKind};
use crate::robot::kinematics::{Coordinates, Frames};
use crate::robot::{LinkMass, Robot};
use crate::{Error, Result};
use nalgebra::{Cholesky, Matrix3, Matrix6, Vector3};

/// The rigid bodies that move with the joints: link k turned by joints 1..=k (link frames
/// [`Frames::joints`]) and the tool (flange frame), fixed to link 6.
#[derive(Debug, Clone, PartialEq)]
pub struct MassModel {
    links: [LinkMass; 6],
    tool: Option<LinkMass>,
    relative_sd: f64,
}

/// How [`MassModel::new`] tells the user to give real inertials.
pub const HOW_TO_GIVE: &str = "give each link's mass_kg, com_mm and inertia_kg_m2 in a robot .toml file, or correct the URDF's <inertial> elements (mass, origin, inertia about the centre of mass)";

impl MassModel {
    /// The robot's links (`robot.masses()`) with the tool's body (flange frame), checked.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`<robot> masses`) when the robot gives no masses, or placeholders:
    /// all six masses equal (the `mass value="1"` of many ROS-Industrial files), or every inertia
    /// tensor zero (point masses leave the wrist without inertia: the mass matrix is singular);
    /// the message says how to give them ([`HOW_TO_GIVE`]).
    pub fn new(robot: &Robot, tool: Option<LinkMass>) -> Result<Self> {
        let invalid = |message: String| Error::InvalidField {
            field: format!("{} masses", crate::common::limits::short(robot.name())),
            message: format!("{message}: {HOW_TO_GIVE}"),
        };
        let Some(links) = robot.masses() else {
            return Err(invalid(
                "the robot's description gives no link masses".into(),
            ));
        };
        let first = links[0].mass;
        if links.iter().all(|l| l.mass == first) {
            return Err(invalid(format!(
                "every link has the mass {first} kg: placeholders, not a robot's inertials"
            )));
        }
        if links.iter().all(|l| l.inertia == Matrix3::zeros()) {
            return Err(invalid(
                "every link's inertia tensor is zero (point masses): the mass matrix would be singular"
                    .into(),
            ));
        }
        Ok(Self {
            links: *links,
            tool,
            relative_sd: 0.0,
        })
    }

    /// This model with every body's mass and inertia known to the relative standard deviation
    /// `sd` (a fraction; 0, the default: exact), independent between bodies (module docs).
    pub(crate) fn with_relative_sd(mut self, sd: f64) -> Self {
        self.relative_sd = sd;
        self
    }

    /// The relative standard deviation of every body's mass and inertia ([`Self::with_relative_sd`]).
    pub(crate) fn relative_sd(&self) -> f64 {
        self.relative_sd
    }

    /// Each body alone, links 1-6 then the tool if there is one: the parts' mass matrices sum to
    /// the model's (the composite rigid body algorithm is linear in the bodies).
    pub fn parts(&self) -> Vec<MassModel> {
        let empty = Self {
            links: [LinkMass::default(); 6],
            tool: None,
            relative_sd: 0.0,
        };
        let links = (0..6).map(|k| {
            let mut part = empty.clone();
            part.links[k] = self.links[k];
            part
        });
        let tool = self.tool.map(|t| Self {
            tool: Some(t),
            ..empty.clone()
        });
        links.chain(tool).collect()
    }

    /// The standard deviation (kg) of the held mass (`held_mass`) along the unit direction `u` (base frame)
    /// at the point whose Jacobian is `jacobian` (6x6, base frame, axis coordinates), from the
    /// model's [`Self::relative_sd`] (module docs); `None` where the Jacobian is singular.
    pub(crate) fn held_mass_sd(
        &self,
        robot: &Robot,
        frames: &Frames,
        jacobian: &Matrix6<f64>,
        u: &Vector3<f64>,
    ) -> Option<f64> {
        let along = nalgebra::Vector6::new(u.x, u.y, u.z, 0.0, 0.0, 0.0);
        let w = jacobian.lu().solve(&along)?;
        let squares: f64 = self
            .parts()
            .iter()
            .map(|part| {
                let a = (w.transpose() * part.mass_matrix(robot, frames, Coordinates::Axis) * w)[0];
                a * a
            })
            .sum();
        let sd = self.relative_sd * squares.sqrt();
        sd.is_finite().then_some(sd)
    }

    /// [`MassModel::new`] for the jobs whose mass results are extras: none (and no warning)
    /// when the robot gives no masses, none with a [`WarningKind::Masses`] warning (the error's
    /// message) when they are placeholders.
    pub fn optional(robot: &Robot, tool: Option<LinkMass>) -> (Option<Self>, Option<Warning>) {
        match (robot.masses(), Self::new(robot, tool)) {
            (_, Ok(m)) => (Some(m), None),
            (None, Err(_)) => (None, None),
            (Some(_), Err(e)) => (None, Some(Warning::new(WarningKind::Masses, e.to_string()))),
        }
    }

    /// The six bodies in the base frame in the posture `frames`, the tool joined to link 6.
    pub(crate) fn world(&self, frames: &Frames) -> [LinkMass; 6] {
        let mut world: [LinkMass; 6] =
            std::array::from_fn(|k| self.links[k].moved(&frames.joints[k]));
        if let Some(tool) = &self.tool {
            world[5] = world[5].plus(&tool.moved(&frames.flange));
        }
        world
    }

    /// The joint-space mass matrix `M(q)` (6x6, symmetric, kg m^2) in the posture `frames` of
    /// `robot`, columns in `coordinates` (axis: `A^T M_theta A`, `A` the axis map's matrix),
    /// by the composite rigid body algorithm (Featherstone 2008, section 6.2).
    pub fn mass_matrix(
        &self,
        robot: &Robot,
        frames: &Frames,
        coordinates: Coordinates,
    ) -> Matrix6<f64> {
        let h = crba::kinematic(frames, &self.world(frames));
        match coordinates {
            Coordinates::Kinematic => h,
            Coordinates::Axis => {
                let a = &robot.axis_map().matrix;
                let m = a.transpose() * h * a;
                (m + m.transpose()) * 0.5
            }
        }
    }
}

/// The mass matrix's Cholesky factor, where it is positive definite (a posture where some
/// joint moves no mass is not).
pub(crate) fn factor(m: &Matrix6<f64>) -> Option<Cholesky<f64, nalgebra::U6>> {
    m.iter().all(|v| v.is_finite()).then_some(())?;
    Cholesky::new(*m)
}

/// The operational-space inertia `Lambda = (J M^-1 J^T)^-1 = J^-T M J^-1` (6x6, symmetric, rows
/// and columns `[v; omega]`: kg, kg m, kg m^2) of the point whose Jacobian is `jacobian` (6x6,
/// base frame, columns in the coordinates of `m`) (Khatib 1987, Eq. 29); `None` where `J` is
/// singular.
pub fn operational_inertia(m: &Matrix6<f64>, jacobian: &Matrix6<f64>) -> Option<Matrix6<f64>> {
    let inverse = crate::math::linalg::inverse(jacobian)?;
    let lambda = inverse.transpose() * m * inverse;
    let lambda = (lambda + lambda.transpose()) * 0.5;
    lambda.iter().all(|v| v.is_finite()).then_some(lambda)
}

/// The effective mass (kg) along the unit direction `u` (base frame) of a point held in the
/// other five directions (a drill in its hole): `u^T Lambda_vv u`, `Lambda_vv` the translational
/// block of the full 6x6 [`operational_inertia`].
pub(crate) fn held_mass(lambda: &Matrix6<f64>, u: &Vector3<f64>) -> f64 {
    let block = lambda.fixed_view::<3, 3>(0, 0);
    (u.transpose() * block * u)[0]
}

/// The effective mass (kg) along the unit direction `u` (base frame) of a free point:
/// `1 / (u^T (J M^-1 J^T)_vv u) = 1 / (u^T (Lambda^-1)_vv u)`; `None` where `Lambda` is singular.
pub fn free_mass(lambda: &Matrix6<f64>, u: &Vector3<f64>) -> Option<f64> {
    let mobility = lambda.cholesky()?.inverse();
    let block = mobility.fixed_view::<3, 3>(0, 0);
    Some(1.0 / (u.transpose() * block * u)[0])
}

#[cfg(test)]
mod body_tests;
