//! The table's angles of a calibration design keep the arm clear of the boxes the positioner
//! carries: with a post on the table, the designed postures read at the angles chosen for them in
//! the same cell without the post meet the post (checked independently, the box turned to each
//! reading's angles); every reading of the design clears it, and the design still separates the
//! calibration's parameters.

use nalgebra::Vector6;
use stiffid::app::purpose::{self, CalibrationOptions};
use stiffid::internal::design::selection::table::{table_angles, Group};
use stiffid::internal::robot::external::ExternalValues;
use stiffid::Setup;

use crate::carried_obstacles::arm_to_box;
use crate::table_design::{designed, SETUP};

/// The table design's cell with a clearance of 20 mm and a tracker in front.
const CELL: &str = "\n[cell]\nclearance_mm = 20\n[tracker]\nposition_mm = [3000, -2000, 1500]\n";

/// A post 1.2 m tall on the table's top, 0.5 to 0.8 m in front of its axis, turned by the table.
const POST: &str = "[[cell.obstacle]]\nname = \"post\"\nmin_mm = [1700, 700, 900]\n\
                    max_mm = [1900, 1000, 2100]\ncarried_by = \"rotate\"\n";

/// The cell, with the post or without it.
fn cell(post: bool) -> Setup {
    let text = SETUP.to_string() + CELL + if post { POST } else { "" };
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
    let setup = cell(true);
    let clearance = setup.cell().unwrap().clearance;
    let (report, _) = designed(&setup);
    // The same postures with the angles chosen in the cell without the post.
    let options = CalibrationOptions::default();
    let group = Group {
        postures: &report.postures,
        station: Some(ExternalValues::new(&[0.0, 0.0]).unwrap()),
        placed: &[],
    };
    let design = |s: &Setup| purpose::design(s, &options);
    let unchecked = table_angles(&cell(false), None, options.criterion(), design, group)
        .unwrap()
        .expect("a positioner with reflectors");
    let hit = (report.postures.iter().zip(&unchecked.placed))
        .filter(|(q, e)| to_post(&setup, q, e) < clearance)
        .count();
    assert!(hit > 0, "no reading chosen without the post meets it");
    let n = report.postures.len();
    assert_eq!(report.placed.len(), n);
    for (i, (q, e)) in report.postures.iter().zip(&report.placed).enumerate() {
        let d = to_post(&setup, q, e);
        assert!(
            d >= clearance - 1e-9,
            "reading {}: {d} m from the post",
            i + 1
        );
    }
    // Still a design that separates the parameters, as good as the angles chosen without the
    // post (to 1%).
    let (value, free) = (report.value, unchecked.value);
    assert!(
        value.is_finite() && value > 0.0 && value <= 1.01 * free,
        "{value} {free}"
    );
}
