//! The document of the kinematics job ([`crate::app::kinematics`]): `stiffid kinematics --json`,
//! Python's `Robot.kinematics(...)`. Millimetres and degrees for positions and angles, SI (m/rad,
//! rad/rad) for the Jacobian, rows `[v; omega]`; base frame (the cell frame of a robot with
//! external axes, [`crate::app::kinematics`]). The report is the document
//! ([`super::Report`]), written through the borrowed view [`Document`]
//! ([`super::Report::document`]), built as it is written.

use crate::app::document::mass::{self, ModeShape};
use crate::app::document::{finite, mm, rows};
use crate::app::kinematics::Report;
use serde::Serialize;
use stiffid_core::common::warning::Warning;
use stiffid_core::robot::external::{ExternalAxes, Role};
use stiffid_core::robot::kinematics::Coordinates;

/// The kinematics of one posture: mm and degrees for positions and angles, SI (m/rad, rad/rad)
/// for the Jacobian, rows `[v; omega]`; base frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "kinematics")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("kinematics")))]
pub struct Document<'a> {
    /// The robot's name.
    pub robot: &'a str,
    /// Where the robot comes from (for a URDF: the file and the tip link used).
    pub robot_source: &'a str,
    /// Axis angles q1..q6, deg.
    pub q_deg: [f64; 6],
    /// The joint coordinates of the Jacobian's columns.
    pub coordinates: Coordinates,
    /// The characteristic length of the dexterity index, mm.
    pub characteristic_length_mm: f64,
    /// Where it comes from: `given`, or `derived` from the robot (the length minimising the
    /// point's median dexterity over the joint limits,
    /// `stiffid_core::setup::prior::robot_characteristic_length`).
    pub characteristic_length_source: &'static str,
    /// The point of the Jacobian, flange frame, mm.
    pub point_mm: [f64; 3],
    /// The flange's origin, mm.
    pub flange_position_mm: [f64; 3],
    /// Rotation matrix of the flange frame in the base frame, row-major.
    pub flange_rotation: [[f64; 3]; 3],
    /// The point's position, mm.
    pub point_position_mm: [f64; 3],
    /// Row-major, rows vx, vy, vz (m/rad), wx, wy, wz (rad/rad); column j is joint j.
    pub jacobian: [[f64; 6]; 6],
    /// The dexterity index k(J_N) (Eq. 20): 1 for an isotropic Jacobian, larger is worse; `null`
    /// at a singularity.
    pub dexterity: Option<f64>,
    /// Origin of each joint frame (after the joint), base frame, mm.
    pub joint_positions_mm: [[f64; 3]; 6],
    /// The joint-space mass matrix `M(q)` (kg m^2, columns in `coordinates`, the robot's links
    /// without a tool); `null` where the robot gives no masses or they are placeholders.
    pub mass_matrix_kg_m2: Option<[[f64; 6]; 6]>,
    /// The operational-space inertia `Lambda = (J M^-1 J^T)^-1` of the point, base frame, rows
    /// and columns `[v; omega]` (kg, kg m, kg m^2); `null` without masses or at a singular
    /// posture.
    pub operational_inertia_si: Option<[[f64; 6]; 6]>,
    /// The natural frequencies, Hz, ascending (`K v = w^2 M v` with `--stiffness-nm-per-rad`);
    /// `null` without a stiffness or masses.
    pub natural_frequencies_hz: Option<[f64; 6]>,
    /// The modes, lowest first, with the point's direction of motion; `null` as
    /// `natural_frequencies_hz`.
    pub mode_shapes: Option<Vec<ModeShape>>,
    /// The external axes' values, in the cell's order (empty for a robot without external
    /// axes).
    pub external: Vec<ExternalValue>,
    /// The Jacobian columns of the external axes (`stiffid::app::kinematics`, module docs):
    /// row-major, 6 rows vx, vy, vz (m/m or m/rad), wx, wy, wz (0 or rad/rad) of one column per
    /// external axis in the cell's order: the tool point's velocity relative to the part, cell
    /// frame; `null` without external axes.
    pub external_jacobian: Option<Vec<Vec<f64>>>,
    /// The part's frame at the external axes' values (the positioner's pose times the setup's
    /// `[workpiece]`): its origin, cell frame, mm; `null` without a positioner or a workpiece.
    pub part_position_mm: Option<[f64; 3]>,
    /// Its rotation matrix in the cell frame, row-major; `null` as `part_position_mm`.
    pub part_rotation: Option<[[f64; 3]; 3]>,
    /// The point's position in the part's frame, mm; `null` as `part_position_mm`.
    pub point_in_part_mm: Option<[f64; 3]>,
    /// What to look at before trusting the document (placeholder masses).
    pub warnings: &'a [Warning],
}

/// One external axis's value.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ExternalValue {
    /// Its column in data files: `e1_mm`, `e2_deg`, ...
    pub column: String,
    /// Its name, as the robot or setup file gives it.
    pub name: String,
    /// `carrier` (under the arm, linear) or `positioner` (under the part, rotary).
    pub role: &'static str,
    /// Its value, mm (linear) or deg (rotary).
    pub value: f64,
}

impl Report {
    /// The document this report is written as: its view in mm and degrees (what it serialises
    /// to).
    pub fn document(&self) -> Document<'_> {
        let report = self;
        let f = &report.frames;
        let (frequencies, shapes) = mass::modes(report.modes.as_ref(), &report.point_directions);
        Document {
            robot: &report.robot,
            robot_source: &report.robot_source,
            q_deg: report.q.map(f64::to_degrees).into(),
            coordinates: report.coordinates,
            characteristic_length_mm: mm(report.characteristic_length),
            characteristic_length_source: match report.derived {
                true => "derived",
                false => "given",
            },
            point_mm: report.point.map(mm).into(),
            flange_position_mm: f.flange.translation.vector.map(mm).into(),
            flange_rotation: rows(&f.flange.rotation.to_rotation_matrix().into_inner()),
            point_position_mm: f.point(&report.point).map(mm).into(),
            jacobian: rows(&report.jacobian),
            dexterity: finite(report.dexterity),
            joint_positions_mm: f.joints.map(|j| j.translation.vector.map(mm).into()),
            mass_matrix_kg_m2: report.mass_matrix.as_ref().map(rows),
            operational_inertia_si: report.operational_inertia.as_ref().map(rows),
            natural_frequencies_hz: frequencies,
            mode_shapes: shapes,
            external: (report.external_axes.as_ref())
                .map_or(Vec::new(), |axes| external_values(axes, &report.external)),
            external_jacobian: (!report.external_jacobian.is_empty()).then(|| {
                (0..6)
                    .map(|r| report.external_jacobian.iter().map(|c| c[r]).collect())
                    .collect()
            }),
            part_position_mm: report.part.map(|p| p.translation.vector.map(mm).into()),
            part_rotation: report
                .part
                .map(|p| rows(&p.rotation.to_rotation_matrix().into_inner())),
            point_in_part_mm: report.part.map(|p| {
                let x = f.point(&report.point);
                p.inverse_transform_point(&x.into()).coords.map(mm).into()
            }),
            warnings: &report.warnings,
        }
    }
}

/// The values `e` (SI, the cell's order) of the external axes `axes` in mm and deg, named.
fn external_values(axes: &ExternalAxes, e: &[f64]) -> Vec<ExternalValue> {
    (axes.axes().iter().zip(axes.column_names()).zip(e))
        .map(|((a, column), v)| ExternalValue {
            column,
            name: a.name.clone(),
            role: match a.role {
                Role::Carrier => "carrier",
                Role::Positioner => "positioner",
            },
            value: a.to_display(*v),
        })
        .collect()
}
