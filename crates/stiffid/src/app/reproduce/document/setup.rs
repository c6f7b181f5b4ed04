//! The resolved setup in the study's summary: SI inside stiffid, mm, deg and N here.

use super::{deg, mm};
use nalgebra::Isometry3;
use serde::Serialize;
use stiffid_core::{Coordinates, Setup};

/// A rigid transform.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct FrameJson {
    /// Translation, mm.
    translation_mm: [f64; 3],
    /// Rotation as a unit quaternion, w, x, y, z.
    rotation_quaternion_wxyz: [f64; 4],
}

impl From<&Isometry3<f64>> for FrameJson {
    fn from(t: &Isometry3<f64>) -> Self {
        let q = t.rotation.quaternion();
        Self {
            translation_mm: mm(&t.translation.vector),
            rotation_quaternion_wxyz: [q.w, q.i, q.j, q.k],
        }
    }
}

/// The resolved setup (SI inside stiffid, mm, deg and N here).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SetupJson<'a> {
    /// The setup's name.
    name: &'a str,
    /// Its description.
    description: &'a str,
    /// The robot, resolved.
    robot: RobotJson<'a>,
    /// The map from axis angles to kinematic angles: `theta = M q + offset`.
    axis_map: AxisMapJson,
    /// Where the springs sit.
    springs: Coordinates,
    /// The tool's points, flange frame.
    tool: ToolJson,
    /// The rope load.
    loading: LoadingJson,
    /// The tracker noise.
    noise: NoiseJson,
    /// The posture bounds of the search.
    bounds: BoundsJson,
    /// The nominal joint stiffness, Nm/rad (the study's true stiffness; a study needs it).
    stiffness_nm_per_rad: Option<[f64; 6]>,
    /// The characteristic length of the dexterity index, mm (a study needs it).
    characteristic_length_mm: Option<f64>,
    /// The test postures, axis angles q1..q6, deg.
    test_postures_deg: Vec<[f64; 6]>,
}

/// The robot, resolved.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct RobotJson<'a> {
    /// The robot as the setup names it (a preset or a file).
    reference: &'a str,
    /// The robot's name.
    name: &'a str,
    /// Where it comes from.
    source: &'a str,
    /// Every joint, base to flange.
    joints: Vec<JointJson>,
    /// Lower axis limits, deg.
    lower_limit_deg: [f64; 6],
    /// Upper axis limits, deg.
    upper_limit_deg: [f64; 6],
    /// The base frame in the world.
    base: FrameJson,
    /// The flange frame after the last joint.
    flange: FrameJson,
    /// The cell's external axes (a track under the arm, a positioner under the part), in the
    /// cell's order; empty without.
    external_axes: Vec<ExternalAxisJson>,
}

/// One external axis of the cell, as its `[[external_axis]]` table gives it.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct ExternalAxisJson {
    /// Its name.
    name: String,
    /// Its column in data files: `e1_mm`, `e2_deg`, ...
    column: String,
    /// `carrier` (linear, under the arm) or `positioner` (rotary, under the part).
    role: &'static str,
    /// Its unit direction, cell frame at e = 0.
    direction: [f64; 3],
    /// A point on a rotary axis's line, cell frame at e = 0, mm (zero for a linear axis).
    point_mm: [f64; 3],
    /// Its travel, mm or deg.
    limits: [f64; 2],
    /// Its offset, mm or deg.
    offset: f64,
    /// A linear axis's error motions, one row per order: positioning, straightness y and z (mm),
    /// roll, pitch, yaw (mrad).
    error_motions: Vec<[f64; 6]>,
}

/// One joint: `pre`, the rotation about `axis` by the angle plus `offset_deg`, `post`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct JointJson {
    /// The fixed transform before the rotation.
    pre: FrameJson,
    /// The unit rotation axis.
    axis: [f64; 3],
    /// The fixed transform after the rotation.
    post: FrameJson,
    /// The kinematic angle offset, deg.
    offset_deg: f64,
}

/// `theta = M q + offset`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct AxisMapJson {
    /// `M`, row-major.
    matrix: [[f64; 6]; 6],
    /// The offset, deg.
    offset_deg: [f64; 6],
}

/// The tool's points, flange frame, mm.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct ToolJson {
    /// Where the rope pulls.
    loading_point_mm: [f64; 3],
    /// The points the tracker measures.
    measuring_points_mm: Vec<[f64; 3]>,
    /// The tool centre point.
    tcp_mm: [f64; 3],
}

/// The rope load.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct LoadingJson {
    /// The rope's tension, N.
    load_n: f64,
    /// The rope's fixed end, base frame, mm.
    anchor_mm: [f64; 3],
}

/// The tracker noise.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct NoiseJson {
    /// The standard deviation of one coordinate of one tracker reading at level multiple 1, mm.
    reading_sd_mm: f64,
    /// The variance of one coordinate of one displacement (a loaded minus an unloaded reading)
    /// at level multiple 1, mm^2: the paper's noise variance (Table 3).
    displacement_variance_mm2: f64,
    /// The noise level multiples of the variance.
    level_multiples: Vec<f64>,
}

/// Posture bounds, axis angles q1..q6, deg.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
struct BoundsJson {
    /// Lower bounds.
    lower_deg: [f64; 6],
    /// Upper bounds.
    upper_deg: [f64; 6],
}

impl<'a> SetupJson<'a> {
    /// The resolved `s`.
    pub fn new(s: &'a Setup) -> Self {
        let r = &s.robot();
        let m = &r.axis_map().matrix;
        Self {
            name: s.name(),
            description: s.description(),
            robot: RobotJson {
                reference: s.robot_ref(),
                name: r.name(),
                source: r.source(),
                joints: r
                    .joints()
                    .iter()
                    .map(|j| JointJson {
                        pre: FrameJson::from(&j.pre),
                        axis: [j.axis.x, j.axis.y, j.axis.z],
                        post: FrameJson::from(&j.post),
                        offset_deg: j.offset.to_degrees(),
                    })
                    .collect(),
                lower_limit_deg: deg(&r.limits().lower),
                upper_limit_deg: deg(&r.limits().upper),
                base: FrameJson::from(r.base()),
                flange: FrameJson::from(r.flange()),
                external_axes: (r.external().into_iter())
                    .flat_map(|a| a.axes().iter().zip(a.column_names()))
                    .map(|(a, column)| ExternalAxisJson {
                        name: a.name.clone(),
                        column,
                        role: match a.role {
                            stiffid_core::robot::external::Role::Carrier => "carrier",
                            stiffid_core::robot::external::Role::Positioner => "positioner",
                        },
                        direction: [a.direction.x, a.direction.y, a.direction.z],
                        point_mm: mm(&a.point),
                        limits: [a.to_display(a.lower), a.to_display(a.upper)],
                        offset: a.to_display(a.offset),
                        error_motions: (a.errors.coefficients().iter())
                            .map(|c| c.map(|v| v * 1e3))
                            .collect(),
                    })
                    .collect(),
            },
            axis_map: AxisMapJson {
                matrix: std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)])),
                offset_deg: deg(&r.axis_map().offset),
            },
            springs: s.springs(),
            tool: ToolJson {
                loading_point_mm: mm(&s.tool().loading_point),
                measuring_points_mm: s.tool().measuring_points.iter().map(mm).collect(),
                tcp_mm: mm(&s.tool().tcp),
            },
            loading: LoadingJson {
                load_n: s.load().load,
                anchor_mm: mm(&s.load().anchor),
            },
            noise: NoiseJson {
                reading_sd_mm: s.noise().reading_sd() * 1e3,
                displacement_variance_mm2: s.noise().displacement_variance() * 1e6,
                level_multiples: s.noise().levels.clone(),
            },
            bounds: BoundsJson {
                lower_deg: deg(&s.bounds().lower),
                upper_deg: deg(&s.bounds().upper),
            },
            stiffness_nm_per_rad: s.nominal_stiffness().map(|k| (*k).into()),
            characteristic_length_mm: s.characteristic_length().map(|l| l * 1e3),
            test_postures_deg: s.test_postures().iter().map(deg).collect(),
        }
    }
}
