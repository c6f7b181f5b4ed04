//! The surge and chatter of a compensated program per operation ([`stiffid_machining::dynamics`]
//! per point): the largest drilling surge and its line, the range of the milling points' first
//! natural frequency, and a chatter warning for an operation with a point near a tooth-passing
//! harmonic ([`stiffid_machining::dynamics::per_operation`]).

use crate::app::document::finite;
use serde::Serialize;
use stiffid_core::common::warning::Warning;
use stiffid_machining::compensate::PathPoint;
use stiffid_machining::dynamics::{per_operation, Dynamics};
use stiffid_machining::process::Process;

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
/// chatter warning for each milling operation with a point near a harmonic
/// ([`stiffid_machining::dynamics::per_operation`]).
pub(crate) fn operations(
    process: &Process,
    points: &[PathPoint],
    operations: &[Option<usize>],
    dynamics: &[Dynamics],
) -> (Vec<OperationDynamics>, Vec<Warning>) {
    let (summaries, warnings) = per_operation(process, points, operations, dynamics);
    let documents = (summaries.into_iter())
        .map(|s| OperationDynamics {
            operation: process.operations[s.index].name.clone(),
            kind: if s.drilling { "drilling" } else { "milling" },
            points: s.points,
            max_surge_mm_s: s.max_surge.map(|(_, m)| m.speed * 1e3),
            max_surge_std_mm_s: s.max_surge.and_then(|(_, m)| m.speed_std.map(|v| v * 1e3)),
            max_surge_effective_mass_kg: s.max_surge.map(|(_, m)| m.mass),
            max_surge_line: s.max_surge.map(|(line, _)| line),
            max_surge_before_mm_s: s.max_surge_before.map(|v| v * 1e3),
            first_frequency_hz: s.first_frequency,
            tooth_passing_hz: s.tooth_passing,
            nearest_harmonic_pct: s
                .nearest_harmonic
                .and_then(|(_, h)| finite(h.distance * 100.0)),
            nearest_harmonic_order: s.nearest_harmonic.map(|(_, h)| h.order),
            nearest_harmonic_line: s.nearest_harmonic.map(|(line, _)| line),
        })
        .collect();
    (documents, warnings)
}
