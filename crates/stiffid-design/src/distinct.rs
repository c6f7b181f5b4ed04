//! Postures of a group that are not distinct: two postures whose axis angles are close, or whose
//! flanges sit at the same pose (a wrist flip, or the elbow's other branch, reaching the same pose
//! counts: for the tracker and the rope both are one measurement place), add little information
//! and are flagged in the plan.
//!
//! Two postures `a`, `b` are *near* when `max_j |q_a,j - q_b,j|` is below the joint distance
//! ([`Distinctness::joint`], default 2 deg) or when their flange origins lie within
//! [`Distinctness::position`] (default 10 mm) and their flange orientations within
//! [`Distinctness::angle`] (default 2 deg) of each other. A pool choice can forbid them
//! ([`distinct_pool`]): it keeps the first of every near pair in pool order.

use nalgebra::{Isometry3, Vector6};
use stiffid_core::common::error::JobOption;
use stiffid_core::common::limits::{self, Range};
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::{Result, Robot};

/// Axis angles closer than this in every joint make two postures near, rad (2 deg).
pub(crate) const JOINT_TOLERANCE: f64 = 2.0 * std::f64::consts::PI / 180.0;
/// Flange origins closer than this (with [`ANGLE_TOLERANCE`]) make two postures near, m (10 mm).
pub(crate) const POSITION_TOLERANCE: f64 = 0.010;
/// Flange orientations closer than this (with [`POSITION_TOLERANCE`]) make two postures near,
/// rad (2 deg).
pub(crate) const ANGLE_TOLERANCE: f64 = 2.0 * std::f64::consts::PI / 180.0;

/// How far apart two postures must be to count as distinct (module docs); the default is the
/// flagging's (`JOINT_TOLERANCE`, 10 mm, 2 deg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distinctness {
    /// Axis angles closer than this in every joint make two postures near, rad.
    pub joint: f64,
    /// Flange origins closer than this (with `angle`) make two postures near, m.
    pub position: f64,
    /// Flange orientations closer than this (with `position`) make two postures near, rad.
    pub angle: f64,
}

impl Default for Distinctness {
    fn default() -> Self {
        Self {
            joint: JOINT_TOLERANCE,
            position: POSITION_TOLERANCE,
            angle: ANGLE_TOLERANCE,
        }
    }
}

/// The accepted distance in axis angles and flange orientation, deg.
pub const DISTINCT_DEG: Range = Range::new(0.0, 180.0, "deg");

/// The accepted distance of flange origins, mm.
pub const DISTINCT_MM: Range = Range::new(0.0, 1e4, "mm");

impl Distinctness {
    /// The default distances with the axis-angle and orientation distance `deg` (deg) and the
    /// flange-origin distance `mm` (mm) where given.
    ///
    /// # Errors
    /// [`stiffid_core::Error::InvalidOption`] ([`JobOption::DistinctDeg`], [`JobOption::DistinctMm`])
    /// for a distance outside [`DISTINCT_DEG`] or [`DISTINCT_MM`].
    pub fn try_from_deg_mm(deg: Option<f64>, mm: Option<f64>) -> Result<Self> {
        let mut d = Self::default();
        if let Some(deg) = deg {
            limits::check("distinct_deg", &[deg], &DISTINCT_DEG)
                .map_err(|e| e.for_option(JobOption::DistinctDeg))?;
            (d.joint, d.angle) = (deg.to_radians(), deg.to_radians());
        }
        if let Some(mm) = mm {
            limits::check("distinct_mm", &[mm], &DISTINCT_MM)
                .map_err(|e| e.for_option(JobOption::DistinctMm))?;
            d.position = mm * 1e-3;
        }
        Ok(d)
    }

    /// The pair `(a, b)` if postures `qa`, `qb` with flanges `fa`, `fb` are near.
    fn near(
        &self,
        (a, qa, fa): (usize, &Vector6<f64>, &Isometry3<f64>),
        (b, qb, fb): (usize, &Vector6<f64>, &Isometry3<f64>),
    ) -> Option<Near> {
        let joint_distance = (qa - qb).amax();
        let position_distance = (fa.translation.vector - fb.translation.vector).norm();
        let angle_distance = fa.rotation.angle_to(&fb.rotation);
        let same_pose = position_distance < self.position && angle_distance < self.angle;
        (joint_distance < self.joint || same_pose).then_some(Near {
            a,
            b,
            joint_distance,
            position_distance,
            angle_distance,
            joint_tolerance: self.joint,
        })
    }
}

/// Two near postures of a group.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Near {
    /// The first posture's index in the group (0-based).
    pub a: usize,
    /// The second's (`> a`).
    pub b: usize,
    /// `max_j |q_a,j - q_b,j|`, rad.
    pub joint_distance: f64,
    /// The distance between their flange origins, m.
    pub position_distance: f64,
    /// The angle between their flange orientations, rad.
    pub angle_distance: f64,
    /// The joint distance below which postures were called near, rad.
    pub joint_tolerance: f64,
}

impl Near {
    /// Whether the flange reaches the same pose with other axis angles (a wrist flip or another
    /// branch), rather than the axis angles being close.
    pub fn same_pose_other_branch(&self) -> bool {
        self.joint_distance >= self.joint_tolerance
    }

    /// The warning of this pair ([`WarningKind::NearPostures`]), postures numbered from 1.
    pub fn warning(&self) -> Warning {
        let why = match self.same_pose_other_branch() {
            true => "reach the same flange pose on another branch (a wrist flip)".to_string(),
            false => format!(
                "have axis angles within {:.3} deg",
                self.joint_tolerance.to_degrees()
            ),
        };
        Warning::new(
            WarningKind::NearPostures,
            format!(
                "postures {} and {} {why}: they measure nearly the same thing; choose another posture for one of them",
                self.a + 1,
                self.b + 1
            ),
        )
    }
}

/// Every near pair of `postures` (axis angles, rad) on `robot` by the default distances, in
/// the order `(a, b)`, `a < b`.
pub fn near_pairs(robot: &Robot, postures: &[Vector6<f64>]) -> Vec<Near> {
    near_pairs_by(robot, postures, &Distinctness::default())
}

/// Every near pair of `postures` (axis angles, rad) on `robot` by the distances `d`, in the
/// order `(a, b)`, `a < b`.
pub(crate) fn near_pairs_by(
    robot: &Robot,
    postures: &[Vector6<f64>],
    d: &Distinctness,
) -> Vec<Near> {
    let flanges: Vec<_> = postures.iter().map(|q| robot.frames(q).flange).collect();
    let mut out = Vec::new();
    for a in 0..postures.len() {
        for b in a + 1..postures.len() {
            out.extend(d.near(
                (a, &postures[a], &flanges[a]),
                (b, &postures[b], &flanges[b]),
            ));
        }
    }
    out
}

/// The pool filter of `--distinct`: of the postures marked `usable` (axis angles, rad, on
/// `robot`), each that is near ([`Distinctness`] `d`) a usable posture kept before it in pool
/// order is no longer usable; returns `(dropped, kept)` pairs, 0-based pool indices, so no
/// two postures left usable are near.
pub fn distinct_pool(
    robot: &Robot,
    postures: &[Vector6<f64>],
    usable: &mut [bool],
    d: &Distinctness,
) -> Vec<(usize, usize)> {
    let flanges: Vec<_> = postures.iter().map(|q| robot.frames(q).flange).collect();
    let mut kept: Vec<usize> = Vec::new();
    let mut dropped = Vec::new();
    for b in 0..postures.len() {
        if !usable[b] {
            continue;
        }
        let near = kept
            .iter()
            .find(|&&a| {
                d.near(
                    (a, &postures[a], &flanges[a]),
                    (b, &postures[b], &flanges[b]),
                )
                .is_some()
            })
            .copied();
        match near {
            Some(a) => {
                usable[b] = false;
                dropped.push((b, a));
            }
            None => kept.push(b),
        }
    }
    dropped
}
