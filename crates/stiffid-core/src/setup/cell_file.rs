//! The setup file's physical cell: `[cell]` (floor, clearance, obstacles), `[robot_geometry]`
//! (the capsule radii) and `[tracker]`, read into SI units (checked when the setup is built).

use super::{cell, mm, Cell, Obstacle, SetupBuilder, Tracker};
use crate::common::limits;
use crate::robot::file::TransformFile;
use crate::Result;
use nalgebra::Vector3;
use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CellFile {
    floor_z_mm: Option<f64>,
    clearance_mm: Option<f64>,
    #[serde(default)]
    obstacle: Vec<ObstacleFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObstacleFile {
    name: String,
    #[serde(deserialize_with = "crate::common::exact::array")]
    min_mm: [f64; 3],
    #[serde(deserialize_with = "crate::common::exact::array")]
    max_mm: [f64; 3],
    carried_by: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GeometryFile {
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    link_radius_mm: Option<[f64; 7]>,
    tool_radius_mm: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TrackerFile {
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    position_mm: Option<[f64; 3]>,
    max_incidence_deg: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option_arrays")]
    measuring_normals: Option<Vec<[f64; 3]>>,
    base_from_tracker: Option<TransformFile>,
    registration_uncertainty_mm: Option<f64>,
}

/// The `[cell]` table in SI units (checked when the setup is built).
pub(super) fn read_cell(f: CellFile) -> Cell {
    Cell {
        floor_z: f.floor_z_mm.map(|z| z * 1e-3),
        clearance: f.clearance_mm.unwrap_or(0.0) * 1e-3,
        obstacles: f
            .obstacle
            .into_iter()
            .map(|o| Obstacle {
                carried_by: o.carried_by,
                ..Obstacle::fixed(o.name, mm(&o.min_mm), mm(&o.max_mm))
            })
            .collect(),
    }
}

/// The builder with the radii the file gives.
pub(super) fn read_geometry(f: GeometryFile, mut b: SetupBuilder) -> SetupBuilder {
    if let Some(radii) = f.link_radius_mm {
        b = b.with_link_radii(radii.map(|r| r * 1e-3));
    }
    if let Some(r) = f.tool_radius_mm {
        b = b.with_tool_radius(r * 1e-3);
    }
    b
}

/// The `[tracker]` table in SI units: the position is `position_mm`, or the translation of
/// `base_from_tracker` (checked when the setup is built).
pub(super) fn read_tracker(f: TrackerFile) -> Result<Tracker> {
    if let Some(t) = &f.base_from_tracker {
        cell::position("tracker.base_from_tracker.xyz_mm", &t.xyz_mm)?;
        let rpy = &limits::ANGLE_DEG;
        limits::check("tracker.base_from_tracker.rpy_deg", &t.rpy_deg, rpy)?;
    }
    if let Some(u) = f.registration_uncertainty_mm {
        limits::check(
            "tracker.registration_uncertainty_mm",
            &[u],
            &limits::MARGIN_MM,
        )?;
    }
    let base_from_tracker = f.base_from_tracker.map(|t| t.isometry());
    let position = match (f.position_mm, &base_from_tracker) {
        (Some(p), _) => mm(&p),
        (None, Some(t)) => t.translation.vector,
        (None, None) => {
            return Err(super::invalid(
                "tracker",
                "expected position_mm or base_from_tracker",
            ))
        }
    };
    Ok(Tracker {
        position,
        max_incidence: f.max_incidence_deg.map(f64::to_radians),
        measuring_normals: f
            .measuring_normals
            .map_or(Vec::new(), |n| n.into_iter().map(Vector3::from).collect()),
        base_from_tracker,
        registration_uncertainty: f.registration_uncertainty_mm.map(|u| u * 1e-3),
    })
}
