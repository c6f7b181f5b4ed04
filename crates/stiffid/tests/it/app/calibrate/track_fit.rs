//! What the choice of a track's error motions states beside the calibration
//! (`stiffid_metrology::calibration::track_notes`): a held-out error above three times the tracker noise
//! is warned of even where the fit's own residuals are below it, and an order the stations
//! capped is said.

use stiffid::internal::common::warning::WarningKind;
use stiffid::internal::metrology::calibration::motions::{Choice, Tried};
use stiffid::internal::metrology::calibration::track_notes::notes;

/// The guide's track cell (a 6 m track and a two-axis positioner; tracker noise 0.0068 mm).
fn cell() -> stiffid::Setup {
    let text = include_str!("../../../../../../examples/track/track-cell.toml");
    stiffid::internal::setup::parse(text, "track-cell.toml", |n, _| {
        stiffid::internal::robot::presets::get(n)
    })
    .unwrap()
}

fn tried(order: usize, rms: f64) -> Tried {
    Tried {
        orders: vec![order, 0, 0],
        rms,
        kept: true,
    }
}

#[test]
fn a_held_out_misfit_and_a_capped_order_are_stated() {
    let s = cell();
    let sd = s.noise().reading_sd();
    // Six stations: orders 0 to 4 tried, 4 kept; held out at 3.8 times the noise per point.
    let rms = 3.8 * 3f64.sqrt() * sd;
    let choice = Choice {
        orders: vec![4, 0, 0],
        rms: Some(rms),
        tried: (0..=4).map(|k| tried(k, rms)).collect(),
    };
    let w = notes(&s, Some(&choice), 2.3);
    let misfit = w
        .iter()
        .find(|w| w.kind == WarningKind::Misfit)
        .expect("misfit");
    assert!(
        misfit.message.contains("3.8 times the tracker noise")
            && misfit.message.contains("2.3 times"),
        "{}",
        misfit.message
    );
    let capped = w
        .iter()
        .find(|w| w.kind == WarningKind::Unidentifiable)
        .expect("capped");
    assert!(
        capped.message.contains("'track' are of order 4")
            && capped.message.contains("6 distinct positions"),
        "{}",
        capped.message
    );
    // Held out within three times the noise, an order below the cap: nothing to say.
    let quiet = Choice {
        orders: vec![2, 0, 0],
        rms: Some(2.0 * 3f64.sqrt() * sd),
        tried: (0..=6).map(|k| tried(k, rms)).collect(),
    };
    assert!(notes(&s, Some(&quiet), 1.0).is_empty());
}
