//! Starting values for a new setup, where the user has no numbers yet: the characteristic length of
//! the dexterity index (Zhang et al. 2021, Eq. 20-21) from the robot's own kinematics, and a rough
//! nominal joint stiffness from the robot's payload class.
//!
//! Neither is a measurement. The characteristic length only normalises the translational rows of
//! the Jacobian; the nominal stiffness only sets the relative sizes of the compliances in the
//! scale-free criteria (their ranking of posture groups does not change when all six are scaled by
//! one factor) and the absolute size of the predicted deviation rates.

use crate::robot::kinematics::{dexterity, Coordinates};
use crate::{Error, Result, Robot};
use nalgebra::{Matrix6, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// Postures sampled for [`characteristic_length`].
pub(crate) const LENGTH_SAMPLES: usize = 512;

/// The search interval of [`characteristic_length`], m.
pub(crate) const LENGTH_RANGE_M: (f64, f64) = (0.05, 20.0);

/// The payload (kg) of the reference robot of [`nominal_stiffness`]: the COMAU SMART5 NJ 165-3.0.
pub(crate) const REFERENCE_PAYLOAD_KG: f64 = 165.0;

/// The joint stiffness (Nm/rad) of the reference robot: Zhang et al. 2021, Table 2.
pub(crate) const REFERENCE_STIFFNESS_NM_PER_RAD: [f64; 6] = [
    950_000.0,
    3_000_000.0,
    900_000.0,
    250_000.0,
    200_000.0,
    150_000.0,
];

/// The largest payload [`nominal_stiffness`] accepts, kg (the heaviest serial industrial robots
/// carry about 2.3 t).
pub(crate) const MAX_PAYLOAD_KG: f64 = 2500.0;

/// The smallest payload [`nominal_stiffness`] accepts, kg: below it the scaled prior falls under
/// the stiffness a setup accepts (1 Nm/rad), and no robot that machines carries less.
pub(crate) const MIN_PAYLOAD_KG: f64 = 0.1;

/// The characteristic length L (m) that minimises the median dexterity `k(J_N)` of the point `tcp`
/// (flange frame, m) over `LENGTH_SAMPLES` postures drawn uniformly within `[lower, upper]` (axis
/// angles, rad; ChaCha8 seeded with `seed`), Jacobians in axis coordinates.
///
/// The paper leaves L open; on its setup this choice gives about 1.2 m. Postures at a singularity
/// (infinite dexterity) count as the worst values of the median. The median is minimised over
/// `LENGTH_RANGE_M` by golden-section search on `log L`, to 0.1%.
///
/// # Errors
/// [`Error::InvalidField`] if a bound is not finite or `lower > upper`, or if the robot is singular
/// at every sampled posture.
pub fn characteristic_length(
    robot: &Robot,
    lower: &Vector6<f64>,
    upper: &Vector6<f64>,
    tcp: &Vector3<f64>,
    seed: u64,
) -> Result<f64> {
    if let Some(a) =
        (0..6).find(|&a| !(lower[a].is_finite() && upper[a].is_finite() && lower[a] <= upper[a]))
    {
        return Err(Error::InvalidField {
            field: format!("bounds, axis {}", a + 1),
            message: format!(
                "expected finite lower <= upper, got [{}, {}] rad",
                lower[a], upper[a]
            ),
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let jacobians: Vec<Matrix6<f64>> = (0..LENGTH_SAMPLES)
        .map(|_| {
            let q = Vector6::from_fn(|a, _| lower[a] + rng.random::<f64>() * (upper[a] - lower[a]));
            robot.frames(&q).jacobian(tcp, Coordinates::Axis)
        })
        .collect();
    let median = |log_l: f64| median_dexterity(&jacobians, log_l.exp());
    if !median(1.0f64.ln()).is_finite() && !median(0.1f64.ln()).is_finite() {
        return Err(Error::InvalidField {
            field: "robot".into(),
            message: "singular at most sampled postures: no characteristic length minimises its dexterity".into(),
        });
    }
    Ok(golden_section(median, LENGTH_RANGE_M.0.ln(), LENGTH_RANGE_M.1.ln(), 1e-3).exp())
}

/// The seed of [`robot_characteristic_length`].
pub(crate) const ROBOT_LENGTH_SEED: u64 = 1;

/// The characteristic length L (m) of `robot` for the point `point` (flange frame, m) when no
/// length is given: [`characteristic_length`] over the robot's joint limits (an unlimited axis
/// within +-180 deg), seeded with `ROBOT_LENGTH_SEED`. A setup's own length
/// (`characteristic_length_mm`) is the one to use where there is a setup; this is for a robot
/// alone (`stiffid kinematics`, Python `Robot.dexterity`).
///
/// # Errors
/// As [`characteristic_length`]: a robot singular at most sampled postures.
pub fn robot_characteristic_length(robot: &Robot, point: &Vector3<f64>) -> Result<f64> {
    let (lower, upper) = within_a_turn(robot);
    characteristic_length(robot, &lower, &upper, point, ROBOT_LENGTH_SEED)
}

/// The robot's joint limits (rad), an unlimited axis within +-180 deg.
fn within_a_turn(robot: &Robot) -> (Vector6<f64>, Vector6<f64>) {
    (
        robot.limits().lower.map(|l| l.max(-PI)),
        robot.limits().upper.map(|u| u.min(PI)),
    )
}

/// The reach (m): the largest distance of the flange origin from the base origin over
/// `LENGTH_SAMPLES` postures drawn uniformly within the joint limits (an unlimited axis within
/// +-180 deg; ChaCha8 seeded with `seed`).
pub fn reach(robot: &Robot, seed: u64) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (lower, upper) = within_a_turn(robot);
    (0..LENGTH_SAMPLES)
        .map(|_| {
            let q = Vector6::from_fn(|a, _| lower[a] + rng.random::<f64>() * (upper[a] - lower[a]));
            robot.frames(&q).point(&Vector3::zeros()).norm()
        })
        .fold(0.0, f64::max)
}

/// A rough payload class (kg) for a robot of `reach` (m) when its payload is not known: the
/// reference robot's payload scaled by the cube of the reach ratio (geometric similarity: mass
/// grows with the cube of size), within `[1, 2500]` kg. `reference_reach` is the reference robot's
/// [`reach`]. A 0.9 m arm gets about 6 kg, a 3.2 m arm about 270 kg.
pub fn payload_class_kg(reach: f64, reference_reach: f64) -> f64 {
    (REFERENCE_PAYLOAD_KG * (reach / reference_reach).powi(3)).clamp(1.0, MAX_PAYLOAD_KG)
}

/// A rough nominal joint stiffness (Nm/rad) for a robot of `payload_kg`: the reference robot's
/// (`REFERENCE_STIFFNESS_NM_PER_RAD`) scaled in proportion to the payload, on the reasoning that
/// drives and gears are sized for the torques the payload causes. Expect the real values to differ
/// by a factor of two or three; identify them, then use the identified ones.
///
/// # Errors
/// [`Error::InvalidField`] (`payload_kg`) unless `0.1 <= payload_kg <= 2500`.
pub fn nominal_stiffness(payload_kg: f64) -> Result<Vector6<f64>> {
    if !(MIN_PAYLOAD_KG..=MAX_PAYLOAD_KG).contains(&payload_kg) {
        return Err(Error::InvalidField {
            field: "payload_kg".into(),
            message: format!(
                "expected a payload in [{MIN_PAYLOAD_KG}, {MAX_PAYLOAD_KG}] kg, got {}",
                crate::common::words::number(payload_kg)
            ),
        });
    }
    let scale = payload_kg / REFERENCE_PAYLOAD_KG;
    Ok(Vector6::from(REFERENCE_STIFFNESS_NM_PER_RAD) * scale)
}

/// The median of `k(J_N)` over `jacobians` at characteristic length `l` (m); infinite values sort
/// last.
fn median_dexterity(jacobians: &[Matrix6<f64>], l: f64) -> f64 {
    let mut k: Vec<f64> = jacobians.iter().map(|j| dexterity(j, l)).collect();
    k.sort_by(f64::total_cmp);
    k[k.len() / 2]
}

/// The minimiser of a unimodal `f` on `[a, b]`, to an interval of width `tol`.
pub(crate) fn golden_section(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64, tol: f64) -> f64 {
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    while b - a > tol {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - r * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    (a + b) / 2.0
}
