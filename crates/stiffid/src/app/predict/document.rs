//! The document of the predict job ([`crate::app::predict`]): `stiffid predict --json`, Python's
//! `predict(...)`. `*_std_*` keys are standard deviations from the compliance covariance, `null`
//! without one. The report is the document ([`super::Report`]), written through the borrowed
//! view [`Document`] ([`super::Report::document`]), built as it is written.

use crate::app::document::mass::{self, ModeShape};
use crate::app::document::{interval_mm, mm, rows};
use crate::app::predict::{Point, Report};
use nalgebra::{Matrix6, Vector6};
use serde::Serialize;
use stiffid_core::common::limits::Violation;
use stiffid_core::common::warning::Warning;
use stiffid_core::io::stiffness::RegionSection;

/// The forward model of one posture under one wrench.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "predict")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("predict")))]
pub struct Document<'a> {
    /// The setup as given.
    pub setup: &'a str,
    /// Axis angles q1..q6, deg.
    pub q_deg: [f64; 6],
    /// The wrench as given, fx, fy, fz (N), mx, my, mz (Nm), in `wrench_frame`.
    pub wrench_n_nm: [f64; 6],
    /// `base` or `tool`.
    pub wrench_frame: &'static str,
    /// Where the wrench acts: a tool point in the flange frame, mm.
    pub wrench_point_mm: [f64; 3],
    /// The wrench in the base frame, N and Nm.
    pub wrench_base_frame_n_nm: [f64; 6],
    /// The drive stiffness used, Nm/rad.
    pub stiffness_nm_per_rad: [f64; 6],
    /// Drive torques, Nm.
    pub torques_nm: [f64; 6],
    /// Drive deflections, mrad.
    pub joint_deflections_mrad: [f64; 6],
    /// Rotation of the flange, base frame, mrad.
    pub flange_rotation_mrad: [f64; 3],
    /// Its standard deviation, mrad.
    pub flange_rotation_std_mrad: Option<[f64; 3]>,
    /// Every measuring point of the setup's tool.
    pub measuring_points: Vec<PointDocument>,
    /// The TCP's position, base frame, mm.
    pub tcp_mm: [f64; 3],
    /// The TCP's displacement, base frame, mm.
    pub tcp_deflection_mm: [f64; 3],
    /// Its standard deviation, mm.
    pub tcp_deflection_std_mm: Option<[f64; 3]>,
    /// The TCP displacement's length, mm.
    pub tcp_deflection_norm_mm: f64,
    /// Its prediction interval `[lower, upper]` per coordinate at `prediction_level`, base frame,
    /// mm (`null` ends: unbounded); `null` without a stiffness file that holds held-out residuals
    /// (`identify --cross-validate`).
    pub tcp_deflection_interval_mm: Option<[[Option<f64>; 2]; 3]>,
    /// The level of the prediction intervals (`--level`).
    pub prediction_level: f64,
    /// The tool's rotation, base frame, mrad.
    pub tcp_rotation_mrad: [f64; 3],
    /// Its standard deviation, mrad.
    pub tcp_rotation_std_mrad: Option<[f64; 3]>,
    /// `C_x` of the loaded point.
    pub cartesian_compliance: ComplianceDocument,
    /// `K_x` of the loaded point; `null` where `C_x` is singular.
    pub cartesian_stiffness: Option<StiffnessDocument>,
    /// The natural frequencies of the posture, Hz, ascending (`K v = w^2 M v`, the model's
    /// springs with the robot's and the tool's mass); `null` where the robot gives no masses.
    pub natural_frequencies_hz: Option<[f64; 6]>,
    /// The modes, lowest first, with the loaded point's direction of motion; `null` as
    /// `natural_frequencies_hz`.
    pub mode_shapes: Option<Vec<ModeShape>>,
    /// The joint-space mass matrix `M(q)`, axis coordinates, kg m^2; `null` without masses.
    pub mass_matrix_kg_m2: Option<[[f64; 6]; 6]>,
    /// The operational-space inertia `Lambda = (J M^-1 J^T)^-1` of the loaded point, base frame,
    /// rows and columns `[v; omega]` (kg, kg m, kg m^2); `null` without masses or at a singular
    /// posture.
    pub operational_inertia_si: Option<[[f64; 6]; 6]>,
    /// The effective mass along the wrench's force with the other five directions held (a drill
    /// in its hole), `u^T Lambda_vv u`, kg; `null` without masses or a force.
    pub effective_mass_kg: Option<f64>,
    /// Its standard deviation from the setup's `[masses] sd_pct`, kg; `null` without it.
    pub effective_mass_std_kg: Option<f64>,
    /// The effective mass along the force with the point free, `1 / (u^T (J M^-1 J^T)_vv u)`, kg.
    pub effective_mass_free_kg: Option<f64>,
    /// The compliance along the force, `u^T C_x u`, mm/N.
    pub compliance_along_force_mm_per_n: Option<f64>,
    /// The energy the force stores in the compliance, `F^2 c / 2`, J.
    pub surge_energy_j: Option<f64>,
    /// The speed the force's sudden release (a drill's breakthrough) gives the loaded point,
    /// `F sqrt(c / m)` with `m` the held effective mass, mm/s.
    pub surge_mm_s: Option<f64>,
    /// Its standard deviation from the compliance covariance and the setup's `[masses]
    /// sd_pct` (first order), mm/s; `null` with neither.
    pub surge_std_mm_s: Option<f64>,
    /// Whether the posture lies outside the region the stiffness was identified from (an axis
    /// beyond the identification postures' range widened by its margin): the prediction
    /// extrapolates; `null` when the stiffness records no region (the setup's nominal, values
    /// given directly, a stiffness file written before files carried it).
    pub extrapolates: Option<bool>,
    /// The axes outside that region, with their angle and the identification postures' range;
    /// empty inside it.
    pub outside_region: Vec<AxisOutside>,
    /// The region of axis angles the stiffness was identified from; `null` as `extrapolates`.
    pub region: Option<RegionSection>,
    /// What to look at before trusting the document (placeholder masses, a posture outside the
    /// region the stiffness was identified from).
    pub warnings: &'a [Warning],
}

/// One axis of a posture outside the region the stiffness was identified from.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct AxisOutside {
    /// The axis, 1-based.
    pub axis: usize,
    /// Its angle, deg.
    pub q_deg: f64,
    /// The identification postures' range of this axis `[lower, upper]`, deg (the region adds
    /// the margin at both ends).
    pub identified_deg: [f64; 2],
}

impl AxisOutside {
    /// The documents' form of `v`.
    pub(crate) fn new(v: &Violation) -> Self {
        AxisOutside {
            axis: v.axis + 1,
            q_deg: v.value.to_degrees(),
            identified_deg: [v.lower.to_degrees(), v.upper.to_degrees()],
        }
    }
}

/// One measuring point's displacement.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PointDocument {
    /// The measuring point (1-based).
    pub point: usize,
    /// Its position, base frame, mm.
    pub position_mm: [f64; 3],
    /// Its displacement, base frame, mm.
    pub displacement_mm: [f64; 3],
    /// Its standard deviation, mm.
    pub displacement_std_mm: Option<[f64; 3]>,
    /// Its prediction interval `[lower, upper]` per coordinate, base frame, mm (as
    /// `tcp_deflection_interval_mm`).
    pub displacement_interval_mm: Option<[[Option<f64>; 2]; 3]>,
    /// The displacement's length, mm.
    pub displacement_norm_mm: f64,
}

/// `C_x` of the loaded point, base frame, by blocks and whole (rows and columns `[f; m]` and
/// `[translation; rotation]`, SI).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ComplianceDocument {
    /// Translation per force, m/N.
    pub translation_per_force_m_per_n: [[f64; 3]; 3],
    /// Translation per moment, m/Nm.
    pub translation_per_moment_m_per_nm: [[f64; 3]; 3],
    /// Rotation per force, rad/N.
    pub rotation_per_force_rad_per_n: [[f64; 3]; 3],
    /// Rotation per moment, rad/Nm.
    pub rotation_per_moment_rad_per_nm: [[f64; 3]; 3],
    /// The whole 6x6 matrix, SI.
    pub matrix_si: [[f64; 6]; 6],
    /// The whole matrix in the units of the text: rows dx, dy, dz (mm), drx, dry, drz (mrad)
    /// per columns fx, fy, fz (kN), mx, my, mz (kNm); `matrix_si` times 1e6.
    pub matrix_mm_mrad_per_kn_knm: [[f64; 6]; 6],
}

/// `K_x = C_x^-1` of the loaded point, base frame, by blocks and whole (SI).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct StiffnessDocument {
    /// Force per translation, N/m.
    pub force_per_translation_n_per_m: [[f64; 3]; 3],
    /// Force per rotation, N/rad.
    pub force_per_rotation_n_per_rad: [[f64; 3]; 3],
    /// Moment per translation, Nm/m.
    pub moment_per_translation_nm_per_m: [[f64; 3]; 3],
    /// Moment per rotation, Nm/rad.
    pub moment_per_rotation_nm_per_rad: [[f64; 3]; 3],
    /// The whole 6x6 matrix, SI.
    pub matrix_si: [[f64; 6]; 6],
    /// The whole matrix in the units of the text: rows fx, fy, fz (N), mx, my, mz (Nm) per
    /// columns dx, dy, dz (um), drx, dry, drz (urad); `matrix_si` times 1e-6.
    pub matrix_n_nm_per_um_urad: [[f64; 6]; 6],
}

impl Report {
    /// The document this report is written as: its view in mm, mrad and N (what it serialises
    /// to).
    pub fn document(&self) -> Document<'_> {
        let report = self;
        let tcp = &report.tcp;
        let d = &tcp.deflection;
        let (c, k) = (&report.cartesian_compliance, &report.cartesian_stiffness);
        let mass = report.mass.as_ref();
        let posture = mass.map(|m| &m.posture);
        let (frequencies, shapes) = match posture {
            Some(p) => mass::modes(p.modes.as_ref(), &p.point_directions),
            None => (None, None),
        };
        let surge = mass.and_then(|m| m.surge.as_ref());
        Document {
            setup: &report.setup,
            q_deg: report.q.map(f64::to_degrees).into(),
            wrench_n_nm: report.wrench.into(),
            wrench_frame: report.frame.name(),
            wrench_point_mm: report.at.map(mm).into(),
            wrench_base_frame_n_nm: report.base_wrench.into(),
            stiffness_nm_per_rad: report.compliance.drives_h().map(|h| 1.0 / h).into(),
            torques_nm: std::array::from_fn(|j| d.torques[j]),
            joint_deflections_mrad: std::array::from_fn(|j| d.joint_deflections[j] * 1e3),
            flange_rotation_mrad: xyz(&d.displacement, 3, 1e3),
            flange_rotation_std_mrad: tcp.std.map(|s| xyz(&s, 3, 1e3)),
            measuring_points: report
                .measuring_points
                .iter()
                .enumerate()
                .map(|(i, p)| PointDocument::new(i, p))
                .collect(),
            tcp_mm: tcp.position.map(mm).into(),
            tcp_deflection_mm: xyz(&d.displacement, 0, 1e3),
            tcp_deflection_std_mm: tcp.std.map(|s| xyz(&s, 0, 1e3)),
            tcp_deflection_norm_mm: xyz(&d.displacement, 0, 1e3)
                .iter()
                .map(|v| v * v)
                .sum::<f64>()
                .sqrt(),
            tcp_deflection_interval_mm: tcp.interval.map(interval_mm),
            prediction_level: report.level,
            tcp_rotation_mrad: xyz(&d.displacement, 3, 1e3),
            tcp_rotation_std_mrad: tcp.std.map(|s| xyz(&s, 3, 1e3)),
            cartesian_compliance: ComplianceDocument {
                translation_per_force_m_per_n: block(c, 0, 0),
                translation_per_moment_m_per_nm: block(c, 0, 3),
                rotation_per_force_rad_per_n: block(c, 3, 0),
                rotation_per_moment_rad_per_nm: block(c, 3, 3),
                matrix_si: block(c, 0, 0),
                matrix_mm_mrad_per_kn_knm: block(&(c * 1e6), 0, 0),
            },
            cartesian_stiffness: k.as_ref().map(|k| StiffnessDocument {
                force_per_translation_n_per_m: block(k, 0, 0),
                force_per_rotation_n_per_rad: block(k, 0, 3),
                moment_per_translation_nm_per_m: block(k, 3, 0),
                moment_per_rotation_nm_per_rad: block(k, 3, 3),
                matrix_si: block(k, 0, 0),
                matrix_n_nm_per_um_urad: block(&(k * 1e-6), 0, 0),
            }),
            natural_frequencies_hz: frequencies,
            mode_shapes: shapes,
            mass_matrix_kg_m2: posture.map(|p| rows(&p.mass_matrix)),
            operational_inertia_si: posture
                .and_then(|p| p.operational_inertia.as_ref())
                .map(rows),
            effective_mass_kg: surge.map(|s| s.mass),
            effective_mass_std_kg: surge.and_then(|s| s.mass_std),
            effective_mass_free_kg: mass.and_then(|m| m.free_mass),
            compliance_along_force_mm_per_n: surge.map(|s| mm(s.compliance)),
            surge_energy_j: surge.map(|s| s.energy),
            surge_mm_s: surge.map(|s| mm(s.speed)),
            surge_std_mm_s: surge.and_then(|s| s.speed_std).map(mm),
            extrapolates: report.outside_region.as_ref().map(|o| !o.is_empty()),
            outside_region: (report.outside_region.iter().flatten())
                .map(AxisOutside::new)
                .collect(),
            region: RegionSection::of(&report.compliance.region),
            warnings: &report.warnings,
        }
    }
}

impl PointDocument {
    /// Measuring point `i` (0-based).
    fn new(i: usize, p: &Point) -> Self {
        let t = p.deflection.displacement.fixed_rows::<3>(0) * 1e3;
        PointDocument {
            point: i + 1,
            position_mm: p.position.map(mm).into(),
            displacement_mm: t.into(),
            displacement_std_mm: p.std.map(|s| xyz(&s, 0, 1e3)),
            displacement_interval_mm: p.interval.map(interval_mm),
            displacement_norm_mm: t.norm(),
        }
    }
}

/// The `N x N` block of `m` from row `r0`, column `c0`.
fn block<const N: usize>(m: &Matrix6<f64>, r0: usize, c0: usize) -> [[f64; N]; N] {
    std::array::from_fn(|r| std::array::from_fn(|c| m[(r0 + r, c0 + c)]))
}

/// Three entries of `v` from `from`, times `scale`.
fn xyz(v: &Vector6<f64>, from: usize, scale: f64) -> [f64; 3] {
    std::array::from_fn(|i| v[from + i] * scale)
}
