//! The arm configuration of a posture: which of the up to eight inverse-kinematics solutions of a
//! pose a 6R arm with a wrist is in, which the configuration data a controller stores with a
//! Cartesian target name.
//!
//! Three binary choices separate the solutions of a pose, each read from the geometry of the
//! posture (so independent of the robot's axis sign conventions):
//! - **shoulder**: the wrist centre (the point of axis 5 nearest to axis 4, their intersection
//!   on a spherical wrist) in front of or behind axis 1, along the arm's forward direction (the
//!   horizontal direction from axis 1 to axis 2, which turns with axis 1: the x axis of KUKA's A1
//!   coordinate system);
//! - **elbow**: the wrist centre in front of or behind the line of the lower arm (axis 2 to axis
//!   3), seen along the arm's side direction `z1 x forward`: in front in the usual posture,
//!   upper arm raised and forearm reaching forward;
//! - **wrist**: the sign of axis 5's angle.
//!
//! Each controller names these choices in its own configuration data (KUKA status and turn,
//! ABB `confdata`, FANUC `CONFIG`), which its language's folder defines from a configuration
//! (`stiffid_machining::program`'s `krl`, `rapid` and `ls`), with the controller's manual.
//!
//! What stiffid assumes: the setup's axis angles are the controller's (same zero and sign, as a
//! joint program of that controller reads them), and the configuration is read from the setup's
//! kinematics. The wrist bit follows the sign of axis 5 as each manual states it, which is robot
//! dependent: a robot whose axis 5 counts the other way has the opposite bit.

use crate::Robot;
use nalgebra::{Vector3, Vector6};

/// Below this, a geometric quantity is on the boundary between two configurations (m, or rad for
/// axis 5).
const MARGIN: f64 = 1e-6;

/// The configuration of a posture (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Configuration {
    /// Axis angles q1..q6, deg.
    pub q_deg: [f64; 6],
    /// The wrist centre's distance in front of axis 1 along the forward direction, m (negative:
    /// behind).
    pub front: f64,
    /// The wrist centre's distance in front of the lower arm's line, m (negative: behind).
    pub elbow: f64,
}

impl Configuration {
    /// The configuration of `robot` at axis angles `q` (rad).
    pub fn of(robot: &Robot, q: &Vector6<f64>) -> Self {
        let f = robot.frames(q);
        let z1 = f.axis_directions[0];
        let wrist = nearest_on(
            f.axis_points[4],
            f.axis_directions[4],
            f.axis_points[3],
            f.axis_directions[3],
        );
        let horizontal = |v: Vector3<f64>| v - z1 * z1.dot(&v);
        let mut forward = horizontal(f.axis_points[1] - f.axis_points[0]);
        if forward.norm() < MARGIN {
            // No shoulder offset: the side direction of axis 2 gives the forward one.
            forward = horizontal(f.axis_directions[1].cross(&z1));
        }
        let forward = forward.normalize();
        let side = z1.cross(&forward);
        let lower = f.axis_points[2] - f.axis_points[1];
        let lower_in_plane = lower - side * side.dot(&lower);
        let reach = wrist - f.axis_points[2];
        let elbow = lower_in_plane.cross(&reach).dot(&side) / lower_in_plane.norm().max(MARGIN);
        Self {
            q_deg: q.map(f64::to_degrees).into(),
            front: (wrist - f.axis_points[0]).dot(&forward),
            elbow,
        }
    }

    /// Whether the wrist centre is behind axis 1.
    pub fn behind(&self) -> bool {
        self.front < 0.0
    }

    /// Whether the wrist centre is behind the lower arm (elbow down).
    pub fn elbow_down(&self) -> bool {
        self.elbow < 0.0
    }

    /// Whether axis 5 is negative.
    pub fn wrist_negative(&self) -> bool {
        self.q_deg[4] < 0.0
    }

    /// What differs from `other` among the shoulder, elbow and wrist choices, each compared only
    /// where both postures are clear of the boundary; `None` when they agree.
    pub fn change_from(&self, other: &Configuration) -> Option<String> {
        let clear = |a: f64, b: f64| a.abs() > MARGIN && b.abs() > MARGIN;
        let mut changes = Vec::new();
        if clear(self.front, other.front) && self.behind() != other.behind() {
            changes.push("the wrist centre crosses to the other side of axis 1");
        }
        if clear(self.elbow, other.elbow) && self.elbow_down() != other.elbow_down() {
            changes.push("the elbow flips");
        }
        let (q5, r5) = (self.q_deg[4].to_radians(), other.q_deg[4].to_radians());
        if clear(q5, r5) && self.wrist_negative() != other.wrist_negative() {
            changes.push("the wrist flips (axis 5 changes sign)");
        }
        (!changes.is_empty()).then(|| changes.join(", "))
    }
}

/// The point of the line `(p, d)` nearest to the line `(r, e)` (unit directions); `p` when they
/// are parallel.
fn nearest_on(p: Vector3<f64>, d: Vector3<f64>, r: Vector3<f64>, e: Vector3<f64>) -> Vector3<f64> {
    let w = p - r;
    let b = d.dot(&e);
    let denominator = 1.0 - b * b;
    if denominator < 1e-12 {
        return p;
    }
    let s = (b * e.dot(&w) - d.dot(&w)) / denominator;
    p + d * s
}
