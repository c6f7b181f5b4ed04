//! What the choice of a track's error motions says beside the calibration's result
//! ([`super::motions`]): its held-out error against the tracker noise, warned of as the fit's
//! own residuals are, and an order that the stations read capped.

use super::motions::Choice;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::Setup;

/// The noise ratio above which the held-out error is warned of (the calibration's misfit
/// ratio).
const MISFIT_RATIO: f64 = 3.0;

/// The highest order the automatic choice tries on a linear axis with enough stations.
const MAX_ORDER: usize = super::motions::MAX_ORDER_TRIED;

/// The warnings of the error motions' `choice` on `setup`'s robot: the held-out RMS error (a
/// 3D length per reading) more than 3 times what the tracker noise leaves,
/// `sqrt(3)` times `reading_sd`, where the fit's own residuals are `noise_ratio` times it; and per
/// linear axis whose chosen order is the highest its distinct positions allowed (two fewer
/// than them) below the highest order tried, a note that the stations capped it.
pub fn notes(setup: &Setup, choice: Option<&Choice>, noise_ratio: f64) -> Vec<Warning> {
    let (Some(c), Some(axes)) = (choice, setup.robot().external()) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if let Some(rms) = c.rms.filter(|_| axes.carrier_len() > 0) {
        let ratio = rms / (3f64.sqrt() * setup.noise().reading_sd());
        if ratio > MISFIT_RATIO {
            out.push(Warning::new(WarningKind::Misfit, format!(
                "the track's error motions hold out at {ratio:.1} times the tracker noise (cross-validation over the postures: {:.4} mm RMS) where the fit's own residuals are {noise_ratio:.1} times it: the model explains the readings it was fitted to better than new ones along the travel; read more stations, or fix the order (--error-motions)",
                rms * 1e3
            )));
        }
    }
    for (i, axis) in axes.axes().iter().enumerate() {
        let highest = (c.tried.iter())
            .filter_map(|t| t.orders.get(i).copied())
            .max()
            .unwrap_or(0);
        let chosen = c.orders.get(i).copied().unwrap_or(0);
        let linear = axis.kind == stiffid_core::robot::external::AxisKind::Linear;
        if linear && c.rms.is_some() && chosen == highest && highest < MAX_ORDER {
            out.push(Warning::new(WarningKind::Unidentifiable, format!(
                "the error motions of '{}' are of order {chosen}, the highest its {} distinct positions in the readings allow (two fewer; up to {MAX_ORDER} with more): a higher order was not tried; read more stations along the travel to try one",
                axis.name,
                chosen + 2
            )));
        }
    }
    out
}
