//! Where the arm stands for a group (`crate::selection::station`) and the campaign's
//! stations (`crate::selection::campaign::check`).

use crate::selection::campaign;
use crate::selection::station::{best, check, setup_at, MAX_STATIONS};
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::presets;
use stiffid_core::setup;
use stiffid_core::Setup;
use stiffid_core::{Error, JobOption};

/// The example track cell: a track (`e1`), a tilt-rotate positioner (`e2`, `e3`).
pub(super) fn track_cell() -> Setup {
    let text = include_str!("../../../../examples/track/track-cell.toml");
    setup::parse(text, "track-cell.toml", |name, _| presets::get(name)).unwrap()
}

fn e(values: &[f64]) -> ExternalValues {
    ExternalValues::new(values).unwrap()
}

fn station_message(r: stiffid_core::Result<impl std::fmt::Debug>) -> String {
    match r.unwrap_err() {
        Error::InvalidOption {
            option: JobOption::Station,
            message,
        } => message,
        other => panic!("{other:?}"),
    }
}

#[test]
fn stations_are_refused_where_the_robot_has_no_external_axes_and_needed_where_it_has() {
    let fixed = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    let m = station_message(check(&fixed, &[e(&[1.0])]));
    assert_eq!(m, "the robot has no external axes: give no station");
    assert!(
        check(&fixed, &[]).is_err(),
        "no external axes: no station at all"
    );
    let track = track_cell();
    let none = best(&track, &[], |_| Ok(0.0), |v: &f64| *v);
    let m = station_message(none);
    assert!(m.contains("give 1 to 100 stations"), "{m}");
    let many = vec![e(&[0.0, 0.0, 0.0]); MAX_STATIONS + 1];
    assert!(station_message(check(&track, &many)).contains("e1_mm"));
    assert!(check(&track, &[e(&[0.5, 0.0, 0.0]), e(&[3.0, 0.0, 0.0])]).is_ok());
}

#[test]
fn a_station_off_the_travel_is_refused_as_a_station() {
    let track = track_cell();
    let m = station_message(setup_at(&track, &e(&[100.0, 0.0, 0.0])));
    assert!(m.contains("e1"), "{m}");
    assert!(setup_at(&track, &e(&[3.0, 0.0, 0.0])).is_ok());
}

#[test]
fn the_best_station_is_the_smallest_value_the_first_of_equal_ones() {
    let track = track_cell();
    let given = [
        e(&[0.5, 0.0, 0.0]),
        e(&[2.0, 0.0, 0.0]),
        e(&[3.5, 0.0, 0.0]),
        e(&[5.0, 0.0, 0.0]),
    ];
    // Each station's "group value": 3, 1, 1, 2 (ties kept at the first).
    let values = [3.0, 1.0, 1.0, 2.0];
    let mut k = 0;
    let run = |_: &stiffid_core::Setup| {
        k += 1;
        Ok((k, values[k - 1]))
    };
    let (at, found, tried) = best(&track, &given, run, |f: &(usize, f64)| f.1).unwrap();
    assert_eq!(at, given[1]);
    assert_eq!(found, (2, 1.0));
    let listed: Vec<(ExternalValues, f64)> = tried.iter().map(|s| (s.e, s.value)).collect();
    let expected: Vec<(ExternalValues, f64)> = given.iter().copied().zip(values).collect();
    assert_eq!(listed, expected);
}

#[test]
fn a_campaign_needs_two_postures_per_station_and_distinct_stations() {
    let s = [
        e(&[0.0, 0.0, 0.0]),
        e(&[3.0, 0.0, 0.0]),
        e(&[6.0, 0.0, 0.0]),
    ];
    assert!(campaign::check(6, &s).is_ok());
    let m = station_message(campaign::check(5, &s));
    assert!(m.contains("give at least 6 postures"), "{m}");
    let repeated = [s[0], s[1], s[0]];
    let m = station_message(campaign::check(6, &repeated));
    assert!(m.starts_with("station 3 repeats station 1"), "{m}");
}
