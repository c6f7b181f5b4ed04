//! The table's candidate angles (`crate::selection::table`).

use super::station_tests::track_cell;
use crate::selection::table::{check_sights, table_grid, CANDIDATE_ANGLES};
use stiffid_core::robot::external::ExternalValues;

#[test]
fn the_grid_is_the_middles_of_equal_parts_of_each_positioner_axis() {
    let setup = track_cell();
    let axes = setup.robot().external().unwrap();
    let carrier = ExternalValues::new(&[3.0, 0.0, 0.0]).unwrap();
    let grid = table_grid(axes, CANDIDATE_ANGLES, &carrier);
    // Two positioner axes: round(64^(1/2)) = 8 values each, the tilt within -95..95 deg and the
    // turn within -360..360 deg, at (j + 1/2) / 8 of each travel.
    assert_eq!(grid.len(), 64);
    let tilt = |j: f64| (-95.0 + (j + 0.5) / 8.0 * 190.0_f64).to_radians();
    let turn = |j: f64| (-360.0 + (j + 0.5) / 8.0 * 720.0_f64).to_radians();
    for (i, e) in grid.iter().enumerate() {
        let v = e.as_slice();
        let (a, b) = ((i / 8) as f64, (i % 8) as f64);
        assert_eq!(v[0], 3.0);
        assert!((v[1] - tilt(a)).abs() < 1e-12, "{i}: {v:?}");
        assert!((v[2] - turn(b)).abs() < 1e-12, "{i}: {v:?}");
    }
    // A count of 10 over two axes: round(sqrt(10)) = 3 values each.
    assert_eq!(table_grid(axes, 10, &carrier).len(), 9);
}

#[test]
fn a_cell_without_table_reflectors_has_no_sight_to_check() {
    let setup = track_cell();
    assert!(check_sights(&setup, None).is_ok());
}
