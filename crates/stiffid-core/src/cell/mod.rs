//! The physical cell: robot and tool bodies as capsules, and whether a posture can really be
//! measured in the cell (the setup's `[cell]`, `[robot_geometry]`, `[tracker]` and `[constraints]`).
//!
//! - [`capsules`]: the bodies of a posture (base, links 1-6, tool), base frame, m: what a plot draws;
//! - [`feasibility`] / [`Checker::feasibility`]: per check ([`CheckKind`]) whether the posture
//!   passes, the smallest margin and clearance, and the tightest pair of bodies;
//! - [`Checker::margins`]: the signed margin of every tested pair, for constrained searches.
//!
//! Distances come from dimforge's `parry3d-f64` (segment-segment closest points for capsules,
//! GJK/EPA for capsules against boxes). Units: m and rad inside; the setup file speaks mm and deg.
//!
//! ```
//! use nalgebra::Vector6;
//! let text = stiffid_core::setup::builtin_text("zhang2021-comau-nj165").unwrap().to_string()
//!     + "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n";
//! let setup = stiffid_core::setup::parse(&text, "cell.toml", |r, _| stiffid_core::robot::presets::get(r)).unwrap();
//! // Upper arm tilted 40 deg forward, forearm pointing 100 deg down: the tool is in the floor.
//! let q = Vector6::new(0.0, 40f64.to_radians(), -170f64.to_radians(), 0.0, 0.0, 0.0);
//! let f = stiffid_core::cell::feasibility(&setup, &q);
//! assert!(!f.feasible());
//! assert!(f.violations().any(|c| c.kind == stiffid_core::cell::CheckKind::Floor));
//! ```

mod bodies;
mod check;
mod distance;
mod feasibility;
mod motion;

pub use bodies::{bodies, capsules, Body, Capsule, Part, Solid};
pub use check::{CheckKind, Margin, Thing};
pub use distance::{body_body, body_box, body_floor, capsule_box};
pub use feasibility::{feasibility, Check, Checker, Feasibility};
