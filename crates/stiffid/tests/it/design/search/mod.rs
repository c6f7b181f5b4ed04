//! The posture searches (`stiffid_design::search`).

mod sqp;
