//! The table's angles of a calibration design keep the arm clear of the boxes the positioner
//! carries: with a post on the table, the designed postures read at angles chosen without the
//! check meet the post (checked independently, the box turned to each reading's angles); every
//! reading of the design clears it, and the design still separates the calibration's parameters.

use nalgebra::Vector6;
use stiffid::app::purpose::{self, CalibrationOptions};
use stiffid::app::select::CANDIDATE_ANGLES;
use stiffid::internal::design::observability::Placed;
use stiffid::internal::robot::external::ExternalValues;
use stiffid::Setup;

use crate::carried_obstacles::arm_to_box;
use crate::table_design::{designed, SETUP};

/// The table design's cell with a clearance of 20 mm, a tracker in front and a post 1.2 m tall
/// on the table's top, 0.5 to 0.8 m in front of its axis, turned by the table.
const CELL: &str = "\n[cell]\nclearance_mm = 20\n[tracker]\nposition_mm = [3000, -2000, 1500]\n\
                    [[cell.obstacle]]\nname = \"post\"\nmin_mm = [1700, 700, 900]\n\
                    max_mm = [1900, 1000, 2100]\ncarried_by = \"rotate\"\n";

fn cell() -> Setup {
    let text = SETUP.to_string() + CELL;
    stiffid::internal::setup::parse(&text, "table.toml", |name, _| {
        stiffid::internal::robot::presets::get(name)
    })
    .unwrap()
}

/// The smallest distance (m) of the arm's bodies at `q` read at `e` to the post turned there
/// (`setup`'s obstacle 1 where `e` puts it).
fn to_post(setup: &Setup, q: &Vector6<f64>, e: &ExternalValues) -> f64 {
    let post = setup.cell().unwrap().obstacles[0].at(setup.robot().external(), e.as_slice());
    arm_to_box(setup, q, e, &post)
}

#[test]
fn the_table_angles_keep_the_arm_clear_of_a_box_on_the_table() {
    let setup = cell();
    let clearance = setup.cell().unwrap().clearance;
    let (report, _) = designed(&setup);
    // The same postures with the angles chosen over the whole grid, the arm unchecked.
    let options = CalibrationOptions::default();
    let design = purpose::design(&setup, &options).unwrap();
    let axes = setup.robot().external().unwrap();
    let rest = ExternalValues::new(&[0.0, 0.0]).unwrap();
    let grid = purpose::table_grid(axes, CANDIDATE_ANGLES, &rest);
    let at_rest: Vec<Placed> = report.postures.iter().map(|q| (*q, rest)).collect();
    let n = at_rest.len();
    let unchecked = design
        .choose_table_angles(options.criterion(), &at_rest, &grid, n, None)
        .unwrap();
    let hit = (report.postures.iter().zip(&unchecked.chosen))
        .filter(|(q, c)| to_post(&setup, q, &grid[**c]) < clearance)
        .count();
    assert!(hit > 0, "no unchecked reading meets the post");
    assert_eq!(report.placed.len(), n);
    for (i, (q, e)) in report.postures.iter().zip(&report.placed).enumerate() {
        let d = to_post(&setup, q, e);
        assert!(
            d >= clearance - 1e-9,
            "reading {}: {d} m from the post",
            i + 1
        );
    }
    // Still a design that separates the parameters, as good as the unchecked angles' (to 1%).
    let (value, free) = (report.value, unchecked.value);
    assert!(
        value.is_finite() && value > 0.0 && value <= 1.01 * free,
        "{value} {free}"
    );
}
