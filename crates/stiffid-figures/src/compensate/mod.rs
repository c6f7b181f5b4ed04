//! The figures of a compensation (`stiffid compensate --report`, Python's `stiffid.compensate(...,
//! figures=True)`), from the compensate job's report: the TCP deflection along the
//! path before and after ([`path::deflection`]), the path over the robot ([`path::path`]), for a
//! program the process force and each segment's deflection ([`machining`]), with the map of the
//! free rotation the map ([`map`]).

pub mod machining;
pub mod map;
pub mod path;

use crate::Drawing;
use stiffid::app::compensate::Report;
use stiffid_core::Setup;
use stiffid_machining::compensate::Compensated;

/// The results of the points the job's summary kept for the figures ([`Report::summary`]'s
/// `sample`, every k-th point), in path order.
pub fn sample(report: &Report) -> Vec<Compensated> {
    report
        .summary
        .sample
        .iter()
        .map(|(_, c)| c.clone())
        .collect()
}

/// Every figure of the compensation on `setup` whose job returned `report`, in report order: `deflection`, `path`, for a program `force` and `segments`, with the map `map`;
/// `sample` is [`sample`] of `report`.
pub fn figures<'a>(
    setup: &'a Setup,
    sample: &'a [Compensated],
    report: &'a Report,
) -> Vec<Drawing<'a>> {
    let mut all = vec![path::deflection(sample), path::path(setup, sample)];
    if let Some(p) = &report.program {
        all.push(machining::force(&report.summary.sample));
        all.push(machining::segments(&p.segments));
    }
    if let Some(map) = &report.map {
        all.push(map::figure(map));
    }
    all
}
