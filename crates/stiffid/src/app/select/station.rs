//! Where a robot on a track (or with other external axes) stands for the group: the selection
//! at each requested station, the best kept ([`stiffid_design::selection::station`]).

use super::{Report, Request};
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::Result;
use stiffid_design::selection::station as design;
pub(crate) use stiffid_design::selection::station::Station;

/// The selection at each of the request's stations, the best kept with every station's value
/// ([`Report::station`], [`Report::stations`]); `run` selects on one setup.
///
/// # Errors
/// Those of [`design::best`] (the stations); those of `run`.
pub(super) fn at_stations(
    request: &Request,
    run: impl Fn(&Request) -> Result<Report>,
) -> Result<Report> {
    let at = |setup: &stiffid_core::Setup| {
        run(&Request {
            setup,
            ..request.clone()
        })
    };
    let (e, best, stations) =
        design::best(request.setup, &request.stations, at, |r: &Report| r.value)?;
    Ok(Report {
        station: Some(e),
        stations,
        ..best
    })
}

/// Refuses stations on a robot without external axes, none on a robot with them, or more
/// than [`MAX_STATIONS`] ([`design::check`]).
pub(super) fn checked(request: &Request) -> Result<()> {
    design::check(request.setup, &request.stations)
}

/// The request's setup with the arm at station `e` ([`design::setup_at`]).
pub(super) fn setup_at(request: &Request, e: &ExternalValues) -> Result<stiffid_core::Setup> {
    design::setup_at(request.setup, e)
}
