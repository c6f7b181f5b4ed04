//! The robot's mass with its springs at one posture: the mass matrix, the operational-space
//! inertia of the tool point, the natural frequencies and mode shapes, and the breakthrough
//! surge of a drill ([`crate::robot::dynamics`] for the mass alone).
//!
//! **Modes.** `K v = w^2 M v` in axis coordinates with the joint-space compliance `C_q` of the
//! model: the drives' `diag(h)` (in kinematic coordinates `A^-1 diag(h) A^-T`), and with virtual
//! springs their compliance carried to the joints through the tool point, `J_q^-1 (sum_s h_s J_s
//! J_s^T) J_q^-T`: the joint compliance that gives the tool point the model's Cartesian
//! compliance `C_x` (a virtual spring's own mass position is not modelled).
//!
//! **Surge.** When a drill breaks through, the thrust `F u` (N, base frame) that held the
//! compliance `c = u^T C_x u` (m/N, the translational block at the tool point) vanishes; the
//! stored energy `E = F^2 c / 2` goes into the mass the tool has along `u` while the hole holds the
//! other five directions, `m = u^T Lambda_vv u` (`robot::dynamics::held_mass`): the tool
//! surges at `v = sqrt(2 E / m) = F sqrt(c / m)`. `c` is linear in the parameters' compliance,
//! `c = sum_p h_p (u^T J_p)^2`, so its variance is `g^T Cov(h) g` with `g_p = (u^T J_p)^2`; with
//! the mass model's standard deviation `std(m)` (`MassModel::held_mass_sd`, from the setup's
//! `[masses] sd_pct`), `std(v) = v sqrt((std(c) / 2c)^2 + (std(m) / 2m)^2)` (first order, the
//! two independent).

use crate::common::warning::Warning;
use crate::model::Compliance;
use crate::robot::dynamics::modes::{self, Modes};
use crate::robot::dynamics::{held_mass, operational_inertia, MassModel};
use crate::robot::kinematics::{Coordinates, Frames};
use crate::setup::Arm;
use nalgebra::{DVector, Matrix6, Vector3};

/// The mass model of the arm: the robot's links ([`crate::Robot::masses`]) and the tool's body
/// ([`crate::setup::Payload::body`]), as [`MassModel::optional`] gives it: none without masses,
/// none with a warning for placeholders.
/// The model carries the setup's relative standard deviation of the masses ([`Arm::mass_sd`]).
pub fn mass_model(arm: &Arm) -> (Option<MassModel>, Option<Warning>) {
    let (model, warning) = MassModel::optional(arm.robot(), arm.payload().map(|p| p.body()));
    (model.map(|m| m.with_relative_sd(arm.mass_sd())), warning)
}

/// The mass and the springs of one posture.
#[derive(Debug, Clone, PartialEq)]
pub struct Posture {
    /// `M(q)`, axis coordinates, kg m^2.
    pub mass_matrix: Matrix6<f64>,
    /// `Lambda` of the tool point (rows `[v; omega]`, SI); `None` at a singular posture.
    pub operational_inertia: Option<Matrix6<f64>>,
    /// The natural frequencies and mode shapes (axis coordinates); `None` where the mass matrix
    /// or the joint compliance is not positive definite (a singular posture with virtual springs).
    pub modes: Option<Modes>,
    /// The direction (unit, base frame) in which each mode moves the tool point, lowest
    /// frequency first (zero where a mode does not move it).
    pub point_directions: [Vector3<f64>; 6],
}

/// The mass matrix, operational-space inertia and modes of the arm in the posture `frames`, at
/// the tool point `point` (flange frame, m), with the compliance `h` of every parameter of the
/// arm's model.
///
/// # Panics
/// If `h` does not have one value per parameter.
pub fn posture(
    masses: &MassModel,
    arm: &Arm,
    frames: &Frames,
    point: &Vector3<f64>,
    h: &DVector<f64>,
) -> Posture {
    let robot = arm.robot();
    let m = masses.mass_matrix(robot, frames, Coordinates::Axis);
    let jacobian = frames.jacobian(point, Coordinates::Axis);
    let modes = joint_compliance(arm, frames, point, h).and_then(|c| modes::modes(&m, &c));
    let point_directions = modes::point_directions(&jacobian, modes.as_ref());
    Posture {
        operational_inertia: operational_inertia(&m, &jacobian),
        mass_matrix: m,
        modes,
        point_directions,
    }
}

/// The joint-space compliance `C_q` (6x6, rad/Nm, axis coordinates) of the arm's model in the
/// posture `frames` (module docs); with virtual springs `None` where the Jacobian of `point`
/// is singular.
///
/// # Panics
/// If `h` does not have one value per parameter.
pub fn joint_compliance(
    arm: &Arm,
    frames: &Frames,
    point: &Vector3<f64>,
    h: &DVector<f64>,
) -> Option<Matrix6<f64>> {
    let model = arm.model();
    assert_eq!(h.len(), model.len(), "one compliance per parameter");
    let drives = Matrix6::from_diagonal(&h.fixed_rows::<6>(0).into_owned());
    let mut c = match arm.springs() {
        Coordinates::Axis => drives,
        Coordinates::Kinematic => {
            let a = crate::math::linalg::inverse(&arm.robot().axis_map().matrix)?;
            a * drives * a.transpose()
        }
    };
    if !model.is_drives_only() {
        let j = model.jacobian(frames, point);
        let inverse = crate::math::linalg::inverse(&frames.jacobian(point, Coordinates::Axis))?;
        let mut springs = Matrix6::zeros();
        for s in 6..model.len() {
            let col = j.column(s);
            springs += col * col.transpose() * h[s];
        }
        c += inverse * springs * inverse.transpose();
    }
    Some((c + c.transpose()) * 0.5)
}

/// The breakthrough surge of a thrust (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surge {
    /// The thrust's magnitude `F`, N.
    pub force: f64,
    /// Its direction `u`, unit, base frame.
    pub direction: Vector3<f64>,
    /// The compliance along it, `c = u^T C_x u`, m/N.
    pub compliance: f64,
    /// The effective mass along it with the other five directions held, `u^T Lambda_vv u`, kg.
    pub mass: f64,
    /// Its standard deviation from the mass model's (`MassModel::held_mass_sd`), kg; `None`
    /// where the masses are taken as exact (no `[masses] sd_pct`).
    pub mass_std: Option<f64>,
    /// The stored energy `F^2 c / 2`, J.
    pub energy: f64,
    /// The surge speed `F sqrt(c / m)`, m/s.
    pub speed: f64,
    /// Its standard deviation from the compliance covariance and the mass model's (first order,
    /// module docs), m/s; `None` with neither.
    pub speed_std: Option<f64>,
}

/// The surge of the thrust `force` (N, base frame) released at the tool point `point` (flange
/// frame, m) of the arm in the posture `frames`, with the point's operational-space inertia
/// `lambda` (of `masses`) and the model's `compliance`; `None` for a zero force or a non-positive
/// mass or compliance along it.
///
/// # Panics
/// If the compliance does not have one value per parameter.
pub fn surge(
    masses: &MassModel,
    arm: &Arm,
    frames: &Frames,
    point: &Vector3<f64>,
    lambda: &Matrix6<f64>,
    compliance: &Compliance,
    force: &Vector3<f64>,
) -> Option<Surge> {
    let f = force.norm();
    let u = force.try_normalize(0.0)?;
    let h = &compliance.h;
    assert_eq!(h.len(), arm.model().len(), "one compliance per parameter");
    let j = arm.model().jacobian(frames, point);
    let g = DVector::from_fn(h.len(), |p, _| {
        let along = u.dot(&j.fixed_view::<3, 1>(0, p));
        along * along
    });
    let c = g.dot(h);
    let mass = held_mass(lambda, &u);
    if !(c > 0.0 && mass > 0.0 && mass.is_finite()) {
        return None;
    }
    let speed = f * (c / mass).sqrt();
    let of_compliance = compliance.covariance.as_ref().map(|cov| {
        let var = (g.transpose() * cov * &g)[0].max(0.0);
        var.sqrt() / (2.0 * c)
    });
    let mass_std = (masses.relative_sd() > 0.0)
        .then(|| {
            let jacobian = frames.jacobian(point, Coordinates::Axis);
            masses.held_mass_sd(arm.robot(), frames, &jacobian, &u)
        })
        .flatten();
    let of_mass = mass_std.map(|s| s / (2.0 * mass));
    let speed_std = match (of_compliance, of_mass) {
        (None, None) => None,
        (a, b) => Some(speed * a.unwrap_or(0.0).hypot(b.unwrap_or(0.0))),
    };
    Some(Surge {
        force: f,
        direction: u,
        compliance: c,
        mass,
        mass_std,
        energy: 0.5 * f * f * c,
        speed,
        speed_std,
    })
}

/// [`surge`] at the arm's TCP in the posture `frames`, with the operational-space inertia of
/// `masses` there ([`operational_inertia`]); `None` at a singular posture or where [`surge`]
/// gives none.
///
/// # Panics
/// If the compliance does not have one value per parameter.
pub fn tcp_surge(
    masses: &MassModel,
    arm: &Arm,
    frames: &Frames,
    compliance: &Compliance,
    force: &Vector3<f64>,
) -> Option<Surge> {
    let point = arm.tool().tcp;
    let m = masses.mass_matrix(arm.robot(), frames, Coordinates::Axis);
    let lambda = operational_inertia(&m, &frames.jacobian(&point, Coordinates::Axis))?;
    surge(masses, arm, frames, &point, &lambda, compliance, force)
}
