//! The surge and chatter of a compensated program per operation ([`stiffid_machining::dynamics`]
//! per point): the largest drilling surge and its line, the range of the milling points' first
//! natural frequency, and a [`WarningKind::Chatter`] warning for an operation with a point
//! within [`CLOSE`] of a tooth-passing harmonic.

use crate::app::document::finite;
use serde::Serialize;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_machining::compensate::PathPoint;
use stiffid_machining::dynamics::{Dynamics, CLOSE};
use stiffid_machining::process::{Kind, Process};

/// The dynamics of one operation of a program. Units in the key names.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct OperationDynamics {
    /// The operation's name.
    pub operation: String,
    /// `milling` or `drilling`.
    pub kind: &'static str,
    /// Drilling: its exits (the points where the drill leaves the material); milling: its points.
    pub points: usize,
    /// Drilling: the largest breakthrough surge over its exits, mm/s; `null` for milling or
    /// without a mass model.
    pub max_surge_mm_s: Option<f64>,
    /// Its standard deviation from the compliance covariance, mm/s; `null` without one.
    pub max_surge_std_mm_s: Option<f64>,
    /// The held effective mass along the drill at that exit, kg.
    pub max_surge_effective_mass_kg: Option<f64>,
    /// The program line of that exit.
    pub max_surge_line: Option<u64>,
    /// With the free tool axis: the largest surge over its exits at the path's own rotation about
    /// tool z (before the rotation was chosen), mm/s.
    pub max_surge_before_mm_s: Option<f64>,
    /// Milling: the lowest and highest first natural frequency over its points, Hz.
    pub first_frequency_hz: Option<[f64; 2]>,
    /// Milling with `cut.spindle_rpm`: the tooth-passing frequency (flutes x spindle speed), Hz.
    pub tooth_passing_hz: Option<f64>,
    /// The point nearest a harmonic of it: the relative distance of its first frequency to the
    /// harmonic, %.
    pub nearest_harmonic_pct: Option<f64>,
    /// That harmonic's order (1 the tooth-passing frequency itself).
    pub nearest_harmonic_order: Option<u32>,
    /// That point's program line.
    pub nearest_harmonic_line: Option<u64>,
}

/// The dynamics of every operation of `process` that cuts a point, in process order, and a
/// chatter warning for each milling operation with a point within [`CLOSE`] of a harmonic.
pub(crate) fn operations(
    process: &Process,
    points: &[PathPoint],
    operations: &[Option<usize>],
    dynamics: &[Dynamics],
) -> (Vec<OperationDynamics>, Vec<Warning>) {
    let mut out = Vec::new();
    let mut warnings = Vec::new();
    for (index, op) in process.operations.iter().enumerate() {
        let mine = || {
            points
                .iter()
                .zip(operations)
                .zip(dynamics)
                .filter(move |((_, o), _)| **o == Some(index))
                .map(|((p, _), d)| (p.line, d))
        };
        let mut doc = OperationDynamics {
            operation: op.name.clone(),
            kind: "milling",
            points: 0,
            max_surge_mm_s: None,
            max_surge_std_mm_s: None,
            max_surge_effective_mass_kg: None,
            max_surge_line: None,
            max_surge_before_mm_s: None,
            first_frequency_hz: None,
            tooth_passing_hz: None,
            nearest_harmonic_pct: None,
            nearest_harmonic_order: None,
            nearest_harmonic_line: None,
        };
        match &op.kind {
            Kind::Drilling(_) => {
                doc.kind = "drilling";
                let surges: Vec<_> = mine()
                    .filter_map(|(l, d)| d.surge.map(|s| (l, s)))
                    .collect();
                doc.points = surges.len();
                if let Some((line, s)) =
                    surges.iter().max_by(|a, b| a.1.speed.total_cmp(&b.1.speed))
                {
                    doc.max_surge_mm_s = Some(s.speed * 1e3);
                    doc.max_surge_std_mm_s = s.speed_std.map(|v| v * 1e3);
                    doc.max_surge_effective_mass_kg = Some(s.mass);
                    doc.max_surge_line = Some(*line);
                }
                doc.max_surge_before_mm_s = mine()
                    .filter_map(|(_, d)| d.surge_before.map(|s| s.speed * 1e3))
                    .reduce(f64::max);
            }
            Kind::Milling(m) => {
                doc.points = mine().count();
                doc.tooth_passing_hz = m.tooth_passing_frequency();
                let firsts: Vec<f64> = mine().filter_map(|(_, d)| d.first_frequency).collect();
                doc.first_frequency_hz = (!firsts.is_empty()).then(|| {
                    let low = firsts.iter().copied().fold(f64::INFINITY, f64::min);
                    let high = firsts.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    [low, high]
                });
                let nearest = mine()
                    .filter_map(|(l, d)| d.harmonic.zip(d.first_frequency).map(|(h, f)| (l, h, f)))
                    .min_by(|a, b| a.1.distance.total_cmp(&b.1.distance));
                if let Some((line, h, f)) = nearest {
                    doc.nearest_harmonic_pct = finite(h.distance * 100.0);
                    doc.nearest_harmonic_order = Some(h.order);
                    doc.nearest_harmonic_line = Some(line);
                    if h.distance <= CLOSE {
                        let t = doc.tooth_passing_hz.unwrap_or(f64::NAN);
                        warnings.push(Warning::new(
                            WarningKind::Chatter,
                            format!(
                                "milling operation '{}': at line {line} the first natural frequency {f:.1} Hz is within {:.1}% of {} x the tooth-passing frequency {t:.1} Hz ({} flutes): chatter is likely there; change the spindle speed or the posture",
                                op.name,
                                h.distance * 100.0,
                                h.order,
                                m.flutes
                            ),
                        ));
                    }
                }
            }
        }
        if doc.points > 0 {
            out.push(doc);
        }
    }
    (out, warnings)
}
