//! The choice of a group as `select` makes it (`stiffid_design::selection`): the pool screened,
//! the stations, the campaign's checks and the table's grid.

mod pool;
mod station;
mod table;

use stiffid::robot::presets;
use stiffid::setup;
use stiffid::Setup;

/// The example track cell: a track (`e1`), a tilt-rotate positioner (`e2`, `e3`).
fn track_cell() -> Setup {
    let text = include_str!("../../../../../../examples/track/track-cell.toml");
    setup::parse(text, "track-cell.toml", |name, _| presets::get(name)).unwrap()
}
