//! The joint error maps' part of the calibration document ([`super::document::Document::maps`]).

use crate::app::document::mm;
use serde::Serialize;

/// The joint error maps ([`stiffid_metrology::calibration::maps`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct MapsDocument {
    /// What was asked: `auto`, `none` or the joints with their harmonics and backlash terms
    /// (`J1:16,J3:8b,J4:b`).
    pub asked: String,
    /// The distinct postures of the fitted readings.
    pub postures: usize,
    /// Why no map was considered or why none is fitted (the ladder chose the model without);
    /// `null` when maps were considered and chosen.
    pub skipped: Option<String>,
    /// The maps fitted, `J3:16,J5:8b` (joint and harmonics, `b` a backlash term, `J2:b` the
    /// backlash alone), or `none`.
    pub chosen: String,
    /// The ridge of the maps fitted (per reading, dimensionless); `null` without maps.
    pub ridge: Option<f64>,
    /// The choice's held-out RMS error in the cross-validation inside the fitted readings (the
    /// figure the choice was tuned on), mm; `null` when maps were not considered.
    pub inner_rms_mm: Option<f64>,
    /// The same without maps, mm.
    pub inner_none_rms_mm: Option<f64>,
    /// Every candidate the choice evaluated, in order.
    pub tried: Vec<MapTried>,
    /// The held-out gain of the choice (the honest figure): an outer cross-validation that makes
    /// the whole choice on each fold's training postures; `null` when maps were not considered
    /// or `auto` keeps none on every posture (the model with maps is then the one without).
    pub nested: Option<MapsNested>,
}

/// A candidate of the maps' choice.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct MapTried {
    /// Its maps, `J3:16,J5:8`.
    pub maps: String,
    /// Its best ridge.
    pub ridge: f64,
    /// Its held-out RMS error (inner cross-validation), mm.
    pub rms_mm: f64,
    /// Whether the forward selection kept it.
    pub kept: bool,
}

/// The nested held-out gain of choosing maps.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct MapsNested {
    /// The outer folds.
    pub folds: usize,
    /// The held-out RMS error without maps, mm.
    pub none_rms_mm: f64,
    /// The held-out RMS error with the maps each fold chose on its own training postures, mm.
    pub rms_mm: f64,
    /// The maps each outer fold chose.
    pub choices: Vec<String>,
}

pub(super) fn maps_document(m: &super::Maps) -> MapsDocument {
    use stiffid_metrology::calibration::maps::{JointMaps, Spec};
    let choice = m.choice.as_ref();
    let chosen = choice.map_or(JointMaps::NONE, |c| c.maps);
    MapsDocument {
        asked: match m.spec {
            Spec::Auto => "auto".into(),
            Spec::None => "none".into(),
            Spec::Fixed(h) => stiffid_metrology::calibration::maps::name(&h),
        },
        postures: m.postures,
        skipped: m.skipped.clone(),
        chosen: stiffid_metrology::calibration::maps::name(&chosen),
        ridge: choice.filter(|_| !chosen.is_none()).map(|c| c.ridge),
        inner_rms_mm: choice.map(|c| mm(c.rms)),
        inner_none_rms_mm: choice.map(|c| mm(c.none_rms)),
        tried: (choice.iter().flat_map(|c| &c.tried))
            .map(|t| MapTried {
                maps: stiffid_metrology::calibration::maps::name(&t.maps),
                ridge: t.ridge,
                rms_mm: mm(t.rms),
                kept: t.kept,
            })
            .collect(),
        nested: m.nested.as_ref().map(|n| MapsNested {
            folds: n.folds,
            none_rms_mm: mm(n.none_rms),
            rms_mm: mm(n.rms),
            choices: n
                .choices
                .iter()
                .map(stiffid_metrology::calibration::maps::name)
                .collect(),
        }),
    }
}
