//! The error budget in the compensate documents: each point's bound and its parts (the CSV's
//! and the JSON points' `bound_*` columns), the worst points of the path ([`Worst`]), the
//! summary ([`BudgetSummary`]) and the refusal of a path whose bound exceeds the largest error
//! accepted (`--max-error-mm`).

use crate::app::document::{finite, mm};
use serde::Serialize;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};
use stiffid_machining::compensate::{budget::PARTS, Compensated};

/// The budget's columns of the CSV and of every JSON point, mm: the bound, then its parts
/// ([`PARTS`]: an absent part empty), then with the free tool axis the bound at the path's own
/// rotation.
pub const COLUMNS: [&str; 7] = [
    "bound_mm",
    "bound_left_mm",
    "bound_compensation_mm",
    "bound_calibration_mm",
    "bound_force_mm",
    "bound_model_form_mm",
    "bound_before_mm",
];

/// The values of [`COLUMNS`] for one point, mm; `None` for an absent part or an infinite value.
pub fn values(r: &Compensated) -> Vec<Option<f64>> {
    let b = &r.budget;
    let mut v = vec![finite(mm(b.bound))];
    v.extend(b.parts().iter().map(|p| p.and_then(|p| finite(mm(p)))));
    v.push(r.bound_before.and_then(|b| finite(mm(b))));
    v
}

/// One of the worst points of a path.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct WorstPoint {
    /// Its line in the path or program file.
    pub line: u64,
    /// Its bound, mm; `null` when infinite (too few held-out values for the level).
    pub bound_mm: Option<f64>,
    /// The part that contributes most to it: `left`, `compensation`, `calibration`, `force` or
    /// `model_form`.
    pub dominant: &'static str,
    /// That part, mm.
    pub dominant_mm: Option<f64>,
}

/// The points of largest bound along a path, accumulated point by point.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Worst {
    /// At most [`Worst::KEPT`], largest bound first: (bound m, line, dominant part, its value m).
    points: Vec<(f64, u64, &'static str, f64)>,
    /// Sum of the bounds, m, and the points added.
    sum: f64,
    count: usize,
    /// Which parts are absent at some point.
    absent: [bool; 5],
    /// With the free tool axis: the largest bound at the path's own rotation, m.
    max_before: Option<f64>,
    /// Each part's largest value and sum over the points, m ([`PARTS`]' order).
    parts: [(f64, f64); 5],
    /// The largest error accepted (`--max-error-mm`), m.
    pub limit: Option<f64>,
}

impl Worst {
    /// The worst points kept.
    pub(crate) const KEPT: usize = 10;

    /// Adds a point from `line`.
    pub(crate) fn add(&mut self, line: u64, r: &Compensated) {
        let b = &r.budget;
        let (part, value) = b.dominant();
        self.sum += b.bound;
        self.count += 1;
        for (k, p) in b.parts().iter().enumerate() {
            self.absent[k] |= p.is_none();
            let v = p.unwrap_or(0.0);
            self.parts[k] = (self.parts[k].0.max(v), self.parts[k].1 + v);
        }
        if let Some(before) = r.bound_before {
            self.max_before = Some(self.max_before.map_or(before, |m| m.max(before)));
        }
        let place = (self.points.iter()).position(|w| w.0 < b.bound || w.0.is_nan());
        let entry = (b.bound, line, part, value);
        match place {
            Some(k) => self.points.insert(k, entry),
            None => self.points.push(entry),
        }
        self.points.truncate(Self::KEPT);
    }

    /// The largest bound, m (0 without points).
    pub(crate) fn max(&self) -> f64 {
        self.points.first().map_or(0.0, |w| w.0)
    }

    /// The summary at `level`.
    pub(crate) fn document(&self, level: f64) -> BudgetSummary {
        BudgetSummary {
            level,
            max_bound_mm: self.points.first().and_then(|w| finite(mm(w.0))),
            max_bound_line: self.points.first().map(|w| w.1),
            mean_bound_mm: finite(mm(self.sum / self.count.max(1) as f64)),
            absent: (PARTS.iter().zip(self.absent))
                .filter(|(_, a)| *a)
                .map(|(n, _)| *n)
                .collect(),
            worst: (self.points.iter())
                .map(|w| WorstPoint {
                    line: w.1,
                    bound_mm: finite(mm(w.0)),
                    dominant: w.2,
                    dominant_mm: finite(mm(w.3)),
                })
                .collect(),
            max_bound_before_mm: self.max_before.and_then(|b| finite(mm(b))),
            made_of: self.made_of(),
            meets: self.limit.map(|limit| Meets {
                max_error_mm: mm(limit),
                level,
                meets: self.meets(limit),
            }),
        }
    }

    /// What the error that remains is made of: each part's largest and mean value along the
    /// path, mm (`null` where absent at every point or infinite).
    fn made_of(&self) -> Vec<PartSummary> {
        let n = self.count.max(1) as f64;
        (PARTS.iter().zip(self.parts).enumerate())
            .map(|(k, (name, (max, sum)))| {
                let present = !self.absent[k] || max > 0.0;
                PartSummary {
                    part: name,
                    max_mm: present.then(|| finite(mm(max))).flatten(),
                    mean_mm: present.then(|| finite(mm(sum / n))).flatten(),
                }
            })
            .collect()
    }

    /// Whether every point's bound is within `limit` (m).
    fn meets(&self, limit: f64) -> bool {
        self.points.first().is_none_or(|w| w.0 <= limit)
    }

    /// Refuses a path whose largest bound exceeds `max_error` (m), naming its worst points and
    /// the part that dominates each bound.
    ///
    /// # Errors
    /// [`Error::Gate`] ([`JobOption::MaxErrorMm`]).
    pub(crate) fn refuse_above(&self, max_error: f64, level: f64) -> Result<()> {
        let above: Vec<String> = (self.points.iter())
            .filter(|w| w.0 > max_error || w.0.is_nan())
            .map(|w| {
                format!(
                    "line {}: {} mm, mostly {} ({} mm)",
                    w.1,
                    shown(w.0, level),
                    w.2.replace('_', " "),
                    shown(w.3, level)
                )
            })
            .collect();
        if above.is_empty() {
            return Ok(());
        }
        Err(Error::Gate {
            option: JobOption::MaxErrorMm,
            message: format!(
                "{} mm: meets {} mm at {}%: no, the program's error bound exceeds it (largest {} mm); the worst points: {}; nothing written (a stiffer posture, a placement nearer the robot, a better calibration or a larger limit)",
                shown(max_error, level),
                shown(max_error, level),
                level * 100.0,
                shown(self.max(), level),
                above.join("; ")
            ),
        })
    }
}

/// A length in m shown in mm with 4 significant decimals; an infinite bound at `level` says
/// how many held-out values a finite one needs.
fn shown(x: f64, level: f64) -> String {
    match x.is_finite() {
        true => format!("{:.4}", x * 1e3),
        false => format!(
            "infinite (a finite bound at {}% needs at least {} held-out values)",
            level * 100.0,
            stiffid_core::model::prediction::held_out_needed(level)
        ),
    }
}

/// The error budget along the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct BudgetSummary {
    /// The level of the bound (`--level`).
    pub level: f64,
    /// The largest bound along the path, mm; `null` when infinite.
    pub max_bound_mm: Option<f64>,
    /// Its line.
    pub max_bound_line: Option<u64>,
    /// The mean bound, mm; `null` when infinite.
    pub mean_bound_mm: Option<f64>,
    /// The parts absent somewhere (counted as 0 there): `compensation` without a covariance or
    /// prediction data in the stiffness file, `calibration` for a robot file without
    /// `[held_out]`, `model_form` without the stiffness file's `model_form` (the compared
    /// models' resamples, `identify --compare-models --bootstrap N --stiffness-out`).
    pub absent: Vec<&'static str>,
    /// The points of largest bound (at most 10), largest first.
    pub worst: Vec<WorstPoint>,
    /// With `--free tool-rotation`: the largest bound at the path's own rotation, mm; else `null`.
    pub max_bound_before_mm: Option<f64>,
    /// What the error that remains after compensation is made of: every part of the bound
    /// (`left`, `compensation`, `calibration`, `force`, `model_form`), its largest and mean value
    /// along the path, mm.
    pub made_of: Vec<PartSummary>,
    /// With `--max-error-mm`: whether every point's bound at the level is within it; else
    /// `null`.
    pub meets: Option<Meets>,
}

impl BudgetSummary {
    /// The words for a part of [`BudgetSummary::made_of`] without a value (`max_mm` `null`):
    /// `absent` when it is absent along the path ([`BudgetSummary::absent`]), else `infinite`
    /// with the count of held-out values a finite bound at the level needs, as the bound's own
    /// words say it.
    pub fn no_value(&self, part: &PartSummary) -> String {
        match self.absent.contains(&part.part) {
            true => "absent".into(),
            false => shown(f64::INFINITY, self.level),
        }
    }
}

/// One part of the bound along the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PartSummary {
    /// The part: `left`, `compensation`, `calibration`, `force` or `model_form`.
    pub part: &'static str,
    /// Its largest value along the path, mm; `null` when absent everywhere or infinite.
    pub max_mm: Option<f64>,
    /// Its mean along the path (0 where absent), mm; `null` when absent everywhere or infinite.
    pub mean_mm: Option<f64>,
}

/// Whether a program meets the largest error accepted at the bound's level.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Meets {
    /// The largest error accepted (`--max-error-mm`), mm.
    pub max_error_mm: f64,
    /// The level of the bound.
    pub level: f64,
    /// Every point's bound is within it (a program that does not is refused, exit 1).
    pub meets: bool,
}
