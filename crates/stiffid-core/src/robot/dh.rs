//! Denavit-Hartenberg tables, in both common notations.

use super::Joint;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Which Denavit-Hartenberg notation a table uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Convention {
    /// Standard (distal) DH: `T_i = RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i)`.
    StandardDh,
    /// Modified (proximal, Craig) DH: `T_i = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i) TransZ(d_i)`;
    /// row i holds `alpha_{i-1}`, `a_{i-1}`, `d_i`.
    ModifiedDh,
}

/// One row of a DH table, SI units (m, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Link length `a` (`a_{i-1}` in modified DH), m.
    pub a: f64,
    /// Link twist `alpha` (`alpha_{i-1}` in modified DH), rad.
    pub alpha: f64,
    /// Link offset `d_i`, m.
    pub d: f64,
    /// Constant added to the kinematic angle `theta_i`, rad.
    pub theta_offset: f64,
}

/// The revolute joint (rotation about its z axis) of one DH row.
pub fn joint(convention: Convention, row: &Row) -> Joint {
    hayati_joint(convention, row, 0.0)
}

/// The revolute joint of one DH row with Hayati's `beta` (rad): a rotation about the y axis after
/// the twist, `T_i = RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i) RotY(beta_i)` (standard)
/// or `RotX(alpha_{i-1}) TransX(a_{i-1}) RotY(beta_{i-1}) RotZ(theta_i) TransZ(d_i)` (modified), for
/// consecutive (nearly) parallel axes, where the common normal and `d` degenerate (Hayati and
/// Mirmirani 1985). `beta = 0` is [`joint`].
pub fn hayati_joint(convention: Convention, row: &Row, beta: f64) -> Joint {
    let rot_x = Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), row.alpha),
    );
    let trans_x = Isometry3::translation(row.a, 0.0, 0.0);
    let trans_z = Isometry3::translation(0.0, 0.0, row.d);
    let (mut pre, mut post) = match convention {
        Convention::ModifiedDh => (rot_x * trans_x, trans_z),
        Convention::StandardDh => (Isometry3::identity(), trans_z * trans_x * rot_x),
    };
    if beta != 0.0 {
        let rot_y = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), beta);
        match convention {
            Convention::ModifiedDh => pre *= rot_y,
            Convention::StandardDh => post *= rot_y,
        }
    }
    Joint {
        pre,
        axis: Vector3::z_axis(),
        post,
        offset: row.theta_offset,
    }
}

/// A chain written as a DH table: the rows, Hayati's `beta` of each row (rad), and the base and
/// flange transforms that complete it (m), so that the table's robot has the chain's kinematics
/// at every kinematic angle ([`table`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The notation of the rows.
    pub convention: Convention,
    /// The six rows, SI.
    pub rows: [Row; 6],
    /// Hayati's `beta` of each row, rad ([`hayati_joint`]).
    pub betas: [f64; 6],
    /// World to the table's first frame, m.
    pub base: Isometry3<f64>,
    /// The table's last frame to the flange, m.
    pub flange: Isometry3<f64>,
}

/// The sine of the angle between consecutive joint axes below which they count as parallel: the
/// previous frame's x axis then points at the next axis (Hayati's form, `d` carried on) instead of
/// along the common normal.
const PARALLEL: f64 = 1e-2;

/// The cosine of Hayati's `beta` below which a row is refused (the axes' angle near 90 degrees
/// about y, where `alpha` and `theta` become one rotation).
const GIMBAL: f64 = 1e-6;

/// One fixed transform between consecutive joint axes, as
/// `Rz(phi) Tz(e) Tx(a) Rx(alpha) Ry(beta) Rz(gamma) Tz(delta)` (rad, m): `phi` turns with the
/// previous joint, `e`, `a`, `alpha`, `beta` are a DH row's, `gamma` turns with the next joint and
/// `delta` slides along its axis.
#[derive(Debug, Clone, Copy)]
struct Split {
    phi: f64,
    e: f64,
    a: f64,
    alpha: f64,
    beta: f64,
    gamma: f64,
    delta: f64,
}

/// The [`Split`] of `g`; with `free_phi` the previous frame's x axis is chosen (along the common
/// normal, or towards the next axis when they are parallel), else it is kept (`phi = 0`). `None`
/// when `beta` nears 90 degrees or, with `phi = 0`, a lateral offset `|y| > tolerance` (m) has no
/// place in the row.
fn split(g: &Isometry3<f64>, free_phi: bool, tolerance: f64) -> Option<Split> {
    let (r, t) = (g.rotation, g.translation.vector);
    let z = r * Vector3::z();
    // Within +-90 degrees, so that a row that is already DH keeps phi = 0.
    let half_turn = |y: f64, x: f64| match x == 0.0 {
        true => std::f64::consts::FRAC_PI_2.copysign(y),
        false => (y / x).atan(),
    };
    let phi = match free_phi {
        false => 0.0,
        true if z.xy().norm() > PARALLEL => half_turn(-z.x, z.y),
        true if t.xy().norm() > tolerance => half_turn(t.y, t.x),
        true => 0.0,
    };
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -phi);
    let (m, t) = ((turn * r).to_rotation_matrix(), turn * t);
    let m = m.matrix();
    let beta = m[(0, 2)].atan2(m[(0, 0)].hypot(m[(0, 1)]));
    if beta.cos() < GIMBAL {
        return None;
    }
    let alpha = (-m[(1, 2)]).atan2(m[(2, 2)]);
    let gamma = (-m[(0, 1)]).atan2(m[(0, 0)]);
    let k = alpha.sin() * beta.cos();
    let delta = match k.abs() > 1e-6 {
        true => -t.y / k,
        false if t.y.abs() <= tolerance => 0.0,
        false => return None,
    };
    Some(Split {
        phi,
        e: t.z - delta * alpha.cos() * beta.cos(),
        a: t.x - delta * beta.sin(),
        alpha,
        beta,
        gamma,
        delta,
    })
}

/// `Rz(angle)`.
fn rot_z(angle: f64) -> Isometry3<f64> {
    Isometry3::rotation(Vector3::z() * angle)
}

/// The chain of `robot` (any axes: each joint turned onto its z axis first) as a DH table in
/// `convention` with the same kinematics at every kinematic angle: the rows from the fixed
/// transforms between consecutive axes (`split`), the theta offsets the robot's plus what
/// turns with each joint, the base and flange the robot's with what no row holds (in modified
/// DH, the first row's `a`, `alpha`, `beta` where they hold the first joint's transform, and the
/// last joint's `d`). `tolerance` (m) is the lateral offset that counts as none. The axis map
/// and joint limits are the robot's (the table does not carry them).
///
/// # Errors
/// `None` when a transform has no row: two consecutive axes at 90 degrees about the previous
/// frame's y axis after the common normal was chosen (not met by a robot's chain).
pub fn table(robot: &super::Robot, convention: Convention, tolerance: f64) -> Option<Table> {
    // Each joint as pre * Rz(theta + offset) * post, its axis turned onto z.
    let joints: [(Isometry3<f64>, Isometry3<f64>); 6] = std::array::from_fn(|i| {
        let j = &robot.joints()[i];
        let onto = UnitQuaternion::rotation_between(&Vector3::z(), &j.axis)
            .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI));
        (j.pre * onto, onto.inverse() * j.post)
    });
    let mut rows = [Row {
        a: 0.0,
        alpha: 0.0,
        d: 0.0,
        theta_offset: 0.0,
    }; 6];
    for (r, j) in rows.iter_mut().zip(robot.joints()) {
        r.theta_offset = j.offset;
    }
    let mut betas = [0.0; 6];
    // The first joint: in modified DH its row's a, alpha, beta when its `pre` has the form.
    let first = joints[0].0;
    let modified_first = match convention {
        Convention::ModifiedDh => split(&first, false, tolerance),
        Convention::StandardDh => None,
    };
    let (base, mut carry) = match modified_first {
        Some(s) => {
            (rows[0].a, rows[0].alpha, betas[0]) = (s.a, s.alpha, s.beta);
            rows[0].theta_offset += s.gamma;
            (
                robot.base() * Isometry3::translation(0.0, 0.0, s.e),
                s.delta,
            )
        }
        None => {
            // What turns about and slides along the first axis joins its row; the rest, the base.
            let m = first.rotation.to_rotation_matrix();
            let gamma = (-m[(0, 1)]).atan2(m[(0, 0)]);
            let delta = (first.rotation.inverse() * first.translation.vector).z;
            rows[0].theta_offset += gamma;
            let rest = first * Isometry3::translation(0.0, 0.0, -delta) * rot_z(-gamma);
            (robot.base() * rest, delta)
        }
    };
    for i in 1..6 {
        let g = Isometry3::translation(0.0, 0.0, carry) * joints[i - 1].1 * joints[i].0;
        let s = split(&g, true, tolerance)?;
        rows[i - 1].theta_offset += s.phi;
        rows[i - 1].d = s.e;
        let target = match convention {
            Convention::StandardDh => i - 1,
            Convention::ModifiedDh => i,
        };
        (rows[target].a, rows[target].alpha, betas[target]) = (s.a, s.alpha, s.beta);
        rows[i].theta_offset += s.gamma;
        carry = s.delta;
    }
    let last = Isometry3::translation(0.0, 0.0, carry) * joints[5].1;
    let flange = match convention {
        Convention::StandardDh => {
            let s = split(&last, true, tolerance)?;
            rows[5].theta_offset += s.phi;
            (rows[5].d, rows[5].a, rows[5].alpha, betas[5]) = (s.e, s.a, s.alpha, s.beta);
            rot_z(s.gamma) * Isometry3::translation(0.0, 0.0, s.delta) * robot.flange()
        }
        Convention::ModifiedDh => {
            rows[5].d = last.translation.vector.z;
            Isometry3::translation(0.0, 0.0, -rows[5].d) * last * robot.flange()
        }
    };
    Some(Table {
        convention,
        rows,
        betas,
        base,
        flange,
    })
}
