//! The ladder of the calibration's models in its document (mm and deg).

use stiffid_core::common::choice::Choice;
use stiffid_metrology::calibration::judgement::ladder::Ladder;
use stiffid_metrology::calibration::judgement::why;

/// The ladder in the calibration's document.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct LadderDocument {
    /// The groups of postures held out in turn (posture `i` in group `i mod folds`); 0 when
    /// the ladder was not climbed (too few postures: its first rung fitted).
    pub folds: usize,
    /// The rungs, simplest first: the gravity models without maps, then with them.
    pub rungs: Vec<RungDocument>,
    /// The rung fitted: the simplest within one standard error of the best held-out error.
    pub chosen: usize,
    /// The scored rung with the least held-out error (it differs from `chosen` where the
    /// one-standard-error rule fitted a simpler rung); `null` when none was scored.
    pub best: Option<usize>,
    /// Why `chosen` was fitted, in words: where `best` differs, the one-standard-error rule with
    /// its figures (the paired per-posture differences of the held-out squared errors).
    pub why: String,
    /// The lower ends of the box of the region where the robot is used, over which each rung's
    /// `workspace_sd_mm` is taken (the joint-space hull of the fitted and held-out postures and
    /// the setup's test postures: 512 postures, half of them those and half on the segment
    /// between two of them, within the joint limits and the setup's bounds), deg.
    pub region_lower_deg: [f64; 6],
    /// The upper ends of that region, deg.
    pub region_upper_deg: [f64; 6],
}

/// A rung of the ladder in the document.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct RungDocument {
    /// Its gravity terms: `none`, `arm`, `lumped`, `lumped-links` or `masses`.
    pub gravity: &'static str,
    /// Whether it fits the joint error maps (chosen inside each training set).
    pub maps: bool,
    /// Its held-out RMS error over the groups (the nested figure), mm; `null` when not scored
    /// (a fit that does not converge, is ill-conditioned or fails; a model skipped because it
    /// extrapolates keeps its figure).
    pub held_out_rms_mm: Option<f64>,
    /// Why it was skipped; `null` when scored.
    pub skipped: Option<String>,
    /// The RMS standard deviation of its gravity model's predicted positions over postures
    /// spread over the region where the robot is used (within `region_lower_deg` to
    /// `region_upper_deg`), from the fit's covariance, mm: how far the readings determine it
    /// where the robot works; `null` when not computed.
    pub workspace_sd_mm: Option<f64>,
}

impl LadderDocument {
    /// The document of `ladder`.
    pub(crate) fn new(ladder: &Ladder) -> Self {
        LadderDocument {
            folds: ladder.folds,
            rungs: (ladder.rungs.iter())
                .map(|r| RungDocument {
                    gravity: r.gravity.name(),
                    maps: r.maps,
                    held_out_rms_mm: r.rms.map(crate::app::document::mm),
                    skipped: r.skipped.clone(),
                    workspace_sd_mm: r.spread.map(crate::app::document::mm),
                })
                .collect(),
            chosen: ladder.chosen,
            best: why::best(&ladder.rungs),
            why: why::why(ladder),
            region_lower_deg: ladder.region.lower.map(f64::to_degrees).into(),
            region_upper_deg: ladder.region.upper.map(f64::to_degrees).into(),
        }
    }
}
