//! Whether the stiffness file's model and the recommended model rank the path's postures alike.
//!
//! A stiffness file written by `identify --compare-models --bootstrap N --stiffness-out` holds the
//! setup's model fitted to every posture (the six drives, for a setup whose `[model]` declares no
//! spring) and, in its `model_form`, the comparison's recommended model fitted to the same postures
//! ([`stiffid_core::model::ModelForm::recommended`]). Where the two differ, the job sets the TCP
//! translation each predicts at every compensated point (the length `|dp|`, m, at the posture
//! chosen, under the point's wrench) side by side: Spearman's rank correlation `rho` of the two
//! over the path's points ([`stiffid_core::math::spearman`]) says whether they rank the postures
//! alike (where the arm is softest, which rotation of the spindle deflects least). Below 0.5 they
//! do not: the document's `model_ranking` lists the points whose ranks differ most with both values
//! and ranks, and a warning of kind `model-form` says so.

use serde::Serialize;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::math::{ranks, spearman};
use stiffid_core::model::FormModel;
use stiffid_core::setup::Arm;
use stiffid_machining::compensate::Compensated;

/// Spearman's rho below which the two models rank the postures differently: at 0.5 a model
/// explains a quarter of the other's rank variance; the two models of the same data agreeing
/// on where the arm is soft give 0.9 and more.
pub(crate) const DISAGREEMENT_RHO: f64 = 0.5;

/// The most points the document lists (those whose ranks differ most).
pub(crate) const MAX_LISTED: usize = 10;

/// The two models' translations at every point so far (module docs).
pub struct Ranking {
    recommended: FormModel,
    /// The recommended model's virtual springs by name.
    springs: Vec<String>,
    lines: Vec<u64>,
    own: Vec<f64>,
    other: Vec<f64>,
}

/// The document's `model_ranking` (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct RankingDocument {
    /// The recommended model's virtual springs (after the six drives).
    pub recommended_springs: Vec<String>,
    /// The points compared.
    pub points: usize,
    /// Spearman's rank correlation of the two models' deflections over the points; `null` for
    /// fewer than 3 points or a constant deflection.
    pub rho: Option<f64>,
    /// The rho below which the models rank the postures differently (0.5).
    pub threshold_rho: f64,
    /// Whether they rank them alike (`rho` at least `threshold_rho`; `true` without a rho).
    pub agree: bool,
    /// The points whose ranks differ most, at most 10, largest difference first.
    pub largest_rank_differences: Vec<RankedPoint>,
}

/// One point under both models: rank 1 is the largest deflection.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct RankedPoint {
    /// The point's line in its file.
    pub line: u64,
    /// `|dp|` by the stiffness file's model, mm.
    pub deflection_mm: f64,
    /// Its rank among the points by the file's model.
    pub rank: f64,
    /// `|dp|` by the recommended model, mm.
    pub recommended_deflection_mm: f64,
    /// Its rank among the points by the recommended model.
    pub recommended_rank: f64,
}

impl Ranking {
    /// The ranking of `arm`'s model against the recommended one of its compliance's model form
    /// `form`; `None` without one, or when it is the arm's own model (the same springs).
    pub fn new(arm: &Arm, form: Option<&stiffid_core::model::ModelForm>) -> Option<Self> {
        let recommended = form?.recommended.clone()?;
        let names = |m: &stiffid_core::model::Model| -> Vec<String> {
            m.springs().iter().map(|s| s.name.clone()).collect()
        };
        let springs = names(&recommended.model);
        (springs != names(arm.model())).then(|| Ranking {
            recommended,
            springs,
            lines: Vec::new(),
            own: Vec::new(),
            other: Vec::new(),
        })
    }

    /// Adds the point of `line` compensated as `r` on `arm`: `|dp|` of `r.deflection` and of the
    /// recommended model at `r.q` under `r.wrench`.
    pub fn add(&mut self, arm: &Arm, line: u64, r: &Compensated) {
        let frames = arm.robot().frames(&r.q);
        let t = self
            .recommended
            .translations(&frames, &arm.tool().tcp, &r.wrench);
        self.lines.push(line);
        self.own.push(r.deflection.fixed_rows::<3>(0).norm());
        self.other.push(t.first().map_or(f64::NAN, |t| t.norm()));
    }

    /// The document's section and, when the models disagree, the warning (kind `model-form`).
    pub fn finish(self) -> (RankingDocument, Option<Warning>) {
        let rho = spearman(&self.own, &self.other);
        let agree = rho.is_none_or(|r| r >= DISAGREEMENT_RHO);
        let n = self.own.len() as f64;
        let descending = |v: &[f64]| -> Vec<f64> { ranks(v).iter().map(|r| n + 1.0 - r).collect() };
        let (a, b) = (descending(&self.own), descending(&self.other));
        let mut order: Vec<usize> = (0..self.own.len()).collect();
        order.sort_by(|&i, &j| (a[j] - b[j]).abs().total_cmp(&(a[i] - b[i]).abs()));
        let listed: Vec<RankedPoint> = (order.iter().take(MAX_LISTED))
            .map(|&i| RankedPoint {
                line: self.lines[i],
                deflection_mm: self.own[i] * 1e3,
                rank: a[i],
                recommended_deflection_mm: self.other[i] * 1e3,
                recommended_rank: b[i],
            })
            .collect();
        let warning = (!agree).then(|| warning(rho.unwrap_or(f64::NAN), &self.springs, &listed));
        let document = RankingDocument {
            recommended_springs: self.springs,
            points: self.own.len(),
            rho,
            threshold_rho: DISAGREEMENT_RHO,
            agree,
            largest_rank_differences: listed,
        };
        (document, warning)
    }
}

/// The warning of models that rank the points differently, naming the point whose ranks differ
/// most.
fn warning(rho: f64, springs: &[String], listed: &[RankedPoint]) -> Warning {
    let worst = listed.first().map_or(String::new(), |p| {
        format!(
            "; most at line {}: {:.4} mm, rank {}, against {:.4} mm, rank {}",
            p.line, p.deflection_mm, p.rank, p.recommended_deflection_mm, p.recommended_rank
        )
    });
    Warning::new(
        WarningKind::ModelForm,
        format!(
            "the stiffness file's model and the recommended model (the drives with {}) rank the path's postures differently (Spearman's rho {rho:.2} of their deflections, below {DISAGREEMENT_RHO}){worst}: a choice of posture by one model is not one by the other; identify with the recommended model or compare the two (model_ranking)",
            springs.join(", ")
        ),
    )
}
